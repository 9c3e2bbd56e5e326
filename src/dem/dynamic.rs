//! Dynamic response of the blocks to a horizontal ground acceleration `a_g(t)` (a record or a
//! pulse, [`super::record`]): after settling under the permanent loads, the ground motion acts
//! as the equivalent body force `-m a_g(t)` on every seismic mass (the blocks' equations
//! written in the frame of the moving ground, where the ground stays fixed), which is the
//! model's seismic load with `lambda(t) = -a_g(t) / g` along +x.
//!
//! No artificial damping acts during the motion: Cundall's local damping, used to settle, is
//! switched off, and energy is lost only where the contact law loses it, in the contact
//! dashpots at impacts (`contact_damping`, 0.3 of critical by default) and by Coulomb sliding.
//! For a rocking block this gives a coefficient of restitution of its own, measured against
//! Housner's (1963) `1 - 1.5 sin^2(alpha)` in `tests/dem_dynamic.rs` and docs/dem.md.

use super::world::{Load, World};
use super::{check_model, check_time_step, DemError, IntegrationParameters};
use crate::geometry::Vec2;
use crate::model::Model;
use std::time::Instant;

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
}

impl Default for DynamicSettings {
    fn default() -> Self {
        DynamicSettings {
            tail: 2.0,
            collapse_share: 0.25,
            control_block: None,
            history_every: Some(0.01),
        }
    }
}

/// One sample of a dynamic run's time history.
#[derive(Debug, Clone, Copy, serde::Serialize)]
pub struct Sample {
    /// Time since the ground started moving (s).
    pub time: f64,
    /// Ground acceleration (m/s^2).
    pub ground_acceleration: f64,
    /// Control block: horizontal displacement of its centroid (m) and rotation (rad).
    pub displacement: f64,
    pub rotation: f64,
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
    pub steps: u64,
    pub time_step: f64,
    pub wall_time_s: f64,
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
    let mut world = World::new(model, params);
    check_time_step(&world)?;
    let settle = super::protocol::run(&mut world, &model.assembly, None, &mut |_| {});
    super::check_finite(&settle)?;
    let mut result = DynamicResult {
        cannot_stand: settle.outcome != super::Outcome::Stands,
        collapsed: false,
        collapse_time: None,
        control_block: settings.control_block.unwrap_or(0),
        peak_displacement: 0.0,
        peak_rotation: 0.0,
        residual_displacement: 0.0,
        residual_rotation: 0.0,
        history: Vec::new(),
        steps: settle.steps,
        time_step: world.dt,
        wall_time_s: 0.0,
    };
    if result.cannot_stand {
        result.wall_time_s = clock.elapsed().as_secs_f64();
        return Ok(result);
    }
    let start: Vec<(Vec2, f64)> = world.bodies.iter().map(|b| (b.pos, b.angle)).collect();
    let size = model.assembly.size();
    let g = params.gravity;
    // The ground motion is horizontal: the body force has no vertical part whatever the
    // scene's vertical seismic ratio (which belongs to the equivalent static load).
    world.seismic_direction = Vec2::new(1.0, 0.0);
    world.local_damping = 0.0;
    world.time = 0.0;
    let end = duration + settings.tail;
    let mut moved = vec![0.0_f64; nb];
    let mut next_sample = 0.0;
    let steps0 = world.steps;
    let sample = |w: &World, c: usize, t: f64, a: f64| Sample {
        time: t,
        ground_acceleration: a,
        displacement: w.bodies[c].pos.x - start[c].0.x,
        rotation: w.bodies[c].angle - start[c].1,
    };
    while world.time < end {
        let t = world.time;
        let a = ground(t);
        world.load = Load {
            gravity: 1.0,
            lambda: -a / g,
        };
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
            let d = (b.pos - start[i].0).norm() + (b.angle - start[i].1).abs() * b.radius;
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
        if largest > settings.collapse_share * size {
            result.collapsed = true;
            result.collapse_time = Some(world.time);
            break;
        }
    }
    let c = settings.control_block.unwrap_or_else(|| argmax(&moved));
    result.control_block = c;
    let last = sample(&world, c, world.time, ground(world.time));
    result.residual_displacement = last.displacement;
    result.residual_rotation = last.rotation;
    if settings.history_every.is_some() {
        result.history.push(last);
    }
    result.steps += world.steps - steps0;
    result.wall_time_s = clock.elapsed().as_secs_f64();
    Ok(result)
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
    let clock = Instant::now();
    if !(tolerance.is_finite() && tolerance > 0.0 && tolerance < 1.0) {
        return Err(DemError::Settings(format!(
            "IDA tolerance = {tolerance}: must be > 0 and < 1"
        )));
    }
    let quiet = DynamicSettings {
        history_every: None,
        ..settings.clone()
    };
    let mut out = IdaResult {
        scale_survives: 0.0,
        scale_collapses: None,
        runs: Vec::new(),
        steps: 0,
        wall_time_s: 0.0,
    };
    let mut scale = 1.0;
    for _ in 0..60 {
        if let Some(hi) = out.scale_collapses {
            if hi - out.scale_survives <= tolerance * hi {
                break;
            }
            scale = 0.5 * (out.scale_survives + hi);
        } else if scale > max_scale {
            break;
        }
        let r = respond(model, params, &|t| scale * ground(t), duration, &quiet)?;
        out.steps += r.steps;
        if r.cannot_stand {
            return Err(DemError::Settings(
                "the structure does not stand under its permanent loads".to_string(),
            ));
        }
        out.runs.push((scale, r.collapsed));
        if r.collapsed {
            out.scale_collapses = Some(scale);
        } else {
            out.scale_survives = scale;
            if out.scale_collapses.is_none() {
                scale *= 2.0;
            }
        }
    }
    out.wall_time_s = clock.elapsed().as_secs_f64();
    Ok(out)
}
