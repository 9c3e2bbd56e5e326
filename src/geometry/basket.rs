//! Basket-handle (three-centred) arches: two side arcs of radius r1 subtending the side angle
//! b each and a crown arc of radius r2 > r1, tangent-continuous.

use super::{radial_joints, Arc, ArchGeometry, ArchShape, Lump, RingPiece, Vec2};
use std::f64::consts::PI;

/// A three-centred basket-handle arch: centreline span, rise, and angle of each side arc.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Basket {
    pub span: f64,
    pub rise: f64,
    pub side_angle: f64,
}

impl Basket {
    /// Centreline radii `(r1, r2)` of the side and crown arcs.
    pub fn radii(&self) -> (f64, f64) {
        basket_radii(self.span, self.rise, self.side_angle)
    }
}

impl ArchShape for Basket {
    fn name(&self) -> &'static str {
        "basket"
    }
    fn keys(&self) -> Vec<(&'static str, f64)> {
        vec![
            ("span", self.span),
            ("rise", self.rise),
            ("side_angle_deg", self.side_angle.to_degrees()),
        ]
    }
    fn describe(&self) -> String {
        format!(
            "basket-handle arch, span {} m, rise {} m, side angle {} deg",
            super::trim(self.span),
            super::trim(self.rise),
            super::trim(self.side_angle.to_degrees())
        )
    }
    fn title(&self) -> String {
        "basket-handle".to_string()
    }
    fn size(&self) -> f64 {
        0.5 * self.span
    }
    fn size_name(&self) -> &'static str {
        "(span/2)"
    }
    fn span(&self) -> f64 {
        self.span
    }
    fn rise(&self) -> f64 {
        self.rise
    }
    fn crown_extrados(&self, t: f64) -> f64 {
        let (r1, r2) = self.radii();
        r2 + 0.5 * t - (r2 - r1) * self.side_angle.sin()
    }
    fn max_thickness(&self, _n: usize) -> f64 {
        2.0 * self.radii().0
    }
    fn horizontal_springings(&self) -> bool {
        true
    }
    fn geometry(&self, t: f64, n: usize) -> ArchGeometry {
        basket(self.span, self.rise, self.side_angle, t, n)
    }
    /// Three annuli: the side arcs and the crown arc (the transition sections belong to both).
    fn ring(&self, _t: f64, _n: usize) -> Result<Vec<RingPiece>, String> {
        let (r1, r2) = self.radii();
        let b = self.side_angle;
        let piece = |centre: Vec2, radius: f64, theta0: f64, sweep: f64| RingPiece::Annulus {
            centre,
            radius,
            theta0,
            sweep,
            head: Lump::default(),
            tail: Lump::default(),
        };
        Ok(vec![
            piece(Vec2::new(-(0.5 * self.span - r1), 0.0), r1, PI, b),
            piece(
                Vec2::new(0.0, -(r2 - r1) * b.sin()),
                r2,
                PI - b,
                PI - 2.0 * b,
            ),
            piece(Vec2::new(0.5 * self.span - r1, 0.0), r1, b, b),
        ])
    }
}

/// Centreline radii `(r1, r2)` of the side and crown arcs for centreline span `span`, rise
/// `rise` and side angle `b` (radians), from `(1 - cos b) r1 + cos b r2 = span/2` and
/// `sin b r1 + (1 - sin b) r2 = rise`.
pub fn basket_radii(span: f64, rise: f64, b: f64) -> (f64, f64) {
    let (s, c) = b.sin_cos();
    let det = (1.0 - c) * (1.0 - s) - c * s;
    let half = 0.5 * span;
    let r1 = (half * (1.0 - s) - c * rise) / det;
    let r2 = ((1.0 - c) * rise - s * half) / det;
    (r1, r2)
}

/// Voussoirs on each side arc: `max(1, round(n r1 b / (2 r1 b + r2 (pi - 2b))))`.
pub fn side_voussoirs(n: usize, r1: f64, r2: f64, b: f64) -> usize {
    let share = n as f64 * r1 * b / (2.0 * r1 * b + r2 * (PI - 2.0 * b));
    // Round half away from zero, as the spec asks; a share within round-off of k + 1/2 is a
    // tie (algebraically equal forms of the denominator differ in the last bit), so it goes up.
    let frac = share - share.floor();
    let rounded = if (frac - 0.5).abs() <= 1e-9 * share.max(1.0) {
        share.floor() + 1.0
    } else {
        share.round()
    };
    (rounded as usize).max(1)
}

/// Basket-handle arch; the caller has checked `0 < r1 < r2`, `t < 2 r1` and that the crown
/// arc gets at least one voussoir.
pub fn basket(span: f64, rise: f64, b: f64, t: f64, n: usize) -> ArchGeometry {
    let (r1, r2) = basket_radii(span, rise, b);
    let ns = side_voussoirs(n, r1, r2, b);
    let nc = n - 2 * ns;
    let left = Arc {
        centre: Vec2::new(-(0.5 * span - r1), 0.0),
        radius: r1,
    };
    let crown = Arc {
        centre: Vec2::new(0.0, -(r2 - r1) * b.sin()),
        radius: r2,
    };
    let right = Arc {
        centre: Vec2::new(0.5 * span - r1, 0.0),
        radius: r1,
    };
    let mut joints = radial_joints(left, t, PI, PI - b, ns);
    joints.extend(radial_joints(crown, t, PI - b, b, nc).into_iter().skip(1));
    joints.extend(radial_joints(right, t, b, 0.0, ns).into_iter().skip(1));
    let mut arcs = vec![left; ns];
    arcs.extend(std::iter::repeat_n(crown, nc));
    arcs.extend(std::iter::repeat_n(right, ns));
    let mut g = ArchGeometry {
        joints,
        arcs,
        thickness: t,
    };
    g.symmetrise();
    g
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn exact_ties_round_up() {
        // span 3, rise 2 - sqrt(3)/2, b = 60 deg: r1 = 1, r2 = 2, and n = 10 gives a share of
        // exactly 2.5 voussoirs per side arc.
        let b = 60f64.to_radians();
        let (r1, r2) = basket_radii(3.0, 2.0 - 3f64.sqrt() / 2.0, b);
        assert!((r1 - 1.0).abs() < 1e-12 && (r2 - 2.0).abs() < 1e-12);
        assert_eq!(side_voussoirs(10, r1, r2, b), 3);
        assert_eq!(side_voussoirs(9, r1, r2, b), 2);
    }
}
