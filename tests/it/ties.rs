//! Tie rods (`[[ties]]`, `voussoir::interaction::tie`): closed forms derived here for a tied
//! block (rocking, sliding, prestress), agreement of the static and kinematic bounds on a
//! tied portal, invariances, the methods that refuse ties, and bad input.

use crate::common;

use voussoir::analysis::{self, KinematicMode, Options};
use voussoir::geometry::Vec2;
use voussoir::interaction::{Anchor, Tie};
use voussoir::kinematic::{self, KinematicSettings};
use voussoir::model::Model;
use voussoir::scene::Scene;
use voussoir::statics::{self, Direction, StaticSettings, Status};

fn scene(text: &str) -> Scene {
    Scene::from_toml_str(text, "ties-test.toml")
        .unwrap_or_else(|e| panic!("valid test scene rejected: {e}\n{text}"))
}

/// A block b x h (on x in [-b/2, b/2], y in [0, h]) with a horizontal tie at height `ht`
/// from a fixed wall (the ground) on `side` (-1 left, +1 right) to the block's face.
fn tied_block(b: f64, h: f64, mu: f64, ht: f64, side: f64, capacity: f64, prestress: f64) -> Model {
    let wall = Anchor {
        block: None,
        point: Vec2::new(side * (0.5 * b + 0.5), ht),
    };
    let face = Anchor {
        block: Some(0),
        point: Vec2::new(side * 0.5 * b, ht),
    };
    Model::self_weight(common::single_block(b, h, mu)).with_ties(vec![Tie {
        from: wall,
        to: face,
        capacity,
        prestress,
        ultimate_strain: voussoir::interaction::tie::DEFAULT_ULTIMATE_STRAIN,
    }])
}

fn lambda_static(m: &Model) -> f64 {
    let r = statics::analyse(m, &StaticSettings::default()).expect("static analysis solves");
    assert_eq!(r.status, Status::Collapse);
    let residual = r.equilibrium_residual;
    assert!(
        residual <= 1e-9 * m.assembly.total_weight(),
        "residual {residual}"
    );
    r.lambda.expect("collapse")
}

fn lambda_kinematic(m: &Model) -> f64 {
    let r = kinematic::analyse(m, &KinematicSettings::default()).expect("kinematic search runs");
    assert_eq!(r.status, Status::Collapse);
    r.lambda_upper.expect("collapse")
}

/// Rocking about the right toe with the tie on the left (the side the load comes from):
/// moments about the toe, `lambda W h/2 = W b/2 + S ht`, so
/// `lambda = (W b/2 + S ht) / (W h/2)`; the tie yields.
#[test]
fn tied_block_rocks_at_the_closed_form() {
    let (b, h) = (0.4, 1.5);
    let w = common::single_block(b, h, f64::INFINITY).total_weight();
    for ht in [0.3, 0.75, 1.5] {
        for s in [0.0, 0.1 * w, 0.4 * w] {
            let m = tied_block(b, h, f64::INFINITY, ht, -1.0, s, 0.0);
            let expected = (w * b / 2.0 + s * ht) / (w * h / 2.0);
            let (ls, lk) = (lambda_static(&m), lambda_kinematic(&m));
            assert!(
                (ls - expected).abs() <= 1e-9 * expected,
                "ht {ht}, S {s}: static {ls}, closed form {expected}"
            );
            assert!(
                (lk - expected).abs() <= 1e-9 * expected,
                "ht {ht}, S {s}: kinematic {lk}, closed form {expected}"
            );
            let r = statics::analyse(&m, &StaticSettings::default()).expect("solves");
            if s > 0.0 {
                assert!(
                    r.ties[0].yielded,
                    "the tie yields at collapse: {:?}",
                    r.ties[0]
                );
                assert!((r.ties[0].force - s).abs() <= 1e-6 * s);
            }
        }
    }
}

/// With finite friction the block may slide first: horizontally `lambda W = V + S` with
/// `|V| <= mu W` (the tie is horizontal, so N = W), so sliding caps lambda at `mu + S/W`;
/// the static bound is the smaller of the two closed forms, and the kinematic search
/// (rotations only) keeps the rocking value, an upper bound.
#[test]
fn tied_block_slides_at_the_closed_form() {
    let (b, h, ht) = (0.6, 1.2, 0.9);
    let w = common::single_block(b, h, f64::INFINITY).total_weight();
    let s = 0.15 * w;
    let rocking = (w * b / 2.0 + s * ht) / (w * h / 2.0);
    for mu in [0.2, 0.4, 0.6, 0.9] {
        let m = tied_block(b, h, mu, ht, -1.0, s, 0.0);
        let expected = rocking.min(mu + s / w);
        let ls = lambda_static(&m);
        assert!(
            (ls - expected).abs() <= 1e-8 * expected,
            "mu {mu}: static {ls}, closed form {expected}"
        );
        let lk = lambda_kinematic(&m);
        assert!((lk - rocking).abs() <= 1e-9 * rocking && lk >= ls * (1.0 - 1e-9));
    }
}

/// A prestressed tie on the far side (toward which the block overturns) shortens in the
/// mechanism: it only ever helps the overturning with its least force, the prestress P,
/// so `lambda W h/2 + P ht = W b/2`; the capacity plays no part (also when it equals the
/// prestress: a fixed force, whose two bounds leave the interior point no interior).
#[test]
fn prestressed_tie_on_the_far_side_pulls_at_its_prestress() {
    let (b, h, ht) = (0.5, 1.0, 0.6);
    let w = common::single_block(b, h, f64::INFINITY).total_weight();
    for (p, c) in [
        (0.0, 0.2 * w),
        (0.1 * w, 0.2 * w),
        (0.3 * w, 5.0 * w),
        (0.2 * w, 0.2 * w),
    ] {
        let m = tied_block(b, h, f64::INFINITY, ht, 1.0, c, p);
        let expected = (w * b / 2.0 - p * ht) / (w * h / 2.0);
        let (ls, lk) = (lambda_static(&m), lambda_kinematic(&m));
        assert!(
            (ls - expected).abs() <= 1e-9 * expected,
            "P {p}: static {ls}, closed form {expected}"
        );
        assert!(
            (lk - expected).abs() <= 1e-9 * expected,
            "P {p}: kinematic {lk}, closed form {expected}"
        );
    }
}

/// The bundled portal with a tie between its springings at `capacity` (N).
fn tied_portal(capacity: f64, y: f64) -> String {
    let portal = std::fs::read_to_string(common::data("portal.toml")).expect("bundled portal");
    format!("{portal}\n[[ties]]\nfrom = [-1.0, {y}]\nto = [1.0, {y}]\ncapacity = {capacity}\n")
}

fn analyse(
    text: &str,
    kinematic: KinematicMode,
    direction: Option<Direction>,
) -> analysis::SceneAnalysis {
    let options = Options {
        kinematic,
        static_settings: StaticSettings::default().direction(direction.unwrap_or(Direction::Right)),
        ..Options::default()
    };
    analysis::analyse(&scene(text), &options).unwrap_or_else(|e| panic!("analysis: {e}\n{text}"))
}

/// A tie of no capacity changes nothing; a tie that yields at collapse gives static =
/// kinematic (the certified mechanism and the exhaustive search) to 1e-8, at several
/// heights; lambda grows with the capacity.
#[test]
fn tied_portal_bounds_agree_while_the_tie_yields() {
    let portal = std::fs::read_to_string(common::data("portal.toml")).expect("bundled portal");
    let bare = analyse(&portal, KinematicMode::Certified, None)
        .lower
        .lambda
        .expect("collapse");
    let zero = analyse(&tied_portal(0.0, -0.05), KinematicMode::Certified, None);
    // The bare portal is solved by the chain program, the tied one by the full program:
    // equal to the interior point's accuracy.
    let zero = zero.lower.lambda.expect("collapse");
    assert!(
        (zero - bare).abs() <= 1e-9 * bare,
        "a tie of capacity 0 is no tie: {zero} vs {bare}"
    );
    for y in [-0.05, -0.4] {
        let mut last = bare;
        for capacity in [250.0, 500.0, 1000.0, 1500.0, 2000.0] {
            for mode in [KinematicMode::Certified, KinematicMode::Exhaustive] {
                let a = analyse(&tied_portal(capacity, y), mode, None);
                let lower = a.lower.lambda.expect("collapse");
                assert!(
                    a.lower.ties[0].yielded,
                    "capacity {capacity} at y = {y}: the tie yields"
                );
                let upper = a.lambda_upper().expect("upper bound");
                assert!(
                    (upper - lower).abs() <= 1e-8 * lower,
                    "capacity {capacity} at y = {y} ({mode:?}): static {lower}, kinematic {upper}"
                );
                assert!(lower > last, "lambda grows with the capacity");
                assert!(a.lower.equilibrium_residual <= 1e-6 * a.model.assembly.total_weight());
            }
            last = analyse(&tied_portal(capacity, y), KinematicMode::Certified, None)
                .lower
                .lambda
                .expect("collapse");
        }
    }
}

/// Once the tie no longer yields, its force settles and lambda stops growing (another
/// mechanism, in which the tie does not stretch, governs); the kinematic search still
/// bounds it from above.
#[test]
fn tied_portal_saturates_when_the_tie_stops_yielding() {
    let strong = analyse(
        &tied_portal(20000.0, -0.05),
        KinematicMode::Exhaustive,
        None,
    );
    let stronger = analyse(
        &tied_portal(50000.0, -0.05),
        KinematicMode::Exhaustive,
        None,
    );
    let (l1, l2) = (
        strong.lower.lambda.expect("collapse"),
        stronger.lower.lambda.expect("collapse"),
    );
    assert!(!strong.lower.ties[0].yielded && !stronger.lower.ties[0].yielded);
    assert!((l1 - l2).abs() <= 1e-7 * l1, "{l1} vs {l2}");
    let f = strong.lower.ties[0].force;
    assert!(f > 2000.0 && f < 20000.0, "tie force {f}");
    assert!(strong.lambda_upper().expect("upper bound") >= l1 * (1.0 - 1e-9));
}

/// A tie that no longer yields keeps its length at collapse: the certified mechanism then has
/// one hinge more than four (`Family::HingesWithHeldTies`), and it meets the static bound to
/// 1e-8 on a grid of capacities and heights, yielded or not.
#[test]
fn tied_portal_certified_bound_meets_the_static_one_on_a_grid() {
    for y in [-0.05, -0.2, -0.4] {
        for capacity in [300.0, 1800.0, 2200.0, 3000.0, 5000.0, 20000.0] {
            let a = analyse(&tied_portal(capacity, y), KinematicMode::Certified, None);
            let lower = a.lower.lambda.expect("collapse");
            let upper = a.lambda_upper().expect("upper bound");
            assert_eq!(
                a.kinematic_search,
                Some(voussoir::kinematic::Search::Certified)
            );
            assert!(
                (upper - lower).abs() <= 1e-8 * lower,
                "capacity {capacity} at y = {y}: static {lower}, certified {upper}"
            );
            let k = a.upper.as_ref().expect("kinematic result");
            let family = k.mechanism.as_ref().expect("mechanism").family;
            let held = !a.lower.ties[0].yielded;
            assert_eq!(
                family == voussoir::kinematic::Family::HingesWithHeldTies,
                held,
                "capacity {capacity} at y = {y}: family {family:?}, tie {:?}",
                a.lower.ties[0]
            );
        }
    }
}

/// The mirror image of a tied portal loaded to the left is the same structure loaded to the
/// right: equal multipliers.
#[test]
fn tied_portal_is_mirror_symmetric() {
    let text = tied_portal(1200.0, -0.3);
    let right = analyse(&text, KinematicMode::Certified, Some(Direction::Right));
    let left = analyse(&text, KinematicMode::Certified, Some(Direction::Left));
    let (r, l) = (
        right.lower.lambda.expect("collapse"),
        left.lower.lambda.expect("collapse"),
    );
    assert!((r - l).abs() <= 1e-9 * r, "right {r}, left {l}");
}

/// The JSON lists each tie with its force, capacity and whether it yielded.
#[test]
fn json_lists_the_ties() {
    let v = common::json_of(&["analyze", "--json"], &tied_portal(1000.0, -0.05));
    let tie = &v["ties"][0];
    assert_eq!(tie["capacity"], 1000.0);
    assert_eq!(tie["yielded"], true);
    let force = tie["force"].as_f64().expect("force");
    assert!((force - 1000.0).abs() <= 1e-6 * 1000.0, "force {force}");
}

/// The DEM, with its ties as elastic-perfectly-plastic bars as stiff as its contacts, brackets
/// the static multiplier of the tied portal, whether the tie yields (1 kN) or keeps its
/// length (5 kN).
#[test]
fn dem_bracket_contains_the_tied_static_value() {
    for capacity in [1000.0, 5000.0] {
        let s = scene(&tied_portal(capacity, -0.05));
        let model = voussoir::scene::build(&s).expect("builds");
        let (lower, lo, hi) = common::static_and_dem_bracket(&model);
        assert!(
            lo <= lower && lower <= hi,
            "capacity {capacity}: static {lower} outside the DEM bracket [{lo}, {hi}]"
        );
    }
}

/// The methods that do not model ties refuse them rather than answer for the untied
/// structure.
#[test]
fn methods_without_ties_refuse_them() {
    let s = scene(&tied_portal(1000.0, -0.05));
    let continuous = analysis::continuous(&s, Direction::Right);
    assert!(matches!(
        continuous,
        Err(kinematic::KinematicError::Ties { count: 1 })
    ));
}

fn refused(extra: &str) -> String {
    let portal = std::fs::read_to_string(common::data("portal.toml")).expect("bundled portal");
    let text = format!("{portal}\n[[ties]]\n{extra}\n");
    let err = Scene::from_toml_str(&text, "ties-test.toml")
        .and_then(|s| voussoir::scene::build(&s).map(|_| ()))
        .expect_err("refused");
    err.to_string()
}

#[test]
fn bad_ties_are_refused_naming_the_key() {
    let cases = [
        (
            "from = [-5.0, 0.5]\nto = [1.0, -0.05]\ncapacity = 1000.0",
            "ties[0].from",
            "outside every block",
        ),
        (
            "from = [-1.0, -0.05]\nto = [-1.0, -0.2]\ncapacity = 1000.0",
            "ties[0].to",
            "both anchors are on block",
        ),
        (
            "from = [-1.0, -0.05]\nto = [1.0, -0.05]\ncapacity = -5.0",
            "ties[0].capacity",
            "from 0",
        ),
        (
            "from = [-1.0, -0.05]\nto = [1.0, -0.05]\ncapacity = 100.0\nprestress = 200.0",
            "ties[0].prestress",
            "capacity",
        ),
        (
            "from = [-1.0, -0.05]\nto = [1.0, -0.05]\ncapacity = \"design\"",
            "ties[0].capacity",
            "retrofit",
        ),
        (
            "from = [-1.0, -0.05]\nto = [1.0, -0.05]",
            "ties[0].capacity",
            "capacity",
        ),
        (
            "from = [-1.0, -0.05]\nto = [1.0, -0.05]\ncapacity = 10.0\nstrength = 3",
            "ties[0].strength",
            "allowed",
        ),
        (
            "from = [-1.0, -0.05]\nto = [-1.0, -0.05]\ncapacity = 10.0",
            "ties[0].to",
            "differ",
        ),
        (
            "from = [-1.0, -0.05]\nto = [1.0, -0.05]\ncapacity = 10.0\nultimate_strain = 0.0",
            "ties[0].ultimate_strain",
            "> 0",
        ),
    ];
    for (extra, key, words) in cases {
        let message = refused(extra);
        assert!(
            message.contains(key) && message.contains(words),
            "{extra}: {message}"
        );
    }
}

/// The minimum-thickness search moves the voussoirs and piers while tie anchors are fixed
/// points: it is refused, naming the key, by the static and the continuous search alike.
#[test]
fn min_thickness_refuses_ties() {
    let s = scene(&tied_portal(1000.0, -0.05));
    let e = voussoir::thickness::analyse(&s, &Options::default())
        .expect_err("refused")
        .to_string();
    assert!(e.contains("ties[0].from") && e.contains("thickness"), "{e}");
    let e = analysis::continuous_min_thickness(&s)
        .expect_err("refused")
        .to_string();
    assert!(e.contains("ties[0].from"), "{e}");
}

/// Units: `capacity = "2 kN"` and anchors in millimetres read as SI.
#[test]
fn tie_keys_take_units() {
    let si = analyse(&tied_portal(2000.0, -0.05), KinematicMode::Certified, None);
    let portal = std::fs::read_to_string(common::data("portal.toml")).expect("bundled portal");
    let text = format!(
        "{portal}\n[[ties]]\nfrom = [\"-1000 mm\", \"-50 mm\"]\nto = [\"1000 mm\", \"-50 mm\"]\ncapacity = \"2 kN\"\n"
    );
    let units = analyse(&text, KinematicMode::Certified, None);
    assert_eq!(si.lower.lambda, units.lower.lambda);
}

/// The capacity curve of `assess` with a tie (rigid-plastic, broken past its ultimate
/// strain), against the virtual work of the tied block derived here: the block rocks about
/// its right toe `O` by `theta` (clockwise), its centroid at `G(theta)`, the tie's face anchor
/// at `A(theta)`; lengthening, the tie pulls with its capacity `S`, so
/// `alpha W dx_G = W dy_G + S dl` (power balance per unit rotation), i.e.
/// `alpha(theta) = (W y_G' + S l') / (W x_G')`, with the derivatives taken here by central
/// differences of the exact rotated positions (not the code's twists). Past the breaking
/// stretch the tie carries nothing and the block's own curve remains.
#[test]
fn tied_block_capacity_curve_follows_virtual_work() {
    use voussoir::assess::{self, CapacitySettings};
    let (b, h, ht) = (0.4, 1.5, 0.75);
    let w = common::single_block(b, h, f64::INFINITY).total_weight();
    let s = 0.2 * w;
    let toe = Vec2::new(0.5 * b, 0.0);
    let wall = Vec2::new(-(0.5 * b + 0.5), ht);
    let turned = |p: Vec2, theta: f64| {
        // Clockwise by theta about the toe.
        let (sn, cs) = theta.sin_cos();
        let r = p - toe;
        toe + Vec2::new(cs * r.x + sn * r.y, -sn * r.x + cs * r.y)
    };
    let centroid = Vec2::new(0.0, 0.5 * h);
    let face = Vec2::new(-0.5 * b, ht);
    let length = |theta: f64| (turned(face, theta) - wall).norm();
    let l0 = length(0.0);
    for strain in [f64::INFINITY, 0.01] {
        let mut m = tied_block(b, h, f64::INFINITY, ht, -1.0, s, 0.0);
        m.ties[0].ultimate_strain = strain;
        let k = kinematic::analyse(&m, &KinematicSettings::default()).expect("kinematic");
        let mech = k.mechanism.expect("a mechanism");
        let settings = CapacitySettings {
            points: 60,
            control_block: None,
            fc: 1.0,
            incremental: false,
        };
        let cap = assess::capacity(&m, &mech, Direction::Right, &settings).expect("capacity");
        let closed0 = (w * b / 2.0 + s * ht) / (w * h / 2.0);
        assert!(
            (cap.alpha0 - closed0).abs() <= 1e-9 * closed0,
            "alpha0 {} vs {closed0}",
            cap.alpha0
        );
        let mut broke = false;
        for p in &cap.curve {
            let theta = p.rotation;
            let d = 1e-6;
            let fd = |f: &dyn Fn(f64) -> f64| (f(theta + d) - f(theta - d)) / (2.0 * d);
            let xg = fd(&|t| turned(centroid, t).x);
            let yg = fd(&|t| turned(centroid, t).y);
            let stretch = length(theta) - l0;
            let tie = if stretch <= strain * l0 {
                s * fd(&length)
            } else {
                broke = true;
                0.0
            };
            let expected = (w * yg + tie) / (w * xg);
            // Skip the points within the difference step of the break.
            if (stretch - strain * l0).abs() < 1e-5 {
                continue;
            }
            assert!(
                (p.alpha - expected).abs() <= 1e-7 * closed0,
                "theta {theta}: alpha {} vs virtual work {expected} (stretch {stretch:.5} m)",
                p.alpha
            );
        }
        // The 1 % tie breaks before alpha reaches 0; the unbreakable one yields all along,
        // and the block's weight still brings alpha to 0 (at 0.48 rad here).
        assert_eq!(broke, strain.is_finite(), "strain {strain}");
        // Where it breaks: the rotation at which the stretch reaches 1 %, by bisection here,
        // and the centroid's horizontal displacement there.
        let on_curve = cap.ties[0];
        assert!(on_curve.lengthens && on_curve.force == s);
        if strain.is_finite() {
            let (mut lo, mut hi) = (0.0, cap.rotation0);
            for _ in 0..100 {
                let mid = 0.5 * (lo + hi);
                if length(mid) - l0 > strain * l0 {
                    hi = mid;
                } else {
                    lo = mid;
                }
            }
            let d_k = turned(centroid, hi).x - centroid.x;
            let found = on_curve.breaks_at_d_k.expect("it breaks");
            assert!((found - d_k).abs() <= 1e-9, "breaks at {found} vs {d_k}");
        } else {
            assert_eq!(on_curve.breaks_at_d_k, None);
        }
        assert!(cap.curve.last().is_some_and(|p| p.alpha.abs() < 1e-6));
    }
}

/// The bundled portal (friction `friction`) with the ties `ties`: `(from, to, capacity,
/// prestress)`, points as `[x, y]` text.
fn portal_with_ties(ties: &[(&str, &str, f64, f64)], friction: &str) -> String {
    let portal = std::fs::read_to_string(common::data("portal.toml")).expect("bundled portal");
    let mut text = portal.replace("friction = inf", &format!("friction = {friction}"));
    for (from, to, capacity, prestress) in ties {
        text.push_str(&format!(
            "\n[[ties]]\nfrom = {from}\nto = {to}\ncapacity = {capacity}\nprestress = {prestress}\n"
        ));
    }
    text
}

/// The chain program with one unknown per tie (`statics::analyse` on a chain, its active
/// set: the ties' tensions beside the chain's three redundants) against the full program
/// (three unknowns per joint, the ties' tensions besides): the same status and multiplier to
/// 1e-9 on a grid of ties (between the piers, from a pier to the arch, to the ground, four at
/// once), capacities (yielding and not, 0), prestress, friction (none and finite) and both
/// directions. Each chain solution is an equilibrium (its residual, ties included, below 1e-9
/// of the weight) with every tension in `[P, C]`, and a single tie's tension is the least at
/// collapse: at most the full program's (whose interior point stops inside the set of optimal
/// tensions), and yielded exactly when the full program's is.
#[test]
fn chain_program_with_ties_equals_the_full_program() {
    let piers = |y: f64| (format!("[-1.0, {y}]"), format!("[1.0, {y}]"));
    let (p1, p2) = piers(-0.05);
    let (p3, _) = piers(-0.3);
    let (p4, p5) = piers(-0.55);
    let arch = "[0.5, 0.866]".to_string();
    let ground_left = "[-2.0, -1.2]".to_string();
    let ground_right = "[2.0, -1.2]".to_string();
    let mut cases: Vec<Vec<(String, String, f64, f64)>> = Vec::new();
    for c in [0.0, 300.0, 1500.0, 2200.0, 20000.0] {
        for p in [0.0, 0.5 * c] {
            cases.push(vec![(p1.clone(), p2.clone(), c, p)]);
            cases.push(vec![(p3.clone(), arch.clone(), c, p)]);
        }
    }
    for c in [500.0, 3000.0, 12000.0] {
        cases.push(vec![(p4.clone(), ground_left.clone(), c, 0.0)]);
        cases.push(vec![(ground_right.clone(), p5.clone(), c, 0.2 * c)]);
    }
    cases.push(vec![
        (p1.clone(), p2.clone(), 800.0, 0.0),
        (p3.clone(), arch.clone(), 600.0, 100.0),
        (p4.clone(), ground_left.clone(), 1500.0, 0.0),
        (ground_right.clone(), p5.clone(), 900.0, 300.0),
    ]);
    // A prestress that pulls the piers over at rest: no equilibrium at lambda = 0.
    cases.push(vec![(p1.clone(), p2.clone(), 60000.0, 50000.0)]);
    let mut yielded = [0, 0];
    let mut cannot_stand = 0;
    for ties in &cases {
        let spec: Vec<(&str, &str, f64, f64)> = ties
            .iter()
            .map(|(a, b, c, p)| (a.as_str(), b.as_str(), *c, *p))
            .collect();
        for friction in ["inf", "0.6"] {
            let text = portal_with_ties(&spec, friction);
            let model = voussoir::scene::build(&scene(&text)).expect("builds");
            assert!(statics::declines(&model).is_none(), "a chain with ties");
            let w = model.assembly.total_weight();
            for d in [Direction::Right, Direction::Left] {
                let (chain, full) = common::chain_and_full(&model, d);
                let what = format!("{ties:?}, friction {friction}, {d:?}");
                assert_eq!(chain.status, full.status, "{what}");
                if chain.status != Status::Collapse {
                    cannot_stand += 1;
                    continue;
                }
                assert!(
                    chain.exact_vertex && chain.solver_status.starts_with("active set"),
                    "{what}: solved by {}",
                    chain.solver_status
                );
                let (lc, lf) = (chain.lambda.expect("lambda"), full.lambda.expect("lambda"));
                assert!(
                    (lc - lf).abs() <= 1e-9 * lf,
                    "{what}: chain {lc}, full {lf}"
                );
                assert!(
                    chain.equilibrium_residual <= 1e-9 * w,
                    "{what}: residual {}",
                    chain.equilibrium_residual
                );
                for ((t, c), f) in model.ties.iter().zip(&chain.ties).zip(&full.ties) {
                    let tol = 1e-9 * t.capacity.max(1.0);
                    assert!(
                        c.force >= t.prestress - tol && c.force <= t.capacity + tol,
                        "{what}: {c:?}"
                    );
                    if model.ties.len() == 1 {
                        assert!(
                            c.force <= f.force + 1e-6 * t.capacity,
                            "{what}: {c:?} {f:?}"
                        );
                        assert_eq!(c.yielded, f.yielded, "{what}: {c:?} {f:?}");
                        yielded[usize::from(c.yielded)] += 1;
                    }
                }
            }
        }
    }
    // The grid holds both kinds of tie and a structure that cannot stand.
    assert!(yielded[0] >= 10 && yielded[1] >= 10, "{yielded:?}");
    assert!(cannot_stand >= 2, "{cannot_stand}");
    // With crushing the chain program declines ties (its working set on the crushing laws
    // has the redundants alone), and the full program answers.
    let crushing = tied_portal(1500.0, -0.05).replace(
        "friction = inf",
        "friction = inf\ncompressive_strength = 5e6",
    );
    let model = voussoir::scene::build(&scene(&crushing)).expect("builds");
    assert_eq!(statics::declines(&model), Some(statics::Declined::Ties));
    let r = statics::analyse(&model, &StaticSettings::default()).expect("full program");
    assert_eq!(r.status, Status::Collapse);
}
