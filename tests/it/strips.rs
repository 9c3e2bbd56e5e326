//! Bonded strips (`[[reinforcements]]`, `voussoir::interaction::strip`): closed forms derived
//! here for a block whose base carries a strip, agreement of the bounds and the DEM on a
//! reinforced portal, invariance, and bad input.

use crate::common;

use voussoir::analysis::{self, KinematicMode, Options};
use voussoir::assembly::JointEnd;
use voussoir::kinematic::{self, KinematicSettings};
use voussoir::model::{Model, Strip};
use voussoir::scene::Scene;
use voussoir::statics::{self, Direction, StaticSettings, Status};

/// A block b x h on the ground whose base joint carries a strip of capacity `f` at the end
/// with x = `side` * b/2.
fn block_with_strip(b: f64, h: f64, f: f64, side: f64) -> Model {
    let a = common::single_block(b, h, f64::INFINITY);
    let j = &a.joints[0];
    let end = if (j.p1.x - side * 0.5 * b).abs() < 1e-12 {
        JointEnd::P1
    } else {
        JointEnd::P2
    };
    let mut m = Model::self_weight(a);
    m.strips = vec![Strip {
        joint: 0,
        end,
        capacity: f,
        source: 0,
    }];
    m
}

fn both(m: &Model) -> (f64, f64) {
    let s = statics::analyse(m, &StaticSettings::default()).expect("static analysis solves");
    assert_eq!(s.status, Status::Collapse);
    assert!(s.equilibrium_residual <= 1e-9 * m.assembly.total_weight());
    let k = kinematic::analyse(m, &KinematicSettings::default()).expect("kinematic search runs");
    (
        s.lambda.expect("collapse"),
        k.lambda_upper.expect("collapse"),
    )
}

/// The load pushes toward +x; the block rocks about its right toe and its heel (the left
/// end of the base) lifts: moments about the toe, `lambda W h/2 = W b/2 + F b`.
#[test]
fn strip_at_the_heel_gives_the_closed_form() {
    for (b, h) in [(0.4, 1.5), (0.8, 1.0)] {
        let w = common::single_block(b, h, f64::INFINITY).total_weight();
        for f in [0.0, 0.05 * w, 0.3 * w] {
            let (ls, lk) = both(&block_with_strip(b, h, f, -1.0));
            let expected = (w * b / 2.0 + f * b) / (w * h / 2.0);
            assert!(
                (ls - expected).abs() <= 1e-9 * expected,
                "static {ls}, closed form {expected}"
            );
            assert!(
                (lk - expected).abs() <= 1e-9 * expected,
                "kinematic {lk}, closed form {expected}"
            );
        }
    }
}

/// A strip at the toe (the end about which the block turns) never opens: b/h unchanged.
#[test]
fn strip_at_the_toe_changes_nothing() {
    let (b, h) = (0.5, 1.2);
    let w = common::single_block(b, h, f64::INFINITY).total_weight();
    let (ls, lk) = both(&block_with_strip(b, h, 0.5 * w, 1.0));
    assert!(
        (ls - b / h).abs() <= 1e-9 && (lk - b / h).abs() <= 1e-9,
        "{ls} {lk}"
    );
}

fn portal(face: &str, from: usize, to: usize, f: f64) -> String {
    let portal = std::fs::read_to_string(common::data("portal.toml")).expect("bundled portal");
    format!("{portal}\n[[reinforcements]]\nface = \"{face}\"\nfrom_joint = {from}\nto_joint = {to}\ntensile_capacity = {f}\n")
}

fn analyse(text: &str, mode: KinematicMode, d: Direction) -> analysis::SceneAnalysis {
    let options = Options {
        kinematic: mode,
        static_settings: StaticSettings::default().direction(d),
        ..Options::default()
    };
    let s = Scene::from_toml_str(text, "strips-test.toml").unwrap_or_else(|e| panic!("{e}"));
    analysis::analyse(&s, &options).unwrap_or_else(|e| panic!("analysis: {e}"))
}

/// Static = kinematic (certified and exhaustive) to 1e-8 on a grid of capacities and faces,
/// the multiplier growing with the capacity; a strip over the whole intrados is mirror
/// symmetric.
#[test]
fn reinforced_portal_bounds_agree() {
    for face in ["intrados", "extrados"] {
        let mut last = 0.0;
        for f in [0.0, 200.0, 500.0, 1000.0] {
            let text = portal(face, 0, 32, f);
            let mut lower = 0.0;
            for mode in [KinematicMode::Certified, KinematicMode::Exhaustive] {
                let a = analyse(&text, mode, Direction::Right);
                lower = a.lower.lambda.expect("collapse");
                let upper = a.lambda_upper().expect("upper bound");
                assert!(
                    (upper - lower).abs() <= 1e-8 * lower,
                    "{face} {f} {mode:?}: {lower} vs {upper}"
                );
            }
            assert!(
                lower >= last * (1.0 - 1e-9),
                "{face}: lambda grows with the capacity"
            );
            last = lower;
            let left = analyse(&text, KinematicMode::Certified, Direction::Left);
            let l = left.lower.lambda.expect("collapse");
            assert!(
                (l - lower).abs() <= 1e-8 * lower,
                "{face} {f}: right {lower}, left {l}"
            );
        }
    }
}

/// The DEM (each strip a bar as stiff as the contacts, along the joint's normal) brackets
/// the static multiplier of the reinforced portal.
#[test]
fn dem_bracket_contains_the_reinforced_static_value() {
    let s = Scene::from_toml_str(&portal("intrados", 0, 32, 500.0), "t").expect("scene");
    let model = voussoir::scene::build(&s).expect("builds");
    let (lower, lo, hi) = common::static_and_dem_bracket(&model);
    assert!(
        lo <= lower && lower <= hi,
        "static {lower} outside [{lo}, {hi}]"
    );
}

/// The JSON lists each strip with its force at every joint it crosses.
#[test]
fn json_lists_the_strips() {
    let v = common::json_of(&["analyze", "--json"], &portal("intrados", 10, 20, 500.0));
    let r = &v["reinforcements"][0];
    assert_eq!(r["face"], "intrados");
    assert_eq!(r["joints"].as_array().map(Vec::len), Some(11));
    assert!(r["joints"]
        .as_array()
        .expect("joints")
        .iter()
        .all(|j| j["force"]
            .as_f64()
            .is_some_and(|f| (0.0..=500.0).contains(&f))));
}

#[test]
fn bad_strips_are_refused_naming_the_key() {
    let portal_text = std::fs::read_to_string(common::data("portal.toml")).expect("portal");
    let cases = [
        (portal("intrados", 0, 40, 500.0), "reinforcements[0].to_joint", "arch joint from 0"),
        (portal("side", 0, 4, 500.0), "reinforcements[0].face", "intrados"),
        (portal("intrados", 5, 4, 500.0), "reinforcements[0].to_joint", "at least"),
        (portal("intrados", 0, 4, -1.0), "reinforcements[0].tensile_capacity", "from 0"),
        (
            format!("{portal_text}\n[[reinforcements]]\nface = \"intrados\"\nfrom_joint = 0\nto_joint = 3\n"),
            "reinforcements[0].tensile_capacity",
            "",
        ),
        (
            "[blocks]\npolygons = [[[0, 0], [1, 0], [1, 1], [0, 1]]]\n[[reinforcements]]\nface = \"intrados\"\nfrom_joint = 0\nto_joint = 0\ntensile_capacity = 10.0\n".to_string(),
            "reinforcements[0].from_joint",
            "has none",
        ),
    ];
    for (text, key, words) in cases {
        let err = Scene::from_toml_str(&text, "t")
            .and_then(|s| voussoir::scene::build(&s).map(|_| ()))
            .expect_err("refused")
            .to_string();
        assert!(err.contains(key) && err.contains(words), "{key}: {err}");
    }
}

/// The chain program (`statics::analyse` on a chain: without crushing a strip is its
/// capacity added to the constants of its end's no-tension row and of Coulomb's rows) against
/// the full program (a tension unknown per strip and joint): the same status and multiplier
/// to 1e-9 on both faces, several joint ranges and capacities, friction none and finite, both
/// directions; each chain solution an equilibrium (its residual, strips included, below 1e-9
/// of the weight) with every strip's tension in `[0, F]`. With crushing the chain program
/// declines strips (its working set has no strip), and the full program answers.
#[test]
fn chain_program_with_strips_equals_the_full_program() {
    let mut compared = 0;
    let mut yielded = 0;
    for face in ["intrados", "extrados"] {
        for (from, to) in [(0, 32), (4, 14), (16, 28)] {
            for f in [0.0, 150.0, 600.0, 3000.0] {
                for friction in ["inf", "0.6"] {
                    let text = portal(face, from, to, f)
                        .replace("friction = inf", &format!("friction = {friction}"));
                    let s = Scene::from_toml_str(&text, "strips-test.toml")
                        .unwrap_or_else(|e| panic!("{e}"));
                    let model = voussoir::scene::build(&s).expect("builds");
                    assert!(statics::declines(&model).is_none(), "a chain with strips");
                    for d in [Direction::Right, Direction::Left] {
                        let (chain, full) = common::chain_and_full(&model, d);
                        let what =
                            format!("{face} {from}..{to}, F {f}, friction {friction}, {d:?}");
                        assert_eq!(chain.status, full.status, "{what}");
                        assert_eq!(chain.status, Status::Collapse, "{what}");
                        assert!(chain.exact_vertex, "{what}: {}", chain.solver_status);
                        let (lc, lf) =
                            (chain.lambda.expect("lambda"), full.lambda.expect("lambda"));
                        assert!(
                            (lc - lf).abs() <= 1e-9 * lf,
                            "{what}: chain {lc}, full {lf}"
                        );
                        assert!(
                            chain.equilibrium_residual <= 1e-9 * model.assembly.total_weight(),
                            "{what}: residual {}",
                            chain.equilibrium_residual
                        );
                        for (st, force) in model.strips.iter().zip(&chain.strips) {
                            let tol = 1e-9 * st.capacity.max(1.0);
                            assert!(
                                force.force >= -tol && force.force <= st.capacity + tol,
                                "{what}: {force:?}"
                            );
                            yielded += usize::from(force.yielded);
                        }
                        compared += 1;
                    }
                }
            }
        }
    }
    assert_eq!(compared, 96);
    assert!(yielded > 0, "some strip debonds at collapse");
    let crushing = portal("intrados", 0, 32, 600.0).replace(
        "friction = inf",
        "friction = inf\ncompressive_strength = 5e6",
    );
    let s = Scene::from_toml_str(&crushing, "strips-test.toml").unwrap_or_else(|e| panic!("{e}"));
    let model = voussoir::scene::build(&s).expect("builds");
    assert_eq!(statics::declines(&model), Some(statics::Declined::Strips));
    let r = statics::analyse(&model, &StaticSettings::default()).expect("full program");
    assert_eq!(r.status, Status::Collapse);
}
