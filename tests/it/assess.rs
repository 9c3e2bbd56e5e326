//! The seismic assessment (issue 14): participating mass, capacity curve by finite rigid-body
//! kinematics, the NTC 2018 spectrum and the checks, against closed forms derived here, the
//! static bound, and the DEM started from configurations on the capacity curve.

use crate::common;

use common::{data, hjoint, model_of, rect, single_block, voussoir};
use voussoir::analysis::{self, AssessOptions, Options};
use voussoir::assembly::{Assembly, JointEnd};
use voussoir::assess::{self, Capacity, CapacitySettings};
use voussoir::dem::{IntegrationParameters, Simulation};
use voussoir::kinematic::{self, KinematicSettings, Mechanism};
use voussoir::model::Model;
use voussoir::outcome::{Direction, Status};
use voussoir::scene::Scene;
use voussoir::spectrum::{Site, Soil, G};

/// The governing mechanism of a model by the exhaustive search (load toward +x).
fn governing(model: &Model) -> Mechanism {
    let k = kinematic::analyse(model, &KinematicSettings::default()).expect("kinematic search");
    assert_eq!(k.status, Status::Collapse);
    k.mechanism.expect("a mechanism")
}

fn capacity_of(model: &Model, fc: f64) -> Capacity {
    let settings = CapacitySettings {
        points: 200,
        control_block: None,
        fc,
        incremental: false,
    };
    assess::capacity(model, &governing(model), Direction::Right, &settings).expect("capacity")
}

fn close(a: f64, b: f64, tol: f64, what: &str) {
    assert!(
        (a - b).abs() <= tol * b.abs().max(1.0),
        "{what}: {a} vs {b} (difference {:e})",
        (a - b).abs()
    );
}

#[test]
fn single_block_rocks_as_the_closed_form() {
    let (b, h, fc) = (0.3, 1.2, 1.35);
    let model = Model::self_weight(single_block(b, h, f64::INFINITY));
    let cap = capacity_of(&model, fc);
    // One mass, moving with its own virtual displacement: e* = 1 exactly.
    close(cap.mass.e_star, 1.0, 1e-12, "e*");
    close(
        cap.mass.m_star * G,
        model.assembly.total_weight(),
        1e-12,
        "M* g = W",
    );
    assert_eq!(cap.control_block, 0);
    // Rocking about the toe: alpha(theta) = tan(atan(b/h) - theta) along the whole curve.
    let beta = (b / h).atan();
    for p in &cap.curve {
        close(p.alpha, (beta - p.rotation).tan(), 1e-9, "alpha(theta)");
    }
    close(cap.rotation0, beta, 1e-9, "rotation at alpha = 0");
    // The centroid reaches the vertical through the toe: d_k0 = b/2.
    close(cap.d_k0, b / 2.0, 1e-9, "d_k0");
    // a0* = (b/h) g / FC with e* = 1.
    close(cap.a0_star, (b / h) * G / fc, 1e-9, "a0*");
    // d* = d_k for a single mass (dx_k = dx_1).
    close(cap.d0_star, cap.d_k0, 1e-12, "d0*");
}

#[test]
fn two_block_column_has_the_hand_derived_participating_mass() {
    // Two equal blocks b x h stacked: the whole column rocks about its right toe
    // (lambda = (b/2)/h, below the top block's b/h).
    let (b, h) = (0.4, 1.0);
    let assembly = Assembly {
        blocks: vec![rect(-0.5 * b, 0.0, b, h), rect(-0.5 * b, h, b, h)],
        joints: vec![
            hjoint(0.5 * b, -0.5 * b, 0.0, None, Some(0), f64::INFINITY),
            hjoint(0.5 * b, -0.5 * b, h, Some(0), Some(1), f64::INFINITY),
        ],
    };
    let model = Model::self_weight(assembly);
    let w = model.assembly.blocks[0].weight;
    let cap = capacity_of(&model, 1.0);
    // Virtual rotation 1 about the toe: dx_i = y_i = h/2, 3h/2.
    // sum P dx = 2 W h, sum P dx^2 = 5 W h^2 / 2, so M* g = 8 W / 5 and e* = 4/5.
    let (y1, y2) = (0.5 * h, 1.5 * h);
    let spdx = w * (y1 + y2);
    let spdx2 = w * (y1 * y1 + y2 * y2);
    close(cap.mass.m_star * G, spdx * spdx / spdx2, 1e-12, "M* g");
    close(cap.mass.m_star * G, 1.6 * w, 1e-12, "M* g = 8W/5");
    close(cap.mass.e_star, 0.8, 1e-12, "e*");
    assert_eq!(cap.control_block, 1, "the top block moves most");
    let beta = (0.5 * b / h).atan();
    close(cap.alpha0, 0.5 * b / h, 1e-12, "alpha0");
    for p in &cap.curve {
        close(p.alpha, (beta - p.rotation).tan(), 1e-9, "alpha(theta)");
    }
    // The top centroid (-b/2, 3h/2) from the toe turns by beta:
    // d_k0 = b/2 + h b / (4 l), l = sqrt(h^2 + b^2/4); d0* = d_k0 spdx2 / (dx_k spdx) = 5/6 d_k0.
    let l = (h * h + 0.25 * b * b).sqrt();
    let d_k0 = 0.5 * b + h * b / (4.0 * l);
    close(cap.d_k0, d_k0, 1e-9, "d_k0");
    close(cap.d0_star, d_k0 * spdx2 / (y2 * spdx), 1e-9, "d0*");
    close(cap.d0_star, d_k0 * 5.0 / 6.0, 1e-9, "d0* = 5/6 d_k0");
}

#[test]
fn three_block_portal_frame_sways_as_a_parallelogram() {
    // Two piers b x h and a lintel on top spanning both: the sway mechanism hinges at the
    // piers' right base toes and their top-left corners; the lintel translates.
    let (b, h, span, t) = (0.4, 2.0, 2.0, 0.5);
    let (xl, xr) = (-0.5 * span - b, 0.5 * span);
    let assembly = Assembly {
        blocks: vec![
            rect(xl, 0.0, b, h),
            rect(xl, h, span + 2.0 * b, t),
            rect(xr, 0.0, b, h),
        ],
        joints: vec![
            hjoint(xl + b, xl, 0.0, None, Some(0), f64::INFINITY),
            hjoint(xl + b, xl, h, Some(0), Some(1), f64::INFINITY),
            hjoint(xr, xr + b, h, Some(1), Some(2), f64::INFINITY),
            hjoint(xr, xr + b, 0.0, Some(2), None, f64::INFINITY),
        ],
    };
    assert!(assembly.is_chain());
    let model = Model::self_weight(assembly);
    let (wp, wl) = (
        model.assembly.blocks[0].weight,
        model.assembly.blocks[1].weight,
    );
    let mech = governing(&model);
    let hinges: Vec<(usize, JointEnd)> = mech.hinges.iter().map(|h| (h.joint, h.end)).collect();
    assert_eq!(
        hinges,
        vec![
            (0, JointEnd::P1),
            (1, JointEnd::P2),
            (2, JointEnd::P1),
            (3, JointEnd::P2)
        ],
        "the sway mechanism"
    );
    let cap = capacity_of(&model, 1.0);
    // Virtual rotation 1 of the piers: pier centroids dx = h/2, lintel dx = h (it moves as
    // the top-left corner of a pier).
    // sum P dx = h (Wp + Wl), sum P dx^2 = h^2 (Wp/2 + Wl), sum P = 2 Wp + Wl.
    let m_star_g = (wp + wl).powi(2) / (0.5 * wp + wl);
    close(cap.mass.m_star * G, m_star_g, 1e-12, "M* g");
    close(
        cap.mass.e_star,
        m_star_g / (2.0 * wp + wl),
        1e-12,
        "e* = (Wp+Wl)^2 / ((Wp/2+Wl)(2Wp+Wl))",
    );
    assert_eq!(cap.control_block, 1, "the lintel moves most");
    // Virtual work: G = b (Wp + Wl), A = h (Wp + Wl): alpha0 = b/h, and the parallelogram
    // keeps alpha(theta) = tan(atan(b/h) - theta).
    close(cap.alpha0, b / h, 1e-12, "alpha0");
    let beta = (b / h).atan();
    for p in &cap.curve {
        close(p.alpha, (beta - p.rotation).tan(), 1e-9, "alpha(theta)");
    }
    // The lintel moves with the corner (-b, h) from the toe: d_k0 = b; d0* = b (Wp/2 + Wl)/(Wp + Wl).
    close(cap.d_k0, b, 1e-9, "d_k0");
    close(cap.d0_star, b * (0.5 * wp + wl) / (wp + wl), 1e-9, "d0*");
}

fn semicircle() -> (Scene, analysis::SceneAnalysis) {
    let scene = Scene::from_file(&data("semicircular.toml")).expect("bundled scene");
    let a = analysis::analyse(&scene, &Options::default()).expect("analysis");
    (scene, a)
}

#[test]
fn arch_curve_starts_at_the_static_multiplier_and_falls_to_zero() {
    let (_, a) = semicircle();
    let mech = a
        .upper
        .as_ref()
        .expect("upper bound")
        .mechanism
        .clone()
        .expect("mechanism");
    let cap = assess::capacity(
        &a.model,
        &mech,
        Direction::Right,
        &CapacitySettings::default(),
    )
    .expect("capacity");
    let lambda = a.lower.lambda.expect("static lambda");
    close(cap.alpha0, lambda, 1e-9, "alpha(0) = static lambda");
    close(cap.curve[0].alpha, lambda, 1e-9, "first point");
    assert_eq!(cap.curve.len(), 200);
    for w in cap.curve.windows(2) {
        assert!(w[1].alpha < w[0].alpha, "alpha falls: {:?}", w);
        assert!(w[1].d_k > w[0].d_k, "d_k grows: {:?}", w);
    }
    let last = cap.curve.last().expect("points");
    assert!(
        last.alpha.abs() < 1e-9 * lambda,
        "alpha(d_k0) = {}",
        last.alpha
    );
    assert!(cap.d_k0 > 0.0 && cap.d0_star > 0.0);
    // The four-bar kinematics checked by energy alone: with self-weight, alpha is the rate of
    // rise of the weights over the rate of their horizontal travel,
    // d(sum W y) / d(sum W x), here by central differences of the moved blocks' positions.
    let moments = |u: f64| {
        let (c, _) = cap.at(&a.model, u).expect("configuration");
        let moved = cap
            .motion
            .linkage()
            .expect("a chain's linkage")
            .moved_model(&a.model, &c);
        moved.assembly.blocks.iter().fold((0.0, 0.0), |(x, y), b| {
            (x + b.weight * b.centroid.x, y + b.weight * b.centroid.y)
        })
    };
    for share in [0.1, 0.5, 0.9] {
        let u = share * cap.rotation0;
        let h = 1e-5 * cap.rotation0;
        let ((x1, y1), (x0, y0)) = (moments(u + h), moments(u - h));
        let (_, alpha) = cap.at(&a.model, u).expect("point");
        close(
            alpha,
            (y1 - y0) / (x1 - x0),
            1e-7,
            "alpha = d(sum W y)/d(sum W x)",
        );
    }
    // Mirror invariance: the mirrored arch pushed to the left has the same curve.
    let mirrored = a.model.mirrored();
    let km = kinematic::analyse(
        &mirrored,
        &KinematicSettings::default().direction(Direction::Left),
    )
    .expect("mirrored search");
    let capm = assess::capacity(
        &mirrored,
        &km.mechanism.expect("mechanism"),
        Direction::Left,
        &CapacitySettings::default(),
    )
    .expect("mirrored capacity");
    close(capm.alpha0, cap.alpha0, 1e-9, "mirrored alpha0");
    close(capm.d_k0, cap.d_k0, 1e-9, "mirrored d_k0");
    close(capm.mass.e_star, cap.mass.e_star, 1e-9, "mirrored e*");
}

#[test]
fn loads_move_with_their_blocks_along_the_curve() {
    // The loaded portal (point and line loads, some seismic): alpha at a configuration is the
    // rate of work of the permanent loads over that of the seismic forces, from the moved
    // loads' positions alone: alpha = d(-sum F . p) / d(sum W_s p_x).
    let scene = Scene::from_file(&data("loaded_portal.toml")).expect("scene");
    let a = analysis::analyse(&scene, &Options::default()).expect("analysis");
    let mech = a
        .upper
        .as_ref()
        .expect("upper")
        .mechanism
        .clone()
        .expect("mechanism");
    let cap = assess::capacity(
        &a.model,
        &mech,
        Direction::Right,
        &CapacitySettings::default(),
    )
    .expect("capacity");
    close(
        cap.alpha0,
        a.lower.lambda.expect("lambda"),
        1e-9,
        "alpha0 = lambda",
    );
    let works = |u: f64| {
        let (c, _) = cap.at(&a.model, u).expect("configuration");
        let moved = cap
            .motion
            .linkage()
            .expect("a chain's linkage")
            .moved_model(&a.model, &c);
        moved.loads.applied().iter().fold((0.0, 0.0), |(g, s), l| {
            (g - l.force.dot(&l.point), s + l.seismic_weight * l.point.x)
        })
    };
    for share in [0.2, 0.6] {
        let u = share * cap.rotation0;
        let h = 1e-5 * cap.rotation0;
        let ((g1, s1), (g0, s0)) = (works(u + h), works(u - h));
        let (_, alpha) = cap.at(&a.model, u).expect("point");
        close(
            alpha,
            (g1 - g0) / (s1 - s0),
            1e-7,
            "alpha from the moved loads",
        );
    }
}

/// Control displacement of the DEM blocks after `duration` s at multiplier `lambda`, from the
/// configuration of the capacity curve at rotation `u`, minus the one it started from.
fn dem_drift(model: &Model, cap: &Capacity, u: f64, lambda: f64) -> (f64, f64) {
    let (config, _) = cap.at(model, u).expect("configuration");
    let moved = cap
        .motion
        .linkage()
        .expect("a chain's linkage")
        .moved_model(model, &config);
    let params = IntegrationParameters::for_model(&moved);
    let mut sim = Simulation::new(&moved, &params).expect("simulation");
    // Gravity and the seismic load ramped in together (their ratio, the multiplier, fixed
    // throughout) under Cundall's local damping, so the contact springs take the load
    // without a dynamic overshoot; the damping keeps the sign of each block's unbalanced
    // force, so it slows the mechanism but never turns it.
    sim.set_local_damping(params.local_damping);
    let ramp = 0.1;
    let steps = 50;
    for i in 1..=steps {
        let r = i as f64 / steps as f64;
        sim.set_load(r, r * lambda);
        sim.run_for(ramp / steps as f64);
    }
    let k = cap.control_block;
    let x0 = sim.blocks()[k].0.x;
    let scale = cap.d_k0;
    let mut drift: f64 = 0.0;
    let mut t = 0.0;
    while t < 2.0 && drift.abs() < 0.05 * scale {
        sim.run_for(0.01);
        t += 0.01;
        drift = sim.blocks()[k].0.x - x0;
    }
    (drift, t)
}

#[test]
fn dem_started_on_the_curve_returns_below_alpha_and_runs_away_above() {
    // The DEM starts from the blocks moved to a configuration of the curve (loads carried
    // along, supports in place) with the multiplier 0.98 or 1.02 times alpha there.
    let (_, a) = semicircle();
    let mech = a
        .upper
        .as_ref()
        .expect("upper")
        .mechanism
        .clone()
        .expect("mechanism");
    let settings = CapacitySettings::default();
    let cap = assess::capacity(&a.model, &mech, Direction::Right, &settings).expect("capacity");
    // Three points over the first 30 % of the rotation to d_k0. Further on, the DEM lets the
    // voussoir next to the first hinge turn on its own (the hinge moves one joint), a
    // mechanism the fixed-hinge curve of the code method does not follow: at half way the DEM
    // runs away at 0.95 alpha already (docs/assessment.md, "What it does not cover").
    for share in [0.1, 0.2, 0.3] {
        let u = share * cap.rotation0;
        let (_, alpha) = cap.at(&a.model, u).expect("point");
        let (back, t_back) = dem_drift(&a.model, &cap, u, 0.98 * alpha);
        let (away, t_away) = dem_drift(&a.model, &cap, u, 1.02 * alpha);
        eprintln!("share {share}: alpha {alpha:.5}: 0.98 -> drift {back:.5} m at {t_back:.2} s; 1.02 -> {away:.5} m at {t_away:.2} s");
        assert!(
            back < 0.0,
            "at 0.98 alpha({share} d) the mechanism returns: drift {back}"
        );
        assert!(
            away > 0.0,
            "at 1.02 alpha({share} d) it runs away: drift {away}"
        );
    }
}

/// The `[site]` table `text` of a small arch scene, read (also for `hazard.rs`).
pub(crate) fn site(text: &str) -> Result<Site, voussoir::error::SceneError> {
    let scene = Scene::from_toml_str(
        &format!(
            "[arch]\nshape = \"circular\"\nradius = 1.0\nthickness = 0.15\nvoussoirs = 8\n[site]\n{text}"
        ),
        "site-test",
    )?;
    Ok(scene.site.expect("site"))
}

#[test]
fn spectrum_at_the_corner_periods_is_the_code_formula() {
    let (ag, f0, tc_star): (f64, f64, f64) = (0.2, 2.5, 0.35);
    let s = site(&format!(
        "ag = {ag}\nsoil = \"C\"\ntopography = \"T2\"\nF0 = {f0}\nTc_star = {tc_star}\n"
    ))
    .expect("site");
    let sp = s.spectrum();
    // NTC 2018 Tab. 3.2.IV, soil C: SS = 1.70 - 0.60 F0 ag (within 1..1.5), CC = 1.05 Tc*^-0.33;
    // Tab. 3.2.V: ST = 1.2 on T2.
    let ss = 1.70 - 0.60 * f0 * ag;
    let tc = 1.05 * tc_star.powf(-0.33) * tc_star;
    let (tb, td) = (tc / 3.0, 4.0 * ag + 1.6);
    let s_amp = ss * 1.2;
    let a = ag * G;
    close(sp.ss, ss, 1e-12, "SS");
    close(sp.tc, tc, 1e-12, "TC");
    close(sp.tb, tb, 1e-12, "TB");
    close(sp.td, td, 1e-12, "TD");
    close(sp.se(0.0), a * s_amp, 1e-12, "Se(0) = ag S");
    close(sp.se(tb), a * s_amp * f0, 1e-12, "Se(TB)");
    close(sp.se(tc), a * s_amp * f0, 1e-12, "Se(TC)");
    close(sp.se(td), a * s_amp * f0 * tc / td, 1e-12, "Se(TD)");
    close(
        sp.se(2.0 * td),
        a * s_amp * f0 * tc * td / (4.0 * td * td),
        1e-12,
        "Se(2 TD)",
    );
    let two_pi = 2.0 * std::f64::consts::PI;
    close(
        sp.sde(tc),
        a * s_amp * f0 * (tc / two_pi).powi(2),
        1e-12,
        "SDe(TC)",
    );
    // A mechanism at height Z of a building H with period T1 (Circolare 2009 C8A.4.9-10,
    // gamma = 1.5): the larger of the ground and the amplified demands.
    let (z, hb, t1, q) = (6.0, 10.0, 0.5, 2.0);
    let high = site(&format!(
        "ag = {ag}\nsoil = \"C\"\ntopography = \"T2\"\nF0 = {f0}\nTc_star = {tc_star}\nZ = {z}\nH = {hb}\nT1 = {t1}\n"
    ))
    .expect("site at height");
    let psi_gamma = z / hb * 1.5;
    close(
        assess::linear_demand(&high),
        (a * s_amp / q).max(sp.se(t1) * psi_gamma / q),
        1e-12,
        "linear demand at height",
    );
    let ts = 0.3;
    let r = ts / t1;
    close(
        assess::nonlinear_demand(&high, ts),
        sp.sde(ts)
            .max(sp.sde(t1) * psi_gamma * r * r / ((1.0 - r).powi(2) + 0.02 * r).sqrt()),
        1e-12,
        "nonlinear demand at height",
    );
    assert!(
        assess::linear_demand(&high) > a * s_amp / q,
        "amplified at 0.6 H"
    );
    // The clamps of SS: soil B at a strong site stays at 1.0, soil D at a weak one at 1.8.
    assert_eq!(Soil::B.ss(0.6, 2.5), 1.0);
    assert_eq!(Soil::D.ss(0.05, 2.4), 1.8);
}

#[test]
fn largest_passing_ag_is_where_the_verdict_flips() {
    let scene = Scene::from_file(&data("semicircular.toml"))
        .expect("scene")
        .with_overrides(&[
            "site.ag=0.25",
            "site.soil=\"B\"",
            "site.F0=2.4",
            "site.Tc_star=0.3",
            "site.FC=1.35",
        ])
        .expect("site overrides");
    let a = analysis::assess(&scene, &Options::default(), &AssessOptions::default())
        .expect("assessment");
    let (cap, v, s) = (&a.capacity, &a.verdict, &a.site);
    // The linear check at ag = 0.25 g: a0* against ag S / q, both from the formulas.
    let sp = s.spectrum();
    close(v.linear.demand, 0.25 * G * sp.s / 2.0, 1e-12, "ag S / q");
    close(
        v.linear.capacity,
        cap.alpha0 * G / (cap.mass.e_star * 1.35),
        1e-12,
        "a0*",
    );
    close(v.du_star, 0.4 * cap.d0_star, 1e-12, "du*");
    close(v.ds_star, 0.16 * cap.d0_star, 1e-12, "ds*");
    close(
        v.ts,
        2.0 * std::f64::consts::PI * (v.ds_star / v.as_star).sqrt(),
        1e-12,
        "Ts",
    );
    close(v.nonlinear.demand, sp.sde(v.ts), 1e-12, "SDe(Ts)");
    for (name, check, passes) in [
        (
            "linear",
            v.linear,
            &(|s: &Site| cap.a0_star >= assess::linear_demand(s)) as &dyn Fn(&Site) -> bool,
        ),
        ("nonlinear", v.nonlinear, &|s: &Site| {
            v.du_star >= assess::nonlinear_demand(s, v.ts)
        }),
    ] {
        let ag = check.ag_max.expect("a largest ag below 2 g");
        assert!(passes(&s.with_ag(ag)), "{name}: passes at {ag}");
        let above = ag * (1.0 + 1e-12);
        assert!(!passes(&s.with_ag(above)), "{name}: fails just above {ag}");
        assert_eq!(check.passes, s.ag <= ag, "{name}: verdict at the site");
    }
    // Soil A: S = 1 whatever ag, so the linear limit is a closed form, a0* q / (S g).
    let rock = s.clone();
    let rock = Site {
        soil: Soil::A,
        ..rock
    };
    let ag_rock = assess::largest_passing_ag(&rock, |s| cap.a0_star >= assess::linear_demand(s))
        .expect("limit");
    close(ag_rock, cap.a0_star * 2.0 / G, 1e-12, "ag = a0* q / g");
    // A capacity below the demand at the grid's first point (0.005 g): its own small ag, by
    // the same closed form, not "more than 2 g"; none at all when it fails at any ag; None
    // only when it passes at 2 g.
    let weak = cap.a0_star * 1e-3;
    let ag_weak =
        assess::largest_passing_ag(&rock, |s| weak >= assess::linear_demand(s)).expect("limit");
    assert!(ag_weak < 0.005, "{ag_weak}");
    close(ag_weak, weak * 2.0 / G, 1e-12, "small ag = a0* q / g");
    assert_eq!(assess::largest_passing_ag(&rock, |_| false), Some(0.0));
    assert_eq!(assess::largest_passing_ag(&rock, |_| true), None);
}

#[test]
fn bad_site_input_is_named_with_its_key() {
    let ok = "ag = 0.2\nsoil = \"B\"\nF0 = 2.4\nTc_star = 0.3\n";
    assert!(site(ok).is_ok());
    for (text, key, words) in [
        (
            "ag = 0.2\nsoil = \"F\"\nF0 = 2.4\nTc_star = 0.3\n",
            "site.soil",
            "unknown soil category",
        ),
        (
            "ag = -0.1\nsoil = \"B\"\nF0 = 2.4\nTc_star = 0.3\n",
            "site.ag",
            "above 0",
        ),
        (
            "ag = 0.2\nsoil = \"B\"\nF0 = 2.4\nTc_star = 0.3\nFC = 0.9\n",
            "site.FC",
            "from 1",
        ),
        (
            "ag = 0.2\nsoil = \"B\"\nF0 = 2.4\nTc_star = 0.3\ntopography = \"T5\"\n",
            "site.topography",
            "T1, T2",
        ),
        ("ag = 0.2\nsoil = \"B\"\nF0 = 2.4\n", "site.Tc_star", "Tc*"),
        (
            "ag = 0.2\nsoil = \"B\"\nF0 = 2.4\nTc_star = 0.3\nZ = 3.0\n",
            "site.H",
            "height",
        ),
        (
            "ag = 0.2\nsoil = \"B\"\nF0 = 2.4\nTc_star = 0.3\nFc = 1.2\n",
            "site.Fc",
            "did you mean `FC`",
        ),
    ] {
        let e = site(text).expect_err(text);
        assert_eq!(e.key(), Some(key), "{text}: {e}");
        let msg = e.to_string();
        assert!(msg.contains(words), "{msg}");
        assert!(msg.contains("site-test"), "names the file: {msg}");
    }
}

#[test]
fn assess_command_reports_json_and_draws() {
    let dir = tempfile::tempdir().expect("tempdir");
    let (cap, adrs, mech) = (
        dir.path().join("capacity.svg"),
        dir.path().join("adrs.svg"),
        dir.path().join("mechanism.svg"),
    );
    let out = voussoir()
        .arg("assess")
        .arg(data("assess_portal.toml"))
        .args(["--json", "--svg"])
        .arg(&cap)
        .arg("--adrs-svg")
        .arg(&adrs)
        .arg("--mechanism-svg")
        .arg(&mech)
        .output()
        .expect("run");
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).expect("json");
    for key in [
        "alpha0",
        "a0_star",
        "d_k0",
        "d0_star",
        "du_star",
        "ds_star",
        "as_star",
        "Ts",
        "control_block",
        "passes",
        "site",
        "spectrum",
        "mechanism",
    ] {
        assert!(v.get(key).is_some(), "field {key}");
    }
    let e = v["participating_mass"]["e_star"].as_f64().expect("e*");
    assert!(e > 0.0 && e <= 1.0);
    assert_eq!(v["capacity_curve"].as_array().map(Vec::len), Some(200));
    assert_eq!(
        v["lambda_lower"]
            .as_f64()
            .map(|l| (l - v["alpha0"].as_f64().unwrap_or(0.0)).abs() < 1e-9),
        Some(true)
    );
    for lin in ["linear_check", "nonlinear_check"] {
        let c = &v[lin];
        let r = c["ratio"].as_f64().expect("ratio");
        assert_eq!(c["passes"].as_bool(), Some(r >= 1.0));
    }
    for path in [&cap, &adrs, &mech] {
        let text = std::fs::read_to_string(path).expect("svg written");
        roxmltree::Document::parse(&text).expect("well-formed svg");
    }
    // --site overrides the scene's table, and a bad value is named with its key.
    let out = voussoir()
        .arg("assess")
        .arg(data("assess_portal.toml"))
        .args(["--site", "soil=Q"])
        .output()
        .expect("run");
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("site.soil") && err.contains("unknown soil category"),
        "{err}"
    );
    // A scene without [site] says how to give one.
    let out = voussoir()
        .arg("assess")
        .arg(data("portal.toml"))
        .output()
        .expect("run");
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("--site ag="));
}

#[test]
fn bundled_example_assesses_through_the_analysis_layer() {
    // model_of is the scene's own model: the capacity of analysis::assess uses it.
    let scene = Scene::from_file(&data("assess_portal.toml")).expect("scene");
    let a = analysis::assess(&scene, &Options::default(), &AssessOptions::default())
        .expect("assessment");
    assert_eq!(
        a.analysis.model.assembly.blocks.len(),
        model_of(&scene).assembly.blocks.len()
    );
    close(
        a.capacity.alpha0,
        a.analysis.lower.lambda.expect("lambda"),
        1e-9,
        "alpha0 = lambda",
    );
}

/// The loaded portal (a 10 kN seismic mass on its right haunch) at a site, through the CLI.
fn loaded_portal_json(extra: &[&str]) -> serde_json::Value {
    let out = voussoir()
        .arg("assess")
        .arg(data("loaded_portal.toml"))
        .args([
            "--site",
            "ag=0.25",
            "--site",
            "soil=B",
            "--site",
            "F0=2.4",
            "--site",
            "Tc_star=0.3",
            "--json",
        ])
        .args(extra)
        .output()
        .expect("run");
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_slice(&out.stdout).expect("json")
}

fn f(v: &serde_json::Value) -> f64 {
    v.as_f64().unwrap_or(f64::NAN)
}

/// The largest passing ag of a direction, None (more than 2 g) as infinity.
fn ag_of(d: &serde_json::Value) -> f64 {
    d["ag_max"].as_f64().unwrap_or(f64::INFINITY)
}

#[test]
fn assess_checks_both_directions_and_the_worse_governs() {
    // Issue 26: the default used to assess the load toward the right only. The seismic mass on
    // the right haunch makes the left the weaker direction of this portal.
    let v = loaded_portal_json(&[]);
    let (right, left) = (&v["directions"]["right"], &v["directions"]["left"]);
    assert_eq!(right["direction"], "right");
    assert_eq!(left["direction"], "left");
    assert_eq!(
        v["directions_assessed"],
        serde_json::json!(["right", "left"])
    );
    assert_eq!(v["restricted"], false);
    // Each direction is what `--direction` alone gives, to the last bit (its own mechanism).
    for (name, d) in [("right", right), ("left", left)] {
        let alone = loaded_portal_json(&["--direction", name]);
        assert_eq!(alone["restricted"], true);
        assert_eq!(alone["directions_assessed"], serde_json::json!([name]));
        assert!(alone["directions"]
            .get(if name == "right" { "left" } else { "right" })
            .is_none());
        for key in ["alpha0", "a0_star", "d_k0", "du_star", "Ts", "ag_max"] {
            assert_eq!(alone[key], d[key], "{name}: {key}");
        }
        assert_eq!(alone["linear_check"], d["linear_check"], "{name}");
        assert_eq!(alone["nonlinear_check"], d["nonlinear_check"], "{name}");
    }
    // The two directions differ here, so the choice of the governing one matters.
    assert!(f(&left["alpha0"]) < f(&right["alpha0"]) * 0.9);
    // The governing direction is the worse one: a failing direction over a passing one, then
    // the smaller largest passing ag.
    let worse = match (right["passes"].as_bool(), left["passes"].as_bool()) {
        (Some(true), Some(false)) => "left",
        (Some(false), Some(true)) => "right",
        _ if ag_of(left) < ag_of(right) => "left",
        _ => "right",
    };
    assert_eq!(v["governing"], worse);
    assert_eq!(v["direction"], worse);
    let g = &v["directions"][worse];
    // The top-level fields (the contract before issue 26) hold the governing direction's values.
    for key in [
        "lambda_lower",
        "alpha0",
        "a0_star",
        "d_k0",
        "d0_star",
        "du_star",
        "ds_star",
        "as_star",
        "Ts",
        "control_block",
        "linear_check",
        "nonlinear_check",
        "participating_mass",
        "mechanism",
        "capacity_curve",
        "ag_max",
        "satisfied",
    ] {
        assert_eq!(
            v[key], g[key],
            "top-level {key} is the governing direction's"
        );
    }
    // The structure passes only if every direction does.
    assert_eq!(
        v["passes"].as_bool(),
        Some(right["passes"] == true && left["passes"] == true)
    );
    // The text shows both directions and names the governing one.
    let out = voussoir()
        .arg("assess")
        .arg(data("loaded_portal.toml"))
        .args([
            "--site",
            "ag=0.25",
            "--site",
            "soil=B",
            "--site",
            "F0=2.4",
            "--site",
            "Tc_star=0.3",
        ])
        .output()
        .expect("run");
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(text.contains("Load toward the right:"), "{text}");
    assert!(text.contains("Load toward the left:"), "{text}");
    assert!(
        text.contains(&format!("Governing direction: the load toward the {worse}")),
        "{text}"
    );
    let out = voussoir()
        .arg("assess")
        .arg(data("loaded_portal.toml"))
        .args([
            "--site",
            "ag=0.25",
            "--site",
            "soil=B",
            "--site",
            "F0=2.4",
            "--site",
            "Tc_star=0.3",
        ])
        .args(["--direction", "right"])
        .output()
        .expect("run");
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(!text.contains("Load toward the left:"), "{text}");
    assert!(
        text.contains("only the load toward the right was assessed"),
        "says the verdict covers one direction: {text}"
    );
}

#[test]
fn mirrored_portal_to_the_right_is_the_portal_to_the_left() {
    // Moving the seismic point load to the mirror point (the line load is symmetric) mirrors
    // the structure: its right assessment must be the original's left one.
    let v = loaded_portal_json(&[]);
    let m = loaded_portal_json(&["--set", "loads[0].at=[-1.2, 2.19]"]);
    let (a, b) = (&v["directions"]["left"], &m["directions"]["right"]);
    for key in ["alpha0", "a0_star", "d_k0", "d0_star", "du_star", "Ts"] {
        close(f(&b[key]), f(&a[key]), 1e-9, key);
    }
    close(ag_of(b), ag_of(a), 1e-9, "ag_max");
    assert_eq!(a["satisfied"], b["satisfied"]);
}

#[test]
fn either_check_satisfied_passes_the_mechanism() {
    // Circolare 2019 C8.7.1: the linear or the nonlinear kinematic analysis verifies a local
    // mechanism. At ag = 0.25 g the portal loaded toward the right satisfies the linear check
    // and not the nonlinear one: it passes (it used to be reported as not passing).
    let v = loaded_portal_json(&["--direction", "right"]);
    let (lin, nonlin) = (&v["linear_check"], &v["nonlinear_check"]);
    assert!(
        f(&lin["ratio"]) >= 1.0 && f(&nonlin["ratio"]) < 1.0,
        "{lin} {nonlin}"
    );
    assert_eq!(v["passes"], true);
    assert_eq!(v["satisfied"], "linear");
    assert_eq!(v["both_checks_pass"], false);
    assert!(v["verdict"]
        .as_str()
        .unwrap_or("")
        .starts_with("passes: linear check satisfied"));
    assert!(v["rule"].as_str().unwrap_or("").contains("C8.7.1"));
    // The largest passing ag by the rule is the larger of the two checks'.
    close(
        f(&v["ag_max"]),
        f(&lin["ag_max"]).max(f(&nonlin["ag_max"])),
        0.0,
        "ag_max",
    );
    // Above both checks' limits nothing passes; between them, only the linear check.
    let mid = 0.5 * (f(&lin["ag_max"]) + f(&nonlin["ag_max"]));
    let between = loaded_portal_json(&["--direction", "right", "--site", &format!("ag={mid}")]);
    assert_eq!(between["passes"], true);
    let above = f(&lin["ag_max"]).max(f(&nonlin["ag_max"])) * 1.01;
    let high = loaded_portal_json(&["--direction", "right", "--site", &format!("ag={above}")]);
    assert_eq!(high["passes"], false);
    assert_eq!(high["satisfied"], "neither");
    assert!(high["verdict"]
        .as_str()
        .unwrap_or("")
        .starts_with("does not pass"));
}

#[test]
fn governing_direction_is_the_failing_then_the_weaker_one() {
    let check = |passes: bool, ag_max: Option<f64>| assess::Check {
        capacity: 1.0,
        demand: 1.0,
        ratio: if passes { 1.0 } else { 0.5 },
        passes,
        ag_max,
    };
    let verdict = |lin: assess::Check, nonlin: assess::Check| assess::Verdict {
        spectrum: Site {
            soil: Soil::A,
            ..site("ag = 0.2\nsoil = \"A\"\nF0 = 2.4\nTc_star = 0.3\n").expect("site")
        }
        .spectrum(),
        du_star: 0.01,
        ds_star: 0.004,
        as_star: 1.0,
        ts: 0.4,
        linear: lin,
        nonlinear: nonlin,
    };
    let a = verdict(check(true, Some(0.3)), check(false, Some(0.1)));
    let b = verdict(check(false, Some(0.15)), check(false, Some(0.12)));
    let c = verdict(check(true, None), check(true, Some(0.5)));
    assert!(a.passes() && !a.both_pass());
    assert_eq!(a.satisfied(), assess::Satisfied::Linear);
    assert_eq!(a.ag_max(), Some(0.3));
    assert!(!b.passes());
    assert_eq!(c.ag_max(), None);
    // A failing direction governs, whatever the ag; then the smaller ag; ties keep the first.
    assert_eq!(assess::governing_index(&[&a, &b]), 1);
    assert_eq!(assess::governing_index(&[&b, &a]), 0);
    assert_eq!(assess::governing_index(&[&c, &a]), 1);
    assert_eq!(assess::governing_index(&[&a, &a]), 0);
    // Round-off is a tie: the symmetric portal's directions differ by 1e-15, the right stays.
    let a2 = verdict(
        check(true, Some(0.3 * (1.0 - 1e-14))),
        check(false, Some(0.1)),
    );
    assert_eq!(assess::governing_index(&[&a, &a2]), 0);
    let out = voussoir()
        .arg("assess")
        .arg(data("assess_portal.toml"))
        .arg("--json")
        .output()
        .expect("run");
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).expect("json");
    let (r, l) = (&v["directions"]["right"], &v["directions"]["left"]);
    close(
        ag_of(r),
        ag_of(l),
        1e-12,
        "symmetric portal: the same ag both ways",
    );
    assert_eq!(v["governing"], "right", "a tie keeps the right");
}

#[test]
fn charts_mark_significant_points_and_speak_the_engineers_symbols() {
    let dir = tempfile::tempdir().expect("tempdir");
    let (cap, adrs, mech) = (
        dir.path().join("capacity.svg"),
        dir.path().join("adrs.svg"),
        dir.path().join("mechanism.svg"),
    );
    let out = voussoir()
        .arg("assess")
        .arg(data("loaded_portal.toml"))
        .args([
            "--site",
            "ag=0.25",
            "--site",
            "soil=B",
            "--site",
            "F0=2.4",
            "--site",
            "Tc_star=0.3",
        ])
        .arg("--svg")
        .arg(&cap)
        .arg("--adrs-svg")
        .arg(&adrs)
        .arg("--mechanism-svg")
        .arg(&mech)
        .output()
        .expect("run");
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    // Circles inside each series group (the legend draws its own, outside them).
    let markers = |text: &str| -> Vec<usize> {
        let doc = roxmltree::Document::parse(text).expect("well-formed svg");
        doc.descendants()
            .filter(|n| n.attribute("class") == Some("series"))
            .map(|g| g.descendants().filter(|n| n.has_tag_name("circle")).count())
            .collect()
    };
    let text = std::fs::read_to_string(&cap).expect("capacity svg");
    // Two curves of 200 points each: rest, du* and the end at alpha = 0 are marked, no more.
    assert_eq!(markers(&text), vec![3, 3], "capacity chart markers");
    let text_adrs = std::fs::read_to_string(&adrs).expect("adrs svg");
    let m = markers(&text_adrs);
    assert_eq!(m[0], 4, "capacity: a0*, (ds*, as*), du*, d0*");
    assert_eq!(m[1], 1, "demand: the point at Ts");
    assert!(m[2..].iter().all(|&k| k == 0), "{m:?}");
    let text_mech = std::fs::read_to_string(&mech).expect("mechanism svg");
    for t in [&text, &text_adrs, &text_mech] {
        for code in [
            "alpha0",
            "lambda_lower",
            "lambda_upper",
            "alpha(",
            "alpha =",
            "d_k",
        ] {
            assert!(!t.contains(code), "a code name {code:?} in a drawing");
        }
    }
    assert!(text.contains("α₀") && text.contains("dₖ"));
    assert!(text_mech.contains("α = "));
}

#[test]
fn a_mechanism_the_static_bound_does_not_reach_is_not_assessed() {
    // Finite friction: the thick semicircle slides at lambda = 0.13, far below its rotational
    // mechanism (0.41). The rotational capacity curve would start 3 times too high; it used to
    // be assessed (and passed) without a word.
    let out = voussoir()
        .arg("assess")
        .arg(data("semicircular.toml"))
        .args([
            "--site",
            "ag=0.25",
            "--site",
            "soil=B",
            "--site",
            "F0=2.4",
            "--site",
            "Tc_star=0.3",
        ])
        .args([
            "--set",
            "material.friction=0.4",
            "--set",
            "arch.thickness=0.25",
            "--json",
        ])
        .output()
        .expect("run");
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("slide") && err.contains("no assessment"),
        "{err}"
    );
    // The same ring with crushing but no sliding: the mechanism is the crushing one, its
    // alpha0 is the static multiplier of the finite strength (below the rigid one).
    let run = |fc: &str| {
        let out = voussoir()
            .arg("assess")
            .arg(data("semicircular.toml"))
            .args([
                "--site",
                "ag=0.25",
                "--site",
                "soil=B",
                "--site",
                "F0=2.4",
                "--site",
                "Tc_star=0.3",
            ])
            .args([
                "--set",
                &format!("material.compressive_strength={fc}"),
                "--json",
            ])
            .output()
            .expect("run");
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        serde_json::from_slice::<serde_json::Value>(&out.stdout).expect("json")
    };
    let (rigid, crushing) = (run("inf"), run("1e6"));
    close(
        f(&crushing["alpha0"]),
        f(&crushing["lambda_lower"]),
        1e-9,
        "alpha0 = lambda",
    );
    assert!(f(&crushing["alpha0"]) < f(&rigid["alpha0"]));
    // Hinges inset by half the compressed zone: a shorter way to alpha = 0.
    assert!(f(&crushing["d_k0"]) < f(&rigid["d_k0"]));
    assert!(
        crushing["mechanism"]["hinges"][0]["offset"]
            .as_f64()
            .unwrap_or(0.0)
            > 0.0
    );
}
