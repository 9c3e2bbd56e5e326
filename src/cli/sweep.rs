//! `voussoir sweep`: the cartesian product of varied scene keys, solved in parallel.

use super::{progress_bar, write_atomically, write_chart, SceneArgs};
use voussoir::analysis;
use voussoir::error::Error;
use voussoir::report;
use voussoir::sweep;
use voussoir::thrustline::chart::Chart;

#[derive(clap::Args)]
pub struct Args {
    #[command(flatten)]
    scene: SceneArgs,
    /// KEY=V1,V2,... or KEY=START:STOP:STEP; KEY is a scene key (arch.thickness) or a
    /// ratio (t/R, e/R, h/R, b/R, t/span, rise/span). Repeatable.
    #[arg(long, value_name = "KEY=VALUES", required = true)]
    vary: Vec<String>,
    /// Write the rows to this CSV file (default: standard output)
    #[arg(long, value_name = "FILE")]
    csv: Option<std::path::PathBuf>,
    /// Draw lambda against --x to this SVG file, one line per value of the other keys
    #[arg(long, value_name = "FILE", requires = "x")]
    svg: Option<std::path::PathBuf>,
    /// Abscissa of the chart: a varied key or a ratio (t/R, e/R, h/R, b/R, t/span, rise/span)
    #[arg(long, value_name = "KEY")]
    x: Option<String>,
    /// Key whose values name the lines of the chart (listed first in the legend)
    #[arg(long, value_name = "KEY")]
    series: Option<String>,
    /// Add the continuous model's multiplier (column lambda_continuous)
    #[arg(long)]
    continuous: bool,
    /// Add the DEM multiplier, bracketed to 1% (column lambda_dem; about a second per case)
    #[arg(long = "dem")]
    run_dem: bool,
    /// Largest chain (joints) for the kinematic search; 0 turns it off
    #[arg(long, default_value_t = analysis::KINEMATIC_DEFAULT_MAX_JOINTS)]
    kinematic_max_joints: usize,
}

pub fn run(args: Args) -> Result<String, Error> {
    let scene = args.scene.load()?;
    let variations = args
        .vary
        .iter()
        .map(|v| sweep::parse_variation(v))
        .collect::<Result<Vec<_>, _>>()?;
    let chart_for = |rows: &[sweep::SweepRow]| -> Result<Option<Chart>, Error> {
        match (&args.svg, &args.x) {
            (Some(_), Some(x)) => Ok(Some(sweep::chart(
                &variations,
                rows,
                x,
                args.series.as_deref(),
                &format!(
                    "{}: collapse multiplier against {x}",
                    report::shape_title(&scene)
                ),
            )?)),
            _ => Ok(None),
        }
    };
    // Check --x and --series before solving anything.
    chart_for(&[])?;
    sweep::check_variations(&scene, &variations)?;
    let cases = sweep::cases(&scene, &variations);
    let bar = progress_bar(cases.len() as u64, "sweep");
    let options = analysis::Options {
        continuous: args.continuous,
        kinematic_max_joints: args.kinematic_max_joints,
        ..analysis::Options::default()
    };
    let rows = sweep::run(
        &cases,
        |values, s| sweep::case(values, s, &options, args.run_dem),
        &|| bar.inc(1),
    );
    bar.finish_and_clear();
    if let (Some(path), Some(chart)) = (&args.svg, chart_for(&rows)?) {
        write_chart(path, &chart)?;
    }
    let mut buf = Vec::new();
    sweep::write_csv(&mut buf, &variations, &rows).map_err(|e| Error::Output {
        path: args.csv.clone().unwrap_or_else(|| "stdout".into()),
        message: e.to_string(),
    })?;
    match &args.csv {
        Some(path) => {
            write_atomically(path, |b| {
                *b = buf;
                Ok(())
            })?;
            let failed = rows.iter().filter(|r| r.status == "error").count();
            Ok(format!(
                "{} cases written to {}{}",
                rows.len(),
                path.display(),
                if failed > 0 {
                    format!(" ({failed} with status error)")
                } else {
                    String::new()
                }
            ))
        }
        None => Ok(String::from_utf8_lossy(&buf).into_owned()),
    }
}
