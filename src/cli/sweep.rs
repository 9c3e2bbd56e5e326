//! `voussoir sweep`: the cartesian product of varied scene keys, solved in parallel.

use super::{draw, progress_bar, write_atomically, Format, SceneArgs};
use voussoir::analysis;
use voussoir::error::{Error, SceneError};
use voussoir::report;
use voussoir::sweep;

#[derive(clap::Args)]
pub struct Args {
    #[command(flatten)]
    scene: SceneArgs,
    /// KEY=V1,V2,... or KEY=START:STOP:STEP; KEY is a scene key (arch.thickness) or a
    /// ratio: t/R, e/R, h/R, b/R (R the centreline radius), t/span, rise/span, e/span (span
    /// the centreline span; e/span keeps a pointed arch's span), sigma (the strength ratio
    /// W/(fc d t): sets material.compressive_strength; 0 is rigid). Repeatable.
    #[arg(long, value_name = "KEY=VALUES", required = true)]
    vary: Vec<String>,
    /// Write the rows to this CSV file (default: standard output)
    #[arg(long, value_name = "FILE")]
    csv: Option<std::path::PathBuf>,
    /// Draw lambda against --x to this SVG file, one line per value of the other keys
    #[arg(long, value_name = "FILE")]
    svg: Option<std::path::PathBuf>,
    /// Abscissa of the chart (with --svg): a varied key, or a ratio that changes with the
    /// varied keys (t/R, e/R, h/R, b/R, t/span, rise/span, e/span, sigma); default: the varied key
    /// when only one is varied
    #[arg(long, value_name = "KEY")]
    x: Option<String>,
    /// Varied key whose values name the lines of the chart (with --svg; listed first in the
    /// legend)
    #[arg(long, value_name = "KEY")]
    series: Option<String>,
    /// Add the continuous model's multiplier (column lambda_continuous)
    #[arg(long)]
    continuous: bool,
    /// Add the DEM multiplier, bracketed to 1% from its own start (columns lambda_dem, its wall
    /// time dem_time_s, not counted in solve_time_s, lambda_dem_low, lambda_dem_high,
    /// dem_bracket_width, static_inside_dem_bracket; a few seconds per case)
    #[arg(long = "dem")]
    run_dem: bool,
    /// Largest chain (joints) for the kinematic search; 0 turns it off
    #[arg(long, default_value_t = analysis::KINEMATIC_DEFAULT_MAX_JOINTS)]
    kinematic_max_joints: usize,
    /// The upper bound: the mechanism of the static hinges (certified) or the exhaustive search
    #[arg(long, value_enum, default_value = "certified")]
    kinematic: super::Kinematic,
}

/// The chart's abscissa: `--x`, or the one varied key; `None` without `--svg` (then `--x`
/// and `--series` are refused rather than ignored).
fn chart_x(args: &Args, variations: &[sweep::Variation]) -> Result<Option<String>, SceneError> {
    if args.svg.is_none() {
        let given: Vec<&str> = [
            args.x.as_ref().map(|_| "--x"),
            args.series.as_ref().map(|_| "--series"),
        ]
        .into_iter()
        .flatten()
        .collect();
        if !given.is_empty() {
            return Err(SceneError::Usage(format!(
                "{} only shape{} the chart: add --svg FILE to draw it",
                given.join(" and "),
                if given.len() == 1 { "s" } else { "" }
            )));
        }
        return Ok(None);
    }
    match (&args.x, variations) {
        (Some(x), _) => Ok(Some(x.clone())),
        (None, [only]) => Ok(Some(only.key.clone())),
        (None, _) => Err(SceneError::Usage(format!(
            "--svg needs --x KEY when more than one key is varied (one of {})",
            variations
                .iter()
                .map(|v| v.key.as_str())
                .collect::<Vec<_>>()
                .join(", ")
        ))),
    }
}

pub fn run(args: Args) -> Result<String, Error> {
    let scene = args.scene.load()?;
    let variations = args
        .vary
        .iter()
        .map(|v| sweep::parse_variation(v))
        .collect::<Result<Vec<_>, _>>()?;
    // Everything is checked before anything is solved: the chart's options, the varied keys
    // and values, and the output paths.
    let x = chart_x(&args, &variations)?;
    let plan = sweep::Sweep::new(&scene, variations)?;
    let variations = plan.variations();
    if let Some(x) = &x {
        sweep::check_chart(&plan, x, args.series.as_deref())?;
    }
    args.scene
        .outputs(&scene)
        .output("--csv", args.csv.as_deref(), Format::Csv)
        .output("--svg", args.svg.as_deref(), Format::Svg)
        .check()?;
    let bar = progress_bar(plan.len() as u64, "sweep");
    let options = analysis::Options {
        continuous: args.continuous,
        kinematic_max_joints: args.kinematic_max_joints,
        kinematic: args.kinematic.into(),
        // A sweep reports the static multiplier: the non-associative iteration of every case
        // would cost its programs for a number no row prints (docs/friction.md).
        friction: analysis::FrictionMode::Associative,
        ..analysis::Options::default()
    };
    // A hidden bar (stderr not a terminal) is not ticked: every case would touch its shared
    // counter.
    let tick = || bar.inc(1);
    let progress: &(dyn Fn() + Sync) = if bar.is_hidden() { &|| {} } else { &tick };
    let rows = plan.run(&options, args.run_dem, progress);
    bar.finish_and_clear();
    if let Some(x) = &x {
        draw(args.svg.as_deref(), || {
            report::figures::sweep(&scene, &plan, &rows, x, args.series.as_deref())
        })?;
    }
    let mut buf = Vec::new();
    sweep::write_csv(&mut buf, variations, &rows).map_err(|e| Error::Output {
        path: args.csv.clone().unwrap_or_else(|| "stdout".into()),
        message: e.to_string(),
    })?;
    let (count, failed) = (
        rows.len(),
        rows.iter().filter(|r| r.status == "error").count(),
    );
    sweep::free_rows(rows);
    match &args.csv {
        Some(path) => {
            write_atomically(path, |b| {
                *b = buf;
                Ok(())
            })?;
            Ok(format!(
                "{} cases written to {}{}",
                count,
                path.display(),
                if failed > 0 {
                    format!(" ({failed} with status error)")
                } else {
                    String::new()
                }
            ))
        }
        // The CSV is UTF-8 (the keys, values and messages are Rust strings): no copy.
        None => Ok(String::from_utf8(buf)
            .unwrap_or_else(|e| String::from_utf8_lossy(e.as_bytes()).into_owned())),
    }
}
