//! Arcades (`[arcade]`) and spandrel walls (`[spandrel]`): one bay is the portal, the bays
//! and the wall are mirror-symmetric, the static solution is in equilibrium and governed by the
//! mechanism docs/geometry.md describes, the wall's pieces fill exactly the region above the
//! rings and meet them on exactly the joints an independent detection finds, loads and fills
//! land where they should, the DEM brackets the static value, and bad keys are refused by name.

use crate::common::{self, data, scene};
use voussoir::assembly::{BlockKind, JointEnd, JointKind};
use voussoir::geometry::{polygon_area_centroid, Vec2};
use voussoir::scene::Scene;
use voussoir::statics::{self, Direction, StaticSettings};

fn bundled(name: &str) -> String {
    std::fs::read_to_string(data(name)).expect("bundled scene")
}

/// The bundled arcade with `bays` bays, with or without its spandrel wall.
fn arcade(bays: usize, wall: bool) -> Scene {
    let s = Scene::from_file(&data("arcade.toml")).expect("bundled arcade");
    let mut table = s.table().clone();
    if !wall {
        table.remove("spandrel");
    }
    Scene::from_table(table, "arcade")
        .expect("valid")
        .with_value("arcade.bays", toml::Value::Integer(bays as i64))
        .expect("valid bays")
}

fn lambda(s: &Scene, direction: Direction) -> statics::StaticResult {
    let model = common::model_of(s);
    model.assembly.validate().expect("a well-formed assembly");
    let settings = StaticSettings {
        direction,
        ..StaticSettings::default()
    };
    statics::analyse(&model, &settings).expect("the static program solves")
}

/// One bay without a wall is the portal: the very same assembly, so the same multiplier.
#[test]
fn one_bay_is_the_portal() {
    let portal = bundled("portal.toml");
    let one = format!("{portal}\n[arcade]\nbays = 1\ncolumn_width = 0.5\n");
    let (a, b) = (
        common::model_of(&scene(&portal)),
        common::model_of(&scene(&one)),
    );
    assert_eq!(a.assembly.blocks.len(), b.assembly.blocks.len());
    assert_eq!(a.assembly.joints.len(), b.assembly.joints.len());
    for (x, y) in a.assembly.blocks.iter().zip(&b.assembly.blocks) {
        assert_eq!(x.polygon, y.polygon);
        assert_eq!((x.weight, x.kind), (y.weight, y.kind));
    }
    for (x, y) in a.assembly.joints.iter().zip(&b.assembly.joints) {
        assert_eq!(
            (x.p1, x.p2, x.from, x.to, x.kind),
            (y.p1, y.p2, y.from, y.to, y.kind)
        );
    }
    let la = lambda(&scene(&portal), Direction::Right)
        .lambda
        .expect("collapse");
    let lb = lambda(&scene(&one), Direction::Right)
        .lambda
        .expect("collapse");
    assert!((la - lb).abs() <= 1e-12 * la, "{la} vs {lb}");
}

/// Every bay of a bare arcade is the bundled ring, translated: bay k's springings at the
/// pitch (intrados span + column width), the whole centred on x = 0.
#[test]
fn bays_repeat_at_the_pitch_and_columns_stand_between_them() {
    let s = arcade(3, false);
    let model = common::model_of(&s);
    let asm = &model.assembly;
    // R = 2, t = 0.25: intrados span 3.75, column 0.5, pitch 4.25; bays at -4.25, 0, 4.25.
    let crown = |k: usize| {
        asm.blocks
            .iter()
            .filter(|b| {
                b.kind == BlockKind::BayVoussoir(k, 7) || b.kind == BlockKind::BayVoussoir(k, 8)
            })
            .map(|b| b.polygon.iter().map(|p| p.x).sum::<f64>() / 4.0)
            .sum::<f64>()
            / 2.0
    };
    for (k, x) in [(0, -4.25), (1, 0.0), (2, 4.25)] {
        assert!((crown(k) - x).abs() < 1e-12, "bay {k} at {}", crown(k));
    }
    // Column 0 spans the intrados springings of bays 0 and 1: x from -2.375 to -1.875.
    let col: Vec<_> = asm
        .blocks
        .iter()
        .filter(|b| matches!(b.kind, BlockKind::Column(0, _)))
        .collect();
    assert_eq!(col.len(), 3);
    for b in col {
        let xs: Vec<f64> = b.polygon.iter().map(|p| p.x).collect();
        let lo = xs.iter().copied().fold(f64::INFINITY, f64::min);
        let hi = xs.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        assert!((lo + 2.375).abs() < 1e-12 && (hi + 1.875).abs() < 1e-12);
    }
    // The weight is the rings', the piers' and the columns' (unit weight 20 kN/m^3).
    let ring: f64 = asm
        .blocks
        .iter()
        .filter(|b| matches!(b.kind, BlockKind::BayVoussoir(..)))
        .map(|b| b.area)
        .sum();
    let piers = 2.0 * 1.5 * 0.8 + 2.0 * 1.5 * 0.5;
    assert!((asm.total_weight() - 20000.0 * (ring + piers)).abs() < 1e-9 * asm.total_weight());
}

/// Kinematic theorem: the portal's collapse mechanism that leaves its left pier at rest is a
/// mechanism of the arcade too (the last bay and the right pier move, everything left of its
/// first hinge stays), with the same virtual work; so no arcade collapses later than the
/// portal, and the static (lower) bound of every arcade is at most the portal's multiplier.
#[test]
fn an_arcade_collapses_no_later_than_its_last_bay_as_a_portal() {
    // The bundled ring (which fails alone) and a deeper one on slender piers (whose last bay
    // and right pier fail together).
    let slender = |bays: usize| {
        arcade(bays, false)
            .with_overrides(&[
                "arch.radius=1.5",
                "piers.height=2.0",
                "piers.width=0.6",
                "piers.courses=4",
            ])
            .expect("valid")
    };
    last_bay_governs(&|bays| arcade(bays, false));
    last_bay_governs(&slender);
}

fn last_bay_governs(arcade: &dyn Fn(usize) -> Scene) {
    let portal = voussoir::analysis::analyse(&arcade(1), &Default::default()).expect("runs");
    let lp = portal.lower.lambda.expect("collapse");
    let k = portal.upper.as_ref().expect("certified");
    assert!((k.lambda_upper.expect("bound") - lp).abs() < 1e-9 * lp);
    // The certified mechanism keeps the left pier at rest: no hinge in it.
    let mechanism = k.mechanism.as_ref().expect("a mechanism");
    assert!(mechanism.hinges.iter().all(|h| !matches!(
        portal.model.assembly.joints[h.joint].kind,
        JointKind::LeftPier(_)
    )));
    for bays in 2..=5 {
        let r = lambda(&arcade(bays), Direction::Right);
        let l = r.lambda.expect("collapse");
        assert!(
            l <= lp * (1.0 + 1e-8),
            "{bays} bays: {l} above the portal's {lp}"
        );
        // Within the solver's accuracy it is the portal's: the last bay governs.
        assert!((l - lp).abs() < 1e-7 * lp, "{bays} bays: {l} vs {lp}");
    }
}

/// The static solution of the arcade with its wall is in equilibrium, and its mechanism (read
/// from the duals) is a sway of the storey: every pier and column rocks on the leeward edge of
/// its base (the hinges the docs' table names).
#[test]
fn the_walled_arcade_sways_on_its_piers_and_columns() {
    for bays in 1..=5 {
        let s = arcade(bays, true);
        let model = common::model_of(&s);
        let r = lambda(&s, Direction::Right);
        let l = r.lambda.expect("collapse");
        assert!(l > 0.0 && l < 1.0);
        let w = model.assembly.total_weight();
        assert!(
            r.equilibrium_residual < 1e-9 * w,
            "{bays} bays: residual {} N of {w} N",
            r.equilibrium_residual
        );
        let hinge_at = |kind: JointKind, end: JointEnd| {
            r.hinges
                .iter()
                .any(|h| model.assembly.joints[h.joint].kind == kind && h.end == end)
        };
        // The left pier on its inner base corner (p1), the right pier on its outer one (p2),
        // each column on its right base corner (p2): all leeward under a load toward +x.
        assert!(
            hinge_at(JointKind::LeftPier(0), JointEnd::P1),
            "{bays} bays"
        );
        assert!(
            hinge_at(JointKind::RightPier(0), JointEnd::P2),
            "{bays} bays"
        );
        for k in 0..bays - 1 {
            assert!(
                hinge_at(JointKind::Column(k, 0), JointEnd::P2),
                "{bays} bays, column {k}"
            );
        }
    }
}

/// A symmetric arcade collapses at the same multiplier toward either side, with and without
/// its wall (the bond is laid symmetrically about the axis).
#[test]
fn mirror_symmetry() {
    for bays in [2, 3] {
        for wall in [false, true] {
            let s = arcade(bays, wall);
            let r = lambda(&s, Direction::Right).lambda.expect("collapse");
            let l = lambda(&s, Direction::Left).lambda.expect("collapse");
            assert!(
                (r - l).abs() <= 1e-9 * r,
                "{bays} bays, wall {wall}: {r} vs {l}"
            );
            // And the mirrored assembly is the same set of blocks.
            let model = common::model_of(&s);
            let m = model.assembly.mirrored();
            let mut a: Vec<(i64, i64)> = model
                .assembly
                .blocks
                .iter()
                .map(|b| key(b.centroid))
                .collect();
            let mut b: Vec<(i64, i64)> = m.blocks.iter().map(|b| key(b.centroid)).collect();
            a.sort_unstable();
            b.sort_unstable();
            assert_eq!(a, b, "{bays} bays, wall {wall}: not mirror-symmetric");
        }
    }
}

fn key(p: Vec2) -> (i64, i64) {
    ((p.x * 1e9).round() as i64, (p.y * 1e9).round() as i64)
}

/// The wall's pieces are convex and fill exactly the region between the springing line, the
/// piers' outer faces, the level and the rings' extrados polygons; their joints are exactly the
/// ones the independent joint detection of the user's blocks finds on the same outlines.
#[test]
fn the_wall_fills_the_spandrels_and_meets_every_neighbour() {
    for bays in [1, 3] {
        let s = arcade(bays, true);
        let model = common::model_of(&s);
        let asm = &model.assembly;
        asm.validate()
            .expect("convex blocks, joints the right way round");
        let pieces: Vec<_> = asm
            .blocks
            .iter()
            .filter(|b| matches!(b.kind, BlockKind::Spandrel(..)))
            .collect();
        let wall: f64 = pieces.iter().map(|b| b.area).sum();
        // The extrados polygons, closed along the springing line.
        let mut under = 0.0;
        for k in 0..bays {
            let mut outline: Vec<Vec2> = Vec::new();
            for b in asm.blocks.iter().filter(|b| match b.kind {
                BlockKind::BayVoussoir(kk, _) => kk == k,
                BlockKind::Voussoir(_) => true,
                _ => false,
            }) {
                // A voussoir [p1(j), p2(j), p2(j+1), p1(j+1)]: its extrados corners.
                outline.push(b.polygon[1]);
                outline.push(b.polygon[2]);
            }
            outline.dedup();
            under += polygon_area_centroid(&outline).0;
        }
        let (x_left, x_right) = asm
            .blocks
            .iter()
            .flat_map(|b| b.polygon.iter())
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), p| {
                (lo.min(p.x), hi.max(p.x))
            });
        let expected = (x_right - x_left) * 3.2 - under;
        assert!(
            (wall - expected).abs() < 1e-10 * expected,
            "{bays} bays: pieces {wall} m^2, region {expected} m^2"
        );
        // Every piece lies between the springing line and the level.
        for b in &pieces {
            assert!(b
                .polygon
                .iter()
                .all(|p| p.y >= -1e-12 && p.y <= 3.2 + 1e-12));
        }
        let polygons = voussoir::blocks::Polygons(
            asm.blocks
                .iter()
                .map(|b| {
                    let mut p = b.polygon.clone();
                    if voussoir::blocks::signed_area2(&p) < 0.0 {
                        p.reverse();
                    }
                    p
                })
                .collect(),
        );
        let found = voussoir::blocks::joints::detect(&polygons, None, 1e-9, 1.0, f64::INFINITY)
            .expect("the outlines form a structure");
        assert_eq!(found.assembly.joints.len(), asm.joints.len(), "{bays} bays");
        let length = |j: &[voussoir::assembly::Joint]| j.iter().map(|j| j.length()).sum::<f64>();
        let (ours, theirs) = (length(&asm.joints), length(&found.assembly.joints));
        assert!((ours - theirs).abs() < 1e-9 * ours, "{ours} vs {theirs}");
    }
}

/// Loads over an arcade: a line load over the whole arcade puts `q * length` on it, on the
/// rings and exposed tops, or on the wall's top; a fill over a bare arcade weighs `bays` times
/// the portal's (the tops of piers and columns carry none); a fill over the wall is a layer of
/// its width.
#[test]
fn loads_and_fill_over_an_arcade() {
    let line = "[[loads]]\ntype = \"line\"\nfrom_x = -9.0\nto_x = 9.0\nintensity = 1000.0\n";
    for wall in [false, true] {
        let s = arcade(3, wall);
        let text = toml::to_string(s.table()).expect("toml") + line;
        let model = common::model_of(&scene(&text));
        let weight = model.assembly.total_weight();
        let total: f64 = (0..model.assembly.blocks.len())
            .map(|i| -model.loads.permanent(i).force.y)
            .sum();
        // The arcade spans -6.925..6.925 m: 3 intrados spans of 3.75 m, 2 columns of 0.5 m
        // and 2 piers of 0.8 m.
        assert!(
            (total - weight - 13.85 * 1000.0).abs() < 1e-9 * total,
            "wall {wall}"
        );
    }
    let fill = |bays: usize| {
        let s = arcade(bays, false);
        let text = toml::to_string(s.table()).expect("toml")
            + "[fill]\nlevel = 2.5\nunit_weight = 18000.0\n";
        let model = common::model_of(&scene(&text));
        let total: f64 = (0..model.assembly.blocks.len())
            .map(|i| -model.loads.permanent(i).force.y)
            .sum();
        total - model.assembly.total_weight()
    };
    let one = fill(1);
    assert!(one > 0.0);
    for bays in [2, 3] {
        assert!((fill(bays) - bays as f64 * one).abs() < 1e-9 * one);
    }
    let s = arcade(3, true);
    let text = toml::to_string(s.table()).expect("toml") + "[fill]\nlevel = 3.5\n";
    let model = common::model_of(&scene(&text));
    let total: f64 = (0..model.assembly.blocks.len())
        .map(|i| -model.loads.permanent(i).force.y)
        .sum();
    let layer = 18000.0 * 13.85 * 0.3;
    assert!((total - model.assembly.total_weight() - layer).abs() < 1e-9 * total);
}

/// The DEM's bracket contains the static multiplier of a small arcade (two bays of 8
/// voussoirs on one-course piers and column).
#[test]
fn dem_bracket_contains_the_static_value() {
    let s = scene(
        "[arch]\nshape = \"circular\"\nradius = 1.0\nthickness = 0.25\nvoussoirs = 8\n\
         [piers]\nheight = 0.8\nwidth = 0.4\ncourses = 1\n\
         [arcade]\nbays = 2\ncolumn_width = 0.5\n",
    );
    let model = common::model_of(&s);
    let (lower, lo, hi) = common::static_and_dem_bracket(&model);
    assert!(
        lo <= lower && lower <= hi,
        "static {lower} outside the DEM bracket [{lo}, {hi}]"
    );
}

/// `--vary arcade.bays=...` and the wall's keys sweep like any key.
#[test]
fn sweeps_vary_the_bays_and_the_wall() {
    let out = common::voussoir()
        .args(["sweep", "--vary", "arcade.bays=1,2"])
        .arg(data("arcade.toml"))
        .args([
            "--set",
            "spandrel.course_height=0.5",
            "--set",
            "spandrel.unit_length=1.0",
        ])
        .output()
        .expect("runs");
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let csv = String::from_utf8_lossy(&out.stdout);
    let rows: Vec<&str> = csv.lines().filter(|l| !l.starts_with('#')).collect();
    assert!(rows[0].starts_with("arcade.bays,status,lambda_lower"));
    assert_eq!(rows.len(), 3);
    assert!(rows[1].starts_with("1,collapse,") && rows[2].starts_with("2,collapse,"));
    for (row, bays) in rows[1..].iter().zip([1, 2]) {
        let l: f64 = row
            .split(',')
            .nth(2)
            .expect("lambda")
            .parse()
            .expect("number");
        let s = arcade(bays, true)
            .with_overrides(&["spandrel.course_height=0.5", "spandrel.unit_length=1.0"])
            .expect("valid");
        let direct = lambda(&s, Direction::Right).lambda.expect("collapse");
        assert!((l - direct).abs() < 1e-12 * l);
    }
}

/// Bad keys are refused, each naming its key.
#[test]
fn bad_keys_are_refused_by_name() {
    let text = bundled("arcade.toml");
    let base = Scene::from_toml_str(&text, "arcade.toml").expect("valid");
    for (set, key) in [
        ("arcade.bays=0", "arcade.bays"),
        ("arcade.bays=51", "arcade.bays"),
        ("arcade.bays=2.5", "arcade.bays"),
        ("arcade.column_width=0", "arcade.column_width"),
        ("arcade.column_width=0.4", "arcade.column_width"),
        ("arcade.colum_width=0.5", "arcade.colum_width"),
        ("spandrel.level=2.0", "spandrel.level"),
        ("spandrel.course_height=-0.25", "spandrel.course_height"),
        ("spandrel.unit_length=0", "spandrel.unit_length"),
        ("spandrel.course_height=0.0001", "spandrel.course_height"),
        ("arch.voussoir_shape=curved", "arch.voussoir_shape"),
        ("piers.right.height=1.0", "piers.right.height"),
        ("piers.width=0.2", "piers.left"),
    ] {
        let e = base.with_override(set).expect_err(set);
        assert_eq!(e.key(), Some(key), "{set}: {e}");
    }
    // An arcade or a wall needs piers.
    let bare = text.replace("[piers]\nheight = 1.5\nwidth = 0.8\ncourses = 3\n", "");
    let e = Scene::from_toml_str(&bare, "t").expect_err("no piers");
    assert_eq!(e.key(), Some("arcade.bays"));
    let no_arcade = bare.replace("[arcade]\nbays = 3\ncolumn_width = 0.5", "");
    let e = Scene::from_toml_str(&no_arcade, "t").expect_err("no piers");
    assert_eq!(e.key(), Some("spandrel.level"));
    // A fill must rest on the wall's top.
    let e = Scene::from_toml_str(&format!("{text}\n[fill]\nlevel = 3.0\n"), "t").expect_err("fill");
    assert_eq!(e.key(), Some("fill.level"));
}
