//! The figures of every command, chosen and drawn in one place: which drawing of the
//! structure or which chart a result gets, its title in the engineer's words, and its SVG
//! ([`Figure`]). The commands ask for a figure by what it shows; no command, front end or
//! analysis module assembles its own. The chart data of an assessment and of a sweep or a
//! study are in [`assess`] and [`mod@sweep`].

pub mod assess;
pub mod sweep;

pub use self::assess::{adrs_chart, capacity_chart};
pub use self::sweep::{chart, chart_of, key_label, study_chart, sweep_title};

use super::document::Figure;
use super::words::{num, shape_title, static_bound_name};
use super::{DemReport, PulseCurveReport};
use crate::analysis::{Assessment, DemAnalysis, SceneAnalysis};
use crate::assembly::Assembly;
use crate::convergence::{Convergence, RefinementRow};
use crate::drawing::chart::{chart_svg, Chart, Series};
use crate::drawing::svg::{structure_svg, Drawing, Mechanism, Placements, SvgError};
use crate::error::SceneError;
use crate::outcome::{Direction, Status};
use crate::scene::Scene;
use crate::thickness::MinThickness;

/// Why a figure could not be drawn.
#[derive(Debug, thiserror::Error)]
pub enum FigureError {
    #[error(transparent)]
    Svg(#[from] SvgError),
    /// The chart's axes do not fit the result (a key that is not varied).
    #[error(transparent)]
    Chart(#[from] SceneError),
    /// The assessment's mechanism cannot turn as far as asked.
    #[error("the mechanism cannot reach a rotation of {0} rad")]
    Unreachable(f64),
}

/// A chart as a figure.
pub fn of_chart(name: &'static str, chart: &Chart) -> Result<Figure, SvgError> {
    Ok(Figure {
        name,
        svg: chart_svg(chart)?,
    })
}

/// A drawing of the structure as a figure.
pub fn of_drawing(
    name: &'static str,
    assembly: &Assembly,
    drawing: &Drawing,
) -> Result<Figure, SvgError> {
    Ok(Figure {
        name,
        svg: structure_svg(assembly, drawing)?,
    })
}

/// The outlines of the scene's fixed blocks (`[blocks] fixed`), drawn behind the blocks.
fn fixed_outlines(scene: &Scene) -> Vec<Vec<crate::geometry::Vec2>> {
    scene.blocks.as_ref().map_or_else(Vec::new, |b| {
        b.detected.fixed.iter().map(|f| f.polygon.clone()).collect()
    })
}

/// A scene before any analysis (Python's `Scene._repr_svg_`): its blocks and loads, the
/// horizontal load toward +x.
pub fn scene(scene: &Scene, model: &crate::model::Model) -> Result<Figure, SvgError> {
    let fixed = fixed_outlines(scene);
    let drawing = Drawing {
        fixed: &fixed,
        title: shape_title(scene),
        load: Some(Direction::Right),
        loads: Some(&model.loads),
        ties: &model.ties,
        strips: &model.strips,
        passive: &model.passive,
        ..Default::default()
    };
    of_drawing("structure", &model.assembly, &drawing)
}

/// The drawing of one analysis, as `voussoir analyze --svg` writes it and `voussoir serve`
/// returns it: the blocks, the thrust line, the hinges, the sliding joints, the mechanism and
/// the loads, under the analysis's title.
pub fn analysis_svg(
    scene: &Scene,
    a: &SceneAnalysis,
    direction: Direction,
) -> Result<String, SvgError> {
    let result = &a.lower;
    let fixed = fixed_outlines(scene);
    // The general kinematic program's mechanism, certified by virtual work, where it ran
    // (assemblies that are not chains, or asked for); the static program's duals otherwise.
    let velocities = match (&a.upper, a.kinematic_search) {
        (Ok(k), Some(crate::kinematic::Search::General)) => k
            .mechanism
            .as_ref()
            .filter(|_| k.status == Status::Collapse)
            .map_or(&result.mechanism, |m| &m.velocities),
        _ => &result.mechanism,
    };
    let drawing = Drawing {
        fixed: &fixed,
        title: drawing_title(scene, a),
        forces: result.forces.as_deref(),
        hinges: &result.hinges,
        sliding: &result.sliding,
        mechanism: (!velocities.is_empty()).then_some(Mechanism {
            velocities,
            amplification: None,
        }),
        // A live action shakes nothing: no seismic arrow; its loads are labelled as multiplied.
        load: (a.model.loads.action() == crate::model::Action::Seismic).then_some(direction),
        loads: Some(&a.model.loads),
        ties: &a.model.ties,
        tie_forces: &result.ties,
        strips: &a.model.strips,
        strip_forces: &result.strips,
        passive: &a.model.passive,
        passive_forces: &result.passive,
        ..Default::default()
    };
    structure_svg(&a.model.assembly, &drawing)
}

/// `analyze`'s figure: [`analysis_svg`].
pub fn analysis(
    scene: &Scene,
    a: &SceneAnalysis,
    direction: Direction,
) -> Result<Figure, SvgError> {
    Ok(Figure {
        name: "structure",
        svg: analysis_svg(scene, a, direction)?,
    })
}

/// `analyze --roll`'s chart: the static (lower bound) and kinematic (upper bound)
/// multipliers against the moving load's position, the critical position marked.
pub fn roll_chart(scene: &Scene, r: &crate::roll::Roll) -> Result<Figure, SvgError> {
    let target = r.spec.target;
    let what = match target {
        crate::roll::Target::Vehicle(k) => format!(
            "vehicle {} (x of its first axle)",
            scene.vehicles.get(k).map_or("?", |v| v.name.as_str())
        ),
        crate::roll::Target::Load(_) => format!("{target}"),
    };
    let critical = r
        .critical
        .as_ref()
        .and_then(|c| c.analysis.lower.lambda.map(|l| (c.position, l)));
    let lower: Vec<(f64, f64)> = r
        .points
        .iter()
        .map(|p| (p.position, p.lambda_lower.unwrap_or(f64::NAN)))
        .collect();
    let mut series = vec![Series::line(
        r.critical
            .as_ref()
            .map_or("static lower bound".into(), |c| {
                static_bound_name(&c.analysis.friction())
            }),
        lower,
        critical,
    )];
    if r.points.iter().any(|p| p.lambda_upper.is_some()) {
        series.push(Series::line(
            "kinematic (upper bound)",
            r.points
                .iter()
                .map(|p| (p.position, p.lambda_upper.unwrap_or(f64::NAN)))
                .collect(),
            None,
        ));
    }
    let title = match critical {
        Some((x, l)) => format!(
            "{}: moving load {target}\ncritical position x = {x:.4} m, lambda = {l:.6}",
            shape_title(scene)
        ),
        None => format!("{}: moving load {target}", shape_title(scene)),
    };
    of_chart(
        "roll",
        &Chart {
            title,
            x_label: format!("position of {what} (m)"),
            y_label: "collapse multiplier lambda".into(),
            legend_title: None,
            series,
        },
    )
}

/// `min-thickness`'s figure: the thrust line at the minimum thickness under the permanent
/// loads; `None` when there is no minimum thickness.
pub fn min_thickness(scene: &Scene, m: &MinThickness) -> Result<Option<Figure>, SvgError> {
    let (Some((at, stand)), Some(t)) = (&m.at_minimum, m.search.min_thickness) else {
        return Ok(None);
    };
    let drawing = Drawing {
        title: format!(
            "{} at its minimum thickness t_min = {t:.6} m\nthrust line under the permanent loads (lambda = 0), {} hinges",
            shape_title(scene),
            stand.hinges.len()
        ),
        forces: Some(&stand.forces),
        hinges: &stand.hinges,
        loads: Some(&at.loads),
        ..Default::default()
    };
    of_drawing("structure", &at.assembly, &drawing).map(Some)
}

/// The direction assessed in words, for the assessment's figures: `load to the right,
/// governing` or `load to the left only`.
fn assessed_direction(all: &Assessment) -> String {
    let words = match all.governing().capacity.direction {
        Direction::Right => "load to the right",
        Direction::Left => "load to the left",
    };
    if all.directions.len() > 1 {
        format!("{words}, governing")
    } else {
        format!("{words} only")
    }
}

/// `assess`'s capacity curves (every direction assessed), under `title` (the scene's name).
pub fn assessment_capacity(all: &Assessment, title: &str) -> Result<Figure, SvgError> {
    let directions: Vec<_> = all
        .directions
        .iter()
        .map(|a| (&a.capacity, &a.verdict))
        .collect();
    of_chart(
        "capacity",
        &capacity_chart(&directions, all.governing, title),
    )
}

/// `assess`'s ADRS plot of the governing direction.
pub fn assessment_adrs(all: &Assessment, title: &str) -> Result<Figure, SvgError> {
    let a = all.governing();
    of_chart(
        "adrs",
        &adrs_chart(&a.capacity, &a.verdict, title, &assessed_direction(all)),
    )
}

/// `assess`'s mechanism of the governing direction turned by the fraction `at` of the
/// rotation at which alpha = 0, to true scale.
pub fn assessment_mechanism(all: &Assessment, title: &str, at: f64) -> Result<Figure, FigureError> {
    let a = all.governing();
    let model = &a.analysis.model;
    let Some(state) = a.capacity.state_at(model, at) else {
        return Err(FigureError::Unreachable(at * a.capacity.rotation0));
    };
    let (moves, d_k, alpha, u) = (state.moves, state.d_k, state.alpha, state.rotation);
    let hinges = a
        .analysis
        .upper
        .as_ref()
        .ok()
        .and_then(|k| k.mechanism.as_ref())
        .map(|m| m.hinges.clone())
        .unwrap_or_default();
    let drawing = Drawing {
        title: format!(
            "{title} ({})\n{}: control displacement dₖ = {:.1} mm, α = {alpha:.4} (α₀ = {:.4})",
            assessed_direction(all),
            match a.capacity.motion {
                // The incremental path is followed in d_k; its control block may not turn
                // (a lintel that translates).
                crate::assess::Motion::Incremental(_) => format!(
                    "mechanism moved {:.0} % of the way to dₖ₀ (incremental)",
                    100.0 * at
                ),
                crate::assess::Motion::Linkage(_) => format!("mechanism turned by {u:.4} rad"),
            },
            1e3 * d_k,
            a.capacity.alpha0
        ),
        hinges: &hinges,
        moved: Some(Placements {
            moves: &moves,
            label: format!("moved (true scale), α = {alpha:.4}"),
        }),
        load: Some(a.capacity.direction),
        loads: Some(&model.loads),
        ..Default::default()
    };
    Ok(of_drawing("mechanism", &model.assembly, &drawing)?)
}

/// `dem`'s figure: the blocks at the end of the collapsing run, the displacements amplified
/// (and said so) when collapse was detected at a small one.
pub fn dem(scene: &Scene, d: &DemAnalysis, rep: &DemReport) -> Result<Figure, SvgError> {
    let (model, result) = (&d.model, &d.result);
    let assembly = &model.assembly;
    let placed = result.final_placements(assembly);
    let (moves, amp) = placed
        .as_ref()
        .map_or((Vec::new(), 1.0), |p| p.amplified(assembly, 0.1));
    let amp_note = if amp > 1.0 {
        format!(", displacements x{amp:.1}")
    } else {
        String::new()
    };
    let label = match (&placed, result.lambda_collapses) {
        (Some(p), Some(l)) => format!(
            "at t = {:.3} s of the run at lambda = {l:.4}{amp_note}",
            p.time
        ),
        (Some(p), None) => format!("at t = {:.3} s of the last run{amp_note}", p.time),
        _ => String::new(),
    };
    let fixed = fixed_outlines(scene);
    let drawing = Drawing {
        fixed: &fixed,
        title: dem_drawing_title(scene, rep, d.lower.status),
        moved: (!moves.is_empty()).then_some(Placements {
            moves: &moves,
            label,
        }),
        loads: Some(&model.loads),
        ..Default::default()
    };
    of_drawing("structure", assembly, &drawing)
}

/// `dem --pulse-curve`'s chart: the minimum collapse amplitude (g) against the pulse period,
/// one line per pulse shape (`shapes`, in the order asked).
pub fn pulse_curve(
    scene: &Scene,
    rep: &PulseCurveReport,
    shapes: &[&str],
) -> Result<Figure, SvgError> {
    let g = crate::dem::record::STANDARD_GRAVITY;
    let series = shapes
        .iter()
        .map(|&name| {
            Series::new(
                format!("{name} pulse"),
                rep.points
                    .iter()
                    .filter(|q| q.shape == name)
                    .map(|q| (q.period, q.amplitude_collapses.map(|a| a / g))),
            )
        })
        .collect();
    let chart = Chart {
        title: format!(
            "Minimum collapse amplitude of one pulse (DEM, to {:.1}%): {}",
            100.0 * rep.tolerance,
            scene.origin
        ),
        x_label: "pulse period T (s)".to_string(),
        y_label: "amplitude (g)".to_string(),
        legend_title: Some("pulse".to_string()),
        series,
    };
    of_chart("chart", &chart)
}

/// `fragility`'s chart: the fitted curve over the samples' empirical fragility.
pub fn fragility(
    scene: &Scene,
    f: &crate::fragility::CapacityFragility,
) -> Result<Figure, SvgError> {
    of_chart("chart", &super::fragility::chart(scene, f))
}

/// `fragility --records`'s chart: the fitted curve over the stripes' shares of collapse.
pub fn dynamic_fragility(
    scene: &Scene,
    f: &crate::fragility::DynamicFragility,
) -> Result<Figure, SvgError> {
    of_chart("chart", &super::fragility::dynamic_chart(scene, f))
}

/// `sweep`'s chart: lambda against `x`, one line per value of the other keys.
pub fn sweep(
    scene: &Scene,
    plan: &crate::sweep::Sweep,
    rows: &[crate::sweep::SweepRow],
    x: &str,
    series: Option<&str>,
) -> Result<Figure, FigureError> {
    let title = sweep_title(scene, plan, x);
    Ok(of_chart(
        "chart",
        &chart(plan.variations(), rows, x, series, &title)?,
    )?)
}

/// `study`'s chart ([`study_chart`]).
pub fn study(
    study: &crate::study::Study,
    rows: &[crate::sweep::SweepRow],
) -> Result<Figure, FigureError> {
    Ok(of_chart("chart", &study_chart(study, rows)?)?)
}

/// log10 of the relative error of each bound against log10 n (the chart module has linear
/// axes only, so the logarithms are plotted; a slope of -2 is second-order convergence).
pub fn convergence_chart(c: &Convergence, title: &str) -> Chart {
    let series = |name: &str, f: fn(&RefinementRow) -> Option<f64>| {
        Series::new(
            name,
            c.refinement.iter().map(|r| {
                (
                    (r.voussoirs as f64).log10(),
                    f(r).filter(|e| *e != 0.0).map(|e| e.abs().log10()),
                )
            }),
        )
    };
    let mut s = vec![series("static lower bound", |r| r.error_lower)];
    if c.refinement.iter().any(|r| r.error_upper.is_some()) {
        s.push(series("kinematic upper bound", |r| r.error_upper));
    }
    Chart {
        title: title.to_string(),
        x_label: "log10 (number of voussoirs n)".into(),
        y_label: "log10 |lambda_n / lambda_continuous - 1|".into(),
        legend_title: None,
        series: s,
    }
}

/// `convergence`'s figure: [`convergence_chart`] under the structure's name.
pub fn convergence(scene: &Scene, c: &Convergence) -> Result<Figure, SvgError> {
    let title = format!(
        "{}: convergence with the number of voussoirs",
        shape_title(scene)
    );
    of_chart("chart", &convergence_chart(c, &title))
}

/// Title of a structure drawing: shape, thickness, voussoirs, and the multipliers of every
/// bound that ran, or in words why there is none (`cannot stand`, `no collapse`). Written for
/// the engineer (λ and the bound's name), not with the JSON keys.
pub fn drawing_title(scene: &Scene, a: &SceneAnalysis) -> String {
    let lower = match (a.lower.status, a.lower.lambda) {
        (Status::Collapse, Some(l)) => {
            format!("λ ({}) = {l:.4}", static_bound_name(&a.friction()))
        }
        (Status::NoCollapse, _) if !a.friction().exact => {
            "no collapse with associative friction: a thrust line fits at any λ (not a proof with real friction)".to_string()
        }
        (Status::NoCollapse, _) => "no collapse: a thrust line fits at any λ".to_string(),
        _ => "cannot stand: no thrust line fits".to_string(),
    };
    let upper = match &a.upper {
        Ok(k) => match (k.status, k.lambda_upper) {
            (Status::Collapse, Some(u))
                if a.sliding_governs() && k.search != crate::kinematic::Search::General =>
            {
                Some(format!(
                    "λ (kinematic upper bound) = {u:.4} (rotation only)"
                ))
            }
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
    // The real joints' multiplier where the iteration found it apart from the static one
    // (sliding joints, or a wall's head joints): the value that governs (docs/friction.md).
    if let (Some(na), Some(l)) = (a.lambda_non_associative(), a.lower.lambda) {
        if (na - l).abs() > 1e-9 * l.abs().max(1.0) {
            second = format!("λ (non-associative, real joints) = {na:.4}\n{second}");
        }
    }
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
