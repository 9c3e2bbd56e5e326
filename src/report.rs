//! What the CLI prints: the JSON objects (a contract for scripts: later versions add fields,
//! never rename them), the thrust-line CSV, and the human summary.

use crate::analysis::SceneAnalysis;
use crate::assembly::{Assembly, Hinge, JointKind};
use crate::kinematic::ContinuousHinge;
use crate::lp::{Direction, ModelSize, StaticResult, Status};
use crate::model::Model;
use crate::scene::{FillSpec, LoadSpec, Scene, Shape, VoussoirShape};
use crate::thickness::{MinThickness, ThicknessAnalysis, ThicknessOutcome};
use serde::Serialize;
use std::fmt::Write as _;

/// One joint in `analyze --json`.
#[derive(Debug, Serialize)]
pub struct JointReport {
    pub index: usize,
    /// What the joint is: `arch`, `left_pier` or `right_pier` with its number.
    pub kind: JointKind,
    pub p1: [f64; 2],
    pub p2: [f64; 2],
    /// Normal force (N), null when the structure has no collapse state.
    #[serde(rename = "N")]
    pub n: Option<f64>,
    /// Shear force (N) along p1 -> p2.
    #[serde(rename = "V")]
    pub v: Option<f64>,
    /// Moment about the joint midpoint (N m), positive toward p2.
    #[serde(rename = "M")]
    pub m: Option<f64>,
    /// Eccentricity M/N (m) from the midpoint toward p2.
    pub e: Option<f64>,
    /// Thrust-line point `p_mid + e u`.
    pub thrust: Option<[f64; 2]>,
}

/// Scene summary echoed in the JSON.
#[derive(Debug, Serialize)]
pub struct SceneReport {
    pub origin: String,
    pub shape: &'static str,
    pub thickness: f64,
    pub voussoirs: usize,
    pub voussoir_shape: &'static str,
    pub portal: bool,
    /// Coulomb coefficient; null means infinite (no sliding).
    pub friction: Option<f64>,
    pub total_weight: f64,
}

/// The loads of a scene as read, and their totals (fields `loads`, `fill`, `vertical_ratio`,
/// `permanent_weight`, `seismic_weight` of every JSON report).
#[derive(Debug, Serialize)]
pub struct LoadsReport {
    /// The `[[loads]]` entries as read (`type`, and `at`/`force` or `from_x`/`to_x`/
    /// `intensity`, and `seismic`).
    pub loads: Vec<LoadSpec>,
    /// `[fill]` as read, or null.
    pub fill: Option<FillSpec>,
    /// `[seismic] vertical_ratio`.
    pub vertical_ratio: f64,
    /// Total downward permanent force (N): self-weight, fill, point and line loads.
    pub permanent_weight: f64,
    /// Total weight of the seismic masses (N): the horizontal seismic force is lambda times
    /// this.
    pub seismic_weight: f64,
}

impl LoadsReport {
    pub fn new(scene: &Scene, model: &Model) -> Self {
        LoadsReport {
            loads: scene.loads.clone(),
            fill: scene.fill.clone(),
            vertical_ratio: scene.seismic.vertical_ratio,
            permanent_weight: model.loads.permanent_weight(),
            seismic_weight: model.loads.seismic_weight(),
        }
    }
}

/// `analyze --json`.
#[derive(Debug, Serialize)]
pub struct AnalysisReport {
    pub status: Status,
    pub lambda_lower: Option<f64>,
    pub hinges: Vec<Hinge>,
    pub sliding: Vec<usize>,
    pub joints: Vec<JointReport>,
    pub mechanism: Vec<[f64; 3]>,
    pub equilibrium_residual: f64,
    pub blocks: usize,
    pub solve_time_s: f64,
    pub direction: Direction,
    pub solver_status: String,
    pub iterations: u32,
    pub model: ModelSize,
    pub scene: SceneReport,
    /// The loads beyond self-weight and the weights they add up to.
    #[serde(flatten)]
    pub loads: LoadsReport,
    /// Discrete kinematic (upper-bound) multiplier, or null (no collapse, cannot stand, or
    /// the search was not run: see `kinematic_note`).
    pub lambda_upper: Option<f64>,
    /// Status of the kinematic search (same words as `status`), or null when not run.
    pub kinematic_status: Option<Status>,
    /// `|lambda_upper - lambda_lower| / max(1, lambda_lower)` when both exist.
    pub gap: Option<f64>,
    /// Hinges of the governing kinematic mechanism (same form as `hinges`).
    pub mechanism_hinges: Vec<Hinge>,
    /// Joints that open completely in that mechanism.
    pub open_joints: Vec<usize>,
    /// Finite friction and a static bound below the rotational upper bound: sliding governs.
    pub sliding_governs: bool,
    /// Block velocities of the kinematic mechanism `[vx, vy, omega]`.
    pub kinematic_mechanism: Vec<[f64; 3]>,
    /// Why the kinematic search was not run or failed, or what a local search covered.
    pub kinematic_note: Option<String>,
    /// `exhaustive` (lambda_upper is the discrete kinematic multiplier), `local` (only the
    /// mechanisms near the static hinges were searched: lambda_upper is an upper bound, null
    /// when that search found none), or null when no kinematic search ran.
    pub kinematic_search: Option<crate::kinematic::Search>,
    pub kinematic_time_s: Option<f64>,
    /// Continuous model (only with `--continuous`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub lambda_continuous: Option<Option<f64>>,
    /// Hinges of the continuous mechanism (only with `--continuous`); angles in degrees.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub continuous_hinges: Option<Vec<ContinuousHinge>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub continuous_note: Option<String>,
}

fn xy(p: crate::geometry::Vec2) -> [f64; 2] {
    [p.x, p.y]
}

fn finite_or_null(x: f64) -> Option<f64> {
    x.is_finite().then_some(x)
}

impl SceneReport {
    pub fn new(scene: &Scene, model: &Model) -> Self {
        SceneReport {
            origin: scene.origin.clone(),
            shape: scene.arch.shape.name(),
            thickness: scene.arch.thickness,
            voussoirs: scene.arch.voussoirs,
            voussoir_shape: match scene.arch.voussoir_shape {
                VoussoirShape::Polygon => "polygon",
                VoussoirShape::Curved => "curved",
            },
            portal: scene.piers.is_some(),
            friction: finite_or_null(scene.material.friction),
            total_weight: model.assembly.total_weight(),
        }
    }
}

impl AnalysisReport {
    pub fn new(scene: &Scene, a: &SceneAnalysis) -> Self {
        let mut report = AnalysisReport::new_static(scene, &a.model, &a.lower);
        match &a.upper {
            Ok(k) => {
                report.lambda_upper = k.lambda_upper;
                report.kinematic_status = Some(k.status);
                report.kinematic_time_s = Some(k.wall_time_s);
                report.kinematic_note.clone_from(&k.note);
                if let Some(m) = &k.mechanism {
                    report.mechanism_hinges = m.hinges.clone();
                    report.open_joints = m.open.clone();
                    report.kinematic_mechanism = m.velocities.clone();
                }
            }
            Err(note) => report.kinematic_note = Some(note.clone()),
        }
        report.kinematic_search = a.kinematic_search;
        report.gap = a.gap();
        report.sliding_governs = a.sliding_governs();
        if let Some(c) = &a.continuous {
            match c {
                Ok(c) => {
                    report.lambda_continuous = Some(c.lambda_continuous);
                    report.continuous_hinges = Some(c.hinges.clone());
                }
                Err(note) => {
                    report.lambda_continuous = Some(None);
                    report.continuous_note = Some(note.clone());
                }
            }
        }
        report
    }

    /// The static part alone.
    pub fn new_static(scene: &Scene, model: &Model, r: &StaticResult) -> Self {
        let assembly = &model.assembly;
        let points = r.thrust_points(assembly);
        let joints = assembly
            .joints
            .iter()
            .enumerate()
            .map(|(i, j)| {
                let f = r.forces.as_ref().and_then(|f| f.get(i));
                JointReport {
                    index: i,
                    kind: j.kind,
                    p1: xy(j.p1),
                    p2: xy(j.p2),
                    n: f.map(|f| f.n),
                    v: f.map(|f| f.v),
                    m: f.map(|f| f.m),
                    e: r.eccentricity(i),
                    thrust: points.get(i).copied().flatten().map(xy),
                }
            })
            .collect();
        AnalysisReport {
            status: r.status,
            lambda_lower: r.lambda,
            hinges: r.hinges.clone(),
            sliding: r.sliding.clone(),
            joints,
            mechanism: r.mechanism.clone(),
            equilibrium_residual: r.equilibrium_residual,
            blocks: assembly.blocks.len(),
            solve_time_s: r.solve_time_s,
            direction: r.direction,
            solver_status: r.solver_status.clone(),
            iterations: r.iterations,
            model: r.model,
            scene: SceneReport::new(scene, model),
            loads: LoadsReport::new(scene, model),
            lambda_upper: None,
            kinematic_status: None,
            gap: None,
            mechanism_hinges: Vec::new(),
            open_joints: Vec::new(),
            sliding_governs: false,
            kinematic_mechanism: Vec::new(),
            kinematic_note: None,
            kinematic_search: None,
            kinematic_time_s: None,
            lambda_continuous: None,
            continuous_hinges: None,
            continuous_note: None,
        }
    }
}

/// `min-thickness --json`.
#[derive(Debug, Serialize)]
pub struct MinThicknessReport {
    /// `found`, `never_stands` or `stands_at_every_thickness`.
    pub outcome: ThicknessOutcome,
    pub min_thickness: Option<f64>,
    /// min_thickness divided by the characteristic size (R for circular and pointed arches,
    /// span/2 for basket arches).
    pub min_thickness_ratio: Option<f64>,
    pub hinges: Vec<Hinge>,
    pub safety_factor: Option<f64>,
    pub thickness: f64,
    pub evaluations: usize,
    pub scene: SceneReport,
    #[serde(flatten)]
    pub loads: LoadsReport,
    /// Kinematic minimum thickness (where lambda_upper reaches 0), or null when not run.
    pub min_thickness_kinematic: Option<f64>,
    /// `|t_static - t_kinematic| / t_static`.
    pub min_thickness_gap: Option<f64>,
    pub kinematic_note: Option<String>,
    /// Continuous-model minimum thickness (only with `--continuous`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub min_thickness_continuous: Option<Option<f64>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub continuous_hinges: Option<Vec<ContinuousHinge>>,
    /// Why the continuous model failed (only with `--continuous`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub continuous_note: Option<String>,
}

impl MinThicknessReport {
    /// The report of every method in `t`.
    pub fn new(scene: &Scene, model: &Model, t: &ThicknessAnalysis) -> Self {
        let mut rep = MinThicknessReport::new_static(scene, model, &t.lower);
        rep.min_thickness_kinematic = t.kinematic.as_ref().and_then(|k| k.min_thickness);
        rep.min_thickness_gap = t.gap();
        rep.kinematic_note = t.kinematic_note.clone();
        match &t.continuous {
            Some(Ok(c)) => {
                rep.min_thickness_continuous = Some(Some(c.thickness));
                rep.continuous_hinges = Some(c.result.hinges.clone());
            }
            Some(Err(e)) => {
                rep.min_thickness_continuous = Some(None);
                rep.continuous_note = Some(format!("continuous model: {e}"));
            }
            None => {}
        }
        rep
    }

    /// The static part alone.
    pub fn new_static(scene: &Scene, model: &Model, m: &MinThickness) -> Self {
        MinThicknessReport {
            outcome: m.search.outcome,
            min_thickness: m.search.min_thickness,
            min_thickness_ratio: m.search.min_thickness.map(|t| t / scene.arch_size()),
            hinges: m.hinges.clone(),
            safety_factor: m.safety_factor,
            thickness: scene.arch.thickness,
            evaluations: m.search.evaluations,
            scene: SceneReport::new(scene, model),
            loads: LoadsReport::new(scene, model),
            min_thickness_kinematic: None,
            min_thickness_gap: None,
            kinematic_note: None,
            min_thickness_continuous: None,
            continuous_hinges: None,
            continuous_note: None,
        }
    }
}

/// Write the thrust line as CSV: one row per joint.
pub fn write_thrust_csv<W: std::io::Write>(
    out: W,
    assembly: &Assembly,
    r: &StaticResult,
) -> Result<(), csv::Error> {
    let mut w = csv::Writer::from_writer(out);
    w.write_record([
        "joint", "kind", "x", "y", "N", "V", "M", "e", "p1_x", "p1_y", "p2_x", "p2_y",
    ])?;
    let forces = r.forces.as_deref().unwrap_or(&[]);
    let points = r.thrust_points(assembly);
    for (i, (j, f)) in assembly.joints.iter().zip(forces).enumerate() {
        let (x, y) = points[i].map_or((String::new(), String::new()), |p| {
            (p.x.to_string(), p.y.to_string())
        });
        let e = r.eccentricity(i).map_or(String::new(), |e| e.to_string());
        w.write_record([
            i.to_string(),
            joint_label(j.kind),
            x,
            y,
            f.n.to_string(),
            f.v.to_string(),
            f.m.to_string(),
            e,
            j.p1.x.to_string(),
            j.p1.y.to_string(),
            j.p2.x.to_string(),
            j.p2.y.to_string(),
        ])?;
    }
    w.flush()?;
    Ok(())
}

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
    let shape = match a.shape {
        Shape::Circular { radius, embrace } => {
            format!(
                "circular arch, R = {radius} m, embrace {} deg",
                trim(embrace.to_degrees())
            )
        }
        Shape::Pointed {
            radius,
            eccentricity,
        } => format!("pointed arch, R = {radius} m, e = {eccentricity} m"),
        Shape::Basket {
            span,
            rise,
            side_angle,
        } => format!(
            "basket-handle arch, span {span} m, rise {rise} m, side angle {} deg",
            trim(side_angle.to_degrees())
        ),
    };
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
                match scene.arch.shape {
                    Shape::Basket { .. } => "(span/2)",
                    _ => "R",
                },
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
    let shape = match scene.arch.shape {
        Shape::Circular { embrace, .. } => {
            let deg = embrace.to_degrees();
            if (deg - 180.0).abs() < 1e-9 {
                "semicircular".to_string()
            } else if deg < 180.0 {
                format!("segmental ({deg:.0} deg)")
            } else {
                format!("horseshoe ({deg:.0} deg)")
            }
        }
        Shape::Pointed { .. } => "pointed".to_string(),
        Shape::Basket { .. } => "basket-handle".to_string(),
    };
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

/// A number with at most 9 significant decimals and no trailing zeros (180, 67.5).
pub fn trim(x: f64) -> String {
    let s = format!("{x:.9}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    s.to_string()
}

/// One DEM run in `dem --json`.
#[derive(Debug, Serialize)]
pub struct DemRunReport {
    /// null for the settling run under gravity alone.
    pub lambda: Option<f64>,
    pub outcome: crate::dem::Outcome,
    /// Simulated time (s) and time steps.
    pub time: f64,
    pub steps: u64,
    pub max_displacement: f64,
}

/// `dem --json`.
#[derive(Debug, Serialize)]
pub struct DemReport {
    /// `collapse`, `no_collapse` (none up to the DEM's max_lambda) or `cannot_stand`.
    pub status: &'static str,
    pub lambda_stands: Option<f64>,
    pub lambda_collapses: Option<f64>,
    pub lambda_dem: Option<f64>,
    /// The static lower bound of the same assembly, for comparison.
    pub lambda_lower: Option<f64>,
    /// `(lambda_dem - lambda_lower) / lambda_lower`.
    pub relative_difference: Option<f64>,
    /// `(lambda_collapses - lambda_stands) / lambda_dem`.
    pub bracket_width: Option<f64>,
    /// Whether `lambda_lower` lies inside `[lambda_stands, lambda_collapses]`: then the DEM
    /// confirms it to within the bracket, and `relative_difference` (the bracket's midpoint
    /// against it, zero when the search was centred on it) is known only to half the width.
    pub static_inside_bracket: Option<bool>,
    pub steps: u64,
    pub wall_time_s: f64,
    /// Joints seen opening at one end, sliding, and opening fully at the onset of collapse.
    pub hinges: Vec<Hinge>,
    pub sliding: Vec<usize>,
    pub open: Vec<usize>,
    /// The Coulomb coefficient the contacts used; `friction_infinite` says it stands for inf.
    pub friction: f64,
    pub friction_infinite: bool,
    pub time_step: f64,
    pub undecided_runs: usize,
    pub runs: Vec<DemRunReport>,
    pub scene: SceneReport,
    #[serde(flatten)]
    pub loads: LoadsReport,
}

impl DemReport {
    pub fn new(
        scene: &Scene,
        model: &Model,
        r: &crate::dem::DemResult,
        lambda_lower: Option<f64>,
    ) -> Self {
        let status = if r.cannot_stand {
            "cannot_stand"
        } else if r.no_collapse {
            "no_collapse"
        } else {
            "collapse"
        };
        DemReport {
            status,
            lambda_stands: r.lambda_stands,
            lambda_collapses: r.lambda_collapses,
            lambda_dem: r.lambda_dem,
            lambda_lower,
            relative_difference: match (r.lambda_dem, lambda_lower) {
                (Some(d), Some(l)) if l > 0.0 => Some((d - l) / l),
                _ => None,
            },
            bracket_width: r.bracket_width,
            static_inside_bracket: match (lambda_lower, r.lambda_stands, r.lambda_collapses) {
                (Some(l), Some(a), Some(b)) => Some(a <= l && l <= b),
                _ => None,
            },
            steps: r.steps,
            wall_time_s: r.wall_time_s,
            hinges: r.hinges.clone(),
            sliding: r.sliding.clone(),
            open: r.open.clone(),
            friction: r.friction,
            friction_infinite: r.friction_infinite,
            time_step: r.time_step,
            undecided_runs: r.undecided_runs,
            runs: r
                .runs
                .iter()
                .map(|run| DemRunReport {
                    lambda: run.lambda,
                    outcome: run.outcome,
                    time: run.time,
                    steps: run.steps,
                    max_displacement: run.max_displacement,
                })
                .collect(),
            scene: SceneReport::new(scene, model),
            loads: LoadsReport::new(scene, model),
        }
    }
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
