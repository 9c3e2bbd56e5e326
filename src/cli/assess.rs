//! `voussoir assess`: the seismic verdict of a scene's governing mechanism at its `[site]`.

use super::{draw, Dir, SceneArgs};
use voussoir::analysis;
use voussoir::error::{AnalysisError, Error};
use voussoir::report::{documents, figures};

#[derive(clap::Args)]
pub struct Args {
    #[command(flatten)]
    scene: SceneArgs,
    /// Set a key of the scene's [site] table, e.g. --site ag=0.25 --site soil=B (repeatable;
    /// keys: ag, soil, topography, F0, Tc_star, q, FC, Z, H, T1; or latitude, longitude,
    /// nominal_life, use_class, limit_state for ag, F0, Tc_star of the national hazard grid)
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
    /// (of d_k0 on the incremental route)
    #[arg(long, default_value_t = 0.5)]
    at: f64,
    /// Points of the capacity curve
    #[arg(long, default_value_t = 200)]
    points: usize,
    /// Control block (its centroid is the control point); default the block that moves most
    #[arg(long)]
    control_block: Option<usize>,
    /// Follow the mechanism by the incremental analysis (re-solved in each displaced
    /// configuration) even when it is a chain's, whose finite kinematics are known in closed
    /// form; mechanisms of walls, lintels and arcades always take it
    #[arg(long)]
    incremental: bool,
    /// Assess one direction of the horizontal acceleration only (default: both, the worse
    /// governs; with this flag the verdict covers the given direction only)
    #[arg(long, value_enum)]
    direction: Option<Dir>,
    /// Friction law of the multiplier: auto (the non-associative multiplier of real joints,
    /// which slide without opening, whenever joints slide in the static mechanism),
    /// associative (the static program's alone), non-associative (always)
    #[arg(long, value_enum, default_value = "auto")]
    friction: super::Friction,
}

pub fn run(args: Args) -> Result<String, Error> {
    let (scene, _) = args.scene.load_with_site(&args.site)?;
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
    let options = analysis::Options {
        friction: args.friction.into(),
        ..analysis::Options::default()
    };
    let assess = analysis::AssessOptions {
        points: args.points,
        control_block: args.control_block,
        incremental: args.incremental,
    };
    let all = voussoir::analysis::assess_directions(
        &scene,
        &options,
        &assess,
        args.direction.map(Into::into),
    )?;
    // The file name: the origin also lists the overrides, too long for a chart title.
    let title = args.scene.scene.file_name().map_or_else(
        || scene.origin.clone(),
        |n| n.to_string_lossy().into_owned(),
    );
    let figures = [
        draw(args.svg.as_deref(), || {
            figures::assessment_capacity(&all, &title)
        })?,
        draw(args.adrs_svg.as_deref(), || {
            figures::assessment_adrs(&all, &title)
        })?,
        draw(args.mechanism_svg.as_deref(), || {
            figures::assessment_mechanism(&all, &title, args.at)
        })?,
    ];
    let mut doc = documents::assessment(&scene, &all);
    doc.figures.extend(figures.into_iter().flatten());
    Ok(super::print(&doc, args.json))
}
