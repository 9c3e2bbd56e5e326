//! The `voussoir` command line: parses arguments, calls the library, prints. Each command is
//! one file under `src/cli/`.

#![forbid(unsafe_code)]

mod cli;

use clap::{Parser, Subcommand};
use std::process::ExitCode;

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

#[derive(Subcommand)]
enum Command {
    /// Collapse multiplier of a scene: static lower bound, kinematic upper bound, mechanism
    Analyze(cli::analyze::Args),
    /// Parametric sweep: the cartesian product of varied keys, solved in parallel
    Sweep(cli::sweep::Args),
    /// Check the collapse multiplier with the discrete element method (rigid blocks in time)
    Dem(cli::dem::Args),
    /// Run a parametric study file (data/studies/*.toml): writes OUT/<output>.csv and .svg
    Study(cli::study::Args),
    /// Smallest arch thickness that stands under its permanent loads
    MinThickness(cli::min_thickness::Args),
    /// Speed against accuracy: refine the voussoir count, vary Clarabel's tolerance and the
    /// DEM's time step, stiffness and bracket tolerance; errors against the continuous model
    Convergence(cli::convergence::Args),
    /// Seismic verdict of the governing mechanism at a site (NTC 2018 / Circolare 2019
    /// C8.7.1: participating mass, capacity curve, linear and nonlinear kinematic checks)
    Assess(cli::assess::Args),
    /// Retrofit design: the smallest capacities of the ties marked capacity = "design" that
    /// give a target multiplier, the steel bars that carry them, and the structure re-analysed
    Retrofit(cli::retrofit::Args),
    /// Fragility curve of a scene with uncertain inputs ([uncertain]): Latin hypercube
    /// samples, each sample's capacity by the NTC nonlinear kinematic check at the site, and
    /// a lognormal fitted by maximum likelihood with confidence bounds
    Fragility(cli::fragility::Args),
    /// The arch explorer in the browser: a local page with sliders, the thrust line and the
    /// mechanism redrawn live, on a JSON API (127.0.0.1 only)
    #[cfg(feature = "serve")]
    Serve(cli::serve::Args),
    /// The hand-in report: one self-contained HTML document (and a PDF through headless
    /// Chromium) with the structure, the method, both bounds, the minimum thickness, the
    /// seismic check at the [site], the sensitivity and what reproduces it
    Report(cli::hand_in::Args),
    /// Spectrum-compatible artificial accelerograms (AT2 files) for the NTC 2018 elastic
    /// spectrum of a site: the mean 5 %-damped spectrum within the code's 10 % (§3.2.3.6)
    Records(cli::records::Args),
    /// Validation: every published or independent result voussoir is compared with,
    /// recomputed now (--markdown writes docs/validation.md)
    Validate(cli::validate::Args),
}

fn main() -> ExitCode {
    let result = match Cli::parse().command {
        Command::Analyze(a) => cli::analyze::run(a),
        Command::Sweep(a) => cli::sweep::run(a),
        Command::Dem(a) => cli::dem::run(a),
        Command::Study(a) => cli::study::run(a),
        Command::MinThickness(a) => cli::min_thickness::run(a),
        Command::Convergence(a) => cli::convergence::run(a),
        Command::Assess(a) => cli::assess::run(a),
        Command::Retrofit(a) => cli::retrofit::run(a),
        Command::Fragility(a) => cli::fragility::run(a),
        Command::Report(a) => cli::hand_in::run(a),
        Command::Validate(a) => cli::validate::run(a),
        Command::Records(a) => cli::records::run(a),
        #[cfg(feature = "serve")]
        Command::Serve(a) => cli::serve::run(a),
    };
    match result {
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
