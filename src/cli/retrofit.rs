//! `voussoir retrofit`: the smallest tie rods that give a target multiplier.

use super::{draw, Format, SceneArgs};
use voussoir::analysis;
use voussoir::error::Error;
use voussoir::report;
use voussoir::statics::StaticSettings;

#[derive(clap::Args)]
pub struct Args {
    #[command(flatten)]
    scene: SceneArgs,
    /// The multiplier the retrofitted structure must carry (in both directions of a seismic
    /// action; the adequacy factor of a live one)
    #[arg(long, value_name = "LAMBDA", conflicts_with = "site")]
    target_lambda: Option<f64>,
    /// Design for a site instead: the least capacities whose structure passes the NTC 2018
    /// check of `voussoir assess` there. Sets a key of the scene's [site] table, e.g.
    /// --site ag=0.25 --site soil=B (repeatable). Without --target-lambda, a scene with a
    /// [site] table is designed for its site
    #[arg(long = "site", value_name = "KEY=VALUE")]
    site: Vec<String>,
    /// Print one JSON object instead of the summary
    #[arg(long)]
    json: bool,
    /// Draw the retrofitted structure at collapse in the governing direction to this SVG file
    #[arg(long, value_name = "FILE")]
    svg: Option<std::path::PathBuf>,
    /// Conic solver tolerance (gap and feasibility, dimensionless; 1e-14..1e-6)
    #[arg(long, default_value_t = 1e-10)]
    tolerance: f64,
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
        .output("--svg", args.svg.as_deref(), Format::Svg)
        .check()?;
    let options = analysis::Options {
        static_settings: StaticSettings::default().tolerance(args.tolerance),
        friction: args.friction.into(),
        ..analysis::Options::default()
    };
    let (site, plain) = match args.target_lambda {
        Some(target) => (
            None,
            Some(voussoir::retrofit::design(&scene, target, &options)?),
        ),
        None if scene.site.is_some() => (
            Some(voussoir::retrofit::design_for_site(
                &scene,
                &options,
                &analysis::AssessOptions::default(),
            )?),
            None,
        ),
        None => {
            return Err(voussoir::error::AnalysisError::Other(format!(
                "{}: what should the retrofit reach? Give --target-lambda L, or a site (--site ag=0.25 --site soil=B ..., or a [site] table in the scene)",
                scene.origin
            ))
            .into())
        }
    };
    let Some(r) = site.as_ref().map(|s| &s.design).or(plain.as_ref()) else {
        return Err(voussoir::error::AnalysisError::Other("no design".into()).into());
    };
    // The governing direction: the least multiplier.
    let governing = r.analyses.iter().min_by(|a, b| {
        let l = |x: &(_, analysis::SceneAnalysis)| x.1.lambda_governing().unwrap_or(f64::INFINITY);
        l(a).total_cmp(&l(b))
    });
    let figure = match governing {
        Some((d, a)) => draw(args.svg.as_deref(), || {
            report::figures::analysis(&scene, a, *d)
        })?,
        None => {
            if let Some(path) = &args.svg {
                eprintln!(
                    "note: the target is not reachable, so there is no retrofitted structure to draw: {} not written",
                    path.display()
                );
            }
            None
        }
    };
    let mut doc = match &site {
        Some(s) => report::retrofit::site_document(&scene, s),
        None => report::retrofit::document(&scene, r),
    };
    doc.figures.extend(figure);
    Ok(super::print(&doc, args.json))
}
