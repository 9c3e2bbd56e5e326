//! Circular arches: semicircular (embrace 180 deg), segmental (< 180) and horseshoe (> 180).

use super::{radial_joints, Arc, ArchGeometry, Vec2};

/// Circular arch of centreline radius `radius`, thickness `t`, full embrace angle `embrace`
/// (radians) and `n` voussoirs; centre at the origin. The centreline polar angle of joint j is
/// `pi/2 + a - 2 a j / n` with `a = embrace / 2`.
pub fn circular(radius: f64, t: f64, embrace: f64, n: usize) -> ArchGeometry {
    let a = 0.5 * embrace;
    let arc = Arc {
        centre: Vec2::zeros(),
        radius,
    };
    let half = std::f64::consts::FRAC_PI_2;
    let mut g = ArchGeometry {
        joints: radial_joints(arc, t, half + a, half - a, n),
        arcs: vec![arc; n],
        thickness: t,
    };
    g.symmetrise();
    g
}
