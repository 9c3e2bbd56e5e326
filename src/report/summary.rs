//! The human summaries printed by the CLI, and the titles of drawings and charts.

use super::{DemReport, MinThicknessReport};
use crate::analysis::SceneAnalysis;
use crate::assembly::{Assembly, Hinge, JointKind};
use crate::lp::StaticResult;
use crate::model::Model;
use crate::outcome::{Direction, Status};
use crate::scene::{LoadSpec, Scene, VoussoirShape};
use crate::thickness::{MinThickness, ThicknessOutcome};
use std::fmt::Write as _;

/// Short label of a joint, e.g. `arch 3`, `left pier 0`.
pub fn joint_label(kind: JointKind) -> String {
    match kind {
        JointKind::Arch(j) => format!("arch {j}"),
        JointKind::LeftPier(j) => format!("left pier {j}"),
        JointKind::RightPier(j) => format!("right pier {j}"),
        JointKind::Other => "joint".to_string(),
    }
}

fn end_name(assembly: &Assembly, h: &Hinge) -> &'static str {
    let arch = matches!(assembly.joints[h.joint].kind, JointKind::Arch(_));
    match (h.end, arch) {
        (crate::assembly::JointEnd::P1, true) => "intrados",
        (crate::assembly::JointEnd::P2, true) => "extrados",
        (crate::assembly::JointEnd::P1, false) => "inner face",
        (crate::assembly::JointEnd::P2, false) => "outer face",
    }
}

/// One line per hinge: `joint 5 (arch 5), intrados, at (x, y)`.
pub fn hinge_lines(assembly: &Assembly, hinges: &[Hinge]) -> String {
    let mut s = String::new();
    for h in hinges {
        let _ = writeln!(
            s,
            "    joint {:>4} ({}), {}, at ({:.4}, {:.4}) m",
            h.joint,
            joint_label(assembly.joints[h.joint].kind),
            end_name(assembly, h),
            h.x,
            h.y
        );
    }
    s
}

/// A one-paragraph description of the scene.
pub fn describe_scene(scene: &Scene, model: &Model) -> String {
    let assembly = &model.assembly;
    let a = &scene.arch;
    let shape = a.shape.describe();
    let vs = match a.voussoir_shape {
        VoussoirShape::Polygon => "polygon",
        VoussoirShape::Curved => "curved",
    };
    let mut s = format!(
        "{shape}, t = {} m, {} {vs} voussoirs",
        a.thickness, a.voussoirs
    );
    if let Some(p) = &scene.piers {
        let _ = write!(
            s,
            "\n  on piers h = {} m, b = {} m, {} course{}",
            p.height,
            p.width,
            p.courses,
            if p.courses == 1 { "" } else { "s" }
        );
    }
    let mu = if scene.material.friction.is_finite() {
        format!("mu = {}", scene.material.friction)
    } else {
        "mu = inf (no sliding)".to_string()
    };
    let _ = write!(
        s,
        "\n  {mu}; {} blocks, {} joints, total weight {:.6} kN",
        assembly.blocks.len(),
        assembly.joints.len(),
        assembly.total_weight() / 1000.0
    );
    if !model.loads.is_self_weight_only() {
        let _ = write!(s, "\n  {}", describe_loads(scene, model));
    }
    s
}

/// One or two lines on the loads beyond self-weight and their totals.
pub fn describe_loads(scene: &Scene, model: &Model) -> String {
    let count = |line: bool| {
        scene
            .loads
            .iter()
            .filter(|l| matches!(l, LoadSpec::Line { .. }) == line)
            .count()
    };
    let plural = |n: usize, what: &str| format!("{n} {what}{}", if n == 1 { "" } else { "s" });
    let mut parts = Vec::new();
    if count(false) > 0 {
        parts.push(plural(count(false), "point load"));
    }
    if count(true) > 0 {
        parts.push(plural(count(true), "line load"));
    }
    if let Some(f) = &scene.fill {
        parts.push(format!(
            "fill to y = {} m ({} N/m^3{})",
            f.level,
            f.unit_weight,
            if f.seismic { "" } else { ", not seismic" }
        ));
    }
    let r = scene.seismic.vertical_ratio;
    if r != 0.0 {
        parts.push(format!("vertical seismic ratio {r}"));
    }
    format!(
        "loads: {}\n  permanent loads {:.6} kN down, seismic masses {:.6} kN (lambda multiplies the seismic forces)",
        parts.join(", "),
        model.loads.permanent_weight() / 1000.0,
        model.loads.seismic_weight() / 1000.0
    )
}

/// The human summary of `analyze` with every method that ran.
pub fn analysis_summary(scene: &Scene, a: &SceneAnalysis) -> String {
    let mut s = static_summary(scene, &a.model, &a.lower);
    s.push('\n');
    match &a.upper {
        Ok(k) => {
            match (k.status, k.lambda_upper) {
                (Status::Collapse, Some(u)) => {
                    let _ = writeln!(
                        s,
                        "Kinematic (upper bound): lambda = {u:.6} over {} admissible mechanisms ({:.1} ms)",
                        k.admissible,
                        k.wall_time_s * 1e3
                    );
                    if let Some(note) = &k.note {
                        let _ = writeln!(s, "  {note}");
                    }
                    if let Some(m) = &k.mechanism {
                        let _ = writeln!(s, "  governing mechanism ({:?}):", m.family);
                        s.push_str(&hinge_lines(&a.model.assembly, &m.hinges));
                        for j in &m.open {
                            let _ = writeln!(
                                s,
                                "    joint {j:>4} ({}), opens completely",
                                joint_label(a.model.assembly.joints[*j].kind)
                            );
                        }
                    }
                }
                (Status::NoCollapse, _) => {
                    let _ = writeln!(s, "Kinematic (upper bound): no admissible mechanism is driven by the load: no collapse");
                }
                _ => {
                    let _ = writeln!(s, "Kinematic (upper bound): a mechanism moves under self-weight alone: cannot stand");
                }
            }
            if let (Some(gap), Some(l)) = (a.gap(), a.lower.lambda) {
                if a.sliding_governs() {
                    let _ = writeln!(
                        s,
                        "  sliding governs: the static bound {l:.6} is below the rotational mechanisms ({:.2}% lower)",
                        100.0 * gap
                    );
                } else {
                    let _ = writeln!(s, "  bounds agree: relative gap {gap:.1e}");
                }
            } else if a.sliding_governs() {
                let _ = writeln!(
                    s,
                    "  sliding governs: only sliding mechanisms collapse the structure"
                );
            } else if k.status != a.lower.status {
                let _ = writeln!(
                    s,
                    "  WARNING: the static status is {} but the kinematic one is {}",
                    a.lower.status.as_str(),
                    k.status.as_str()
                );
            }
        }
        Err(note) => {
            let _ = writeln!(s, "Kinematic (upper bound): {note}");
        }
    }
    if let Some(c) = &a.continuous {
        match c {
            Ok(c) => {
                let l = c
                    .lambda_continuous
                    .map_or("none".to_string(), |l| format!("{l:.6}"));
                let _ = writeln!(
                    s,
                    "\nContinuous model (hinges anywhere, infinitely many voussoirs): lambda = {l} ({}, {:.2} ms)",
                    c.status.as_str(),
                    c.wall_time_s * 1e3
                );
                for h in &c.hinges {
                    let at = match h.location {
                        crate::kinematic::HingeLocation::Arch {
                            from_vertical_deg,
                            polar_deg,
                        } => {
                            format!("arch section at {polar_deg:.3} deg (polar), {from_vertical_deg:.3} deg from the vertical")
                        }
                        crate::kinematic::HingeLocation::Pier { left, joint } => {
                            format!("{} pier joint {joint}", if left { "left" } else { "right" })
                        }
                    };
                    let end = match h.end {
                        Some(crate::assembly::JointEnd::P1) => "p1",
                        Some(crate::assembly::JointEnd::P2) => "p2",
                        None => "open",
                    };
                    let _ = writeln!(s, "    {at}, {end}, at ({:.4}, {:.4}) m", h.x, h.y);
                }
            }
            Err(note) => {
                let note = note.strip_prefix("continuous model: ").unwrap_or(note);
                let _ = writeln!(s, "\nContinuous model: {note}");
            }
        }
    }
    s
}

/// The human summary of the static analysis.
pub fn static_summary(scene: &Scene, model: &Model, r: &StaticResult) -> String {
    let assembly = &model.assembly;
    let mut s = format!("{}\n  {}\n\n", scene.origin, describe_scene(scene, model));
    let dir = match r.direction {
        Direction::Right => "toward +x (right)",
        Direction::Left => "toward -x (left)",
    };
    match (r.status, r.lambda) {
        (Status::Collapse, Some(l)) => {
            let _ = writeln!(
                s,
                "Static (lower bound): collapse multiplier lambda = {l:.6}\n  the arch becomes a mechanism under a horizontal acceleration of {l:.4} g {dir}"
            );
            let _ = writeln!(s, "  hinges of the thrust line:");
            s.push_str(&hinge_lines(assembly, &r.hinges));
            if !r.sliding.is_empty() {
                let list: Vec<String> = r.sliding.iter().map(|j| j.to_string()).collect();
                let _ = writeln!(s, "  sliding joints (|V| = mu N): {}", list.join(", "));
            }
            let _ = writeln!(
                s,
                "  equilibrium residual {:.2e} N ({:.1e} of the weight)",
                r.equilibrium_residual,
                r.equilibrium_residual / model.loads.force_scale()
            );
        }
        (Status::NoCollapse, _) => {
            let _ = writeln!(
                s,
                "Static (lower bound): NO COLLAPSE — a thrust line fits inside the structure for any horizontal acceleration {dir}"
            );
        }
        _ => {
            let _ = writeln!(
                s,
                "Static (lower bound): CANNOT STAND — no thrust line fits inside the structure even without horizontal load\n  (thinner than its minimum thickness, piers too slender, or too little friction)"
            );
        }
    }
    let _ = writeln!(
        s,
        "  conic program: {} variables, {} constraints; Clarabel {} in {} iterations, {:.2} ms",
        r.model.variables,
        r.model.constraints,
        r.solver_status,
        r.iterations,
        r.solve_time_s * 1e3
    );
    s
}

/// The human summary of `min-thickness`.
pub fn min_thickness_summary(
    scene: &Scene,
    model: &Model,
    m: &MinThickness,
    rep: &MinThicknessReport,
) -> String {
    let assembly = &model.assembly;
    let mut s = format!("{}\n  {}\n\n", scene.origin, describe_scene(scene, model));
    match (m.search.outcome, m.search.min_thickness) {
        (ThicknessOutcome::Found, Some(t)) => {
            let _ = writeln!(
                s,
                "Minimum thickness (static, lambda = 0): t_min = {t:.9} m  (t_min / {} = {:.6})",
                scene.arch.shape.size_name(),
                t / scene.arch_size()
            );
            if let Some(f) = m.safety_factor {
                let _ = writeln!(
                    s,
                    "  geometric safety factor of t = {} m: {f:.4}{}",
                    scene.arch.thickness,
                    if f < 1.0 {
                        "  (below 1: this arch cannot stand)"
                    } else {
                        ""
                    }
                );
            }
            let _ = writeln!(s, "  hinges of the thrust line at t_min:");
            s.push_str(&hinge_lines(assembly, &m.hinges));
        }
        (ThicknessOutcome::NeverStands, _) => {
            let _ = writeln!(
                s,
                "No thickness lets this structure stand (up to the largest the shape admits, {} m).",
                scene.max_thickness()
            );
        }
        _ => {
            let _ = writeln!(
                s,
                "The structure stands at every thickness tried, down to the thinnest a scene admits (1e-6 of the largest, at least 1e-6 m): no minimum thickness."
            );
        }
    }
    let _ = writeln!(s, "  {} static analyses", m.search.evaluations);
    match (rep.min_thickness_kinematic, &rep.kinematic_note) {
        (Some(t), note) => {
            let _ = writeln!(
                s,
                "Kinematic minimum thickness (lambda_upper = 0): t_min = {t:.9} m{}",
                rep.min_thickness_gap.map_or(String::new(), |g| format!(
                    "  (relative difference {g:.1e})"
                ))
            );
            if let Some(note) = note {
                let _ = writeln!(s, "  note: {note}");
            }
        }
        (None, Some(note)) => {
            let _ = writeln!(s, "Kinematic: {note}");
        }
        _ => {}
    }
    if let Some(c) = rep.min_thickness_continuous {
        match c {
            Some(t) => {
                let _ = writeln!(
                    s,
                    "Continuous model minimum thickness: t_min = {t:.6} m (t_min / size = {:.6})",
                    t / scene.arch_size()
                );
            }
            None => {
                let _ = writeln!(
                    s,
                    "Continuous model: no minimum thickness found{}",
                    rep.continuous_note
                        .as_ref()
                        .map_or(String::new(), |n| format!(" ({n})"))
                );
            }
        }
    }
    s
}

/// A short name of the structure for titles, e.g. `semicircular arch` or `pointed portal`.
pub fn shape_title(scene: &Scene) -> String {
    let shape = scene.arch.shape.title();
    format!(
        "{shape} {}",
        if scene.piers.is_some() {
            "portal"
        } else {
            "arch"
        }
    )
}

/// Title of a structure drawing: shape, thickness, voussoirs and the multipliers.
pub fn drawing_title(scene: &Scene, lower: Option<f64>, upper: Option<f64>) -> String {
    let fmt = |x: Option<f64>| x.map_or("none".to_string(), |v| format!("{v:.4}"));
    let mut second = format!("lambda_lower = {}", fmt(lower));
    if upper.is_some() {
        second.push_str(&format!("   lambda_upper = {}", fmt(upper)));
    }
    format!(
        "{}, t = {} m, {} voussoirs\n{second}",
        shape_title(scene),
        scene.arch.thickness,
        scene.arch.voussoirs
    )
}

/// The human summary of `dem`.
pub fn dem_summary(scene: &Scene, model: &Model, rep: &DemReport) -> String {
    let mut s = format!("{}\n  {}\n\n", scene.origin, describe_scene(scene, model));
    let fmt = |x: Option<f64>| x.map_or("none".to_string(), |v| format!("{v:.6}"));
    match rep.status {
        "collapse" => {
            let _ = writeln!(
                s,
                "DEM: stands at lambda = {}, collapses at lambda = {}  ->  lambda_dem = {} (bracket {:.2}%)",
                fmt(rep.lambda_stands),
                fmt(rep.lambda_collapses),
                fmt(rep.lambda_dem),
                100.0 * rep.bracket_width.unwrap_or(f64::NAN)
            );
            if let (Some(l), Some(d)) = (rep.lambda_lower, rep.relative_difference) {
                let inside = rep.lambda_stands.is_some_and(|a| a <= l)
                    && rep.lambda_collapses.is_some_and(|b| l <= b);
                if inside {
                    let _ = writeln!(
                        s,
                        "  the static lower bound {l:.6} lies inside the DEM bracket: they agree to within its width (narrow it with --tolerance)"
                    );
                } else {
                    let _ = writeln!(
                        s,
                        "  static lower bound {l:.6} lies outside the DEM bracket: the DEM differs by {:+.2}%",
                        100.0 * d
                    );
                }
            }
            if !rep.hinges.is_empty() {
                let _ = writeln!(s, "  hinges at the onset of collapse:");
                s.push_str(&hinge_lines(&model.assembly, &rep.hinges));
            }
            if !rep.sliding.is_empty() {
                let list: Vec<String> = rep.sliding.iter().map(|j| j.to_string()).collect();
                let _ = writeln!(s, "  sliding joints: {}", list.join(", "));
            }
        }
        "no_collapse" => {
            let _ = writeln!(s, "DEM: no collapse up to the largest multiplier tried");
        }
        _ => {
            let _ = writeln!(
                s,
                "DEM: CANNOT STAND — the blocks do not come to rest under self-weight"
            );
        }
    }
    if rep.friction_infinite {
        let _ = writeln!(s, "  mu = inf simulated as mu = {}", rep.friction);
    }
    let _ = writeln!(
        s,
        "  {} runs, {} time steps of {:.3e} s, {:.2} s wall time",
        rep.runs.len(),
        rep.steps,
        rep.time_step,
        rep.wall_time_s
    );
    s
}
