//! Circular arches: semicircular (embrace 180 deg), segmental (< 180) and horseshoe (> 180).

use super::{radial_joints, Arc, ArchGeometry, ArchShape, Lump, RingPiece, Vec2};
use std::f64::consts::PI;

/// A circular arch: centreline radius and full embrace angle (pi = semicircular).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Circular {
    pub radius: f64,
    pub embrace: f64,
}

impl ArchShape for Circular {
    fn name(&self) -> &'static str {
        "circular"
    }
    fn keys(&self) -> Vec<(&'static str, f64)> {
        vec![
            ("radius", self.radius),
            ("embrace_deg", self.embrace.to_degrees()),
        ]
    }
    fn describe(&self) -> String {
        format!(
            "circular arch, R = {} m, embrace {} deg",
            super::trim(self.radius),
            super::trim(self.embrace.to_degrees())
        )
    }
    fn title(&self) -> String {
        let deg = self.embrace.to_degrees();
        if (deg - 180.0).abs() < 1e-9 {
            "semicircular".to_string()
        } else if deg < 180.0 {
            format!("segmental ({deg:.0} deg)")
        } else {
            format!("horseshoe ({deg:.0} deg)")
        }
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
        2.0 * self.radius * (0.5 * self.embrace).sin()
    }
    fn rise(&self) -> f64 {
        self.radius * (1.0 - (0.5 * self.embrace).cos())
    }
    fn crown_extrados(&self, t: f64) -> f64 {
        self.radius + 0.5 * t
    }
    fn max_thickness(&self, _n: usize) -> f64 {
        2.0 * self.radius
    }
    fn horizontal_springings(&self) -> bool {
        (self.embrace - PI).abs() <= 1e-12
    }
    fn geometry(&self, t: f64, n: usize) -> ArchGeometry {
        circular(self.radius, t, self.embrace, n)
    }
    fn ring(&self, _t: f64, _n: usize) -> Result<Vec<RingPiece>, String> {
        Ok(vec![RingPiece::Annulus {
            centre: Vec2::zeros(),
            radius: self.radius,
            theta0: 0.5 * PI + 0.5 * self.embrace,
            sweep: self.embrace,
            head: Lump::default(),
            tail: Lump::default(),
        }])
    }
}

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
