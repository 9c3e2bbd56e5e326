//! `[[vehicles]]`: trains of axles, each a vertical point load standing on the top of the
//! structure (on the fill's road surface when there is a fill, spread through it by
//! [`super::spread`]; on the extrados otherwise), placed by `scene::placement`.
//!
//! ```toml
//! [[vehicles]]
//! name = "tandem"
//! axles = [[0.0, 150000.0], [1.2, 150000.0]]   # [position along the train (m), load (N)]
//! at = 2.0                                     # m, x of the first axle
//! live = true                                  # default true
//! ```
//!
//! Two load models are built in by name (their axles are then not given):
//! - `"EN1991-2 LM1"`: the tandem system of load model 1 in lane 1 (EN 1991-2:2003, 4.3.2
//!   and Table 4.2): two axles of `Q1k = 300 kN` 1.2 m apart (adjustment factor
//!   `alpha_Q1 = 1`). Lanes 2 and 3 carry 200 kN and 100 kN axles: give those as `axles`.
//!   The uniformly distributed part of LM1 (9 kN/m^2 in lane 1) is not part of the tandem:
//!   add it as a `[[loads]]` line load if wanted;
//! - `"EN1991-2 LM71"`: load model 71 (EN 1991-2:2003, 6.3.2 and Figure 6.1): four axles of
//!   `Qvk = 250 kN` 1.6 m apart, and `qvk = 80 kN/m` beyond them, from 0.8 m past the first
//!   and the last axle to the ends of the structure's top (classification factor
//!   `alpha = 1`). The distributed part is a line load on each side (not spread: a uniform
//!   load stays uniform through the fill); the code's rule that it is applied on the
//!   unfavourable parts only is left to the user (write the axles and a one-sided line load).
//!
//! Loads are per the model's depth (`material.depth`): a lane's axle on a barrel wider than
//! the modelled depth must be scaled by the user (the share of the axle the modelled strip
//! carries). Under a live action the adequacy factor is linear in the live loads, so the
//! factor of a share `s` of a vehicle is `lambda / s`.

use super::{short, Section, MAX_FORCE, MAX_LENGTH};
use crate::error::SceneError;
use toml::{Table, Value};

/// A vehicle as the user wrote it (or as a built-in model names it).
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct VehicleSpec {
    /// `name` (a built-in load model's, or the user's own).
    pub name: String,
    /// `(position along the train from its first axle (m), load (N, downward))`.
    pub axles: Vec<(f64, f64)>,
    /// A uniformly distributed load `(intensity (N/m), gap (m))` beyond the axles: from `gap`
    /// past the first and the last axle to the ends of the structure's top (LM71's 80 kN/m).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub beyond: Option<(f64, f64)>,
    /// `at`: x of the first axle (m).
    pub at: f64,
    /// Whether the vehicle is live (multiplied by lambda under `[action] kind = "live"`).
    pub live: bool,
}

impl VehicleSpec {
    /// The axles' x (m) and loads (N).
    pub fn axle_positions(&self) -> impl Iterator<Item = (f64, f64)> + '_ {
        self.axles.iter().map(move |&(p, f)| (self.at + p, f))
    }

    /// The x-range of the axles (m): the first and the last axle's x.
    pub fn extent(&self) -> (f64, f64) {
        self.axle_positions()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), (x, _)| {
                (lo.min(x), hi.max(x))
            })
    }
}

/// The built-in load models: name, axles, and the distributed part beyond them.
type BuiltIn = (&'static str, &'static [(f64, f64)], Option<(f64, f64)>);

/// The load models built in by name (see the module docs for their sources).
pub const BUILT_IN: &[BuiltIn] = &[
    ("EN1991-2 LM1", &[(0.0, 300e3), (1.2, 300e3)], None),
    (
        "EN1991-2 LM71",
        &[(0.0, 250e3), (1.6, 250e3), (3.2, 250e3), (4.8, 250e3)],
        Some((80e3, 0.8)),
    ),
];

const VEHICLE_KEYS: &[&str] = &["name", "axles", "at", "live"];

/// The `[[vehicles]]` list of a scene (empty when absent).
pub(super) fn parse(table: &Table, origin: &str) -> Result<Vec<VehicleSpec>, SceneError> {
    let items = super::entries(table, "vehicles", origin)?;
    let mut vehicles = Vec::with_capacity(items.len());
    let names = BUILT_IN
        .iter()
        .map(|b| format!("\"{}\"", b.0))
        .collect::<Vec<_>>()
        .join(", ");
    for (k, t) in items.into_iter().enumerate() {
        let mut s = Section::new(format!("vehicles[{k}]"), t, origin);
        s.check_known(VEHICLE_KEYS, "")?;
        let name = s.string("name", Some(&format!("vehicles[{k}]")))?;
        let built_in = BUILT_IN.iter().find(|b| b.0 == name);
        s.used.insert("axles");
        let (axles, beyond) = match (built_in, t.get("axles")) {
            (Some(_), Some(v)) => {
                return Err(s.out_of_range(
                    "axles",
                    crate::error::excerpt(&v.to_string()),
                    &format!("name = \"{name}\" is a built-in load model with its own axles: leave axles out, or give the vehicle another name"),
                ))
            }
            (Some(b), None) => (b.1.to_vec(), b.2),
            (None, Some(v)) => (axles(&s, v)?, None),
            (None, None) => {
                return Err(s.missing(
                    "axles",
                    &format!("the axles [[position (m), load (N)], ...], or a built-in name ({names})"),
                ))
            }
        };
        let at = s.finite("at", "x of the first axle in metres")?;
        if at.abs() > MAX_LENGTH {
            return Err(s.out_of_range(
                "at",
                short(at),
                &format!("must lie within +-{MAX_LENGTH:e} m"),
            ));
        }
        let live = s.boolean("live", true)?;
        s.finish("")?;
        vehicles.push(VehicleSpec {
            name,
            axles,
            beyond,
            at,
            live,
        });
    }
    Ok(vehicles)
}

/// The `axles` list: `[position, load]` pairs, positions within the length bound, loads from
/// 0 to [`MAX_FORCE`], at least one axle.
fn axles(s: &Section, v: &Value) -> Result<Vec<(f64, f64)>, SceneError> {
    let form = "a list of [position (m), load (N)] pairs, e.g. [[0.0, 150000.0], [1.2, 150000.0]]";
    let Value::Array(items) = v else {
        return Err(s.wrong_type("axles", v, form));
    };
    if items.is_empty() {
        return Err(s.out_of_range("axles", "[]", "a vehicle needs at least one axle"));
    }
    let num = |x: &Value| match x {
        Value::Float(f) => Some(*f),
        Value::Integer(i) => Some(*i as f64),
        _ => None,
    };
    items
        .iter()
        .map(|item| {
            let pair = match item {
                Value::Array(p) if p.len() == 2 => num(&p[0]).zip(num(&p[1])),
                _ => None,
            };
            let (pos, load) = pair.ok_or_else(|| s.wrong_type("axles", item, form))?;
            if !(pos.is_finite() && pos.abs() <= MAX_LENGTH) {
                return Err(s.out_of_range(
                    "axles",
                    item,
                    &format!("an axle's position must be finite, within +-{MAX_LENGTH:e} m"),
                ));
            }
            if !(load.is_finite() && (0.0..=MAX_FORCE).contains(&load)) {
                return Err(s.out_of_range(
                    "axles",
                    item,
                    &format!("an axle's load must be from 0 to {MAX_FORCE:e} N (downward)"),
                ));
            }
            Ok((pos, load))
        })
        .collect()
}
