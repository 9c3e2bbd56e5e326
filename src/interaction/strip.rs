//! Bonded strips: an FRP or FRCM strip glued on the intrados or the extrados across arch
//! joints. At each joint it crosses, the reinforced end may carry a tension up to the
//! strip's capacity there (its debonding force), so a hinge can open on that side only
//! past it (rigid-plastic, as the tie; Foraboschi, 2004, and the CNR-DT 200 design of
//! strengthened arches by limit analysis).
//!
//! Static rows: one unknown `S` per crossed joint (over the force scale), `0 <= S <= F`,
//! a force that pulls the two sides of the joint together at the reinforced end: the joint
//! transmits `-S n` from `from` to `to` there, besides its contact force.
//!
//! Work rate: the reinforced end opening at the normal rate `vn >= 0` dissipates `F vn`
//! (nothing when it stays closed, as at a hinge on that end).

use super::Rows;
use crate::assembly::{Assembly, JointEnd};

/// A strip's anchorage across one joint.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Strip {
    /// The joint (assembly index).
    pub joint: usize,
    /// The reinforced end.
    pub end: JointEnd,
    /// Its tensile capacity there (N), finite and >= 0.
    pub capacity: f64,
    /// Index of the `[[reinforcements]]` entry it belongs to.
    pub source: usize,
}

/// A strip's force in a solution.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StripForce {
    /// Tension (N).
    pub force: f64,
    pub capacity: f64,
    /// Whether it has reached its capacity (debonded), to the solver's accuracy.
    pub yielded: bool,
}

impl Strip {
    /// What is wrong with the strip in `assembly`, in words (None when well formed).
    pub fn problem(&self, assembly: &Assembly) -> Option<String> {
        if !(self.capacity.is_finite() && self.capacity >= 0.0) {
            return Some(format!(
                "capacity {} N: must be a finite number >= 0",
                self.capacity
            ));
        }
        (self.joint >= assembly.joints.len()).then(|| {
            format!(
                "on joint {}, but there are {} joints",
                self.joint,
                assembly.joints.len()
            )
        })
    }

    /// The reinforced end's point.
    pub fn point(&self, assembly: &Assembly) -> crate::geometry::Vec2 {
        let j = &assembly.joints[self.joint];
        match self.end {
            JointEnd::P1 => j.p1,
            JointEnd::P2 => j.p2,
        }
    }

    /// The strip's part of the static program: its tension, pulling the joint's two sides
    /// together at the reinforced end, and its bounds `0 <= S <= F`. Returns its column.
    pub fn static_rows(&self, assembly: &Assembly, rows: &mut Rows) -> usize {
        let col = self.pull(assembly, rows);
        rows.nonnegative(vec![(col, -1.0)], 0.0, false);
        rows.nonnegative(vec![(col, 1.0)], self.capacity / rows.force_scale, false);
        col
    }

    /// [`Strip::static_rows`] with its capacity an unknown, column `capacity` (over the force
    /// scale), as a retrofit design sizes it: `0 <= S <= C`, the one capacity of its
    /// `[[reinforcements]]` entry at every joint it crosses. Returns the tension's column.
    pub fn static_rows_designed(
        &self,
        assembly: &Assembly,
        rows: &mut Rows,
        capacity: usize,
    ) -> usize {
        let col = self.pull(assembly, rows);
        rows.nonnegative(vec![(col, -1.0)], 0.0, false);
        rows.nonnegative(vec![(col, 1.0), (capacity, -1.0)], 0.0, false);
        col
    }

    /// The tension's column and its pull on the joint's two sides at the reinforced end.
    fn pull(&self, assembly: &Assembly, rows: &mut Rows) -> usize {
        let col = rows.add_columns(1);
        let j = &assembly.joints[self.joint];
        let (n, p) = (j.normal(), self.point(assembly));
        rows.force_on(j.to, col, n, p, -1.0);
        rows.force_on(j.from, col, n, p, 1.0);
        col
    }

    /// The largest power it dissipates when its end opens at the normal rate `rate`.
    pub fn dissipation(&self, rate: f64) -> f64 {
        self.capacity * rate.max(0.0)
    }

    /// The force `force` (N) read from a solution, clamped into `[0, F]`.
    pub fn force_of(&self, force: f64) -> StripForce {
        let force = force.clamp(0.0, self.capacity);
        StripForce {
            force,
            capacity: self.capacity,
            yielded: self.capacity > 0.0
                && force >= self.capacity * (1.0 - super::tie::YIELD_TOLERANCE),
        }
    }
}
