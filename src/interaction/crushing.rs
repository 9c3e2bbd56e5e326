//! Crushing: a finite compressive strength of the contacts, a rectangular stress block of
//! intensity `fc` over the out-of-plane depth `d` (RING's crushing model; Gilbert, Casapulla &
//! Ahmed, 2006; Gilbert, 2007).
//!
//! A joint of length `L` carries a resultant `N` at eccentricity `e` only if `N <= fc d L`
//! and `|N e| <= N L/2 - N^2/(2 fc d)`: the compressed zone `a = N/(fc d)` lies inside the
//! joint, the resultant at its centre. With the contact unknowns `c1, c2`
//! ([`super::contact`]), `N = c1 + c2`, `M = (c2 - c1) L/2`, the condition is exactly
//! `2 c1 kappa >= N^2` and `2 c2 kappa >= N^2`, `kappa = fc d L / fs` (since
//! `N L/2 - M = c1 L`, `N L/2 + M = c2 L`), and `N <= fc d L` follows from the two: two
//! rotated second-order cones per joint, given to Clarabel as `SecondOrderConeT(3)` divided
//! by kappa for scaling, `||(c - 1, sqrt2 N / sqrt(kappa))|| <= c + 1`; no linearisation.
//! They imply `c >= 0`, so the contacts' no-tension rows are left out with them.
//!
//! Work rate: a hinge at the centre of the compressed zone dissipates nothing more than the
//! rigid hinge; the kinematic side is the mechanism rotating about those points
//! (`crate::kinematic::certify_crushing`).

use super::{contact, Rows};
use crate::assembly::Assembly;

/// Finite compressive strength of the joints: a rectangular stress block of intensity `fc`
/// over the out-of-plane depth `d` (RING's crushing model; Gilbert, 2007). A joint of length
/// `L` then carries a resultant `N` at eccentricity `e` from its midpoint only if
/// `N <= fc d L` and `|N e| <= N L/2 - N^2/(2 fc d)`: the compressed zone `a = N/(fc d)` lies
/// inside the joint, and the resultant at its centre, `a/2` from the joint's end.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Strength {
    /// Compressive strength fc (Pa); `f64::INFINITY` for rigid (uncrushable) joints.
    pub compressive: f64,
    /// Out-of-plane depth d (m) over which the stress block acts.
    pub depth: f64,
}

impl Strength {
    /// Infinite compressive strength (Heyman's assumption).
    pub fn rigid() -> Strength {
        Strength {
            compressive: f64::INFINITY,
            depth: 1.0,
        }
    }

    /// Whether the strength is finite (the static program then has second-order cones).
    pub fn is_finite(&self) -> bool {
        self.compressive.is_finite()
    }

    /// The force per unit joint length a fully compressed joint carries, `fc d` (N/m);
    /// infinite for rigid joints.
    pub fn line_capacity(&self) -> f64 {
        self.compressive * self.depth
    }

    /// Width `a = N/(fc d)` of the compressed zone under a resultant `n` (m); 0 when rigid.
    pub fn compressed_zone(&self, n: f64) -> f64 {
        if self.is_finite() {
            n.max(0.0) / self.line_capacity()
        } else {
            0.0
        }
    }
}

impl Default for Strength {
    fn default() -> Self {
        Strength::rigid()
    }
}

/// The crushing cones of every joint, on the contact unknowns starting at column `first`:
/// per joint and end, `s = [c + 1, c - 1, sqrt2 N / sqrt(kappa)]` in the second-order cone
/// (`c + tau` in place of `c` in the phase-one program). Written with kappa itself the
/// cone's rows would hold `c +- kappa`, and at a strong material (kappa ~ 1e6 and more) `c`
/// would drown in round-off of kappa; `c` and `N` are O(1) here (forces over the weight).
/// Nothing for rigid joints.
pub fn static_rows(assembly: &Assembly, strength: Strength, rows: &mut Rows, first: usize) {
    if !strength.is_finite() {
        return;
    }
    let fs = rows.force_scale;
    for (j, jt) in assembly.joints.iter().enumerate() {
        let kappa = strength.line_capacity() * jt.length() / fs;
        let w = std::f64::consts::SQRT_2 / kappa.sqrt();
        let col = |which| contact::column_from(first, j, which);
        for which in 0..2 {
            let end = |rhs: f64| {
                let mut e = vec![(col(which), -1.0)];
                if rows.relax {
                    e.push((0, -1.0));
                }
                (e, rhs)
            };
            rows.cone([end(1.0), end(-1.0), (vec![(col(0), -w), (col(1), -w)], 0.0)]);
        }
    }
}
