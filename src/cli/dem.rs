//! `voussoir dem`: the collapse multiplier bracketed by discrete-element runs.

use super::{json, progress_bar, write_svg, SceneArgs};
use voussoir::analysis::{self, DemOptions};
use voussoir::dem;
use voussoir::dem::record::{self, AccelUnit, Excitation, Pulse, PulseShape};
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
    /// rotation) to this CSV file
    #[arg(long, value_name = "FILE")]
    history: Option<std::path::PathBuf>,
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

fn excitation(args: &Args) -> Result<Option<Excitation>, Error> {
    let unit = match args.units {
        UnitsArg::G => AccelUnit::G,
        UnitsArg::Ms2 => AccelUnit::MetersPerSecondSquared,
        UnitsArg::Cms2 => AccelUnit::CentimetersPerSecondSquared,
    };
    let bad = |e: record::RecordError| {
        Error::Analysis(voussoir::error::AnalysisError::Other(e.to_string()))
    };
    let motion = if let Some(path) = &args.record {
        Excitation::Record(record::read(path, unit, args.dt).map_err(bad)?)
    } else if let (Some(shape), Some(a), Some(t)) = (args.pulse, args.amplitude, args.period) {
        let shape = match shape {
            PulseArg::Sine => PulseShape::Sine,
            PulseArg::Rect => PulseShape::Rect,
        };
        Excitation::Pulse(Pulse::new(shape, a * unit.factor(), t).map_err(bad)?)
    } else {
        return Ok(None);
    };
    if !(args.scale.is_finite() && args.scale >= 0.0) {
        return Err(bad(record::RecordError::Pulse(format!(
            "--scale {}: must be a finite number >= 0",
            args.scale
        ))));
    }
    Ok(Some(motion.scaled(args.scale)))
}

fn run_dynamic(
    args: &Args,
    scene: &voussoir::scene::Scene,
    motion: &Excitation,
) -> Result<String, Error> {
    let settings = dem::dynamic::DynamicSettings::default();
    if args.ida {
        let (model, r) = analysis::dem_ida(scene, motion, &settings, args.tolerance)?;
        let rep = report::IdaReport::new(motion, &r);
        return Ok(if args.json {
            json(&rep)
        } else {
            report::ida_summary(scene, &model, &rep)
        });
    }
    let d = analysis::dem_dynamic(scene, motion, &settings)?;
    if let Some(path) = &args.history {
        let err = |e: &dyn std::fmt::Display| Error::Output {
            path: path.clone(),
            message: e.to_string(),
        };
        let mut w = csv::Writer::from_path(path).map_err(|e| err(&e))?;
        w.write_record([
            "time_s",
            "ground_acceleration_m_s2",
            "displacement_m",
            "rotation_rad",
        ])
        .map_err(|e| err(&e))?;
        for h in &d.result.history {
            w.write_record([
                format!("{:.6}", h.time),
                format!("{:.6e}", h.ground_acceleration),
                format!("{:.9e}", h.displacement),
                format!("{:.9e}", h.rotation),
            ])
            .map_err(|e| err(&e))?;
        }
        w.flush().map_err(|e| err(&e))?;
    }
    let rep = report::DynamicReport::new(scene, &d);
    Ok(if args.json {
        json(&rep)
    } else {
        report::dynamic_summary(scene, &d.model, &rep)
    })
}

pub fn run(args: Args) -> Result<String, Error> {
    let scene = args.scene.load()?;
    if let Some(motion) = excitation(&args)? {
        super::check_output_paths([args.history.as_ref()])?;
        return run_dynamic(&args, &scene, &motion);
    }
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
