//! `voussoir analyze`: the collapse multiplier of a scene by both bounds.

use super::{draw, write_atomically, Dir, Format, SceneArgs};
use voussoir::analysis;
use voussoir::error::Error;
use voussoir::report;
use voussoir::roll;
use voussoir::statics::StaticSettings;

#[derive(clap::Args)]
pub struct Args {
    #[command(flatten)]
    scene: SceneArgs,
    /// Print one JSON object instead of the summary
    #[arg(long)]
    json: bool,
    /// Write the thrust line (one row per joint) to this CSV file
    #[arg(long, value_name = "FILE")]
    thrust_csv: Option<std::path::PathBuf>,
    /// Draw the blocks, thrust line, hinges and mechanism to this SVG file
    #[arg(long, value_name = "FILE")]
    svg: Option<std::path::PathBuf>,
    /// Direction of the horizontal acceleration (default right; refused with a live action,
    /// which has none)
    #[arg(long, value_enum)]
    direction: Option<Dir>,
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
    /// The upper bound: the mechanism of the static hinges (certified, falling back to a
    /// search when it does not meet the static bound) or the exhaustive search
    #[arg(long, value_enum, default_value = "certified")]
    kinematic: super::Kinematic,
    /// Friction law of the multiplier: auto (the non-associative multiplier of real joints,
    /// which slide without opening, whenever joints slide in the static mechanism),
    /// associative (the static program's alone), non-associative (always)
    #[arg(long, value_enum, default_value = "auto")]
    friction: super::Friction,
    /// Also run the DEM (Coulomb contacts that slide without opening) and show where the
    /// associative, the non-associative and the DEM's multipliers sit
    #[arg(long)]
    dem: bool,
    /// Move a load along x and analyse the scene at each position: loads[K] (a point load
    /// standing on the top, or a line load by its from_x) or vehicles[K] (by its first axle);
    /// the summary, --json and --svg are then the analysis at the critical position
    #[arg(long, value_name = "TARGET", requires_all = ["from", "to", "step"])]
    roll: Option<String>,
    /// First position of --roll (m)
    #[arg(
        long,
        value_name = "X0",
        requires = "roll",
        allow_negative_numbers = true
    )]
    from: Option<f64>,
    /// Last position of --roll (m), included when reached
    #[arg(
        long,
        value_name = "X1",
        requires = "roll",
        allow_negative_numbers = true
    )]
    to: Option<f64>,
    /// Distance between positions of --roll (m)
    #[arg(long, value_name = "DX", requires = "roll")]
    step: Option<f64>,
    /// Draw the multiplier against the position of --roll to this SVG file
    #[arg(long, value_name = "FILE", requires = "roll")]
    roll_svg: Option<std::path::PathBuf>,
}

pub fn run(args: Args) -> Result<String, Error> {
    let scene = args.scene.load()?;
    args.scene
        .outputs(&scene)
        .output("--thrust-csv", args.thrust_csv.as_deref(), Format::Csv)
        .output("--svg", args.svg.as_deref(), Format::Svg)
        .output("--roll-svg", args.roll_svg.as_deref(), Format::Svg)
        .check()?;
    // The range of --tolerance is the library's to check (StaticSettings::validate), so
    // Python and the page's server refuse the same values.
    let tolerance = args.tolerance;
    let direction = analysis::direction_for(&scene, args.direction.map(Into::into))?;
    let options = analysis::Options {
        static_settings: StaticSettings::default()
            .direction(direction)
            .tolerance(tolerance),
        kinematic_max_joints: args.kinematic_max_joints,
        kinematic: args.kinematic.into(),
        continuous: args.continuous,
        friction: args.friction.into(),
        dem: args.dem,
    };
    let rolled = match &args.roll {
        Some(target) => {
            let spec = roll::RollSpec {
                target: target.parse()?,
                from: args.from.unwrap_or_default(),
                to: args.to.unwrap_or_default(),
                step: args.step.unwrap_or_default(),
                refine: true,
            };
            let r = roll::roll(&scene, &spec, &options)?;
            if r.critical.is_none() {
                let mut doc = report::documents::roll(&scene, &r);
                doc.figures.extend(draw(args.roll_svg.as_deref(), || {
                    report::figures::roll_chart(&scene, &r)
                })?);
                return Ok(super::print(&doc, args.json));
            }
            Some(r)
        }
        None => None,
    };
    // With --roll, everything below is the analysis at the critical position.
    let (scene, a) = match &rolled {
        Some(r) => {
            let c = r.critical.as_ref().expect("checked above");
            (c.scene.clone(), c.analysis.clone())
        }
        None => {
            let a = analysis::analyse(&scene, &options)?;
            (scene, a)
        }
    };
    let (assembly, result) = (&a.model.assembly, &a.lower);
    if let Some(path) = &args.thrust_csv {
        if result.forces.is_some() {
            write_atomically(path, |buf| {
                report::write_thrust_csv(buf, assembly, result).map_err(|e| e.to_string())
            })?;
        } else {
            eprintln!(
                "note: no thrust line at collapse ({}): {} not written",
                result.status.as_str(),
                path.display()
            );
        }
    }
    let figure = draw(args.svg.as_deref(), || {
        report::figures::analysis(&scene, &a, options.direction())
    })?;
    let mut doc = match &rolled {
        Some(r) => {
            let mut doc = report::documents::roll(&scene, r);
            doc.figures.extend(draw(args.roll_svg.as_deref(), || {
                report::figures::roll_chart(&scene, r)
            })?);
            doc
        }
        None => report::documents::analysis(&scene, &a),
    };
    doc.figures.extend(figure);
    Ok(super::print(&doc, args.json))
}
