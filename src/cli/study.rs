//! `voussoir study`: a parametric study file (data/studies/*.toml) to a CSV and a chart.

use super::{draw, progress_bar, write_atomically, Format, Outputs};
use voussoir::error::Error;

#[derive(clap::Args)]
pub struct Args {
    /// Study file (TOML: title, output, vary, x, series, y, baseline, continuous, [scene.*])
    study: std::path::PathBuf,
    /// Directory for OUTPUT.csv and OUTPUT.svg (created if missing); required, so that no run
    /// writes where it was not asked to (`--out docs/figures` regenerates the committed
    /// figures). The CSV has no wall-time column, so the same code writes the same bytes
    #[arg(long, value_name = "DIR", required = true)]
    out: std::path::PathBuf,
    /// Thin every range to 3 values (a quick check of the study)
    #[arg(long)]
    reduced: bool,
}

pub fn run(args: Args) -> Result<String, Error> {
    let mut st = voussoir::study::Study::from_file(&args.study)?;
    if args.reduced {
        st = st.reduced(3);
    }
    let out = &args.out;
    // The outputs are checked before anything is solved.
    if out.exists() && !out.is_dir() {
        return Err(Error::Output {
            path: out.clone(),
            message: "--out takes a directory, and this is a file".into(),
        });
    }
    std::fs::create_dir_all(out).map_err(|e| Error::Output {
        path: out.clone(),
        message: e.to_string(),
    })?;
    let csv_path = out.join(format!("{}.csv", st.output));
    let svg_path = out.join(format!("{}.svg", st.output));
    Outputs::new()
        .input(&args.study, "the study file")
        .read_by(&st.scene)
        .output("the study's CSV", Some(&csv_path), Format::Csv)
        .output("the study's chart", Some(&svg_path), Format::Svg)
        .check()?;
    let total = st.cases();
    let bar = progress_bar(total as u64, "study");
    let rows = st.run(&|| bar.inc(1))?;
    bar.finish_and_clear();
    let mut buf = Vec::new();
    st.write_csv(&mut buf, &rows).map_err(|e| Error::Output {
        path: csv_path.clone(),
        message: e.to_string(),
    })?;
    write_atomically(&csv_path, |b| {
        *b = buf;
        Ok(())
    })?;
    draw(Some(&svg_path), || {
        voussoir::report::figures::study(&st, &rows)
    })?;
    let failed = rows.iter().filter(|r| r.status == "error").count();
    Ok(format!(
        "{}: {} cases{} -> {} and {}",
        st.title,
        rows.len(),
        if failed > 0 {
            format!(" ({failed} invalid)")
        } else {
            String::new()
        },
        csv_path.display(),
        svg_path.display()
    ))
}
