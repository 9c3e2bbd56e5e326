//! Static (lower-bound) limit analysis: the largest load multiplier lambda for which the
//! blocks can be in equilibrium with no-tension joints whose resultants stay inside them and
//! whose shear obeys Coulomb's law — the safe theorem of limit analysis for masonry
//! (Heyman, *The Stone Skeleton*, 1995; Livesley, 1978; Gilbert, Casapulla & Ahmed, 2006).
//! With rigid joints the program is linear (a conic program over the zero and nonnegative
//! cones) and is solved with Clarabel; with a finite compressive strength (a rectangular stress
//! block, [`crate::model::Strength`]; Gilbert, Casapulla & Ahmed's crushing extension, as in
//! RING) every joint adds two rotated second-order cones; the chain program is then solved by
//! a working set (`chain/working_set.rs`: an active set on the curved crushing laws from the
//! rigid hinges, Clarabel on the cones of a few joints next, every joint checked), Clarabel
//! on all joints as the fallback. For associative (non-sliding or normality) joints its optimum is the
//! collapse multiplier; the duals of the equilibrium rows are the virtual velocities of the
//! blocks, i.e. the collapse mechanism.

mod chain;
pub(crate) mod conic;
pub mod design;
mod friction;
mod mirror;
pub mod non_associative;
mod problem;
mod settings;
pub mod simplex;

pub use chain::{analyse_chain, declines, Declined};
pub use friction::{slipping_joints, FrictionCheck, SLIP_TOL};
pub use non_associative::{
    analyse_non_associative, NonAssociative, NonAssociativeSettings, SettledBy, Start, StartOutcome,
};

pub use crate::outcome::{Direction, Status, LAMBDA_CAP};
pub use problem::{column, Objective, StaticProblem};
pub use settings::{Program, Refinement, StaticSettings, LARGE_KKT};

use crate::assembly::{Assembly, Hinge, JointEnd, JointForce};
use crate::error::AnalysisError;
use crate::interaction::contact::ShearLimit;
use crate::model::{Model, PassiveForce, Strength, StripForce, TieForce};
use clarabel::solver::SolverStatus;
use std::time::Instant;

/// Size of the conic program that was solved.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
pub struct ModelSize {
    pub variables: usize,
    pub constraints: usize,
    pub equality_rows: usize,
    pub inequality_rows: usize,
    pub friction_rows: usize,
    /// Rows in second-order cones (the crushing cones: 3 per cone, 2 cones per joint; 0 for
    /// rigid joints). Counted in `constraints`.
    pub cone_rows: usize,
}

/// Result of the static analysis.
#[derive(Debug, Clone)]
pub struct StaticResult {
    pub status: Status,
    /// The collapse multiplier (status `Collapse` only).
    pub lambda: Option<f64>,
    /// Joint forces at collapse (status `Collapse` only), in joint order.
    pub forces: Option<Vec<JointForce>>,
    /// Joints whose resultant sits at an end.
    pub hinges: Vec<Hinge>,
    /// Joints where `|V| = mu N`.
    pub sliding: Vec<usize>,
    /// Joints that carry no force at collapse (opened completely).
    pub open: Vec<usize>,
    /// Virtual velocities `[vx, vy, omega]` of the blocks (centroid velocity and rotation
    /// rate, rad per unit time), scaled so the fastest centroid moves at 1. Empty when not
    /// collapsing.
    pub mechanism: Vec<[f64; 3]>,
    /// Largest out-of-balance force of any block (N), 0 when there are no forces.
    pub equilibrium_residual: f64,
    pub direction: Direction,
    /// Wall time of building and solving the program (s).
    pub solve_time_s: f64,
    /// Interior-point iterations, or the active-set method's pivots (`solver_status` says
    /// which ran).
    pub iterations: u32,
    /// Clarabel's status word, for the record.
    pub solver_status: String,
    /// Whether the multiplier is an exact vertex of the chain program (its active-set method,
    /// or the interior point's solution moved onto the vertex): the dispatcher of
    /// [`analyse`] trusts such a collapse and sends the others to the full program.
    pub exact_vertex: bool,
    pub model: ModelSize,
    /// The tie rods' forces at collapse, in tie order (empty without ties or collapse).
    pub ties: Vec<TieForce>,
    /// The bonded strips' forces at collapse, in strip order (empty without strips or
    /// collapse).
    pub strips: Vec<StripForce>,
    /// The fill's passive reactions at collapse, in face order (empty without
    /// `[fill] passive` or collapse).
    pub passive: Vec<PassiveForce>,
}

/// Run the static analysis of `model` (an assembly and its loads).
pub fn analyse(model: &Model, settings: &StaticSettings) -> Result<StaticResult, AnalysisError> {
    if settings.program == Program::Auto && chain::declines(model).is_none() {
        // The chain's program is exact when its vertex step lands; when it does not (a
        // degenerate optimum) or the interior-point solve falls short, the full program,
        // the proven path, decides.
        // With finite compressive strength the chain program is conic (no vertex to land on):
        // its interior-point solution is the answer, as the full program's is.
        let conic = model.strength.is_finite();
        match analyse_chain(model, settings) {
            Ok(r) if conic || r.status != Status::Collapse || r.exact_vertex => return Ok(r),
            Ok(_) | Err(AnalysisError::SolverFailed { .. }) => {}
            Err(e) => return Err(e),
        }
    }
    analyse_full(model, settings)
}

/// The static analysis by the full program (any assembly).
pub fn analyse_full(
    model: &Model,
    settings: &StaticSettings,
) -> Result<StaticResult, AnalysisError> {
    let start = Instant::now();
    let assembly = &model.assembly;
    model.validate()?;
    let sign = settings.direction.sign();
    let strength = model.strength;
    let problem = StaticProblem::of_model(
        model,
        ShearLimit::Coulomb,
        Objective::MaxLambda { sign, cap: None },
    );
    let mut sol = run(&problem, settings)?;
    let mut size = problem_size(&problem);
    let mut lambda_capped = false;
    if matches!(
        sol.status,
        SolverStatus::DualInfeasible | SolverStatus::AlmostDualInfeasible
    ) {
        // Unbounded above, or both infeasible: a capped program tells which.
        let capped = StaticProblem::of_model(
            model,
            ShearLimit::Coulomb,
            Objective::MaxLambda {
                sign,
                cap: Some(LAMBDA_CAP),
            },
        );
        sol = run(&capped, settings)?;
        size = problem_size(&capped);
        lambda_capped = true;
    }
    let mut result =
        StaticResult::unsolved(settings, sol.iterations, format!("{:?}", sol.status), size);
    match sol.status {
        SolverStatus::Solved | SolverStatus::AlmostSolved => {
            let lambda = sol.x[0];
            let forces = read_forces(assembly, &problem, &sol.x);
            let tensions = Tensions::read(&problem, &sol.x);
            let residual = tensions.residual(model, &forces, lambda, sign);
            check_almost_solved(sol.status, residual, problem.force_scale, sol.iterations)?;
            result = result.read_solution(
                assembly,
                strength,
                settings,
                lambda,
                forces,
                residual,
                lambda_capped,
                || read_mechanism(assembly, &problem, &sol.z),
            );
            result.read_interactions(model, &tensions.ties, &tensions.strips, &tensions.passive);
        }
        SolverStatus::PrimalInfeasible | SolverStatus::AlmostPrimalInfeasible => {
            result.status = Status::CannotStand;
        }
        other => result = result.settle_stalled(model, settings, other)?,
    }
    result = stands_at_zero(model, settings, result)?;
    result.solve_time_s = start.elapsed().as_secs_f64();
    Ok(result)
}

/// Whether `model` is its own mirror image under self-weight alone, its ties and strips
/// included: its multipliers toward the right and the left are then the same. The blocks and
/// joints may be numbered in any order (`mirror::mirror_map`).
pub fn symmetric_self_weight(model: &Model) -> bool {
    model.loads.is_self_weight_only()
        && model.passive.is_empty()
        && mirror::mirror_map(&model.assembly).is_some_and(|m| interactions_symmetric(model, &m))
}

/// Whether the ties and the strips of `model` (whose assembly maps onto its own mirror image
/// by `map`) are their own mirror image: each one's image is another of them, one for one,
/// with the same capacity and prestress.
fn interactions_symmetric(model: &Model, map: &mirror::MirrorMap) -> bool {
    use crate::interaction::Anchor;
    let tol = 1e-9 * model.assembly.size();
    let image = |a: Anchor, b: Anchor| {
        a.block.map(|i| map.blocks[i]) == b.block && (map.point(a.point) - b.point).norm() <= tol
    };
    let close = |a: f64, b: f64| a == b || (a - b).abs() <= 1e-12 * a.abs().max(b.abs());
    // Greedy one-for-one matching: "is the image of" pairs equal items, so it cannot miss.
    let matched = |n: usize, pairs: &dyn Fn(usize, usize) -> bool| {
        let mut used = vec![false; n];
        (0..n).all(|i| {
            let j = (0..n).find(|&j| !used[j] && pairs(i, j));
            j.map(|j| used[j] = true).is_some()
        })
    };
    let ties = &model.ties;
    let strips = &model.strips;
    matched(ties.len(), &|i, j| {
        let (t, u) = (&ties[i], &ties[j]);
        close(t.capacity, u.capacity)
            && close(t.prestress, u.prestress)
            && ((image(t.from, u.from) && image(t.to, u.to))
                || (image(t.from, u.to) && image(t.to, u.from)))
    }) && matched(strips.len(), &|i, j| {
        let (s, u) = (&strips[i], &strips[j]);
        u.joint == map.joints[s.joint].0
            && u.end == map.end(s.joint, s.end)
            && close(s.capacity, u.capacity)
    })
}

/// Under loads or a structure that are not symmetric the multipliers equilibrium allows form
/// an interval that may lie entirely above 0; then the structure cannot stand without the
/// earthquake. The least multiplier (chains) or the phase-one program at lambda = 0 tells.
/// A mirror-symmetric structure under self-weight alone (its ties and strips included) needs
/// no test: the mirror image of an equilibrium at lambda is one at -lambda, so the interval
/// straddles 0.
fn stands_at_zero(
    model: &Model,
    settings: &StaticSettings,
    result: StaticResult,
) -> Result<StaticResult, AnalysisError> {
    if result.status == Status::CannotStand || symmetric_self_weight(model) {
        return Ok(result);
    }
    // On a chain the least multiplier tells at the cost of one more active-set solve; the
    // phase-one program (a conic solve of the full program) otherwise.
    let why = match (settings.active_set)
        .then(|| chain::least_lambda(model, settings))
        .flatten()
    {
        Some(least) if least <= 0.0 => return Ok(result),
        Some(least) => format!("the least multiplier equilibrium allows is {least:.6} > 0"),
        None => {
            let stand = stands(model, settings)?;
            if stand.stands {
                return Ok(result);
            }
            format!("the phase-one least tension is {:.3e} N > 0", stand.tension)
        }
    };
    Ok(StaticResult {
        solve_time_s: result.solve_time_s,
        ..StaticResult::unsolved(
            settings,
            result.iterations,
            format!("{}; at lambda = 0 {why}", result.solver_status),
            result.model,
        )
    })
}

impl StaticResult {
    /// At collapse, the ties' and the strips' forces from their tensions and the passive
    /// reactions (N, in their order), and no hinge where a strip holds the joint's other end.
    fn read_interactions(&mut self, model: &Model, ties: &[f64], strips: &[f64], passive: &[f64]) {
        if self.status != Status::Collapse {
            return;
        }
        self.set_tensions(model, ties, strips, passive);
        // A joint whose contact resultant sits at one end is no hinge while a strip on its
        // other end holds below its capacity: it cannot open there.
        let strip_forces = &self.strips;
        self.hinges.retain(|h| {
            !model
                .strips
                .iter()
                .zip(strip_forces)
                .any(|(s, f)| s.joint == h.joint && s.end != h.end && !f.yielded)
        });
    }

    /// The ties' and the strips' forces from their tensions, and the passive reactions (N, in
    /// their order).
    fn set_tensions(&mut self, model: &Model, ties: &[f64], strips: &[f64], passive: &[f64]) {
        self.passive = model
            .passive
            .iter()
            .zip(passive)
            .map(|(p, &f)| p.force_of(f))
            .collect();
        self.ties = model
            .ties
            .iter()
            .zip(ties)
            .map(|(t, &f)| t.force_of(f))
            .collect();
        self.strips = model
            .strips
            .iter()
            .zip(strips)
            .map(|(s, &f)| s.force_of(f))
            .collect();
    }

    /// A result with no solution read yet: status cannot stand, no multiplier.
    fn unsolved(
        settings: &StaticSettings,
        iterations: u32,
        solver_status: String,
        model: ModelSize,
    ) -> Self {
        StaticResult {
            status: Status::CannotStand,
            lambda: None,
            forces: None,
            hinges: Vec::new(),
            sliding: Vec::new(),
            open: Vec::new(),
            mechanism: Vec::new(),
            equilibrium_residual: 0.0,
            direction: settings.direction,
            solve_time_s: 0.0,
            iterations,
            solver_status,
            exact_vertex: false,
            model,
            ties: Vec::new(),
            strips: Vec::new(),
            passive: Vec::new(),
        }
    }

    /// Read a solution with multiplier `lambda` and joint forces `forces` (equilibrium
    /// residual `residual`): a negative multiplier cannot stand, one at the cap (when the
    /// program was capped) does not collapse, and at collapse the joints' states, the
    /// mechanism (`mechanism`, read only then) and the forces are kept.
    #[allow(clippy::too_many_arguments)]
    fn read_solution(
        mut self,
        assembly: &Assembly,
        strength: Strength,
        settings: &StaticSettings,
        lambda: f64,
        forces: Vec<JointForce>,
        residual: f64,
        capped: bool,
        mechanism: impl FnOnce() -> Vec<[f64; 3]>,
    ) -> Self {
        if lambda < 0.0 {
            self.status = Status::CannotStand;
        } else if capped && lambda >= LAMBDA_CAP * (1.0 - 1e-6) {
            self.status = Status::NoCollapse;
        } else {
            self.status = Status::Collapse;
            self.lambda = Some(lambda);
            self.equilibrium_residual = residual;
            let states = classify_joints(assembly, strength, &forces, settings.hinge_tolerance);
            self.hinges = states.hinges;
            self.sliding = states.sliding;
            self.open = states.open;
            self.mechanism = mechanism();
            self.forces = Some(forces);
        }
        self
    }

    /// The interior point stopped short (`status`): next to the minimum thickness the program
    /// is nearly infeasible and may stall; the phase-one program settles it, a positive least
    /// tension certifying that nothing stands at lambda = 0. Otherwise the failure is an error.
    fn settle_stalled(
        mut self,
        model: &Model,
        settings: &StaticSettings,
        status: SolverStatus,
    ) -> Result<Self, AnalysisError> {
        let stand = stands(model, settings)?;
        if stand.stands {
            return Err(AnalysisError::SolverFailed {
                status: format!("{status:?}"),
                iterations: self.iterations,
            });
        }
        self.status = Status::CannotStand;
        self.solver_status = format!(
            "{status:?}; phase-one least tension {:.3e} N > 0",
            stand.tension
        );
        Ok(self)
    }
}

/// An AlmostSolved solution is read only when its equilibrium residual is small.
fn check_almost_solved(
    status: SolverStatus,
    residual: f64,
    force_scale: f64,
    iterations: u32,
) -> Result<(), AnalysisError> {
    if status == SolverStatus::AlmostSolved && residual > 1e-6 * force_scale {
        return Err(AnalysisError::SolverFailed {
            status: format!("AlmostSolved with equilibrium residual {residual:.3e} N"),
            iterations,
        });
    }
    Ok(())
}

fn problem_size(p: &StaticProblem) -> ModelSize {
    ModelSize {
        variables: p.variables(),
        constraints: p.equality_rows + p.inequality_rows + p.cone_rows,
        equality_rows: p.equality_rows,
        inequality_rows: p.inequality_rows,
        friction_rows: 2 * p.friction_joints.len(),
        cone_rows: p.cone_rows,
    }
}

use conic::Solution as RawSolution;

fn run(problem: &StaticProblem, s: &StaticSettings) -> Result<RawSolution, AnalysisError> {
    solve_conic(
        &problem.p,
        &problem.q,
        &problem.a,
        &problem.b,
        &problem.cones,
        s,
    )
}

/// Solve `min q'x + x'Px/2  s.t.  A x + s = b, s in cones` with Clarabel under `s`
/// ([`conic::solve`]: a large program is first solved without iterative refinement under
/// [`Refinement::Auto`], and again with it when that solve does not end solved or infeasible).
fn solve_conic(
    p: &clarabel::algebra::CscMatrix<f64>,
    q: &[f64],
    a: &clarabel::algebra::CscMatrix<f64>,
    b: &[f64],
    cones: &[clarabel::solver::SupportedConeT<f64>],
    s: &StaticSettings,
) -> Result<RawSolution, AnalysisError> {
    let program = conic::Conic { p, q, a, b, cones };
    let knobs = conic::Knobs {
        tol_gap: s.tol_gap,
        tol_feas: s.tol_feas,
        max_iter: s.max_iter,
        linear_solver: Some(&s.linear_solver),
        refinement: s.refinement,
    };
    conic::solve(&program, &knobs).map_err(AnalysisError::SolverSetup)
}

fn read_forces(assembly: &Assembly, p: &StaticProblem, x: &[f64]) -> Vec<JointForce> {
    assembly
        .joints
        .iter()
        .enumerate()
        .map(|(j, jt)| {
            // Interior-point iterates sit a hair inside the cone; a fully open joint's c1, c2
            // are round-off of either sign. Clamp so N >= 0 and |e| <= L/2 exactly.
            let c1 = x[column(j, 0)].max(0.0) * p.force_scale;
            let c2 = x[column(j, 1)].max(0.0) * p.force_scale;
            let v = x[column(j, 2)] * p.force_scale;
            JointForce {
                n: c1 + c2,
                v,
                m: 0.5 * (c2 - c1) * jt.length(),
            }
        })
        .collect()
}

/// The tensions of the interactions beside the contacts read from a solution `x` (N): the
/// ties', the strips' and the passive reactions', each in its own order.
struct Tensions {
    ties: Vec<f64>,
    strips: Vec<f64>,
    passive: Vec<f64>,
}

impl Tensions {
    fn read(p: &StaticProblem, x: &[f64]) -> Tensions {
        let read = |columns: &[usize]| columns.iter().map(|&c| x[c] * p.force_scale).collect();
        Tensions {
            ties: read(&p.tie_columns),
            strips: read(&p.strip_columns),
            passive: read(&p.passive_columns),
        }
    }

    /// The largest out-of-balance force of any block of `model` (N) with the joint forces
    /// `forces` and these tensions at the multiplier `lambda` toward `sign`.
    fn residual(&self, model: &Model, forces: &[JointForce], lambda: f64, sign: f64) -> f64 {
        model.residual_with_passive(
            forces,
            &self.ties,
            &self.strips,
            &self.passive,
            lambda,
            sign,
        )
    }
}

/// What the joint forces say about each joint: hinges, sliding joints, open joints.
#[derive(Debug, Default)]
struct JointStates {
    hinges: Vec<Hinge>,
    sliding: Vec<usize>,
    open: Vec<usize>,
}

/// A joint is a hinge when its resultant lies within `tol L` of the farthest point it may
/// reach: the joint's end for rigid joints, the centre of the compressed zone (`a/2` from the
/// end, `a = N/(fc d)`) with finite strength, where the crushing cone is tight.
fn classify_joints(
    assembly: &Assembly,
    strength: Strength,
    forces: &[JointForce],
    tol: f64,
) -> JointStates {
    let mut states = JointStates::default();
    let nmax = forces.iter().fold(0.0_f64, |a, f| a.max(f.n));
    for (j, (jt, f)) in assembly.joints.iter().zip(forces).enumerate() {
        if f.n <= tol * nmax {
            states.open.push(j);
            continue;
        }
        let length = jt.length();
        let zone = strength.compressed_zone(f.n);
        let reach = 0.5 * (length - zone);
        let e = f.m / f.n;
        let hinge = |end| {
            if strength.is_finite() {
                Hinge::crushing(assembly, j, end, zone)
            } else {
                Hinge::at(assembly, j, end)
            }
        };
        // Rigid joints: the end, within tol L (written as before crushing, so rigid results
        // stay bit for bit the same).
        let limit = if zone > 0.0 {
            reach - tol * length
        } else {
            reach * (1.0 - 2.0 * tol)
        };
        if e >= limit {
            states.hinges.push(hinge(JointEnd::P2));
        } else if e <= -limit {
            states.hinges.push(hinge(JointEnd::P1));
        }
        if jt.friction.is_finite() && f.v.abs() >= (1.0 - tol) * jt.friction * f.n {
            states.sliding.push(j);
        }
    }
    states
}

fn read_mechanism(assembly: &Assembly, p: &StaticProblem, z: &[f64]) -> Vec<[f64; 3]> {
    // Moment rows are divided by the length scale, so their duals are rotations times it.
    let mut v: Vec<[f64; 3]> = (0..assembly.blocks.len())
        .map(|i| [z[3 * i], z[3 * i + 1], z[3 * i + 2] / p.length_scale])
        .collect();
    let vmax = v
        .iter()
        .fold(0.0_f64, |a, b| a.max((b[0] * b[0] + b[1] * b[1]).sqrt()));
    if vmax > 0.0 {
        for b in &mut v {
            for c in b.iter_mut() {
                *c /= vmax;
            }
        }
    }
    v
}

impl StaticResult {
    /// Eccentricity e = M/N of each joint (None where N = 0 or there are no forces).
    /// The thrust-line point of every joint (`p_mid + e u`), None where the joint carries no
    /// force or has opened completely.
    pub fn thrust_points(&self, assembly: &Assembly) -> Vec<Option<crate::geometry::Vec2>> {
        // One pass, not eccentricity() per joint: that scans `open` each time.
        let mut points = self
            .forces
            .as_ref()
            .map(|f| crate::assembly::thrust_points(assembly, f))
            .unwrap_or_else(|| vec![None; assembly.joints.len()]);
        for &j in &self.open {
            points[j] = None;
        }
        points
    }

    pub fn eccentricity(&self, joint: usize) -> Option<f64> {
        if self.open.contains(&joint) {
            // An open joint carries only solver round-off: its resultant has no position.
            return None;
        }
        let f = self.forces.as_ref()?.get(joint)?;
        (f.n > 0.0).then(|| f.m / f.n)
    }
}

/// Result of the phase-one program at lambda = 0 (see [`Objective::MinTension`]).
#[derive(Debug, Clone)]
pub struct StandResult {
    /// Whether the structure can carry its own weight (`tau <= 0`).
    pub stands: bool,
    /// The least uniform tension (N) every joint end would have to carry for equilibrium at
    /// lambda = 0; negative when the structure stands, by the margin of its weakest joint.
    pub tension: f64,
    /// The joint forces of that solution.
    pub forces: Vec<JointForce>,
    /// Joints whose resultant sits at an end (within the hinge tolerance), when it stands.
    pub hinges: Vec<Hinge>,
    pub equilibrium_residual: f64,
}

/// Whether `model` can stand under its permanent loads (lambda = 0), by the phase-one
/// program.
pub fn stands(model: &Model, settings: &StaticSettings) -> Result<StandResult, AnalysisError> {
    stands_full(model, settings)
}

/// Whether `model` stands under its permanent loads (lambda = 0), and nothing else: on a chain
/// (with [`Program::Auto`] and the active set on) one active-set solve of the chain program in
/// its redundants, a few microseconds per hundred joints; the phase-one program of [`stands`]
/// otherwise, and whenever the active set does not decide. The minimum-thickness search calls
/// this at every trial thickness.
pub fn stands_at_rest(model: &Model, settings: &StaticSettings) -> Result<bool, AnalysisError> {
    if settings.program == Program::Auto && settings.active_set {
        model.validate()?;
        if let Some(stands) = chain::stands_at_rest(model) {
            return Ok(stands);
        }
    }
    Ok(stands_full(model, settings)?.stands)
}

/// The phase-one program on the full program (any assembly).
fn stands_full(model: &Model, settings: &StaticSettings) -> Result<StandResult, AnalysisError> {
    let assembly = &model.assembly;
    model.validate()?;
    let problem = StaticProblem::of_model(model, ShearLimit::Coulomb, Objective::MinTension);
    let sol = run(&problem, settings)?;
    if !matches!(
        sol.status,
        SolverStatus::Solved | SolverStatus::AlmostSolved
    ) {
        return Err(AnalysisError::SolverFailed {
            status: format!("{:?} (stand test at lambda = 0)", sol.status),
            iterations: sol.iterations,
        });
    }
    let tau = sol.x[0];
    // Undo the relaxation so the forces are those of a real (tau <= 0) thrust line.
    let forces = read_forces(assembly, &problem, &sol.x);
    let residual = Tensions::read(&problem, &sol.x).residual(model, &forces, 0.0, 1.0);
    let stands = tau <= 0.0;
    let hinges = if stands {
        classify_joints(assembly, model.strength, &forces, settings.hinge_tolerance).hinges
    } else {
        Vec::new()
    };
    Ok(StandResult {
        stands,
        tension: tau * problem.force_scale,
        forces,
        hinges,
        equilibrium_residual: residual,
    })
}
