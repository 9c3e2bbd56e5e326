//! The words every document and figure title uses: numbers for reading, statuses, joints,
//! hinges, the scene and its loads in a paragraph, the structure's short name.

use crate::assembly::{Assembly, Hinge, JointEnd, JointKind};
use crate::geometry::Stereotomy;
use crate::hazard::SiteHazard;
use crate::kinematic::Family;
use crate::model::Model;
use crate::outcome::Status;
use crate::scene::{LoadSpec, Scene, VoussoirShape};
use crate::statics::FrictionCheck;
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
        JointKind::Fixed(a, f) => format!("block {a}|fixed {f}"),
        JointKind::Bay(k, j) => format!("bay {k} arch {j}"),
        JointKind::Column(k, c) => format!("column {k} joint {c}"),
        JointKind::Spandrel(a, b) => format!("spandrel {a}|{b}"),
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

/// How the national hazard grid gave a site's `ag`, `F0`, `Tc*` (NTC 2018 §2.4.3, §3.2.1;
/// NTC 2008 Allegati A, B), in one line.
pub fn hazard_words(h: &SiteHazard) -> String {
    let ids: Vec<String> = h.nodes.iter().map(|n| n.id.to_string()).collect();
    let between = if h.return_periods[0] == h.return_periods[1] {
        format!("the grid's T_R = {} years column", h.return_periods[0])
    } else {
        format!(
            "log-interpolated between T_R = {} and {} years",
            h.return_periods[0], h.return_periods[1]
        )
    };
    format!(
        "hazard at latitude {}, longitude {}: V_N = {} years, use class {} (C_U = {}), V_R = {} years; {} (P_VR = {} %): T_R = {:.1} years; ag = {:.4} g, F0 = {:.3}, Tc* = {:.3} s from the NTC 2008 Allegato B grid, nodes {} (inverse distance), {}",
        num(h.latitude),
        num(h.longitude),
        num(h.nominal_life),
        h.use_class.as_str(),
        num(h.cu),
        num(h.v_r),
        h.limit_state.as_str(),
        num(100.0 * h.p_vr),
        h.t_r,
        h.params.ag,
        h.params.f0,
        h.params.tc_star,
        ids.join(", "),
        between
    )
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
        Family::General => "blocks rocking, lifting and sliding (the general kinematic program)",
        Family::HingesWithHeldTies => "hinges, with tie rods that keep their length",
    }
}

/// What a mechanism through `joints` moves: `the arcade` when one of them is a joint of an
/// arcade's bays, columns or piers, `the portal` when one of them is a pier joint, `the arch`
/// when all are arch joints, `the structure` otherwise.
pub fn what_moves(assembly: &Assembly, joints: impl IntoIterator<Item = usize>) -> &'static str {
    let arcade = assembly
        .joints
        .iter()
        .any(|j| matches!(j.kind, JointKind::Bay(..) | JointKind::Column(..)));
    let mut arch_only = true;
    for j in joints {
        match assembly.joints.get(j).map(|j| j.kind) {
            Some(JointKind::Arch(_)) => {}
            Some(JointKind::LeftPier(_) | JointKind::RightPier(_)) if arcade => {
                return "the arcade"
            }
            Some(JointKind::LeftPier(_) | JointKind::RightPier(_)) => return "the portal",
            Some(JointKind::Bay(..) | JointKind::Column(..)) => return "the arcade",
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
    if matches!(
        kind,
        JointKind::Between(..) | JointKind::Fixed(..) | JointKind::Spandrel(..)
    ) {
        // A joint between the user's blocks has no intrados or faces, only its two ends.
        return match end {
            JointEnd::P1 => "end p1",
            JointEnd::P2 => "end p2",
        };
    }
    let pier = matches!(
        kind,
        JointKind::LeftPier(_) | JointKind::RightPier(_) | JointKind::Column(..)
    );
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

/// One item per hinge: `joint 5 (arch 5), intrados (p1), at (x, y) m, polar 146.250 deg,
/// 56.250 deg from the vertical` (the direction p1 -> p2 of an arch joint, as the continuous
/// model gives its sections); pier joints without the angles.
pub fn hinge_items(assembly: &Assembly, hinges: &[Hinge]) -> Vec<String> {
    let mut items = Vec::new();
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
        items.push(format!(
            "joint {:>4} ({}), {}{inset}, at ({:.4}, {:.4}) m{angles}",
            h.joint,
            joint_label(joint.kind),
            end_words(joint.kind, h.end),
            h.x,
            h.y
        ));
    }
    items
}

/// The description of the scene as lines (a document's lead).
pub fn scene_lines(scene: &Scene, model: &Model) -> Vec<String> {
    describe_scene(scene, model)
        .split("\n  ")
        .map(str::to_string)
        .collect()
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
    if let Some(a) = &scene.arcade {
        let _ = write!(s, "\n  {}", a.describe());
    }
    if let Some(w) = &scene.spandrel {
        let pieces = assembly
            .blocks
            .iter()
            .filter(|b| matches!(b.kind, crate::assembly::BlockKind::Spandrel(..)))
            .count();
        let _ = write!(s, "\n  {} ({pieces} pieces)", w.describe());
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

/// The user's blocks in words: where from, how many joints were found (on the ground and on
/// each fixed block), whether a chain, and how the outlines were mended.
pub fn describe_blocks(b: &crate::scene::BlocksSpec) -> String {
    let d = &b.detected;
    let between = d.assembly.joints.len() - d.supports;
    let shape = match &d.topology {
        crate::blocks::Topology::Chain => "a chain between two supports".to_string(),
        crate::blocks::Topology::Column => "a chain standing on one support".to_string(),
        crate::blocks::Topology::Other(why) => format!("not a chain: {why}"),
    };
    let mut supports = Vec::new();
    if let Some(g) = d.ground_y {
        supports.push(format!(
            "{} on the ground y = {} m",
            count(d.ground_supports() as u64, "support", "supports"),
            num(g)
        ));
    }
    for f in &d.fixed {
        supports.push(format!(
            "{} on the fixed block {}",
            count(f.supports as u64, "support", "supports"),
            f.block
        ));
    }
    let mut s = format!(
        "{} from {} ({}): {} found between blocks and {} (tolerance {} m); {shape}",
        count(d.assembly.blocks.len() as u64, "user block", "user blocks"),
        b.source_words(),
        b.units.name(),
        count(between as u64, "joint", "joints"),
        supports.join(" and "),
        sci(d.tolerance, 1)
    );
    if b.mending.any() {
        let _ = write!(s, "\n  {}", mending_words(&b.mending));
    }
    s
}

/// How the outlines were mended, in words: `3 outlines mended as read: 1 open polyline closed
/// on its repeated first vertex, 2 turned counter-clockwise`.
pub fn mending_words(m: &crate::blocks::Mending) -> String {
    let how: Vec<String> = [
        (
            m.closed,
            "open polyline",
            "closed at a repeated first vertex",
        ),
        (m.repeated_vertices, "outline", "rid of repeated vertices"),
        (
            m.straight_vertices,
            "outline",
            "rid of vertices on a straight edge",
        ),
        (m.reversed, "outline", "turned counter-clockwise"),
    ]
    .into_iter()
    .filter(|(n, _, _)| *n > 0)
    .map(|(n, what, done)| format!("{} {done}", count(n as u64, what, &format!("{what}s"))))
    .collect();
    format!(
        "{} mended as read: {}",
        count(m.outlines as u64, "outline", "outlines"),
        how.join(", ")
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
        let d = &f.dispersal;
        if d.surface.is_some() || d.spread_deg.is_some() || d.spread.is_some() {
            let law = match d.law() {
                crate::scene::spread::Law::Boussinesq => "spread by Boussinesq".to_string(),
                crate::scene::spread::Law::Angle(a) if a > 0.0 => {
                    format!("spread at {} deg", num(a.to_degrees()))
                }
                _ => "not spread".to_string(),
            };
            parts.push(format!(
                "loads on the road surface y = {} m {law} through the fill",
                num(d.surface(f.level))
            ));
        }
        if let Some(p) = &f.passive {
            parts.push(format!(
                "the fill's passive resistance (phi = {} deg, K_p = {}, mobilisation {})",
                num(p.friction.to_degrees()),
                num(crate::interaction::passive::rankine_kp(p.friction)),
                num(p.mobilisation)
            ));
        }
    }
    for v in &scene.vehicles {
        parts.push(format!(
            "vehicle {} ({}, first at x = {} m{})",
            v.name,
            count(v.axles.len() as u64, "axle", "axles"),
            num(v.at),
            if v.beyond.is_some() {
                ", distributed load beyond"
            } else {
                ""
            }
        ));
    }
    let r = scene.seismic.vertical_ratio;
    if r != 0.0 {
        parts.push(format!("vertical seismic ratio {}", num(r)));
    }
    let live = (scene.loads.iter().filter(|l| l.live()).count()
        + scene.vehicles.iter().filter(|v| v.live).count()) as u64;
    if live > 0 {
        parts.push(format!("{live} live (multiplied by lambda)"));
    }
    if !model.ties.is_empty() {
        parts.push(count(model.ties.len() as u64, "tie rod", "tie rods"));
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

/// What finite friction makes of a static result with status `status`, in words (None when
/// it is exact, docs/friction.md): at collapse, how many joints slide in the associative
/// mechanism and that the multiplier is then an upper bound of the real collapse multiplier.
pub fn friction_words(f: &FrictionCheck, status: Status) -> Option<String> {
    if f.exact {
        return None;
    }
    Some(match status {
        Status::Collapse => format!(
            "associative friction: {} at collapse, so this multiplier is an upper bound of the real (non-associative) collapse multiplier, not a safe lower bound",
            count(f.slipping.len() as u64, "joint slides", "joints slide")
        ),
        _ => "associative friction: real joints slide without opening (non-associative), so no collapse of the static program does not prove that the structure holds".to_string(),
    })
}

/// What an exact multiplier with finite friction is where lower collapse states of real
/// joints are possible ([`FrictionCheck::lower_states_possible`]); `None` elsewhere.
pub fn exact_friction_words(f: &FrictionCheck) -> Option<String> {
    f.lower_states_possible.then(|| {
        format!(
            "friction: no joint slips in the collapse mechanism, so this is a collapse state of real joints (which slide without opening) too, but not proved the lowest: where joints carry little or no compression, as the head joints of a wall may, real joints can have lower ones (docs/friction.md): the non-associative iteration searches for them, by default in assemblies of up to {} blocks",
            crate::analysis::AUTO_SEARCH_MAX_BLOCKS
        )
    })
}

/// The static multiplier's name in a drawing's title: the static lower bound, or with sliding
/// joints the associative multiplier, an upper bound of the real one (docs/friction.md).
pub fn static_bound_name(f: &FrictionCheck) -> String {
    if f.lower_states_possible {
        "associative friction, exact, not proved the lowest".to_string()
    } else if f.exact {
        "static lower bound".to_string()
    } else {
        format!(
            "associative friction, an upper bound: {}",
            count(f.slipping.len() as u64, "joint slides", "joints slide")
        )
    }
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
    let wall = if scene.spandrel.is_some() {
        " with a spandrel wall"
    } else {
        ""
    };
    match &scene.arcade {
        Some(a) if a.bays > 1 => format!("{shape} arcade of {} bays{wall}", a.bays),
        _ => format!(
            "{shape} {}{wall}",
            if scene.piers.is_some() {
                "portal"
            } else {
                "arch"
            }
        ),
    }
}

/// How a dynamic run's criterion calls collapse, for the summaries.
pub fn criterion_words(criterion: crate::dem::dynamic::Criterion, displacement: f64) -> String {
    match criterion {
        crate::dem::dynamic::Criterion::Displacement => format!(
            "collapse criterion: displacement (a block point moved by {displacement:.4} m, a quarter of the structure's size)"
        ),
        crate::dem::dynamic::Criterion::Overturning => format!(
            "collapse criterion: overturning (the structure fell: a block point moved by {displacement:.4} m, its whole size; otherwise run until at rest)"
        ),
    }
}

/// How a motion along `component` acts, for the summaries.
pub fn component_words(component: &str) -> &'static str {
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

/// What a tie rod does along an assessment's capacity curve, in words.
pub fn tie_on_curve_words(t: &crate::assess::TieOnCurve) -> String {
    if t.lengthens && t.force <= 0.0 {
        return format!(
            "tie {}: no capacity, so it carries nothing along the curve",
            t.index
        );
    }
    if !t.lengthens {
        return format!(
            "tie {}: the mechanism shortens it, so it goes slack and carries nothing along the curve",
            t.index
        );
    }
    let breaks = match t.breaks_at_d_k {
        Some(d) => format!(
            "until it breaks at d_k = {:.2} mm (its ultimate strain), then nothing",
            1e3 * d
        ),
        None => "all along the curve (it does not reach its ultimate strain before d_k0)".into(),
    };
    format!(
        "tie {}: lengthened by the mechanism, it carries its capacity {:.1} N {breaks}",
        t.index, t.force
    )
}

/// What the non-associative multiplier `na` is, in words (docs/friction.md).
pub fn non_associative_words(na: &crate::statics::NonAssociative) -> String {
    if na.unsearched {
        return format!(
            "non-associative friction: not iterated: no joint slips in the associative mechanism, so its collapse state is a real one too, but lower ones are possible in this assembly and were not searched for above {} blocks (about 200 s at 984 blocks); --friction non-associative searches for them",
            crate::analysis::AUTO_SEARCH_MAX_BLOCKS
        );
    }
    if na.from_exact {
        return "non-associative friction: no joint slips in the associative mechanism, so its collapse state is a real one too, taken as the real multiplier (not iterated)".to_string();
    }
    let tried: Vec<&str> = na.starts.iter().map(|s| s.start.as_str()).collect();
    match na.lambda {
        Some(l) => {
            let slide = match na.sliding.len() {
                0 => "no joint slides".to_string(),
                1 => "1 joint slides without opening".to_string(),
                n => format!("{n} joints slide without opening"),
            };
            format!(
                "non-associative friction (real joints slide without opening): lambda = {l:.6} after {} programs, the lowest converged value from the starts {} ({slide}); such problems can have several solutions, and the real collapse multiplier is at most this value",
                na.iterations,
                tried.join(", ")
            )
        }
        None => format!(
            "non-associative friction: no start ({}) converged in {} programs, so there is no non-associative multiplier; the associative value remains an upper bound of the real collapse",
            tried.join(", "),
            na.iterations
        ),
    }
}

/// The analysis in one sentence, for the conclusion of a report: whether the structure
/// stands, the multiplier that governs and which bound or law it is (docs/friction.md), and
/// whether sliding governs, in the summaries' words.
pub fn conclusion_words(scene: &Scene, a: &crate::analysis::SceneAnalysis) -> String {
    let f = a.friction();
    let what = shape_title(scene);
    match (a.lower.status, a.lambda_governing()) {
        (Status::CannotStand, _) if a.sliding_governs() => format!(
            "The {what} cannot stand: with mu = {} the structure slides under its permanent loads alone, so it cannot stand.",
            num(scene.material.friction)
        ),
        (Status::CannotStand, _) => format!(
            "The {what} cannot stand: no thrust line fits under its permanent loads alone, so it collapses without any horizontal action."
        ),
        (Status::NoCollapse, _) => format!(
            "The {what} does not collapse: no admissible mechanism is driven by the load."
        ),
        (Status::Collapse, Some(l)) => {
            let name = if a.lambda_non_associative().is_some() && !f.exact {
                "the non-associative multiplier, joints that slide without opening".to_string()
            } else {
                static_bound_name(&f)
            };
            let mut s = format!(
                "The {what} stands under its permanent loads and becomes a mechanism at lambda = {l:.6} ({name})."
            );
            if a.sliding_governs() {
                s.push_str(" Sliding governs: joints slide in the collapse mechanism.");
            }
            s
        }
        (Status::Collapse, None) => format!("The {what} collapses, with no multiplier found."),
    }
}

/// What the fill's passive resistance does at collapse (`[fill] passive = true`): whether it
/// governs (some face's reaction at its cap: the fill yields in the mechanism) and how much
/// of it is mobilised.
pub fn passive_words(forces: &[crate::model::PassiveForce]) -> String {
    let at_cap = forces.iter().filter(|f| f.yielded && f.force > 0.0).count();
    let total: f64 = forces.iter().map(|f| f.force).sum();
    let cap: f64 = forces.iter().map(|f| f.cap).sum();
    if crate::interaction::passive::governs(forces) {
        format!(
            "the fill's passive resistance GOVERNS: {at_cap} of {} faces against the fill push back at their cap (m_p K_p sigma_v h), {:.3} kN of {:.3} kN in all: the multiplier counts on the fill yielding there",
            forces.len(),
            total / 1e3,
            cap / 1e3
        )
    } else {
        format!(
            "the fill's passive resistance does not govern: no face against the fill is at its cap ({} faces, {:.3} kN mobilised of {:.3} kN)",
            forces.len(),
            total / 1e3,
            cap / 1e3
        )
    }
}
