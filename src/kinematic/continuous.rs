//! Continuous kinematic model: the arch ring treated as a continuum in which a hinge can form
//! at any radial section, not only at the joints between voussoirs — the limit of infinitely
//! many voussoirs, and the "analytical model" of the seed paper (after Oppenheim, 1992;
//! Ochsendorf, 2002; De Luca, Giordano & Mele, 2004).
//!
//! # The structure
//! - Arch: annular pieces (centre c, centreline radius r, thickness t) between radial
//!   sections. The weight and first moments of the piece between polar angles `theta_a` and
//!   `theta_b` (`d = |theta_a - theta_b|`, `m` the mid angle) are, exactly and with no
//!   differences of large prefix sums,
//!   `W = gamma r t d`, `W x = c_x W + gamma K 2 sin(d/2) cos m`, `W y = c_y W + gamma K 2 sin(d/2)
//!   sin m`, `K = (r_e^3 - r_i^3)/3 = t (r^2 + t^2/12)`.
//!   Circular arches are one annulus; basket arches three (sections at the transitions belong
//!   to both arcs); a pointed arch is two annuli, left and right, meeting at the vertical crown
//!   joint of `geometry.md`. Radial sections of the left arc of a pointed arch exist only
//!   where they lie entirely left of the crown line (polar angle about the left centre
//!   `>= acos(-e / r_i)`); the small "keystone" between that last radial section and the
//!   crown joint (extrados sector minus a triangle) is rigid and moves with the left annulus
//!   (mirror on the right). A discrete pointed arch with very many voussoirs has radial joints
//!   inside this keystone that cross the crown joint; such voussoirs are not proper blocks.
//!   The last radial sections on both sides and the crown joint all have the intrados apex
//!   as their p1: three hinges there leave the closure matrix of rank 2 (every minor is
//!   round-off), which `kinematic::solve_motion` rejects; before it did, such a noise
//!   "mechanism" made sound pointed arches "cannot stand".
//! - Loads ([`crate::model::LoadCase`]): loads spread along the extrados (line loads, fill)
//!   are integrated exactly between any two sections (a strip `dx` of the extrados at `(x, y)`
//!   carries `q dx` at `(x, y)`, or the fill column `g (level - y) dx` at its middle), by
//!   Gauss-Legendre quadrature in the polar angle on the pieces where the integrand is smooth;
//!   a point load on the ring acts on the side of a section its polar angle lies on (in a
//!   pointed arch's keystone when it lies there); seismic masses follow their loads. This is
//!   the limit of the discrete arch with curved voussoirs, whose blocks carry the same loads
//!   by the same definitions (`tests/it/loads.rs` checks the convergence).
//! - Piers are kept as given: a coursed pier has horizontal bed joints, and a crack across a
//!   course would be a tensile fracture of a stone, which the no-tension model excludes; so a
//!   pier can only hinge or open at its bed joints (base, course joints), and the
//!   arch-pier interface is the springing joint of `geometry.md` (the part of the arch's
//!   springing section that rests on the pier). Only with infinitely many courses could a pier
//!   hinge at any height; that would be a different structure, not a limit of this one.
//!
//! # The search
//! The families are those of the discrete search ([`crate::kinematic`]). A global search runs
//! the exhaustive discrete search on a coarse set of sections (about 24 along the arch, plus
//! every pier joint) with the exact continuum weights between them, and keeps the best
//! mechanism of every *signature* (which piece each active section lies in, and what it does).
//! The signatures whose coarse multiplier is near the best are refined: every arch section is
//! moved by golden-section minimisation along its piece (bounded by its neighbours), one
//! coordinate at a time, until the multiplier stops decreasing. Pier joints stay where they
//! are.
//!
//! Both stages use the rayon pool. The coarse families run on separate tasks, each keeping
//! the best of every signature below a cut (the best so far plus twice the refinement
//! margin), the lowest cut shared between tasks; since the cut never falls below the final
//! best plus the margin, every signature within the margin is kept with its exact coarse
//! minimum, whatever the order of the tasks. The chosen signatures are refined independently
//! and compared in the order of their coarse multipliers. The result is that of a sequential
//! run, bit for bit.
//!
//! # Angles
//! A section's `polar_deg` is the polar angle of its direction p1 -> p2 (intrados to extrados),
//! in degrees: for a radial section, the centreline angle about its arc's centre (180 at the
//! left springing of a semicircle, 90 at its crown, 0 at the right springing; 90 for the
//! vertical crown joint of a pointed arch). `from_vertical_deg = |polar_deg - 90|` is the angle
//! from the crown direction, e.g. the haunch hinge of the semicircle at minimum thickness at
//! 54.5 deg.

use super::discrete::{visit_all_par, Chain, Key, Sink};
use super::{
    motion_work, solve_motion, Act, Active, Direction, Extremes, Family, KinematicError, Status,
    Sums,
};
use crate::assembly::{BlockKind, JointEnd, JointKind};
use crate::geometry::{polar, ArchShape, Lump, RingPiece, Vec2};
use crate::model::{Model, Spread, SpreadLoad};
use rayon::prelude::*;
use std::collections::HashMap;
use std::f64::consts::PI;
use std::hash::BuildHasherDefault;
use std::sync::atomic::{AtomicU64, Ordering};
use std::time::Instant;

/// Sections of the coarse global search along the arch.
const COARSE_SECTIONS: usize = 24;

/// Where a hinge (or an open section) of the continuous model is.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum HingeLocation {
    /// A section of the arch ring (springing sections included). Angles in degrees, see the
    /// module docs.
    Arch {
        polar_deg: f64,
        from_vertical_deg: f64,
    },
    /// A bed joint of a pier: `joint` counts from the pier base (0 = the base on the ground).
    Pier { left: bool, joint: usize },
}

/// A hinge or open section of the continuous mechanism.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct ContinuousHinge {
    pub location: HingeLocation,
    /// The end the hinge sits at (None: the section opens completely).
    pub end: Option<JointEnd>,
    /// Hinge point (for an open section, its p1).
    pub x: f64,
    pub y: f64,
}

/// Result of the continuous model.
#[derive(Debug, Clone)]
pub struct ContinuousResult {
    pub status: Status,
    /// The continuous collapse multiplier (status `Collapse` only).
    pub lambda_continuous: Option<f64>,
    /// The least `G/A` over mechanisms driven by the load, whatever its sign (negative below
    /// the minimum thickness).
    pub lambda_signed: Option<f64>,
    pub family: Option<Family>,
    /// Hinges of the governing mechanism in chain order (idle ones left out).
    pub hinges: Vec<ContinuousHinge>,
    /// Sections that open completely.
    pub open: Vec<ContinuousHinge>,
    pub direction: Direction,
    /// Sections of the coarse search and signatures refined.
    pub coarse_sections: usize,
    pub refined: usize,
    /// Mechanism evaluations of the refinement.
    pub evaluations: u64,
    pub wall_time_s: f64,
}

impl ContinuousResult {
    /// The angles from the crown (deg) of the hinges on the intrados (end p1) in the arch
    /// ring: the haunch hinges of a semicircle at its minimum thickness.
    pub fn intrados_hinges_deg(&self) -> Vec<f64> {
        self.hinges
            .iter()
            .filter_map(|h| match h.location {
                HingeLocation::Arch {
                    from_vertical_deg, ..
                } if h.end == Some(JointEnd::P1) => Some(from_vertical_deg),
                _ => None,
            })
            .collect()
    }
}

/// The continuous model's minimum thickness: where `lambda_continuous` reaches 0.
#[derive(Debug, Clone)]
pub struct MinThickness {
    /// Arch thickness t (m).
    pub thickness: f64,
    /// The continuous analysis at that thickness (its hinges are the mechanism of the
    /// minimum-thickness arch).
    pub result: ContinuousResult,
    /// Continuous analyses run by the root finder.
    pub iterations: usize,
}

#[derive(Debug, Clone, Copy)]
struct Annulus {
    centre: Vec2,
    ri: f64,
    re: f64,
    /// Polar angle at u = 0; the angle is `theta0 + dir u`, u in [0, len].
    theta0: f64,
    dir: f64,
    len: f64,
    /// Rigid material attached before u = 0 and after u = len (pointed keystones).
    head: Sums,
    tail: Sums,
    gamma: f64,
    /// Seismic force per unit lambda and unit weight (`(d, r)`).
    seismic: Vec2,
}

impl Annulus {
    fn section(&self, u: f64) -> (Vec2, Vec2) {
        let d = polar(self.theta0 + self.dir * u);
        (self.centre + self.ri * d, self.centre + self.re * d)
    }

    /// Weight and first moments of the annular piece between u0 <= u1 (closed form).
    fn sums(&self, u0: f64, u1: f64) -> Sums {
        let du = u1 - u0;
        if du <= 0.0 {
            return Sums::default();
        }
        let r = 0.5 * (self.ri + self.re);
        let t = self.re - self.ri;
        let mid = self.theta0 + self.dir * 0.5 * (u0 + u1);
        let w = self.gamma * r * t * du;
        let k = self.gamma * t * (r * r + t * t / 12.0) * 2.0 * (0.5 * du).sin();
        Sums::of_mass(
            w,
            self.centre.x * w + k * mid.cos(),
            self.centre.y * w + k * mid.sin(),
            self.seismic,
        )
    }
}

#[derive(Debug, Clone, Copy)]
enum Item {
    Joint { p1: Vec2, p2: Vec2, kind: JointKind },
    Block(Sums),
    Annulus(Annulus),
}

/// Resultant of a point load: permanent force `force` at `point`, and a seismic mass of weight
/// `seismic_weight` there.
fn point_sums(point: Vec2, force: Vec2, seismic_weight: f64, seismic: Vec2) -> Sums {
    let mass = Sums::of_mass(
        seismic_weight,
        seismic_weight * point.x,
        seismic_weight * point.y,
        seismic,
    );
    Sums {
        p: [force.x, force.y, point.x * force.y - point.y * force.x],
        s: mass.s,
    }
}

/// Resultant of the loads spread along the extrados arc (centre `c`, radius `r`) between polar
/// angles `a` and `b`: for a strip `dx` of the arc at `(x, y)`, a line load `q` puts `q dx` at
/// `(x, y)`; a fill of density `g` up to `level` puts `g (level - y) dx` at
/// `(x, (level + y) / 2)`. Each load is a weight (down) and, when seismic, a seismic mass of
/// the same weight. The arc is cut where x turns back (`sin = 0`) and where a line load starts
/// or ends, and each piece is integrated by Gauss-Legendre quadrature in the angle, exact to
/// round-off for these smooth integrands.
///
/// Under a live action (`live`), a live load's weight is the action (lambda multiplies it)
/// instead of a permanent force.
fn spread_sums(
    c: Vec2,
    r: f64,
    a: f64,
    b: f64,
    loads: &[SpreadLoad],
    seismic: Vec2,
    live: bool,
) -> Sums {
    let (lo, hi) = if a <= b { (a, b) } else { (b, a) };
    if hi <= lo {
        return Sums::default();
    }
    let mut total = Sums::default();
    for load in loads {
        let mut cuts = vec![lo, hi];
        // Angles in (lo, hi) where x turns back: multiples of pi.
        let mut m = (lo / PI).ceil();
        while m * PI < hi {
            cuts.push(m * PI);
            m += 1.0;
        }
        if let Spread::Line { from_x, to_x, .. } = load.kind {
            for x in [from_x, to_x] {
                let cosv = (x - c.x) / r;
                if cosv.abs() < 1.0 {
                    let base = cosv.acos();
                    for root in [base, -base] {
                        // Every angle congruent to the root that falls in (lo, hi).
                        let mut phi = root + 2.0 * PI * ((lo - root) / (2.0 * PI)).ceil();
                        while phi < hi {
                            if phi > lo {
                                cuts.push(phi);
                            }
                            phi += 2.0 * PI;
                        }
                    }
                }
            }
        }
        cuts.sort_by(f64::total_cmp);
        let (mut w, mut wx, mut wy) = (0.0, 0.0, 0.0);
        for pair in cuts.windows(2) {
            let (p0, p1) = (pair[0], pair[1]);
            if p1 <= p0 {
                continue;
            }
            // Only an extrados that faces up carries spread loads: with the ring running left
            // to right (decreasing angle), x increases where sin > 0.
            if (0.5 * (p0 + p1)).sin() <= 0.0 {
                continue;
            }
            let mid = c.x + r * (0.5 * (p0 + p1)).cos();
            if let Spread::Line { from_x, to_x, .. } = load.kind {
                if mid < from_x || mid > to_x {
                    continue;
                }
            }
            let half = 0.5 * (p1 - p0);
            for (node, weight) in gauss_legendre() {
                let phi = p0 + half * (1.0 + node);
                let (sin, cos) = phi.sin_cos();
                let (x, y) = (c.x + r * cos, c.y + r * sin);
                // |dx / dphi| = r |sin phi|.
                let dx = weight * half * r * sin.abs();
                let (dw, ycen) = match load.kind {
                    Spread::Line { intensity, .. } => (intensity * dx, y),
                    Spread::Fill { level, density } => {
                        (density * (level - y) * dx, 0.5 * (level + y))
                    }
                };
                w += dw;
                wx += dw * x;
                wy += dw * ycen;
            }
        }
        let mass = Sums::of_mass(w, wx, wy, seismic);
        total = total
            + if live && load.live {
                mass.as_action()
            } else if load.seismic {
                mass
            } else {
                Sums {
                    p: mass.p,
                    s: [0.0; 3],
                }
            };
    }
    total
}

/// Nodes and weights of the 16-point Gauss-Legendre rule on [-1, 1] (Newton's method on the
/// Legendre polynomial, computed once).
fn gauss_legendre() -> &'static [(f64, f64)] {
    static RULE: std::sync::OnceLock<Vec<(f64, f64)>> = std::sync::OnceLock::new();
    RULE.get_or_init(|| {
        const N: usize = 16;
        let mut rule = Vec::with_capacity(N);
        for i in 0..N {
            let mut x = (PI * (i as f64 + 0.75) / (N as f64 + 0.5)).cos();
            let mut dp = 1.0;
            for _ in 0..100 {
                // P_N(x) and its derivative by the three-term recurrence.
                let (mut p0, mut p1) = (1.0, x);
                for k in 2..=N {
                    let p2 = ((2 * k - 1) as f64 * x * p1 - (k - 1) as f64 * p0) / k as f64;
                    p0 = p1;
                    p1 = p2;
                }
                dp = N as f64 * (x * p1 - p0) / (x * x - 1.0);
                let dx = p1 / dp;
                x -= dx;
                if dx.abs() < 1e-16 {
                    break;
                }
            }
            rule.push((x, 2.0 / ((1.0 - x * x) * dp * dp)));
        }
        rule
    })
}

/// A position along the chain: an item and, in an annulus, the parameter u.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Pos {
    item: usize,
    u: f64,
}

struct Structure {
    items: Vec<Item>,
    /// Sums of each whole item (with heads and tails).
    full: Vec<Sums>,
    size: f64,
    /// Loads spread along the extrados (line loads, fill), integrated between any sections.
    spread: Vec<SpreadLoad>,
    /// Point loads on the ring, per item: `(u, resultant)`, in no order.
    points: Vec<Vec<(f64, Sums)>>,
    /// Seismic force per unit lambda and unit weight (`(d, r)`; zero under a live action).
    seismic: Vec2,
    /// Whether lambda multiplies the live loads (a live action).
    live: bool,
}

impl Structure {
    fn new(
        model: &Model,
        shape: &dyn ArchShape,
        t: f64,
        direction: Direction,
    ) -> Result<Structure, KinematicError> {
        let asm = &model.assembly;
        model.validate()?;
        let count = |f: fn(&BlockKind) -> bool| asm.blocks.iter().filter(|b| f(&b.kind)).count();
        let k = count(|b| matches!(b, BlockKind::LeftPier(_)));
        let kr = count(|b| matches!(b, BlockKind::RightPier(_)));
        let n = count(|b| matches!(b, BlockKind::Voussoir(_)));
        if n == 0 || n + k + kr != asm.blocks.len() || !asm.is_chain() {
            return Err(KinematicError::Continuous(
                "the continuous model needs an arch (with or without two piers) built from a parametric shape".into(),
            ));
        }
        // Every voussoir has the ring's unit weight times depth.
        let first = &asm.blocks[k];
        let gamma = first.weight / first.area;
        let sign = direction.sign();
        // The force per unit lambda and unit seismic weight: zero under a live action (no
        // mass is shaken; the live loads are the action instead).
        let seismic = model.loads.variable_direction(sign);
        let live = model.loads.action() == crate::model::Action::Live;
        // The ring is a continuum: its own weight and the loads spread along its extrados are
        // integrated exactly between any two sections, and a point load belongs to the side of
        // a section its polar angle lies on. The piers keep the loads of their blocks.
        let spread: Vec<SpreadLoad> = model.loads.spread().to_vec();
        let ring_point = |l: &&crate::model::AppliedLoad| {
            matches!(
                l.source,
                crate::model::LoadSource::Load(_) | crate::model::LoadSource::Vehicle(..)
            ) && !spread.iter().any(|s| s.source == l.source)
                && matches!(asm.blocks[l.block].kind, BlockKind::Voussoir(_))
        };
        let ring_points: Vec<&crate::model::AppliedLoad> =
            model.loads.applied().iter().filter(ring_point).collect();
        let sums_of = |i: usize| Sums::of_block(&model.loads, i, sign);
        let lump = |centre: Vec2, re: f64, l: Lump| {
            let mut s = Sums::of_mass(
                gamma * l.area,
                gamma * l.moment.x,
                gamma * l.moment.y,
                seismic,
            );
            if let Some((a, b)) = l.extrados {
                s = s + spread_sums(centre, re, a, b, &spread, seismic, live);
            }
            s
        };
        let joint = |j: usize| {
            let jt = &asm.joints[j];
            Item::Joint {
                p1: jt.p1,
                p2: jt.p2,
                kind: jt.kind,
            }
        };
        let mut items = Vec::new();
        for c in 0..k {
            items.push(joint(c));
            items.push(Item::Block(sums_of(c)));
        }
        items.push(joint(k));
        for piece in shape.ring(t, n).map_err(KinematicError::Continuous)? {
            items.push(match piece {
                RingPiece::Annulus {
                    centre,
                    radius,
                    theta0,
                    sweep,
                    head,
                    tail,
                } => Item::Annulus(Annulus {
                    centre,
                    ri: radius - 0.5 * t,
                    re: radius + 0.5 * t,
                    theta0,
                    dir: -1.0,
                    len: sweep,
                    head: lump(centre, radius + 0.5 * t, head),
                    tail: lump(centre, radius + 0.5 * t, tail),
                    gamma,
                    seismic,
                }),
                RingPiece::Joint { p1, p2, joint } => Item::Joint {
                    p1,
                    p2,
                    kind: JointKind::Arch(joint),
                },
            });
        }
        items.push(joint(k + n));
        for c in 0..kr {
            items.push(Item::Block(sums_of(k + n + c)));
            items.push(joint(k + n + 1 + c));
        }
        // Each point load on the ring goes to the annulus its voussoir lies on, at its polar
        // angle; past either end of the annulus it is in a keystone lump.
        let arcs = shape.geometry(t, n).arcs;
        let tol = 1e-9 * asm.size();
        let mut points: Vec<Vec<(f64, Sums)>> = vec![Vec::new(); items.len()];
        for l in &ring_points {
            let arc = arcs[l.block - k];
            let found = items.iter_mut().enumerate().find_map(|(i, it)| match it {
                Item::Annulus(a)
                    if (a.centre - arc.centre).norm() <= tol
                        && (0.5 * (a.ri + a.re) - arc.radius).abs() <= tol =>
                {
                    Some((i, a))
                }
                _ => None,
            });
            let Some((i, a)) = found else {
                return Err(KinematicError::Continuous(format!(
                    "{} on voussoir {} lies on no arc of the ring",
                    l.source,
                    l.block - k
                )));
            };
            let d = l.point - a.centre;
            let u = (a.theta0 - d.y.atan2(d.x)).rem_euclid(2.0 * PI);
            let sums = if live && l.live {
                point_sums(l.point, l.force, 0.0, seismic).as_action()
            } else {
                point_sums(l.point, l.force, l.seismic_weight, seismic)
            };
            if u <= a.len {
                points[i].push((u, sums));
            } else if u <= a.len + 0.5 * (2.0 * PI - a.len) {
                a.tail = a.tail + sums;
            } else {
                a.head = a.head + sums;
            }
        }
        let mut st = Structure {
            items,
            full: Vec::new(),
            size: asm.size(),
            spread,
            points,
            seismic,
            live,
        };
        st.full = (0..st.items.len())
            .map(|i| match &st.items[i] {
                Item::Joint { .. } => Sums::default(),
                Item::Block(s) => *s,
                Item::Annulus(a) => a.head + st.ring_sums(i, 0.0, a.len) + a.tail,
            })
            .collect();
        Ok(st)
    }

    /// Material and loads of annulus `item` between `u0 <= u1`: its own weight, the loads
    /// spread along its extrados there, and the point loads whose polar angle lies there (the
    /// end of the annulus included when `u1` reaches it).
    fn ring_sums(&self, item: usize, u0: f64, u1: f64) -> Sums {
        let Item::Annulus(a) = &self.items[item] else {
            return Sums::default();
        };
        if u1 <= u0 {
            return Sums::default();
        }
        let mut s = a.sums(u0, u1);
        if !self.spread.is_empty() {
            s = s + spread_sums(
                a.centre,
                a.re,
                a.theta0 + a.dir * u0,
                a.theta0 + a.dir * u1,
                &self.spread,
                self.seismic,
                self.live,
            );
        }
        for &(u, p) in &self.points[item] {
            if u >= u0 && (u < u1 || (u1 >= a.len && u <= u1)) {
                s = s + p;
            }
        }
        s
    }

    fn section(&self, p: Pos) -> (Vec2, Vec2) {
        match &self.items[p.item] {
            Item::Joint { p1, p2, .. } => (*p1, *p2),
            Item::Annulus(a) => a.section(p.u),
            Item::Block(_) => (Vec2::zeros(), Vec2::zeros()),
        }
    }

    /// Material between positions p < q.
    fn between(&self, p: Pos, q: Pos) -> Sums {
        if p.item == q.item {
            return self.ring_sums(p.item, p.u, q.u);
        }
        let mut s = match &self.items[p.item] {
            Item::Annulus(a) => self.ring_sums(p.item, p.u, a.len) + a.tail,
            _ => Sums::default(),
        };
        for f in &self.full[p.item + 1..q.item] {
            s = s + *f;
        }
        if let Item::Annulus(a) = &self.items[q.item] {
            s = s + a.head + self.ring_sums(q.item, 0.0, q.u);
        }
        s
    }

    /// Coarse sections: every joint, and points along each annulus (without duplicating a
    /// neighbouring joint or the end of the previous annulus).
    fn coarse(&self) -> Vec<Pos> {
        let total: f64 = self
            .items
            .iter()
            .map(|it| match it {
                Item::Annulus(a) => a.len,
                _ => 0.0,
            })
            .sum();
        let tol = 1e-12 * self.size;
        let mut out = Vec::new();
        for (i, it) in self.items.iter().enumerate() {
            match it {
                Item::Joint { .. } => out.push(Pos { item: i, u: 0.0 }),
                Item::Block(_) => {}
                Item::Annulus(a) => {
                    let m = ((COARSE_SECTIONS as f64 * a.len / total).round() as usize).max(2);
                    let same = |p: (Vec2, Vec2), q: (Vec2, Vec2)| {
                        (p.0 - q.0).norm() <= tol && (p.1 - q.1).norm() <= tol
                    };
                    let skip_first = match self.items.get(i.wrapping_sub(1)) {
                        Some(Item::Annulus(_)) => true,
                        Some(Item::Joint { p1, p2, .. }) => same((*p1, *p2), a.section(0.0)),
                        _ => false,
                    };
                    let skip_last = match self.items.get(i + 1) {
                        Some(Item::Joint { p1, p2, .. }) => same((*p1, *p2), a.section(a.len)),
                        _ => false,
                    };
                    for s in 0..=m {
                        if (s == 0 && skip_first) || (s == m && skip_last) {
                            continue;
                        }
                        out.push(Pos {
                            item: i,
                            u: a.len * s as f64 / m as f64,
                        });
                    }
                }
            }
        }
        out
    }

    /// The active sections at the positions `pos` (at most four) doing `acts`, in the first
    /// `pos.len()` places.
    fn actives(&self, pos: &[Pos], acts: &[Act]) -> [Active; 4] {
        let mut actives = [Active {
            p1: Vec2::zeros(),
            p2: Vec2::zeros(),
            act: Act::Open,
        }; 4];
        for (k, (p, a)) in pos.iter().zip(acts).enumerate() {
            let (p1, p2) = self.section(*p);
            actives[k] = Active { p1, p2, act: *a };
        }
        actives
    }

    /// `(A, G)` of the mechanism with active sections `pos` doing `acts`, if admissible.
    fn evaluate(&self, pos: &[Pos], acts: &[Act]) -> Option<(f64, f64)> {
        let actives = self.actives(pos, acts);
        let m = solve_motion(&actives[..pos.len()], true)?;
        let mut bodies = [Sums::default(); 3];
        for k in 0..pos.len() - 1 {
            bodies[k] = self.between(pos[k], pos[k + 1]);
        }
        Some(motion_work(&m, &bodies[..pos.len() - 1]))
    }
}

/// A signature: the item and action of each active section.
type Signature = [(usize, u8); 4];

/// Multiplicative hash for the few small integers of a signature (the std SipHash, built
/// against adversarial keys, was a tenth of the coarse search).
#[derive(Default)]
struct SignatureHasher(u64);

impl std::hash::Hasher for SignatureHasher {
    fn finish(&self) -> u64 {
        self.0
    }
    fn write(&mut self, bytes: &[u8]) {
        for &b in bytes {
            self.write_u64(u64::from(b));
        }
    }
    fn write_u8(&mut self, i: u8) {
        self.write_u64(u64::from(i));
    }
    fn write_usize(&mut self, i: usize) {
        self.write_u64(i as u64);
    }
    fn write_u64(&mut self, i: u64) {
        self.0 = (self.0.rotate_left(5) ^ i).wrapping_mul(0x517c_c1b7_2722_0a95);
    }
}

/// Best coarse mechanism of each signature.
struct Collector<'a> {
    ext: Extremes<Key>,
    best: HashMap<Signature, (f64, Key), BuildHasherDefault<SignatureHasher>>,
    coarse: &'a [Pos],
    /// Signatures are refined only within `REFINE_MARGIN` of the best; keep every candidate
    /// below this looser cut (the best can only decrease as the search goes on). Updated with
    /// the best.
    cut: f64,
    /// The lowest cut of all the collectors of a parallel search (bits of an f64): a
    /// collector skips what another one's best already puts out of reach.
    shared: &'a AtomicU64,
}

impl Collector<'_> {
    /// The cut of a best multiplier `b`.
    fn cut_of(b: f64) -> f64 {
        b + 2.0 * REFINE_MARGIN * b.abs().max(0.05)
    }

    /// Lower the own and the shared cut to that of the own best.
    fn update_cut(&mut self) {
        if let Some(b) = &self.ext.best {
            self.cut = Self::cut_of(b.0);
            let mut cur = self.shared.load(Ordering::Relaxed);
            while self.cut < f64::from_bits(cur) {
                match self.shared.compare_exchange_weak(
                    cur,
                    self.cut.to_bits(),
                    Ordering::Relaxed,
                    Ordering::Relaxed,
                ) {
                    Ok(_) => break,
                    Err(now) => cur = now,
                }
            }
        }
    }
}

impl Collector<'_> {
    /// The collector of the mechanisms of both (the best of each signature is the lower one,
    /// ties to the lower key, so the result does not depend on the order of the merges).
    fn merge(mut self, o: Self) -> Self {
        self.ext = self.ext.merge(o.ext);
        for (sig, (l, key)) in o.best {
            let e = self.best.entry(sig).or_insert((l, key));
            if l < e.0 || (l == e.0 && key < e.1) {
                *e = (l, key);
            }
        }
        self.update_cut();
        self
    }
}

/// Relative margin (of |best|, at least 0.05 absolute) within which signatures are refined.
const REFINE_MARGIN: f64 = 0.2;

impl Sink for Collector<'_> {
    fn wants(&self, ax: f64, g: f64) -> bool {
        if ax > 0.0 {
            let shared = f64::from_bits(self.shared.load(Ordering::Relaxed));
            g <= self.cut.min(shared) * ax
        } else {
            self.ext.wants(ax, g)
        }
    }
    fn take(&mut self, ax: f64, g: f64, key: Key) {
        self.ext.record(ax, g, || key);
        if ax > 0.0 {
            self.update_cut();
            let l = g / ax;
            let mut sig = [(usize::MAX, 0u8); 4];
            for (k, (j, a)) in key.items().enumerate() {
                sig[k] = (self.coarse[j].item, a);
            }
            let e = self.best.entry(sig).or_insert((l, key));
            if l < e.0 || (l == e.0 && key < e.1) {
                *e = (l, key);
            }
        }
    }
    fn count(&mut self, n: u64) {
        self.ext.admissible += n;
    }
}

fn act_of(a: u8) -> Act {
    match a {
        0 => Act::Hinge(JointEnd::P1),
        1 => Act::Hinge(JointEnd::P2),
        _ => Act::Open,
    }
}

/// Continuous model (hinges at any section of the arch; piers as given) of `model`, an arch of
/// shape `shape` and thickness `thickness` (with or without piers, as built by
/// [`crate::scene::build`]), for the seismic load in direction `direction`.
pub fn continuous(
    model: &Model,
    shape: &dyn ArchShape,
    thickness: f64,
    direction: Direction,
) -> Result<ContinuousResult, KinematicError> {
    let start = Instant::now();
    if !model.ties.is_empty() {
        return Err(KinematicError::Ties {
            count: model.ties.len(),
        });
    }
    if !model.strips.is_empty() {
        return Err(KinematicError::Strips {
            count: model.strips.len(),
        });
    }
    if !model.passive.is_empty() {
        return Err(KinematicError::Passive {
            count: model.passive.len(),
        });
    }
    if model.strength.is_finite() {
        return Err(KinematicError::FiniteStrength {
            compressive_strength: model.strength.compressive,
        });
    }
    let st = Structure::new(model, shape, thickness, direction)?;
    let coarse = st.coarse();
    let sections: Vec<(Vec2, Vec2)> = coarse.iter().map(|p| st.section(*p)).collect();
    let segments: Vec<Sums> = coarse.windows(2).map(|w| st.between(w[0], w[1])).collect();
    let chain = Chain::from_sections(&sections, &segments, st.size);
    let shared = AtomicU64::new(f64::INFINITY.to_bits());
    let make = || Collector {
        ext: Extremes::new(),
        best: HashMap::default(),
        coarse: &coarse,
        cut: f64::INFINITY,
        shared: &shared,
    };
    let col = visit_all_par(&chain, make, Collector::merge);

    // Refine the signatures whose coarse multiplier is near the best one.
    let mut cands: Vec<(f64, Key)> = col.best.values().copied().collect();
    cands.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
    let chosen: Vec<Key> = match cands.first() {
        Some(&(l0, _)) => {
            let margin = REFINE_MARGIN * l0.abs().max(0.05);
            cands
                .iter()
                .take(8)
                .take_while(|(l, _)| *l <= l0 + margin)
                .map(|(_, key)| *key)
                .collect()
        }
        None => Vec::new(),
    };
    let refined = chosen.len();
    // The signatures are refined independently (in parallel), then taken in the order of
    // their coarse multipliers: the first strictly lowest wins, as in a sequential loop.
    let runs: Vec<(f64, Vec<Pos>, Vec<Act>, u64)> = chosen
        .par_iter()
        .map(|key| {
            let pos: Vec<Pos> = key.items().map(|(j, _)| coarse[j]).collect();
            let acts: Vec<Act> = key.items().map(|(_, a)| act_of(a)).collect();
            let mut ev = 0u64;
            let (lr, pr) = refine(&st, pos, &acts, &mut ev);
            (lr, pr, acts, ev)
        })
        .collect();
    let evaluations: u64 = runs.iter().map(|r| r.3).sum();
    let mut best: Option<(f64, Vec<Pos>, Vec<Act>)> = None;
    for (lr, pr, acts, _) in runs {
        if best.as_ref().is_none_or(|b| lr < b.0) {
            best = Some((lr, pr, acts));
        }
    }
    let mut ext = col.ext.clone();
    if let Some((l, _, _)) = &best {
        if let Some(b) = ext.best.as_mut() {
            b.0 = b.0.min(*l);
        }
    }
    let (status, _) = ext.verdict();
    let lambda_signed = ext.best.as_ref().map(|b| b.0);
    let mut hinges = Vec::new();
    let mut open = Vec::new();
    let mut family = None;
    if let Some((_, pos, acts)) = &best {
        // Drop idle hinges (zero relative rotation), as the discrete search does.
        let actives = st.actives(pos, acts);
        let motion = solve_motion(&actives[..pos.len()], true);
        let n_open = acts.iter().filter(|a| **a == Act::Open).count();
        family = Some(match n_open {
            0 => Family::FourHinges,
            1 => Family::TwoHingesOneOpen,
            _ => Family::TwoOpen,
        });
        for (k, (p, a)) in pos.iter().zip(acts).enumerate() {
            let (p1, p2) = st.section(*p);
            let location = match &st.items[p.item] {
                Item::Joint {
                    kind: JointKind::LeftPier(c),
                    ..
                } => HingeLocation::Pier {
                    left: true,
                    joint: *c,
                },
                Item::Joint {
                    kind: JointKind::RightPier(c),
                    ..
                } => HingeLocation::Pier {
                    left: false,
                    joint: *c,
                },
                _ => {
                    let d = p2 - p1;
                    let polar_deg = d.y.atan2(d.x).to_degrees();
                    HingeLocation::Arch {
                        polar_deg,
                        from_vertical_deg: (polar_deg - 90.0).abs(),
                    }
                }
            };
            match a {
                Act::Open => open.push(ContinuousHinge {
                    location,
                    end: None,
                    x: p1.x,
                    y: p1.y,
                }),
                Act::Hinge(e) => {
                    if motion.is_some_and(|m| m.opening[k] <= super::ADMISSIBLE_TOL) {
                        continue;
                    }
                    let q = if *e == JointEnd::P1 { p1 } else { p2 };
                    hinges.push(ContinuousHinge {
                        location,
                        end: Some(*e),
                        x: q.x,
                        y: q.y,
                    });
                }
            }
        }
    }
    Ok(ContinuousResult {
        status,
        lambda_continuous: if status == Status::Collapse {
            lambda_signed
        } else {
            None
        },
        lambda_signed,
        family,
        hinges,
        open,
        direction,
        coarse_sections: coarse.len(),
        refined,
        evaluations,
        wall_time_s: start.elapsed().as_secs_f64(),
    })
}

/// Coordinate-wise golden-section refinement of the arch sections of one mechanism
/// signature. Returns the refined multiplier and positions.
fn refine(
    st: &Structure,
    mut pos: Vec<Pos>,
    acts: &[Act],
    evaluations: &mut u64,
) -> (f64, Vec<Pos>) {
    let f = |pos: &[Pos], ev: &mut u64| -> f64 {
        *ev += 1;
        match st.evaluate(pos, acts) {
            Some((ax, g)) if ax > 0.0 => g / ax,
            _ => f64::INFINITY,
        }
    };
    let n = pos.len();
    let vars: Vec<usize> = (0..n)
        .filter(|&k| matches!(st.items[pos[k].item], Item::Annulus(_)))
        .collect();
    let mut best = f(&pos, evaluations);
    // Initial bracket half-width: a coarse step along the piece.
    let mut width: Vec<f64> = vars
        .iter()
        .map(|&k| match &st.items[pos[k].item] {
            Item::Annulus(a) => a.len / 4.0,
            _ => 0.0,
        })
        .collect();
    for _sweep in 0..60 {
        let before = best;
        let mut moved = 0.0_f64;
        for (vi, &k) in vars.iter().enumerate() {
            let Item::Annulus(a) = &st.items[pos[k].item] else {
                continue;
            };
            let mut lo = 0.0_f64;
            let mut hi = a.len;
            if k > 0 && pos[k - 1].item == pos[k].item {
                lo = pos[k - 1].u;
            }
            if k + 1 < pos.len() && pos[k + 1].item == pos[k].item {
                hi = pos[k + 1].u;
            }
            let u0 = pos[k].u;
            let (mut x0, mut x3) = ((u0 - width[vi]).max(lo), (u0 + width[vi]).min(hi));
            let r = 0.5 * (5f64.sqrt() - 1.0);
            // Only section k moves: the other sections and the bodies not bounded by it are
            // computed once per coordinate (the same functions of the same positions as
            // `Structure::evaluate`, so every value is bit for bit the same).
            let mut trial = pos.clone();
            let mut actives = st.actives(&trial, acts);
            let mut bodies = [Sums::default(); 3];
            for j in 0..n - 1 {
                bodies[j] = st.between(trial[j], trial[j + 1]);
            }
            let mut eval = |u: f64, ev: &mut u64| {
                *ev += 1;
                trial[k].u = u;
                let (p1, p2) = st.section(trial[k]);
                actives[k].p1 = p1;
                actives[k].p2 = p2;
                if k > 0 {
                    bodies[k - 1] = st.between(trial[k - 1], trial[k]);
                }
                if k + 1 < n {
                    bodies[k] = st.between(trial[k], trial[k + 1]);
                }
                let Some(m) = solve_motion(&actives[..n], true) else {
                    return f64::INFINITY;
                };
                let (ax, g) = motion_work(&m, &bodies[..n - 1]);
                if ax > 0.0 {
                    g / ax
                } else {
                    f64::INFINITY
                }
            };
            let mut x1 = x3 - r * (x3 - x0);
            let mut x2 = x0 + r * (x3 - x0);
            let mut f1 = eval(x1, evaluations);
            let mut f2 = eval(x2, evaluations);
            while x3 - x0 > 1e-11 * a.len.max(1e-300) {
                if f1 <= f2 {
                    x3 = x2;
                    x2 = x1;
                    f2 = f1;
                    x1 = x3 - r * (x3 - x0);
                    f1 = eval(x1, evaluations);
                } else {
                    x0 = x1;
                    x1 = x2;
                    f1 = f2;
                    x2 = x0 + r * (x3 - x0);
                    f2 = eval(x2, evaluations);
                }
            }
            // Also try the ends of the bracket (a section may want to sit on a bound).
            let mut cand = [
                (f1, x1),
                (f2, x2),
                (eval(x0, evaluations), x0),
                (eval(x3, evaluations), x3),
            ];
            cand.sort_by(|a, b| a.0.total_cmp(&b.0));
            if cand[0].0 < best {
                best = cand[0].0;
                moved = moved.max((cand[0].1 - u0).abs());
                pos[k].u = cand[0].1;
            }
            width[vi] = (4.0 * (pos[k].u - u0).abs()).max(1e-4 * a.len);
        }
        let gain = before - best;
        if (gain.is_nan() || gain <= 1e-15 * best.abs().max(1e-3)) && moved < 1e-9 {
            break;
        }
    }
    (best, pos)
}

/// The continuous model's minimum thickness: the root of `lambda_signed(t)`, bracketed from
/// the thickness `t0` below the largest admissible one `tmax` and found by the Illinois variant
/// of regula falsi. `at(t)` runs the continuous model at thickness `t` (load toward +x).
pub fn continuous_min_thickness(
    t0: f64,
    tmax: f64,
    mut at: impl FnMut(f64) -> Result<ContinuousResult, KinematicError>,
) -> Result<MinThickness, KinematicError> {
    let mut iterations = 0;
    let mut lam = |t: f64| -> Result<(f64, ContinuousResult), KinematicError> {
        iterations += 1;
        let r = at(t)?;
        let l = r.lambda_signed.unwrap_or(f64::INFINITY);
        Ok((l, r))
    };
    let mut hi = t0;
    let (mut fhi, _) = lam(hi)?;
    while fhi <= 0.0 {
        hi = 0.5 * (hi + tmax);
        if tmax - hi < 1e-6 * tmax {
            return Err(KinematicError::Continuous(
                "the arch cannot stand at any thickness".into(),
            ));
        }
        fhi = lam(hi)?.0;
    }
    let mut lo = hi;
    let mut flo = fhi;
    while flo > 0.0 {
        lo *= 0.5;
        if lo < 1e-4 * tmax {
            return Err(KinematicError::Continuous(format!(
                "lambda stays positive down to thickness {lo:e}: no minimum thickness"
            )));
        }
        flo = lam(lo)?.0;
    }
    if !fhi.is_finite() {
        // Bisect until the upper end has a finite multiplier.
        while !fhi.is_finite() {
            hi = 0.5 * (lo + hi);
            fhi = lam(hi)?.0;
        }
    }
    // Illinois regula falsi on [lo, hi] with f(lo) < 0 < f(hi).
    let mut side = 0;
    let mut t = lo;
    for _ in 0..100 {
        t = (lo * fhi - hi * flo) / (fhi - flo);
        let (ft, _) = lam(t)?;
        if ft > 0.0 {
            hi = t;
            fhi = ft;
            if side == 1 {
                flo *= 0.5;
            }
            side = 1;
        } else {
            lo = t;
            flo = ft;
            if side == -1 {
                fhi *= 0.5;
            }
            side = -1;
        }
        if hi - lo < 1e-10 * tmax || ft == 0.0 {
            break;
        }
    }
    let (_, result) = lam(t)?;
    Ok(MinThickness {
        thickness: t,
        result,
        iterations,
    })
}
