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
    #[arg(long, value_name = "LAMBDA")]
    target_lambda: f64,
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
    let scene = args.scene.load()?;
    args.scene
        .outputs(&scene)
        .output("--svg", args.svg.as_deref(), Format::Svg)
        .check()?;
    let options = analysis::Options {
        static_settings: StaticSettings::default().tolerance(args.tolerance),
        friction: args.friction.into(),
        ..analysis::Options::default()
    };
    let r = voussoir::retrofit::design(&scene, args.target_lambda, &options)?;
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
    let mut doc = report::retrofit::document(&scene, &r);
    doc.figures.extend(figure);
    Ok(super::print(&doc, args.json))
}
