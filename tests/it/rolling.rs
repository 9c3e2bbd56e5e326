//! Moving loads and the spread of loads through the fill (issue 29, items 1 and 2): a live
//! point load rolled over a semicircle (its least multiplier against a golden-section search
//! written here and the virtual work of its own mechanism, the critical position mirrored),
//! the spread against the equivalent line load and Flamant's closed form, the built-in load
//! models, and bad input named by its key.

use crate::common;
use crate::live_loads::four_hinge_lambda;
use voussoir::analysis::{self, Options};
use voussoir::geometry::Vec2;
use voussoir::model::Model;
use voussoir::roll::{self, RollSpec, Target};
use voussoir::scene::Scene;
use voussoir::statics::Status;

const R: f64 = 1.0;
const T: f64 = 0.2;
const N: usize = 16;

fn base() -> String {
    format!("[arch]\nshape = \"circular\"\nradius = {R}\nthickness = {T}\nvoussoirs = {N}\n")
}

fn scene(text: &str) -> Scene {
    Scene::from_toml_str(text, "test").expect("valid test scene")
}

/// The extrados of the polygon-voussoir semicircle at `x`: the chord between the extrados
/// corners `(R + t/2) (cos a_j, sin a_j)`, `a_j = pi (1 - j/n)`; and the voussoir under x.
fn extrados(x: f64) -> (f64, usize) {
    let re = R + 0.5 * T;
    let corner = |j: usize| {
        let a = std::f64::consts::PI * (1.0 - j as f64 / N as f64);
        Vec2::new(re * a.cos(), re * a.sin())
    };
    for j in 0..N {
        let (a, b) = (corner(j), corner(j + 1));
        if a.x <= x && x <= b.x {
            return (a.y + (x - a.x) / (b.x - a.x) * (b.y - a.y), j);
        }
    }
    panic!("x = {x} is off the arch");
}

/// The semicircle with a live point load `p` (N, down) on the extrados at `x`.
fn loaded(x: f64, p: f64) -> String {
    format!(
        "{}[action]\nkind = \"live\"\n[[loads]]\ntype = \"point\"\nat = [{x:?}, {:?}]\nforce = [0.0, {:?}]\nlive = true\n",
        base(),
        extrados(x).0,
        -p
    )
}

fn static_lambda(text: &str) -> f64 {
    let options = Options {
        kinematic_max_joints: 0,
        ..Options::default()
    };
    analysis::analyse(&scene(text), &options)
        .expect("analysis")
        .lower
        .lambda
        .expect("a multiplier")
}

/// The test's own golden-section search for the least of `f` over `[lo, hi]`.
fn golden(mut lo: f64, mut hi: f64, f: impl Fn(f64) -> f64) -> (f64, f64) {
    let r = 0.5 * (5f64.sqrt() - 1.0);
    let (mut c, mut d) = (hi - r * (hi - lo), lo + r * (hi - lo));
    let (mut fc, mut fd) = (f(c), f(d));
    while hi - lo > 1e-11 {
        if fc <= fd {
            hi = d;
            d = c;
            fd = fc;
            c = hi - r * (hi - lo);
            fc = f(c);
        } else {
            lo = c;
            c = d;
            fc = fd;
            d = lo + r * (hi - lo);
            fd = f(d);
        }
    }
    if fc <= fd {
        (c, fc)
    } else {
        (d, fd)
    }
}

fn roll_of(text: &str, target: Target, from: f64, to: f64, step: f64) -> roll::Roll {
    let spec = RollSpec {
        target,
        from,
        to,
        step,
        refine: true,
    };
    roll::roll(&scene(text), &spec, &Options::default()).expect("roll")
}

/// A live point load rolled over a semicircle: the least multiplier of the roll is the least
/// of a golden-section search of the test's own around the grid's least value, and the
/// virtual work of the mechanism of the critical position (1e-8); the bounds agree at every
/// position.
#[test]
fn rolled_point_load_minimum_is_golden_section_and_virtual_work() {
    let p = 3000.0;
    let text = loaded(-0.5, p);
    let r = roll_of(&text, Target::Load(0), -0.8, 0.8, 0.05);
    assert_eq!(r.points.len(), 33);
    for q in &r.points {
        let (l, u) = (
            q.lambda_lower.expect("lower"),
            q.lambda_upper.expect("upper"),
        );
        assert!(
            (l - u).abs() <= 1e-8 * l.max(1.0),
            "x = {}: {l} vs {u}",
            q.position
        );
    }
    let c = r.critical.as_ref().expect("a critical position");
    let lambda = c.analysis.lower.lambda.expect("collapse");
    // The grid's least value, and the search of the test between its neighbours.
    let i = (0..r.points.len())
        .min_by(|&i, &j| {
            r.points[i]
                .lambda_lower
                .unwrap()
                .total_cmp(&r.points[j].lambda_lower.unwrap())
        })
        .unwrap();
    assert_eq!(r.points[i].position, c.grid_position);
    let (lo, hi) = (r.points[i - 1].position, r.points[i + 1].position);
    let (x_g, lambda_g) = golden(lo, hi, |x| static_lambda(&loaded(x, p)));
    assert!(
        (lambda - lambda_g).abs() <= 1e-8 * lambda_g,
        "roll {lambda} at {}, golden section {lambda_g} at {x_g}",
        c.position
    );
    assert!(lambda <= r.points[i].lambda_lower.unwrap() + 1e-12);
    // The virtual work of the critical position's own hinges, from the blocks' weights and
    // the load at (x, extrados(x)).
    let model: Model = common::model_of(&c.scene);
    let hinges: Vec<(usize, Vec2)> = c
        .analysis
        .lower
        .hinges
        .iter()
        .map(|h| (h.joint, Vec2::new(h.x, h.y)))
        .collect();
    let permanent: Vec<(usize, Vec2, Vec2)> = model
        .assembly
        .blocks
        .iter()
        .enumerate()
        .map(|(k, b)| (k, b.centroid, Vec2::new(0.0, -b.weight)))
        .collect();
    // The block that carries the load is the placement's (a load within round-off of a
    // joint rests on the first block in chain order); its point is the extrados at x.
    let (y, _) = extrados(c.position);
    let carrier = model
        .loads
        .applied()
        .iter()
        .find(|a| a.live)
        .expect("the live load")
        .block;
    let vw = four_hinge_lambda(
        &hinges,
        &permanent,
        &[(carrier, Vec2::new(c.position, y), Vec2::new(0.0, -p))],
    );
    assert!(
        (lambda - vw).abs() <= 1e-8 * vw,
        "roll {lambda}, virtual work {vw}"
    );
    let upper = c.analysis.lambda_upper().expect("upper bound");
    assert!(
        (upper - vw).abs() <= 1e-8 * vw,
        "kinematic {upper}, vw {vw}"
    );
}

/// The symmetric arch's critical position is found on both sides: rolled over the left half
/// and over the right half, the critical positions are mirror images with the same
/// multiplier; over the whole span the multipliers of mirrored positions agree.
#[test]
fn critical_position_is_found_on_both_sides() {
    let text = loaded(-0.5, 2000.0);
    let left = roll_of(&text, Target::Load(0), -0.8, 0.0, 0.04);
    let right = roll_of(&text, Target::Load(0), 0.0, 0.8, 0.04);
    let (l, r) = (left.critical.unwrap(), right.critical.unwrap());
    let (ll, lr) = (
        l.analysis.lower.lambda.unwrap(),
        r.analysis.lower.lambda.unwrap(),
    );
    assert!(l.position < 0.0 && r.position > 0.0);
    assert!(
        (l.position + r.position).abs() < 1e-6,
        "{} vs {}",
        l.position,
        r.position
    );
    assert!((ll - lr).abs() <= 1e-8 * ll, "{ll} vs {lr}");
    let whole = roll_of(&text, Target::Load(0), -0.8, 0.8, 0.1);
    let m = whole.points.len();
    for i in 0..m {
        let (a, b) = (&whole.points[i], &whole.points[m - 1 - i]);
        assert!((a.position + b.position).abs() < 1e-12);
        let (la, lb) = (a.lambda_lower.unwrap(), b.lambda_lower.unwrap());
        assert!(
            (la - lb).abs() <= 1e-8 * la,
            "x = {}: {la} vs {lb}",
            a.position
        );
    }
    // The critical multiplier of the whole span is that of either side.
    let lw = whole.critical.unwrap().analysis.lower.lambda.unwrap();
    assert!((lw - ll).abs() <= 1e-8 * ll, "{lw} vs {ll}");
}

/// A one-axle vehicle on the bare arch is the point load on the extrados below it; a
/// two-axle vehicle rolled is the same roll as the scene with its axles as two point loads.
#[test]
fn vehicle_axles_are_point_loads_on_the_top() {
    let x = -0.37;
    let (y, _) = extrados(x);
    let vehicle = format!(
        "{}[action]\nkind = \"live\"\n[[vehicles]]\nname = \"one\"\naxles = [[0.0, 2500.0]]\nat = {x:?}\n",
        base()
    );
    let point = format!(
        "{}[action]\nkind = \"live\"\n[[loads]]\ntype = \"point\"\nat = [{x:?}, {y:?}]\nforce = [0.0, -2500.0]\nlive = true\n",
        base()
    );
    assert_same_loads(
        &common::model_of(&scene(&vehicle)),
        &common::model_of(&scene(&point)),
        1e-12,
    );
    let (a, b) = (static_lambda(&vehicle), static_lambda(&point));
    assert!((a - b).abs() <= 1e-12 * a, "{a} vs {b}");
    // A tandem rolled: each position against its axles written as point loads.
    let tandem = format!(
        "{}[action]\nkind = \"live\"\n[[vehicles]]\naxles = [[0.0, 1500.0], [0.6, 1000.0]]\nat = -0.9\n",
        base()
    );
    let r = roll_of(&tandem, Target::Vehicle(0), -0.9, 0.3, 0.3);
    assert_eq!(r.points.len(), 5);
    for q in &r.points {
        let (x0, x1) = (q.position, q.position + 0.6);
        let text = format!(
            "{}[action]\nkind = \"live\"\n[[loads]]\ntype = \"point\"\nat = [{x0:?}, {:?}]\nforce = [0.0, -1500.0]\nlive = true\n[[loads]]\ntype = \"point\"\nat = [{x1:?}, {:?}]\nforce = [0.0, -1000.0]\nlive = true\n",
            base(),
            extrados(x0).0,
            extrados(x1).0
        );
        let l = static_lambda(&text);
        let got = q.lambda_lower.unwrap();
        assert!(
            (got - l).abs() <= 1e-10 * l,
            "at {}: {got} vs {l}",
            q.position
        );
    }
}

/// Every block's permanent and live resultants of two models agree to `tol` (relative to
/// the largest force).
fn assert_same_loads(a: &Model, b: &Model, tol: f64) {
    assert_eq!(a.loads.len(), b.loads.len());
    let scale = a.loads.force_scale().max(1.0);
    for i in 0..a.loads.len() {
        for (wa, wb) in [
            (a.loads.permanent(i), b.loads.permanent(i)),
            (a.loads.variable(i, 1.0), b.loads.variable(i, 1.0)),
        ] {
            let d = (wa.force - wb.force).norm() + (wa.moment - wb.moment).abs();
            assert!(d <= tol * scale, "block {i}: {wa:?} vs {wb:?}");
        }
    }
}

/// The filled semicircle: fill to `level`, `spread` keys, and a live load at `at`.
fn filled(level: f64, spread: &str, load: &str) -> String {
    format!(
        "{}[fill]\nlevel = {level:?}\nunit_weight = 18000.0\n{spread}\n[action]\nkind = \"live\"\n{load}",
        base()
    )
}

/// A point load on the fill spread at an angle is the line load `F / w` over the width
/// `w = 2 d tan(theta)` under it, `d` the depth of fill under the load (1e-12); spread 0 is
/// the point load on the extrados below it.
#[test]
fn spread_point_load_is_the_equivalent_line_load() {
    let (level, f) = (1.3, 4000.0);
    for (x, deg) in [(-0.42, 26.6f64), (0.13, 45.0), (-0.71, 10.0)] {
        let (y, _) = extrados(x);
        let d = level - y;
        let w = 2.0 * d * deg.to_radians().tan();
        let on_fill = filled(
            level,
            &format!("spread_deg = {deg:?}"),
            &live_point([x, level], [0.0, -f]),
        );
        let line = filled(
            level,
            "",
            &format!(
                "[[loads]]\ntype = \"line\"\nfrom_x = {:?}\nto_x = {:?}\nintensity = {:?}\nlive = true\n",
                x - 0.5 * w,
                x + 0.5 * w,
                f / w
            ),
        );
        let (ms, ml) = (
            common::model_of(&scene(&on_fill)),
            common::model_of(&scene(&line)),
        );
        assert_same_loads(&ms, &ml, 1e-12);
        assert!((ms.loads.live_magnitude() - f).abs() <= 1e-12 * f);
        let (a, b) = (static_lambda(&on_fill), static_lambda(&line));
        assert!((a - b).abs() <= 1e-12 * a, "{deg} deg: {a} vs {b}");
        // The continuous model takes the spread as the line load it is.
        let ca = analysis::continuous(&scene(&on_fill), voussoir::statics::Direction::Right)
            .expect("continuous");
        let cb = analysis::continuous(&scene(&line), voussoir::statics::Direction::Right)
            .expect("continuous");
        let (ca, cb) = (ca.lambda_continuous.unwrap(), cb.lambda_continuous.unwrap());
        assert!((ca - cb).abs() <= 1e-9 * ca, "{ca} vs {cb}");
        // Spread 0: the point load on the extrados below.
        let zero = filled(
            level,
            "spread_deg = 0.0",
            &live_point([x, level], [0.0, -f]),
        );
        let below = filled(level, "", &live_point([x, y], [0.0, -f]));
        assert_same_loads(
            &common::model_of(&scene(&zero)),
            &common::model_of(&scene(&below)),
            1e-12,
        );
        let (a, b) = (static_lambda(&zero), static_lambda(&below));
        assert!((a - b).abs() <= 1e-12 * a, "spread 0: {a} vs {b}");
    }
}

/// A load with no fill above the arch is unchanged: a vehicle on a fill whose surface is the
/// crown extrados, standing at the crown, is the point load there, whatever the spread law.
#[test]
fn no_fill_above_leaves_the_load_unchanged() {
    let crown = R + 0.5 * T;
    let point = filled(crown, "", &live_point([0.0, crown], [0.0, -3000.0]));
    for law in ["spread_deg = 30.0", "spread = \"boussinesq\""] {
        let vehicle = filled(
            crown,
            law,
            "[[vehicles]]\naxles = [[0.0, 3000.0]]\nat = 0.0\n",
        );
        assert_same_loads(
            &common::model_of(&scene(&vehicle)),
            &common::model_of(&scene(&point)),
            1e-12,
        );
    }
}

/// Boussinesq: the share of the load the arch carries is Flamant's between the ends of the
/// extrados, `F [Q(x_r - x) - Q(x_l - x)]`, `Q(u) = (atan(u/d) + u d / (u^2 + d^2)) / pi`
/// (the rest rests on the ground beyond the springings), and its moment about the load's
/// line is Flamant's too.
#[test]
fn boussinesq_spread_carries_flamant_share() {
    let (level, f) = (1.6, 5000.0);
    let re = R + 0.5 * T;
    for x in [-0.3, 0.0, 0.55] {
        let (y, _) = extrados(x);
        let d = level - y;
        let text = filled(
            level,
            "spread = \"boussinesq\"",
            &live_point([x, level], [0.0, -f]),
        );
        let model = common::model_of(&scene(&text));
        let q = |u: f64| ((u / d).atan() + u * d / (u * u + d * d)) / std::f64::consts::PI;
        let m = |u: f64| -d.powi(3) / (std::f64::consts::PI * (u * u + d * d));
        let share = f * (q(re - x) - q(-re - x));
        let moment = f * (m(re - x) - m(-re - x));
        assert!(
            (model.loads.live_magnitude() - share).abs() <= 1e-12 * f,
            "{} vs {share}",
            model.loads.live_magnitude()
        );
        // The moment of the live loads about the vertical through the load: sum of
        // -force_y (x_i - x) over the live pieces.
        let about: f64 = model
            .loads
            .applied()
            .iter()
            .filter(|a| a.live)
            .map(|a| -a.force.y * (a.point.x - x))
            .sum();
        assert!((about - moment).abs() <= 1e-12 * f, "{about} vs {moment}");
        assert!(share < f && share > 0.5 * f);
    }
}

/// The built-in load models: LM1's tandem (2 x 300 kN at 1.2 m) and LM71 (4 x 250 kN at
/// 1.6 m, 80 kN/m from 0.8 m beyond the outer axles to the ends of the top).
#[test]
fn built_in_load_models() {
    let big = "[arch]\nshape = \"circular\"\nradius = 6.0\nthickness = 0.8\nvoussoirs = 24\n";
    let lm1 = scene(&format!(
        "{big}[action]\nkind = \"live\"\n[[vehicles]]\nname = \"EN1991-2 LM1\"\nat = -2.0\n"
    ));
    assert_eq!(lm1.vehicles[0].axles, vec![(0.0, 300e3), (1.2, 300e3)]);
    assert!((common::model_of(&lm1).loads.live_magnitude() - 600e3).abs() < 1e-6);
    let at = -3.0;
    let lm71 = scene(&format!(
        "{big}[action]\nkind = \"live\"\n[[vehicles]]\nname = \"EN1991-2 LM71\"\nat = {at}\n"
    ));
    let v = &lm71.vehicles[0];
    assert_eq!(v.axles.len(), 4);
    assert!(v.axles.iter().all(|a| a.1 == 250e3));
    assert!((v.axles[3].0 - 4.8).abs() < 1e-12);
    // The extrados runs over |x| <= R + t/2; the distributed load covers it but for the
    // 0.8 + 4.8 + 0.8 m over the axles.
    let re = 6.4;
    let covered = (at - 0.8 + re) + (re - (at + 4.8 + 0.8));
    let expected = 1000e3 + 80e3 * covered;
    let got = common::model_of(&lm71).loads.live_magnitude();
    assert!(
        (got - expected).abs() <= 1e-9 * expected,
        "{got} vs {expected}"
    );
    let a = analysis::analyse(&lm71, &Options::default()).expect("analysis");
    assert_eq!(a.lower.status, Status::Collapse);
    assert!(a.gap().unwrap() < 1e-8);
}

/// A live point load's `[[loads]]` entry.
fn live_point(at: [f64; 2], force: [f64; 2]) -> String {
    format!(
        "[[loads]]\ntype = \"point\"\nat = [{:?}, {:?}]\nforce = [{:?}, {:?}]\nlive = true\n",
        at[0], at[1], force[0], force[1]
    )
}

/// Bad input is refused with the key, the file and the value named.
#[test]
fn bad_input_names_the_key() {
    let live = "[action]\nkind = \"live\"\n";
    let cases: [(String, &str, &str); 10] = [
        (
            format!(
                "{}{live}[[vehicles]]\naxles = [[0.0, 1000.0], [1.5, 1000.0]]\nat = 0.0\n",
                base()
            ),
            "vehicles[0].at",
            "x = 1.5",
        ),
        (
            filled(
                1.3,
                "spread_deg = -5.0",
                &live_point([0.0, 1.3], [0.0, -1.0]),
            ),
            "fill.spread_deg",
            "-5",
        ),
        (
            filled(
                1.3,
                "spread = \"elastic\"",
                &live_point([0.0, 1.3], [0.0, -1.0]),
            ),
            "fill.spread",
            "elastic",
        ),
        (
            filled(
                1.3,
                "spread = \"boussinesq\"\nspread_deg = 30.0",
                &live_point([0.0, 1.3], [0.0, -1.0]),
            ),
            "fill.spread",
            "boussinesq",
        ),
        (
            filled(1.3, "surface = 0.5", &live_point([0.0, 1.3], [0.0, -1.0])),
            "fill.surface",
            "0.5",
        ),
        (
            format!(
                "{}{live}[[vehicles]]\naxles = [[0.0, -1000.0]]\nat = 0.0\n",
                base()
            ),
            "vehicles[0].axles",
            "-1000",
        ),
        (
            format!(
                "{}{live}[[vehicles]]\nname = \"EN1991-2 LM1\"\naxles = [[0.0, 1.0]]\nat = 0.0\n",
                base()
            ),
            "vehicles[0].axles",
            "built-in",
        ),
        (
            format!("{}{live}[[vehicles]]\nname = \"lorry\"\nat = 0.0\n", base()),
            "vehicles[0].axles",
            "EN1991-2 LM71",
        ),
        (
            filled(1.3, "", &live_point([0.0, 1.2], [500.0, -1.0])),
            "loads[0].force",
            "500",
        ),
        (
            filled(1.3, "", &live_point([0.0, 1.5], [0.0, -1.0])),
            "loads[0].at",
            "1.5",
        ),
    ];
    for (text, key, value) in cases {
        let e = Scene::from_toml_str(&text, "bridge.toml")
            .and_then(|s| voussoir::scene::build(&s).map(|_| ()))
            .expect_err(key);
        let message = e.to_string();
        assert_eq!(e.key(), Some(key), "{message}");
        assert!(
            message.contains("bridge.toml") && message.contains(value),
            "{key}: {message}"
        );
    }
    // The roll's own settings.
    let text = loaded(-0.5, 1000.0);
    let s = scene(&text);
    let spec = |target, from, to, step| RollSpec {
        target,
        from,
        to,
        step,
        refine: true,
    };
    let opts = Options::default();
    let e = roll::roll(&s, &spec(Target::Load(3), -0.5, 0.5, 0.1), &opts).unwrap_err();
    assert!(e.to_string().contains("loads[3]"), "{e}");
    let e = roll::roll(&s, &spec(Target::Load(0), -0.5, 0.5, 0.0), &opts).unwrap_err();
    assert!(e.to_string().contains("--step"), "{e}");
    let e = roll::roll(&s, &spec(Target::Load(0), 0.5, -0.5, 0.1), &opts).unwrap_err();
    assert!(e.to_string().contains("--to"), "{e}");
    // A point load rolled off the arch.
    let e = roll::roll(&s, &spec(Target::Load(0), 0.5, 1.5, 0.25), &opts).unwrap_err();
    assert!(e.to_string().contains("loads[0].at"), "{e}");
    assert!("vehicle[0]".parse::<Target>().is_err());
}

/// `analyze --roll --json`: the analysis at the critical position with a `roll` object of
/// the positions and both bounds at each; `--roll-svg` writes the chart.
#[test]
fn cli_roll_json_and_chart() {
    let text = format!(
        "{}[fill]\nlevel = 1.4\nspread_deg = 26.6\n[action]\nkind = \"live\"\n[[vehicles]]\nname = \"tandem\"\naxles = [[0.0, 1500.0], [0.3, 1500.0]]\nat = -0.5\n",
        base()
    );
    let (dir, path) = common::scene_file(&text);
    let chart = dir.path().join("roll.svg");
    let out = common::voussoir()
        .args([
            "analyze",
            "--json",
            "--roll",
            "vehicles[0]",
            "--from",
            "-1.0",
            "--to",
            "0.7",
            "--step",
            "0.1",
            "--roll-svg",
        ])
        .arg(&chart)
        .arg(&path)
        .output()
        .expect("runs");
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).expect("JSON");
    let r = &v["roll"];
    assert_eq!(r["target"], "vehicles[0]");
    let positions = r["positions"].as_array().unwrap();
    assert_eq!(positions.len(), 18);
    let lower: Vec<f64> = r["lambda_lower"]
        .as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect();
    let least = lower.iter().cloned().fold(f64::INFINITY, f64::min);
    let critical = common::f64_of(&v, "lambda_lower");
    assert!(critical <= least + 1e-12, "{critical} vs {least}");
    assert!(r["critical_position"].as_f64().is_some());
    assert_eq!(v["vehicles"][0]["name"], "tandem");
    assert_eq!(v["fill"]["spread_deg"], 26.6);
    let svg = std::fs::read_to_string(&chart).expect("chart written");
    assert!(svg.contains("<svg") && svg.contains("critical position"));
    // The same scene without the flags prints no roll object.
    let plain = common::json_of(&["analyze", "--json"], &text);
    assert!(plain.get("roll").is_none());
}
