//! `voussoir fragility`: the fragility curve of a scene with uncertain inputs
//! (docs/fragility.md).

use super::{draw, write_atomically, Format, SceneArgs};
use voussoir::analysis;
use voussoir::error::Error;
use voussoir::fragility::{self, Settings};
use voussoir::report;
use voussoir::statics::StaticSettings;

#[derive(clap::Args)]
pub struct Args {
    #[command(flatten)]
    scene: SceneArgs,
    /// Latin hypercube samples of the scene's [uncertain] inputs
    #[arg(long, value_name = "N", default_value_t = 100)]
    samples: usize,
    /// Seed of the samples (the same seed gives the same samples on every platform)
    #[arg(long, value_name = "S", default_value_t = 1)]
    seed: u64,
    /// The dynamic route: a directory of ground-motion records (.AT2, PEER NGA), each run in
    /// the DEM scaled to every --stripes PGA (multiple-stripe analysis); needs --stripes
    #[arg(long, value_name = "DIR", requires = "stripes")]
    records: Option<std::path::PathBuf>,
    /// The stripes of the dynamic route: peak ground accelerations in g, e.g.
    /// 0.05,0.1,0.2,0.3; needs --records
    #[arg(
        long,
        value_name = "PGA,...",
        value_delimiter = ',',
        requires = "records"
    )]
    stripes: Vec<f64>,
    /// Set a key of the scene's [site] table, e.g. --site ag=0.25 --site soil=B (repeatable);
    /// the capacity route searches ag with the others held
    #[arg(long = "site", value_name = "KEY=VALUE")]
    site: Vec<String>,
    /// Write the per-sample table (inputs, outcome, capacity) to this CSV file
    #[arg(long, value_name = "FILE")]
    csv: Option<std::path::PathBuf>,
    /// Draw the fitted curve over the samples' empirical fragility to this SVG file
    #[arg(long, value_name = "FILE")]
    svg: Option<std::path::PathBuf>,
    /// Print one JSON object instead of the summary
    #[arg(long)]
    json: bool,
    /// Conic solver tolerance (gap and feasibility, dimensionless; 1e-14..1e-6)
    #[arg(long, default_value_t = 1e-10)]
    tolerance: f64,
    /// Friction law of the multiplier (as assess): auto, associative, non-associative
    #[arg(long, value_enum, default_value = "auto")]
    friction: super::Friction,
}

pub fn run(args: Args) -> Result<String, Error> {
    let (scene, _) = args.scene.load_with_site(&args.site)?;
    args.scene
        .outputs(&scene)
        .output("--csv", args.csv.as_deref(), Format::Csv)
        .output("--svg", args.svg.as_deref(), Format::Svg)
        .check()?;
    let settings = Settings {
        samples: args.samples,
        seed: args.seed,
        options: analysis::Options {
            static_settings: StaticSettings::default().tolerance(args.tolerance),
            friction: args.friction.into(),
            ..analysis::Options::default()
        },
        ..Settings::default()
    };
    if let Some(dir) = &args.records {
        let records = fragility::read_records(dir)?;
        // Seconds a run and thousands of runs in a study: a progress bar on a terminal.
        let runs = fragility::dynamic_run_count(&scene, &settings, &records, &args.stripes)?;
        let bar = super::progress_bar(runs as u64, "DEM runs");
        let f = fragility::dynamic_route_with_progress(
            &scene,
            &settings,
            &records,
            &args.stripes,
            &voussoir::dem::dynamic::DynamicSettings::default(),
            &|| bar.inc(1),
        );
        bar.finish_and_clear();
        let f = f?;
        if let Some(path) = &args.csv {
            let table = report::fragility::dynamic_table(&f);
            write_atomically(path, |b| {
                report::csv::write_table(b, &table).map_err(|e| e.to_string())
            })?;
        }
        let figure = draw(args.svg.as_deref(), || {
            report::figures::dynamic_fragility(&scene, &f)
        })?;
        let mut doc = report::fragility::dynamic_document(&scene, &f);
        doc.figures.extend(figure);
        return Ok(super::print(&doc, args.json));
    }
    let f = fragility::capacity_route(&scene, &settings)?;
    if let Some(path) = &args.csv {
        let table = report::fragility::sample_table(&f);
        write_atomically(path, |b| {
            report::csv::write_table(b, &table).map_err(|e| e.to_string())
        })?;
    }
    let figure = draw(args.svg.as_deref(), || {
        report::figures::fragility(&scene, &f)
    })?;
    let mut doc = report::fragility::document(&scene, &f);
    doc.figures.extend(figure);
    Ok(super::print(&doc, args.json))
}
