//! `voussoir assess`: the seismic verdict of a scene's governing mechanism at its `[site]`.

use super::{json, write_chart, write_svg, Dir, SceneArgs};
use voussoir::analysis;
use voussoir::drawing::svg::{Drawing, Placements};
use voussoir::error::{AnalysisError, Error};
use voussoir::outcome::Direction;
use voussoir::report::assessment::{assessment_summary, AssessmentReport};

#[derive(clap::Args)]
pub struct Args {
    #[command(flatten)]
    scene: SceneArgs,
    /// Set a key of the scene's [site] table, e.g. --site ag=0.25 --site soil=B (repeatable;
    /// keys: ag, soil, topography, F0, Tc_star, q, FC, Z, H, T1)
    #[arg(long = "site", value_name = "KEY=VALUE")]
    site: Vec<String>,
    /// Print one JSON object instead of the summary
    #[arg(long)]
    json: bool,
    /// Draw the capacity curve (alpha against the control displacement d_k) to this SVG file
    #[arg(long, value_name = "FILE")]
    svg: Option<std::path::PathBuf>,
    /// Draw the ADRS plot (capacity against the demand spectrum) to this SVG file
    #[arg(long, value_name = "FILE")]
    adrs_svg: Option<std::path::PathBuf>,
    /// Draw the mechanism moved along its capacity curve to this SVG file
    #[arg(long, value_name = "FILE")]
    mechanism_svg: Option<std::path::PathBuf>,
    /// Where the mechanism is drawn: the fraction (0..1) of the rotation at which alpha = 0
    #[arg(long, default_value_t = 0.5)]
    at: f64,
    /// Points of the capacity curve
    #[arg(long, default_value_t = 200)]
    points: usize,
    /// Control block (its centroid is the control point); default the block that moves most
    #[arg(long)]
    control_block: Option<usize>,
    /// Assess one direction of the horizontal acceleration only (default: both, the worse
    /// governs; with this flag the verdict covers the given direction only)
    #[arg(long, value_enum)]
    direction: Option<Dir>,
}

pub fn run(args: Args) -> Result<String, Error> {
    let mut scene = args.scene.load()?;
    if !args.site.is_empty() {
        let sets: Vec<String> = args.site.iter().map(|s| format!("site.{s}")).collect();
        scene = scene.with_overrides(&sets)?;
    }
    args.scene
        .outputs(&scene)
        .output("--svg", args.svg.as_deref(), super::Format::Svg)
        .output("--adrs-svg", args.adrs_svg.as_deref(), super::Format::Svg)
        .output(
            "--mechanism-svg",
            args.mechanism_svg.as_deref(),
            super::Format::Svg,
        )
        .check()?;
    if !(args.at.is_finite() && (0.0..=1.0).contains(&args.at)) {
        return Err(Error::Analysis(AnalysisError::Other(format!(
            "--at {}: must be a fraction from 0 to 1",
            args.at
        ))));
    }
    let options = analysis::Options::default();
    let assess = analysis::AssessOptions {
        points: args.points,
        control_block: args.control_block,
    };
    let all = voussoir::analysis::assess_directions(
        &scene,
        &options,
        &assess,
        args.direction.map(Into::into),
    )?;
    let a = all.governing();
    // The file name: the origin also lists the overrides, too long for a chart title.
    let title = args.scene.scene.file_name().map_or_else(
        || scene.origin.clone(),
        |n| n.to_string_lossy().into_owned(),
    );
    let dir_words = match a.capacity.direction {
        Direction::Right => "load to the right",
        Direction::Left => "load to the left",
    };
    let note = if all.directions.len() > 1 {
        format!("{dir_words}, governing")
    } else {
        format!("{dir_words} only")
    };
    if let Some(path) = &args.svg {
        write_chart(
            path,
            &voussoir::assess::pictures::capacity_chart(
                &all.directions
                    .iter()
                    .map(|a| (&a.capacity, &a.verdict))
                    .collect::<Vec<_>>(),
                all.governing,
                &title,
            ),
        )?;
    }
    if let Some(path) = &args.adrs_svg {
        write_chart(
            path,
            &voussoir::assess::pictures::adrs_chart(&a.capacity, &a.verdict, &title, &note),
        )?;
    }
    if let Some(path) = &args.mechanism_svg {
        let model = &a.analysis.model;
        let u = args.at * a.capacity.rotation0;
        let Some((config, alpha)) = a.capacity.at(model, u) else {
            return Err(Error::Analysis(AnalysisError::Other(format!(
                "the mechanism cannot reach a rotation of {u} rad"
            ))));
        };
        let moves = a.capacity.linkage.placements(&model.assembly, &config);
        let d_k = a.capacity.d_k(model, &config);
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
                "{title} ({note})\nmechanism turned by {u:.4} rad: control displacement dₖ = {:.1} mm, α = {alpha:.4} (α₀ = {:.4})",
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
        write_svg(path, &model.assembly, &drawing)?;
    }
    Ok(if args.json {
        json(&AssessmentReport::new(&scene, &all))
    } else {
        assessment_summary(&scene, &all)
    })
}
