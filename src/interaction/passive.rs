//! Passive resistance of the fill: where a block's face lies against the fill (an arch's
//! extrados under `[fill]`, or a block's side with fill beside it), the fill resists that face
//! being pushed into it with a horizontal reaction up to its mobilised passive force
//!
//! `P = m_p K_p gamma d ∫ (L - y) dy` over the face's vertical extent below the fill level `L`,
//!
//! i.e. `m_p K_p sigma_v h` with `sigma_v = gamma (L - y_m)` the fill's vertical stress at the
//! face's mid-depth `y_m`, `h` its vertical extent under the level, `gamma d` the unit weight
//! times the scene's depth, Rankine's passive coefficient `K_p = tan^2(45° + phi/2)` and the
//! mobilisation `m_p` (0.33 by default: a third of the full passive pressure, which needs
//! large movements to develop; the default is issue 29's, not traced to a published page).
//! The horizontal pressure of the fill growing linearly with depth against the extrados, and
//! mobilised only where the arch sways into the fill, is the model of Gelfi, "Role of
//! horizontal backfill passive pressure on the stability of masonry vaults", Int. J. for
//! Restoration of Buildings and Monuments 8(6), 573-590 (2002), and of the fill's "passive
//! restraint" in the RING software for masonry arch bridges (LimitState Ltd, after Gilbert's
//! rigid-block analysis), which the Italian guidelines for masonry arch bridges
//! (CNR-DT 213/2015) name among the fill's effects.
//!
//! The reaction is **one-sided** and **horizontal**: the fill pushes the face back (along
//! `-into`, where `into = ±1` is the sign of the face's outward normal's horizontal component,
//! the direction in which the face moves into the fill), never pulls it. An extrados edge on
//! the left haunch (outward normal up and to the left) resists motion toward -x, one on the right
//! haunch motion toward +x: whichever way the arch sways, the faces that move into the fill are
//! on the side it sways into, and the mechanism decides which (a face that moves away from the
//! fill dissipates nothing). The pressure's resultant over the face acts at the centroid
//! of the pressure diagram, `y_p = ∫ y (L - y) dy / ∫ (L - y) dy`; its horizontal component
//! depends only on the face's end heights (`∫ p n_x ds = ∫ p dy`), so a curved extrados edge
//! and its chord carry the same force. The active pressure on the side that moves away is not
//! counted (the fill's weight already rests on the extrados as a vertical load).
//!
//! Static rows: one unknown `R` per face (over the force scale), `0 <= R <= P`, the force
//! `-into R e_x` on the face's block at `point` (rigid-plastic: any reaction between none and the
//! cap is admissible, so the lower-bound theorem holds with it).
//!
//! Work rate: with the horizontal velocity `v_x` of the block's point at `point` in a
//! mechanism, the largest power the reaction can dissipate is `P max(into v_x, 0)` (the support
//! function of `[0, P]`), which the virtual-work equation adds to the work against the
//! permanent loads, as a tie's or a strip's.
//!
//! DEM: a capped one-sided spring (see `crate::dem`), elastic-perfectly-plastic.

use super::Rows;
use crate::geometry::Vec2;

/// The default mobilisation of the passive pressure, `[fill] passive_mobilisation`.
pub const DEFAULT_MOBILISATION: f64 = 0.33;

/// Rankine's passive earth pressure coefficient `K_p = tan^2(pi/4 + phi/2)` for the fill's
/// angle of friction `phi` (radians).
pub fn rankine_kp(phi: f64) -> f64 {
    let t = (std::f64::consts::FRAC_PI_4 + 0.5 * phi).tan();
    t * t
}

/// A face of a block against the fill, with the passive reaction it can take.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Passive {
    /// The block (assembly index).
    pub block: usize,
    /// The face's ends (m), clipped to the fill level.
    pub a: Vec2,
    pub b: Vec2,
    /// The direction (+1: +x, -1: -x) in which the face moves into the fill.
    pub into: f64,
    /// Where the reaction acts (m): on the chord `a b` at the height of the pressure's
    /// centroid.
    pub point: Vec2,
    /// The largest reaction (N), finite and >= 0.
    pub cap: f64,
}

/// A face's reaction in a solution.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PassiveForce {
    /// The reaction (N, >= 0), pushing the face out of the fill.
    pub force: f64,
    pub cap: f64,
    /// Whether it has reached its cap (the fill yields there), to the solver's accuracy.
    pub yielded: bool,
}

impl Passive {
    /// The face from `a` to `b` of `block` (either order), moving into the fill along `into`,
    /// under a fill of level `level` whose pressure per unit depth below the level is
    /// `coefficient` (N/m^3: `m_p K_p gamma d`). None when no part of it lies below the level
    /// or the part that does has no vertical extent.
    pub fn face(
        block: usize,
        a: Vec2,
        b: Vec2,
        into: f64,
        level: f64,
        coefficient: f64,
    ) -> Option<Passive> {
        let (lo, hi) = if a.y <= b.y { (a, b) } else { (b, a) };
        if lo.y >= level {
            return None;
        }
        let at = |y: f64| {
            let t = if hi.y > lo.y {
                (y - lo.y) / (hi.y - lo.y)
            } else {
                0.0
            };
            lo + t * (hi - lo)
        };
        let top = if hi.y > level { at(level) } else { hi };
        let (y0, y1) = (lo.y, top.y);
        let h = y1 - y0;
        if h <= 1e-12 * (1.0 + level.abs()) {
            return None;
        }
        // ∫ (L - y) dy and ∫ y (L - y) dy over [y0, y1].
        let force = level * h - 0.5 * (y1 * y1 - y0 * y0);
        let moment = 0.5 * level * (y1 * y1 - y0 * y0) - (y1 * y1 * y1 - y0 * y0 * y0) / 3.0;
        let yp = moment / force;
        Some(Passive {
            block,
            a: lo,
            b: top,
            into,
            point: at(yp),
            cap: coefficient * force,
        })
    }

    /// What is wrong with the face in an assembly of `blocks` blocks, in words (None when well
    /// formed).
    pub fn problem(&self, blocks: usize) -> Option<String> {
        if !(self.cap.is_finite() && self.cap >= 0.0) {
            return Some(format!("cap {} N: must be a finite number >= 0", self.cap));
        }
        if self.into.abs() != 1.0 {
            return Some(format!("direction {}: must be +1 or -1", self.into));
        }
        (self.block >= blocks)
            .then(|| format!("on block {}, but there are {blocks} blocks", self.block))
    }

    /// The unit force the reaction applies to the block (away from the fill).
    pub fn direction(&self) -> Vec2 {
        Vec2::new(-self.into, 0.0)
    }

    /// The reaction's part of the static program: its unknown, its force on the block and its
    /// bounds `0 <= R <= P`. Returns its column.
    pub fn static_rows(&self, rows: &mut Rows) -> usize {
        let col = rows.add_columns(1);
        rows.force_on(Some(self.block), col, self.direction(), self.point, 1.0);
        rows.nonnegative(vec![(col, -1.0)], 0.0, false);
        rows.nonnegative(vec![(col, 1.0)], self.cap / rows.force_scale, false);
        col
    }

    /// The largest power it dissipates when its point moves horizontally at `vx`.
    pub fn dissipation(&self, vx: f64) -> f64 {
        self.cap * (self.into * vx).max(0.0)
    }

    /// The reaction `force` (N) read from a solution, clamped into `[0, P]`.
    pub fn force_of(&self, force: f64) -> PassiveForce {
        let force = force.clamp(0.0, self.cap);
        PassiveForce {
            force,
            cap: self.cap,
            yielded: self.cap > 0.0 && force >= self.cap * (1.0 - super::tie::YIELD_TOLERANCE),
        }
    }

    /// The same face mirrored about x = 0, on block `block` of the mirror.
    pub fn mirrored(&self, block: usize) -> Passive {
        use crate::geometry::mirror;
        Passive {
            block,
            a: mirror(self.a),
            b: mirror(self.b),
            into: -self.into,
            point: mirror(self.point),
            cap: self.cap,
        }
    }
}

/// Whether the passive reactions govern a collapse: some reaction is at its cap, i.e. the fill
/// yields in the mechanism (a reaction below its cap does no work in it).
pub fn governs(forces: &[PassiveForce]) -> bool {
    forces.iter().any(|f| f.yielded && f.force > 0.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn vertical_face_takes_the_rankine_triangle() {
        // A vertical face from y = 0 to 2 under a level at 1.5: P = c L^2/2, at L/3.
        let f = Passive::face(0, Vec2::new(1.0, 2.0), Vec2::new(1.0, 0.0), 1.0, 1.5, 10.0)
            .expect("face under the level");
        assert!((f.cap - 10.0 * 1.5 * 1.5 / 2.0).abs() < 1e-12);
        assert!((f.point.y - 0.5).abs() < 1e-12);
        assert!((f.point.x - 1.0).abs() < 1e-12);
        assert!(
            Passive::face(0, Vec2::new(0.0, 2.0), Vec2::new(1.0, 3.0), 1.0, 1.5, 1.0).is_none()
        );
        assert!((rankine_kp(30f64.to_radians()) - 3.0).abs() < 1e-12);
    }
}
