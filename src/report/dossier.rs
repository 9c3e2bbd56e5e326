//! The hand-in report (`voussoir report`, docs/report.md): the analyses of a
//! [`crate::dossier::Dossier`] as chapters in an engineer's order, each chapter a
//! [`Document`] for the HTML printer ([`super::html`]), with the JSON of the same run
//! ([`DossierReport`]: the objects `analyze --json`, `min-thickness --json` and
//! `assess --json` print, and the sensitivity table).
//!
//! The chapters: identification (the scene's `[report]` table and the conclusion), the
//! structure (its drawing, its words and every key of the scene), method and assumptions
//! (with references), results (the documents of `analyze` and `min-thickness`, in their
//! words, and their figures), the seismic check (the document of `assess` and its figures),
//! the sensitivity, the limits of validity, and reproducibility (the scene as given, the
//! version and the input's SHA-256). The results' words are the summaries' own
//! ([`super::documents`], [`super::words`]): the report adds no second wording of a result.

use super::assessment::AssessmentReport;
use super::document::{Column, Document, Figure, Row, Table, Value};
use super::html::Chapter;
use super::words::*;
use super::{documents, figures, AnalysisReport, MinThicknessReport};
use crate::dossier::{Dossier, Sensitivity};
use crate::outcome::Status;
use crate::scene::Scene;
use serde::Serialize;
use sha2::{Digest, Sha256};

/// The scene as the user gave it: its text (printed in full and hashed) and the overrides
/// applied on top (`--site KEY=VALUE`).
#[derive(Debug, Clone)]
pub struct Source {
    /// The scene file's text as read (or the TOML the caller passed).
    pub text: String,
    /// The overrides applied to it, `KEY=VALUE` each, in order.
    pub overrides: Vec<String>,
}

impl Source {
    /// The SHA-256 of the scene's text (its bytes as read), in hex.
    pub fn sha256(&self) -> String {
        Sha256::digest(self.text.as_bytes())
            .iter()
            .map(|b| format!("{b:02x}"))
            .collect()
    }
}

/// The report's JSON (`voussoir report --json`): the objects of the single-purpose commands
/// for the same scene, so that every number the report prints is one of these.
#[derive(Debug, Serialize)]
pub struct DossierReport {
    /// voussoir's version (Cargo's package version).
    pub voussoir_version: &'static str,
    /// SHA-256 of the scene file's bytes, hex.
    pub scene_sha256: String,
    /// The overrides applied to the file (`site.ag=0.25`, ...).
    pub overrides: Vec<String>,
    /// The scene's `[report]` keys that were given.
    pub identification: std::collections::BTreeMap<&'static str, String>,
    /// `voussoir analyze --json` (with `--dem`: its `dem` object).
    pub analysis: AnalysisReport,
    /// `voussoir min-thickness --json`, null when there is none (`min_thickness_note` says
    /// why).
    pub min_thickness: Option<MinThicknessReport>,
    pub min_thickness_note: Option<String>,
    /// `voussoir assess --json` when the scene has a `[site]` and it could be assessed
    /// (`assessment_note` says why not).
    pub assessment: Option<AssessmentReport>,
    pub assessment_note: Option<String>,
    /// The governing multiplier at the thickness and the friction coefficient -10 % / +10 %.
    pub sensitivity: Vec<SensitivityReport>,
    /// Keys not varied and why.
    pub sensitivity_skipped: Vec<SkippedReport>,
    /// Wall time of all the analyses (s).
    pub wall_time_s: f64,
}

/// One row of the sensitivity table.
#[derive(Debug, Serialize)]
pub struct SensitivityReport {
    pub key: &'static str,
    pub base: f64,
    pub factor: f64,
    pub value: f64,
    /// Null when the varied scene could not be analysed (`note` says why).
    pub status: Option<Status>,
    pub lambda_lower: Option<f64>,
    pub lambda_upper: Option<f64>,
    pub lambda_governing: Option<f64>,
    /// The governing multiplier's change against the scene's own, relative.
    pub change: Option<f64>,
    pub note: Option<String>,
}

/// A key the sensitivity table does not vary.
#[derive(Debug, Serialize)]
pub struct SkippedReport {
    pub key: &'static str,
    pub why: String,
}

/// The report: its title, its chapters and its JSON.
#[derive(Debug)]
pub struct HandIn {
    pub title: String,
    pub chapters: Vec<Chapter>,
    pub data: DossierReport,
}

impl HandIn {
    /// The report as one self-contained HTML document.
    pub fn html(&self) -> String {
        super::html::print(&self.title, &self.chapters)
    }

    /// The report's JSON.
    pub fn json(&self) -> String {
        super::json::pretty(&self.data)
    }
}

/// A figure, or a warning in `doc` saying why it could not be drawn.
fn figure<E: std::fmt::Display>(doc: &mut Document, what: &str, f: Result<Figure, E>) {
    match f {
        Ok(f) => doc.figures.push(f),
        Err(e) => {
            doc.untitled()
                .warning(format!("the {what} could not be drawn: {e}"));
        }
    }
}

/// `doc` as a chapter headed `title`: its own title and lead dropped (the report says once
/// what the structure is).
fn chapter(mut doc: Document, title: &str) -> Document {
    doc.title = title.to_string();
    doc.lead.clear();
    doc
}

/// The report of `scene` from the analyses `d`.
pub fn hand_in(scene: &Scene, source: &Source, d: &Dossier) -> HandIn {
    let a = &d.analysis;
    let info = scene.report.clone().unwrap_or_default();
    let title = info
        .title
        .clone()
        .unwrap_or_else(|| format!("Assessment of a {}", shape_title(scene)));
    let analysis_data = AnalysisReport::new(scene, a);
    let mut chapters = vec![identification(scene, source, d, &info)];
    chapters.push(structure(scene, d));
    chapters.push(method(scene, d));
    // Results: the documents of `analyze` and `min-thickness`, in their words.
    let mut results = chapter(documents::analysis(scene, a), "Results");
    results.data = None;
    results.lead.push(format!(
        "The collapse multiplier lambda: the horizontal acceleration, in g, at which the structure becomes a mechanism under {} (docs/friction.md, docs/kinematic.md).",
        if a.model.loads.action() == crate::model::Action::Live {
            "its permanent loads and lambda times its live loads"
        } else {
            "its permanent loads and lambda times its weight acting horizontally"
        }
    ));
    figure(
        &mut results,
        "structure",
        figures::analysis(scene, a, a.lower.direction),
    );
    chapters.push(results);
    let (min_thickness, min_thickness_note) = match &d.thickness {
        Ok(t) => {
            let mut doc = chapter(
                documents::min_thickness(scene, &a.model, t),
                "Minimum thickness",
            );
            doc.data = None;
            doc.lead.push("The thinnest ring that stands under its permanent loads (lambda = 0); the geometric safety factor is the thickness over it (Heyman's).".into());
            match figures::min_thickness(scene, &t.lower) {
                Ok(Some(f)) => doc.figures.push(f),
                Ok(None) => {}
                Err(e) => {
                    doc.untitled()
                        .warning(format!("the thrust line at t_min could not be drawn: {e}"));
                }
            }
            chapters.push(doc);
            (Some(MinThicknessReport::new(scene, &a.model, t)), None)
        }
        Err(why) => {
            let mut doc = Document::new("Minimum thickness");
            doc.untitled()
                .statement(format!("No minimum thickness: {why}"));
            chapters.push(doc);
            (None, Some(why.clone()))
        }
    };
    let (assessment, assessment_note) = seismic(scene, d, &mut chapters);
    chapters.push(sensitivity_chapter(d));
    chapters.push(limits(scene, d));
    chapters.push(reproducibility(scene, source, d));
    let data = DossierReport {
        voussoir_version: env!("CARGO_PKG_VERSION"),
        scene_sha256: source.sha256(),
        overrides: source.overrides.clone(),
        identification: info
            .entries()
            .into_iter()
            .map(|(k, v)| (k, v.to_string()))
            .collect(),
        analysis: analysis_data,
        min_thickness,
        min_thickness_note,
        assessment,
        assessment_note,
        sensitivity: d
            .sensitivity
            .iter()
            .map(|s| sensitivity_row(a, s))
            .collect(),
        sensitivity_skipped: d
            .sensitivity_skipped
            .iter()
            .map(|(key, why)| SkippedReport {
                key,
                why: why.clone(),
            })
            .collect(),
        wall_time_s: d.wall_time_s,
    };
    // The long chapters start a page when printed; the short ones run on.
    const NEW_PAGE: &[&str] = &["The structure", "Results", SEISMIC_TITLE, "Reproducibility"];
    let chapters = chapters
        .into_iter()
        .map(|doc| Chapter {
            new_page: NEW_PAGE.contains(&doc.title.as_str()),
            doc,
        })
        .collect();
    HandIn {
        title,
        chapters,
        data,
    }
}

/// The governing multiplier of the varied analysis against the scene's own.
fn change(base: Option<f64>, varied: Option<f64>) -> Option<f64> {
    match (base, varied) {
        (Some(b), Some(v)) if b != 0.0 => Some((v - b) / b),
        _ => None,
    }
}

fn sensitivity_row(a: &crate::analysis::SceneAnalysis, s: &Sensitivity) -> SensitivityReport {
    let (status, lower, upper, governing, note) = match &s.result {
        Ok(v) => (
            Some(v.status),
            v.lambda_lower,
            v.lambda_upper,
            v.lambda_governing,
            None,
        ),
        Err(why) => (None, None, None, None, Some(why.clone())),
    };
    SensitivityReport {
        key: s.key,
        base: s.base,
        factor: s.factor,
        value: s.value(),
        status,
        lambda_lower: lower,
        lambda_upper: upper,
        lambda_governing: governing,
        change: change(a.lambda_governing(), governing),
        note,
    }
}

/// Chapter 1: who and what, and the conclusion in a few sentences.
fn identification(
    scene: &Scene,
    source: &Source,
    d: &Dossier,
    info: &crate::scene::ReportInfo,
) -> Document {
    let a = &d.analysis;
    let mut doc = Document::new("Identification");
    let mut rows: Vec<Row> = info
        .entries()
        .into_iter()
        .filter(|(k, _)| *k != "title" && *k != "notes")
        .map(|(k, v)| Row::new(capitalised(k), Value::text(v)))
        .collect();
    rows.push(Row::new("Scene file", Value::text(scene_name(scene))));
    if !source.overrides.is_empty() {
        rows.push(Row::new(
            "Overrides",
            Value::text(source.overrides.join(", ")),
        ));
    }
    rows.push(Row::new(
        "Computed by",
        Value::text(format!("voussoir {}", env!("CARGO_PKG_VERSION"))),
    ));
    doc.untitled().rows(rows);
    if let Some(notes) = &info.notes {
        doc.untitled().line(notes.clone());
    }
    let sec = doc.section("Conclusion");
    sec.statement(conclusion_words(scene, a));
    if let Ok(t) = &d.thickness {
        if let Some(f) = t.lower.safety_factor {
            sec.statement(format!(
                "Geometric safety factor t / t_min = {f:.4}{}",
                if f < 1.0 {
                    " (below 1: this arch cannot stand)"
                } else {
                    ""
                }
            ));
        }
    }
    match &d.assessment {
        Some(Ok(all)) => {
            sec.statement(format!(
                "Seismic check (NTC 2018, Circolare 2019 C8.7.1): the mechanism {}",
                super::assessment::verdict_line(all)
            ));
        }
        Some(Err(why)) => {
            sec.statement(format!("Seismic check: not made ({why})"));
        }
        None => {
            sec.statement("Seismic check: not made (the scene has no [site]; give one, or --site ag=... --site soil=...)");
        }
    }
    doc
}

fn capitalised(key: &str) -> String {
    let mut c = key.chars();
    c.next().map_or(String::new(), |f| {
        f.to_uppercase().collect::<String>() + c.as_str()
    })
}

/// The scene file's name (the origin without the overrides it lists).
fn scene_name(scene: &Scene) -> String {
    scene
        .origin
        .split(" (with")
        .next()
        .unwrap_or(&scene.origin)
        .to_string()
}

/// Chapter 2: the structure as given.
fn structure(scene: &Scene, d: &Dossier) -> Document {
    let model = &d.analysis.model;
    let mut doc = Document::new("The structure");
    doc.lead = scene_lines(scene, model);
    figure(&mut doc, "structure", figures::scene(scene, model));
    let sec = doc.section("Model");
    sec.rows(vec![
        Row::new("blocks", Value::Count(model.assembly.blocks.len() as u64)),
        Row::new("joints", Value::Count(model.assembly.joints.len() as u64)),
        Row::new("tie rods", Value::Count(model.ties.len() as u64)),
        Row::new("bonded strips", Value::Count(model.strips.len() as u64)),
    ]);
    let mut table = Table {
        columns: vec![
            Column::left("table", 14),
            Column::left("key", 20),
            Column::left("value", 30),
        ],
        rows: Vec::new(),
    };
    // The identification and the site have chapters of their own.
    let mut keys = scene.table().clone();
    keys.remove("report");
    keys.remove("site");
    scene_rows(&mut table, "", &keys);
    doc.section("Geometry, materials, loads, supports and ties (the scene's keys)")
        .table(table);
    doc
}

/// Every key of `table` with its value, one row each; sub-tables and arrays of tables under
/// their dotted name.
fn scene_rows(out: &mut Table, prefix: &str, table: &toml::Table) {
    for (key, value) in table {
        let name = if prefix.is_empty() {
            key.clone()
        } else {
            format!("{prefix}.{key}")
        };
        match value {
            toml::Value::Table(t)
                if t.values().any(|v| !v.is_table() && !is_tables(v)) || t.is_empty() =>
            {
                scene_rows(out, &name, t)
            }
            toml::Value::Table(t) => scene_rows(out, &name, t),
            v if is_tables(v) => {
                if let Some(items) = v.as_array() {
                    for (i, item) in items.iter().enumerate() {
                        if let Some(t) = item.as_table() {
                            scene_rows(out, &format!("{name}[{i}]"), t);
                        }
                    }
                }
            }
            v => {
                let (section, key) = name.rsplit_once('.').unwrap_or(("", name.as_str()));
                out.rows.push(vec![
                    Value::text(format!("[{section}]")),
                    Value::text(key),
                    Value::text(toml_value(v)),
                ]);
            }
        }
    }
}

/// Whether `v` is an array of tables (`[[loads]]`).
fn is_tables(v: &toml::Value) -> bool {
    v.as_array()
        .is_some_and(|a| !a.is_empty() && a.iter().all(toml::Value::is_table))
}

/// A scene value as the scene file writes it (floats in the shortest form).
fn toml_value(v: &toml::Value) -> String {
    match v {
        toml::Value::Float(x) => num(*x),
        toml::Value::Array(items) => format!(
            "[{}]",
            items.iter().map(toml_value).collect::<Vec<_>>().join(", ")
        ),
        toml::Value::String(s) => s.clone(),
        other => other.to_string(),
    }
}

/// Chapter 3: method and assumptions, in words, with references.
fn method(scene: &Scene, d: &Dossier) -> Document {
    let a = &d.analysis;
    let mut doc = Document::new("Method and assumptions");
    doc.section("Limit analysis of rigid blocks (Heyman's hypotheses)")
        .line("The masonry is taken as rigid blocks with no tensile strength at the joints; sliding is prevented by friction unless a finite coefficient is given; the compressive strength is infinite unless one is given (Heyman 1966, 1982). Under these hypotheses the theorems of limit analysis hold.")
        .item("Static (safe) theorem: any load multiplier for which a thrust line in equilibrium lies within the structure, with every joint force inside its cone, is at most the collapse multiplier. voussoir finds the largest such multiplier by a second-order cone program (Clarabel), the static lower bound.")
        .item("Kinematic (unsafe) theorem: the multiplier that makes the virtual work of any admissible mechanism vanish is at least the collapse multiplier. voussoir values the mechanism of the static hinges by virtual work, or searches every mechanism of the chain (or solves the general kinematic program of any assembly): the kinematic upper bound.")
        .item("Where both bounds meet, their common value is the collapse multiplier of the model (the uniqueness theorem; Gilbert, Casapulla and Ahmed 2006 for blocks with friction).");
    let joint = doc.section("The joint law and friction");
    joint.line(format!(
        "Each joint carries a normal force within its length (no tension) and a shear force at most mu times the normal force (Coulomb), with mu = {} here.",
        num(scene.material.friction)
    ));
    joint.line("The static program's friction cone is associative (a joint that slides also opens, dilatancy). With sliding in the collapse mechanism the associative multiplier is then an upper bound of the real (non-associative) one, not a safe lower bound: the report says so with `friction_exact` false (docs/friction.md), and gives the non-associative multiplier (a sequence of programs with fixed shear capacities) where it was computed.");
    if let Some(words) = friction_words(&a.friction(), a.lower.status) {
        joint.warning(words);
    }
    let crush = doc.section("Crushing");
    if a.model.strength.is_finite() {
        crush.line(format!(
            "A finite compressive strength ({} Pa) bounds each joint's normal force and moment by a stress block (two second-order cones per joint); the kinematic search keeps rigid hinges at the joint ends.",
            num(scene.material.compressive_strength)
        ));
    } else {
        crush.line("The compressive strength is infinite (Heyman's hypothesis): hinges form at the joint ends.");
    }
    doc.section("The seismic check")
        .line("With a [site], the governing mechanism of each direction is assessed by the kinematic method of NTC 2018 (7.x, local mechanisms of masonry) and Circolare 2019 C8.7.1: the participating mass and fraction, the capacity curve of the mechanism turned by finite rotations, the linear check (spectral acceleration a0* at collapse against the demand) and the nonlinear check (ultimate displacement against the spectral demand at the secant period). The structure passes when either check is satisfied in both directions (docs/assessment.md).");
    if d.analysis.dem.is_some() {
        doc.section("The discrete element check")
            .line("The discrete element method (DEM) integrates the rigid blocks in time with penalty contacts that slide without opening (Coulomb, no dilatancy), and brackets the multiplier at which the structure no longer comes to rest: an independent estimate of the non-associative collapse (docs/dem.md).");
    }
    doc.section("References").items([
        "Heyman, J. (1966). The stone skeleton. International Journal of Solids and Structures 2, 249-279.".to_string(),
        "Heyman, J. (1969). The safety of masonry arches. International Journal of Mechanical Sciences 11, 363-385.".to_string(),
        "Heyman, J. (1982). The masonry arch. Ellis Horwood, Chichester.".to_string(),
        "Gilbert, M., Casapulla, C. and Ahmed, H. M. (2006). Limit analysis of masonry block structures with non-associative frictional joints using linear programming. Computers and Structures 84, 873-887.".to_string(),
        "D.M. 17 gennaio 2018, Aggiornamento delle Norme tecniche per le costruzioni (NTC 2018), chapter 7.".to_string(),
        "Circolare 21 gennaio 2019, n. 7 C.S.LL.PP., C8.7.1: analisi dei meccanismi locali di collasso.".to_string(),
    ]);
    doc
}

const SEISMIC_TITLE: &str = "Seismic check (NTC 2018, Circolare 2019 C8.7.1)";

/// Chapter: the seismic check, when the scene has a site; the JSON's assessment and why it
/// is missing.
fn seismic(
    scene: &Scene,
    d: &Dossier,
    chapters: &mut Vec<Document>,
) -> (Option<AssessmentReport>, Option<String>) {
    let title = SEISMIC_TITLE;
    match &d.assessment {
        Some(Ok(all)) => {
            let mut doc = chapter(documents::assessment(scene, all), title);
            doc.data = None;
            let name = scene_name(scene);
            let name = name.rsplit('/').next().unwrap_or(&name);
            figure(
                &mut doc,
                "capacity curve",
                figures::assessment_capacity(all, name),
            );
            figure(&mut doc, "ADRS plot", figures::assessment_adrs(all, name));
            figure(
                &mut doc,
                "mechanism",
                figures::assessment_mechanism(all, name, 0.5),
            );
            chapters.push(doc);
            (Some(AssessmentReport::new(scene, all)), None)
        }
        Some(Err(why)) => {
            let mut doc = Document::new(title);
            doc.untitled()
                .statement(format!("The seismic check could not be made: {why}"));
            chapters.push(doc);
            (None, Some(why.clone()))
        }
        None => {
            let mut doc = Document::new(title);
            doc.untitled().statement("Not made: the scene has no [site] table (give one, or --site ag=0.25 --site soil=B --site F0=2.4 --site Tc_star=0.3).");
            chapters.push(doc);
            (None, Some("no [site]".to_string()))
        }
    }
}

/// Chapter: the sensitivity table.
fn sensitivity_chapter(d: &Dossier) -> Document {
    let a = &d.analysis;
    let mut doc = Document::new("Sensitivity");
    let sec = doc.untitled();
    sec.line(format!(
        "The governing multiplier with one input changed by -10 % and +10 %, everything else as given (the scene's own: {}).",
        a.lambda_governing()
            .map_or_else(|| status_words(a.lower.status).to_string(), |l| format!("lambda = {l:.6}"))
    ));
    let mut table = Table {
        columns: vec![
            Column::left("key", 18),
            Column::right("factor", 6),
            Column::right("value", 10),
            Column::left("status", 12),
            Column::right("lambda", 10),
            Column::right("change", 8),
        ],
        rows: Vec::new(),
    };
    for s in &d.sensitivity {
        let (status, lambda) = match &s.result {
            Ok(v) => (
                Value::text(status_words(v.status)),
                Value::maybe(v.lambda_governing, 6, "-"),
            ),
            Err(_) => (Value::text("not analysed"), Value::text("-")),
        };
        let ch = s
            .result
            .as_ref()
            .ok()
            .and_then(|v| change(a.lambda_governing(), v.lambda_governing));
        table.rows.push(vec![
            Value::text(s.key),
            Value::number(s.factor, 1),
            Value::number(s.value(), 6),
            status,
            lambda,
            ch.map_or(Value::text("-"), |c| Value::Number {
                value: 100.0 * c,
                digits: 1,
                unit: "%",
            }),
        ]);
    }
    if !table.rows.is_empty() {
        sec.table(table);
    }
    for s in &d.sensitivity {
        if let Err(why) = &s.result {
            sec.item(format!("{} x {}: {why}", s.key, s.factor));
        }
    }
    for (key, why) in &d.sensitivity_skipped {
        sec.item(format!("{key} not varied: {why}"));
    }
    doc
}

/// Chapter: the limits of validity.
fn limits(scene: &Scene, d: &Dossier) -> Document {
    let mut doc = Document::new("Limits of validity");
    let sec = doc.untitled();
    sec.item("Plane model: the structure is a plane assembly of its depth; out-of-plane mechanisms, the barrel's three-dimensional behaviour and the fill's passive resistance are not modelled.".to_string());
    sec.item("Rigid blocks: the blocks do not deform; the elastic and settlement behaviour before collapse is outside the model. The multiplier is that of the geometry as given: measured geometry, including deformations already present, should be used.".to_string());
    sec.item("The seismic action is equivalent static (lambda times the weight, horizontally); the capacity curve keeps the hinges at their joints, as the code method does.".to_string());
    if scene.material.friction.is_finite() {
        sec.item("With finite friction the static program is associative: where joints slip, the safe value is the non-associative one (docs/friction.md).".to_string());
    }
    if d.analysis.dem.is_some() {
        sec.item("The DEM's bracket depends on its contact stiffness, damping and time step (docs/dem.md); it is a check, not a bound.".to_string());
    }
    sec.item("The check is of the mechanism found: NTC 2018 asks the engineer to consider every plausible local mechanism of the building, of which this arch or portal is one.".to_string());
    doc
}

/// Chapter: how to get the same numbers again.
fn reproducibility(scene: &Scene, source: &Source, d: &Dossier) -> Document {
    let mut doc = Document::new("Reproducibility");
    let mut rows = vec![
        Row::new("voussoir version", Value::text(env!("CARGO_PKG_VERSION"))),
        Row::new("scene file", Value::text(scene_name(scene))),
        Row::new("SHA-256 of the scene file", Value::text(source.sha256())),
    ];
    if !source.overrides.is_empty() {
        rows.push(Row::new(
            "overrides",
            Value::text(source.overrides.join(" ")),
        ));
    }
    rows.push(Row::new(
        "DEM",
        Value::text(if d.analysis.dem.is_some() {
            "run (--dem)"
        } else {
            "not run"
        }),
    ));
    doc.untitled().rows(rows);
    doc.section("The scene file in full")
        .preformatted(source.text.clone());
    doc
}
