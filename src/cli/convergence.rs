//! `voussoir convergence`: speed against accuracy for one scene.

use super::{draw, progress_spinner, write_atomically, Format, SceneArgs};
use voussoir::analysis;
use voussoir::error::{AnalysisError, Error};
use voussoir::report;

#[derive(clap::Args)]
pub struct Args {
    #[command(flatten)]
    scene: SceneArgs,
    /// Print one JSON object instead of the tables
    #[arg(long)]
    json: bool,
    /// Write the refinement table (one row per voussoir count) to this CSV file
    #[arg(long, value_name = "FILE")]
    csv: Option<std::path::PathBuf>,
    /// Draw log10 of the relative error against log10 n to this SVG file
    #[arg(long, value_name = "FILE")]
    svg: Option<std::path::PathBuf>,
    /// Largest voussoir count of the refinement (counts double from 8)
    #[arg(long, default_value_t = 1024)]
    max_voussoirs: usize,
    /// Largest chain (joints) for the exhaustive kinematic search; 0 turns it off
    #[arg(long, default_value_t = analysis::KINEMATIC_DEFAULT_MAX_JOINTS)]
    kinematic_max_joints: usize,
    /// Skip the DEM study (a few seconds on a 16-voussoir copy of the scene)
    #[arg(long)]
    no_dem: bool,
}

pub fn run(args: Args) -> Result<String, Error> {
    let scene = args.scene.load()?;
    args.scene
        .outputs(&scene)
        .output("--csv", args.csv.as_deref(), Format::Csv)
        .output("--svg", args.svg.as_deref(), Format::Svg)
        .check()?;
    let settings = voussoir::convergence::ConvergenceSettings {
        max_voussoirs: args.max_voussoirs,
        kinematic_max_joints: args.kinematic_max_joints,
        dem: !args.no_dem,
        ..Default::default()
    };
    let bar = progress_spinner("convergence");
    let c = voussoir::convergence::run(&scene, &settings, &mut |what| {
        bar.set_message(what.to_string())
    })
    .map_err(|e| Error::Analysis(AnalysisError::Other(e.to_string())))?;
    bar.finish_and_clear();
    let figure = draw(args.svg.as_deref(), || {
        report::figures::convergence(&scene, &c)
    })?;
    if let Some(path) = &args.csv {
        write_atomically(path, |b| c.write_csv(b).map_err(|e| e.to_string()))?;
    }
    let mut doc = report::documents::convergence(c);
    doc.figures.extend(figure);
    Ok(super::print(&doc, args.json))
}
