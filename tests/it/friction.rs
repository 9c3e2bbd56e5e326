//! Issue 25, item 1: whether the static multiplier with finite friction is exact. The static
//! program's friction is associative (a sliding joint also opens); real joints slide without
//! opening, so where joints slip in the collapse mechanism the multiplier is an upper bound of
//! the real collapse multiplier, not a safe lower bound (docs/friction.md). Every answer says
//! which: `friction_exact`, `lambda_associative`, `slipping_joints` and `friction_note` in the
//! JSON, and words in the summary and the drawing's title.

use crate::common::*;
use voussoir::analysis::{self, Options};
use voussoir::statics::{self, Program, StaticSettings, Status};

/// A semicircle of radius 1 with `voussoirs` polygon voussoirs, thickness `t`, friction `mu`.
fn semicircle_text(t: f64, voussoirs: usize, mu: &str) -> String {
    format!(
        "[arch]\nshape = \"circular\"\nradius = 1.0\nthickness = {t}\nvoussoirs = {voussoirs}\n[material]\nfriction = {mu}\n"
    )
}

/// A single 1 m x 1 m block on the ground with friction `mu`: it slides at lambda = mu when
/// mu < b/h = 1, and rocks at lambda = 1 otherwise.
fn block_text(mu: &str) -> String {
    format!(
        "[blocks]\npolygons = [[[-0.5, 0.0], [0.5, 0.0], [0.5, 1.0], [-0.5, 1.0]]]\n[material]\nfriction = {mu}\n"
    )
}

/// A thin semicircle with ample friction rocks: no joint slips in its mechanism, so the
/// multiplier is exact, the associative value is the same number, and it is the one of
/// infinite friction.
#[test]
fn a_rocking_arch_with_finite_friction_is_exact() {
    let text = semicircle_text(0.15, 16, "0.6");
    let v = json_of(&["analyze", "--json"], &text);
    assert_eq!(v["status"], "collapse");
    assert_eq!(v["friction_exact"], true, "{v}");
    let (lower, associative) = (f64_of(&v, "lambda_lower"), f64_of(&v, "lambda_associative"));
    assert!(
        (lower - associative).abs() <= 1e-12,
        "{lower} vs {associative}"
    );
    assert_eq!(v["slipping_joints"], serde_json::json!([]));
    assert!(v["friction_note"].is_null());
    // Nothing slides: the multiplier is the one of joints that cannot slide.
    let inf = json_of(
        &["analyze", "--json"],
        &semicircle_text(0.15, 16, "\"inf\""),
    );
    let rigid = f64_of(&inf, "lambda_lower");
    assert!((lower - rigid).abs() <= 1e-9, "{lower} vs {rigid}");
    // The summary keeps the lower bound's name and says nothing of associative friction.
    let (_dir, path) = scene_file(&text);
    let out = voussoir().arg("analyze").arg(&path).output().expect("runs");
    let summary = String::from_utf8_lossy(&out.stdout);
    assert!(
        summary.contains("Static (lower bound): collapse multiplier"),
        "{summary}"
    );
    assert!(!summary.contains("associative"), "{summary}");
}

/// A single block with mu below b/h slides at lambda = mu: the joint slips in the mechanism,
/// so the answer is not exact and the associative value, lambda_lower, is named an upper bound
/// in the JSON, the summary and the drawing.
#[test]
fn a_sliding_block_is_not_exact() {
    let text = block_text("0.5");
    let v = json_of(&["analyze", "--json"], &text);
    assert_eq!(v["status"], "collapse");
    assert_eq!(v["friction_exact"], false, "{v}");
    let (lower, associative) = (f64_of(&v, "lambda_lower"), f64_of(&v, "lambda_associative"));
    assert_eq!(lower, associative);
    assert!((lower - 0.5).abs() <= 1e-6, "slides at mu: {lower}");
    assert_eq!(v["slipping_joints"], serde_json::json!([0]));
    let note = v["friction_note"].as_str().expect("a note");
    assert!(
        note.contains("1 joint slides") && note.contains("upper bound of the real"),
        "{note}"
    );
    let (dir, path) = scene_file(&text);
    let svg = dir.path().join("block.svg");
    let out = voussoir()
        .arg("analyze")
        .arg(&path)
        .arg("--svg")
        .arg(&svg)
        .output()
        .expect("runs");
    assert!(out.status.success());
    let summary = String::from_utf8_lossy(&out.stdout);
    assert!(
        summary.contains("Static (associative friction): collapse multiplier lambda = 0.5"),
        "{summary}"
    );
    assert!(summary.contains(note), "{summary}");
    assert!(
        summary.contains("joints that slip in the collapse mechanism: 0"),
        "{summary}"
    );
    let drawing = std::fs::read_to_string(&svg).expect("svg written");
    assert!(
        drawing.contains("λ (associative friction, an upper bound: 1 joint slides) = 0.5000"),
        "{drawing}"
    );
    // With friction above b/h the block rocks: exact again.
    let v = json_of(&["analyze", "--json"], &block_text("1.5"));
    assert_eq!(v["friction_exact"], true, "{v}");
    assert!((f64_of(&v, "lambda_lower") - 1.0).abs() <= 1e-6);
}

/// A thick semicircle with low friction slides at its springing (issue 25's case): both
/// static programs (the chain's active set, the full conic program) name the same slipping
/// joints, and they are the sliding joints of the thrust line; with more friction it rocks.
#[test]
fn a_thick_arch_with_low_friction_slides_in_both_programs() {
    for (mu, exact) in [("0.4", false), ("0.5", false), ("1.0", true)] {
        let model = model_of(&scene(&semicircle_text(0.25, 16, mu)));
        let mut slipping = Vec::new();
        for program in [Program::Auto, Program::Full] {
            let settings = StaticSettings {
                program,
                ..StaticSettings::default()
            };
            let r = statics::analyse(&model, &settings).expect("static");
            assert_eq!(r.status, Status::Collapse);
            let f = r.friction(&model.assembly);
            assert!(f.finite);
            assert_eq!(f.exact, exact, "mu = {mu}, {program:?}: {f:?}");
            assert_eq!(f.exact, f.slipping.is_empty());
            assert_eq!(f.lambda_associative, r.lambda);
            // A joint that slips is on its friction limit.
            assert!(f.slipping.iter().all(|j| r.sliding.contains(j)), "{f:?}");
            slipping.push(f.slipping);
        }
        assert_eq!(slipping[0], slipping[1], "mu = {mu}: the programs disagree");
    }
}

/// With infinite friction nothing can slide: exact, and the associative value is the static
/// multiplier still (so it always compares with lambda_lower). A structure that cannot stand
/// is exact too: no equilibrium exists for either friction law.
#[test]
fn infinite_friction_and_cannot_stand_are_exact() {
    let v = json_of(
        &["analyze", "--json"],
        &semicircle_text(0.15, 16, "\"inf\""),
    );
    assert_eq!(v["friction_exact"], true);
    assert_eq!(v["lambda_associative"], v["lambda_lower"]);
    assert!(v["friction_note"].is_null());
    let v = json_of(&["analyze", "--json"], &semicircle_text(0.25, 16, "0.2"));
    assert_eq!(v["status"], "cannot_stand", "{v}");
    assert_eq!(v["friction_exact"], true);
    assert!(v["lambda_associative"].is_null() && v["lambda_lower"].is_null());
}

/// The analysis layer gives the front ends the static result's own check.
#[test]
fn the_analysis_layer_reads_the_same_check() {
    let scene = scene(&semicircle_text(0.25, 16, "0.4"));
    let a = analysis::analyse(&scene, &Options::default()).expect("analysis");
    let f = a.friction();
    assert_eq!(f, a.lower.friction(&a.model.assembly));
    assert!(!f.exact && a.sliding_governs());
}

/// The DEM's comparison line names the static multiplier for what it is: the static lower
/// bound when friction is exact, the associative multiplier (an upper bound) when the block
/// slides; its JSON carries `friction_exact` as `analyze` does.
#[test]
fn the_dem_comparison_says_which_static_multiplier_it_is() {
    for (mu, exact) in [("0.5", false), ("1.5", true)] {
        let (_dir, path) = crate::common::scene_file(&block_text(mu));
        let json = crate::common::json_of(&["dem", "--json", "--from-static"], &block_text(mu));
        assert_eq!(json["friction_exact"], exact, "mu = {mu}");
        let out = crate::common::voussoir()
            .args(["dem", "--from-static"])
            .arg(&path)
            .output()
            .expect("runs");
        let text = String::from_utf8_lossy(&out.stdout);
        assert_eq!(
            text.contains("the static multiplier (associative friction, an upper bound"),
            !exact,
            "mu = {mu}: {text}"
        );
        let line = text
            .lines()
            .find(|l| l.contains("the DEM bracket"))
            .expect("a comparison line");
        assert_eq!(
            line.trim_start().starts_with("the static lower bound"),
            exact,
            "mu = {mu}: {line}"
        );
    }
}
