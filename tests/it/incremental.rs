//! The assessment of any assembly (issue 23 item 5): the participating mass from the general
//! mechanism, and the capacity curve by the incremental analysis (`assess::incremental`),
//! checked against the closed-form curve of a rocking block, against the chain's finite
//! kinematics (`assess::Linkage`) on the bundled portal, and on walls, a lintel portal and an
//! arcade, whose `alpha0` must be the static multiplier.

use crate::common::{self, data, rect_polygons};
use voussoir::analysis::{self, AssessOptions, Options};
use voussoir::assess::{self, Capacity, CapacitySettings, Motion};
use voussoir::model::Model;
use voussoir::scene::Scene;
use voussoir::statics::{Direction, StaticSettings, Status};

fn options(direction: Direction) -> Options {
    Options {
        static_settings: StaticSettings::default().direction(direction),
        ..Options::default()
    }
}

/// The static multiplier, the model and the capacity of the governing mechanism, by the
/// linkage (`incremental` false, chains only) or the incremental analysis.
fn capacity(scene: &Scene, direction: Direction, incremental: bool) -> (f64, Model, Capacity) {
    let a = analysis::analyse(scene, &options(direction)).expect("analysis");
    assert_eq!(a.lower.status, Status::Collapse);
    let lambda = a.lower.lambda.expect("static multiplier");
    let k = a.upper.as_ref().expect("kinematic analysis");
    let mechanism = k.mechanism.clone().expect("a mechanism");
    let settings = CapacitySettings {
        incremental,
        ..CapacitySettings::default()
    };
    let c = assess::capacity(&a.model, &mechanism, direction, &settings).expect("capacity");
    (lambda, a.model, c)
}

fn path(c: &Capacity) -> &assess::incremental::Path {
    match &c.motion {
        Motion::Incremental(p) => p,
        Motion::Linkage(_) => panic!("expected the incremental route"),
    }
}

fn blocks_scene(rects: &[[f64; 4]]) -> Scene {
    common::scene(&format!(
        "[blocks]\nground_y = 0.0\npolygons = {}\n[material]\nunit_weight = 20000.0\ndepth = 1.0\nfriction = inf\n",
        rect_polygons(rects)
    ))
}

#[test]
fn a_rocking_block_follows_its_closed_form() {
    // A block b x h rocking on its leeward toe: turned by theta, its centroid (b/2, h/2) from
    // the toe has the lever arms (b/2) cos - (h/2) sin (horizontal) and (h/2) cos + (b/2) sin
    // (vertical), so alpha = the ratio of the two, and the centroid has moved by
    // (b/2)(1 - cos) + (h/2) sin toward the load; alpha = 0 at tan(theta0) = b/h.
    let (b, h) = (0.4, 1.2);
    let s = blocks_scene(&[[0.0, 0.0, b, h]]);
    for direction in [Direction::Right, Direction::Left] {
        let (lambda, _, c) = capacity(&s, direction, true);
        assert!((c.alpha0 - b / h).abs() < 1e-9 && (lambda - b / h).abs() < 1e-9);
        let p = path(&c);
        assert!(p.steps.len() > 50, "{} steps", p.steps.len());
        for st in &p.steps {
            let t = st.rotation;
            let alpha =
                (0.5 * b * t.cos() - 0.5 * h * t.sin()) / (0.5 * h * t.cos() + 0.5 * b * t.sin());
            let d = 0.5 * b * (1.0 - t.cos()) + 0.5 * h * t.sin();
            // The last step is interpolated to alpha = 0 (linear between two steps).
            let tol = if std::ptr::eq(st, p.steps.last().expect("steps")) {
                1e-4
            } else {
                1e-7
            };
            assert!(
                (st.alpha - alpha).abs() < tol,
                "{direction:?} theta {t}: alpha {} vs {alpha}",
                st.alpha
            );
            assert!(
                (st.d_k - d).abs() < 1e-7,
                "{direction:?} theta {t}: d_k {} vs {d}",
                st.d_k
            );
        }
        let theta0 = (b / h).atan();
        let d0 = 0.5 * b * (1.0 - theta0.cos()) + 0.5 * h * theta0.sin();
        assert!((c.d_k0 - d0).abs() < 1e-5 * d0, "d_k0 {} vs {d0}", c.d_k0);
        // One block: the whole weight takes part.
        assert!((c.mass.e_star - 1.0).abs() < 1e-12);
        assert_eq!(c.curve.len(), CapacitySettings::default().points);
    }
}

#[test]
fn the_incremental_curve_is_the_linkage_curve_on_the_bundled_portal() {
    let s = Scene::from_file(&data("portal.toml")).expect("bundled portal");
    for direction in [Direction::Right, Direction::Left] {
        let (lambda, model, linkage) = capacity(&s, direction, false);
        let (_, _, inc) = capacity(&s, direction, true);
        assert!(matches!(linkage.motion, Motion::Linkage(_)));
        assert!(
            (inc.alpha0 - lambda).abs() < 1e-9,
            "{} vs {lambda}",
            inc.alpha0
        );
        assert!((inc.mass.e_star - linkage.mass.e_star).abs() < 1e-9);
        assert!((inc.mass.m_star - linkage.mass.m_star).abs() < 1e-9 * linkage.mass.m_star);
        // The linkage's alpha at control displacement d, by bisection on its rotation.
        let alpha_at = |d: f64| {
            let (mut lo, mut hi) = (0.0, linkage.rotation0);
            for _ in 0..100 {
                let mid = 0.5 * (lo + hi);
                let (cfg, _) = linkage.at(&model, mid).expect("reachable");
                if linkage.d_k(&model, &cfg) < d {
                    lo = mid;
                } else {
                    hi = mid;
                }
            }
            linkage.at(&model, 0.5 * (lo + hi)).expect("reachable").1
        };
        let third = linkage.d_k0 / 3.0;
        let p = path(&inc);
        let compared: Vec<_> = p.steps.iter().filter(|st| st.d_k <= third).collect();
        assert!(
            compared.len() > 20,
            "{} steps in the first third",
            compared.len()
        );
        let worst = compared
            .iter()
            .map(|st| (st.alpha - alpha_at(st.d_k)).abs())
            .fold(0.0_f64, f64::max);
        assert!(
            worst < 1e-4,
            "{direction:?}: worst difference {worst:e} in alpha"
        );
        // The incremental curve goes on to a point where the displaced portal stands under no
        // multiplier (a hinge would have to move), or to alpha = 0; never past the linkage's.
        assert!(
            inc.d_k0 <= linkage.d_k0 * (1.0 + 1e-6),
            "{} vs {}",
            inc.d_k0,
            linkage.d_k0
        );
        assert!(inc.d_k0 > third);
    }
}

fn running_bond() -> Vec<[f64; 4]> {
    common::running_bond_wall_rects()
}

fn lintel_portal() -> Vec<[f64; 4]> {
    let (b, h, span, t) = (0.4, 0.5, 1.2, 0.35);
    let mut rects = Vec::new();
    for c in 0..3 {
        let (y0, y1) = (c as f64 * h, (c + 1) as f64 * h);
        rects.push([0.0, y0, b, y1]);
        rects.push([b + span, y0, 2.0 * b + span, y1]);
    }
    rects.push([0.0, 3.0 * h, 2.0 * b + span, 3.0 * h + t]);
    rects
}

fn bare_arcade(bays: i64) -> Scene {
    let s = Scene::from_file(&data("arcade.toml")).expect("bundled arcade");
    let mut table = s.table().clone();
    table.remove("spandrel");
    Scene::from_table(table, "arcade")
        .expect("valid")
        .with_value("arcade.bays", toml::Value::Integer(bays))
        .expect("valid bays")
}

/// The checks every incremental assessment must pass: alpha0 the static multiplier, a
/// participating mass fraction in (0, 1], a curve from alpha0 falling to 0 at d_k0.
fn check_any_assembly(name: &str, s: &Scene) -> [f64; 2] {
    let mut d0 = [0.0; 2];
    for (i, direction) in [Direction::Right, Direction::Left].into_iter().enumerate() {
        let (lambda, _, c) = capacity(s, direction, true);
        assert!(
            (c.alpha0 - lambda).abs() < 1e-9 * lambda.max(1.0),
            "{name} {direction:?}: alpha0 {} vs static {lambda}",
            c.alpha0
        );
        let e = c.mass.e_star;
        assert!(e > 0.0 && e <= 1.0 + 1e-12, "{name}: e* = {e}");
        let first = c.curve.first().expect("curve");
        let last = c.curve.last().expect("curve");
        assert!((first.alpha - lambda).abs() < 1e-9 * lambda.max(1.0));
        assert!(
            last.alpha.abs() < 1e-6 * lambda,
            "{name}: alpha at d_k0 = {}",
            last.alpha
        );
        assert_eq!(c.motion.end(), "alpha_zero", "{name}");
        assert!(
            c.curve
                .windows(2)
                .all(|w| w[1].d_k > w[0].d_k && w[1].alpha <= w[0].alpha + 1e-9),
            "{name}: the curve falls"
        );
        d0[i] = c.d_k0;
    }
    d0
}

#[test]
fn walls_lintels_and_arcades_are_assessed_from_their_own_mechanism() {
    // Mirror-symmetric assemblies: the same d_k0 in both directions.
    for (name, s) in [
        ("running bond wall", blocks_scene(&running_bond())),
        ("lintel portal", blocks_scene(&lintel_portal())),
        ("two-bay arcade", bare_arcade(2)),
    ] {
        let [right, left] = check_any_assembly(name, &s);
        assert!(
            (right - left).abs() < 1e-6 * right,
            "{name}: d_k0 {right} vs {left}"
        );
    }
}

#[test]
fn an_assessment_the_incremental_analysis_cannot_follow_is_refused_in_words() {
    // The walled arcade: its sway mechanism moves every block of the wall, and once moved the
    // wall's parts close back under their own weight, so there is no curve to report.
    let s = Scene::from_file(&data("arcade.toml"))
        .expect("bundled arcade")
        .with_overrides(&[
            "site.ag=0.15".to_string(),
            "site.soil=B".to_string(),
            "site.F0=2.4".to_string(),
            "site.Tc_star=0.3".to_string(),
        ])
        .expect("site");
    let e = analysis::assess_directions(&s, &Options::default(), &AssessOptions::default(), None)
        .expect_err("no capacity curve")
        .to_string();
    assert!(
        e.contains("cannot stand under any multiplier") && e.contains("alpha0"),
        "{e}"
    );
}
