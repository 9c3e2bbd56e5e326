//! Tie rods: a steel bar anchored at two points, on two blocks or on a block and the ground,
//! that carries tension only, between its prestress `P` and its capacity `C` (the force at
//! which it yields: bar, anchor plate or masonry punching, whichever is least). Rigid-plastic
//! in the limit analyses, as in the retrofit literature on masonry arches (Heyman's bounds
//! hold for any bounded, convex set of internal forces: the tie's is the interval `[P, C]`).
//!
//! Static rows: one unknown `T` per tie (over the force scale), `P <= T <= C`; the tie pulls
//! its `from` block toward `to` along the unit vector `e = (to - from)/|to - from|`, applied
//! at the anchor point, and its `to` block back along `-e`.
//!
//! Work rate: with the elongation rate `de = (v_to(to) - v_from(from)) . e` of a mechanism,
//! the tie's force does the power `-T de` on the blocks; the largest dissipation any
//! admissible force gives is `D = C max(de, 0) + P min(de, 0)` (the support function of
//! `[P, C]`), so the virtual-work equation of a mechanism reads `lambda A = G + D`, and every
//! mechanism's `(G + D)/A` bounds the collapse multiplier from above.

use super::Rows;
use crate::geometry::Vec2;

/// Where a tie is anchored: a point of a block, or of the ground (`block = None`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Anchor {
    pub block: Option<usize>,
    /// The anchor point (m).
    pub point: Vec2,
}

/// A tie rod.
#[derive(Debug, Clone, PartialEq)]
pub struct Tie {
    pub from: Anchor,
    pub to: Anchor,
    /// The force at which it yields (N), finite and >= 0.
    pub capacity: f64,
    /// The force it carries at rest (N), `0 <= prestress <= capacity`.
    pub prestress: f64,
    /// The strain at which it breaks (elongation over its length, > 0, or infinite): the
    /// capacity curve of an assessment drops the tie once it is stretched beyond it. The limit
    /// analyses do not need it (they are rigid-plastic at the onset of motion).
    pub ultimate_strain: f64,
}

/// The default ultimate strain of a tie: 7.5 %, the least uniform elongation at maximum force
/// `A_gt` of B450C reinforcing steel (NTC 2018, 11.3.2.1).
pub const DEFAULT_ULTIMATE_STRAIN: f64 = 0.075;

/// A tie's force in a solution.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TieForce {
    /// Tension (N).
    pub force: f64,
    pub capacity: f64,
    /// Whether the force has reached the capacity (to the solver's accuracy).
    pub yielded: bool,
}

/// Relative tolerance of "yielded": a force within this fraction of the capacity.
pub const YIELD_TOLERANCE: f64 = 1e-6;

impl Tie {
    /// The tie's length (m).
    pub fn length(&self) -> f64 {
        (self.to.point - self.from.point).norm()
    }

    /// Unit vector from the `from` anchor to the `to` anchor.
    pub fn direction(&self) -> Vec2 {
        (self.to.point - self.from.point) / self.length()
    }

    /// What is wrong with the tie in an assembly of `blocks` blocks, in words (None when
    /// well formed).
    pub fn problem(&self, blocks: usize) -> Option<String> {
        let (c, p) = (self.capacity, self.prestress);
        if !(c.is_finite() && c >= 0.0) {
            return Some(format!("capacity {c} N: must be a finite number >= 0"));
        }
        if !(p.is_finite() && (0.0..=c).contains(&p)) {
            return Some(format!(
                "prestress {p} N: must be between 0 and the capacity {c} N"
            ));
        }
        if !(self.length().is_finite() && self.length() > 0.0) {
            return Some("its two anchors are the same point".into());
        }
        match (self.from.block, self.to.block) {
            (None, None) => return Some("both anchors are on the ground".into()),
            (Some(a), Some(b)) if a == b => {
                return Some(format!(
                    "both anchors are on block {a}: a tie within one rigid block carries nothing"
                ))
            }
            _ => {}
        }
        for b in [self.from.block, self.to.block].into_iter().flatten() {
            if b >= blocks {
                return Some(format!(
                    "anchored on block {b}, but there are {blocks} blocks"
                ));
            }
        }
        None
    }

    /// The tie's part of the static program: its unknown (the tension over the force scale),
    /// its pull on both anchored blocks and its bounds `P <= T <= C`. Returns its column.
    pub fn static_rows(&self, rows: &mut Rows) -> usize {
        let col = self.pull(rows);
        let fs = rows.force_scale;
        // Bounds, not relaxed by the phase-one program: a tie is no joint that could be
        // asked to carry tension (it always does), and the interval has an interior when
        // C > P.
        rows.nonnegative(vec![(col, -1.0)], -self.prestress / fs, false);
        rows.nonnegative(vec![(col, 1.0)], self.capacity / fs, false);
        col
    }

    /// [`Tie::static_rows`] with its capacity an unknown, column `capacity` (over the force
    /// scale), as a retrofit design sizes it: `P <= T <= C`. Returns the tension's column.
    pub fn static_rows_designed(&self, rows: &mut Rows, capacity: usize) -> usize {
        let col = self.pull(rows);
        let fs = rows.force_scale;
        rows.nonnegative(vec![(col, -1.0)], -self.prestress / fs, false);
        rows.nonnegative(vec![(col, 1.0), (capacity, -1.0)], 0.0, false);
        col
    }

    /// The tension's column and its pull on both anchored blocks.
    fn pull(&self, rows: &mut Rows) -> usize {
        let col = rows.add_columns(1);
        let e = self.direction();
        rows.force_on(self.from.block, col, e, self.from.point, 1.0);
        rows.force_on(self.to.block, col, e, self.to.point, -1.0);
        col
    }

    /// The largest power the tie dissipates at elongation rate `rate` (m/s, positive when
    /// the anchors move apart): `C max(rate, 0) + P min(rate, 0)`.
    pub fn dissipation(&self, rate: f64) -> f64 {
        if rate > 0.0 {
            self.capacity * rate
        } else {
            self.prestress * rate
        }
    }

    /// Elongation rate for the velocities `velocity(block, point)` of a mechanism (the
    /// ground's is zero).
    /// The power the tie absorbs in a finite configuration of a mechanism (the capacity
    /// curve of an assessment): `place` moves a point of a block (None: the ground) to where
    /// the configuration has it, `velocity` gives its velocity there. Rigid-plastic with a
    /// breaking strain: at the onset (no stretch yet) it is [`Tie::dissipation`] of the
    /// elongation rate; stretched, the tie carries its capacity while it lengthens (its
    /// prestress while it shortens) until its stretch passes `ultimate_strain` times its
    /// length, when it has broken and carries nothing; shortened from rest, it has gone slack
    /// (a prestress is an elastic stretch far smaller than any rotation the curve takes).
    pub fn power_moved(
        &self,
        place: impl Fn(Option<usize>, Vec2) -> Vec2,
        velocity: impl Fn(Option<usize>, Vec2) -> Vec2,
    ) -> f64 {
        let (from, to) = self.anchors_moved(place);
        let length = self.length();
        let now = (to - from).norm();
        let stretch = now - length;
        let slack = stretch < -1e-12 * length;
        if slack || self.broken(stretch) || now.is_nan() || now <= 0.0 {
            return 0.0;
        }
        let e = (to - from) / now;
        let rate = (velocity(self.to.block, to) - velocity(self.from.block, from)).dot(&e);
        self.dissipation(rate)
    }

    /// The stretch (m) in a finite configuration: its anchors where `place` moves them, less
    /// its length at rest.
    pub fn stretch_moved(&self, place: impl Fn(Option<usize>, Vec2) -> Vec2) -> f64 {
        let (from, to) = self.anchors_moved(place);
        (to - from).norm() - self.length()
    }

    /// The anchor points where `place` moves them (`from`, `to`).
    fn anchors_moved(&self, place: impl Fn(Option<usize>, Vec2) -> Vec2) -> (Vec2, Vec2) {
        (
            place(self.from.block, self.from.point),
            place(self.to.block, self.to.point),
        )
    }

    /// Whether a stretch (m) breaks the tie (past `ultimate_strain` times its length).
    pub fn broken(&self, stretch: f64) -> bool {
        stretch > self.ultimate_strain * self.length()
    }

    pub fn elongation_rate(&self, velocity: impl Fn(Option<usize>, Vec2) -> Vec2) -> f64 {
        let dv =
            velocity(self.to.block, self.to.point) - velocity(self.from.block, self.from.point);
        dv.dot(&self.direction())
    }

    /// The force `force` (N) read from a solution, clamped into `[P, C]` (an interior point
    /// sits a hair inside its bounds).
    pub fn force_of(&self, force: f64) -> TieForce {
        let force = force.clamp(self.prestress, self.capacity);
        TieForce {
            force,
            capacity: self.capacity,
            yielded: force >= self.capacity * (1.0 - YIELD_TOLERANCE) && self.capacity > 0.0,
        }
    }
}
