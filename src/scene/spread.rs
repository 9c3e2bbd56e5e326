//! The spread of a load through the fill (`[fill] surface`, `spread_deg`, `spread`): a
//! vertical point load that stands on the road surface (or anywhere in the fill) reaches the
//! extrados below it over a width that grows with the depth of fill, and the voussoirs under
//! that width carry it. `scene::placement` asks this file how a load of `F` newtons at
//! depth `d` is shared along x, and places the shares on the roof as it places a line load.
//!
//! Two laws, both of a load per unit depth of the model (a plane problem):
//! - **an angle** `theta` from the vertical (`spread_deg`; 26.6 deg is the 2:1 dispersal,
//!   `tan theta = 1/2`, of UK practice, e.g. CS 454 / BD 21 and the RING manual): a uniform
//!   load `F / w` over the width `w = 2 d tan theta` centred under the load. `theta = 0` (the
//!   default when no law is given) is no spread: the load acts at the extrados point below it;
//! - **Boussinesq** (`spread = "boussinesq"`): the vertical stress under a line load `F` on an
//!   elastic half-plane, Flamant's solution (Timoshenko & Goodier, Theory of Elasticity,
//!   3rd ed., §36): `q(u) = 2 F d^3 / (pi (u^2 + d^2)^2)` at horizontal offset `u` and depth
//!   `d`, which integrates to `F` over the whole line. Its share between `u0` and `u1` is
//!   `F [Q(u1) - Q(u0)]` with `Q(u) = (atan(u/d) + u d / (u^2 + d^2)) / pi`, its moment about
//!   the load's line `F [M(u1) - M(u0)]` with `M(u) = -d^3 / (pi (u^2 + d^2))`, both exact.
//!
//! The depth `d` is taken under the load: the load's height (the surface, for a vehicle's
//! axles) less the top of the structure at its x. What of the spread width falls beyond the
//! structure's top (past the springings) rests on the ground and loads no block.

use super::Section;
use crate::error::SceneError;

/// The keys this file reads from `[fill]`.
pub(super) const KEYS: &[&str] = &["surface", "spread_deg", "spread"];

/// How loads on the fill reach the structure, as the scene gave it (all optional: no key, no
/// spread and the surface at the fill's level). Serialised with the `[fill]` table only when
/// given, so a scene without these keys prints the fill as before.
#[derive(Debug, Clone, Copy, PartialEq, Default, serde::Serialize)]
pub struct Dispersal {
    /// `surface`: y of the road surface (m), where a vehicle's axles stand.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub surface: Option<f64>,
    /// `spread_deg`: the angle of spread from the vertical (degrees).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub spread_deg: Option<f64>,
    /// `spread = "boussinesq"`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub spread: Option<SpreadLaw>,
}

/// A spread law named by `spread`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum SpreadLaw {
    /// Flamant's stress under a line load on an elastic half-plane.
    Boussinesq,
}

/// The law a load spreads by.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Law {
    /// A uniform load over `2 d tan(angle)`, `angle` in radians.
    Angle(f64),
    Boussinesq,
}

impl Dispersal {
    /// The road surface: `surface`, or the fill's level.
    pub fn surface(&self, level: f64) -> f64 {
        self.surface.unwrap_or(level)
    }

    /// The law loads spread by (an angle of 0, no spread, when none is given).
    pub fn law(&self) -> Law {
        match (self.spread, self.spread_deg) {
            (Some(SpreadLaw::Boussinesq), _) => Law::Boussinesq,
            (None, deg) => Law::Angle(deg.unwrap_or(0.0).to_radians()),
        }
    }
}

/// The spread keys of `[fill]` (the rest of the table is read by the caller). The surface
/// must not be below `lowest` (the crown extrados over a parametric arch), when given.
pub(super) fn parse(s: &mut Section, lowest: Option<f64>) -> Result<Dispersal, SceneError> {
    let surface = s.opt_f64("surface")?;
    if let Some(y) = surface {
        if !(y.is_finite() && y.abs() <= super::MAX_LENGTH) {
            return Err(s.out_of_range(
                "surface",
                y,
                &format!(
                    "must be a finite y in metres within +-{:e}",
                    super::MAX_LENGTH
                ),
            ));
        }
        if let Some(crown) = lowest.filter(|&c| y < c) {
            return Err(s.out_of_range(
                "surface",
                y,
                &format!("the road surface must not be below the crown extrados, y = {crown}"),
            ));
        }
    }
    let spread_deg = s.opt_f64("spread_deg")?;
    if let Some(a) = spread_deg {
        if !(a.is_finite() && (0.0..90.0).contains(&a)) {
            return Err(s.out_of_range(
                "spread_deg",
                a,
                "must be an angle from the vertical of at least 0 and below 90 degrees (26.6 for a 2:1 dispersal)",
            ));
        }
    }
    let spread = match s.table.get("spread") {
        None => {
            s.used.insert("spread");
            None
        }
        Some(_) => {
            let word = s.string("spread", None)?;
            if word != "boussinesq" {
                return Err(s.out_of_range(
                    "spread",
                    format!("\"{word}\""),
                    "must be \"boussinesq\" (or give spread_deg for a spread at an angle)",
                ));
            }
            if spread_deg.is_some() {
                return Err(s.out_of_range(
                    "spread",
                    "\"boussinesq\"",
                    "give either spread_deg (a spread at an angle) or spread = \"boussinesq\", not both",
                ));
            }
            Some(SpreadLaw::Boussinesq)
        }
    };
    Ok(Dispersal {
        surface,
        spread_deg,
        spread,
    })
}

/// The width (m) a load at depth `depth` spreads over at the angle `angle` (radians).
pub fn width(depth: f64, angle: f64) -> f64 {
    2.0 * depth.max(0.0) * angle.tan()
}

/// The share of a unit load at depth `d > 0` that Flamant's stress puts between the offsets
/// `u0 < u1` from the load's line, and its moment about that line (see the module docs).
pub fn boussinesq_share(d: f64, u0: f64, u1: f64) -> (f64, f64) {
    let q = |u: f64| ((u / d).atan() + u * d / (u * u + d * d)) / std::f64::consts::PI;
    let m = |u: f64| -d.powi(3) / (std::f64::consts::PI * (u * u + d * d));
    (q(u1) - q(u0), m(u1) - m(u0))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn boussinesq_share_is_the_integral_of_flamant() {
        // Against a fine midpoint rule of q(u) and u q(u).
        let (d, u0, u1): (f64, f64, f64) = (0.7, -0.4, 1.3);
        let n = 200_000;
        let (mut f, mut m) = (0.0, 0.0);
        for i in 0..n {
            let u = u0 + (i as f64 + 0.5) * (u1 - u0) / n as f64;
            let q = 2.0 * d.powi(3) / (std::f64::consts::PI * (u * u + d * d).powi(2));
            f += q * (u1 - u0) / n as f64;
            m += u * q * (u1 - u0) / n as f64;
        }
        let (bf, bm) = boussinesq_share(d, u0, u1);
        assert!(
            (bf - f).abs() < 1e-9 && (bm - m).abs() < 1e-9,
            "{bf} {f} {bm} {m}"
        );
        // The whole line carries the whole load, with no moment about its line.
        let (all, moment) = boussinesq_share(d, -1e9, 1e9);
        assert!((all - 1.0).abs() < 1e-8 && moment.abs() < 1e-8);
    }
}
