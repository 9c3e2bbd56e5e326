//! Fixed blocks of any shape (`[blocks] fixed`) and drawings as CAD writes them (issue 23,
//! items 1 and 2).
//!
//! The structure: a segmental arch (centreline radius 2 m, thickness 0.45 m, springing 20 deg
//! above the horizontal, 9 voussoirs) whose springers sit on inclined skewbacks cut into one
//! non-convex fixed base (a plinth with two abutments, a U). On plain skewbacks each springer
//! rests on one inclined face and the arch is a chain between two supports; in a stepped
//! notch each springer also leans its back (its extrados face) on the abutment, so it rests on
//! two faces and the structure is no chain. Each is compared with the same voussoirs built by
//! hand (`Assembly` written out here, supports on the very faces the base offers): the
//! detection must find exactly those faces, so the static multipliers agree to 1e-9. The DEM
//! brackets the chain's multiplier; the order of the blocks and the units (mm against m) leave
//! it unchanged; a wall on an L-shaped fixed block and the ground together give the rocking
//! block's closed form; bad fixed points are refused naming `blocks.fixed[k]`.
//!
//! Item 2: the same arch drawn as CAD writes it (open polylines that repeat their first vertex,
//! clockwise outlines, repeated vertices, POLYLINE and LWPOLYLINE entities) reads to the very
//! polygons of the clean drawing and gives its lambda exactly; the mending is reported; an
//! outline that crosses itself is refused naming the block and the two edges.

use crate::common;

use std::f64::consts::PI;
use voussoir::assembly::{Assembly, Block, BlockKind, Joint, JointKind};
use voussoir::geometry::{polygon_area_centroid, Vec2};
use voussoir::model::Model;
use voussoir::outcome::Direction;
use voussoir::scene::Scene;
use voussoir::statics::{self, StaticSettings, Status};

const RADIUS: f64 = 2.0;
const THICKNESS: f64 = 0.45;
const SPRINGING_DEG: f64 = 20.0;
const VOUSSOIRS: usize = 9;
const UNIT_WEIGHT: f64 = 20000.0;
const FRICTION: f64 = 0.7;

/// The material of every scene here.
fn material() -> String {
    format!("[material]\nunit_weight = {UNIT_WEIGHT}\ndepth = 1.0\nfriction = {FRICTION}\n")
}

/// Joint j of the arch, numbered from the left springing: (intrados, extrados) points.
fn joint(j: usize) -> (Vec2, Vec2) {
    let phi0 = SPRINGING_DEG.to_radians();
    let phi = PI - phi0 - j as f64 * (PI - 2.0 * phi0) / VOUSSOIRS as f64;
    let u = Vec2::new(phi.cos(), phi.sin());
    (
        (RADIUS - 0.5 * THICKNESS) * u,
        (RADIUS + 0.5 * THICKNESS) * u,
    )
}

/// The voussoirs, left to right, counter-clockwise.
fn voussoirs() -> Vec<Vec<Vec2>> {
    (0..VOUSSOIRS)
        .map(|j| {
            let ((a, b), (c, d)) = (joint(j), joint(j + 1));
            vec![a, c, d, b]
        })
        .collect()
}

/// The fixed base, counter-clockwise: a plinth 6 m wide from y = -1 to 0 and two abutments
/// whose tops are the skewbacks (the springing joints); `stepped`: each abutment rises on along
/// its springer's back to the springer's upper extrados corner (a notch).
fn base(stepped: bool) -> Vec<Vec2> {
    let (il, el) = joint(0);
    let (ir, er) = joint(VOUSSOIRS);
    let (e1l, e1r) = (joint(1).1, joint(VOUSSOIRS - 1).1);
    let (topl, topr) = if stepped {
        (e1l.y, e1r.y)
    } else {
        (el.y, er.y)
    };
    let mut b = vec![
        Vec2::new(-3.0, -1.0),
        Vec2::new(3.0, -1.0),
        Vec2::new(3.0, topr),
    ];
    if stepped {
        b.push(e1r);
    }
    b.extend([er, ir, Vec2::new(ir.x, 0.0), Vec2::new(il.x, 0.0), il, el]);
    if stepped {
        b.push(e1l);
    }
    b.push(Vec2::new(-3.0, topl));
    b
}

fn xy(p: &[Vec2], scale: f64) -> Vec<[f64; 2]> {
    p.iter().map(|q| [q.x * scale, q.y * scale]).collect()
}

/// A point inside the base (in the base's units at `scale`): the middle of the plinth.
fn base_point(scale: f64) -> [f64; 2] {
    [0.0, -0.5 * scale]
}

/// A support joint of `block` on the face `p`-`q`, oriented so that its normal points into
/// the block.
fn support(p: Vec2, q: Vec2, block: usize, blocks: &[Block]) -> Joint {
    let mut j = Joint {
        p1: p,
        p2: q,
        from: None,
        to: Some(block),
        friction: FRICTION,
        kind: JointKind::Other,
    };
    if (blocks[block].centroid - j.midpoint()).dot(&j.normal()) < 0.0 {
        std::mem::swap(&mut j.p1, &mut j.p2);
    }
    j
}

/// The arch built by hand: the voussoirs, the joints between them, and supports on the faces
/// the base offers (the two skewbacks, and with `stepped` the springers' backs).
fn hand_built(stepped: bool) -> Model {
    let blocks: Vec<Block> = voussoirs()
        .into_iter()
        .map(|polygon| {
            let (area, centroid) = polygon_area_centroid(&polygon);
            Block {
                polygon,
                area,
                centroid,
                weight: UNIT_WEIGHT * area,
                kind: BlockKind::Other,
            }
        })
        .collect();
    let n = VOUSSOIRS;
    let mut joints: Vec<Joint> = (0..=n)
        .map(|j| {
            let (i, e) = joint(j);
            // p1 on the intrados: the normal (u_y, -u_x) turns clockwise, from block j - 1
            // into block j.
            Joint {
                p1: i,
                p2: e,
                from: j.checked_sub(1),
                to: (j < n).then_some(j),
                friction: FRICTION,
                kind: JointKind::Other,
            }
        })
        .collect();
    if stepped {
        joints.push(support(joint(0).1, joint(1).1, 0, &blocks));
        joints.push(support(joint(n - 1).1, joint(n).1, n - 1, &blocks));
    }
    let assembly = Assembly { blocks, joints };
    assembly.validate().expect("a well-formed assembly");
    assert_eq!(assembly.is_chain(), !stepped);
    Model::self_weight(assembly)
}

use common::scene_in;

/// The JSON block file of `polygons` (any units).
fn json_file(polygons: &[Vec<[f64; 2]>]) -> Vec<u8> {
    serde_json::json!({ "polygons": polygons })
        .to_string()
        .into_bytes()
}

/// The arch on its base as a scene of blocks: the base first (`base_first`) or last, in
/// `scale` units per metre (1: m, 1000: mm), as JSON, the base fixed by a point in it.
fn skewback_scene(stepped: bool, base_first: bool, scale: f64, reversed: bool) -> Scene {
    let mut polys: Vec<Vec<[f64; 2]>> = voussoirs().iter().map(|v| xy(v, scale)).collect();
    if reversed {
        polys.reverse();
    }
    let b = xy(&base(stepped), scale);
    if base_first {
        polys.insert(0, b);
    } else {
        polys.push(b);
    }
    let units = if scale == 1.0 { "m" } else { "mm" };
    let [px, py] = base_point(scale);
    let dir = tempfile::tempdir().expect("tempdir");
    scene_in(
        dir.path(),
        &format!(
            "[blocks]\nfile = \"arch.json\"\nunits = \"{units}\"\nfixed = [[{px}, {py}]]\n{}",
            material()
        ),
        &[("arch.json", &json_file(&polys))],
    )
    .expect("the skewback scene reads")
}

fn lambda(model: &Model, direction: Direction) -> f64 {
    let r = statics::analyse(model, &StaticSettings::default().direction(direction))
        .expect("the static program solves");
    assert_eq!(r.status, Status::Collapse);
    r.lambda.expect("lambda")
}

fn close(a: f64, b: f64, tol: f64) -> bool {
    (a - b).abs() <= tol * a.abs().max(1.0)
}

#[test]
fn an_arch_on_skewbacks_cut_in_a_non_convex_base_is_the_hand_built_chain() {
    let s = skewback_scene(false, true, 1.0, false);
    let b = s.blocks.as_ref().expect("blocks");
    let d = &b.detected;
    assert_eq!(d.topology, voussoir::blocks::Topology::Chain);
    assert_eq!(d.assembly.blocks.len(), VOUSSOIRS);
    assert_eq!(d.ground_y, None, "with `fixed` and no ground_y, no ground");
    assert_eq!(d.fixed.len(), 1);
    assert_eq!((d.fixed[0].block, d.fixed[0].supports), (0, 2));
    // The supports name the fixed block: the base is block 0 of the file, the springers 1
    // and 9.
    let kinds: Vec<JointKind> = d.assembly.joints.iter().map(|j| j.kind).collect();
    assert_eq!(kinds[0], JointKind::Fixed(1, 0));
    assert_eq!(kinds[VOUSSOIRS], JointKind::Fixed(VOUSSOIRS, 0));
    let model = common::model_of(&s);
    let hand = hand_built(false);
    for dir in [Direction::Right, Direction::Left] {
        let (a, h) = (lambda(&model, dir), lambda(&hand, dir));
        assert!(
            close(a, h, 1e-9),
            "{dir:?}: on the fixed base {a}, by hand {h}"
        );
    }
    // The kinematic search runs on the chain and closes the gap.
    let opts = voussoir::analysis::Options {
        kinematic: voussoir::analysis::KinematicMode::Exhaustive,
        ..Default::default()
    };
    let a = voussoir::analysis::analyse(&s, &opts).expect("analysis");
    let (l, u) = (
        a.lower.lambda.expect("lower"),
        a.lambda_upper().expect("upper"),
    );
    // Finite friction: the static multiplier is exact only if no joint slips.
    if a.lower.friction(&a.model.assembly).exact {
        assert!(close(l, u, 1e-6), "static {l} against kinematic {u}");
    } else {
        assert!(u >= l * (1.0 - 1e-9), "kinematic {u} below static {l}");
    }
    // The DEM, whose ground under each support is the face the base offers, brackets it.
    let (lower, stands, collapses) = common::static_and_dem_bracket(&model);
    assert!(
        stands <= lower && lower <= collapses,
        "DEM bracket [{stands}, {collapses}] misses the static {lower}"
    );
}

#[test]
fn a_springer_in_a_stepped_notch_rests_on_two_faces_as_built_by_hand() {
    let s = skewback_scene(true, false, 1.0, false);
    let d = &s.blocks.as_ref().expect("blocks").detected;
    assert!(
        matches!(&d.topology, voussoir::blocks::Topology::Other(why) if why.contains("fixed 9")),
        "{:?}",
        d.topology
    );
    assert_eq!(d.fixed[0].supports, 4);
    assert_eq!(d.supports, 4);
    let model = common::model_of(&s);
    let hand = hand_built(true);
    for dir in [Direction::Right, Direction::Left] {
        let (a, h) = (lambda(&model, dir), lambda(&hand, dir));
        assert!(close(a, h, 1e-9), "{dir:?}: in the notch {a}, by hand {h}");
        // Held at their backs, the springers do not turn outward: a stronger arch.
        let plain = lambda(&hand_built(false), dir);
        assert!(a > plain, "{dir:?}: notched {a} not above plain {plain}");
    }
}

#[test]
fn block_order_and_units_leave_lambda_unchanged() {
    let reference = lambda(
        &common::model_of(&skewback_scene(false, true, 1.0, false)),
        Direction::Right,
    );
    for (base_first, scale, reversed) in [
        (false, 1.0, false),
        (true, 1000.0, false),
        (false, 1000.0, true),
        (true, 1.0, true),
    ] {
        let s = skewback_scene(false, base_first, scale, reversed);
        let l = lambda(&common::model_of(&s), Direction::Right);
        assert!(
            close(l, reference, 1e-9),
            "base first {base_first}, scale {scale}, reversed {reversed}: {l} vs {reference}"
        );
    }
}

#[test]
fn the_ground_and_a_fixed_block_support_together() {
    // Two columns, no sliding: one 0.3 x 1 on the ground y = 0, one 0.4 x 1 on the step of an
    // L-shaped fixed block. Each rocks about a base corner at lambda = b/h (Heyman), so the
    // pair collapses at the lesser, 0.3; alone, the column on the step at 0.4.
    let ground_column = "[[0, 0], [0.3, 0], [0.3, 1], [0, 1]]";
    let step_column = "[[2, 0.5], [2.4, 0.5], [2.4, 1.5], [2, 1.5]]";
    let step = "[[1.5, 0], [3, 0], [3, 2], [2.6, 2], [2.6, 0.5], [1.5, 0.5]]";
    let scene = |polygons: &str, ground: &str| {
        format!(
            "[blocks]\npolygons = [{polygons}]\n{ground}fixed = [[2.8, 1.0]]\n\
             [material]\nunit_weight = 20000\nfriction = \"inf\"\n"
        )
    };
    let both = common::scene(&scene(
        &format!("{ground_column}, {step_column}, {step}"),
        "ground_y = 0\n",
    ));
    let d = &both.blocks.as_ref().expect("blocks").detected;
    assert_eq!(d.ground_y, Some(0.0));
    assert_eq!(
        (d.supports, d.ground_supports(), d.fixed[0].supports),
        (2, 1, 1)
    );
    let on_step = common::scene(&scene(&format!("{step_column}, {step}"), ""));
    assert_eq!(
        on_step.blocks.as_ref().expect("blocks").detected.ground_y,
        None
    );
    for dir in [Direction::Right, Direction::Left] {
        let l = lambda(&common::model_of(&both), dir);
        assert!(close(l, 0.3, 1e-9), "{dir:?}: both {l} vs 0.3");
        let l = lambda(&common::model_of(&on_step), dir);
        assert!(close(l, 0.4, 1e-9), "{dir:?}: on the step {l} vs 0.4");
    }
    // Without ground_y the column on the ground rests on nothing.
    let e = Scene::from_toml_str(
        &scene(&format!("{ground_column}, {step_column}, {step}"), ""),
        "t",
    )
    .map(|_| ())
    .expect_err("a column on no support");
    let e = e.to_string();
    assert!(
        e.contains("block 0") && e.contains("touches nothing") && e.contains("a fixed block"),
        "{e}"
    );
}

/// The error of a scene `text` (in a directory with `files`).
fn refused(text: &str, files: &[(&str, &[u8])]) -> String {
    let dir = tempfile::tempdir().expect("tempdir");
    match scene_in(dir.path(), text, files) {
        Ok(_) => panic!("accepted: {text}"),
        Err(e) => e,
    }
}

#[test]
fn bad_fixed_points_are_refused_naming_them() {
    let mut polys: Vec<Vec<[f64; 2]>> = voussoirs().iter().map(|v| xy(v, 1.0)).collect();
    polys.push(xy(&base(false), 1.0));
    // A fixed block far from everything: a rock 10 m away.
    let mut with_rock = polys.clone();
    with_rock.push(vec![[10.0, 0.0], [11.0, 0.0], [11.0, 1.0], [10.0, 1.0]]);
    let scene = |fixed: &str| {
        format!(
            "[blocks]\nfile = \"b.json\"\nfixed = {fixed}\n{}",
            material()
        )
    };
    // (fixed points, the blocks file's polygons, words the error must contain)
    type Case<'a> = (&'a str, &'a [Vec<[f64; 2]>], &'a [&'a str]);
    let cases: &[Case] = &[
        (
            "[[0, -0.5], [20, 20]]",
            &polys,
            &[
                "blocks.fixed[1]",
                "[20, 20]",
                "outside every block",
                "nearest is block 9",
            ],
        ),
        (
            "[[0, -0.5], [10.5, 0.5]]",
            &with_rock,
            &[
                "blocks.fixed[1]",
                "[10.5, 0.5]",
                "fixed block 10",
                "touches no moving block",
            ],
        ),
        (
            "[[0, -0.5], [0.1, -0.9]]",
            &polys,
            &["blocks.fixed[1]", "lies in block 9, as fixed[0] does"],
        ),
        (
            // A point in the crown fixes the crown, and leaves the base to move: refused as
            // a moving block that is not convex, with the hint.
            "[[0, 1.9]]",
            &polys,
            &["block 9", "not convex", "name it in `fixed`"],
        ),
    ];
    // A point on the joint between voussoirs 2 and 3 is on both outlines.
    let (i, e) = joint(3);
    let on_joint = format!(
        "[[0, -0.5], [{}, {}]]",
        0.5 * (i.x + e.x),
        0.5 * (i.y + e.y)
    );
    let e = refused(&scene(&on_joint), &[("b.json", &json_file(&polys))]);
    assert!(
        e.contains("blocks.fixed[1]") && e.contains("on the outlines of blocks 2 and 3"),
        "{e}"
    );
    for (fixed, files, words) in cases {
        let e = refused(&scene(fixed), &[("b.json", &json_file(files))]);
        for w in *words {
            assert!(e.contains(w), "fixed = {fixed}: `{w}` not in: {e}");
        }
    }
    // The same with inline polygons, whose units are the fixed points' too.
    let mm: Vec<Vec<[f64; 2]>> = polys
        .iter()
        .map(|p| p.iter().map(|q| [q[0] * 1000.0, q[1] * 1000.0]).collect())
        .collect();
    let inline = format!(
        "[blocks]\npolygons = {}\nunits = \"mm\"\nfixed = [[0, -500], [99999, 0]]\n{}",
        serde_json::to_string(&mm).expect("JSON"),
        material()
    );
    let e = refused(&inline, &[]);
    assert!(
        e.contains("blocks.fixed[1]") && e.contains("[99999, 0]") && e.contains(" mm away"),
        "{e}"
    );
}

/// How an outline is written into a DXF drawing.
#[derive(Clone, Copy, PartialEq)]
enum Written {
    /// A closed LWPOLYLINE, as given.
    Closed,
    /// An open polyline whose last vertex repeats the first (no closed flag).
    OpenRepeated,
    /// Clockwise: the vertices reversed, closed.
    Reversed,
    /// Each vertex written twice, closed.
    Doubled,
    /// An old-style POLYLINE, open, clockwise, its first vertex repeated at the end.
    OldOpenReversed,
    /// Open, its first vertex not repeated: no block.
    Open,
}

/// A DXF drawing of `outlines` (in the drawing's units) on layer `layer`.
fn dxf_of(outlines: &[(Vec<[f64; 2]>, Written)], layer: &str) -> Vec<u8> {
    let mut d = dxf::Drawing::new();
    d.header.version = dxf::enums::AcadVersion::R2000;
    for (points, how) in outlines {
        let mut pts = points.clone();
        let closed = match how {
            Written::Closed => true,
            Written::OpenRepeated => {
                pts.push(pts[0]);
                false
            }
            Written::Reversed => {
                pts.reverse();
                true
            }
            Written::Doubled => {
                pts = pts.iter().flat_map(|p| [*p, *p]).collect();
                true
            }
            Written::OldOpenReversed => {
                pts.reverse();
                pts.push(pts[0]);
                false
            }
            Written::Open => false,
        };
        let specific = if *how == Written::OldOpenReversed {
            let mut p = dxf::entities::Polyline::default();
            p.set_is_closed(closed);
            for q in &pts {
                p.add_vertex(
                    &mut d,
                    dxf::entities::Vertex::new(dxf::Point::new(q[0], q[1], 0.0)),
                );
            }
            dxf::entities::EntityType::Polyline(p)
        } else {
            common::lwpolyline(&pts, closed)
        };
        let mut e = dxf::entities::Entity::new(specific);
        e.common.layer = layer.to_string();
        d.add_entity(e);
    }
    let mut out = Vec::new();
    d.save(&mut out).expect("DXF written");
    out
}

/// The arch on its plain skewbacks in millimetres, base last, each outline written as `how`
/// says (cycling through the list).
fn arch_dxf(how: &[Written]) -> Vec<u8> {
    let mut outlines: Vec<Vec<[f64; 2]>> = voussoirs().iter().map(|v| xy(v, 1000.0)).collect();
    outlines.push(xy(&base(false), 1000.0));
    let list: Vec<(Vec<[f64; 2]>, Written)> = outlines
        .into_iter()
        .enumerate()
        .map(|(i, o)| (o, how[i % how.len()]))
        .collect();
    dxf_of(&list, "STONES")
}

fn dxf_scene_text(file: &str) -> String {
    let [px, py] = base_point(1000.0);
    format!(
        "[blocks]\nfile = \"{file}\"\nunits = \"mm\"\nfixed = [[{px}, {py}]]\n{}",
        material()
    )
}

#[test]
fn outlines_as_cad_writes_them_read_as_the_clean_drawing() {
    let clean = arch_dxf(&[Written::Closed]);
    let messy = arch_dxf(&[
        Written::OpenRepeated,
        Written::Reversed,
        Written::Doubled,
        Written::Closed,
        Written::OldOpenReversed,
    ]);
    let dir = tempfile::tempdir().expect("tempdir");
    let read = |name: &str, bytes: &[u8]| {
        scene_in(dir.path(), &dxf_scene_text(name), &[(name, bytes)]).expect("reads")
    };
    let (a, b) = (read("clean.dxf", &clean), read("messy.dxf", &messy));
    let (ba, bb) = (
        a.blocks.as_ref().expect("blocks"),
        b.blocks.as_ref().expect("blocks"),
    );
    assert_eq!(ba.polygons, bb.polygons, "the same blocks");
    assert!(!ba.mending.any(), "{:?}", ba.mending);
    // Ten outlines cycling through five ways: 2 open and repeated, 2 reversed, 2 doubled,
    // 2 clean, 2 old-style open and reversed.
    let m = bb.mending;
    assert_eq!(
        (
            m.outlines,
            m.closed,
            m.repeated_vertices,
            m.straight_vertices,
            m.reversed
        ),
        (8, 4, 2, 0, 4),
        "{m:?}"
    );
    for dir in [Direction::Right, Direction::Left] {
        let (la, lb) = (
            lambda(&common::model_of(&a), dir),
            lambda(&common::model_of(&b), dir),
        );
        assert_eq!(
            la.to_bits(),
            lb.to_bits(),
            "{dir:?}: clean {la}, as CAD wrote it {lb}"
        );
    }
    // The JSON says what was mended, and the summary too.
    let path = dir.path().join("messy.dxf");
    let text = dxf_scene_text(&path.display().to_string());
    let v = common::json_of(&["analyze", "--json"], &text);
    assert_eq!(
        v["scene"]["blocks"]["mended"],
        serde_json::json!({"outlines": 8, "closed": 4, "repeated_vertices": 2,
            "straight_vertices": 0, "reversed": 4})
    );
    assert_eq!(v["scene"]["blocks"]["ground_y"], serde_json::Value::Null);
    assert_eq!(
        v["scene"]["blocks"]["fixed"],
        serde_json::json!([{"point": [0.0, -500.0], "block": 9, "supports": 2}])
    );
    assert_eq!(v["joints"][0]["kind"], serde_json::json!({"fixed": [0, 9]}));
    let (_d, scene) = common::scene_file(&text);
    let out = common::voussoir()
        .arg("analyze")
        .arg(&scene)
        .output()
        .expect("runs");
    let summary = String::from_utf8_lossy(&out.stdout);
    assert!(
        summary.contains("8 outlines mended as read: 4 open polylines closed at a repeated first vertex, 2 outlines rid of repeated vertices, 4 outlines turned counter-clockwise")
            && summary.contains("2 supports on the fixed block 9"),
        "{summary}"
    );
}

#[test]
fn an_outline_that_crosses_itself_or_stays_open_is_refused() {
    let mut outlines: Vec<(Vec<[f64; 2]>, Written)> = voussoirs()
        .iter()
        .map(|v| (xy(v, 1000.0), Written::Closed))
        .collect();
    outlines.push((xy(&base(false), 1000.0), Written::Closed));
    // Voussoir 4 with its last two vertices swapped: a bow tie.
    let mut crossed = outlines.clone();
    crossed[4].0.swap(2, 3);
    // Written open, its first vertex repeated at the end, and a vertex doubled: the edges are
    // named by the vertices as written (vertex 3 repeats vertex 2, vertex 5 vertex 0).
    let bow = crossed[4].0.clone();
    crossed[4] = (
        vec![bow[0], bow[1], bow[2], bow[2], bow[3]],
        Written::OpenRepeated,
    );
    let dir = tempfile::tempdir().expect("tempdir");
    let e = scene_in(
        dir.path(),
        &dxf_scene_text("b.dxf"),
        &[("b.dxf", &dxf_of(&crossed, "STONES"))],
    )
    .map(|_| ())
    .expect_err("a bow tie");
    // Written: 0 a, 1 c, 2 b, 3 b (repeated), 4 d; the edge c-b crosses the edge d-a. The
    // coordinates are the file's, to the digits DXF keeps.
    for words in [
        "block 4: its outline intersects itself",
        "the edge from vertex 1 (",
        ") to vertex 2 (",
        ") crosses the edge from vertex 4 (",
        ") to vertex 0 (",
        "block 4 is handle",
    ] {
        assert!(e.contains(words), "`{words}` not in: {e}");
    }
    // An open polyline whose ends differ is no block: never closed silently.
    let mut open = outlines.clone();
    open[2].1 = Written::Open;
    let e = scene_in(
        dir.path(),
        &dxf_scene_text("c.dxf"),
        &[("c.dxf", &dxf_of(&open, "STONES"))],
    )
    .map(|_| ())
    .expect_err("an open outline");
    assert!(
        e.contains("block 2") && e.contains("is open") && e.contains("does not repeat its first"),
        "{e}"
    );
}

/// The bundled example's block drawing, as this test writes it (`VOUSSOIR_WRITE_EXAMPLES=1`
/// writes it into data/blocks/): the arch on its skewbacks in millimetres, drawn as a CAD
/// program may write it (open polylines repeating their first vertex, some clockwise).
fn skewback_example() -> Vec<u8> {
    arch_dxf(&[Written::OpenRepeated, Written::Reversed, Written::Closed])
}

#[test]
fn the_bundled_skewback_example_is_current_and_analyses() {
    let name = "blocks/skewback_arch.dxf";
    let bytes = skewback_example();
    if std::env::var_os("VOUSSOIR_WRITE_EXAMPLES").is_some() {
        std::fs::write(common::data(name), &bytes).expect("example written");
    }
    let dir = tempfile::tempdir().expect("tempdir");
    let fresh = dir.path().join("skewback_arch.dxf");
    std::fs::write(&fresh, &bytes).expect("fresh copy");
    let units = voussoir::blocks::Units::Millimetres;
    let a = voussoir::blocks::read_file(&common::data(name), units, None).expect("committed");
    let b = voussoir::blocks::read_file(&fresh, units, None).expect("fresh");
    assert_eq!(
        a, b,
        "{name} is not what this test writes (VOUSSOIR_WRITE_EXAMPLES=1)"
    );
    let s = Scene::from_file(&common::data("blocks_skewback_arch.toml")).expect("scene");
    let blocks = s.blocks.as_ref().expect("blocks");
    assert_eq!(blocks.detected.topology, voussoir::blocks::Topology::Chain);
    assert!(blocks.mending.closed > 0 && blocks.mending.reversed > 0);
    common::voussoir()
        .arg("analyze")
        .arg(common::data("blocks_skewback_arch.toml"))
        .assert()
        .success();
}

#[test]
fn ties_anchor_in_a_fixed_block_and_loads_on_one_are_refused() {
    let mut polys: Vec<Vec<[f64; 2]>> = voussoirs().iter().map(|v| xy(v, 1.0)).collect();
    polys.push(xy(&base(false), 1.0));
    let c = polygon_area_centroid(&voussoirs()[1]).1;
    let head = format!(
        "[blocks]\nfile = \"b.json\"\nfixed = [[0, -0.5]]\n{}",
        material()
    );
    let files: &[(&str, &[u8])] = &[("b.json", &json_file(&polys))];
    // A tie from voussoir 1 back into the left abutment: anchored to the ground there.
    let dir = tempfile::tempdir().expect("tempdir");
    let tied = scene_in(
        dir.path(),
        &format!(
            "{head}[[ties]]\nfrom = [{}, {}]\nto = [-2.5, 0.3]\ncapacity = 20000\n",
            c.x, c.y
        ),
        files,
    )
    .expect("reads");
    let m = common::model_of(&tied);
    assert_eq!(m.ties.len(), 1);
    assert_eq!((m.ties[0].from.block, m.ties[0].to.block), (Some(1), None));
    // A tie only adds resistance: the multiplier is not lower.
    let (free, held) = (
        lambda(&hand_built(false), Direction::Left),
        lambda(&m, Direction::Left),
    );
    assert!(
        held >= free * (1.0 - 1e-9),
        "tied {held} below untied {free}"
    );
    // A point load inside the base acts on nothing: refused when the model is built, saying
    // why.
    let loaded = scene_in(
        dir.path(),
        &format!("{head}[[loads]]\ntype = \"point\"\nat = [0, -0.5]\nforce = [0, -1000]\n"),
        files,
    )
    .expect("reads");
    let e = voussoir::scene::build(&loaded)
        .map(|_| ())
        .expect_err("a load on the base")
        .to_string();
    assert!(
        e.contains("loads[0].at") && e.contains("in the fixed block 9"),
        "{e}"
    );
}

#[test]
fn fill_over_a_fixed_top_rests_on_it() {
    // In the stepped notches the abutments rise over the springers' backs: the fill above
    // them rests on the abutments, so the arch carries only the fill between the notches'
    // upper corners, over the extrados chords of voussoirs 1 to 7.
    let level = 2.6;
    let mut polys: Vec<Vec<[f64; 2]>> = voussoirs().iter().map(|v| xy(v, 1.0)).collect();
    polys.push(xy(&base(true), 1.0));
    let dir = tempfile::tempdir().expect("tempdir");
    let s = scene_in(
        dir.path(),
        &format!(
            "[blocks]\nfile = \"b.json\"\nfixed = [[0, -0.5]]\n{}[fill]\nlevel = {level}\nunit_weight = 18000\n",
            material()
        ),
        &[("b.json", &json_file(&polys))],
    )
    .expect("reads");
    let m = common::model_of(&s);
    let carried: f64 = m
        .loads
        .applied()
        .iter()
        .filter(|l| l.source == voussoir::model::LoadSource::Fill)
        .map(|l| -l.force.y)
        .sum();
    let mut region: Vec<Vec2> = (1..VOUSSOIRS).map(|j| joint(j).1).collect();
    let (first, last) = (region[0], region[region.len() - 1]);
    region.push(Vec2::new(last.x, level));
    region.push(Vec2::new(first.x, level));
    let expected = 18000.0 * polygon_area_centroid(&region).0;
    assert!(
        close(carried, expected, 1e-9),
        "fill carried {carried} N, over the chords between the notches {expected} N"
    );
}
