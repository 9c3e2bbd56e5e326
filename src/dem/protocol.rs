//! The collapse protocol: settle under the permanent loads (gravity), then runs at constant
//! seismic multipliers `lambda` (the model's seismic forces `lambda W_s (1, r)`), each ending
//! at rest or in collapse, and a bracket search on lambda.

use super::world::{Load, World};
use crate::assembly::{Assembly, Hinge, JointEnd};
use crate::geometry::Vec2;

/// How a run ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Outcome {
    /// Kinetic state and unbalanced forces fell below the rest thresholds.
    Stands,
    /// A block point moved farther than the collapse displacement.
    Collapses,
    /// Keeps moving: after the ramp, the displacement grew by at least as much in each of
    /// five consecutive windows (one ramp time each) as in the one before — an accelerating
    /// mechanism, or one so close to its threshold that it slides steadily against the
    /// damping and would take very long to reach the collapse displacement. Counts as not
    /// standing.
    Creeps,
    /// Neither within `max_time`.
    Undecided,
}

/// Block outlines at one instant of a run.
#[derive(Debug, Clone)]
pub struct Snapshot {
    /// Simulated time since the start of the run (s).
    pub time: f64,
    /// Seismic multiplier applied at that instant (ramped).
    pub lambda: f64,
    /// World vertices of every assembly block, in block order.
    pub blocks: Vec<Vec<Vec2>>,
}

/// What the joints did when a run collapsed (at the instant the collapse displacement was
/// reached).
#[derive(Debug, Clone, Default)]
pub struct Onset {
    /// Joints open at one end only, with the end that still touches.
    pub hinges: Vec<Hinge>,
    /// Joints whose two sides slipped along each other.
    pub sliding: Vec<usize>,
    /// Joints open at both ends.
    pub open: Vec<usize>,
}

/// One DEM run.
#[derive(Debug, Clone)]
pub struct Run {
    /// `None` for the settling run under the permanent loads alone.
    pub lambda: Option<f64>,
    pub outcome: Outcome,
    /// Simulated time (s) and steps the run took.
    pub time: f64,
    pub steps: u64,
    /// Largest displacement of a block point since the start of the run (m).
    pub max_displacement: f64,
    pub onset: Option<Onset>,
    pub snapshots: Vec<Snapshot>,
}

/// Consecutive windows of non-decreasing displacement growth that make a run creep.
const CREEP_WINDOWS: usize = 5;
/// Smallest growth per window (fraction of the collapse displacement) that counts: well above
/// the round-off of a structure at rest, well below the elastic response to the ramp.
const CREEP_GROWTH: f64 = 2e-4;

/// Run `world` from its current state with the permanent loads ramped to 1 (`lambda =
/// None`), or with full permanent loads and the seismic ones ramped to `lambda`, until rest,
/// collapse or `max_time`. `assembly` (the world's, in its initial geometry) is read for the
/// joints at the onset of collapse, not for loads. `progress` receives the fraction of
/// `max_time` used.
pub(crate) fn run(
    world: &mut World,
    assembly: &Assembly,
    lambda: Option<f64>,
    progress: &mut dyn FnMut(f64),
) -> Run {
    let p = world.params.clone();
    let t0 = world.time;
    let steps0 = world.steps;
    let start: Vec<(Vec2, f64)> = world.bodies.iter().map(|b| (b.pos, b.angle)).collect();
    let mut snapshots = Vec::new();
    let mut next_snapshot = 0.0;
    let check_every = 10;
    let mut max_disp: f64 = 0.0;
    let total = p.ramp_time + p.max_time;
    let mut last_progress = 0.0;
    // Creep detection: displacement growth per window of one ramp time after the ramp.
    let window = p.ramp_time;
    let mut next_window = 2.0 * p.ramp_time;
    let mut window_start_disp = f64::NAN;
    let mut last_growth = f64::NAN;
    let mut growing = 0;
    let outcome = loop {
        let t = world.time - t0;
        let ramp = (t / p.ramp_time).min(1.0);
        // Strong local damping while the load is ramped in keeps the loading quasi-static
        // (no dynamic overshoot); once it is held, only the contact dashpots damp, so a
        // mechanism runs freely instead of creeping against the local damping.
        world.local_damping = if t < p.ramp_time {
            p.local_damping
        } else {
            p.hold_damping
        };
        world.load = match lambda {
            None => Load {
                gravity: ramp,
                lambda: 0.0,
            },
            Some(l) => Load {
                gravity: 1.0,
                lambda: l * ramp,
            },
        };
        if let Some(dt) = p.snapshot_interval {
            if t >= next_snapshot {
                snapshots.push(snapshot(world, t));
                next_snapshot += dt;
            }
        }
        world.step();
        if !(world.steps - steps0).is_multiple_of(check_every) {
            continue;
        }
        if super::interrupt_requested() {
            // The caller sees the flag and reports the interruption, not this outcome.
            break Outcome::Undecided;
        }
        max_disp = world
            .bodies
            .iter()
            .zip(&start)
            .filter(|(b, _)| !b.fixed)
            .map(|(b, (pos, angle))| (b.pos - pos).norm() + (b.angle - angle).abs() * b.radius)
            // f64::max would drop a NaN: keep it, so a diverging run is noticed.
            .fold(max_disp, |a, d| if d.is_nan() { d } else { a.max(d) });
        if max_disp.is_nan() {
            break Outcome::Undecided;
        }
        let t = world.time - t0;
        if max_disp > p.collapse_displacement {
            break Outcome::Collapses;
        }
        // At rest only once the full load has been held for one more ramp time: a structure
        // just past its threshold is still all but motionless when the ramp ends (rigid
        // contacts hold it exactly at rest until the load crosses the threshold, in the last
        // step or two of a ramp of a hundred), and its mechanism needs that time to gather
        // speed. Tested at the ramp's end, the rigid stepping stood up to 1 % above the
        // threshold (the load's increment per step; docs/dem.md).
        if t > 2.0 * p.ramp_time
            && world.max_speed() < p.rest_velocity
            && world.unbalanced() < p.rest_force
        {
            break Outcome::Stands;
        }
        if t >= next_window {
            let growth = max_disp - window_start_disp;
            if growth >= last_growth && growth > CREEP_GROWTH * p.collapse_displacement {
                growing += 1;
            } else {
                growing = 0;
            }
            if growing >= CREEP_WINDOWS {
                break Outcome::Creeps;
            }
            last_growth = growth;
            window_start_disp = max_disp;
            next_window += window;
        }
        if t > total {
            break Outcome::Undecided;
        }
        if t > last_progress + 0.01 * total {
            last_progress = t;
            progress(t / total);
        }
    };
    let t = world.time - t0;
    if p.snapshot_interval.is_some() {
        snapshots.push(snapshot(world, t));
    }
    let onset = matches!(outcome, Outcome::Collapses | Outcome::Creeps)
        .then(|| onset(world, assembly, max_disp));
    Run {
        lambda,
        outcome,
        time: t,
        steps: world.steps - steps0,
        max_displacement: max_disp,
        onset,
        snapshots,
    }
}

fn snapshot(world: &World, time: f64) -> Snapshot {
    Snapshot {
        time,
        lambda: world.load.lambda,
        blocks: world
            .bodies
            .iter()
            .filter(|b| b.block.is_some())
            .map(|b| b.world.clone())
            .collect(),
    }
}

/// Which joints of the assembly have opened (at one end: a hinge at the other; at both:
/// open) or slipped, from where the blocks on either side carry the joint's ends.
fn onset(world: &World, assembly: &Assembly, moved: f64) -> Onset {
    let size = assembly.size();
    let d = moved;
    let mut out = Onset::default();
    // The ground bodies follow the blocks (`World::new`); they never move, so any of them
    // carries a support joint's points where they were.
    let ground = world.bodies.iter().position(|b| b.fixed);
    for (j, jt) in assembly.joints.iter().enumerate() {
        let ground_here = if jt.is_support() { ground } else { None };
        let body = |b: Option<usize>| b.or(ground_here).map(|i| &world.bodies[i]);
        let (Some(from), Some(to)) = (body(jt.from), body(jt.to)) else {
            continue;
        };
        let n = from.rotate(jt.normal());
        let u = from.rotate(jt.tangent());
        let rel = |q: Vec2| to.carry(q) - from.carry(q);
        let (g1, g2) = (rel(jt.p1).dot(&n), rel(jt.p2).dot(&n));
        // A hinge rotation that moves a block point by `d` (the largest displacement of the
        // run) over the structure's size opens the far end of a joint of length L by about
        // d L / size; a tenth of it is unambiguous.
        let open_gap = 0.1 * d * jt.length() / size;
        let (o1, o2) = (g1 > open_gap, g2 > open_gap);
        match (o1, o2) {
            (true, true) => out.open.push(j),
            (true, false) => out.hinges.push(Hinge::at(assembly, j, JointEnd::P2)),
            (false, true) => out.hinges.push(Hinge::at(assembly, j, JointEnd::P1)),
            (false, false) => {}
        }
        // Slip measured at the end that still touches (or the midpoint of a closed joint).
        let q = match (o1, o2) {
            (true, false) => jt.p2,
            (false, true) => jt.p1,
            _ => jt.midpoint(),
        };
        if !(o1 && o2) && rel(q).dot(&u).abs() > 0.1 * d {
            out.sliding.push(j);
        }
    }
    out
}
