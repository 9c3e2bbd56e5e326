//! The reduced static program of a chain (four unknowns: lambda and the three redundants at
//! the first support) gives what the full program (three unknowns per joint) gives: the same
//! status, multiplier, joint forces, hinges and mechanism, on every shape, portals, loads,
//! both directions and finite friction.

use voussoir::model::Model;
use voussoir::scene::Scene;
use voussoir::statics::{self, Direction, StaticResult, StaticSettings, Status};

fn bundled(name: &str) -> Scene {
    Scene::from_file(
        &std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("data")
            .join(name),
    )
    .expect("bundled scene")
}

fn both(m: &Model, d: Direction) -> (StaticResult, StaticResult) {
    let s = StaticSettings::default().direction(d);
    let full = statics::analyse_full(m, &s).expect("full program solves");
    let reduced = statics::analyse_chain(m, &s).expect("reduced program solves");
    // The chain program by the interior point alone (its fallback) gives the same answer.
    let ip =
        statics::analyse_chain(m, &s.clone().active_set(false)).expect("interior point solves");
    assert_eq!(ip.status, reduced.status);
    if let (Some(a), Some(b)) = (ip.lambda, reduced.lambda) {
        assert!(
            (a - b).abs() <= 1e-9 * a.abs().max(1e-3),
            "interior point {a}, active set {b}"
        );
    }
    (full, reduced)
}

static VERTICES: std::sync::atomic::AtomicUsize = std::sync::atomic::AtomicUsize::new(0);
/// Collapse cases the active-set method solved (the rest went to the interior point).
static ACTIVE_SET: std::sync::atomic::AtomicUsize = std::sync::atomic::AtomicUsize::new(0);

fn compare(label: &str, m: &Model, d: Direction) -> Option<f64> {
    let (f, r) = both(m, d);
    assert_eq!(f.status, r.status, "{label} {d:?}: statuses");
    let (Some(lf), Some(lr)) = (f.lambda, r.lambda) else {
        assert_eq!(f.lambda, r.lambda, "{label}");
        return None;
    };
    if r.solver_status.starts_with("active set") {
        ACTIVE_SET.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
    }
    let rel = (lf - lr).abs() / lf.abs().max(1e-300);
    assert!(
        rel < 1e-9,
        "{label} {d:?}: full {lf}, reduced {lr} ({rel:.2e})"
    );
    // The residual of the reduced solution, recomputed from the joint forces.
    let scale = m.loads.force_scale();
    assert!(
        r.equilibrium_residual < 1e-8 * scale,
        "{label}: residual {}",
        r.equilibrium_residual
    );
    let finite = m.assembly.joints.iter().any(|j| j.friction.is_finite());
    if !finite {
        // A non-degenerate collapse state is unique: the same hinges and mechanism.
        assert_eq!(f.hinges, r.hinges, "{label} {d:?}: hinges");
        for (a, b) in f.mechanism.iter().zip(&r.mechanism) {
            for c in 0..3 {
                assert!(
                    (a[c] - b[c]).abs() < 1e-5,
                    "{label} {d:?}: mechanism {a:?} vs {b:?}"
                );
            }
        }
        // The exact vertex step lands on the kinematic multiplier of the same mechanism to
        // round-off, where the interior-point optimum stops near 1e-10.
        if r.solver_status.contains("exact vertex") && m.assembly.joints.len() <= 200 {
            let k = voussoir::kinematic::analyse(
                m,
                &voussoir::kinematic::KinematicSettings::default().direction(d),
            )
            .expect("kinematic search");
            let lk = k.lambda_upper.expect("kinematic multiplier");
            VERTICES.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
            let rel = (lr - lk).abs() / lk;
            assert!(
                rel < 1e-12,
                "{label} {d:?}: vertex {lr}, kinematic {lk} ({rel:.1e})"
            );
        }
        let ff = f.forces.as_ref().expect("forces");
        let fr = r.forces.as_ref().expect("forces");
        for (a, b) in ff.iter().zip(fr) {
            assert!(
                (a.n - b.n).abs() < 1e-6 * scale,
                "{label}: N {} vs {}",
                a.n,
                b.n
            );
        }
    }
    Some(lr)
}

#[test]
fn reduced_equals_full_on_every_shape_and_load() {
    let names = [
        "semicircular.toml",
        "segmental.toml",
        "pointed.toml",
        "basket.toml",
        "portal.toml",
        "loaded_portal.toml",
        "filled_arch.toml",
    ];
    let mut checked = 0;
    for name in names {
        let base = bundled(name);
        for set in [
            vec![],
            vec!["material.friction=0.4"],
            vec!["arch.voussoir_shape=\"curved\""],
            vec!["arch.voussoirs=64"],
        ] {
            let Ok(s) = base.with_overrides(&set) else {
                continue;
            };
            let m = voussoir::scene::build(&s).expect("builds");
            for d in [Direction::Right, Direction::Left] {
                if compare(&format!("{name} {set:?}"), &m, d).is_some() {
                    checked += 1;
                }
            }
        }
    }
    assert!(checked >= 40, "only {checked} collapse cases compared");
    let vertices = VERTICES.load(std::sync::atomic::Ordering::Relaxed);
    assert!(
        vertices >= 20,
        "only {vertices} exact vertices checked against the kinematic value"
    );
    let active = ACTIVE_SET.load(std::sync::atomic::Ordering::Relaxed);
    assert!(
        active >= 40,
        "the active-set method solved only {active} of {checked} cases"
    );
}

#[test]
fn reduced_reports_cannot_stand_and_no_collapse_like_the_full_program() {
    let base = bundled("semicircular.toml");
    // Thinner than the minimum thickness (t/R = 0.1075): cannot stand.
    let thin = base.with_override("arch.thickness=0.09").expect("valid");
    let m = voussoir::scene::build(&thin).expect("builds");
    let (f, r) = both(&m, Direction::Right);
    assert_eq!(f.status, Status::CannotStand);
    assert_eq!(r.status, Status::CannotStand);
    // A thick, flat segmental arch that cannot slide never collapses.
    let flat = bundled("segmental.toml")
        .with_overrides(&["arch.embrace_deg=60", "arch.thickness=0.4"])
        .expect("valid");
    let m = voussoir::scene::build(&flat).expect("builds");
    let (f, r) = both(&m, Direction::Right);
    assert_eq!(f.status, r.status);
}

#[test]
fn reduced_program_is_refused_for_an_assembly_that_is_not_a_chain() {
    let m = voussoir::scene::build(&bundled("semicircular.toml")).expect("builds");
    let mut a = m.assembly.clone();
    a.joints.swap(3, 4);
    let e = statics::analyse_chain(&Model::self_weight(a), &StaticSettings::default());
    assert!(e.is_err());
}

/// On long chains the interior-point optimum of the full program stops about 5e-9 below the
/// collapse multiplier; the reduced program's exact vertex step lands on it: its multiplier is
/// that of the mechanism its active rows define, which the kinematic search (local, around
/// the static hinges) finds independently.
#[test]
fn exact_vertex_on_long_chains_meets_the_kinematic_bound() {
    for n in [4000usize, 20000] {
        let s = bundled("semicircular.toml")
            .with_override(&format!("arch.voussoirs={n}"))
            .expect("valid");
        let m = voussoir::scene::build(&s).expect("builds");
        let settings = StaticSettings::default();
        let r = statics::analyse_chain(&m, &settings).expect("reduced");
        assert!(
            r.solver_status.contains("exact vertex"),
            "n = {n}: {}",
            r.solver_status
        );
        let lr = r.lambda.expect("collapse");
        let k = voussoir::kinematic::analyse_local(
            &m,
            &r,
            &voussoir::kinematic::KinematicSettings::default(),
            voussoir::kinematic::DEFAULT_LOCAL_WINDOW,
        )
        .expect("local kinematic search");
        let lk = k.lambda_upper.expect("upper bound");
        let rel = (lr - lk).abs() / lk;
        assert!(
            rel < 1e-12,
            "n = {n}: vertex {lr}, kinematic {lk} ({rel:.1e})"
        );
        assert!(r.equilibrium_residual < 1e-8 * m.loads.force_scale());
    }
}

/// The upper bound certified from the static hinges: on every bundled shape and load case
/// (no sliding) it is the exhaustive search's multiplier and mechanism; on a 20,000-voussoir
/// arch, far beyond the exhaustive search, it meets the reduced program's exact vertex to
/// 1e-12, so the collapse multiplier is certified.
#[test]
fn certified_upper_bound_from_the_static_hinges() {
    use voussoir::kinematic::{self, KinematicSettings, Search};
    let mut certified = 0;
    for name in [
        "semicircular.toml",
        "segmental.toml",
        "pointed.toml",
        "basket.toml",
        "portal.toml",
        "loaded_portal.toml",
        "filled_arch.toml",
    ] {
        let m = voussoir::scene::build(&bundled(name)).expect("builds");
        for d in [Direction::Right, Direction::Left] {
            let s = StaticSettings::default().direction(d);
            let ks = KinematicSettings::default().direction(d);
            let r = statics::analyse_chain(&m, &s).expect("reduced");
            let Ok(c) = kinematic::certify(&m, &r, &ks) else {
                continue;
            };
            let ex = kinematic::analyse(&m, &ks).expect("exhaustive");
            assert_eq!(c.search, Search::Certified);
            let (lc, le) = (
                c.lambda_upper.expect("bound"),
                ex.lambda_upper.expect("bound"),
            );
            assert!((lc - le).abs() <= 1e-12 * le, "{name} {d:?}: {lc} vs {le}");
            let hc = &c.mechanism.as_ref().expect("mechanism").hinges;
            let he = &ex.mechanism.as_ref().expect("mechanism").hinges;
            assert_eq!(hc, he, "{name} {d:?}");
            let ls = r.lambda.expect("collapse");
            assert!(
                (lc - ls).abs() <= 1e-12 * ls,
                "{name} {d:?}: static {ls}, certified {lc}"
            );
            certified += 1;
        }
    }
    assert!(certified >= 12, "only {certified} cases certified");
    let s = bundled("semicircular.toml")
        .with_override("arch.voussoirs=20000")
        .expect("valid");
    let m = voussoir::scene::build(&s).expect("builds");
    let r = statics::analyse_chain(&m, &StaticSettings::default()).expect("reduced");
    let c = kinematic::certify(&m, &r, &KinematicSettings::default()).expect("certified");
    let (lc, ls) = (c.lambda_upper.expect("bound"), r.lambda.expect("collapse"));
    assert!(
        (lc - ls).abs() <= 1e-12 * ls,
        "n = 20000: static {ls}, certified {lc}"
    );
}

/// The kinematic minimum thickness certified from the static hinges equals the exhaustive
/// bisection's on every bundled scene, and both bracket the static value; the semicircle of
/// many voussoirs approaches Milankovitch's t/R = 0.1075 from below by both.
#[test]
fn certified_minimum_thickness_matches_the_exhaustive_bisection() {
    use voussoir::analysis::{KinematicMode, Options};
    use voussoir::kinematic::Search;
    let rel = |a: f64, b: f64| (a - b).abs() / a;
    let with = |mode| Options {
        kinematic: mode,
        ..Options::default()
    };
    for name in [
        "semicircular.toml",
        "segmental.toml",
        "pointed.toml",
        "basket.toml",
        "portal.toml",
        "loaded_portal.toml",
        "filled_arch.toml",
    ] {
        let s = bundled(name);
        let c =
            voussoir::thickness::analyse(&s, &with(KinematicMode::Certified)).expect("certified");
        let e =
            voussoir::thickness::analyse(&s, &with(KinematicMode::Exhaustive)).expect("exhaustive");
        assert_eq!(
            c.kinematic_search,
            Some(Search::Certified),
            "{name}: {:?}",
            c.kinematic_note
        );
        assert_eq!(e.kinematic_search, Some(Search::Exhaustive), "{name}");
        let ts = c.lower.search.min_thickness.expect("static t_min");
        let tc = c
            .kinematic
            .as_ref()
            .and_then(|k| k.min_thickness)
            .expect("certified t_min");
        let te = e
            .kinematic
            .as_ref()
            .and_then(|k| k.min_thickness)
            .expect("exhaustive t_min");
        // The static search's bracket is 1e-9 wide; the certified root is found to 1e-13.
        assert!(
            rel(ts, tc) <= 2e-9 && rel(ts, te) <= 2e-9,
            "{name}: static {ts}, certified {tc}, exhaustive {te}"
        );
        let (lo, hi) = c.lower.search.bracket.expect("bracket");
        assert!(
            lo <= tc * (1.0 + 1e-12) && tc <= hi * (1.0 + 1e-12),
            "{name}: {tc} outside [{lo}, {hi}]"
        );
    }
    let s = bundled("semicircular.toml")
        .with_override("arch.voussoirs=400")
        .expect("valid");
    let c = voussoir::thickness::analyse(&s, &Options::default()).expect("certified");
    assert_eq!(c.kinematic_search, Some(Search::Certified));
    let r = s.arch_size();
    let tc = c
        .kinematic
        .as_ref()
        .and_then(|k| k.min_thickness)
        .expect("t_min")
        / r;
    assert!((0.1072..0.1075).contains(&tc), "n = 400: t/R = {tc}");
}

mod random {
    use super::*;
    use proptest::prelude::*;
    use proptest::test_runner::{Config, RngSeed, TestRunner};

    /// A random scene: any shape, with or without piers, finite or infinite friction, with or
    /// without fill, a point load at a voussoir's centroid and a vertical ratio.
    fn scene_text() -> impl Strategy<Value = (String, usize, f64, bool, f64)> {
        (
            0usize..3,
            0.08f64..0.3,
            4usize..28,
            prop::option::of((0.5f64..2.0, 0.2f64..0.6, 1usize..3)),
            prop::option::of(0.3f64..1.2),
            (0usize..64, -3000.0f64..3000.0, -8000.0f64..0.0, any::<bool>()),
            (prop::option::of(0.1f64..0.5), -0.4f64..0.4),
        )
            .prop_map(|(shape, t, n, piers, mu, (j, fx, fy, seismic), (fill, r))| {
                let arch = match shape {
                    0 => format!("shape = \"circular\"\nradius = 1.0\nthickness = {t}\nvoussoirs = {n}\n"),
                    1 => format!(
                        "shape = \"pointed\"\nradius = 1.0\neccentricity = 0.2\nthickness = {t}\nvoussoirs = {}\n",
                        2 * (n / 2).max(1)
                    ),
                    _ => format!(
                        "shape = \"basket\"\nspan = 2.0\nrise = 0.7\nthickness = {t}\nvoussoirs = {}\n",
                        n.max(5)
                    ),
                };
                let mut text = format!("[arch]\n{arch}");
                if let Some((h, b, k)) = piers {
                    text.push_str(&format!("[piers]\nheight = {h}\nwidth = {b}\ncourses = {k}\n"));
                }
                if let Some(mu) = mu {
                    text.push_str(&format!("[material]\nfriction = {mu}\n"));
                }
                if let Some(f) = fill {
                    text.push_str(&format!("[fill]\nlevel = {}\n", 1.0 + t + f));
                }
                text.push_str(&format!("[seismic]\nvertical_ratio = {r}\n"));
                (text, j, fx, seismic, fy)
            })
    }

    /// Reduced = full on random scenes with random loads, finite and infinite friction, both
    /// directions: the same status, and the same multiplier to the full program's accuracy.
    #[test]
    fn reduced_equals_full_on_random_loaded_scenes() {
        let mut runner = TestRunner::new(Config {
            cases: 48,
            rng_seed: RngSeed::Fixed(20261123),
            failure_persistence: None,
            ..Config::default()
        });
        runner
            .run(&scene_text(), |(text, j, fx, seismic, fy)| {
                let Ok(base) = Scene::from_toml_str(&text, "random.toml") else {
                    return Ok(());
                };
                let m0 = voussoir::scene::build(&base).expect("valid scene builds");
                // A point load at (near) the centroid of a voussoir.
                let blocks: Vec<_> = m0
                    .assembly
                    .blocks
                    .iter()
                    .filter(|b| matches!(b.kind, voussoir::assembly::BlockKind::Voussoir(_)))
                    .collect();
                let c = blocks[j % blocks.len()].centroid;
                let text = format!(
                    "{text}[[loads]]\ntype = \"point\"\nat = [{}, {}]\nforce = [{fx}, {fy}]\nseismic = {seismic}\n",
                    c.x, c.y
                );
                let s = Scene::from_toml_str(&text, "random.toml").expect("loaded scene");
                let m = voussoir::scene::build(&s).expect("builds");
                for d in [Direction::Right, Direction::Left] {
                    let st = StaticSettings::default().direction(d);
                    let full = statics::analyse_full(&m, &st).expect("full program");
                    let Ok(red) = statics::analyse_chain(&m, &st) else {
                        // The chain program may stop short; `statics::analyse` then runs the full
                        // one, so only its answers are compared.
                        continue;
                    };
                    prop_assert_eq!(full.status, red.status, "{} {:?}", text, d);
                    if let (Some(a), Some(b)) = (full.lambda, red.lambda) {
                        COMPARED.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
                        let rel = (a - b).abs() / a.abs().max(1e-3);
                        prop_assert!(rel < 1e-8, "{} {:?}: full {} reduced {} ({:e})", text, d, a, b, rel);
                    }
                }
                Ok(())
            })
            .expect("reduced = full");
        let compared = COMPARED.load(std::sync::atomic::Ordering::Relaxed);
        assert!(
            compared >= 40,
            "only {compared} collapse multipliers compared"
        );
    }

    static COMPARED: std::sync::atomic::AtomicUsize = std::sync::atomic::AtomicUsize::new(0);
}
