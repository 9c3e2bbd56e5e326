//! The rest test of dynamic DEM runs (issue 28; `dem::rest`, docs/dem.md "The rest test"):
//! while the ground acceleration stays below the static multiplier's threshold the rigid
//! blocks stay at rest, so nothing is integrated; above it the run starts at the start of the
//! half-cycle that first reaches it, and ends as the full integration does.
//!
//! The threshold of a rectangular block b x h on the ground (no sliding), derived here: in the
//! frame of the ground the block carries `m (-a_h, -(g + a_v))` at its centroid, at height
//! h / 2 over the base; it tips about the leeward base corner, b / 2 from the centroid's
//! vertical, when the overturning moment `m |a_h| h / 2` passes the restoring one
//! `m (g + a_v) b / 2`. It stays at rest while `|a_h| < (b / h) (g + a_v)` and `g + a_v > 0`:
//! the static multiplier `lambda = b / h` in either direction, times the effective gravity.

use voussoir::analysis;
use voussoir::dem::dynamic::{self, DynamicResult, DynamicSettings, EndState};
use voussoir::dem::record::{Component, Excitation, GroundInput, GroundMotion, Pulse, PulseShape};
use voussoir::dem::rest::{self, RestTest, RestThreshold};
use voussoir::dem::IntegrationParameters;
use voussoir::model::Model;
use voussoir::scene::Scene;

use crate::common;

/// A rectangular block b x h standing on the ground, with friction `mu`.
fn block(b: f64, h: f64, mu: f64) -> Model {
    Model::self_weight(common::rect_block(b, h, mu))
}

/// A synthetic record sampled every 0.01 s for `duration` s: a sum of sines of
/// `freqs` Hz under a 0.5 s rise and fall, scaled to the peak `peak` (m/s^2).
fn record(duration: f64, freqs: &[f64], peak: f64) -> GroundMotion {
    let dt = 0.01;
    let n = (duration / dt).round() as usize;
    let time: Vec<f64> = (0..=n).map(|i| i as f64 * dt).collect();
    let raw: Vec<f64> = time
        .iter()
        .map(|&t| {
            let envelope = (t / 0.5).min(1.0).min((duration - t) / 0.5).max(0.0);
            envelope
                * freqs
                    .iter()
                    .enumerate()
                    .map(|(k, f)| {
                        (std::f64::consts::TAU * f * t + k as f64).sin() / (1.0 + k as f64)
                    })
                    .sum::<f64>()
        })
        .collect();
    let top = raw.iter().fold(0.0_f64, |m, a| m.max(a.abs()));
    GroundMotion {
        time,
        accel: raw.iter().map(|a| a * peak / top).collect(),
        source: "synthetic".into(),
    }
}

fn with_rest(rest_test: bool) -> DynamicSettings {
    DynamicSettings {
        rest_test,
        ..Default::default()
    }
}

fn threshold_of(m: &Model) -> RestThreshold {
    let p = IntegrationParameters::for_model(m);
    match rest::rest_test(m, &p) {
        RestTest::Applied(t) => t,
        other => panic!("rest test not applied: {other:?}"),
    }
}

/// The static thresholds of a block are b / h both ways, and the test compares the horizontal
/// ground acceleration with b / h times the effective gravity `g + a_v`; a block that slides
/// in its static mechanism (finite friction) gets no rest test.
#[test]
fn threshold_of_a_block_is_b_over_h_times_the_effective_gravity() {
    let (b, h) = (0.25, 1.0);
    let m = block(b, h, f64::INFINITY);
    let th = threshold_of(&m);
    let lambda = b / h;
    assert!((th.lambda_right / lambda - 1.0).abs() < 1e-8, "{th:?}");
    assert!((th.lambda_left / lambda - 1.0).abs() < 1e-8, "{th:?}");
    assert!(th.homogeneous, "self-weight alone is the seismic weight");
    assert_eq!(th.gravity, IntegrationParameters::for_model(&m).gravity);
    let g = th.gravity;
    for a_v in [-0.3 * g, 0.0, 0.3 * g] {
        let limit = lambda * (g + a_v);
        for sign in [1.0, -1.0] {
            assert!(th.holds(sign * 0.999 * limit, a_v), "a_v {a_v}, {sign}");
            assert!(!th.holds(sign * 1.001 * limit, a_v), "a_v {a_v}, {sign}");
        }
    }
    // The ground falling faster than a free body: nothing holds the block down.
    assert!(!th.holds(0.0, -1.01 * g));
    // A squat block on mu = 0.4 slides (b / h = 2 > mu): the associative multiplier bounds the
    // real collapse from above, so rest below it is not certain.
    let sliding = block(1.0, 0.5, 0.4);
    let p = IntegrationParameters::for_model(&sliding);
    match rest::rest_test(&sliding, &p) {
        RestTest::NotApplicable(why) => assert!(why.contains("slide"), "{why}"),
        other => panic!("expected not applicable: {other:?}"),
    }
    // The running-bond wall with infinite friction (the DEM's Coulomb coefficient 1000): no
    // joint slides in its static mechanism (exact, 1.0), but its head joints carry no
    // compression and real joints collapse lower (the DEM at 0.85, docs/friction.md), so
    // rest below 1.0 is not certain either.
    let wall = common::model_of(&common::scene(&format!(
        "[blocks]\nground_y = 0.0\npolygons = {}\n",
        common::rect_polygons(&common::running_bond_wall_rects())
    )));
    let p = IntegrationParameters::for_model(&wall);
    match rest::rest_test(&wall, &p) {
        RestTest::NotApplicable(why) => assert!(why.contains("may collapse lower"), "{why}"),
        other => panic!("expected not applicable: {other:?}"),
    }
}

/// The first exceedance and the start of its half-cycle on a hand-made record (lambda = 0.25,
/// no vertical motion): samples every 0.1 s of 0.1 g, -0.1 g, 0.05 g, 0.3 g, 0. The record
/// passes 0.25 g between 0.2 s (0.05 g) and 0.3 s (0.3 g), at 0.2 + 0.1 (0.2 / 0.25) = 0.28 s;
/// that half-cycle started where it crossed zero from -0.1 g (0.1 s) to 0.05 g (0.2 s), at
/// 0.1 + 0.1 (0.1 / 0.15) = 0.1667 s.
#[test]
fn first_exceedance_and_half_cycle_start_of_a_hand_record() {
    let g = 9.80665;
    let th = RestThreshold {
        lambda_right: 0.25,
        lambda_left: 0.25,
        gravity: g,
        homogeneous: true,
        solve_time_s: 0.0,
    };
    let motion = |accel: Vec<f64>| -> GroundInput {
        Excitation::Record(GroundMotion {
            time: (0..accel.len()).map(|i| 0.1 * i as f64).collect(),
            accel: accel.iter().map(|a| a * g).collect(),
            source: "hand".into(),
        })
        .into()
    };
    let plan = rest::plan(&motion(vec![0.1, -0.1, 0.05, 0.3, 0.0]), &th);
    let first = plan.first_exceedance.expect("exceeds");
    let start = plan.integration_start.expect("starts");
    assert!((first - 0.28).abs() < 1e-6, "{first}");
    assert!((start - (0.1 + 0.1 / 1.5)).abs() < 1e-12, "{start}");
    // Toward -x the same way (the ground accelerating toward -x pushes the blocks toward +x).
    let plan = rest::plan(&motion(vec![-0.1, 0.1, -0.05, -0.3, 0.0]), &th);
    assert!((plan.integration_start.expect("starts") - (0.1 + 0.1 / 1.5)).abs() < 1e-12);
    // Below everywhere: never.
    let plan = rest::plan(&motion(vec![0.1, -0.24, 0.2, 0.0]), &th);
    assert_eq!(plan.integration_start, None);
    assert_eq!(plan.first_exceedance, None);
    // A rectangular pulse above the threshold starts at once; a sine's first half-cycle
    // starts at 0, its second (when only the negative half exceeds one side) at T / 2.
    let rect: GroundInput =
        Excitation::Pulse(Pulse::new(PulseShape::Rect, 0.3 * g, 0.5).unwrap()).into();
    assert_eq!(rest::plan(&rect, &th).integration_start, Some(0.0));
    let one_sided = RestThreshold {
        lambda_left: 0.5,
        ..th
    };
    let sine: GroundInput =
        Excitation::Pulse(Pulse::new(PulseShape::Sine, 0.3 * g, 1.0).unwrap()).into();
    assert_eq!(rest::plan(&sine, &one_sided).integration_start, Some(0.5));
    // A vertical motion alone lifts nothing until g + a_v <= 0.
    let vertical = GroundInput::new(
        Excitation::Pulse(Pulse::new(PulseShape::Rect, -0.9 * g, 0.5).unwrap()),
        Component::Y,
        None,
    )
    .unwrap();
    assert_eq!(rest::plan(&vertical, &th).integration_start, None);
}

/// A record with a vertical component that stays below the threshold everywhere: with the
/// rest test the block is exactly at rest (nothing integrated, not even the settling); the
/// full integration shows only the contacts' elastic micro-motion. Its bound, stated: the
/// settled overlap of each base corner is `delta = W / (2 kn)`; under the largest effective
/// gravity (1.3 g) and a moment up to the threshold the leeward corner at most doubles it and
/// the windward one unloads, a tilt of at most `2.6 delta / b`, and a load arriving at once
/// rings a spring to twice its static deflection: the tolerance is `6 delta / b` (about 1e-4
/// rad here, 4e-4 of the block's slenderness).
#[test]
fn sub_threshold_record_is_rest_exactly_and_agrees_with_the_full_integration() {
    let (b, h) = (0.25, 1.0);
    let m = block(b, h, f64::INFINITY);
    let p = IntegrationParameters::for_model(&m);
    let g = p.gravity;
    let lambda = b / h;
    let peak_v = 0.3 * g;
    let horizontal = record(4.0, &[1.3, 2.2, 3.1], 0.9 * lambda * (g - peak_v));
    let vertical = record(4.0, &[4.7, 6.1], peak_v);
    let ground = GroundInput::new(
        Excitation::Record(horizontal),
        Component::X,
        Some(Excitation::Record(vertical)),
    )
    .expect("motion");
    let skipped = dynamic::respond_input(&m, &p, &ground, &with_rest(true)).expect("run");
    assert_eq!(skipped.rest_test.name(), "applied");
    assert_eq!(skipped.integration_start, None);
    assert_eq!(skipped.first_exceedance, None);
    assert_eq!(skipped.steps, 0);
    assert_eq!(skipped.end_state, EndState::AtRest);
    assert_eq!(skipped.status(), "survives");
    assert_eq!(
        (skipped.peak_displacement, skipped.peak_rotation),
        (0.0, 0.0)
    );
    assert_eq!(
        (skipped.residual_displacement, skipped.residual_rotation),
        (0.0, 0.0)
    );
    // The history is the rest's, with the ground's accelerations at its times.
    assert!(skipped.history.len() > 600);
    for s in &skipped.history {
        assert_eq!((s.displacement, s.rotation), (0.0, 0.0));
        let a = ground.at(s.time);
        assert_eq!(
            (s.ground_acceleration, s.ground_acceleration_vertical),
            (a.x, a.y)
        );
    }
    let full = dynamic::respond_input(&m, &p, &ground, &with_rest(false)).expect("run");
    assert_eq!(full.rest_test, RestTest::Off);
    assert_eq!(full.integration_start, Some(0.0));
    assert_eq!(full.status(), "survives");
    let delta = m.assembly.blocks[0].weight / (2.0 * p.normal_stiffness);
    let tolerance = 6.0 * delta / b;
    eprintln!(
        "full integration: peak rotation {:.3e} rad, peak displacement {:.3e} m (tolerance {tolerance:.3e} rad), {} steps",
        full.peak_rotation, full.peak_displacement, full.steps
    );
    assert!(full.peak_rotation < tolerance, "{}", full.peak_rotation);
    assert!(
        full.peak_displacement < tolerance * h,
        "{}",
        full.peak_displacement
    );
    assert!(full.residual_rotation.abs() < tolerance);
}

/// A record that shakes below the threshold for 3 s (0.6 of it), then carries one sine
/// cycle above it: with and without the rest test the block does the same thing. The two runs
/// differ only in the state at the start of the half-cycle that first exceeds (at rest,
/// settled, against the full integration's elastic vibration of about 1e-5 rad left by the
/// earlier shaking), a difference of the size of the micro-motion, which one pulse of rocking
/// carries along without growing it much: the same outcome, collapse times within 0.01 s and
/// peak rotations within 1% (measured: 0.4 ms and 0.07%).
#[test]
fn exceeding_record_gives_the_same_outcome_with_and_without_the_rest_test() {
    let (b, h) = (0.25, 1.0);
    let m = block(b, h, f64::INFINITY);
    let p = IntegrationParameters::for_model(&m);
    let g = p.gravity;
    let lambda = b / h;
    let shaking = record(3.0, &[1.7, 2.9, 4.3], 0.6 * lambda * g);
    for (amplitude, period, falls) in [(1.3, 0.6, false), (1.4, 1.0, true)] {
        let mut time = shaking.time.clone();
        let mut accel = shaking.accel.clone();
        let pulse = Pulse::new(PulseShape::Sine, amplitude * lambda * g, period).unwrap();
        let n = (period / 0.01).round() as usize;
        for i in 1..=n + 50 {
            let t = 0.01 * i as f64;
            time.push(3.0 + t);
            accel.push(pulse.at(t));
        }
        let ground: GroundInput = Excitation::Record(GroundMotion {
            time,
            accel,
            source: "shaking and a pulse".into(),
        })
        .into();
        let settings = |rest| DynamicSettings {
            tail: 3.0,
            ..with_rest(rest)
        };
        let with = dynamic::respond_input(&m, &p, &ground, &settings(true)).expect("run");
        let without = dynamic::respond_input(&m, &p, &ground, &settings(false)).expect("run");
        let start = with.integration_start.expect("integrated");
        let first = with.first_exceedance.expect("exceeds");
        eprintln!(
            "pulse {amplitude} lambda g, T {period}: with the test from {start:.4} s (first exceedance {first:.4} s): {} at {:?}, peak rotation {:.5} rad, {} steps; without: {} at {:?}, peak {:.5} rad, {} steps",
            with.status(), with.collapse_time, with.peak_rotation, with.steps,
            without.status(), without.collapse_time, without.peak_rotation, without.steps
        );
        assert!(start >= 3.0 && start <= first, "{start} {first}");
        assert!(with.steps < without.steps);
        assert_eq!(with.status(), without.status());
        assert_eq!(with.collapsed, falls);
        match (with.collapse_time, without.collapse_time) {
            (Some(a), Some(b)) => assert!((a - b).abs() < 0.01, "{a} {b}"),
            (None, None) => {
                let (a, b) = (with.peak_rotation, without.peak_rotation);
                assert!(a > 0.1 * (b / h).atan(), "the block rocked: {a}");
                assert!((a / b - 1.0).abs() < 0.01, "{a} {b}");
            }
            other => panic!("{other:?}"),
        }
    }
}

/// An arch under records that exceed its threshold (an 8-voussoir semicircle, t / R = 0.15,
/// 1.2 and 1.4 times its threshold at the peak): the same outcome with and without the rest
/// test. Where it survives, peak displacements within 1% (measured 0.06%). Where it collapses,
/// it does so by displacements accumulated over several exceedances, and the collapse time is
/// sensitive to the smallest change of the run: the full integration itself collapses at 2.73,
/// 3.91 and 2.71 s with time steps 1, 0.98 and 0.96 times the default. The rest test's
/// collapse time must lie within that spread of the full integration (widened by 0.05 s), not
/// closer than the integration is to itself.
#[test]
fn arch_under_an_exceeding_record_with_and_without_the_rest_test() {
    let scene = Scene::from_toml_str(
        "[arch]\nshape = \"circular\"\nradius = 1.0\nthickness = 0.15\nvoussoirs = 8\n\
         [material]\nfriction = 0.8\n",
        "arch",
    )
    .expect("scene");
    let model = voussoir::scene::build(&scene).expect("model");
    let p = analysis::dem_parameters(&scene, &model).expect("params");
    let th = threshold_of(&model);
    let lambda = th.lambda_right.min(th.lambda_left);
    let run = |f: f64, rest: bool, factor: f64| -> DynamicResult {
        let ground: GroundInput =
            Excitation::Record(record(4.0, &[1.1, 2.3, 3.7], f * lambda * p.gravity)).into();
        let s = DynamicSettings {
            history_every: None,
            ..with_rest(rest)
        };
        let params = IntegrationParameters {
            time_step_factor: p.time_step_factor * factor,
            ..p.clone()
        };
        dynamic::respond_input(&model, &params, &ground, &s).expect("run")
    };
    let (with, without) = (run(1.2, true, 1.0), run(1.2, false, 1.0));
    eprintln!(
        "1.2 x threshold: with the test from {:?} s: {}, peak displacement {:.4e} m, {} steps; without: {}, peak {:.4e} m, {} steps",
        with.integration_start, with.status(), with.peak_displacement, with.steps,
        without.status(), without.peak_displacement, without.steps
    );
    assert!(with.integration_start.is_some_and(|t| t > 0.0));
    assert_eq!((with.status(), without.status()), ("survives", "survives"));
    let (a, b) = (with.peak_displacement, without.peak_displacement);
    assert!((a / b - 1.0).abs() < 0.01, "{a} {b}");
    let with = run(1.4, true, 1.0);
    let full: Vec<DynamicResult> = [1.0, 0.98, 0.96]
        .into_iter()
        .map(|factor| run(1.4, false, factor))
        .collect();
    let times: Vec<f64> = full.iter().filter_map(|r| r.collapse_time).collect();
    eprintln!(
        "1.4 x threshold: with the test from {:?} s: collapse at {:?}; full integration at time steps x1, x0.98, x0.96: {times:?}",
        with.integration_start, with.collapse_time
    );
    assert_eq!(times.len(), 3, "the full integration collapses");
    let t = with
        .collapse_time
        .expect("collapses with the rest test too");
    let lo = times.iter().fold(f64::INFINITY, |m, x| m.min(*x));
    let hi = times.iter().fold(0.0_f64, |m, x| m.max(*x));
    assert!(t >= lo - 0.05 && t <= hi + 0.05, "{t} outside [{lo}, {hi}]");
}

/// The IDA's scales whose motion stays below the threshold cost no integration: with a
/// horizontal record the test is exact at the samples, so a scale is integrated exactly when
/// its peak reaches lambda g.
#[test]
fn ida_scales_below_the_threshold_cost_nothing() {
    let (b, h) = (0.25, 1.0);
    let m = block(b, h, f64::INFINITY);
    let p = IntegrationParameters::for_model(&m);
    let lambda = b / h;
    let pga = 0.3 * lambda * p.gravity;
    let ground: GroundInput = Excitation::Record(record(3.0, &[1.3, 2.1], pga)).into();
    let r = dynamic::ida_input(&m, &p, &ground, &with_rest(true), 0.05, 100.0).expect("IDA");
    assert_eq!(r.rest_test.name(), "applied");
    assert_eq!(r.runs.len(), r.integration_starts.len());
    let mut skipped = 0;
    for ((scale, collapsed), start) in r.runs.iter().zip(&r.integration_starts) {
        let below = scale * pga < (1.0 - rest::REST_MARGIN) * lambda * p.gravity;
        assert_eq!(start.is_none(), below, "scale {scale}");
        if below {
            assert!(!collapsed);
            skipped += 1;
        }
    }
    eprintln!(
        "IDA: {} runs, {skipped} below the threshold, bracket [{}, {:?}]",
        r.runs.len(),
        r.scale_survives,
        r.scale_collapses
    );
    assert!(skipped >= 2, "scales 1 and 2 stay below: {:?}", r.runs);
    assert!(r.scale_collapses.is_some());
}

/// The command line says what the rest test did, in the JSON and the summary; `--rest-test
/// off` integrates from the start.
#[test]
fn cli_reports_the_rest_test() {
    let (dir, scene) = common::scene_file(
        "[arch]\nshape = \"circular\"\nradius = 1.0\nthickness = 0.15\nvoussoirs = 8\n\
         [material]\nfriction = 0.8\n",
    );
    let rec = dir.path().join("quiet.txt");
    let text: Vec<String> = (0..100)
        .map(|i| format!("{}", 0.05 * (0.3 * i as f64).sin()))
        .collect();
    std::fs::write(&rec, text.join("\n")).expect("record");
    let json = |extra: &[&str]| -> serde_json::Value {
        let out = common::voussoir()
            .args(["dem", "--record"])
            .arg(&rec)
            .args(["--dt", "0.01", "--units", "g", "--tail", "0.2", "--json"])
            .args(extra)
            .arg(&scene)
            .assert()
            .success();
        serde_json::from_slice(&out.get_output().stdout).expect("JSON")
    };
    let on = json(&[]);
    assert_eq!(on["rest_test"], "applied");
    assert!(on["integration_start_s"].is_null());
    assert!(on["first_exceedance_s"].is_null());
    assert!(on["rest_test_note"].is_null());
    assert_eq!(on["steps"], 0);
    assert_eq!(on["status"], "survives");
    let right = on["rest_lambda_right"].as_f64().expect("number");
    let left = on["rest_lambda_left"].as_f64().expect("number");
    // A symmetric arch: the same threshold both ways, above the record's 0.05 g.
    assert!(
        (right / left - 1.0).abs() < 1e-6 && right > 0.05,
        "{right} {left}"
    );
    let off = json(&["--rest-test", "off"]);
    assert_eq!(off["rest_test"], "off");
    assert_eq!(off["integration_start_s"], 0.0);
    assert!(off["rest_lambda_right"].is_null());
    assert!(off["steps"].as_u64().expect("steps") > 0);
    // Without a motion the flag means nothing, and is refused.
    common::voussoir()
        .args(["dem", "--rest-test", "off"])
        .arg(&scene)
        .assert()
        .failure();
}
