//! Issue 25, items 2 to 4: the non-associative collapse multiplier (joints that slide without
//! opening), found by the iteration of Gilbert, Casapulla & Ahmed (2006) on programs with
//! fixed shear capacities (`statics::non_associative`, docs/friction.md), checked against hand
//! derivations, the published minimum thicknesses of their 27-voussoir semicircle, and the DEM,
//! whose Coulomb contacts slide without dilatancy.

use crate::common::*;
use voussoir::analysis::{self, FrictionMode, Options};
use voussoir::assembly::{Assembly, Joint, JointKind};
use voussoir::geometry::Vec2;
use voussoir::model::Model;
use voussoir::scene::Scene;
use voussoir::statics::{
    self, Direction, NonAssociativeSettings, SettledBy, StaticSettings, Status,
};

/// The associative static result and the non-associative multiplier of `model`.
fn both(model: &Model, direction: Direction) -> (statics::StaticResult, statics::NonAssociative) {
    let s = StaticSettings::default().direction(direction);
    let a = statics::analyse(model, &s).expect("static program");
    let na = statics::analyse_non_associative(model, &s, &a, &NonAssociativeSettings::default())
        .expect("non-associative iteration");
    (a, na)
}

/// Issue 25's first acceptance case: a thin semicircle with ample friction rocks (no joint
/// slips in its mechanism), so the non-associative multiplier is the associative one, to the
/// bit, and nothing is iterated; `--friction associative` leaves it out, and `--friction
/// non-associative` iterates anyway and lands on the same value.
#[test]
fn a_rocking_arch_with_finite_friction_is_exact_and_not_iterated() {
    let text = "[arch]\nshape = \"circular\"\nradius = 1.0\nthickness = 0.15\nvoussoirs = 16\n[material]\nfriction = 0.6\n";
    let v = json_of(&["analyze", "--json"], text);
    assert_eq!(v["friction_exact"], true, "{v}");
    let associative = f64_of(&v, "lambda_associative");
    let na = f64_of(&v, "lambda_non_associative");
    assert!((na - associative).abs() <= 1e-12, "{na} vs {associative}");
    assert_eq!(v["non_associative_iterations"], 0);
    assert_eq!(v["non_associative_converged"], true);
    assert_eq!(v["non_associative_starts"], serde_json::json!([]));
    assert_eq!(f64_of(&v, "lambda_governing"), f64_of(&v, "lambda_lower"));
    let off = json_of(&["analyze", "--json", "--friction", "associative"], text);
    assert!(off["lambda_non_associative"].is_null(), "{off}");
    assert!(off["non_associative_converged"].is_null(), "{off}");
    assert_eq!(off["lambda_governing"], off["lambda_lower"]);
    let forced = json_of(
        &["analyze", "--json", "--friction", "non-associative"],
        text,
    );
    assert_eq!(forced["non_associative_converged"], true, "{forced}");
    assert!(forced["non_associative_iterations"].as_u64().unwrap_or(0) >= 2);
    let iterated = f64_of(&forced, "lambda_non_associative");
    assert!(
        (iterated - associative).abs() <= 1e-6 * associative.max(1.0),
        "{iterated} vs {associative}"
    );
    assert!(iterated <= associative + 1e-9);
}

/// A b x h block on a flat base, pushed at mid-height (its centroid) by lambda W: with
/// mu < b/h it slides at lambda = mu. The joint is horizontal, so N = W whatever the
/// mechanism: the associative mechanism (slip s, lift mu s) and the real one (slip s,
/// dissipation mu W s) both give lambda W s = mu W s. Both values are mu.
#[test]
fn a_block_pushed_at_mid_height_slides_at_mu_in_both_laws() {
    for mu in [0.3, 0.5, 0.8] {
        let model = Model::self_weight(single_block(1.0, 1.0, mu));
        let (a, na) = both(&model, Direction::Right);
        let l = a.lambda.expect("collapse");
        assert!((l - mu).abs() <= 1e-9, "associative {l} vs mu {mu}");
        assert!(!a.friction(&model.assembly).exact);
        assert!(na.converged, "{:?}", na.starts);
        let n = na.lambda.expect("converged value");
        assert!((n - mu).abs() <= 1e-8, "non-associative {n} vs mu {mu}");
        assert_eq!(na.sliding, vec![0]);
    }
}

/// Two b x h blocks side by side on the ground, touching along the vertical joint x = 0 (a
/// two-block stack laid on its side: a stack with horizontal beds is statically determinate,
/// so its two multipliers are always equal; this pair is not). Load lambda W on each toward
/// +x, friction mu everywhere, b/h < mu.
///
/// Associative (by hand): at collapse both blocks sit on their right toes (A's at (0, 0), B's
/// at (b, 0)); A pushes B with P at height y and the joint's friction F acts up on A, down on
/// B, |F| <= mu P. Moments about the toes: A: lambda W h/2 = W b/2 + P y; B: lambda W h/2 =
/// W b/2 - P y + b F. So lambda = b/h + b F/(W h), largest with F = mu P and P as large as B's
/// base allows: |V_B| = lambda W + P <= mu N_B = mu (W + mu P). With p = P/W both bind at
/// p* = (mu - b/h) / (1 - mu^2 + mu b/h), lambda_assoc = (b/h)(1 + mu p*): the mechanism
/// rocks both blocks and slides (with dilatancy) at the head joint and under B.
///
/// Non-associative (by hand): lambda = b/h with P = 0 is a complete solution: each block on its
/// toe, |V| = (b/h) W < mu W on each base, and a mechanism in which both rock and the empty
/// head joint slides freely. Below b/h each base joint is strictly inside its yield surface
/// with P = 0, so nothing can move: lambda_c = b/h, below the associative value. (Every value
/// between them is also a non-associative solution, with P > 0 in the mechanism: the problem
/// has many; the least-friction start finds the lowest.)
#[test]
fn two_blocks_side_by_side_rock_at_b_over_h_but_the_associative_joint_reaches_higher() {
    let pair = |b: f64, h: f64, mu: f64| -> Model {
        Model::self_weight(Assembly {
            blocks: vec![rect(-b, 0.0, b, h), rect(0.0, 0.0, b, h)],
            joints: vec![
                hjoint(0.0, -b, 0.0, None, Some(0), mu),
                hjoint(b, 0.0, 0.0, None, Some(1), mu),
                Joint {
                    p1: Vec2::new(0.0, 0.0),
                    p2: Vec2::new(0.0, h),
                    from: Some(0),
                    to: Some(1),
                    friction: mu,
                    kind: JointKind::Other,
                },
            ],
        })
    };
    for (b, h, mu) in [(0.5, 2.0, 0.6), (0.4, 1.0, 0.55)] {
        let r = b / h;
        let p = (mu - r) / (1.0 - mu * mu + mu * r);
        let hand_associative = r * (1.0 + mu * p);
        let model = pair(b, h, mu);
        for d in [Direction::Right, Direction::Left] {
            // The load toward the left on the mirror image is the same problem.
            let m = if d == Direction::Left {
                model.mirrored()
            } else {
                model.clone()
            };
            let (a, na) = both(&m, d);
            let l = a.lambda.expect("collapse");
            assert!(
                (l - hand_associative).abs() <= 1e-8,
                "{d:?}: associative {l} vs hand {hand_associative}"
            );
            assert!(!a.friction(&m.assembly).exact);
            let n = na.lambda.expect("a start converged");
            // The iteration stops when successive multipliers agree to 1e-6.
            assert!(
                (n - r).abs() <= 2e-6,
                "{d:?}: non-associative {n} vs b/h {r}"
            );
            assert!(n < l);
            let least = na
                .starts
                .iter()
                .find(|s| s.start == statics::Start::LeastFriction)
                .expect("the least-friction start ran");
            assert!(
                least.converged() && least.lambda == na.lambda,
                "{:?}",
                na.starts
            );
        }
    }
}

/// Gilbert, Casapulla & Ahmed (2006), the 27-voussoir semicircle under self-weight, centreline
/// radius R = 10 m: minimum thickness 1.26, 1.51, 1.78 and 1.95 m at mu = 0.375, 0.35, 0.325
/// and 0.31 (the thickness in metres: t/R = 0.126 at mu = 0.375, against Heyman's 0.107 with
/// infinite friction). Both the associative and the non-associative minimum thickness are
/// within 2.5 % of them, and the non-associative one is not below the associative one (every
/// non-associative solution is an admissible equilibrium).
#[test]
fn gilbert_semicircle_minimum_thickness_against_friction() {
    let published = [(0.375, 1.26), (0.35, 1.51), (0.325, 1.78), (0.31, 1.95)];
    for (mu, t_pub) in published {
        let s = scene(&format!(
            "[arch]\nshape = \"circular\"\nradius = 10.0\nthickness = 2.5\nvoussoirs = 27\n[material]\nfriction = {mu}\n"
        ));
        let options = Options {
            kinematic_max_joints: 0,
            friction: FrictionMode::NonAssociative,
            ..Options::default()
        };
        let t = voussoir::thickness::analyse(&s, &options).expect("thickness search");
        let assoc = t.lower.search.min_thickness.expect("associative minimum");
        let na = t
            .non_associative
            .as_ref()
            .and_then(|n| n.min_thickness)
            .expect("non-associative minimum");
        println!(
            "mu {mu}: associative {assoc:.4} m, non-associative {na:.4} m, published {t_pub} m"
        );
        for (what, value) in [("associative", assoc), ("non-associative", na)] {
            assert!(
                (value / t_pub - 1.0).abs() <= 0.025,
                "mu {mu}: {what} {value} vs published {t_pub}"
            );
        }
        assert!(na >= assoc * (1.0 - 1e-6), "{na} < {assoc}");
    }
}

fn polygons_scene(blocks: &[[f64; 4]], mu: f64) -> Scene {
    let polys: Vec<String> = blocks
        .iter()
        .map(|[x0, y0, x1, y1]| format!("[[{x0}, {y0}], [{x1}, {y0}], [{x1}, {y1}], [{x0}, {y1}]]"))
        .collect();
    scene(&format!(
        "[blocks]\npolygons = [{}]\n[material]\nfriction = {mu}\n",
        polys.join(", ")
    ))
}

/// The running-bond wall of `tests/it/blocks.rs` and docs/dem.md: three courses of 0.4 m,
/// 1.2 m long, the middle one offset by half a block.
fn running_bond_wall(mu: f64) -> Scene {
    polygons_scene(&running_bond_wall_rects(), mu)
}

/// A lintel portal: two piers 0.6 x 1.2 m, 1.2 m apart, and a 2.4 x 0.4 m lintel on them.
fn lintel_portal(mu: f64) -> Scene {
    polygons_scene(
        &[
            [0.0, 0.0, 0.6, 1.2],
            [1.8, 0.0, 2.4, 1.2],
            [0.0, 1.2, 2.4, 1.6],
        ],
        mu,
    )
}

fn stepped_buttresses(mu: f64) -> Scene {
    Scene::from_file(&data("blocks_stepped_buttresses.toml"))
        .expect("bundled scene")
        .with_overrides(&[format!("material.friction={mu}")])
        .expect("friction override")
}

/// The cases of [`walls_and_portals_sit_below_the_associative_value_and_on_the_dem`] whose
/// DEM lies more than 3 % from the non-associative value (docs/friction.md, "The check").
const OUTSIDE: [(&str, f64); 1] = [("running-bond wall", 0.7)];

/// Issue 25's last acceptance case: a running-bond wall, a lintel portal and the
/// stepped-buttress portal with mu = 0.4 to 0.7. The non-associative multiplier is at most
/// the associative one, its forces are in equilibrium and obey Coulomb's law, and the DEM
/// (whose contacts slide without opening, from its own start) brackets a value within 3 % of
/// it, but on the wall at mu = 0.7 ([`OUTSIDE`]): there the associative value is 0.613, the
/// lowest non-associative solution found 0.536 and the DEM's 0.565, another solution, which
/// moves toward the associative value as the contacts stiffen (docs/dem.md).
#[test]
fn walls_and_portals_sit_below_the_associative_value_and_on_the_dem() {
    let mut worst: f64 = 0.0;
    for mu in [0.4, 0.55, 0.7] {
        for (name, s) in [
            ("running-bond wall", running_bond_wall(mu)),
            ("lintel portal", lintel_portal(mu)),
            ("stepped buttresses", stepped_buttresses(mu)),
        ] {
            let a = analysis::analyse(&s, &Options::default()).expect("analysis");
            assert_eq!(a.lower.status, Status::Collapse, "{name}");
            let associative = a.lower.lambda.expect("collapse");
            let na = a.non_associative.as_ref().expect("computed in auto mode");
            assert!(na.converged, "{name} mu {mu}: {:?}", na.starts);
            let n = na.lambda.expect("converged value");
            assert!(
                n <= associative + 1e-9 * associative.max(1.0),
                "{name} mu {mu}: non-associative {n} above associative {associative}"
            );
            assert_eq!(a.lambda_governing(), Some(n));
            if let Some(r) = &na.result {
                let fs = a.model.loads.force_scale();
                assert!(r.equilibrium_residual <= 1e-6 * fs, "{name}: residual");
                for (j, f) in a
                    .model
                    .assembly
                    .joints
                    .iter()
                    .zip(r.forces.iter().flatten())
                {
                    assert!(
                        f.v.abs() <= j.friction * f.n + 1e-6 * fs,
                        "{name} mu {mu}: |V| {} > mu N {}",
                        f.v.abs(),
                        j.friction * f.n
                    );
                }
            }
            let dem =
                analysis::dem(&s, &analysis::DemOptions::default(), &mut |_| {}).expect("DEM");
            let (lo, hi) = (
                dem.result.lambda_stands.expect("a standing run"),
                dem.result.lambda_collapses.expect("a collapsing run"),
            );
            let mid = 0.5 * (lo + hi);
            let off = mid / n - 1.0;
            println!(
                "{name} mu {mu}: associative {associative:.5}, non-associative {n:.5} ({} programs), DEM [{lo:.5}, {hi:.5}] ({:+.2} %)",
                na.iterations,
                100.0 * off
            );
            if OUTSIDE.contains(&(name, mu)) {
                // Documented outside 3 % (docs/friction.md): the DEM reaches another of the
                // several non-associative solutions, above the lowest found and below the
                // associative bound (Radenkovic).
                // The documented offset (+5.5 % at the default stiffness), and the DEM's value
                // between the lowest solution found and the associative bound (up to the
                // bracket's own width).
                assert!(
                    off > 0.03 && off < 0.08 && lo > n && lo <= associative,
                    "{name} mu {mu}: DEM [{lo}, {hi}] vs non-associative {n}, associative {associative}"
                );
                continue;
            }
            worst = worst.max(off.abs());
            assert!(
                off.abs() <= 0.03,
                "{name} mu {mu}: DEM {mid} vs non-associative {n}"
            );
        }
    }
    println!("largest DEM offset {:.2} %", 100.0 * worst);
}

/// A start that has not settled is never reported as a solution: with a single program per
/// start (the convergence test needs two) nothing converges, and there is no multiplier.
#[test]
fn an_iteration_that_does_not_settle_gives_no_multiplier() {
    let model = voussoir::scene::build(&running_bond_wall(0.7)).expect("model");
    let s = StaticSettings::default();
    let a = statics::analyse(&model, &s).expect("static");
    let one = NonAssociativeSettings {
        max_iterations: 1,
        ..NonAssociativeSettings::default()
    };
    let na = statics::analyse_non_associative(&model, &s, &a, &one).expect("runs");
    assert!(!na.converged);
    assert_eq!(na.lambda, None);
    assert!(na
        .starts
        .iter()
        .all(|s| !s.converged() && s.stopped.is_some()));
    assert!(
        na.starts.iter().all(|s| s.lambda.is_some()),
        "the last iterates are kept"
    );
    // Nothing to iterate without a collapse: no multiplier, no start.
    let thin = model_of(&semicircle(0.05, 16));
    let r = statics::analyse(&thin, &s).expect("static");
    assert_eq!(r.status, Status::CannotStand);
    let na = statics::analyse_non_associative(&thin, &s, &r, &NonAssociativeSettings::default())
        .expect("runs");
    assert!(na.lambda.is_none() && na.starts.is_empty());
}

/// The wall at mu = 0.7 through the command line: the JSON's fields, the summary's words and
/// `--dem`'s placement of the three values; `--friction` refuses other words.
#[test]
fn the_command_line_says_where_the_three_values_sit() {
    let text = "[blocks]\npolygons = [[[0.0,0.0],[0.6,0.0],[0.6,0.4],[0.0,0.4]], [[0.6,0.0],[1.2,0.0],[1.2,0.4],[0.6,0.4]], [[0.0,0.4],[0.3,0.4],[0.3,0.8],[0.0,0.8]], [[0.3,0.4],[0.9,0.4],[0.9,0.8],[0.3,0.8]], [[0.9,0.4],[1.2,0.4],[1.2,0.8],[0.9,0.8]], [[0.0,0.8],[0.6,0.8],[0.6,1.2],[0.0,1.2]], [[0.6,0.8],[1.2,0.8],[1.2,1.2],[0.6,1.2]]]\n[material]\nfriction = 0.7\n";
    let v = json_of(&["analyze", "--json", "--dem"], text);
    assert_eq!(v["friction_exact"], false);
    assert_eq!(v["non_associative_converged"], true);
    let na = f64_of(&v, "lambda_non_associative");
    assert!(na < f64_of(&v, "lambda_associative"));
    assert_eq!(f64_of(&v, "lambda_governing"), na);
    assert!(v["non_associative_iterations"].as_u64().unwrap_or(0) > 0);
    let starts: Vec<&str> = v["non_associative_starts"]
        .as_array()
        .expect("starts")
        .iter()
        .filter_map(|s| s["start"].as_str())
        .collect();
    assert_eq!(starts, ["associative", "least_friction", "at_rest"]);
    // How each start settled: a converged start says how, one that did not says null.
    for s in v["non_associative_starts"].as_array().expect("starts") {
        match (s["converged"].as_bool(), s["settled_by"].as_str()) {
            (Some(true), Some("relaxation" | "mechanism_step")) => {}
            (Some(false), None) => assert!(s["settled_by"].is_null()),
            other => panic!("start {s}: {other:?}"),
        }
    }
    assert!(v["non_associative_sliding_joints"].is_array());
    assert!(v["non_associative_note"]
        .as_str()
        .is_some_and(|n| n.contains("several solutions")));
    let dem = &v["dem"];
    let (lo, hi) = (
        f64_of(dem, "lambda_stands"),
        f64_of(dem, "lambda_collapses"),
    );
    // The DEM's value sits between the lowest non-associative solution found and the
    // associative bound (one of the several solutions: docs/friction.md, "The check").
    assert!(
        lo < hi && na < lo && hi <= 1.01 * f64_of(&v, "lambda_associative"),
        "{dem}"
    );
    let (_dir, path) = scene_file(text);
    let out = voussoir()
        .args(["analyze", "--dem"])
        .arg(&path)
        .output()
        .expect("runs");
    let summary = String::from_utf8_lossy(&out.stdout);
    assert!(
        summary.contains("Non-associative friction (joints slide without opening): lambda = ")
            && summary.contains("Where the multipliers sit")
            && summary.contains("DEM (Coulomb contacts, no dilatancy): stands at"),
        "{summary}"
    );
    let bad = voussoir()
        .args(["analyze", "--friction", "dilatant"])
        .arg(&path)
        .output()
        .expect("runs");
    assert!(!bad.status.success());
    assert!(String::from_utf8_lossy(&bad.stderr).contains("non-associative"));
}

/// The non-associative multiplier of `model` toward `direction` by the chain's active set
/// (the default settings) and by the full conic program (`Program::Full`, the path every
/// program took before), from the same associative result.
fn by_both_paths(
    model: &Model,
    direction: Direction,
) -> (statics::NonAssociative, statics::NonAssociative) {
    let s = StaticSettings::default().direction(direction);
    let a = statics::analyse(model, &s).expect("static program");
    // The relaxation alone on both paths: the chain's active set takes no mechanism step
    // (it gives no interior-point duals), and the comparison is of the same iteration.
    let na = NonAssociativeSettings {
        mechanism_step: false,
        ..NonAssociativeSettings::default()
    };
    let chain = statics::analyse_non_associative(model, &s, &a, &na).expect("chain path");
    let full_settings = s.clone().program(statics::Program::Full);
    let full = statics::analyse_non_associative(model, &full_settings, &a, &na).expect("full path");
    (chain, full)
}

/// Issue 25's benchmark item: on a chain the iteration's programs are solved by the chain's
/// active set with fixed capacities (`statics/chain/fixed_shear.rs`) instead of the full
/// conic program. On a grid of arches whose joints slide (semicircles, segmental and pointed
/// arches, thick and thin, low friction, 8 to 48 voussoirs, with and without a line load, both
/// directions) both paths take the same number of programs from every start, converge alike,
/// and give the same multiplier to 1e-9 (each program's optimum is an LP's, unique in value;
/// the interior point's tolerance leaves about 1e-11).
#[test]
fn the_chain_path_gives_the_full_programs_multiplier() {
    let mut worst: f64 = 0.0;
    let (mut cases, mut compared) = (0, 0);
    for (shape, extra) in [
        ("circular", ""),
        ("circular", "embrace_deg = 140.0\n"),
        ("pointed", "eccentricity = 0.2\n"),
    ] {
        for (t, mu) in [(0.25, 0.4), (0.3, 0.35), (0.2, 0.45), (0.35, 0.3)] {
            for n in [8, 20, 48] {
                for load in [
                    "",
                    "[[loads]]\ntype = \"line\"\nfrom_x = 0.0\nto_x = 0.6\nintensity = 2000.0\n",
                ] {
                    let text = format!(
                        "[arch]\nshape = \"{shape}\"\nradius = 1.0\n{extra}thickness = {t}\nvoussoirs = {n}\n[material]\nfriction = {mu}\n{load}"
                    );
                    let m = model_of(&scene(&text));
                    for d in [Direction::Right, Direction::Left] {
                        let (chain, full) = by_both_paths(&m, d);
                        assert_eq!(chain.converged, full.converged, "{text} {d:?}");
                        for (c, f) in chain.starts.iter().zip(&full.starts) {
                            assert_eq!(
                                (c.start, c.converged(), c.iterations),
                                (f.start, f.converged(), f.iterations),
                                "{text} {d:?}"
                            );
                        }
                        cases += 1;
                        let (lc, lf) = match (chain.lambda, full.lambda) {
                            (Some(lc), Some(lf)) => (lc, lf),
                            (None, None) => continue,
                            (c, f) => panic!("{text} {d:?}: chain {c:?}, full {f:?}"),
                        };
                        let diff = (lc - lf).abs() / lf.abs().max(1.0);
                        assert!(diff <= 1e-9, "{text} {d:?}: chain {lc}, full {lf}");
                        assert!(!chain.sliding.is_empty(), "{text} {d:?}: nothing slides");
                        worst = worst.max(diff);
                        compared += 1;
                    }
                }
            }
        }
    }
    println!("{cases} cases, {compared} with a multiplier; largest difference {worst:.1e}");
    assert!(compared >= cases / 2, "{compared} of {cases}");
}

/// An exact answer is not called a lower bound where real joints can collapse lower: the
/// running-bond wall with mu = 1000 rocks as one body at 1.0 with no joint slipping
/// (`friction_exact`), and its head joints, which carry no compression, let real joints
/// collapse at 0.536 (docs/friction.md), which `auto` now iterates for and governs with. A
/// chain (the bundled semicircle with mu = 0.6, rocking) keeps the name and is not iterated.
#[test]
fn an_exact_wall_answer_is_not_called_a_lower_bound() {
    let text = format!(
        "[blocks]\npolygons = {}\n[material]\nfriction = 1000\n",
        crate::common::rect_polygons(&running_bond_wall_rects())
    );
    let v = json_of(&["analyze", "--json"], &text);
    assert_eq!(v["friction_exact"], true);
    assert_eq!(v["friction_lower_states_possible"], true);
    // Said in words for scripts and the page (which shows the server's words).
    let note = v["friction_lower_states_note"].as_str().unwrap_or("");
    assert!(note.contains("not proved the lowest"), "{note}");
    assert!((f64_of(&v, "lambda_lower") - 1.0).abs() < 1e-9);
    assert_eq!(v["non_associative_converged"], true);
    assert!(v["non_associative_iterations"].as_u64().unwrap_or(0) > 0);
    let na = f64_of(&v, "lambda_non_associative");
    assert!(na < 0.6, "a real collapse well below the exact 1.0: {na}");
    assert_eq!(f64_of(&v, "lambda_governing"), na);
    let (dir, path) = scene_file(&text);
    let out = voussoir().arg("analyze").arg(&path).output().expect("runs");
    let summary = String::from_utf8_lossy(&out.stdout);
    // The drawing's title gives the governing value on a line of its own above the static one.
    let svg_path = dir.path().join("wall.svg");
    let svg_run = voussoir()
        .arg("analyze")
        .arg(&path)
        .arg("--svg")
        .arg(&svg_path)
        .output()
        .expect("runs");
    assert!(svg_run.status.success());
    let svg = std::fs::read_to_string(&svg_path).expect("svg written");
    assert!(
        svg.contains(&format!(
            "\nλ (non-associative, real joints) = {na:.4}\nλ (associative friction, exact, not proved the lowest) = 1.0000"
        )),
        "{svg}"
    );
    assert!(
        summary.contains("Static (associative friction): collapse multiplier lambda = 1.000000")
            && summary.contains("not proved the lowest"),
        "{summary}"
    );
    let arch = std::fs::read_to_string(
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("data/semicircular.toml"),
    )
    .expect("bundled scene");
    let v = json_of(
        &["analyze", "--json", "--set", "material.friction=0.6"],
        &arch,
    );
    assert_eq!(v["friction_exact"], true, "{v}");
    assert!(v["slipping_joints"]
        .as_array()
        .is_some_and(|s| s.is_empty()));
    assert_eq!(v["friction_lower_states_possible"], false);
    assert!(v["friction_lower_states_note"].is_null(), "{v}");
    assert_eq!(v["non_associative_iterations"], 0);
    assert_eq!(
        f64_of(&v, "lambda_non_associative"),
        f64_of(&v, "lambda_lower")
    );
}

/// Above `analysis::AUTO_SEARCH_MAX_BLOCKS` blocks `auto` keeps an exact wall's value without
/// searching for lower collapse states (each program of the search is the whole wall's: 200 s
/// at 984 blocks), and says so in `non_associative_note` and the summary.
#[test]
fn a_large_exact_wall_is_not_searched_by_default_and_says_so() {
    // A running-bond wall of 21 courses of 20 units (0.4 x 0.2 m, half units at the ends of
    // every other course): 430 blocks.
    let mut rects = Vec::new();
    for c in 0..21 {
        let (y0, y1) = (0.2 * c as f64, 0.2 * (c + 1) as f64);
        let mut xs: Vec<f64> = (0..=20).map(|i| 0.4 * i as f64).collect();
        if c % 2 == 1 {
            xs = std::iter::once(0.0)
                .chain((0..20).map(|i| 0.2 + 0.4 * i as f64))
                .chain(std::iter::once(8.0))
                .collect();
        }
        for w in xs.windows(2) {
            rects.push([w[0], y0, w[1], y1]);
        }
    }
    assert!(rects.len() > voussoir::analysis::AUTO_SEARCH_MAX_BLOCKS);
    let text = format!(
        "[blocks]\npolygons = {}\n[material]\nfriction = 1000\n",
        crate::common::rect_polygons(&rects)
    );
    let v = json_of(&["analyze", "--json"], &text);
    assert_eq!(v["friction_exact"], true);
    assert_eq!(v["friction_lower_states_possible"], true);
    assert_eq!(v["non_associative_iterations"], 0);
    assert_eq!(
        f64_of(&v, "lambda_non_associative"),
        f64_of(&v, "lambda_lower")
    );
    let note = v["non_associative_note"].as_str().unwrap_or("");
    assert!(
        note.contains("were not searched for above 400 blocks")
            && note.contains("--friction non-associative"),
        "{note}"
    );
}

/// The running-bond wall of `courses` courses of `per` units (0.4 x 0.2 m, half units at the
/// ends of every other course), friction `mu`: the bench's wall (`benches/common`).
fn bench_wall(courses: usize, per: usize, mu: f64) -> Scene {
    let (b, h) = (0.4, 0.2);
    let mut rects = Vec::new();
    for c in 0..courses {
        let y0 = c as f64 * h;
        let mut xs: Vec<f64> = (0..=per).map(|k| k as f64 * b).collect();
        if c % 2 == 1 {
            xs = std::iter::once(0.0)
                .chain((0..per).map(|k| (k as f64 + 0.5) * b))
                .chain(std::iter::once(per as f64 * b))
                .collect();
        }
        for w in xs.windows(2) {
            rects.push([w[0], y0, w[1], y0 + h]);
        }
    }
    scene(&format!(
        "[blocks]\npolygons = {}\n[material]\nfriction = {mu}\n",
        rect_polygons(&rects)
    ))
}

/// What makes `r` (multiplier `lambda`) a complete solution of the non-associative problem of
/// `model`, checked from outside the library: its forces are in equilibrium (the library's
/// own residual) and obey Coulomb's law; its mechanism (the block velocities) does not
/// interpenetrate at any joint, and no dilatancy is asked of it where it slides; where a joint
/// opens at an end that end carries no force, where it slips the shear is `mu N` against the
/// slip; and its virtual work, recomputed from the load case, balances the friction it
/// dissipates, `lambda A = G + sum mu N |slip|`. Returns the joints that slip.
fn check_complete_solution(model: &Model, r: &statics::StaticResult, lambda: f64) -> usize {
    assert_eq!(r.lambda, Some(lambda));
    let fs = model.loads.force_scale();
    assert!(
        r.equilibrium_residual <= 1e-6 * fs,
        "{}",
        r.equilibrium_residual
    );
    let forces = r.forces.as_ref().expect("forces");
    let nmax = forces.iter().fold(0.0_f64, |m, f| m.max(f.n));
    for (jt, f) in model.assembly.joints.iter().zip(forces) {
        if jt.friction.is_finite() {
            assert!(f.v.abs() <= jt.friction * f.n + 1e-7 * nmax, "Coulomb");
        }
    }
    // The mechanism: centroid velocities and rotation rates.
    let v = |b: Option<usize>, q: Vec2| -> Vec2 {
        b.map_or(Vec2::zeros(), |i| {
            let [vx, vy, w] = r.mechanism[i];
            let c = model.assembly.blocks[i].centroid;
            Vec2::new(vx - w * (q.y - c.y), vy + w * (q.x - c.x))
        })
    };
    let rates: Vec<[f64; 3]> = model
        .assembly
        .joints
        .iter()
        .map(|jt| {
            let dv = |q: Vec2| v(jt.to, q) - v(jt.from, q);
            [
                dv(jt.p1).dot(&jt.normal()),
                dv(jt.p2).dot(&jt.normal()),
                dv(jt.midpoint()).dot(&jt.tangent()),
            ]
        })
        .collect();
    let largest = rates.iter().flatten().fold(0.0_f64, |m, x| m.max(x.abs()));
    assert!(largest > 0.0);
    let (tol_v, tol_f) = (1e-6 * largest, 1e-6 * nmax);
    let mut dissipation = 0.0;
    let mut slipping = 0;
    for ((jt, f), [dn1, dn2, dt]) in model.assembly.joints.iter().zip(forces).zip(&rates) {
        assert!(*dn1 >= -tol_v && *dn2 >= -tol_v, "interpenetration");
        // The ends' forces: N = c1 + c2, M = (c2 - c1) L / 2.
        let d = f.m / jt.length();
        let (c1, c2) = (0.5 * f.n - d, 0.5 * f.n + d);
        if *dn1 > tol_v {
            assert!(c1.abs() <= tol_f, "an opening end carries {c1}");
        }
        if *dn2 > tol_v {
            assert!(c2.abs() <= tol_f, "an opening end carries {c2}");
        }
        if dt.abs() > tol_v {
            assert!(
                jt.friction.is_finite(),
                "a joint of infinite friction slips"
            );
            slipping += 1;
            assert!(
                (f.v.abs() - jt.friction * f.n).abs() <= tol_f,
                "a slipping joint below its capacity: |V| {} against mu N {}",
                f.v.abs(),
                jt.friction * f.n
            );
            // The force `from` puts on `to` opposes `to`'s slip relative to `from`.
            assert!(f.v * dt <= tol_f * tol_v, "friction drives the slip");
        }
        dissipation -= f.v * dt;
    }
    // Virtual work: the action's power A and the permanent loads' G (minus their power),
    // reduced to each block's reference point.
    let (mut act, mut g) = (0.0, 0.0);
    for (i, vel) in r.mechanism.iter().enumerate() {
        let u = v(Some(i), model.loads.reference(i));
        let p = model.loads.permanent(i);
        let sv = model.loads.variable(i, 1.0);
        g -= p.force.dot(&u) + p.moment * vel[2];
        act += sv.force.dot(&u) + sv.moment * vel[2];
    }
    assert!(act > 0.0);
    let by_work = (g + dissipation) / act;
    assert!(
        (by_work - lambda).abs() <= 1e-6 * lambda,
        "virtual work {by_work} against {lambda}"
    );
    slipping
}

/// The mechanism's fixed point (`NonAssociativeSettings::mechanism_step`, docs/friction.md)
/// on the 205-block running-bond wall with mu = 0.6 and the 3-bay arcade of
/// `data/arcade.toml` with mu = 0.4: the answer it retains is a complete solution of the
/// non-associative problem ([`check_complete_solution`]), at most the associative value, and
/// it takes fewer programs than the relaxation alone (when measured: 21 against 142 on the
/// wall, 52 against 376 on the arcade).
#[test]
fn the_mechanisms_fixed_point_is_a_complete_non_associative_solution() {
    let arcade = std::fs::read_to_string(data("arcade.toml"))
        .expect("data/arcade.toml")
        .replace("friction = inf", "friction = 0.4");
    for (name, scene) in [
        ("205-block wall", bench_wall(10, 20, 0.6)),
        ("3-bay arcade", crate::common::scene(&arcade)),
    ] {
        let model = model_of(&scene);
        let s = StaticSettings::default();
        let a = statics::analyse(&model, &s).expect("static program");
        let associative = a.lambda.expect("collapse");
        let step =
            statics::analyse_non_associative(&model, &s, &a, &NonAssociativeSettings::default())
                .expect("iteration");
        let plain = NonAssociativeSettings {
            mechanism_step: false,
            ..NonAssociativeSettings::default()
        };
        let relaxed = statics::analyse_non_associative(&model, &s, &a, &plain).expect("iteration");
        assert!(step.converged && relaxed.converged, "{name}");
        let lambda = step.lambda.expect("converged");
        let relaxed_lambda = relaxed.lambda.expect("converged");
        println!(
            "{name}: associative {associative:.6}; mechanism step {lambda:.6} in {} programs; relaxation {relaxed_lambda:.6} in {}",
            step.iterations, relaxed.iterations
        );
        assert!(
            lambda <= associative && relaxed_lambda <= associative,
            "{name}"
        );
        assert!(step.iterations < relaxed.iterations, "{name}");
        // The relaxation alone never settles by a step.
        assert!(relaxed
            .starts
            .iter()
            .all(|st| st.settled_by != Some(SettledBy::MechanismStep)));
        let r = step.result.as_ref().expect("retained solution");
        assert!(
            r.solver_status.contains("fixed point of the mechanism"),
            "{name}: a proposal is what was retained here: {}",
            r.solver_status
        );
        assert!(
            step.starts
                .iter()
                .any(|st| st.settled_by == Some(SettledBy::MechanismStep)
                    && st.lambda == Some(lambda))
        );
        assert!(
            check_complete_solution(&model, r, lambda) > 0,
            "{name}: nothing slides"
        );
    }
}
