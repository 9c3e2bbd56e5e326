//! Speed against accuracy: the discrete multiplier converges to the continuous one as the arch
//! is cut finer, the convergence study's rows are consistent, the solver tolerance and the DEM
//! settings behave as documented, and the 1000-voussoir acceptance case (library path; its
//! timing lives in `benches/`).

use crate::common;

use assert_cmd::Command;
use voussoir::analysis::{self, Options};
use voussoir::convergence::{self, loglog_slope, ConvergenceSettings, DemCase};
use voussoir::statics::Status;

fn quiet() -> impl FnMut(&str) {
    |_| {}
}

/// Static and kinematic bounds at n = 8..256 against the continuous model of a semicircle
/// (t/R = 0.15): the discrete arch is stronger (it can only hinge at joints), the errors fall
/// by orders of magnitude and about as n^-2, and the two discrete bounds coincide (rigid
/// blocks, no sliding: the static and kinematic theorems meet).
#[test]
fn discrete_converges_to_continuous() {
    let scene = common::semicircle(0.15, 8);
    let settings = ConvergenceSettings {
        max_voussoirs: 256,
        kinematic_max_joints: 70,
        solver_tolerances: Vec::new(),
        dem: false,
        ..Default::default()
    };
    let c = convergence::run(&scene, &settings, &mut quiet()).expect("study runs");
    let lc = c.lambda_continuous.expect("continuous value");
    // Published value of the continuous semicircle at t/R = 0.15 (e.g. Ochsendorf 2002;
    // DeJong 2009): about 0.1443.
    assert!((lc - 0.1443).abs() < 5e-4, "continuous {lc}");
    let ns: Vec<usize> = c.refinement.iter().map(|r| r.voussoirs).collect();
    assert_eq!(ns, vec![8, 16, 32, 64, 128, 256]);
    for r in &c.refinement {
        assert_eq!(r.status, "collapse", "n = {}", r.voussoirs);
        assert_eq!(r.joints, r.voussoirs + 1);
        let l = r.lambda_lower.expect("lower bound");
        let e = r.error_lower.expect("error");
        assert!((e - (l - lc) / lc).abs() < 1e-15);
        // The discrete arch is stronger than the continuum (up to the solver tolerance).
        assert!(e > -1e-8, "n = {}: error {e}", r.voussoirs);
        assert!(r.lower_time_s > 0.0 && r.lower_iterations > 0);
        if r.joints <= 70 {
            let u = r
                .lambda_upper
                .expect("upper bound where the chain is small");
            assert!((u - l).abs() <= 1e-6 * l, "n = {}: {l} vs {u}", r.voussoirs);
            assert!(r.upper_time_s.is_some());
        } else {
            assert!(r.lambda_upper.is_none());
            assert!(r
                .upper_note
                .as_deref()
                .is_some_and(|s| s.contains("skipped")));
        }
    }
    // Errors shrink with refinement: every quadrupling of n cuts the error by at least 4
    // (the doubling 128 -> 256 need not: a joint may happen to sit on the optimal section).
    let err: Vec<f64> = c
        .refinement
        .iter()
        .map(|r| r.error_lower.unwrap_or(f64::NAN))
        .collect();
    for k in 0..err.len() - 2 {
        assert!(
            err[k + 2] < err[k] / 4.0,
            "n = {} -> {}: {} -> {}",
            ns[k],
            ns[k + 2],
            err[k],
            err[k + 2]
        );
    }
    assert!(err[err.len() - 1] < err[0] / 300.0, "{err:?}");
    let order = c.order_lower.expect("fitted order");
    assert!((-2.7..=-1.6).contains(&order), "order {order}");
}

/// The convergence study's CSV and chart carry the same numbers as its rows.
#[test]
fn csv_and_chart_match_rows() {
    let scene = common::semicircle(0.2, 8);
    let settings = ConvergenceSettings {
        max_voussoirs: 64,
        kinematic_max_joints: 0,
        solver_tolerances: Vec::new(),
        dem: false,
        ..Default::default()
    };
    let c = convergence::run(&scene, &settings, &mut quiet()).expect("study runs");
    assert_eq!(c.refinement.len(), 4);
    let mut buf = Vec::new();
    c.write_csv(&mut buf).expect("csv");
    let mut rd = csv::Reader::from_reader(buf.as_slice());
    let head = rd.headers().expect("header").clone();
    let col = |name: &str| head.iter().position(|h| h == name).expect("column");
    let recs: Vec<csv::StringRecord> = rd.records().map(|r| r.expect("record")).collect();
    assert_eq!(recs.len(), c.refinement.len());
    for (rec, row) in recs.iter().zip(&c.refinement) {
        let n: usize = rec[col("voussoirs")].parse().expect("n");
        assert_eq!(n, row.voussoirs);
        let l: f64 = rec[col("lambda_lower")].parse().expect("lambda");
        assert!((l - row.lambda_lower.expect("lower")).abs() < 1e-9 * l);
        let e: f64 = rec[col("error_lower")].parse().expect("error");
        assert!((e - row.error_lower.expect("error")).abs() < 1e-9 * e.abs());
        assert!(rec[col("lambda_upper")].is_empty());
        assert!(rec[col("note")].contains("turned off"));
    }
    let chart = voussoir::report::figures::convergence_chart(&c, "test");
    assert_eq!(
        chart.series.len(),
        1,
        "no upper-bound series without the search"
    );
    for (&(x, y), row) in chart.series[0].points.iter().zip(&c.refinement) {
        assert!((x - (row.voussoirs as f64).log10()).abs() < 1e-12);
        assert!((y - row.error_lower.expect("error").abs().log10()).abs() < 1e-12);
    }
    let svg = voussoir::drawing::chart::chart_svg(&chart).expect("svg");
    assert!(svg.contains("static lower bound"));
}

/// Clarabel's tolerance is a relative accuracy on lambda (the program is dimensionless): the
/// multiplier at tolerance tol differs from the tightest one by about tol, and tighter
/// tolerances never take fewer iterations.
#[test]
fn solver_tolerance_is_relative_accuracy() {
    let scene = common::semicircle(0.15, 32);
    let settings = ConvergenceSettings {
        max_voussoirs: 8,
        kinematic_max_joints: 0,
        continuous: false,
        dem: false,
        ..Default::default()
    };
    let c = convergence::run(&scene, &settings, &mut quiet()).expect("study runs");
    assert!(c.lambda_continuous.is_none() && c.refinement[0].error_lower.is_none());
    let tols: Vec<f64> = c.tolerances.iter().map(|r| r.tolerance).collect();
    assert_eq!(tols, vec![1e-4, 1e-6, 1e-8, 1e-10]);
    for w in c.tolerances.windows(2) {
        assert!(w[1].iterations >= w[0].iterations);
    }
    for r in &c.tolerances {
        assert_eq!(r.status, "collapse");
        let d = r.difference.expect("difference");
        assert!(d <= 10.0 * r.tolerance, "tol {}: {d}", r.tolerance);
        // The reported forces are clamped to no tension, so the equilibrium residual also
        // measures how far the solver's iterate sat outside the cones: about tol / 10.
        assert!(r.residual_over_weight.expect("residual") <= r.tolerance);
    }
    assert_eq!(c.tolerances[3].difference, Some(0.0));
    assert!(
        c.tolerances[0].difference.expect("d") > 1e-8,
        "the loose solve differs"
    );
}

/// The DEM, started away from the answer (lambda = 0.2), brackets the collapse multiplier of
/// a 16-voussoir semicircle to its tolerance and lands within 2% of the static value of the
/// same discretisation.
#[test]
fn dem_study_row() {
    let scene = common::semicircle(0.15, 16);
    let settings = ConvergenceSettings {
        max_voussoirs: 8,
        kinematic_max_joints: 0,
        continuous: false,
        solver_tolerances: Vec::new(),
        dem_cases: vec![DemCase::new(0.02, 0.9, 1.0)],
        ..Default::default()
    };
    let c = convergence::run(&scene, &settings, &mut quiet()).expect("study runs");
    assert_eq!(c.dem.len(), 1);
    let r = &c.dem[0];
    assert_eq!(r.voussoirs, 16);
    let (a, b) = (
        r.lambda_stands.expect("stands"),
        r.lambda_collapses.expect("collapses"),
    );
    assert!(a < b && (b - a) <= 0.02 * 0.5 * (a + b) * (1.0 + 1e-9));
    let s = r.lambda_static.expect("static");
    let e = r.error.expect("error");
    assert!((e - (0.5 * (a + b) - s) / s).abs() < 1e-12);
    assert!(e.abs() < 0.02, "DEM error {e}");
    assert!(r.steps > 0 && r.steps_per_s > 0.0 && r.time_step_s > 0.0);
    // The study varies the explicit stepping's knobs: its rows run that stepping, also at
    // the default factors (the rigid stepping's step is about 1e-3 s, the explicit's 1e-5).
    assert_eq!(r.integrator, "explicit");
    assert!(r.time_step_s < 1e-4, "dt {}", r.time_step_s);
}

/// Acceptance: a 1000-voussoir semicircle (t/R = 0.15) through the same library path as
/// `voussoir analyze` with its defaults (static bound; above 200 joints the exhaustive kinematic
/// search is replaced by the mechanism of the static hinges, certified, or else the local
/// search around them): lambda within 5e-4 of 0.1443, equilibrium to round-off, and both the
/// certified and the local upper bounds meet it.
#[test]
fn thousand_voussoirs_acceptance() {
    let scene = common::semicircle(0.15, 1000);
    let a = analysis::analyse(&scene, &Options::default()).expect("analyses");
    assert_eq!(a.lower.status, Status::Collapse);
    let l = a.lower.lambda.expect("lambda");
    assert!((l - 0.1443).abs() < 5e-4, "lambda {l}");
    assert!(a.lower.equilibrium_residual < 1e-9 * a.model.assembly.total_weight());
    let k = a.upper.as_ref().expect("certified kinematic bound");
    assert_eq!(k.search, voussoir::kinematic::Search::Certified);
    assert!(k.note.as_deref().is_some_and(|n| n.contains("certified")));
    let u = a.lambda_upper().expect("upper bound");
    assert!((u - l).abs() <= 1e-6, "lower {l}, upper {u}");
    // The local search around the static hinges, which runs when certification fails.
    let local = voussoir::kinematic::analyse_local(
        &a.model,
        &a.lower,
        &voussoir::kinematic::KinematicSettings::default(),
        analysis::KINEMATIC_LOCAL_WINDOW,
    )
    .expect("local kinematic search");
    assert_eq!(local.search, voussoir::kinematic::Search::Local);
    assert!(local
        .note
        .as_deref()
        .is_some_and(|n| n.contains("of 1001 joints")));
    let ul = local.lambda_upper.expect("local upper bound");
    assert!((ul - l).abs() <= 1e-6, "lower {l}, local upper {ul}");
    assert!(a.continuous.is_none());
    assert_eq!(a.lower.hinges.len(), 4);
}

#[test]
fn settings_are_checked() {
    let scene = common::semicircle(0.15, 16);
    let bad = [
        ConvergenceSettings {
            min_voussoirs: 64,
            max_voussoirs: 32,
            ..Default::default()
        },
        ConvergenceSettings {
            solver_tolerances: vec![0.0],
            ..Default::default()
        },
        ConvergenceSettings {
            max_voussoirs: 1 << 20,
            ..Default::default()
        },
        ConvergenceSettings {
            dem_cases: vec![DemCase::new(0.01, 1.5, 1.0)],
            ..Default::default()
        },
    ];
    for s in bad {
        assert!(convergence::run(&scene, &s, &mut quiet()).is_err());
    }
    assert_eq!(
        ConvergenceSettings {
            max_voussoirs: 100,
            ..Default::default()
        }
        .voussoir_counts(),
        vec![8, 16, 32, 64]
    );
}

#[test]
fn loglog_slope_recovers_exponents() {
    let pts: Vec<(f64, f64)> = [8.0, 16.0, 64.0, 1000.0]
        .iter()
        .map(|&n: &f64| (n, 3.0 * n.powf(-2.0)))
        .collect();
    assert!((loglog_slope(&pts).expect("slope") + 2.0).abs() < 1e-12);
    assert!(loglog_slope(&pts[..1]).is_none());
    assert!(loglog_slope(&[(1.0, 0.0), (2.0, -1.0)]).is_none());
}

/// The CLI wiring: tables on stdout, or JSON, and the CSV and SVG files.
#[test]
fn cli_convergence() {
    let dir = tempfile::tempdir().expect("tempdir");
    let scene = dir.path().join("s.toml");
    std::fs::write(
        &scene,
        "[arch]\nshape = \"circular\"\nradius = 1.0\nthickness = 0.15\nvoussoirs = 16\n",
    )
    .expect("write scene");
    let (csv, svg) = (dir.path().join("c.csv"), dir.path().join("c.svg"));
    let out = Command::cargo_bin("voussoir")
        .expect("binary")
        .args(["convergence", "--max-voussoirs", "32", "--no-dem", "--json"])
        .arg(&scene)
        .arg("--csv")
        .arg(&csv)
        .arg("--svg")
        .arg(&svg)
        .output()
        .expect("runs");
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).expect("json");
    assert_eq!(v["refinement"].as_array().map(|a| a.len()), Some(3));
    assert!(v["dem"].as_array().is_some_and(|a| a.is_empty()));
    assert!(v["lambda_continuous"].as_f64().is_some());
    assert_eq!(
        std::fs::read_to_string(&csv).expect("csv").lines().count(),
        4
    );
    assert!(std::fs::read_to_string(&svg).expect("svg").contains("<svg"));
}
