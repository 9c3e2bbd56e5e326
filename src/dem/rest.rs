//! The rest test of a dynamic run: rigid blocks stay at rest while no admissible load path
//! is exceeded, so the time integration can wait until the ground acceleration first reaches
//! the static collapse multiplier's threshold, and need not run at all when it never does.
//!
//! Under the ground acceleration `a_g = (a_h, a_v)` the DEM loads every seismic weight `W_s`
//! with `W_s (-a_h, -a_v) / g` (the frame of the moving ground, [`super::dynamic`]) beside the
//! permanent loads `P`. When the permanent loads are exactly the seismic weights (each load a
//! weight `W_s` down at its seismic centre: self-weight, and fill or point loads that are
//! seismic masses; no ties, no strips), `P` is the seismic load along `(0, -1)`, and the load
//! is
//!
//! ```text
//! P + S(-a_h / g, -a_v / g) = (1 + a_v / g) [P + S(mu, 0)],   mu = -a_h / (g + a_v),
//! ```
//!
//! the permanent loads and the horizontal seismic load at the multiplier `mu`, scaled by
//! `1 + a_v / g`. The set of loads a rigid assembly equilibrates with no-tension, Coulomb
//! contacts (and no crushing, which the DEM refuses anyway) is a cone, so the scale does not
//! matter while it is positive, and the blocks can stay at rest exactly when
//!
//! ```text
//! g + a_v > 0   and   -lambda_left <= -a_h / (g + a_v) <= lambda_right,
//! ```
//!
//! that is `a_h <= lambda_left (g + a_v)` (ground toward +x, blocks pushed toward -x) and
//! `-a_h <= lambda_right (g + a_v)`, with `lambda_right` and `lambda_left` the static
//! multipliers toward +x and -x at no vertical seismic component (the static program,
//! `crate::statics`, on the polygons the DEM simulates and with its Coulomb coefficient on
//! every joint). With other permanent loads (a load that is no seismic mass, a tie's capacity
//! or prestress) the scale matters, and the test holds only for a horizontal motion
//! (`a_v = 0`, where the admissible multipliers along the horizontal are exactly
//! `[-lambda_left, lambda_right]` by convexity); a vertical component there turns the test off.
//!
//! Below the threshold an admissible equilibrium exists and rest is a solution of the rigid
//! blocks' motion; it is taken as the motion when no joint slides in the static mechanism
//! of a chain (friction exact, docs/friction.md: the associative collapse state is then a
//! non-associative one). Where joints slide, the associative multiplier bounds the real
//! (non-associative) collapse from above (Radenkovic), rest below it is not certain, and the
//! test is off; so it is in any assembly that is not a chain, where the value may be exact
//! but real joints may have lower collapse states (`FrictionCheck::lower_states_possible`: a
//! wall whose head joints carry no compression, which the DEM sees collapse at 0.85 of its
//! exact 1.0, infinite friction included, since the DEM's contacts are Coulomb's).
//!
//! A motion is read piece by piece between its breaks ([`super::record::Excitation::breaks`]):
//! on a piece where both components are linear (records, rectangular pulses) the three terms of
//! the test are linear and their maximum lies at an end, so the test is exact there; on a
//! piece of a sine it uses the components' ranges (the ends: they are monotone), which can
//! only flag a piece early.

use super::record::GroundInput;
use super::{simulated_model, IntegrationParameters};
use crate::model::{Action, LoadSource, Model};
use crate::statics::{self, Direction, StaticSettings, Status, LAMBDA_CAP};

/// The relative margin by which a ground acceleration must stay below the threshold to count
/// as below it: the static program's multiplier is accurate to about 1e-9 (Clarabel's gap of
/// 1e-10 on the dimensionless program, or the chain program's exact vertex), so the rest test
/// never calls rest what the exact multiplier would not.
pub const REST_MARGIN: f64 = 1e-6;

/// The static thresholds of the rest test.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct RestThreshold {
    /// Static collapse multipliers of the simulated blocks with the seismic forces toward +x
    /// and toward -x, no vertical component ([`LAMBDA_CAP`] for a structure that does not
    /// collapse with infinite friction).
    pub lambda_right: f64,
    pub lambda_left: f64,
    /// The gravity of the run (m/s^2, `dem.gravity`).
    pub gravity: f64,
    /// Whether the permanent loads are exactly the seismic weights (no tie, no strip), so
    /// that the test holds with a vertical component too.
    pub homogeneous: bool,
    /// Wall time of the two static solves (s).
    pub solve_time_s: f64,
}

impl RestThreshold {
    /// Whether the rigid blocks can stay at rest under the ground acceleration `(a_h, a_v)`
    /// (m/s^2), [`REST_MARGIN`] below the threshold.
    pub fn holds(&self, a_h: f64, a_v: f64) -> bool {
        let ge = self.gravity + a_v;
        let keep = 1.0 - REST_MARGIN;
        ge > 0.0 && a_h < keep * self.lambda_left * ge && -a_h < keep * self.lambda_right * ge
    }
}

/// What the rest test of a run was.
#[derive(Debug, Clone, PartialEq)]
pub enum RestTest {
    /// Not asked for (`DynamicSettings::rest_test` false): the run integrates from t = 0.
    Off,
    /// Asked for, but not exact for this structure or motion (why, in words): the run
    /// integrates from t = 0.
    NotApplicable(String),
    /// Applied with these thresholds.
    Applied(RestThreshold),
}

impl RestTest {
    /// `off`, `not_applicable` or `applied`, as the JSON says it.
    pub fn name(&self) -> &'static str {
        match self {
            RestTest::Off => "off",
            RestTest::NotApplicable(_) => "not_applicable",
            RestTest::Applied(_) => "applied",
        }
    }

    /// The thresholds, when applied.
    pub fn threshold(&self) -> Option<&RestThreshold> {
        match self {
            RestTest::Applied(t) => Some(t),
            _ => None,
        }
    }

    /// Why it was not applied, when asked for.
    pub fn note(&self) -> Option<&str> {
        match self {
            RestTest::NotApplicable(why) => Some(why),
            _ => None,
        }
    }
}

/// The rest test of `model` under `params`: the static multipliers toward +x and -x of the
/// blocks the DEM simulates (chord polygons for curved voussoirs,
/// [`super::simulated_model`]), at no vertical seismic component, with the DEM's Coulomb
/// coefficient on every joint; [`RestTest::NotApplicable`] where rest below them is not
/// certain (sliding in a static mechanism, finite friction without collapse, no equilibrium,
/// a live action) or the static program fails.
pub fn rest_test(model: &Model, params: &IntegrationParameters) -> RestTest {
    let clock = std::time::Instant::now();
    if model.loads.action() != Action::Seismic {
        return RestTest::NotApplicable("the action is not seismic".into());
    }
    // Not a chain: joints that may carry no compression (a wall's head joints) slide under
    // the DEM's Coulomb contacts, infinite friction included (simulated as
    // `dem.infinite_friction`), so real joints may collapse below the static value
    // (`FrictionCheck::lower_states_possible`, docs/friction.md). Decided by the topology
    // alone, before any static solve.
    if !model.assembly.is_single_thrust_path() {
        return RestTest::NotApplicable(
            "real joints may collapse lower than the static multiplier in an assembly that is not a chain (joints without compression slide under the DEM's Coulomb contacts, docs/friction.md), so rest below it is not certain".into(),
        );
    }
    let mut m = simulated_model(model).unwrap_or_else(|| model.clone());
    m.loads = m.loads.clone().with_vertical_ratio(0.0);
    // The DEM gives every contact one Coulomb coefficient, the largest of the joints'
    // (`World::new`); infinite friction stays infinite here (the DEM's stand-in,
    // `dem.infinite_friction`, is 1000).
    let mu = m
        .assembly
        .joints
        .iter()
        .map(|j| j.friction)
        .fold(0.0_f64, f64::max);
    for j in &mut m.assembly.joints {
        j.friction = mu;
    }
    let mut lambdas = [0.0; 2];
    for (k, direction) in [Direction::Right, Direction::Left].into_iter().enumerate() {
        let side = match direction {
            Direction::Right => "+x",
            Direction::Left => "-x",
        };
        let settings = StaticSettings {
            direction,
            ..StaticSettings::default()
        };
        let r = match statics::analyse(&m, &settings) {
            Ok(r) => r,
            Err(e) => {
                return RestTest::NotApplicable(format!(
                    "the static program toward {side} failed ({e})"
                ))
            }
        };
        let friction = r.friction(&m.assembly);
        lambdas[k] = match (r.status, r.lambda) {
            (Status::Collapse, Some(l)) if l > 0.0 && friction.exact => l,
            (Status::Collapse, Some(l)) if l > 0.0 => {
                return RestTest::NotApplicable(format!(
                    "joints slide in the static mechanism toward {side} (associative friction: lambda = {l:.6} bounds the real collapse from above, so rest below it is not certain)"
                ))
            }
            (Status::Collapse, _) => {
                return RestTest::NotApplicable(format!(
                    "the static multiplier toward {side} is not positive"
                ))
            }
            (Status::NoCollapse, _) if friction.exact => LAMBDA_CAP,
            (Status::NoCollapse, _) => {
                return RestTest::NotApplicable(format!(
                    "no collapse toward {side} with finite friction (no mechanism shows that real joints hold)"
                ))
            }
            (Status::CannotStand, _) => {
                return RestTest::NotApplicable(
                    "the static program finds no equilibrium under the permanent loads".into(),
                )
            }
        };
    }
    RestTest::Applied(RestThreshold {
        lambda_right: lambdas[0],
        lambda_left: lambdas[1],
        gravity: params.gravity,
        homogeneous: homogeneous(model),
        solve_time_s: clock.elapsed().as_secs_f64(),
    })
}

/// Whether the permanent loads of `model` are exactly its seismic weights: every load a
/// weight `W_s` straight down at its own point, no live load, no tie, no strip, no passive fill.
fn homogeneous(model: &Model) -> bool {
    model.ties.is_empty()
        && model.strips.is_empty()
        && model.passive.is_empty()
        && model.loads.applied().iter().all(|l| {
            l.source == LoadSource::SelfWeight
                || (!l.live
                    && l.force.x.abs() <= 1e-12 * l.seismic_weight
                    && (l.force.y + l.seismic_weight).abs() <= 1e-12 * l.seismic_weight)
        })
}

/// When the integration of a run under a ground motion starts.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RestPlan {
    /// The first time (s) at which the ground acceleration may reach the threshold: exact on
    /// pieces where the motion is linear, the start of the piece on a sine's; `None` when it
    /// never does.
    pub first_exceedance: Option<f64>,
    /// When the integration starts (s): the last time before the first exceedance at which
    /// the horizontal ground acceleration was zero (or changed sign), so the contacts take up
    /// the load of that half-cycle as the full integration has them take it; 0 when there is
    /// none. `None` when the ground never reaches the threshold.
    pub integration_start: Option<f64>,
}

/// One piece of a motion between two breaks: the components' values at its ends (right limit
/// at the start, left limit at the end), and whether both are linear on it.
struct Piece {
    t0: f64,
    t1: f64,
    h: (f64, f64),
    v: (f64, f64),
    linear: bool,
}

/// When the integration of a run under `ground` starts, given the thresholds.
pub fn plan(ground: &GroundInput, threshold: &RestThreshold) -> RestPlan {
    let vertical = match ground.component {
        super::record::Component::X => ground.vertical.as_ref(),
        super::record::Component::Y => Some(&ground.main),
    };
    let horizontal = match ground.component {
        super::record::Component::X => Some(&ground.main),
        super::record::Component::Y => None,
    };
    let limits =
        |e: Option<&super::record::Excitation>, t: f64| e.map_or((0.0, 0.0), |e| e.limits(t));
    let point = |e: Option<&super::record::Excitation>, t: f64| e.map_or(0.0, |e| e.at(t));
    let linear = horizontal.is_none_or(|e| e.piecewise_linear())
        && vertical.is_none_or(|e| e.piecewise_linear());
    let mut breaks: Vec<f64> = horizontal
        .into_iter()
        .chain(vertical)
        .flat_map(|e| e.breaks())
        .chain(std::iter::once(0.0))
        .filter(|t| *t >= 0.0)
        .collect();
    breaks.sort_by(f64::total_cmp);
    breaks.dedup();
    let holds = |h: f64, v: f64| threshold.holds(h, v);
    let never = RestPlan {
        first_exceedance: None,
        integration_start: None,
    };
    // The first break or piece where the test may fail, and the sign of a_h there.
    let mut found: Option<(usize, f64, f64)> = None;
    for (i, &t) in breaks.iter().enumerate() {
        let (hl, hr) = limits(horizontal, t);
        let (vl, vr) = limits(vertical, t);
        let (hp, vp) = (point(horizontal, t), point(vertical, t));
        if let Some(&(h, _)) = [(hl, vl), (hp, vp), (hr, vr)]
            .iter()
            .find(|(h, v)| !holds(*h, *v))
        {
            found = Some((i, t, h));
            break;
        }
        let Some(&t1) = breaks.get(i + 1) else {
            break;
        };
        let piece = Piece {
            t0: t,
            t1,
            h: (hr, limits(horizontal, t1).0),
            v: (vr, limits(vertical, t1).0),
            linear,
        };
        if let Some((te, h)) = piece_exceedance(&piece, threshold) {
            found = Some((i, te, h));
            break;
        }
    }
    let Some((i, te, h)) = found else {
        return never;
    };
    RestPlan {
        first_exceedance: Some(te),
        integration_start: Some(half_cycle_start(
            &breaks[..=i],
            te,
            h,
            |t| limits(horizontal, t),
            linear,
        )),
    }
}

/// Where on `piece` the test first fails (time, and a_h there), if it does: by the three
/// linear terms' zero crossings on a linear piece, at its start on a sine's piece whose
/// ranges do not pass.
fn piece_exceedance(piece: &Piece, th: &RestThreshold) -> Option<(f64, f64)> {
    let keep = 1.0 - REST_MARGIN;
    let terms = |h: f64, v: f64| {
        let ge = th.gravity + v;
        [
            h - keep * th.lambda_left * ge,
            -h - keep * th.lambda_right * ge,
            -ge,
        ]
    };
    if piece.linear {
        let (a, b) = (terms(piece.h.0, piece.v.0), terms(piece.h.1, piece.v.1));
        // Each term is linear on the piece: the first where one reaches 0.
        let s = a
            .iter()
            .zip(&b)
            .filter(|(x, y)| **y >= 0.0 && **x < 0.0)
            .map(|(x, y)| x / (x - y))
            .fold(f64::INFINITY, f64::min);
        if s.is_finite() {
            let s = s.clamp(0.0, 1.0);
            let t = piece.t0 + s * (piece.t1 - piece.t0);
            return Some((t, piece.h.0 + s * (piece.h.1 - piece.h.0)));
        }
        return None;
    }
    // Monotone components: the ends give their ranges; the test's terms grow with |a_h| and
    // fall with a_v.
    let (hmin, hmax) = (piece.h.0.min(piece.h.1), piece.h.0.max(piece.h.1));
    let vmin = piece.v.0.min(piece.v.1);
    if th.holds(hmax, vmin) && th.holds(hmin, vmin) {
        return None;
    }
    let h = if !th.holds(hmax, vmin) { hmax } else { hmin };
    Some((piece.t0, h))
}

/// The last time at or before `te` (where a_h is `h_te`, in the piece starting at the last
/// of `breaks`) at which the horizontal acceleration was zero or of the sign opposite to
/// `h_te`'s: the start of the half-cycle in which the test first fails; 0 when there is none.
fn half_cycle_start(
    breaks: &[f64],
    te: f64,
    h_te: f64,
    limits: impl Fn(f64) -> (f64, f64),
    linear: bool,
) -> f64 {
    let sign = h_te.signum();
    if h_te == 0.0 {
        // Lift-off by the vertical component alone: start where it fails.
        return te;
    }
    let off = |h: f64| sign * h <= 0.0;
    // Walk the pieces back from `(te, h_te)`: on a piece `(t0, t1)` whose start is off-sign
    // (its end is on-sign), the crossing (interpolated on a linear piece, the start
    // otherwise); at a break whose left limit is off-sign (a jump), the break.
    let (mut t1, mut h1) = (te, h_te);
    for &t0 in breaks.iter().rev() {
        let (hl, hr) = limits(t0);
        if t0 < t1 && off(hr) {
            return if linear && hr != h1 {
                (t0 + (t1 - t0) * hr / (hr - h1)).clamp(t0, t1)
            } else {
                t0
            };
        }
        if off(hl) {
            return t0;
        }
        (t1, h1) = (t0, hl);
    }
    0.0
}
