//! The files a command writes: checked together before any work is done, and written whole or
//! not at all.
//!
//! [`Outputs`] is the one check every command makes before it solves anything. It refuses
//! - an output that is one of the command's inputs (`--svg scene.toml` would replace the scene;
//!   the comparison is on resolved paths, and on the file's identity where it exists, so
//!   `./scene.toml`, `../dir/scene.toml` and a symbolic link to it are the same file);
//! - two outputs on one path (`--thrust-csv x --svg x` would keep only the last written);
//! - a file name whose extension does not match what is written to it (`--svg out.png` would
//!   be an SVG drawing named as a PNG picture), case-insensitively;
//! - a path that cannot be written: a directory, a missing directory, or a directory where no
//!   file can be created ([`check_output_path`]).
//!
//! [`write_atomically`] writes each file to a uniquely named temporary file in the same
//! directory, flushes it to the disk (fsync) and renames it over the target, so a reader sees
//! the old file or the new one, never a part; an interrupted run leaves the old file (and at
//! most a hidden `.NAME.*.voussoir-tmp` beside it), and two runs never share a temporary file.

use std::path::{Path, PathBuf};
use voussoir::error::Error;
use voussoir::scene::{BlockSource, Scene};

/// What an output file holds, and so the extension its name must have.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Format {
    Svg,
    Csv,
    // For the outputs of `dem` (--animation, snapshots) once it checks them here.
    #[allow(dead_code)]
    Json,
    Html,
    Markdown,
    Pdf,
}

impl Format {
    /// The extension a file of this format must have (compared case-insensitively).
    pub fn extension(self) -> &'static str {
        match self {
            Format::Svg => "svg",
            Format::Csv => "csv",
            Format::Json => "json",
            Format::Html => "html",
            Format::Markdown => "md",
            Format::Pdf => "pdf",
        }
    }

    /// The format in words, for messages.
    fn words(self) -> &'static str {
        match self {
            Format::Svg => "an SVG drawing",
            Format::Csv => "a CSV table",
            Format::Json => "a JSON document",
            Format::Html => "an HTML page",
            Format::Markdown => "a Markdown page",
            Format::Pdf => "a PDF document",
        }
    }

    /// Other extensions accepted for the format.
    fn aliases(self) -> &'static [&'static str] {
        match self {
            Format::Html => &["htm"],
            _ => &[],
        }
    }
}

/// One file a command reads.
struct Input {
    path: PathBuf,
    what: String,
}

/// One file a command writes.
struct Output {
    path: PathBuf,
    what: String,
    format: Format,
}

/// The files of one command, checked together by [`Outputs::check`] before any work.
///
/// ```ignore
/// Outputs::new()
///     .scene(&args.scene.scene, &scene)
///     .output("--svg", args.svg.as_deref(), Format::Svg)
///     .check()?;
/// ```
#[derive(Default)]
pub struct Outputs {
    inputs: Vec<Input>,
    outputs: Vec<Output>,
}

impl Outputs {
    pub fn new() -> Self {
        Self::default()
    }

    /// A file the command reads (`what` names it in messages: "the scene file").
    pub fn input(mut self, path: &Path, what: &str) -> Self {
        self.inputs.push(Input {
            path: path.to_path_buf(),
            what: what.to_string(),
        });
        self
    }

    /// The scene file and every file the scene reads ([`Outputs::read_by`]).
    pub fn scene(self, path: &Path, scene: &Scene) -> Self {
        self.input(path, "the scene file").read_by(scene)
    }

    /// Every file `scene` reads (its blocks file), wherever the scene came from.
    pub fn read_by(self, scene: &Scene) -> Self {
        match scene.blocks.as_deref().map(|b| &b.source) {
            Some(BlockSource::File { path, .. }) => self.input(path, "the scene's blocks file"),
            _ => self,
        }
    }

    /// A file the command writes when `path` is given: `what` names it in messages (the
    /// option, `--svg`), `format` is what is written to it.
    pub fn output(mut self, what: &str, path: Option<&Path>, format: Format) -> Self {
        if let Some(path) = path {
            self.outputs.push(Output {
                path: path.to_path_buf(),
                what: what.to_string(),
                format,
            });
        }
        self
    }

    /// Check every output: that it is no input and no other output, that it can be written
    /// ([`check_output_path`]), and its extension. Nothing is written.
    pub fn check(&self) -> Result<(), Error> {
        let resolved: Vec<PathBuf> = self.outputs.iter().map(|o| resolve(&o.path)).collect();
        for (k, o) in self.outputs.iter().enumerate() {
            let fail = |message: String| Error::Output {
                path: o.path.clone(),
                message,
            };
            for i in &self.inputs {
                if same_file(&o.path, &resolved[k], &i.path) {
                    return Err(fail(format!(
                        "{} would overwrite {} {} (an input); give another file name",
                        o.what,
                        i.what,
                        i.path.display()
                    )));
                }
            }
            if let Some(first) = (0..k).find(|&j| resolved[j] == resolved[k]) {
                return Err(fail(format!(
                    "{} and {} both name this file, and one would replace the other; give each its own file",
                    self.outputs[first].what, o.what
                )));
            }
        }
        // Then each on its own (after the clashes, which are the graver mistakes).
        for o in &self.outputs {
            check_output_path(&o.path)?;
            check_extension(&o.path, o.format).map_err(|m| Error::Output {
                path: o.path.clone(),
                message: format!("{} {m}", o.what),
            })?;
        }
        Ok(())
    }
}

/// Whether `path` has the extension of `format` (case-insensitively); the message says what
/// to do when not.
pub fn check_extension(path: &Path, format: Format) -> Result<(), String> {
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    match ext {
        Some(e) if e == format.extension() || format.aliases().contains(&e.as_str()) => Ok(()),
        Some(e) => Err(format!(
            "writes {}, not a .{e} file; give a file name ending in .{}",
            format.words(),
            format.extension()
        )),
        None => Err(format!(
            "writes {}; give a file name ending in .{}",
            format.words(),
            format.extension()
        )),
    }
}

/// The absolute path a file name stands for, symbolic links resolved as far as the file
/// exists: the file itself when it exists, else its directory joined with its name, else
/// (no such directory) the path made absolute with `.` and `..` folded away.
pub fn resolve(path: &Path) -> PathBuf {
    if let Ok(p) = std::fs::canonicalize(path) {
        return p;
    }
    let dir = match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => Path::new("."),
    };
    match (std::fs::canonicalize(dir), path.file_name()) {
        (Ok(d), Some(name)) => d.join(name),
        _ => {
            let absolute = std::path::absolute(path).unwrap_or_else(|_| path.to_path_buf());
            let mut folded = PathBuf::new();
            for part in absolute.components() {
                match part {
                    std::path::Component::ParentDir => {
                        folded.pop();
                    }
                    std::path::Component::CurDir => {}
                    other => folded.push(other),
                }
            }
            folded
        }
    }
}

/// Whether writing `output` (resolved: `resolved`) would replace the file `input`: the same
/// resolved path, or (where both exist) the same file on the disk, which also catches a
/// case-insensitive file system's `Scene.TOML` for `scene.toml`.
pub fn same_file(output: &Path, resolved: &Path, input: &Path) -> bool {
    if resolve(input) == resolved {
        return true;
    }
    #[cfg(unix)]
    {
        use std::os::unix::fs::MetadataExt;
        if let (Ok(a), Ok(b)) = (std::fs::metadata(output), std::fs::metadata(input)) {
            return a.dev() == b.dev() && a.ino() == b.ino();
        }
    }
    false
}

/// The directory a file is written in (`.` for a bare file name).
fn directory_of(path: &Path) -> &Path {
    match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => Path::new("."),
    }
}

/// A new temporary file in `dir`, named after `path` (hidden, unique: `.NAME.XXXXXX.voussoir-tmp`),
/// with the permissions a new file gets (`0666` less the umask, as `std::fs::write` would
/// give, not the `0600` of a private temporary file).
fn temporary_in(dir: &Path, path: &Path) -> std::io::Result<tempfile::NamedTempFile> {
    let name = path
        .file_name()
        .map_or_else(|| "output".into(), |n| n.to_string_lossy().into_owned());
    let prefix = format!(".{name}.");
    let mut builder = tempfile::Builder::new();
    builder.prefix(&prefix).suffix(".voussoir-tmp");
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        builder.permissions(std::fs::Permissions::from_mode(0o666));
    }
    builder.tempfile_in(dir)
}

/// Check that `path` can be written, before any work is done (so an unwritable output is
/// reported at once, not after minutes of solving): it is not empty or a directory, its
/// directory exists, and a temporary file can be created there (it is created and removed
/// again; nothing else is touched). [`Outputs::check`] calls it for each output.
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
    let dir = directory_of(path);
    if !dir.is_dir() {
        return Err(fail(format!(
            "the directory {} does not exist",
            dir.display()
        )));
    }
    // Created and removed (on drop): a writable directory is all this needs to know.
    temporary_in(dir, path)
        .map(drop)
        .map_err(|e| fail(e.to_string()))
}

/// Write a file whole or not at all: `write` fills a buffer, which goes to a new temporary
/// file in the target's directory (a unique name: two runs never share it, and no file of the
/// user's is touched), is flushed to the disk (fsync), and is then renamed over `path` (an
/// atomic replacement on one file system). On any failure the temporary file is removed and
/// `path` is left as it was.
pub fn write_atomically(
    path: &Path,
    write: impl FnOnce(&mut Vec<u8>) -> Result<(), String>,
) -> Result<(), Error> {
    let fail = |message: String| Error::Output {
        path: path.to_path_buf(),
        message,
    };
    let mut buf = Vec::new();
    write(&mut buf).map_err(fail)?;
    let dir = directory_of(path);
    let mut tmp = temporary_in(dir, path).map_err(|e| fail(e.to_string()))?;
    use std::io::Write;
    tmp.write_all(&buf)
        .and_then(|_| tmp.as_file().sync_all())
        .map_err(|e| fail(e.to_string()))?;
    // On failure `persist` hands the temporary file back; dropping it removes it.
    tmp.persist(path).map_err(|e| fail(e.error.to_string()))?;
    // The rename itself is made durable by flushing the directory (where the platform can).
    #[cfg(unix)]
    if let Ok(d) = std::fs::File::open(dir) {
        let _ = d.sync_all();
    }
    Ok(())
}

/// Write text to a file whole or not at all ([`write_atomically`]).
pub fn write_text(path: &Path, text: &str) -> Result<(), Error> {
    write_atomically(path, |b| {
        b.extend_from_slice(text.as_bytes());
        Ok(())
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn files_in(dir: &Path) -> Vec<String> {
        let mut names: Vec<String> = std::fs::read_dir(dir)
            .expect("dir")
            .map(|e| e.expect("entry").file_name().to_string_lossy().into_owned())
            .collect();
        names.sort();
        names
    }

    #[test]
    fn output_paths_are_checked_without_leaving_files() {
        let dir = tempfile::tempdir().expect("tempdir");
        let ok = dir.path().join("a.csv");
        assert!(check_output_path(&ok).is_ok());
        assert!(files_in(dir.path()).is_empty());
        assert!(check_output_path(&dir.path().join("missing/a.csv")).is_err());
        assert!(check_output_path(dir.path()).is_err());
    }

    #[test]
    fn a_write_replaces_the_file_whole_and_leaves_no_temporary() {
        let dir = tempfile::tempdir().expect("tempdir");
        let path = dir.path().join("out.csv");
        // A user's file with the old fixed temporary name is not touched.
        let theirs = dir.path().join("out.voussoir-tmp");
        std::fs::write(&theirs, "mine").expect("write");
        std::fs::write(&path, "old").expect("write");
        write_text(&path, "new").expect("written");
        assert_eq!(std::fs::read_to_string(&path).expect("read"), "new");
        assert_eq!(std::fs::read_to_string(&theirs).expect("read"), "mine");
        assert_eq!(files_in(dir.path()), ["out.csv", "out.voussoir-tmp"]);
        // A failed write leaves the old file and no temporary.
        let e = write_atomically(&path, |_| Err("no rows".into())).expect_err("fails");
        assert!(e.to_string().contains("no rows"), "{e}");
        assert_eq!(std::fs::read_to_string(&path).expect("read"), "new");
        assert_eq!(files_in(dir.path()), ["out.csv", "out.voussoir-tmp"]);
    }

    #[cfg(unix)]
    #[test]
    fn a_new_file_gets_the_usual_permissions() {
        use std::os::unix::fs::PermissionsExt;
        let dir = tempfile::tempdir().expect("tempdir");
        let path = dir.path().join("out.svg");
        write_text(&path, "<svg/>").expect("written");
        let reference = dir.path().join("reference");
        std::fs::write(&reference, "x").expect("write");
        let mode = |p: &Path| std::fs::metadata(p).expect("meta").permissions().mode() & 0o777;
        assert_eq!(mode(&path), mode(&reference));
    }

    #[test]
    fn extensions_must_match_the_format_in_any_case() {
        assert!(check_extension(Path::new("a.svg"), Format::Svg).is_ok());
        assert!(check_extension(Path::new("dir.x/A.SVG"), Format::Svg).is_ok());
        assert!(check_extension(Path::new("a.htm"), Format::Html).is_ok());
        let e = check_extension(Path::new("out.png"), Format::Svg).expect_err("png");
        assert!(e.contains("not a .png file") && e.contains(".svg"), "{e}");
        assert!(check_extension(Path::new("out"), Format::Csv).is_err());
        assert!(check_extension(Path::new("out.svg"), Format::Csv).is_err());
    }

    #[test]
    fn an_output_may_be_no_input_and_no_other_output() {
        let dir = tempfile::tempdir().expect("tempdir");
        let scene = dir.path().join("scene.toml");
        std::fs::write(&scene, "x").expect("write");
        let sub = dir.path().join("sub");
        std::fs::create_dir(&sub).expect("dir");
        // The same file by another spelling.
        let other = sub.join("..").join("scene.toml");
        let e = Outputs::new()
            .input(&scene, "the scene file")
            .output("--svg", Some(&other), Format::Svg)
            .check()
            .expect_err("input");
        assert!(
            e.to_string()
                .contains("--svg would overwrite the scene file"),
            "{e}"
        );
        let drawing = dir.path().join("in.svg");
        std::fs::write(&drawing, "<svg/>").expect("write");
        let e = Outputs::new()
            .input(&drawing, "the record")
            .output("--svg", Some(&sub.join("../in.svg")), Format::Svg)
            .check()
            .expect_err("input");
        assert!(e.to_string().contains("would overwrite the record"), "{e}");
        let x = dir.path().join("x.svg");
        let e = Outputs::new()
            .output("--svg", Some(&x), Format::Svg)
            .output("--adrs-svg", Some(&sub.join("../x.svg")), Format::Svg)
            .check()
            .expect_err("twice");
        assert!(e.to_string().contains("--svg and --adrs-svg"), "{e}");
        assert!(Outputs::new()
            .input(&scene, "the scene file")
            .output("--svg", Some(&x), Format::Svg)
            .output("--csv", None, Format::Csv)
            .check()
            .is_ok());
        assert_eq!(files_in(dir.path()), ["in.svg", "scene.toml", "sub"]);
    }
}
