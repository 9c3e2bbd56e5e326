//! Dynamic DEM runs against Housner's rocking block (Housner 1963, "The behavior of inverted
//! pendulum structures during earthquakes", BSSA 53:403-417), closed forms derived here for a
//! rectangular block of width b and height h on rigid ground, with R the half-diagonal,
//! alpha = atan(b / h) its slenderness and p = sqrt(3 g / (4 R)) its frequency parameter
//! (polar inertia about a base corner I_O = (4/3) m R^2).

use voussoir::dem::dynamic::{self, DynamicSettings};
use voussoir::dem::record::{Pulse, PulseShape};
use voussoir::dem::{IntegrationParameters, Simulation};
use voussoir::geometry::Vec2;
use voussoir::model::Model;

use crate::common;

const G: f64 = 9.81;

/// A rectangular block b x h standing on the ground, no sliding.
fn block(b: f64, h: f64) -> Model {
    Model::self_weight(common::rect_block(b, h, f64::INFINITY))
}

struct Housner {
    alpha: f64,
    p: f64,
}

fn housner(b: f64, h: f64) -> Housner {
    let r = 0.5 * (b * b + h * h).sqrt();
    Housner {
        alpha: (b / h).atan(),
        p: (3.0 * G / (4.0 * r)).sqrt(),
    }
}

fn settled(m: &Model) -> Simulation {
    let p = IntegrationParameters::for_model(m);
    let mut s = Simulation::new(m, &p).expect("simulation");
    s.settle(&m.assembly);
    s
}

/// Free rocking released from a tilt theta0 about the right base corner. About that corner
/// I_O theta'' = m g R sin(alpha - theta), linearised theta'' = p^2 (theta - alpha) with
/// theta the tilt: theta = alpha - (alpha - theta0) cosh(p t) reaches 0 (upright, the impact)
/// at cosh(p t) = alpha / (alpha - theta0): the time to the first impact is a quarter of
/// Housner's period T = (4 / p) acosh(1 / (1 - theta0 / alpha)). Housner's impact (the new
/// corner sticks, angular momentum about it conserved) keeps omega_after / omega_before =
/// 1 - 1.5 sin^2(alpha) of the angular speed.
#[test]
fn free_rocking_period_and_restitution() {
    let (b, h) = (0.2, 1.0);
    let k = housner(b, h);
    for ratio in [0.2, 0.5, 0.8] {
        let m = block(b, h);
        let mut s = settled(&m);
        let theta0 = ratio * k.alpha;
        s.rotate_block_about(0, Vec2::new(0.5 * b, 0.0), -theta0);
        s.set_ground_acceleration(0.0);
        s.set_local_damping(0.0);
        let t0 = s.time();
        let mut before = None;
        let mut impact = None;
        let mut after = None;
        let mark = 0.05 * theta0;
        while s.time() - t0 < 5.0 {
            s.step();
            let rot = s.blocks()[0].1;
            let om = s.velocities()[0].1.abs();
            if before.is_none() && rot > -mark {
                before = Some(om);
            }
            if impact.is_none() && rot >= 0.0 {
                impact = Some(s.time() - t0);
            }
            if impact.is_some() && after.is_none() && rot > mark {
                after = Some(om);
                break;
            }
        }
        let period = 4.0 * (1.0 / (1.0 - ratio)).acosh() / k.p;
        let t = 4.0 * impact.expect("impact");
        let e = after.expect("after") / before.expect("before");
        let housner_e = 1.0 - 1.5 * k.alpha.sin().powi(2);
        eprintln!(
            "theta0/alpha {ratio}: period {t:.5} s, Housner {period:.5} s ({:+.2}%), restitution {e:.4}, Housner {housner_e:.4}",
            100.0 * (t / period - 1.0),
        );
        assert!((t / period - 1.0).abs() < 0.02, "period {t} vs {period}");
        // Energy is lost at the impact (contact dashpots), and about as much as Housner's
        // sticking impact loses (docs/dem.md gives the DEM's own, a little less lossy).
        assert!(e < 1.0, "{e}");
        assert!(
            (e / housner_e - 1.0).abs() < 0.05,
            "restitution {e} vs {housner_e}"
        );
    }
}

/// Under a horizontal ground acceleration a the block uplifts when the inertial force m a
/// about the far base corner beats its weight: a > g tan(alpha) = g b / h. Ramped in over
/// 0.1 s (the contacts are springs: a step would ring them) and held for 2 s.
#[test]
fn no_uplift_below_g_tan_alpha() {
    let (b, h) = (0.2, 1.0);
    let m = block(b, h);
    let threshold = G * b / h;
    let p = IntegrationParameters::for_model(&m);
    let settings = DynamicSettings {
        tail: 0.0,
        ..Default::default()
    };
    let run = |f: f64| {
        let a = f * threshold;
        dynamic::respond(&m, &p, &|t: f64| a * (t / 0.1).min(1.0), 2.0, &settings)
            .expect("dynamic run")
    };
    let below = run(0.95);
    let above = run(1.05);
    let alpha = (b / h).atan();
    eprintln!(
        "0.95: peak rotation {:.3e} rad, 1.05: collapsed {} at {:?}",
        below.peak_rotation, above.collapsed, above.collapse_time
    );
    // Below: only the elastic tilt of the contact springs (overlaps of 3e-5 b).
    assert!(!below.collapsed);
    assert!(
        below.peak_rotation < 1e-3 * alpha,
        "{}",
        below.peak_rotation
    );
    assert!(above.collapsed);
}

/// A rectangular pulse of amplitude a and duration t1 overturns the block only above
/// a_min = g alpha / (1 - exp(-p t1)) (small angles: during the pulse theta'' = p^2 (theta +
/// u) with u = a / g - alpha, so theta = u (cosh p t1 - 1), theta' / p = u sinh p t1; the free
/// motion after it reaches the upright-over-the-corner position theta = alpha when theta' / p
/// >= alpha - theta, i.e. u (e^{p t1} - 1) >= alpha).
#[test]
fn rectangular_pulse_overturning_threshold() {
    let (b, h) = (0.1, 1.0);
    let m = block(b, h);
    let k = housner(b, h);
    let p = IntegrationParameters::for_model(&m);
    let settings = DynamicSettings {
        tail: 4.0,
        history_every: None,
        ..Default::default()
    };
    for x in [0.5_f64, 1.0] {
        let t1 = x / k.p;
        let a_min = G * k.alpha / (1.0 - (-x).exp());
        let run = |f: f64| {
            let pulse = Pulse::new(PulseShape::Rect, f * a_min, t1).expect("pulse");
            dynamic::respond(&m, &p, &|t: f64| pulse.at(t), t1, &settings).expect("run")
        };
        let (lo, hi) = (run(0.97), run(1.03));
        eprintln!(
            "p t1 = {x}: 0.97 a_min collapsed {} (peak {:.4} rad, alpha {:.4}), 1.03 collapsed {}",
            lo.collapsed, lo.peak_rotation, k.alpha, hi.collapsed
        );
        assert!(!lo.collapsed, "p t1 = {x}: overturned at 0.97 a_min");
        assert!(hi.collapsed, "p t1 = {x}: survived 1.03 a_min");
    }
}

/// The incremental dynamic analysis of a rectangular pulse finds Housner's threshold: the
/// collapse scale times the pulse amplitude brackets a_min = g alpha / (1 - exp(-p t1)) within
/// the 3% the direct runs show (p t1 = 1).
#[test]
fn ida_of_a_rectangular_pulse_finds_the_overturning_amplitude() {
    let (b, h) = (0.1, 1.0);
    let m = block(b, h);
    let k = housner(b, h);
    let p = IntegrationParameters::for_model(&m);
    let t1 = 1.0 / k.p;
    let a_min = G * k.alpha / (1.0 - (-1.0_f64).exp());
    // A unit pulse of a_min / 4: the IDA must double twice and then bisect.
    let pulse = Pulse::new(PulseShape::Rect, 0.25 * a_min, t1).expect("pulse");
    let settings = DynamicSettings {
        tail: 4.0,
        ..Default::default()
    };
    let r = dynamic::ida(&m, &p, &|t: f64| pulse.at(t), t1, &settings, 0.01, 100.0).expect("IDA");
    let hi = r.scale_collapses.expect("collapses");
    let lo = r.scale_survives;
    assert!(hi - lo <= 0.01 * hi && lo < hi, "[{lo}, {hi}]");
    let (a_lo, a_hi) = (lo * 0.25 * a_min, hi * 0.25 * a_min);
    eprintln!(
        "IDA: [{a_lo:.5}, {a_hi:.5}] m/s^2 against a_min {a_min:.5} ({} runs)",
        r.runs.len()
    );
    assert!(
        a_hi >= 0.97 * a_min && a_lo <= 1.03 * a_min,
        "[{a_lo}, {a_hi}] vs {a_min}"
    );
}

/// `voussoir dem --record` and `--pulse`: the JSON of a dynamic run, its history CSV, and a bad
/// record refused with the line named.
#[test]
fn cli_runs_records_and_pulses() {
    let dir = tempfile::tempdir().expect("tempdir");
    // A block of the user's own: the single block 0.2 x 1 as a scene.
    let scene = dir.path().join("block.toml");
    std::fs::write(
        &scene,
        "[blocks]\npolygons = [[[-0.1, 0.0], [0.1, 0.0], [0.1, 1.0], [-0.1, 1.0]]]\n[material]\nfriction = \"inf\"\n",
    )
    .expect("scene");
    let rec = dir.path().join("rec.csv");
    // Half the uplift threshold g tan(alpha) = 0.2 g for 0.5 s: the block stays put.
    std::fs::write(&rec, "time,acc\n0,0\n0.1,0.1\n0.4,0.1\n0.5,0\n").expect("record");
    let history = dir.path().join("h.csv");
    let out = common::voussoir()
        .args(["dem", "--json", "--record"])
        .arg(&rec)
        .arg("--history")
        .arg(&history)
        .arg(&scene)
        .assert()
        .success();
    let v: serde_json::Value = serde_json::from_slice(&out.get_output().stdout).expect("JSON");
    assert_eq!(v["status"], "survives", "{v}");
    assert!((v["pga"].as_f64().expect("pga") - 0.1 * 9.80665).abs() < 1e-12);
    assert!(v["peak_rotation"].as_f64().expect("rotation") < 1e-3);
    let h = std::fs::read_to_string(&history).expect("history");
    assert!(h.starts_with("time_s,ground_acceleration_m_s2,displacement_m,rotation_rad"));
    assert!(h.lines().count() > 50);
    // A rectangular pulse of 0.5 g for 1 s overturns it (far above g alpha / (1 - e^{-p t1})).
    let out = common::voussoir()
        .args([
            "dem",
            "--json",
            "--pulse",
            "rect",
            "--amplitude",
            "0.5",
            "--period",
            "1",
        ])
        .arg(&scene)
        .assert()
        .success();
    let v: serde_json::Value = serde_json::from_slice(&out.get_output().stdout).expect("JSON");
    assert_eq!(v["status"], "collapse", "{v}");
    // A bad record: the error names the file and the line.
    let bad = dir.path().join("bad.AT2");
    std::fs::write(
        &bad,
        "PEER\nEVENT\nACCELERATION TIME HISTORY IN UNITS OF G\nNPTS=    3, DT=   .0100 SEC\n0.1 0.2\n",
    )
    .expect("bad");
    let out = common::voussoir()
        .args(["dem", "--record"])
        .arg(&bad)
        .arg(&scene)
        .assert()
        .failure();
    let err = String::from_utf8_lossy(&out.get_output().stderr).to_string();
    assert!(
        err.contains("bad.AT2, line 4") && err.contains("NPTS = 3"),
        "{err}"
    );
}

/// A vertical ground acceleration a_v (upward positive) acts on the block as the body force
/// -m a_v: the effective gravity is g + a_v, and with no horizontal force nothing turns the
/// block. While g + a_v > 0 the ground keeps pushing up on it, so it never leaves the ground
/// (only the contact springs breathe); past a_v = -g (the ground falling faster than g) it
/// floats. Ramped in over 0.1 s, held 1 s; and one sine cycle of 0.9 g over 0.5 s.
#[test]
fn vertical_acceleration_below_g_never_uplifts() {
    let (b, h) = (0.2, 1.0);
    let m = block(b, h);
    let p = IntegrationParameters::for_model(&m);
    let settings = DynamicSettings {
        tail: 0.5,
        history_every: None,
        frames_every: Some(0.005),
        ..Default::default()
    };
    // Largest rise of the centroid and largest rotation over the run.
    let run = |ground: &dyn Fn(f64) -> Vec2, duration: f64| {
        let r = dynamic::respond_xy(&m, &p, ground, duration, &settings).expect("run");
        let y0 = r.start[0].0.y;
        let rise = r
            .frames
            .iter()
            .map(|f| f.blocks[0].0.y - y0)
            .fold(f64::NEG_INFINITY, f64::max);
        (r, rise)
    };
    // The block stands on its two base corners, each pressed into the ground by the spring
    // overlap W / (2 kn) under its weight (g + a_v scales it): the centroid can rise by less
    // than that while the corners still touch, and leaves the ground when it rises more.
    let overlap = 0.5 * m.assembly.blocks[0].weight / p.normal_stiffness;
    for a_v in [-0.9 * G, 0.9 * G] {
        let (r, rise) = run(&|t: f64| Vec2::new(0.0, a_v * (t / 0.1).min(1.0)), 1.1);
        eprintln!(
            "a_v = {:+.2} g held: rise {rise:.3e} m (overlap {overlap:.3e} m), peak rotation {:.3e} rad",
            a_v / G,
            r.peak_rotation
        );
        assert!(!r.collapsed);
        assert!(rise < overlap, "rose {rise} m: the corners left the ground");
        assert!(r.peak_rotation < 1e-9, "{}", r.peak_rotation);
    }
    let cycle = Pulse::new(PulseShape::Sine, 0.9 * G, 0.5).expect("pulse");
    let (r, rise) = run(&|t: f64| Vec2::new(0.0, cycle.at(t)), 0.5);
    eprintln!(
        "sine 0.9 g: rise {rise:.3e} m, peak rotation {:.3e}",
        r.peak_rotation
    );
    assert!(!r.collapsed);
    assert!(rise < overlap, "rose {rise} m: the corners left the ground");
    // Past -g the ground falls away from the block: it rises relative to the ground as
    // (-a_v - g) t^2 / 2 once the springs have let go.
    let a_v = -1.2 * G;
    let (_, rise) = run(&|t: f64| Vec2::new(0.0, a_v * (t / 0.1).min(1.0)), 0.5);
    eprintln!("a_v = -1.2 g: rise {rise:.3e} m");
    assert!(rise > 100.0 * overlap, "rose only {rise} m");
}

/// With a simultaneous vertical acceleration a_v (upward positive) the block is loaded by
/// m (g + a_v) down and m a_h sideways: moments about the far base corner, m a_h h/2 against
/// m (g + a_v) b/2, put the uplift at |a_h| = (g + a_v) tan(alpha). Both ramped in over 0.1 s,
/// held; the same +-5 % as the horizontal test (docs/dem.md), at a_v = +-0.3 g.
#[test]
fn uplift_under_simultaneous_vertical_acceleration() {
    let (b, h) = (0.2, 1.0);
    let m = block(b, h);
    let alpha = (b / h).atan();
    let p = IntegrationParameters::for_model(&m);
    let settings = DynamicSettings {
        tail: 0.0,
        history_every: None,
        ..Default::default()
    };
    for a_v in [0.3 * G, -0.3 * G] {
        let threshold = (G + a_v) * alpha.tan();
        let run = |f: f64| {
            let a_h = f * threshold;
            dynamic::respond_xy(
                &m,
                &p,
                &|t: f64| Vec2::new(a_h, a_v) * (t / 0.1).min(1.0),
                3.0,
                &settings,
            )
            .expect("run")
        };
        let (below, above) = (run(0.95), run(1.05));
        eprintln!(
            "a_v = {:+.1} g: threshold {threshold:.4} m/s^2; 0.95: peak rotation {:.3e}; 1.05: collapsed {} at {:?}",
            a_v / G,
            below.peak_rotation,
            above.collapsed,
            above.collapse_time
        );
        assert!(!below.collapsed);
        assert!(
            below.peak_rotation < 1e-3 * alpha,
            "{}",
            below.peak_rotation
        );
        assert!(
            above.collapsed,
            "a_v = {a_v}: no uplift at 1.05 (g + a_v) tan(alpha)"
        );
        // Not the horizontal-only threshold: at a_v = +0.3 g, 1.05 (g + a_v) tan(alpha) is
        // above it, at -0.3 g below it, and the block follows the combined one.
    }
}

/// A one-sine pulse `a sin(2 pi t / period)` on `[0, period]`.
fn sine(a: f64, period: f64) -> impl Fn(f64) -> f64 {
    move |t| {
        Pulse {
            shape: PulseShape::Sine,
            amplitude: a,
            period,
        }
        .at(t)
    }
}

/// Issue 26: the block 0.2 x 2 under one sine cycle of T = 0.29 s (omega_p / p = 8) at 7.6,
/// 8.0 and 12.0 m/s^2 ended the default 2 s tail past its overturning angle, the ground
/// still, and was reported as surviving. The end state is now decided by the state: each of
/// them collapses, as Housner's block (integrated in `common::housner_overturns`) does; and
/// below Housner's minimum (0.95 of it) the block survives, at rest or rocking with less
/// energy than it needs to tip.
#[test]
fn survival_is_decided_by_the_end_state_not_the_clock() {
    use voussoir::dem::dynamic::EndState;
    let (b, h) = (0.2, 2.0);
    let m = block(b, h);
    let p = IntegrationParameters::for_model(&m);
    let settings = DynamicSettings {
        history_every: None,
        ..Default::default()
    };
    assert_eq!(settings.tail, 2.0, "the default tail of the report");
    let period = 0.29;
    for a in [7.6, 8.0, 12.0] {
        assert!(common::housner_overturns(b, h, G, &sine(a, period), period));
        let r = dynamic::respond(&m, &p, &sine(a, period), period, &settings).expect("run");
        eprintln!(
            "{a} m/s^2: {} ({:?}) at {:?}, peak rotation {:.3} rad",
            r.status(),
            r.end_state,
            r.collapse_time,
            r.peak_rotation
        );
        assert!(
            r.collapsed && r.end_state == EndState::Collapsed,
            "{a}: {:?}",
            r.end_state
        );
        assert_eq!(r.status(), "collapse");
    }
    let housner = common::housner_minimum_amplitude(b, h, G, &|a, t| sine(a, period)(t), period);
    let a = 0.95 * housner;
    assert!(!common::housner_overturns(
        b,
        h,
        G,
        &sine(a, period),
        period
    ));
    let r = dynamic::respond(&m, &p, &sine(a, period), period, &settings).expect("run");
    eprintln!(
        "0.95 x Housner's {housner:.4}: {} ({:?}), decided {:.3} s past the tail",
        r.status(),
        r.end_state,
        r.extended
    );
    assert_eq!(r.status(), "survives");
    assert!(matches!(
        r.end_state,
        EndState::AtRest | EndState::Rocking | EndState::Settling
    ));
}

/// Both collapse criteria against Housner's overturning of the block 0.3 x 1 under one sine
/// cycle at omega_p / p = 4 (the minimum amplitude of `common::housner_minimum_amplitude`):
/// `overturning` (run on until at rest or fallen) survives 0.97 of it and falls at 1.03;
/// `displacement` (a block point moved by a quarter of the size) collapses at 1.03 too, and no
/// lower than 0.95 of it (measured 2.2% below: a block rocking past a quarter of its size
/// during the pulse is called collapsed although the ground could still have brought it back).
#[test]
fn displacement_and_overturning_criteria_against_housner() {
    use voussoir::dem::dynamic::Criterion;
    let (b, h) = (0.3, 1.0);
    let m = block(b, h);
    let k = housner(b, h);
    let p = IntegrationParameters::for_model(&m);
    let period = std::f64::consts::TAU / (4.0 * k.p);
    let a_h = common::housner_minimum_amplitude(b, h, G, &|a, t| sine(a, period)(t), period);
    let run = |criterion: Criterion, f: f64| {
        let settings = DynamicSettings {
            criterion,
            history_every: None,
            ..Default::default()
        };
        let r = dynamic::respond(&m, &p, &sine(f * a_h, period), period, &settings).expect("run");
        eprintln!(
            "{} at {f} x {a_h:.4}: {} ({:?}), collapse displacement {:.3} m",
            criterion.name(),
            r.status(),
            r.end_state,
            r.collapse_displacement
        );
        r
    };
    let below = run(Criterion::Overturning, 0.97);
    assert_eq!(below.status(), "survives");
    assert!(run(Criterion::Overturning, 1.03).collapsed);
    assert!(run(Criterion::Displacement, 1.03).collapsed);
    assert_eq!(run(Criterion::Displacement, 0.95).status(), "survives");
    // Overturning means a fall: a block point past the whole size, four times the
    // displacement criterion's quarter.
    let d = run(Criterion::Displacement, 1.03);
    let o = run(Criterion::Overturning, 1.03);
    assert!((o.collapse_displacement - 4.0 * d.collapse_displacement).abs() < 1e-12);
    assert!(o.collapse_time > d.collapse_time);
}

/// A ground motion that overflows the contact forces (1e300 m/s^2, only reachable through the
/// library: records and pulses refuse more than 100 g) ends in a typed error naming the
/// divergence, not a panic in the contact law (`f64::clamp` of a NaN panicked).
#[test]
fn an_overflowing_ground_motion_is_an_error_not_a_panic() {
    let m = block(0.2, 1.0);
    let p = IntegrationParameters::for_model(&m);
    let r = dynamic::respond(
        &m,
        &p,
        &|t: f64| if t < 0.01 { 1e300 } else { 0.0 },
        0.01,
        &DynamicSettings::default(),
    );
    let err = r.expect_err("diverges").to_string();
    assert!(err.contains("diverged"), "{err}");
}
