//! What a newcomer reads (issue 11): the summaries, titles and CSV of the reports say what
//! they mean in words, with numbers formatted for reading.

use crate::common;
use common::{data, scene, voussoir};
use voussoir::analysis::{self, DemOptions, Options};
use voussoir::kinematic::Family;
use voussoir::outcome::Status;
use voussoir::report;
use voussoir::scene::Scene;

/// The summary `voussoir ARGS SCENE` prints.
fn summary(args: &[&str], scene: &str) -> String {
    let out = voussoir().args(args).arg(data(scene)).assert().success();
    String::from_utf8_lossy(&out.get_output().stdout).to_string()
}

/// The line of `text` that contains `what`, and the one after it.
fn line_after<'a>(text: &'a str, what: &str) -> (&'a str, &'a str) {
    let mut lines = text.lines();
    while let Some(l) = lines.next() {
        if l.contains(what) {
            return (l, lines.next().unwrap_or(""));
        }
    }
    panic!("no line with `{what}` in\n{text}");
}

fn bundled(name: &str) -> Scene {
    Scene::from_file(&data(name)).expect("bundled scene")
}

// Item 1: the sliding note's percentage is (upper - lower) / upper.
#[test]
fn sliding_note_gives_the_difference_relative_to_the_upper_bound() {
    let text = summary(
        &["analyze", "--set", "material.friction=0.4"],
        "semicircular.toml",
    );
    let (line, _) = line_after(&text, "sliding governs");
    assert!(line.contains("0.052868"), "{line}");
    assert!(line.contains("(63.7% lower)"), "{line}");
    assert!(!text.contains("9.28"), "{text}");
    // The same number from the library, against the analysis itself.
    let s = bundled("semicircular.toml")
        .with_override("material.friction=0.4")
        .expect("scene");
    let a = analysis::analyse(&s, &Options::default()).expect("analysis");
    let (l, u) = (
        a.lower.lambda.expect("lower"),
        a.lambda_upper().expect("upper"),
    );
    let d = report::sliding_shortfall(l, u).expect("both positive");
    assert!((d - (u - l) / u).abs() < 1e-15);
    assert!((0.636..0.638).contains(&d), "{d}");
    // The JSON gap keeps its meaning: |u - l| / max(1, l).
    let gap = a.gap().expect("gap");
    assert!((gap - (u - l).abs() / l.max(1.0)).abs() < 1e-15);
    assert_eq!(report::sliding_shortfall(0.1, 0.0), None);
}

// Item 2: a kinematic multiplier under a static "cannot stand" says it ignores sliding.
#[test]
fn kinematic_lambda_under_cannot_stand_says_rotational_mechanisms_only() {
    let text = summary(
        &[
            "analyze",
            "--set",
            "material.friction=0.3",
            "--set",
            "arch.thickness=0.25",
        ],
        "semicircular.toml",
    );
    assert!(text.contains("CANNOT STAND"), "{text}");
    let (line, next) = line_after(&text, "Kinematic (upper bound): lambda = 0.406089");
    assert!(line.contains("admissible mechanisms"), "{line}");
    assert_eq!(
        next.trim(),
        "rotational mechanisms only: with mu = 0.3 the structure slides before any of them forms",
        "{text}"
    );
    let (line, _) = line_after(&text, "sliding governs");
    assert!(line.contains("cannot stand"), "{line}");
    // With sliding governing a collapse, the same words, and the static bound it slides at.
    let text = summary(
        &["analyze", "--set", "material.friction=0.4"],
        "semicircular.toml",
    );
    let (_, next) = line_after(&text, "Kinematic (upper bound): lambda = 0.145673");
    assert!(
        next.contains("rotational mechanisms only: with mu = 0.4 the structure slides first")
            && next.contains("0.052868"),
        "{text}"
    );
    // Without sliding, no such note.
    let text = summary(&["analyze"], "semicircular.toml");
    assert!(!text.contains("rotational mechanisms only"), "{text}");
}

// Item 3: no internal names; the portal, not the arch, when pier joints take part.
#[test]
fn mechanisms_are_named_in_words() {
    assert_eq!(report::family_words(Family::FourHinges), "four hinges");
    assert_eq!(
        report::family_words(Family::TwoHingesOneOpen),
        "two hinges and an opening joint"
    );
    assert_eq!(report::family_words(Family::TwoOpen), "two opening joints");
    assert_eq!(report::family_words(Family::OneHinge), "one hinge");
    for scene in ["semicircular.toml", "portal.toml", "loaded_portal.toml"] {
        let text = summary(&["analyze", "--continuous"], scene);
        for word in [
            "FourHinges",
            "TwoHingesOneOpen",
            "TwoOpen",
            "OneHinge",
            "Some(",
            "None",
        ] {
            assert!(!text.contains(word), "{scene}: `{word}` in\n{text}");
        }
    }
    let arch = summary(&["analyze"], "semicircular.toml");
    assert!(arch.contains("  the arch becomes a mechanism"), "{arch}");
    assert!(
        arch.contains("governing mechanism of the arch: four hinges"),
        "{arch}"
    );
    // portal.toml: the fourth hinge is at the base of the right pier.
    let portal = summary(&["analyze"], "portal.toml");
    assert!(
        portal.contains("(right pier 0), outer face (p2)"),
        "{portal}"
    );
    assert!(
        portal.contains("  the portal becomes a mechanism"),
        "{portal}"
    );
    assert!(!portal.contains("the arch becomes"), "{portal}");
    assert!(
        portal.contains("governing mechanism of the portal: four hinges"),
        "{portal}"
    );
}

// Item 4: numbers for reading, counts in the singular or plural, hinge angles, end names.
#[test]
fn numbers_are_formatted_for_reading() {
    assert_eq!(report::num(0.49999999999999994), "0.5");
    assert_eq!(report::num(0.30000000000000004), "0.3");
    assert_eq!(report::num(119.99999999999999), "120");
    assert_eq!(report::num(1.0), "1");
    assert_eq!(report::num(0.0), "0");
    assert_eq!(report::num(-0.0), "0");
    assert_eq!(report::num(1e-6), "0.000001");
    assert_eq!(report::num(0.123456789), "0.123456789");
    assert_eq!(report::num(f64::INFINITY), "inf");
    assert_eq!(report::sci(0.0, 1), "0");
    assert_eq!(report::sci(2.5e-12, 1), "2.5e-12");
    assert_eq!(report::count(1, "run", "runs"), "1 run");
    assert_eq!(report::count(3, "run", "runs"), "3 runs");
    assert_eq!(report::count(0, "run", "runs"), "0 runs");

    // Float noise in echoed scene values.
    let s = scene(
        "[arch]\nshape = \"circular\"\nradius = 1.0\nembrace_deg = 180.0\nthickness = 0.30000000000000004\nvoussoirs = 16\n\n[piers]\nheight = 0.49999999999999994\nwidth = 0.4\ncourses = 1\n\n[material]\nfriction = 0.49999999999999994\n",
    );
    let model = s.model().expect("model");
    let d = report::describe_scene(&s, &model);
    assert!(d.contains("t = 0.3 m, 16 polygon voussoirs"), "{d}");
    assert!(d.contains("h = 0.5 m, b = 0.4 m, 1 course\n"), "{d}");
    assert!(d.contains("mu = 0.5;"), "{d}");
    assert!(!d.contains("0000"), "{d}");
    let a = analysis::analyse(&s, &Options::default()).expect("analysis");
    let title = report::drawing_title(&s, &a);
    assert!(title.contains("t = 0.3 m"), "{title}");

    // The relative difference 0 is "0", not "0.0e0" (the exhaustive bisection visits the
    // static search's thicknesses and lands on the same one; the certified root does not).
    let text = summary(
        &["min-thickness", "--kinematic", "exhaustive"],
        "semicircular.toml",
    );
    assert!(!text.contains("0.0e0"), "{text}");
    assert!(text.contains("(relative difference 0)"), "{text}");
    assert!(text.contains("39 static analyses"), "{text}");

    // Hinge lines: the end's word with its JSON/CSV name, and an arch joint's angles (joint 4
    // of 32 on a semicircle: polar 180 - 4 x 180/32 = 157.5 deg).
    let text = summary(&["analyze", "--continuous"], "semicircular.toml");
    assert!(
        text.contains(
            "    joint    4 (arch 4), intrados (p1), at (-0.8546, 0.3540) m, polar 157.500 deg, 67.500 deg from the vertical\n"
        ),
        "{text}"
    );
    for l in text
        .lines()
        .filter(|l| l.trim_start().starts_with("joint "))
    {
        assert!(
            l.contains("deg from the vertical")
                && (l.contains("intrados (p1)") || l.contains("extrados (p2)")),
            "{l}"
        );
    }
    // The continuous model's sections use the same end words.
    let (_, first) = line_after(&text, "Continuous model");
    assert!(
        first.contains("intrados (p1)") || first.contains("extrados (p2)"),
        "{first}"
    );
    // Pier joints: their faces, no angle.
    let text = summary(&["analyze"], "portal.toml");
    let (pier, _) = line_after(&text, "(right pier 0)");
    assert!(
        pier.contains("outer face (p2)") && !pier.contains("deg"),
        "{pier}"
    );
}

// Item 4: the hinge angles are those of the joint's direction p1 -> p2.
#[test]
fn hinge_angles_are_those_of_the_joint_direction() {
    let s = common::semicircle(0.15, 32);
    let model = s.model().expect("model");
    for (j, joint) in model.assembly.joints.iter().enumerate() {
        let (polar, vertical) = report::joint_angles_deg(&model.assembly, j).expect("joint");
        let expected = 180.0 - j as f64 * 180.0 / 32.0;
        assert!((polar - expected).abs() < 1e-9, "joint {j}: {polar}");
        assert!((vertical - (expected - 90.0).abs()).abs() < 1e-9);
        let d = joint.p2 - joint.p1;
        assert!((d.y.atan2(d.x).to_degrees() - polar).abs() < 1e-12);
    }
    assert!(report::joint_angles_deg(&model.assembly, 999).is_none());
}

// Item 4: the thrust-line CSV keeps its column names (scripts rely on them).
#[test]
fn thrust_csv_keeps_its_columns() {
    let dir = tempfile::tempdir().expect("tempdir");
    let path = dir.path().join("thrust.csv");
    voussoir()
        .arg("analyze")
        .arg(data("portal.toml"))
        .arg("--thrust-csv")
        .arg(&path)
        .assert()
        .success();
    let text = std::fs::read_to_string(&path).expect("csv");
    assert_eq!(
        text.lines().next(),
        Some("joint,kind,x,y,N,V,M,e,p1_x,p1_y,p2_x,p2_y")
    );
    assert_eq!(text.lines().count(), 1 + 41);
}

// Item 6: a drawing's title says "cannot stand" or "no collapse" in words.
#[test]
fn drawing_titles_say_why_there_is_no_multiplier() {
    let opts = Options::default();
    let thin = bundled("semicircular.toml")
        .with_override("arch.thickness=0.08")
        .expect("scene");
    let a = analysis::analyse(&thin, &opts).expect("analysis");
    assert_eq!(a.lower.status, Status::CannotStand);
    let t = report::drawing_title(&thin, &a);
    assert!(t.contains("cannot stand"), "{t}");
    assert!(!t.contains("none"), "{t}");

    let flat = bundled("semicircular.toml")
        .with_overrides(&["arch.embrace_deg=60", "arch.thickness=0.6"])
        .expect("scene");
    let a = analysis::analyse(&flat, &opts).expect("analysis");
    assert_eq!(a.lower.status, Status::NoCollapse);
    let t = report::drawing_title(&flat, &a);
    assert!(t.contains("no collapse"), "{t}");
    assert!(!t.contains("none"), "{t}");

    let slides = bundled("semicircular.toml")
        .with_overrides(&["material.friction=0.3", "arch.thickness=0.25"])
        .expect("scene");
    let a = analysis::analyse(&slides, &opts).expect("analysis");
    let t = report::drawing_title(&slides, &a);
    assert!(
        t.contains("cannot stand")
            && t.contains("λ (kinematic upper bound) = 0.4061 (rotation only)"),
        "{t}"
    );

    let a = analysis::analyse(&bundled("semicircular.toml"), &opts).expect("analysis");
    let t = report::drawing_title(&bundled("semicircular.toml"), &a);
    assert!(
        t.contains("λ (static lower bound) = 0.14")
            && t.contains("λ (kinematic upper bound) = 0.14")
            && !t.contains("lambda_"),
        "{t}"
    );

    // The SVG of analyze carries the words.
    let dir = tempfile::tempdir().expect("tempdir");
    let path = dir.path().join("thin.svg");
    voussoir()
        .args(["analyze", "--set", "arch.thickness=0.08", "--svg"])
        .arg(&path)
        .arg(data("semicircular.toml"))
        .assert()
        .success();
    let svg = std::fs::read_to_string(&path).expect("svg");
    assert!(svg.contains("cannot stand: no thrust line fits"));
    assert!(!svg.contains("lambda_lower = none"));
    // Issue 26: no JSON key names in a drawing.
    assert!(!svg.contains("lambda_lower") && !svg.contains("lambda_upper"));
}

// Item 6 (DEM) and item 4 (counts): the DEM's title and summary.
#[test]
fn dem_title_and_counts_in_words() {
    let s = bundled("semicircular.toml")
        .with_overrides(&["arch.thickness=0.08", "arch.voussoirs=12"])
        .expect("scene");
    let d = analysis::dem(&s, &DemOptions::default(), &mut |_| {}).expect("dem");
    let mut rep = report::DemReport::new(&s, &d.model, &d.result, d.lower.lambda);
    assert_eq!(rep.status, "cannot_stand");
    let t = report::dem_drawing_title(&s, &rep, d.lower.status);
    assert!(
        t.contains("DEM: cannot stand") && t.contains("static: cannot stand"),
        "{t}"
    );
    assert!(!t.contains("none"), "{t}");
    rep.runs.truncate(1);
    let text = report::text::print(&report::documents::dem(&s, &d.model, rep));
    assert!(text.contains("  1 run, "), "{text}");
    assert!(!text.contains("1 runs"), "{text}");
}

// Item 7: the DEM summary says that curved voussoirs are simulated as polygons.
#[test]
fn dem_summary_says_curved_voussoirs_are_polygons() {
    let args = [
        "dem",
        "--set",
        "arch.voussoirs=12",
        "--tolerance",
        "0.05",
        "--set",
    ];
    let curved = summary(
        &[&args[..], &["arch.voussoir_shape=curved"]].concat(),
        "semicircular.toml",
    );
    assert!(curved.contains("12 curved voussoirs"), "{curved}");
    assert!(
        curved.contains("curved voussoirs are simulated as polygons"),
        "{curved}"
    );
    let polygon = summary(
        &[&args[..], &["arch.voussoir_shape=polygon"]].concat(),
        "semicircular.toml",
    );
    assert!(!polygon.contains("simulated as polygons"), "{polygon}");
}

// Item 3: no internal names in the notes either (min-thickness without a minimum).
#[test]
fn min_thickness_note_is_in_words() {
    let dir = tempfile::tempdir().expect("tempdir");
    let path = dir.path().join("never.svg");
    let out = voussoir()
        .args(["min-thickness", "--set", "material.friction=0.01", "--svg"])
        .arg(&path)
        .arg(data("portal.toml"))
        .assert()
        .success();
    let err = String::from_utf8_lossy(&out.get_output().stderr).to_string();
    assert!(
        err.contains("no minimum thickness (no thickness lets the structure stand)"),
        "{err}"
    );
    assert!(!err.contains("NeverStands"), "{err}");
    assert!(!path.exists());
}

// Items 3 and 6: statuses in words in the summary (the JSON keeps `no_collapse`,
// `cannot_stand`).
#[test]
fn statuses_are_words_in_the_summary() {
    let text = summary(
        &[
            "analyze",
            "--continuous",
            "--set",
            "arch.embrace_deg=60",
            "--set",
            "arch.thickness=0.6",
        ],
        "semicircular.toml",
    );
    assert!(
        text.contains("infinitely many voussoirs): no collapse ("),
        "{text}"
    );
    assert!(
        !text.contains("no_collapse") && !text.contains("none"),
        "{text}"
    );
    let text = summary(
        &["analyze", "--continuous", "--set", "arch.thickness=0.08"],
        "semicircular.toml",
    );
    assert!(
        text.contains("infinitely many voussoirs): cannot stand ("),
        "{text}"
    );
    assert!(
        !text.contains("cannot_stand") && !text.contains("none"),
        "{text}"
    );
    assert_eq!(report::status_words(Status::NoCollapse), "no collapse");
}

/// A summary lists at most 24 hinges (or mechanism joints) under a line, then says how many
/// there are and where the JSON lists them all; long joint lists are cut after 40 numbers
/// with their count. The bundled arcade (over a hundred hinges, hundreds of mechanism
/// joints) and a chain (four hinges, listed whole).
#[test]
fn long_hinge_and_joint_lists_are_cut_with_their_count() {
    let text = summary(&["analyze"], "arcade.toml");
    let json_out = voussoir()
        .args(["analyze", "--json"])
        .arg(data("arcade.toml"))
        .assert()
        .success();
    let json: serde_json::Value =
        serde_json::from_slice(&json_out.get_output().stdout).expect("JSON");
    let count = |key: &str| json[key].as_array().map_or(0, Vec::len);
    let hinges = count("hinges");
    assert!(hinges > 24, "{hinges} hinges");
    let lines: Vec<&str> = text.lines().collect();
    let at = lines
        .iter()
        .position(|l| l.trim() == "hinges of the thrust line:")
        .expect("hinge heading");
    let items = lines[at + 1..]
        .iter()
        .take_while(|l| l.trim_start().starts_with("joint "))
        .count();
    assert_eq!(items, 24);
    assert_eq!(
        lines[at + 25].trim(),
        format!(
            "... and {} more ({hinges} in all; every one in `analyze --json`'s `hinges`)",
            hinges - 24
        )
    );
    let mechanism = count("mechanism_hinges") + count("open_joints") + count("mechanism_sliding");
    assert!(mechanism > 25, "{mechanism} mechanism joints");
    assert!(
        text.contains(&format!(
            "... and {} more ({mechanism} in all; every one in `analyze --json`'s `mechanism_hinges`, `open_joints` and `mechanism_sliding`)",
            mechanism - 24
        )),
        "{text}"
    );

    let chain = summary(&["analyze"], "portal.toml");
    assert!(!chain.contains("more ("), "{chain}");
    let (_, first) = line_after(&chain, "hinges of the thrust line:");
    assert!(first.trim_start().starts_with("joint "), "{first}");

    // Joint lists: the arcade with friction 0.4 slides at hundreds of joints; each line shows
    // 40 numbers and the count of the JSON's list.
    let args = ["analyze", "--set", "material.friction=0.4"];
    let slid = summary(&args, "arcade.toml");
    let out = voussoir()
        .args(args)
        .arg("--json")
        .arg(data("arcade.toml"))
        .assert()
        .success();
    let json: serde_json::Value = serde_json::from_slice(&out.get_output().stdout).expect("JSON");
    for (head, key) in [
        ("sliding joints (|V| = mu N):", "sliding"),
        (
            "joints that slip in the collapse mechanism:",
            "slipping_joints",
        ),
        (
            "joints that slide in its mechanism:",
            "non_associative_sliding_joints",
        ),
    ] {
        let all = json[key].as_array().map_or(0, Vec::len);
        assert!(all > 41, "{key}: {all}");
        let (line, _) = line_after(&slid, head);
        let shown = line
            .split(": ")
            .nth(1)
            .expect("list")
            .split(", ")
            .take_while(|s| s.parse::<usize>().is_ok())
            .count();
        assert_eq!(shown, 40, "{line}");
        let tail = format!(
            "and {} more ({all} in all; every one in `analyze --json`'s `{key}`)",
            all - 40
        );
        assert!(line.ends_with(&tail), "{line}");
    }
}
