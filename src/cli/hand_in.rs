//! `voussoir report`: the hand-in report of a scene, one self-contained HTML document
//! (docs/report.md), and a PDF of it through a headless Chromium when one is installed.

use super::{write_atomically, write_text, Format, SceneArgs};
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};
use voussoir::dossier::{self, DossierOptions};
use voussoir::error::{Error, SceneError};
use voussoir::report::dossier::{hand_in, Source};

#[derive(clap::Args)]
pub struct Args {
    #[command(flatten)]
    scene: SceneArgs,
    /// Set a key of the scene's [site] table, e.g. --site ag=0.25 --site soil=B (repeatable;
    /// as `voussoir assess`)
    #[arg(long = "site", value_name = "KEY=VALUE")]
    site: Vec<String>,
    /// Also run the DEM's bracket of the collapse multiplier (as `analyze --dem`; minutes on
    /// large structures)
    #[arg(long)]
    dem: bool,
    /// Write the report (HTML) to this file; without -o, --pdf or --json the HTML goes to
    /// standard output
    #[arg(short = 'o', long = "output", value_name = "FILE")]
    output: Option<PathBuf>,
    /// Also print the report to PDF (A4) through a headless Chromium (looked for as
    /// $VOUSSOIR_CHROMIUM, then chromium, chromium-browser, google-chrome,
    /// google-chrome-stable on the PATH)
    #[arg(long, value_name = "FILE")]
    pdf: Option<PathBuf>,
    /// Print the report's JSON (the objects of analyze, min-thickness and assess, and the
    /// sensitivity) instead of the summary
    #[arg(long)]
    json: bool,
}

/// The executables `--pdf` looks for on the PATH, in order (after `$VOUSSOIR_CHROMIUM`).
pub const CHROMIUM_NAMES: &[&str] = &[
    "chromium",
    "chromium-browser",
    "google-chrome",
    "google-chrome-stable",
];

/// How long the browser may take to print the page.
const PDF_TIMEOUT: Duration = Duration::from_secs(120);

pub fn run(args: Args) -> Result<String, Error> {
    let (scene, sets) = args.scene.load_with_site(&args.site)?;
    args.scene
        .outputs(&scene)
        .output("-o", args.output.as_deref(), Format::Html)
        .output("--pdf", args.pdf.as_deref(), Format::Pdf)
        .check()?;
    // Found before any work: a missing browser is said at once, not after the analyses.
    let browser = match &args.pdf {
        Some(_) => Some(find_chromium()?),
        None => None,
    };
    let text = std::fs::read_to_string(&args.scene.scene).map_err(|source| SceneError::Io {
        path: args.scene.scene.clone(),
        source,
    })?;
    let source = Source {
        text,
        overrides: args.scene.set.iter().cloned().chain(sets).collect(),
    };
    let d = dossier::run(&scene, &DossierOptions { dem: args.dem })?;
    let report = hand_in(&scene, &source, &d);
    let html = report.html();
    let mut written = Vec::new();
    if let Some(path) = &args.output {
        write_text(path, &html)?;
        written.push(path.display().to_string());
    }
    if let (Some(path), Some(browser)) = (&args.pdf, &browser) {
        print_pdf(browser, &html, path)?;
        written.push(path.display().to_string());
    }
    if args.json {
        return Ok(report.json());
    }
    if written.is_empty() {
        return Ok(html);
    }
    Ok(format!(
        "{}: report written to {} ({} chapters, analyses in {:.2} s)",
        scene.origin,
        written.join(" and "),
        report.chapters.len(),
        d.wall_time_s
    ))
}

/// The browser `--pdf` prints with: `$VOUSSOIR_CHROMIUM` when set, else the first of
/// [`CHROMIUM_NAMES`] on the PATH; an error naming what was looked for and how to get one
/// otherwise.
fn find_chromium() -> Result<PathBuf, Error> {
    if let Some(p) = std::env::var_os("VOUSSOIR_CHROMIUM") {
        let p = PathBuf::from(p);
        if p.is_file() {
            return Ok(p);
        }
        return Err(pdf_error(format!(
            "VOUSSOIR_CHROMIUM={} is not a file",
            p.display()
        )));
    }
    let path = std::env::var_os("PATH").unwrap_or_default();
    for name in CHROMIUM_NAMES {
        for dir in std::env::split_paths(&path) {
            let candidate = dir.join(name);
            if candidate.is_file() {
                return Ok(candidate);
            }
        }
    }
    Err(pdf_error(format!(
        "no headless Chromium found (looked for $VOUSSOIR_CHROMIUM, then {} on the PATH): install one (Debian/Ubuntu: apt-get install chromium), or write the HTML with -o and use a browser's Print to PDF (A4)",
        CHROMIUM_NAMES.join(", ")
    )))
}

fn pdf_error(message: String) -> Error {
    Error::Analysis(voussoir::error::AnalysisError::Other(format!(
        "--pdf: {message}"
    )))
}

/// Print `html` to `pdf` with the headless browser: the page written to a private temporary
/// directory (with the browser's own profile, so a running browser is not disturbed), printed
/// there, and the PDF moved into place whole.
fn print_pdf(browser: &Path, html: &str, pdf: &Path) -> Result<(), Error> {
    let fail = |message: String| Error::Output {
        path: pdf.to_path_buf(),
        message,
    };
    let dir = tempfile::tempdir().map_err(|e| fail(format!("no temporary directory: {e}")))?;
    let page = dir.path().join("report.html");
    let printed = dir.path().join("report.pdf");
    std::fs::write(&page, html).map_err(|e| fail(e.to_string()))?;
    let mut child = Command::new(browser)
        .arg("--headless")
        // The page has no script and reads nothing: the sandbox (which refuses to run as root)
        // guards nothing here.
        .arg("--no-sandbox")
        .arg("--disable-gpu")
        // The page's own header (title, page numbers) replaces the browser's date and URL.
        .arg("--no-pdf-header-footer")
        .arg(format!(
            "--user-data-dir={}",
            dir.path().join("profile").display()
        ))
        .arg(format!("--print-to-pdf={}", printed.display()))
        .arg(format!("file://{}", page.display()))
        .stdin(Stdio::null())
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .map_err(|e| fail(format!("cannot start {}: {e}", browser.display())))?;
    let start = Instant::now();
    let status = loop {
        match child.try_wait() {
            Ok(Some(status)) => break status,
            Ok(None) if start.elapsed() > PDF_TIMEOUT => {
                let _ = child.kill();
                let _ = child.wait();
                return Err(fail(format!(
                    "{} did not print the page within {} s",
                    browser.display(),
                    PDF_TIMEOUT.as_secs()
                )));
            }
            Ok(None) => std::thread::sleep(Duration::from_millis(50)),
            Err(e) => return Err(fail(e.to_string())),
        }
    };
    let bytes = std::fs::read(&printed)
        .ok()
        .filter(|b| b.starts_with(b"%PDF"));
    let Some(bytes) = bytes.filter(|_| status.success()) else {
        let mut stderr = String::new();
        if let Some(mut e) = child.stderr.take() {
            use std::io::Read;
            let _ = e.read_to_string(&mut stderr);
        }
        let tail: String = stderr.lines().rev().take(5).collect::<Vec<_>>().join(" | ");
        return Err(fail(format!(
            "{} printed no PDF ({status}): {tail}",
            browser.display()
        )));
    };
    write_atomically(pdf, |b| {
        b.extend_from_slice(&bytes);
        Ok(())
    })
}
