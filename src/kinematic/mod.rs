//! Kinematic (upper-bound) limit analysis of chains of rigid blocks: the collapse multiplier
//! as the least load multiplier that makes some admissible hinge mechanism move — the unsafe
//! theorem of limit analysis for no-tension, non-sliding masonry (Heyman, *The Stone
//! Skeleton*, 1995, ch. 3; Oppenheim, 1992; Ochsendorf, 2002; De Luca et al., 2004).
//!
//! # Mechanisms of a chain
//! A chain is a row of blocks between two supports (joint k joins block k - 1, or the ground,
//! to block k, or the ground). A joint is *closed* (no relative motion), a *hinge* (relative
//! rotation about its end p1 or p2, the other end opening) or *open* (relative motion without
//! tangential slip that separates both ends: a rotation about a point of the joint's line
//! outside the joint, or a translation along its normal). The relative motion of the block
//! after a joint with respect to the block before it is a twist `r = (omega, vx0, vy0)`, with
//! velocity field `v(q) = (vx0 - omega q_y, vy0 + omega q_x)`; a rotation `c` about `p` is
//! `c (1, p_y, -p_x)`, a normal translation `c (0, n_x, n_y)`. Closure of the chain (both
//! supports fixed) is `sum_k r_k = 0`: three equations. A hinge contributes one unknown, an
//! open joint two, so the one-degree-of-freedom mechanisms (the extreme rays of the cone of
//! admissible motions) have `hinges + 2 open = 4`; with exactly four unknown columns the
//! mechanism is the null vector of a 3 x 4 matrix, i.e. its signed 3 x 3 minors (cofactors).
//! For four hinges a < b < c < d this gives the relative rotations
//! `T(b,c,d), -T(a,c,d), T(a,b,d), -T(a,b,c)` with `T(p,q,r) = (q - p) x (r - p)`, which needs no
//! division and stays valid when two hinge lines are parallel (a translating body).
//! Degenerate mechanisms with fewer active joints (three collinear hinges, a hinge on the line
//! of an open joint) are the members of these families in which one joint does not move.
//!
//! A one-support chain (a column or cantilever, the last block free) has the mechanisms of a
//! single hinge.
//!
//! # Admissibility and virtual work
//! A hinge at p1 needs the relative rotation to be negative (so that p2 opens), at p2 positive;
//! an open joint needs both ends to separate. The mechanism's sign is fixed by these
//! conditions (or it is inadmissible). The virtual-work equation `lambda A = G`, with `A` the
//! power of the seismic forces per unit lambda and `G` minus the power of the permanent
//! forces (the load's power equals the rate of increase of potential energy; hinges dissipate
//! nothing), gives `lambda = G / A`. Both come from the [`crate::model::LoadCase`] through
//! per-body resultants (`Sums`); with self-weight alone, `G = sum(W vy)` and
//! `A = d sum(W vx)` (d = +-1 the load direction), the seed paper's equation.
//! Equilibrium at lambda is possible iff `lambda A <= G` for every admissible mechanism, so
//! the static set of multipliers is `[max_{A<0} G/A, min_{A>0} G/A]` (LP duality with the
//! static program of `crate::statics`). Hence:
//! - `Collapse`: the interval is non-empty and its top `lambda_upper = min_{A>0} G/A >= 0`;
//! - `NoCollapse`: no admissible mechanism is driven by the load (`A > 0`), the top is open;
//! - `CannotStand`: `min_{A>0} G/A < 0` (a mechanism runs even against a load pushing it back,
//!   i.e. it moves under its own weight, `G < 0`), or the interval is empty (some mechanism
//!   with `A < 0` needs more than `lambda_upper`, or one with `A = 0` has `G < 0`). Every
//!   witness of `CannotStand` is a mechanism with `G < 0`: gravity alone drives it.
//!
//! These rotational mechanisms are admissible for any friction coefficient, so `lambda_upper`
//! bounds the collapse multiplier from above for finite friction as well (sliding can only
//! lower it).
//!
//! # Local search
//! Any admissible mechanism bounds the collapse multiplier from above, whether or not it is the
//! least one, so a search over a subset of the candidates still gives an upper bound. The
//! exhaustive search examines about joints^4 candidates and costs about joints^3.6;
//! [`analyse_local`] searches only the mechanisms
//! whose active joints all lie within a window of +-w joints around the hinges (and open or
//! sliding joints) of the static solution — which, at collapse, are the hinges of the governing
//! mechanism (complementary slackness of the static program). It runs the same search on the
//! chain restricted to those joints (the bodies between them keep their full weight), so its
//! kinematics, admissibility and virtual work are those of the exhaustive search. Its result is
//! flagged [`Search::Local`]: `lambda_upper` is the least `G/A` over the mechanisms it saw,
//! `>= lambda_c`; when it equals the static `lambda_lower` the two bounds certify `lambda_c`.
//! A local search that finds no mechanism driven by the load proves nothing (no `NoCollapse`):
//! it is reported as [`KinematicError::LocalFoundNothing`]. A `CannotStand` witness (a
//! mechanism that gravity alone drives) is a proof wherever it was found and is reported.
//!
//! The discrete search is in [`discrete`], the continuous model of the arch (hinges anywhere)
//! in [`mod@continuous`].

pub mod continuous;
pub mod discrete;
pub mod general;

pub use continuous::{
    continuous, continuous_min_thickness, ContinuousHinge, ContinuousResult, HingeLocation,
    MinThickness,
};
pub use discrete::{analyse, analyse_local, certify, certify_crushing, mechanism_work};
pub use general::analyse_general;

use crate::assembly::{Hinge, JointEnd};
use crate::geometry::Vec2;
pub use crate::outcome::{Direction, Status};
use thiserror::Error;

/// Errors of the kinematic analyses (physical outcomes are statuses, not errors).
#[derive(Debug, Error)]
pub enum KinematicError {
    #[error("the kinematic search needs a chain of blocks between two supports (or standing on one support): joint k must join block k-1 (ground for k = 0) to block k (ground for the last joint); this assembly is not one")]
    NotAChain,
    #[error("exhaustive kinematic search over {joints} joints exceeds the limit of {max} joints (its candidate count grows as joints^4, its cost as about joints^3.6); raise KinematicSettings::max_joints to run it anyway")]
    TooManyJoints { joints: usize, max: usize },
    #[error("invalid assembly: {0}")]
    Assembly(#[from] crate::error::AnalysisError),
    #[error("{0}")]
    Scene(#[from] crate::error::SceneError),
    #[error("continuous model: {0}")]
    Continuous(String),
    #[error("local kinematic search needs a static solution at collapse (its hinges locate the mechanism); the static status is {0}")]
    LocalNeedsCollapse(&'static str),
    #[error("local kinematic search: the static solution has no hinge, open or sliding joint to search around")]
    LocalNoCentres,
    #[error("local kinematic search found no admissible mechanism driven by the load among {joints} of {total} joints (within {window} joints of the static hinges); the search is not exhaustive, so this proves nothing: no upper bound")]
    LocalFoundNothing {
        joints: usize,
        total: usize,
        window: usize,
    },
    #[error("no certified upper bound: {0}")]
    NotCertified(String),
    #[error("general kinematic program: {0}")]
    General(String),
    #[error("the continuous model puts rigid hinges on the intrados and extrados, so it does not model a finite compressive strength (material.compressive_strength = {compressive_strength:e} Pa); it is not run rather than report the rigid arch's multiplier as the crushing one")]
    FiniteStrength { compressive_strength: f64 },
    #[error("the continuous model's hinges fall anywhere on the ring, between the blocks a tie rod is anchored on, so it does not model tie rods ({count} in the scene); it is not run rather than report the untied arch's multiplier")]
    Ties { count: usize },
    #[error("the continuous model's hinges fall anywhere on the ring, not at the joints bonded strips cross, so it does not model bonded strips ({count} joints crossed); it is not run rather than report the unreinforced arch's multiplier")]
    Strips { count: usize },
    #[error("the continuous model's hinges fall anywhere on the ring, but the fill's passive reactions act on the voussoirs' extrados edges ({count} faces against the fill), so it does not model the fill's passive resistance; it is not run rather than report the multiplier without it")]
    Passive { count: usize },
}

/// Default half-width (joints) of the window of the local search around each static hinge.
pub const DEFAULT_LOCAL_WINDOW: usize = 12;

/// Which candidates a kinematic search examined.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Search {
    /// Every one-degree-of-freedom mechanism with hinges at joint ends: `lambda_upper` is the
    /// discrete kinematic multiplier, and every status is proved.
    Exhaustive,
    /// Only the mechanisms near the static hinges: `lambda_upper` is an upper bound of the
    /// collapse multiplier, not necessarily the least one.
    Local,
    /// The one mechanism whose hinges are those of the static solution at collapse
    /// ([`certify`]): its multiplier by virtual work bounds the collapse multiplier from
    /// above, and when it equals the static one the two certify it.
    Certified,
    /// The general kinematic program over every admissible mechanism of any assembly
    /// ([`general`]: rocking, opening and sliding of every block with associative friction),
    /// its optimum certified by virtual work: the least kinematic multiplier, equal to the
    /// static one by duality.
    General,
}

impl Search {
    pub fn as_str(self) -> &'static str {
        match self {
            Search::Exhaustive => "exhaustive",
            Search::Local => "local",
            Search::Certified => "certified",
            Search::General => "general",
        }
    }
}

/// Settings of the discrete kinematic search.
#[derive(Debug, Clone)]
pub struct KinematicSettings {
    /// Direction of the seismic load. Default: right (+x).
    pub direction: Direction,
    /// Largest number of joints searched exhaustively. Default 600 (about 5e9 four-joint
    /// combinations, tens of seconds).
    pub max_joints: usize,
    /// Use rayon threads. Default true.
    pub parallel: bool,
    /// Clarabel's iterative refinement in the general kinematic program, as in the static one
    /// ([`crate::statics::Refinement`]). Default `Auto`: off from
    /// [`crate::statics::LARGE_KKT`] rows of its KKT matrix, the solve repeated with it when
    /// the first does not end solved or infeasible.
    pub refinement: crate::statics::Refinement,
}

impl Default for KinematicSettings {
    fn default() -> Self {
        KinematicSettings {
            direction: Direction::Right,
            max_joints: 600,
            parallel: true,
            refinement: crate::statics::Refinement::Auto,
        }
    }
}

impl KinematicSettings {
    pub fn direction(mut self, d: Direction) -> Self {
        self.direction = d;
        self
    }
}

/// Which family of one-degree-of-freedom mechanisms a mechanism belongs to.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Family {
    /// Four hinges, three moving bodies.
    FourHinges,
    /// Two hinges and a joint that opens completely.
    TwoHingesOneOpen,
    /// Two joints that open completely: one body lifts off.
    TwoOpen,
    /// Four hinges and one more per tie rod that keeps its length (a force between its
    /// prestress and its capacity): the certified mechanism of a tied chain.
    HingesWithHeldTies,
    /// A single hinge of a one-support chain (column, cantilever).
    OneHinge,
    /// The optimum of the general kinematic program ([`general`]): any blocks rocking,
    /// lifting or sliding.
    General,
}

/// A mechanism: its active joints and the motion of the blocks.
#[derive(Debug, Clone)]
pub struct Mechanism {
    pub family: Family,
    /// Hinges (joint, end, coordinates), in chain order. A hinge of the family whose relative
    /// rotation vanishes (a degenerate member, e.g. three collinear hinges) is left out.
    pub hinges: Vec<Hinge>,
    /// Joints that open completely.
    pub open: Vec<usize>,
    /// Joints that slide (their relative velocity has a tangential part): only the general
    /// program's mechanisms slide.
    pub sliding: Vec<usize>,
    /// `[vx, vy, omega]` of each block (centroid velocity, rotation rate), scaled so the
    /// fastest centroid moves at 1 and the load does positive work (for `Collapse`), or so
    /// gravity does positive work (the witness of `CannotStand`).
    pub velocities: Vec<[f64; 3]>,
    /// `G / A` of this mechanism.
    pub lambda: f64,
}

/// Result of the discrete kinematic search.
#[derive(Debug, Clone)]
pub struct KinematicResult {
    /// Consistent with the static status (see the module docs).
    pub status: Status,
    /// The kinematic collapse multiplier `min_{A>0} G/A` (status `Collapse` only).
    pub lambda_upper: Option<f64>,
    /// `min_{A>0} G/A` whatever its sign (None when no mechanism is driven by the load): a
    /// continuous function of the geometry, negative below the minimum thickness; this is what
    /// a root finder on thickness wants.
    pub lambda_signed: Option<f64>,
    /// `max_{A<0} G/A`: the least multiplier the structure needs (None when no admissible
    /// mechanism runs against the load).
    pub lambda_needed: Option<f64>,
    /// The governing mechanism (status `Collapse`), or the witness of `CannotStand`.
    pub mechanism: Option<Mechanism>,
    pub direction: Direction,
    /// Candidates examined (joint sets times hinge-end patterns, as if enumerated one by one).
    pub candidates: u64,
    /// Candidates that were admissible.
    pub admissible: u64,
    /// Wall time of the search (s).
    pub wall_time_s: f64,
    /// Exhaustive, or local (then `lambda_upper` is an upper bound, and `lambda_signed` and
    /// `lambda_needed` are over the mechanisms searched only).
    pub search: Search,
    /// Joints the search placed active joints on (all of them when exhaustive).
    pub searched_joints: usize,
    /// What a local search covered, in words (None for the exhaustive search).
    pub note: Option<String>,
}

// ---------------------------------------------------------------------------------------------
// Kinematics shared by the discrete and continuous models.

/// A planar twist `(omega, vx0, vy0)`: velocity field `v(q) = (vx0 - omega q_y, vy0 + omega q_x)`.
pub(crate) type Twist = [f64; 3];

/// Unit rotation about `p`.
#[inline]
pub(crate) fn rot(p: Vec2) -> Twist {
    [1.0, p.y, -p.x]
}

/// Unit translation along `n`.
#[inline]
pub(crate) fn trans(n: Vec2) -> Twist {
    [0.0, n.x, n.y]
}

#[inline]
pub(crate) fn det3(a: Twist, b: Twist, c: Twist) -> f64 {
    a[0] * (b[1] * c[2] - b[2] * c[1]) - b[0] * (a[1] * c[2] - a[2] * c[1])
        + c[0] * (a[1] * b[2] - a[2] * b[1])
}

/// Velocity of twist `t` at `q`.
#[inline]
pub(crate) fn velocity(t: Twist, q: Vec2) -> Vec2 {
    Vec2::new(t[1] - t[0] * q.y, t[2] + t[0] * q.x)
}

/// How a joint takes part in a mechanism.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Act {
    Hinge(JointEnd),
    Open,
}

/// An active joint (or section) of a mechanism: its ends and what it does.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Active {
    pub p1: Vec2,
    pub p2: Vec2,
    pub act: Act,
}

impl Active {
    fn normal(&self) -> Vec2 {
        let d = self.p2 - self.p1;
        Vec2::new(d.y, -d.x) / d.norm()
    }
}

/// Load resultants of a body, for virtual work: its permanent forces `p` and its seismic
/// forces per unit lambda `s` (load direction included), each as `[Fx, Fy, M]` with `M` the
/// moment about the origin. Sums of bodies add.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub(crate) struct Sums {
    pub p: [f64; 3],
    pub s: [f64; 3],
}

impl Sums {
    /// Self-weight-like material of weight `w` with first moments `wx = sum W x`,
    /// `wy = sum W y`: its weight down, and a seismic mass of the same weight whose force per
    /// unit lambda and unit weight is `dir` (`(d, r)`, see [`crate::model::LoadCase`]).
    pub fn of_mass(w: f64, wx: f64, wy: f64, dir: Vec2) -> Sums {
        Sums {
            p: [0.0, -w, -wx],
            s: [dir.x * w, dir.y * w, dir.y * wx - dir.x * wy],
        }
    }

    /// The permanent part of these sums moved into the action: a load that lambda multiplies
    /// (a live load under a live action), with no permanent part left.
    pub fn as_action(self) -> Sums {
        Sums {
            p: [0.0; 3],
            s: self.p,
        }
    }

    /// The loads of block `i` of a load case, seismic forces toward `sign`.
    pub fn of_block(loads: &crate::model::LoadCase, i: usize, sign: f64) -> Sums {
        let g = loads.reference(i);
        let p = loads.permanent(i).moved(g, Vec2::zeros());
        let s = loads.variable(i, sign).moved(g, Vec2::zeros());
        Sums {
            p: [p.force.x, p.force.y, p.moment],
            s: [s.force.x, s.force.y, s.moment],
        }
    }
}

impl std::ops::Add for Sums {
    type Output = Sums;
    fn add(self, o: Sums) -> Sums {
        let f = |a: [f64; 3], b: [f64; 3]| [a[0] + b[0], a[1] + b[1], a[2] + b[2]];
        Sums {
            p: f(self.p, o.p),
            s: f(self.s, o.s),
        }
    }
}

impl std::ops::Sub for Sums {
    type Output = Sums;
    fn sub(self, o: Sums) -> Sums {
        let f = |a: [f64; 3], b: [f64; 3]| [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
        Sums {
            p: f(self.p, o.p),
            s: f(self.s, o.s),
        }
    }
}

/// `(A, G)` of a body moving with twist `t`: `A` the power of its seismic forces per unit
/// lambda, `G` minus the power of its permanent forces (for self-weight, `sum W vy`). The
/// virtual-work equation `lambda A = G` gives the multiplier of a mechanism.
#[inline]
pub(crate) fn work(t: Twist, s: Sums) -> (f64, f64) {
    (
        t[1] * s.s[0] + t[2] * s.s[1] + t[0] * s.s[2],
        -(t[1] * s.p[0] + t[2] * s.p[1] + t[0] * s.p[2]),
    )
}

/// [`work`] of the unit rotation about `p` (twist `(1, p_y, -p_x)`).
#[inline]
pub(crate) fn rot_work(p: Vec2, s: &Sums) -> (f64, f64) {
    (
        p.y * s.s[0] - p.x * s.s[1] + s.s[2],
        -(p.y * s.p[0] - p.x * s.p[1] + s.p[2]),
    )
}

/// An admissible mechanism: the relative twist of each active joint (sign fixed by
/// admissibility) and the opening velocity of each hinge's free end (to spot hinges that do
/// not move).
#[derive(Debug, Clone, Copy)]
pub(crate) struct Motion {
    pub rel: [Twist; 4],
    pub opening: [f64; 4],
}

/// Relative tolerance of admissibility: an opening velocity above `-ADMISSIBLE_TOL` times the
/// largest one counts as opening (it is a joint that does not move, round-off aside).
pub(crate) const ADMISSIBLE_TOL: f64 = 1e-9;

/// The one-degree-of-freedom motion with the given active joints, if admissible. `closed`:
/// both ends of the chain are supported (closure `sum r = 0`, needs hinges + 2 open = 4);
/// otherwise a single hinge of a one-support chain.
pub(crate) fn solve_motion(actives: &[Active], closed: bool) -> Option<Motion> {
    let mut cols: [Twist; 4] = [[0.0; 3]; 4];
    let mut owner = [0usize; 4];
    let mut nc = 0;
    for (i, a) in actives.iter().enumerate() {
        let push = |cols: &mut [Twist; 4], owner: &mut [usize; 4], nc: &mut usize, t| {
            if *nc < 4 {
                cols[*nc] = t;
                owner[*nc] = i;
            }
            *nc += 1;
        };
        match a.act {
            Act::Hinge(JointEnd::P1) => push(&mut cols, &mut owner, &mut nc, rot(a.p1)),
            Act::Hinge(JointEnd::P2) => push(&mut cols, &mut owner, &mut nc, rot(a.p2)),
            Act::Open => {
                push(&mut cols, &mut owner, &mut nc, rot(a.p1));
                push(&mut cols, &mut owner, &mut nc, trans(a.normal()));
            }
        }
    }
    let mut coef = [0.0; 4];
    if closed {
        if nc != 4 {
            return None;
        }
        coef[0] = det3(cols[1], cols[2], cols[3]);
        coef[1] = -det3(cols[0], cols[2], cols[3]);
        coef[2] = det3(cols[0], cols[1], cols[3]);
        coef[3] = -det3(cols[0], cols[1], cols[2]);
        if rank_deficient(&cols, &coef, actives) {
            return None;
        }
    } else {
        if nc != 1 {
            return None;
        }
        coef[0] = 1.0;
    }
    let mut rel = [[0.0; 3]; 4];
    for k in 0..nc {
        for c in 0..3 {
            rel[owner[k]][c] += coef[k] * cols[k][c];
        }
    }
    // Opening velocities (normal relative velocity, `to` minus `from`, along n).
    let mut values = [0.0; 8];
    let mut opening = [0.0; 4];
    let mut nv = 0;
    for (i, a) in actives.iter().enumerate() {
        let n = a.normal();
        let vn = |q: Vec2| velocity(rel[i], q).dot(&n);
        match a.act {
            Act::Hinge(JointEnd::P1) => {
                opening[i] = vn(a.p2);
                values[nv] = opening[i];
                nv += 1;
            }
            Act::Hinge(JointEnd::P2) => {
                opening[i] = vn(a.p1);
                values[nv] = opening[i];
                nv += 1;
            }
            Act::Open => {
                values[nv] = vn(a.p1);
                values[nv + 1] = vn(a.p2);
                opening[i] = values[nv].min(values[nv + 1]);
                nv += 2;
            }
        }
    }
    let vmax = values[..nv].iter().fold(0.0_f64, |m, v| m.max(v.abs()));
    if vmax.is_nan() || vmax <= 0.0 || !vmax.is_finite() {
        return None;
    }
    let tol = ADMISSIBLE_TOL * vmax;
    let sigma = if values[..nv].iter().all(|&v| v >= -tol) {
        1.0
    } else if values[..nv].iter().all(|&v| v <= tol) {
        -1.0
    } else {
        return None;
    };
    for r in rel.iter_mut().take(actives.len()) {
        for c in r.iter_mut() {
            *c *= sigma;
        }
    }
    for o in opening.iter_mut() {
        *o *= sigma / vmax;
    }
    Some(Motion { rel, opening })
}

/// Relative round-off level below which a 3 x 3 minor of the closure matrix counts as zero.
/// Well below the threshold at which the discrete search treats three hinge points as
/// collinear (`1e-11 size^2`), so no candidate of its fast paths is ever rejected here.
const RANK_TOL: f64 = 1e-12;

/// Whether every 3 x 3 minor (`coef`) of the closure matrix `cols` is zero within round-off:
/// then the matrix has rank < 3, the active joints allow more than one degree of freedom, and
/// the cofactors are round-off noise whose signs mean nothing. This happens when three hinges
/// sit at one point, e.g. the intrados apex of a pointed arch in the continuous model, shared
/// by the vertical crown joint and the last radial sections on both sides of it: the apex is
/// computed three ways, the points differ by ~1e-16, and the noise "mechanism" can have any
/// G/A (it made a sound pointed arch "cannot stand"). The one-degree-of-freedom members of
/// such a set have fewer distinct active joints and are found as such.
///
/// A minor of `r` rotation columns `(1, p_y, -p_x)` and `3 - r` unit translations has the
/// dimension length^(r - 1) and is computed from coordinates of size up to `x`, so its
/// round-off is about `eps x^(r - 1)`.
fn rank_deficient(cols: &[Twist; 4], coef: &[f64; 4], actives: &[Active]) -> bool {
    let x = actives
        .iter()
        .flat_map(|a| [a.p1.norm(), a.p2.norm()])
        .fold(0.0_f64, f64::max);
    let rotation = |c: &Twist| c[0] != 0.0;
    coef.iter().enumerate().all(|(k, c)| {
        let r = (0..4).filter(|&i| i != k && rotation(&cols[i])).count() as i32;
        c.abs() <= RANK_TOL * x.powi(r - 1)
    })
}

/// `(A, G)` (see [`work`]) of a motion whose bodies (between consecutive active joints, and
/// after the last one for a one-support chain) have sums `bodies`.
pub(crate) fn motion_work(m: &Motion, bodies: &[Sums]) -> (f64, f64) {
    let mut t = [0.0; 3];
    let (mut a, mut g) = (0.0, 0.0);
    for (k, s) in bodies.iter().enumerate() {
        for (tc, rc) in t.iter_mut().zip(m.rel[k]) {
            *tc += rc;
        }
        let (da, dg) = work(t, *s);
        a += da;
        g += dg;
    }
    (a, g)
}

/// The least multiplier a structure needs (`max G/A` over `A < 0`) above which it cannot stand
/// at lambda = 0: an absolute round-off allowance, as `G` of a mechanism that lifts nothing is
/// zero only to round-off.
const NEEDED_TOL: f64 = 1e-12;

/// Running extremes of `G/A` over admissible mechanisms, with the arguments attached.
#[derive(Debug, Clone)]
pub(crate) struct Extremes<K> {
    /// `min G/A` over `A > 0`.
    pub best: Option<(f64, K)>,
    /// `max G/A` over `A < 0`.
    pub needed: Option<(f64, K)>,
    /// A mechanism with `A = 0` and `G < 0`.
    pub stalled: Option<K>,
    pub admissible: u64,
}

impl<K: Clone + Ord> Extremes<K> {
    pub fn new() -> Self {
        Extremes {
            best: None,
            needed: None,
            stalled: None,
            admissible: 0,
        }
    }

    /// Record an admissible mechanism with load power `a` and gravity power `g`.
    #[inline]
    pub fn push(&mut self, a: f64, g: f64, key: impl FnOnce() -> K) {
        self.admissible += 1;
        self.record(a, g, key);
    }

    /// As `push`, without counting the mechanism (the caller counts).
    #[inline]
    pub fn record(&mut self, a: f64, g: f64, key: impl FnOnce() -> K) {
        if a > 0.0 {
            let l = g / a;
            match &self.best {
                Some((b, _)) if *b < l => {}
                Some((b, k)) if *b == l => {
                    let key = key();
                    if key < *k {
                        self.best = Some((l, key));
                    }
                }
                _ => self.best = Some((l, key())),
            }
        } else if a < 0.0 {
            let l = g / a;
            match &self.needed {
                Some((b, _)) if *b >= l => {}
                _ => self.needed = Some((l, key())),
            }
        } else if g < 0.0 && self.stalled.is_none() {
            self.stalled = Some(key());
        }
    }

    /// The same extremes with every key mapped by `f`.
    pub fn map_keys<L>(self, f: impl Fn(K) -> L) -> Extremes<L> {
        Extremes {
            best: self.best.map(|(l, k)| (l, f(k))),
            needed: self.needed.map(|(l, k)| (l, f(k))),
            stalled: self.stalled.map(&f),
            admissible: self.admissible,
        }
    }

    pub fn merge(mut self, o: Self) -> Self {
        self.admissible += o.admissible;
        if let Some((l, k)) = o.best {
            match &self.best {
                Some((b, bk)) if *b < l || (*b == l && *bk <= k) => {}
                _ => self.best = Some((l, k)),
            }
        }
        if let Some((l, k)) = o.needed {
            match &self.needed {
                Some((b, _)) if *b >= l => {}
                _ => self.needed = Some((l, k)),
            }
        }
        if self.stalled.is_none() {
            self.stalled = o.stalled;
        }
        self
    }

    /// The status, per the module docs, and the key of the mechanism that decides it.
    pub fn verdict(&self) -> (Status, Option<K>) {
        if let Some(k) = &self.stalled {
            return (Status::CannotStand, Some(k.clone()));
        }
        match (&self.best, &self.needed) {
            (Some((b, _)), Some((n, nk))) if n > b => (Status::CannotStand, Some(nk.clone())),
            // Every multiplier that equilibrium allows lies above 0: without the earthquake
            // the permanent loads already drive this mechanism (possible when they are not
            // symmetric; under self-weight alone the interval always straddles 0).
            (_, Some((n, nk))) if *n > NEEDED_TOL => (Status::CannotStand, Some(nk.clone())),
            (Some((b, k)), _) if *b < 0.0 => (Status::CannotStand, Some(k.clone())),
            (Some((_, k)), _) => (Status::Collapse, Some(k.clone())),
            (None, _) => (Status::NoCollapse, None),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn hinge(x: f64, y: f64, end: JointEnd, top: Vec2) -> Active {
        let p = Vec2::new(x, y);
        let (p1, p2) = match end {
            JointEnd::P1 => (p, top),
            JointEnd::P2 => (top, p),
        };
        Active {
            p1,
            p2,
            act: Act::Hinge(end),
        }
    }

    /// Three hinges at one point (off by round-off, as the intrados apex of a pointed arch
    /// computed three ways) are not a one-degree-of-freedom mechanism, whatever the signs of
    /// the noise; two hinges at one point and two elsewhere still are.
    #[test]
    fn three_hinges_at_one_point_are_no_mechanism() {
        let top = Vec2::new(0.0, 1.05);
        let apex = 0.90312;
        for (dx, dy) in [(1e-17, 0.0), (-1e-17, 1e-16), (0.0, -1e-16), (2e-17, 1e-16)] {
            let actives = [
                hinge(-0.2, 0.83, JointEnd::P1, Vec2::new(-0.26, 0.97)),
                hinge(-1e-17, apex, JointEnd::P1, Vec2::new(-0.03, 1.05)),
                hinge(0.0, apex + dy, JointEnd::P1, top),
                hinge(dx, apex, JointEnd::P1, Vec2::new(0.03, 1.05)),
            ];
            assert!(solve_motion(&actives, true).is_none());
        }
        // A proper four-hinge mechanism of the same arch is still found.
        let actives = [
            hinge(-0.7, 0.19, JointEnd::P1, Vec2::new(-0.85, 0.22)),
            hinge(-0.3, 0.95, JointEnd::P2, Vec2::new(-0.25, 0.8)),
            hinge(0.5, 0.6, JointEnd::P1, Vec2::new(0.6, 0.7)),
            hinge(0.875, 0.0, JointEnd::P2, Vec2::new(0.725, 0.0)),
        ];
        assert!(solve_motion(&actives, true).is_some());
    }
}
