//! The commands of the `voussoir` binary, one file each: every command parses its arguments,
//! calls the library's analysis layer ([`voussoir::analysis`]) and returns what to print.
//! This module holds what they share: reading the scene, checking output paths before any
//! work, writing output files whole or not at all, and the progress bar.

pub mod analyze;
pub mod assess;
pub mod convergence;
pub mod dem;
pub mod min_thickness;
#[cfg(feature = "serve")]
pub mod serve;
pub mod study;
pub mod sweep;

use std::path::{Path, PathBuf};
use voussoir::assembly::Assembly;
use voussoir::error::Error;
use voussoir::scene::Scene;
use voussoir::thrustline::svg::{self, Drawing};

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
}

impl From<Kinematic> for voussoir::analysis::KinematicMode {
    fn from(k: Kinematic) -> Self {
        match k {
            Kinematic::Certified => voussoir::analysis::KinematicMode::Certified,
            Kinematic::Exhaustive => voussoir::analysis::KinematicMode::Exhaustive,
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
}

impl SceneArgs {
    /// Read the scene and apply the overrides, validating once (so an override can mend the
    /// file).
    pub fn load(&self) -> Result<Scene, Error> {
        Ok(Scene::from_file_with_overrides(&self.scene, &self.set)?)
    }
}

/// The temporary sibling a file is written to before it is renamed into place.
fn temp_sibling(path: &Path) -> PathBuf {
    path.with_extension("voussoir-tmp")
}

/// Check that `path` can be written, before any work is done (so an unwritable output is
/// reported at once, not after minutes of solving): it is not a directory, its directory
/// exists, and the temporary sibling [`write_atomically`] writes first can be created there
/// (it is created and removed again). Nothing else is touched.
pub fn check_output_path(path: &Path) -> Result<(), Error> {
    let fail = |message: String| Error::Output {
        path: path.to_path_buf(),
        message,
    };
    if path.as_os_str().is_empty() {
        return Err(fail("empty file name".into()));
    }
    if path.is_dir() {
        return Err(fail("it is a directory; give a file name".into()));
    }
    let dir = match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => Path::new("."),
    };
    if !dir.is_dir() {
        return Err(fail(format!(
            "the directory {} does not exist",
            dir.display()
        )));
    }
    let tmp = temp_sibling(path);
    match std::fs::OpenOptions::new()
        .write(true)
        .create_new(true)
        .open(&tmp)
    {
        Ok(file) => {
            drop(file);
            std::fs::remove_file(&tmp).map_err(|e| fail(e.to_string()))
        }
        // A leftover of an interrupted run: writable is all we need to know.
        Err(e) if e.kind() == std::io::ErrorKind::AlreadyExists => std::fs::OpenOptions::new()
            .write(true)
            .open(&tmp)
            .map(drop)
            .map_err(|e| fail(e.to_string())),
        Err(e) => Err(fail(e.to_string())),
    }
}

/// [`check_output_path`] for each path given.
pub fn check_output_paths<'a>(
    paths: impl IntoIterator<Item = Option<&'a PathBuf>>,
) -> Result<(), Error> {
    paths
        .into_iter()
        .flatten()
        .try_for_each(|p| check_output_path(p))
}

/// Write a file whole or not at all: to a temporary sibling, then rename.
pub fn write_atomically(
    path: &Path,
    write: impl FnOnce(&mut Vec<u8>) -> Result<(), String>,
) -> Result<(), Error> {
    let mut buf = Vec::new();
    write(&mut buf).map_err(|message| Error::Output {
        path: path.to_path_buf(),
        message,
    })?;
    let tmp = temp_sibling(path);
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
pub fn write_text(path: &Path, text: &str) -> Result<(), Error> {
    write_atomically(path, |b| {
        b.extend_from_slice(text.as_bytes());
        Ok(())
    })
}

/// Draw a chart to an SVG file.
pub fn write_chart(path: &Path, chart: &voussoir::thrustline::chart::Chart) -> Result<(), Error> {
    let text = voussoir::thrustline::chart::chart_svg(chart).map_err(|e| Error::Output {
        path: path.to_path_buf(),
        message: e.to_string(),
    })?;
    write_text(path, &text)
}

/// Draw a structure to an SVG file.
pub fn write_svg(path: &Path, assembly: &Assembly, drawing: &Drawing) -> Result<(), Error> {
    let text = svg::structure_svg(assembly, drawing).map_err(|e| Error::Output {
        path: path.to_path_buf(),
        message: e.to_string(),
    })?;
    write_text(path, &text)
}

/// Pretty JSON of a report.
pub fn json<T: serde::Serialize>(value: &T) -> String {
    serde_json::to_string_pretty(value).unwrap_or_else(|e| format!("{{\"error\": \"{e}\"}}"))
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

    #[test]
    fn output_paths_are_checked_without_leaving_files() {
        let dir = tempfile::tempdir().expect("tempdir");
        let ok = dir.path().join("a.csv");
        assert!(check_output_path(&ok).is_ok());
        assert!(std::fs::read_dir(dir.path()).expect("dir").next().is_none());
        assert!(check_output_path(&dir.path().join("missing/a.csv")).is_err());
        assert!(check_output_path(dir.path()).is_err());
        assert!(check_output_paths([Some(&ok), None]).is_ok());
    }
}
