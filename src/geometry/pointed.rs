//! Pointed (two-centred) arches: each half is a circular arc of centreline radius R whose
//! centre is offset by the eccentricity e across the axis; e = 0 is the semicircle and
//! e = R/2 the equilateral Gothic arch. The crown joint is vertical.

use super::{mirror, radial_joints, Arc, ArchGeometry, Vec2};

/// Pointed arch of centreline radius `radius`, eccentricity `e`, thickness `t` and `n`
/// (even) voussoirs.
pub fn pointed(radius: f64, e: f64, t: f64, n: usize) -> ArchGeometry {
    let h = n / 2;
    let left = Arc {
        centre: Vec2::new(e, 0.0),
        radius,
    };
    let right = Arc {
        centre: Vec2::new(-e, 0.0),
        radius,
    };
    let phi_end = (-e / radius).acos();
    let mut joints = radial_joints(left, t, std::f64::consts::PI, phi_end, h);
    // The crown joint is vertical on x = 0, between the intrados and extrados apexes.
    let ri = radius - 0.5 * t;
    let re = radius + 0.5 * t;
    joints[h] = (
        Vec2::new(0.0, (ri * ri - e * e).sqrt()),
        Vec2::new(0.0, (re * re - e * e).sqrt()),
    );
    for j in (0..h).rev() {
        let (p1, p2) = joints[j];
        joints.push((mirror(p1), mirror(p2)));
    }
    let mut arcs = vec![left; h];
    arcs.extend(std::iter::repeat_n(right, n - h));
    ArchGeometry {
        joints,
        arcs,
        thickness: t,
    }
}
