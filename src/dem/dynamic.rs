//! Dynamic response of the blocks to a ground acceleration `a_g(t) = (a_h(t), a_v(t))` (a
//! record or a pulse, [`super::record`]): after settling under the permanent loads, the ground
//! motion acts as the equivalent body force `-m a_g(t)` on every seismic mass (the blocks'
//! equations written in the frame of the moving ground, where the ground stays fixed), which
//! is the model's seismic load at unit multiplier along the direction `-a_g(t) / g`.
//!
//! Sign convention: `a_h > 0` accelerates the ground toward +x (the body force then pushes the
//! blocks toward -x), `a_v > 0` accelerates it upward (the body force `-m a_v` adds to the
//! weight: the effective gravity is `g + a_v`). A block of slenderness `alpha` on the ground
//! therefore uplifts when `|a_h| > (g + a_v) tan(alpha)`, and a vertical motion alone lifts
//! nothing while `a_v > -g`.
//!
//! No artificial damping acts during the motion: Cundall's local damping, used to settle, is
//! switched off, and energy is lost only where the contact law loses it, in the contact
//! dashpots at impacts (`contact_damping`, 0.3 of critical by default) and by Coulomb sliding.
//! For a rocking block this gives a coefficient of restitution of its own, measured against
//! Housner's (1963) `1 - 1.5 sin^2(alpha)` in `tests/it/dem_dynamic.rs` and docs/dem.md.
//!
//! A motion given as a record or a pulse ([`respond_input`], [`ida_input`]) is first read
//! against the static threshold of the rest test ([`super::rest`]): rigid blocks stay at rest
//! while `-lambda_right (g + a_v) < a_h < lambda_left (g + a_v)`, so the settled state is held
//! until the half-cycle in which the ground first reaches it, and nothing is integrated when it
//! never does.

use super::record::{Component, GroundInput};
use super::rest::{self, RestPlan, RestTest};
use super::world::{surely_within, Load, World};
use super::{
    check_interrupt, check_model, check_params, check_steps, check_time_step, longest_run,
    settled_warnings, DemError, IntegrationParameters, Purpose,
};
use crate::geometry::Vec2;
use crate::model::Model;
use std::time::Instant;

/// When a dynamic run has collapsed.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Criterion {
    /// A block point has moved farther than `DynamicSettings::collapse_share` of the
    /// structure's size (a quarter by default): a mechanism that has run well away. Quick to
    /// decide, and conservative: a block rocking that far during the motion may still have
    /// come back (on a slender block, 11% below Housner's overturning at omega_p / p = 4).
    #[default]
    Displacement,
    /// Loss of stability: the run goes on, after the motion, until the structure is at rest
    /// (it survives, however displaced) or has fallen, a block point having moved farther
    /// than the structure's whole size (a block lying on its side). For a rigid block on the
    /// ground this is Housner's overturning.
    Overturning,
}

impl Criterion {
    /// `displacement` or `overturning`, as the command line and the JSON say it.
    pub fn name(self) -> &'static str {
        match self {
            Criterion::Displacement => "displacement",
            Criterion::Overturning => "overturning",
        }
    }
}

/// The displacement of a block point, as a share of the structure's size, that means it has
/// fallen ([`Criterion::Overturning`]).
pub const OVERTURNING_SHARE: f64 = 1.0;

/// The largest motion of a block point over a window, as a share of the structure's size,
/// that counts as settling ([`EndState::Settling`]): a hundredth of the displacement
/// criterion's quarter of the size.
pub const SETTLING_SHARE: f64 = 0.0025;

/// The most animation frames kept while a run goes on past its motion and tail to a decided
/// end (over `IntegrationParameters::max_time` at most).
pub const EXTENSION_FRAMES: f64 = 250.0;

/// How a dynamic run ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum EndState {
    /// The structure did not settle under its permanent loads: no motion was run.
    CannotStand,
    /// The collapse criterion was met.
    Collapsed,
    /// At rest after the ground stopped (speeds and unbalanced forces below the rest
    /// thresholds of the `[dem]` table): it survives.
    AtRest,
    /// Still moving with the ground still, but no block point has moved by more than
    /// [`SETTLING_SHARE`] of the structure's size over a window of
    /// `IntegrationParameters::max_time / 10`: small rocking dying out. Its energy is then far
    /// below what overturning or a mechanism needs (a rigid block rocking to a tenth of its
    /// slenderness has a fifth of the energy it needs to pass it), and the ground no longer
    /// feeds it: it survives.
    Settling,
    /// A single block on the ground, still rocking with the ground still, with less energy
    /// above its settled state (kinetic, potential and elastic) than it needs to tip over a
    /// corner of its base (its weight times the rise of its centroid to over the corner,
    /// Housner's unstable equilibrium), less a margin of 5%: energy only leaves once the ground
    /// is still, so it cannot fall, and it survives.
    Rocking,
    /// Still moving `IntegrationParameters::max_time` after the planned end: undecided,
    /// counted as not surviving by the IDA and the pulse curve.
    Moving,
}

/// How a dynamic run is carried out.
#[derive(Debug, Clone)]
pub struct DynamicSettings {
    /// Free motion after the excitation ends (s), so a block still rocking can come back or
    /// fall. Default 2 s.
    pub tail: f64,
    /// A run has collapsed when a block point has moved farther than this share of the
    /// structure's size (a toppled block or a mechanism that has run away). Default 0.25.
    pub collapse_share: f64,
    /// Block whose motion is reported (peak and residual); default the block that moves most.
    pub control_block: Option<usize>,
    /// Keep a time history sample every this many seconds; `None` keeps none. Default 0.01 s.
    pub history_every: Option<f64>,
    /// Keep the placement of every block every this many seconds (frames of an animation);
    /// `None` keeps none. Default `None`.
    pub frames_every: Option<f64>,
    /// When the run has collapsed. Default [`Criterion::Displacement`].
    pub criterion: Criterion,
    /// The most time steps the run may plan, instead of `IntegrationParameters::max_steps`.
    pub max_steps: Option<u64>,
    /// The rest test ([`super::rest`]): skip the time integration while the ground
    /// acceleration stays below the static multiplier's threshold (rigid blocks stay at rest
    /// there), and start it in the half-cycle of the first exceedance. Default true; applied
    /// to motions given as records or pulses ([`respond_input`], [`ida_input`]) where it is
    /// exact, and reported as not applicable otherwise.
    pub rest_test: bool,
}

impl Default for DynamicSettings {
    fn default() -> Self {
        DynamicSettings {
            tail: 2.0,
            collapse_share: 0.25,
            control_block: None,
            history_every: Some(0.01),
            frames_every: None,
            criterion: Criterion::Displacement,
            max_steps: None,
            rest_test: true,
        }
    }
}

/// One sample of a dynamic run's time history.
#[derive(Debug, Clone, Copy, serde::Serialize)]
pub struct Sample {
    /// Time since the ground started moving (s).
    pub time: f64,
    /// Horizontal ground acceleration (m/s^2, toward +x).
    pub ground_acceleration: f64,
    /// Vertical ground acceleration (m/s^2, upward).
    pub ground_acceleration_vertical: f64,
    /// Control block: horizontal displacement of its centroid (m) and rotation (rad).
    pub displacement: f64,
    pub rotation: f64,
}

/// Every block's placement at one instant of a dynamic run (a frame of an animation).
#[derive(Debug, Clone)]
pub struct Frame {
    /// Time since the ground started moving (s).
    pub time: f64,
    /// Ground acceleration (m/s^2): horizontal (toward +x), vertical (upward).
    pub ground: Vec2,
    /// Per assembly block: centroid position and rotation (rad) of the simulated body.
    pub blocks: Vec<(Vec2, f64)>,
}

/// The outcome of a dynamic run.
#[derive(Debug, Clone)]
pub struct DynamicResult {
    /// Whether the structure did not settle under its permanent loads (no dynamic run then).
    pub cannot_stand: bool,
    /// Whether a block point moved farther than `collapse_share` of the size, and when.
    pub collapsed: bool,
    pub collapse_time: Option<f64>,
    /// The control block and its peaks (absolute) and residuals (at the end of the run).
    pub control_block: usize,
    pub peak_displacement: f64,
    pub peak_rotation: f64,
    pub residual_displacement: f64,
    pub residual_rotation: f64,
    pub history: Vec<Sample>,
    /// Every block's placement, every `frames_every` seconds and at the end (empty unless
    /// asked), and the simulated polygons (world vertices) and placements the motion started
    /// from: a frame moves start vertex `v` of block `i` to
    /// `blocks[i].0 + R(blocks[i].1 - start[i].1) (v - start[i].0)`.
    pub frames: Vec<Frame>,
    pub start: Vec<(Vec2, f64)>,
    pub start_polygons: Vec<Vec<Vec2>>,
    pub steps: u64,
    pub time_step: f64,
    pub wall_time_s: f64,
    /// How the run ended: the end state is decided, not read off the clock. A run that is
    /// neither collapsed nor at rest when the motion and its tail are over goes on (the
    /// ground still) until it is, for up to `IntegrationParameters::max_time` more.
    pub end_state: EndState,
    /// The criterion used, and the displacement of a block point (m) it calls collapse.
    pub criterion: Criterion,
    pub collapse_displacement: f64,
    /// Free motion run past the motion and its tail to decide the end state (s).
    pub extended: f64,
    /// The most time steps the run could take (settling, motion, tail and the longest
    /// extension), checked against the limit before it started.
    pub planned_steps: u64,
    /// What looked implausible (see `DemResult::warnings`), one sentence each.
    pub warnings: Vec<String>,
    /// The rest test of the run ([`super::rest`]): off, not applicable (and why), or applied
    /// with its static thresholds.
    pub rest_test: RestTest,
    /// When the ground acceleration first reaches the rest test's threshold (s); `None` when
    /// it never does or the test was not applied.
    pub first_exceedance: Option<f64>,
    /// When the time integration started (s since the ground started moving): 0 without the
    /// rest test; `None` when the ground never reached the threshold and the blocks stayed at
    /// rest throughout (nothing was integrated, not even the settling).
    pub integration_start: Option<f64>,
    /// The time stepping used (`dem.integrator`).
    pub integrator: crate::dem_settings::Integrator,
}

impl DynamicResult {
    /// `collapse`, `survives`, `cannot_stand`, or `undecided` (still moving when the run
    /// gave up).
    pub fn status(&self) -> &'static str {
        match self.end_state {
            EndState::CannotStand => "cannot_stand",
            EndState::Collapsed => "collapse",
            EndState::AtRest | EndState::Settling | EndState::Rocking => "survives",
            EndState::Moving => "undecided",
        }
    }
}

/// Run `model` under the horizontal ground acceleration `ground(t)` (m/s^2, toward +x) for
/// `duration` seconds plus `settings.tail`.
pub fn respond(
    model: &Model,
    params: &IntegrationParameters,
    ground: &dyn Fn(f64) -> f64,
    duration: f64,
    settings: &DynamicSettings,
) -> Result<DynamicResult, DemError> {
    respond_xy(
        model,
        params,
        &|t| Vec2::new(ground(t), 0.0),
        duration,
        settings,
    )
}

/// Run `model` under the ground acceleration `ground(t) = (a_h, a_v)` (m/s^2; toward +x and
/// upward, see the module's sign convention) for `duration` seconds plus `settings.tail`.
/// A motion given as a function is integrated from its start: the rest test needs the
/// motion's pieces ([`respond_input`]).
pub fn respond_xy(
    model: &Model,
    params: &IntegrationParameters,
    ground: &dyn Fn(f64) -> Vec2,
    duration: f64,
    settings: &DynamicSettings,
) -> Result<DynamicResult, DemError> {
    run_motion(
        model,
        params,
        ground,
        duration,
        settings,
        function_rest(settings),
        None,
    )
}

/// Run `model` under the ground motion `ground` (a record or a pulse, with an optional
/// vertical component) for its duration plus `settings.tail`, with the rest test when
/// `settings.rest_test` asks for it ([`super::rest`]): the time integration starts in the
/// half-cycle where the ground acceleration first reaches the static threshold, and does not
/// run at all when it never does.
pub fn respond_input(
    model: &Model,
    params: &IntegrationParameters,
    ground: &GroundInput,
    settings: &DynamicSettings,
) -> Result<DynamicResult, DemError> {
    let rest = if settings.rest_test {
        check_model(model)?;
        rest::rest_test(model, params)
    } else {
        RestTest::Off
    };
    respond_with(model, params, ground, settings, &rest)
}

/// [`respond_input`] with the rest test already found (the IDA finds it once for all scales).
fn respond_with(
    model: &Model,
    params: &IntegrationParameters,
    ground: &GroundInput,
    settings: &DynamicSettings,
    rest: &RestTest,
) -> Result<DynamicResult, DemError> {
    let vertical = ground.component == Component::Y || ground.vertical.is_some();
    let (rest, plan) = match rest {
        RestTest::Applied(th) if vertical && !th.homogeneous => (
            RestTest::NotApplicable(
                "a vertical ground acceleration on permanent loads that are not all seismic weights (a load with no seismic mass, a tie or a strip): the threshold then depends on the vertical acceleration".into(),
            ),
            None,
        ),
        RestTest::Applied(th) => (rest.clone(), Some(rest::plan(ground, th))),
        other => (other.clone(), None),
    };
    run_motion(
        model,
        params,
        &|t| ground.at(t),
        ground.duration(),
        settings,
        rest,
        plan,
    )
}

/// The dynamic run itself: settle, hold the settled state until `plan`'s integration start
/// (0 without a plan), then integrate; no settling and no integration when the plan says the
/// ground never reaches the threshold.
fn run_motion(
    model: &Model,
    params: &IntegrationParameters,
    ground: &dyn Fn(f64) -> Vec2,
    duration: f64,
    settings: &DynamicSettings,
    rest: RestTest,
    plan: Option<RestPlan>,
) -> Result<DynamicResult, DemError> {
    let clock = Instant::now();
    check_model(model)?;
    if !(duration.is_finite()
        && duration >= 0.0
        && settings.tail.is_finite()
        && settings.tail >= 0.0)
    {
        return Err(DemError::Settings(format!(
            "duration {duration} s and tail {} s must be finite and >= 0",
            settings.tail
        )));
    }
    let nb = model.assembly.blocks.len();
    if let Some(c) = settings.control_block.filter(|&c| c >= nb) {
        return Err(DemError::Settings(format!(
            "control block {c}: the structure has blocks 0 to {}",
            nb.saturating_sub(1)
        )));
    }
    check_params(params, model)?;
    // `auto` resolved here by the rule the plan and the IDA's label read
    // (`IntegrationParameters::resolved`), not left to `World::new`'s fallback.
    let params = &IntegrationParameters {
        max_steps: settings.max_steps.unwrap_or(params.max_steps),
        ..params.resolved(model, Purpose::GroundMotion)
    };
    let mut world = World::new(model, params);
    check_time_step(&world)?;
    let settle_steps = check_steps(&world, longest_run(params), "settling")?;
    let motion_steps = check_steps(
        &world,
        duration + settings.tail + params.max_time,
        &format!(
            "the dynamic run ({duration:.4e} s of ground motion, {:.4e} s of tail, and up to dem.max_time = {:.4e} s more to decide its end)",
            settings.tail, params.max_time
        ),
    )?;
    let size = model.assembly.size();
    let threshold = match settings.criterion {
        Criterion::Displacement => settings.collapse_share,
        Criterion::Overturning => OVERTURNING_SHARE,
    } * size;
    let integration_start = match plan {
        None => Some(0.0),
        Some(p) => p.integration_start,
    };
    let first_exceedance = plan.and_then(|p| p.first_exceedance);
    let Some(start_at) = integration_start else {
        // The ground never reaches the threshold: the rigid blocks stay where they are.
        return Ok(at_rest_throughout(
            model,
            &world,
            ground,
            duration + settings.tail,
            settings,
            threshold,
            settle_steps.saturating_add(motion_steps),
            rest,
            clock,
        ));
    };
    let settle = super::protocol::run(&mut world, &model.assembly, None, &mut |_| {});
    check_interrupt(settle.steps)?;
    super::check_finite(&settle)?;
    let cannot_stand = settle.outcome != super::Outcome::Stands;
    let mut result = DynamicResult {
        rest_test: rest,
        first_exceedance,
        integration_start,
        cannot_stand: settle.outcome != super::Outcome::Stands,
        collapsed: false,
        collapse_time: None,
        control_block: settings.control_block.unwrap_or(0),
        peak_displacement: 0.0,
        peak_rotation: 0.0,
        residual_displacement: 0.0,
        residual_rotation: 0.0,
        history: Vec::new(),
        frames: Vec::new(),
        start: Vec::new(),
        start_polygons: Vec::new(),
        steps: settle.steps,
        time_step: world.dt,
        wall_time_s: 0.0,
        end_state: if cannot_stand {
            EndState::CannotStand
        } else {
            EndState::Moving
        },
        criterion: settings.criterion,
        collapse_displacement: threshold,
        extended: 0.0,
        planned_steps: settle_steps.saturating_add(motion_steps),
        warnings: settled_warnings(&world, model),
        integrator: world.params.integrator,
    };
    if result.cannot_stand {
        result.wall_time_s = clock.elapsed().as_secs_f64();
        return Ok(result);
    }
    let start: Vec<(Vec2, f64)> = world.bodies.iter().map(|b| (b.pos, b.angle)).collect();
    result.start = start[..nb].to_vec();
    result.start_polygons = world.bodies[..nb].iter().map(|b| b.world.clone()).collect();
    let g = params.gravity;
    // The seismic forces act at unit multiplier along `-a_g / g`, set every step: the body
    // force follows the ground motion alone, whatever the scene's vertical seismic ratio
    // (which belongs to the equivalent static load).
    world.load = Load {
        gravity: 1.0,
        lambda: 1.0,
    };
    world.local_damping = 0.0;
    // Until the integration starts the blocks hold their settled state (the rest test).
    world.time = start_at;
    let end = duration + settings.tail;
    // Past the planned end the state decides, not the clock: on until at rest or collapsed.
    let give_up = end + params.max_time;
    let barrier = tipping_barrier(model, &world, start[0].0);
    let elastic0 = world.elastic_energy();
    let window = 0.1 * params.max_time;
    let mut window_end = end + window;
    let mut window_ref: Vec<(Vec2, f64)> = Vec::new();
    let mut window_motion: f64 = 0.0;
    let mut moved = vec![0.0_f64; nb];
    let mut next_sample = 0.0;
    let mut next_frame = 0.0;
    let steps0 = world.steps;
    let sample = |w: &World, c: usize, t: f64, a: Vec2| Sample {
        time: t,
        ground_acceleration: a.x,
        ground_acceleration_vertical: a.y,
        displacement: w.bodies[c].pos.x - start[c].0.x,
        rotation: w.bodies[c].angle - start[c].1,
    };
    let frame = |w: &World, t: f64, a: Vec2| Frame {
        time: t,
        ground: a,
        blocks: w.bodies[..nb].iter().map(|b| (b.pos, b.angle)).collect(),
    };
    // The samples and frames of the time held at rest, at the times the run would take them.
    if let Some(every) = settings.history_every {
        while next_sample < start_at {
            let a = ground(next_sample);
            result.history.push(sample(&world, 0, next_sample, a));
            next_sample += every;
        }
    }
    if let Some(every) = settings.frames_every {
        while next_frame < start_at {
            result
                .frames
                .push(frame(&world, next_frame, ground(next_frame)));
            next_frame += every;
        }
    }
    loop {
        let t = world.time;
        if t >= end {
            let at_rest = world.steps > steps0
                && world.max_speed() < params.rest_velocity
                && world.unbalanced() < params.rest_force;
            if at_rest {
                result.end_state = EndState::AtRest;
                break;
            }
            if let Some(barrier) = barrier.filter(|_| ground(t) == Vec2::zeros()) {
                let b = &world.bodies[0];
                let energy = world.kinetic_energy()
                    + b.loads.weight * (b.pos.y - start[0].0.y)
                    + world.elastic_energy()
                    - elastic0;
                if energy < 0.95 * barrier {
                    result.end_state = EndState::Rocking;
                    break;
                }
            }
            if window_ref.is_empty() {
                window_ref = world.bodies[..nb]
                    .iter()
                    .map(|b| (b.pos, b.angle))
                    .collect();
            }
            for (b, (p0, a0)) in world.bodies[..nb].iter().zip(&window_ref) {
                window_motion =
                    window_motion.max((b.pos - p0).norm() + (b.angle - a0).abs() * b.radius);
            }
            if t >= window_end {
                if window_motion <= SETTLING_SHARE * size {
                    result.end_state = EndState::Settling;
                    break;
                }
                window_ref.clear();
                window_motion = 0.0;
                window_end += window;
            }
            if t >= give_up {
                break;
            }
        }
        if (world.steps - steps0).is_multiple_of(16) {
            check_interrupt(result.steps + world.steps - steps0)?;
        }
        let a = ground(t);
        world.seismic_direction = -a / g;
        if let Some(every) = settings.frames_every {
            if t >= next_frame {
                result.frames.push(frame(&world, t, a));
                // Past the planned end, at most EXTENSION_FRAMES more: the caller sized the
                // interval for the planned length, not for the run on to a decided end.
                let every = if t >= end {
                    every.max(params.max_time / EXTENSION_FRAMES)
                } else {
                    every
                };
                next_frame += every;
            }
        }
        if let Some(every) = settings.history_every {
            if t >= next_sample {
                let c = settings.control_block.unwrap_or_else(|| argmax(&moved));
                result.history.push(sample(&world, c, t, a));
                next_sample += every;
            }
        }
        world.step();
        let mut largest: f64 = 0.0;
        for (i, b) in world.bodies.iter().enumerate().take(nb) {
            let dp = b.pos - start[i].0;
            let turn = (b.angle - start[i].1).abs() * b.radius;
            // A displacement that cannot exceed its block's farthest so far changes nothing
            // here: not `moved`, and not the tests of `largest` below (the farthest is finite
            // and not beyond the threshold, or the run would have ended). Its square root is
            // not taken.
            if surely_within(dp, turn, moved[i]) {
                continue;
            }
            let d = dp.norm() + turn;
            moved[i] = moved[i].max(d);
            largest = largest.max(d);
        }
        if !largest.is_finite() {
            return Err(DemError::Settings(
                "the simulation diverged (non-finite block positions): reduce dem.time_step_factor or the contact stiffness".to_string(),
            ));
        }
        let c = settings.control_block.unwrap_or_else(|| argmax(&moved));
        let b = &world.bodies[c];
        result.peak_displacement = result.peak_displacement.max((b.pos.x - start[c].0.x).abs());
        result.peak_rotation = result.peak_rotation.max((b.angle - start[c].1).abs());
        if largest > threshold {
            result.collapsed = true;
            result.collapse_time = Some(world.time);
            result.end_state = EndState::Collapsed;
            break;
        }
    }
    result.extended = (world.time - end).max(0.0);
    if world.unconverged > 0 {
        result.warnings.push(super::moreau::unconverged_warning(
            world.unconverged,
            world.steps,
        ));
    }
    if result.end_state == EndState::Moving {
        result.warnings.push(format!(
            "still moving {:.3} s after the ground motion and its tail ended (speed {:.3e} m/s): neither at rest nor collapsed, the run is undecided",
            result.extended, world.max_speed()
        ));
    }
    let c = settings.control_block.unwrap_or_else(|| argmax(&moved));
    result.control_block = c;
    let last = sample(&world, c, world.time, ground(world.time));
    result.residual_displacement = last.displacement;
    result.residual_rotation = last.rotation;
    if settings.history_every.is_some() {
        result.history.push(last);
    }
    if settings.frames_every.is_some() {
        result
            .frames
            .push(frame(&world, world.time, ground(world.time)));
    }
    result.steps += world.steps - steps0;
    result.wall_time_s = clock.elapsed().as_secs_f64();
    Ok(result)
}

/// The result of a run whose ground never reaches the rest test's threshold: the rigid blocks
/// stay where the assembly puts them (no settling, no integration), the history and frames
/// are those of rest at the times a run takes them, and the run survives at rest.
#[allow(clippy::too_many_arguments)]
fn at_rest_throughout(
    model: &Model,
    world: &World,
    ground: &dyn Fn(f64) -> Vec2,
    end: f64,
    settings: &DynamicSettings,
    collapse_displacement: f64,
    planned_steps: u64,
    rest: RestTest,
    clock: Instant,
) -> DynamicResult {
    let nb = model.assembly.blocks.len();
    let control = settings.control_block.unwrap_or(0);
    let placements: Vec<(Vec2, f64)> = world.bodies[..nb]
        .iter()
        .map(|b| (b.pos, b.angle))
        .collect();
    let times = |every: Option<f64>| {
        let mut out = Vec::new();
        if let Some(every) = every {
            let mut t = 0.0;
            while t < end {
                out.push(t);
                t += every;
            }
            out.push(end);
        }
        out
    };
    let rest_sample = |t: f64| {
        let a = ground(t);
        Sample {
            time: t,
            ground_acceleration: a.x,
            ground_acceleration_vertical: a.y,
            displacement: 0.0,
            rotation: 0.0,
        }
    };
    DynamicResult {
        cannot_stand: false,
        collapsed: false,
        collapse_time: None,
        control_block: control,
        peak_displacement: 0.0,
        peak_rotation: 0.0,
        residual_displacement: 0.0,
        residual_rotation: 0.0,
        history: times(settings.history_every)
            .into_iter()
            .map(rest_sample)
            .collect(),
        frames: times(settings.frames_every)
            .into_iter()
            .map(|t| Frame {
                time: t,
                ground: ground(t),
                blocks: placements.clone(),
            })
            .collect(),
        start: placements.clone(),
        start_polygons: world.bodies[..nb].iter().map(|b| b.world.clone()).collect(),
        steps: 0,
        time_step: world.dt,
        wall_time_s: clock.elapsed().as_secs_f64(),
        end_state: EndState::AtRest,
        criterion: settings.criterion,
        collapse_displacement,
        extended: 0.0,
        planned_steps,
        warnings: settled_warnings(world, model),
        rest_test: rest,
        first_exceedance: None,
        integration_start: None,
        integrator: world.params.integrator,
    }
}

/// For one block standing alone on the ground under its own weight only, with no sliding
/// (Housner's rocking block), the energy (J) it needs above its settled state to tip over a
/// corner of its base: its weight times the rise of its centroid (settled at `centroid`) to
/// over the corner. `None` for any other structure, whose barrier is not known in closed form.
fn tipping_barrier(model: &Model, world: &World, centroid: Vec2) -> Option<f64> {
    let a = &model.assembly;
    let [joint] = a.joints.as_slice() else {
        return None;
    };
    let body = world.bodies.first()?;
    if a.blocks.len() != 1
        || !joint.is_support()
        || joint.friction.is_finite()
        || body.loads.extra.is_some()
    {
        return None;
    }
    let rise = [joint.p1, joint.p2]
        .iter()
        .map(|p| (centroid - p).norm() - (centroid.y - p.y))
        .fold(f64::INFINITY, f64::min);
    Some(body.loads.weight * rise)
}

fn argmax(v: &[f64]) -> usize {
    v.iter()
        .enumerate()
        .fold(
            (0, f64::NEG_INFINITY),
            |(k, m), (i, &x)| if x > m { (i, x) } else { (k, m) },
        )
        .0
}

/// An incremental dynamic analysis: the scale factor of a ground motion that brings down
/// the structure, bracketed.
#[derive(Debug, Clone)]
pub struct IdaResult {
    /// Largest scale a run survived (0: none tried) and smallest one that collapsed (`None`:
    /// none up to the largest scale tried).
    pub scale_survives: f64,
    pub scale_collapses: Option<f64>,
    /// Scales run, with whether each collapsed.
    pub runs: Vec<(f64, bool)>,
    pub steps: u64,
    pub wall_time_s: f64,
    /// The collapse criterion of the runs.
    pub criterion: Criterion,
    /// The rest test of the runs ([`super::rest`]; found once for all scales), and, for each
    /// run in the order of `runs`, when its integration started (`None`: the scaled ground
    /// never reached the threshold and nothing was integrated).
    pub rest_test: RestTest,
    pub integration_starts: Vec<Option<f64>>,
    /// The time stepping of the runs (`dem.integrator`).
    pub integrator: crate::dem_settings::Integrator,
}

/// Scale `ground` up (doubling from 1) until a run collapses, then bisect until the bracket
/// `[scale_survives, scale_collapses]` is narrower than `tolerance` times its top, or stop at
/// `max_scale`. Dynamic collapse need not be monotonic in the scale (a stronger motion can
/// push a block back): this reports the first bracket found, from below.
pub fn ida(
    model: &Model,
    params: &IntegrationParameters,
    ground: &dyn Fn(f64) -> f64,
    duration: f64,
    settings: &DynamicSettings,
    tolerance: f64,
    max_scale: f64,
) -> Result<IdaResult, DemError> {
    ida_xy(
        model,
        params,
        &|t| Vec2::new(ground(t), 0.0),
        duration,
        settings,
        tolerance,
        max_scale,
    )
}

/// [`ida`] of a ground motion with horizontal and vertical components `(a_h, a_v)`, both
/// scaled alike.
pub fn ida_xy(
    model: &Model,
    params: &IntegrationParameters,
    ground: &dyn Fn(f64) -> Vec2,
    duration: f64,
    settings: &DynamicSettings,
    tolerance: f64,
    max_scale: f64,
) -> Result<IdaResult, DemError> {
    let clock = Instant::now();
    ida_runs(
        clock,
        params.resolved(model, Purpose::GroundMotion).integrator,
        settings,
        tolerance,
        max_scale,
        function_rest(settings),
        |scale, quiet| respond_xy(model, params, &|t| scale * ground(t), duration, quiet),
    )
}

/// [`ida_xy`] of a ground motion given as a record or a pulse (with an optional vertical
/// component, scaled alike), with the rest test when `settings.rest_test` asks for it: its
/// thresholds are found once, and a scale whose motion stays below them costs no
/// integration at all.
pub fn ida_input(
    model: &Model,
    params: &IntegrationParameters,
    ground: &GroundInput,
    settings: &DynamicSettings,
    tolerance: f64,
    max_scale: f64,
) -> Result<IdaResult, DemError> {
    let clock = Instant::now();
    check_tolerance(tolerance, "IDA")?;
    let rest = if settings.rest_test {
        check_model(model)?;
        rest::rest_test(model, params)
    } else {
        RestTest::Off
    };
    ida_runs(
        clock,
        params.resolved(model, Purpose::GroundMotion).integrator,
        settings,
        tolerance,
        max_scale,
        rest.clone(),
        |scale, quiet| respond_with(model, params, &ground.scaled(scale), quiet, &rest),
    )
}

/// The rest test of a motion given as a function of time: not applicable when asked for.
fn function_rest(settings: &DynamicSettings) -> RestTest {
    if settings.rest_test {
        RestTest::NotApplicable(
            "the motion is given as a function of time (the rest test reads records and pulses)"
                .into(),
        )
    } else {
        RestTest::Off
    }
}

/// The IDA's search over the scales, `run(scale, settings)` running one scale (without
/// history or frames); `rest` is the test asked for, reported as the runs applied it.
fn ida_runs(
    clock: Instant,
    integrator: crate::dem_settings::Integrator,
    settings: &DynamicSettings,
    tolerance: f64,
    max_scale: f64,
    rest: RestTest,
    mut run: impl FnMut(f64, &DynamicSettings) -> Result<DynamicResult, DemError>,
) -> Result<IdaResult, DemError> {
    check_tolerance(tolerance, "IDA")?;
    let quiet = DynamicSettings {
        history_every: None,
        frames_every: None,
        ..settings.clone()
    };
    let mut starts = Vec::new();
    let mut used = None;
    let found = first_collapse_bracket(1.0, tolerance, max_scale, 2.0, |scale| {
        let r = run(scale, &quiet)?;
        starts.push(r.integration_start);
        used.get_or_insert_with(|| r.rest_test.clone());
        Ok(r)
    })?;
    Ok(IdaResult {
        scale_survives: found.survives,
        scale_collapses: found.collapses,
        runs: found.runs,
        steps: found.steps,
        wall_time_s: clock.elapsed().as_secs_f64(),
        criterion: settings.criterion,
        rest_test: used.unwrap_or(rest),
        integration_starts: starts,
        integrator,
    })
}

/// Refuse a relative bracket width outside (0, 1).
fn check_tolerance(tolerance: f64, what: &str) -> Result<(), DemError> {
    if tolerance.is_finite() && tolerance > 0.0 && tolerance < 1.0 {
        Ok(())
    } else {
        Err(DemError::Settings(format!(
            "{what} tolerance = {tolerance}: must be > 0 and < 1"
        )))
    }
}

/// The smallest amplitude of a pulse that brings the structure down, bracketed.
#[derive(Debug, Clone)]
pub struct AmplitudeBracket {
    /// Largest amplitude a run survived (0: none tried) and smallest one that collapsed
    /// (`None`: none up to the largest amplitude tried), m/s^2.
    pub survives: f64,
    pub collapses: Option<f64>,
    /// Amplitudes run, with whether each collapsed.
    pub runs: Vec<(f64, bool)>,
    pub steps: u64,
    /// The factor between the amplitudes tried before the first collapse (the resolution of
    /// the scan: a collapse window narrower than it can be stepped over).
    pub scan_ratio: f64,
}

/// The factor between the amplitudes a pulse curve tries before bisecting: fine enough to
/// find collapse windows like the one of a slender block under a sine pulse at
/// omega_p / p = 8 (collapse from 8.2 to 11.1 m/s^2, survival from 11.2 to 14, collapse
/// again above), which doubling steps over.
pub const PULSE_SCAN_RATIO: f64 = 1.2;

/// The minimum collapse amplitude of the pulse `pulse(a, t)` (the ground acceleration at time
/// `t` of the pulse of amplitude `a`, horizontal), lasting `duration` s: from `start`, the
/// amplitude is scanned up by the factor `scan_ratio` until a run collapses (or down until
/// one survives), then bisected until `collapses - survives <= tolerance * collapses`; it
/// gives up above `max_amplitude`. Collapse need not be monotonic in the amplitude (Zhang &
/// Makris 2001): this is the lowest collapse found on the scan, a first bracket, not a
/// proven minimum; a collapse window narrower than `scan_ratio` can be missed.
#[allow(clippy::too_many_arguments)]
pub fn minimum_amplitude(
    model: &Model,
    params: &IntegrationParameters,
    pulse: &dyn Fn(f64, f64) -> f64,
    duration: f64,
    settings: &DynamicSettings,
    start: f64,
    tolerance: f64,
    max_amplitude: f64,
    scan_ratio: f64,
) -> Result<AmplitudeBracket, DemError> {
    check_tolerance(tolerance, "amplitude")?;
    if !(start.is_finite() && start > 0.0 && max_amplitude >= start) {
        return Err(DemError::Settings(format!(
            "starting amplitude {start} m/s^2: must be > 0 and at most {max_amplitude}"
        )));
    }
    let quiet = DynamicSettings {
        history_every: None,
        frames_every: None,
        ..settings.clone()
    };
    if !(scan_ratio.is_finite() && scan_ratio > 1.0 + tolerance && scan_ratio <= 4.0) {
        return Err(DemError::Settings(format!(
            "amplitude scan ratio {scan_ratio}: must be above 1 + tolerance and at most 4"
        )));
    }
    first_collapse_bracket(start, tolerance, max_amplitude, scan_ratio, |a| {
        respond(model, params, &|t| pulse(a, t), duration, &quiet)
    })
}

/// The first bracket of the size `x` of a motion (a record's scale, a pulse's amplitude) at
/// which `run(x)` collapses the structure: from `start`, `x` is doubled until a run collapses
/// (giving up above `max`) or halved until one survives (giving up below `start / 2^30`), then
/// bisected until `collapses - survives <= tolerance * collapses`. The IDA and the pulse
/// curve both search this way.
fn first_collapse_bracket(
    start: f64,
    tolerance: f64,
    max: f64,
    ratio: f64,
    mut run: impl FnMut(f64) -> Result<DynamicResult, DemError>,
) -> Result<AmplitudeBracket, DemError> {
    let mut out = AmplitudeBracket {
        survives: 0.0,
        collapses: None,
        runs: Vec::new(),
        steps: 0,
        scan_ratio: ratio,
    };
    let mut x = start;
    // Scanning up to `max` or down to 2^-30 start, then bisection to `tolerance`: the loop
    // ends long before this bound.
    for _ in 0..200 {
        match out.collapses {
            Some(hi) => {
                if hi - out.survives <= tolerance * hi {
                    break;
                }
                if out.survives > 0.0 {
                    x = 0.5 * (out.survives + hi);
                } else if hi < start * 2f64.powi(-30) {
                    break;
                } else {
                    x = hi / ratio;
                }
            }
            None if x > max => break,
            None => {}
        }
        let r = run(x)?;
        out.steps += r.steps;
        if r.cannot_stand {
            return Err(DemError::Settings(
                "the structure does not stand under its permanent loads".to_string(),
            ));
        }
        // Only a run at rest survives: one still moving when it gave up is not verified
        // to stand, and counts with the collapses.
        let fell = !matches!(
            r.end_state,
            EndState::AtRest | EndState::Settling | EndState::Rocking
        );
        out.runs.push((x, fell));
        if fell {
            out.collapses = Some(x);
        } else {
            out.survives = x;
            if out.collapses.is_none() {
                x *= ratio;
            }
        }
    }
    Ok(out)
}
