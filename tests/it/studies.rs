//! The parametric studies of `data/studies/` (the charts of `docs/studies.md`), each run
//! reduced to three values per varied key: every file loads and runs, its rows and chart
//! are complete and consistent, and the physical trends the full studies show hold.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use voussoir::drawing::chart::{chart_svg, Chart};
use voussoir::study::{Baseline, Study};
use voussoir::sweep::SweepRow;

fn study_files() -> Vec<PathBuf> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("data/studies");
    let mut files: Vec<PathBuf> = std::fs::read_dir(&dir)
        .expect("data/studies exists")
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x == "toml"))
        .collect();
    files.sort();
    files
}

fn load(name: &str) -> Study {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("data/studies")
        .join(format!("{name}.toml"));
    Study::from_file(&path).unwrap_or_else(|e| panic!("{name}: {e}"))
}

fn run(study: &Study) -> (Vec<SweepRow>, Chart) {
    let rows = study
        .run(&|| {})
        .unwrap_or_else(|e| panic!("{}: {e}", study.output));
    let chart = voussoir::report::figures::study_chart(study, &rows)
        .unwrap_or_else(|e| panic!("{}: {e}", study.output));
    (rows, chart)
}

fn extra(row: &SweepRow, name: &str) -> Option<f64> {
    row.extra
        .iter()
        .find(|(n, _)| *n == name)
        .and_then(|(_, v)| *v)
}

/// `lambda_lower` by (series value, x value) for a study with one series key and one x key,
/// both varied; `None` where the arch cannot stand.
fn table(study: &Study, rows: &[SweepRow]) -> BTreeMap<(String, String), Option<f64>> {
    let xi = study
        .variations
        .iter()
        .position(|v| v.key == study.x)
        .expect("x is varied");
    let si = 1 - xi;
    rows.iter()
        .map(|r| {
            (
                (r.values[si].to_string(), r.values[xi].to_string()),
                r.lambda_lower,
            )
        })
        .collect()
}

/// The `lambda_lower` of the case with `series = s` and `x = x`.
fn at(t: &BTreeMap<(String, String), Option<f64>>, s: &str, x: &str) -> Option<f64> {
    *t.get(&(s.to_string(), x.to_string()))
        .unwrap_or_else(|| panic!("no case {s}, {x}"))
}

#[test]
fn every_study_runs_reduced_with_complete_rows_and_chart() {
    let files = study_files();
    assert!(files.len() >= 9, "{files:?}");
    let mut outputs = Vec::new();
    for path in &files {
        let study = Study::from_file(path)
            .unwrap_or_else(|e| panic!("{}: {e}", path.display()))
            .reduced(3);
        outputs.push(study.output.clone());
        let name = path.display();
        let (rows, chart) = run(&study);
        let expected: usize = study.variations.iter().map(|v| v.values.len()).product();
        assert_eq!(rows.len(), expected, "{name}");
        let cases = voussoir::sweep::cases(&study.scene, &study.variations);
        for (k, r) in rows.iter().enumerate() {
            // Every case is a valid scene: ranges are chosen inside the geometry's limits.
            assert_ne!(r.status, "error", "{name} row {k}: {:?}", r.error);
            match r.status.as_str() {
                "collapse" => {
                    let l = r.lambda_lower.expect("collapse has a multiplier");
                    assert!(l.is_finite() && l >= 0.0, "{name} row {k}: {l}");
                    // The exhaustive kinematic search runs on every study's chain (at most
                    // 200 joints) and closes the bracket.
                    let u = r.lambda_upper.expect("kinematic bound");
                    assert!(
                        (u - l).abs() <= 1e-6 * l.max(1.0),
                        "{name} row {k}: {l} vs {u}"
                    );
                    if study.continuous {
                        // Hinges anywhere in the ring: never above the discrete multiplier
                        // (the curved voussoirs are exact pieces of that ring).
                        let c = extra(r, "lambda_continuous").expect("continuous");
                        assert!(c <= l * (1.0 + 1e-9) + 1e-12, "{name} row {k}: {c} > {l}");
                        assert!(c > 0.95 * l - 0.01, "{name} row {k}: {c} far below {l}");
                    }
                }
                "cannot_stand" => assert!(r.lambda_lower.is_none(), "{name} row {k}"),
                other => panic!("{name} row {k}: unexpected status {other}"),
            }
            if let Some(b) = study.baseline {
                let (lb, ratio) = (extra(r, "lambda_baseline"), extra(r, "lambda_ratio"));
                if let (Some(l), Some(lb)) = (r.lambda_lower, lb) {
                    if lb > 0.0 {
                        let q = ratio.expect("ratio");
                        assert!((q - l / lb).abs() <= 1e-12 * q.abs().max(1.0), "{name}");
                    }
                }
                // The baseline scene itself is valid for every case.
                let scene = cases[k].1.as_ref().expect("valid case");
                assert!(b.scene_of(scene).is_ok(), "{name} row {k}");
            }
        }
        // One line per value of the series key, plus the baseline on lambda charts.
        let series_key = study
            .series
            .as_deref()
            .expect("every study names its series");
        let values = &study
            .variations
            .iter()
            .find(|v| v.key == series_key)
            .expect("series is varied")
            .values;
        let extra_line = usize::from(study.baseline.is_some() && !study.plot_ratio);
        assert_eq!(chart.series.len(), values.len() + extra_line, "{name}");
        for (s, v) in chart.series.iter().zip(values) {
            assert_eq!(s.name, v.to_string(), "{name}");
            let xs = study
                .variations
                .iter()
                .find(|v| v.key == study.x)
                .map_or(0, |v| v.values.len());
            assert_eq!(s.points.len(), xs, "{name}: {}", s.name);
            assert!(
                s.points.iter().any(|p| p.1.is_finite()),
                "{name}: series {} has no finite point",
                s.name
            );
        }
        let svg = chart_svg(&chart).expect("chart draws");
        let doc = roxmltree::Document::parse(&svg).expect("well-formed SVG");
        let groups = doc
            .descendants()
            .filter(|n| n.attribute("class") == Some("series"))
            .count();
        assert_eq!(groups, chart.series.len(), "{name}");
    }
    // Output names are distinct: no study overwrites another's figure.
    let mut unique = outputs.clone();
    unique.sort();
    unique.dedup();
    assert_eq!(unique.len(), outputs.len(), "{outputs:?}");
}

/// Thicker arches carry more, and an arch that stands keeps standing when thickened.
#[test]
fn multiplier_grows_with_thickness_in_every_arch_study() {
    for name in [
        "circular_embrace",
        "pointed_equal_radius",
        "pointed_equal_span",
        "basket_equal_span",
    ] {
        let study = load(name).reduced(3);
        let (rows, _) = run(&study);
        let t = table(&study, &rows);
        let mut by_series: BTreeMap<&str, Vec<(f64, Option<f64>)>> = BTreeMap::new();
        for ((s, x), l) in &t {
            by_series
                .entry(s)
                .or_default()
                .push((x.parse().expect("number"), *l));
        }
        for (s, mut pts) in by_series {
            pts.sort_by(|a, b| a.0.total_cmp(&b.0));
            // The thickest case of every series stands (the ranges are chosen so).
            assert!(pts.last().is_some_and(|p| p.1.is_some()), "{name} {s}");
            for w in pts.windows(2) {
                match (w[0].1, w[1].1) {
                    (Some(a), Some(b)) => assert!(b > a, "{name} {s}: {w:?}"),
                    (Some(_), None) => panic!("{name} {s}: stops standing when thicker: {w:?}"),
                    _ => {}
                }
            }
        }
    }
}

/// Embrace: at equal t/R, the deeper the arch (larger embrace), the lower the multiplier.
#[test]
fn circular_multiplier_falls_with_embrace() {
    let study = load("circular_embrace").reduced(3);
    let (rows, _) = run(&study);
    let t = table(&study, &rows);
    // Reduced: embrace 120, 160, 200 and t/R 0.02, 0.16, 0.3.
    let l: Vec<f64> = ["120", "160", "200"]
        .iter()
        .map(|e| at(&t, e, "0.3").expect("stands at t/R = 0.3"))
        .collect();
    assert!(l[0] > l[1] && l[1] > l[2], "{l:?}");
    // The horseshoe cannot stand at t/R = 0.16, the semicircle can (minimum about 0.107).
    assert_eq!(at(&t, "200", "0.16"), None);
    assert!(at(&t, "160", "0.16").is_some());
}

/// The two normalisations of pointed arches: at equal R the pointed arch carries more the
/// more pointed it is; at equal span and thickness (thick arches) it carries less.
#[test]
fn pointed_arches_win_at_equal_radius_and_lose_at_equal_span() {
    let study = load("pointed_equal_radius").reduced(3);
    let (rows, _) = run(&study);
    let t = table(&study, &rows);
    // Reduced: e/R 0, 0.2, 0.5 and t/R 0.04, 0.12, 0.2.
    let r: Vec<f64> = ["0", "0.2", "0.5"]
        .iter()
        .map(|e| at(&t, e, "0.2").expect("stands"))
        .collect();
    assert!(r[0] < r[1] && r[1] < r[2], "equal radius: {r:?}");

    let study = load("pointed_equal_span").reduced(3);
    let (rows, _) = run(&study);
    let t = table(&study, &rows);
    // Reduced: t/span 0.02, 0.07, 0.12.
    let s: Vec<f64> = ["0", "0.2", "0.5"]
        .iter()
        .map(|e| at(&t, e, "0.12").expect("stands"))
        .collect();
    assert!(s[0] > s[1] && s[1] > s[2], "equal span: {s:?}");
    // The same arch in both studies: e/R = 0.5 at t/span = 0.12 has span = R, so t/R = 0.12.
    let same = load("pointed_equal_radius")
        .scene
        .with_override("arch.eccentricity=0.5")
        .and_then(|s| s.with_override("arch.thickness=0.12"))
        .expect("valid");
    let direct = voussoir::statics::analyse(
        &voussoir::scene::build(&same).expect("valid model"),
        &voussoir::statics::StaticSettings::default(),
    )
    .expect("solves")
    .lambda
    .expect("collapse");
    assert!((direct - s[2]).abs() < 1e-9, "{direct} vs {}", s[2]);
}

/// Ratio studies: e/R = 0 is the semicircle itself (ratio 1); the equal-radius ratio grows
/// with the eccentricity; every ratio is positive and finite.
#[test]
fn relative_stability_is_one_for_the_semicircle() {
    for (name, base) in [
        ("pointed_equal_radius_ratio", Baseline::EqualRadius),
        ("pointed_equal_span_ratio", Baseline::EqualSpan),
        ("basket_equal_span_ratio", Baseline::EqualSpan),
    ] {
        let study = load(name).reduced(3);
        assert!(study.plot_ratio, "{name}");
        assert_eq!(study.baseline, Some(base), "{name}");
        let (rows, chart) = run(&study);
        for r in &rows {
            // The ranges start above the semicircle's minimum thickness.
            let lb = extra(r, "lambda_baseline").expect("the baseline stands over the range");
            assert!(lb > 0.0, "{name}");
            if r.lambda_lower.is_some() {
                let q = extra(r, "lambda_ratio").expect("ratio");
                assert!(q.is_finite() && q > 0.0, "{name}: {q}");
            }
        }
        if name.starts_with("pointed") {
            let line = chart
                .series
                .iter()
                .find(|s| s.name == "0")
                .expect("e/R = 0");
            for (x, y) in &line.points {
                assert!((y - 1.0).abs() < 1e-6, "{name} at {x}: {y}");
            }
        }
        if name == "pointed_equal_radius_ratio" {
            for k in 0..3 {
                let ys: Vec<f64> = chart.series.iter().map(|s| s.points[k].1).collect();
                assert!(ys.windows(2).all(|w| w[1] > w[0]), "{ys:?}");
            }
        }
    }
    // Lowering a basket arch raises its multiplier at equal span (thick end).
    let study = load("basket_equal_span_ratio").reduced(3);
    let (rows, _) = run(&study);
    let t = table(&study, &rows);
    let l: Vec<f64> = ["0.25", "0.35", "0.45"]
        .iter()
        .map(|f| at(&t, f, "0.12").expect("stands"))
        .collect();
    assert!(l[0] > l[1] && l[1] > l[2], "{l:?}");
}

/// Portals: taller piers carry less, wider piers more; with short piers the arch's own
/// mechanism governs; slender tall piers cannot stand; courses change nothing (the base
/// joint governs a rectangular pier).
#[test]
fn portal_trends() {
    let study = load("portal_pier_width").reduced(3);
    let (rows, _) = run(&study);
    let t = table(&study, &rows);
    // Reduced: b/R 0.2, 0.4, 0.6 and h/R 0.1, 1.5, 3.
    for b in ["0.2", "0.4", "0.6"] {
        let ls: Vec<Option<f64>> = ["0.1", "1.5", "3.0"].iter().map(|h| at(&t, b, h)).collect();
        for w in ls.windows(2) {
            if let (Some(a), Some(c)) = (w[0], w[1]) {
                assert!(c <= a * (1.0 + 1e-9), "b/R = {b}: {ls:?}");
            }
        }
    }
    for h in ["0.1", "1.5", "3.0"] {
        let ls: Vec<Option<f64>> = ["0.2", "0.4", "0.6"].iter().map(|b| at(&t, b, h)).collect();
        for w in ls.windows(2) {
            match (w[0], w[1]) {
                (Some(a), Some(c)) => assert!(c >= a * (1.0 - 1e-9), "h/R = {h}: {ls:?}"),
                (Some(_), None) => panic!("a wider pier stops standing at h/R = {h}: {ls:?}"),
                _ => {}
            }
        }
    }
    assert_eq!(
        at(&t, "0.2", "3.0"),
        None,
        "slender tall piers cannot stand"
    );
    // Short wide piers: the arch governs, as on fixed springings.
    let arch_alone = {
        let mut s = load("portal_pier_width").scene.table().clone();
        s.remove("piers");
        let scene = voussoir::scene::Scene::from_table(s, "arch alone").expect("valid");
        voussoir::statics::analyse(
            &voussoir::scene::build(&scene).expect("valid model"),
            &voussoir::statics::StaticSettings::default(),
        )
        .expect("solves")
        .lambda
        .expect("collapse")
    };
    let short = at(&t, "0.6", "0.1").expect("stands");
    assert!((short - arch_alone).abs() < 1e-7, "{short} vs {arch_alone}");

    let study = load("portal_courses").reduced(3);
    let (rows, _) = run(&study);
    let t = table(&study, &rows);
    // Reduced: courses 1, 2, 8.
    for h in ["0.1", "1.5", "3.0"] {
        let one = at(&t, "1", h).expect("stands");
        for k in ["2", "8"] {
            let l = at(&t, k, h).expect("stands");
            assert!(
                (l - one).abs() < 1e-7 * one.max(1.0),
                "h/R = {h}: {k} courses {l} vs {one}"
            );
        }
    }
}

/// A study's CSV and chart are the same bytes on every run (no wall times), so regenerating
/// the committed figures leaves them unchanged.
#[test]
fn a_study_run_twice_writes_the_same_bytes() {
    let study = Path::new(env!("CARGO_MANIFEST_DIR")).join("data/studies/portal_courses.toml");
    let dirs = [
        tempfile::tempdir().expect("tempdir"),
        tempfile::tempdir().expect("tempdir"),
    ];
    for dir in &dirs {
        assert_cmd::Command::cargo_bin("voussoir")
            .expect("binary built")
            .args(["study", "--reduced", "--out"])
            .arg(dir.path())
            .arg(&study)
            .assert()
            .success();
    }
    for ext in ["csv", "svg"] {
        let read = |d: &tempfile::TempDir| {
            std::fs::read(d.path().join(format!("portal_courses.{ext}"))).expect("written")
        };
        assert_eq!(read(&dirs[0]), read(&dirs[1]), "portal_courses.{ext}");
    }
    let csv =
        String::from_utf8(std::fs::read(dirs[0].path().join("portal_courses.csv")).expect("csv"))
            .expect("utf8");
    let header = csv.lines().next().unwrap_or("");
    assert!(header.contains(",hinges,"), "{header}");
    assert!(!header.contains("time_s"), "{header}");
    assert_eq!(csv.lines().count(), 1 + 9);
}

#[test]
fn study_writes_only_where_it_is_told() {
    let file = Path::new(env!("CARGO_MANIFEST_DIR")).join("data/studies/portal_courses.toml");
    // No --out: refused by the command line, before anything is read or written.
    let out = assert_cmd::Command::cargo_bin("voussoir")
        .expect("binary")
        .arg("study")
        .arg(&file)
        .assert()
        .failure();
    let e = String::from_utf8_lossy(&out.get_output().stderr).to_string();
    assert!(e.contains("--out <DIR>"), "{e}");
    let dir = tempfile::tempdir().expect("tempdir");
    let target = dir.path().join("figures");
    assert_cmd::Command::cargo_bin("voussoir")
        .expect("binary")
        .arg("study")
        .arg(&file)
        .arg("--reduced")
        .arg("--out")
        .arg(&target)
        .assert()
        .success();
    let mut names: Vec<String> = std::fs::read_dir(&target)
        .expect("created")
        .map(|e| e.expect("entry").file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    assert_eq!(names, ["portal_courses.csv", "portal_courses.svg"]);
}

/// The committed figures are what the code computes today: every study run in full, its CSV
/// read cell by cell against `docs/figures/<output>.csv` (statuses and hinges exactly,
/// numbers to 1e-9 relative plus 1e-12, so round-off of another platform passes and a stale
/// figure does not).
#[test]
fn the_committed_study_csvs_are_what_the_code_writes() {
    let figures = Path::new(env!("CARGO_MANIFEST_DIR")).join("docs/figures");
    for path in study_files() {
        let study = Study::from_file(&path).expect("study");
        let (rows, _) = run(&study);
        let mut buf = Vec::new();
        study.write_csv(&mut buf, &rows).expect("csv");
        let committed = std::fs::read(figures.join(format!("{}.csv", study.output)))
            .unwrap_or_else(|e| panic!("{}: {e}", study.output));
        let read = |bytes: &[u8]| -> Vec<Vec<String>> {
            csv::ReaderBuilder::new()
                .has_headers(false)
                .from_reader(bytes)
                .records()
                .map(|r| r.expect("row").iter().map(str::to_string).collect())
                .collect()
        };
        let (now, then) = (read(&buf), read(&committed));
        assert_eq!(now.len(), then.len(), "{}: rows", study.output);
        assert_eq!(now[0], then[0], "{}: columns", study.output);
        for (r, (a, b)) in now.iter().zip(&then).enumerate().skip(1) {
            for (c, (x, y)) in a.iter().zip(b).enumerate() {
                let same = match (x.parse::<f64>(), y.parse::<f64>()) {
                    // `gap` is round-off (1e-15): an absolute floor of 1e-12.
                    (Ok(x), Ok(y)) => (x - y).abs() <= 1e-9 * x.abs().max(y.abs()) + 1e-12,
                    _ => x == y,
                };
                assert!(
                    same,
                    "{} row {r} column {}: now {x}, committed {y} (regenerate: voussoir study {} --out docs/figures)",
                    study.output,
                    now[0][c],
                    path.display()
                );
            }
        }
    }
}
