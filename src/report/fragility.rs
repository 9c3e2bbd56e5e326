//! `voussoir fragility`: its JSON object, its document (with the per-sample table the CSV
//! printer writes) and its chart (the fitted curve over the empirical points).

use super::assessment::SiteReport;
use super::document::{Column, Data, Document, Row, Table, Value};
use crate::drawing::chart::{Chart, Series};
use crate::fragility::{Capacity, CapacityFragility, DynamicFragility, FitError, LognormalFit};
use crate::outcome::Direction;
use crate::scene::uncertain::UncertainInput;
use crate::scene::Scene;
use serde::Serialize;

/// `fragility --json`.
#[derive(Debug, Serialize)]
pub struct FragilityReport {
    pub scene: String,
    /// `"capacity"`: each sample's capacity by the NTC nonlinear kinematic check;
    /// `"dynamic"`: the DEM under records scaled to stripes of PGA (multiple-stripe analysis).
    pub route: &'static str,
    /// The intensity measure: `"ag"` (capacity route: peak ground acceleration on rock, in
    /// g) or `"pga"` (dynamic route: the records' peak ground acceleration, in g).
    pub intensity: &'static str,
    /// The check whose largest passing `ag` is a sample's capacity (`"nonlinear"`); null on
    /// the dynamic route.
    pub check: Option<&'static str>,
    pub sample_count: usize,
    pub seed: u64,
    /// The uncertain inputs: `key`, `dist` and its parameters as the scene gives them.
    pub inputs: Vec<InputReport>,
    /// The rank (Spearman) correlations imposed between inputs: `between` (two keys) and
    /// `rank`; empty when the inputs are independent.
    pub correlation: Vec<crate::scene::uncertain::RankCorrelation>,
    /// The site, its `ag` the scene's (the capacities search `ag` with the rest held); null
    /// on the dynamic route.
    pub site: Option<SiteReport>,
    /// The dynamic route's records (their files) and stripes (`pga` in g, `runs`,
    /// `collapses` over every sample and record); null on the capacity route.
    pub records: Option<Vec<String>>,
    pub stripes: Option<Vec<StripeReport>>,
    /// The fitted lognormal, its fields in this object.
    #[serde(flatten)]
    pub fit: FitReport,
    /// Samples with a capacity found, above the search's largest `ag` (2 g), below its
    /// least (0.005 g), and not assessed.
    pub assessed: usize,
    pub above_search: usize,
    pub below_search: usize,
    pub not_assessed: usize,
    /// One row per sample.
    pub samples: Vec<SampleReport>,
}

/// The fitted lognormal: median (g), dispersion beta, their bounds at `confidence`; `null`
/// when no fit exists (`fit_error` says why). The same for both routes.
#[derive(Debug, Serialize)]
pub struct FitReport {
    pub median: Option<f64>,
    pub beta: Option<f64>,
    pub median_bounds: Option<[f64; 2]>,
    pub beta_bounds: Option<[f64; 2]>,
    pub confidence: Option<f64>,
    pub fit_error: Option<String>,
}

impl FitReport {
    fn new(fit: &Result<LognormalFit, FitError>) -> Self {
        let ok = fit.as_ref().ok();
        FitReport {
            median: ok.map(|x| x.median),
            beta: ok.map(|x| x.beta),
            median_bounds: ok.map(|x| x.median_bounds),
            beta_bounds: ok.map(|x| x.beta_bounds),
            confidence: ok.map(|x| x.confidence),
            fit_error: fit.as_ref().err().map(|e| e.to_string()),
        }
    }
}

/// One stripe of the dynamic route.
#[derive(Debug, Serialize)]
pub struct StripeReport {
    pub pga: f64,
    pub runs: u64,
    pub collapses: u64,
}

/// One uncertain input.
#[derive(Debug, Serialize)]
pub struct InputReport {
    pub key: String,
    pub dist: &'static str,
    #[serde(flatten)]
    pub parameters: std::collections::BTreeMap<&'static str, f64>,
}

/// One sample.
#[derive(Debug, Serialize)]
pub struct SampleReport {
    pub index: usize,
    /// The inputs' values, in the order of `inputs`.
    pub values: Vec<f64>,
    /// `"fails_at"`, `"passes_at_search_max"`, `"fails_at_search_min"` or `"not_assessed"`.
    pub outcome: &'static str,
    /// The largest passing `ag` (g); null unless `fails_at`.
    pub ag_capacity: Option<f64>,
    /// The direction whose capacity governs (`"right"`, `"left"`); null unless `fails_at`.
    pub direction: Option<&'static str>,
    /// Why the sample was not assessed; null otherwise.
    pub reason: Option<String>,
    /// Dynamic route: at each stripe, the records under which the sample collapsed (a count
    /// out of `records`); null on the capacity route.
    pub collapses: Option<Vec<u64>>,
}

fn outcome_words(c: &Capacity) -> &'static str {
    match c {
        Capacity::At { .. } => "fails_at",
        Capacity::Above => "passes_at_search_max",
        Capacity::Below(_) => "fails_at_search_min",
        Capacity::NotAssessed(_) => "not_assessed",
    }
}

fn direction_name(d: Direction) -> &'static str {
    match d {
        Direction::Right => "right",
        Direction::Left => "left",
    }
}

impl FragilityReport {
    pub fn new(scene: &Scene, f: &CapacityFragility) -> Self {
        let count = |p: fn(&Capacity) -> bool| f.samples.iter().filter(|s| p(&s.capacity)).count();
        FragilityReport {
            scene: scene.origin.clone(),
            route: "capacity",
            intensity: "ag",
            check: Some("nonlinear"),
            sample_count: f.samples.len(),
            seed: f.seed,
            inputs: inputs(&f.inputs),
            correlation: f.correlation.clone(),
            site: Some(SiteReport::new(&f.site)),
            records: None,
            stripes: None,
            fit: FitReport::new(&f.fit),
            assessed: count(|c| matches!(c, Capacity::At { .. })),
            above_search: count(|c| matches!(c, Capacity::Above)),
            below_search: count(|c| matches!(c, Capacity::Below(_))),
            not_assessed: f.not_assessed(),
            samples: f
                .samples
                .iter()
                .enumerate()
                .map(|(index, s)| SampleReport {
                    index,
                    values: s.values.clone(),
                    outcome: outcome_words(&s.capacity),
                    ag_capacity: s.capacity.ag(),
                    direction: match &s.capacity {
                        Capacity::At { direction, .. } => Some(direction_name(*direction)),
                        _ => None,
                    },
                    reason: match &s.capacity {
                        Capacity::NotAssessed(why) => Some(why.clone()),
                        _ => None,
                    },
                    collapses: None,
                })
                .collect(),
        }
    }

    /// The dynamic route's object.
    pub fn dynamic(scene: &Scene, f: &DynamicFragility) -> Self {
        FragilityReport {
            scene: scene.origin.clone(),
            route: "dynamic",
            intensity: "pga",
            check: None,
            sample_count: f.samples.len(),
            seed: f.seed,
            inputs: inputs(&f.inputs),
            correlation: f.correlation.clone(),
            site: None,
            records: Some(f.records.clone()),
            stripes: Some(
                f.stripes
                    .iter()
                    .map(|s| StripeReport {
                        pga: s.pga,
                        runs: s.runs,
                        collapses: s.collapses,
                    })
                    .collect(),
            ),
            fit: FitReport::new(&f.fit),
            assessed: f.samples.len(),
            above_search: 0,
            below_search: 0,
            not_assessed: 0,
            samples: f
                .samples
                .iter()
                .enumerate()
                .map(|(index, s)| SampleReport {
                    index,
                    values: s.values.clone(),
                    outcome: "ran",
                    ag_capacity: None,
                    direction: None,
                    reason: None,
                    collapses: Some(
                        s.collapsed
                            .iter()
                            .map(|c| c.iter().filter(|&&x| x).count() as u64)
                            .collect(),
                    ),
                })
                .collect(),
        }
    }
}

fn inputs(inputs: &[crate::scene::uncertain::UncertainInput]) -> Vec<InputReport> {
    inputs
        .iter()
        .map(|i| InputReport {
            key: i.key.clone(),
            dist: i.dist.name(),
            parameters: parameters(&i.dist),
        })
        .collect()
}

fn parameters(d: &crate::sampling::Distribution) -> std::collections::BTreeMap<&'static str, f64> {
    use crate::sampling::Distribution::*;
    match *d {
        Normal { mean, cov } => [("mean", mean), ("cov", cov)].into(),
        Uniform { low, high } => [("low", low), ("high", high)].into(),
        Lognormal { median, beta } => [("median", median), ("beta", beta)].into(),
    }
}

/// The per-sample table (the CSV of `--csv`): the sample, each input's value, the outcome,
/// the capacity and its direction.
pub fn sample_table(f: &CapacityFragility) -> Table {
    let mut columns = input_columns(&f.inputs);
    columns.push(Column::left("outcome", 20).gap(2));
    columns.push(Column::right("ag_capacity_g", 20));
    columns.push(Column::left("direction", 9).gap(2));
    let rows = f
        .samples
        .iter()
        .enumerate()
        .map(|(i, s)| {
            let mut row = input_cells(i, &s.values);
            row.push(Value::text(outcome_words(&s.capacity)));
            row.push(Value::Text(
                s.capacity.ag().map_or(String::new(), |a| format!("{a}")),
            ));
            row.push(Value::text(match &s.capacity {
                Capacity::At { direction, .. } => direction_name(*direction),
                _ => "",
            }));
            row
        })
        .collect();
    Table { columns, rows }
}

/// The most samples whose table the document itself carries.
pub const TABLE_ROWS: usize = 50;

/// The fitted curve's sentence.
fn fit_words(fit: &LognormalFit) -> String {
    if fit.beta == 0.0 {
        return format!(
            "every sample fails above ag = {:.6} g: the fragility is a step there (beta = 0)",
            fit.median
        );
    }
    format!(
        "lognormal fit (maximum likelihood): median {:.4} g [{:.4}, {:.4}], beta {:.4} [{:.4}, {:.4}] ({:.0} % bounds from the observed information)",
        fit.median,
        fit.median_bounds[0],
        fit.median_bounds[1],
        fit.beta,
        fit.beta_bounds[0],
        fit.beta_bounds[1],
        100.0 * fit.confidence
    )
}

/// The document of a capacity-route fragility.
pub fn document(scene: &Scene, f: &CapacityFragility) -> Document {
    let report = FragilityReport::new(scene, f);
    let mut doc = Document::new(&scene.origin);
    doc.lead.push(format!(
        "Fragility by the capacity route: {} Latin hypercube samples (seed {}); each sample's capacity is the largest ag its NTC 2018 nonlinear kinematic check passes (the worse direction), with soil {}, F0 = {}, Tc* = {} s held",
        f.samples.len(),
        f.seed,
        f.site.soil.as_str(),
        f.site.f0,
        f.site.tc_star
    ));
    inputs_section(
        &mut doc,
        &f.inputs,
        &f.correlation,
        "every sample is the scene itself, so the fragility is a step at its largest passing ag",
    );
    let sec = doc.section("Fragility");
    match &f.fit {
        Ok(fit) => {
            sec.line(fit_words(fit));
            sec.rows(vec![
                Row::new(
                    "median",
                    Value::Number {
                        value: fit.median,
                        digits: 4,
                        unit: "g",
                    },
                ),
                Row::new("beta", Value::number(fit.beta, 4)),
                Row::new("samples assessed", Value::Count(report.assessed as u64)),
            ]);
        }
        Err(e) => {
            sec.warning(format!("no lognormal fit: {e}"));
        }
    }
    if report.above_search > 0 {
        sec.line(format!(
            "{} sample(s) pass even at ag = {} g: their capacity is known only to lie above it (censored in the fit)",
            report.above_search,
            crate::assess::AG_SEARCH_MAX
        ));
    }
    if report.below_search > 0 {
        sec.line(format!(
            "{} sample(s) fail at any ag or cannot stand: their capacity lies below {} g (censored in the fit)",
            report.below_search,
            crate::assess::AG_GRID_FIRST
        ));
    }
    if report.not_assessed > 0 {
        sec.warning(format!(
            "{} of {} samples could not be assessed (no rotational capacity curve: the structure cannot stand, or joints slide at collapse) and are left out of the fit, so the curve is conditional on the rotational mechanism governing; first reason: {}",
            report.not_assessed,
            f.samples.len(),
            report
                .samples
                .iter()
                .find_map(|s| s.reason.clone())
                .unwrap_or_default()
        ));
    }
    samples_section(&mut doc, f.samples.len(), || sample_table(f));
    doc.data = Some(Data::Fragility(Box::new(report)));
    doc
}

/// The chart: the fitted lognormal CDF over the empirical fragility (each sample's capacity
/// against the share of samples that fail at or below it).
pub fn chart(scene: &Scene, f: &CapacityFragility) -> Chart {
    let empirical = f.empirical();
    let top = empirical
        .last()
        .map(|p| p.0)
        .into_iter()
        .chain(f.fit.as_ref().ok().map(|x| x.median * (3.0 * x.beta).exp()))
        .fold(0.0_f64, f64::max)
        .max(1e-3)
        * 1.15;
    let mut series = Vec::new();
    series.extend(f.fit.as_ref().ok().map(|fit| fit_series(fit, top)));
    series.push(Series {
        name: "samples (share failing at or below)".into(),
        points: empirical.clone(),
        markers: crate::drawing::chart::Markers::Every,
    });
    Chart {
        title: format!(
            "Fragility (capacity route, {} samples): {}",
            f.samples.len(),
            scene.origin
        ),
        x_label: "peak ground acceleration on rock ag (g)".into(),
        y_label: "probability of failing the nonlinear check".into(),
        legend_title: None,
        series,
    }
}

/// The per-sample table of the dynamic route: the sample, each input's value, and at each
/// stripe the records under which it collapsed.
pub fn dynamic_table(f: &DynamicFragility) -> Table {
    let mut columns = input_columns(&f.inputs);
    columns.extend(
        f.stripes
            .iter()
            .map(|s| Column::right(format!("collapses_at_{}g", s.pga), 18)),
    );
    let rows = f
        .samples
        .iter()
        .enumerate()
        .map(|(i, s)| {
            let mut row = input_cells(i, &s.values);
            row.extend(
                s.collapsed
                    .iter()
                    .map(|c| Value::Count(c.iter().filter(|&&x| x).count() as u64)),
            );
            row
        })
        .collect();
    Table { columns, rows }
}

/// The document of a dynamic-route fragility.
pub fn dynamic_document(scene: &Scene, f: &DynamicFragility) -> Document {
    let report = FragilityReport::dynamic(scene, f);
    let mut doc = Document::new(&scene.origin);
    doc.lead.push(format!(
        "Fragility by the dynamic route (multiple-stripe analysis): {} Latin hypercube samples (seed {}), each run in the DEM under each of {} record(s) scaled to each of {} stripe(s) of PGA",
        f.samples.len(),
        f.seed,
        f.records.len(),
        f.stripes.len()
    ));
    inputs_section(
        &mut doc,
        &f.inputs,
        &f.correlation,
        "every sample is the scene itself (the spread comes from the records alone)",
    );
    let sec = doc.section("Stripes");
    sec.table(Table {
        columns: vec![
            Column::right("PGA (g)", 8),
            Column::right("runs", 6),
            Column::right("collapses", 9),
            Column::right("share", 6),
        ],
        rows: f
            .stripes
            .iter()
            .map(|s| {
                vec![
                    Value::number(s.pga, 3),
                    Value::Count(s.runs),
                    Value::Count(s.collapses),
                    Value::number(s.collapses as f64 / s.runs as f64, 3),
                ]
            })
            .collect(),
    });
    for r in &f.records {
        sec.item(format!("record: {r}"));
    }
    let sec = doc.section("Fragility");
    match &f.fit {
        Ok(fit) => {
            sec.line(fit_words(fit).replace(" g ", " g PGA "));
        }
        Err(e) => {
            sec.warning(format!("no lognormal fit: {e}"));
        }
    }
    samples_section(&mut doc, f.samples.len(), || dynamic_table(f));
    doc.data = Some(Data::Fragility(Box::new(report)));
    doc
}

/// The dynamic route's chart: the fitted lognormal over each stripe's share of collapses.
pub fn dynamic_chart(scene: &Scene, f: &DynamicFragility) -> Chart {
    let top = f
        .stripes
        .iter()
        .map(|s| s.pga)
        .fold(0.0_f64, f64::max)
        .max(1e-3)
        * 1.15;
    let mut series = Vec::new();
    series.extend(f.fit.as_ref().ok().map(|fit| fit_series(fit, top)));
    series.push(Series {
        name: "stripes (share of runs that collapse)".into(),
        points: f
            .stripes
            .iter()
            .map(|s| (s.pga, s.collapses as f64 / s.runs as f64))
            .collect(),
        markers: crate::drawing::chart::Markers::Every,
    });
    Chart {
        title: format!(
            "Fragility (dynamic route, {} samples x {} record(s)): {}",
            f.samples.len(),
            f.records.len(),
            scene.origin
        ),
        x_label: "peak ground acceleration PGA (g)".into(),
        y_label: "probability of collapse (DEM)".into(),
        legend_title: None,
        series,
    }
}

/// The uncertain inputs as a section (`empty`: what a scene without them gives).
fn inputs_section(
    doc: &mut Document,
    inputs: &[UncertainInput],
    correlation: &[crate::scene::uncertain::RankCorrelation],
    empty: &str,
) {
    let sec = doc.section("Uncertain inputs");
    if inputs.is_empty() {
        sec.warning(format!("the scene has no [uncertain] table: {empty}"));
    }
    for i in inputs {
        sec.item(format!(
            "{}: {} ({})",
            i.key,
            i.dist.name(),
            i.dist.parameters()
        ));
    }
    for c in correlation {
        sec.item(format!(
            "rank correlation {} between {} and {} (Iman-Conover)",
            c.rank, c.between[0], c.between[1]
        ));
    }
    if !inputs.is_empty() && correlation.is_empty() && inputs.len() > 1 {
        sec.line("the inputs are sampled independently");
    }
}

/// The per-sample table, or where to find it: a long table is for the CSV (or the JSON),
/// not the terminal.
fn samples_section(doc: &mut Document, samples: usize, table: impl FnOnce() -> Table) {
    let sec = doc.section("Samples");
    if samples <= TABLE_ROWS {
        sec.table(table());
    } else {
        sec.line(format!(
            "{samples} samples: the per-sample table is in --csv FILE (and --json)"
        ));
    }
}

/// The first columns of a per-sample table: the sample and each input.
fn input_columns(inputs: &[UncertainInput]) -> Vec<Column> {
    let mut columns = vec![Column::right("sample", 6)];
    columns.extend(inputs.iter().map(|i| Column::right(i.key.clone(), 20)));
    columns
}

/// The first cells of sample `i`'s row, its values at full precision (the table is the data
/// of the CSV).
fn input_cells(i: usize, values: &[f64]) -> Vec<Value> {
    let mut row = vec![Value::Count(i as u64)];
    row.extend(values.iter().map(|&v| Value::Text(format!("{v}"))));
    row
}

/// The fitted lognormal CDF from 0 to `top`, its median marked; a step drawn as a vertical
/// rise at the median.
fn fit_series(fit: &LognormalFit, top: f64) -> Series {
    let n = 200;
    let mut points: Vec<(f64, f64)> = (0..=n)
        .map(|i| {
            let a = top * i as f64 / n as f64;
            (a, fit.probability(a))
        })
        .collect();
    if fit.beta == 0.0 {
        points.push((fit.median, 0.0));
        points.push((fit.median, 1.0));
        points.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.total_cmp(&b.1)));
    }
    Series::line(
        format!(
            "lognormal fit: median {:.3} g, beta {:.3}",
            fit.median, fit.beta
        ),
        points,
        [(fit.median, 0.5)],
    )
}
