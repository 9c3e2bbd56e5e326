//! From the collapse multiplier to a seismic verdict: the linear and nonlinear kinematic
//! analysis of a local mechanism of the Italian code (NTC 2018 §8.7.1 and its Circolare
//! n. 7/2019, C8.7.1.2; the same method as Circolare n. 617/2009, C8A.4), with the elastic
//! spectrum of [`crate::spectrum`]. docs/assessment.md states every formula and its clause.
//!
//! 1. **Participating mass** ([`ParticipatingMass`]): the governing mechanism of the kinematic
//!    analysis moves every seismic mass `P_i` (the blocks' self-weights at their centroids and
//!    the seismic loads at their points) by a virtual horizontal displacement `dx_i`;
//!    `M* = (sum P_i dx_i)^2 / (g sum P_i dx_i^2)`, `e* = g M* / sum P_i` (sums over the
//!    masses of the moving blocks), `a0* = alpha0 g / (e* FC)` (C8.7.1.2.1).
//! 2. **Capacity curve** ([`capacity`]): the mechanism is moved through finite rotations with
//!    exact rigid-body kinematics ([`Linkage`]: one block group rocking about its hinge, or the
//!    four-bar linkage of a four-hinge mechanism, its coupler placed by the intersection of two
//!    circles), the hinges staying at their joint ends; at each configuration the multiplier
//!    that holds it is `alpha = G / A` by virtual work with the loads carried by the blocks
//!    (weights stay vertical, seismic forces horizontal). The control point is a block's
//!    centroid, `d_k` its horizontal displacement toward the load; the curve ends at `d_k0`
//!    where alpha = 0. The single-degree-of-freedom curve is `a* = alpha g / (e* FC)`,
//!    `d* = d_k sum P_i dx_i^2 / (dx_k sum P_i dx_i)` (C8.7.1.2.2).
//! 3. **Verdict** ([`verdict`]): `du* = 0.4 d0*`, `ds* = 0.4 du*`, `as* = a*(ds*)`,
//!    `Ts = 2 pi sqrt(ds*/as*)`; linear check `a0* >= ag S / q`, nonlinear check
//!    `du* >= SDe(Ts)` (and the amplified demands of a mechanism at height `Z`); the largest
//!    `ag` passing each check, by bisection. The mechanism passes when either check is
//!    satisfied (C8.7.1 lets the engineer verify it with either analysis, [`RULE`]).
//! 4. **Both directions** ([`crate::analysis::assess_directions`]): the seismic action is reversible, so the
//!    scene is assessed with the load toward the right and toward the left (each its own
//!    governing mechanism) and the worse direction governs ([`crate::analysis::Assessment::governing`]).
//!
//! Tie rods move with their blocks: at each configuration a tie that has lengthened carries its
//! capacity (rigid-plastic, as in the limit analyses, so `alpha0` is the kinematic multiplier
//! with the ties), until its stretch passes its ultimate strain (`ties[].ultimate_strain`,
//! default 7.5 %, B450C's `A_gt`) and it has broken; a tie that has shortened has gone slack
//! ([`crate::model::Tie::power_moved`]). Mechanisms that hold a tie at its length
//! (`Family::HingesWithHeldTies`) and bonded strips are refused.
//!
//! Mechanisms with a joint that opens completely (families other than four hinges or one
//! hinge) have no finite motion fixed by their hinges alone and are refused.

use crate::assembly::Assembly;
use crate::geometry::Vec2;
use crate::kinematic::{det3, rot, velocity, Family, Mechanism};
use crate::model::Model;
use crate::outcome::Direction;
use crate::spectrum::{Site, Spectrum, G};
use std::ops::Range;
use thiserror::Error;

pub mod incremental;

/// Why a mechanism has no capacity curve.
#[derive(Debug, Error)]
pub enum AssessError {
    #[error("no capacity curve for a {family} mechanism: only mechanisms of hinges (one block group rocking on one support, or four hinges) have a finite motion fixed by their hinges")]
    Unsupported { family: &'static str },
    #[error("the control block {block} does not exist (the structure has {blocks} blocks)")]
    NoSuchBlock { block: usize, blocks: usize },
    #[error("the control block {block} does not move in the mechanism; choose a block between its hinges")]
    StillBlock { block: usize },
    #[error("the capacity curve needs at least 3 points, not {0}")]
    TooFewPoints(usize),
    #[error("the mechanism {0} before its multiplier reaches 0, so it has no d_k0")]
    NoZero(String),
    #[error("incremental analysis: {0}")]
    Incremental(String),
    #[error("the incremental capacity curve does not follow tie rods ({count} in the scene): their moved anchors and breaking are followed for the mechanisms of chains (one hinge or four hinges) only; the static and kinematic multipliers with the ties are given by `voussoir analyze`")]
    IncrementalTies { count: usize },
    #[error("the seismic load does no work on the mechanism")]
    NoSeismicWork,
    #[error("the capacity curve does not follow bonded strips ({count} joints crossed) through the finite motion of the mechanism: a rigid-plastic strip debonds at the first opening of its joint, and what it carries after needs a bond-slip law this model does not have; so the reinforced structure is not assessed rather than assessed without them; the static and kinematic multipliers with the strips are given by `voussoir analyze`")]
    Strips { count: usize },
    #[error("the capacity curve does not follow the fill's passive resistance ({count} faces against the fill): the reaction grows with the face's movement into the fill (the mobilisation) in a way this rigid-plastic model does not describe along the finite motion of the mechanism; so the structure is not assessed rather than assessed without it; the static and kinematic multipliers with it are given by `voussoir analyze`")]
    Passive { count: usize },
}

/// `(F, point, seismic weight)` of a load.
type Load = (Vec2, Vec2, f64);

/// A rigid motion `x -> to + R(angle) (x - from)`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Rigid {
    pub from: Vec2,
    pub to: Vec2,
    /// Rotation (rad, counter-clockwise).
    pub angle: f64,
}

impl Rigid {
    /// The motion of a block whose centroid, at `centroid` at rest, has moved by `m.0` and
    /// turned by `m.1` about itself (the form of [`Linkage::placements`]).
    pub fn of_block(centroid: Vec2, m: (Vec2, f64)) -> Rigid {
        Rigid {
            from: centroid,
            to: centroid + m.0,
            angle: m.1,
        }
    }

    fn rotation(about: Vec2, angle: f64) -> Rigid {
        Rigid {
            from: about,
            to: about,
            angle,
        }
    }
    pub fn apply(&self, x: Vec2) -> Vec2 {
        let (sn, cs) = self.angle.sin_cos();
        let r = x - self.from;
        self.to + Vec2::new(cs * r.x - sn * r.y, sn * r.x + cs * r.y)
    }
}

/// How the bodies of a mechanism move.
#[derive(Debug, Clone, Copy)]
enum Kind {
    /// One body turning about a hinge on the ground.
    Rocking { pivot: Vec2 },
    /// Three bodies: `a` and `d` on the ground, `b` and `c` between bodies. `branch`: the side
    /// of the line `b d` that `c` stays on.
    FourBar {
        a: Vec2,
        b: Vec2,
        c: Vec2,
        d: Vec2,
        branch: f64,
    },
}

/// The finite kinematics of a mechanism: its bodies (ranges of blocks) and how they move as
/// the first body turns by `u >= 0` in its direction of motion.
#[derive(Debug, Clone)]
pub struct Linkage {
    kind: Kind,
    bodies: Vec<Range<usize>>,
    /// Sense (+1 counter-clockwise) of the first body's rotation in the mechanism.
    sense: f64,
    /// Signs of the hinges' relative rotations at `u = 0` (the hinges must keep opening).
    signs: [f64; 4],
}

/// One configuration of a linkage: the rigid motion of each body from the rest position and
/// its twist `(omega, vx0, vy0)` (arbitrary scale, sense of increasing `u`).
#[derive(Debug, Clone)]
pub struct Configuration {
    pub motions: Vec<Rigid>,
    pub twists: Vec<[f64; 3]>,
}

impl Linkage {
    /// The linkage of a mechanism of the kinematic analysis.
    pub fn new(assembly: &Assembly, mechanism: &Mechanism) -> Result<Linkage, AssessError> {
        let nb = assembly.blocks.len();
        let family = match mechanism.family {
            Family::FourHinges => "four-hinge (with a hinge that does not turn)",
            Family::TwoHingesOneOpen => "two-hinges-and-one-open-joint",
            Family::TwoOpen => "two-open-joints",
            Family::OneHinge => "one-hinge",
            Family::HingesWithHeldTies => "tied",
            Family::General => "general (any blocks rocking, lifting or sliding)",
        };
        let point = |k: usize| Vec2::new(mechanism.hinges[k].x, mechanism.hinges[k].y);
        let omega = |b: usize| mechanism.velocities.get(b).map_or(0.0, |v| v[2]);
        let linkage = match (mechanism.family, mechanism.hinges.len()) {
            (Family::OneHinge, 1) => {
                let j = mechanism.hinges[0].joint;
                let sense = omega(j).signum();
                Linkage {
                    kind: Kind::Rocking { pivot: point(0) },
                    bodies: std::iter::once(j..nb).collect(),
                    sense,
                    signs: [sense, 0.0, 0.0, 0.0],
                }
            }
            (Family::FourHinges, 4) => {
                let js: Vec<usize> = mechanism.hinges.iter().map(|h| h.joint).collect();
                let (a, b, c, d) = (point(0), point(1), point(2), point(3));
                let branch = crate::geometry::cross(d - b, c - b).signum();
                let mut l = Linkage {
                    kind: Kind::FourBar { a, b, c, d, branch },
                    bodies: vec![js[0]..js[1], js[1]..js[2], js[2]..js[3]],
                    sense: omega(js[0]).signum(),
                    signs: [0.0; 4],
                };
                let coef = cofactors(a, b, c, d);
                let s = l.sense * coef[0].signum();
                for (sg, cf) in l.signs.iter_mut().zip(coef) {
                    *sg = (s * cf).signum();
                }
                l
            }
            _ => return Err(AssessError::Unsupported { family }),
        };
        if linkage.sense == 0.0
            || linkage
                .signs
                .iter()
                .take(linkage.hinges())
                .any(|s| *s == 0.0)
        {
            return Err(AssessError::Unsupported { family });
        }
        Ok(linkage)
    }

    fn hinges(&self) -> usize {
        match self.kind {
            Kind::Rocking { .. } => 1,
            Kind::FourBar { .. } => 4,
        }
    }

    /// The blocks of each moving body.
    pub fn bodies(&self) -> &[Range<usize>] {
        &self.bodies
    }

    /// The body block `b` belongs to, if it moves.
    pub fn body_of(&self, b: usize) -> Option<usize> {
        self.bodies.iter().position(|r| r.contains(&b))
    }

    /// The configuration after the first body turned by `u` (rad) in its sense of motion, or
    /// None when the linkage cannot reach it (it locks) or a hinge would close.
    pub fn configure(&self, u: f64) -> Option<Configuration> {
        let theta = self.sense * u;
        match self.kind {
            Kind::Rocking { pivot } => Some(Configuration {
                motions: vec![Rigid::rotation(pivot, theta)],
                twists: vec![scaled(rot(pivot), self.sense)],
            }),
            Kind::FourBar { a, b, c, d, branch } => {
                let b1 = Rigid::rotation(a, theta).apply(b);
                let (r2, r3) = ((c - b).norm(), (c - d).norm());
                let dv = d - b1;
                let l = dv.norm();
                if l.is_nan() || l <= 0.0 || l > r2 + r3 || l < (r2 - r3).abs() {
                    return None;
                }
                let along = (r2 * r2 - r3 * r3 + l * l) / (2.0 * l);
                let h = (r2 * r2 - along * along).max(0.0).sqrt();
                let e = dv / l;
                let perp = Vec2::new(-e.y, e.x);
                let c1 = b1 + along * e + branch * h * perp;
                let angle = |v: Vec2| v.y.atan2(v.x);
                let phi2 = angle(c1 - b1) - angle(c - b);
                let phi3 = angle(c1 - d) - angle(c - d);
                let coef = cofactors(a, b1, c1, d);
                let s = self.sense * coef[0].signum();
                if coef
                    .iter()
                    .zip(&self.signs)
                    .any(|(cf, sg)| (s * cf).signum() != *sg)
                {
                    return None;
                }
                let cols = [rot(a), rot(b1), rot(c1), rot(d)];
                let mut twists = Vec::with_capacity(3);
                let mut t = [0.0; 3];
                for k in 0..3 {
                    for (tc, cc) in t.iter_mut().zip(cols[k]) {
                        *tc += s * coef[k] * cc;
                    }
                    twists.push(t);
                }
                Some(Configuration {
                    motions: vec![
                        Rigid::rotation(a, theta),
                        Rigid {
                            from: b,
                            to: b1,
                            angle: phi2,
                        },
                        Rigid::rotation(d, phi3),
                    ],
                    twists,
                })
            }
        }
    }

    /// Per block: translation of its centroid and rotation about it (rad) in configuration
    /// `config` (zero for the blocks that do not move), as drawings and
    /// [`crate::model::LoadCase::moved`] take them.
    pub fn placements(&self, assembly: &Assembly, config: &Configuration) -> Vec<(Vec2, f64)> {
        (0..assembly.blocks.len())
            .map(|b| match self.body_of(b) {
                Some(k) => {
                    let c = assembly.blocks[b].centroid;
                    let m = config.motions[k];
                    (m.apply(c) - c, m.angle)
                }
                None => (Vec2::zeros(), 0.0),
            })
            .collect()
    }

    /// The model with its blocks (and the loads they carry) in configuration `config`; the
    /// joints stay where they were (the supports do not move).
    pub fn moved_model(&self, model: &Model, config: &Configuration) -> Model {
        let moves = self.placements(&model.assembly, config);
        let mut assembly = model.assembly.clone();
        move_blocks(&mut assembly.blocks, &moves);
        Model {
            assembly,
            loads: model.loads.moved(&moves),
            strength: model.strength,
            ties: model.ties.clone(),
            strips: model.strips.clone(),
            passive: model.passive.clone(),
        }
    }
}

/// Move every block (its outline and centroid) by its placement in `moves`.
fn move_blocks(blocks: &mut [crate::assembly::Block], moves: &[(Vec2, f64)]) {
    for (block, &m) in blocks.iter_mut().zip(moves) {
        let r = Rigid::of_block(block.centroid, m);
        block.polygon = block.polygon.iter().map(|p| r.apply(*p)).collect();
        block.centroid = r.apply(block.centroid);
    }
}

fn scaled(t: [f64; 3], s: f64) -> [f64; 3] {
    [s * t[0], s * t[1], s * t[2]]
}

/// Relative rotations of the four hinges `a, b, c, d` (the cofactors of the closure matrix,
/// as in `crate::kinematic`), up to a common factor.
fn cofactors(a: Vec2, b: Vec2, c: Vec2, d: Vec2) -> [f64; 4] {
    let cols = [rot(a), rot(b), rot(c), rot(d)];
    [
        det3(cols[1], cols[2], cols[3]),
        -det3(cols[0], cols[2], cols[3]),
        det3(cols[0], cols[1], cols[3]),
        -det3(cols[0], cols[1], cols[2]),
    ]
}

/// The participating mass of a mechanism (C8.7.1.2.1).
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct ParticipatingMass {
    /// `sum P_i` over the seismic masses of the moving blocks (N).
    pub seismic_weight: f64,
    /// `sum P_i dx_i` (N m, virtual displacements scaled so that `dx_k = 1`).
    pub sum_p_dx: f64,
    /// `sum P_i dx_i^2` (N m^2, same scale).
    pub sum_p_dx2: f64,
    /// `M* = (sum P_i dx_i)^2 / (g sum P_i dx_i^2)` (kg).
    pub m_star: f64,
    /// `e* = g M* / sum P_i`, the participating mass fraction.
    pub e_star: f64,
}

/// One point of the capacity curve.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct CapacityPoint {
    /// Rotation of the mechanism's first body (rad, magnitude).
    pub rotation: f64,
    /// Horizontal displacement of the control point toward the load (m).
    pub d_k: f64,
    /// Multiplier that holds the configuration.
    pub alpha: f64,
    /// Spectral displacement `d*` (m).
    pub d_star: f64,
    /// Spectral acceleration `a* = alpha g / (e* FC)` (m/s^2).
    pub a_star: f64,
}

/// Settings of the capacity curve.
#[derive(Debug, Clone)]
pub struct CapacitySettings {
    /// Points of the curve, from rest to `d_k0` (>= 3). Default 200.
    pub points: usize,
    /// Control block (its centroid is the control point). Default: the block whose centroid
    /// moves most horizontally in the mechanism.
    pub control_block: Option<usize>,
    /// Confidence factor `FC` dividing `a*`. Default 1.
    pub fc: f64,
    /// Follow the mechanism by the incremental analysis ([`incremental`]) even when it is a
    /// chain's (one or four hinges), whose finite kinematics [`Linkage`] gives in closed
    /// form. Default false; mechanisms of other families always take the incremental route.
    pub incremental: bool,
}

impl Default for CapacitySettings {
    fn default() -> Self {
        CapacitySettings {
            points: 200,
            control_block: None,
            fc: 1.0,
            incremental: false,
        }
    }
}

/// How the capacity curve moves the mechanism.
#[derive(Debug, Clone)]
pub enum Motion {
    /// The closed-form finite kinematics of a chain's mechanism (one hinge, or four).
    Linkage(Linkage),
    /// The incremental analysis of any assembly's mechanism ([`incremental`]).
    Incremental(incremental::Path),
}

impl Motion {
    /// `"linkage"` or `"incremental"`, as the JSON says.
    pub fn name(&self) -> &'static str {
        match self {
            Motion::Linkage(_) => "linkage",
            Motion::Incremental(_) => "incremental",
        }
    }

    /// The moving blocks: a linkage's bodies, or for the incremental analysis the runs of
    /// consecutive blocks that move at rest.
    pub fn bodies(&self) -> Vec<Range<usize>> {
        match self {
            Motion::Linkage(l) => l.bodies().to_vec(),
            Motion::Incremental(p) => {
                let mut runs: Vec<Range<usize>> = Vec::new();
                for (b, _) in p.moving.iter().enumerate().filter(|(_, m)| **m) {
                    match runs.last_mut() {
                        Some(r) if r.end == b => r.end = b + 1,
                        _ => runs.push(b..b + 1),
                    }
                }
                runs
            }
        }
    }

    /// The linkage, on the closed-form route.
    pub fn linkage(&self) -> Option<&Linkage> {
        match self {
            Motion::Linkage(l) => Some(l),
            Motion::Incremental(_) => None,
        }
    }

    /// `"alpha_zero"`, or `"cannot_stand"` when the incremental path ended where the displaced
    /// structure has no equilibrium under any multiplier.
    pub fn end(&self) -> &'static str {
        match self {
            Motion::Incremental(p) if p.falls => "cannot_stand",
            _ => "alpha_zero",
        }
    }

    /// The kinematic programs the incremental path solved (0 for a linkage).
    pub fn programs(&self) -> usize {
        match self {
            Motion::Incremental(p) => p.solves,
            Motion::Linkage(_) => 0,
        }
    }

    fn moves_block(&self, b: usize) -> bool {
        match self {
            Motion::Linkage(l) => l.body_of(b).is_some(),
            Motion::Incremental(p) => p.moving.get(b).copied().unwrap_or(false),
        }
    }
}

/// One configuration along the curve, in the form drawings take.
#[derive(Debug, Clone)]
pub struct State {
    /// Per block: translation of its centroid and rotation about it (rad), from rest.
    pub moves: Vec<(Vec2, f64)>,
    /// The control displacement (m).
    pub d_k: f64,
    /// The multiplier that holds the configuration.
    pub alpha: f64,
    /// The rotation of the linkage's first body, or of the incremental path's control block
    /// (rad, magnitude).
    pub rotation: f64,
}

/// The capacity of a mechanism: participating mass and capacity curve.
#[derive(Debug, Clone)]
pub struct Capacity {
    pub motion: Motion,
    pub direction: Direction,
    pub control_block: usize,
    /// Horizontal virtual displacement of the control point, in the scale of the mass sums.
    pub dx_k: f64,
    pub mass: ParticipatingMass,
    pub fc: f64,
    /// `alpha0`, the multiplier at rest (the mechanism's collapse multiplier).
    pub alpha0: f64,
    /// `a0* = alpha0 g / (e* FC)` (m/s^2).
    pub a0_star: f64,
    /// Rotation at which alpha = 0 (rad): of the linkage's first body, or of the incremental
    /// path's control block.
    pub rotation0: f64,
    /// `d_k0`, the control displacement at alpha = 0 (m).
    pub d_k0: f64,
    /// `d0* = d*(d_k0)` (m).
    pub d0_star: f64,
    /// The curve, from rest to `d_k0`, equally spaced in rotation.
    pub curve: Vec<CapacityPoint>,
    /// Seismic masses of the moving blocks: `(block, force, point, seismic weight)`.
    loads: Vec<(usize, Load)>,
    /// The tie rods along the curve, in `[[ties]]` order.
    pub ties: Vec<TieOnCurve>,
}

/// The seismic masses and permanent loads of the moving blocks, by block.
fn moving_loads(model: &Model, moves: impl Fn(usize) -> bool) -> Vec<(usize, Load)> {
    model
        .loads
        .applied()
        .iter()
        .filter(|a| moves(a.block))
        .map(|a| (a.block, (a.force, a.point, a.seismic_weight)))
        .collect()
}

impl Capacity {
    /// `alpha = G / A` in configuration `config`: `A` the power of the seismic forces per
    /// unit multiplier, `G` minus the power of the permanent forces, every load moved with its
    /// block.
    fn alpha_at(&self, linkage: &Linkage, model: &Model, config: &Configuration) -> f64 {
        alpha_of(linkage, model, &self.loads, config, self.direction)
    }

    /// The linkage's configuration and multiplier at rotation `u` (None on the incremental
    /// route, or where the linkage cannot go).
    pub fn at(&self, model: &Model, u: f64) -> Option<(Configuration, f64)> {
        let Motion::Linkage(linkage) = &self.motion else {
            return None;
        };
        let c = linkage.configure(u)?;
        let a = self.alpha_at(linkage, model, &c);
        Some((c, a))
    }

    /// The control displacement `d_k` in the linkage's configuration `config`.
    pub fn d_k(&self, model: &Model, config: &Configuration) -> f64 {
        let c = model.assembly.blocks[self.control_block].centroid;
        let k = match &self.motion {
            Motion::Linkage(l) => l.body_of(self.control_block).unwrap_or(0),
            Motion::Incremental(_) => 0,
        };
        self.direction.sign() * (config.motions[k].apply(c).x - c.x)
    }

    /// The configuration a fraction `fraction` (0 to 1) of the way to `alpha = 0`: of the
    /// rotation for a linkage, of `d_k0` for the incremental path.
    pub fn state_at(&self, model: &Model, fraction: f64) -> Option<State> {
        match &self.motion {
            Motion::Linkage(l) => {
                let u = fraction * self.rotation0;
                let (config, alpha) = self.at(model, u)?;
                Some(State {
                    moves: l.placements(&model.assembly, &config),
                    d_k: self.d_k(model, &config),
                    alpha,
                    rotation: u,
                })
            }
            Motion::Incremental(p) => {
                let s = p.at_d_k(fraction * self.d_k0)?;
                Some(State {
                    moves: s.moves,
                    d_k: s.d_k,
                    alpha: s.alpha,
                    rotation: s.rotation,
                })
            }
        }
    }

    /// `d* = d_k sum P dx^2 / (dx_k sum P dx)`.
    pub fn d_star(&self, d_k: f64) -> f64 {
        d_k * self.mass.sum_p_dx2 / (self.dx_k * self.mass.sum_p_dx)
    }

    /// `a* = alpha g / (e* FC)`.
    pub fn a_star(&self, alpha: f64) -> f64 {
        alpha * G / (self.mass.e_star * self.fc)
    }

    /// The rotation at which `d*` equals `d` (bisection; `d*` grows along the curve), with
    /// `a*` there.
    pub fn at_d_star(&self, model: &Model, d: f64) -> Option<(f64, f64)> {
        let linkage = match &self.motion {
            Motion::Linkage(l) => l,
            Motion::Incremental(p) => {
                // d* is proportional to d_k.
                let s = p.at_d_k(d * self.dx_k * self.mass.sum_p_dx / self.mass.sum_p_dx2)?;
                return Some((s.rotation, self.a_star(s.alpha)));
            }
        };
        let (mut lo, mut hi) = (0.0, self.rotation0);
        for _ in 0..200 {
            let mid = 0.5 * (lo + hi);
            let c = linkage.configure(mid)?;
            if self.d_star(self.d_k(model, &c)) < d {
                lo = mid;
            } else {
                hi = mid;
            }
            if hi - lo <= 1e-15 * self.rotation0 {
                break;
            }
        }
        let (_, alpha) = self.at(model, 0.5 * (lo + hi))?;
        Some((0.5 * (lo + hi), self.a_star(alpha)))
    }
}

fn alpha_of(
    linkage: &Linkage,
    model: &Model,
    loads: &[(usize, Load)],
    config: &Configuration,
    direction: Direction,
) -> f64 {
    let dir = model.loads.seismic_direction(direction.sign());
    let (mut a, mut g) = (0.0, 0.0);
    for &(block, (force, point, seismic)) in loads {
        let Some(k) = linkage.body_of(block) else {
            continue;
        };
        let p = config.motions[k].apply(point);
        let v = velocity(config.twists[k], p);
        g -= force.dot(&v);
        a += seismic * dir.dot(&v);
    }
    // Tie rods, carried by their blocks (rigid-plastic, broken past their ultimate strain).
    let place = placing(linkage, config);
    let speed = |b: Option<usize>, p: Vec2| {
        b.and_then(|b| linkage.body_of(b))
            .map_or(Vec2::zeros(), |k| velocity(config.twists[k], p))
    };
    for tie in &model.ties {
        g += tie.power_moved(place, speed);
    }
    g / a
}

/// Where configuration `config` moves a point of block `b` (None: the ground; a block that
/// is not in the mechanism stays).
fn placing<'a>(
    linkage: &'a Linkage,
    config: &'a Configuration,
) -> impl Fn(Option<usize>, Vec2) -> Vec2 + Copy + 'a {
    move |b: Option<usize>, p: Vec2| {
        b.and_then(|b| linkage.body_of(b))
            .map_or(p, |k| config.motions[k].apply(p))
    }
}

/// What a tie rod does along the capacity curve.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct TieOnCurve {
    /// Index in `[[ties]]`.
    pub index: usize,
    /// `true` when the mechanism lengthens it (it carries its capacity), `false` when it
    /// shortens it (it goes slack).
    pub lengthens: bool,
    /// The force it carries from the onset of motion (N): its capacity when it lengthens, 0
    /// when it goes slack.
    pub force: f64,
    /// The control displacement `d_k` (m) at which it breaks (its stretch reaches
    /// `ultimate_strain` times its length); None when it does not break before `d_k0`.
    pub breaks_at_d_k: Option<f64>,
}

/// The ties along the curve of `cap`: whether each lengthens, and where it breaks (by
/// bisection between the curve's points, to 1e-12 of the rotation).
fn ties_on_curve(cap: &Capacity, linkage: &Linkage, model: &Model) -> Vec<TieOnCurve> {
    let stretch = |tie: &crate::model::Tie, u: f64| {
        linkage
            .configure(u)
            .map(|c| tie.stretch_moved(placing(linkage, &c)))
    };
    model
        .ties
        .iter()
        .enumerate()
        .map(|(index, tie)| {
            // The first rotation of the curve where it is broken, then the bracket.
            let first = cap
                .curve
                .iter()
                .position(|p| stretch(tie, p.rotation).is_some_and(|s| tie.broken(s)));
            let breaks_at_d_k = first.map(|i| {
                let (mut lo, mut hi) = (
                    cap.curve[i.saturating_sub(1)].rotation,
                    cap.curve[i].rotation,
                );
                while hi - lo > 1e-12 * cap.rotation0.max(1e-300) {
                    let mid = 0.5 * (lo + hi);
                    if stretch(tie, mid).is_some_and(|s| tie.broken(s)) {
                        hi = mid;
                    } else {
                        lo = mid;
                    }
                }
                linkage
                    .configure(hi)
                    .map_or(f64::NAN, |c| cap.d_k(model, &c))
            });
            let ahead = cap.curve.get(1).map_or(0.0, |p| p.rotation);
            let lengthens = stretch(tie, ahead.min(1e-6)).is_some_and(|s| s > 0.0);
            TieOnCurve {
                index,
                lengthens,
                force: if lengthens { tie.capacity } else { 0.0 },
                breaks_at_d_k,
            }
        })
        .collect()
}

/// Largest rotation (rad) the search for `alpha = 0` goes to.
const MAX_ROTATION: f64 = std::f64::consts::FRAC_PI_2;
/// Step (rad) of the march toward `alpha = 0` before the bisection.
const ROTATION_STEP: f64 = 1e-3;

/// The capacity of `mechanism` (of `model`, load toward `direction`): participating mass,
/// `alpha0`, `d_k0` and the capacity curve.
pub fn capacity(
    model: &Model,
    mechanism: &Mechanism,
    direction: Direction,
    settings: &CapacitySettings,
) -> Result<Capacity, AssessError> {
    if settings.points < 3 {
        return Err(AssessError::TooFewPoints(settings.points));
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
    if settings.incremental || mechanism.family == Family::General {
        return incremental_capacity(model, direction, settings);
    }
    let linkage = Linkage::new(&model.assembly, mechanism)?;
    let rest = linkage
        .configure(0.0)
        .ok_or(AssessError::Unsupported { family: "locked" })?;
    let sign = direction.sign();
    let nb = model.assembly.blocks.len();
    let dx_of = |b: usize, p: Vec2| -> Option<f64> {
        let k = linkage.body_of(b)?;
        Some(sign * velocity(rest.twists[k], p).x)
    };
    let control_block = match settings.control_block {
        Some(b) if b >= nb => {
            return Err(AssessError::NoSuchBlock {
                block: b,
                blocks: nb,
            })
        }
        Some(b) => {
            if linkage.body_of(b).is_none() {
                return Err(AssessError::StillBlock { block: b });
            }
            b
        }
        None => {
            (0..nb)
                .filter_map(|b| Some((b, dx_of(b, model.assembly.blocks[b].centroid)?.abs())))
                .fold(
                    (0, -1.0),
                    |best, (b, d)| if d > best.1 { (b, d) } else { best },
                )
                .0
        }
    };
    let dx_k0 = dx_of(control_block, model.assembly.blocks[control_block].centroid).unwrap_or(0.0);
    if dx_k0 == 0.0 {
        return Err(AssessError::StillBlock {
            block: control_block,
        });
    }
    let motion = Motion::Linkage(linkage.clone());
    let loads = moving_loads(model, |b| motion.moves_block(b));
    let mass = participating_mass(&loads, |b, p| dx_of(b, p).unwrap_or(0.0) / dx_k0)?;
    let mut cap = Capacity {
        motion,
        direction,
        control_block,
        dx_k: 1.0,
        mass,
        fc: settings.fc,
        alpha0: 0.0,
        a0_star: 0.0,
        rotation0: 0.0,
        d_k0: 0.0,
        d0_star: 0.0,
        curve: Vec::new(),
        loads,
        ties: Vec::new(),
    };
    cap.alpha0 = cap.alpha_at(&linkage, model, &rest);
    if !(cap.alpha0.is_finite() && cap.alpha0 > 0.0) {
        return Err(AssessError::NoZero(format!(
            "needs alpha = {} at rest, not a positive multiplier,",
            cap.alpha0
        )));
    }
    cap.a0_star = cap.a_star(cap.alpha0);
    // March to the first rotation where alpha <= 0, then bisect.
    let (mut lo, mut hi) = (0.0, f64::NAN);
    let mut u = 0.0;
    while u < MAX_ROTATION {
        u = (u + ROTATION_STEP).min(MAX_ROTATION);
        match cap.at(model, u) {
            Some((_, a)) if a > 0.0 => lo = u,
            Some(_) => {
                hi = u;
                break;
            }
            None => {
                return Err(AssessError::NoZero(format!(
                    "locks (or a hinge would close) at a rotation of {u:.4} rad"
                )))
            }
        }
    }
    if hi.is_nan() {
        return Err(AssessError::NoZero(format!(
            "still needs alpha > 0 at a rotation of {MAX_ROTATION:.4} rad"
        )));
    }
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        match cap.at(model, mid) {
            Some((_, a)) if a > 0.0 => lo = mid,
            _ => hi = mid,
        }
        if hi - lo <= f64::EPSILON * hi {
            break;
        }
    }
    // The rotation where alpha crosses zero, by the secant through the final bracket.
    let alpha_lo = cap.at(model, lo).map_or(0.0, |(_, a)| a);
    let alpha_hi = cap.at(model, hi).map_or(0.0, |(_, a)| a);
    cap.rotation0 = if alpha_lo > alpha_hi {
        lo + (hi - lo) * alpha_lo / (alpha_lo - alpha_hi)
    } else {
        lo
    };
    let n = settings.points;
    let mut curve = Vec::with_capacity(n);
    for i in 0..n {
        let u = cap.rotation0 * i as f64 / (n - 1) as f64;
        let Some((c, alpha)) = cap.at(model, u) else {
            return Err(AssessError::NoZero(format!(
                "locks at a rotation of {u:.4} rad"
            )));
        };
        let d_k = cap.d_k(model, &c);
        curve.push(CapacityPoint {
            rotation: u,
            d_k,
            alpha,
            d_star: cap.d_star(d_k),
            a_star: cap.a_star(alpha),
        });
    }
    if let Some(last) = curve.last_mut() {
        cap.d_k0 = last.d_k;
        cap.d0_star = last.d_star;
    }
    cap.curve = curve;
    cap.ties = ties_on_curve(&cap, &linkage, model);
    Ok(cap)
}

/// The participating mass of the seismic masses in `loads` (C8.7.1.2.1), `dx(block, point)`
/// their virtual horizontal displacements toward the load, scaled so that `dx_k = 1` (the
/// sums are scale-free in the ratios that matter, but their values are reported).
fn participating_mass(
    loads: &[(usize, Load)],
    dx: impl Fn(usize, Vec2) -> f64,
) -> Result<ParticipatingMass, AssessError> {
    let (mut sp, mut spdx, mut spdx2) = (0.0, 0.0, 0.0);
    for &(b, (_, point, w)) in loads {
        if w > 0.0 {
            let dx = dx(b, point);
            sp += w;
            spdx += w * dx;
            spdx2 += w * dx * dx;
        }
    }
    if spdx2.is_nan() || spdx2 <= 0.0 {
        return Err(AssessError::NoSeismicWork);
    }
    let m_star = spdx * spdx / (G * spdx2);
    Ok(ParticipatingMass {
        seismic_weight: sp,
        sum_p_dx: spdx,
        sum_p_dx2: spdx2,
        m_star,
        e_star: G * m_star / sp,
    })
}

/// The capacity of the least mechanism of any assembly by the incremental analysis
/// ([`incremental`]): the participating mass from its block velocities at rest, `alpha0` its
/// multiplier (the general kinematic program's, equal to the static one with associative
/// friction), the curve re-solved along the path.
fn incremental_capacity(
    model: &Model,
    direction: Direction,
    settings: &CapacitySettings,
) -> Result<Capacity, AssessError> {
    let path = incremental::follow(model, direction, settings.control_block)?;
    let sign = direction.sign();
    let control_block = path.control_block;
    let blocks = &model.assembly.blocks;
    let dx_k0 = sign * velocity(path.rest[control_block], blocks[control_block].centroid).x;
    let loads = moving_loads(model, |b| path.moving.get(b).copied().unwrap_or(false));
    let mass = participating_mass(&loads, |b, p| sign * velocity(path.rest[b], p).x / dx_k0)?;
    let (alpha0, d_k0, rotation0) = match (path.steps.first(), path.steps.last()) {
        (Some(a), Some(z)) => (a.alpha, z.d_k, z.rotation),
        _ => {
            return Err(AssessError::Incremental(
                "the path has no configuration".into(),
            ))
        }
    };
    if !(alpha0.is_finite() && alpha0 > 0.0) {
        return Err(AssessError::NoZero(format!(
            "needs alpha = {alpha0} at rest, not a positive multiplier,"
        )));
    }
    let curve_of = |cap: &Capacity| {
        let n = settings.points;
        (0..n)
            .filter_map(|i| path.at_d_k(d_k0 * i as f64 / (n - 1) as f64))
            .map(|s| CapacityPoint {
                rotation: s.rotation,
                d_k: s.d_k,
                alpha: s.alpha,
                d_star: cap.d_star(s.d_k),
                a_star: cap.a_star(s.alpha),
            })
            .collect()
    };
    let mut cap = Capacity {
        motion: Motion::Incremental(path.clone()),
        direction,
        control_block,
        dx_k: 1.0,
        mass,
        fc: settings.fc,
        alpha0,
        a0_star: 0.0,
        rotation0,
        d_k0,
        d0_star: 0.0,
        curve: Vec::new(),
        loads,
        ties: Vec::new(),
    };
    cap.a0_star = cap.a_star(alpha0);
    cap.d0_star = cap.d_star(d_k0);
    cap.curve = curve_of(&cap);
    Ok(cap)
}

/// Share of `d0*` that is the ultimate displacement `du*` (C8.7.1.2.2).
pub const DU_SHARE: f64 = 0.4;
/// Share of `du*` that is the displacement `ds*` defining the secant period `Ts`.
pub const DS_SHARE: f64 = 0.4;
/// Modal participation factor of a mechanism at height: the limit of `3N/(2N+1)` for many
/// storeys (Circolare 2009 C8A.4.9), used as its upper bound since the scene gives no storey
/// count.
pub const GAMMA: f64 = 1.5;
/// Largest `ag` (in g) the search for the largest passing `ag` goes to.
pub const AG_SEARCH_MAX: f64 = 2.0;
/// Steps of the grid of the search for the largest passing `ag` (0.005 g each; its least
/// point is `AG_SEARCH_MAX / AG_GRID_STEPS`).
pub const AG_GRID_STEPS: usize = 400;
/// The least point of that grid (0.005 g): a capacity known only to lie below it is
/// reported as below this `ag`.
pub const AG_GRID_FIRST: f64 = AG_SEARCH_MAX / AG_GRID_STEPS as f64;

/// One check: demand, capacity and the largest `ag` that passes.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct Check {
    /// The capacity (`a0*` in m/s^2, or `du*` in m).
    pub capacity: f64,
    /// The demand at the site's `ag` (same units), the larger of the ground-level and, for a
    /// mechanism at height, the amplified one.
    pub demand: f64,
    /// `capacity / demand`; the check passes when it is at least 1.
    pub ratio: f64,
    pub passes: bool,
    /// Largest `ag` (in g) that passes, by bisection (0 when none does); None when even
    /// `ag` = 2 g passes.
    pub ag_max: Option<f64>,
}

/// The verdict at a site.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct Verdict {
    pub spectrum: Spectrum,
    /// `du* = 0.4 d0*` (m).
    pub du_star: f64,
    /// `ds* = 0.4 du*` (m).
    pub ds_star: f64,
    /// `as* = a*(ds*)` (m/s^2).
    pub as_star: f64,
    /// `Ts = 2 pi sqrt(ds*/as*)` (s).
    pub ts: f64,
    /// Linear kinematic check: `a0* >= ag S / q` (and `Se(T1) psi(Z) gamma / q` at height).
    pub linear: Check,
    /// Nonlinear kinematic check: `du* >= SDe(Ts)` (and its amplified form at height).
    pub nonlinear: Check,
}

/// Which of the two checks a verdict satisfies.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Satisfied {
    Both,
    Linear,
    Nonlinear,
    Neither,
}

/// The rule that turns the two checks into a verdict, as the reports state it.
pub const RULE: &str = "Circolare 2019 C8.7.1: a local mechanism is verified by the linear or by the nonlinear kinematic analysis; either check satisfied suffices";

impl Verdict {
    /// The code's verdict (Circolare 2019 C8.7.1): the mechanism passes when the linear or
    /// the nonlinear kinematic check is satisfied; the engineer may verify it with either.
    pub fn passes(&self) -> bool {
        self.linear.passes || self.nonlinear.passes
    }

    /// Whether both checks are satisfied (the stricter reading, reported beside the verdict).
    pub fn both_pass(&self) -> bool {
        self.linear.passes && self.nonlinear.passes
    }

    /// Which checks are satisfied.
    pub fn satisfied(&self) -> Satisfied {
        match (self.linear.passes, self.nonlinear.passes) {
            (true, true) => Satisfied::Both,
            (true, false) => Satisfied::Linear,
            (false, true) => Satisfied::Nonlinear,
            (false, false) => Satisfied::Neither,
        }
    }

    /// The largest `ag` (in g) at which the mechanism passes by [`Verdict::passes`]: the larger
    /// of the two checks' `ag_max` (None when one of them passes even at [`AG_SEARCH_MAX`]).
    pub fn ag_max(&self) -> Option<f64> {
        match (self.linear.ag_max, self.nonlinear.ag_max) {
            (Some(a), Some(b)) => Some(a.max(b)),
            _ => None,
        }
    }

    /// The verdict in words: "passes: linear check satisfied", "does not pass: neither the
    /// linear nor the nonlinear check is satisfied", ...
    pub fn text(&self) -> &'static str {
        match self.satisfied() {
            Satisfied::Both => "passes: linear and nonlinear checks satisfied",
            Satisfied::Linear => "passes: linear check satisfied (the nonlinear one is not)",
            Satisfied::Nonlinear => "passes: nonlinear check satisfied (the linear one is not)",
            Satisfied::Neither => {
                "does not pass: neither the linear nor the nonlinear check is satisfied"
            }
        }
    }
}

/// `psi(Z) gamma` of a mechanism at height, 0 at ground level.
fn height_factor(site: &Site) -> f64 {
    match site.h {
        Some(h) if site.elevated() => site.z / h * GAMMA,
        _ => 0.0,
    }
}

/// Demand of the linear check (m/s^2): `ag S / q`, and at height `Se(T1) psi gamma / q`.
pub fn linear_demand(site: &Site) -> f64 {
    let sp = site.spectrum();
    let ground = sp.ag * sp.s / site.q;
    match site.t1 {
        Some(t1) if site.elevated() => ground.max(sp.se(t1) * height_factor(site) / site.q),
        _ => ground,
    }
}

/// Demand of the nonlinear check (m): `SDe(Ts)`, and at height
/// `SDe(T1) psi gamma (Ts/T1)^2 / sqrt((1 - Ts/T1)^2 + 0.02 Ts/T1)`.
pub fn nonlinear_demand(site: &Site, ts: f64) -> f64 {
    let sp = site.spectrum();
    let ground = sp.sde(ts);
    match site.t1 {
        Some(t1) if site.elevated() => {
            let r = ts / t1;
            let amplified =
                sp.sde(t1) * height_factor(site) * r * r / ((1.0 - r).powi(2) + 0.02 * r).sqrt();
            ground.max(amplified)
        }
        _ => ground,
    }
}

/// The largest `ag` (in g, up to [`AG_SEARCH_MAX`]) at which `passes` holds: the largest
/// passing point of a grid of steps of 0.005 g, then bisection between it and the next
/// (failing) grid point down to round-off. The demand of soils B-E is not monotone in `ag`
/// everywhere (`SS` falls as `ag` grows), hence the grid before the bisection. When no grid
/// point passes, the bisection runs between 0 and the first one (the demand vanishes with
/// `ag`), so a weak structure gets its own small `ag`, and 0 when it fails at any `ag`. None
/// only when the check passes at [`AG_SEARCH_MAX`].
pub fn largest_passing_ag(site: &Site, passes: impl Fn(&Site) -> bool) -> Option<f64> {
    const STEPS: usize = AG_GRID_STEPS;
    if passes(&site.with_ag(AG_SEARCH_MAX)) {
        return None;
    }
    let grid = |i: usize| AG_SEARCH_MAX * i as f64 / STEPS as f64;
    // Before this fix a check failing at every grid point also returned None, which the
    // reports read as "passes at more than 2 g" (issue 30's fragility work found it).
    let i = (1..STEPS)
        .rev()
        .find(|&i| passes(&site.with_ag(grid(i))))
        .unwrap_or(0);
    let (mut lo, mut hi) = (grid(i), grid(i + 1));
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            break;
        }
        if passes(&site.with_ag(mid)) {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    Some(lo)
}

/// The verdict of a capacity at a site (the capacity's `FC` must be the site's).
pub fn verdict(model: &Model, capacity: &Capacity, site: &Site) -> Verdict {
    let du_star = DU_SHARE * capacity.d0_star;
    let ds_star = DS_SHARE * du_star;
    let as_star = capacity
        .at_d_star(model, ds_star)
        .map_or(f64::NAN, |(_, a)| a);
    let ts = 2.0 * std::f64::consts::PI * (ds_star / as_star).sqrt();
    let a0 = capacity.a0_star;
    let check = |cap: f64, demand: &dyn Fn(&Site) -> f64| {
        let d = demand(site);
        Check {
            capacity: cap,
            demand: d,
            ratio: cap / d,
            passes: cap >= d,
            ag_max: largest_passing_ag(site, |s| cap >= demand(s)),
        }
    };
    Verdict {
        spectrum: site.spectrum(),
        du_star,
        ds_star,
        as_star,
        ts,
        linear: check(a0, &linear_demand),
        nonlinear: check(du_star, &|s: &Site| nonlinear_demand(s, ts)),
    }
}

/// Relative difference of the largest passing `ag` below which two directions tie (a
/// symmetric structure's two directions differ by round-off only).
pub const AG_TIE: f64 = 1e-9;

/// Index of the governing direction among `verdicts`: a direction that fails governs over
/// one that passes; among equals, the one with the smaller largest passing `ag` (None, passing
/// beyond [`AG_SEARCH_MAX`], counts as infinite); on a tie (within [`AG_TIE`]), the first.
pub fn governing_index(verdicts: &[&Verdict]) -> usize {
    let key = |v: &Verdict| (v.passes(), v.ag_max().unwrap_or(f64::INFINITY));
    let mut best = 0;
    for (i, v) in verdicts.iter().enumerate().skip(1) {
        let (p, ag) = key(v);
        let (bp, bag) = key(verdicts[best]);
        if (!p && bp) || (p == bp && ag < bag * (1.0 - AG_TIE)) {
            best = i;
        }
    }
    best
}
