//! The commands of the `voussoir` binary, one file each: every command parses its arguments,
//! calls the library's analysis layer ([`voussoir::analysis`]), asks `report::documents` for
//! its result document and `report::figures` for the figures its flags name, and returns the
//! document printed as the flags ask ([`print`]).
//! This module holds what they share: reading the scene, the output files ([`outputs`]:
//! checked before any work, written whole or not at all), and the progress bar.

pub mod analyze;
pub mod assess;
pub mod convergence;
pub mod dem;
pub mod fragility;
pub mod hand_in;
pub mod min_thickness;
pub mod outputs;
pub mod records;
pub mod retrofit;
#[cfg(feature = "serve")]
pub mod serve;
pub mod study;
pub mod sweep;
pub mod validate;

pub use outputs::{write_atomically, write_text, Format, Outputs};
use std::path::{Path, PathBuf};
use voussoir::error::{AnalysisError, Error, SceneError};
use voussoir::report::{self, figures::FigureError, Document, Figure};
use voussoir::scene::{BlockSource, Scene};

/// Direction of the horizontal acceleration, as the command line names it.
#[derive(Clone, Copy, clap::ValueEnum)]
pub enum Dir {
    Right,
    Left,
}

impl From<Dir> for voussoir::outcome::Direction {
    fn from(d: Dir) -> Self {
        match d {
            Dir::Right => voussoir::outcome::Direction::Right,
            Dir::Left => voussoir::outcome::Direction::Left,
        }
    }
}

/// How the kinematic upper bound is found, as the command line names it.
#[derive(Clone, Copy, clap::ValueEnum)]
pub enum Kinematic {
    /// The mechanism of the static hinges by virtual work (falls back to a search)
    Certified,
    /// The exhaustive search over every mechanism, up to --kinematic-max-joints
    Exhaustive,
    /// The general kinematic program (any blocks rocking, lifting, sliding), on chains too;
    /// assemblies that are not chains always get it (analyze and sweep only)
    General,
}

impl From<Kinematic> for voussoir::analysis::KinematicMode {
    fn from(k: Kinematic) -> Self {
        match k {
            Kinematic::Certified => voussoir::analysis::KinematicMode::Certified,
            Kinematic::Exhaustive => voussoir::analysis::KinematicMode::Exhaustive,
            Kinematic::General => voussoir::analysis::KinematicMode::General,
        }
    }
}

/// Which friction law the collapse multiplier is given for, as the command line names it
/// (docs/friction.md).
#[derive(Clone, Copy, clap::ValueEnum)]
pub enum Friction {
    /// The non-associative multiplier whenever joints slide in the associative mechanism
    Auto,
    /// The static program's (associative) multiplier alone
    Associative,
    /// The non-associative multiplier always (and the minimum thickness of real joints)
    NonAssociative,
}

impl From<Friction> for voussoir::analysis::FrictionMode {
    fn from(f: Friction) -> Self {
        match f {
            Friction::Auto => voussoir::analysis::FrictionMode::Auto,
            Friction::Associative => voussoir::analysis::FrictionMode::Associative,
            Friction::NonAssociative => voussoir::analysis::FrictionMode::NonAssociative,
        }
    }
}

/// The scene file and its overrides, common to every command that reads one scene.
#[derive(clap::Args)]
pub struct SceneArgs {
    /// Scene file (TOML, see README)
    pub scene: PathBuf,
    /// Override a scene value, e.g. --set arch.thickness=0.2 (repeatable)
    #[arg(long = "set", value_name = "KEY=VALUE")]
    pub set: Vec<String>,
    /// Most user blocks ([blocks]) a scene may have; up to 100000 (the cost grows faster than
    /// the blocks: a 10,050-block wall takes about 24 s of CPU for its static bound; with
    /// finite friction where joints slip, the non-associative iteration solves some tens of
    /// such programs: 39 for a 972-block wall with mu = 0.6, 14 s)
    #[arg(long, value_name = "N", default_value_t = DEFAULT_MAX_BLOCKS)]
    pub max_blocks: usize,
}

/// How many user blocks a command takes unless `--max-blocks` says more. Analysing a wall of
/// blocks (the full conic program) grows faster than the number of blocks: a 10,050-block
/// running-bond wall takes about 24 s of CPU and 210 MiB for the static bound
/// (docs/performance.md, "Large assemblies (issue 28)"). The readers' own bound,
/// [`voussoir::blocks::MAX_BLOCKS`], stays the ceiling.
pub const DEFAULT_MAX_BLOCKS: usize = 10_000;

impl SceneArgs {
    /// Read the scene and apply the overrides, validating once (so an override can mend the
    /// file).
    pub fn load(&self) -> Result<Scene, Error> {
        let limit = self.max_blocks;
        if limit > voussoir::blocks::MAX_BLOCKS {
            return Err(SceneError::Usage(format!(
                "--max-blocks {limit}: at most {} (voussoir::blocks::MAX_BLOCKS)",
                voussoir::blocks::MAX_BLOCKS
            ))
            .into());
        }
        let scene = Scene::from_file_with_overrides(&self.scene, &self.set)?;
        if let Some(b) = &scene.blocks {
            let count = b.polygons.len();
            if count > limit {
                return Err(SceneError::OutOfRange {
                    origin: scene.origin.clone(),
                    key: match b.source {
                        BlockSource::File { .. } => "blocks.file".into(),
                        BlockSource::Inline => "blocks.polygons".into(),
                    },
                    value: format!("\"{}\" ({count} blocks)", b.source_words()),
                    allowed: format!(
                        "more than the {limit} blocks a command takes{}; --max-blocks {count} lifts the limit (up to {}), at the cost of minutes and gigabytes (docs/geometry.md)",
                        if limit == DEFAULT_MAX_BLOCKS { " by default" } else { "" },
                        voussoir::blocks::MAX_BLOCKS
                    ),
                }
                .into());
            }
        }
        Ok(scene)
    }

    /// Read the scene as [`Self::load`] does, then set the `[site]` keys given as
    /// `--site KEY=VALUE` (each an override `site.KEY=VALUE`); the scene and those overrides.
    pub fn load_with_site(&self, site: &[String]) -> Result<(Scene, Vec<String>), Error> {
        let mut scene = self.load()?;
        let sets: Vec<String> = site.iter().map(|s| format!("site.{s}")).collect();
        if !sets.is_empty() {
            scene = scene.with_overrides(&sets)?;
        }
        Ok((scene, sets))
    }

    /// The command's files, starting with the inputs of `scene` (the scene file and its
    /// blocks file), for the command to add its outputs to and [`Outputs::check`].
    pub fn outputs(&self, scene: &Scene) -> Outputs {
        Outputs::new().scene(&self.scene, scene)
    }
}

/// Write a figure (its SVG) to `path`.
pub fn write_figure(path: &Path, figure: &Figure) -> Result<(), Error> {
    write_text(path, &figure.svg)
}

/// A figure that could not be drawn, as the error of the file it was for.
pub fn figure_error(path: &Path) -> impl Fn(FigureError) -> Error + '_ {
    move |e| match e {
        FigureError::Chart(e) => Error::Scene(e),
        FigureError::Unreachable(_) => Error::Analysis(AnalysisError::Other(e.to_string())),
        FigureError::Svg(e) => Error::Output {
            path: path.to_path_buf(),
            message: e.to_string(),
        },
    }
}

/// Draw the figure `figure` to `path` when the command was given one, and return it for the
/// command's document: the figures a command draws are chosen in `report::figures`, the
/// command only says where they go.
pub fn draw<E: Into<FigureError>>(
    path: Option<&Path>,
    figure: impl FnOnce() -> Result<Figure, E>,
) -> Result<Option<Figure>, Error> {
    let Some(path) = path else { return Ok(None) };
    let figure = figure().map_err(|e| figure_error(path)(e.into()))?;
    write_figure(path, &figure)?;
    Ok(Some(figure))
}

/// The document printed as the flags ask: the JSON contract with `--json`, the text
/// otherwise.
pub fn print(doc: &Document, json: bool) -> String {
    report::print(
        doc,
        if json {
            report::Format::Json
        } else {
            report::Format::Text
        },
    )
}

/// A progress bar on stderr when it is a terminal, hidden otherwise.
pub fn progress_bar(len: u64, what: &str) -> indicatif::ProgressBar {
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

/// A spinner on stderr when it is a terminal (hidden otherwise), for work whose number of
/// steps is not known in advance: `what` as its prefix, the current step as its message.
pub fn progress_spinner(what: &str) -> indicatif::ProgressBar {
    use std::io::IsTerminal;
    if !std::io::stderr().is_terminal() {
        return indicatif::ProgressBar::hidden();
    }
    let bar = spinner(what);
    bar.enable_steady_tick(std::time::Duration::from_millis(120));
    bar
}

/// The spinner itself: no length, so no "0/0".
fn spinner(what: &str) -> indicatif::ProgressBar {
    let bar = indicatif::ProgressBar::new_spinner();
    if let Ok(style) =
        indicatif::ProgressStyle::with_template("{spinner} {prefix} [{elapsed_precise}] {msg}")
    {
        bar.set_style(style);
    }
    bar.set_prefix(what.to_string());
    bar
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_spinner_shows_the_step_and_no_count() {
        let bar = spinner("convergence");
        assert_eq!(bar.length(), None);
        bar.set_message("n = 64");
        assert_eq!(bar.message(), "n = 64");
        assert_eq!(bar.prefix(), "convergence");
    }
}
