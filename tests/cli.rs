//! End-to-end runs of the `voussoir` binary.

mod common;
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
