//! DEM check of the collapse multiplier with the explicit stepping: hand-derived single-block
//! values, agreement with the static lower bound on arches and a portal, the sliding case
//! against the associative bound, energy conservation of the integrator, the `[dem]` table's
//! validation and snapshots.

use voussoir::assembly::{Assembly, JointEnd};
use voussoir::dem::{self, DemResult, IntegrationParameters, Outcome};
use voussoir::geometry::Vec2;
use voussoir::model::Model;
use voussoir::scene::Scene;
use voussoir::statics::{self, Status};

/// A rectangular block b x h standing on the ground (one support joint along its base).
fn block(b: f64, h: f64, mu: f64) -> Assembly {
    crate::common::rect_block(b, h, mu)
}

fn scene(text: &str) -> Scene {
    Scene::from_toml_str(text, "test").expect("valid scene")
}

fn arch(n: usize, t: f64, mu: f64) -> Scene {
    scene(&format!(
        "[arch]\nshape = \"circular\"\nradius = 1.0\nthickness = {t}\nvoussoirs = {n}\n\
         [material]\nfriction = {}\n",
        if mu.is_finite() {
            mu.to_string()
        } else {
            "\"inf\"".to_string()
        }
    ))
}

/// The scene's DEM parameters with the explicit stepping: this file validates it (the
/// default `auto` takes the rigid stepping for a chain's collapse search, validated in
/// `tests/it/dem_moreau.rs`).
fn explicit_parameters(
    s: &Scene,
    m: &Model,
) -> Result<IntegrationParameters, voussoir::error::SceneError> {
    voussoir::analysis::dem_parameters(s, m).map(|p| p.integrator(dem::Integrator::Explicit))
}

fn build(s: &Scene) -> Model {
    voussoir::scene::build(s).expect("model")
}

fn run(model: &Model, params: &IntegrationParameters, tol: f64) -> DemResult {
    dem::collapse_multiplier(model, params, tol, &mut |_| {}).expect("DEM runs")
}

/// The bracket is made of DEM runs: one that stood at `lambda_stands` (or the settling run)
/// and one that did not at `lambda_collapses`, with nothing undecided.
fn check_bracket(r: &DemResult, tol: f64) -> (f64, f64, f64) {
    assert!(!r.cannot_stand && !r.no_collapse);
    assert_eq!(r.undecided_runs, 0);
    let (lo, hi, mid) = (
        r.lambda_stands.expect("stands"),
        r.lambda_collapses.expect("collapses"),
        r.lambda_dem.expect("midpoint"),
    );
    assert!(lo < hi && (hi - lo) <= tol * mid * (1.0 + 1e-12));
    assert_eq!(
        r.standing_run().expect("standing run").outcome,
        Outcome::Stands
    );
    assert_ne!(
        r.collapsing_run().expect("collapsing run").outcome,
        Outcome::Stands
    );
    (lo, hi, mid)
}

#[test]
fn single_block_rocks_at_b_over_h() {
    let (b, h) = (0.5, 1.0);
    let a = block(b, h, f64::INFINITY);
    // Start the search away from the answer so the bracket is found by the DEM alone.
    let p = IntegrationParameters::for_assembly(&a).initial_guess(Some(0.3));
    let r = run(&Model::self_weight(a), &p, 0.01);
    let (_, _, mid) = check_bracket(&r, 0.01);
    let exact = b / h;
    println!(
        "rocking: lambda_dem {mid:.5} vs b/h {exact} ({:+.3}%)",
        100.0 * (mid / exact - 1.0)
    );
    assert!((mid / exact - 1.0).abs() < 0.02);
    assert!(r.friction_infinite && r.friction >= 100.0);
    // It turns about the downstream corner (p2 = (b/2, 0)) and does not slide.
    assert_eq!(r.hinges.len(), 1);
    assert_eq!(r.hinges[0].end, JointEnd::P2);
    assert!(r.sliding.is_empty());
}

#[test]
fn single_block_slides_at_mu() {
    let (b, h, mu) = (1.0, 0.5, 0.4);
    let a = block(b, h, mu);
    let p = IntegrationParameters::for_assembly(&a).initial_guess(Some(0.6));
    let r = run(&Model::self_weight(a), &p, 0.01);
    let (_, _, mid) = check_bracket(&r, 0.01);
    println!(
        "sliding: lambda_dem {mid:.5} vs mu {mu} ({:+.3}%)",
        100.0 * (mid / mu - 1.0)
    );
    assert!((mid / mu - 1.0).abs() < 0.02);
    assert_eq!(r.sliding, vec![0]);
    assert!(r.hinges.is_empty());
}

/// DEM against the static lower bound: within 2% (the issue asks 5%, aims at 2%), with a
/// bracket of relative width `tol`, narrower than the 2% the comparison claims. The search
/// starts from the static value, so a first bracket that verifies puts its midpoint on it:
/// `tol` well below 1% makes the DEM find its own threshold inside.
fn compare_with_static(name: &str, s: &Scene, tol: f64) -> (f64, f64) {
    let m = build(s);
    let st = statics::analyse(&m, &statics::StaticSettings::default()).expect("static");
    assert_eq!(st.status, Status::Collapse);
    let lower = st.lambda.expect("lambda");
    let p = explicit_parameters(s, &m).expect("params");
    let r = run(&m, &p, tol);
    let (lo, hi, mid) = check_bracket(&r, tol);
    let diff = mid / lower - 1.0;
    println!(
        "{name}: lambda_lower {lower:.5}  DEM [{lo:.5}, {hi:.5}] mid {mid:.5}  diff {:+.2}%  \
         width {:.2}%  runs {}  steps {}  {:.2} s  hinges {:?}",
        100.0 * diff,
        100.0 * (hi - lo) / mid,
        r.runs.len(),
        r.steps,
        r.wall_time_s,
        r.hinges
            .iter()
            .map(|h| (h.joint, h.end))
            .collect::<Vec<_>>()
    );
    assert!(diff.abs() < 0.02, "{name}: DEM {mid} vs static {lower}");
    assert!((hi - lo) / mid < 0.02);
    // The DEM sees hinges at the joints the static solution puts them at.
    for h in &st.hinges {
        assert!(
            r.hinges
                .iter()
                .any(|d| d.end == h.end && d.joint.abs_diff(h.joint) <= 1),
            "{name}: static hinge {:?} not seen by the DEM ({:?})",
            (h.joint, h.end),
            r.hinges
        );
    }
    (lower, mid)
}

#[test]
fn semicircular_arches_agree_with_the_static_bound() {
    for (n, t) in [(16, 0.15), (16, 0.25), (32, 0.15), (32, 0.25)] {
        compare_with_static(
            &format!("semicircle n={n} t/R={t}"),
            &arch(n, t, 0.8),
            0.002,
        );
    }
}

#[test]
fn portal_agrees_with_the_static_bound() {
    let s = scene(
        "[arch]\nshape = \"circular\"\nradius = 1.0\nthickness = 0.15\nvoussoirs = 16\n\
         [piers]\nheight = 1.0\nwidth = 0.4\ncourses = 2\n[material]\nfriction = 0.8\n",
    );
    compare_with_static("portal", &s, 0.002);
}

#[test]
fn other_shapes_agree_with_the_static_bound_with_default_settings() {
    let cases = [
        (
            "pointed",
            "[arch]\nshape = \"pointed\"\nradius = 1.0\neccentricity = 0.2\nthickness = 0.15\n\
             voussoirs = 16\n[material]\nfriction = 0.8\n",
        ),
        (
            "basket",
            "[arch]\nshape = \"basket\"\nspan = 2.0\nrise = 0.7\nthickness = 0.2\nvoussoirs = 17\n\
             [material]\nfriction = 0.8\n",
        ),
        (
            "segmental",
            "[arch]\nshape = \"circular\"\nradius = 1.0\nembrace_deg = 120\nthickness = 0.15\n\
             voussoirs = 16\n",
        ),
    ];
    for (name, text) in cases {
        compare_with_static(name, &scene(text), 0.01);
    }
}

/// Where sliding governs: a semicircle t/R = 0.25 with mu = 0.35 slides at three joints in
/// the static solution. The static program uses associative friction (normality), the DEM
/// Coulomb's non-associative law (slip without dilatancy), whose collapse multiplier can only
/// be lower (Radenkovic's theorem): the DEM must not stand above the bound, and the test
/// prints and bounds the difference it finds.
#[test]
fn sliding_case_against_the_associative_bound() {
    for (t, mu) in [(0.25, 0.35), (0.15, 0.4)] {
        let s = arch(16, t, mu);
        let m = build(&s);
        let st = statics::analyse(&m, &statics::StaticSettings::default()).expect("static");
        let assoc = st.lambda.expect("collapse");
        assert!(!st.sliding.is_empty());
        let p = explicit_parameters(&s, &m).expect("params");
        let tol = 0.005;
        let r = run(&m, &p, tol);
        let (lo, hi, mid) = check_bracket(&r, tol);
        let diff = mid / assoc - 1.0;
        println!(
            "t/R={t} mu={mu}: associative static {assoc:.5} (sliding {:?})  DEM [{lo:.5}, \
             {hi:.5}] (sliding {:?}, hinges {:?})  difference {:+.2}%",
            st.sliding,
            r.sliding,
            r.hinges
                .iter()
                .map(|h| (h.joint, h.end))
                .collect::<Vec<_>>(),
            100.0 * diff
        );
        assert!(
            lo <= assoc * (1.0 + 1e-9),
            "DEM stands above the associative bound"
        );
        assert!(diff.abs() < 0.02);
        assert_eq!(r.sliding, st.sliding);
    }
}

#[test]
fn an_arch_that_cannot_stand_says_so() {
    let s = arch(16, 0.25, 0.3);
    let m = build(&s);
    let st = statics::analyse(&m, &statics::StaticSettings::default()).expect("static");
    assert_eq!(st.status, Status::CannotStand);
    let p = explicit_parameters(&s, &m).expect("params");
    let r = run(&m, &p, 0.01);
    assert!(r.cannot_stand);
    assert!(r.lambda_dem.is_none());
    assert_ne!(r.runs[0].outcome, Outcome::Stands);
}

/// Largest energy error over `duration` s of an undamped settled arch nudged by a 1% rise of
/// gravity, its first and second halves, and the elastic energy of the contact springs.
fn energy_error(time_step_factor: f64, duration: f64) -> (f64, f64, f64) {
    // No friction limit: a slipping contact would dissipate.
    let s = arch(16, 0.25, f64::INFINITY);
    let m = build(&s);
    let a = &m.assembly;
    let p = explicit_parameters(&s, &m)
        .expect("params")
        .contact_damping(0.0)
        .time_step_factor(time_step_factor);
    let mut sim = dem::Simulation::new(&m, &p).expect("sim");
    // Settle with local damping only, then switch it off.
    assert_eq!(sim.settle(a).outcome, Outcome::Stands);
    sim.set_local_damping(0.0);
    sim.set_load(1.01, 0.0);
    let contacts = sim.active_contacts();
    let e0 = sim.kinetic_energy() + sim.potential_energy();
    let (mut first, mut second) = (0.0_f64, 0.0_f64);
    let samples = 200;
    for k in 0..samples {
        sim.run_for(duration / samples as f64);
        let err = (sim.kinetic_energy() + sim.potential_energy() - e0).abs();
        if k < samples / 2 {
            first = first.max(err);
        } else {
            second = second.max(err);
        }
        assert_eq!(sim.active_contacts(), contacts, "a contact opened");
        assert_eq!(sim.sliding_contacts(), 0);
    }
    (first, second, sim.elastic_energy())
}

/// With no damping at all and no contact opening or slipping, a settled arch keeps its total
/// energy (kinetic + potential of the weight + elastic in the contact springs): symplectic
/// Euler's error is a bounded oscillation, first order in the time step, with no drift.
#[test]
fn energy_is_conserved_without_damping() {
    let (first, second, elastic) = energy_error(0.9, 1.0);
    let (fine, _, _) = energy_error(0.3, 0.2);
    println!(
        "energy error: {first:.3e} J (first 0.5 s), {second:.3e} J (last 0.5 s), {fine:.3e} J \
         with a third of the time step; elastic energy {elastic:.3e} J"
    );
    // Small: symplectic Euler's energy error on an oscillation of energy E is about
    // (omega dt / 2) E, with omega dt < 2 below the stability limit; the 1% nudge sets
    // oscillations of about 2% of the spring energy (which grows as the load squared) ...
    assert!(first.max(second) < 0.02 * elastic);
    // ... no drift ...
    assert!(second < 1.5 * first);
    // ... and first order in the time step.
    assert!(fine < 0.5 * first);
}

#[test]
fn dem_table_is_validated_and_applied() {
    let base = "[arch]\nshape = \"circular\"\nradius = 1.0\nthickness = 0.15\nvoussoirs = 16\n";
    let s = scene(&format!("{base}[dem]\nlocal_damping = 0.3\nmax_time = 5\n"));
    let m = build(&s);
    let a = m.assembly.clone();
    let p = explicit_parameters(&s, &m).expect("valid");
    assert_eq!(p.local_damping, 0.3);
    assert_eq!(p.max_time, 5.0);
    for (text, key) in [
        ("colour = 3", "dem.colour"),
        ("local_damping = 1.5", "dem.local_damping"),
        ("normal_stiffness = -1", "dem.normal_stiffness"),
        ("time_step = \"fast\"", "dem.time_step"),
    ] {
        // The scene itself validates its [dem] table, so a typo is caught by every command.
        let e = voussoir::scene::Scene::from_toml_str(&format!("{base}[dem]\n{text}\n"), "test")
            .expect_err(text);
        assert_eq!(e.key(), Some(key), "{text}: {e}");
        assert!(e.to_string().contains(key));
    }
    let p = p.with_override("dem.rest_force=1e-6").expect("override");
    assert_eq!(p.rest_force, 1e-6);
    assert!(p.with_override("dem.rest_force=2").is_err());
    // Defaults follow the geometry: a scene twice as large gets the same dimensionless
    // settings (stiffness x weight / length, times x sqrt(length)).
    let big =
        scene("[arch]\nshape = \"circular\"\nradius = 2.0\nthickness = 0.3\nvoussoirs = 16\n");
    let mb = build(&big);
    let ab = mb.assembly.clone();
    let pb = explicit_parameters(&big, &mb).expect("valid");
    let p0 = IntegrationParameters::for_assembly(&a);
    let w = ab.total_weight() / a.total_weight();
    assert!((pb.normal_stiffness / p0.normal_stiffness - w / 2.0).abs() < 1e-9 * w);
    assert!((pb.ramp_time / p0.ramp_time - 2f64.sqrt()).abs() < 1e-12);
    assert!((pb.collapse_displacement / p0.collapse_displacement - 2.0).abs() < 1e-12);
}

#[test]
fn snapshots_are_written_as_csv() {
    let s = arch(16, 0.25, 0.8);
    let m = build(&s);
    let a = &m.assembly;
    let p = explicit_parameters(&s, &m)
        .expect("params")
        .snapshot_interval(Some(0.05));
    let r = run(&m, &p, 0.02);
    let dir = tempfile::tempdir().expect("tempdir");
    let files = dem::write_snapshots(dir.path(), &r).expect("written");
    let names: Vec<_> = files
        .iter()
        .map(|f| {
            f.file_name()
                .unwrap_or_default()
                .to_string_lossy()
                .to_string()
        })
        .collect();
    assert_eq!(names, ["settle.csv", "stands.csv", "collapses.csv"]);
    let text = std::fs::read_to_string(&files[2]).expect("read");
    let mut lines = text.lines();
    assert_eq!(lines.next(), Some("time_s,lambda,block,vertex,x,y"));
    let rows: Vec<Vec<f64>> = lines
        .map(|l| l.split(',').map(|x| x.parse().expect("number")).collect())
        .collect();
    let snaps = r.collapsing_run().expect("run").snapshots.len();
    assert!(snaps >= 2);
    assert_eq!(rows.len(), snaps * a.blocks.len() * 4);
    // The first snapshot is the settled arch: every vertex within the collapse displacement
    // of where the assembly puts it.
    for row in rows.iter().take(a.blocks.len() * 4) {
        let v = a.blocks[row[2] as usize]
            .polygon
            .iter()
            .any(|q| (q - Vec2::new(row[4], row[5])).norm() < p.collapse_displacement);
        assert!(v);
    }
}

#[test]
fn a_time_step_above_the_stability_limit_is_refused() {
    let s = scene("[arch]\nshape = \"circular\"\nradius = 1.0\nthickness = 0.15\nvoussoirs = 16\n[dem]\ntime_step = 1e-3\nintegrator = \"explicit\"\n");
    let m = build(&s);
    let p = explicit_parameters(&s, &m).expect("valid table");
    let e =
        voussoir::dem::collapse_multiplier(&m, &p, 0.01, &mut |_| {}).expect_err("unstable step");
    assert!(e.to_string().contains("stability limit"), "{e}");
    assert!(voussoir::dem::Simulation::new(&m, &p).is_err());
}

/// The DEM honours the loads of the model: with loads that move the static multiplier well
/// away from its self-weight value, the DEM bracket (relative width `tol`, 0.2% as for the
/// semicircles: a bracket that narrow shows the DEM's own threshold) still contains the
/// static `lambda_lower` of the loaded model, not the unloaded one, and its collapse
/// mechanism has the static hinges. Returns (static, bracket).
fn loaded_bracket_contains_static(
    name: &str,
    loaded: &Scene,
    unloaded: &Scene,
    tol: f64,
) -> (f64, f64, f64) {
    let m = build(loaded);
    assert!(!m.loads.is_self_weight_only(), "{name}: no loads");
    let st = statics::analyse(&m, &statics::StaticSettings::default()).expect("static");
    assert_eq!(st.status, Status::Collapse, "{name}");
    let lower = st.lambda.expect("lambda");
    let bare = build(unloaded);
    let bare_lower = statics::analyse(&bare, &statics::StaticSettings::default())
        .expect("static")
        .lambda
        .expect("lambda");
    let p = explicit_parameters(loaded, &m).expect("params");
    let r = run(&m, &p, tol);
    let (lo, hi, mid) = check_bracket(&r, tol);
    println!(
        "{name}: lambda_lower {lower:.5} (without the loads {bare_lower:.5})  DEM [{lo:.5}, \
         {hi:.5}] mid {mid:.5} ({:+.2}%)  runs {}  steps {}  {:.2} s  hinges {:?}",
        100.0 * (mid / lower - 1.0),
        r.runs.len(),
        r.steps,
        r.wall_time_s,
        r.hinges
            .iter()
            .map(|h| (h.joint, h.end))
            .collect::<Vec<_>>()
    );
    assert!(
        lo <= lower && lower <= hi,
        "{name}: static {lower} outside the DEM bracket [{lo}, {hi}]"
    );
    // The loads matter: the self-weight value lies outside the bracket.
    assert!(
        !(lo..=hi).contains(&bare_lower),
        "{name}: the bracket [{lo}, {hi}] also holds the unloaded {bare_lower}"
    );
    // The DEM sees hinges at the joints the static solution puts them at.
    for h in &st.hinges {
        assert!(
            r.hinges
                .iter()
                .any(|d| d.end == h.end && d.joint.abs_diff(h.joint) <= 1),
            "{name}: static hinge {:?} not seen by the DEM ({:?})",
            (h.joint, h.end),
            r.hinges
        );
    }
    (lower, lo, hi)
}

const PORTAL: &str = "[arch]\nshape = \"circular\"\nradius = 1.0\nthickness = 0.2\nvoussoirs = 10\n\
                      [piers]\nheight = 1.0\nwidth = 0.4\ncourses = 2\n[material]\nfriction = 0.8\n";

/// A portal with a point load of 3 kN on the voussoir right of the crown (on the
/// centreline, at 81 deg), a seismic mass: the static value lies inside the DEM bracket.
#[test]
fn loaded_portal_bracket_contains_the_static_value() {
    let at = 81f64.to_radians();
    let loaded = scene(&format!(
        "{PORTAL}[[loads]]\ntype = \"point\"\nat = [{}, {}]\nforce = [0.0, -3000.0]\n",
        at.cos(),
        at.sin()
    ));
    loaded_bracket_contains_static("portal + point load", &loaded, &scene(PORTAL), 0.002);
}

/// A semicircular arch under a fill up to 0.1 m above its crown extrados (18 kN/m^3, a
/// seismic mass): the static value lies inside the DEM bracket.
#[test]
fn filled_arch_bracket_contains_the_static_value() {
    let bare = "[arch]\nshape = \"circular\"\nradius = 1.0\nthickness = 0.2\nvoussoirs = 12\n\
                [material]\nfriction = 0.8\n";
    let loaded = scene(&format!(
        "{bare}[fill]\nlevel = 1.2\nunit_weight = 18000.0\n"
    ));
    loaded_bracket_contains_static("filled arch", &loaded, &scene(bare), 0.002);
}

/// A vertical seismic component (r = 0.3, upward with the horizontal one) on a small arch:
/// the static value lies inside the DEM bracket.
#[test]
fn vertical_seismic_component_bracket_contains_the_static_value() {
    let bare = "[arch]\nshape = \"circular\"\nradius = 1.0\nthickness = 0.25\nvoussoirs = 12\n\
                [material]\nfriction = 0.8\n";
    let loaded = scene(&format!("{bare}[seismic]\nvertical_ratio = 0.3\n"));
    loaded_bracket_contains_static("vertical ratio 0.3", &loaded, &scene(bare), 0.002);
}

/// A single block b x h with a point load P at (x, y) (block frame: base centre at the
/// origin) rocks about its downstream corner when the seismic moment about it overcomes the
/// restoring one: lambda = (W b/2 + P (b/2 - x)) / (W h/2 + S y), with S = P when the load
/// is a seismic mass and 0 when it is not. The load rides on the block (its point turns with
/// it) and its seismic mass adds to the block's.
#[test]
fn single_block_with_a_point_load_rocks_at_the_hand_value() {
    use voussoir::model::{AppliedLoad, LoadSource};
    let (b, h) = (0.5, 1.0);
    let (x, y, load) = (-0.15, 0.9, 5000.0);
    for seismic in [true, false] {
        let a = block(b, h, f64::INFINITY);
        let w = a.blocks[0].weight;
        let mut m = Model::self_weight(a);
        m.loads.add(AppliedLoad {
            block: 0,
            point: Vec2::new(x, y),
            force: Vec2::new(0.0, -load),
            seismic_weight: if seismic { load } else { 0.0 },
            live: false,
            source: LoadSource::Load(0),
            region: None,
        });
        let s = if seismic { load } else { 0.0 };
        let exact = (w * 0.5 * b + load * (0.5 * b - x)) / (w * 0.5 * h + s * y);
        let st = statics::analyse(&m, &statics::StaticSettings::default()).expect("static");
        let lower = st.lambda.expect("lambda");
        assert!(
            (lower / exact - 1.0).abs() < 1e-6,
            "static {lower} vs {exact}"
        );
        let p = IntegrationParameters::for_assembly(&m.assembly).initial_guess(Some(0.3));
        let r = run(&m, &p, 0.01);
        let (lo, hi, mid) = check_bracket(&r, 0.01);
        println!(
            "block + point load (seismic {seismic}): DEM [{lo:.5}, {hi:.5}] mid {mid:.5} vs \
             hand {exact:.5} ({:+.3}%)",
            100.0 * (mid / exact - 1.0)
        );
        assert!((mid / exact - 1.0).abs() < 0.01);
        assert_eq!(r.hinges.len(), 1);
        assert_eq!(r.hinges[0].end, JointEnd::P2);
    }
}

/// The courses of a wall stand side by side on one ground: each corner of the bottom course
/// touches it once. Before the supports on one line shared their ground, every support had
/// its own rectangle, three joint lengths wide, and neighbouring rectangles overlapped: each
/// base corner of the wall touched two grounds at one point, twice the contact stiffness
/// (explicit stepping) and one rigid constraint twice (Moreau-Jean). The weight still reaches
/// the ground whole, equally in both integrators.
#[test]
fn a_wall_stands_on_one_ground_touched_once_at_each_corner() {
    let s = crate::common::scene(&format!(
        "[blocks]\nground_y = 0.0\npolygons = {}\n",
        crate::common::rect_polygons(&crate::common::running_bond_wall_rects())
    ));
    let m = build(&s);
    let weight: f64 = m.assembly.blocks.iter().map(|b| b.weight).sum();
    for integrator in ["explicit", "moreau"] {
        let s = s
            .with_overrides(&[format!("dem.integrator={integrator}")])
            .expect("integrator");
        let p = voussoir::analysis::dem_parameters(&s, &m).expect("params");
        let mut sim = dem::Simulation::new(&m, &p).expect("sim");
        assert_eq!(sim.settle(&m.assembly).outcome, Outcome::Stands);
        let ground: Vec<_> = sim
            .contacts()
            .into_iter()
            .filter(|c| c.vertex_block.is_none() || c.edge_block.is_none())
            .collect();
        // The bottom course: blocks [0, 0.6] and [0.6, 1.2]; their base corners at x = 0,
        // 0.6 (twice: one corner of each block) and 1.2, each seen once from its block.
        let mut xs: Vec<f64> = ground.iter().map(|c| c.point.x).collect();
        xs.sort_by(f64::total_cmp);
        assert_eq!(xs.len(), 4, "{integrator}: ground contacts at {xs:?}");
        for (x, want) in xs.iter().zip([0.0, 0.6, 0.6, 1.2]) {
            assert!((x - want).abs() < 1e-6, "{integrator}: {xs:?}");
        }
        assert!(ground.iter().all(|c| c.vertex_block.is_some()));
        let carried: f64 = ground.iter().map(|c| c.normal_force).sum();
        assert!(
            (carried / weight - 1.0).abs() < 1e-3,
            "{integrator}: the ground carries {carried} N of {weight} N"
        );
    }
}
