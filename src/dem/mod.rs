//! Discrete element check of the collapse multiplier: the blocks of a model's assembly as 2D
//! rigid convex polygons moving in time under the model's permanent loads and its seismic
//! loads scaled by a constant multiplier `lambda`, touching through no-tension, cohesionless
//! Coulomb contacts — the distinct element method of Cundall (1971; Cundall & Strack 1979) as
//! used for masonry arches in UDEC (Lemos 2007, "Discrete element modeling of masonry
//! structures", Int. J. Archit. Herit. 1:190-213; DeJong, De Lorenzis, Adams & Ochsendorf
//! 2008).
//!
//! Model (see `world` for the equations):
//! - every assembly block is a rigid convex polygon with the mass and polar moment of the
//!   uniform polygon (`unit_weight depth / g` per unit area). Curved voussoirs are simulated
//!   by their chord polygon (the DEM does not model circular faces): their weight and centroid
//!   then differ slightly from the exact annular ones the static analysis uses;
//! - the loads come from the model's [`crate::model::LoadCase`] and nowhere else: each block's
//!   own weight `m0 g` down at its centroid, every other permanent load (point, line, fill) as
//!   a force fixed to the block at its point of application (it turns with the block, so its
//!   moment about the centroid is `cross(R r, F)`), and the seismic force
//!   `lambda W_s (1, vertical_ratio)` of the block's seismic weight `W_s` at its centre (the
//!   DEM shakes toward +x, the static program's default direction). The block's mass is its
//!   own plus the seismic masses `S / g` of its other loads, its polar inertia scaled in the
//!   same proportion; loads that are not seismic add force, not mass. With self-weight alone
//!   this is `W` down and `lambda W` along +x at every centroid, computed exactly as before
//!   loads existed;
//! - the ground is a fixed rectangle under every support joint;
//! - vertex-to-edge contacts, found by a sort-and-sweep broad phase and a vertex-in-polygon
//!   narrow phase every step, so blocks that separate and touch again are handled;
//! - penalty normal and shear springs with dashpots, no tension, no cohesion, Coulomb friction
//!   with the joints' coefficient (`inf` is replaced by `IntegrationParameters::
//!   infinite_friction` and reported);
//! - symplectic Euler (central differences) with Cundall's local damping, time step from the
//!   stability limit of the stiffest block.
//!
//! Protocol ([`collapse_multiplier`]): settle under the permanent loads ramped from 0; then,
//! from the settled state, runs at constant `lambda` (ramped in, then held) that end at rest
//! (tested once the load has been held for one ramp time), in collapse (a block point moved by the collapse displacement) or creeping (the
//! displacement kept growing at a non-decreasing rate for five windows); a bracket
//! `[lambda_stands, lambda_collapses]` is searched from a first guess (the static lower bound
//! of the same model by default) and narrowed by bisection until its width is below
//! `tolerance` times its midpoint. Both ends of the bracket are DEM runs.

mod active_set;
mod body;
pub mod dynamic;
// The DEM's settings and the `[dem]` table live beside it (`crate::dem_settings`), so a scene
// checks its `[dem]` knobs without importing the simulation.
use crate::dem_settings as params;
mod moreau;
mod protocol;
pub mod record;
pub mod rest;
mod world;

pub use crate::dem_settings::{
    allowed_range, show_value, IntegrationParameters, Integrator, Purpose, DEFAULT_MAX_STEPS,
    DEM_KEYS,
};
pub use protocol::{Onset, Outcome, Run, Snapshot};

use crate::assembly::{Assembly, Hinge};
use crate::error::AnalysisError;
use crate::geometry::Vec2;
use crate::model::Model;
use crate::statics;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Instant;
use thiserror::Error;
use world::World;

/// Failures of the DEM check that are not physical answers.
#[derive(Debug, Error)]
pub enum DemError {
    #[error("invalid assembly: {0}")]
    Assembly(#[from] AnalysisError),
    #[error("invalid DEM setting: {0}")]
    Settings(String),
    #[error("cannot write snapshots to {path}: {message}")]
    Output { path: PathBuf, message: String },
    /// A `[dem]` knob (or a builder setting) outside its range.
    #[error("{key} = {value}: {allowed}")]
    Knob {
        key: String,
        value: String,
        allowed: String,
    },
    /// A run would plan more time steps than the limit.
    #[error("{what} would take up to {steps:.3e} time steps of {time_step:.3e} s, above the limit of {limit} steps a run (check the settings: the default limit is met only by runs of hours; --max-steps N sets it; docs/dem.md)")]
    TooManySteps {
        what: String,
        steps: f64,
        time_step: f64,
        limit: u64,
    },
    /// Stopped by [`request_interrupt`] (Ctrl-C on the command line).
    #[error("interrupted after {steps} time steps: nothing is reported")]
    Interrupted { steps: u64 },
    #[error("the DEM models rigid contacts (point contacts at the block corners, with no cap on the normal force), so it cannot check a finite compressive strength (material.compressive_strength = {compressive_strength:e} Pa); run it without that key for the rigid structure, or rely on the static program, which models crushing")]
    FiniteStrength { compressive_strength: f64 },
}

/// Set by [`request_interrupt`] (the command line's Ctrl-C handler), read by every DEM time
/// loop every few steps: a run then stops and its search returns [`DemError::Interrupted`].
static INTERRUPT: AtomicBool = AtomicBool::new(false);

/// Ask every DEM run in this process to stop at its next check (a few time steps).
pub fn request_interrupt() {
    INTERRUPT.store(true, Ordering::Relaxed);
}

/// Whether an interrupt was asked for (and not cleared since).
pub fn interrupt_requested() -> bool {
    INTERRUPT.load(Ordering::Relaxed)
}

/// Forget an interrupt asked for (before starting new work in the same process).
pub fn clear_interrupt() {
    INTERRUPT.store(false, Ordering::Relaxed);
}

/// Penetration of a contact under the permanent loads, as a fraction of the shortest joint,
/// beyond which a run warns that the contacts are too soft to stand for rigid blocks (the
/// default stiffness gives about 1e-5).
pub const PENETRATION_WARNING: f64 = 0.01;

/// The first multiplier of a bracket search that is not told where to start and must not
/// lean on the static bound: `crate::analysis::dem_of` starts here unless the scene sets
/// `dem.initial_guess` or the caller asks for the static start. Independent of the structure
/// on purpose; the search widens or bisects from it (docs/dem.md).
pub const DEFAULT_INITIAL_GUESS: f64 = 0.2;

/// Where the bracket search started.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum GuessSource {
    /// `IntegrationParameters::initial_guess` (the scene's `dem.initial_guess`).
    Given,
    /// The static lower bound (solved by `collapse_multiplier`, or handed to it by the
    /// analysis layer's `--from-static` mode): the bracket then verifies that value.
    Static,
    /// [`DEFAULT_INITIAL_GUESS`]: nothing given (or the static program found no multiplier).
    Default,
}

/// Result of the DEM collapse search.
#[derive(Debug, Clone)]
pub struct DemResult {
    /// The structure does not settle under its own weight (it collapses, or does not come
    /// to rest within `max_time`): no multiplier.
    pub cannot_stand: bool,
    /// No collapse up to `max_lambda`.
    pub no_collapse: bool,
    /// Largest multiplier verified to stand (0 = the settling run itself).
    pub lambda_stands: Option<f64>,
    /// Smallest multiplier verified to collapse (or, if `undecided_runs > 0`, not to come to
    /// rest).
    pub lambda_collapses: Option<f64>,
    /// Midpoint of the bracket.
    pub lambda_dem: Option<f64>,
    /// `(lambda_collapses - lambda_stands) / lambda_dem`.
    pub bracket_width: Option<f64>,
    /// Hinges, sliding joints and fully open joints of the run at `lambda_collapses`, when
    /// the collapse displacement was reached.
    pub hinges: Vec<Hinge>,
    pub sliding: Vec<usize>,
    pub open: Vec<usize>,
    /// Every run, the settling one first.
    pub runs: Vec<Run>,
    /// Runs that neither came to rest nor collapsed within `max_time` (counted as not
    /// standing).
    pub undecided_runs: usize,
    /// Total time steps and wall time (s).
    pub steps: u64,
    pub wall_time_s: f64,
    /// The time step used (s).
    pub time_step: f64,
    /// The Coulomb coefficient the contacts used, and whether it stands for `inf`.
    pub friction: f64,
    pub friction_infinite: bool,
    /// First guess of the bracket search and where it came from.
    pub initial_guess: f64,
    pub guess_source: GuessSource,
    /// The settings used.
    pub params: IntegrationParameters,
    /// The most time steps one run could take (its longest length over the time step),
    /// checked against `params.max_steps` before the search starts.
    pub planned_steps_per_run: u64,
    /// What looked implausible (soft contacts, a time scale the defaults do not fit, the
    /// static program disagreeing): one sentence each.
    pub warnings: Vec<String>,
}

impl DemResult {
    /// The run at `lambda_stands` (the settling run if it is 0).
    pub fn standing_run(&self) -> Option<&Run> {
        let l = self.lambda_stands?;
        self.runs
            .iter()
            .find(|r| r.outcome == Outcome::Stands && r.lambda.unwrap_or(0.0) == l)
    }

    /// The run at `lambda_collapses`.
    pub fn collapsing_run(&self) -> Option<&Run> {
        let l = self.lambda_collapses?;
        self.runs
            .iter()
            .find(|r| r.outcome != Outcome::Stands && r.lambda == Some(l))
    }
}

/// The model must be valid: a valid assembly, and a load case that matches it with finite
/// loads on existing blocks.
fn check_model(model: &Model) -> Result<(), DemError> {
    model.validate()?;
    if model.strength.is_finite() {
        // Never a silent rigid run presented as the crushing one.
        return Err(DemError::FiniteStrength {
            compressive_strength: model.strength.compressive,
        });
    }
    let nb = model.assembly.blocks.len();
    for (k, l) in model.loads.applied().iter().enumerate() {
        let finite = [l.point.x, l.point.y, l.force.x, l.force.y, l.seismic_weight]
            .iter()
            .all(|v| v.is_finite());
        if l.block >= nb || !finite || l.seismic_weight < 0.0 {
            return Err(DemError::Assembly(AnalysisError::Assembly(format!(
                "applied load {k} (on block {} of {nb}) is not a finite load on a block",
                l.block
            ))));
        }
    }
    Ok(())
}

/// Every knob in its range ([`IntegrationParameters::check`]), and the contact tolerance
/// small against the shortest joint (the corner rounding would otherwise glue blocks).
fn check_params(params: &IntegrationParameters, model: &Model) -> Result<(), DemError> {
    params
        .check()
        .map_err(|(key, value, allowed)| DemError::Knob {
            key,
            value: params::show_value(value),
            allowed: allowed.to_string(),
        })?;
    if let Some(g) = params.initial_guess.filter(|g| *g > params.max_lambda) {
        return Err(DemError::Knob {
            key: "dem.initial_guess".to_string(),
            value: params::show_value(g),
            allowed: format!(
                "must be at most dem.max_lambda = {} (the search never looks above it)",
                params.max_lambda
            ),
        });
    }
    let joint = shortest_joint(&model.assembly);
    if params.contact_tolerance > 0.1 * joint {
        return Err(DemError::Knob {
            key: "dem.contact_tolerance".to_string(),
            value: params::show_value(params.contact_tolerance),
            allowed: format!(
                "must be at most 0.1 of the shortest joint ({joint:.4e} m; the default is 1e-3 of it)"
            ),
        });
    }
    Ok(())
}

/// The shortest joint of the assembly (m), or its size when it has none.
fn shortest_joint(assembly: &Assembly) -> f64 {
    assembly
        .joints
        .iter()
        .map(|j| j.length())
        .fold(assembly.size(), f64::min)
}

/// The time steps a stretch of `seconds` of simulated time takes, refused above
/// `params.max_steps` (`what` says which run, for the error).
fn check_steps(world: &World, seconds: f64, what: &str) -> Result<u64, DemError> {
    let steps = (seconds / world.dt).ceil();
    // A NaN step count (a NaN time) is refused with the rest.
    if steps.is_nan() || steps > world.params.max_steps as f64 {
        return Err(DemError::TooManySteps {
            what: what.to_string(),
            steps,
            time_step: world.dt,
            limit: world.params.max_steps,
        });
    }
    Ok(steps as u64)
}

/// The time step of `model` under `params` (s) and the most time steps one run may take: a
/// settling or constant-lambda run of the collapse search (`motion = None`), or the settling
/// plus a dynamic run of `motion` seconds (ground motion and tail) and its longest extension
/// to decide its end (`max_time`), and the time stepping those runs use (`params`'
/// integrator, [`Integrator::Auto`] decided for that purpose). Refused, before anything runs,
/// above `params.max_steps` ([`DemError::TooManySteps`]), or with a knob out of range.
pub fn plan(
    model: &Model,
    params: &IntegrationParameters,
    motion: Option<f64>,
) -> Result<(f64, u64, Integrator), DemError> {
    let purpose = match motion {
        None => Purpose::CollapseSearch,
        Some(_) => Purpose::GroundMotion,
    };
    let params = &params.resolved(model, purpose);
    check_model(model)?;
    check_params(params, model)?;
    let world = World::new(model, params);
    check_time_step(&world)?;
    let integrator = params.integrator;
    match motion {
        None => Ok((
            world.dt,
            check_steps(&world, longest_run(params), "each run of the search")?,
            integrator,
        )),
        Some(m) => {
            let settle = check_steps(&world, longest_run(params), "settling")?;
            let run = check_steps(
                &world,
                m + params.max_time,
                &format!(
                    "the dynamic run ({m:.4e} s of ground motion and tail, and up to dem.max_time = {:.4e} s more to decide its end)",
                    params.max_time
                ),
            )?;
            Ok((world.dt, settle.saturating_add(run), integrator))
        }
    }
}

/// Say so when some Moreau-Jean steps of the search ended with the contact laws broken
/// beyond the solve's tolerance (`World::unconverged`).
fn push_unconverged(result: &mut DemResult, unconverged: u64) {
    if unconverged > 0 {
        result
            .warnings
            .push(moreau::unconverged_warning(unconverged, result.steps));
    }
}

/// The longest a settling or constant-lambda run can last (s).
fn longest_run(params: &IntegrationParameters) -> f64 {
    params.ramp_time + params.max_time
}

/// Warnings about a settled world: contacts pressed in by more than
/// [`PENETRATION_WARNING`] of the shortest joint (soft contacts: the DEM then measures an
/// elastic structure, not rigid blocks), and a `max_time` short against the time scale of
/// the gravity used (a tiny `dem.gravity` slows everything down, and runs stop undecided).
fn settled_warnings(world: &World, model: &Model) -> Vec<String> {
    let mut out = Vec::new();
    let joint = shortest_joint(&model.assembly);
    let depth = world.max_penetration();
    if depth > PENETRATION_WARNING * joint {
        out.push(format!(
            "the contacts press in by {depth:.3e} m under the permanent loads, {:.1}% of the shortest joint ({joint:.3e} m): far softer than rigid blocks (the default stiffness gives about 0.001%); check dem.normal_stiffness",
            100.0 * depth / joint
        ));
    }
    let p = &world.params;
    let scale = (model.assembly.size() / p.gravity).sqrt();
    if p.max_time < 10.0 * scale {
        out.push(format!(
            "dem.max_time = {:.3e} s is short against the time scale sqrt(L / g) = {scale:.3e} s of dem.gravity = {} m/s^2: runs may stop undecided (read as not standing); check dem.gravity and dem.max_time",
            p.max_time, p.gravity
        ));
    }
    out
}

/// A time step above the explicit stability limit makes the integration blow up, which
/// would then read as a collapse: refuse it. The Moreau-Jean stepping has no such limit, but
/// a step longer than `MOREAU_MAX_STEP_SHARE` of the gravity time finds contacts too late,
/// and it cannot integrate the stiff bars of ties, strips and passive fill: refused too.
fn check_time_step(world: &World) -> Result<(), DemError> {
    if world.params.integrator == Integrator::Moreau {
        let size = world
            .bodies
            .iter()
            .filter_map(|b| b.block.map(|_| b.radius))
            .fold(0.0, f64::max);
        let limit = params::MOREAU_MAX_STEP_SHARE * (2.0 * size / world.params.gravity).sqrt();
        if !(world.dt > 0.0 && world.dt <= limit) {
            return Err(DemError::Settings(format!(
                "dem.time_step = {:e} s is too long for dem.integrator = \"moreau\": at most {limit:e} s ({} of the gravity time of the largest block)",
                world.dt,
                params::MOREAU_MAX_STEP_SHARE
            )));
        }
        if !world.bars.is_empty() {
            return Err(DemError::Settings(
                "dem.integrator = \"moreau\" does not model ties, strips or the fill's passive reaction (elastic bars as stiff as the explicit contacts): use dem.integrator = \"explicit\"".to_string(),
            ));
        }
        return Ok(());
    }
    if world.dt > world.stability_limit {
        return Err(DemError::Settings(format!(
            "dem.time_step = {:e} s exceeds the stability limit {:e} s of the stiffest contact (leave it unset to use {} of the limit)",
            world.dt, world.stability_limit, world.params.time_step_factor
        )));
    }
    Ok(())
}

/// Stop with [`DemError::Interrupted`] when an interrupt was asked for.
fn check_interrupt(steps: u64) -> Result<(), DemError> {
    if interrupt_requested() {
        Err(DemError::Interrupted { steps })
    } else {
        Ok(())
    }
}

/// A run whose block positions stopped being finite diverged: an error, not a collapse.
fn check_finite(run: &Run) -> Result<(), DemError> {
    if run.max_displacement.is_finite() {
        Ok(())
    } else {
        Err(DemError::Settings(
            "the simulation diverged (non-finite block positions): reduce dem.time_step_factor or the contact stiffness".to_string(),
        ))
    }
}

/// Block positions at one instant of a DEM run, as rigid motions of the assembly's blocks.
#[derive(Debug, Clone)]
pub struct Placements {
    /// Per block: translation of its centroid and rotation about it (rad).
    pub moves: Vec<(Vec2, f64)>,
    /// Simulated time of the snapshot within its run (s).
    pub time: f64,
}

impl Placements {
    /// The moves scaled so the largest corner displacement is `share` of the structure's
    /// size (never shrunk), with the factor used: collapse is detected at a small
    /// displacement, which a drawing must amplify to show.
    pub fn amplified(&self, assembly: &Assembly, share: f64) -> (Vec<(Vec2, f64)>, f64) {
        let largest = assembly
            .blocks
            .iter()
            .zip(&self.moves)
            .flat_map(|(b, &(d, rot))| {
                b.polygon
                    .iter()
                    .map(move |p| (moved(*p, b.centroid, d, rot) - p).norm())
            })
            .fold(0.0_f64, f64::max);
        let target = share * assembly.size();
        let amp = if largest > 0.0 && largest < target {
            target / largest
        } else {
            1.0
        };
        (
            self.moves.iter().map(|(d, r)| (amp * d, amp * r)).collect(),
            amp,
        )
    }
}

/// Where `p` of a block with centroid `c` goes under the rigid motion `(d, rot)`.
fn moved(p: Vec2, c: Vec2, d: Vec2, rot: f64) -> Vec2 {
    let (sn, cs) = rot.sin_cos();
    let r = p - c;
    c + d + Vec2::new(cs * r.x - sn * r.y, sn * r.x + cs * r.y)
}

/// The rigid motion (centroid translation, rotation) that takes polygon `before` (centroid
/// `c`) to `after`, vertex for vertex.
fn rigid_motion(before: &[Vec2], after: &[Vec2], c: Vec2) -> (Vec2, f64) {
    if before.len() < 2 || after.len() != before.len() {
        return (Vec2::zeros(), 0.0);
    }
    let (a0, a1) = (before[1] - before[0], after[1] - after[0]);
    let rot = a1.y.atan2(a1.x) - a0.y.atan2(a0.x);
    let at_origin = moved(before[0], c, Vec2::zeros(), rot) - c;
    (after[0] - at_origin - c, rot)
}

impl DemResult {
    /// The blocks at the last snapshot of the collapsing run (or of the last run), when
    /// snapshots were recorded.
    pub fn final_placements(&self, assembly: &Assembly) -> Option<Placements> {
        let last = self
            .collapsing_run()
            .or_else(|| self.runs.last())
            .and_then(|run| run.snapshots.last())?;
        // The simulation may store a block's vertices in another order: match them through
        // the first frame, where every block is still where the assembly put it.
        let first = self.runs.first().and_then(|run| run.snapshots.first())?;
        let moves = assembly
            .blocks
            .iter()
            .enumerate()
            .map(|(i, b)| {
                let now: Vec<Vec2> = b
                    .polygon
                    .iter()
                    .map(|p| {
                        let k = first.blocks[i]
                            .iter()
                            .enumerate()
                            .min_by(|x, y| (x.1 - p).norm().total_cmp(&(y.1 - p).norm()))
                            .map_or(0, |(k, _)| k);
                        last.blocks[i][k]
                    })
                    .collect();
                rigid_motion(&b.polygon, &now, b.centroid)
            })
            .collect();
        Some(Placements {
            moves,
            time: last.time,
        })
    }
}

/// The model the DEM actually simulates, when it differs from `model`: every block as its
/// polygon (curved voussoirs as their chord polygons) with the polygon's area, centroid and
/// weight (the unit weight of the block times the polygon's area, as `World::new` does),
/// and the same other loads, seismic masses and vertical ratio. `None` when every block
/// already is its polygon (relative area and centroid differences below 1e-12), so the static
/// bound of `model` is the one to compare a DEM bracket with.
pub fn simulated_model(model: &Model) -> Option<Model> {
    let assembly = &model.assembly;
    let mut changed = false;
    let mut blocks = assembly.blocks.clone();
    let size = assembly.size().max(f64::MIN_POSITIVE);
    for b in &mut blocks {
        if b.polygon.len() < 3 || b.area.is_nan() || b.area <= 0.0 {
            continue;
        }
        let (area, centroid) = crate::geometry::polygon_area_centroid(&b.polygon);
        let area = area.abs();
        if (area - b.area).abs() > 1e-12 * b.area || (centroid - b.centroid).norm() > 1e-12 * size {
            changed = true;
            b.weight *= area / b.area;
            b.area = area;
            b.centroid = centroid;
        }
    }
    if !changed {
        return None;
    }
    let polygons = Assembly {
        blocks,
        joints: assembly.joints.clone(),
    };
    let mut loads = crate::model::LoadCase::self_weight(&polygons)
        .with_vertical_ratio(model.loads.vertical_ratio())
        .with_action(model.loads.action());
    for l in model.loads.applied() {
        if l.source != crate::model::LoadSource::SelfWeight {
            loads.add(l.clone());
        }
    }
    for s in model.loads.spread() {
        loads.add_spread(*s);
    }
    // Everything else about the model (e.g. joint properties added later) stays as it is.
    let mut simulated = model.clone();
    simulated.assembly = polygons;
    simulated.loads = loads;
    Some(simulated)
}

/// Most runs one search may take (a bisection from a 1% bracket needs a handful).
const MAX_RUNS: usize = 60;

/// Bracket the collapse multiplier of `model` (its assembly under its load case) by DEM runs, to a relative width of
/// `tolerance` (e.g. 0.01). `progress` receives a fraction of the expected work in [0, 1].
pub fn collapse_multiplier(
    model: &Model,
    params: &IntegrationParameters,
    tolerance: f64,
    progress: &mut dyn FnMut(f64),
) -> Result<DemResult, DemError> {
    let clock = Instant::now();
    let params = &params.resolved(model, Purpose::CollapseSearch);
    let assembly = &model.assembly;
    check_model(model)?;
    if !(tolerance.is_finite() && tolerance > 0.0 && tolerance < 1.0) {
        return Err(DemError::Settings(format!(
            "tolerance = {tolerance}: must be > 0 and < 1"
        )));
    }
    let (guess, guess_source) = match params.initial_guess {
        Some(g) => (g, GuessSource::Given),
        None => match statics::analyse(model, &statics::StaticSettings::default()) {
            Ok(r) if r.lambda.is_some_and(|l| l > 0.0) => {
                (r.lambda.unwrap_or(0.2), GuessSource::Static)
            }
            _ => (DEFAULT_INITIAL_GUESS, GuessSource::Default),
        },
    };
    check_params(params, model)?;
    let mut world = World::new(model, params);
    check_time_step(&world)?;
    let planned = check_steps(&world, longest_run(params), "each run of the search")?;
    let friction_infinite = assembly.joints.iter().any(|j| j.friction.is_infinite());
    let mut result = DemResult {
        cannot_stand: false,
        no_collapse: false,
        lambda_stands: None,
        lambda_collapses: None,
        lambda_dem: None,
        bracket_width: None,
        hinges: Vec::new(),
        sliding: Vec::new(),
        open: Vec::new(),
        runs: Vec::new(),
        undecided_runs: 0,
        steps: 0,
        wall_time_s: 0.0,
        time_step: world.dt,
        friction: world.mu,
        friction_infinite,
        initial_guess: guess,
        guess_source,
        params: params.clone(),
        planned_steps_per_run: planned,
        warnings: Vec::new(),
    };

    // Progress: runs done plus the fraction of the current one, over the runs still expected.
    let mut reported: f64 = 0.0;
    let mut report = |done: f64, expected: f64, progress: &mut dyn FnMut(f64)| {
        let f = (done / expected.max(done + 0.5)).clamp(0.0, 0.99);
        if f > reported {
            reported = f;
            progress(f);
        }
    };

    let settle = protocol::run(&mut world, assembly, None, &mut |f| {
        report(f, 3.0, progress)
    });
    check_interrupt(result.steps + settle.steps)?;
    check_finite(&settle)?;
    result.warnings = settled_warnings(&world, model);
    let settled_ok = settle.outcome == Outcome::Stands;
    result.steps += settle.steps;
    result.runs.push(settle);
    // Moreau-Jean steps whose contact solve did not settle, over every run of the search
    // (each run starts from a copy of the settled world and its count).
    let mut unconverged = world.unconverged;
    if !settled_ok {
        push_unconverged(&mut result, unconverged);
        result.cannot_stand = true;
        result.wall_time_s = clock.elapsed().as_secs_f64();
        progress(1.0);
        return Ok(result);
    }
    world.time = 0.0;
    let settled = world;

    let h = 0.45 * tolerance;
    let mut lo = 0.0_f64;
    let mut hi: Option<f64> = None;
    let mut up = 4.0 * h;
    let mut down = 2.0 * h / (1.0 + h);
    for k in 0..MAX_RUNS {
        let x = match hi {
            None if lo == 0.0 => guess * (1.0 + h),
            None => {
                let x = lo * (1.0 + up);
                up *= 2.0;
                x
            }
            Some(hi) => {
                if hi - lo <= tolerance * 0.5 * (hi + lo) {
                    break;
                }
                let x = (0.5 * (lo + hi)).max(hi * (1.0 - down));
                down *= 2.0;
                x
            }
        };
        // A search that would step over the cap runs at the cap first: `no_collapse` is said
        // only of a structure verified to stand at `max_lambda`.
        let x = if hi.is_none() && x > params.max_lambda {
            if lo >= params.max_lambda {
                result.no_collapse = true;
                break;
            }
            params.max_lambda
        } else {
            x
        };
        let expected = 1.0
            + k as f64
            + match hi {
                None => 3.0,
                Some(hi) => 1.0 + ((hi - lo) / (tolerance * 0.5 * (hi + lo))).log2().max(0.0),
            };
        let mut w = settled.clone();
        let done = 1.0 + k as f64;
        let r = protocol::run(&mut w, assembly, Some(x), &mut |f| {
            report(done + f, expected, progress)
        });
        check_interrupt(result.steps + r.steps)?;
        check_finite(&r)?;
        result.steps += r.steps;
        unconverged += w.unconverged - settled.unconverged;
        match r.outcome {
            Outcome::Stands => lo = lo.max(x),
            Outcome::Collapses | Outcome::Creeps | Outcome::Undecided => {
                if r.outcome == Outcome::Undecided {
                    result.undecided_runs += 1;
                }
                if hi.is_none_or(|h| x < h) {
                    hi = Some(x);
                    if let Some(o) = &r.onset {
                        result.hinges = o.hinges.clone();
                        result.sliding = o.sliding.clone();
                        result.open = o.open.clone();
                    } else {
                        result.hinges.clear();
                        result.sliding.clear();
                        result.open.clear();
                    }
                }
            }
        }
        result.runs.push(r);
        report(done + 1.0, expected, progress);
    }
    push_unconverged(&mut result, unconverged);
    result.lambda_stands = Some(lo);
    result.lambda_collapses = hi;
    if let Some(hi) = hi {
        let mid = 0.5 * (lo + hi);
        result.lambda_dem = Some(mid);
        result.bracket_width = Some((hi - lo) / mid);
    }
    result.wall_time_s = clock.elapsed().as_secs_f64();
    progress(1.0);
    Ok(result)
}

/// Write the snapshots of the settling run, the run at `lambda_stands` and the run at
/// `lambda_collapses` as CSV files `settle.csv`, `stands.csv`, `collapses.csv` in `dir`
/// (created if needed), one row per block vertex: `time_s,lambda,block,vertex,x,y`.
/// Returns the files written. Snapshots are recorded only when
/// `IntegrationParameters::snapshot_interval` is set.
pub fn write_snapshots(dir: &Path, result: &DemResult) -> Result<Vec<PathBuf>, DemError> {
    let err = |path: &Path, e: &dyn std::fmt::Display| DemError::Output {
        path: path.to_path_buf(),
        message: e.to_string(),
    };
    std::fs::create_dir_all(dir).map_err(|e| err(dir, &e))?;
    let mut written = Vec::new();
    let stands = result.standing_run().filter(|r| r.lambda.is_some());
    let runs = [
        ("settle.csv", result.runs.first()),
        ("stands.csv", stands),
        ("collapses.csv", result.collapsing_run()),
    ];
    for (name, run) in runs {
        let Some(run) = run else { continue };
        let path = dir.join(name);
        let mut w = csv::Writer::from_path(&path).map_err(|e| err(&path, &e))?;
        w.write_record(["time_s", "lambda", "block", "vertex", "x", "y"])
            .map_err(|e| err(&path, &e))?;
        for s in &run.snapshots {
            for (b, poly) in s.blocks.iter().enumerate() {
                for (v, p) in poly.iter().enumerate() {
                    w.write_record([
                        format!("{:.6}", s.time),
                        format!("{:.6}", s.lambda),
                        b.to_string(),
                        v.to_string(),
                        format!("{:.9}", p.x),
                        format!("{:.9}", p.y),
                    ])
                    .map_err(|e| err(&path, &e))?;
                }
            }
        }
        w.flush().map_err(|e| err(&path, &e))?;
        written.push(path);
    }
    Ok(written)
}

/// One vertex-to-edge contact of a [`Simulation`].
#[derive(Debug, Clone, Copy)]
pub struct ContactState {
    pub vertex_block: Option<usize>,
    pub edge_block: Option<usize>,
    pub point: crate::geometry::Vec2,
    pub normal: crate::geometry::Vec2,
    pub normal_force: f64,
    pub shear_force: f64,
    pub sliding: bool,
}

/// Direct access to one DEM simulation, for checks and drawings: the same world and stages
/// `collapse_multiplier` uses.
#[derive(Debug, Clone)]
pub struct Simulation {
    world: World,
}

impl Simulation {
    /// The blocks of the model's assembly at rest in their assembly positions, carrying the
    /// model's loads at factor 0 (none applied yet).
    pub fn new(model: &Model, params: &IntegrationParameters) -> Result<Self, DemError> {
        check_model(model)?;
        check_params(params, model)?;
        let world = World::new(model, params);
        check_time_step(&world)?;
        Ok(Simulation { world })
    }
    /// Set the fraction of the permanent loads (gravity) and the seismic multiplier applied
    /// from now on.
    pub fn set_load(&mut self, gravity: f64, lambda: f64) {
        self.world.load = world::Load { gravity, lambda };
    }
    /// Set Cundall's local damping coefficient used from now on (initially
    /// `IntegrationParameters::local_damping`).
    pub fn set_local_damping(&mut self, alpha: f64) {
        self.world.local_damping = alpha;
    }
    /// Apply a horizontal ground acceleration `a` (m/s^2, toward +x) from now on, as the
    /// equivalent body force `-m a` on every seismic mass (see [`dynamic`]), with full
    /// permanent loads. The body force is horizontal whatever the vertical seismic ratio.
    pub fn set_ground_acceleration(&mut self, a: f64) {
        self.world.seismic_direction = Vec2::new(1.0, 0.0);
        self.world.load = world::Load {
            gravity: 1.0,
            lambda: -a / self.world.params.gravity,
        };
    }
    /// Turn block `i` rigidly by `angle` (rad, counter-clockwise) about the point `pivot`, at
    /// rest (for initial conditions such as a rocking block released from a tilt).
    pub fn rotate_block_about(&mut self, i: usize, pivot: Vec2, angle: f64) {
        let Some(b) = self.world.bodies.iter_mut().find(|b| b.block == Some(i)) else {
            return;
        };
        let (sn, cs) = angle.sin_cos();
        let r = b.pos - pivot;
        b.pos = pivot + Vec2::new(cs * r.x - sn * r.y, sn * r.x + cs * r.y);
        b.angle += angle;
        b.vel = Vec2::zeros();
        b.omega = 0.0;
        b.refresh();
        self.world.broad_phase();
        self.world.narrow_phase();
    }
    /// Centroid velocity and angular velocity (rad/s) of every assembly block.
    pub fn velocities(&self) -> Vec<(Vec2, f64)> {
        self.world
            .bodies
            .iter()
            .filter(|b| b.block.is_some())
            .map(|b| (b.vel, b.omega))
            .collect()
    }
    /// Advance one time step.
    pub fn step(&mut self) {
        self.world.step();
    }
    /// Advance by `duration` seconds at the current load.
    pub fn run_for(&mut self, duration: f64) {
        let end = self.world.time + duration;
        while self.world.time < end {
            self.world.step();
        }
    }
    /// Ramp gravity in and run to rest (or collapse, or `max_time`), as the settling run of
    /// `collapse_multiplier`.
    pub fn settle(&mut self, assembly: &Assembly) -> Run {
        protocol::run(&mut self.world, assembly, None, &mut |_| {})
    }
    /// Ramp the seismic multiplier `lambda` in (full permanent loads) and run to rest or
    /// collapse.
    pub fn run_at(&mut self, assembly: &Assembly, lambda: f64) -> Run {
        protocol::run(&mut self.world, assembly, Some(lambda), &mut |_| {})
    }
    /// Simulated time (s) and steps so far.
    pub fn time(&self) -> f64 {
        self.world.time
    }
    pub fn steps(&self) -> u64 {
        self.world.steps
    }
    /// The time step (s).
    pub fn time_step(&self) -> f64 {
        self.world.dt
    }
    /// Kinetic energy of the blocks (J).
    pub fn kinetic_energy(&self) -> f64 {
        self.world.kinetic_energy()
    }
    /// Potential energy of the loads at their current factors plus the elastic energy of
    /// the contact springs (J).
    pub fn potential_energy(&self) -> f64 {
        self.world.potential_energy()
    }
    /// Elastic energy of the contact springs (J).
    pub fn elastic_energy(&self) -> f64 {
        self.world.elastic_energy()
    }
    /// Number of vertex-to-edge contacts that carry a force.
    pub fn active_contacts(&self) -> usize {
        self.world
            .pairs
            .iter()
            .flat_map(|p| &p.contacts)
            .filter(|c| c.normal_force > 0.0)
            .count()
    }
    /// Every touching contact: the block whose vertex touches (None = ground), the block whose
    /// edge is touched, the vertex position, the edge's outward normal, and the normal and
    /// shear forces (N) of the last step.
    pub fn contacts(&self) -> Vec<ContactState> {
        let mut out = Vec::new();
        for pair in &self.world.pairs {
            for c in &pair.contacts {
                let (vi, ei) = if c.flipped {
                    (pair.b, pair.a)
                } else {
                    (pair.a, pair.b)
                };
                let (vb, eb) = (&self.world.bodies[vi], &self.world.bodies[ei]);
                out.push(ContactState {
                    vertex_block: vb.block,
                    edge_block: eb.block,
                    point: vb.world[c.vertex],
                    normal: eb.normals[c.edge],
                    normal_force: c.normal_force,
                    shear_force: c.shear,
                    sliding: c.sliding,
                });
            }
        }
        out
    }
    /// Number of contacts that slid in the last step.
    pub fn sliding_contacts(&self) -> usize {
        self.world
            .pairs
            .iter()
            .flat_map(|p| &p.contacts)
            .filter(|c| c.sliding)
            .count()
    }
    /// Centroid and rotation (rad) of every assembly block.
    pub fn blocks(&self) -> Vec<(crate::geometry::Vec2, f64)> {
        self.world
            .bodies
            .iter()
            .filter(|b| b.block.is_some())
            .map(|b| (b.pos, b.angle))
            .collect()
    }
    /// Largest speed of a block point (m/s) and largest unbalanced force over the block's
    /// load scale (its weight plus the magnitudes of the other loads it carries), from the
    /// last step.
    pub fn max_speed(&self) -> f64 {
        self.world.max_speed()
    }
    pub fn unbalanced(&self) -> f64 {
        self.world.unbalanced()
    }
}
