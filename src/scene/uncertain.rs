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
//! Inputs may be given a rank (Spearman) correlation, pair by pair, imposed on the Latin
//! hypercube samples by Iman and Conover's reordering ([`crate::sampling`]); inputs not named
//! in a pair are independent:
//!
//! ```toml
//! correlation = [
//!   { between = ["arch.thickness", "fill.unit_weight"], rank = 0.5 },
//! ]
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

/// The key of `[uncertain]` that holds the correlations (a key of one segment: no scene
/// path, so no input, can be named so).
pub const CORRELATION: &str = "correlation";

/// A rank correlation between two uncertain inputs.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct RankCorrelation {
    /// The two inputs' keys, as `[uncertain]` names them.
    pub between: [String; 2],
    /// Spearman's rank correlation, in (-1, 1).
    pub rank: f64,
}

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
        if key == CORRELATION {
            continue;
        }
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

/// `[uncertain] correlation`: the rank correlations between `inputs` (empty when not given).
/// Each pair names two different inputs of the table, once; the whole set must be a possible
/// correlation matrix (positive definite in the Pearson form the sampling imposes).
pub fn parse_correlation(
    table: &Table,
    inputs: &[UncertainInput],
    origin: &str,
) -> Result<Vec<RankCorrelation>, SceneError> {
    let Some(value) = table.get(CORRELATION) else {
        return Ok(Vec::new());
    };
    let wrong = |key: String, value: &Value, expected: &str| SceneError::WrongType {
        origin: origin.into(),
        key,
        value: value.to_string(),
        expected: expected.into(),
    };
    let pair_shape = "a table { between = [\"arch.thickness\", \"fill.unit_weight\"], rank = 0.5 }";
    let Value::Array(items) = value else {
        return Err(wrong(
            "uncertain.correlation".into(),
            value,
            &format!("an array of pairs, each {pair_shape}"),
        ));
    };
    let mut out: Vec<RankCorrelation> = Vec::with_capacity(items.len());
    for (i, item) in items.iter().enumerate() {
        let name = format!("uncertain.correlation[{i}]");
        let Value::Table(t) = item else {
            return Err(wrong(name, item, pair_shape));
        };
        for k in t.keys() {
            if k != "between" && k != "rank" {
                return Err(SceneError::UnknownKey {
                    origin: origin.into(),
                    key: format!("{name}.{k}"),
                    hint: format!(
                        "{} (a correlation takes between and rank)",
                        did_you_mean(k, &["between", "rank"])
                    ),
                });
            }
        }
        let keys: Vec<&str> = match t.get("between") {
            Some(Value::Array(a)) if a.len() == 2 && a.iter().all(Value::is_str) => {
                a.iter().filter_map(Value::as_str).collect()
            }
            Some(v) => {
                return Err(wrong(
                    format!("{name}.between"),
                    v,
                    "two keys of [uncertain], e.g. [\"arch.thickness\", \"fill.unit_weight\"]",
                ))
            }
            None => {
                return Err(SceneError::MissingKey {
                    origin: origin.into(),
                    key: format!("{name}.between"),
                    what: "the two inputs it correlates".into(),
                })
            }
        };
        let known: Vec<&str> = inputs.iter().map(|u| u.key.as_str()).collect();
        for k in &keys {
            if !known.contains(k) {
                return Err(SceneError::OutOfRange {
                    origin: origin.into(),
                    key: format!("{name}.between"),
                    value: format!("\"{k}\""),
                    allowed: format!(
                        "a key of [uncertain]: {}{}",
                        known.join(", "),
                        did_you_mean(k, &known)
                    ),
                });
            }
        }
        if keys[0] == keys[1] {
            return Err(SceneError::OutOfRange {
                origin: origin.into(),
                key: format!("{name}.between"),
                value: format!("[\"{}\", \"{}\"]", keys[0], keys[1]),
                allowed: "two different inputs (an input is fully correlated with itself)".into(),
            });
        }
        let rank = match t.get("rank") {
            Some(Value::Float(x)) => *x,
            Some(Value::Integer(x)) => *x as f64,
            Some(v) => return Err(wrong(format!("{name}.rank"), v, "a number in (-1, 1)")),
            None => {
                return Err(SceneError::MissingKey {
                    origin: origin.into(),
                    key: format!("{name}.rank"),
                    what: "Spearman's rank correlation, in (-1, 1)".into(),
                })
            }
        };
        if !(rank > -1.0 && rank < 1.0) {
            return Err(SceneError::OutOfRange {
                origin: origin.into(),
                key: format!("{name}.rank"),
                value: rank.to_string(),
                allowed: "a rank correlation strictly between -1 and 1 (+-1 would make one input a function of the other: give it as one input)".into(),
            });
        }
        let pair = [keys[0].to_string(), keys[1].to_string()];
        if let Some(j) = out.iter().position(|c| {
            (c.between[0] == pair[0] && c.between[1] == pair[1])
                || (c.between[0] == pair[1] && c.between[1] == pair[0])
        }) {
            return Err(SceneError::OutOfRange {
                origin: origin.into(),
                key: format!("{name}.between"),
                value: format!("[\"{}\", \"{}\"]", pair[0], pair[1]),
                allowed: format!("each pair once (uncertain.correlation[{j}] gives it already)"),
            });
        }
        out.push(RankCorrelation {
            between: pair,
            rank,
        });
    }
    let matrix = correlation_matrix(inputs, &out);
    if crate::sampling::rank_correlation_factor(&matrix).is_none() {
        return Err(SceneError::OutOfRange {
            origin: origin.into(),
            key: "uncertain.correlation".into(),
            value: out
                .iter()
                .map(|c| format!("{} ~ {}: {}", c.between[0], c.between[1], c.rank))
                .collect::<Vec<_>>()
                .join("; "),
            allowed: "correlations that can hold together (their matrix positive definite): e.g. a ~ b and a ~ c both near 1 with b ~ c near -1 cannot".into(),
        });
    }
    Ok(out)
}

/// The inputs' rank correlation matrix (`k x k`, unit diagonal, 0 where no pair is given).
pub fn correlation_matrix(inputs: &[UncertainInput], pairs: &[RankCorrelation]) -> Vec<Vec<f64>> {
    let k = inputs.len();
    let mut m = vec![vec![0.0; k]; k];
    for (i, row) in m.iter_mut().enumerate() {
        row[i] = 1.0;
    }
    let index = |key: &str| inputs.iter().position(|u| u.key == key);
    for c in pairs {
        if let (Some(a), Some(b)) = (index(&c.between[0]), index(&c.between[1])) {
            m[a][b] = c.rank;
            m[b][a] = c.rank;
        }
    }
    m
}
