//! Pointed (two-centred) arches: each half is a circular arc of centreline radius R whose
//! centre is offset by the eccentricity e across the axis; e = 0 is the semicircle and
//! e = R/2 the equilateral Gothic arch. The crown joint is vertical.

use super::{mirror, polygon_area_centroid, radial_joints, Arc, ArchGeometry, ArchShape, Lump};
use super::{RingPiece, Vec2};
use std::f64::consts::PI;

/// A pointed arch: centreline radius and eccentricity of the two centres.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Pointed {
    pub radius: f64,
    pub eccentricity: f64,
}

impl ArchShape for Pointed {
    fn name(&self) -> &'static str {
        "pointed"
    }
    fn keys(&self) -> Vec<(&'static str, f64)> {
        vec![("radius", self.radius), ("eccentricity", self.eccentricity)]
    }
    fn describe(&self) -> String {
        format!(
            "pointed arch, R = {} m, e = {} m",
            super::trim(self.radius),
            super::trim(self.eccentricity)
        )
    }
    fn title(&self) -> String {
        "pointed".to_string()
    }
    fn size(&self) -> f64 {
        self.radius
    }
    fn size_name(&self) -> &'static str {
        "R"
    }
    fn radius(&self) -> Option<f64> {
        Some(self.radius)
    }
    fn span(&self) -> f64 {
        2.0 * (self.radius - self.eccentricity)
    }
    fn rise(&self) -> f64 {
        (self.radius * self.radius - self.eccentricity * self.eccentricity).sqrt()
    }
    fn crown_extrados(&self, t: f64) -> f64 {
        ((self.radius + 0.5 * t).powi(2) - self.eccentricity * self.eccentricity).sqrt()
    }
    /// 2(R - e) with two voussoirs; with more, the thickness at which the intrados meets the
    /// axis exactly at the radial joint next to the crown, `2 (R - e / (-cos phi_last))` (a
    /// thicker arch with n voussoirs would have that voussoir fold over the crown joint).
    fn max_thickness(&self, n: usize) -> f64 {
        let (radius, e) = (self.radius, self.eccentricity);
        let h = (n / 2).max(1) as f64;
        let phi_end = (-e / radius).acos();
        let phi_last = PI - (PI - phi_end) * (h - 1.0) / h;
        // phi_last >= phi_end >= pi/2, so -cos(phi_last) is in [0, 1] (1 for n = 2).
        let c = -phi_last.cos();
        if c > 0.0 {
            2.0 * (radius - e / c)
        } else {
            2.0 * radius
        }
    }
    fn horizontal_springings(&self) -> bool {
        true
    }
    fn geometry(&self, t: f64, n: usize) -> ArchGeometry {
        pointed(self.radius, self.eccentricity, t, n)
    }
    /// Two annuli, left (centre (e, 0)) and right (centre (-e, 0)), meeting at the vertical
    /// crown joint. Radial sections of the left annulus exist only where they lie entirely left
    /// of the crown line (polar angle `>= acos(-e / r_i)`); the small keystone between the last
    /// of them and the crown joint (the extrados sector minus the triangle centre - intrados
    /// apex - extrados apex) is rigid and moves with its annulus (mirror on the right).
    fn ring(&self, t: f64, n: usize) -> Result<Vec<RingPiece>, String> {
        let (radius, e) = (self.radius, self.eccentricity);
        let ri = radius - 0.5 * t;
        let re = radius + 0.5 * t;
        if e >= ri {
            return Err(format!(
                "pointed arch with eccentricity {e} >= intrados radius {ri}"
            ));
        }
        let phi_i = (-e / ri).acos();
        let phi_e = (-e / re).acos();
        let o = Vec2::new(e, 0.0);
        let apex_i = Vec2::new(0.0, (ri * ri - e * e).sqrt());
        let apex_e = Vec2::new(0.0, (re * re - e * e).sqrt());
        let d = phi_i - phi_e;
        let mid = 0.5 * (phi_i + phi_e);
        let sector = 0.5 * re * re * d;
        let sector_moment =
            o * sector + re * re * re / 3.0 * 2.0 * (0.5 * d).sin() * super::polar(mid);
        let (ta, tc) = polygon_area_centroid(&[o, apex_i, apex_e]);
        let left_key = Lump {
            area: sector - ta,
            moment: sector_moment - ta * tc,
            extrados: Some((phi_i, phi_e)),
        };
        let right_key = Lump {
            area: left_key.area,
            moment: mirror(left_key.moment),
            extrados: Some((PI - phi_e, PI - phi_i)),
        };
        Ok(vec![
            RingPiece::Annulus {
                centre: o,
                radius,
                theta0: PI,
                sweep: PI - phi_i,
                head: Lump::default(),
                tail: left_key,
            },
            RingPiece::Joint {
                p1: apex_i,
                p2: apex_e,
                joint: n / 2,
            },
            RingPiece::Annulus {
                centre: Vec2::new(-e, 0.0),
                radius,
                theta0: PI - phi_i,
                sweep: PI - phi_i,
                head: right_key,
                tail: Lump::default(),
            },
        ])
    }
}

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
