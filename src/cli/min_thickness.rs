//! `voussoir min-thickness`: the thinnest ring that stands under its permanent loads.

use super::{json, write_svg, Format, SceneArgs};
use voussoir::analysis;
use voussoir::drawing::svg::Drawing;
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
    };
    let t = thickness::analyse(&scene, &options)?;
    let m = &t.lower;
    if let Some(path) = &args.svg {
        match (&m.at_minimum, m.search.min_thickness) {
            (Some((at, stand)), Some(t)) => {
                let drawing = Drawing {
                    title: format!(
                        "{} at its minimum thickness t_min = {t:.6} m\nthrust line under the permanent loads (lambda = 0), {} hinges",
                        report::shape_title(&scene),
                        stand.hinges.len()
                    ),
                    forces: Some(&stand.forces),
                    hinges: &stand.hinges,
                    loads: Some(&at.loads),
                    ..Default::default()
                };
                write_svg(path, &at.assembly, &drawing)?;
            }
            _ => eprintln!(
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
    let rep = report::MinThicknessReport::new(&scene, &model, &t);
    Ok(if args.json {
        json(&rep)
    } else {
        report::min_thickness_summary(&scene, &model, m, &rep)
    })
}
