//! The general kinematic program (`voussoir::kinematic::general`, issue 23 item 3): an upper
//! bound for any assembly, certified by virtual work. By LP duality it equals the static
//! multiplier whenever friction is associative (finite friction included), and on chains it
//! equals the chain search's least multiplier. Checked here on running-bond walls, a lintel
//! portal, every bundled block scene and the chains of `bounds.rs`; the certified mechanism's
//! virtual work is recomputed here from its block velocities; mirror images give the same
//! multiplier in the mirrored direction.

use crate::common;
use voussoir::analysis::{self, KinematicMode, Options};
use voussoir::assembly::{Assembly, Block, Joint, JointEnd, JointKind};
use voussoir::geometry::Vec2;
use voussoir::kinematic::{self, KinematicResult, KinematicSettings, Search};
use voussoir::model::{Model, Strip};
use voussoir::scene::Scene;
use voussoir::statics::{self, Direction, StaticSettings, Status};

/// Relative difference scaled by max(1, |a|).
fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / a.abs().max(1.0)
}

fn general(model: &Model, dir: Direction) -> KinematicResult {
    kinematic::analyse_general(model, &KinematicSettings::default().direction(dir))
        .expect("general kinematic program")
}

fn full_static(model: &Model, dir: Direction) -> statics::StaticResult {
    statics::analyse_full(model, &StaticSettings::default().direction(dir)).expect("static")
}

/// A joint from `p1` to `p2`: `from` on the side of `-n`, `to` on `+n`, `n = (u_y, -u_x)`.
fn joint(p1: Vec2, p2: Vec2, from: Option<usize>, to: Option<usize>, mu: f64) -> Joint {
    Joint {
        p1,
        p2,
        from,
        to,
        friction: mu,
        kind: JointKind::Other,
    }
}

/// The assembly of axis-aligned rectangles `rects` on the ground `y = 0`, with a joint
/// wherever two of them (or one and the ground) share a segment of positive length:
/// horizontal beds (normal up, from the lower block) and vertical head joints (normal toward
/// +x, from the left block).
fn rect_assembly(rects: &[[f64; 4]], mu: f64) -> Assembly {
    let blocks: Vec<Block> = rects
        .iter()
        .map(|r| common::rect(r[0], r[1], r[2] - r[0], r[3] - r[1]))
        .collect();
    let mut joints = Vec::new();
    let tol = 1e-12;
    for (i, a) in rects.iter().enumerate() {
        // On the ground.
        if a[1].abs() < tol {
            joints.push(joint(
                Vec2::new(a[2], 0.0),
                Vec2::new(a[0], 0.0),
                None,
                Some(i),
                mu,
            ));
        }
        for (k, b) in rects.iter().enumerate() {
            // b on top of a.
            if (a[3] - b[1]).abs() < tol {
                let (lo, hi) = (a[0].max(b[0]), a[2].min(b[2]));
                if hi - lo > tol {
                    joints.push(joint(
                        Vec2::new(hi, a[3]),
                        Vec2::new(lo, a[3]),
                        Some(i),
                        Some(k),
                        mu,
                    ));
                }
            }
            // b to the right of a.
            if (a[2] - b[0]).abs() < tol {
                let (lo, hi) = (a[1].max(b[1]), a[3].min(b[3]));
                if hi - lo > tol {
                    joints.push(joint(
                        Vec2::new(a[2], lo),
                        Vec2::new(a[2], hi),
                        Some(i),
                        Some(k),
                        mu,
                    ));
                }
            }
        }
    }
    let assembly = Assembly { blocks, joints };
    assembly.validate().expect("valid assembly");
    assembly
}

/// A running-bond wall of `courses` courses of `units` units (length `unit`, height `h`),
/// every other course offset by half a unit with half units at its ends.
fn running_bond(courses: usize, units: usize, unit: f64, h: f64) -> Vec<[f64; 4]> {
    let length = units as f64 * unit;
    let mut rects = Vec::new();
    for c in 0..courses {
        let (y0, y1) = (c as f64 * h, (c + 1) as f64 * h);
        let mut xs = vec![0.0];
        if c % 2 == 1 {
            xs.push(0.5 * unit);
        }
        while *xs.last().expect("a start") + unit < length - 1e-9 {
            let next = xs.last().expect("a start") + unit;
            xs.push(next);
        }
        xs.push(length);
        for w in xs.windows(2) {
            rects.push([w[0], y0, w[1], y1]);
        }
    }
    rects
}

/// A lintel portal: two piers of `courses` courses and one lintel block resting on both.
fn lintel_portal(courses: usize) -> Vec<[f64; 4]> {
    let (b, h, span, t) = (0.4, 0.5, 1.2, 0.35);
    let mut rects = Vec::new();
    for c in 0..courses {
        let (y0, y1) = (c as f64 * h, (c + 1) as f64 * h);
        rects.push([0.0, y0, b, y1]);
        rects.push([b + span, y0, 2.0 * b + span, y1]);
    }
    let top = courses as f64 * h;
    rects.push([0.0, top, 2.0 * b + span, top + t]);
    rects
}

/// The certificate, checked from outside: the mechanism's block velocities are admissible
/// at every joint (no interpenetration, the associative flow rule; to 1e-7 of the largest
/// relative velocity), and its virtual work, recomputed here from the load case, gives its
/// multiplier `(G + D)/A` (no ties or strips here: D = 0).
fn check_virtual_work(model: &Model, k: &KinematicResult, dir: Direction) {
    let m = k.mechanism.as_ref().expect("mechanism");
    let lambda = k.lambda_upper.expect("lambda_upper");
    assert_eq!(m.lambda, lambda);
    let sign = dir.sign();
    let v = |b: Option<usize>, q: Vec2| -> Vec2 {
        b.map_or(Vec2::zeros(), |i| {
            let [vx, vy, w] = m.velocities[i];
            let c = model.assembly.blocks[i].centroid;
            Vec2::new(vx - w * (q.y - c.y), vy + w * (q.x - c.x))
        })
    };
    let mut largest = 0.0_f64;
    let mut rates = Vec::new();
    for jt in &model.assembly.joints {
        let dv = |q: Vec2| v(jt.to, q) - v(jt.from, q);
        let r = (
            dv(jt.p1).dot(&jt.normal()),
            dv(jt.p2).dot(&jt.normal()),
            dv(jt.midpoint()).dot(&jt.tangent()),
        );
        largest = largest.max(r.0.abs()).max(r.1.abs()).max(r.2.abs());
        rates.push(r);
    }
    assert!(largest > 0.0);
    for (jt, (dn1, dn2, dt)) in model.assembly.joints.iter().zip(rates) {
        let slip = if jt.friction.is_finite() {
            jt.friction * dt.abs()
        } else {
            assert!(dt.abs() <= 1e-7 * largest, "slip {dt} at infinite friction");
            0.0
        };
        assert!(dn1 >= slip - 1e-7 * largest, "{dn1} < {slip}");
        assert!(dn2 >= slip - 1e-7 * largest, "{dn2} < {slip}");
    }
    // Virtual work: the power of the permanent loads and of the action, from the per-block
    // wrenches about the centroids.
    let (mut a, mut g) = (0.0, 0.0);
    for (i, vel) in m.velocities.iter().enumerate() {
        // The velocity of the point the wrenches are reduced to (the centroid).
        let u = v(Some(i), model.loads.reference(i));
        let p = model.loads.permanent(i);
        let s = model.loads.variable(i, sign);
        g -= p.force.dot(&u) + p.moment * vel[2];
        a += s.force.dot(&u) + s.moment * vel[2];
    }
    assert!(a > 0.0, "the action does positive work");
    assert!(
        rel(lambda, g / a) <= 1e-9,
        "virtual work {} vs lambda {lambda}",
        g / a
    );
}

/// General = static on running-bond walls, with and without friction, both directions; the
/// certificate holds; the mirrored wall in the mirrored direction gives the same multiplier.
#[test]
fn general_equals_static_on_running_bond_walls() {
    for (courses, units) in [(3, 2), (6, 4), (10, 6)] {
        for (unit, h) in [(0.5, 0.25), (0.4, 0.3)] {
            for mu in [f64::INFINITY, 0.7, 0.4, 0.2] {
                let asm = rect_assembly(&running_bond(courses, units, unit, h), mu);
                let model = Model::self_weight(asm);
                for dir in [Direction::Right, Direction::Left] {
                    let st = full_static(&model, dir);
                    let k = general(&model, dir);
                    let label = format!("wall {courses}x{units} {unit}x{h} mu={mu} {dir:?}");
                    assert_eq!(st.status, k.status, "{label}");
                    assert_eq!(k.search, Search::General);
                    let (Some(ls), Some(lk)) = (st.lambda, k.lambda_upper) else {
                        continue;
                    };
                    assert!(rel(ls, lk) <= 1e-8, "{label}: static {ls} general {lk}");
                    check_virtual_work(&model, &k, dir);
                    let mirrored = model.mirrored();
                    let other = match dir {
                        Direction::Right => Direction::Left,
                        Direction::Left => Direction::Right,
                    };
                    let km = general(&mirrored, other);
                    let lm = km.lambda_upper.expect("mirrored lambda");
                    assert!(rel(lk, lm) <= 1e-8, "{label}: mirror {lm} vs {lk}");
                }
            }
        }
    }
}

/// The lintel portal (two piers of 1..4 courses and a lintel resting on both, numbered pier by
/// pier and course by course, so that the analysis layer sees no chain and the chain searches
/// do not apply): general = static for infinite and finite friction, both directions, with its
/// certificate and its mirror image.
#[test]
fn general_equals_static_on_a_lintel_portal() {
    for courses in 1..=4 {
        for mu in [f64::INFINITY, 0.8, 0.5, 0.3] {
            let model = Model::self_weight(rect_assembly(&lintel_portal(courses), mu));
            assert!(analysis::not_a_chain(&model.assembly).is_some());
            for dir in [Direction::Right, Direction::Left] {
                let st = full_static(&model, dir);
                let k = general(&model, dir);
                let label = format!("lintel portal {courses} courses mu={mu} {dir:?}");
                assert_eq!(st.status, Status::Collapse, "{label}");
                assert_eq!(k.status, Status::Collapse, "{label}");
                let (ls, lk) = (st.lambda.expect("static"), k.lambda_upper.expect("upper"));
                assert!(rel(ls, lk) <= 1e-8, "{label}: static {ls} general {lk}");
                check_virtual_work(&model, &k, dir);
                let other = if dir == Direction::Right {
                    Direction::Left
                } else {
                    Direction::Right
                };
                let lm = general(&model.mirrored(), other)
                    .lambda_upper
                    .expect("mirror");
                assert!(rel(lk, lm) <= 1e-8, "{label}: mirror {lm} vs {lk}");
            }
        }
    }
}

fn options(mode: KinematicMode, dir: Direction) -> Options {
    Options {
        static_settings: StaticSettings::default().direction(dir),
        kinematic: mode,
        ..Options::default()
    }
}

/// Every bundled block scene (`data/blocks_*.toml`, finite friction as they are written and
/// infinite): the analysis layer's general upper bound equals the static bound (1e-8), the
/// certificate holds, and the chain search agrees where the blocks are a chain.
#[test]
fn general_equals_static_on_every_bundled_block_scene() {
    let data = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("data");
    let mut scenes: Vec<_> = std::fs::read_dir(&data)
        .expect("data/")
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| {
            p.file_name()
                .is_some_and(|n| n.to_string_lossy().starts_with("blocks_"))
                && p.extension().is_some_and(|e| e == "toml")
        })
        .collect();
    scenes.sort();
    assert!(scenes.len() >= 3, "{scenes:?}");
    for path in scenes {
        let scene = Scene::from_file(&path).expect("bundled scene");
        for friction in [
            None,
            Some("material.friction=inf"),
            Some("material.friction=0.3"),
        ] {
            let scene = match friction {
                Some(o) => scene.with_overrides(&[o]).expect("override"),
                None => scene.clone(),
            };
            for dir in [Direction::Right, Direction::Left] {
                let label = format!("{} {friction:?} {dir:?}", path.display());
                let a = analysis::analyse(&scene, &options(KinematicMode::General, dir))
                    .expect("analysis");
                assert_eq!(a.kinematic_search, Some(Search::General), "{label}");
                let k = a.upper.as_ref().expect("general upper bound");
                assert_eq!(k.status, a.lower.status, "{label}");
                let (Some(ls), Some(lk)) = (a.lower.lambda, k.lambda_upper) else {
                    continue;
                };
                assert!(rel(ls, lk) <= 1e-8, "{label}: static {ls} general {lk}");
                check_virtual_work(&a.model, k, dir);
                let gap = a.gap().expect("gap");
                assert!(gap <= 1e-8, "{label}: gap {gap}");
            }
        }
    }
}

/// On every chain of `bounds.rs`, both directions: the general program and the chain's
/// exhaustive search give the same status and multiplier (1e-9).
#[test]
fn general_equals_the_chain_search_on_every_chain_of_bounds() {
    let mut worst = 0.0_f64;
    let mut compared = 0;
    let mut failures = Vec::new();
    for case in crate::bounds::grid() {
        let scene = Scene::from_toml_str(&case.toml, &case.label).expect("scene");
        let model = voussoir::scene::build(&scene).expect("model");
        for dir in [Direction::Right, Direction::Left] {
            let chain = kinematic::analyse(&model, &KinematicSettings::default().direction(dir))
                .expect("chain search");
            let k = general(&model, dir);
            let label = format!("{} {dir:?}", case.label);
            if chain.status != k.status {
                failures.push(format!(
                    "{label}: status chain {:?} general {:?}",
                    chain.status, k.status
                ));
                continue;
            }
            if let (Some(lc), Some(lk)) = (chain.lambda_upper, k.lambda_upper) {
                compared += 1;
                worst = worst.max(rel(lc, lk));
                if rel(lc, lk) > 1e-9 {
                    failures.push(format!("{label}: chain {lc} general {lk}"));
                } else {
                    check_virtual_work(&model, &k, dir);
                }
            }
        }
    }
    eprintln!("general vs chain search: {compared} multipliers, largest difference {worst:.1e}");
    assert!(compared > 150, "{compared}");
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// Ties (the tied portal), a bonded strip (closed form of a block with a strip at its heel),
/// and the live action (the bundled live-load arch): the general program, asked for on these
/// chains, equals the static bound.
#[test]
fn general_takes_ties_strips_and_the_live_action() {
    for name in ["tied_portal.toml", "live_load_arch.toml", "portal.toml"] {
        let scene = Scene::from_file(&common::data(name)).expect("bundled scene");
        let dirs: &[Direction] = if name == "live_load_arch.toml" {
            &[Direction::Right]
        } else {
            &[Direction::Right, Direction::Left]
        };
        for &dir in dirs {
            let a =
                analysis::analyse(&scene, &options(KinematicMode::General, dir)).expect("analysis");
            let k = a.upper.as_ref().expect("general");
            let (ls, lk) = (
                a.lower.lambda.expect("static"),
                k.lambda_upper.expect("general"),
            );
            assert!(
                rel(ls, lk) <= 1e-8,
                "{name} {dir:?}: static {ls} general {lk}"
            );
        }
    }
    // A block b x h with a strip of capacity F at its heel: lambda = (W b/2 + F b)/(W h/2).
    let (b, h) = (0.4, 1.5);
    let asm = common::single_block(b, h, f64::INFINITY);
    let w = asm.total_weight();
    let heel = if asm.joints[0].p1.x < 0.0 {
        JointEnd::P1
    } else {
        JointEnd::P2
    };
    for f in [0.0, 0.05 * w, 0.3 * w] {
        let mut m = Model::self_weight(asm.clone());
        m.strips = vec![Strip {
            joint: 0,
            end: heel,
            capacity: f,
            source: 0,
        }];
        let lk = general(&m, Direction::Right).lambda_upper.expect("general");
        let expected = (w * b / 2.0 + f * b) / (w * h / 2.0);
        assert!(rel(expected, lk) <= 1e-9, "strip {f}: {lk} vs {expected}");
    }
}

/// With a finite compressive strength the general program keeps rigid joints: its multiplier
/// is the rigid structure's (an upper bound of the crushing one), and the analysis says so.
#[test]
fn with_crushing_the_general_bound_is_the_rigid_one_and_says_so() {
    let text = format!(
        "[blocks]\nground_y = 0.0\npolygons = {}\n[material]\nunit_weight = 20000.0\n",
        common::rect_polygons(&running_bond(4, 3, 0.5, 0.25))
    );
    let rigid = Scene::from_toml_str(&text, "wall").expect("scene");
    let crushing = rigid
        .with_overrides(&["material.compressive_strength=2e5"])
        .expect("override");
    let r = analysis::analyse(&rigid, &Options::default()).expect("rigid");
    let c = analysis::analyse(&crushing, &Options::default()).expect("crushing");
    let (lr, lc) = (
        r.lower.lambda.expect("rigid"),
        c.lower.lambda.expect("crushing"),
    );
    assert!(lc < lr * (1.0 - 1e-4), "crushing {lc} below rigid {lr}");
    let ku = c.upper.as_ref().expect("general");
    let u = ku.lambda_upper.expect("upper");
    assert!(rel(lr, u) <= 1e-8, "rigid {lr} vs general {u}");
    assert!(u >= lc);
    assert!(
        ku.note
            .as_deref()
            .is_some_and(|n| n.contains("rigid hinges")),
        "{:?}",
        ku.note
    );
}

/// `analyze --json` of a wall: `lambda_upper`, `kinematic_search = "general"`, the mechanism
/// (block velocities, hinges) and the gap.
#[test]
fn the_json_of_a_wall_has_the_general_bound() {
    let dir = tempfile::tempdir().expect("tempdir");
    let path = dir.path().join("wall.toml");
    std::fs::write(
        &path,
        "[blocks]\npolygons = [[[0,0],[1,0],[1,0.5],[0,0.5]], [[1,0],[2,0],[2,0.5],[1,0.5]], \
         [[0.5,0.5],[1.5,0.5],[1.5,1],[0.5,1]]]\n[material]\nfriction = 0.6\n",
    )
    .expect("scene");
    let out = common::voussoir()
        .arg("analyze")
        .arg(&path)
        .arg("--json")
        .assert()
        .success();
    let v: serde_json::Value = serde_json::from_slice(&out.get_output().stdout).expect("JSON");
    assert_eq!(v["kinematic_search"], "general");
    assert_eq!(v["kinematic_status"], "collapse");
    let (l, u) = (
        v["lambda_lower"].as_f64().expect("lower"),
        v["lambda_upper"].as_f64().expect("upper"),
    );
    assert!(rel(l, u) <= 1e-8, "{l} {u}");
    assert!(v["gap"].as_f64().expect("gap") <= 1e-8);
    assert_eq!(
        v["kinematic_mechanism"]
            .as_array()
            .expect("velocities")
            .len(),
        3
    );
    assert!(v["mechanism_sliding"].is_array());
    let hinges = v["mechanism_hinges"].as_array().expect("hinges").len();
    let open = v["open_joints"].as_array().expect("open").len();
    let sliding = v["mechanism_sliding"].as_array().expect("sliding").len();
    assert!(hinges + open + sliding > 0, "{v}");
}

/// The arcades of `[arcade]` / `[spandrel]` (issue 23): the general upper bound equals the
/// static one (1e-8) on the bundled 3-bay arcade with its spandrel wall (314 blocks), on 2 and
/// 4 bays, bare and walled, with infinite and finite friction, both directions; its mechanism
/// passes the virtual-work check of this file.
#[test]
fn general_equals_static_on_arcades_with_and_without_a_wall() {
    let text = std::fs::read_to_string(common::data("arcade.toml")).expect("bundled arcade");
    let bare: String = {
        let at = text.find("\n[spandrel]").expect("a [spandrel] table") + 1;
        let rest = &text[at..];
        let end = rest.find("\n[material]").expect("[material] after it");
        format!("{}{}", &text[..at], &rest[end + 1..])
    };
    for (name, scene_text) in [("walled", &text), ("bare", &bare)] {
        for (bays, mu) in [(3, "inf"), (2, "0.6"), (4, "inf")] {
            let s = common::scene(scene_text)
                .with_overrides(&[
                    format!("arcade.bays={bays}"),
                    format!("material.friction={mu}"),
                ])
                .expect("overrides");
            let model = voussoir::scene::build(&s).expect("model");
            for dir in [Direction::Right, Direction::Left] {
                let st = full_static(&model, dir);
                let k = general(&model, dir);
                let label = format!("{name} arcade of {bays} bays, mu {mu}, {dir:?}");
                assert_eq!(st.status, k.status, "{label}");
                let (ls, lk) = (
                    st.lambda.expect("static lambda"),
                    k.lambda_upper.expect("general lambda"),
                );
                assert!(rel(ls, lk) <= 1e-8, "{label}: static {ls} general {lk}");
                check_virtual_work(&model, &k, dir);
            }
        }
    }
}

/// Issue 28 item 4: a program whose KKT matrix has at least `statics::LARGE_KKT` rows (the
/// 1,008-block running-bond wall of the `general_kinematic` bench, 23,528) is solved without
/// Clarabel's iterative refinement by default. Its multiplier equals the refined solve's to
/// 1e-9 (relative), its forces balance every block to 1e-8 of the wall's weight, and it stays
/// below the general kinematic (upper) bound; below the size the default is the refined solve
/// itself, bit for bit.
#[test]
fn large_programs_without_refinement_keep_the_multiplier() {
    let refined = StaticSettings {
        refinement: statics::Refinement::Always,
        ..StaticSettings::default()
    };
    let model = Model::self_weight(rect_assembly(&running_bond(32, 31, 0.4, 0.2), 0.6));
    assert_eq!(model.assembly.blocks.len(), 1008);
    let objective = statics::Objective::MaxLambda {
        sign: 1.0,
        cap: None,
    };
    let p = statics::StaticProblem::new(&model.assembly, &model.loads, objective);
    assert!(p.a.n + p.a.m >= statics::LARGE_KKT, "{}", p.a.n + p.a.m);
    let auto = full_static(&model, Direction::Right);
    let always = statics::analyse_full(&model, &refined).expect("static");
    assert_eq!(auto.status, Status::Collapse);
    assert_eq!(always.status, Status::Collapse);
    let (la, lr) = (auto.lambda.expect("lambda"), always.lambda.expect("lambda"));
    assert!(rel(la, lr) <= 1e-9, "without refinement {la}, with {lr}");
    let weight: f64 = model.assembly.blocks.iter().map(|b| b.weight).sum();
    assert!(
        auto.equilibrium_residual <= 1e-8 * weight,
        "residual {} N of {weight} N",
        auto.equilibrium_residual
    );
    let upper = general(&model, Direction::Right)
        .lambda_upper
        .expect("upper bound");
    assert!(
        la <= upper * (1.0 + 1e-9),
        "static {la} above upper {upper}"
    );
    // Below the size nothing changes.
    let small = Model::self_weight(rect_assembly(&running_bond(10, 6, 0.4, 0.2), 0.6));
    let (a, b) = (
        full_static(&small, Direction::Right),
        statics::analyse_full(&small, &refined).expect("static"),
    );
    assert_eq!(a.lambda, b.lambda);
    assert_eq!(a.iterations, b.iterations);
}

/// The general kinematic program of a wall of 1,580 blocks (three unknowns per block, four
/// rows per joint of finite friction and the normalisation: more than `statics::LARGE_KKT`)
/// is solved without iterative refinement by default too: its certified multiplier equals the
/// refined solve's to 1e-9 (relative) and stays above the static (lower) bound.
#[test]
fn large_kinematic_programs_without_refinement_keep_the_multiplier() {
    let model = Model::self_weight(rect_assembly(&running_bond(40, 39, 0.4, 0.2), 0.6));
    let (nb, nj) = (model.assembly.blocks.len(), model.assembly.joints.len());
    assert_eq!(nb, 1580);
    assert!(
        3 * nb + 4 * nj + 1 >= statics::LARGE_KKT,
        "{nb} blocks, {nj} joints"
    );
    let auto = general(&model, Direction::Right);
    let refined = kinematic::analyse_general(
        &model,
        &KinematicSettings {
            refinement: statics::Refinement::Always,
            ..KinematicSettings::default()
        },
    )
    .expect("general kinematic program");
    let (la, lr) = (
        auto.lambda_upper.expect("upper bound"),
        refined.lambda_upper.expect("upper bound"),
    );
    assert!(rel(la, lr) <= 1e-9, "without refinement {la}, with {lr}");
    check_virtual_work(&model, &auto, Direction::Right);
    let lower = full_static(&model, Direction::Right)
        .lambda
        .expect("static bound");
    assert!(
        lower <= la * (1.0 + 1e-9),
        "static {lower} above upper {la}"
    );
}
