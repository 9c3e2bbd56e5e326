//! `voussoir retrofit`: its JSON object and its document.

use super::assessment::AssessmentReport;
use super::document::{Data, Document};
use super::{num, scene_lines, AnalysisReport};
use crate::retrofit::{Bar, Retrofit, SiteRetrofit};
use crate::scene::Scene;
use serde::Serialize;

/// `retrofit --json`.
#[derive(Debug, Serialize)]
pub struct RetrofitReport {
    /// The multiplier the design reaches in every direction.
    pub target_lambda: f64,
    /// Whether tie capacities reach it.
    pub feasible: bool,
    /// `"seismic"` (both directions designed) or `"live"` (the adequacy factor).
    pub action: &'static str,
    /// The designed ties (`capacity = "design"`), in the scene's order.
    pub ties: Vec<DesignedTieReport>,
    /// Indices of the designed ties that are not needed (capacity 0).
    pub not_needed: Vec<usize>,
    /// Added: the designed bonded strips (`tensile_capacity = "design"`), in the scene's
    /// order.
    pub reinforcements: Vec<DesignedStripReport>,
    /// Added: indices of the designed strips that are not needed (capacity 0).
    pub reinforcements_not_needed: Vec<usize>,
    /// The least static multiplier of the retrofitted structure over the directions (null
    /// when infeasible).
    pub lambda_lower: Option<f64>,
    /// The least governing multiplier of the retrofitted structure over the directions: the
    /// non-associative one where joints slide without opening, `lambda_lower` otherwise
    /// (docs/friction.md); null when infeasible.
    pub lambda_governing: Option<f64>,
    /// The largest multiplier any capacities reach in every direction (infeasible designs
    /// only; null otherwise, or when the structure cannot stand).
    pub best_reachable_lambda: Option<f64>,
    /// The design strength of the bars (Pa).
    pub tie_design_strength: f64,
    /// The analysis of the retrofitted structure in each direction (`analyze --json`'s
    /// object), with its `direction`.
    pub analyses: Vec<AnalysisReport>,
    /// Added: the design for a site (`--site`): its verdict there; null for `--target-lambda`.
    pub site: Option<SiteDesignReport>,
}

/// `retrofit --site --json`: the design's verdict at the site.
#[derive(Debug, Serialize)]
pub struct SiteDesignReport {
    /// Whether the designed structure passes there (by the code's rule, both directions).
    pub passes: bool,
    /// The least target multiplier whose design passed (`target_lambda`), to 0.1 %; null
    /// when the structure passes as it is, or no capacities make it pass.
    pub lambda_needed: Option<f64>,
    /// The largest target multiplier whose design failed (the bracket's lower end).
    pub lambda_failing: Option<f64>,
    /// Designs and assessments the search computed.
    pub evaluations: usize,
    /// `assess --json`'s object for the designed structure (null when none passes).
    pub assessment: Option<AssessmentReport>,
}

/// One designed tie.
#[derive(Debug, Serialize)]
pub struct DesignedTieReport {
    /// Index in `[[ties]]`.
    pub index: usize,
    /// The least capacity it needs (N), 0 when not needed.
    pub capacity_required: f64,
    pub needed: bool,
    pub cost: f64,
    /// The smallest standard bar that carries it (null when not needed or above the
    /// largest, 40 mm).
    pub bar: Option<Bar>,
}

/// One designed bonded strip.
#[derive(Debug, Serialize)]
pub struct DesignedStripReport {
    /// Index in `[[reinforcements]]`.
    pub index: usize,
    /// `intrados` or `extrados`.
    pub face: &'static str,
    pub from_joint: usize,
    pub to_joint: usize,
    /// The least debonding force it needs at each joint it crosses (N), 0 when not needed:
    /// the strip system (product, width, bond) must reach it; no steel bar.
    pub capacity_required: f64,
    pub needed: bool,
    pub cost: f64,
}

impl RetrofitReport {
    pub fn new(scene: &Scene, r: &Retrofit) -> Self {
        RetrofitReport {
            target_lambda: r.target,
            feasible: r.feasible,
            action: scene.action.as_str(),
            ties: r
                .ties
                .iter()
                .map(|t| DesignedTieReport {
                    index: t.index,
                    capacity_required: t.capacity,
                    needed: t.needed,
                    cost: t.cost,
                    bar: t.bar,
                })
                .collect(),
            not_needed: r
                .ties
                .iter()
                .filter(|t| !t.needed)
                .map(|t| t.index)
                .collect(),
            reinforcements: r
                .strips
                .iter()
                .map(|t| {
                    let spec = &scene.reinforcements[t.index];
                    DesignedStripReport {
                        index: t.index,
                        face: super::json::face_name(spec.face),
                        from_joint: spec.from_joint,
                        to_joint: spec.to_joint,
                        capacity_required: t.capacity,
                        needed: t.needed,
                        cost: t.cost,
                    }
                })
                .collect(),
            reinforcements_not_needed: r
                .strips
                .iter()
                .filter(|t| !t.needed)
                .map(|t| t.index)
                .collect(),
            lambda_lower: r.lambda(),
            lambda_governing: r.lambda_governing(),
            best_reachable_lambda: r.best_reachable,
            tie_design_strength: r.design_strength,
            analyses: r
                .analyses
                .iter()
                .map(|(_, a)| AnalysisReport::new(scene, a))
                .collect(),
            site: None,
        }
    }
}

impl RetrofitReport {
    /// `retrofit --site --json`: the design's object with its verdict at the site.
    pub fn for_site(scene: &Scene, r: &SiteRetrofit) -> Self {
        let designed = crate::retrofit::designed_scene(scene, &r.design);
        let mut report = RetrofitReport::new(scene, &r.design);
        report.site = Some(SiteDesignReport {
            passes: r.assessment.as_ref().is_some_and(|a| a.passes()),
            lambda_needed: r.assessment.as_ref().and(r.bracket.0).map(|_| r.bracket.1),
            lambda_failing: r.bracket.0,
            evaluations: r.evaluations,
            assessment: r
                .assessment
                .as_ref()
                .map(|a| AssessmentReport::new(&designed, a)),
        });
        report
    }
}

/// The document of a retrofit design.
pub fn document(scene: &Scene, r: &Retrofit) -> Document {
    let mut doc = Document::new(&scene.origin);
    if let Some((_, a)) = r.analyses.first() {
        doc.lead = scene_lines(scene, &a.model);
    }
    let sec = doc.untitled();
    let what = designed_words(r);
    if r.feasible {
        let needed = r.ties.iter().any(|t| t.needed) || r.strips.iter().any(|t| t.needed);
        if !needed {
            sec.head(format!(
                "Retrofit for lambda >= {}: no {what} is needed, the structure already carries it",
                num(r.target)
            ));
        } else {
            sec.head(format!(
                "Retrofit for lambda >= {}: the least capacities (static program, both bounds checked below)",
                num(r.target)
            ));
        }
        if !r.ties.is_empty() {
            sec.line("designed ties:");
        }
        for t in &r.ties {
            sec.item(match (t.needed, t.bar) {
                (false, _) => format!("tie {}: not needed (capacity 0)", t.index),
                (true, Some(b)) => format!(
                    "tie {}: needs {:.1} N; the smallest bar that carries it: {} mm ({:.1} kN at {} MPa)",
                    t.index,
                    t.capacity,
                    num(b.diameter_mm),
                    b.capacity / 1000.0,
                    num(r.design_strength / 1e6)
                ),
                (true, None) => format!(
                    "tie {}: needs {:.1} N, more than one 40 mm bar carries",
                    t.index, t.capacity
                ),
            });
        }
        if !r.strips.is_empty() {
            sec.line("designed strips (the debonding force at each joint a strip crosses; the strip system, its product, width and bond, must reach it: no steel bar):");
        }
        for t in &r.strips {
            let spec = &scene.reinforcements[t.index];
            let at = format!(
                "strip {} ({}, joints {} to {})",
                t.index,
                super::json::face_name(spec.face),
                spec.from_joint,
                spec.to_joint
            );
            sec.item(if t.needed {
                format!(
                    "{at}: needs a debonding force of {:.1} N at each joint",
                    t.capacity
                )
            } else {
                format!("{at}: not needed (capacity 0)")
            });
        }
        for (d, a) in &r.analyses {
            let dir = match d {
                crate::outcome::Direction::Right => "toward +x",
                crate::outcome::Direction::Left => "toward -x",
            };
            let lower = a
                .lower
                .lambda
                .map_or("none".to_string(), |l| format!("{l:.6}"));
            let upper = a
                .lambda_upper()
                .map_or("none".to_string(), |u| format!("{u:.6}"));
            let dir = if r.analyses.len() == 1 { "" } else { dir };
            sec.line(format!(
                "re-analysed {dir}: lambda_lower = {lower}, lambda_upper = {upper}"
            ));
            if let Some(na) = a.lambda_non_associative().filter(|_| !a.friction().exact) {
                sec.line(format!(
                    "non-associative multiplier (joints slide without opening) {dir}: {na:.6}"
                ));
                if na < r.target * (1.0 - 1e-6) {
                    sec.warning(format!(
                        "the non-associative multiplier {na:.6} is below the target {}: the capacities come from the static (associative) program, which real joints, sliding without opening, do not reach (docs/friction.md)",
                        r.target
                    ));
                }
            }
        }
    } else {
        sec.head(format!(
            "Retrofit for lambda >= {}: NOT REACHABLE with the {what}s given",
            num(r.target)
        ));
        match r.best_reachable {
            Some(b) => sec.line(format!(
                "the best these {what}s reach, whatever their capacity, is lambda = {b:.6} (another mechanism, which they do not restrain, governs)"
            )),
            None => sec.line(format!("the structure cannot stand under its permanent loads, whatever the {what}s")),
        };
    }
    doc.data = Some(Data::Retrofit(Box::new(RetrofitReport::new(scene, r))));
    doc
}

/// What a design sized, in words: "tie", "strip" or "tie or strip".
fn designed_words(r: &Retrofit) -> &'static str {
    match (r.ties.is_empty(), r.strips.is_empty()) {
        (false, true) => "tie",
        (true, false) => "strip",
        _ => "tie or strip",
    }
}

/// The document of a retrofit design for a site: the design's own document, the search's
/// bracket, and the verdict of the designed structure (`assess`'s words).
pub fn site_document(scene: &Scene, r: &SiteRetrofit) -> Document {
    let designed = crate::retrofit::designed_scene(scene, &r.design);
    let mut doc = document(scene, &r.design);
    // The design's heading names the target multiplier the search settled on.
    if let Some(first) = doc.sections.first_mut() {
        first.heading = Some(match (&r.assessment, r.bracket) {
            (Some(_), (None, _)) => {
                "Retrofit for the site: no tie is needed, the structure passes as it is".into()
            }
            (Some(_), (Some(_), hi)) => format!(
                "Retrofit for the site: the least capacities that pass, those for lambda >= {hi:.4}"
            ),
            (None, (_, hi)) => format!(
                "Retrofit for the site: NOT REACHABLE with the ties given (their strongest design fails at the site; lambda >= {hi:.4} is beyond them)"
            ),
        });
    }
    let sec = doc.section(match (&r.assessment, r.bracket) {
        (Some(_), (None, _)) => {
            "Site design: the structure passes at the site as it is; no tie is needed".to_string()
        }
        (Some(_), (Some(lo), hi)) => format!(
            "Site design: the least capacities that pass at the site are those for lambda >= {hi:.4} (a design for lambda >= {lo:.4} fails; {} designs assessed)",
            r.evaluations
        ),
        (None, _) => {
            "Site design: NO capacities of these ties pass at the site: the strongest design they allow fails there".to_string()
        }
    });
    if let Some(a) = &r.assessment {
        sec.line(format!(
            "the designed structure's verdict: {} (governing direction: {})",
            a.governing().verdict.text(),
            match a.governing().capacity.direction {
                crate::outcome::Direction::Right => "load toward the right",
                crate::outcome::Direction::Left => "load toward the left",
            }
        ));
        let assessment = super::documents::assessment(&designed, a);
        doc.sections.extend(assessment.sections);
    }
    doc.data = Some(Data::Retrofit(Box::new(RetrofitReport::for_site(scene, r))));
    doc
}
