//! The human summaries printed by the CLI, and the titles of drawings and charts.

use super::{DemReport, MinThicknessReport};
use crate::analysis::SceneAnalysis;
use crate::assembly::{Assembly, Hinge, JointEnd, JointKind};
use crate::geometry::Stereotomy;
use crate::kinematic::{Family, Search};
use crate::model::Model;
use crate::outcome::{Direction, Status};
use crate::scene::{LoadSpec, Scene, VoussoirShape};
use crate::statics::StaticResult;
use crate::thickness::{MinThickness, ThicknessOutcome};
use std::fmt::Write as _;

/// Short label of a joint, e.g. `arch 3`, `left pier 0`.
pub fn joint_label(kind: JointKind) -> String {
    match kind {
        JointKind::Arch(j) => format!("arch {j}"),
        JointKind::LeftPier(j) => format!("left pier {j}"),
        JointKind::RightPier(j) => format!("right pier {j}"),
        JointKind::Other => "joint".to_string(),
        JointKind::Between(a, Some(b)) => format!("blocks {a}|{b}"),
        JointKind::Between(a, None) => format!("block {a}|ground"),
    }
}

/// A scene value for reading: float noise such as `0.49999999999999994` (a value that went
/// through a ratio or through radians) rounded off to 12 significant digits, then printed in
/// the shortest form (`0.5`, `1`, `inf`).
pub fn num(x: f64) -> String {
    if x == 0.0 {
        return "0".to_string();
    }
    if !x.is_finite() {
        return format!("{x}");
    }
    let rounded: f64 = format!("{x:.11e}").parse().unwrap_or(x);
    format!("{rounded}")
}

/// A small dimensionless number (a relative gap or difference, a residual) in scientific
/// notation with `digits` decimals, and exactly zero as `0` (not `0.0e0`).
pub fn sci(x: f64, digits: usize) -> String {
    if x == 0.0 {
        "0".to_string()
    } else {
        format!("{x:.digits$e}")
    }
}

/// A status in words: `collapse`, `no collapse`, `cannot stand` (the JSON writes
/// `no_collapse`, `cannot_stand`).
pub fn status_words(status: Status) -> &'static str {
    match status {
        Status::Collapse => "collapse",
        Status::NoCollapse => "no collapse",
        Status::CannotStand => "cannot stand",
    }
}

/// `1 run`, `3 runs`: a count with its noun in the singular or the plural.
pub fn count(n: u64, singular: &str, plural: &str) -> String {
    format!("{n} {}", if n == 1 { singular } else { plural })
}

/// The family of a kinematic mechanism in words: `four hinges`, `two hinges and an opening
/// joint`, `two opening joints`, `one hinge`.
pub fn family_words(f: Family) -> &'static str {
    match f {
        Family::FourHinges => "four hinges",
        Family::TwoHingesOneOpen => "two hinges and an opening joint",
        Family::TwoOpen => "two opening joints",
        Family::OneHinge => "one hinge",
        Family::HingesWithHeldTies => "hinges, with tie rods that keep their length",
    }
}

/// What a mechanism through `joints` moves: `the portal` when one of them is a pier joint,
/// `the arch` when all are arch joints, `the structure` otherwise.
pub fn what_moves(assembly: &Assembly, joints: impl IntoIterator<Item = usize>) -> &'static str {
    let mut arch_only = true;
    for j in joints {
        match assembly.joints.get(j).map(|j| j.kind) {
            Some(JointKind::Arch(_)) => {}
            Some(JointKind::LeftPier(_) | JointKind::RightPier(_)) => return "the portal",
            _ => arch_only = false,
        }
    }
    if arch_only {
        "the arch"
    } else {
        "the structure"
    }
}

/// The end of a joint a hinge sits at, in words with its name in the JSON and the CSV:
/// `intrados (p1)`, `extrados (p2)` on the arch, `inner face (p1)`, `outer face (p2)` on a pier.
pub fn end_words(kind: JointKind, end: JointEnd) -> &'static str {
    if matches!(kind, JointKind::Between(..)) {
        // A joint between the user's blocks has no intrados or faces, only its two ends.
        return match end {
            JointEnd::P1 => "end p1",
            JointEnd::P2 => "end p2",
        };
    }
    let pier = matches!(kind, JointKind::LeftPier(_) | JointKind::RightPier(_));
    match (end, pier) {
        (JointEnd::P1, false) => "intrados (p1)",
        (JointEnd::P2, false) => "extrados (p2)",
        (JointEnd::P1, true) => "inner face (p1)",
        (JointEnd::P2, true) => "outer face (p2)",
    }
}

/// The direction of a joint p1 -> p2 as the continuous model gives its sections: the polar
/// angle in degrees (-180..180) and the angle from the vertical `|polar - 90|`.
pub fn joint_angles_deg(assembly: &Assembly, joint: usize) -> Option<(f64, f64)> {
    let j = assembly.joints.get(joint)?;
    let d = j.p2 - j.p1;
    let polar = d.y.atan2(d.x).to_degrees();
    Some((polar, (polar - 90.0).abs()))
}

/// One line per hinge: `joint 5 (arch 5), intrados (p1), at (x, y) m, polar 146.250 deg,
/// 56.250 deg from the vertical` (the direction p1 -> p2 of an arch joint, as the continuous
/// model gives its sections); pier joints without the angles.
pub fn hinge_lines(assembly: &Assembly, hinges: &[Hinge]) -> String {
    let mut s = String::new();
    for h in hinges {
        let Some(joint) = assembly.joints.get(h.joint) else {
            continue;
        };
        let angles = match (joint.kind, joint_angles_deg(assembly, h.joint)) {
            (JointKind::Arch(_), Some((polar, vertical))) => {
                format!(", polar {polar:.3} deg, {vertical:.3} deg from the vertical")
            }
            _ => String::new(),
        };
        // A crushing hinge sits a/2 inside the joint, at the centre of its compressed zone.
        let inset = if h.compressed_zone > 0.0 {
            format!(
                ", {:.2} mm in (compressed zone {:.2} mm)",
                1e3 * h.offset,
                1e3 * h.compressed_zone
            )
        } else {
            String::new()
        };
        let _ = writeln!(
            s,
            "    joint {:>4} ({}), {}{inset}, at ({:.4}, {:.4}) m{angles}",
            h.joint,
            joint_label(joint.kind),
            end_words(joint.kind, h.end),
            h.x,
            h.y
        );
    }
    s
}

/// A one-paragraph description of the scene.
pub fn describe_scene(scene: &Scene, model: &Model) -> String {
    let assembly = &model.assembly;
    let mut s = match (&scene.arch, &scene.blocks) {
        (Some(a), _) => {
            let shape = a.shape.describe();
            let vs = match a.voussoir_shape {
                VoussoirShape::Polygon => "polygon",
                VoussoirShape::Curved => "curved",
            };
            let mut s = format!(
                "{shape}, t = {} m, {} {vs} voussoir{}",
                num(a.thickness),
                a.voussoirs,
                if a.voussoirs == 1 { "" } else { "s" }
            );
            match a.joints {
                Stereotomy::Radial => {}
                Stereotomy::Vertical => s.push_str(", vertical joints"),
                Stereotomy::HorizontalBed { angle } => {
                    let _ = write!(
                        s,
                        ", horizontal beds up to {} deg, radial joints above",
                        num(angle.to_degrees())
                    );
                }
            }
            s
        }
        (None, Some(b)) => describe_blocks(b),
        (None, None) => String::new(),
    };
    if let Some(p) = &scene.piers {
        let _ = write!(s, "\n  {}", p.describe());
    }
    let _ = write!(
        s,
        "\n  {}; {}, {}, total weight {:.6} kN",
        mu_words(scene),
        count(assembly.blocks.len() as u64, "block", "blocks"),
        count(assembly.joints.len() as u64, "joint", "joints"),
        assembly.total_weight() / 1000.0
    );
    if !model.loads.is_self_weight_only() {
        let _ = write!(s, "\n  {}", describe_loads(scene, model));
    }
    s
}

/// The user's blocks in words: where from, how many joints were found, whether a chain.
pub fn describe_blocks(b: &crate::scene::BlocksSpec) -> String {
    let d = &b.detected;
    let between = d.assembly.joints.len() - d.supports;
    let shape = match &d.topology {
        crate::blocks::Topology::Chain => "a chain between two supports".to_string(),
        crate::blocks::Topology::Column => "a chain standing on one support".to_string(),
        crate::blocks::Topology::Other(why) => format!("not a chain: {why}"),
    };
    format!(
        "{} from {} ({}): {} found between blocks and {} on the ground y = {} m (tolerance {} m); {shape}",
        count(d.assembly.blocks.len() as u64, "user block", "user blocks"),
        b.source_words(),
        b.units.name(),
        count(between as u64, "joint", "joints"),
        count(d.supports as u64, "support", "supports"),
        num(d.ground_y),
        sci(d.tolerance, 1)
    )
}

/// `mu = 0.4`, or `mu = inf (no sliding)`; with a finite compressive strength also
/// `fc = 1 MPa (crushing)`.
fn mu_words(scene: &Scene) -> String {
    let mu = scene.material.friction;
    let mut words = if mu.is_finite() {
        format!("mu = {}", num(mu))
    } else {
        "mu = inf (no sliding)".to_string()
    };
    let fc = scene.material.compressive_strength;
    if fc.is_finite() {
        let _ = write!(words, ", fc = {} MPa (crushing)", num(fc / 1e6));
    }
    words
}

/// One or two lines on the loads beyond self-weight and their totals.
pub fn describe_loads(scene: &Scene, model: &Model) -> String {
    let of_kind = |line: bool| {
        scene
            .loads
            .iter()
            .filter(|l| matches!(l, LoadSpec::Line { .. }) == line)
            .count() as u64
    };
    let mut parts = Vec::new();
    if of_kind(false) > 0 {
        parts.push(count(of_kind(false), "point load", "point loads"));
    }
    if of_kind(true) > 0 {
        parts.push(count(of_kind(true), "line load", "line loads"));
    }
    if let Some(f) = &scene.fill {
        parts.push(format!(
            "fill to y = {} m ({} N/m^3{})",
            num(f.level),
            num(f.unit_weight),
            if f.seismic { "" } else { ", not seismic" }
        ));
    }
    let r = scene.seismic.vertical_ratio;
    if r != 0.0 {
        parts.push(format!("vertical seismic ratio {}", num(r)));
    }
    let live = scene.loads.iter().filter(|l| l.live()).count() as u64;
    if live > 0 {
        parts.push(format!("{live} live (multiplied by lambda)"));
    }
    match model.loads.action() {
        crate::model::Action::Seismic => format!(
            "loads: {}\n  permanent loads {:.6} kN down, seismic masses {:.6} kN (lambda multiplies the seismic forces)",
            parts.join(", "),
            model.loads.permanent_weight() / 1000.0,
            model.loads.seismic_weight() / 1000.0
        ),
        crate::model::Action::Live => format!(
            "loads: {}\n  permanent loads {:.6} kN down, live loads {:.6} kN (lambda multiplies the live loads: the adequacy factor; no seismic force)",
            parts.join(", "),
            model.loads.permanent_weight() / 1000.0,
            model.loads.live_magnitude() / 1000.0
        ),
    }
}

/// How far the static bound `lower` sits below the rotational upper bound `upper`, as a
/// fraction of the upper bound: `(upper - lower) / upper` (the JSON's `gap` is another
/// measure, `|upper - lower| / max(1, lower)`).
pub fn sliding_shortfall(lower: f64, upper: f64) -> Option<f64> {
    (upper > 0.0 && upper.is_finite() && lower.is_finite()).then(|| (upper - lower) / upper)
}

/// The human summary of `analyze` with every method that ran.
pub fn analysis_summary(scene: &Scene, a: &SceneAnalysis) -> String {
    let assembly = &a.model.assembly;
    let mut s = static_summary(scene, &a.model, &a.lower);
    s.push('\n');
    match &a.upper {
        Ok(k) => {
            match (k.status, k.lambda_upper) {
                (Status::Collapse, Some(u)) => {
                    if k.search == crate::kinematic::Search::Certified {
                        let _ = writeln!(
                            s,
                            "Kinematic (upper bound): lambda = {u:.6}, the mechanism of the static hinges by virtual work ({:.2} ms)",
                            k.wall_time_s * 1e3
                        );
                    } else {
                        let _ = writeln!(
                            s,
                            "Kinematic (upper bound): lambda = {u:.6} over {} ({:.1} ms)",
                            count(
                                k.admissible,
                                "admissible mechanism",
                                "admissible mechanisms"
                            ),
                            k.wall_time_s * 1e3
                        );
                    }
                    if a.sliding_governs() {
                        let mu = num(scene.material.friction);
                        let words = if a.lower.status == Status::CannotStand {
                            format!("with mu = {mu} the structure slides before any of them forms")
                        } else {
                            format!(
                                "with mu = {mu} the structure slides first, at the static bound {:.6}",
                                a.lower.lambda.unwrap_or(f64::NAN)
                            )
                        };
                        let _ = writeln!(s, "  rotational mechanisms only: {words}");
                    }
                    if let Some(note) = &k.note {
                        let _ = writeln!(s, "  {note}");
                    }
                    if let Some(m) = &k.mechanism {
                        let joints = m
                            .hinges
                            .iter()
                            .map(|h| h.joint)
                            .chain(m.open.iter().copied());
                        let _ = writeln!(
                            s,
                            "  governing mechanism of {}: {}",
                            what_moves(assembly, joints),
                            family_words(m.family)
                        );
                        s.push_str(&hinge_lines(assembly, &m.hinges));
                        for j in &m.open {
                            let label = assembly
                                .joints
                                .get(*j)
                                .map_or("joint".to_string(), |joint| joint_label(joint.kind));
                            let _ = writeln!(s, "    joint {j:>4} ({label}), opens completely");
                        }
                    }
                }
                (Status::NoCollapse, _) => {
                    let _ = writeln!(s, "Kinematic (upper bound): no admissible mechanism is driven by the load: no collapse");
                }
                _ => {
                    let _ = writeln!(s, "Kinematic (upper bound): a mechanism moves under its permanent loads alone: cannot stand");
                }
            }
            if let (Some(gap), Some(l), Some(u)) = (a.gap(), a.lower.lambda, k.lambda_upper) {
                if a.sliding_governs() {
                    let below = sliding_shortfall(l, u)
                        .map_or(String::new(), |d| format!(" ({:.1}% lower)", 100.0 * d));
                    let _ = writeln!(
                        s,
                        "  sliding governs: the static bound {l:.6} is below the rotational mechanisms' {u:.6}{below}"
                    );
                } else if a.model.strength.is_finite() && k.search != Search::Certified {
                    let _ = writeln!(
                        s,
                        "  the upper bound is the rigid structure's (rigid hinges), {} above the static bound with crushing",
                        sci(gap, 1)
                    );
                } else {
                    let _ = writeln!(s, "  bounds agree: relative gap {}", sci(gap, 1));
                }
            } else if a.sliding_governs() {
                if a.lower.status == Status::CannotStand {
                    let _ = writeln!(
                        s,
                        "  sliding governs: with mu = {} the structure slides under its permanent loads alone, so it cannot stand",
                        num(scene.material.friction)
                    );
                } else {
                    let _ = writeln!(
                        s,
                        "  sliding governs: only sliding mechanisms collapse the structure"
                    );
                }
            } else if k.status != a.lower.status {
                let _ = writeln!(
                    s,
                    "  WARNING: the static status is {} but the kinematic one is {}",
                    status_words(a.lower.status),
                    status_words(k.status)
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
                let l = match c.lambda_continuous {
                    Some(l) => format!("lambda = {l:.6}"),
                    None => status_words(c.status).to_string(),
                };
                let _ = writeln!(
                    s,
                    "\nContinuous model (hinges anywhere, infinitely many voussoirs): {l} ({:.2} ms)",
                    c.wall_time_s * 1e3
                );
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
    let live = model.loads.action() == crate::model::Action::Live;
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
                let _ = writeln!(
                    s,
                    "Static (lower bound): adequacy factor lambda = {l:.6}\n  {} becomes a mechanism when the live loads are {l:.4} times as given",
                    what_moves(assembly, moving)
                );
            } else {
                let _ = writeln!(
                    s,
                    "Static (lower bound): collapse multiplier lambda = {l:.6}\n  {} becomes a mechanism under a horizontal acceleration of {l:.4} g {dir}{vertical}",
                    what_moves(assembly, moving)
                );
            }
            let _ = writeln!(s, "  hinges of the thrust line:");
            s.push_str(&hinge_lines(assembly, &r.hinges));
            if !r.sliding.is_empty() {
                let list: Vec<String> = r.sliding.iter().map(|j| j.to_string()).collect();
                let _ = writeln!(s, "  sliding joints (|V| = mu N): {}", list.join(", "));
            }
            let _ = writeln!(
                s,
                "  equilibrium residual {} N ({} of the weight)",
                sci(r.equilibrium_residual, 2),
                sci(r.equilibrium_residual / model.loads.force_scale(), 1)
            );
        }
        (Status::NoCollapse, _) if live => {
            let _ = writeln!(
                s,
                "Static (lower bound): NO COLLAPSE — a thrust line fits inside the structure for any multiple of the live loads"
            );
        }
        (Status::NoCollapse, _) => {
            let _ = writeln!(
                s,
                "Static (lower bound): NO COLLAPSE — a thrust line fits inside the structure for any horizontal acceleration {dir}"
            );
        }
        _ => {
            let without = if live {
                "without the live loads"
            } else {
                "without horizontal load"
            };
            let _ = writeln!(
                s,
                "Static (lower bound): CANNOT STAND — no thrust line fits inside the structure even {without}\n  (thinner than its minimum thickness, loads too heavy or too one-sided, piers too slender, or too little friction)"
            );
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
    let _ = writeln!(
        s,
        "  {program}: {}, {}; {solver}, {:.2} ms",
        count(r.model.variables as u64, "variable", "variables"),
        count(r.model.constraints as u64, "constraint", "constraints"),
        r.solve_time_s * 1e3
    );
    s
}

/// The name of the arch's size (`R`, `span/2`), or `size` for the user's blocks.
fn size_name(scene: &Scene) -> &'static str {
    scene.arch.as_ref().map_or("size", |a| a.shape.size_name())
}

/// The arch's thickness (NaN for the user's blocks).
fn thickness(scene: &Scene) -> f64 {
    scene.arch.as_ref().map_or(f64::NAN, |a| a.thickness)
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
                size_name(scene),
                t / scene.arch_size()
            );
            if let Some(f) = m.safety_factor {
                let _ = writeln!(
                    s,
                    "  geometric safety factor of t = {} m: {f:.4}{}",
                    num(thickness(scene)),
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
                num(scene.max_thickness())
            );
        }
        _ => {
            let _ = writeln!(
                s,
                "The structure stands at every thickness tried, down to the thinnest a scene admits (1e-6 of the largest, at least 1e-6 m): no minimum thickness."
            );
        }
    }
    let _ = writeln!(
        s,
        "  {}",
        count(
            m.search.evaluations as u64,
            "static analysis",
            "static analyses"
        )
    );
    match (rep.min_thickness_kinematic, &rep.kinematic_note) {
        (Some(t), note) => {
            let _ = writeln!(
                s,
                "Kinematic minimum thickness (lambda_upper = 0): t_min = {t:.9} m{}",
                rep.min_thickness_gap.map_or(String::new(), |g| format!(
                    "  (relative difference {})",
                    sci(g, 1)
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
                    "Continuous model minimum thickness: t_min = {t:.6} m (t_min / {} = {:.6})",
                    size_name(scene),
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
    let Some(arch) = &scene.arch else {
        let n = scene
            .blocks
            .as_ref()
            .map_or(0, |b| b.detected.assembly.blocks.len());
        return format!(
            "structure of {}",
            count(n as u64, "user block", "user blocks")
        );
    };
    let shape = arch.shape.title();
    format!(
        "{shape} {}",
        if scene.piers.is_some() {
            "portal"
        } else {
            "arch"
        }
    )
}

/// Title of a structure drawing: shape, thickness, voussoirs, and the multipliers of every
/// bound that ran, or in words why there is none (`cannot stand`, `no collapse`). Written for
/// the engineer (λ and the bound's name), not with the JSON keys.
pub fn drawing_title(scene: &Scene, a: &SceneAnalysis) -> String {
    let lower = match (a.lower.status, a.lower.lambda) {
        (Status::Collapse, Some(l)) => format!("λ (static lower bound) = {l:.4}"),
        (Status::NoCollapse, _) => "no collapse: a thrust line fits at any λ".to_string(),
        _ => "cannot stand: no thrust line fits".to_string(),
    };
    let upper = match &a.upper {
        Ok(k) => match (k.status, k.lambda_upper) {
            (Status::Collapse, Some(u)) if a.sliding_governs() => Some(format!(
                "λ (kinematic upper bound) = {u:.4} (rotation only)"
            )),
            (Status::Collapse, Some(u)) => Some(format!("λ (kinematic upper bound) = {u:.4}")),
            (status, _) if status == a.lower.status => None,
            (Status::NoCollapse, _) => Some("kinematic: no collapse".to_string()),
            _ => Some("kinematic: cannot stand".to_string()),
        },
        Err(_) => None,
    };
    let mut second = match upper {
        Some(u) => format!("{lower}, {u}"),
        None => lower,
    };
    if a.model.loads.action() == crate::model::Action::Live {
        // λ multiplies the live loads: say so where a reader expects an acceleration.
        second = format!("adequacy factor of the live loads: {second}");
    }
    match &scene.arch {
        Some(arch) => format!(
            "{}, t = {} m, {} voussoirs\n{second}",
            shape_title(scene),
            num(arch.thickness),
            arch.voussoirs
        ),
        None => format!("{}\n{second}", shape_title(scene)),
    }
}

/// Title of the DEM drawing: shape, thickness, and the DEM and static multipliers, or in
/// words why there is none (`lower` is the static status of the same model).
pub fn dem_drawing_title(scene: &Scene, rep: &DemReport, lower: Status) -> String {
    let dem = match (rep.status, rep.lambda_dem) {
        ("collapse", Some(l)) => format!("λ (DEM) = {l:.4}"),
        ("no_collapse", _) => "DEM: no collapse up to the largest λ tried".to_string(),
        _ => "DEM: cannot stand (no rest under the permanent loads)".to_string(),
    };
    let lower = match (lower, rep.lambda_lower) {
        (Status::Collapse, Some(l)) => format!("static lower bound λ = {l:.4}"),
        (Status::NoCollapse, _) => "static: no collapse".to_string(),
        _ => "static: cannot stand".to_string(),
    };
    match &scene.arch {
        Some(arch) => format!(
            "{}, t = {} m: DEM\n{dem}  ({lower})",
            shape_title(scene),
            num(arch.thickness)
        ),
        None => format!("{}: DEM\n{dem}  ({lower})", shape_title(scene)),
    }
}

/// The human summary of `dem`.
pub fn dem_summary(scene: &Scene, model: &Model, rep: &DemReport) -> String {
    let mut s = format!("{}\n  {}\n\n", scene.origin, describe_scene(scene, model));
    let fmt = |x: Option<f64>| x.map_or("none".to_string(), |v| format!("{v:.6}"));
    match rep.status {
        "collapse" => {
            let bracket = rep
                .bracket_width
                .map_or(String::new(), |w| format!(" (bracket {:.2}%)", 100.0 * w));
            let _ = writeln!(
                s,
                "DEM: stands at lambda = {}, collapses at lambda = {}  ->  lambda_dem = {}{bracket}",
                fmt(rep.lambda_stands),
                fmt(rep.lambda_collapses),
                fmt(rep.lambda_dem),
            );
            let shape = if rep.simulated_shape == "chord_polygons" {
                " of the chord polygons the DEM simulates"
            } else {
                ""
            };
            if let (Some(l), Some(d)) = (rep.lambda_lower_simulated, rep.relative_difference) {
                let inside = rep.static_inside_bracket == Some(true);
                if inside {
                    let _ = writeln!(
                        s,
                        "  the static lower bound{shape} {l:.6} lies inside the DEM bracket: they agree to within its width (narrow it with --tolerance)"
                    );
                } else {
                    let _ = writeln!(
                        s,
                        "  the static lower bound{shape} {l:.6} lies outside the DEM bracket: the DEM differs by {:+.2}%",
                        100.0 * d
                    );
                }
            }
            if let (true, Some(l)) = (rep.simulated_shape == "chord_polygons", rep.lambda_lower) {
                let _ = writeln!(
                    s,
                    "  (the static lower bound of the curved voussoirs themselves is {l:.6})"
                );
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
                "DEM: CANNOT STAND — the blocks do not come to rest under their permanent loads"
            );
        }
    }
    if rep.simulated_shape == "chord_polygons" {
        let _ = writeln!(
            s,
            "  curved voussoirs are simulated as polygons (straight chords), so the DEM is compared with\n  the static bound of those polygons, not of the exact annular pieces (docs/dem.md)"
        );
    }
    let start = match rep.guess_source {
        crate::dem::GuessSource::Static => "the static lower bound (--from-static: the DEM verifies the static value; a difference near 0 is by construction)",
        crate::dem::GuessSource::Given => "dem.initial_guess",
        crate::dem::GuessSource::Default => "the default start, independent of the static bound",
    };
    let _ = writeln!(
        s,
        "  bracket searched from lambda = {:.6}, {start}",
        rep.initial_guess
    );
    if rep.friction_infinite {
        let _ = writeln!(s, "  mu = inf simulated as mu = {}", num(rep.friction));
    }
    let _ = writeln!(
        s,
        "  {}, {} of {:.3e} s (at most {} a run, limit {}), {:.2} s wall time",
        count(rep.runs.len() as u64, "run", "runs"),
        count(rep.steps, "time step", "time steps"),
        rep.time_step,
        rep.planned_steps_per_run,
        rep.max_steps,
        rep.wall_time_s
    );
    warning_lines(&mut s, &rep.warnings);
    s
}

/// The warnings of a DEM report, one `warning:` line each.
fn warning_lines(s: &mut String, warnings: &[String]) {
    for w in warnings {
        let _ = writeln!(s, "warning: {w}");
    }
}

/// How a dynamic run's criterion calls collapse, for the summaries.
fn criterion_words(criterion: crate::dem::dynamic::Criterion, displacement: f64) -> String {
    match criterion {
        crate::dem::dynamic::Criterion::Displacement => format!(
            "collapse criterion: displacement (a block point moved by {displacement:.4} m, a quarter of the structure's size)"
        ),
        crate::dem::dynamic::Criterion::Overturning => format!(
            "collapse criterion: overturning (the structure fell: a block point moved by {displacement:.4} m, its whole size; otherwise run until at rest)"
        ),
    }
}

/// The text summary of a dynamic DEM run.
pub fn dynamic_summary(scene: &Scene, model: &Model, rep: &crate::report::DynamicReport) -> String {
    let mut s = format!("{}\n  {}\n\n", scene.origin, describe_scene(scene, model));
    let _ = writeln!(
        s,
        "ground motion: {} (PGA {:.4} m/s^2 = {:.4} g, {:.3} s){}",
        rep.excitation,
        rep.pga,
        rep.pga / crate::dem::record::STANDARD_GRAVITY,
        rep.duration,
        component_words(rep.component)
    );
    if let (Some(v), Some(pga)) = (&rep.vertical_excitation, rep.pga_vertical) {
        let _ = writeln!(
            s,
            "  with the vertical {v} (PGA {pga:.4} m/s^2 = {:.4} g, upward positive)",
            pga / crate::dem::record::STANDARD_GRAVITY
        );
    }
    match rep.status {
        "cannot_stand" => {
            let _ = writeln!(
                s,
                "DEM: CANNOT STAND — the blocks do not come to rest under their permanent loads"
            );
            return s;
        }
        "collapse" => {
            let _ = writeln!(
                s,
                "DEM: COLLAPSE at t = {:.3} s",
                rep.collapse_time.unwrap_or(f64::NAN)
            );
        }
        "undecided" => {
            let _ = writeln!(
                s,
                "DEM: UNDECIDED — still moving {:.3} s after the motion and its tail, neither at rest nor collapsed",
                rep.extended
            );
        }
        _ => {
            let how = match rep.end_state {
                crate::dem::dynamic::EndState::Settling => "its motion dying out after the ground stopped: no block point moved by more than 0.25% of the structure's size over the last window",
                crate::dem::dynamic::EndState::Rocking => "still rocking after the ground stopped, with less energy than it needs to tip over its base corner",
                _ => "at rest after the ground stopped",
            };
            let _ = writeln!(
                s,
                "DEM: survives ({how}{})",
                if rep.extended > 0.0 {
                    format!("; decided {:.3} s past the tail", rep.extended)
                } else {
                    String::new()
                }
            );
        }
    }
    let _ = writeln!(
        s,
        "  {}",
        criterion_words(rep.criterion, rep.collapse_displacement)
    );
    let _ = writeln!(
        s,
        "  block {}: peak displacement {:.4e} m, peak rotation {:.4e} rad; residual {:.4e} m, {:.4e} rad",
        rep.control_block,
        rep.peak_displacement,
        rep.peak_rotation,
        rep.residual_displacement,
        rep.residual_rotation
    );
    let _ = writeln!(
        s,
        "  no local damping: energy is lost only at the contacts (docs/dem.md)\n  {} (at most {}), time step {:.3e} s, {:.2} s wall time",
        count(rep.steps, "time step", "time steps"),
        rep.planned_steps,
        rep.time_step,
        rep.wall_time_s
    );
    warning_lines(&mut s, &rep.warnings);
    s
}

/// How a motion along `component` acts, for the summaries.
fn component_words(component: &str) -> &'static str {
    if component == "y" {
        ", acting vertically (upward positive)"
    } else {
        ", horizontal (toward +x positive)"
    }
}

/// One line saying what a dynamic run did (the title of its animation).
pub fn dynamic_headline(rep: &crate::report::DynamicReport) -> String {
    let g = crate::dem::record::STANDARD_GRAVITY;
    let what = match rep.status {
        "cannot_stand" => "cannot stand".to_string(),
        "collapse" => format!(
            "collapses at t = {:.3} s",
            rep.collapse_time.unwrap_or(f64::NAN)
        ),
        "undecided" => "undecided (still moving)".to_string(),
        _ => "survives".to_string(),
    };
    let vertical = rep
        .pga_vertical
        .map_or(String::new(), |p| format!(", vertical PGA {:.3} g", p / g));
    format!(
        "{} (PGA {:.3} g{}{}): {what}",
        rep.excitation,
        rep.pga / g,
        if rep.component == "y" {
            ", vertical"
        } else {
            ""
        },
        vertical
    )
}

/// The text summary of a pulse curve.
pub fn pulse_curve_summary(
    scene: &Scene,
    model: &Model,
    rep: &crate::report::PulseCurveReport,
) -> String {
    let g = crate::dem::record::STANDARD_GRAVITY;
    let mut s = format!("{}\n  {}\n\n", scene.origin, describe_scene(scene, model));
    let _ = writeln!(
        s,
        "minimum collapse amplitude of one pulse, bracketed to {:.1}% (searches start at {:.4} m/s^2 = {:.4} g{})",
        100.0 * rep.tolerance,
        rep.start_amplitude,
        rep.start_amplitude / g,
        if rep.lambda_lower.is_some() {
            ", the static multiplier times g"
        } else {
            ""
        }
    );
    let _ = writeln!(
        s,
        "  {:<6} {:>9} {:>14} {:>14} {:>9} {:>5}",
        "shape", "T (s)", "survives", "collapses", "(g)", "runs"
    );
    for p in &rep.points {
        let (hi, hi_g) = p.amplitude_collapses.map_or(
            (
                format!("none <= {:.0} g", crate::analysis::PULSE_CURVE_MAX_G),
                String::new(),
            ),
            |a| (format!("{a:.4}"), format!("{:.4}", a / g)),
        );
        let _ = writeln!(
            s,
            "  {:<6} {:>9.4} {:>14.4} {:>14} {:>9} {:>5}",
            p.shape, p.period, p.amplitude_survives, hi, hi_g, p.runs
        );
    }
    let _ = writeln!(
        s,
        "  amplitudes in m/s^2; {:.2} s wall time; collapse criterion: {}",
        rep.wall_time_s,
        rep.criterion.name()
    );
    let _ = writeln!(
        s,
        "  each point is {} (scan ratio {}: a collapse window narrower than that can be missed)",
        crate::report::json::PULSE_CURVE_SEARCH,
        rep.scan_ratio
    );
    s
}

/// The text summary of an incremental dynamic analysis.
pub fn ida_summary(scene: &Scene, model: &Model, rep: &crate::report::IdaReport) -> String {
    let mut s = format!("{}\n  {}\n\n", scene.origin, describe_scene(scene, model));
    let g = crate::dem::record::STANDARD_GRAVITY;
    let _ = writeln!(
        s,
        "ground motion: {} (PGA {:.4} m/s^2 = {:.4} g){}",
        rep.excitation,
        rep.pga,
        rep.pga / g,
        component_words(rep.component)
    );
    if let (Some(v), Some(pga)) = (&rep.vertical_excitation, rep.pga_vertical) {
        let _ = writeln!(
            s,
            "  with the vertical {v} (PGA {pga:.4} m/s^2 = {:.4} g, scaled alike)",
            pga / g
        );
    }
    match (rep.scale_collapses, rep.collapse_pga) {
        (Some(hi), Some(pga)) => {
            let _ = writeln!(
                s,
                "IDA: survives at scale {:.4}, collapses at scale {hi:.4} (PGA {pga:.4} m/s^2 = {:.4} g)",
                rep.scale_survives,
                pga / g
            );
        }
        _ => {
            let _ = writeln!(s, "IDA: no collapse up to scale {:.4}", rep.scale_survives);
        }
    }
    let _ = writeln!(
        s,
        "  {}, {}, {:.2} s wall time (the first bracket from below: dynamic collapse need not be monotonic in the scale); collapse criterion: {}",
        count(rep.runs.len() as u64, "run", "runs"),
        count(rep.steps, "time step", "time steps"),
        rep.wall_time_s,
        rep.criterion.name()
    );
    s
}
