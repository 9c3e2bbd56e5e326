//! Parametric sweeps: the cartesian product of varied scene keys, each case analysed
//! independently (in parallel), rows returned in a deterministic order (the first varied key
//! changes slowest). Besides scene keys, the dimensionless ratios the paper plots can be
//! varied directly: `t/R`, `e/R`, `h/R`, `b/R` (R the centreline radius), `t/span` and
//! `rise/span` (span the centreline span), each setting the underlying scene key, and
//! `e/span`, which sets a pointed arch's eccentricity while keeping its span (so R changes).

use crate::analysis::{self, Options};
use crate::assembly::{Hinge, JointEnd};
use crate::error::SceneError;
use crate::scene::{parse_assignment, Scene};
use crate::statics::StaticSettings;
use rayon::prelude::*;
use toml::Value;

/// Dimensionless keys that can be varied instead of scene keys.
pub const DERIVED_KEYS: &[&str] = &[
    "t/R",
    "e/R",
    "h/R",
    "b/R",
    "t/span",
    "rise/span",
    "e/span",
    "sigma",
];

/// Largest number of cases in one sweep (the product of the varied keys' value counts):
/// checked before any case is built, so three long lists are refused at once rather than
/// run for hours. A case takes 0.03 to a few milliseconds for a small arch, so this is
/// seconds to minutes on a few cores; split a larger study into several sweeps.
pub const MAX_CASES: usize = 100_000;

/// Largest number of values of one `START:STOP:STEP` range.
pub const MAX_RANGE_VALUES: usize = 100_000;

/// The number of cases of `variations` (the product of their value counts), or None when it
/// overflows.
pub fn case_count(variations: &[Variation]) -> Option<usize> {
    variations
        .iter()
        .try_fold(1usize, |n, v| n.checked_mul(v.values.len()))
}

/// One varied key and its values.
#[derive(Debug, Clone, PartialEq)]
pub struct Variation {
    pub key: String,
    pub values: Vec<Value>,
}

/// Parse `KEY=V1,V2,...` or `KEY=START:STOP:STEP` (STOP included when reached within
/// round-off).
pub fn parse_variation(text: &str) -> Result<Variation, SceneError> {
    let bad = |message: String| SceneError::BadVariation {
        text: text.to_string(),
        message,
    };
    let (key, spec) = text
        .split_once('=')
        .ok_or_else(|| bad("expected KEY=V1,V2,... or KEY=START:STOP:STEP".into()))?;
    let key = key.trim().to_string();
    let spec = spec.trim();
    if key.is_empty() || spec.is_empty() {
        return Err(bad("empty key or values".into()));
    }
    let values = if spec.contains(':') {
        let parts: Vec<&str> = spec.split(':').collect();
        let nums: Vec<f64> = parts
            .iter()
            .map(|p| p.trim().parse::<f64>())
            .collect::<Result<_, _>>()
            .map_err(|_| bad(format!("`{spec}`: START:STOP:STEP must be three numbers")))?;
        let [start, stop, step] = nums[..] else {
            return Err(bad(format!(
                "`{spec}`: START:STOP:STEP must be three numbers"
            )));
        };
        if !(start.is_finite() && stop.is_finite() && step.is_finite())
            || step <= 0.0
            || stop < start
        {
            return Err(bad(format!(
                "`{spec}`: need finite START <= STOP and STEP > 0"
            )));
        }
        // Counted in floating point, so a range of 2^70 values is refused rather than wrapped.
        let intervals = ((stop - start) / step + 1e-9).floor();
        if intervals + 1.0 > MAX_RANGE_VALUES as f64 {
            return Err(bad(format!(
                "`{spec}` gives {} values; at most {MAX_RANGE_VALUES}",
                short_count(intervals + 1.0)
            )));
        }
        let count = intervals as usize + 1;
        let whole: Vec<Option<i64>> = parts.iter().map(|p| p.trim().parse::<i64>().ok()).collect();
        // The decimals the user wrote in START and STEP: every value start + i * step is
        // rounded to them, so 1.8:2:0.025 gives 1.825, not 1.8250000000000002.
        let places = match (decimals(parts[0]), decimals(parts[2])) {
            (Some(a), Some(b)) => Some(a.max(b)),
            _ => None,
        };
        (0..count)
            .map(|i| {
                // Whole-number ranges (voussoirs, courses) stay integers.
                if let [Some(a), Some(_), Some(st)] = whole[..] {
                    if let Some(v) = i64::try_from(i)
                        .ok()
                        .and_then(|i| st.checked_mul(i))
                        .and_then(|d| a.checked_add(d))
                    {
                        return Value::Integer(v);
                    }
                }
                Value::Float(rounded(start + step * i as f64, places))
            })
            .collect()
    } else {
        spec.split(',')
            .map(|v| parse_assignment(&format!("{key}={}", v.trim())).map(|(_, v)| v))
            .collect::<Result<Vec<_>, _>>()?
    };
    Ok(Variation { key, values })
}

/// The number of decimal places written in a number (`0.025`: 3, `2`: 0); None in exponent
/// form (`1e-3`), where the places are not what was written.
fn decimals(text: &str) -> Option<usize> {
    let t = text.trim();
    if t.contains(['e', 'E']) {
        return None;
    }
    Some(t.split_once('.').map_or(0, |(_, frac)| frac.len()))
}

/// `x` rounded to `places` decimals when known (and at most 15), else to 12 significant
/// digits: the value of a range as the user meant it, without the noise of `start + i * step`.
fn rounded(x: f64, places: Option<usize>) -> f64 {
    match places {
        Some(p) if p <= 15 => format!("{x:.p$}").parse().unwrap_or(x),
        _ => tidy(x),
    }
}

/// `x` to 12 significant digits: a ratio of the user's inputs (a ratio of two lengths) as it
/// is reported, without the last bits of round-off, so it prints as the user would write it
/// (0.5, not 0.49999999999999994). 12 digits is far beyond any input's precision and far
/// above the round-off of a few operations.
pub fn tidy(x: f64) -> f64 {
    significant(x, 12)
}

/// `x` rounded to `digits` significant digits.
fn significant(x: f64, digits: usize) -> f64 {
    if !x.is_finite() || x == 0.0 || digits == 0 {
        return x;
    }
    let p = digits - 1;
    format!("{x:.p$e}").parse().unwrap_or(x)
}

/// A scene value set from a ratio (`t/R` times R) to 15 significant digits: the round-off of
/// the product goes (t/R = 0.1825 at R = 10 sets 1.825, not 1.8250000000000002) and the
/// ratio reads back from the scene to 5e-15.
fn set_value(x: f64) -> f64 {
    significant(x, 15)
}

/// A count that may exceed any integer type, in words (`1180591620717411303424` as `1.2e21`).
fn short_count(n: f64) -> String {
    if n < 1e15 {
        format!("{n}")
    } else {
        format!("{n:.1e}")
    }
}

/// The scene keys a varied key sets (a ratio sets its underlying key).
fn targets(key: &str) -> Vec<&str> {
    match key {
        "t/R" | "t/span" => vec!["arch.thickness"],
        "e/R" => vec!["arch.eccentricity"],
        "e/span" => vec!["arch.eccentricity", "arch.radius"],
        "rise/span" => vec!["arch.rise"],
        "h/R" => vec!["piers.height"],
        "b/R" => vec!["piers.width"],
        "sigma" => vec!["material.compressive_strength"],
        other => vec![other],
    }
}

/// A value as the user typed it (strings without their TOML quotes).
fn value_text(v: &Value) -> String {
    match v {
        Value::String(s) => s.clone(),
        other => other.to_string(),
    }
}

/// Check the varied keys before anything is solved: no key varied twice (directly or through
/// a ratio that sets the same scene key), every key known to the scene format, and every
/// value of a type the key takes (a ratio takes numbers; `arch.thickness=0.1,abc` is refused,
/// not solved as a row with status `error`). Values out of range are the cases' own business:
/// they stay in the sweep as rows with status `error`.
pub fn check_variations(base: &Scene, variations: &[Variation]) -> Result<(), SceneError> {
    check_case_count(variations)?;
    let mut set: Vec<(&str, &str)> = Vec::new();
    for v in variations {
        if v.key.contains('/') && !DERIVED_KEYS.contains(&v.key.as_str()) {
            return Err(SceneError::BadVariation {
                text: v.key.clone(),
                message: format!(
                    "unknown ratio `{}`{} (ratios: {}; scene keys are SECTION.KEY, e.g. arch.thickness)",
                    v.key,
                    crate::error::did_you_mean(&v.key, DERIVED_KEYS),
                    DERIVED_KEYS.join(", ")
                ),
            });
        }
        for t in targets(&v.key) {
            if let Some((other, _)) = set.iter().find(|(_, s)| *s == t) {
                return Err(SceneError::BadVariation {
                    text: v.key.clone(),
                    message: if *other == v.key {
                        "this key is varied twice".to_string()
                    } else {
                        format!("sets `{t}`, which `--vary {other}` already sets")
                    },
                });
            }
            set.push((&v.key, t));
        }
    }
    for v in variations {
        if v.values.is_empty() {
            return Err(SceneError::BadVariation {
                text: v.key.clone(),
                message: "no values".into(),
            });
        }
        // Each kind of value (number, whole number, string, ...) is tried once on the base
        // scene: a value of the wrong type is refused whatever the other keys are.
        let mut tried: Vec<std::mem::Discriminant<Value>> = Vec::new();
        for value in &v.values {
            let kind = std::mem::discriminant(value);
            if tried.contains(&kind) {
                continue;
            }
            tried.push(kind);
            check_value(base, &v.key, value)?;
        }
    }
    Ok(())
}

/// Refuse a sweep of more than [`MAX_CASES`] cases, naming the keys and their counts.
pub fn check_case_count(variations: &[Variation]) -> Result<(), SceneError> {
    let count = case_count(variations);
    if count.is_some_and(|n| n <= MAX_CASES) {
        return Ok(());
    }
    let keys: Vec<&str> = variations.iter().map(|v| v.key.as_str()).collect();
    let counts: Vec<String> = variations
        .iter()
        .map(|v| v.values.len().to_string())
        .collect();
    let total = count.map_or_else(
        || {
            // Beyond usize: say it in floating point.
            let x: f64 = variations.iter().map(|v| v.values.len() as f64).product();
            format!("{x:.1e}")
        },
        |n| n.to_string(),
    );
    Err(SceneError::BadVariation {
        text: keys.join(", "),
        message: format!(
            "{} values make {total} cases; a sweep may have at most {MAX_CASES} (voussoir::sweep::MAX_CASES): vary fewer values, or split the sweep",
            counts.join(" x ")
        ),
    })
}

/// Refuse a varied value the key cannot take at all (unknown key, wrong type, a ratio that
/// is not a number); a value out of range is left to its case.
fn check_value(base: &Scene, key: &str, value: &Value) -> Result<(), SceneError> {
    let text = format!("{key}={}", value_text(value));
    if DERIVED_KEYS.contains(&key) && !matches!(value, Value::Float(_) | Value::Integer(_)) {
        return Err(SceneError::BadVariation {
            text,
            message: format!(
                "`{}` is not a number (the ratio {key} takes numbers)",
                value_text(value)
            ),
        });
    }
    match apply(base, &[(key, value)]) {
        Err(e @ SceneError::UnknownKey { .. }) => Err(SceneError::BadVariation {
            text,
            message: e.to_string(),
        }),
        Err(SceneError::WrongType { expected, .. }) => Err(SceneError::BadVariation {
            message: format!("`{key}` takes {expected}, not `{}`", value_text(value)),
            text,
        }),
        Err(SceneError::BadOverride { message, .. }) => {
            Err(SceneError::BadVariation { text, message })
        }
        _ => Ok(()),
    }
}

/// Apply `key = value` pairs to a scene: scene keys first (together), then the
/// [`DERIVED_KEYS`] ratios (together), computed from the radius or span of the result.
pub fn apply(scene: &Scene, pairs: &[(&str, &Value)]) -> Result<Scene, SceneError> {
    let (derived, plain): (Vec<_>, Vec<_>) =
        pairs.iter().partition(|(k, _)| DERIVED_KEYS.contains(k));
    let plain: Vec<(&str, Value)> = plain.iter().map(|(k, v)| (*k, (*v).clone())).collect();
    let scene = if plain.is_empty() {
        scene.clone()
    } else {
        scene.with_values(&plain)?
    };
    if derived.is_empty() {
        return Ok(scene);
    }
    // Shape ratios first, then the sizes measured on the reshaped arch: `t/span` together
    // with `e/R` must use the span of the pointed arch with that eccentricity, not the span
    // of the base scene.
    let mut scene = scene;
    for phase in [SHAPE_KEYS, SIZE_KEYS, STRENGTH_KEYS] {
        let mut targets = Vec::new();
        for (k, v) in derived.iter().filter(|(k, _)| phase.contains(k)) {
            targets.extend(derived_target(&scene, k, v)?);
        }
        if !targets.is_empty() {
            scene = scene.with_values(&targets)?;
        }
    }
    Ok(scene)
}

/// Ratios that change the shape of the arch (applied first).
const SHAPE_KEYS: &[&str] = &["e/R", "e/span", "rise/span"];
/// Ratios that size the ring or the piers on the shaped arch (applied second).
const SIZE_KEYS: &[&str] = &["t/R", "t/span", "h/R", "b/R"];
/// The strength ratio, measured on the sized structure (applied last).
const STRENGTH_KEYS: &[&str] = &["sigma"];

/// The strength ratio `sigma = W/(fc d t)` of a scene: the weight W of its blocks (N) over
/// the force its arch ring's section carries at the compressive strength, `fc d t` (depth d,
/// ring thickness t). For a circular arch W = gamma d A with A proportional to R t, so sigma
/// is gamma R / fc times a shape factor: with the shape ratios it fixes lambda (scaling the
/// scene by k and fc by k keeps it). 0 for rigid joints (fc = inf).
pub fn sigma(scene: &Scene) -> Result<f64, SceneError> {
    let fc = scene.material.compressive_strength;
    if !fc.is_finite() {
        return Ok(0.0);
    }
    let t = scene.parametric("the strength ratio sigma")?.thickness;
    let weight = crate::scene::build(scene)?.assembly.total_weight();
    Ok(weight / (fc * scene.material.depth * t))
}

/// The scene key and value a ratio stands for.
fn derived_target(
    scene: &Scene,
    key: &str,
    value: &Value,
) -> Result<Vec<(&'static str, Value)>, SceneError> {
    let v = match value {
        Value::Float(x) => *x,
        Value::Integer(i) => *i as f64,
        other => {
            return Err(SceneError::BadOverride {
                text: format!("{key}={other}"),
                message: "a ratio must be a number".into(),
            })
        }
    };
    let shape = &scene.parametric("a ratio")?.shape;
    let radius = shape.radius();
    let has_key = |k: &str| shape.keys().iter().any(|(key, _)| *key == k);
    let need_radius = || SceneError::BadOverride {
        text: format!("{key}={v}"),
        message: format!("`{key}` needs a circular or pointed arch (R is its radius)"),
    };
    let (target, x) = match key {
        "t/R" => ("arch.thickness", v * radius.ok_or_else(need_radius)?),
        "e/R" => ("arch.eccentricity", v * radius.ok_or_else(need_radius)?),
        "h/R" => ("piers.height", v * radius.ok_or_else(need_radius)?),
        "b/R" => ("piers.width", v * radius.ok_or_else(need_radius)?),
        "t/span" => ("arch.thickness", v * span(scene)),
        "sigma" => {
            if !(v.is_finite() && v >= 0.0) {
                return Err(SceneError::BadOverride {
                    text: format!("{key}={v}"),
                    message:
                        "the strength ratio sigma = W/(fc d t) must be >= 0 (0 for rigid joints)"
                            .into(),
                });
            }
            // sigma = W/(fc d t): the weight does not depend on fc.
            let weight = crate::scene::build(scene)?.assembly.total_weight();
            let fc = if v == 0.0 {
                f64::INFINITY
            } else {
                weight / (v * scene.material.depth * scene.parametric("sigma")?.thickness)
            };
            ("material.compressive_strength", fc)
        }
        "e/span" => {
            if !has_key("eccentricity") {
                return Err(SceneError::BadOverride {
                    text: format!("{key}={v}"),
                    message: "`e/span` needs a pointed arch".into(),
                });
            }
            let sp = span(scene);
            let e = v * sp;
            return Ok(vec![
                ("arch.eccentricity", Value::Float(set_value(e))),
                ("arch.radius", Value::Float(set_value(0.5 * sp + e))),
            ]);
        }
        _ => {
            if !has_key("rise") {
                return Err(SceneError::BadOverride {
                    text: format!("{key}={v}"),
                    message: "`rise/span` needs a basket arch".into(),
                });
            }
            ("arch.rise", v * span(scene))
        }
    };
    // Without round-off noise: t/R = 0.1825 at R = 10 sets the thickness 1.825 (not
    // 1.8250000000000002), as a message or the scene's JSON then shows it.
    Ok(vec![(target, Value::Float(set_value(x)))])
}

/// Centreline span of the arch.
pub fn span(scene: &Scene) -> f64 {
    scene.arch.as_ref().map_or(f64::NAN, |a| a.shape.span())
}

/// Centreline rise of the arch above the springing line.
pub fn rise(scene: &Scene) -> f64 {
    scene.arch.as_ref().map_or(f64::NAN, |a| a.shape.rise())
}

/// The dimensionless ratios of a scene, as `(name, value)`; NaN where not defined.
pub fn ratios(scene: &Scene) -> Vec<(&'static str, f64)> {
    let Some(arch) = &scene.arch else {
        // The user's blocks have none of these ratios.
        return ["t/R", "t/span", "e/R", "rise/span", "h/R", "b/R", "e/span"]
            .into_iter()
            .map(|k| (k, f64::NAN))
            .collect();
    };
    let radius = arch.shape.radius().unwrap_or(f64::NAN);
    let e = arch
        .shape
        .keys()
        .iter()
        .find(|(k, _)| *k == "eccentricity")
        .map_or(0.0, |(_, v)| *v);
    let (h, b) = scene.piers.as_ref().map_or((f64::NAN, f64::NAN), |p| {
        (p.left.height, p.left.base_width())
    });
    let t = arch.thickness;
    // Ratios of the user's inputs, to 12 significant digits ([`tidy`]): a semicircle's
    // rise/span is 0.5, not 0.49999999999999994.
    [
        ("t/R", t / radius),
        ("t/span", t / span(scene)),
        ("e/R", e / radius),
        ("rise/span", rise(scene) / span(scene)),
        ("h/R", h / radius),
        ("b/R", b / radius),
        ("e/span", e / span(scene)),
        ("sigma", sigma(scene).unwrap_or(f64::NAN)),
    ]
    .into_iter()
    .map(|(k, v)| (k, tidy(v)))
    .collect()
}

/// Check the chart's axes before anything is solved: `x` is a varied key, or a ratio
/// ([`DERIVED_KEYS`]) that takes more than one value over the valid cases (a ratio the
/// varied keys do not change would draw every line as a single dot); `series` is a varied
/// key other than `x`. Errors name the options `--x` and `--series`. A ratio's range is
/// measured over the sweep's cases, built in parallel ([`Sweep::par_cases`]).
pub fn check_chart(sweep: &Sweep, x: &str, series: Option<&str>) -> Result<(), SceneError> {
    let varied: Vec<&str> = sweep.variations.iter().map(|v| v.key.as_str()).collect();
    let bad = |message: String| SceneError::BadChart {
        option: "--x".into(),
        key: x.to_string(),
        message,
    };
    if !varied.contains(&x) {
        if !DERIVED_KEYS.contains(&x) {
            let mut candidates = varied.clone();
            candidates.extend(DERIVED_KEYS);
            return Err(bad(format!(
                "neither a varied key ({}) nor a ratio ({}){}",
                varied.join(", "),
                DERIVED_KEYS.join(", "),
                crate::error::did_you_mean(x, &candidates)
            )));
        }
        // The ratio's finite values over the valid cases, each case built by the thread that
        // takes it (the sweep holds none).
        let values = || {
            sweep
                .par_cases()
                .filter_map(|(_, s)| s.ok())
                .filter_map(|s| ratios(&s).into_iter().find(|(n, _)| *n == x))
                .map(|(_, v)| v)
                .filter(|v| v.is_finite())
        };
        let Some(first) = values().find_first(|_| true) else {
            return Err(bad(format!(
                "the ratio is not defined for these cases (varied: {})",
                varied.join(", ")
            )));
        };
        // Two values apart by more than twice the tolerance of the larger show that the range
        // exceeds its tolerance (below): the usual answer, found among the first cases taken.
        let apart = |v: f64| (v - first).abs() > 2e-9 * v.abs().max(first.abs()).max(1e-300);
        if !values().any(apart) {
            // The smallest and largest value (min and max do not depend on the order the
            // threads meet the cases in).
            let (lo, hi) = values()
                .map(|v| (v, v))
                .reduce(|| (first, first), |(a, b), (c, d)| (a.min(c), b.max(d)));
            if hi - lo <= 1e-9 * lo.abs().max(hi.abs()).max(1e-300) {
                return Err(bad(format!(
                    "the ratio does not vary in this sweep (it is {} in every case); --x takes a varied key ({}) or a ratio that changes with them",
                    lo + 0.0,
                    varied.join(", ")
                )));
            }
        }
    }
    if let Some(sk) = series {
        if !varied.contains(&sk) || sk == x {
            return Err(SceneError::BadChart {
                option: "--series".into(),
                key: sk.to_string(),
                message: format!(
                    "must be a varied key other than --x ({})",
                    varied
                        .iter()
                        .filter(|k| **k != x)
                        .copied()
                        .collect::<Vec<_>>()
                        .join(", ")
                ),
            });
        }
    }
    Ok(())
}

/// One case of a sweep: its varied values (in the order of the variations) and its scene, or
/// the error that made the case invalid.
pub type Case = (Vec<Value>, Result<Scene, SceneError>);

/// Case `index` of the sweep of `variations` over `base` (the first varied key changes
/// slowest), built on its own: the cases of a sweep need not be built in order, nor on one
/// thread, nor all at once. `index` is below the number of cases ([`case_count`]); a larger
/// one wraps round.
pub fn case_at(base: &Scene, variations: &[Variation], index: usize) -> Case {
    let mut idx = vec![0; variations.len()];
    let mut rest = index;
    for (i, v) in variations.iter().enumerate().rev() {
        let n = v.values.len().max(1);
        idx[i] = rest % n;
        rest /= n;
    }
    let values: Vec<Value> = idx
        .iter()
        .zip(variations)
        .filter_map(|(&i, v)| v.values.get(i).cloned())
        .collect();
    let pairs: Vec<(&str, &Value)> = variations
        .iter()
        .zip(&values)
        .map(|(v, x)| (v.key.as_str(), x))
        .collect();
    let scene = apply(base, &pairs);
    (values, scene)
}

/// Every case of the sweep ([`case_at`]), in order, built in parallel. A sweep run through
/// [`Sweep`] never holds them all: each is built by the thread that solves it.
pub fn cases(base: &Scene, variations: &[Variation]) -> Vec<Case> {
    let total = case_count(variations).unwrap_or(0);
    (0..total)
        .into_par_iter()
        .map(|i| case_at(base, variations, i))
        .collect()
}

/// A sweep ready to run: its base scene and its variations, checked against the scene before
/// anything is solved ([`check_variations`]). Its cases are not built in advance: each is
/// built from its index by the thread that solves it ([`case_at`]), so the whole sweep, from
/// the scenes to the rows, runs in parallel, and rows come back in the order of the cases.
/// The `sweep` command, the studies, the server and the Python package all run sweeps through
/// it, so they give the same rows.
#[derive(Debug)]
pub struct Sweep {
    base: Scene,
    variations: Vec<Variation>,
    len: usize,
}

impl Sweep {
    /// Check `variations` against `base` (invalid cases stay, as errors, to become rows with
    /// status `error`).
    pub fn new(base: &Scene, variations: Vec<Variation>) -> Result<Sweep, SceneError> {
        check_variations(base, &variations)?;
        // check_variations refused a count that overflows or exceeds MAX_CASES.
        let len = case_count(&variations).unwrap_or(0);
        Ok(Sweep {
            base: base.clone(),
            variations,
            len,
        })
    }

    /// The varied keys and their values, in order (the first changes slowest).
    pub fn variations(&self) -> &[Variation] {
        &self.variations
    }

    /// The number of cases.
    pub fn len(&self) -> usize {
        self.len
    }

    /// Whether the sweep has no case (never, once [`Sweep::new`] accepted it).
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// Case `index` ([`case_at`]).
    pub fn case(&self, index: usize) -> Case {
        case_at(&self.base, &self.variations, index)
    }

    /// Every case, in order, each built by the thread that takes it.
    pub fn par_cases(&self) -> impl IndexedParallelIterator<Item = Case> + '_ {
        (0..self.len).into_par_iter().map(|i| self.case(i))
    }

    /// Analyse every case by `options` (and the DEM when `dem`) in parallel, as rows in
    /// order ([`case`]); `progress` is called after each case (from worker threads).
    pub fn run(&self, options: &Options, dem: bool, progress: &(dyn Fn() + Sync)) -> Vec<SweepRow> {
        self.run_with(|values, scene| case(values, scene, options, dem), progress)
    }

    /// Build and analyse every case by `analyse` in parallel, keeping the order; `progress`
    /// is called after each case (from worker threads).
    pub fn run_with<R, F>(&self, analyse: F, progress: &(dyn Fn() + Sync)) -> Vec<R>
    where
        R: Send,
        F: Fn(&[Value], &Result<Scene, SceneError>) -> R + Sync,
    {
        self.par_cases()
            .map(|(values, scene)| {
                let r = analyse(&values, &scene);
                progress();
                r
            })
            .collect()
    }
}

/// Run `analyse` on every case of a list already built ([`cases`]) in parallel, keeping the
/// order; `progress` is called after each case (from worker threads).
pub fn run<R, F>(cases: &[Case], analyse: F, progress: &(dyn Fn() + Sync)) -> Vec<R>
where
    R: Send,
    F: Fn(&[Value], &Result<Scene, SceneError>) -> R + Sync,
{
    cases
        .par_iter()
        .map(|(values, scene)| {
            let r = analyse(values, scene);
            progress();
            r
        })
        .collect()
}

/// The outcome of one case.
#[derive(Debug, Clone)]
pub struct SweepRow {
    pub values: Vec<Value>,
    pub ratios: Vec<(&'static str, f64)>,
    /// `collapse`, `no_collapse`, `cannot_stand`, or `error`.
    pub status: String,
    pub lambda_lower: Option<f64>,
    pub lambda_upper: Option<f64>,
    pub hinges: Vec<Hinge>,
    pub solve_time_s: f64,
    /// Why the case failed, for status `error`.
    pub error: Option<String>,
    /// Further named columns (e.g. a baseline multiplier and the ratio to it).
    pub extra: Vec<(&'static str, Option<f64>)>,
}

impl SweepRow {
    /// Relative gap `|upper - lower| / max(1, lower)` when both bounds exist.
    pub fn gap(&self) -> Option<f64> {
        Some((self.lambda_upper? - self.lambda_lower?).abs() / self.lambda_lower?.abs().max(1.0))
    }
}

/// Free a sweep's rows on every thread: each row holds a few small allocations, which one
/// thread would otherwise free one by one after the parallel work (a serial tail of a large
/// sweep).
pub fn free_rows(rows: Vec<SweepRow>) {
    rows.into_par_iter().for_each(drop);
}

/// Hinges as a compact string: `4:p1 15:p2 ...`.
pub fn hinge_string(hinges: &[Hinge]) -> String {
    hinges
        .iter()
        .map(|h| {
            format!(
                "{}:{}",
                h.joint,
                match h.end {
                    JointEnd::P1 => "p1",
                    JointEnd::P2 => "p2",
                }
            )
        })
        .collect::<Vec<_>>()
        .join(" ")
}

/// The static analysis of one case, as a row (errors become rows with status `error`).
pub fn static_case(
    values: &[Value],
    scene: &Result<Scene, SceneError>,
    settings: &StaticSettings,
) -> SweepRow {
    let options = Options {
        static_settings: settings.clone(),
        kinematic_max_joints: 0,
        friction: crate::analysis::FrictionMode::Associative,
        ..Options::default()
    };
    case(values, scene, &options, false)
}

/// One case by every method in `options` (the static bound always; the kinematic bound when
/// the chain is small enough; the continuous model and the DEM when asked), as a row.
/// Extra columns: `lambda_continuous` with `options.continuous`; with `dem`, `lambda_dem`,
/// `dem_time_s` (the DEM's wall time), the bracket `lambda_dem_low`, `lambda_dem_high`, its
/// relative width `dem_bracket_width` and `static_inside_dem_bracket` (1 when the static bound
/// of the shapes simulated lies inside, else 0). The DEM starts from its own guess, not from
/// the static bound (see `analysis::DemOptions::from_static`). `solve_time_s` is the time of the static,
/// kinematic and continuous analyses, without the DEM.
pub fn case(
    values: &[Value],
    scene: &Result<Scene, SceneError>,
    options: &Options,
    dem: bool,
) -> SweepRow {
    let mut row = SweepRow {
        values: values.to_vec(),
        ratios: Vec::new(),
        status: "error".into(),
        lambda_lower: None,
        lambda_upper: None,
        hinges: Vec::new(),
        solve_time_s: 0.0,
        error: None,
        extra: Vec::new(),
    };
    let scene = match scene {
        Ok(s) => s,
        Err(e) => {
            row.error = Some(e.to_string());
            return row;
        }
    };
    row.ratios = ratios(scene);
    let start = std::time::Instant::now();
    match analysis::analyse(scene, options) {
        Ok(a) => {
            row.solve_time_s = start.elapsed().as_secs_f64();
            row.status = a.lower.status.as_str().to_string();
            row.lambda_lower = a.lower.lambda;
            row.lambda_upper = a.lambda_upper();
            row.hinges = a.lower.hinges.clone();
            if options.continuous {
                let c = a
                    .continuous
                    .as_ref()
                    .and_then(|c| c.as_ref().ok())
                    .and_then(|c| c.lambda_continuous);
                row.extra.push(("lambda_continuous", c));
            }
            if dem {
                let dem_start = std::time::Instant::now();
                let d = analysis::dem_of(
                    scene,
                    &a.model,
                    a.lower.lambda,
                    &analysis::DemOptions::default(),
                    &mut |_| {},
                )
                .and_then(|r| {
                    // Compared with the static bound of the shapes simulated (curved voussoirs
                    // as chord polygons), solved only when those differ.
                    let (l, _) = analysis::simulated_static(&a.model, a.lower.lambda)?;
                    Ok((r, l))
                });
                let (mid, low, high, width, inside) = match d {
                    Ok((r, l)) => {
                        let inside = match (l, r.lambda_stands, r.lambda_collapses) {
                            (Some(l), Some(lo), Some(hi)) => {
                                Some(f64::from(u8::from(lo <= l && l <= hi)))
                            }
                            _ => None,
                        };
                        (
                            r.lambda_dem,
                            r.lambda_stands,
                            r.lambda_collapses,
                            r.bracket_width,
                            inside,
                        )
                    }
                    Err(e) => {
                        // The static and kinematic results stand; say why the DEM has none.
                        row.error = Some(format!("DEM: {e}"));
                        (None, None, None, None, None)
                    }
                };
                row.extra.push(("lambda_dem", mid));
                row.extra
                    .push(("dem_time_s", Some(dem_start.elapsed().as_secs_f64())));
                row.extra.push(("lambda_dem_low", low));
                row.extra.push(("lambda_dem_high", high));
                row.extra.push(("dem_bracket_width", width));
                row.extra.push(("static_inside_dem_bracket", inside));
            }
        }
        Err(e) => {
            row.solve_time_s = start.elapsed().as_secs_f64();
            row.error = Some(e.to_string());
        }
    }
    row
}

/// A result in a CSV cell: every digit (the shortest text that reads back as the same
/// number), in exponent form when tiny or huge (`1.6653345369377348e-16`, not 33 characters
/// of zeros); empty when there is none.
fn opt(x: Option<f64>) -> String {
    x.filter(|v| v.is_finite()).map_or(String::new(), number)
}

/// `x` in the shortest text that reads back as `x`: positional from 1e-4 to 1e15, exponent
/// form outside.
pub fn number(x: f64) -> String {
    if x != 0.0 && !(1e-4..1e15).contains(&x.abs()) {
        format!("{x:e}")
    } else {
        x.to_string()
    }
}

/// Write the rows as CSV: the varied keys, then `status, lambda_lower, lambda_upper, gap,
/// hinges, solve_time_s`, any `extra` columns, the dimensionless ratios, and `error`.
pub fn write_csv<W: std::io::Write>(
    out: W,
    variations: &[Variation],
    rows: &[SweepRow],
) -> Result<(), csv::Error> {
    write_csv_with(out, variations, rows, true)
}

/// Like [`write_csv`]; without `timings` the wall-time columns (`solve_time_s` and every
/// extra column ending in `_time_s`) are left out, so the file is the same on every run
/// (the committed figures of the studies).
pub fn write_csv_with<W: std::io::Write>(
    mut out: W,
    variations: &[Variation],
    rows: &[SweepRow],
    timings: bool,
) -> Result<(), csv::Error> {
    let is_timing = |name: &str| name.ends_with("_time_s");
    // The varied keys, then the results in the order the issue fixed (status ... solve_time_s),
    // then the optional columns, the dimensionless ratios not varied, and the error message.
    let mut header: Vec<String> = variations.iter().map(|v| v.key.clone()).collect();
    let ratio_names: Vec<&str> = DERIVED_KEYS
        .iter()
        .copied()
        .filter(|k| !variations.iter().any(|v| v.key == *k))
        .collect();
    for h in [
        "status",
        "lambda_lower",
        "lambda_upper",
        "gap",
        "hinges",
        "solve_time_s",
    ] {
        if timings || !is_timing(h) {
            header.push(h.to_string());
        }
    }
    let extra: Vec<&str> = rows
        .iter()
        .find(|r| !r.extra.is_empty())
        .map(|r| {
            r.extra
                .iter()
                .map(|(n, _)| *n)
                .filter(|n| timings || !is_timing(n))
                .collect()
        })
        .unwrap_or_default();
    header.extend(extra.iter().map(|s| s.to_string()));
    header.extend(ratio_names.iter().map(|s| s.to_string()));
    header.push("error".to_string());
    let record = |r: &SweepRow| -> Vec<String> {
        let mut rec: Vec<String> = r.values.iter().map(value_text).collect();
        rec.push(r.status.clone());
        rec.push(opt(r.lambda_lower));
        rec.push(opt(r.lambda_upper));
        rec.push(opt(r.gap()));
        rec.push(hinge_string(&r.hinges));
        if timings {
            rec.push(number(r.solve_time_s));
        }
        for name in &extra {
            rec.push(opt(r
                .extra
                .iter()
                .find(|(n, _)| n == name)
                .and_then(|(_, v)| *v)));
        }
        for name in &ratio_names {
            let v = r.ratios.iter().find(|(n, _)| n == name).map(|(_, v)| *v);
            rec.push(opt(v));
        }
        rec.push(r.error.clone().unwrap_or_default());
        rec
    };
    // Each block of rows is formatted by a worker thread into its own buffer; the buffers
    // are written in order. A CSV record's text depends on that record alone, so the bytes are
    // those of one writer taking every row in turn.
    out.write_all(&csv_text(std::slice::from_ref(&header))?)?;
    let blocks: Vec<Vec<u8>> = rows
        .par_chunks(CSV_BLOCK_ROWS)
        .map(|block| csv_text(&block.iter().map(record).collect::<Vec<_>>()))
        .collect::<Result<_, _>>()?;
    for block in &blocks {
        out.write_all(block)?;
    }
    out.flush()?;
    Ok(())
}

/// Rows a CSV block formatted by one worker holds: enough to outweigh the hand-over, few
/// enough to share a sweep's rows among many threads.
const CSV_BLOCK_ROWS: usize = 256;

/// `records` as CSV text.
fn csv_text(records: &[Vec<String>]) -> Result<Vec<u8>, csv::Error> {
    let mut w = csv::Writer::from_writer(Vec::new());
    for r in records {
        w.write_record(r)?;
    }
    w.into_inner().map_err(|e| e.into_error().into())
}
