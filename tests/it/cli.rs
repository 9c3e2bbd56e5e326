//! End-to-end runs of the `voussoir` binary.

use crate::common;
use common::{data, voussoir};

#[test]
fn analyze_prints_a_summary() {
    let out = voussoir()
        .arg("analyze")
        .arg(data("semicircular.toml"))
        .assert()
        .success();
    let text = String::from_utf8_lossy(&out.get_output().stdout).to_string();
    assert!(text.contains("collapse multiplier lambda = 0.14"), "{text}");
    assert!(text.contains("intrados") && text.contains("extrados"));
}

#[test]
fn analyze_json_has_the_contract_fields() {
    for scene in [
        "semicircular.toml",
        "segmental.toml",
        "pointed.toml",
        "basket.toml",
        "portal.toml",
    ] {
        let out = voussoir()
            .arg("analyze")
            .arg(data(scene))
            .arg("--json")
            .assert()
            .success();
        let v: serde_json::Value = serde_json::from_slice(&out.get_output().stdout).expect("JSON");
        for key in [
            "status",
            "lambda_lower",
            "hinges",
            "sliding",
            "joints",
            "mechanism",
            "equilibrium_residual",
            "blocks",
            "solve_time_s",
        ] {
            assert!(v.get(key).is_some(), "{scene}: missing {key}");
        }
        assert_eq!(v["status"], "collapse");
        let l = v["lambda_lower"].as_f64().expect("number");
        assert!(l > 0.0 && l < 1.0);
        let j = &v["joints"][0];
        for key in ["index", "p1", "p2", "N", "V", "M", "e"] {
            assert!(j.get(key).is_some(), "{scene}: joint lacks {key}");
        }
        let h = &v["hinges"][0];
        assert!(h["end"] == "p1" || h["end"] == "p2");
        assert_eq!(
            v["mechanism"].as_array().map(|a| a.len()),
            v["blocks"].as_u64().map(|n| n as usize)
        );
    }
}

#[test]
fn set_overrides_and_statuses_reach_the_json() {
    let out = voussoir()
        .args(["analyze", "--json", "--set", "arch.thickness=0.08"])
        .arg(data("semicircular.toml"))
        .assert()
        .success();
    let v: serde_json::Value = serde_json::from_slice(&out.get_output().stdout).expect("JSON");
    assert_eq!(v["status"], "cannot_stand");
    assert!(v["lambda_lower"].is_null());
    let out = voussoir()
        .args([
            "analyze",
            "--json",
            "--set",
            "arch.embrace_deg=60",
            "--set",
            "arch.thickness=0.6",
        ])
        .arg(data("semicircular.toml"))
        .assert()
        .success();
    let v: serde_json::Value = serde_json::from_slice(&out.get_output().stdout).expect("JSON");
    assert_eq!(v["status"], "no_collapse");
    assert!(v["lambda_lower"].is_null());
}

/// `--set` values are applied to the file before it is validated, once: an override can
/// mend a file that is invalid on its own (a pointed arch needs an even voussoir count), and
/// the result is the same scene as a valid file with that value.
#[test]
fn set_can_mend_a_file_invalid_on_its_own() {
    let dir = tempfile::tempdir().expect("tempdir");
    let odd = dir.path().join("odd.toml");
    let text = std::fs::read_to_string(data("pointed.toml")).expect("pointed.toml");
    assert!(text.contains("voussoirs = 32"));
    std::fs::write(&odd, text.replace("voussoirs = 32", "voussoirs = 33")).expect("write");
    let err = voussoir().arg("analyze").arg(&odd).assert().failure();
    let err = String::from_utf8_lossy(&err.get_output().stderr).to_string();
    assert!(
        err.contains("arch.voussoirs") && err.contains("even"),
        "{err}"
    );
    let lambda = |file: &std::path::Path, set: &[&str]| -> serde_json::Value {
        let mut cmd = voussoir();
        cmd.arg("analyze").arg(file).arg("--json");
        for s in set {
            cmd.args(["--set", s]);
        }
        let out = cmd.assert().success();
        let v: serde_json::Value = serde_json::from_slice(&out.get_output().stdout).expect("JSON");
        v["lambda_lower"].clone()
    };
    let mended = lambda(&odd, &["arch.voussoirs=12"]);
    let valid = lambda(
        std::path::Path::new(&data("pointed.toml")),
        &["arch.voussoirs=12"],
    );
    assert!(mended.as_f64().is_some_and(|l| l > 0.0), "{mended}");
    assert_eq!(mended, valid);
}

#[test]
fn thrust_csv_has_a_row_per_joint() {
    let dir = tempfile::tempdir().expect("tempdir");
    let csv = dir.path().join("thrust.csv");
    voussoir()
        .arg("analyze")
        .arg(data("portal.toml"))
        .arg("--thrust-csv")
        .arg(&csv)
        .assert()
        .success();
    let text = std::fs::read_to_string(&csv).expect("written");
    let lines: Vec<&str> = text.lines().collect();
    assert!(lines[0].starts_with("joint,kind,x,y,N,V,M,e"));
    assert_eq!(lines.len(), 1 + 41);
}

#[test]
fn min_thickness_json() {
    let out = voussoir()
        .args(["min-thickness", "--json", "--set", "arch.voussoirs=64"])
        .arg(data("semicircular.toml"))
        .assert()
        .success();
    let v: serde_json::Value = serde_json::from_slice(&out.get_output().stdout).expect("JSON");
    let t = v["min_thickness"].as_f64().expect("number");
    assert!((t - 0.1075).abs() < 3e-4, "{t}");
    assert!((v["safety_factor"].as_f64().expect("number") - 0.15 / t).abs() < 1e-9);
    assert_eq!(v["hinges"].as_array().map(|a| a.len()), Some(5));
}

#[test]
fn errors_go_to_stderr_with_nothing_on_stdout() {
    for args in [
        vec!["analyze".to_string(), "no/such/scene.toml".to_string()],
        vec![
            "analyze".to_string(),
            data("semicircular.toml").display().to_string(),
            "--set".into(),
            "arch.thickness=-1".into(),
        ],
        vec![
            "analyze".to_string(),
            data("semicircular.toml").display().to_string(),
            "--set".into(),
            "arch.bogus=1".into(),
        ],
    ] {
        let out = voussoir().args(&args).assert().failure();
        let o = out.get_output();
        assert!(o.stdout.is_empty(), "{args:?}");
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(err.starts_with("error: "), "{err}");
        assert_eq!(err.trim_end().lines().count(), 1, "{err}");
    }
}

#[test]
fn svg_outputs_are_written_and_parse() {
    let dir = tempfile::tempdir().expect("tempdir");
    let a = dir.path().join("a.svg");
    let m = dir.path().join("m.svg");
    let s = dir.path().join("s.svg");
    let c = dir.path().join("s.csv");
    voussoir()
        .arg("analyze")
        .arg(data("portal.toml"))
        .arg("--svg")
        .arg(&a)
        .assert()
        .success();
    voussoir()
        .args(["min-thickness", "--set", "arch.voussoirs=16", "--svg"])
        .arg(&m)
        .arg(data("semicircular.toml"))
        .assert()
        .success();
    voussoir()
        .args([
            "sweep",
            "--vary",
            "t/R=0.12:0.2:0.04",
            "--vary",
            "arch.voussoirs=8,16",
            "--x",
            "t/R",
            "--series",
            "arch.voussoirs",
            "--svg",
        ])
        .arg(&s)
        .arg("--csv")
        .arg(&c)
        .arg(data("semicircular.toml"))
        .assert()
        .success();
    for f in [&a, &m, &s] {
        let text = std::fs::read_to_string(f).expect("written");
        roxmltree::Document::parse(&text).expect("well-formed SVG");
    }
    assert_eq!(
        std::fs::read_to_string(&c).expect("csv").lines().count(),
        1 + 6
    );
    // A bad --x is refused before anything is solved or written.
    let bad = dir.path().join("bad.svg");
    voussoir()
        .args([
            "sweep",
            "--vary",
            "t/R=0.12,0.2",
            "--x",
            "nonsense",
            "--svg",
        ])
        .arg(&bad)
        .arg(data("semicircular.toml"))
        .assert()
        .failure();
    assert!(!bad.exists());
}

#[test]
fn analyze_json_reports_both_bounds_and_the_continuous_model() {
    let out = voussoir()
        .args(["analyze", "--json", "--continuous"])
        .arg(data("portal.toml"))
        .assert()
        .success();
    let v: serde_json::Value = serde_json::from_slice(&out.get_output().stdout).expect("JSON");
    for key in [
        "lambda_upper",
        "gap",
        "mechanism_hinges",
        "open_joints",
        "sliding_governs",
        "lambda_continuous",
        "continuous_hinges",
    ] {
        assert!(v.get(key).is_some(), "missing {key}");
    }
    let (l, u) = (
        v["lambda_lower"].as_f64().expect("l"),
        v["lambda_upper"].as_f64().expect("u"),
    );
    assert!((l - u).abs() <= 1e-6 * l.max(1.0), "{l} vs {u}");
    assert_eq!(v["sliding_governs"], false);
    assert_eq!(v["hinges"], v["mechanism_hinges"]);
    let c = v["lambda_continuous"].as_f64().expect("continuous");
    assert!(c > 0.0 && c <= u * (1.0 + 1e-9) + 5e-3, "{c} vs {u}");
    // Without the flag the continuous fields are absent, the others stay.
    let out = voussoir()
        .args(["analyze", "--json"])
        .arg(data("pointed.toml"))
        .assert()
        .success();
    let v: serde_json::Value = serde_json::from_slice(&out.get_output().stdout).expect("JSON");
    assert!(v.get("lambda_continuous").is_none());
    assert!(v.get("lambda_upper").is_some());
}

#[test]
fn friction_makes_sliding_govern_in_the_json() {
    let out = voussoir()
        .args(["analyze", "--json", "--set", "material.friction=0.3"])
        .arg(data("segmental.toml"))
        .assert()
        .success();
    let v: serde_json::Value = serde_json::from_slice(&out.get_output().stdout).expect("JSON");
    assert_eq!(v["sliding_governs"], true);
    assert!(v["lambda_lower"].as_f64().expect("l") < v["lambda_upper"].as_f64().expect("u"));
    assert!(!v["sliding"].as_array().expect("array").is_empty());
}

#[test]
fn dem_json_brackets_the_static_bound() {
    let out = voussoir()
        .args(["dem", "--json", "--set", "arch.voussoirs=16"])
        .arg(data("semicircular.toml"))
        .assert()
        .success();
    let v: serde_json::Value = serde_json::from_slice(&out.get_output().stdout).expect("JSON");
    for key in [
        "lambda_stands",
        "lambda_collapses",
        "lambda_dem",
        "lambda_lower",
        "relative_difference",
        "steps",
        "wall_time_s",
    ] {
        assert!(v.get(key).is_some(), "missing {key}");
    }
    let a = v["lambda_stands"].as_f64().expect("stands");
    let b = v["lambda_collapses"].as_f64().expect("collapses");
    let l = v["lambda_lower"].as_f64().expect("lower");
    assert!(a < b && (b - a) <= 0.011 * b, "[{a}, {b}]");
    assert!((v["lambda_dem"].as_f64().expect("dem") - l).abs() <= 0.05 * l);
}

#[test]
fn unknown_dem_keys_are_rejected_by_every_command() {
    let out = voussoir()
        .args(["analyze", "--set", "dem.bogus=1"])
        .arg(data("semicircular.toml"))
        .assert()
        .failure();
    assert!(String::from_utf8_lossy(&out.get_output().stderr).contains("dem.bogus"));
}

#[test]
fn a_scene_key_typo_names_the_key_and_suggests_the_right_one() {
    let dir = tempfile::tempdir().expect("tempdir");
    let scene = dir.path().join("typo.toml");
    std::fs::write(
        &scene,
        "[arch]\nshape = \"circular\"\nradius = 1.0\nthicknes = 0.2\nvoussoirs = 8\n",
    )
    .expect("written");
    let out = voussoir().arg("analyze").arg(&scene).assert().failure();
    let o = out.get_output();
    assert!(o.stdout.is_empty());
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains("unknown key `arch.thicknes` (did you mean `thickness`?)"),
        "{err}"
    );
    assert!(!err.contains("missing required key"), "{err}");
    assert_eq!(err.trim_end().lines().count(), 1, "{err}");
}

/// The stderr of a run that must fail, with nothing on stdout.
fn failure(args: &[&str], extra: &[&std::path::Path]) -> String {
    let out = voussoir().args(args).args(extra).assert().failure();
    let o = out.get_output();
    assert!(o.stdout.is_empty(), "{args:?}");
    let err = String::from_utf8_lossy(&o.stderr).to_string();
    assert!(err.starts_with("error: "), "{err}");
    assert_eq!(err.trim_end().lines().count(), 1, "{err}");
    err
}

#[test]
fn sweep_refuses_values_that_are_not_numbers_before_solving() {
    let scene = data("semicircular.toml");
    for (vary, key, value) in [
        ("t/R=0.1,abc", "t/R", "abc"),
        ("arch.thickness=0.1,abc", "arch.thickness", "abc"),
        ("arch.voussoirs=8,8.5", "arch.voussoirs", "8.5"),
        ("e/R=zero", "e/R", "zero"),
    ] {
        let err = failure(&["sweep", "--vary", vary], &[&scene]);
        assert!(err.contains("--vary"), "{err}");
        assert!(err.contains(key) && err.contains(value), "{err}");
        assert!(!err.contains("--set"), "{err}");
    }
    // Out-of-range values stay rows with status error; physical statuses stay as they are.
    let out = voussoir()
        .args(["sweep", "--vary", "arch.thickness=0.08,0.15,5"])
        .arg(&scene)
        .assert()
        .success();
    let text = String::from_utf8_lossy(&out.get_output().stdout).to_string();
    let statuses: Vec<&str> = text
        .lines()
        .skip(1)
        .map(|l| l.split(',').nth(1).unwrap_or(""))
        .collect();
    assert_eq!(statuses, ["cannot_stand", "collapse", "error"], "{text}");
}

#[test]
fn sweep_chart_options_are_checked_before_solving() {
    let dir = tempfile::tempdir().expect("tempdir");
    let scene = data("semicircular.toml");
    let svg = dir.path().join("c.svg");
    // A ratio that does not change in the sweep (e/R of a semicircle is 0 in every case).
    let err = failure(
        &["sweep", "--vary", "t/R=0.1,0.2", "--x", "e/R", "--svg"],
        &[&svg, &scene],
    );
    assert!(
        err.contains("--x e/R") && err.contains("does not vary"),
        "{err}"
    );
    // A ratio of keys that are not varied does not vary either.
    let err = failure(
        &[
            "sweep",
            "--vary",
            "arch.voussoirs=8,16",
            "--x",
            "t/R",
            "--svg",
        ],
        &[&svg, &scene],
    );
    assert!(err.contains("--x t/R"), "{err}");
    assert!(!svg.exists());
    // --x and --series need --svg.
    let err = failure(&["sweep", "--vary", "t/R=0.1,0.2", "--x", "t/R"], &[&scene]);
    assert!(err.contains("--x") && err.contains("--svg"), "{err}");
    let err = failure(
        &[
            "sweep",
            "--vary",
            "t/R=0.1,0.2",
            "--vary",
            "arch.voussoirs=8,16",
            "--series",
            "arch.voussoirs",
        ],
        &[&scene],
    );
    assert!(err.contains("--series") && err.contains("--svg"), "{err}");
    // With more than one varied key --svg needs --x.
    let err = failure(
        &[
            "sweep",
            "--vary",
            "t/R=0.1,0.2",
            "--vary",
            "arch.voussoirs=8,16",
            "--svg",
        ],
        &[&svg, &scene],
    );
    assert!(err.contains("--x"), "{err}");
    assert!(!svg.exists());
    // A ratio the varied keys change is a valid axis.
    voussoir()
        .args([
            "sweep",
            "--vary",
            "arch.radius=1,1.5",
            "--x",
            "t/R",
            "--svg",
        ])
        .arg(&svg)
        .arg(&scene)
        .assert()
        .success();
    assert!(svg.exists());
    std::fs::remove_file(&svg).expect("removed");
    // With one varied key --x defaults to it.
    voussoir()
        .args(["sweep", "--vary", "t/R=0.12:0.2:0.04", "--svg"])
        .arg(&svg)
        .arg(&scene)
        .assert()
        .success();
    let text = std::fs::read_to_string(&svg).expect("written");
    let doc = roxmltree::Document::parse(&text).expect("well-formed SVG");
    let title = doc
        .descendants()
        .find(|n| n.has_tag_name("title"))
        .and_then(|n| n.text())
        .unwrap_or("");
    assert!(title.ends_with("against t/R"), "{title}");
}

#[test]
fn chart_errors_speak_of_the_chart_options_not_of_set() {
    let dir = tempfile::tempdir().expect("tempdir");
    let scene = data("semicircular.toml");
    let svg = dir.path().join("c.svg");
    let err = failure(
        &[
            "sweep",
            "--vary",
            "t/R=0.1,0.2",
            "--vary",
            "arch.voussoirs=8,16",
            "--x",
            "arch.thickness",
            "--svg",
        ],
        &[&svg, &scene],
    );
    assert!(err.starts_with("error: --x arch.thickness: "), "{err}");
    assert!(!err.contains("--set"), "{err}");
    let err = failure(
        &[
            "sweep",
            "--vary",
            "t/R=0.1,0.2",
            "--vary",
            "arch.voussoirs=8,16",
            "--x",
            "t/R",
            "--series",
            "arch.radius",
            "--svg",
        ],
        &[&svg, &scene],
    );
    assert!(err.starts_with("error: --series arch.radius: "), "{err}");
    assert!(!err.contains("--set"), "{err}");
}

#[test]
fn unwritable_outputs_are_refused_before_solving() {
    let dir = tempfile::tempdir().expect("tempdir");
    let scene = data("semicircular.toml");
    let svg = dir.path().join("c.svg");
    let missing = dir.path().join("no/such/dir/out.csv");
    // sweep: the chart would be written after solving and before the CSV; it is not.
    let err = failure(
        &["sweep", "--vary", "t/R=0.1,0.2", "--svg"],
        &[&svg, std::path::Path::new("--csv"), &missing, &scene],
    );
    assert!(
        err.contains("cannot write") && err.contains("out.csv"),
        "{err}"
    );
    assert!(!svg.exists());
    let err = failure(
        &["sweep", "--vary", "t/R=0.1,0.2", "--svg"],
        &[dir.path(), &scene],
    );
    assert!(
        err.contains("cannot write") && err.contains("directory"),
        "{err}"
    );
    // convergence: refused at once (the refinement alone takes seconds).
    let start = std::time::Instant::now();
    let err = failure(
        &["convergence", "--no-dem", "--svg"],
        &[&svg, std::path::Path::new("--csv"), &missing, &scene],
    );
    assert!(
        err.contains("cannot write") && err.contains("out.csv"),
        "{err}"
    );
    assert!(!svg.exists());
    assert!(start.elapsed().as_secs_f64() < 5.0);
    // study: an --out that is a file cannot hold the outputs.
    let file = dir.path().join("a-file");
    std::fs::write(&file, "x").expect("written");
    let study =
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("data/studies/circular_embrace.toml");
    let err = failure(&["study", "--reduced", "--out"], &[&file, &study]);
    assert!(err.contains("cannot write"), "{err}");
    // A file named as the old fixed temporary file was does not stop a run and is not
    // touched (it is the user's), and the check leaves no file behind.
    let ok = dir.path().join("ok.csv");
    std::fs::write(dir.path().join("ok.voussoir-tmp"), "old").expect("written");
    voussoir()
        .args(["sweep", "--vary", "t/R=0.1,0.2", "--csv"])
        .arg(&ok)
        .arg(&scene)
        .assert()
        .success();
    assert!(ok.exists());
    assert_eq!(
        std::fs::read_to_string(dir.path().join("ok.voussoir-tmp")).expect("kept"),
        "old"
    );
}

#[test]
fn sweep_help_lists_every_ratio() {
    let out = voussoir().args(["sweep", "--help"]).assert().success();
    let help = String::from_utf8_lossy(&out.get_output().stdout).to_string();
    for section in ["--vary", "--x"] {
        // The help of the option: from its name to the next option.
        let start = help.find(&format!("  {section} ")).expect("option listed");
        let rest = &help[start + 2..];
        let end = rest[2..].find("\n  -").map_or(rest.len(), |e| e + 2);
        let words: Vec<&str> = rest[..end]
            .split(|c: char| c.is_whitespace() || ",;:()".contains(c))
            .collect();
        for ratio in voussoir::sweep::DERIVED_KEYS {
            assert!(
                words.contains(ratio),
                "{section} help lacks {ratio}:\n{help}"
            );
        }
    }
}

#[test]
fn sweep_dem_times_the_dem_in_its_own_column() {
    let out = voussoir()
        .args([
            "sweep",
            "--dem",
            "--vary",
            "t/R=0.15",
            "--set",
            "arch.voussoirs=8",
        ])
        .arg(data("semicircular.toml"))
        .assert()
        .success();
    let text = String::from_utf8_lossy(&out.get_output().stdout).to_string();
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().expect("header").split(',').collect();
    let row: Vec<&str> = lines.next().expect("row").split(',').collect();
    let col = |name: &str| {
        header
            .iter()
            .position(|h| *h == name)
            .unwrap_or_else(|| panic!("no column {name}: {header:?}"))
    };
    // Columns are added, never renamed: dem_time_s right after lambda_dem.
    assert_eq!(col("dem_time_s"), col("lambda_dem") + 1);
    assert_eq!(col("solve_time_s"), col("hinges") + 1);
    let num = |name: &str| -> f64 { row[col(name)].parse().expect("a number") };
    assert!(num("lambda_dem") > 0.0);
    // The DEM's own bracket (issue 15): its ends, width and whether the static bound lies in it.
    assert_eq!(col("lambda_dem_low"), col("dem_time_s") + 1);
    let (lo, hi, mid) = (
        num("lambda_dem_low"),
        num("lambda_dem_high"),
        num("lambda_dem"),
    );
    assert!(lo < mid && mid < hi, "[{lo}, {hi}] {mid}");
    assert!((num("dem_bracket_width") - (hi - lo) / mid).abs() < 1e-9);
    let l = num("lambda_lower");
    let inside = num("static_inside_dem_bracket");
    assert_eq!(inside, if lo <= l && l <= hi { 1.0 } else { 0.0 });
    // The DEM (thousands of time steps) takes far longer than the static and kinematic
    // analyses of 8 voussoirs; solve_time_s no longer includes it.
    assert!(
        num("solve_time_s") < num("dem_time_s"),
        "{} vs {}",
        num("solve_time_s"),
        num("dem_time_s")
    );
}

#[test]
fn sweep_chart_title_and_legend_read_as_words() {
    let dir = tempfile::tempdir().expect("tempdir");
    let svg = dir.path().join("e.svg");
    voussoir()
        .args([
            "sweep",
            "--vary",
            "arch.embrace_deg=120,150,180",
            "--vary",
            "t/R=0.12:0.2:0.04",
            "--x",
            "t/R",
            "--svg",
        ])
        .arg(&svg)
        .arg(data("semicircular.toml"))
        .assert()
        .success();
    let text = std::fs::read_to_string(&svg).expect("written");
    let doc = roxmltree::Document::parse(&text).expect("well-formed SVG");
    let texts: Vec<String> = doc
        .descendants()
        .filter(|n| n.has_tag_name("text"))
        .filter_map(|n| n.text().map(|t| t.trim().to_string()))
        .collect();
    assert!(
        texts.iter().any(|t| t.starts_with("circular arch:")),
        "{texts:?}"
    );
    assert!(!text.contains("semicircular"), "{texts:?}");
    assert!(texts.iter().any(|t| t == "embrace (deg)"), "{texts:?}");
    assert!(
        !texts.iter().any(|t| t.contains("arch.embrace_deg")),
        "{texts:?}"
    );
    // A thickness axis has its unit; the semicircle keeps its own title when its shape does
    // not change.
    voussoir()
        .args(["sweep", "--vary", "arch.thickness=0.12,0.15", "--svg"])
        .arg(&svg)
        .arg(data("semicircular.toml"))
        .assert()
        .success();
    let text = std::fs::read_to_string(&svg).expect("written");
    assert!(text.contains("thickness t (m)"), "{text}");
    assert!(text.contains("semicircular arch:"), "{text}");
}

/// A scene file and a CSV blocks file it reads, copied into a fresh directory.
fn scene_dir() -> (tempfile::TempDir, std::path::PathBuf, std::path::PathBuf) {
    let dir = tempfile::tempdir().expect("tempdir");
    let scene = dir.path().join("scene.toml");
    std::fs::copy(data("semicircular.toml"), &scene).expect("copy");
    let blocks = dir.path().join("column.csv");
    std::fs::write(
        &blocks,
        "block,x,y\na,0,0\na,1,0\na,1,1\na,0,1\nb,0,1\nb,1,1\nb,1,2\nb,0,2\n",
    )
    .expect("write");
    std::fs::write(
        dir.path().join("blocks.toml"),
        "[blocks]\nfile = \"column.csv\"\n",
    )
    .expect("write");
    (dir, scene, blocks)
}

fn stderr_of(out: &assert_cmd::assert::Assert) -> String {
    String::from_utf8_lossy(&out.get_output().stderr).to_string()
}

#[test]
fn an_output_on_an_input_is_refused_and_the_input_kept() {
    let (dir, scene, blocks) = scene_dir();
    let before = std::fs::read(&scene).expect("read");
    let blocks_before = std::fs::read(&blocks).expect("read");
    let other_spelling = dir.path().join(".").join("scene.toml");
    for args in [
        vec![
            "analyze".into(),
            scene.clone(),
            "--svg".into(),
            scene.clone(),
        ],
        vec![
            "analyze".into(),
            scene.clone(),
            "--thrust-csv".into(),
            other_spelling,
        ],
        vec![
            "sweep".into(),
            scene.clone(),
            "--vary".into(),
            "arch.thickness=0.1,0.2".into(),
            "--csv".into(),
            scene.clone(),
        ],
        vec![
            "min-thickness".into(),
            scene.clone(),
            "--svg".into(),
            scene.clone(),
        ],
    ] {
        let out = voussoir().args(&args).assert().failure();
        let e = stderr_of(&out);
        assert!(
            e.contains("would overwrite the scene file") && e.contains("an input"),
            "{args:?}: {e}"
        );
    }
    // The blocks file the scene reads, written by the name the scene gives it.
    let blocks_scene = dir.path().join("blocks.toml");
    let out = voussoir()
        .arg("analyze")
        .arg(&blocks_scene)
        .arg("--thrust-csv")
        .arg(dir.path().join("column.csv"))
        .assert()
        .failure();
    let e = stderr_of(&out);
    assert!(e.contains("would overwrite the scene's blocks file"), "{e}");
    assert_eq!(std::fs::read(&scene).expect("read"), before);
    assert_eq!(std::fs::read(&blocks).expect("read"), blocks_before);
}

#[test]
fn two_outputs_on_one_file_are_refused_before_any_work() {
    let (dir, scene, _) = scene_dir();
    std::fs::create_dir(dir.path().join("sub")).expect("dir");
    let x = dir.path().join("x.svg");
    let out = voussoir()
        .arg("analyze")
        .arg(&scene)
        .arg("--svg")
        .arg(&x)
        .arg("--thrust-csv")
        .arg(dir.path().join("sub/../x.svg"))
        .assert()
        .failure();
    let e = stderr_of(&out);
    assert!(
        e.contains("--thrust-csv and --svg both name this file"),
        "{e}"
    );
    assert!(!x.exists());
}

#[test]
fn an_output_named_for_another_format_is_refused() {
    let (dir, scene, _) = scene_dir();
    let png = dir.path().join("out.png");
    let out = voussoir()
        .arg("analyze")
        .arg(&scene)
        .arg("--svg")
        .arg(&png)
        .assert()
        .failure();
    let e = stderr_of(&out);
    assert!(
        e.contains("--svg writes an SVG drawing, not a .png file") && e.contains(".svg"),
        "{e}"
    );
    assert!(!png.exists());
    let out = voussoir()
        .args(["sweep", "--vary", "arch.thickness=0.1,0.2", "--csv"])
        .arg(dir.path().join("rows.txt"))
        .arg(&scene)
        .assert()
        .failure();
    assert!(stderr_of(&out).contains("--csv writes a CSV table"));
    // The extension in any case.
    let upper = dir.path().join("OUT.SVG");
    voussoir()
        .arg("analyze")
        .arg(&scene)
        .arg("--svg")
        .arg(&upper)
        .assert()
        .success();
    let text = std::fs::read_to_string(&upper).expect("written");
    assert!(text.contains("<svg"), "an SVG drawing");
}

#[test]
fn outputs_replace_files_whole_and_touch_no_file_of_the_user() {
    let (dir, scene, _) = scene_dir();
    // A file of the user's with the name the old fixed temporary file had.
    let theirs = dir.path().join("out.voussoir-tmp");
    std::fs::write(&theirs, "keep me").expect("write");
    let svg = dir.path().join("out.svg");
    std::fs::write(&svg, "old").expect("write");
    voussoir()
        .arg("analyze")
        .arg(&scene)
        .arg("--svg")
        .arg(&svg)
        .assert()
        .success();
    assert!(std::fs::read_to_string(&svg)
        .expect("read")
        .contains("<svg"));
    assert_eq!(std::fs::read_to_string(&theirs).expect("read"), "keep me");
    // No temporary file is left beside them.
    let mut names: Vec<String> = std::fs::read_dir(dir.path())
        .expect("dir")
        .map(|e| e.expect("entry").file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    assert_eq!(
        names,
        [
            "blocks.toml",
            "column.csv",
            "out.svg",
            "out.voussoir-tmp",
            "scene.toml"
        ]
    );
}

/// A CSV file of `n` unit blocks in courses of 10 (running bond) and a scene reading it.
fn wall(dir: &std::path::Path, n: usize) -> std::path::PathBuf {
    let mut csv = String::from("block,x,y\n");
    let mut b = 0;
    let mut course = 0;
    while b < n {
        let (y0, y1) = (course as f64, course as f64 + 1.0);
        let mut xs: Vec<f64> = (0..=10).map(|k| k as f64).collect();
        if course % 2 == 1 {
            xs = std::iter::once(0.0)
                .chain((0..10).map(|k| k as f64 + 0.5))
                .chain(std::iter::once(10.0))
                .collect();
            xs.dedup();
        }
        for w in xs.windows(2) {
            if b == n {
                break;
            }
            for (x, y) in [(w[0], y0), (w[1], y0), (w[1], y1), (w[0], y1)] {
                csv.push_str(&format!("b{b},{x},{y}\n"));
            }
            b += 1;
        }
        course += 1;
    }
    std::fs::write(dir.join(format!("wall{n}.csv")), csv).expect("write");
    let scene = dir.join(format!("wall{n}.toml"));
    std::fs::write(&scene, format!("[blocks]\nfile = \"wall{n}.csv\"\n")).expect("write");
    scene
}

#[test]
fn the_number_of_user_blocks_is_bounded_and_the_bound_can_be_lifted() {
    let dir = tempfile::tempdir().expect("tempdir");
    // One block over the default: refused at once, with the way to lift the limit.
    let big = wall(dir.path(), 10_001);
    let out = voussoir().arg("analyze").arg(&big).assert().failure();
    let e = stderr_of(&out);
    assert!(
        e.contains("(10001 blocks)")
            && e.contains("more than the 10000 blocks a command takes by default")
            && e.contains("--max-blocks 10001"),
        "{e}"
    );
    // A small wall under a lowered limit, then lifted.
    let small = wall(dir.path(), 25);
    let out = voussoir()
        .args(["analyze", "--max-blocks", "20"])
        .arg(&small)
        .assert()
        .failure();
    assert!(stderr_of(&out).contains("more than the 20 blocks a command takes;"));
    voussoir()
        .args(["analyze", "--max-blocks", "25"])
        .arg(&small)
        .assert()
        .success();
    let out = voussoir()
        .args(["analyze", "--max-blocks", "100001"])
        .arg(&small)
        .assert()
        .failure();
    assert!(stderr_of(&out).contains("at most 100000"));
}
