//! The user's own blocks (`[blocks]`): the parametric structures written out as block files
//! give the same answers; closed forms of single and stacked blocks; a wall that is not a
//! chain, static against DEM; bad files refused with clear errors; the example scenes.

use crate::common;

use std::path::{Path, PathBuf};
use voussoir::analysis::{self, KinematicMode, Options};
use voussoir::assembly::{Assembly, JointKind};
use voussoir::geometry::Vec2;
use voussoir::outcome::Direction;
use voussoir::scene::Scene;
use voussoir::statics::{self, StaticSettings, Status};

/// A JSON block file of the polygons of `assembly`, in its block order.
fn json_of(assembly: &Assembly) -> String {
    let polygons: Vec<Vec<[f64; 2]>> = assembly
        .blocks
        .iter()
        .map(|b| b.polygon.iter().map(|p| [p.x, p.y]).collect())
        .collect();
    serde_json::json!({ "polygons": polygons }).to_string()
}

use common::scene_in;

fn options(direction: Direction) -> Options {
    Options {
        static_settings: StaticSettings::default().direction(direction),
        kinematic: KinematicMode::Exhaustive,
        ..Options::default()
    }
}

fn close(a: f64, b: f64, tol: f64) -> bool {
    (a - b).abs() <= tol * a.abs().max(1.0)
}

/// The parametric scene and the same blocks read from a JSON file give the same lambda (both
/// bounds), hinges and mechanism, in both directions.
fn same_as_parametric(name: &str, parametric: &str, ground_y: f64) {
    let p = common::scene(parametric);
    let model = common::model_of(&p);
    let dir = tempfile::tempdir().expect("tempdir");
    // Everything but the structure: material, loads, seismic.
    let mut rest: toml::Table = parametric.parse().expect("TOML");
    rest.remove("arch");
    rest.remove("piers");
    let user = scene_in(
        dir.path(),
        &format!("[blocks]\nfile = \"blocks.json\"\nground_y = {ground_y}\n{rest}"),
        &[("blocks.json", json_of(&model.assembly).as_bytes())],
    )
    .unwrap_or_else(|e| panic!("{name}: {e}"));
    let b = user.blocks.as_ref().expect("a block scene");
    assert_eq!(
        b.detected.topology,
        voussoir::blocks::Topology::Chain,
        "{name}"
    );
    assert_eq!(
        b.detected.assembly.joints.len(),
        model.assembly.joints.len(),
        "{name}: joints found"
    );
    for dir in [Direction::Right, Direction::Left] {
        let a = analysis::analyse(&p, &options(dir)).expect("parametric analysis");
        let u = analysis::analyse(&user, &options(dir)).expect("block analysis");
        let (la, lu) = (
            a.lower.lambda.expect("lambda"),
            u.lower.lambda.expect("lambda"),
        );
        assert!(close(la, lu, 1e-10), "{name} {dir:?}: static {la} vs {lu}");
        assert_eq!(a.lower.hinges.len(), u.lower.hinges.len(), "{name}");
        for (h, g) in a.lower.hinges.iter().zip(&u.lower.hinges) {
            assert_eq!((h.joint, h.end), (g.joint, g.end), "{name} {dir:?}");
            assert!(
                (h.x - g.x).abs() < 1e-10 && (h.y - g.y).abs() < 1e-10,
                "{name}"
            );
        }
        let (ka, ku) = (
            a.upper.as_ref().expect("kinematic"),
            u.upper.as_ref().expect("kinematic on the user chain"),
        );
        let (ua, uu) = (
            ka.lambda_upper.expect("upper"),
            ku.lambda_upper.expect("upper"),
        );
        assert!(
            close(ua, uu, 1e-10),
            "{name} {dir:?}: kinematic {ua} vs {uu}"
        );
        assert!(close(la, ua, 1e-6), "{name}: static = kinematic");
        let (ma, mu) = (
            ka.mechanism.as_ref().expect("mechanism"),
            ku.mechanism.as_ref().expect("mechanism"),
        );
        assert_eq!(ma.family, mu.family, "{name}");
        assert_eq!(ma.open, mu.open, "{name}");
        let ends = |m: &voussoir::kinematic::Mechanism| {
            m.hinges
                .iter()
                .map(|h| (h.joint, h.end))
                .collect::<Vec<_>>()
        };
        assert_eq!(ends(ma), ends(mu), "{name} {dir:?}");
        for (va, vu) in ma.velocities.iter().zip(&mu.velocities) {
            for c in 0..3 {
                assert!(
                    (va[c] - vu[c]).abs() < 1e-10,
                    "{name}: velocities {va:?} {vu:?}"
                );
            }
        }
    }
}

#[test]
fn parametric_structures_written_as_blocks_give_the_same_answers() {
    same_as_parametric(
        "semicircle",
        "[arch]\nshape = \"circular\"\nradius = 1.0\nthickness = 0.15\nvoussoirs = 16\n",
        0.0,
    );
    same_as_parametric(
        "pointed",
        "[arch]\nshape = \"pointed\"\nradius = 1.0\neccentricity = 0.2\nthickness = 0.15\nvoussoirs = 14\n",
        0.0,
    );
    same_as_parametric(
        "basket",
        "[arch]\nshape = \"basket\"\nspan = 2.0\nrise = 0.7\nthickness = 0.15\nvoussoirs = 15\n",
        0.0,
    );
    same_as_parametric(
        "portal",
        "[arch]\nshape = \"circular\"\nradius = 1.0\nthickness = 0.2\nvoussoirs = 12\n\
         [piers]\nheight = 1.2\nwidth = 0.35\ncourses = 3\n[material]\nunit_weight = 22000\n",
        -1.2,
    );
    // A point load (on a block found by its point) and a line load (on the extrados and the
    // top of the structure) land on the same blocks with the same resultants.
    let loaded = std::fs::read_to_string(data("loaded_portal.toml")).expect("bundled scene");
    same_as_parametric("loaded portal", &loaded, -2.5);
}

/// `[fill]` over the user's blocks: the bundled filled arch written as blocks gives the
/// parametric scene's answers (both bounds, hinges, mechanism, both directions). With polygon
/// voussoirs: the blocks' extrados is the chord, so the parametric scene's curved extrados
/// (its fill follows the arc) is not what the blocks describe.
#[test]
fn fill_over_blocks_is_the_parametric_fill() {
    let filled = std::fs::read_to_string(data("filled_arch.toml")).expect("bundled scene");
    let polygon = filled.replace(
        "voussoir_shape = \"curved\"",
        "voussoir_shape = \"polygon\"",
    );
    assert_ne!(
        polygon, filled,
        "the bundled filled arch has curved voussoirs"
    );
    same_as_parametric("filled arch (polygon voussoirs)", &polygon, 0.0);
    // A single block under a fill up to 0.5 m above its top: the fill is a block of the same
    // width on it, so b/h of the combined weight about the toe: lambda = b / (h + 0.5) for the
    // same unit weight, both seismic masses.
    let dir = tempfile::tempdir().expect("tempdir");
    let s = scene_in(
        dir.path(),
        "[blocks]\npolygons = [[[0, 0], [0.4, 0], [0.4, 1.0], [0, 1.0]]]\n[material]\nunit_weight = 18000\n[fill]\nlevel = 1.5\nunit_weight = 18000\n",
        &[],
    )
    .expect("scene");
    let a = analysis::analyse(&s, &options(Direction::Right)).expect("analysis");
    let l = a.lower.lambda.expect("lambda");
    assert!((l - 0.4 / 1.5).abs() < 1e-9, "block under fill: {l}");
}

#[test]
fn a_single_rectangular_block_rocks_at_b_over_h() {
    let dir = tempfile::tempdir().expect("tempdir");
    for (b, h) in [(0.4, 1.0), (1.0, 0.25), (0.3, 2.7)] {
        let json = format!(
            "{{\"polygons\": [[[2, 1], [{0}, 1], [{0}, {1}], [2, {1}]]]}}",
            2.0 + b,
            1.0 + h
        );
        let s = scene_in(
            dir.path(),
            "[blocks]\nfile = \"one.json\"\nground_y = 1.0\n",
            &[("one.json", json.as_bytes())],
        )
        .expect("scene");
        for d in [Direction::Right, Direction::Left] {
            let a = analysis::analyse(&s, &options(d)).expect("analysis");
            let l = a.lower.lambda.expect("lambda");
            assert!((l - b / h).abs() < 1e-9, "{b} x {h}: {l}");
            let u = a.lambda_upper().expect("upper");
            assert!((u - b / h).abs() < 1e-9, "{b} x {h}: kinematic {u}");
        }
    }
}

/// The collapse multiplier of a column of blocks (one support) toward +x: the least, over its
/// joints, of `(x_end - x_G) / (y_G - y_joint)`, with `G` the centre of gravity of the blocks
/// above the joint and `x_end` the joint's right end (rocking about it; nothing can slide).
fn column_lambda(blocks: &[[f64; 4]], joints: &[(f64, f64)]) -> f64 {
    // blocks: [x0, y0, x1, y1] from the bottom; joints[k] = (y, right end x) under block k.
    let mut best = f64::INFINITY;
    for (k, &(y, x_end)) in joints.iter().enumerate() {
        let (mut w, mut mx, mut my) = (0.0, 0.0, 0.0);
        for r in &blocks[k..] {
            let a = (r[2] - r[0]) * (r[3] - r[1]);
            w += a;
            mx += a * 0.5 * (r[0] + r[2]);
            my += a * 0.5 * (r[1] + r[3]);
        }
        best = best.min((x_end - mx / w) / (my / w - y));
    }
    best
}

fn inline_scene(blocks: &[[f64; 4]]) -> Scene {
    common::scene(&format!(
        "[blocks]\nground_y = 0.0\npolygons = {}\n",
        common::rect_polygons(blocks)
    ))
}

#[test]
fn two_stacked_blocks_and_an_l_shaped_pair_give_their_hand_values() {
    // Two stacked blocks, the upper narrower and off-centre: it rocks on its own
    // (0.7 - 0.4) / (1.6 - 1) = 0.5, below the whole column's 0.5419 / 0.9605 = 0.564.
    // The same with a wide, low upper block: the whole column rocks, 0.5 / 0.65 = 0.769.
    // An L: a slab on the ground with a post standing on its left end: the post rocks on
    // the slab (0.25 / 1 = 0.25 toward +x); toward -x too (its left end, x = 0).
    let cases: [(&str, Vec<[f64; 4]>); 3] = [
        ("stacked", vec![[0.0, 0.0, 1.0, 1.0], [0.1, 1.0, 0.7, 2.2]]),
        (
            "stacked, low top",
            vec![[0.0, 0.0, 1.0, 1.0], [0.0, 1.0, 1.0, 1.3]],
        ),
        ("L", vec![[0.0, 0.0, 2.0, 0.5], [0.0, 0.5, 0.5, 2.5]]),
    ];
    let hand = [0.5, 0.5 / 0.65, 0.25];
    for ((name, blocks), expected) in cases.iter().zip(hand) {
        // Joints: the ground under block 0, then each block on the one below; right ends.
        let joints: Vec<(f64, f64)> = (0..blocks.len())
            .map(|k| {
                let x_end = if k == 0 {
                    blocks[0][2]
                } else {
                    blocks[k][2].min(blocks[k - 1][2])
                };
                (blocks[k][1], x_end)
            })
            .collect();
        let derived = column_lambda(blocks, &joints);
        assert!(
            (derived - expected).abs() < 1e-12,
            "{name}: {derived} vs {expected}"
        );
        let s = inline_scene(blocks);
        let a = analysis::analyse(&s, &options(Direction::Right)).expect("analysis");
        let l = a.lower.lambda.expect("lambda");
        assert!(
            (l - derived).abs() < 1e-9,
            "{name}: static {l} vs hand {derived}"
        );
        let u = a.lambda_upper().expect("kinematic on a column");
        assert!(
            (u - derived).abs() < 1e-9,
            "{name}: kinematic {u} vs hand {derived}"
        );
        // Toward -x the same formula on the mirror image.
        let mirrored: Vec<[f64; 4]> = blocks.iter().map(|r| [-r[2], r[1], -r[0], r[3]]).collect();
        let mj: Vec<(f64, f64)> = (0..mirrored.len())
            .map(|k| {
                let x_end = if k == 0 {
                    mirrored[0][2]
                } else {
                    mirrored[k][2].min(mirrored[k - 1][2])
                };
                (mirrored[k][1], x_end)
            })
            .collect();
        let left = column_lambda(&mirrored, &mj);
        let a = analysis::analyse(&s, &options(Direction::Left)).expect("analysis");
        let l = a.lower.lambda.expect("lambda");
        assert!(
            (l - left).abs() < 1e-9,
            "{name} left: static {l} vs hand {left}"
        );
    }
    // Stacked blocks given top first are renumbered from the support; the joint labels keep
    // the file's indices.
    let s = inline_scene(&[[0.1, 1.0, 0.7, 2.2], [0.0, 0.0, 1.0, 1.0]]);
    let m = common::model_of(&s);
    assert_eq!(m.assembly.joints[0].kind, JointKind::Between(1, None));
    assert_eq!(m.assembly.joints[1].kind, JointKind::Between(0, Some(1)));
}

/// A running-bond wall: three courses, the middle one offset by half a block.
fn wall() -> Scene {
    inline_scene(&common::running_bond_wall_rects())
}

#[test]
fn a_running_bond_wall_is_no_chain_and_the_dem_slides_its_head_joints_below_the_static_value() {
    let s = wall();
    let b = s.blocks.as_ref().expect("blocks");
    assert!(matches!(
        b.detected.topology,
        voussoir::blocks::Topology::Other(_)
    ));
    // 2 + 3 + 2 blocks: 1 + 2 + 1 head joints, 4 + 4 bed joints, 2 supports.
    assert_eq!(b.detected.assembly.joints.len() - b.detected.supports, 12);
    assert_eq!(b.detected.supports, 2);
    let a = analysis::analyse(&s, &options(Direction::Right)).expect("analysis");
    assert_eq!(a.lower.status, Status::Collapse);
    let lower = a.lower.lambda.expect("lambda");
    // Not a chain: the general kinematic program gives the upper bound (issue 23), equal to
    // the static one by duality.
    assert_eq!(
        a.kinematic_search,
        Some(voussoir::kinematic::Search::General)
    );
    let upper = a.lambda_upper().expect("general upper bound");
    assert!((upper - lower).abs() < 1e-8, "{upper} vs {lower}");
    assert!(
        !a.lower.mechanism.is_empty(),
        "the mechanism comes from the duals"
    );
    // Without sliding the wall rocks as one body about its right toe: b/h = 1.2/1.2.
    assert!((lower - 1.0).abs() < 1e-9, "{lower}");
    // The DEM is not the same joint law. With `friction = inf` the static program lets no
    // joint slide, not even a head joint that carries no compression; the DEM's contacts are
    // Coulomb's (infinite friction is simulated as `dem.infinite_friction` = 1000) and slide
    // without opening, so a joint without compression slides freely: the DEM solves the
    // non-associative problem (docs/friction.md). Its collapse is at most the associative
    // one (Radenkovic), and here well below it: the courses part along head joints.
    let r = analysis::dem(
        &s,
        &analysis::DemOptions {
            tolerance: 0.005,
            ..Default::default()
        },
        &mut |_| {},
    )
    .expect("DEM");
    let (lo, hi) = (
        r.result.lambda_stands.expect("stands"),
        r.result.lambda_collapses.expect("collapses"),
    );
    println!("wall: static {lower:.5}, DEM [{lo:.5}, {hi:.5}]");
    assert!(hi < 0.95 * lower, "DEM [{lo}, {hi}] vs static {lower}");
    let joints = &r.model.assembly.joints;
    assert!(!r.result.sliding.is_empty());
    assert!(
        r.result
            .sliding
            .iter()
            .all(|&j| joints[j].normal().y.abs() < 1e-9),
        "only head joints slide: {:?}",
        r.result.sliding
    );
    // The static program finds a non-associative collapse of the same law (mu = 1000, zero
    // dilatancy) lower still: non-associative problems have several solutions, and the
    // DEM's elastic start reaches another (measured, not a theorem: docs/dem.md).
    let coulomb = s
        .with_overrides(&["material.friction=1000"])
        .expect("friction 1000");
    let a = analysis::analyse(
        &coulomb,
        &Options {
            friction: analysis::FrictionMode::NonAssociative,
            ..options(Direction::Right)
        },
    )
    .expect("analysis");
    // No joint slides in the associative mechanism (the wall rocks as one body): the
    // associative collapse state is also a non-associative one, "exact" in the literature's
    // word, and still not the only one (docs/friction.md).
    assert!(a.friction().exact);
    assert!((a.lower.lambda.expect("collapse") - 1.0).abs() < 1e-9);
    let na = a.non_associative.as_ref().expect("forced");
    assert!(na.converged);
    let n = na.lambda.expect("converged");
    println!("wall, mu = 1000: non-associative {n:.5}");
    assert!(n < lo, "non-associative {n} vs DEM [{lo}, {hi}]");
}

/// A scene refused: the error's text.
fn refused(toml: &str, files: &[(&str, &[u8])]) -> String {
    let dir = tempfile::tempdir().expect("tempdir");
    // Refused when read, or when its model is built (a fill over no block top).
    let built = scene_in(dir.path(), toml, files)
        .and_then(|s| voussoir::scene::build(&s).map_err(|e| e.to_string()));
    match built {
        Ok(_) => panic!("accepted: {toml}"),
        Err(e) => e,
    }
}

fn dxf_of(polylines: &[(&[[f64; 2]], bool, &str)]) -> Vec<u8> {
    let mut d = dxf::Drawing::new();
    d.header.version = dxf::enums::AcadVersion::R2000;
    for (pts, closed, layer) in polylines {
        let mut e = dxf::entities::Entity::new(common::lwpolyline(pts, *closed));
        e.common.layer = layer.to_string();
        d.add_entity(e);
    }
    let mut out = Vec::new();
    d.save(&mut out).expect("DXF written");
    out
}

#[test]
fn bad_block_files_get_clear_errors() {
    let scene = |file: &str| format!("[blocks]\nfile = \"{file}\"\nground_y = 0\n");
    let sq = |x: f64, y: f64| {
        format!(
            "[[{x},{y}],[{},{y}],[{},{}],[{x},{}]]",
            x + 1.0,
            x + 1.0,
            y + 1.0,
            y + 1.0
        )
    };
    let json = |polys: &[String]| format!("{{\"polygons\": [{}]}}", polys.join(","));
    let open = dxf_of(&[(
        &[[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]],
        false,
        "0",
    )]);
    let closed = dxf_of(&[(
        &[[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]],
        true,
        "WALLS",
    )]);
    // (what, scene, files, words the error must contain)
    type Case<'a> = (&'a str, String, Vec<(&'a str, Vec<u8>)>, &'a [&'a str]);
    let cases: Vec<Case> = vec![
        (
            "overlap",
            scene("b.json"),
            vec![("b.json", json(&[sq(0.0, 0.0), sq(0.5, 0.0)]).into_bytes())],
            &["blocks 0 and 1 overlap", "around ("],
        ),
        (
            "gap",
            scene("b.json"),
            vec![("b.json", json(&[sq(0.0, 0.0), sq(0.0, 1.01)]).into_bytes())],
            &["block 1", "touches nothing", "(0.000000, 1.010000)"],
        ),
        (
            "single-point contact",
            scene("b.json"),
            vec![("b.json", json(&[sq(0.0, 0.0), sq(1.0, 1.0)]).into_bytes())],
            &["block 1", "only at the point (1.000000, 1.000000)"],
        ),
        (
            "open polyline",
            scene("b.dxf"),
            vec![("b.dxf", open)],
            &["block 0", "is open", "closed polyline"],
        ),
        (
            "DXF layer without blocks",
            format!("{}layer = \"BLOCKS\"\n", scene("b.dxf")),
            vec![("b.dxf", closed)],
            &["no LWPOLYLINE", "layer `BLOCKS`", "WALLS"],
        ),
        (
            "empty JSON file",
            scene("b.json"),
            vec![("b.json", Vec::new())],
            &["b.json", "not a block file"],
        ),
        (
            "empty CSV file",
            scene("b.csv"),
            vec![("b.csv", Vec::new())],
            &["holds no polygon"],
        ),
        (
            "empty polygon list",
            scene("b.json"),
            vec![("b.json", b"{\"polygons\": []}".to_vec())],
            &["no blocks", "holds no polygon"],
        ),
        (
            "NaN",
            scene("b.csv"),
            vec![("b.csv", b"block,x,y\n0,0,0\n0,1,0\n0,NaN,1\n".to_vec())],
            &["block 0", "vertex 2 is (NaN, 1)", "finite"],
        ),
        (
            "NaN in JSON",
            scene("b.json"),
            vec![(
                "b.json",
                b"{\"polygons\": [[[0,0],[1,0],[NaN,1]]]}".to_vec(),
            )],
            &["not a block file", "line 1"],
        ),
        (
            "wrong units",
            format!("{}units = \"inch\"\n", scene("b.json")),
            vec![("b.json", json(&[sq(0.0, 0.0)]).into_bytes())],
            &["blocks.units", "\"inch\"", "\"mm\""],
        ),
        (
            "misspelt units key",
            format!("{}unit = \"mm\"\n", scene("b.json")),
            vec![("b.json", json(&[sq(0.0, 0.0)]).into_bytes())],
            &["unknown key `blocks.unit`", "did you mean `units`"],
        ),
        (
            "self-intersecting",
            scene("b.json"),
            vec![(
                "b.json",
                b"{\"polygons\": [[[0,0],[1,1],[1,0],[0,1]]]}".to_vec(),
            )],
            &["block 0", "intersects itself", "(0.500000, 0.500000)"],
        ),
        (
            "non-convex",
            scene("b.json"),
            vec![(
                "b.json",
                b"{\"polygons\": [[[0,0],[2,0],[2,2],[1,1],[0,2]]]}".to_vec(),
            )],
            &["block 0", "not convex", "(1.000000, 1.000000)"],
        ),
        (
            "not reaching the ground",
            "[blocks]\nfile = \"b.json\"\nground_y = -1\n".to_string(),
            vec![("b.json", json(&[sq(0.0, 0.0), sq(0.0, 1.0)]).into_bytes())],
            &["does not reach the ground y = -1", "blocks 0, 1", "y = 0"],
        ),
        (
            "below the ground",
            "[blocks]\nfile = \"b.json\"\nground_y = 0.5\n".to_string(),
            vec![("b.json", json(&[sq(0.0, 0.0)]).into_bytes())],
            &["block 0", "below the ground y = 0.5"],
        ),
        (
            "open CSV block",
            scene("b.csv"),
            vec![("b.csv", b"a,0,0\na,1,0\n".to_vec())],
            &["block 0", "2 distinct vertices"],
        ),
        (
            "missing file",
            scene("nothing.json"),
            vec![],
            &["cannot read", "nothing.json"],
        ),
        (
            "unknown file type",
            scene("b.svg"),
            vec![("b.svg", b"<svg/>".to_vec())],
            &["extension must be .json, .csv or .dxf"],
        ),
        (
            "fill below every block top",
            format!("{}[fill]\nlevel = -2.0\n", scene("b.json")),
            vec![("b.json", json(&[sq(0.0, 0.0)]).into_bytes())],
            &["fill.level", "above the top of some block"],
        ),
        (
            "both file and polygons",
            format!("{}polygons = [[[0,0],[1,0],[0,1]]]\n", scene("b.json")),
            vec![("b.json", json(&[sq(0.0, 0.0)]).into_bytes())],
            &["either `file` or `polygons`"],
        ),
    ];
    for (name, toml, files, words) in &cases {
        let files: Vec<(&str, &[u8])> = files.iter().map(|(n, b)| (*n, b.as_slice())).collect();
        let e = refused(toml, &files);
        for w in *words {
            assert!(e.contains(w), "{name}: `{w}` not in: {e}");
        }
    }
}

#[test]
fn a_billion_vertices_are_refused_before_reading() {
    // A sparse file as long as a billion vertices of text: refused by its size, unread.
    let dir = tempfile::tempdir().expect("tempdir");
    for ext in ["json", "csv", "dxf"] {
        let path = dir.path().join(format!("huge.{ext}"));
        let f = std::fs::File::create(&path).expect("file");
        f.set_len(16_000_000_000).expect("sparse file");
        let e = scene_in(
            dir.path(),
            &format!("[blocks]\nfile = \"huge.{ext}\"\n"),
            &[],
        )
        .expect_err("a huge file");
        assert!(
            e.contains("16000000000 bytes is more than the 67108864"),
            "{ext}: {e}"
        );
    }
    // Inline: the count is checked before the polygons are copied.
    let too_many = voussoir::blocks::MAX_BLOCKS + 1;
    let poly = "[[0,0],[1,0],[0,1]]";
    let text = format!(
        "[blocks]\npolygons = [{}]\n",
        vec![poly; too_many].join(",")
    );
    let e = Scene::from_toml_str(&text, "t").expect_err("too many");
    assert!(e.to_string().contains("at most 100000 blocks"), "{e}");
}

#[test]
fn units_and_renumbering_do_not_change_lambda() {
    let dir = tempfile::tempdir().expect("tempdir");
    let p = common::scene(
        "[arch]\nshape = \"circular\"\nradius = 1.0\nthickness = 0.15\nvoussoirs = 10\n\
         [piers]\nheight = 1.0\nwidth = 0.3\ncourses = 2\n",
    );
    let model = common::model_of(&p);
    let reference = statics::analyse(&model, &StaticSettings::default())
        .expect("static")
        .lambda
        .expect("lambda");
    // Millimetres, CSV, blocks shuffled, outlines clockwise.
    let n = model.assembly.blocks.len();
    let mut csv = String::from("block,x,y\n");
    for k in 0..n {
        let i = (k * 5) % n;
        for q in model.assembly.blocks[i].polygon.iter().rev() {
            csv.push_str(&format!("b{i},{},{}\n", q.x * 1000.0, q.y * 1000.0));
        }
    }
    let s = scene_in(
        dir.path(),
        "[blocks]\nfile = \"b.csv\"\nunits = \"mm\"\nground_y = -1000\n",
        &[("b.csv", csv.as_bytes())],
    )
    .expect("scene");
    let a = analysis::analyse(&s, &options(Direction::Right)).expect("analysis");
    let l = a.lower.lambda.expect("lambda");
    assert!(close(l, reference, 1e-9), "{l} vs {reference}");
}

#[test]
fn loads_apply_to_user_blocks() {
    // A 1 x 1 block with a point load of its own weight on its left edge, and a line load
    // over its top: resultant moments by hand.
    let s = common::scene(
        "[blocks]\npolygons = [[[0,0],[1,0],[1,1],[0,1]]]\n[material]\nunit_weight = 1000\n\
         [[loads]]\ntype = \"point\"\nat = [0.0, 1.0]\nforce = [0.0, -1000.0]\nseismic = false\n",
    );
    // Weight 1000 at x = 0.5 and 1000 at x = 0: G = 0.25; rocking right about x = 1:
    // lambda W_s y_s = W_tot (1 - x_G): 1000 * 0.5 * lambda = 2000 * 0.75.
    let a = analysis::analyse(&s, &options(Direction::Right)).expect("analysis");
    let l = a.lower.lambda.expect("lambda");
    assert!((l - 3.0).abs() < 1e-9, "{l}");
    let s = common::scene(
        "[blocks]\npolygons = [[[0,0],[1,0],[1,1],[0,1]], [[1,0],[2,0],[2,2],[1,2]]]\n\
         [[loads]]\ntype = \"line\"\nfrom_x = 0.5\nto_x = 2.0\nintensity = 5000\n",
    );
    let m = common::model_of(&s);
    // 0.5 m over the low block (at y = 1), 1 m over the tall one (at y = 2), seismic.
    let applied: Vec<_> = m
        .loads
        .applied()
        .iter()
        .filter(|l| l.source == voussoir::model::LoadSource::Load(0))
        .collect();
    assert_eq!(applied.len(), 2);
    let on = |b: usize| applied.iter().find(|l| l.block == b).expect("load");
    assert!((on(0).force.y + 2500.0).abs() < 1e-9 && (on(0).point.y - 1.0).abs() < 1e-12);
    assert!((on(1).force.y + 5000.0).abs() < 1e-9 && (on(1).point.y - 2.0).abs() < 1e-12);
    assert!((m.loads.seismic_weight() - m.assembly.total_weight() - 7500.0).abs() < 1e-6);
}

// ---- The example scenes under data/ ----

fn data(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("data")
        .join(name)
}

/// The example block files, as this test writes them (`VOUSSOIR_WRITE_EXAMPLES=1` writes them
/// into data/blocks/; otherwise the committed files must read back to the same polygons).
fn examples() -> Vec<(&'static str, Vec<u8>)> {
    vec![
        (
            "blocks/surveyed_portal.json",
            surveyed_portal().into_bytes(),
        ),
        (
            "blocks/stepped_buttresses.json",
            stepped_buttresses().into_bytes(),
        ),
        ("blocks/pointed_arch.dxf", pointed_arch_dxf()),
    ]
}

/// Round to the millimetre, as a survey gives.
fn mm(x: f64) -> f64 {
    (x * 1000.0).round() / 1000.0
}

/// An asymmetric portal: unequal piers (springings at 2.0 m and 2.3 m), irregular voussoirs
/// of varying thickness and joint angles, coordinates to the millimetre.
fn surveyed_portal() -> String {
    let n = 11;
    let (xl, yl, xr, yr) = (-2.0, 2.0, 2.05, 2.3);
    let mut joints = Vec::new();
    for j in 0..=n {
        let s = j as f64 / n as f64;
        // Centreline: a half-ellipse between the springings, rise 1.9 m above the lower one.
        let theta = std::f64::consts::PI * (1.0 - s) + 0.03 * (7.0 * s).sin();
        let theta = if j == 0 || j == n {
            std::f64::consts::PI * (1.0 - s)
        } else {
            theta
        };
        let cx = 0.5 * (xl + xr);
        let a = 0.5 * (xr - xl);
        let base = yl + (yr - yl) * s;
        let c = Vec2::new(cx + a * theta.cos(), base + 1.9 * theta.sin());
        let t = 0.42 + 0.05 * (3.1 * j as f64).sin();
        // Joint direction: along the ellipse's normal, tilted a little; horizontal at the
        // springings.
        let nrm = Vec2::new(theta.cos() / a, theta.sin() / 1.9).normalize();
        let tilt = if j == 0 || j == n {
            0.0
        } else {
            0.06 * (5.3 * j as f64).cos()
        };
        let d = Vec2::new(
            nrm.x * tilt.cos() - nrm.y * tilt.sin(),
            nrm.x * tilt.sin() + nrm.y * tilt.cos(),
        );
        let d = if j == 0 || j == n {
            Vec2::new(d.x.signum(), 0.0)
        } else {
            d
        };
        let (i, e) = (c - 0.5 * t * d, c + 0.5 * t * d);
        joints.push(([mm(i.x), mm(i.y)], [mm(e.x), mm(e.y)]));
    }
    let mut polys: Vec<Vec<[f64; 2]>> = Vec::new();
    // Left pier: three courses to the springing at y = 2.0, 0.85 m wide.
    let (li, le) = joints[0];
    let (ri, re) = joints[n];
    let left_x = (le[0] - 0.25, li[0]);
    for (y0, y1) in [(0.0, 0.72), (0.72, 1.38), (1.38, 2.0)] {
        polys.push(vec![
            [mm(left_x.0), y0],
            [left_x.1, y0],
            [left_x.1, y1],
            [mm(left_x.0), y1],
        ]);
    }
    for j in 0..n {
        let (a, b) = (joints[j], joints[j + 1]);
        polys.push(vec![a.0, b.0, b.1, a.1]);
    }
    // Right pier: four courses to the springing at y = 2.3, 0.95 m wide, listed top down.
    let right_x = (ri[0], mm(re[0] + 0.3));
    for (y0, y1) in [(1.74, 2.3), (1.1, 1.74), (0.55, 1.1), (0.0, 0.55)] {
        polys.push(vec![
            [right_x.0, y0],
            [right_x.1, y0],
            [right_x.1, y1],
            [right_x.0, y1],
        ]);
    }
    let _ = (yl, yr);
    serde_json::to_string_pretty(&serde_json::json!({ "polygons": polys })).unwrap_or_default()
}

/// A semicircular portal (R = 2 m, t = 0.4 m, 12 voussoirs) on buttresses of three courses
/// that step back outward: 1.4, 1.1 and 0.8 m wide, inner faces flush.
fn stepped_buttresses() -> String {
    let p = common::scene(
        "[arch]\nshape = \"circular\"\nradius = 2.0\nthickness = 0.4\nvoussoirs = 12\n",
    );
    let m = common::model_of(&p);
    let mut polys: Vec<Vec<[f64; 2]>> = Vec::new();
    let xi = 1.8; // the intrados at the springing
    let steps = [(0.0, 1.0, 1.4), (1.0, 2.0, 1.1), (2.0, 3.0, 0.8)];
    for &(y0, y1, w) in &steps {
        polys.push(vec![
            [-xi - w, y0 - 3.0],
            [-xi, y0 - 3.0],
            [-xi, y1 - 3.0],
            [-xi - w, y1 - 3.0],
        ]);
    }
    for b in &m.assembly.blocks {
        polys.push(b.polygon.iter().map(|q| [q.x, q.y]).collect());
    }
    for &(y0, y1, w) in steps.iter().rev() {
        polys.push(vec![
            [xi, y0 - 3.0],
            [xi + w, y0 - 3.0],
            [xi + w, y1 - 3.0],
            [xi, y1 - 3.0],
        ]);
    }
    serde_json::to_string_pretty(&serde_json::json!({ "polygons": polys })).unwrap_or_default()
}

/// A pointed arch (R = 3 m, e = 0.6 m, t = 0.45 m, 12 voussoirs) drawn in millimetres on
/// layer BLOCKS, with its axes on layer AXES (which the scene leaves out).
fn pointed_arch_dxf() -> Vec<u8> {
    let p = common::scene(
        "[arch]\nshape = \"pointed\"\nradius = 3.0\neccentricity = 0.6\nthickness = 0.45\nvoussoirs = 12\n",
    );
    let m = common::model_of(&p);
    let polys: Vec<Vec<[f64; 2]>> = m
        .assembly
        .blocks
        .iter()
        .map(|b| {
            b.polygon
                .iter()
                .map(|q| [q.x * 1000.0, q.y * 1000.0])
                .collect()
        })
        .collect();
    let axes: Vec<[f64; 2]> = vec![[-4000.0, 0.0], [4000.0, 0.0], [0.0, 4000.0]];
    let mut list: Vec<(&[[f64; 2]], bool, &str)> = polys
        .iter()
        .map(|p| (p.as_slice(), true, "BLOCKS"))
        .collect();
    list.push((axes.as_slice(), false, "AXES"));
    dxf_of(&list)
}

#[test]
fn example_block_files_are_current_and_analyse() {
    let write = std::env::var_os("VOUSSOIR_WRITE_EXAMPLES").is_some();
    let dir = tempfile::tempdir().expect("tempdir");
    for (name, bytes) in examples() {
        if write {
            std::fs::write(data(name), &bytes).expect("example written");
        }
        // The committed file and a fresh one read to the same polygons.
        let fresh = dir.path().join(Path::new(name).file_name().expect("name"));
        std::fs::write(&fresh, &bytes).expect("fresh copy");
        let units = if name.ends_with(".dxf") {
            voussoir::blocks::Units::Millimetres
        } else {
            voussoir::blocks::Units::Metres
        };
        let layer = name.ends_with(".dxf").then_some("BLOCKS");
        let a = voussoir::blocks::read_file(&data(name), units, layer).expect("committed file");
        let b = voussoir::blocks::read_file(&fresh, units, layer).expect("fresh file");
        assert_eq!(
            a, b,
            "{name} is not what this test writes (VOUSSOIR_WRITE_EXAMPLES=1)"
        );
    }
    for (scene, blocks, chain) in [
        ("blocks_surveyed_portal.toml", 18, true),
        ("blocks_stepped_buttresses.toml", 18, true),
        ("blocks_dxf_arch.toml", 12, true),
    ] {
        let s = Scene::from_file(&data(scene)).expect("example scene");
        let b = s.blocks.as_ref().expect("blocks");
        assert_eq!(b.detected.assembly.blocks.len(), blocks, "{scene}");
        assert_eq!(
            b.detected.topology == voussoir::blocks::Topology::Chain,
            chain
        );
        for d in [Direction::Right, Direction::Left] {
            let a = analysis::analyse(&s, &options(d)).expect("analysis");
            let (l, u) = (
                a.lower.lambda.expect("lambda"),
                a.lambda_upper().expect("upper"),
            );
            assert!(close(l, u, 1e-6), "{scene} {d:?}: {l} vs {u}");
        }
    }
    // The DXF arch is the parametric pointed arch, drawn in millimetres.
    let s = Scene::from_file(&data("blocks_dxf_arch.toml")).expect("scene");
    let p = common::scene(
        "[arch]\nshape = \"pointed\"\nradius = 3.0\neccentricity = 0.6\nthickness = 0.45\nvoussoirs = 12\n\
         [[loads]]\ntype = \"line\"\nfrom_x = -0.3\nto_x = 0.3\nintensity = 20000\n",
    );
    let ls = statics::analyse(&common::model_of(&s), &StaticSettings::default()).expect("static");
    let lp_ = statics::analyse(&common::model_of(&p), &StaticSettings::default()).expect("static");
    let (a, b) = (ls.lambda.expect("lambda"), lp_.lambda.expect("lambda"));
    assert!(close(a, b, 1e-9), "DXF arch {a} vs parametric {b}");
}

#[test]
fn the_cli_counts_the_joints_and_refuses_what_needs_an_arch() {
    let scene = data("blocks_stepped_buttresses.toml");
    let out = common::voussoir()
        .arg("analyze")
        .arg(&scene)
        .assert()
        .success();
    let text = String::from_utf8_lossy(&out.get_output().stdout).to_string();
    assert!(
        text.contains("17 joints found between blocks and 2 supports"),
        "{text}"
    );
    assert!(text.contains("(blocks 3|4), end p1"), "{text}");
    let out = common::voussoir()
        .arg("analyze")
        .arg(&scene)
        .arg("--json")
        .assert()
        .success();
    let v: serde_json::Value =
        serde_json::from_slice(&out.get_output().stdout).expect("JSON report");
    assert_eq!(v["scene"]["shape"], "blocks");
    assert_eq!(v["scene"]["blocks"]["joints"], 17);
    assert_eq!(v["scene"]["blocks"]["chain"], true);
    assert_eq!(v["joints"][4]["kind"]["between"], serde_json::json!([3, 4]));
    let out = common::voussoir()
        .arg("min-thickness")
        .arg(&scene)
        .assert()
        .failure();
    let err = String::from_utf8_lossy(&out.get_output().stderr).to_string();
    assert!(
        err.contains("the minimum-thickness search needs a parametric structure"),
        "{err}"
    );
    // A wall: no chain, said plainly; the DEM runs.
    let dir = tempfile::tempdir().expect("tempdir");
    let path = dir.path().join("wall.toml");
    std::fs::write(
        &path,
        "[blocks]\npolygons = [[[0,0],[1,0],[1,0.5],[0,0.5]], [[1,0],[2,0],[2,0.5],[1,0.5]], \
         [[0.5,0.5],[1.5,0.5],[1.5,1],[0.5,1]]]\n",
    )
    .expect("scene");
    let out = common::voussoir()
        .arg("analyze")
        .arg(&path)
        .assert()
        .success();
    let text = String::from_utf8_lossy(&out.get_output().stdout).to_string();
    assert!(
        text.contains("not a chain: block 0 has 3 joints (with 1, 2, ground)")
            && text.contains("the general kinematic program"),
        "{text}"
    );
}

mod random {
    use proptest::prelude::*;

    /// A coordinate: mostly on a coarse grid (so blocks touch, share edges and overlap), now
    /// and then anything, including NaN, infinities and huge values.
    fn coordinate() -> impl Strategy<Value = f64> {
        prop_oneof![
            8 => (0i32..6).prop_map(|k| f64::from(k) * 0.5),
            1 => any::<f64>(),
            1 => prop::sample::select(vec![f64::NAN, f64::INFINITY, -1e300, 1e-300, 0.25]),
        ]
    }

    /// An outline: any vertices, or a rectangle on the grid (which makes stacks, walls,
    /// overlaps and corner contacts common).
    fn outline() -> impl Strategy<Value = Vec<[f64; 2]>> {
        prop_oneof![
            prop::collection::vec((coordinate(), coordinate()).prop_map(|(x, y)| [x, y]), 0..7),
            (0i32..4, 0i32..4, 1i32..3, 1i32..3).prop_map(|(x, y, w, h)| {
                let (x0, y0, x1, y1) = (x as f64, y as f64, (x + w) as f64, (y + h) as f64);
                vec![[x0, y0], [x1, y0], [x1, y1], [x0, y1]]
            }),
        ]
    }

    fn polygons() -> impl Strategy<Value = Vec<Vec<[f64; 2]>>> {
        prop::collection::vec(outline(), 0..7)
    }

    proptest! {
        #![proptest_config(ProptestConfig { cases: 2_000, failure_persistence: None, ..ProptestConfig::default() })]

        /// Any polygons are read and joined, or refused with an error: never a panic, and a
        /// structure found is a valid assembly.
        #[test]
        fn random_blocks_never_panic(raw in polygons(), ground in prop::option::of(coordinate())) {
            let Ok(polys) = voussoir::blocks::from_vertices(raw, voussoir::blocks::Units::Metres) else {
                return Ok(());
            };
            if let Ok(d) = voussoir::blocks::detect(&polys, ground.filter(|g| g.is_finite()), 1e-6, 1.0, f64::INFINITY) {
                prop_assert!(d.assembly.validate().is_ok(), "{:?}", d.assembly.validate());
            }
        }
    }
}

#[test]
fn dxf_polylines_of_both_kinds_on_a_layer_are_blocks() {
    // An old-style POLYLINE (a block 0.4 x 1.0 on the ground, in millimetres) and an
    // LWPOLYLINE on another layer: with `layer`, only the POLYLINE is read.
    let mut d = dxf::Drawing::new();
    d.header.version = dxf::enums::AcadVersion::R2000;
    let mut p = dxf::entities::Polyline::default();
    p.set_is_closed(true);
    for (x, y) in [(0.0, 0.0), (400.0, 0.0), (400.0, 1000.0), (0.0, 1000.0)] {
        p.add_vertex(
            &mut d,
            dxf::entities::Vertex::new(dxf::Point::new(x, y, 0.0)),
        );
    }
    let mut e = dxf::entities::Entity::new(dxf::entities::EntityType::Polyline(p));
    e.common.layer = "Stones".into();
    d.add_entity(e);
    // A triangle leaning on it, on layer Notes: it would make the block no column.
    let mut e = dxf::entities::Entity::new(common::lwpolyline(
        &[[0.0, 1000.0], [400.0, 1000.0], [0.0, 2000.0]],
        true,
    ));
    e.common.layer = "Notes".into();
    d.add_entity(e);
    let mut bytes = Vec::new();
    d.save(&mut bytes).expect("DXF");
    let dir = tempfile::tempdir().expect("tempdir");
    let all = scene_in(
        dir.path(),
        "[blocks]\nfile = \"b.dxf\"\nunits = \"mm\"\n",
        &[("b.dxf", bytes.as_slice())],
    )
    .expect("scene");
    assert_eq!(all.blocks.as_ref().expect("blocks").polygons.len(), 2);
    let s = scene_in(
        dir.path(),
        "[blocks]\nfile = \"b.dxf\"\nunits = \"mm\"\nlayer = \"stones\"\n",
        &[("b.dxf", bytes.as_slice())],
    )
    .expect("scene");
    let a = analysis::analyse(&s, &options(Direction::Right)).expect("analysis");
    assert!((a.lower.lambda.expect("lambda") - 0.4).abs() < 1e-9);
    // The layer is matched without regard to case; a JSON file has no layers.
    let e = scene_in(
        dir.path(),
        "[blocks]\nfile = \"b.json\"\nlayer = \"stones\"\n",
        &[("b.json", b"{\"polygons\": [[[0,0],[1,0],[0,1]]]}")],
    )
    .expect_err("layer on JSON");
    assert!(e.contains("only a .dxf block file has layers"), "{e}");
}

#[test]
fn errors_name_the_blocks_file_and_where_the_blocks_lie_in_it() {
    let scene = |file: &str| format!("[blocks]\nfile = \"{file}\"\n");
    // CSV: the lines and label of each block named (a comment line counts as a line).
    let csv = "block,x,y\n# the base\na,0,0\na,1,0\na,1,1\na,0,1\nb,0.5,0.5\nb,1.5,0.5\nb,1.5,1.5\nb,0.5,1.5\n";
    let e = refused(&scene("walls.csv"), &[("walls.csv", csv.as_bytes())]);
    assert!(e.contains("walls.csv: blocks 0 and 1 overlap"), "{e}");
    assert!(
        e.contains("block 0 is lines 3-6, label `a`; block 1 is lines 7-10, label `b`"),
        "{e}"
    );
    // JSON: the index in the list; the file is named, not only the scene.
    let json =
        r#"{"polygons": [[[0,0],[1,0],[1,1],[0,1]], [[0,1],[1,1],[0.5,2],[0.6,1.5],[0.4,1.5]]]}"#;
    let e = refused(&scene("walls.json"), &[("walls.json", json.as_bytes())]);
    assert!(e.contains("walls.json: block 1: it is not convex"), "{e}");
    assert!(e.contains("(block 1 is polygons[1])"), "{e}");
    // DXF: the entity's handle and layer.
    let dxf = dxf_of(&[
        (
            &[[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]],
            true,
            "WALLS",
        ),
        (
            &[[0.5, 0.5], [1.5, 0.5], [1.5, 1.5], [0.5, 1.5]],
            true,
            "WALLS",
        ),
    ]);
    let e = refused(&scene("walls.dxf"), &[("walls.dxf", &dxf)]);
    assert!(e.contains("walls.dxf: blocks 0 and 1 overlap"), "{e}");
    assert!(
        e.contains("block 0 is handle") && e.contains("layer `WALLS`"),
        "{e}"
    );
}

#[test]
fn a_byte_order_mark_is_accepted_in_every_block_format() {
    let dir = tempfile::tempdir().expect("tempdir");
    let json = br#"{"polygons": [[[0,0],[1,0],[1,1],[0,1]], [[0,1],[1,1],[1,2],[0,2]]]}"#;
    let csv = b"block,x,y\na,0,0\na,1,0\na,1,1\na,0,1\nb,0,1\nb,1,1\nb,1,2\nb,0,2\n";
    let bom = |b: &[u8]| [b"\xef\xbb\xbf".as_slice(), b].concat();
    let lambda = |scene: Scene| {
        statics::analyse(&scene.model().expect("model"), &StaticSettings::default())
            .expect("static")
            .lambda
    };
    for (name, bytes) in [("c.json", json.as_slice()), ("c.csv", csv.as_slice())] {
        let plain = scene_in(
            dir.path(),
            &format!("[blocks]\nfile = \"{name}\"\n"),
            &[(name, bytes)],
        )
        .expect("plain file");
        let with_bom = scene_in(
            dir.path(),
            &format!("\u{feff}[blocks]\nfile = \"{name}\"\n"),
            &[(name, &bom(bytes))],
        )
        .unwrap_or_else(|e| panic!("{name} with a BOM: {e}"));
        assert_eq!(lambda(with_bom), lambda(plain), "{name}");
    }
}
