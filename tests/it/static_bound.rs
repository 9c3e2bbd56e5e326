//! Static (lower-bound) analysis: published values, hand-derived values, equilibrium,
//! invariance and statuses.

use crate::common;
use common::*;
use voussoir::assembly::JointEnd;
use voussoir::model::equilibrium_residual;
use voussoir::model::Model;
use voussoir::statics::{self, Direction, StaticSettings, Status};
use voussoir::thickness::{self, ThicknessOutcome};

fn lambda(scene: &voussoir::scene::Scene) -> f64 {
    let r = statics::analyse(&model_of(scene), &StaticSettings::default()).expect("solves");
    assert_eq!(r.status, Status::Collapse);
    r.lambda.expect("collapse has a multiplier")
}

#[test]
fn semicircle_minimum_thickness_matches_milankovitch() {
    // Milankovitch / Cocchetti & Rizzi (2020): t/R = 0.107426 with the weight on the
    // centreline; with true voussoir weights the value is 0.1075 +- 0.0003, and the haunch
    // intrados hinges sit 54.5 deg from the crown.
    for (n, vs) in [(64, "polygon"), (128, "polygon"), (128, "curved")] {
        let s = circular(0.15, n, 180.0, vs);
        let m = thickness::min_thickness(&s, &StaticSettings::default()).expect("search runs");
        assert_eq!(m.search.outcome, ThicknessOutcome::Found);
        let t = m.search.min_thickness.expect("found");
        assert!((t - 0.1075).abs() <= 3e-4, "n = {n} {vs}: t_min = {t}");
        let (lo, hi) = m.search.bracket.expect("bracket");
        assert!(hi - lo <= 1e-9 * hi);
        // Five hinges: both springings (extrados), crown (extrados), two haunches (intrados).
        assert_eq!(m.hinges.len(), 5, "{:?}", m.hinges);
        let haunch: Vec<_> = m.hinges.iter().filter(|h| h.end == JointEnd::P1).collect();
        assert_eq!(haunch.len(), 2);
        if n >= 128 {
            for h in haunch {
                let from_crown = h.x.abs().atan2(h.y).to_degrees();
                assert!(
                    (from_crown - 54.5).abs() <= 1.5,
                    "haunch hinge at {from_crown} deg"
                );
            }
        }
        // Safety factor of the scene's own thickness.
        let sf = m.safety_factor.expect("factor");
        assert!((sf - 0.15 / t).abs() < 1e-12);
    }
}

#[test]
fn semicircle_thousand_voussoirs_matches_continuous_values() {
    // Continuous (infinitely many voussoirs) values from two independent computations.
    for (t, expected) in [(0.15, 0.1443), (0.20, 0.2837)] {
        let l = lambda(&semicircle(t, 1000));
        assert!((l - expected).abs() <= 5e-4, "t/R = {t}: lambda = {l}");
    }
}

#[test]
fn single_block_rocks_at_b_over_h_or_slides_at_mu() {
    let (b, h) = (0.4, 1.3);
    for mu in [f64::INFINITY, 0.5, 1.0] {
        let r = statics::analyse(
            &Model::self_weight(single_block(b, h, mu)),
            &StaticSettings::default(),
        )
        .expect("solves");
        let l = r.lambda.expect("collapse");
        assert!(
            (l - b / h).abs() <= 1e-8,
            "mu = {mu}: lambda = {l}, b/h = {}",
            b / h
        );
        assert_eq!(r.hinges.len(), 1);
        // Toppling to the right: rotation about the right toe, which is p1 (x = +b/2).
        assert_eq!(r.hinges[0].end, JointEnd::P1);
        assert!(r.sliding.is_empty());
    }
    for mu in [0.1, 0.25] {
        let r = statics::analyse(
            &Model::self_weight(single_block(b, h, mu)),
            &StaticSettings::default(),
        )
        .expect("solves");
        let l = r.lambda.expect("collapse");
        assert!((l - mu).abs() <= 1e-8, "mu = {mu}: lambda = {l}");
        assert_eq!(r.sliding, vec![0]);
        // The mechanism is a slip without rotation; the associative (normality) flow rule of
        // the Coulomb cone makes it dilate: the block lifts by mu per unit of slip.
        let [vx, vy, w] = r.mechanism[0];
        assert!(vx > 0.0 && w.abs() < 1e-6, "{:?}", r.mechanism);
        assert!((vy - mu * vx).abs() < 1e-6, "{:?}", r.mechanism);
    }
}

#[test]
fn forces_are_in_equilibrium_and_admissible() {
    for s in [
        semicircle(0.15, 32),
        circular(0.25, 24, 140.0, "curved"),
        scene("[arch]\nshape = \"pointed\"\nradius = 1.0\neccentricity = 0.3\nthickness = 0.12\nvoussoirs = 20\n[material]\nfriction = 0.6\n"),
        scene("[arch]\nshape = \"basket\"\nspan = 2.0\nrise = 0.6\nthickness = 0.15\nvoussoirs = 25\n[piers]\nheight = 1.5\nwidth = 0.5\ncourses = 3\n"),
    ] {
        let m = model_of(&s);
        let a = &m.assembly;
        let r = statics::analyse(&m, &StaticSettings::default()).expect("solves");
        let l = r.lambda.expect("collapse");
        let w = a.total_weight();
        let f = r.forces.as_ref().expect("forces");
        // Recomputed independently of the program's matrices.
        let res = equilibrium_residual(a, &m.loads, f, l, 1.0);
        assert!(res < 1e-8 * w, "residual {res} vs weight {w}");
        assert!((res - r.equilibrium_residual).abs() <= 1e-12 * w);
        for (jt, f) in a.joints.iter().zip(f) {
            assert!(f.n >= -1e-9 * w, "tension {}", f.n);
            assert!(f.m.abs() <= 0.5 * jt.length() * f.n + 1e-9 * w * jt.length());
            if jt.friction.is_finite() {
                assert!(f.v.abs() <= jt.friction * f.n + 1e-9 * w);
            }
        }
    }
}

#[test]
fn scale_unit_weight_and_depth_do_not_change_lambda() {
    let base = semicircle(0.17, 24);
    let l0 = lambda(&base);
    let scaled =
        scene("[arch]\nshape = \"circular\"\nradius = 1000.0\nthickness = 170.0\nvoussoirs = 24\n");
    let l1 = lambda(&scaled);
    assert!((l1 - l0).abs() <= 1e-7 * l0, "{l0} vs {l1}");
    let small = scene(
        "[arch]\nshape = \"circular\"\nradius = 0.001\nthickness = 0.00017\nvoussoirs = 24\n",
    );
    let l2 = lambda(&small);
    assert!((l2 - l0).abs() <= 1e-7 * l0, "{l0} vs {l2}");
    let heavy = base
        .with_override("material.unit_weight=27000")
        .and_then(|s| s.with_override("material.depth=0.35"))
        .expect("valid");
    let l3 = lambda(&heavy);
    assert!((l3 - l0).abs() <= 1e-9 * l0, "{l0} vs {l3}");
}

#[test]
fn symmetric_arch_has_same_capacity_both_ways_and_mirror_is_consistent() {
    let s = scene("[arch]\nshape = \"pointed\"\nradius = 1.0\neccentricity = 0.25\nthickness = 0.14\nvoussoirs = 18\n[piers]\nheight = 0.8\nwidth = 0.35\ncourses = 2\n");
    let a = model_of(&s);
    let right = statics::analyse(&a, &StaticSettings::default()).expect("solves");
    let left = statics::analyse(&a, &StaticSettings::default().direction(Direction::Left))
        .expect("solves");
    let (lr, ll) = (right.lambda.expect("c"), left.lambda.expect("c"));
    assert!((lr - ll).abs() <= 1e-8 * lr, "{lr} vs {ll}");

    // An asymmetric assembly: a leaning stack. Its capacity to the left equals that of its
    // mirror image to the right.
    let asym = Model::self_weight(voussoir::assembly::Assembly {
        blocks: vec![rect(-0.3, 0.0, 0.6, 1.0), rect(-0.1, 1.0, 0.5, 0.8)],
        joints: vec![
            hjoint(0.3, -0.3, 0.0, None, Some(0), f64::INFINITY),
            hjoint(0.3, -0.1, 1.0, Some(0), Some(1), f64::INFINITY),
        ],
    });
    let l_left = statics::analyse(&asym, &StaticSettings::default().direction(Direction::Left))
        .expect("solves")
        .lambda
        .expect("c");
    let l_mirror = statics::analyse(&asym.mirrored(), &StaticSettings::default())
        .expect("solves")
        .lambda
        .expect("c");
    let l_right = statics::analyse(&asym, &StaticSettings::default())
        .expect("solves")
        .lambda
        .expect("c");
    assert!((l_left - l_mirror).abs() <= 1e-8, "{l_left} vs {l_mirror}");
    assert!(
        (l_left - l_right).abs() > 1e-3,
        "the stack leans: capacities differ"
    );
}

#[test]
fn block_renumbering_does_not_change_lambda() {
    let m = model_of(&semicircle(0.2, 12));
    let a = &m.assembly;
    let l0 = statics::analyse(&m, &StaticSettings::default())
        .expect("solves")
        .lambda
        .expect("c");
    // Reverse the block order and shuffle the joints: the program is written for any
    // assembly, not only ordered chains.
    let nb = a.blocks.len();
    let mut b = a.clone();
    b.blocks.reverse();
    for j in &mut b.joints {
        j.from = j.from.map(|i| nb - 1 - i);
        j.to = j.to.map(|i| nb - 1 - i);
    }
    b.joints.rotate_left(5);
    assert!(!b.is_chain());
    let l1 = statics::analyse(&Model::self_weight(b), &StaticSettings::default())
        .expect("solves")
        .lambda
        .expect("c");
    assert!((l1 - l0).abs() <= 1e-9 * l0, "{l0} vs {l1}");
}

#[test]
fn lambda_rises_with_thickness_and_statuses_are_honest() {
    let mut last = 0.0;
    for t in [0.11, 0.13, 0.16, 0.2, 0.25, 0.3, 0.4] {
        let l = lambda(&semicircle(t, 48));
        assert!(l > last, "t = {t}: {l} <= {last}");
        last = l;
    }
    let thin = statics::analyse(&model_of(&semicircle(0.1, 48)), &StaticSettings::default())
        .expect("solves");
    assert_eq!(thin.status, Status::CannotStand);
    assert!(thin.lambda.is_none());
    let flat = statics::analyse(
        &model_of(&circular(0.3, 16, 60.0, "polygon")),
        &StaticSettings::default(),
    )
    .expect("solves");
    assert_eq!(flat.status, Status::NoCollapse);
    assert!(flat.lambda.is_none());
    // With finite friction the same flat arch slides at its springings.
    let slides = statics::analyse(
        &model_of(
            &circular(0.3, 16, 60.0, "polygon")
                .with_override("material.friction=0.4")
                .expect("valid"),
        ),
        &StaticSettings::default(),
    )
    .expect("solves");
    assert_eq!(slides.status, Status::Collapse);
    assert!(!slides.sliding.is_empty());
}

#[test]
fn too_little_friction_cannot_stand_and_no_thickness_helps() {
    // Springing joints of a horseshoe arch are inclined outward: with mu = 0.05 nothing holds.
    let s = circular(0.3, 16, 240.0, "polygon")
        .with_override("material.friction=0.05")
        .expect("valid");
    let r = statics::analyse(&model_of(&s), &StaticSettings::default()).expect("solves");
    assert_eq!(r.status, Status::CannotStand);
    let m = thickness::min_thickness(&s, &StaticSettings::default()).expect("runs");
    assert_eq!(m.search.outcome, ThicknessOutcome::NeverStands);
    assert!(m.search.min_thickness.is_none() && m.safety_factor.is_none());
}

#[test]
fn mechanism_from_duals_is_a_four_hinge_mechanism() {
    let m = model_of(&semicircle(0.15, 32));
    let a = &m.assembly;
    let r = statics::analyse(&m, &StaticSettings::default()).expect("solves");
    assert_eq!(r.hinges.len(), 4);
    // Blocks between consecutive hinges move as rigid bodies: equal rotation rates.
    let joints: Vec<usize> = r.hinges.iter().map(|h| h.joint).collect();
    for seg in joints.windows(2) {
        let w0 = r.mechanism[seg[0]][2];
        for b in seg[0]..seg[1] {
            assert!(
                (r.mechanism[b][2] - w0).abs() <= 1e-5 * w0.abs().max(1.0),
                "block {b}"
            );
        }
    }
    // The load does positive work and the weights are lifted at the same rate.
    let work_h: f64 = a
        .blocks
        .iter()
        .zip(&r.mechanism)
        .map(|(b, v)| b.weight * v[0])
        .sum();
    let work_v: f64 = a
        .blocks
        .iter()
        .zip(&r.mechanism)
        .map(|(b, v)| b.weight * v[1])
        .sum();
    let l = r.lambda.expect("c");
    assert!(work_h > 0.0);
    assert!(
        (l * work_h - work_v).abs() <= 1e-6 * work_v.abs(),
        "{l} {work_h} {work_v}"
    );
}

#[test]
fn the_model_holds_only_what_the_scene_requires() {
    // No friction rows without friction limits, two per joint with them.
    let m = model_of(&semicircle(0.15, 16));
    let a = &m.assembly;
    let r = statics::analyse_full(&m, &StaticSettings::default()).expect("solves");
    assert_eq!(r.model.friction_rows, 0);
    assert_eq!(r.model.variables, 1 + 3 * a.joints.len());
    assert_eq!(r.model.equality_rows, 3 * a.blocks.len());
    assert_eq!(r.model.inequality_rows, 2 * a.joints.len());
    // The chain's program (the default for chains): four unknowns, two rows per joint.
    let c = statics::analyse(&m, &StaticSettings::default()).expect("solves");
    assert_eq!(c.model.variables, 4);
    assert_eq!(c.model.equality_rows, 0);
    assert_eq!(c.model.inequality_rows, 2 * a.joints.len());
    assert_eq!(c.model.friction_rows, 0);
    let mf = model_of(
        &semicircle(0.15, 16)
            .with_override("material.friction=0.6")
            .expect("valid"),
    );
    let f = &mf.assembly;
    let rf = statics::analyse_full(&mf, &StaticSettings::default()).expect("solves");
    assert_eq!(rf.model.friction_rows, 2 * f.joints.len());
    let cf = statics::analyse(&mf, &StaticSettings::default()).expect("solves");
    assert_eq!(cf.model.friction_rows, 2 * f.joints.len());
    assert_eq!(cf.model.inequality_rows, 4 * f.joints.len());
    // No pier blocks without piers; k courses per pier with them.
    assert!(a
        .blocks
        .iter()
        .all(|b| matches!(b.kind, voussoir::assembly::BlockKind::Voussoir(_))));
    let p = model_of(
        &semicircle(0.15, 16)
            .with_overrides(&["piers.height=1", "piers.width=0.3", "piers.courses=3"])
            .expect("valid"),
    )
    .assembly;
    assert_eq!(p.blocks.len(), 16 + 2 * 3);
    assert_eq!(p.joints.len(), 17 + 2 * 3);
    assert!(p.is_chain());
}

#[test]
fn reported_resultants_stay_inside_their_joints() {
    // A flat segmental arch whose springing opens completely at collapse, and a two-voussoir
    // arch: solver round-off on open joints must not show up as tension or as a resultant
    // outside the joint.
    for s in [
        circular(0.1, 24, 40.0, "polygon")
            .with_override("arch.radius=2.0")
            .expect("valid"),
        semicircle(0.3, 2),
    ] {
        let m = model_of(&s);
        let a = &m.assembly;
        let r = statics::analyse(&m, &StaticSettings::default()).expect("solves");
        let forces = r.forces.as_ref().expect("collapse");
        for (j, (jt, f)) in a.joints.iter().zip(forces).enumerate() {
            assert!(f.n >= 0.0, "joint {j}: N = {}", f.n);
            match r.eccentricity(j) {
                Some(e) => assert!(e.abs() <= 0.5 * jt.length(), "joint {j}: e = {e}"),
                None => assert!(r.open.contains(&j)),
            }
        }
    }
}
