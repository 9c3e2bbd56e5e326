//! Live loads: `[action] kind = "live"` makes lambda the adequacy factor of the loads marked
//! `live = true` (issue 22). Closed forms and virtual work derived here, agreement of the
//! bounds over shapes and load positions, the DEM's bracket, and the refusals.

use crate::common;

use voussoir::analysis::{self, KinematicMode, Options};
use voussoir::geometry::Vec2;
use voussoir::model::Action;
use voussoir::scene::Scene;
use voussoir::statics::Status;

fn scene(text: &str) -> Scene {
    Scene::from_toml_str(text, "test").unwrap_or_else(|e| panic!("scene: {e}\n{text}"))
}

fn exhaustive() -> Options {
    Options {
        kinematic: KinematicMode::Exhaustive,
        ..Options::default()
    }
}

/// A single block b x h on the ground with a live horizontal load P at height y on its left
/// face: it overturns about its right toe when P y lambda = W b / 2 (no sliding), so
/// lambda = W b / (2 P y).
#[test]
fn single_block_overturned_by_a_live_push() {
    let (b, h, gamma) = (0.4, 1.5, 20000.0);
    let w = gamma * b * h;
    for (p, y) in [(1000.0, 1.0), (2500.0, 0.4), (300.0, 1.5)] {
        let text = format!(
            "[blocks]\npolygons = [[[0, 0], [{b}, 0], [{b}, {h}], [0, {h}]]]\n[material]\nunit_weight = {gamma}\nfriction = \"inf\"\n[action]\nkind = \"live\"\n[[loads]]\ntype = \"point\"\nat = [0.0, {y}]\nforce = [{p}, 0.0]\nlive = true\n"
        );
        let a = analysis::analyse(&scene(&text), &exhaustive()).expect("analysis");
        let expected = w * b / (2.0 * p * y);
        let lower = a.lower.lambda.expect("collapse");
        assert!(
            (lower - expected).abs() <= 1e-9 * expected,
            "P = {p}, y = {y}: static {lower}, closed form {expected}"
        );
        let upper = a.lambda_upper().expect("upper bound");
        assert!(
            (upper - expected).abs() <= 1e-9 * expected,
            "P = {p}, y = {y}: kinematic {upper}, closed form {expected}"
        );
        assert!(a.lower.equilibrium_residual <= 1e-9 * w);
    }
}

/// The lambda of a four-hinge mechanism of an arch chain, by virtual work computed here:
/// blocks before hinge A's joint are still; block group AB turns about A, CD about D, and BC
/// about the instantaneous centre where lines AB and DC meet. `loads` are `(block, point,
/// force)` of the permanent loads and `live` those lambda multiplies.
pub(crate) fn four_hinge_lambda(
    hinges: &[(usize, Vec2)],
    permanent: &[(usize, Vec2, Vec2)],
    live: &[(usize, Vec2, Vec2)],
) -> f64 {
    assert_eq!(hinges.len(), 4);
    let (ja, a) = hinges[0];
    let (jb, b) = hinges[1];
    let (jc, c) = hinges[2];
    let (jd, d) = hinges[3];
    // Lines A + s (B - A) and D + r (C - D) meet at I.
    let (u, v) = (b - a, c - d);
    let det = u.x * (-v.y) - u.y * (-v.x);
    let rhs = d - a;
    let s = (rhs.x * (-v.y) - rhs.y * (-v.x)) / det;
    let i = a + s * u;
    // Rotation rates: w1 about A; B moves alike on both sides: w1 (B - A) = w2 (B - I).
    let w1 = 1.0;
    let w2 = w1 * (b - a).dot(&(b - i)) / (b - i).norm_squared();
    let w3 = w2 * (c - i).dot(&(c - d)) / (c - d).norm_squared();
    let velocity = |block: usize, p: Vec2| -> Vec2 {
        let (w, o) = if block < ja {
            (0.0, a)
        } else if block < jb {
            (w1, a)
        } else if block < jc {
            (w2, i)
        } else if block < jd {
            (w3, d)
        } else {
            (0.0, d)
        };
        let r = p - o;
        Vec2::new(-w * r.y, w * r.x)
    };
    let power = |loads: &[(usize, Vec2, Vec2)]| -> f64 {
        loads
            .iter()
            .map(|&(blk, p, f)| f.dot(&velocity(blk, p)))
            .sum()
    };
    -power(permanent) / power(live)
}

/// A semicircle with a live point load at quarter span: the static multiplier equals the
/// virtual work of its own four hinges, valued here from the blocks' weights and the load.
#[test]
fn semicircle_live_point_load_by_virtual_work() {
    for (t, n, p) in [(0.12, 16, 2000.0), (0.15, 24, 5000.0), (0.13, 40, 800.0)] {
        let base = format!(
            "[arch]\nshape = \"circular\"\nradius = 1.0\nthickness = {t}\nvoussoirs = {n}\n"
        );
        let bare = common::model_of(&scene(&base));
        // The load at quarter span, on the extrados chord of the voussoir over x = -0.5.
        let k = bare
            .assembly
            .blocks
            .iter()
            .position(|blk| {
                let xs: Vec<f64> = blk.polygon.iter().map(|q| q.x).collect();
                let lo = xs.iter().cloned().fold(f64::INFINITY, f64::min);
                let hi = xs.iter().cloned().fold(f64::NEG_INFINITY, f64::max);
                lo <= -0.5 && -0.5 <= hi
            })
            .expect("a voussoir over quarter span");
        let at = bare.assembly.blocks[k].centroid;
        let text = format!(
            "{base}[action]\nkind = \"live\"\n[[loads]]\ntype = \"point\"\nat = [{}, {}]\nforce = [0.0, {}]\nlive = true\n",
            at.x, at.y, -p
        );
        let a = analysis::analyse(&scene(&text), &Options::default()).expect("analysis");
        assert_eq!(a.lower.status, Status::Collapse);
        let lower = a.lower.lambda.expect("collapse");
        let hinges: Vec<(usize, Vec2)> = a
            .lower
            .hinges
            .iter()
            .map(|h| (h.joint, Vec2::new(h.x, h.y)))
            .collect();
        let permanent: Vec<(usize, Vec2, Vec2)> = bare
            .assembly
            .blocks
            .iter()
            .enumerate()
            .map(|(i, blk)| (i, blk.centroid, Vec2::new(0.0, -blk.weight)))
            .collect();
        let live = [(k, at, Vec2::new(0.0, -p))];
        let vw = four_hinge_lambda(&hinges, &permanent, &live);
        assert!(
            (lower - vw).abs() <= 1e-9 * vw.abs().max(1.0),
            "t = {t}, n = {n}: static {lower}, virtual work of its hinges {vw}"
        );
        assert!(lower > 0.0);
    }
}

/// Static = exhaustive kinematic to 1e-9 with a live point load moved over the voussoirs of
/// every shape, and over the arch of a portal.
#[test]
fn static_equals_kinematic_over_shapes_and_load_positions() {
    let shapes = [
        "[arch]\nshape = \"circular\"\nradius = 1.0\nthickness = 0.12\nvoussoirs = 18\n",
        "[arch]\nshape = \"circular\"\nradius = 1.0\nembrace_deg = 140\nthickness = 0.1\nvoussoirs = 14\n",
        "[arch]\nshape = \"pointed\"\nradius = 1.0\neccentricity = 0.2\nthickness = 0.12\nvoussoirs = 16\n",
        "[arch]\nshape = \"basket\"\nspan = 2.0\nrise = 0.7\nthickness = 0.12\nvoussoirs = 18\n",
        "[arch]\nshape = \"circular\"\nradius = 1.0\nthickness = 0.2\nvoussoirs = 16\n[piers]\nheight = 1.0\nwidth = 0.4\ncourses = 3\n",
    ];
    let mut checked = 0;
    for base in shapes {
        let bare = common::model_of(&scene(base));
        let voussoirs: Vec<usize> = bare
            .assembly
            .blocks
            .iter()
            .enumerate()
            .filter(|(_, b)| matches!(b.kind, voussoir::assembly::BlockKind::Voussoir(_)))
            .map(|(i, _)| i)
            .collect();
        for &i in voussoirs.iter().step_by(3) {
            let at = bare.assembly.blocks[i].centroid;
            let text = format!(
                "{base}[material]\nfriction = \"inf\"\n[action]\nkind = \"live\"\n[[loads]]\ntype = \"point\"\nat = [{}, {}]\nforce = [0.0, -3000.0]\nlive = true\n",
                at.x, at.y
            );
            let a = analysis::analyse(&scene(&text), &exhaustive()).expect("analysis");
            match (a.lower.status, a.lower.lambda, a.lambda_upper()) {
                (Status::Collapse, Some(l), Some(u)) => {
                    assert!(
                        (l - u).abs() <= 1e-9 * l.abs().max(1.0),
                        "{base} load on block {i}: static {l}, kinematic {u}"
                    );
                    checked += 1;
                }
                (status, l, u) => {
                    // A load over a hinge-free region may never collapse it: both must say so.
                    let k = a.upper.as_ref().expect("kinematic ran").status;
                    assert_eq!(status, k, "{base} block {i}: static {l:?}, kinematic {u:?}");
                }
            }
        }
    }
    assert!(checked >= 15, "only {checked} collapses compared");
}

/// Under a seismic action a load marked live is a permanent load without seismic mass: the
/// same as `seismic = false`.
#[test]
fn live_on_a_seismic_action_changes_nothing() {
    let base = "[arch]\nshape = \"circular\"\nradius = 1.0\nthickness = 0.15\nvoussoirs = 20\n";
    let load = |flag: &str| {
        format!(
            "{base}[[loads]]\ntype = \"point\"\nat = [0.4, 0.95]\nforce = [0.0, -2000.0]\n{flag}\n[[loads]]\ntype = \"line\"\nfrom_x = -0.8\nto_x = -0.2\nintensity = 1500.0\n{flag}\n"
        )
    };
    let opts = exhaustive();
    let live = analysis::analyse(&scene(&load("live = true")), &opts).expect("live");
    let plain = analysis::analyse(&scene(&load("seismic = false")), &opts).expect("plain");
    assert_eq!(live.lower.lambda, plain.lower.lambda);
    assert_eq!(live.lambda_upper(), plain.lambda_upper());
    assert_eq!(live.lower.hinges, plain.lower.hinges);
    assert_eq!(live.model.loads.action(), Action::Seismic);
    // Both directions too.
    let left = Options {
        static_settings: opts
            .static_settings
            .clone()
            .direction(voussoir::statics::Direction::Left),
        ..exhaustive()
    };
    let live_l = analysis::analyse(&scene(&load("live = true")), &left).expect("live");
    let plain_l = analysis::analyse(&scene(&load("seismic = false")), &left).expect("plain");
    assert_eq!(live_l.lower.lambda, plain_l.lower.lambda);
}

/// Mirror invariance: the load and the arch mirrored about x = 0 give the same factor.
#[test]
fn live_factor_is_mirror_invariant() {
    let base = "[arch]\nshape = \"pointed\"\nradius = 1.0\neccentricity = 0.25\nthickness = 0.1\nvoussoirs = 24\n";
    let at = |x: f64| {
        format!(
            "{base}[action]\nkind = \"live\"\n[[loads]]\ntype = \"line\"\nfrom_x = {}\nto_x = {}\nintensity = 4000.0\nlive = true\n",
            x, x + 0.3
        )
    };
    let right = analysis::analyse(&scene(&at(0.2)), &exhaustive()).expect("right");
    let left = analysis::analyse(&scene(&at(-0.5)), &exhaustive()).expect("left");
    let (r, l) = (
        right.lower.lambda.expect("r"),
        left.lower.lambda.expect("l"),
    );
    assert!((r - l).abs() <= 1e-9 * r, "mirrored factors {r} and {l}");
    let (ru, lu) = (
        right.lambda_upper().expect("r"),
        left.lambda_upper().expect("l"),
    );
    assert!((ru - lu).abs() <= 1e-9 * ru);
    assert!((ru - r).abs() <= 1e-9 * r);
}

/// The continuous model takes the live line load too: with curved voussoirs its factor is
/// at most the discrete one (its hinge sections include the discrete joints), and the
/// discrete one tends to it as the voussoirs multiply.
#[test]
fn continuous_model_takes_live_loads() {
    let text = |n: usize| {
        format!(
            "[arch]\nshape = \"circular\"\nradius = 1.0\nthickness = 0.12\nvoussoirs = {n}\nvoussoir_shape = \"curved\"\n[action]\nkind = \"live\"\n[[loads]]\ntype = \"line\"\nfrom_x = -0.9\nto_x = -0.1\nintensity = 3000.0\nlive = true\n"
        )
    };
    let opts = Options {
        continuous: true,
        ..Options::default()
    };
    let mut previous_gap = f64::INFINITY;
    for n in [16, 64, 256] {
        let a = analysis::analyse(&scene(&text(n)), &opts).expect("analysis");
        let discrete = a.lower.lambda.expect("collapse");
        let cont = a
            .continuous
            .as_ref()
            .expect("ran")
            .as_ref()
            .expect("continuous")
            .lambda_continuous
            .expect("collapse");
        let gap = discrete - cont;
        assert!(
            gap >= -1e-9 * cont,
            "n = {n}: discrete {discrete} below continuous {cont}"
        );
        assert!(
            gap <= previous_gap + 1e-12,
            "n = {n}: gap {gap} grew from {previous_gap}"
        );
        previous_gap = gap;
    }
    assert!(
        previous_gap <= 2e-3,
        "discrete n = 256 still {previous_gap} above the continuum"
    );
}

/// The DEM's bracket `[stands, collapses]` contains the static adequacy factor.
#[test]
fn dem_bracket_contains_the_static_factor() {
    let text = "[arch]\nshape = \"circular\"\nradius = 1.0\nthickness = 0.15\nvoussoirs = 12\n[material]\nfriction = 0.8\n[action]\nkind = \"live\"\n[[loads]]\ntype = \"point\"\nat = [-0.45, 0.9]\nforce = [0.0, -4000.0]\nlive = true\n";
    let s = scene(text);
    let d = analysis::dem(
        &s,
        &analysis::DemOptions {
            tolerance: 0.05,
            ..analysis::DemOptions::default()
        },
        &mut |_| {},
    )
    .expect("dem");
    let lower = d.lower.lambda.expect("static collapse");
    let stands = d.result.lambda_stands.expect("a load it stands");
    let collapses = d.result.lambda_collapses.expect("a load it collapses");
    assert!(
        stands <= lower * (1.0 + 1e-9) && lower <= collapses * (1.0 + 0.02),
        "DEM bracket [{stands}, {collapses}] against the static {lower}"
    );
}

/// What a live action refuses, each naming what was wrong.
#[test]
fn live_action_refusals() {
    let arch = "[arch]\nshape = \"circular\"\nradius = 1.0\nthickness = 0.15\nvoussoirs = 12\n";
    let live_load =
        "[[loads]]\ntype = \"point\"\nat = [0.3, 0.95]\nforce = [0.0, -1000.0]\nlive = true\n";
    let refused = |text: String, needle: &str| {
        let e = Scene::from_toml_str(&text, "t.toml")
            .expect_err("refused")
            .to_string();
        assert!(e.contains(needle), "{e}\nshould mention {needle}");
    };
    refused(format!("{arch}[action]\nkind = \"live\"\n"), "live = true");
    refused(
        format!("{arch}[action]\nkind = \"live\"\n[seismic]\nvertical_ratio = 0.1\n{live_load}"),
        "[seismic]",
    );
    refused(
        format!("{arch}[action]\nkind = \"quake\"\n{live_load}"),
        "kind",
    );
    refused(
        format!("{arch}[[loads]]\ntype = \"point\"\nat = [0.3, 0.95]\nforce = [0.0, -1.0]\nlive = true\nseismic = true\n"),
        "seismic mass",
    );
    refused(
        format!("{arch}[fill]\nlevel = 1.3\nlive = true\n[action]\nkind = \"live\"\n{live_load}"),
        "fill",
    );
    let s = scene(&format!("{arch}[action]\nkind = \"live\"\n{live_load}"));
    let e = analysis::direction_for(&s, Some(voussoir::statics::Direction::Left))
        .expect_err("direction refused")
        .to_string();
    assert!(e.contains("--direction") && e.contains("live"), "{e}");
    assert!(analysis::direction_for(&s, None).is_ok());
    let e = voussoir::thickness::min_thickness(&s, &Default::default())
        .expect_err("min thickness refused")
        .to_string();
    assert!(e.contains("minimum thickness"), "{e}");
}
