//! Plane geometry of arches: joints (p1 on the intrados, p2 on the extrados) and the arcs the
//! voussoirs lie on, for every shape of `shared/spec/geometry.md`, plus the polygon and
//! circular-segment formulas the blocks need.
//!
//! Every arc is described by its centreline radius; intrados and extrados are offset by t/2
//! about the same centre, and joints are radial to the centre of the arc they lie on.

mod basket;
mod circular;
mod pointed;
mod stereotomy;

pub use basket::{basket, basket_radii, side_voussoirs, Basket};
pub use circular::{circular, Circular};
pub use pointed::{pointed, Pointed};
pub use stereotomy::{recut, Stereotomy};

/// An arch shape: everything the rest of voussoir needs to know about one family of arches.
/// Each shape is one type in its own file of this module; a new shape is one more file here
/// and one more arm where the scene is read (`crate::scene`).
///
/// Lengths in metres, angles in radians. Joints are numbered from the left springing.
pub trait ArchShape: std::fmt::Debug + Send + Sync {
    /// The scene-file word (`shape = "..."`).
    fn name(&self) -> &'static str;
    /// The shape's own scene keys under `[arch]` (besides `shape`, `thickness`, `voussoirs`,
    /// `voussoir_shape`), with their values as the scene gives them (`_deg` keys in degrees).
    fn keys(&self) -> Vec<(&'static str, f64)>;
    /// The shape and its dimensions in words, e.g. `circular arch, R = 1 m, embrace 180 deg`.
    fn describe(&self) -> String;
    /// A short adjective for titles: `semicircular`, `segmental (120 deg)`, `pointed`, ...
    fn title(&self) -> String;
    /// The arch's own size: R for circular and pointed arches, span/2 for basket arches
    /// (ratios such as t_min / size use it).
    fn size(&self) -> f64;
    /// How `size` is written in ratios: `R` or `(span/2)`.
    fn size_name(&self) -> &'static str;
    /// Centreline radius, for shapes that have one radius.
    fn radius(&self) -> Option<f64> {
        None
    }
    /// Centreline span.
    fn span(&self) -> f64;
    /// Centreline rise above the springing line.
    fn rise(&self) -> f64;
    /// Height of the extrados at the crown for thickness `t`: the ring's highest point.
    fn crown_extrados(&self, t: f64) -> f64;
    /// The largest thickness (exclusive) the shape admits with `n` voussoirs.
    fn max_thickness(&self, n: usize) -> f64;
    /// Whether both springing joints are horizontal (a portal needs them).
    fn horizontal_springings(&self) -> bool;
    /// Joints and arcs of the ring with thickness `t` and `n` voussoirs.
    fn geometry(&self, t: f64, n: usize) -> ArchGeometry;
    /// The ring as a continuum (for the continuous kinematic model), from the left springing
    /// to the right one, with thickness `t` and `n` voussoirs (which number its fixed joints).
    fn ring(&self, t: f64, n: usize) -> Result<Vec<RingPiece>, String>;
}

/// A number with at most 9 significant decimals and no trailing zeros (180, 67.5).
pub fn trim(x: f64) -> String {
    let s = format!("{x:.9}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    s.to_string()
}

/// A piece of an arch ring seen as a continuum.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum RingPiece {
    /// An annular piece about `centre`, centreline radius `radius`, from polar angle `theta0`
    /// clockwise through `sweep` (left to right), with rigid material attached before its start
    /// (`head`) and after its end (`tail`).
    Annulus {
        centre: Vec2,
        radius: f64,
        theta0: f64,
        sweep: f64,
        head: Lump,
        tail: Lump,
    },
    /// A joint at a fixed place between two annuli (the vertical crown joint of a pointed
    /// arch): arch joint `joint` from `p1` (intrados) to `p2` (extrados).
    Joint { p1: Vec2, p2: Vec2, joint: usize },
}

/// A rigid piece of material: its area and first moment of area about the origin, and the
/// part of the annulus's extrados arc that bounds it (polar angles about the annulus's centre,
/// in the order the ring runs), which carries its share of loads spread along the extrados.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Lump {
    pub area: f64,
    pub moment: Vec2,
    pub extrados: Option<(f64, f64)>,
}

/// A point or vector in the plane of the arch (metres).
pub type Vec2 = nalgebra::Vector2<f64>;

/// z-component of the cross product `a x b`.
#[inline]
pub fn cross(a: Vec2, b: Vec2) -> f64 {
    a.x * b.y - a.y * b.x
}

/// Mirror image about the vertical axis x = 0.
#[inline]
pub fn mirror(p: Vec2) -> Vec2 {
    Vec2::new(-p.x, p.y)
}

/// Unit vector at polar angle `theta` (radians).
#[inline]
pub fn polar(theta: f64) -> Vec2 {
    // Springings of semicircular and pointed arches sit at exactly 0 and pi: keep their y = 0
    // exact rather than sin(pi) = 1.2e-16.
    use std::f64::consts::{FRAC_PI_2, PI};
    if theta == PI {
        Vec2::new(-1.0, 0.0)
    } else if theta == 0.0 {
        Vec2::new(1.0, 0.0)
    } else if theta == FRAC_PI_2 {
        Vec2::new(0.0, 1.0)
    } else {
        Vec2::new(theta.cos(), theta.sin())
    }
}

/// Whether a polygon is convex (every turn the same way; straight angles allowed).
pub fn is_convex(polygon: &[Vec2]) -> bool {
    let m = polygon.len();
    if m < 3 {
        return false;
    }
    let (mut pos, mut neg) = (false, false);
    for k in 0..m {
        let a = polygon[k];
        let b = polygon[(k + 1) % m];
        let c = polygon[(k + 2) % m];
        let turn = cross(b - a, c - b);
        let scale = (b - a).norm() * (c - b).norm();
        if turn > 1e-12 * scale {
            pos = true;
        } else if turn < -1e-12 * scale {
            neg = true;
        }
    }
    !(pos && neg)
}

/// Area (always positive) and centroid of a simple polygon given in either orientation.
pub fn polygon_area_centroid(points: &[Vec2]) -> (f64, Vec2) {
    // Shoelace formula relative to the first vertex, which keeps round-off small for blocks
    // far from the origin.
    let o = points[0];
    let mut a2 = 0.0;
    let mut c = Vec2::zeros();
    for k in 1..points.len().saturating_sub(1) {
        let p = points[k] - o;
        let q = points[k + 1] - o;
        let w = cross(p, q);
        a2 += w;
        c += w * (p + q);
    }
    if a2 == 0.0 {
        return (0.0, o);
    }
    (0.5 * a2.abs(), o + c / (3.0 * a2))
}

/// The circular arc a voussoir lies on: its centre and centreline radius.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Arc {
    pub centre: Vec2,
    pub radius: f64,
}

/// Area and centroid of the circular segment cut from the circle (centre `c`, radius `r`) by
/// the chord from `a` to `b` (both on the circle), on the side away from the centre.
pub fn circular_segment(c: Vec2, r: f64, a: Vec2, b: Vec2) -> (f64, Vec2) {
    let chord = (b - a).norm();
    let delta = 2.0 * (chord / (2.0 * r)).clamp(-1.0, 1.0).asin();
    // delta - sin(delta) loses all its digits for thin voussoirs: use its series there.
    let d_minus_sin = if delta < 0.1 {
        let d2 = delta * delta;
        delta * d2 / 6.0 * (1.0 - d2 / 20.0 * (1.0 - d2 / 42.0 * (1.0 - d2 / 72.0)))
    } else {
        delta - delta.sin()
    };
    let area = 0.5 * r * r * d_minus_sin;
    if area <= 0.0 {
        return (0.0, 0.5 * (a + b));
    }
    let s = (0.5 * delta).sin();
    let dist = 4.0 * r * s * s * s / (3.0 * d_minus_sin);
    let mid = 0.5 * (a + b) - c;
    let dir = if mid.norm() > 0.0 {
        mid / mid.norm()
    } else {
        Vec2::new(0.0, 1.0)
    };
    (area, c + dist * dir)
}

/// Joints and arcs of an arch, before it is cut into blocks.
#[derive(Debug, Clone)]
pub struct ArchGeometry {
    /// n + 1 joints `(p1, p2)` from the left springing to the right springing; p1 on the
    /// intrados, p2 on the extrados.
    pub joints: Vec<(Vec2, Vec2)>,
    /// For each of the n voussoirs (between joints j and j + 1), the arc it lies on.
    pub arcs: Vec<Arc>,
    /// Radial thickness t.
    pub thickness: f64,
}

impl ArchGeometry {
    /// Number of voussoirs.
    pub fn voussoirs(&self) -> usize {
        self.arcs.len()
    }

    /// Polygon of voussoir `j`: `[p1(j), p2(j), p2(j+1), p1(j+1)]`.
    pub fn quad(&self, j: usize) -> [Vec2; 4] {
        let (a1, a2) = self.joints[j];
        let (b1, b2) = self.joints[j + 1];
        [a1, a2, b2, b1]
    }

    /// Area and centroid of voussoir `j`: of its quadrilateral (`curved = false`) or of the
    /// exact annular piece (quadrilateral minus the intrados segment plus the extrados one).
    pub fn voussoir_area_centroid(&self, j: usize, curved: bool) -> (f64, Vec2) {
        let q = self.quad(j);
        let (aq, cq) = polygon_area_centroid(&q);
        if !curved {
            return (aq, cq);
        }
        let arc = self.arcs[j];
        let (ai, ci) = circular_segment(arc.centre, arc.radius - 0.5 * self.thickness, q[0], q[3]);
        let (ae, ce) = circular_segment(arc.centre, arc.radius + 0.5 * self.thickness, q[1], q[2]);
        let area = aq - ai + ae;
        (area, (aq * cq - ai * ci + ae * ce) / area)
    }

    /// Mirror the left half onto the right: joint j > n/2 becomes the image of joint n - j,
    /// so a symmetric arch is symmetric to the last bit.
    fn symmetrise(&mut self) {
        let n = self.joints.len() - 1;
        for j in 0..=n {
            if 2 * j == n {
                self.joints[j].0.x = 0.0;
                self.joints[j].1.x = 0.0;
            } else if 2 * j > n {
                let (p1, p2) = self.joints[n - j];
                self.joints[j] = (mirror(p1), mirror(p2));
            }
        }
    }
}

/// Joints radial to `arc`, at centreline angles from `from` to `to` (radians) in `steps`
/// equal steps, both ends included.
fn radial_joints(arc: Arc, t: f64, from: f64, to: f64, steps: usize) -> Vec<(Vec2, Vec2)> {
    (0..=steps)
        .map(|k| {
            let theta = from + (to - from) * k as f64 / steps as f64;
            let d = polar(theta);
            (
                arc.centre + (arc.radius - 0.5 * t) * d,
                arc.centre + (arc.radius + 0.5 * t) * d,
            )
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn segment_matches_sector_minus_triangle() {
        let c = Vec2::new(1.0, -2.0);
        let r = 3.0;
        for &delta in &[1e-4, 0.05, 0.3, 1.5, 3.0] {
            let a = c + r * polar(0.2);
            let b = c + r * polar(0.2 + delta);
            let (area, cen) = circular_segment(c, r, a, b);
            let exact = 0.5 * r * r * (delta - delta.sin());
            assert!((area - exact).abs() <= 1e-12 * exact.max(1e-300) + 1e-15);
            // Centroid lies on the bisector, further out than the chord.
            let bis = polar(0.2 + 0.5 * delta);
            let along = (cen - c).dot(&bis);
            assert!(along > r * (0.5 * delta).cos() && along < r);
            assert!(cross(bis, cen - c).abs() < 1e-9);
        }
    }

    #[test]
    fn polygon_centroid_of_rectangle() {
        let p = [
            Vec2::new(2.0, 1.0),
            Vec2::new(4.0, 1.0),
            Vec2::new(4.0, 2.0),
            Vec2::new(2.0, 2.0),
        ];
        let (a, c) = polygon_area_centroid(&p);
        assert!((a - 2.0).abs() < 1e-14);
        assert!((c - Vec2::new(3.0, 1.5)).norm() < 1e-14);
        let rev: Vec<Vec2> = p.iter().rev().copied().collect();
        let (a2, c2) = polygon_area_centroid(&rev);
        assert!((a2 - 2.0).abs() < 1e-14 && (c2 - c).norm() < 1e-14);
    }
}
