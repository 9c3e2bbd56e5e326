//! One Clarabel solve of a conic program `min q'x + x'Px/2  s.t.  A x + s = b, s in K`, with
//! the rule of [`Refinement::Auto`] on Clarabel's iterative refinement: a program whose KKT
//! matrix (variables plus constraints) has at least [`LARGE_KKT`] rows is solved without the
//! refinement first, and again with it when that solve does not end solved or infeasible, the
//! iterations of both counted (docs/performance.md, "Large assemblies"). The static programs
//! (`statics`, `statics::design`, the chain's interior point, the non-associative iteration)
//! and the general kinematic program (`kinematic::general`) solve through it, so the rule is
//! written once.

use super::{Refinement, LARGE_KKT};
use clarabel::algebra::CscMatrix;
use clarabel::solver::{
    DefaultSettingsBuilder, DefaultSolver, IPSolver, SolverStatus, SupportedConeT,
};

/// The program `min q'x + x'Px/2  s.t.  A x + s = b, s in cones`.
pub(crate) struct Conic<'a> {
    pub p: &'a CscMatrix<f64>,
    pub q: &'a [f64],
    pub a: &'a CscMatrix<f64>,
    pub b: &'a [f64],
    pub cones: &'a [SupportedConeT<f64>],
}

/// How Clarabel solves it: the duality-gap tolerance (absolute and relative), the
/// feasibility tolerance, the iteration limit, the LDL method (None: Clarabel's default) and
/// the refinement rule.
pub(crate) struct Knobs<'a> {
    pub tol_gap: f64,
    pub tol_feas: f64,
    pub max_iter: u32,
    pub linear_solver: Option<&'a str>,
    pub refinement: Refinement,
}

/// What Clarabel ended with: its status, the primal `x` and the cone duals `z`, and the
/// iterations (of both solves when the first was repeated with the refinement).
pub(crate) struct Solution {
    pub status: SolverStatus,
    pub x: Vec<f64>,
    pub z: Vec<f64>,
    pub iterations: u32,
}

/// Solve `program` under `knobs` (the module docs' rule). `Err`: Clarabel refused the
/// settings or the program's data (its message).
pub(crate) fn solve(program: &Conic<'_>, knobs: &Knobs<'_>) -> Result<Solution, String> {
    let kkt = program.a.n + program.a.m;
    let plain = knobs.refinement == Refinement::Auto && large(kkt);
    let first = once(program, knobs, !plain)?;
    let settled = matches!(
        first.status,
        SolverStatus::Solved | SolverStatus::PrimalInfeasible | SolverStatus::DualInfeasible
    );
    if !plain || settled {
        return Ok(first);
    }
    let mut refined = once(program, knobs, true)?;
    refined.iterations += first.iterations;
    Ok(refined)
}

/// One Clarabel solve, with or without iterative refinement (`refine`).
fn once(program: &Conic<'_>, knobs: &Knobs<'_>, refine: bool) -> Result<Solution, String> {
    let mut builder = DefaultSettingsBuilder::default();
    builder
        .iterative_refinement_enable(refine)
        .verbose(false)
        .tol_gap_abs(knobs.tol_gap)
        .tol_gap_rel(knobs.tol_gap)
        .tol_feas(knobs.tol_feas)
        .max_iter(if refine {
            knobs.max_iter
        } else {
            unrefined_limit(knobs.max_iter)
        });
    if let Some(method) = knobs.linear_solver {
        builder.direct_solve_method(method.to_string());
    }
    let settings = builder.build().map_err(|e| e.to_string())?;
    let Conic { p, q, a, b, cones } = *program;
    let mut solver = DefaultSolver::new(p, q, a, b, cones, settings).map_err(|e| e.to_string())?;
    solver.solve();
    let sol = &mut solver.solution;
    Ok(Solution {
        status: sol.status,
        x: std::mem::take(&mut sol.x),
        z: std::mem::take(&mut sol.z),
        iterations: sol.iterations,
    })
}

/// Whether a program of `kkt` KKT rows is large enough to be solved without the refinement
/// first (every program, under the test hook [`STALL_UNREFINED`]).
fn large(kkt: usize) -> bool {
    #[cfg(test)]
    if STALL_UNREFINED.get().is_some() {
        return true;
    }
    kkt >= LARGE_KKT
}

/// The iteration limit of a solve without the refinement: `max_iter`, or the test hook's.
fn unrefined_limit(max_iter: u32) -> u32 {
    #[cfg(test)]
    if let Some(limit) = STALL_UNREFINED.get() {
        return limit;
    }
    max_iter
}

#[cfg(test)]
thread_local! {
    /// Test hook (this thread only): with `Some(k)` every program takes the rule of a large
    /// one, and its solve without the refinement stops after `k` iterations, so that a
    /// program that does not end solved without the refinement is at hand at any size.
    pub(crate) static STALL_UNREFINED: std::cell::Cell<Option<u32>> =
        const { std::cell::Cell::new(None) };
}
