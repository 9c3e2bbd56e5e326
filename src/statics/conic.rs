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
/// first (every program, under the test hook `STALL_UNREFINED`).
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

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use crate::scene::{build, Scene};
    use crate::statics::{
        analyse, Objective, Program, StaticProblem, StaticSettings, Status, LAMBDA_CAP,
    };

    /// A semicircular arch with a line load on one haunch (no mirror symmetry), its joints
    /// frictional (also the general kinematic program's test of the retry).
    pub(crate) fn arch() -> crate::model::Model {
        let text = "[arch]\nshape = \"circular\"\nradius = 1.0\nthickness = 0.15\nvoussoirs = 24\n[material]\nfriction = 0.6\n[[loads]]\ntype = \"line\"\nfrom_x = 0.2\nto_x = 0.6\nintensity = 3000.0\n";
        build(&Scene::from_toml_str(text, "test").expect("scene")).expect("model")
    }

    /// The retry: a program that does not end solved without the refinement (the hook stops
    /// that solve after 4 iterations, where the refined one needs more) is solved again with
    /// it. The answer is the refined solve's, bit for bit (the same program, the same
    /// settings), in equilibrium, and its iterations are those of both solves.
    #[test]
    fn a_stalled_unrefined_solve_is_repeated_with_the_refinement() {
        let model = arch();
        let refined = StaticSettings {
            program: Program::Full,
            refinement: Refinement::Always,
            ..StaticSettings::default()
        };
        let auto = StaticSettings {
            refinement: Refinement::Auto,
            ..refined.clone()
        };
        let always = analyse(&model, &refined).expect("refined solve");
        assert_eq!(always.status, Status::Collapse);
        const STALL: u32 = 4;
        assert!(
            always.iterations > STALL,
            "{} iterations",
            always.iterations
        );
        STALL_UNREFINED.set(Some(STALL));
        // The first solve alone: stopped short, not solved or infeasible.
        let problem = StaticProblem::of_model(
            &model,
            crate::interaction::contact::ShearLimit::Coulomb,
            Objective::MaxLambda {
                sign: 1.0,
                cap: None,
            },
        );
        let program = Conic {
            p: &problem.p,
            q: &problem.q,
            a: &problem.a,
            b: &problem.b,
            cones: &problem.cones,
        };
        let knobs = Knobs {
            tol_gap: auto.tol_gap,
            tol_feas: auto.tol_feas,
            max_iter: auto.max_iter,
            linear_solver: Some(&auto.linear_solver),
            refinement: auto.refinement,
        };
        let first = once(&program, &knobs, false).expect("unrefined solve");
        assert_eq!(first.status, SolverStatus::MaxIterations);
        assert_eq!(first.iterations, STALL);
        let retried = analyse(&model, &auto);
        STALL_UNREFINED.set(None);
        let retried = retried.expect("retried solve");
        assert_eq!(retried.status, Status::Collapse);
        let (lambda, expected) = (
            retried.lambda.expect("lambda"),
            always.lambda.expect("lambda"),
        );
        assert_eq!(
            lambda.to_bits(),
            expected.to_bits(),
            "{lambda} vs {expected}"
        );
        assert!(lambda > 0.0 && lambda < LAMBDA_CAP, "{lambda}");
        assert_eq!(retried.iterations, STALL + always.iterations);
        // Equilibrium of every block, to the solver's accuracy on the total weight.
        let weight = model.loads.force_scale();
        assert!(
            retried.equilibrium_residual <= 1e-8 * weight,
            "residual {} N of {weight} N",
            retried.equilibrium_residual
        );
        assert_eq!(retried.hinges.len(), always.hinges.len());
    }
}
