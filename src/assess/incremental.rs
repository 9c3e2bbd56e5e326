//! The capacity curve of any assembly by an incremental analysis: the structure is moved along
//! its mechanism in small steps, its contacts are found again in each displaced configuration,
//! and the multiplier that holds it is re-solved there (C8.7.1.2.2 of the Circolare 2019 asks
//! for the multiplier "in configurazioni variate" along the mechanism; for the four-hinge chains
//! [`super::Linkage`] does it in closed form, this does it for walls, lintels, arcades and
//! spandrels, whose mechanisms rock, lift and slide many blocks at once).
//!
//! # One step
//! In configuration `X` (each block's rigid motion from rest) the general kinematic program
//! (`crate::kinematic::general`, the dual of the static program) gives the least multiplier
//! `alpha(X)` over the admissible mechanisms of the displaced structure and the block twists
//! of that mechanism, scaled so that the control point moves toward the load at unit speed.
//! Where several mechanisms share the least multiplier (the bays of an arcade), the interior
//! point would return their blend; the mechanism followed is one of them, the vertex that
//! opens least (`kinematic::general`, a second program with the opening rates weighted by
//! 1e-5), while `alpha` is the least multiplier itself.
//! The configuration is advanced by the exact rigid motion of each block's twist (the
//! exponential of a planar twist: a rotation by `omega tau` about its instantaneous centre, or
//! a translation), by the midpoint rule: a half step with the twists of `X`, the program
//! solved there, a full step from `X` with the midpoint's twists. The step is chosen in the
//! control displacement `d_k`: a small first step, then a hundredth of the distance to
//! `alpha = 0` extrapolated along the last secant ([`TARGET_STEPS`]); the curve ends where
//! `alpha` crosses 0, found by linear interpolation between the last two steps.
//!
//! # Contacts in a displaced configuration
//! The contacts are those of the joints at rest, carried by their two blocks (each end at the
//! midpoint of its two copies, one moved with each block; the gap at an end is
//! `n . (x_to - x_from)` with the `from` block's face normal). A joint whose two ends touch is
//! a face contact; a joint with one end touching is a point contact there, a
//! hinge about which the blocks may turn either way (a joint of length [`POINT_LENGTH`] times
//! the size along the mean of the two faces); a joint with neither end touching carries
//! nothing. Which ends touch is the contacts' state, carried from step to step: an end the
//! mechanism opens stops touching, and an end that does not touch touches again once its
//! gap has closed to [`GAP_TOL`] of the size (so that blocks never pass through each other).
//! Blocks that do not touch at rest never touch (no new contacts), and a joint that slides dilates with the associative flow
//! rule, so it separates and carries nothing after the first step: the incremental curve of a
//! sliding mechanism is that of the associative model (docs/friction.md).
//!
//! # Where the curve ends
//! Where `alpha` reaches 0 (`capacity_curve_end = "alpha_zero"`), or earlier where the
//! displaced structure has no equilibrium under any multiplier (the kinematic program is
//! unbounded: a mechanism the action does no work on is driven by gravity, typically a hinge
//! that has to move to a neighbouring joint by a snap the quasi-static path cannot follow):
//! the curve then ends at the last configuration that stands, and `d_k0` is taken there
//! (`"cannot_stand"`; conservative: the curve is cut short). A structure that cannot stand
//! two steps away from rest has no curve, and is refused in words.
//!
//! # Limits
//! Rigid joints (a finite compressive strength is ignored, as in the general program); tie
//! rods and bonded strips are refused (their moved anchors and breaking are followed by
//! [`super::Linkage`] for chains only). Quasi-static: no inertia, no impact; the mechanism may
//! change along the path (a new hinge forms, a contact is lost), which is what re-solving
//! captures.

use super::{AssessError, Rigid};
use crate::assembly::{Assembly, Joint, JointEnd};
use crate::geometry::Vec2;
use crate::kinematic::general::{joint_rates, least_mechanism, Least, MOVES_REL_TOL};
use crate::kinematic::{velocity, Twist};
use crate::model::Model;
use crate::outcome::Direction;

/// A joint end whose gap is below this fraction of the structure's size still touches.
pub const GAP_TOL: f64 = 1e-7;
/// Length of a point contact (a hinge in a displaced configuration), as a fraction of the
/// structure's size. It does not change the multiplier of a mechanism that keeps turning the
/// same way (the least mechanism turns about the hinge end itself), but it gives the contact a
/// moment capacity `N l / 2` against turning back; it must exceed the path's drift (the
/// midpoint rule leaves a hinge's two copies about 1e-7 of the size apart after a hundred
/// steps), or round-off alone makes the displaced structure look unable to stand. On the
/// bundled portal the curve ends (cannot stand) at d_k = 51.8 mm with 1e-7 and 1e-5, and at
/// 71.6 mm with 1e-3: it converges as the length falls.
pub const POINT_LENGTH: f64 = 1e-5;
/// Steps aimed at between rest and `alpha = 0`.
pub const TARGET_STEPS: f64 = 100.0;
/// The first step, as a fraction of the structure's size.
const FIRST_STEP: f64 = 1e-4;
/// The smallest step, as a fraction of the structure's size.
const MIN_STEP: f64 = 1e-7;
/// Steps after which the path is given up.
pub const MAX_STEPS: usize = 2000;
/// A block whose rest velocity is below this fraction of the fastest one's does not move.
const MOVES_TOL: f64 = 1e-4;

/// Per block: the translation of its centroid and its rotation about it (rad), from rest (the
/// form of [`super::Linkage::placements`] and [`crate::model::LoadCase::moved`]).
pub type Moves = Vec<(Vec2, f64)>;

/// One configuration of the path.
#[derive(Debug, Clone)]
pub struct Step {
    /// The control point's horizontal displacement toward the load (m).
    pub d_k: f64,
    /// The multiplier that holds the configuration.
    pub alpha: f64,
    /// The control block's rotation (rad, magnitude).
    pub rotation: f64,
    /// Every block's motion from rest.
    pub moves: Moves,
}

/// The path of a mechanism from rest to `alpha = 0`.
#[derive(Debug, Clone)]
pub struct Path {
    /// The configurations, from rest; the last is at `alpha = 0` (interpolated), or the last
    /// one that stands when the structure falls under its own weight first (`falls`).
    pub steps: Vec<Step>,
    /// Whether each block moves in the mechanism at rest.
    pub moving: Vec<bool>,
    /// The block twists (about the origin) of the mechanism at rest, the control point
    /// moving toward the load at unit speed.
    pub rest: Vec<Twist>,
    /// The control block.
    pub control_block: usize,
    /// Programs solved along the path.
    pub solves: usize,
    /// Whether the path ended because the displaced structure falls under its own weight
    /// (an admissible mechanism the action does no work on is driven by the permanent loads)
    /// before `alpha` reached 0; the curve then ends at the last configuration that stands.
    pub falls: bool,
}

/// Where a block's motion `m` takes point `p` of that block (`c` its centroid at rest).
fn place(c: Vec2, m: (Vec2, f64), p: Vec2) -> Vec2 {
    Rigid::of_block(c, m).apply(p)
}

/// `v` turned by `angle` (rad).
fn rotate(v: Vec2, angle: f64) -> Vec2 {
    Rigid::rotation(Vec2::zeros(), angle).apply(v)
}

/// How a joint at rest touches in a displaced configuration.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Contact {
    /// Face to face (the joint's blocks have not turned or slid relative to each other).
    Face,
    /// At one end only: a hinge.
    Point(JointEnd),
    /// Not at all.
    Open,
}

/// The model displaced by `moves`, each joint at rest touching as `contacts` says (module
/// docs), with the index of the joint at rest of each of its joints.
pub fn displaced(
    model: &Model,
    moves: &[(Vec2, f64)],
    contacts: &[Contact],
) -> (Model, Vec<usize>) {
    let rest = &model.assembly;
    let size = rest.size();
    let at =
        |b: Option<usize>, p: Vec2| b.map_or(p, |b| place(rest.blocks[b].centroid, moves[b], p));
    let turned = |b: Option<usize>| b.map_or(0.0, |b| moves[b].1);
    let mut joints = Vec::with_capacity(rest.joints.len());
    let mut of = Vec::with_capacity(rest.joints.len());
    for (j, (jt, contact)) in rest.joints.iter().zip(contacts).enumerate() {
        // Each end at the midpoint of its two copies (one carried by each block).
        let p1 = 0.5 * (at(jt.from, jt.p1) + at(jt.to, jt.p1));
        let p2 = 0.5 * (at(jt.from, jt.p2) + at(jt.to, jt.p2));
        let along = {
            let u = jt.tangent();
            let m = rotate(u, turned(jt.from)) + rotate(u, turned(jt.to));
            m / m.norm()
        };
        let l = POINT_LENGTH * size;
        let ends = match contact {
            Contact::Face => (p1, p2),
            Contact::Point(JointEnd::P1) => (p1, p1 + l * along),
            Contact::Point(JointEnd::P2) => (p2 - l * along, p2),
            Contact::Open => continue,
        };
        joints.push(Joint {
            p1: ends.0,
            p2: ends.1,
            ..jt.clone()
        });
        of.push(j);
    }
    let mut assembly = Assembly {
        blocks: rest.blocks.clone(),
        joints,
    };
    super::move_blocks(&mut assembly.blocks, moves);
    let model = Model {
        assembly,
        loads: model.loads.moved(moves),
        strength: model.strength,
        ties: Vec::new(),
        strips: Vec::new(),
        passive: Vec::new(),
    };
    (model, of)
}

/// The gaps `n . (x_to - x_from)` at the two ends of every joint at rest in configuration
/// `moves` (the `from` block's face normal, each end's two copies moved with their blocks).
fn gaps(rest: &Assembly, moves: &[(Vec2, f64)]) -> Vec<[f64; 2]> {
    let at =
        |b: Option<usize>, p: Vec2| b.map_or(p, |b| place(rest.blocks[b].centroid, moves[b], p));
    rest.joints
        .iter()
        .map(|jt| {
            let n = rotate(jt.normal(), jt.from.map_or(0.0, |b| moves[b].1));
            let gap = |p: Vec2| n.dot(&(at(jt.to, p) - at(jt.from, p)));
            [gap(jt.p1), gap(jt.p2)]
        })
        .collect()
}

/// The contacts `contacts` of `displaced` (whose joint `k` is the rest joint `of[k]`) once
/// its mechanism `twists` moves: an end the mechanism opens stops touching.
fn opened(contacts: &[Contact], displaced: &Model, of: &[usize], twists: &[Twist]) -> Vec<Contact> {
    let rates = joint_rates(&displaced.assembly, twists);
    let largest = rates.iter().fold(0.0_f64, |m, r| {
        m.max(r.dn1.abs()).max(r.dn2.abs()).max(r.dt.abs())
    });
    let opens = |dn: f64| dn > MOVES_REL_TOL * largest;
    let mut next = contacts.to_vec();
    for (k, r) in rates.iter().enumerate() {
        let j = of[k];
        next[j] = match (contacts[j], opens(r.dn1), opens(r.dn2)) {
            (Contact::Face | Contact::Point(_), true, true) => Contact::Open,
            (Contact::Face, true, false) => Contact::Point(JointEnd::P2),
            (Contact::Face, false, true) => Contact::Point(JointEnd::P1),
            (c, _, _) => c,
        };
    }
    next
}

/// The contacts `contacts` with every end that does not touch but whose gap (`gaps`) has
/// closed to [`GAP_TOL`] of the size touching again (so that blocks do not pass through
/// each other, and an end a mechanism opened by round-off only closes at once).
fn reclosed(contacts: &[Contact], gaps: &[[f64; 2]], size: f64) -> Vec<Contact> {
    let closed = |g: f64| g <= GAP_TOL * size;
    contacts
        .iter()
        .zip(gaps)
        .map(|(c, g)| match (*c, closed(g[0]), closed(g[1])) {
            (Contact::Open, true, true)
            | (Contact::Point(JointEnd::P1), _, true)
            | (Contact::Point(JointEnd::P2), true, _) => Contact::Face,
            (Contact::Open, true, false) => Contact::Point(JointEnd::P1),
            (Contact::Open, false, true) => Contact::Point(JointEnd::P2),
            (c, _, _) => c,
        })
        .collect()
}

/// `moves` advanced by the rigid motion of each block's twist (about the origin, in the
/// current configuration) over a time `tau`: `x -> R(phi) x + V(phi) v tau`, `phi = omega
/// tau`, `V(phi) = [[sin phi, cos phi - 1], [1 - cos phi, sin phi]] / phi`, the exponential
/// of a planar twist.
fn advance(rest: &Assembly, moves: &[(Vec2, f64)], twists: &[Twist], tau: f64) -> Moves {
    rest.blocks
        .iter()
        .zip(moves)
        .zip(twists)
        .map(|((b, &(d, angle)), t)| {
            let phi = t[0] * tau;
            let (s, c1) = if phi.abs() < 1e-6 {
                // sin(phi)/phi and (1 - cos phi)/phi by their series (exact to 1e-24).
                (1.0 - phi * phi / 6.0, phi / 2.0 - phi.powi(3) / 24.0)
            } else {
                (phi.sin() / phi, (1.0 - phi.cos()) / phi)
            };
            let v = Vec2::new(t[1], t[2]) * tau;
            let shift = Vec2::new(s * v.x - c1 * v.y, c1 * v.x + s * v.y);
            let now = b.centroid + d;
            let next = rotate(now, phi) + shift;
            (next - b.centroid, angle + phi)
        })
        .collect()
}

/// The control point's displacement toward the load.
fn control_displacement(moves: &[(Vec2, f64)], k: usize, sign: f64) -> f64 {
    sign * moves[k].0.x
}

/// What the program says in a displaced configuration.
enum Solve {
    /// The mechanism's twists (the control point toward the load at unit speed), its
    /// multiplier, and the contacts once it has moved (the ends it opens no longer touch).
    Moves(Vec<Twist>, f64, Vec<Contact>),
    /// The displaced structure falls under its own weight.
    Falls,
}

struct Follower<'a> {
    model: &'a Model,
    sign: f64,
    control: usize,
    size: f64,
    solves: usize,
}

impl Follower<'_> {
    fn at(&self, moves: &[(Vec2, f64)]) -> String {
        format!(
            "at d_k = {:.4e} m",
            control_displacement(moves, self.control, self.sign)
        )
    }

    /// The contacts `contacts` in configuration `moves`, with the ends whose gap has closed
    /// touching again.
    fn reclosed(&self, contacts: &[Contact], moves: &[(Vec2, f64)]) -> Vec<Contact> {
        reclosed(contacts, &gaps(&self.model.assembly, moves), self.size)
    }

    fn solve(&mut self, moves: &[(Vec2, f64)], contacts: &[Contact]) -> Result<Solve, AssessError> {
        let (m, of) = displaced(self.model, moves, contacts);
        self.solves += 1;
        let least = least_mechanism(&m, self.sign, true)
            .map_err(|e| AssessError::Incremental(format!("{}: {e}", self.at(moves))))?;
        match least {
            Least::Mechanism(t, alpha) => {
                let k = self.control;
                let speed = self.sign * velocity(t[k], m.assembly.blocks[k].centroid).x;
                let largest = t
                    .iter()
                    .zip(&m.assembly.blocks)
                    .fold(0.0_f64, |a, (t, b)| a.max(velocity(*t, b.centroid).norm()));
                if speed.is_nan() || speed <= MOVES_TOL * largest {
                    return Err(AssessError::Incremental(format!(
                        "{} the mechanism no longer moves the control block {k} toward the load",
                        self.at(moves)
                    )));
                }
                let t: Vec<Twist> = t.iter().map(|t| t.map(|x| x / speed)).collect();
                let next = opened(contacts, &m, &of, &t);
                Ok(Solve::Moves(t, alpha, next))
            }
            Least::Falls => Ok(Solve::Falls),
            Least::Nothing => Err(AssessError::Incremental(format!(
                "{} no admissible mechanism is driven by the load",
                self.at(moves)
            ))),
        }
    }
}

/// Follow the mechanism of `model` (the load toward `direction`) from rest to `alpha = 0`;
/// `control`: the control block (default: the block whose centroid moves most horizontally
/// at rest).
pub fn follow(
    model: &Model,
    direction: Direction,
    control: Option<usize>,
) -> Result<Path, AssessError> {
    if !model.ties.is_empty() {
        return Err(AssessError::IncrementalTies {
            count: model.ties.len(),
        });
    }
    if !model.strips.is_empty() {
        return Err(AssessError::Strips {
            count: model.strips.len(),
        });
    }
    if !model.passive.is_empty() {
        return Err(AssessError::Passive {
            count: model.passive.len(),
        });
    }
    let rest = &model.assembly;
    let nb = rest.blocks.len();
    let sign = direction.sign();
    let size = rest.size();
    let zero: Moves = vec![(Vec2::zeros(), 0.0); nb];
    let faces = vec![Contact::Face; rest.joints.len()];
    // The mechanism at rest, before the control block is known.
    let (raw, alpha0) = match least_mechanism(model, sign, true)
        .map_err(|e| AssessError::Incremental(format!("at rest: {e}")))?
    {
        Least::Mechanism(t, a) => (t, a),
        Least::Nothing => {
            return Err(AssessError::Incremental(
                "at rest no admissible mechanism is driven by the load".into(),
            ))
        }
        Least::Falls => {
            return Err(AssessError::Incremental(
                "at rest the structure falls under its own weight".into(),
            ))
        }
    };
    let speed = |b: usize| velocity(raw[b], rest.blocks[b].centroid).norm();
    let largest = (0..nb).map(speed).fold(0.0_f64, f64::max);
    let moving: Vec<bool> = (0..nb).map(|b| speed(b) > MOVES_TOL * largest).collect();
    let dx = |b: usize| sign * velocity(raw[b], rest.blocks[b].centroid).x;
    let control_block = match control {
        Some(b) if b >= nb => {
            return Err(AssessError::NoSuchBlock {
                block: b,
                blocks: nb,
            })
        }
        Some(b) if !moving[b] || dx(b) == 0.0 => return Err(AssessError::StillBlock { block: b }),
        Some(b) => b,
        None => {
            (0..nb)
                .filter(|&b| moving[b])
                .fold((0, -1.0), |best, b| {
                    let d = dx(b).abs();
                    if d > best.1 {
                        (b, d)
                    } else {
                        best
                    }
                })
                .0
        }
    };
    let mut f = Follower {
        model,
        sign,
        control: control_block,
        size,
        solves: 1,
    };
    let Solve::Moves(twists0, _, opened0) = f.solve(&zero, &faces)? else {
        return Err(AssessError::Incremental(
            "at rest the structure falls under its own weight".into(),
        ));
    };
    let mut steps = vec![Step {
        d_k: 0.0,
        alpha: alpha0,
        rotation: 0.0,
        moves: zero.clone(),
    }];
    // The configuration, the mechanism there, and the contacts once it moves.
    let (mut moves, mut twists, mut contacts) = (zero, twists0.clone(), opened0);
    let mut falls = false;
    let mut dd = FIRST_STEP * size;
    while steps.last().is_some_and(|s| s.alpha > 0.0) {
        if steps.len() > MAX_STEPS {
            return Err(AssessError::NoZero(format!(
                "still needs alpha > 0 after {MAX_STEPS} steps of the incremental analysis"
            )));
        }
        let n = steps.len();
        if n >= 2 {
            let (a, b) = (&steps[n - 2], &steps[n - 1]);
            let slope = (b.alpha - a.alpha) / (b.d_k - a.d_k);
            if slope < 0.0 {
                dd = ((b.d_k + b.alpha / -slope) / TARGET_STEPS).max(MIN_STEP * size);
            }
        }
        // The midpoint rule: the mechanism half a step ahead carries the whole step.
        let mid = advance(rest, &moves, &twists, 0.5 * dd);
        let Solve::Moves(at_mid, _, opened_mid) = f.solve(&mid, &f.reclosed(&contacts, &mid))?
        else {
            falls = true;
            break;
        };
        let next = advance(rest, &moves, &at_mid, dd);
        let touching = f.reclosed(&opened_mid, &next);
        let (t, alpha, opened_next) = match f.solve(&next, &touching)? {
            Solve::Moves(t, a, o) => (t, a, o),
            Solve::Falls => {
                falls = true;
                break;
            }
        };
        let d_k = control_displacement(&next, control_block, sign);
        let last = steps[n - 1].d_k;
        if d_k.is_nan() || d_k <= last {
            return Err(AssessError::Incremental(format!(
                "the control point stops moving toward the load at d_k = {last:.4e} m"
            )));
        }
        steps.push(Step {
            d_k,
            alpha,
            rotation: next[control_block].1.abs(),
            moves: next.clone(),
        });
        moves = next;
        twists = t;
        contacts = opened_next;
    }
    // A structure that cannot stand a step away from rest has no curve to speak of.
    if falls && steps.len() < 3 {
        return Err(AssessError::Incremental(format!(
            "the displaced structure cannot stand under any multiplier once moved by d_k = {:.3e} m along its mechanism (parts of it close back under their own weight), so the incremental analysis has no capacity curve; alpha0 = {alpha0:.6} holds at rest",
            steps.last().map_or(0.0, |s| s.d_k) + dd
        )));
    }
    // The last step crossed alpha = 0: the configuration there, by linear interpolation.
    let n = steps.len();
    if !falls && n >= 2 {
        let (a, b) = (&steps[n - 2], &steps[n - 1]);
        let w = a.alpha / (a.alpha - b.alpha);
        let zero = interpolate(a, b, w);
        steps[n - 1] = zero;
    }
    Ok(Path {
        steps,
        moving,
        rest: twists0,
        control_block,
        solves: f.solves,
        falls,
    })
}

/// The step a fraction `w` of the way from `a` to `b` (every quantity linearly).
fn interpolate(a: &Step, b: &Step, w: f64) -> Step {
    let lerp = |x: f64, y: f64| x + w * (y - x);
    Step {
        d_k: lerp(a.d_k, b.d_k),
        alpha: lerp(a.alpha, b.alpha),
        rotation: lerp(a.rotation, b.rotation),
        moves: a
            .moves
            .iter()
            .zip(&b.moves)
            .map(|(p, q)| (p.0 + w * (q.0 - p.0), lerp(p.1, q.1)))
            .collect(),
    }
}

impl Path {
    /// `d_k0`, the control displacement where the curve ends.
    pub fn d_k0(&self) -> f64 {
        self.steps.last().map_or(0.0, |s| s.d_k)
    }

    /// The configuration at control displacement `d` (0 <= d <= d_k0), interpolated linearly
    /// between the steps.
    pub fn at_d_k(&self, d: f64) -> Option<Step> {
        // The end itself (a fraction 1 of d_k0 may round a hair past it).
        let end = self.d_k0();
        let d = if d > end && d <= end * (1.0 + 1e-12) {
            end
        } else {
            d
        };
        let i = self.steps.iter().position(|s| s.d_k >= d)?;
        if i == 0 {
            return self.steps.first().cloned();
        }
        let (a, b) = (&self.steps[i - 1], &self.steps[i]);
        Some(interpolate(a, b, (d - a.d_k) / (b.d_k - a.d_k)))
    }
}
