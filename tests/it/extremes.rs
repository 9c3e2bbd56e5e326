//! Numerical stability at the extremes: each case gives the right status and a finite,
//! correct multiplier, or a clear status or error — never NaN, a panic, or a solver failure
//! reported as a number.

use crate::common;
use common::*;
use voussoir::scene::Scene;
use voussoir::statics::{self, StaticResult, StaticSettings, Status};
use voussoir::thickness;

fn analyse(s: &Scene) -> StaticResult {
    let m = model_of(s);
    let a = &m.assembly;
    let r = statics::analyse(&m, &StaticSettings::default()).expect("no solver failure");
    if let Some(l) = r.lambda {
        assert!(l.is_finite() && l >= 0.0);
        assert!(r.equilibrium_residual < 1e-8 * a.total_weight());
    }
    r
}

#[test]
fn lambda_goes_to_zero_continuously_at_the_minimum_thickness() {
    let base = semicircle(0.15, 128);
    let m = thickness::min_thickness(&base, &StaticSettings::default()).expect("runs");
    let t_min = m.search.min_thickness.expect("found");
    // Above t_min lambda is positive and shrinks in proportion to t - t_min.
    let mut slopes = Vec::new();
    for d in [1e-3, 1e-5, 1e-7] {
        let r = analyse(&base.with_thickness(t_min * (1.0 + d)).expect("valid"));
        assert_eq!(r.status, Status::Collapse, "d = {d}");
        let l = r.lambda.expect("collapse");
        assert!(l > 0.0);
        slopes.push(l / (t_min * d));
    }
    for s in &slopes[1..] {
        assert!(
            (s / slopes[0] - 1.0).abs() < 0.05,
            "dlambda/dt not steady: {slopes:?}"
        );
    }
    for d in [1e-7, 1e-5, 1e-3] {
        let r = analyse(&base.with_thickness(t_min * (1.0 - d)).expect("valid"));
        assert_eq!(r.status, Status::CannotStand, "d = {d}");
        assert!(r.lambda.is_none());
    }
}

#[test]
fn thick_flat_and_horseshoe_arches() {
    // Very thick: the thicker, the stronger, up to the limit t < 2R.
    let l09 = analyse(&semicircle(0.9, 64)).lambda.expect("collapse");
    let l19 = analyse(&semicircle(1.9, 64)).lambda.expect("collapse");
    assert!(l09 > 1.0 && l19 > l09, "{l09} {l19}");
    // Very flat (20 deg): no collapse when thick enough, a (large) multiplier when thin.
    assert_eq!(
        analyse(&circular(0.05, 32, 20.0, "polygon")).status,
        Status::NoCollapse
    );
    let thin = analyse(&circular(0.005, 32, 20.0, "polygon"));
    assert_eq!(thin.status, Status::Collapse);
    // Horseshoe (300 deg): the springings overhang; thin and thick rings cannot stand.
    for t in [0.3, 0.6] {
        assert_eq!(
            analyse(&circular(t, 64, 300.0, "polygon")).status,
            Status::CannotStand
        );
    }
}

#[test]
fn very_pointed_arches_are_solved_or_rejected_clearly() {
    // e up to the largest the geometry allows for the voussoir count.
    for (e, n) in [(0.7, 16), (0.8, 10), (0.9, 4)] {
        let s = scene(&format!(
            "[arch]\nshape = \"pointed\"\nradius = 1.0\neccentricity = {e}\nthickness = 0.15\nvoussoirs = {n}\n"
        ));
        let r = analyse(&s);
        assert!(
            r.status == Status::Collapse || r.status == Status::NoCollapse,
            "e = {e}"
        );
    }
    // Beyond that a voussoir would fold over the crown: an error naming the key.
    let e = Scene::from_toml_str(
        "[arch]\nshape = \"pointed\"\nradius = 1.0\neccentricity = 0.92\nthickness = 0.15\nvoussoirs = 32\n",
        "t",
    )
    .expect_err("folded voussoirs");
    assert_eq!(e.key(), Some("arch.eccentricity"));
}

#[test]
fn basket_arches_over_their_rise_range() {
    for (rs, side) in [
        (0.1, 80.0),
        (0.2, 60.0),
        (0.3, 60.0),
        (0.45, 60.0),
        (0.49, 60.0),
    ] {
        let s = scene(&format!(
            "[arch]\nshape = \"basket\"\nspan = 2.0\nrise = {}\nside_angle_deg = {side}\nthickness = 0.2\nvoussoirs = 32\n",
            2.0 * rs
        ));
        let r = analyse(&s);
        assert!(matches!(
            r.status,
            Status::Collapse | Status::CannotStand | Status::NoCollapse
        ));
    }
}

#[test]
fn slender_and_squat_piers() {
    // h/b = 20: the thrust of the arch overturns the piers.
    let slender = semicircle(0.2, 32)
        .with_overrides(&["piers.height=4.0", "piers.width=0.2", "piers.courses=4"])
        .expect("valid");
    assert_eq!(analyse(&slender).status, Status::CannotStand);
    // h/b = 0.2: squat piers barely change the arch's own capacity.
    let squat = semicircle(0.2, 32)
        .with_overrides(&["piers.height=0.1", "piers.width=0.5", "piers.courses=4"])
        .expect("valid");
    let l_squat = analyse(&squat).lambda.expect("collapse");
    let l_arch = analyse(&semicircle(0.2, 32)).lambda.expect("collapse");
    assert!(
        l_squat <= l_arch + 1e-9 && l_squat > 0.9 * l_arch,
        "{l_squat} {l_arch}"
    );
}

#[test]
fn two_and_two_thousand_voussoirs() {
    let r2 = analyse(&semicircle(0.3, 2));
    assert_eq!(r2.status, Status::Collapse);
    let l2000 = analyse(&semicircle(0.15, 2000)).lambda.expect("collapse");
    assert!((l2000 - 0.1443).abs() < 5e-4, "{l2000}");
}

#[test]
fn friction_from_tiny_to_infinite_without_a_jump() {
    let mut last = 0.0;
    for mu in ["0.01", "0.1", "0.3", "0.5", "1", "10", "1e3", "1e6"] {
        let s = semicircle(0.2, 32)
            .with_override(&format!("material.friction={mu}"))
            .expect("valid");
        let r = analyse(&s);
        let l = r.lambda.unwrap_or(0.0);
        assert!(
            l >= last - 1e-9 * last,
            "mu = {mu}: lambda not monotone in mu"
        );
        last = l;
    }
    let inf = analyse(&semicircle(0.2, 32)).lambda.expect("collapse");
    assert!(
        (last - inf).abs() <= 1e-8 * inf,
        "mu = 1e6 gives {last}, inf gives {inf}"
    );
}
