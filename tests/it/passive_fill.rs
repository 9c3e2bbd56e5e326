//! The fill's passive resistance (`[fill] passive = true`, issue 29 item 3): a single block
//! with the fill against one face gives the closed form of the overturning multiplier with
//! the Rankine passive force derived here; the static and the kinematic multipliers of filled
//! arches with passive resistance agree (both directions, seismic and live actions); the DEM's
//! bracket contains the static value; bad input is refused naming the key.

use crate::common;

use voussoir::analysis::{self, KinematicMode, Options};
use voussoir::outcome::Direction;
use voussoir::scene::Scene;
use voussoir::statics::{self, StaticSettings, Status};

const B: f64 = 0.6;
const H: f64 = 2.0;
/// The fill's level beside the block (below its top, so no fill rests on it).
const LEVEL: f64 = 1.2;
const GAMMA_MASONRY: f64 = 20000.0;
const GAMMA_FILL: f64 = 18000.0;
const PHI_DEG: f64 = 30.0;

/// A block `B x H` on a fixed base that reaches out to its right only, with a fill up to
/// `LEVEL` over the base: the fill lies against the block's right face alone.
fn block_scene(passive: &str) -> String {
    let (l, r) = (-0.5 * B, 0.5 * B);
    format!(
        "[blocks]\npolygons = [[[{l}, 0], [{r}, 0], [{r}, {H}], [{l}, {H}]], \
         [[{l}, -0.5], [4, -0.5], [4, 0], [{l}, 0]]]\nfixed = [[2.0, -0.25]]\n\
         [material]\nunit_weight = {GAMMA_MASONRY}\ndepth = 1.0\nfriction = \"inf\"\n\
         [fill]\nlevel = {LEVEL}\nunit_weight = {GAMMA_FILL}\n{passive}"
    )
}

fn static_lambda(scene: &Scene, direction: Direction) -> f64 {
    let model = common::model_of(scene);
    let r = statics::analyse(
        &model,
        &StaticSettings {
            direction,
            ..StaticSettings::default()
        },
    )
    .expect("the static program solves");
    assert_eq!(r.status, Status::Collapse, "{direction:?}");
    r.lambda.expect("a multiplier")
}

fn close(a: f64, b: f64, tol: f64) -> bool {
    (a - b).abs() <= tol * b.abs().max(1.0)
}

#[test]
fn a_block_with_fill_against_one_face_gives_the_closed_form() {
    // Rankine: K_p = tan^2(45 + phi/2); the mobilised pressure m K_p gamma (L - y) on the
    // face from y = 0 to L (per unit depth) sums to P_p = m K_p gamma L^2 / 2 and acts at the
    // centroid of its triangle, y_p = L / 3. Toppling to the right about the right toe, the
    // right face moves into the fill at the rate omega y: virtual work gives
    // lambda W h/2 = W b/2 + P_p y_p.
    let m = 0.33;
    let kp = (std::f64::consts::FRAC_PI_4 + 0.5 * PHI_DEG.to_radians())
        .tan()
        .powi(2);
    let pp = m * kp * GAMMA_FILL * LEVEL * LEVEL / 2.0;
    let yp = LEVEL / 3.0;
    let w = GAMMA_MASONRY * B * H;
    let expected = (w * B / 2.0 + pp * yp) / (w * H / 2.0);
    let scene = common::scene(&block_scene(&format!(
        "passive = true\nfriction_deg = {PHI_DEG}\n"
    )));
    let model = common::model_of(&scene);
    assert_eq!(
        model.passive.len(),
        1,
        "one face against the fill: {:?}",
        model.passive
    );
    assert!(close(model.passive[0].cap, pp, 1e-12));
    assert!(close(model.passive[0].point.y, yp, 1e-12));
    let right = static_lambda(&scene, Direction::Right);
    assert!(close(right, expected, 1e-7), "{right} vs {expected}");
    // Toppling to the left the face moves out of the fill: Heyman's b/h, passive idle.
    let left = static_lambda(&scene, Direction::Left);
    assert!(close(left, B / H, 1e-7), "{left} vs {}", B / H);
    // Off by default: the same scene without the switch is the bare block both ways.
    let bare = common::scene(&block_scene(&format!("friction_deg = {PHI_DEG}\n")));
    assert!(common::model_of(&bare).passive.is_empty());
    assert!(close(static_lambda(&bare, Direction::Right), B / H, 1e-7));
    // The kinematic bound (the general program: a block on a fixed base is no chain) meets it,
    // and the mobilisation scales the passive term alone.
    for (dir, want) in [(Direction::Right, expected), (Direction::Left, B / H)] {
        let a = analysis::analyse(&scene, &options(dir, KinematicMode::Certified)).expect("runs");
        let upper = a.lambda_upper().expect("an upper bound");
        assert!(close(upper, want, 1e-7), "{dir:?}: upper {upper} vs {want}");
        assert_eq!(
            voussoir::interaction::passive::governs(&a.lower.passive),
            dir == Direction::Right,
            "{dir:?}: the passive reaction governs toppling into the fill"
        );
    }
    let full = common::scene(&block_scene(&format!(
        "passive = true\nfriction_deg = {PHI_DEG}\npassive_mobilisation = 1.0\n"
    )));
    let want = (w * B / 2.0 + pp / m * yp) / (w * H / 2.0);
    let got = static_lambda(&full, Direction::Right);
    assert!(close(got, want, 1e-7), "{got} vs {want}");
}

fn options(direction: Direction, kinematic: KinematicMode) -> Options {
    Options {
        static_settings: StaticSettings {
            direction,
            ..StaticSettings::default()
        },
        kinematic,
        ..Options::default()
    }
}

/// The filled semicircle of `data/filled_arch.toml` with the fill's passive resistance.
fn filled_arch(extra: &str) -> String {
    let text = std::fs::read_to_string(common::data("filled_arch.toml")).expect("bundled scene");
    text.replace(
        "seismic = true\n",
        &format!("seismic = true\npassive = true\nfriction_deg = 30.0\n{extra}"),
    )
}

#[test]
fn static_equals_kinematic_on_filled_arches_with_passive_resistance() {
    let with = common::scene(&filled_arch(""));
    let without = common::scene(
        &std::fs::read_to_string(common::data("filled_arch.toml")).expect("bundled scene"),
    );
    let model = common::model_of(&with);
    assert!(!model.passive.is_empty());
    // Every extrados edge under the level on the left haunch resists motion toward -x, on the
    // right toward +x.
    for p in &model.passive {
        assert_eq!(p.into, p.point.x.signum(), "{p:?}");
    }
    for dir in [Direction::Right, Direction::Left] {
        let bare = static_lambda(&without, dir);
        for mode in [KinematicMode::Certified, KinematicMode::General] {
            let a = analysis::analyse(&with, &options(dir, mode)).expect("runs");
            let lower = a.lower.lambda.expect("collapse");
            let upper = a.lambda_upper().expect("an upper bound");
            assert!(
                close(upper, lower, 1e-8),
                "{dir:?} {mode:?}: static {lower} vs kinematic {upper}"
            );
            assert!(
                lower > bare * 1.05,
                "{dir:?}: passive {lower} vs bare {bare}"
            );
            assert!(voussoir::interaction::passive::governs(&a.lower.passive));
        }
    }
}

#[test]
fn static_equals_kinematic_under_a_live_load_with_passive_fill() {
    // A live point load at the left haunch: the right haunch rises and sways into the fill.
    let text = filled_arch("")
        .replace("[seismic]\nvertical_ratio = 0.3\n", "")
        + "[action]\nkind = \"live\"\n[[loads]]\ntype = \"point\"\nat = [-1.3186, 1.5037]\nforce = [0.0, -10000.0]\nlive = true\n";
    // The static and the kinematic (general program) multipliers of a scene.
    let bounds = |text: &str| {
        let a = analysis::analyse(
            &common::scene(text),
            &options(Direction::Right, KinematicMode::General),
        )
        .expect("runs");
        (
            a.lower.lambda.expect("collapse"),
            a.lambda_upper().expect("an upper bound"),
        )
    };
    let (lower, upper) = bounds(&text);
    assert!(
        close(upper, lower, 1e-8),
        "static {lower} vs kinematic {upper}"
    );
    let (bare, _) = bounds(&text.replace("passive = true\n", ""));
    assert!(lower > bare, "passive {lower} vs bare {bare}");
    // The mirror image gives the same multiplier.
    let (m, _) = bounds(&text.replace("at = [-1.3186, 1.5037]", "at = [1.3186, 1.5037]"));
    assert!(close(m, lower, 1e-7), "mirror {m} vs {lower}");
}

#[test]
fn the_dem_bracket_contains_the_static_value() {
    let scene = common::scene(&block_scene(&format!(
        "passive = true\nfriction_deg = {PHI_DEG}\n"
    )));
    let (lower, stands, collapses) = common::static_and_dem_bracket(&common::model_of(&scene));
    // Without the fill the block would topple at b/h = 0.3, far below the bracket.
    assert!(stands > B / H, "DEM [{stands}, {collapses}] against b/h");
    assert!(
        (stands..=collapses).contains(&lower),
        "static {lower}, DEM [{stands}, {collapses}]"
    );
}

#[test]
fn bad_passive_input_is_refused_naming_the_key() {
    for (extra, key, words) in [
        (
            "passive = true\nfriction_deg = 30\npassive_mobilisation = 1.5\n",
            "fill.passive_mobilisation",
            "from 0 to 1",
        ),
        (
            "passive = true\nfriction_deg = 30\npassive_mobilisation = -0.1\n",
            "fill.passive_mobilisation",
            "from 0 to 1",
        ),
        (
            "passive = true\nfriction_deg = -5\n",
            "fill.friction_deg",
            "from 0 to below 90",
        ),
        (
            "passive = true\n",
            "fill.friction_deg",
            "passive = true needs",
        ),
        ("passive = \"yes\"\n", "fill.passive", ""),
    ] {
        let e = Scene::from_toml_str(&block_scene(extra), "t")
            .map(|_| ())
            .expect_err(extra)
            .to_string();
        assert!(e.contains(key) && e.contains(words), "{extra}: {e}");
    }
}
