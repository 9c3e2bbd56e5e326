//! The charts of a sweep and of a study: the collapse multiplier against a varied key or a
//! ratio, one line per value of the other keys (and a study's baseline), with the keys named
//! in words and units.

use crate::drawing::chart::{Chart, Series};
use crate::error::SceneError;
use crate::scene::Scene;
use crate::study::{Baseline, Study};
use crate::sweep::{Sweep, SweepRow, Variation, DERIVED_KEYS};
use rayon::prelude::*;
use toml::Value;

/// How charts name a key: a readable name with its unit (`thickness t (m)`, `embrace
/// (deg)`); ratios and keys without a name stay as they are.
pub fn key_label(key: &str) -> String {
    match key_name(key) {
        Some((name, "")) => name.to_string(),
        Some((name, unit)) => format!("{name} ({unit})"),
        None => key.to_string(),
    }
}

/// `key = value` as a chart legend says it (`embrace = 120 deg`).
fn key_value_label(key: &str, value: &str) -> String {
    match key_name(key) {
        Some((name, "")) => format!("{name} = {value}"),
        Some((name, unit)) => format!("{name} = {value} {unit}"),
        None => format!("{key} = {value}"),
    }
}

/// The readable name and unit of a scene key.
fn key_name(key: &str) -> Option<(&'static str, &'static str)> {
    Some(match key {
        "arch.thickness" => ("thickness t", "m"),
        "arch.radius" => ("radius R", "m"),
        "arch.embrace_deg" => ("embrace", "deg"),
        "arch.voussoirs" => ("voussoirs n", ""),
        "arch.eccentricity" => ("eccentricity e", "m"),
        "arch.span" => ("span L", "m"),
        "arch.rise" => ("rise f", "m"),
        "arch.side_angle_deg" => ("side angle", "deg"),
        "arch.shape" => ("shape", ""),
        "arch.voussoir_shape" => ("voussoir shape", ""),
        "piers.height" => ("pier height h", "m"),
        "piers.width" => ("pier width b", "m"),
        "piers.courses" => ("pier courses k", ""),
        "material.friction" => ("friction coefficient mu", ""),
        "material.unit_weight" => ("unit weight", "N/m^3"),
        "material.depth" => ("depth", "m"),
        "material.compressive_strength" => ("compressive strength fc", "Pa"),
        "fill.level" => ("fill level", "m"),
        "fill.unit_weight" => ("fill unit weight", "N/m^3"),
        "fill.seismic" => ("seismic fill", ""),
        "seismic.vertical_ratio" => ("vertical seismic ratio", ""),
        _ => return None,
    })
}

/// The chart of a sweep: lambda against the `x` key (a varied key or a ratio), one line per
/// combination of the other varied keys (the `series` key first in the legend when given).
pub fn chart(
    variations: &[Variation],
    rows: &[SweepRow],
    x: &str,
    series: Option<&str>,
    title: &str,
) -> Result<Chart, SceneError> {
    chart_of(variations, rows, x, series, title, None)
}

/// Like [`chart`], plotting the extra column `y` (e.g. `lambda_ratio`) when given.
pub fn chart_of(
    variations: &[Variation],
    rows: &[SweepRow],
    x: &str,
    series: Option<&str>,
    title: &str,
    y: Option<&str>,
) -> Result<Chart, SceneError> {
    let x_index = variations.iter().position(|v| v.key == x);
    if x_index.is_none() && !DERIVED_KEYS.contains(&x) {
        return Err(SceneError::BadChart {
            option: "--x".into(),
            key: x.to_string(),
            message: format!(
                "neither a varied key nor a ratio ({})",
                DERIVED_KEYS.join(", ")
            ),
        });
    }
    if let Some(sk) = series {
        if !variations.iter().any(|v| v.key == sk) || Some(sk) == Some(x) {
            return Err(SceneError::BadChart {
                option: "--series".into(),
                key: sk.to_string(),
                message: "must be a varied key other than --x".into(),
            });
        }
    }
    let mut others: Vec<usize> = (0..variations.len())
        .filter(|&i| Some(i) != x_index)
        .collect();
    if let Some(sk) = series {
        others.sort_by_key(|&i| variations[i].key != sk);
    }
    let text = |v: &Value| match v {
        Value::String(s) => s.clone(),
        other => other.to_string(),
    };
    // (series name, its points), in order of first appearance.
    type Line = (String, Vec<(f64, Option<f64>)>);
    let mut groups: Vec<Line> = Vec::new();
    for r in rows {
        let xv = match x_index {
            Some(i) => match &r.values[i] {
                Value::Float(f) => Some(*f),
                Value::Integer(n) => Some(*n as f64),
                _ => None,
            },
            None => r.ratios.iter().find(|(n, _)| *n == x).map(|(_, v)| *v),
        };
        let Some(xv) = xv else { continue };
        let name = if others.len() == 1 {
            text(&r.values[others[0]])
        } else {
            others
                .iter()
                .map(|&i| key_value_label(&variations[i].key, &text(&r.values[i])))
                .collect::<Vec<_>>()
                .join(", ")
        };
        let yv = match y {
            Some(col) => r
                .extra
                .iter()
                .find(|(n, _)| *n == col)
                .and_then(|(_, v)| *v),
            None => r.lambda_lower,
        };
        match groups.iter_mut().find(|(n, _)| *n == name) {
            Some((_, pts)) => pts.push((xv, yv)),
            None => groups.push((name, vec![(xv, yv)])),
        }
    }
    Ok(Chart {
        title: title.to_string(),
        x_label: key_label(x),
        y_label: match y {
            Some("lambda_ratio") => "λ / λ of the semicircle of equal span".to_string(),
            Some(col) => col.to_string(),
            None => "collapse multiplier λ (static lower bound)".to_string(),
        },
        legend_title: match others.len() {
            0 => None,
            1 => Some(key_label(&variations[others[0]].key)),
            _ => Some("series".to_string()),
        },
        series: groups
            .into_iter()
            .map(|(name, pts)| {
                Series::new(
                    if name.is_empty() {
                        "λ".to_string()
                    } else {
                        name
                    },
                    pts,
                )
            })
            .collect(),
    })
}

/// A sweep chart's title: the structure the cases share ("semicircular arch"), or, when the
/// varied keys change the shape's own words (an embrace, an eccentricity, the shape itself),
/// the kind of arch they all are ("circular arch"), or just "arch" / "portal"; then what is
/// drawn against what.
pub fn sweep_title(base: &Scene, plan: &Sweep, x: &str) -> String {
    // The cases are built anew, in parallel: the sweep holds none of them.
    let same = |f: &(dyn Fn(&Scene) -> String + Sync)| {
        let wanted = f(base);
        plan.par_cases()
            .all(|(_, s)| s.as_ref().map_or(true, |s| f(s) == wanted))
    };
    let structure = |s: &Scene| if s.piers.is_some() { "portal" } else { "arch" }.to_string();
    let shape_name = |s: &Scene| {
        s.arch
            .as_ref()
            .map_or("blocks", |a| a.shape.name())
            .to_string()
    };
    let what = if same(&|s| super::super::shape_title(s)) {
        super::super::shape_title(base)
    } else if same(&shape_name) && same(&structure) {
        format!("{} {}", shape_name(base), structure(base))
    } else if same(&structure) {
        structure(base)
    } else {
        "arch and portal".to_string()
    };
    format!("{what}: collapse multiplier against {}", key_label(x))
}

/// A study's chart: its rows against its `x`, one line per value of its series key, and the
/// baseline (its multiplier as one more line, or the ratio to it on the y axis).
pub fn study_chart(study: &Study, rows: &[SweepRow]) -> Result<Chart, SceneError> {
    let mut chart = chart_of(
        &study.variations,
        rows,
        &study.x,
        study.series.as_deref(),
        &study.title,
        study.plot_ratio.then_some("lambda_ratio"),
    )
    .map_err(|e| study.chart_error(e))?;
    if let Some(baseline) = study.baseline {
        if study.plot_ratio {
            chart.y_label = format!("lambda / lambda of the {}", baseline.describe());
        } else {
            chart
                .series
                .push(baseline_series(rows, &study.x, &study.variations, baseline));
        }
    }
    Ok(chart)
}

/// The line of the baseline's multiplier against `x` on a chart of `lambda_lower`: one point
/// per distinct x (cases that differ only in the series key share their baseline when the
/// baseline does not depend on it, e.g. the semicircle of equal span for several e/R at the
/// same t/span).
fn baseline_series(
    rows: &[SweepRow],
    x: &str,
    variations: &[Variation],
    baseline: Baseline,
) -> Series {
    let x_index = variations.iter().position(|v| v.key == x);
    let mut points: Vec<(f64, Option<f64>)> = Vec::new();
    for r in rows {
        let xv = match x_index {
            Some(i) => r.values[i]
                .as_float()
                .or(r.values[i].as_integer().map(|n| n as f64)),
            None => r.ratios.iter().find(|(n, _)| *n == x).map(|(_, v)| *v),
        };
        let Some(xv) = xv else { continue };
        let lb = r
            .extra
            .iter()
            .find(|(n, _)| *n == "lambda_baseline")
            .and_then(|(_, v)| *v);
        if !points.iter().any(|(px, _)| *px == xv) {
            points.push((xv, lb));
        }
    }
    Series::new(baseline.describe(), points)
}
