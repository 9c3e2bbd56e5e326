//! `voussoir min-thickness`: the thinnest ring that stands under its permanent loads.

use super::{write_figure, Format, SceneArgs};
use voussoir::analysis;
use voussoir::error::Error;
use voussoir::report;
use voussoir::statics::StaticSettings;
use voussoir::thickness;

#[derive(clap::Args)]
pub struct Args {
    #[command(flatten)]
    scene: SceneArgs,
    /// Print one JSON object instead of the summary
    #[arg(long)]
    json: bool,
    /// Draw the thrust line at the minimum thickness to this SVG file
    #[arg(long, value_name = "FILE")]
    svg: Option<std::path::PathBuf>,
    /// Also find the continuous model's minimum thickness
    #[arg(long)]
    continuous: bool,
    /// Largest chain (joints) for the exhaustive kinematic bisection; 0 turns it off
    #[arg(long, default_value_t = analysis::KINEMATIC_DEFAULT_MAX_JOINTS)]
    kinematic_max_joints: usize,
    /// The kinematic minimum thickness: the mechanism of the static hinges at t_min valued by
    /// virtual work (certified, falling back to the exhaustive bisection when it does not meet
    /// the static value) or the exhaustive bisection
    #[arg(long, value_enum, default_value = "certified")]
    kinematic: super::Kinematic,
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
    let model = voussoir::scene::build(&scene)?;
    let options = analysis::Options {
        static_settings: StaticSettings::default(),
        kinematic_max_joints: args.kinematic_max_joints,
        kinematic: args.kinematic.into(),
        continuous: args.continuous,
        friction: args.friction.into(),
        ..analysis::Options::default()
    };
    let t = thickness::analyse(&scene, &options)?;
    let m = &t.lower;
    let mut figure = None;
    if let Some(path) = &args.svg {
        match report::figures::min_thickness(&scene, m)
            .map_err(|e| super::figure_error(path)(e.into()))?
        {
            Some(drawn) => {
                write_figure(path, &drawn)?;
                figure = Some(drawn);
            }
            None => eprintln!(
                "note: no minimum thickness ({}): {} not written",
                match m.search.outcome {
                    thickness::ThicknessOutcome::NeverStands =>
                        "no thickness lets the structure stand",
                    _ => "the structure stands at every thickness",
                },
                path.display()
            ),
        }
    }
    let mut doc = report::documents::min_thickness(&scene, &model, &t);
    doc.figures.extend(figure);
    Ok(super::print(&doc, args.json))
}
