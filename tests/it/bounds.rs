//! The static (lower-bound: the chain's reduced program and the full program) and kinematic
//! (upper-bound: the exhaustive hinge mechanism search, and the mechanism certified from the
//! static hinges) collapse multipliers must coincide for non-sliding joints (mu = inf): limit
//! analysis of no-tension rigid blocks has both theorems, and the programs are dual to each
//! other. A grid over every shape, both voussoir shapes, portals and numbers of
//! voussoirs checks the multipliers, the statuses and, where the mechanism is unique, the
//! hinges and the block velocities.

use voussoir::assembly::JointEnd;
use voussoir::kinematic::{self, KinematicSettings};
use voussoir::scene::Scene;
use voussoir::statics::{self, Direction, StaticSettings, Status};

pub(crate) struct Case {
    pub label: String,
    pub toml: String,
}

fn arch(shape: &str, t: f64, n: usize, vs: &str) -> String {
    format!("[arch]\n{shape}\nthickness = {t}\nvoussoirs = {n}\nvoussoir_shape = \"{vs}\"\n")
}

/// The chains every bound is checked on (also by `general_kinematic.rs`).
pub(crate) fn grid() -> Vec<Case> {
    let mut cases = Vec::new();
    let shapes = ["polygon", "curved"];
    let mut k = 0usize;
    let next = |k: &mut usize, list: &[usize]| {
        *k += 1;
        list[*k % list.len()]
    };
    // Circular: segmental, semicircular, horseshoe.
    for emb in [60.0, 100.0, 140.0, 180.0, 220.0] {
        for t in [0.11, 0.15, 0.25, 0.4] {
            for vs in shapes {
                let n = next(&mut k, &[8, 17, 32, 64]);
                cases.push(Case {
                    label: format!("circular embrace={emb} t={t} n={n} {vs}"),
                    toml: arch(
                        &format!("shape = \"circular\"\nradius = 1.0\nembrace_deg = {emb}"),
                        t,
                        n,
                        vs,
                    ),
                });
            }
        }
    }
    // Pointed.
    for e in [0.0, 0.1, 0.25, 0.4] {
        for t in [0.11, 0.2, 0.35] {
            for vs in shapes {
                let mut n = next(&mut k, &[8, 16, 32, 64]);
                // Very pointed, thick arches admit only a few voussoirs before the one next to
                // the crown folds over it (the scene rejects those): take 16 there.
                let text = arch(
                    &format!("shape = \"pointed\"\nradius = 1.0\neccentricity = {e}"),
                    t,
                    n,
                    vs,
                );
                if Scene::from_toml_str(&text, "probe").is_err() {
                    n = 16;
                }
                cases.push(Case {
                    label: format!("pointed e={e} t={t} n={n} {vs}"),
                    toml: arch(
                        &format!("shape = \"pointed\"\nradius = 1.0\neccentricity = {e}"),
                        t,
                        n,
                        vs,
                    ),
                });
            }
        }
    }
    // Basket.
    for rise in [0.5, 0.7, 0.9] {
        for t in [0.08, 0.15, 0.3] {
            for vs in shapes {
                let n = next(&mut k, &[9, 16, 33, 64]);
                cases.push(Case {
                    label: format!("basket rise/span={} t={t} n={n} {vs}", rise / 2.0),
                    toml: arch(
                        &format!("shape = \"basket\"\nspan = 2.0\nrise = {rise}"),
                        t,
                        n,
                        vs,
                    ),
                });
            }
        }
    }
    // Portals on every shape.
    let portal_shapes = [
        "shape = \"circular\"\nradius = 1.0",
        "shape = \"pointed\"\nradius = 1.0\neccentricity = 0.25",
        "shape = \"basket\"\nspan = 2.0\nrise = 0.7",
    ];
    for (si, sh) in portal_shapes.iter().enumerate() {
        for h in [0.5, 1.0, 2.0] {
            for b in [0.3, 0.6] {
                for courses in [1, 4] {
                    let n = next(&mut k, &[8, 16, 24, 32]);
                    let t = [0.15, 0.2, 0.25][(k + si) % 3];
                    let vs = shapes[k % 2];
                    cases.push(Case {
                        label: format!(
                            "portal {} h={h} b={b} k={courses} t={t} n={n} {vs}",
                            sh.lines().next().unwrap_or("")
                        ),
                        toml: format!(
                            "{}[piers]\nheight = {h}\nwidth = {b}\ncourses = {courses}\n",
                            arch(sh, t, n, vs)
                        ),
                    });
                }
            }
        }
    }
    cases
}

/// Relative difference, scaled by max(1, |a|).
fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / a.abs().max(1.0)
}

/// On every case and both directions: the chain's reduced program, the full program and the
/// exhaustive search give the same status and multiplier (1e-9); where the mechanism is unique
/// (hinges + 2 open = 4 in both the static solution and the exhaustive search) the
/// certificate from the static hinges succeeds, meets the multiplier to 1e-9, and names the
/// exhaustive search's hinges, open joints and block velocities.
#[test]
fn static_and_kinematic_bounds_coincide() {
    const TOL: f64 = 1e-9;
    let mut failures = Vec::new();
    let mut counts = [0usize; 3];
    let mut compared_mechanisms = 0;
    let mut worst = [0.0_f64; 2];
    for case in grid() {
        let scene = Scene::from_toml_str(&case.toml, &case.label).expect("valid scene");
        let asm = voussoir::scene::build(&scene).expect("valid model");
        for dir in [Direction::Right, Direction::Left] {
            let settings = StaticSettings::default().direction(dir);
            let st = statics::analyse_chain(&asm, &settings).expect("reduced program");
            let full = statics::analyse_full(&asm, &settings).expect("full program");
            let kin = kinematic::analyse(&asm, &KinematicSettings::default().direction(dir))
                .expect("kinematic");
            let label = format!("{} {:?}", case.label, dir);
            counts[match st.status {
                Status::Collapse => 0,
                Status::NoCollapse => 1,
                Status::CannotStand => 2,
            }] += 1;
            if st.status != kin.status || st.status != full.status {
                failures.push(format!(
                    "{label}: status reduced {:?} {:?}, full {:?} {:?}, kinematic {:?} {:?} (signed {:?}, needed {:?})",
                    st.status, st.lambda, full.status, full.lambda, kin.status, kin.lambda_upper, kin.lambda_signed, kin.lambda_needed
                ));
                continue;
            }
            let (Some(ls), Some(lf), Some(lk)) = (st.lambda, full.lambda, kin.lambda_upper) else {
                continue;
            };
            worst[0] = worst[0].max(rel(ls, lf));
            worst[1] = worst[1].max(rel(ls, lk));
            if rel(ls, lf) > TOL || rel(ls, lk) > TOL {
                failures.push(format!("{label}: reduced {ls} full {lf} kinematic {lk}"));
                continue;
            }
            // Unique mechanism: the static solution shows exactly hinges + 2 open = 4 and
            // the kinematic one has no idle hinge.
            let m = kin.mechanism.as_ref().expect("mechanism");
            if st.hinges.len() + 2 * st.open.len() == 4 && m.hinges.len() + 2 * m.open.len() == 4 {
                compared_mechanisms += 1;
                let hs: Vec<(usize, JointEnd)> =
                    st.hinges.iter().map(|h| (h.joint, h.end)).collect();
                let hk: Vec<(usize, JointEnd)> =
                    m.hinges.iter().map(|h| (h.joint, h.end)).collect();
                if hs != hk || st.open != m.open {
                    failures.push(format!(
                        "{label}: hinges static {hs:?} open {:?}, kinematic {hk:?} open {:?}",
                        st.open, m.open
                    ));
                    continue;
                }
                let dv = st
                    .mechanism
                    .iter()
                    .zip(&m.velocities)
                    .flat_map(|(a, b)| (0..2).map(move |i| (a[i] - b[i]).abs()))
                    .fold(0.0_f64, f64::max);
                if dv > 1e-4 {
                    failures.push(format!("{label}: block velocities differ by {dv:.2e}"));
                }
                let ks = KinematicSettings::default().direction(dir);
                match kinematic::certify(&asm, &st, &ks) {
                    Ok(c) => {
                        let lc = c.lambda_upper.unwrap_or(f64::NAN);
                        let cm = c.mechanism.as_ref().expect("certified mechanism");
                        let hc: Vec<(usize, JointEnd)> =
                            cm.hinges.iter().map(|h| (h.joint, h.end)).collect();
                        if rel(ls, lc).is_nan()
                            || rel(ls, lc) > TOL
                            || hc != hk
                            || cm.open != m.open
                        {
                            failures.push(format!(
                                "{label}: certified {lc} hinges {hc:?} open {:?}; exhaustive {lk} hinges {hk:?} open {:?}",
                                cm.open, m.open
                            ));
                        }
                    }
                    Err(e) => failures.push(format!("{label}: not certified: {e}")),
                }
            }
        }
    }
    eprintln!(
        "statuses (collapse, no_collapse, cannot_stand): {counts:?}; mechanisms compared and certified: {compared_mechanisms}; largest differences reduced-full {:.1e}, reduced-kinematic {:.1e}",
        worst[0], worst[1]
    );
    assert!(
        compared_mechanisms > 100,
        "only {compared_mechanisms} unique mechanisms"
    );
    assert!(
        failures.is_empty(),
        "{} disagreements:\n{}",
        failures.len(),
        failures.join("\n")
    );
}

/// With finite friction the rotational mechanisms stay admissible, so the kinematic value is
/// still an upper bound; sliding can only lower the static multiplier (then sliding governs).
#[test]
fn finite_friction_static_stays_below_kinematic() {
    let mut slid = 0;
    for mu in [0.2, 0.4, 0.7] {
        for (sh, piers) in [
            ("shape = \"circular\"\nradius = 1.0\nembrace_deg = 100", ""),
            (
                "shape = \"circular\"\nradius = 1.0",
                "[piers]\nheight = 1.0\nwidth = 0.5\ncourses = 4\n",
            ),
            ("shape = \"pointed\"\nradius = 1.0\neccentricity = 0.25", ""),
        ] {
            let text = format!(
                "{}{piers}[material]\nfriction = {mu}\n",
                arch(sh, 0.25, 16, "polygon")
            );
            let scene = Scene::from_toml_str(&text, "friction").expect("scene");
            let asm = voussoir::scene::build(&scene).expect("valid model");
            let st = statics::analyse(&asm, &StaticSettings::default()).expect("static");
            let kin = kinematic::analyse(&asm, &KinematicSettings::default()).expect("kinematic");
            let (Some(ls), Some(lk)) = (st.lambda, kin.lambda_upper) else {
                continue;
            };
            assert!(
                ls <= lk * (1.0 + 1e-7) + 1e-9,
                "mu = {mu} {sh}: static {ls} > kinematic {lk}"
            );
            if ls < lk * (1.0 - 1e-6) {
                slid += 1;
                assert!(
                    !st.sliding.is_empty(),
                    "static below kinematic without sliding joints"
                );
            }
        }
    }
    assert!(slid > 0, "no case where sliding governs");
}
