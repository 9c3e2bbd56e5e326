//! Stereotomy: how the ring is cut into voussoirs (`arch.joints` in a scene).
//!
//! Every shape lays out radial joints (`geometry.md`). Two other cuts keep the intrados end
//! `p1` of every interior joint where the radial cut puts it and move only the extrados end:
//!
//! - **vertical**: the joint runs straight up from `p1` to the extrados, as in the Cartesian
//!   stereotomy of Makris & Alexakis (2013, "The effect of stereotomy on the shape of the
//!   thrust-line and the minimum thickness of semicircular masonry arches", Arch. Appl.
//!   Mech. 83), whose semicircle needs t/R = 0.1095 against Milankovitch's 0.1075 with radial
//!   joints;
//! - **horizontal_bed**: the interior joints whose radial cut is inclined at most `angle` to
//!   the horizontal (the haunches, the *tas-de-charge* of real arches) run horizontally
//!   outward from `p1` to the extrados; the joints above stay radial.
//!
//! The springing joints (0 and n) are never changed: they are the arch's bearing on its
//! supports or piers. The new extrados end is the first point where the ray from `p1` meets
//! the extrados, which is the chain of arcs of the radial geometry (`r + t/2` about each
//! arc's centre, between consecutive radial extrados points). A cut that leaves the ring
//! (runs into the opening) or folds a voussoir over itself is an error naming the joint.

use super::{cross, ArchGeometry, Vec2};

/// The joint stereotomy of an arch ring.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Stereotomy {
    /// Joints radial to the centre of their arc (the default of every shape).
    Radial,
    /// Interior joints vertical, from the radial intrados point up to the extrados.
    Vertical,
    /// Interior joints whose radial cut is inclined at most `angle` (radians, 0 < angle < pi/2)
    /// to the horizontal become horizontal beds; the others stay radial.
    HorizontalBed { angle: f64 },
}

impl Stereotomy {
    /// The scene word (`arch.joints = "..."`).
    pub fn name(&self) -> &'static str {
        match self {
            Stereotomy::Radial => "radial",
            Stereotomy::Vertical => "vertical",
            Stereotomy::HorizontalBed { .. } => "horizontal_bed",
        }
    }

    /// Whether every joint is radial (what the continuous model's sections assume).
    pub fn is_radial(&self) -> bool {
        *self == Stereotomy::Radial
    }
}

/// The geometry `g` (radial joints) recut with stereotomy `s`. `curved` says the voussoirs are
/// exact annular pieces, which needs both extrados corners of every voussoir on the arc it
/// lies on. Errors say which joint or voussoir cannot be cut and why.
pub fn recut(g: &ArchGeometry, s: Stereotomy, curved: bool) -> Result<ArchGeometry, String> {
    if s.is_radial() {
        return Ok(g.clone());
    }
    let n = g.voussoirs();
    let t = g.thickness;
    let size = g
        .joints
        .iter()
        .flat_map(|(a, b)| [a.norm(), b.norm()])
        .fold(t, f64::max);
    let tol = 1e-9 * size;
    let mut out = g.clone();
    for j in 1..n {
        let (p1, p2) = g.joints[j];
        let radial = p2 - p1;
        let dir = match s {
            Stereotomy::Radial => continue,
            Stereotomy::Vertical => Vec2::new(0.0, 1.0),
            Stereotomy::HorizontalBed { angle } => {
                let inclination = radial.y.abs().atan2(radial.x.abs());
                if inclination > angle || radial.x == 0.0 {
                    continue;
                }
                Vec2::new(radial.x.signum(), 0.0)
            }
        };
        // The cut must enter the ring, i.e. leave the intrados outward.
        if dir.dot(&radial) <= 1e-9 * radial.norm() {
            return Err(format!(
                "the {} joint {j} from the intrados at ({}, {}) would run into the opening, not through the ring (only arches that stay above their centres, not horseshoes, can be cut so)",
                s.name(),
                short(p1.x),
                short(p1.y)
            ));
        }
        let hit = extrados_hit(g, p1, dir, tol).ok_or_else(|| {
            format!(
                "the {} joint {j} from the intrados at ({}, {}) does not meet the extrados",
                s.name(),
                short(p1.x),
                short(p1.y)
            )
        })?;
        out.joints[j] = (p1, hit);
    }
    for j in 0..n {
        let old = g.quad(j);
        let new = out.quad(j);
        let (so, sn) = (signed_area(&old), signed_area(&new));
        if !(super::is_convex(&new) && so * sn > 0.0 && sn.abs() > 1e-12 * size * size) {
            return Err(format!(
                "with {} joints voussoir {j} (between joints {j} and {}) folds over itself: use fewer voussoirs, a thinner ring or another stereotomy",
                s.name(),
                j + 1
            ));
        }
        if curved {
            let arc = g.arcs[j];
            let re = arc.radius + 0.5 * t;
            for p in [new[1], new[2]] {
                if ((p - arc.centre).norm() - re).abs() > 1e-7 * size {
                    return Err(format!(
                        "with {} joints voussoir {j} spans two arcs of the extrados, which a curved voussoir cannot: use voussoir_shape = \"polygon\"",
                        s.name()
                    ));
                }
            }
        }
    }
    Ok(out)
}

/// The first point where the ray `p + s dir` (s > 0) meets the extrados of `g`.
fn extrados_hit(g: &ArchGeometry, p: Vec2, dir: Vec2, tol: f64) -> Option<Vec2> {
    let t = g.thickness;
    let mut best: Option<(f64, Vec2)> = None;
    for (m, arc) in g.arcs.iter().enumerate() {
        let c = arc.centre;
        let re = arc.radius + 0.5 * t;
        let q = p - c;
        let b = dir.dot(&q);
        let disc = b * b - (q.norm_squared() - re * re);
        if disc < 0.0 {
            continue;
        }
        let s = -b + disc.sqrt();
        if s <= 0.0 {
            continue;
        }
        let hit = p + s * dir;
        // On this arc's part of the extrados: between its two radial extrados corners.
        let (ea, eb) = (g.joints[m].1 - c, g.joints[m + 1].1 - c);
        let h = hit - c;
        let turn = cross(ea, eb).signum();
        let inside = turn * cross(ea, h) >= -tol * re && turn * cross(h, eb) >= -tol * re;
        if inside && best.is_none_or(|(sb, _)| s < sb) {
            best = Some((s, hit));
        }
    }
    best.map(|(_, h)| h)
}

fn signed_area(q: &[Vec2; 4]) -> f64 {
    let mut a = 0.0;
    for k in 0..4 {
        a += cross(q[k], q[(k + 1) % 4]);
    }
    0.5 * a
}

fn short(x: f64) -> String {
    format!("{:.6}", x)
        .trim_end_matches('0')
        .trim_end_matches('.')
        .to_string()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::circular;

    #[test]
    fn vertical_joints_keep_the_intrados_and_end_on_the_extrados() {
        let (r, t) = (1.0, 0.12);
        let g = circular(r, t, std::f64::consts::PI, 12);
        let v = recut(&g, Stereotomy::Vertical, true).unwrap();
        for j in 1..12 {
            let (p1, p2) = v.joints[j];
            assert_eq!(p1, g.joints[j].0);
            assert!((p2.x - p1.x).abs() < 1e-15 && p2.y > p1.y);
            assert!((p2.norm() - (r + 0.5 * t)).abs() < 1e-12);
        }
        assert_eq!(v.joints[0], g.joints[0]);
        assert_eq!(v.joints[12], g.joints[12]);
    }

    #[test]
    fn horizontal_beds_only_up_to_the_angle() {
        let g = circular(1.0, 0.2, std::f64::consts::PI, 12);
        let angle = 40f64.to_radians();
        let h = recut(&g, Stereotomy::HorizontalBed { angle }, false).unwrap();
        for j in 1..12 {
            let (p1, p2) = g.joints[j];
            let inc = (p2 - p1).y.abs().atan2((p2 - p1).x.abs());
            let (q1, q2) = h.joints[j];
            if inc <= angle {
                assert!((q2.y - q1.y).abs() < 1e-15, "joint {j} horizontal");
                assert!((q2.norm() - 1.1).abs() < 1e-12);
            } else {
                assert_eq!((q1, q2), (p1, p2));
            }
        }
    }
}
