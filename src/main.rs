//! The `voussoir` command line: parses arguments, calls the library, prints.

use clap::{Parser, Subcommand, ValueEnum};
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use voussoir::analysis;
use voussoir::assembly::Assembly;
use voussoir::dem;
use voussoir::error::Error;
use voussoir::lp::{Direction, StaticSettings};
use voussoir::report;
use voussoir::scene::Scene;
use voussoir::sweep;
use voussoir::thickness;
use voussoir::thrustline::svg::{self, Drawing, Mechanism};

#[derive(Parser)]
#[command(
    name = "voussoir",
    version,
    about = "Seismic collapse multiplier of masonry arches and portals",
    long_about = "voussoir computes how much horizontal ground acceleration (lambda * g) a masonry \
arch or portal of rigid voussoirs with no-tension joints can take before it becomes a mechanism."
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Clone, Copy, ValueEnum)]
enum Dir {
    Right,
    Left,
}

#[derive(clap::Args)]
struct SceneArgs {
    /// Scene file (TOML, see README)
    scene: PathBuf,
    /// Override a scene value, e.g. --set arch.thickness=0.2 (repeatable)
    #[arg(long = "set", value_name = "KEY=VALUE")]
    set: Vec<String>,
}

#[derive(Subcommand)]
enum Command {
    /// Collapse multiplier of a scene: static lower bound, kinematic upper bound, mechanism
    Analyze {
        #[command(flatten)]
        scene: SceneArgs,
        /// Print one JSON object instead of the summary
        #[arg(long)]
        json: bool,
        /// Write the thrust line (one row per joint) to this CSV file
        #[arg(long, value_name = "FILE")]
        thrust_csv: Option<PathBuf>,
        /// Draw the blocks, thrust line, hinges and mechanism to this SVG file
        #[arg(long, value_name = "FILE")]
        svg: Option<PathBuf>,
        /// Direction of the horizontal acceleration
        #[arg(long, value_enum, default_value = "right")]
        direction: Dir,
        /// Conic solver tolerance (gap and feasibility, dimensionless; 1e-14..1e-6). Looser
        /// tolerances would let lambda exceed the true multiplier
        #[arg(long, default_value_t = 1e-10)]
        tolerance: f64,
        /// Also run the continuous model (hinges anywhere: the limit of infinitely many voussoirs)
        #[arg(long)]
        continuous: bool,
        /// Largest chain (joints) for the exhaustive kinematic search (above it, a local search
        /// around the static hinges); 0 turns the kinematic analysis off
        #[arg(long, default_value_t = analysis::KINEMATIC_DEFAULT_MAX_JOINTS)]
        kinematic_max_joints: usize,
    },
    /// Parametric sweep: the cartesian product of varied keys, solved in parallel
    Sweep {
        #[command(flatten)]
        scene: SceneArgs,
        /// KEY=V1,V2,... or KEY=START:STOP:STEP; KEY is a scene key (arch.thickness) or a
        /// ratio (t/R, e/R, h/R, b/R, t/span, rise/span). Repeatable.
        #[arg(long, value_name = "KEY=VALUES", required = true)]
        vary: Vec<String>,
        /// Write the rows to this CSV file (default: standard output)
        #[arg(long, value_name = "FILE")]
        csv: Option<PathBuf>,
        /// Draw lambda against --x to this SVG file, one line per value of the other keys
        #[arg(long, value_name = "FILE", requires = "x")]
        svg: Option<PathBuf>,
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
    },
    /// Check the collapse multiplier with the discrete element method (rigid blocks in time)
    Dem {
        #[command(flatten)]
        scene: SceneArgs,
        /// Print one JSON object instead of the summary
        #[arg(long)]
        json: bool,
        /// Relative width of the final bracket [lambda_stands, lambda_collapses]
        #[arg(long, default_value_t = 0.01)]
        tolerance: f64,
        /// Write block positions during the runs (CSV) into this directory
        #[arg(long, value_name = "DIR")]
        snapshots: Option<PathBuf>,
        /// Draw the initial and final block positions of the collapsing run to this SVG file
        #[arg(long, value_name = "FILE")]
        svg: Option<PathBuf>,
    },
    /// Run a parametric study file (data/studies/*.toml): writes OUT/<output>.csv and .svg
    Study {
        /// Study file (TOML: title, output, vary, x, series, y, baseline, continuous, [scene.*])
        study: PathBuf,
        /// Directory for the CSV and SVG
        #[arg(long, value_name = "DIR", default_value = "docs/figures")]
        out: PathBuf,
        /// Thin every range to 3 values (a quick check of the study)
        #[arg(long)]
        reduced: bool,
    },
    /// Smallest arch thickness that stands under its own weight
    MinThickness {
        #[command(flatten)]
        scene: SceneArgs,
        /// Print one JSON object instead of the summary
        #[arg(long)]
        json: bool,
        /// Draw the thrust line at the minimum thickness to this SVG file
        #[arg(long, value_name = "FILE")]
        svg: Option<PathBuf>,
        /// Also find the continuous model's minimum thickness
        #[arg(long)]
        continuous: bool,
        /// Largest chain (joints) for the kinematic bisection; 0 turns it off
        #[arg(long, default_value_t = analysis::KINEMATIC_DEFAULT_MAX_JOINTS)]
        kinematic_max_joints: usize,
    },
    /// Speed against accuracy: refine the voussoir count, vary Clarabel's tolerance and the
    /// DEM's time step, stiffness and bracket tolerance; errors against the continuous model
    Convergence {
        #[command(flatten)]
        scene: SceneArgs,
        /// Print one JSON object instead of the tables
        #[arg(long)]
        json: bool,
        /// Write the refinement table (one row per voussoir count) to this CSV file
        #[arg(long, value_name = "FILE")]
        csv: Option<PathBuf>,
        /// Draw log10 of the relative error against log10 n to this SVG file
        #[arg(long, value_name = "FILE")]
        svg: Option<PathBuf>,
        /// Largest voussoir count of the refinement (counts double from 8)
        #[arg(long, default_value_t = 1024)]
        max_voussoirs: usize,
        /// Largest chain (joints) for the exhaustive kinematic search; 0 turns it off
        #[arg(long, default_value_t = analysis::KINEMATIC_DEFAULT_MAX_JOINTS)]
        kinematic_max_joints: usize,
        /// Skip the DEM study (a few seconds on a 16-voussoir copy of the scene)
        #[arg(long)]
        no_dem: bool,
    },
}

fn load(args: &SceneArgs) -> Result<Scene, Error> {
    let scene = Scene::from_file(&args.scene)?;
    if args.set.is_empty() {
        return Ok(scene);
    }
    Ok(scene.with_overrides(&args.set)?)
}

/// Write a file whole or not at all: to a temporary sibling, then rename.
fn write_atomically(
    path: &Path,
    write: impl FnOnce(&mut Vec<u8>) -> Result<(), String>,
) -> Result<(), Error> {
    let mut buf = Vec::new();
    write(&mut buf).map_err(|message| Error::Output {
        path: path.to_path_buf(),
        message,
    })?;
    let tmp = path.with_extension("voussoir-tmp");
    std::fs::write(&tmp, &buf)
        .and_then(|_| std::fs::rename(&tmp, path))
        .map_err(|e| {
            let _ = std::fs::remove_file(&tmp);
            Error::Output {
                path: path.to_path_buf(),
                message: e.to_string(),
            }
        })
}

/// Write text to a file whole or not at all.
fn write_text(path: &Path, text: &str) -> Result<(), Error> {
    write_atomically(path, |b| {
        b.extend_from_slice(text.as_bytes());
        Ok(())
    })
}

/// Draw a chart to an SVG file.
fn write_chart(path: &Path, chart: &voussoir::thrustline::chart::Chart) -> Result<(), Error> {
    let text = voussoir::thrustline::chart::chart_svg(chart).map_err(|e| Error::Output {
        path: path.to_path_buf(),
        message: e.to_string(),
    })?;
    write_text(path, &text)
}

fn write_svg(path: &Path, assembly: &Assembly, drawing: &Drawing) -> Result<(), Error> {
    let text = svg::structure_svg(assembly, drawing).map_err(|e| Error::Output {
        path: path.to_path_buf(),
        message: e.to_string(),
    })?;
    write_text(path, &text)
}

fn json<T: serde::Serialize>(value: &T) -> String {
    serde_json::to_string_pretty(value).unwrap_or_else(|e| format!("{{\"error\": \"{e}\"}}"))
}

fn run(cli: Cli) -> Result<String, Error> {
    match cli.command {
        Command::Analyze {
            scene,
            json: as_json,
            thrust_csv,
            svg,
            direction,
            tolerance,
            continuous,
            kinematic_max_joints,
        } => {
            let scene = load(&scene)?;
            if !(tolerance.is_finite() && (1e-14..=1e-6).contains(&tolerance)) {
                return Err(Error::Analysis(voussoir::error::AnalysisError::Other(
                    format!("--tolerance {tolerance}: must be from 1e-14 to 1e-6 (looser solutions are not safe: lambda may exceed the collapse multiplier)"),
                )));
            }
            let settings = StaticSettings::default()
                .direction(match direction {
                    Dir::Right => Direction::Right,
                    Dir::Left => Direction::Left,
                })
                .tolerance(tolerance);
            let options = analysis::Options {
                static_settings: settings,
                kinematic_max_joints,
                continuous,
            };
            let a = analysis::analyse(&scene, &options)?;
            let (assembly, result) = (&a.model.assembly, &a.lower);
            let mut notes = String::new();
            if let Some(path) = thrust_csv {
                if result.forces.is_some() {
                    write_atomically(&path, |buf| {
                        report::write_thrust_csv(buf, assembly, result).map_err(|e| e.to_string())
                    })?;
                } else {
                    notes.push_str(&format!(
                        "note: no thrust line at collapse ({}): {} not written\n",
                        result.status.as_str(),
                        path.display()
                    ));
                }
            }
            if let Some(path) = svg {
                let title = report::drawing_title(&scene, result.lambda, a.lambda_upper());
                let drawing = Drawing {
                    title,
                    forces: result.forces.as_deref(),
                    hinges: &result.hinges,
                    sliding: &result.sliding,
                    mechanism: (!result.mechanism.is_empty()).then_some(Mechanism {
                        velocities: &result.mechanism,
                        amplification: None,
                    }),
                    load: Some(options.direction()),
                    ..Default::default()
                };
                write_svg(&path, assembly, &drawing)?;
            }
            if !notes.is_empty() {
                eprint!("{notes}");
            }
            Ok(if as_json {
                json(&report::AnalysisReport::new(&scene, &a))
            } else {
                report::analysis_summary(&scene, &a)
            })
        }
        Command::Sweep {
            scene,
            vary,
            csv,
            svg,
            x,
            series,
            continuous,
            run_dem,
            kinematic_max_joints,
        } => {
            let scene = load(&scene)?;
            let variations = vary
                .iter()
                .map(|v| sweep::parse_variation(v))
                .collect::<Result<Vec<_>, _>>()?;
            let chart_for = |rows: &[sweep::SweepRow]| -> Result<Option<voussoir::thrustline::chart::Chart>, Error> {
                match (&svg, &x) {
                    (Some(_), Some(x)) => Ok(Some(sweep::chart(
                        &variations,
                        rows,
                        x,
                        series.as_deref(),
                        &format!("{}: collapse multiplier against {x}", report::shape_title(&scene)),
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
                continuous,
                kinematic_max_joints,
                ..analysis::Options::default()
            };
            let rows = sweep::run(
                &cases,
                |values, s| sweep::case(values, s, &options, run_dem),
                &|| bar.inc(1),
            );
            bar.finish_and_clear();
            if let (Some(path), Some(chart)) = (&svg, chart_for(&rows)?) {
                write_chart(path, &chart)?;
            }
            let mut buf = Vec::new();
            sweep::write_csv(&mut buf, &variations, &rows).map_err(|e| Error::Output {
                path: csv.clone().unwrap_or_else(|| "stdout".into()),
                message: e.to_string(),
            })?;
            match csv {
                Some(path) => {
                    write_atomically(&path, |b| {
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
        Command::Dem {
            scene,
            json: as_json,
            tolerance,
            snapshots,
            svg,
        } => {
            let scene = load(&scene)?;
            let model = voussoir::model::build(&scene)?;
            let assembly = &model.assembly;
            let lower = voussoir::lp::analyse(&model, &StaticSettings::default())?;
            let mut params = dem::IntegrationParameters::from_scene(&scene, &assembly)?
                .initial_guess(lower.lambda.filter(|l| *l > 0.0));
            if (snapshots.is_some() || svg.is_some()) && params.snapshot_interval.is_none() {
                let every = params.ramp_time / 3.0;
                params = params.snapshot_interval(Some(every));
            }
            let bar = progress_bar(1000, "dem");
            let result = dem::collapse_multiplier(&model, &params, tolerance, &mut |f| {
                bar.set_position((f.clamp(0.0, 1.0) * 1000.0) as u64)
            })
            .map_err(|e| Error::Analysis(voussoir::error::AnalysisError::Other(e.to_string())))?;
            bar.finish_and_clear();
            if let Some(dir) = &snapshots {
                dem::write_snapshots(dir, &result).map_err(|e| Error::Output {
                    path: dir.clone(),
                    message: e.to_string(),
                })?;
            }
            let rep = report::DemReport::new(&scene, &model, &result, lower.lambda);
            if let Some(path) = svg {
                // Collapse is detected at a small displacement: amplify it so the mechanism
                // shows, and say so.
                let placed = result.final_placements(&assembly);
                let (moves, amp) = placed
                    .as_ref()
                    .map_or((Vec::new(), 1.0), |p| p.amplified(&assembly, 0.1));
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
                    title: format!(
                        "{}, t = {} m: DEM\nlambda_dem = {}  (static lambda_lower = {})",
                        report::shape_title(&scene),
                        scene.arch.thickness,
                        rep.lambda_dem.map_or("none".into(), |l| format!("{l:.4}")),
                        rep.lambda_lower
                            .map_or("none".into(), |l| format!("{l:.4}"))
                    ),
                    moved: (!moves.is_empty()).then_some(svg::Placements {
                        moves: &moves,
                        label,
                    }),
                    ..Default::default()
                };
                write_svg(&path, &assembly, &drawing)?;
            }
            Ok(if as_json {
                json(&rep)
            } else {
                report::dem_summary(&scene, &model, &rep)
            })
        }
        Command::Study {
            study,
            out,
            reduced,
        } => {
            let mut st = voussoir::study::Study::from_file(&study)?;
            if reduced {
                st = st.reduced(3);
            }
            let total: usize = st.variations.iter().map(|v| v.values.len()).product();
            let bar = progress_bar(total as u64, "study");
            let (rows, chart) = st.run(&|| bar.inc(1))?;
            bar.finish_and_clear();
            let mut buf = Vec::new();
            sweep::write_csv(&mut buf, &st.variations, &rows).map_err(|e| Error::Output {
                path: out.clone(),
                message: e.to_string(),
            })?;
            std::fs::create_dir_all(&out).map_err(|e| Error::Output {
                path: out.clone(),
                message: e.to_string(),
            })?;
            let csv_path = out.join(format!("{}.csv", st.output));
            let svg_path = out.join(format!("{}.svg", st.output));
            write_atomically(&csv_path, |b| {
                *b = buf;
                Ok(())
            })?;
            write_chart(&svg_path, &chart)?;
            let failed = rows.iter().filter(|r| r.status == "error").count();
            Ok(format!(
                "{}: {} cases{} -> {} and {}",
                st.title,
                rows.len(),
                if failed > 0 {
                    format!(" ({failed} invalid)")
                } else {
                    String::new()
                },
                csv_path.display(),
                svg_path.display()
            ))
        }
        Command::Convergence {
            scene,
            json: as_json,
            csv,
            svg,
            max_voussoirs,
            kinematic_max_joints,
            no_dem,
        } => {
            let scene = load(&scene)?;
            let settings = voussoir::convergence::ConvergenceSettings {
                max_voussoirs,
                kinematic_max_joints,
                dem: !no_dem,
                ..Default::default()
            };
            let bar = progress_bar(0, "convergence");
            let c = voussoir::convergence::run(&scene, &settings, &mut |what| {
                bar.set_prefix(format!("convergence: {what}"))
            })
            .map_err(|e| Error::Analysis(voussoir::error::AnalysisError::Other(e.to_string())))?;
            bar.finish_and_clear();
            if let Some(path) = &svg {
                let title = format!(
                    "{}: convergence with the number of voussoirs",
                    report::shape_title(&scene)
                );
                write_chart(path, &c.chart(&title))?;
            }
            if let Some(path) = &csv {
                write_atomically(path, |b| c.write_csv(b).map_err(|e| e.to_string()))?;
            }
            Ok(if as_json { json(&c) } else { c.summary() })
        }
        Command::MinThickness {
            scene,
            json: as_json,
            svg,
            continuous,
            kinematic_max_joints,
        } => {
            let scene = load(&scene)?;
            let model = voussoir::model::build(&scene)?;
            let t = thickness::analyse(
                &scene,
                &StaticSettings::default(),
                kinematic_max_joints,
                continuous,
            )?;
            let m = &t.lower;
            if let Some(path) = svg {
                match (&m.at_minimum, m.search.min_thickness) {
                    (Some((at, stand)), Some(t)) => {
                        let drawing = Drawing {
                            title: format!(
                                "{} at its minimum thickness t_min = {t:.6} m\nthrust line under self-weight (lambda = 0), {} hinges",
                                report::shape_title(&scene),
                                stand.hinges.len()
                            ),
                            forces: Some(&stand.forces),
                            hinges: &stand.hinges,
                            ..Default::default()
                        };
                        write_svg(&path, &at.assembly, &drawing)?;
                    }
                    _ => eprintln!(
                        "note: no minimum thickness ({:?}): {} not written",
                        m.search.outcome,
                        path.display()
                    ),
                }
            }
            let rep = report::MinThicknessReport::new(&scene, &model, &t);
            Ok(if as_json {
                json(&rep)
            } else {
                report::min_thickness_summary(&scene, &model, m, &rep)
            })
        }
    }
}

/// A progress bar on stderr when it is a terminal, hidden otherwise.
fn progress_bar(len: u64, what: &str) -> indicatif::ProgressBar {
    use std::io::IsTerminal;
    if !std::io::stderr().is_terminal() {
        return indicatif::ProgressBar::hidden();
    }
    let bar = indicatif::ProgressBar::new(len);
    if let Ok(style) = indicatif::ProgressStyle::with_template(
        "{prefix} [{elapsed_precise}] {wide_bar} {pos}/{len} ({eta} left)",
    ) {
        bar.set_style(style);
    }
    bar.set_prefix(what.to_string());
    bar
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    match run(cli) {
        Ok(out) => {
            use std::io::Write;
            // A closed pipe (`voussoir ... | head`) is not an error of ours.
            let mut stdout = std::io::stdout().lock();
            match writeln!(stdout, "{}", out.trim_end()).and_then(|_| stdout.flush()) {
                Err(e) if e.kind() != std::io::ErrorKind::BrokenPipe => {
                    eprintln!("error: cannot write to standard output: {e}");
                    ExitCode::FAILURE
                }
                _ => ExitCode::SUCCESS,
            }
        }
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::FAILURE
        }
    }
}
