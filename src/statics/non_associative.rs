//! The non-associative collapse multiplier: joints that slide without opening (docs/friction.md).
//!
//! Real masonry joints obey Coulomb's `|V| <= mu N` but slide with no dilatancy, so the
//! normality rule (and with it the safe theorem) does not hold: the associative multiplier of
//! the static program is only an upper bound of the real collapse multiplier (Drucker 1954;
//! Radenkovic 1961). Gilbert, Casapulla & Ahmed (2006, *Limit analysis of masonry block
//! structures with non-associative frictional joints using linear programming*, Computers &
//! Structures 84, 873-887) find a non-associative collapse state by a sequence of convex
//! programs in which each joint's shear capacity is fixed from normal forces already known:
//!
//! 1. `S_j = mu_j Nbar_j`, with `Nbar` the normal forces of a starting solution;
//! 2. solve the static program with `|V_j| <= S_j` in place of `|V_j| <= mu_j N_j`
//!    ([`ShearLimit::Fixed`]): its failure surface is flat in N, so its normality rule is slip
//!    without opening, the flow rule of the real joint, and the program is a linear (or, with
//!    crushing, conic) program like the associative one;
//! 3. relax: `Nbar <- Nbar + beta (N - Nbar)`, with `N` the new normal forces, and repeat
//!    until the multiplier and the normal forces settle.
//!
//! At a fixed point (`N = Nbar` wherever a joint's shear reaches its capacity, and
//! `|V| <= mu N` everywhere) the forces are in equilibrium and admissible for Coulomb's law,
//! and the program's mechanism (its duals) slides without opening at exactly the joints whose
//! shear is `mu N`, dissipating `mu N |slip|`: a complete solution of the non-associative
//! problem. Such problems can have several solutions (Gilbert et al. 2006; Casapulla & Lauro
//! 2000 name a class with a unique one); the iteration finds one per start, and the lowest
//! converged value of the starts tried is kept. Nothing guarantees that it is the lowest of
//! all: the true collapse multiplier is at most that value.
//!
//! **The mechanism's fixed point** ([`NonAssociativeSettings::mechanism_step`], from a
//! start's third iteration on): a program's duals `y` stay dual feasible whatever the
//! capacities, so an equilibrium that obeys Coulomb's law and has no duality gap with `y` in
//! the program of its own capacities (`S_j = mu_j N_j`) is an optimum of that program and
//! reproduces them: a fixed point. The gap is linear in the equilibrium, so the step solves
//! one linear program, the associative program minimising it (`propose`), and the next
//! program verifies the answer. Where it does not verify, the iteration relaxes as below
//! (docs/friction.md).
//!
//! What is implemented (the relaxation is ours: only the paper's abstract was at hand when
//! this was written, so its exact relaxation rule is not reproduced): `beta` starts at
//! [`NonAssociativeSettings::relaxation`] (1: each capacity from the last normal forces) and
//! is halved, down to 1/64, whenever the multiplier's increments change sign twice in a row
//! (an oscillation: the capacities then mix the previous and the new normal forces);
//! convergence asks that the multiplier change by at most `tolerance * max(1, |lambda|)`
//! between two iterations and that the fixed-point conditions above hold to `tolerance` times
//! the largest normal force. Three starts, in this order ([`Start`]): the normal forces of the
//! associative collapse solution; the same, with every program followed by a second one that
//! picks, among its optima, the equilibrium of least friction capacity `sum mu N`
//! ([`Objective::LeastFriction`]), which steers toward the lower solutions; and the normal
//! forces of the most central equilibrium under the permanent loads alone (the phase-one
//! program's).
//!
//! On a chain (rigid joints, no ties, strips or passive resistance) each program is solved by
//! the chain program's dual active set with fixed capacities, warm-started from the previous
//! iterate's basis (`chain/fixed_shear.rs`); the full conic program otherwise, and wherever
//! the active set does not decide. [`NonAssociativeSettings::simplex`] (off by default,
//! measured slower) solves the programs of other linear models by the warm-started dual
//! simplex of [`super::simplex`], each followed by the optimum nearest the last iterate
//! ([`super::simplex::BoundedLp::nearest`]), Clarabel wherever the simplex does not decide. The starts are independent and run side by side (rayon),
//! read back in the order above.

use super::chain::FixedShearChain;
use super::problem::column;
use super::problem::{Objective, StaticProblem};
use super::simplex::{BoundedLp, DualSimplex, LpOutcome};
use super::{
    check_almost_solved, problem_size, read_forces, read_mechanism, run, slipping_joints, Program,
    StaticResult, StaticSettings, Status, Tensions, LAMBDA_CAP,
};
use crate::assembly::JointForce;
use crate::error::AnalysisError;
use crate::interaction::contact::ShearLimit;
use crate::model::Model;
use clarabel::solver::SolverStatus;
use rayon::prelude::*;
use std::time::Instant;

/// How the non-associative iteration runs.
#[derive(Debug, Clone, PartialEq)]
pub struct NonAssociativeSettings {
    /// The most iterations from one start (one program each, two for
    /// [`Start::LeastFriction`], and two more for each mechanism step tried, at most
    /// `MAX_FAILED_PROPOSALS` = 10 of them that fail). Default 100.
    pub max_iterations: u32,
    /// Relative change of the multiplier, and mismatch of the normal forces (over the largest
    /// one), below which the iteration has settled. Default 1e-6.
    pub tolerance: f64,
    /// The first relaxation factor `beta` (0 < beta <= 1). Default 1.
    pub relaxation: f64,
    /// Solve the fixed-shear programs of assemblies that are not chains by the warm-started
    /// dual simplex ([`super::simplex`], each program followed by the optimum nearest the
    /// last iterate) instead of Clarabel. Default false: on the 205-block wall and the 3-bay
    /// arcade it measured slower than Clarabel per program (docs/performance.md), and its
    /// vertex solutions settle on other solutions of the non-associative problem than the
    /// interior point's (docs/friction.md).
    pub simplex: bool,
    /// From a start's third iteration on, after a program solved by Clarabel (linear: no
    /// crushing cones), try the fixed point of its mechanism (`propose`, one more program)
    /// and verify it by the program of its capacities (another): verified, it is the start's
    /// answer; otherwise the relaxation goes on as if it had not been tried. Default true
    /// (docs/friction.md, "The mechanism's fixed point").
    pub mechanism_step: bool,
}

impl Default for NonAssociativeSettings {
    fn default() -> Self {
        NonAssociativeSettings {
            max_iterations: 100,
            tolerance: 1e-6,
            relaxation: 1.0,
            simplex: false,
            mechanism_step: true,
        }
    }
}

/// The first iteration from which a start proposes the fixed point of its program's
/// mechanism: the first two relax, so that the iteration leaves its start before it is drawn
/// to the nearest fixed point (on the running-bond wall with mu = 1000 a proposal from the
/// first program verifies the start itself, 1.0, where the relaxation finds 0.536;
/// docs/friction.md).
const FIRST_PROPOSAL: u32 = 3;

/// Mechanism steps from one start that were not verified (two programs each), after which
/// that start only relaxes. The 3-bay arcade's starts verify at their third, fifth and fifth
/// step (docs/friction.md); the budget leaves room beyond that, at a cost of at most 20
/// programs to a start where no step verifies.
const MAX_FAILED_PROPOSALS: u32 = 10;

/// The smallest relaxation factor the oscillation damping goes down to.
const MIN_RELAXATION: f64 = 1.0 / 64.0;

/// Where an iteration started.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Start {
    /// The normal forces of the associative collapse solution.
    Associative,
    /// The normal forces of the most central equilibrium under the permanent loads (the
    /// phase-one program at lambda = 0).
    AtRest,
    /// The normal forces of the associative collapse solution, and at every iteration the
    /// equilibrium with the least friction capacity `sum mu N` among the optima (a second
    /// program, [`Objective::LeastFriction`]): it steers the iteration toward the solutions
    /// with the least normal forces where joints slide, the lower ones when there are
    /// several.
    LeastFriction,
}

impl Start {
    pub fn as_str(self) -> &'static str {
        match self {
            Start::Associative => "associative",
            Start::AtRest => "at_rest",
            Start::LeastFriction => "least_friction",
        }
    }
}

/// How a start settled.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum SettledBy {
    /// Two programs in a row with the same multiplier, the second a fixed point of the
    /// capacities of the first.
    Relaxation,
    /// A verified mechanism step ([`NonAssociativeSettings::mechanism_step`]).
    MechanismStep,
}

impl SettledBy {
    pub fn as_str(self) -> &'static str {
        match self {
            SettledBy::Relaxation => "relaxation",
            SettledBy::MechanismStep => "mechanism_step",
        }
    }
}

/// One start's iteration.
#[derive(Debug, Clone)]
pub struct StartOutcome {
    pub start: Start,
    /// The multiplier of the last program solved (None when none was solved).
    pub lambda: Option<f64>,
    /// Programs solved from this start (two per iteration for [`Start::LeastFriction`], two
    /// per mechanism step tried).
    pub iterations: u32,
    /// How it settled (None when it did not).
    pub settled_by: Option<SettledBy>,
    /// Why it stopped, when it did not converge.
    pub stopped: Option<String>,
}

impl StartOutcome {
    /// Whether it settled (a fixed point, to the tolerance).
    pub fn converged(&self) -> bool {
        self.settled_by.is_some()
    }

    /// A start that settled `by` on `result` after `programs` programs.
    fn settled(
        start: Start,
        result: StaticResult,
        programs: u32,
        by: SettledBy,
    ) -> (StartOutcome, Option<StaticResult>) {
        let outcome = StartOutcome {
            start,
            lambda: result.lambda,
            iterations: programs,
            settled_by: Some(by),
            stopped: None,
        };
        (outcome, Some(result))
    }
}

/// The non-associative multiplier of a model.
#[derive(Debug, Clone)]
pub struct NonAssociative {
    /// The lowest multiplier among the converged starts; None when none converged (then
    /// `starts` holds the last iterates, which are not solutions).
    pub lambda: Option<f64>,
    /// Whether some start converged.
    pub converged: bool,
    /// Programs solved, all starts together (0 when the associative multiplier is exact and
    /// nothing was iterated).
    pub iterations: u32,
    /// The joints that slip (without opening) in the mechanism of the retained solution.
    pub sliding: Vec<usize>,
    /// Every start tried, in order.
    pub starts: Vec<StartOutcome>,
    /// The retained solution: forces, hinges, mechanism (of the last fixed-capacity program).
    pub result: Option<StaticResult>,
    /// Whether the associative multiplier was taken as it is (friction exact), with no
    /// iteration.
    pub from_exact: bool,
    /// Taken as it is although lower collapse states of real joints are possible (exact in an
    /// assembly that is not a chain), because the assembly has more blocks than
    /// `analysis::AUTO_SEARCH_MAX_BLOCKS`: those states were not searched for.
    pub unsearched: bool,
    /// Wall time of all the iterations (s).
    pub solve_time_s: f64,
}

impl NonAssociative {
    /// The associative solution taken as it is, when it is exact in a chain (no joint slips
    /// in its mechanism, and no lower collapse state is looked for: docs/friction.md).
    pub fn exact(associative: &StaticResult) -> NonAssociative {
        NonAssociative {
            lambda: associative.lambda,
            converged: true,
            iterations: 0,
            sliding: Vec::new(),
            starts: Vec::new(),
            result: None,
            from_exact: true,
            unsearched: false,
            solve_time_s: 0.0,
        }
    }
}

/// One program with fixed shear capacities: its multiplier, forces and result.
struct Iterate {
    lambda: f64,
    forces: Vec<JointForce>,
    result: StaticResult,
    /// Programs solved for it.
    programs: u32,
    /// The largest-multiplier program and its duals, when Clarabel solved it (the mechanism
    /// a step starts from, and the duals a verified proposal reads).
    dual: Option<Dual>,
}

/// A program solved by Clarabel: the program, how Clarabel ended, and its cone duals `z`.
struct Dual {
    problem: StaticProblem,
    status: SolverStatus,
    z: Vec<f64>,
}

/// The fixed-shear programs of a model that is not a chain but a linear program (rigid
/// joints; ties, strips and passive reactions are bounds), by the dual simplex of
/// [`super::simplex`], each warm-started from the last optimal basis of its kind, since only
/// the capacities (bounds) change between iterations. A simplex answers a vertex of the
/// optimal face where the interior point answers a point inside it; the iteration reads the
/// normal forces, and vertices jump between iterations where the face is wide (a wall), so
/// each program is followed by a second one that picks among its optima the equilibrium
/// nearest the last iterate's ([`BoundedLp::nearest`]): at a fixed point that is the last
/// iterate itself.
#[derive(Clone)]
struct FixedShearLp {
    /// The largest-multiplier program's simplex (None before the first solve, or after one
    /// it did not decide).
    main: Option<DualSimplex>,
    /// The second program's (the nearest optimum, or the least-friction one).
    near: Option<DualSimplex>,
    /// The contact columns' values (c1, c2 of every joint, over the force scale) of the last
    /// iterate: the centre of the next second program.
    centre: Vec<f64>,
}

/// The weight of the distance to the last iterate beside the least-friction objective
/// (`sum mu N` over the force scale): a tie-break among its optima.
const NEAREST_TIE_BREAK: f64 = 1e-6;

impl FixedShearLp {
    /// The simplex path for `model`, or None when the full program should solve every
    /// iterate: `settings` asking for the full program or no active set (the cross-checks),
    /// crushing (a conic program), a chain (its own active set, [`FixedShearChain`]), or a
    /// program [`BoundedLp::from_problem`] does not take (too large, rows of several entries).
    fn new(
        model: &Model,
        settings: &StaticSettings,
        chain: bool,
        capacity: &[f64],
    ) -> Option<FixedShearLp> {
        let off = settings.program != Program::Auto || !settings.active_set;
        if off || chain || model.strength.is_finite() {
            return None;
        }
        let problem = fixed_program(model, settings, capacity);
        let lp = BoundedLp::from_problem(&problem).ok()?;
        // The first program of the two starts from the associative solution, solved here
        // once: every start then begins from its optimal basis, not from the slack basis.
        let mut main = DualSimplex::new(lp);
        let main = matches!(main.solve(), LpOutcome::Optimal(_)).then_some(main);
        Some(FixedShearLp {
            main,
            near: None,
            centre: Vec::new(),
        })
    }

    /// The contact columns and their values (over the force scale) for joint forces `forces`.
    fn contact_values(model: &Model, forces: &[JointForce], fs: f64) -> Vec<f64> {
        model
            .assembly
            .joints
            .iter()
            .zip(forces)
            .flat_map(|(jt, f)| {
                // N = c1 + c2, M = (c2 - c1) L / 2.
                let half = 0.5 * f.n.max(0.0);
                let d = f.m / jt.length();
                [(half - d).max(0.0) / fs, (half + d).max(0.0) / fs]
            })
            .collect()
    }

    /// Start from the normal forces `n` (centred resultants).
    fn start_at(&mut self, model: &Model, n: &[f64]) {
        let forces: Vec<JointForce> = n
            .iter()
            .map(|&n| JointForce { n, v: 0.0, m: 0.0 })
            .collect();
        self.centre = Self::contact_values(model, &forces, model.loads.force_scale());
    }
}

/// Solve `lp` with the simplex kept in `slot` (warm when it has the same matrix); a simplex
/// that did not decide is dropped, so the next program starts afresh.
fn solve_in(slot: &mut Option<DualSimplex>, lp: BoundedLp) -> LpOutcome {
    let simplex = match slot {
        Some(s) => {
            s.update(lp);
            s
        }
        None => slot.insert(DualSimplex::new(lp)),
    };
    let out = simplex.solve();
    if matches!(out, LpOutcome::Undecided(_)) {
        *slot = None;
    }
    out
}

/// The largest-multiplier program of `model` with the shear capacities `capacity` (N).
fn fixed_program(model: &Model, settings: &StaticSettings, capacity: &[f64]) -> StaticProblem {
    let sign = settings.direction.sign();
    let cap = Some(LAMBDA_CAP);
    program_with(model, capacity, Objective::MaxLambda { sign, cap })
}

/// The static program of `model` with the shear capacities `capacity` (N) and `objective`.
fn program_with(model: &Model, capacity: &[f64], objective: Objective) -> StaticProblem {
    StaticProblem::of_model(model, ShearLimit::Fixed(capacity), objective)
}

/// One iterate by the simplex path on `problem` (the largest-multiplier program with the
/// iteration's capacities): the largest multiplier, then the optimum nearest the last
/// iterate (or, with `least_friction`, the least-friction optimum, nearest it among those).
/// `Some(None)`: no equilibrium with these capacities; None: the simplex did not decide, and
/// Clarabel should (on the same `problem`).
fn solve_fixed_lp(
    model: &Model,
    settings: &StaticSettings,
    lp: &mut FixedShearLp,
    problem: &StaticProblem,
    least_friction: bool,
) -> Result<Option<Option<Iterate>>, AnalysisError> {
    let Ok(first) = BoundedLp::from_problem(problem) else {
        return Ok(None);
    };
    let sol = match solve_in(&mut lp.main, first.clone()) {
        LpOutcome::Optimal(sol) => sol,
        LpOutcome::Infeasible => return Ok(Some(None)),
        LpOutcome::Undecided(_) => return Ok(None),
    };
    let lambda = sol.x[0];
    let below = lambda - 1e-9 * lambda.abs().max(1.0);
    let nj = model.assembly.joints.len();
    let columns: Vec<usize> = (0..nj).flat_map(|j| [column(j, 0), column(j, 1)]).collect();
    if lp.centre.len() != columns.len() {
        lp.centre = columns.iter().map(|&k| sol.x[k]).collect();
    }
    let (primary, weight): (Vec<f64>, f64) = if least_friction {
        let mu = |j: usize| {
            let f = model.assembly.joints[j].friction;
            if f.is_finite() {
                f
            } else {
                0.0
            }
        };
        let primary = (0..nj).flat_map(|j| [mu(j), mu(j)]).collect();
        (primary, NEAREST_TIE_BREAK)
    } else {
        (vec![0.0; columns.len()], 1.0)
    };
    let second = first.nearest(below, &columns, &lp.centre, &primary, weight);
    let x = match solve_in(&mut lp.near, second) {
        LpOutcome::Optimal(s) => s.x,
        // The vertex of the first program is an optimum too; the least-friction one is not.
        _ if !least_friction => sol.x.clone(),
        _ => return Ok(None),
    };
    let iterate = read_fixed(
        model,
        settings,
        problem,
        &x,
        &sol.z,
        (lambda, SolverStatus::Solved, sol.pivots),
        "dual simplex; optimal vertex (fixed shear capacities)".to_string(),
        2,
    )?;
    lp.centre = columns.iter().map(|&k| x[k]).collect();
    Ok(Some(Some(iterate)))
}

/// One iterate read from a program's solution: the forces of `x`, the mechanism of the
/// duals `z`, the multiplier, status and iterations of `solved`; `programs` solved.
#[allow(clippy::too_many_arguments)]
fn read_fixed(
    model: &Model,
    settings: &StaticSettings,
    problem: &StaticProblem,
    x: &[f64],
    z: &[f64],
    solved: (f64, SolverStatus, u32),
    words: String,
    programs: u32,
) -> Result<Iterate, AnalysisError> {
    let (lambda, status, iterations) = solved;
    let sign = settings.direction.sign();
    let forces = read_forces(&model.assembly, problem, x);
    let tensions = Tensions::read(problem, x);
    let residual = tensions.residual(model, &forces, lambda, sign);
    check_almost_solved(status, residual, problem.force_scale, iterations)?;
    let mut result = StaticResult::unsolved(settings, iterations, words, problem_size(problem));
    result = result.read_iterate(model, settings, lambda, forces.clone(), residual, || {
        read_mechanism(&model.assembly, problem, z)
    });
    result.set_tensions(model, &tensions.ties, &tensions.strips, &tensions.passive);
    Ok(Iterate {
        lambda,
        forces,
        result,
        programs,
        dual: None,
    })
}

/// Solve the static program of `model` with each joint's shear bounded by `capacity` (N),
/// maximising lambda toward `settings.direction` (capped at [`LAMBDA_CAP`]). None when the
/// program has no solution (no equilibrium with these capacities at any multiplier).
fn solve_fixed(
    model: &Model,
    settings: &StaticSettings,
    chain: Option<&mut FixedShearChain>,
    lp: Option<&mut FixedShearLp>,
    capacity: &[f64],
    least_friction: bool,
) -> Result<Option<Iterate>, AnalysisError> {
    // A chain's program by its active set (exact), the full program where it does not decide.
    if let Some(found) = chain.and_then(|c| c.solve(model, settings, capacity, least_friction)) {
        return Ok(found.map(|s| Iterate {
            lambda: s.lambda,
            forces: s.forces,
            result: s.result,
            programs: 1 + u32::from(least_friction),
            dual: None,
        }));
    }
    // Any other program is built once: the warm-started simplex solves it when it is linear
    // and the simplex decides, Clarabel otherwise. The iterate's time counts from the build.
    let start = Instant::now();
    let problem = fixed_program(model, settings, capacity);
    if let Some(lp) = lp {
        if let Some(found) = solve_fixed_lp(model, settings, lp, &problem, least_friction)? {
            return Ok(found.map(|mut iterate| {
                iterate.result.solve_time_s = start.elapsed().as_secs_f64();
                iterate
            }));
        }
    }
    let sign = settings.direction.sign();
    let sol = run(&problem, settings)?;
    if !matches!(
        sol.status,
        SolverStatus::Solved | SolverStatus::AlmostSolved
    ) {
        return Ok(None);
    }
    let lambda = sol.x[0];
    // The equilibrium with the least friction capacity at (a hair below) that multiplier:
    // the mechanism stays the first program's (its duals hold on the whole optimal face).
    let least = if least_friction {
        let below = lambda - 1e-9 * lambda.abs().max(1.0);
        let p2 = program_with(
            model,
            capacity,
            Objective::LeastFriction {
                sign,
                lambda: below,
            },
        );
        let s2 = run(&p2, settings)?;
        matches!(s2.status, SolverStatus::Solved | SolverStatus::AlmostSolved).then_some(s2.x)
    } else {
        None
    };
    let x = least.as_deref().unwrap_or(&sol.x);
    let mut iterate = read_fixed(
        model,
        settings,
        &problem,
        x,
        &sol.z,
        (lambda, sol.status, sol.iterations),
        format!("{:?} (fixed shear capacities)", sol.status),
        1 + u32::from(least_friction),
    )?;
    iterate.result.solve_time_s = start.elapsed().as_secs_f64();
    iterate.dual = Some(Dual {
        problem,
        status: sol.status,
        z: sol.z,
    });
    Ok(Some(iterate))
}

impl StaticResult {
    /// One iterate's solution (multiplier `lambda`, `forces`, equilibrium `residual`, the
    /// program's `mechanism`) read into the result, as a collapse whatever the sign of lambda:
    /// the iteration needs the forces of every iterate (a negative multiplier is judged by
    /// the caller), and `lambda` is kept as it is.
    pub(super) fn read_iterate(
        self,
        model: &Model,
        settings: &StaticSettings,
        lambda: f64,
        forces: Vec<JointForce>,
        residual: f64,
        mechanism: impl FnOnce() -> Vec<[f64; 3]>,
    ) -> StaticResult {
        let mut result = self.read_solution(
            &model.assembly,
            model.strength,
            settings,
            lambda.max(0.0),
            forces,
            residual,
            true,
            mechanism,
        );
        result.lambda = Some(lambda);
        result
    }
}

/// The shear capacities `S_j = mu_j N_j` (N) of the normal forces `n` (N, joint order; a
/// negative one counts as 0).
fn capacities(model: &Model, n: &[f64]) -> Vec<f64> {
    model
        .assembly
        .joints
        .iter()
        .zip(n)
        .map(|(j, n)| j.friction * n.max(0.0))
        .collect()
}

/// Whether `it`, solved with the capacities of normal forces `nbar`, is a fixed point to
/// `tol`: Coulomb's law holds with its own normal forces, and every joint whose shear reaches
/// its capacity carries the normal force the capacity was set from.
fn fixed_point(model: &Model, nbar: &[f64], it: &Iterate, tol: f64) -> bool {
    let nmax = it
        .forces
        .iter()
        .fold(0.0_f64, |a, f| a.max(f.n))
        .max(1e-300);
    let eps = tol * nmax;
    model
        .assembly
        .joints
        .iter()
        .zip(nbar.iter().zip(&it.forces))
        .filter(|(j, _)| j.friction.is_finite())
        .all(|(j, (&nb, f))| {
            let mu = j.friction;
            let admissible = f.v.abs() <= mu * f.n + mu * eps;
            let at_capacity = f.v.abs() >= mu * nb - mu * eps;
            admissible && (!at_capacity || (f.n - nb).abs() <= eps)
        })
}

/// A fixed point proposed from a mechanism (`propose`): its multiplier, its forces and the
/// program's primal solution (the columns of the static program of `model`).
struct Proposal {
    lambda: f64,
    forces: Vec<JointForce>,
    x: Vec<f64>,
}

/// The weight of the multiplier beside the duality gap in `propose`'s objective (the duals
/// scaled to a largest of 1): a tie-break toward the least multiplier among the equilibria
/// of (nearly) no gap.
const PROPOSAL_LAMBDA_WEIGHT: f64 = 1e-6;

/// The fixed point of the mechanism of `dual` (a program with fixed capacities, solved by
/// Clarabel), or the equilibrium nearest one. With `y` the program's duals, which stay dual
/// feasible whatever the capacities (they are right-hand sides), an equilibrium `x` that
/// obeys Coulomb's law is feasible for the program with the capacities of its own normal
/// forces, `S_j = mu_j N_j`, and on every inequality row that program's slack is the
/// associative program's `s_i(x)` (`mu N -+ V`, `c`, ...). The duality gap of `x` and `y` in
/// that program is `sum_i y_i s_i(x) >= 0`: where it is 0, `x` is an optimum of the program
/// of its own capacities (with `y` its mechanism): a complete solution of the
/// non-associative problem. So the step
/// solves one linear program, the associative program (Coulomb's law, the multiplier free up
/// to its cap) minimising `sum_i y_i s_i(x)` (`y` over its largest), plus
/// [`PROPOSAL_LAMBDA_WEIGHT`] times the multiplier. No row is classified as tight or loose:
/// a row weighs by its dual, so the rows an interior point leaves ambiguous (dual and slack
/// both near 0) weigh next to nothing. `y` is an interior point's, so the caller verifies
/// the answer by the program with its capacities.
fn propose(
    model: &Model,
    settings: &StaticSettings,
    dual: &Dual,
) -> Result<Proposed, AnalysisError> {
    let sign = settings.direction.sign();
    let cap = Some(LAMBDA_CAP);
    let mut associative = StaticProblem::of_model(
        model,
        ShearLimit::Coulomb,
        Objective::MaxLambda { sign, cap },
    );
    let (eq, ineq) = (dual.problem.equality_rows, dual.problem.inequality_rows);
    // The associative program has the fixed one's rows in the same order (the shear law
    // changes a row's entries, not the rows), so the duals carry over; second-order cones
    // (crushing) are left out.
    if dual.problem.cone_rows > 0
        || associative.inequality_rows != ineq
        || associative.equality_rows != eq
    {
        return Ok(Proposed::NotTried);
    }
    let rows = eq..eq + ineq;
    let ymax = dual.z[rows.clone()].iter().fold(0.0_f64, |m, &y| m.max(y));
    if !(ymax > 0.0 && ymax.is_finite()) {
        return Ok(Proposed::NotTried);
    }
    // sum_i y_i s_i(x) = sum_i y_i (b_i - A_i x): the constant dropped, -A' y on the columns.
    let a = &associative.a;
    let mut q = vec![0.0; associative.variables()];
    q[0] = PROPOSAL_LAMBDA_WEIGHT;
    for (col, qc) in q.iter_mut().enumerate() {
        for k in a.colptr[col]..a.colptr[col + 1] {
            if rows.contains(&a.rowval[k]) {
                *qc -= dual.z[a.rowval[k]].max(0.0) / ymax * a.nzval[k];
            }
        }
    }
    associative.q = q;
    let sol = run(&associative, settings)?;
    if sol.status != SolverStatus::Solved {
        return Ok(Proposed::Unsolved);
    }
    let forces = read_forces(&model.assembly, &associative, &sol.x);
    Ok(Proposed::Found(Proposal {
        lambda: sol.x[0],
        forces,
        x: sol.x,
    }))
}

/// What `propose` gave.
enum Proposed {
    /// Nothing solved: the program has second-order cones (crushing), its rows do not match
    /// the associative program's, or no dual weighs.
    NotTried,
    /// The proposal's program did not end solved.
    Unsolved,
    Found(Proposal),
}

/// One mechanism step from the program whose Clarabel solution is `dual`: the proposal
/// (`propose`), then the program with the capacities of its normal forces, which verifies
/// it. Returns the programs solved (0: nothing to propose from) and the verified solution:
/// the proposal's forces, an optimum of the verifying program (which ended solved with the
/// proposal's multiplier to `tol`; the proposal obeys Coulomb's law, so it is feasible
/// there), with that program's duals as the mechanism. The step is tried aside: a solver
/// error in either program is a step that did not verify, not an error of the analysis.
fn mechanism_step(
    model: &Model,
    settings: &StaticSettings,
    dual: &Dual,
    tol: f64,
) -> Result<(u32, Option<Iterate>), AnalysisError> {
    let p = match propose(model, settings, dual) {
        Ok(Proposed::NotTried) => return Ok((0, None)),
        Ok(Proposed::Unsolved) | Err(_) => return Ok((1, None)),
        Ok(Proposed::Found(p)) => p,
    };
    let nbar: Vec<f64> = p.forces.iter().map(|f| f.n).collect();
    let capacity = capacities(model, &nbar);
    // By Clarabel (no chain, no simplex): the check reads its duals.
    let Ok(Some(verify)) = solve_fixed(model, settings, None, None, &capacity, false) else {
        return Ok((2, None));
    };
    let Some(verifying) = verify.dual.as_ref() else {
        return Ok((2, None));
    };
    if verifying.status != SolverStatus::Solved
        || (verify.lambda - p.lambda).abs() > tol * verify.lambda.abs().max(1.0)
    {
        return Ok((2, None));
    }
    let iterate = read_fixed(
        model,
        settings,
        &verifying.problem,
        &p.x,
        &verifying.z,
        (p.lambda, SolverStatus::Solved, verify.result.iterations),
        "fixed point of the mechanism, verified by the program of its capacities".to_string(),
        0,
    )?;
    Ok((
        2,
        fixed_point(model, &nbar, &iterate, tol).then_some(iterate),
    ))
}

/// Iterate from the normal forces `n0` (N, joint order).
fn iterate_from(
    model: &Model,
    settings: &StaticSettings,
    na: &NonAssociativeSettings,
    mut chain: Option<FixedShearChain>,
    mut lp: Option<FixedShearLp>,
    start: Start,
    n0: Vec<f64>,
) -> Result<(StartOutcome, Option<StaticResult>), AnalysisError> {
    let mut nbar = n0;
    let mut beta = na.relaxation;
    let mut lambdas: Vec<f64> = Vec::new();
    let mut turns = 0;
    let mut iterations = 0;
    let mut programs = 0;
    let mut last: Option<StaticResult> = None;
    let mut stopped = format!("no fixed point in {} iterations", na.max_iterations);
    // Proposals that were not verified.
    let mut failed = 0;
    while iterations < na.max_iterations {
        iterations += 1;
        let capacity = capacities(model, &nbar);
        let least = start == Start::LeastFriction;
        let Some(it) = solve_fixed(
            model,
            settings,
            chain.as_mut(),
            lp.as_mut(),
            &capacity,
            least,
        )?
        else {
            programs += 1;
            stopped = format!(
                "the program with the capacities of iteration {iterations} has no solution"
            );
            break;
        };
        programs += it.programs;
        let settled = lambdas.last().is_some_and(|&prev| {
            (it.lambda - prev).abs() <= na.tolerance * it.lambda.abs().max(1.0)
        }) && fixed_point(model, &nbar, &it, na.tolerance);
        lambdas.push(it.lambda);
        if settled {
            return Ok(StartOutcome::settled(
                start,
                it.result,
                programs,
                SettledBy::Relaxation,
            ));
        }
        // Damp an oscillation: successive increments of opposite signs, twice in a row.
        if let [.., a, b, c] = lambdas[..] {
            if (c - b) * (b - a) < 0.0 {
                turns += 1;
                if turns >= 2 && beta > MIN_RELAXATION {
                    beta = (beta * 0.5).max(MIN_RELAXATION);
                    turns = 0;
                }
            } else {
                turns = 0;
            }
        }
        // The fixed point of this program's mechanism, tried aside: verified, it is the
        // answer; otherwise the relaxation goes on as if it had not been tried.
        // Not on the active set's or the simplex's path, even for a program either hands to
        // Clarabel: those paths relax (docs/friction.md).
        let proposing = na.mechanism_step
            && chain.is_none()
            && lp.is_none()
            && iterations >= FIRST_PROPOSAL
            && failed < MAX_FAILED_PROPOSALS;
        if let (true, Some(dual)) = (proposing, &it.dual) {
            let (tried, found) = mechanism_step(model, settings, dual, na.tolerance)?;
            programs += tried;
            match found {
                Some(found) => {
                    return Ok(StartOutcome::settled(
                        start,
                        found.result,
                        programs,
                        SettledBy::MechanismStep,
                    ));
                }
                // Nothing to propose from, now or later (a conic program, rows that do not
                // match, or no dual to weigh them).
                None if tried == 0 => failed = MAX_FAILED_PROPOSALS,
                None => failed += 1,
            }
        }
        for (nb, f) in nbar.iter_mut().zip(&it.forces) {
            *nb += beta * (f.n - *nb);
        }
        last = Some(it.result);
    }
    Ok((
        StartOutcome {
            start,
            lambda: last.as_ref().and_then(|r| r.lambda),
            iterations: programs,
            settled_by: None,
            stopped: Some(stopped),
        },
        None,
    ))
}

/// The non-associative multiplier of `model` in `settings.direction`, given its associative
/// static result `associative` (a collapse with forces; otherwise nothing is iterated and the
/// answer has no multiplier). Each start of [`Start`] is iterated; the lowest converged
/// multiplier is kept.
pub fn analyse_non_associative(
    model: &Model,
    settings: &StaticSettings,
    associative: &StaticResult,
    na: &NonAssociativeSettings,
) -> Result<NonAssociative, AnalysisError> {
    let clock = Instant::now();
    let mut out = NonAssociative {
        lambda: None,
        converged: false,
        iterations: 0,
        sliding: Vec::new(),
        starts: Vec::new(),
        result: None,
        from_exact: false,
        unsearched: false,
        solve_time_s: 0.0,
    };
    let Some(forces) = associative
        .forces
        .as_ref()
        .filter(|_| associative.status == Status::Collapse)
    else {
        return Ok(out);
    };
    let n_associative: Vec<f64> = forces.iter().map(|f| f.n).collect();
    let chain = FixedShearChain::new(model, settings);
    let capacity = capacities(model, &n_associative);
    let lp = na
        .simplex
        .then(|| FixedShearLp::new(model, settings, chain.is_some(), &capacity))
        .flatten();
    let mut starts = vec![
        (Start::Associative, n_associative.clone()),
        (Start::LeastFriction, n_associative),
    ];
    // The at-rest start's phase-one program relaxes every inequality row by tau (rows of two
    // entries, not bounds): it stays with Clarabel (one program per analysis), or with the
    // chain's active set on a chain.
    let rest = match chain.as_ref().and_then(|_| FixedShearChain::at_rest(model)) {
        Some(rest) => rest,
        None => {
            let rest = super::stands(model, settings)?;
            rest.stands
                .then(|| rest.forces.iter().map(|f| f.n).collect())
        }
    };
    if let Some(n) = rest {
        starts.push((Start::AtRest, n));
    }
    // The starts are independent: run them side by side, and read them in their order.
    let outcomes: Vec<_> = starts
        .into_par_iter()
        .map(|(start, n0)| {
            let mut lp = lp.clone();
            if let Some(lp) = lp.as_mut() {
                lp.start_at(model, &n0);
            }
            iterate_from(model, settings, na, chain.clone(), lp, start, n0)
        })
        .collect();
    let mut best: Option<StaticResult> = None;
    for found in outcomes {
        let (outcome, result) = found?;
        out.iterations += outcome.iterations;
        if let (true, Some(r)) = (outcome.converged(), result) {
            let value = |x: &StaticResult| x.lambda.unwrap_or(f64::INFINITY);
            if best.as_ref().is_none_or(|b| value(&r) < value(b)) {
                best = Some(r);
            }
        }
        out.starts.push(outcome);
    }
    if let Some(r) = best {
        out.converged = true;
        out.lambda = r.lambda;
        out.sliding = slipping_joints(&model.assembly, &r.mechanism, &r.open);
        out.result = Some(r);
    }
    out.solve_time_s = clock.elapsed().as_secs_f64();
    Ok(out)
}
