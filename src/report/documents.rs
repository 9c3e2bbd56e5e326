//! The document of each command ([`Document`]): what `analyze`, `min-thickness`, `dem`,
//! `assess` and `convergence` found, in sections, for any printer ([`super::text`],
//! [`super::json`]). The words they use are in [`super::words`].

use super::assessment::{ag_text, direction_words, verdict_line, verdict_word, AssessmentReport};
use super::document::{Column, Data, Document, Section, Table, Value};
use super::words::*;
use super::{
    AnalysisReport, DemReport, DynamicReport, IdaReport, MinThicknessReport, PulseCurveReport,
};
use crate::analysis::{Assessment, SceneAnalysis, SiteAssessment};
use crate::assembly::JointKind;
use crate::assess::RULE;
use crate::convergence::Convergence;
use crate::kinematic::Search;
use crate::model::Model;
use crate::outcome::{Direction, Status};
use crate::scene::Scene;
use crate::statics::StaticResult;
use crate::thickness::{ThicknessAnalysis, ThicknessOutcome};

/// The document of `analyze`: the static bound and every other method that ran.
pub fn analysis(scene: &Scene, a: &SceneAnalysis) -> Document {
    let assembly = &a.model.assembly;
    let mut doc = Document::new(&scene.origin);
    doc.lead = scene_lines(scene, &a.model);
    static_section(&mut doc, &a.model, &a.lower);
    let sec = doc.untitled();
    match &a.upper {
        Ok(k) => {
            match (k.status, k.lambda_upper) {
                (Status::Collapse, Some(u)) => {
                    let general = k.search == Search::General;
                    if k.search == crate::kinematic::Search::Certified {
                        sec.head(format!("Kinematic (upper bound): lambda = {u:.6}, the mechanism of the static hinges by virtual work ({:.2} ms)",
                            k.wall_time_s * 1e3));
                    } else if general {
                        sec.head(format!("Kinematic (upper bound): lambda = {u:.6}, the least over every admissible mechanism of the blocks (the general kinematic program, certified by virtual work; {:.1} ms)",
                            k.wall_time_s * 1e3));
                    } else {
                        sec.head(format!(
                            "Kinematic (upper bound): lambda = {u:.6} over {} ({:.1} ms)",
                            count(
                                k.admissible,
                                "admissible mechanism",
                                "admissible mechanisms"
                            ),
                            k.wall_time_s * 1e3
                        ));
                    }
                    if a.sliding_governs() && !general {
                        let mu = num(scene.material.friction);
                        let words = if a.lower.status == Status::CannotStand {
                            format!("with mu = {mu} the structure slides before any of them forms")
                        } else {
                            format!(
                                "with mu = {mu} the structure slides first, at the static bound {:.6}",
                                a.lower.lambda.unwrap_or(f64::NAN)
                            )
                        };
                        sec.line(format!("rotational mechanisms only: {words}"));
                    }
                    if let Some(note) = &k.note {
                        sec.line(note.clone());
                    }
                    if let Some(m) = &k.mechanism {
                        let joints = m
                            .hinges
                            .iter()
                            .map(|h| h.joint)
                            .chain(m.open.iter().copied());
                        sec.line(format!(
                            "governing mechanism of {}: {}",
                            what_moves(assembly, joints),
                            family_words(m.family)
                        ));
                        let mut items = hinge_items(assembly, &m.hinges);
                        let what = m.open.iter().map(|j| (j, "opens completely"));
                        for (j, does) in what.chain(m.sliding.iter().map(|j| (j, "slides"))) {
                            let label = assembly
                                .joints
                                .get(*j)
                                .map_or("joint".to_string(), |joint| joint_label(joint.kind));
                            items.push(format!("joint {j:>4} ({label}), {does}"));
                        }
                        listed(
                            sec,
                            items,
                            "`mechanism_hinges`, `open_joints` and `mechanism_sliding`",
                        );
                    }
                }
                (Status::NoCollapse, _) => {
                    sec.head("Kinematic (upper bound): no admissible mechanism is driven by the load: no collapse");
                }
                _ => {
                    sec.head("Kinematic (upper bound): a mechanism moves under its permanent loads alone: cannot stand");
                }
            }
            if let (Some(gap), Some(l), Some(u)) = (a.gap(), a.lower.lambda, k.lambda_upper) {
                if k.search == Search::General {
                    // The general program's mechanisms slide too: by duality its bound meets
                    // the static one whether or not sliding governs.
                    sec.line(format!("bounds agree: relative gap {}", sci(gap, 1)));
                    if a.sliding_governs() {
                        sec.line("sliding governs: joints slide in the collapse mechanism (associative friction: both numbers are the associative multiplier, docs/friction.md)");
                    }
                } else if a.sliding_governs() {
                    let below = sliding_shortfall(l, u)
                        .map_or(String::new(), |d| format!(" ({:.1}% lower)", 100.0 * d));
                    sec.line(format!("sliding governs: the static bound {l:.6} is below the rotational mechanisms' {u:.6}{below}"));
                } else if a.model.strength.is_finite() && k.search != Search::Certified {
                    sec.line(format!("the upper bound is the rigid structure's (rigid hinges), {} above the static bound with crushing",
                        sci(gap, 1)));
                } else {
                    sec.line(format!("bounds agree: relative gap {}", sci(gap, 1)));
                }
            } else if a.sliding_governs() {
                if a.lower.status == Status::CannotStand {
                    sec.line(format!("sliding governs: with mu = {} the structure slides under its permanent loads alone, so it cannot stand",
                        num(scene.material.friction)));
                } else {
                    sec.line("sliding governs: only sliding mechanisms collapse the structure");
                }
            } else if k.status != a.lower.status {
                sec.line(format!(
                    "WARNING: the static status is {} but the kinematic one is {}",
                    status_words(a.lower.status),
                    status_words(k.status)
                ));
            }
        }
        Err(note) => {
            sec.head(format!("Kinematic (upper bound): {note}"));
        }
    }
    if let Some(c) = &a.continuous {
        match c {
            Ok(c) => {
                let l = match c.lambda_continuous {
                    Some(l) => format!("lambda = {l:.6}"),
                    None => status_words(c.status).to_string(),
                };
                let sec = doc.section(format!(
                    "Continuous model (hinges anywhere, infinitely many voussoirs): {l} ({:.2} ms)",
                    c.wall_time_s * 1e3
                ));
                for h in &c.hinges {
                    let (at, pier) = match h.location {
                        crate::kinematic::HingeLocation::Arch {
                            from_vertical_deg,
                            polar_deg,
                        } => (
                            format!("arch section at {polar_deg:.3} deg (polar), {from_vertical_deg:.3} deg from the vertical"),
                            false,
                        ),
                        crate::kinematic::HingeLocation::Pier { left, joint } => (
                            format!("{} pier joint {joint}", if left { "left" } else { "right" }),
                            true,
                        ),
                    };
                    let kind = if pier {
                        JointKind::LeftPier(0)
                    } else {
                        JointKind::Arch(0)
                    };
                    let end = h.end.map_or("opens completely", |e| end_words(kind, e));
                    sec.item(format!("{at}, {end}, at ({:.4}, {:.4}) m", h.x, h.y));
                }
            }
            Err(note) => {
                let note = note.strip_prefix("continuous model: ").unwrap_or(note);
                doc.section(format!("Continuous model: {note}"));
            }
        }
    }
    friction_section(&mut doc, a);
    doc.with_data(Data::Analysis(Box::new(AnalysisReport::new(scene, a))))
}

/// `analyze --roll`: the multiplier at every position of the moving load, then the analysis
/// at its critical position (its mechanism); the JSON is that analysis's object with `roll`.
pub fn roll(scene: &Scene, r: &crate::roll::Roll) -> Document {
    let mut doc = match &r.critical {
        Some(c) => analysis(&c.scene, &c.analysis),
        None => Document::new(&scene.origin),
    };
    let target = r.spec.target;
    let mut sec = Section::new(Some(match &r.critical {
        Some(c) => format!(
            "Moving load {target}: critical position {:.6} m (lambda = {}), from {} positions {} to {} m every {} m",
            c.position,
            c.analysis.lower.lambda.map_or("none".into(), |l| format!("{l:.6}")),
            r.points.len(),
            r.spec.from,
            r.spec.to,
            r.spec.step
        ),
        None => format!(
            "Moving load {target}: the structure cannot stand at any of the {} positions",
            r.points.len()
        ),
    }));
    if let Some(c) = &r.critical {
        sec.line(format!(
            "The least static multiplier of the grid is at {:.6} m; the position is refined between its neighbours by golden section, and the analysis below is at the critical position.",
            c.grid_position
        ));
    }
    sec.table(Table {
        columns: vec![
            Column::right("position_m", 12),
            Column::left("status", 14),
            Column::right("lambda_lower", 14),
            Column::right("lambda_upper", 14),
        ],
        rows: r
            .points
            .iter()
            .map(|p| {
                vec![
                    Value::number(p.position, 4),
                    Value::text(p.status.as_str()),
                    Value::maybe(p.lambda_lower, 6, "none"),
                    Value::maybe(p.lambda_upper, 6, "none"),
                ]
            })
            .collect(),
    });
    doc.sections.insert(0, sec);
    if let Some(Data::Analysis(report)) = &mut doc.data {
        report.roll = Some(super::json::RollReport::new(r));
    }
    doc
}

/// The non-associative multiplier and the DEM check, when they ran: where the associative,
/// the non-associative and the DEM's values sit (docs/friction.md).
fn friction_section(doc: &mut Document, a: &SceneAnalysis) {
    if let Some(na) = a
        .non_associative
        .as_ref()
        .filter(|n| !n.from_exact || n.unsearched)
    {
        let head = match na.lambda {
            _ if na.unsearched => {
                "Non-associative friction: not iterated (lower collapse states not searched for)"
                    .to_string()
            }
            Some(l) => {
                format!("Non-associative friction (joints slide without opening): lambda = {l:.6}")
            }
            None => "Non-associative friction: no converged multiplier".to_string(),
        };
        let sec = doc.section(head);
        sec.line(super::words::non_associative_words(na));
        if !na.sliding.is_empty() {
            sec.line(format!(
                "joints that slide in its mechanism: {}",
                joint_list(&na.sliding, "non_associative_sliding_joints")
            ));
        }
        sec.items(na.starts.iter().map(|s| {
            let l = s.lambda.map_or("none".to_string(), |l| format!("{l:.6}"));
            let how = if let Some(by) = s.settled_by {
                format!("converged ({})", by.as_str().replace('_', " "))
            } else {
                format!(
                    "not converged ({})",
                    s.stopped.as_deref().unwrap_or("stopped")
                )
            };
            format!(
                "start {}: lambda = {l} after {} programs, {how}",
                s.start.as_str(),
                s.iterations
            )
        }));
    }
    if let Some(d) = &a.dem {
        let sec = doc.section("Where the multipliers sit");
        if let Some(l) = a.lower.lambda {
            sec.item(format!("associative (static program): {l:.6}"));
        }
        match a.non_associative.as_ref().and_then(|n| n.lambda) {
            Some(l) => sec.item(format!("non-associative (iteration): {l:.6}")),
            None => sec.item("non-associative: not computed or not converged".to_string()),
        };
        match d {
            Ok(d) => match (d.lambda_stands, d.lambda_collapses) {
                (Some(s), Some(c)) => sec.item(format!(
                    "DEM (Coulomb contacts, no dilatancy): stands at {s:.6}, collapses at {c:.6}"
                )),
                _ => sec.item("DEM: no bracket (see `voussoir dem`)".to_string()),
            },
            Err(e) => sec.item(format!("DEM: {e}")),
        };
    }
}

/// The section of the static analysis.
fn static_section(doc: &mut Document, model: &Model, r: &StaticResult) {
    let assembly = &model.assembly;
    let sec = doc.untitled();
    let dir = match r.direction {
        Direction::Right => "toward +x (right)",
        Direction::Left => "toward -x (left)",
    };
    let live = model.loads.action() == crate::model::Action::Live;
    let friction = r.friction(assembly);
    // Without sliding in the mechanism the static multiplier is exact (a lower bound unless
    // real joints may have lower collapse states, in a wall); with it, the associative one, an
    // upper bound of the real collapse (docs/friction.md).
    let bound = if friction.is_lower_bound() {
        "Static (lower bound)"
    } else {
        "Static (associative friction)"
    };
    match (r.status, r.lambda) {
        (Status::Collapse, Some(l)) => {
            let moving = r
                .hinges
                .iter()
                .map(|h| h.joint)
                .chain(r.sliding.iter().copied())
                .chain(r.open.iter().copied());
            let r_v = model.loads.vertical_ratio();
            let vertical = if r_v != 0.0 {
                format!(
                    ", with a vertical one of {:.4} g {}",
                    (r_v * l).abs(),
                    if r_v > 0.0 { "upward" } else { "downward" }
                )
            } else {
                String::new()
            };
            if live {
                sec.head(format!("{bound}: adequacy factor lambda = {l:.6}"))
                    .line(format!(
                        "{} becomes a mechanism when the live loads are {l:.4} times as given",
                        what_moves(assembly, moving)
                    ));
            } else {
                sec.head(format!("{bound}: collapse multiplier lambda = {l:.6}"))
                    .line(format!(
                        "{} becomes a mechanism under a horizontal acceleration of {l:.4} g {dir}{vertical}",
                        what_moves(assembly, moving)
                    ));
            }
            if let Some(words) = friction_words(&friction, r.status) {
                sec.line(words);
            }
            if let Some(words) = super::words::exact_friction_words(&friction) {
                sec.line(words);
            }
            sec.line("hinges of the thrust line:");
            listed(sec, hinge_items(assembly, &r.hinges), "`hinges`");
            if !r.sliding.is_empty() {
                sec.line(format!(
                    "sliding joints (|V| = mu N): {}",
                    joint_list(&r.sliding, "sliding")
                ));
            }
            if !friction.slipping.is_empty() {
                sec.line(format!(
                    "joints that slip in the collapse mechanism: {}",
                    joint_list(&friction.slipping, "slipping_joints")
                ));
            }
            if !r.ties.is_empty() {
                sec.line("tie rods at collapse:");
                sec.items(tie_items(model, &r.ties));
            }
            if !r.strips.is_empty() {
                sec.line("bonded strips at collapse:");
                sec.items(strip_items(model, &r.strips));
            }
            if !model.passive.is_empty() {
                sec.line(super::words::passive_words(&r.passive));
            }
            sec.line(format!(
                "equilibrium residual {} N ({} of the weight)",
                sci(r.equilibrium_residual, 2),
                sci(r.equilibrium_residual / model.loads.force_scale(), 1)
            ));
        }
        (Status::NoCollapse, _) if live => {
            sec.head(format!("{bound}: NO COLLAPSE — a thrust line fits inside the structure for any multiple of the live loads"));
        }
        (Status::NoCollapse, _) => {
            sec.head(format!("{bound}: NO COLLAPSE — a thrust line fits inside the structure for any horizontal acceleration {dir}"));
        }
        _ => {
            let without = if live {
                "without the live loads"
            } else {
                "without horizontal load"
            };
            sec.head(format!("Static (lower bound): CANNOT STAND — no thrust line fits inside the structure even {without}"))
                .line("(thinner than its minimum thickness, loads too heavy or too one-sided, piers too slender, or too little friction)");
        }
    }
    if r.status == Status::NoCollapse {
        if let Some(words) = friction_words(&friction, r.status) {
            sec.line(words);
        }
    }
    let program = if r.model.variables == 4 && r.model.equality_rows == 0 {
        "chain program (lambda and the three redundants)"
    } else {
        "conic program"
    };
    let solver = if r.solver_status.starts_with("active set") {
        // The stand test at lambda = 0, when it decided the status, says why.
        let at_zero = r
            .solver_status
            .find("; at lambda = 0")
            .map_or(String::new(), |i| {
                format!(" ({})", &r.solver_status[i + 2..])
            });
        format!(
            "active set, exact vertex, in {}{at_zero}",
            count(u64::from(r.iterations), "pivot", "pivots")
        )
    } else {
        format!(
            "Clarabel {} in {}",
            r.solver_status,
            count(u64::from(r.iterations), "iteration", "iterations")
        )
    };
    sec.line(format!(
        "{program}: {}, {}; {solver}, {:.2} ms",
        count(r.model.variables as u64, "variable", "variables"),
        count(r.model.constraints as u64, "constraint", "constraints"),
        r.solve_time_s * 1e3
    ));
}

/// One line per bonded strip: the joints where it has debonded (reached its capacity).
fn strip_items(model: &Model, forces: &[crate::model::StripForce]) -> Vec<String> {
    let sources = model
        .strips
        .iter()
        .map(|s| s.source)
        .max()
        .map_or(0, |m| m + 1);
    (0..sources)
        .map(|k| {
            let mine: Vec<_> = model
                .strips
                .iter()
                .zip(forces)
                .filter(|(s, _)| s.source == k)
                .collect();
            let face = match mine.first().map(|(s, _)| s.end) {
                Some(crate::assembly::JointEnd::P1) => "intrados",
                _ => "extrados",
            };
            let debonded: Vec<String> = mine
                .iter()
                .filter(|(_, f)| f.yielded)
                .map(|(s, _)| {
                    format!(
                        "{} ({})",
                        s.joint,
                        joint_label(model.assembly.joints[s.joint].kind)
                    )
                })
                .collect();
            let capacity = mine.first().map_or(0.0, |(s, _)| s.capacity);
            format!(
                "strip {k} ({face}, {} N at each of {} joints): {}",
                num(capacity),
                mine.len(),
                if debonded.is_empty() {
                    "holds everywhere (below its capacity)".to_string()
                } else {
                    format!(
                        "at its capacity (debonding) at joint {}",
                        debonded.join(", ")
                    )
                }
            )
        })
        .collect()
}

/// One line per tie rod: its force at collapse, whether it yielded, and where it is anchored.
fn tie_items(model: &Model, forces: &[crate::model::TieForce]) -> Vec<String> {
    let anchor = |a: &crate::model::Anchor| {
        let on = a
            .block
            .map_or("the ground".to_string(), |b| format!("block {b}"));
        format!("({}, {}) m on {on}", num(a.point.x), num(a.point.y))
    };
    model
        .ties
        .iter()
        .zip(forces)
        .enumerate()
        .map(|(k, (t, f))| {
            let state = if f.yielded {
                "yielded".to_string()
            } else if f.force <= t.prestress * (1.0 + 1e-6) {
                "at its prestress".to_string()
            } else {
                format!(
                    "{:.0} % of its capacity, keeps its length",
                    100.0 * f.force / t.capacity
                )
            };
            format!(
                "tie {k}: {:.1} N of {} N ({state}), from {} to {}",
                f.force,
                num(t.capacity),
                anchor(&t.from),
                anchor(&t.to)
            )
        })
        .collect()
}

/// The name of the arch's size (`R`, `span/2`), or `size` for the user's blocks.
fn size_name(scene: &Scene) -> &'static str {
    scene.arch.as_ref().map_or("size", |a| a.shape.size_name())
}

/// The arch's thickness (NaN for the user's blocks).
fn thickness(scene: &Scene) -> f64 {
    scene.arch.as_ref().map_or(f64::NAN, |a| a.thickness)
}

/// The document of `min-thickness`: the static minimum thickness, then the kinematic and the
/// continuous model's where they ran.
pub fn min_thickness(scene: &Scene, model: &Model, t: &ThicknessAnalysis) -> Document {
    let assembly = &model.assembly;
    let (m, rep) = (&t.lower, MinThicknessReport::new(scene, model, t));
    let mut doc = Document::new(&scene.origin);
    doc.lead = scene_lines(scene, model);
    let sec = doc.untitled();
    match (m.search.outcome, m.search.min_thickness) {
        (ThicknessOutcome::Found, Some(t)) => {
            sec.head(format!(
                "Minimum thickness (static, lambda = 0): t_min = {t:.9} m  (t_min / {} = {:.6})",
                size_name(scene),
                t / scene.arch_size()
            ));
            if let Some(f) = m.safety_factor {
                sec.line(format!(
                    "geometric safety factor of t = {} m: {f:.4}{}",
                    num(thickness(scene)),
                    if f < 1.0 {
                        "  (below 1: this arch cannot stand)"
                    } else {
                        ""
                    }
                ));
            }
            sec.line("hinges of the thrust line at t_min:");
            sec.items(hinge_items(assembly, &m.hinges));
        }
        (ThicknessOutcome::NeverStands, _) => {
            sec.head(format!("No thickness lets this structure stand (up to the largest the shape admits, {} m).",
                num(scene.max_thickness())));
        }
        _ => {
            sec.head("The structure stands at every thickness tried, down to the thinnest a scene admits (1e-6 of the largest, at least 1e-6 m): no minimum thickness.");
        }
    }
    sec.line(count(
        m.search.evaluations as u64,
        "static analysis",
        "static analyses",
    ));
    match (rep.min_thickness_kinematic, &rep.kinematic_note) {
        (Some(t), note) => {
            let sec = doc.section(format!(
                "Kinematic minimum thickness (lambda_upper = 0): t_min = {t:.9} m{}",
                rep.min_thickness_gap.map_or(String::new(), |g| format!(
                    "  (relative difference {})",
                    sci(g, 1)
                ))
            ));
            if let Some(note) = note {
                sec.line(format!("note: {note}"));
            }
        }
        (None, Some(note)) => {
            doc.section(format!("Kinematic: {note}"));
        }
        _ => {}
    }
    if let Some(na) = &t.non_associative {
        doc.section(match na.min_thickness {
            Some(v) => format!(
                "Non-associative minimum thickness (joints slide without opening): t_min = {v:.6} m ({} trials, bisected to 1e-6; docs/friction.md)",
                na.evaluations
            ),
            None => format!(
                "Non-associative minimum thickness: none found ({:?}, {} trials)",
                na.outcome, na.evaluations
            ),
        });
    }
    if let Some(c) = rep.min_thickness_continuous {
        match c {
            Some(t) => {
                doc.section(format!(
                    "Continuous model minimum thickness: t_min = {t:.6} m (t_min / {} = {:.6})",
                    size_name(scene),
                    t / scene.arch_size()
                ));
            }
            None => {
                doc.section(format!(
                    "Continuous model: no minimum thickness found{}",
                    rep.continuous_note
                        .as_ref()
                        .map_or(String::new(), |n| format!(" ({n})"))
                ));
            }
        }
    }
    doc.with_data(Data::MinThickness(Box::new(rep)))
}

/// The document of `dem`: the DEM's bracket of the collapse multiplier against the static
/// bound.
pub fn dem(scene: &Scene, model: &Model, rep: DemReport) -> Document {
    let mut doc = Document::new(&scene.origin);
    doc.lead = scene_lines(scene, model);
    let sec = doc.untitled();
    let fmt = |x: Option<f64>| x.map_or("none".to_string(), |v| format!("{v:.6}"));
    match rep.status {
        "collapse" => {
            let bracket = rep
                .bracket_width
                .map_or(String::new(), |w| format!(" (bracket {:.2}%)", 100.0 * w));
            sec.head(format!("DEM: stands at lambda = {}, collapses at lambda = {}  ->  lambda_dem = {}{bracket}",
                fmt(rep.lambda_stands),
                fmt(rep.lambda_collapses),
                fmt(rep.lambda_dem)));
            let shape = if rep.simulated_shape == "chord_polygons" {
                " of the chord polygons the DEM simulates"
            } else {
                ""
            };
            // With sliding joints the static program's multiplier is the associative one, an
            // upper bound of the real collapse (docs/friction.md), which the DEM's Coulomb
            // contacts (no dilatancy) may well fall below.
            let bound = if rep.friction_exact == Some(false) {
                "the static multiplier (associative friction, an upper bound of the real collapse)"
            } else if rep.friction_lower_states_possible == Some(true) {
                "the static multiplier (associative friction, exact, not proved the lowest)"
            } else {
                "the static lower bound"
            };
            if let (Some(l), Some(d)) = (rep.lambda_lower_simulated, rep.relative_difference) {
                let inside = rep.static_inside_bracket == Some(true);
                if inside {
                    sec.line(format!("{bound}{shape} {l:.6} lies inside the DEM bracket: they agree to within its width (narrow it with --tolerance)"));
                } else {
                    sec.line(format!("{bound}{shape} {l:.6} lies outside the DEM bracket: the DEM differs by {:+.2}%",
                        100.0 * d));
                }
            }
            if let (true, Some(l)) = (rep.simulated_shape == "chord_polygons", rep.lambda_lower) {
                sec.line(format!(
                    "(the static lower bound of the curved voussoirs themselves is {l:.6})"
                ));
            }
            if !rep.hinges.is_empty() {
                sec.line("hinges at the onset of collapse:");
                sec.items(hinge_items(&model.assembly, &rep.hinges));
            }
            if !rep.sliding.is_empty() {
                let list: Vec<String> = rep.sliding.iter().map(|j| j.to_string()).collect();
                sec.line(format!("sliding joints: {}", list.join(", ")));
            }
        }
        "no_collapse" => {
            sec.head("DEM: no collapse up to the largest multiplier tried");
        }
        _ => {
            sec.head(
                "DEM: CANNOT STAND — the blocks do not come to rest under their permanent loads",
            );
        }
    }
    if rep.simulated_shape == "chord_polygons" {
        sec.line("curved voussoirs are simulated as polygons (straight chords), so the DEM is compared with\nthe static bound of those polygons, not of the exact annular pieces (docs/dem.md)");
    }
    let start = match rep.guess_source {
        crate::dem::GuessSource::Static => "the static lower bound (--from-static: the DEM verifies the static value; a difference near 0 is by construction)",
        crate::dem::GuessSource::Given => "dem.initial_guess",
        crate::dem::GuessSource::Default => "the default start, independent of the static bound",
    };
    sec.line(format!(
        "bracket searched from lambda = {:.6}, {start}",
        rep.initial_guess
    ));
    if rep.friction_infinite {
        sec.line(format!("mu = inf simulated as mu = {}", num(rep.friction)));
    }
    sec.line(format!(
        "{}, {} of {:.3e} s (at most {} a run, limit {}), {:.2} s wall time",
        count(rep.runs.len() as u64, "run", "runs"),
        count(rep.steps, "time step", "time steps"),
        rep.time_step,
        rep.planned_steps_per_run,
        rep.max_steps,
        rep.wall_time_s
    ));
    for w in &rep.warnings {
        sec.warning(w.as_str());
    }
    doc.with_data(Data::Dem(Box::new(rep)))
}

/// The document of a dynamic DEM run: the ground motion, then what the blocks did.
pub fn dynamic(scene: &Scene, model: &Model, rep: DynamicReport) -> Document {
    let mut doc = Document::new(&scene.origin);
    doc.lead = scene_lines(scene, model);
    let sec = doc.section(format!(
        "ground motion: {} (PGA {:.4} m/s^2 = {:.4} g, {:.3} s){}",
        rep.excitation,
        rep.pga,
        rep.pga / crate::dem::record::STANDARD_GRAVITY,
        rep.duration,
        component_words(rep.component)
    ));
    if let (Some(v), Some(pga)) = (&rep.vertical_excitation, rep.pga_vertical) {
        sec.line(format!(
            "with the vertical {v} (PGA {pga:.4} m/s^2 = {:.4} g, upward positive)",
            pga / crate::dem::record::STANDARD_GRAVITY
        ));
    }
    let sec = doc.untitled();
    match rep.status {
        "cannot_stand" => {
            sec.head(
                "DEM: CANNOT STAND — the blocks do not come to rest under their permanent loads",
            );
            return doc.with_data(Data::Dynamic(Box::new(rep)));
        }
        "collapse" => {
            sec.head(format!(
                "DEM: COLLAPSE at t = {:.3} s",
                rep.collapse_time.unwrap_or(f64::NAN)
            ));
        }
        "undecided" => {
            sec.head(format!("DEM: UNDECIDED — still moving {:.3} s after the motion and its tail, neither at rest nor collapsed",
                rep.extended));
        }
        _ => {
            let how = match rep.end_state {
                crate::dem::dynamic::EndState::Settling => "its motion dying out after the ground stopped: no block point moved by more than 0.25% of the structure's size over the last window",
                crate::dem::dynamic::EndState::Rocking => "still rocking after the ground stopped, with less energy than it needs to tip over its base corner",
                _ => "at rest after the ground stopped",
            };
            sec.head(format!(
                "DEM: survives ({how}{})",
                if rep.extended > 0.0 {
                    format!("; decided {:.3} s past the tail", rep.extended)
                } else {
                    String::new()
                }
            ));
        }
    }
    sec.line(criterion_words(rep.criterion, rep.collapse_displacement));
    sec.line(format!("block {}: peak displacement {:.4e} m, peak rotation {:.4e} rad; residual {:.4e} m, {:.4e} rad",
        rep.control_block,
        rep.peak_displacement,
        rep.peak_rotation,
        rep.residual_displacement,
        rep.residual_rotation));
    sec.line(rest_test_words(
        &rep.rest,
        Some((rep.first_exceedance_s, rep.integration_start_s)),
    ));
    sec.line(format!("no local damping: energy is lost only at the contacts (docs/dem.md)\n{} (at most {}), time step {:.3e} s, {:.2} s wall time",
        count(rep.steps, "time step", "time steps"),
        rep.planned_steps,
        rep.time_step,
        rep.wall_time_s));
    for w in &rep.warnings {
        sec.warning(w.as_str());
    }
    doc.with_data(Data::Dynamic(Box::new(rep)))
}

/// The document of a pulse curve: the minimum collapse amplitude against the period, a
/// table.
pub fn pulse_curve(scene: &Scene, model: &Model, rep: PulseCurveReport) -> Document {
    let g = crate::dem::record::STANDARD_GRAVITY;
    let mut doc = Document::new(&scene.origin);
    doc.lead = scene_lines(scene, model);
    let sec = doc.section(format!("minimum collapse amplitude of one pulse, bracketed to {:.1}% (searches start at {:.4} m/s^2 = {:.4} g{})",
        100.0 * rep.tolerance,
        rep.start_amplitude,
        rep.start_amplitude / g,
        if rep.lambda_lower.is_some() {
            ", the static multiplier times g"
        } else {
            ""
        }));
    let amplitude = |value: f64| Value::Number {
        value,
        digits: 4,
        unit: "m/s^2",
    };
    let rows = rep
        .points
        .iter()
        .map(|p| {
            let (hi, hi_g) = p.amplitude_collapses.map_or(
                (
                    Value::Text(format!(
                        "none <= {:.0} g",
                        crate::analysis::PULSE_CURVE_MAX_G
                    )),
                    Value::text(""),
                ),
                |a| {
                    (
                        amplitude(a),
                        Value::Number {
                            value: a / g,
                            digits: 4,
                            unit: "g",
                        },
                    )
                },
            );
            vec![
                Value::text(p.shape),
                Value::Number {
                    value: p.period,
                    digits: 4,
                    unit: "s",
                },
                amplitude(p.amplitude_survives),
                hi,
                hi_g,
                Value::Count(p.runs as u64),
            ]
        })
        .collect();
    sec.table(Table {
        columns: [
            vec![Column::left("shape", 6)],
            Column::right_all(&[
                ("T (s)", 9),
                ("survives", 14),
                ("collapses", 14),
                ("(g)", 9),
                ("runs", 5),
            ]),
        ]
        .concat(),
        rows,
    });
    sec.line(format!(
        "amplitudes in m/s^2; {:.2} s wall time; collapse criterion: {}",
        rep.wall_time_s,
        rep.criterion.name()
    ));
    sec.line(format!(
        "each point is {} (scan ratio {}: a collapse window narrower than that can be missed)",
        crate::report::json::PULSE_CURVE_SEARCH,
        rep.scan_ratio
    ));
    doc.with_data(Data::PulseCurve(Box::new(rep)))
}

/// The document of an incremental dynamic analysis: the ground motion, then the scale
/// that brackets collapse.
pub fn ida(scene: &Scene, model: &Model, rep: IdaReport) -> Document {
    let mut doc = Document::new(&scene.origin);
    doc.lead = scene_lines(scene, model);
    let g = crate::dem::record::STANDARD_GRAVITY;
    let sec = doc.section(format!(
        "ground motion: {} (PGA {:.4} m/s^2 = {:.4} g){}",
        rep.excitation,
        rep.pga,
        rep.pga / g,
        component_words(rep.component)
    ));
    if let (Some(v), Some(pga)) = (&rep.vertical_excitation, rep.pga_vertical) {
        sec.line(format!(
            "with the vertical {v} (PGA {pga:.4} m/s^2 = {:.4} g, scaled alike)",
            pga / g
        ));
    }
    let sec = doc.untitled();
    match (rep.scale_collapses, rep.collapse_pga) {
        (Some(hi), Some(pga)) => {
            sec.head(format!("IDA: survives at scale {:.4}, collapses at scale {hi:.4} (PGA {pga:.4} m/s^2 = {:.4} g)",
                rep.scale_survives,
                pga / g));
        }
        _ => {
            sec.head(format!(
                "IDA: no collapse up to scale {:.4}",
                rep.scale_survives
            ));
        }
    }
    sec.line(format!("{}, {}, {:.2} s wall time (the first bracket from below: dynamic collapse need not be monotonic in the scale); collapse criterion: {}",
        count(rep.runs.len() as u64, "run", "runs"),
        count(rep.steps, "time step", "time steps"),
        rep.wall_time_s,
        rep.criterion.name()));
    let skipped = rep
        .runs_integration_start_s
        .iter()
        .filter(|s| s.is_none())
        .count();
    let mut words = rest_test_words(&rep.rest, None);
    if rep.rest.rest_test == "applied" {
        words.push_str(&format!(
            "; {} stayed below it and cost no integration",
            count(skipped as u64, "run", "runs")
        ));
    }
    sec.line(words);
    doc.with_data(Data::Ida(Box::new(rep)))
}

/// The summary's line on a dynamic run's rest test (docs/dem.md): the thresholds, and, for
/// one run (`times`: first exceedance and integration start), when the integration started.
fn rest_test_words(
    rest: &super::RestTestReport,
    times: Option<(Option<f64>, Option<f64>)>,
) -> String {
    let note = rest.rest_test_note.as_deref();
    match (
        rest.rest_test,
        rest.rest_lambda_right.zip(rest.rest_lambda_left),
    ) {
        ("applied", Some((right, left))) => {
            let head = format!("rest test: rigid blocks stay at rest while -{right:.6} (g + a_v) < a_h < {left:.6} (g + a_v) (the static multipliers toward +x and -x)");
            match times {
                Some((_, None)) => format!("{head}; the ground never reached it: at rest throughout, nothing integrated (not even the settling)"),
                Some((first, Some(start))) => format!(
                    "{head}; first reached at t = {} s, time integration from t = {start:.4} s (the start of that half-cycle)",
                    first.map_or("?".to_string(), |t| format!("{t:.4}"))
                ),
                None => head,
            }
        }
        ("off", _) => {
            "rest test off: time integration from t = 0 (the contacts' elastic micro-motion shows)"
                .to_string()
        }
        _ => format!(
            "rest test not applicable ({}): time integration from t = 0",
            note.unwrap_or("no threshold")
        ),
    }
}
/// The section of one direction assessed.
fn direction_section(doc: &mut Document, a: &SiteAssessment) {
    let (c, v, s) = (&a.capacity, &a.verdict, &a.site);
    let t = doc.section(format!(
        "Load toward the {}: governing mechanism alpha0 = lambda = {:.6} (static lower bound {}), bodies {}",
        match c.direction {
            Direction::Right => "right",
            Direction::Left => "left",
        },
        c.alpha0,
        a.analysis
            .lower
            .lambda
            .map_or("none".to_string(), |l| format!("{l:.6}")),
        c.motion
            .bodies()
            .iter()
            .map(|r| format!("blocks {}-{}", r.start, r.end.saturating_sub(1)))
            .collect::<Vec<_>>()
            .join(", ")
    ));
    let m = &c.mass;
    t.line(format!("Participating mass: M* = {:.1} kg, e* = {:.4} (of {:.1} N of seismic weight on the moving blocks)",
        m.m_star, m.e_star, m.seismic_weight));
    t.line(format!("Capacity curve ({} points): control point = centroid of block {}, d_k0 = {:.2} mm, d0* = {:.2} mm",
        c.curve.len(),
        c.control_block,
        1e3 * c.d_k0,
        1e3 * c.d0_star));
    t.item(format!("a0* = alpha0 g/(e* FC) = {:.4} m/s^2 (FC = {}), du* = 0.4 d0* = {:.2} mm, ds* = {:.2} mm, as* = {:.4} m/s^2, Ts = {:.3} s",
        c.a0_star,
        s.fc,
        1e3 * v.du_star,
        1e3 * v.ds_star,
        v.as_star,
        v.ts));
    for tie in &c.ties {
        t.item(crate::report::words::tie_on_curve_words(tie));
    }
    let (lin, nonlin) = if s.elevated() {
        (
            "a0* >= max(ag S/q, Se(T1) psi gamma/q)",
            "du* >= max(SDe(Ts), amplified at Z)",
        )
    } else {
        ("a0* >= ag S/q", "du* >= SDe(Ts)")
    };
    t.line(format!(
        "Linear check ({lin}): {:.4} vs {:.4} m/s^2, ratio {:.3}: {}; largest passing ag = {}",
        v.linear.capacity,
        v.linear.demand,
        v.linear.ratio,
        verdict_word(&v.linear),
        ag_text(v.linear.ag_max)
    ));
    t.line(format!(
        "Nonlinear check ({nonlin}): {:.2} vs {:.2} mm, ratio {:.3}: {}; largest passing ag = {}",
        1e3 * v.nonlinear.capacity,
        1e3 * v.nonlinear.demand,
        v.nonlinear.ratio,
        verdict_word(&v.nonlinear),
        ag_text(v.nonlinear.ag_max)
    ));
    t.line(format!(
        "This direction {}; largest passing ag = {}",
        v.text(),
        ag_text(v.ag_max())
    ));
}

/// How the capacity curve was obtained, in words.
fn curve_words(c: &crate::assess::Capacity) -> String {
    use crate::assess::Motion;
    match &c.motion {
        Motion::Linkage(_) => "(The capacity curve keeps the hinges at their joints, as the code method does; past about a third of d_k0 a real arch may move a hinge: docs/assessment.md)".to_string(),
        Motion::Incremental(p) => format!(
            "(The capacity curve is incremental: the structure is moved along its mechanism and the multiplier re-solved in each displaced configuration, {} kinematic programs, so hinges may move and contacts open; {}: docs/assessment.md)",
            p.solves,
            if p.falls {
                "it ends where the displaced structure can no longer stand under any multiplier, before alpha reaches 0 (d_k0 is taken there)"
            } else {
                "it ends where alpha reaches 0"
            }
        ),
    }
}

/// The document of `assess`: the site, each direction assessed, the rule and the verdict
/// of the governing direction.
pub fn assessment(scene: &Scene, all: &Assessment) -> Document {
    let g = all.governing();
    let (v, s) = (&g.verdict, &g.site);
    let sp = &v.spectrum;
    let mut doc = Document::new(format!("Scene: {}", scene.origin));
    // Values the grid gave are interpolated: shown to the digits that mean something (the
    // JSON keeps them whole); given values as given.
    let shown = |x: f64, digits: usize| match s.hazard {
        Some(_) => format!("{x:.digits$}"),
        None => format!("{x}"),
    };
    let t = doc.section(format!(
        "Site: ag = {} g, soil {}, topography {}, F0 = {}, Tc* = {} s, q = {}{}",
        shown(s.ag, 4),
        s.soil.as_str(),
        s.topography.as_str(),
        shown(s.f0, 3),
        shown(s.tc_star, 3),
        s.q,
        if s.elevated() {
            format!(
                ", Z = {} m of H = {} m, T1 = {} s",
                s.z,
                s.h.unwrap_or(f64::NAN),
                s.t1.unwrap_or(f64::NAN)
            )
        } else {
            String::new()
        }
    ));
    if let Some(h) = &s.hazard {
        t.line(crate::report::words::hazard_words(h));
    }
    t.line(format!(
        "spectrum: S = SS ST = {:.3} x {:.2}, TB = {:.3} s, TC = {:.3} s, TD = {:.3} s",
        sp.ss, sp.st, sp.tb, sp.tc, sp.td
    ));
    for a in &all.directions {
        direction_section(&mut doc, a);
    }
    let t = doc.untitled();
    t.statement(curve_words(&g.capacity));
    t.statement(format!("Rule: {RULE}."));
    let words = direction_words(g.capacity.direction);
    if all.restricted {
        t.statement(format!("Direction: only the {words} was assessed (--direction); the other direction is not covered by this verdict"));
    } else {
        let other = all
            .directions
            .iter()
            .enumerate()
            .filter(|(i, _)| *i != all.governing)
            .map(|(_, a)| {
                format!(
                    "{} {}",
                    direction_words(a.capacity.direction),
                    ag_text(a.verdict.ag_max())
                )
            })
            .collect::<Vec<_>>()
            .join(", ");
        t.statement(format!(
            "Governing direction: the {words} (largest passing ag {}; {other})",
            ag_text(v.ag_max())
        ));
    }
    t.statement(format!("Verdict: the mechanism {}", verdict_line(all)));
    doc.with_data(Data::Assessment(Box::new(AssessmentReport::new(
        scene, all,
    ))))
}

/// A number or `-`.
fn opt(v: Option<f64>, digits: usize) -> Value {
    Value::maybe(v, digits, "-")
}

/// A signed relative error, `+1.23e-4`, or `-`.
fn pct(v: Option<f64>) -> Value {
    Value::Text(v.map_or("-".to_string(), |x| format!("{x:+.2e}")))
}

/// A time in milliseconds from seconds.
fn ms(seconds: f64) -> Value {
    Value::Number {
        value: seconds * 1e3,
        digits: 3,
        unit: "ms",
    }
}

/// The document of `convergence`: the refinement, the tolerance and the DEM tables, with the
/// fitted orders.
pub fn convergence(c: Convergence) -> Document {
    let mut doc = Document::new(format!("Convergence study of {}", c.origin));
    doc.lead
        .push(match (c.lambda_continuous, c.continuous_time_s) {
            (Some(l), Some(t)) => format!(
                "continuous model: lambda = {l:.6} ({:.1} ms); errors are relative to it",
                t * 1e3
            ),
            _ => format!(
                "continuous model: none ({}); no errors computed",
                c.continuous_note.as_deref().unwrap_or("not run")
            ),
        });
    let rows = c
        .refinement
        .iter()
        .map(|r| {
            vec![
                Value::Count(r.voussoirs as u64),
                Value::Count(r.joints as u64),
                opt(r.lambda_lower, 6),
                pct(r.error_lower),
                ms(r.lower_time_s),
                Value::Count(u64::from(r.lower_iterations)),
                opt(r.lambda_upper, 6),
                pct(r.error_upper),
                r.upper_time_s.map_or(Value::text("-"), ms),
                Value::text(r.error.as_deref().or(r.upper_note.as_deref()).unwrap_or("")),
            ]
        })
        .collect();
    let order = |o: Option<f64>| o.map_or("-".to_string(), |x| format!("{x:.2}"));
    let sec = doc.section("Refinement");
    sec.table(Table {
        columns: [
            Column::right_all(&[
                ("n", 6),
                ("joints", 6),
                ("lower", 10),
                ("rel err", 10),
                ("ms", 10),
                ("iter", 5),
                ("upper", 10),
                ("rel err", 10),
                ("ms", 10),
            ]),
            vec![Column::left("note", 0).gap(2)],
        ]
        .concat(),
        rows,
    });
    sec.statement(format!(
        "fitted order (slope of log|error| on log n): lower {}, upper {}; static time grows as n^{} (n >= 64)",
        order(c.order_lower),
        order(c.order_upper),
        order(c.lower_time_exponent)
    ));
    if !c.tolerances.is_empty() {
        let rows = c
            .tolerances
            .iter()
            .map(|r| {
                vec![
                    Value::Scientific {
                        value: r.tolerance,
                        digits: 0,
                    },
                    Value::Count(r.voussoirs as u64),
                    opt(r.lambda_lower, 9),
                    Value::Text(r.difference.map_or("-".into(), |d| {
                        if d == 0.0 {
                            "0".into()
                        } else {
                            format!("{d:.1e}")
                        }
                    })),
                    Value::Text(
                        r.residual_over_weight
                            .map_or("-".into(), |d| format!("{d:.1e}")),
                    ),
                    Value::Count(u64::from(r.iterations)),
                    ms(r.time_s),
                    Value::text(r.error.as_deref().unwrap_or("")),
                ]
            })
            .collect();
        doc.section("Clarabel tolerance (static program)")
            .table(Table {
                columns: [
                    Column::right_all(&[
                        ("tol", 8),
                        ("n", 6),
                        ("lower", 12),
                        ("diff", 10),
                        ("resid/W", 10),
                        ("iter", 5),
                        ("ms", 9),
                    ]),
                    vec![Column::left("", 0).gap(2)],
                ]
                .concat(),
                rows,
            });
    }
    if let Some(first) = c.dem.first() {
        let heading = format!(
            "DEM (n = {}, bracket searches started at lambda = {}; error against the static value of the same n)",
            first.voussoirs, c.dem_start
        );
        let rows = c
            .dem
            .iter()
            .map(|r| {
                vec![
                    Value::Text(r.case.tolerance.to_string()),
                    Value::Text(r.case.time_step_factor.to_string()),
                    Value::Text(r.case.stiffness_factor.to_string()),
                    Value::text(r.integrator),
                    Value::Scientific {
                        value: r.time_step_s,
                        digits: 2,
                    },
                    opt(r.lambda_stands, 5),
                    opt(r.lambda_collapses, 5),
                    opt(r.lambda_static, 5),
                    pct(r.error),
                    Value::text(
                        r.brackets_static
                            .map_or("-", |b| if b { "yes" } else { "no" }),
                    ),
                    Value::Count(r.runs as u64),
                    Value::Count(r.steps),
                    Value::number(r.steps_per_s, 0),
                    Value::Number {
                        value: r.time_s,
                        digits: 2,
                        unit: "s",
                    },
                    Value::text(r.error_message.as_deref().unwrap_or("")),
                ]
            })
            .collect();
        doc.section(heading).table(Table {
            columns: [
                Column::right_all(&[
                    ("tol", 7),
                    ("dt x", 5),
                    ("k x", 6),
                    ("stepping", 9),
                    ("dt (s)", 9),
                    ("stands", 9),
                    ("collapses", 9),
                    ("static", 9),
                    ("err", 9),
                    ("brackets", 8),
                    ("runs", 5),
                    ("steps", 9),
                    ("steps/s", 9),
                    ("s", 7),
                ]),
                vec![Column::left("", 0).gap(2)],
            ]
            .concat(),
            rows,
        });
    }
    doc.with_data(Data::Convergence(Box::new(c)))
}

/// How many items (hinges, joints) a summary lists one by one under a line: beyond it the
/// first ones are listed and one more item says how many there are and that the JSON lists
/// them all (a wall's or an arcade's hundreds of hinges would bury the answer; a chain has a
/// handful).
const LISTED_ITEMS: usize = 24;

/// How many joint numbers a summary's line of sliding or slipping joints shows.
const LISTED_JOINTS: usize = 40;

/// How many of `all` things a list that shows at most `most` shows: all of them, unless that
/// hides more than one (a line to hide one would be no shorter).
fn shown(all: usize, most: usize) -> usize {
    if all > most + 1 {
        most
    } else {
        all
    }
}

/// What the cut of a list of `all` things after `shown` says: how many more there are, and
/// the fields of `analyze --json` (`json`) that hold them all (the report's JSON nests that
/// object under `analysis`).
fn more(all: usize, shown: usize, json: &str) -> String {
    format!(
        "and {} more ({all} in all; every one in `analyze --json`'s {json})",
        all - shown
    )
}

/// `items` as a list under the section's last line, cut after [`LISTED_ITEMS`] with an item
/// that counts them and names the JSON fields (`json`) that hold them all.
fn listed(sec: &mut Section, items: Vec<String>, json: &str) {
    let all = items.len();
    let n = shown(all, LISTED_ITEMS);
    sec.items(items.into_iter().take(n));
    if n < all {
        sec.item(format!("... {}", more(all, n, json)));
    }
}

/// The joints `joints` as a comma-separated list, cut after [`LISTED_JOINTS`] with the count
/// and the JSON field (`json_key`) that holds them all.
fn joint_list(joints: &[usize], json_key: &str) -> String {
    let n = shown(joints.len(), LISTED_JOINTS);
    let list: Vec<String> = joints[..n].iter().map(|j| j.to_string()).collect();
    let list = list.join(", ");
    if n < joints.len() {
        format!(
            "{list}, {}",
            more(joints.len(), n, &format!("`{json_key}`"))
        )
    } else {
        list
    }
}
