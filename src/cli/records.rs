//! `voussoir records`: spectrum-compatible artificial accelerograms for a site
//! ([`voussoir::records`]), written as `.AT2` files (which `voussoir dem --record` reads) and a
//! CSV of their spectra against the target, into a directory.

use super::outputs::{check_output_path, write_text};
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use voussoir::error::{Error, SceneError};
use voussoir::records::{self, Request};
use voussoir::spectrum::{Site, G};

#[derive(clap::Args)]
pub struct Args {
    /// A key of the site, e.g. --site ag=0.25 --site soil=B --site F0=2.4 --site Tc_star=0.3
    /// (repeatable; the keys of a scene's [site] table: ag, soil, topography, F0, Tc_star; or
    /// latitude, longitude, nominal_life, use_class, limit_state for the national hazard grid)
    #[arg(long = "site", value_name = "KEY=VALUE")]
    site: Vec<String>,
    /// Number of records (NTC 2018 §7.3.5: with 7 or more the mean of the results may be
    /// used, with fewer, at least 3, the worst)
    #[arg(long, default_value_t = 7)]
    count: usize,
    /// Duration of each record (s); NTC 2018 §3.2.3.6 asks for 25 s (a 10 s pseudo-stationary
    /// part with a rise and a decay) when no specific study sets it
    #[arg(long, default_value_t = records::CODE_DURATION)]
    duration: f64,
    /// Time step of the records (s)
    #[arg(long, default_value_t = records::DEFAULT_DT)]
    dt: f64,
    /// Seed of the random phases: the same seed gives the same records
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// The structure's fundamental period T (s): the check then covers 0.15 s - 2T when
    /// 2T > 2 s (NTC 2018 §3.2.3.6)
    #[arg(long, value_name = "T")]
    period: Option<f64>,
    /// Directory the records go to (created if missing): record_01.AT2, ..., spectra.csv
    #[arg(long, value_name = "DIR")]
    out: PathBuf,
    /// Replace files of the same names already in DIR (refused otherwise)
    #[arg(long)]
    force: bool,
}

/// The site of the `--site KEY=VALUE` flags, read as a scene's `[site]` table.
fn site(flags: &[String]) -> Result<Site, Error> {
    let mut table = toml::Table::new();
    for text in flags {
        let (key, value) = voussoir::overrides::parse_assignment(text)?;
        if table.insert(key.clone(), value).is_some() {
            return Err(SceneError::Usage(format!(
                "--site {text}: the key `{key}` is given twice"
            ))
            .into());
        }
    }
    if table.is_empty() {
        return Err(SceneError::Usage(
            "records: give the site, e.g. --site ag=0.25 --site soil=B --site F0=2.4 --site Tc_star=0.3 (or --site latitude=... --site longitude=...)".into(),
        )
        .into());
    }
    Ok(Site::from_table(&table, "--site")?)
}

/// The files a run writes into `dir`.
fn file_names(count: usize) -> Vec<String> {
    let mut names: Vec<String> = (1..=count).map(|k| format!("record_{k:02}.AT2")).collect();
    names.push("spectra.csv".to_string());
    names
}

/// Refuse a run that would replace a file (unless `force`) or cannot write one, before any
/// work is done.
fn check_outputs(dir: &Path, names: &[String], force: bool) -> Result<(), Error> {
    if dir.exists() && !dir.is_dir() {
        return Err(Error::Output {
            path: dir.to_path_buf(),
            message: "--out must name a directory, and this is a file".into(),
        });
    }
    if !dir.exists() {
        std::fs::create_dir_all(dir).map_err(|e| Error::Output {
            path: dir.to_path_buf(),
            message: format!("cannot create the directory: {e}"),
        })?;
    }
    for name in names {
        let path = dir.join(name);
        if !force && path.exists() {
            return Err(Error::Output {
                path,
                message: "the file exists; give another --out directory, or --force to replace it"
                    .into(),
            });
        }
        check_output_path(&path)?;
    }
    Ok(())
}

pub fn run(args: Args) -> Result<String, Error> {
    let site = site(&args.site)?;
    let request = Request {
        count: args.count,
        duration: args.duration,
        dt: args.dt,
        seed: args.seed,
        period: args.period,
    };
    request.validate()?;
    let names = file_names(args.count);
    let created = !args.out.exists();
    check_outputs(&args.out, &names, args.force)?;
    let records = records::generate(&site, &request).inspect_err(|_| {
        // A run refused after the directory was made for it (the spectra miss the code's
        // tolerance) leaves nothing behind: remove the directory again, if still empty.
        if created {
            let _ = std::fs::remove_dir(&args.out);
        }
    })?;
    let sp = &records.spectrum;
    let describe = format!(
        "ag = {:.4} g, soil {}, topography {}, F0 = {:.3}, Tc* = {:.3} s; S = {:.3}, TB = {:.3} s, TC = {:.3} s, TD = {:.3} s",
        site.ag,
        site.soil.as_str(),
        site.topography.as_str(),
        site.f0,
        site.tc_star,
        sp.s,
        sp.tb,
        sp.tc,
        sp.td
    );
    let mut out = String::new();
    let _ = writeln!(
        out,
        "Artificial records for the NTC 2018 elastic spectrum (5 % damping): {describe}"
    );
    let _ = writeln!(
        out,
        "{} records of {} s every {} s, seed {} (docs/records.md)",
        args.count, args.duration, args.dt, args.seed
    );
    for (k, accel) in records.accel.iter().enumerate() {
        let title = format!(
            "voussoir records {}/{}, seed {}: NTC 2018 spectrum, {describe}",
            k + 1,
            args.count,
            args.seed
        );
        let path = args.out.join(&names[k]);
        write_text(&path, &records::at2_text(accel, args.dt, &title))?;
        let pga = accel.iter().fold(0.0_f64, |m, a| m.max(a.abs())) / G;
        let _ = writeln!(out, "  {}  PGA {:.4} g", path.display(), pga);
    }
    let csv_path = args.out.join(&names[args.count]);
    write_text(&csv_path, &spectra_csv(&records))?;
    let _ = writeln!(
        out,
        "  {}  the spectra at {} periods",
        csv_path.display(),
        records.periods.len()
    );
    let (lo, hi) = (records.worst_low, records.worst_high);
    let _ = writeln!(
        out,
        "Check (NTC 2018 §3.2.3.6, {:.2}-{:.2} s): mean spectrum / target from {:.3} (T = {:.3} s) to {:.3} (T = {:.3} s); at most 10 % below: met",
        records.range.0, records.range.1, lo.1, lo.0, hi.1, hi.0
    );
    if args.duration < records::CODE_DURATION {
        let _ = writeln!(
            out,
            "Note: {} s is shorter than the 25 s NTC 2018 §3.2.3.6 asks for when no specific study sets the duration",
            args.duration
        );
    }
    Ok(out)
}

/// The check as a table: period, target, mean, then each record (m/s^2).
fn spectra_csv(records: &records::Records) -> String {
    let mut s = String::from("period_s,target_m_s2,mean_m_s2,mean_over_target");
    for k in 1..=records.each.len() {
        let _ = write!(s, ",record_{k:02}_m_s2");
    }
    s.push('\n');
    for (i, t) in records.periods.iter().enumerate() {
        let _ = write!(
            s,
            "{t:.6},{:.6},{:.6},{:.6}",
            records.target[i],
            records.mean[i],
            records.mean[i] / records.target[i]
        );
        for each in &records.each {
            let _ = write!(s, ",{:.6}", each[i]);
        }
        s.push('\n');
    }
    s
}
