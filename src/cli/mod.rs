//! The commands of the `voussoir` binary, one file each: every command parses its arguments,
//! calls the library's analysis layer ([`voussoir::analysis`]) and returns what to print.
//! This module holds what they share: reading the scene, writing output files whole or not
//! at all, and the progress bar.

pub mod analyze;
pub mod convergence;
pub mod dem;
pub mod min_thickness;
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
    /// Read the scene and apply the overrides.
    pub fn load(&self) -> Result<Scene, Error> {
        let scene = Scene::from_file(&self.scene)?;
        if self.set.is_empty() {
            return Ok(scene);
        }
        Ok(scene.with_overrides(&self.set)?)
    }
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
