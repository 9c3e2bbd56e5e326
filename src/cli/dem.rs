//! `voussoir dem`: the collapse multiplier bracketed by discrete-element runs.

use super::{json, progress_bar, write_svg, SceneArgs};
use voussoir::analysis::{self, DemOptions};
use voussoir::dem;
use voussoir::error::Error;
use voussoir::report;
use voussoir::thrustline::svg::{self, Drawing};

#[derive(clap::Args)]
pub struct Args {
    #[command(flatten)]
    scene: SceneArgs,
    /// Print one JSON object instead of the summary
    #[arg(long)]
    json: bool,
    /// Relative width of the final bracket [lambda_stands, lambda_collapses]
    #[arg(long, default_value_t = 0.01)]
    tolerance: f64,
    /// Start the bracket search at the static lower bound (fast: the DEM then verifies the
    /// static value instead of finding its own threshold from dem.initial_guess or 0.2)
    #[arg(long)]
    from_static: bool,
    /// Write block positions during the runs (CSV) into this directory
    #[arg(long, value_name = "DIR")]
    snapshots: Option<std::path::PathBuf>,
    /// Draw the initial and final block positions of the collapsing run to this SVG file
    #[arg(long, value_name = "FILE")]
    svg: Option<std::path::PathBuf>,
}

pub fn run(args: Args) -> Result<String, Error> {
    let scene = args.scene.load()?;
    super::check_output_paths([args.svg.as_ref()])?;
    let options = DemOptions {
        tolerance: args.tolerance,
        snapshots: args.snapshots.is_some() || args.svg.is_some(),
        from_static: args.from_static,
    };
    let bar = progress_bar(1000, "dem");
    let d = analysis::dem(&scene, &options, &mut |f| {
        bar.set_position((f.clamp(0.0, 1.0) * 1000.0) as u64)
    })?;
    bar.finish_and_clear();
    let (model, result) = (&d.model, &d.result);
    let assembly = &model.assembly;
    if let Some(dir) = &args.snapshots {
        dem::write_snapshots(dir, result).map_err(|e| Error::Output {
            path: dir.clone(),
            message: e.to_string(),
        })?;
    }
    let rep = report::DemReport::of(&scene, &d);
    if let Some(path) = &args.svg {
        // Collapse is detected at a small displacement: amplify it so the mechanism shows,
        // and say so.
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
        let drawing = Drawing {
            title: report::dem_drawing_title(&scene, &rep, d.lower.status),
            moved: (!moves.is_empty()).then_some(svg::Placements {
                moves: &moves,
                label,
            }),
            loads: Some(&model.loads),
            ..Default::default()
        };
        write_svg(path, assembly, &drawing)?;
    }
    Ok(if args.json {
        json(&rep)
    } else {
        report::dem_summary(&scene, model, &rep)
    })
}
