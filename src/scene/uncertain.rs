//! `[uncertain]`: the scene's uncertain inputs (docs/geometry.md, docs/fragility.md). Each
//! key is the path of a scene value as `--set` writes it (`"arch.thickness"`), and its value
//! a distribution:
//!
//! ```toml
//! [uncertain]
//! "arch.thickness" = { dist = "normal", mean = 0.30, cov = 0.10 }
//! "material.friction" = { dist = "uniform", low = 0.5, high = 0.8 }
//! "fill.unit_weight" = { dist = "lognormal", median = 18000.0, beta = 0.1 }
//! ```
//!
//! Only the distributions are read here; whether each key names a value of the scene is
//! checked where the samples are applied (`crate::fragility`), with the scene's own
//! validation, and no analysis but `fragility` reads the table (the others analyse the
//! scene's own values).

use super::Table;
use crate::error::{did_you_mean, SceneError};
use crate::sampling::Distribution;
use toml::Value;

/// One uncertain input: the scene key it varies and its distribution.
#[derive(Debug, Clone, PartialEq)]
pub struct UncertainInput {
    /// The override path, e.g. `arch.thickness`.
    pub key: String,
    pub dist: Distribution,
}

const DISTS: &[&str] = &["normal", "uniform", "lognormal"];

/// The `[uncertain]` table's inputs, in the file's key order (sorted, as TOML tables are).
pub fn parse(table: &Table, origin: &str) -> Result<Vec<UncertainInput>, SceneError> {
    let mut out = Vec::with_capacity(table.len());
    for (key, value) in table {
        let name = format!("uncertain.\"{key}\"");
        if key.split('.').count() < 2 || key.split('.').any(str::is_empty) {
            return Err(SceneError::OutOfRange {
                origin: origin.into(),
                key: name,
                value: format!("\"{key}\""),
                allowed: "the key of an uncertain input is the path of a scene value as --set writes it, e.g. \"arch.thickness\"".into(),
            });
        }
        if key.starts_with("uncertain.") {
            return Err(SceneError::OutOfRange {
                origin: origin.into(),
                key: name,
                value: format!("\"{key}\""),
                allowed: "an uncertain input cannot vary the [uncertain] table itself".into(),
            });
        }
        let Value::Table(t) = value else {
            return Err(SceneError::WrongType {
                origin: origin.into(),
                key: name,
                value: value.to_string(),
                expected: "a table such as { dist = \"normal\", mean = 0.3, cov = 0.1 }".into(),
            });
        };
        out.push(UncertainInput {
            key: key.clone(),
            dist: distribution(t, &name, origin)?,
        });
    }
    Ok(out)
}

fn distribution(t: &Table, name: &str, origin: &str) -> Result<Distribution, SceneError> {
    let dist = match t.get("dist") {
        Some(Value::String(s)) => s.as_str(),
        Some(v) => {
            return Err(SceneError::WrongType {
                origin: origin.into(),
                key: format!("{name}.dist"),
                value: v.to_string(),
                expected: format!("one of \"{}\"", DISTS.join("\", \"")),
            })
        }
        None => {
            return Err(SceneError::MissingKey {
                origin: origin.into(),
                key: format!("{name}.dist"),
                what: format!("the distribution: {}", DISTS.join(", ")),
            })
        }
    };
    let params: &[&str] = match dist {
        "normal" => &["mean", "cov"],
        "uniform" => &["low", "high"],
        "lognormal" => &["median", "beta"],
        other => {
            return Err(SceneError::OutOfRange {
                origin: origin.into(),
                key: format!("{name}.dist"),
                value: format!("\"{other}\""),
                allowed: format!(
                    "one of \"{}\"{}",
                    DISTS.join("\", \""),
                    did_you_mean(other, DISTS)
                ),
            })
        }
    };
    for k in t.keys() {
        if k != "dist" && !params.contains(&k.as_str()) {
            return Err(SceneError::UnknownKey {
                origin: origin.into(),
                key: format!("{name}.{k}"),
                hint: format!(
                    "{} (a {dist} distribution takes {})",
                    did_you_mean(k, params),
                    params.join(", ")
                ),
            });
        }
    }
    let number = |k: &str| -> Result<f64, SceneError> {
        match t.get(k) {
            Some(Value::Float(x)) if x.is_finite() => Ok(*x),
            Some(Value::Integer(i)) => Ok(*i as f64),
            Some(v) => Err(SceneError::WrongType {
                origin: origin.into(),
                key: format!("{name}.{k}"),
                value: v.to_string(),
                expected: "a finite number".into(),
            }),
            None => Err(SceneError::MissingKey {
                origin: origin.into(),
                key: format!("{name}.{k}"),
                what: format!("a {dist} distribution needs {}", params.join(" and ")),
            }),
        }
    };
    let out_of_range = |k: &str, x: f64, allowed: &str| SceneError::OutOfRange {
        origin: origin.into(),
        key: format!("{name}.{k}"),
        value: x.to_string(),
        allowed: allowed.into(),
    };
    Ok(match dist {
        "normal" => {
            let (mean, cov) = (number("mean")?, number("cov")?);
            if cov < 0.0 {
                return Err(out_of_range(
                    "cov",
                    cov,
                    "a coefficient of variation >= 0 (0: the value is certain)",
                ));
            }
            Distribution::Normal { mean, cov }
        }
        "uniform" => {
            let (low, high) = (number("low")?, number("high")?);
            if high < low {
                return Err(out_of_range("high", high, &format!("at least low = {low}")));
            }
            Distribution::Uniform { low, high }
        }
        _ => {
            let (median, beta) = (number("median")?, number("beta")?);
            if median <= 0.0 {
                return Err(out_of_range("median", median, "a median > 0"));
            }
            if beta < 0.0 {
                return Err(out_of_range(
                    "beta",
                    beta,
                    "a logarithmic standard deviation >= 0 (0: the value is certain)",
                ));
            }
            Distribution::Lognormal { median, beta }
        }
    })
}
