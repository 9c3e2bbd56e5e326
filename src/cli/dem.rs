//! `voussoir dem`: the collapse multiplier bracketed by discrete-element runs.

use super::{draw, progress_bar, write_text, Format, SceneArgs};
use voussoir::analysis::{self, DemOptions};
use voussoir::dem;
use voussoir::dem::record::{
    self, AccelUnit, Component, Excitation, GroundInput, Pulse, PulseShape, RecordError,
};
use voussoir::error::{AnalysisError, Error};
use voussoir::report;

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
    /// Run the blocks under this ground-acceleration record instead of bracketing lambda:
    /// PEER NGA .AT2 (in g), or one/two-column text or CSV in --units
    #[arg(long, value_name = "FILE", conflicts_with = "pulse")]
    record: Option<std::path::PathBuf>,
    /// Run the blocks under an analytic pulse: one sine cycle or a rectangular pulse of
    /// --amplitude (in --units) and --period (s)
    #[arg(long, value_enum, requires_all = ["amplitude", "period"])]
    pulse: Option<PulseArg>,
    /// Pulse amplitude, in --units
    #[arg(long)]
    amplitude: Option<f64>,
    /// Pulse period (sine) or duration (rect), s
    #[arg(long)]
    period: Option<f64>,
    /// Unit of the accelerations of a text record and of --amplitude (AT2 files are in g)
    #[arg(long, value_enum, default_value = "g")]
    units: UnitsArg,
    /// Time step (s) of a one-column text record
    #[arg(long)]
    dt: Option<f64>,
    /// Multiply the ground motion by this factor
    #[arg(long, default_value_t = 1.0)]
    scale: f64,
    /// Scale the ground motion up until collapse (incremental dynamic analysis) to
    /// --tolerance, and report the collapse scale and PGA
    #[arg(long)]
    ida: bool,
    /// Write the control block's time history (time, ground acceleration, displacement,
    /// rotation, vertical ground acceleration) to this CSV file
    #[arg(long, value_name = "FILE")]
    history: Option<std::path::PathBuf>,
    /// Direction the --record or --pulse motion acts in: x (horizontal, toward +x for a
    /// positive acceleration) or y (vertical, upward)
    #[arg(long, value_enum, default_value = "x", conflicts_with = "pulse_curve")]
    component: ComponentArg,
    /// A vertical ground-acceleration record acting together with the horizontal --record or
    /// --pulse (upward positive; same --units, --dt and --scale)
    #[arg(long, value_name = "FILE", conflicts_with = "pulse_curve")]
    record_vertical: Option<std::path::PathBuf>,
    /// Free motion after the ground stops (s), so a block still moving can come back or fall
    #[arg(long, default_value_t = 2.0)]
    tail: f64,
    /// Write an animation of the blocks under the ground motion, with the ground acceleration
    /// plotted under them, to this self-contained HTML page
    #[arg(long, value_name = "FILE.html", conflicts_with = "ida")]
    animation: Option<std::path::PathBuf>,
    /// Find the minimum collapse amplitude of sine and rectangular pulses against their
    /// period (to --tolerance) and draw it to this SVG file (the numbers go to the CSV file
    /// of the same name)
    #[arg(long, value_name = "FILE.svg", conflicts_with_all = ["record", "pulse", "ida", "animation"])]
    pulse_curve: Option<std::path::PathBuf>,
    /// Pulse periods (s) of --pulse-curve, comma-separated [default: 0.1,0.15,0.25,0.4,0.6,1,1.5,2.5]
    #[arg(long, value_delimiter = ',', requires = "pulse_curve")]
    periods: Vec<f64>,
    /// Pulse shapes of --pulse-curve (horizontal pulses) [default: sine,rect]
    #[arg(long, value_enum, value_delimiter = ',', requires = "pulse_curve")]
    shapes: Vec<PulseArg>,
    /// The most time steps one run may take (its longest length over the time step); a run
    /// planning more is refused before it starts [default: 50000000]
    #[arg(long, value_name = "N")]
    max_steps: Option<u64>,
    /// When a dynamic run (--record, --pulse, --ida, --pulse-curve) has collapsed:
    /// displacement (a block point moved by a quarter of the structure's size) or overturning
    /// (it fell: run on until at rest or fallen) [default: displacement]
    #[arg(long, value_enum)]
    criterion: Option<CriterionArg>,
    /// The rest test of a dynamic run (--record, --pulse, --ida): on skips the time
    /// integration while the ground acceleration stays below the static multiplier's
    /// threshold (rigid blocks stay at rest there; docs/dem.md), off integrates from the
    /// start and shows the contacts' elastic micro-motion [default: on]
    #[arg(long, value_enum, conflicts_with = "pulse_curve")]
    rest_test: Option<RestTestArg>,
}

#[derive(Clone, Copy, clap::ValueEnum)]
enum RestTestArg {
    On,
    Off,
}

#[derive(Clone, Copy, clap::ValueEnum)]
enum CriterionArg {
    /// A block point moved by a quarter of the structure's size
    Displacement,
    /// Loss of stability: at rest (survives) or fallen (a block point moved by the size)
    Overturning,
}

#[derive(Clone, Copy, clap::ValueEnum)]
enum ComponentArg {
    /// Horizontal
    X,
    /// Vertical
    Y,
}

#[derive(Clone, Copy, clap::ValueEnum)]
enum PulseArg {
    Sine,
    Rect,
}

#[derive(Clone, Copy, clap::ValueEnum)]
enum UnitsArg {
    /// Multiples of g = 9.80665 m/s^2
    G,
    /// m/s^2
    #[value(name = "m/s2")]
    Ms2,
    /// cm/s^2
    #[value(name = "cm/s2")]
    Cms2,
}

fn shape(p: PulseArg) -> PulseShape {
    match p {
        PulseArg::Sine => PulseShape::Sine,
        PulseArg::Rect => PulseShape::Rect,
    }
}

fn excitation(args: &Args) -> Result<Option<GroundInput>, Error> {
    let unit = match args.units {
        UnitsArg::G => AccelUnit::G,
        UnitsArg::Ms2 => AccelUnit::MetersPerSecondSquared,
        UnitsArg::Cms2 => AccelUnit::CentimetersPerSecondSquared,
    };
    let bad = |e: RecordError| Error::Analysis(AnalysisError::Record(e));
    let motion = if let Some(path) = &args.record {
        Excitation::Record(record::read(path, unit, args.dt).map_err(bad)?)
    } else if let (Some(p), Some(a), Some(t)) = (args.pulse, args.amplitude, args.period) {
        Excitation::Pulse(Pulse::new(shape(p), a * unit.factor(), t).map_err(bad)?)
    } else {
        if let Some(path) = &args.record_vertical {
            return Err(bad(RecordError::Flag {
                flag: "--record-vertical".to_string(),
                value: path.display().to_string(),
                message: "acts together with a horizontal --record or --pulse: give one"
                    .to_string(),
            }));
        }
        return Ok(None);
    };
    if !(args.scale.is_finite() && args.scale >= 0.0) {
        return Err(bad(RecordError::Flag {
            flag: "--scale".to_string(),
            value: args.scale.to_string(),
            message: "must be a finite number >= 0".to_string(),
        }));
    }
    let vertical = match &args.record_vertical {
        Some(path) => Some(Excitation::Record(
            record::read(path, unit, args.dt).map_err(bad)?,
        )),
        None => None,
    };
    let component = match args.component {
        ComponentArg::X => Component::X,
        ComponentArg::Y => Component::Y,
    };
    let ground = GroundInput::new(motion, component, vertical)
        .map_err(bad)?
        .scaled(args.scale);
    // The readers refuse samples beyond 100 g; a scale must not bring them back (1e300 only
    // made the blocks' positions overflow, reported as a divergence of the integration).
    let (h, v) = ground.pga_xy();
    let limit = record::MAX_ACCELERATION_G * record::STANDARD_GRAVITY;
    if h.max(v) > limit {
        return Err(bad(RecordError::Flag {
            flag: "--scale".to_string(),
            value: dem::show_value(args.scale),
            message: format!(
                "the scaled motion peaks at {:.4e} g, beyond the {} g any ground motion stays within",
                h.max(v) / record::STANDARD_GRAVITY,
                record::MAX_ACCELERATION_G
            ),
        }));
    }
    Ok(Some(ground))
}

fn settings(args: &Args) -> Result<dem::dynamic::DynamicSettings, Error> {
    if !(args.tail.is_finite() && args.tail >= 0.0) {
        return Err(Error::Analysis(AnalysisError::Record(RecordError::Flag {
            flag: "--tail".to_string(),
            value: args.tail.to_string(),
            message: "must be a finite number of seconds >= 0".to_string(),
        })));
    }
    Ok(dem::dynamic::DynamicSettings {
        tail: args.tail,
        criterion: match args.criterion {
            None | Some(CriterionArg::Displacement) => dem::dynamic::Criterion::Displacement,
            Some(CriterionArg::Overturning) => dem::dynamic::Criterion::Overturning,
        },
        max_steps: args.max_steps,
        rest_test: !matches!(args.rest_test, Some(RestTestArg::Off)),
        ..Default::default()
    })
}

/// The most frames an animation holds (25 per second of simulated time up to this; at least
/// `report::animation::MIN_FRAMES` over a short run).
const MAX_FRAMES: usize = 1500;

fn run_pulse_curve(
    args: &Args,
    scene: &voussoir::scene::Scene,
    path: &std::path::Path,
) -> Result<String, Error> {
    let pulses: &[PulseArg] = if args.shapes.is_empty() {
        &[PulseArg::Sine, PulseArg::Rect]
    } else {
        &args.shapes
    };
    let periods: &[f64] = if args.periods.is_empty() {
        analysis::PULSE_CURVE_PERIODS
    } else {
        &args.periods
    };
    let shapes: Vec<PulseShape> = pulses.iter().map(|&p| shape(p)).collect();
    let total = shapes.len() * periods.len();
    let bar = progress_bar(total as u64, "pulse curve");
    let curve = analysis::dem_pulse_curve(
        scene,
        &shapes,
        periods,
        &settings(args)?,
        args.tolerance,
        &mut |f| bar.set_position((f * total as f64).round() as u64),
    )?;
    bar.finish_and_clear();
    let rep = report::PulseCurveReport::new(&curve);
    let csv_path = path.with_extension("csv");
    // Written whole through a temporary, as every output (super::write_atomically).
    super::write_atomically(&csv_path, |buf| {
        report::csv::write_pulse_curve_csv(buf, &rep).map_err(|e| e.to_string())
    })?;
    let names: Vec<&str> = pulses
        .iter()
        .map(|&p| match p {
            PulseArg::Sine => "sine",
            PulseArg::Rect => "rect",
        })
        .collect();
    let figure = draw(Some(path), || {
        report::figures::pulse_curve(scene, &rep, &names)
    })?;
    let mut doc = report::documents::pulse_curve(scene, &curve.model, rep);
    doc.figures.extend(figure);
    Ok(super::print(&doc, args.json))
}

fn run_dynamic(
    args: &Args,
    scene: &voussoir::scene::Scene,
    motion: &GroundInput,
) -> Result<String, Error> {
    let mut settings = settings(args)?;
    if args.ida {
        let (model, r) = analysis::dem_ida(scene, motion, &settings, args.tolerance)?;
        let rep = report::IdaReport::new(motion, &r, args.tolerance);
        return Ok(super::print(
            &report::documents::ida(scene, &model, rep),
            args.json,
        ));
    }
    if args.animation.is_some() {
        settings.frames_every = Some(report::animation::frame_interval(
            motion.duration() + settings.tail,
            MAX_FRAMES,
        ));
    }
    let d = analysis::dem_dynamic(scene, motion, &settings)?;
    if let Some(path) = &args.history {
        super::write_atomically(path, |buf| {
            report::csv::write_history_csv(buf, &d.result.history).map_err(|e| e.to_string())
        })?;
    }
    let rep = report::DynamicReport::new(scene, &d);
    if let Some(path) = &args.animation {
        let title = format!("{} — {}", scene.origin, report::dynamic_headline(&rep));
        let page = report::animation::html(&d, &title).ok_or_else(|| Error::Output {
            path: path.clone(),
            message:
                "the structure does not stand under its permanent loads: nothing moves to animate"
                    .to_string(),
        })?;
        write_text(path, &page)?;
    }
    Ok(super::print(
        &report::documents::dynamic(scene, &d.model, rep),
        args.json,
    ))
}

/// Let Ctrl-C stop a DEM run cleanly: the first sets the DEM's interrupt flag (the running
/// search stops at its next check and reports the interruption), a second one exits at once
/// (for work that does not check the flag, such as a static solve). Without a handler (it
/// cannot be installed) Ctrl-C keeps its default, which ends the process.
fn stop_on_ctrl_c() {
    let _ = ctrlc::set_handler(|| {
        if dem::interrupt_requested() {
            std::process::exit(130);
        }
        dem::request_interrupt();
    });
}

/// Say on stderr, before anything runs, the time step and the most steps a run may take, and
/// refuse a run planning more than `--max-steps` (`motion`: seconds of ground motion and tail).
fn state_plan(
    args: &Args,
    scene: &voussoir::scene::Scene,
    motion: Option<f64>,
) -> Result<(), Error> {
    let (dt, steps, integrator) = analysis::dem_plan(scene, motion, args.max_steps)?;
    eprintln!(
        "dem: {} time stepping (dem.integrator), time step {dt:.3e} s, at most {steps} time steps a run (limit {}; --max-steps lifts it); Ctrl-C stops",
        integrator.name(),
        args.max_steps.unwrap_or(dem::DEFAULT_MAX_STEPS)
    );
    Ok(())
}

pub fn run(args: Args) -> Result<String, Error> {
    stop_on_ctrl_c();
    let scene = args.scene.load()?;
    // Every file this run reads and writes, checked at once before any work: no output on an
    // input (the scene, its blocks, a record) or on another output, each named for its format.
    let mut outputs = args.scene.outputs(&scene);
    for (what, path) in [
        ("the record", &args.record),
        ("the vertical record", &args.record_vertical),
    ] {
        if let Some(path) = path {
            outputs = outputs.input(path, what);
        }
    }
    let curve_csv = args.pulse_curve.as_ref().map(|p| p.with_extension("csv"));
    outputs
        .output("--svg", args.svg.as_deref(), Format::Svg)
        .output("--history", args.history.as_deref(), Format::Csv)
        .output("--animation", args.animation.as_deref(), Format::Html)
        .output("--pulse-curve", args.pulse_curve.as_deref(), Format::Svg)
        .output("the pulse curve's CSV", curve_csv.as_deref(), Format::Csv)
        .check()?;
    // clap lets `--periods` through beside `--pulse` (which excludes `--pulse-curve`): a
    // curve's option without the curve would be ignored, so it is refused.
    if args.pulse_curve.is_none() && !(args.periods.is_empty() && args.shapes.is_empty()) {
        return Err(Error::Scene(voussoir::error::SceneError::Usage(
            "--periods and --shapes set the pulses of --pulse-curve FILE.svg; without it they would be ignored".into(),
        )));
    }
    if let Some(path) = &args.pulse_curve {
        let periods: &[f64] = if args.periods.is_empty() {
            analysis::PULSE_CURVE_PERIODS
        } else {
            &args.periods
        };
        let longest = periods.iter().fold(0.0_f64, |m, t| m.max(*t));
        state_plan(&args, &scene, Some(longest + args.tail.max(0.0)))?;
        return run_pulse_curve(&args, &scene, path);
    }
    if let Some(path) = args.animation.as_ref().filter(|p| {
        !p.extension()
            .and_then(|e| e.to_str())
            .is_some_and(|e| e.eq_ignore_ascii_case("html") || e.eq_ignore_ascii_case("htm"))
    }) {
        return Err(Error::Analysis(AnalysisError::Record(RecordError::Flag {
            flag: "--animation".to_string(),
            value: path.display().to_string(),
            message: "the animation is an HTML page: name the file .html".to_string(),
        })));
    }
    if let Some(motion) = excitation(&args)? {
        state_plan(&args, &scene, Some(motion.duration() + args.tail.max(0.0)))?;
        return run_dynamic(&args, &scene, &motion);
    }
    if args.criterion.is_some() {
        // The collapse search has its own test (the displacement `dem.collapse_displacement`
        // at a constant lambda): a dynamic criterion there would be ignored.
        return Err(Error::Scene(voussoir::error::SceneError::Usage(
            "--criterion decides when a dynamic run (--record, --pulse, --ida, --pulse-curve) has collapsed; the lambda search does not use it".into(),
        )));
    }
    if args.rest_test.is_some() {
        return Err(Error::Scene(voussoir::error::SceneError::Usage(
            "--rest-test decides whether a dynamic run (--record, --pulse, --ida) waits while the ground stays below the static threshold; the lambda search does not use it".into(),
        )));
    }
    if args.animation.is_some() {
        return Err(Error::Analysis(AnalysisError::Record(RecordError::Flag {
            flag: "--animation".to_string(),
            value: args
                .animation
                .as_ref()
                .map_or(String::new(), |p| p.display().to_string()),
            message: "animates a dynamic run: give a --record or a --pulse".to_string(),
        })));
    }
    state_plan(&args, &scene, None)?;
    let options = DemOptions {
        tolerance: args.tolerance,
        snapshots: args.snapshots.is_some() || args.svg.is_some(),
        from_static: args.from_static,
        max_steps: args.max_steps,
    };
    let bar = progress_bar(1000, "dem");
    let d = analysis::dem(&scene, &options, &mut |f| {
        bar.set_position((f.clamp(0.0, 1.0) * 1000.0) as u64)
    })?;
    bar.finish_and_clear();
    if let Some(dir) = &args.snapshots {
        dem::write_snapshots(dir, &d.result).map_err(|e| Error::Output {
            path: dir.clone(),
            message: e.to_string(),
        })?;
    }
    let rep = report::DemReport::of(&scene, &d);
    let figure = draw(args.svg.as_deref(), || {
        report::figures::dem(&scene, &d, &rep)
    })?;
    let mut doc = report::documents::dem(&scene, &d.model, rep);
    doc.figures.extend(figure);
    Ok(super::print(&doc, args.json))
}
