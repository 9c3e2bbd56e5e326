//! The local kinematic search (mechanisms near the static hinges only): on chains small enough
//! for the exhaustive search it finds the same multiplier; on chains of 400-1000 voussoirs it
//! meets the static lower bound (certifying lambda_c); any window gives an upper bound; and a
//! search that finds nothing claims nothing.

use crate::common;

use voussoir::analysis::{self, Options};
use voussoir::kinematic::{self, KinematicError, KinematicResult, KinematicSettings, Search};
use voussoir::model::Model;
use voussoir::report::AnalysisReport;
use voussoir::scene::Scene;
use voussoir::statics::{self, Direction, StaticResult, StaticSettings, Status};

/// A pointed arch; the geometry admits fewer voussoirs the larger e/R (at most 164 at 0.2).
fn pointed(e: f64, t: f64, n: usize) -> Scene {
    common::scene(&format!(
        "[arch]\nshape = \"pointed\"\nradius = 1.0\neccentricity = {e}\nthickness = {t}\nvoussoirs = {n}\n"
    ))
}

fn basket(t: f64, n: usize) -> Scene {
    common::scene(&format!(
        "[arch]\nshape = \"basket\"\nspan = 2.0\nrise = 0.7\nside_angle_deg = 60.0\nthickness = {t}\nvoussoirs = {n}\n"
    ))
}

fn portal(n: usize, courses: usize, friction: &str) -> Scene {
    common::scene(&format!(
        "[arch]\nshape = \"circular\"\nradius = 1.0\nthickness = 0.2\nvoussoirs = {n}\n[piers]\nheight = 1.0\nwidth = 0.4\ncourses = {courses}\n[material]\nfriction = {friction}\n"
    ))
}

fn statics(asm: &Model, dir: Direction) -> StaticResult {
    let st =
        statics::analyse(asm, &StaticSettings::default().direction(dir)).expect("static solve");
    assert_eq!(st.status, Status::Collapse);
    st
}

fn mechanism_joints(k: &KinematicResult) -> Vec<usize> {
    let m = k.mechanism.as_ref().expect("mechanism");
    let mut j: Vec<usize> = m
        .hinges
        .iter()
        .map(|h| h.joint)
        .chain(m.open.clone())
        .collect();
    j.sort_unstable();
    j
}

/// Chains of 33-129 joints (semicircles, segmental, pointed, basket, portal; both load
/// directions for the asymmetric-in-effect cases): the local search with an 8-joint window
/// examines only part of the candidates yet finds the exhaustive search's multiplier and
/// mechanism, because the static hinges are those of the governing mechanism.
#[test]
fn local_equals_exhaustive_on_small_chains() {
    let cases: Vec<(&str, Scene, Direction)> = vec![
        (
            "semicircle 0.15 n32",
            common::semicircle(0.15, 32),
            Direction::Right,
        ),
        (
            "semicircle 0.15 n64",
            common::semicircle(0.15, 64),
            Direction::Right,
        ),
        (
            "semicircle 0.25 n128",
            common::semicircle(0.25, 128),
            Direction::Right,
        ),
        (
            "segmental 120deg n64",
            common::circular(0.12, 64, 120.0, "polygon"),
            Direction::Left,
        ),
        ("pointed n64", pointed(0.2, 0.15, 64), Direction::Right),
        ("pointed n96 left", pointed(0.2, 0.2, 96), Direction::Left),
        ("basket n80", basket(0.15, 80), Direction::Right),
        ("portal n48", portal(48, 6, "inf"), Direction::Right),
    ];
    let window = 8;
    let mut local_runs = 0;
    for (label, scene, dir) in cases {
        let asm = common::model_of(&scene);
        let st = statics(&asm, dir);
        let settings = KinematicSettings::default().direction(dir);
        let ex = kinematic::analyse(&asm, &settings).expect("exhaustive");
        let loc = kinematic::analyse_local(&asm, &st, &settings, window).expect("local");
        assert_eq!(ex.search, Search::Exhaustive);
        assert_eq!(ex.searched_joints, asm.assembly.joints.len());
        if loc.search == Search::Local {
            local_runs += 1;
            assert!(loc.searched_joints < asm.assembly.joints.len(), "{label}");
            assert!(loc.candidates < ex.candidates, "{label}");
            assert!(loc.note.as_deref().is_some_and(|n| n.contains("local")));
        } else {
            // The window covered every joint: then it is the exhaustive search, said so.
            assert_eq!(loc.searched_joints, asm.assembly.joints.len(), "{label}");
        }
        assert_eq!(loc.status, Status::Collapse, "{label}");
        let (le, ll) = (
            ex.lambda_upper.expect("exhaustive lambda"),
            loc.lambda_upper.expect("local lambda"),
        );
        assert!(
            (le - ll).abs() <= 1e-12 * le.abs().max(1.0),
            "{label}: exhaustive {le}, local {ll}"
        );
        assert_eq!(mechanism_joints(&ex), mechanism_joints(&loc), "{label}");
        // And both meet the static bound (rigid blocks, no sliding).
        let ls = st.lambda.expect("static lambda");
        assert!(
            (ll - ls).abs() <= 1e-6 * ls.abs().max(1.0),
            "{label}: {ls} vs {ll}"
        );
    }
    assert!(
        local_runs >= 6,
        "only {local_runs} cases were actually local"
    );
}

/// Any window, even one placed away from the governing hinges, gives an upper bound: the
/// local multiplier is never below the exhaustive one, and equals it once the window holds
/// the governing mechanism.
#[test]
fn any_window_bounds_from_above() {
    let asm = common::model_of(&common::semicircle(0.15, 64));
    let settings = KinematicSettings::default();
    let st = statics(&asm, Direction::Right);
    let le = kinematic::analyse(&asm, &settings)
        .expect("exhaustive")
        .lambda_upper
        .expect("lambda");
    let mut above = 0;
    for shift in [-6i64, -3, 3, 6] {
        let mut moved = st.clone();
        for h in &mut moved.hinges {
            h.joint =
                (h.joint as i64 + shift).clamp(0, asm.assembly.joints.len() as i64 - 1) as usize;
        }
        for window in [1, 2, 4] {
            match kinematic::analyse_local(&asm, &moved, &settings, window) {
                Ok(k) => {
                    let l = k.lambda_upper.expect("a bound when a mechanism is found");
                    assert!(
                        l >= le * (1.0 - 1e-12),
                        "shift {shift} w {window}: {l} < {le}"
                    );
                    if l > le * (1.0 + 1e-6) {
                        above += 1;
                    }
                    // The reported mechanism is admissible and has this multiplier.
                    let m = k.mechanism.expect("mechanism");
                    assert!((m.lambda - l).abs() <= 1e-9 * l.abs().max(1.0));
                }
                Err(KinematicError::LocalFoundNothing { .. }) => {}
                Err(e) => panic!("shift {shift} w {window}: {e}"),
            }
        }
    }
    assert!(above > 0, "misplaced windows never gave a larger bound");
}

/// A local search that finds no mechanism proves nothing: it is an error, not `NoCollapse`;
/// and it needs a static collapse to locate the mechanism.
#[test]
fn local_search_claims_nothing_without_a_mechanism() {
    let asm = common::model_of(&common::semicircle(0.15, 64));
    let settings = KinematicSettings::default();
    let mut st = statics(&asm, Direction::Right);
    // A single joint cannot carry a one-degree-of-freedom mechanism of a two-support chain.
    st.hinges.truncate(1);
    st.open.clear();
    st.sliding.clear();
    let e = kinematic::analyse_local(&asm, &st, &settings, 0).expect_err("no mechanism");
    assert!(
        matches!(e, KinematicError::LocalFoundNothing { joints: 1, .. }),
        "{e}"
    );
    assert!(e.to_string().contains("proves nothing"));
    st.hinges.clear();
    assert!(matches!(
        kinematic::analyse_local(&asm, &st, &settings, 8),
        Err(KinematicError::LocalNoCentres)
    ));
    // A thin semicircle cannot stand: no local search.
    let thin = common::model_of(&common::semicircle(0.05, 64));
    let st = statics::analyse(&thin, &StaticSettings::default()).expect("static");
    assert_eq!(st.status, Status::CannotStand);
    assert!(matches!(
        kinematic::analyse_local(&thin, &st, &settings, 8),
        Err(KinematicError::LocalNeedsCollapse(_))
    ));
}

/// Acceptance: semicircles of 500 and 1000 voussoirs (t/R 0.15, 0.25), pointed and basket arches
/// and portals of 400-1000 joints, through `analysis::analyse` with its defaults (as
/// `voussoir analyze`): the exhaustive search is skipped, the local one runs, and its upper
/// bound meets the static lower bound within 1e-6 max(1, lambda): lambda_c is certified.
#[test]
fn local_bound_meets_static_on_large_chains() {
    let cases: Vec<(String, Scene)> = vec![
        ("semicircle 0.15 n500".into(), common::semicircle(0.15, 500)),
        ("semicircle 0.25 n500".into(), common::semicircle(0.25, 500)),
        (
            "semicircle 0.15 n1000".into(),
            common::semicircle(0.15, 1000),
        ),
        (
            "semicircle 0.25 n1000".into(),
            common::semicircle(0.25, 1000),
        ),
        ("pointed e0.1 n350".into(), pointed(0.1, 0.15, 350)),
        ("pointed e0.05 n600".into(), pointed(0.05, 0.15, 600)),
        ("basket n800".into(), basket(0.15, 800)),
        ("portal n400".into(), portal(400, 20, "inf")),
        ("portal n900".into(), portal(900, 50, "inf")),
    ];
    for (label, scene) in cases {
        let a = analysis::analyse(&scene, &Options::default()).expect("analysis");
        assert!(a.model.assembly.joints.len() > analysis::KINEMATIC_DEFAULT_MAX_JOINTS);
        assert_eq!(a.lower.status, Status::Collapse, "{label}");
        // The analysis certifies the static multiplier with the mechanism of its hinges.
        assert_eq!(a.kinematic_search, Some(Search::Certified), "{label}");
        let l = a.lower.lambda.expect("lower");
        let tol = 1e-6 * l.abs().max(1.0);
        let uc = a.lambda_upper().expect("certified upper bound");
        assert!((uc - l).abs() <= tol, "{label}: lower {l}, certified {uc}");
        assert!(a.gap().is_some_and(|g| g <= 1e-6), "{label}");
        assert!(!a.sliding_governs(), "{label}");
        let json = serde_json::to_value(AnalysisReport::new(&scene, &a)).expect("json");
        assert_eq!(json["kinematic_search"], "certified", "{label}");
        assert_eq!(json["lambda_upper"].as_f64(), Some(uc));
        // The local search, the fallback when certification fails, meets it too.
        let k = kinematic::analyse_local(
            &a.model,
            &a.lower,
            &KinematicSettings::default(),
            analysis::KINEMATIC_LOCAL_WINDOW,
        )
        .expect("local search result");
        assert_eq!(k.search, Search::Local);
        assert_eq!(k.status, Status::Collapse, "{label}");
        let u = k.lambda_upper.expect("upper");
        assert!((u - l).abs() <= tol, "{label}: lower {l}, upper {u}");
        // The window holds the certified mechanism, so the local least multiplier is at most it.
        assert!(
            u <= uc * (1.0 + 1e-12),
            "{label}: local {u} above the certified {uc}"
        );
        assert!(k
            .note
            .as_deref()
            .is_some_and(|n| n.contains("not an exhaustive search")));
    }
}

/// Finite friction where sliding governs (a low segmental arch, mu = 0.2, 401 joints): the static
/// bound slides and falls below every rotational mechanism, so the local rotational bound is
/// strictly above it and `sliding_governs` holds.
#[test]
fn sliding_governs_with_a_local_bound() {
    let scene = common::scene(
        "[arch]\nshape = \"circular\"\nradius = 1.0\nembrace_deg = 100\nthickness = 0.25\nvoussoirs = 400\n[material]\nfriction = 0.2\n",
    );
    let a = analysis::analyse(&scene, &Options::default()).expect("analysis");
    assert_eq!(a.kinematic_search, Some(Search::Local));
    let l = a.lower.lambda.expect("lower");
    let u = a.lambda_upper().expect("rotational upper bound");
    assert!(!a.lower.sliding.is_empty(), "the static solution slides");
    assert!(u > l * (1.0 + 1e-3), "lower {l}, upper {u}");
    assert!(a.sliding_governs());
    let json = serde_json::to_value(AnalysisReport::new(&scene, &a)).expect("json");
    assert_eq!(json["sliding_governs"], true);
    assert_eq!(json["kinematic_search"], "local");
}

/// Above the limit with a static status other than collapse, no search runs, and it says why.
#[test]
fn no_local_search_when_static_is_not_collapse() {
    let scene = common::semicircle(0.05, 400);
    let exhaustive = Options {
        kinematic: analysis::KinematicMode::Exhaustive,
        ..Options::default()
    };
    let a = analysis::analyse(&scene, &exhaustive).expect("analysis");
    assert_eq!(a.lower.status, Status::CannotStand);
    assert_eq!(a.kinematic_search, None);
    assert!(a
        .upper
        .as_ref()
        .is_err_and(|e| e.contains("skipped") && e.contains("not collapse")));
    assert!(a.lambda_upper().is_none());
    // By default (certified), a structure that cannot stand without sliding needs no search:
    // the static program's infeasibility proves it, and the note says so.
    let a = analysis::analyse(&scene, &Options::default()).expect("analysis");
    assert_eq!(a.lower.status, Status::CannotStand);
    assert_eq!(a.kinematic_search, None);
    assert!(a.upper.as_ref().is_err_and(|e| e.contains("proves")));
    // Small chains: the certified bound by default, the exhaustive search on request, and the
    // two meet.
    let small = common::semicircle(0.15, 32);
    let c = analysis::analyse(&small, &Options::default()).expect("a");
    assert_eq!(c.kinematic_search, Some(Search::Certified));
    let json = serde_json::to_value(AnalysisReport::new(&small, &c)).expect("json");
    assert_eq!(json["kinematic_search"], "certified");
    let exhaustive = Options {
        kinematic: analysis::KinematicMode::Exhaustive,
        ..Options::default()
    };
    let a = analysis::analyse(&small, &exhaustive).expect("a");
    assert_eq!(a.kinematic_search, Some(Search::Exhaustive));
    let json = serde_json::to_value(AnalysisReport::new(&small, &a)).expect("json");
    assert_eq!(json["kinematic_search"], "exhaustive");
    assert!(json["kinematic_note"].is_null());
    let (uc, ue) = (c.lambda_upper().expect("c"), a.lambda_upper().expect("e"));
    assert!(
        (uc - ue).abs() <= 1e-12 * ue,
        "certified {uc}, exhaustive {ue}"
    );
    assert_eq!(
        c.upper
            .as_ref()
            .expect("c")
            .mechanism
            .as_ref()
            .expect("m")
            .hinges,
        a.upper
            .as_ref()
            .expect("e")
            .mechanism
            .as_ref()
            .expect("m")
            .hinges
    );
}
