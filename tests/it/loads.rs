//! Load cases beyond self-weight: point and line loads, fill and the vertical seismic
//! component. Every expected value is derived here from the definitions (virtual work of a
//! mechanism, equivalent point loads, the overturning of a rigid block, mirror symmetry,
//! agreement of the two bounds), never taken from a previous run.

use proptest::prelude::*;
use proptest::test_runner::RngSeed;
use voussoir::assembly::{Assembly, Block, BlockKind, Joint, JointKind};
use voussoir::geometry::{polygon_area_centroid, Vec2};
use voussoir::kinematic::{self, KinematicResult, KinematicSettings};
use voussoir::model::{LoadCase, Model};
use voussoir::scene::Scene;
use voussoir::statics::{self, Direction, StaticResult, StaticSettings, Status};

// ---------------------------------------------------------------------------------------------
// Helpers.

fn scene(text: &str) -> Scene {
    Scene::from_toml_str(text, "loads-test.toml")
        .unwrap_or_else(|e| panic!("valid test scene rejected: {e}\n{text}"))
}

fn build(text: &str) -> Model {
    voussoir::scene::build(&scene(text))
        .unwrap_or_else(|e| panic!("scene does not build: {e}\n{text}"))
}

fn statics(m: &Model, d: Direction) -> StaticResult {
    statics::analyse(m, &StaticSettings::default().direction(d)).expect("static analysis solves")
}

fn kinematics(m: &Model, d: Direction) -> KinematicResult {
    kinematic::analyse(m, &KinematicSettings::default().direction(d))
        .expect("kinematic analysis runs")
}

fn lambda_static(m: &Model) -> f64 {
    let r = statics(m, Direction::Right);
    assert_eq!(r.status, Status::Collapse, "static status");
    r.lambda.expect("collapse has a multiplier")
}

fn lambda_kinematic(m: &Model) -> f64 {
    let r = kinematics(m, Direction::Right);
    assert_eq!(r.status, Status::Collapse, "kinematic status");
    r.lambda_upper.expect("collapse has a multiplier")
}

fn rel(a: f64, b: f64) -> f64 {
    if a == b {
        return 0.0;
    }
    (a - b).abs() / a.abs().max(b.abs())
}

/// The `[arch]` table of a scene.
fn arch(shape: &str, t: f64, n: usize, curved: bool) -> String {
    format!(
        "[arch]\n{shape}thickness = {t:?}\nvoussoirs = {n}\nvoussoir_shape = \"{}\"\n",
        if curved { "curved" } else { "polygon" }
    )
}

const SEMICIRCLE: &str = "shape = \"circular\"\nradius = 2.0\nembrace_deg = 180.0\n";
const SEGMENTAL: &str = "shape = \"circular\"\nradius = 2.5\nembrace_deg = 140.0\n";
const POINTED: &str = "shape = \"pointed\"\nradius = 2.0\neccentricity = 0.3\n";
const BASKET: &str = "shape = \"basket\"\nspan = 4.0\nrise = 1.5\nside_angle_deg = 60.0\n";
const PIERS: &str = "[piers]\nheight = 2.0\nwidth = 1.0\ncourses = 2\n";

fn point_load(at: Vec2, force: Vec2, seismic: bool) -> String {
    format!(
        "[[loads]]\ntype = \"point\"\nat = [{:?}, {:?}]\nforce = [{:?}, {:?}]\nseismic = {seismic}\n",
        at.x, at.y, force.x, force.y
    )
}

fn line_load(from_x: f64, to_x: f64, intensity: f64, seismic: bool) -> String {
    format!(
        "[[loads]]\ntype = \"line\"\nfrom_x = {from_x:?}\nto_x = {to_x:?}\nintensity = {intensity:?}\nseismic = {seismic}\n"
    )
}

fn fill(level: f64, unit_weight: f64, seismic: bool) -> String {
    format!("[fill]\nlevel = {level:?}\nunit_weight = {unit_weight:?}\nseismic = {seismic}\n")
}

fn vertical_ratio(r: f64) -> String {
    format!("[seismic]\nvertical_ratio = {r:?}\n")
}

/// Whether `p` lies in the convex polygon `poly` (either orientation), boundary included.
fn inside(poly: &[Vec2], p: Vec2) -> bool {
    let m = poly.len();
    let cr = |a: Vec2, b: Vec2| a.x * b.y - a.y * b.x;
    let area: f64 = (0..m).map(|k| cr(poly[k], poly[(k + 1) % m])).sum();
    (0..m).all(|k| {
        let (a, b) = (poly[k], poly[(k + 1) % m]);
        area.signum() * cr(b - a, p - a) >= 0.0
    })
}

/// One load as the definitions say it acts: a permanent force at a point and the weight of
/// the seismic mass attached to it (0 when not seismic).
#[derive(Debug, Clone, Copy)]
struct Load {
    block: usize,
    point: Vec2,
    force: Vec2,
    seismic_weight: f64,
}

/// Self-weight of every block: its weight down at its centroid, and a seismic mass of that
/// weight there.
fn self_weights(a: &Assembly) -> Vec<Load> {
    a.blocks
        .iter()
        .enumerate()
        .map(|(i, b)| Load {
            block: i,
            point: b.centroid,
            force: Vec2::new(0.0, -b.weight),
            seismic_weight: b.weight,
        })
        .collect()
}

/// A point load as the scene contract defines it: on the block whose outline contains `at`.
fn point(a: &Assembly, at: Vec2, force: Vec2, seismic: bool) -> Load {
    let block = (0..a.blocks.len())
        .find(|&i| inside(&a.blocks[i].polygon, at))
        .expect("the point lies in a block");
    Load {
        block,
        point: at,
        force,
        seismic_weight: if seismic { force.y.abs() } else { 0.0 },
    }
}

/// A planar twist `[omega, vx0, vy0]`: velocity `v(q) = (vx0 - omega q_y, vy0 + omega q_x)`.
type Twist = [f64; 3];

fn twist_velocity(t: Twist, q: Vec2) -> Vec2 {
    Vec2::new(t[1] - t[0] * q.y, t[2] + t[0] * q.x)
}

/// Block twists of the four-hinge mechanism of a chain with hinges at `hinges` (joint index,
/// hinge point), in chain order: the relative rotations `c_k` about the hinge points close the
/// chain, `sum c_k (1, y_k, -x_k) = 0` (the null vector of a 3 x 4 matrix, by cofactors), and
/// a block moves with the sum of the relative twists of the joints before it. Scaled so that
/// the seismic load does positive work is left to the caller.
fn four_hinge_twists(a: &Assembly, hinges: &[(usize, Vec2)]) -> Vec<Twist> {
    assert_eq!(hinges.len(), 4, "a four-hinge mechanism");
    let cols: Vec<[f64; 3]> = hinges.iter().map(|&(_, p)| [1.0, p.y, -p.x]).collect();
    let det = |a: [f64; 3], b: [f64; 3], c: [f64; 3]| {
        a[0] * (b[1] * c[2] - b[2] * c[1]) - b[0] * (a[1] * c[2] - a[2] * c[1])
            + c[0] * (a[1] * b[2] - a[2] * b[1])
    };
    let c = [
        det(cols[1], cols[2], cols[3]),
        -det(cols[0], cols[2], cols[3]),
        det(cols[0], cols[1], cols[3]),
        -det(cols[0], cols[1], cols[2]),
    ];
    let mut sum = [0.0; 3];
    for k in 0..4 {
        for i in 0..3 {
            sum[i] += c[k] * cols[k][i];
        }
    }
    assert!(
        sum.iter()
            .all(|s| s.abs() < 1e-9 * c.iter().map(|x| x.abs()).sum::<f64>()),
        "closure {sum:?}"
    );
    // Chain: joint k carries block k - 1 (or the ground) to block k.
    (0..a.blocks.len())
        .map(|b| {
            let mut t = [0.0; 3];
            for (k, &(j, _)) in hinges.iter().enumerate() {
                assert_eq!(a.joints[j].to.map_or(a.blocks.len(), |x| x), j, "a chain");
                if j <= b {
                    for i in 0..3 {
                        t[i] += c[k] * cols[k][i];
                    }
                }
            }
            t
        })
        .collect()
}

/// Twists of blocks moving with centroid velocity `(vx, vy)` and rotation rate `omega`.
fn twists_of_velocities(a: &Assembly, v: &[[f64; 3]]) -> Vec<Twist> {
    v.iter()
        .zip(&a.blocks)
        .map(|(v, b)| {
            let c = b.centroid;
            // v(q) = v_c + omega x (q - c) = (vx + omega c_y - omega q_y, vy - omega c_x + omega q_x)
            [v[2], v[0] + v[2] * c.y, v[1] - v[2] * c.x]
        })
        .collect()
}

/// `(G, A)` of a mechanism: `G = -sum F . v(q)` over the permanent forces, `A = sum W_s (d, r)
/// . v(q)` over the seismic masses.
fn virtual_work(loads: &[Load], twists: &[Twist], d: f64, r: f64) -> (f64, f64) {
    let mut g = 0.0;
    let mut a = 0.0;
    for l in loads {
        let v = twist_velocity(twists[l.block], l.point);
        g -= l.force.dot(&v);
        a += l.seismic_weight * (d * v.x + r * v.y);
    }
    (g, a)
}

/// `lambda = G / A` of a mechanism, signed so that the seismic load does positive work.
fn mechanism_lambda(loads: &[Load], twists: &[Twist], d: f64, r: f64) -> f64 {
    let (g, a) = virtual_work(loads, twists, d, r);
    assert!(a.abs() > 0.0, "the mechanism is driven by the seismic load");
    g / a
}

/// A rectangular block `b x h` standing on the ground, base centred at the origin.
fn single_block(b: f64, h: f64) -> Assembly {
    let polygon = vec![
        Vec2::new(-0.5 * b, 0.0),
        Vec2::new(0.5 * b, 0.0),
        Vec2::new(0.5 * b, h),
        Vec2::new(-0.5 * b, h),
    ];
    let (area, centroid) = polygon_area_centroid(&polygon);
    Assembly {
        blocks: vec![Block {
            polygon,
            area,
            centroid,
            weight: 2.0e4 * area,
            kind: BlockKind::Other,
        }],
        // p1 -> p2 toward -x, so the normal (u_y, -u_x) points up into the block.
        joints: vec![Joint {
            p1: Vec2::new(0.5 * b, 0.0),
            p2: Vec2::new(-0.5 * b, 0.0),
            from: None,
            to: Some(0),
            friction: f64::INFINITY,
            kind: JointKind::Other,
        }],
    }
}

/// The centroid of the voussoir a fraction `at` of the way along the arch (0 = left springing).
fn voussoir_centroid(text: &str, at: f64) -> Vec2 {
    let a = build(text).assembly;
    let vs: Vec<&Block> = a
        .blocks
        .iter()
        .filter(|b| matches!(b.kind, BlockKind::Voussoir(_)))
        .collect();
    vs[((at * vs.len() as f64) as usize).min(vs.len() - 1)].centroid
}

/// The extrados chord `(a, b)` of every voussoir: polygon `[p1(j), p2(j), p2(j+1), p1(j+1)]`.
fn extrados_chords(a: &Assembly) -> Vec<(usize, Vec2, Vec2)> {
    a.blocks
        .iter()
        .enumerate()
        .filter(|(_, b)| matches!(b.kind, BlockKind::Voussoir(_)))
        .map(|(i, b)| (i, b.polygon[1], b.polygon[2]))
        .collect()
}

/// The point loads equivalent to a line load by the contract: per voussoir, `q * overlap` at
/// the point of its extrados chord at the overlap's mid x.
fn equivalent_point_loads(a: &Assembly, from_x: f64, to_x: f64, q: f64) -> Vec<(Vec2, f64)> {
    extrados_chords(a)
        .into_iter()
        .filter_map(|(_, p, r)| {
            let lo = from_x.max(p.x.min(r.x));
            let hi = to_x.min(p.x.max(r.x));
            (hi > lo).then(|| {
                let x = 0.5 * (lo + hi);
                let s = (x - p.x) / (r.x - p.x);
                (p + s * (r - p), q * (hi - lo))
            })
        })
        .collect()
}

// ---------------------------------------------------------------------------------------------
// 1. A point load at the crown changes lambda as the virtual work of the mechanism says.

#[test]
fn crown_point_load_follows_virtual_work() {
    let (r, t, n) = (2.0, 0.4, 15);
    let base = arch(SEMICIRCLE, t, n, false);
    let unloaded = lambda_static(&build(&base));
    let at = Vec2::new(0.0, r); // centreline radius at the crown, inside voussoir 7
    let force = Vec2::new(0.0, -10_000.0);
    for seismic in [true, false] {
        let text = base.clone() + &point_load(at, force, seismic);
        let m = build(&text);
        let a = &m.assembly;
        let mut loads = self_weights(a);
        let p = point(a, at, force, seismic);
        assert_eq!(
            a.blocks[p.block].kind,
            BlockKind::Voussoir(n / 2),
            "crown voussoir"
        );
        loads.push(p);

        let st = statics(&m, Direction::Right);
        assert_eq!(st.status, Status::Collapse);
        let lambda = st.lambda.unwrap();
        assert!(st.equilibrium_residual < 1e-6 * m.loads.permanent_weight());

        // From the static hinges.
        let hinges: Vec<(usize, Vec2)> = st
            .hinges
            .iter()
            .map(|h| (h.joint, Vec2::new(h.x, h.y)))
            .collect();
        let tw = four_hinge_twists(a, &hinges);
        // G/A does not depend on the mechanism's scale or sign.
        let from_hinges = mechanism_lambda(&loads, &tw, 1.0, 0.0);

        // From the kinematic mechanism's block velocities.
        let kin = kinematics(&m, Direction::Right);
        assert_eq!(kin.status, Status::Collapse);
        let mech = kin.mechanism.as_ref().expect("governing mechanism");
        let tk = twists_of_velocities(a, &mech.velocities);
        let (gk, ak) = virtual_work(&loads, &tk, 1.0, 0.0);
        assert!(
            ak > 0.0,
            "the kinematic mechanism is driven by the load: A = {ak}"
        );
        let from_velocities = gk / ak;

        // From the static program's mechanism (the duals).
        let ts = twists_of_velocities(a, &st.mechanism);
        let from_duals = mechanism_lambda(&loads, &ts, 1.0, 0.0);

        eprintln!(
            "crown load seismic={seismic}: static {lambda:.12}, hinges {:?}, G/A from hinges {from_hinges:.12}, from kinematic velocities {from_velocities:.12}, from static duals {from_duals:.12}, kinematic {:.12}, unloaded {unloaded:.12}",
            st.hinges.iter().map(|h| h.joint).collect::<Vec<_>>(),
            kin.lambda_upper.unwrap()
        );
        assert!(rel(from_hinges, lambda) < 1e-6, "{from_hinges} vs {lambda}");
        assert!(
            rel(from_velocities, lambda) < 1e-6,
            "{from_velocities} vs {lambda}"
        );
        assert!(rel(from_duals, lambda) < 1e-6, "{from_duals} vs {lambda}");
        assert!(rel(kin.lambda_upper.unwrap(), lambda) < 1e-6);
        // The load matters.
        assert!(
            rel(lambda, unloaded) > 1e-3,
            "loaded {lambda} vs unloaded {unloaded}"
        );
    }
}

// ---------------------------------------------------------------------------------------------
// 2. A point load of zero force changes nothing.

#[test]
fn zero_point_load_changes_nothing() {
    for (shape, piers) in [(SEMICIRCLE, ""), (POINTED, PIERS), (BASKET, "")] {
        let base = arch(shape, 0.3, 12, false) + piers;
        let m0 = build(&base);
        // Inside a voussoir off the axis: its centroid.
        let c = m0.assembly.blocks[m0.assembly.blocks.len() / 2 + 2].centroid;
        for seismic in [true, false] {
            let m1 = build(&(base.clone() + &point_load(c, Vec2::zeros(), seismic)));
            let (s0, s1) = (lambda_static(&m0), lambda_static(&m1));
            let (k0, k1) = (lambda_kinematic(&m0), lambda_kinematic(&m1));
            eprintln!("zero load: static {s0} -> {s1}, kinematic {k0} -> {k1}");
            assert!(rel(s0, s1) <= 1e-12, "static {s0} vs {s1}");
            assert!(rel(k0, k1) <= 1e-12, "kinematic {k0} vs {k1}");
        }
    }
}

// ---------------------------------------------------------------------------------------------
// 3. A line load is the sum of its equivalent point loads.

#[test]
fn line_load_equals_its_point_loads() {
    let cases = [
        (arch(SEMICIRCLE, 0.3, 12, false), -2.5, 2.5),
        (arch(SEMICIRCLE, 0.3, 13, false), -0.7, 1.3),
        (arch(POINTED, 0.3, 12, false), -2.5, 2.5),
        (arch(BASKET, 0.4, 11, false), -1.2, 0.4),
    ];
    let q = 3000.0;
    for (base, from_x, to_x) in cases {
        let a = build(&base).assembly;
        let points = equivalent_point_loads(&a, from_x, to_x, q);
        assert!(points.len() >= 3);
        for seismic in [true, false] {
            let line = build(&(base.clone() + &line_load(from_x, to_x, q, seismic)));
            let text: String = points
                .iter()
                .map(|&(p, w)| point_load(p, Vec2::new(0.0, -w), seismic))
                .collect();
            let pts = build(&(base.clone() + &text));
            assert!(
                (line.loads.permanent_weight() - pts.loads.permanent_weight()).abs()
                    <= 1e-12 * line.loads.permanent_weight()
            );
            let (sl, sp) = (lambda_static(&line), lambda_static(&pts));
            let (kl, kp) = (lambda_kinematic(&line), lambda_kinematic(&pts));
            eprintln!(
                "line [{from_x}, {to_x}] seismic={seismic}: static {sl:.12} vs points {sp:.12} ({:.1e}), kinematic {kl:.12} vs {kp:.12} ({:.1e})",
                rel(sl, sp),
                rel(kl, kp)
            );
            assert!(rel(sl, sp) <= 1e-9, "static {sl} vs {sp}");
            assert!(rel(kl, kp) <= 1e-9, "kinematic {kl} vs {kp}");
        }
    }
}

// ---------------------------------------------------------------------------------------------
// 4. Fill.

/// Shapes of the fill grid: (name, `[arch]` shape keys, whether a portal of it is allowed).
const SHAPES: [(&str, &str, bool); 4] = [
    ("semicircle", SEMICIRCLE, true),
    ("segmental", SEGMENTAL, false),
    ("pointed", POINTED, true),
    ("basket", BASKET, true),
];

#[test]
fn fill_of_zero_weight_changes_nothing() {
    for (_, shape, portal) in SHAPES {
        let mut base = arch(shape, 0.3, 10, false);
        if portal {
            base += PIERS;
        }
        let crown = scene(&base).arch.expect("arch").shape.crown_extrados(0.3);
        let m0 = build(&base);
        let m1 = build(&(base.clone() + &fill(crown + 0.5, 0.0, true)));
        let (s0, s1) = (lambda_static(&m0), lambda_static(&m1));
        let (k0, k1) = (lambda_kinematic(&m0), lambda_kinematic(&m1));
        eprintln!("zero-weight fill: static {s0} -> {s1}, kinematic {k0} -> {k1}");
        assert!(rel(s0, s1) <= 1e-12, "static {s0} vs {s1}");
        assert!(rel(k0, k1) <= 1e-12, "kinematic {k0} vs {k1}");
    }
}

/// Static and kinematic analyses of one scene, with the checks of a collapse state: the
/// thrust line inside every joint and the bounds equal. Returns the static multiplier.
fn check_bounds_agree(text: &str, label: &str, worst: &mut (f64, String)) -> Option<f64> {
    let m = build(text);
    let st = statics(&m, Direction::Right);
    let kin = kinematics(&m, Direction::Right);
    assert_eq!(st.status, kin.status, "{label}: statuses\n{text}");
    if st.status != Status::Collapse {
        eprintln!("{label}: {:?}", st.status);
        return None;
    }
    let forces = st.forces.as_ref().expect("forces at collapse");
    assert_eq!(forces.len(), m.assembly.joints.len());
    for (j, joint) in m.assembly.joints.iter().enumerate() {
        if let Some(e) = st.eccentricity(j) {
            assert!(
                e.abs() <= 0.5 * joint.length() * (1.0 + 1e-9),
                "{label}: joint {j}: |e| = {} > L/2 = {}",
                e.abs(),
                0.5 * joint.length()
            );
        }
    }
    let (ls, lk) = (st.lambda.unwrap(), kin.lambda_upper.unwrap());
    let d = rel(ls, lk);
    if d > worst.0 {
        *worst = (d, format!("{label}: static {ls} kinematic {lk}"));
    }
    assert!(d <= 1e-6, "{label}: static {ls} vs kinematic {lk}\n{text}");
    Some(ls)
}

#[test]
fn heavy_fill_keeps_the_thrust_inside_and_the_bounds_equal() {
    let t = 0.3;
    let mut worst = (0.0, String::new());
    let mut collapses = 0;
    let mut cases = 0;
    for (name, shape, portal_ok) in SHAPES {
        for portal in [false, true] {
            if portal && !portal_ok {
                continue;
            }
            for curved in [false, true] {
                let n = if portal { 8 } else { 12 };
                let mut base = arch(shape, t, n, curved);
                if portal {
                    base += PIERS;
                }
                let crown = scene(&base).arch.expect("arch").shape.crown_extrados(t);
                let haunch = voussoir_centroid(&base, 2.0 / 3.0);
                let mut unfilled = None;
                for extra in [0.0, 0.4, 1.2] {
                    for (gamma, seismic) in [(18_000.0, true), (40_000.0, false)] {
                        for loads in [
                            String::new(),
                            point_load(haunch, Vec2::new(0.0, -8000.0), true)
                                + &line_load(-1.0, 0.3, 6000.0, false),
                        ] {
                            let text = base.clone() + &fill(crown + extra, gamma, seismic) + &loads;
                            let label = format!(
                                "{name} portal={portal} curved={curved} level=crown+{extra} gamma={gamma} seismic={seismic} loads={}",
                                !loads.is_empty()
                            );
                            cases += 1;
                            if let Some(l) = check_bounds_agree(&text, &label, &mut worst) {
                                collapses += 1;
                                if extra == 1.2 && gamma == 40_000.0 && loads.is_empty() {
                                    unfilled.get_or_insert_with(|| {
                                        check_bounds_agree(&base, "no fill", &mut worst)
                                    });
                                    eprintln!(
                                        "{label}: lambda {l:.6} (unfilled {:?})",
                                        unfilled.unwrap()
                                    );
                                }
                            }
                        }
                    }
                }
            }
        }
    }
    eprintln!(
        "fill grid: {collapses} of {cases} collapse; worst static/kinematic difference {:.2e} ({})",
        worst.0, worst.1
    );
    assert!(collapses * 2 > cases, "most of the grid collapses");
}

// ---------------------------------------------------------------------------------------------
// 5. The vertical seismic ratio.

#[test]
fn single_block_overturns_at_b_over_h_plus_r_b() {
    for (b, h) in [(0.5, 1.0), (0.4, 2.0), (1.0, 1.5)] {
        let a = single_block(b, h);
        for r in [-0.5, -0.25, 0.0, 0.1, 0.3, 0.5] {
            let m = Model {
                loads: LoadCase::self_weight(&a).with_vertical_ratio(r),
                assembly: a.clone(),
                strength: voussoir::model::Strength::rigid(),
                ties: Vec::new(),
                strips: Vec::new(),
                passive: Vec::new(),
            };
            // Overturning about the toe (b/2, 0): lambda W h/2 + r lambda W b/2 = W b/2.
            let expected = b / (h + r * b);
            let s = lambda_static(&m);
            let k = lambda_kinematic(&m);
            assert!(
                rel(s, expected) <= 1e-8,
                "b {b} h {h} r {r}: static {s} vs {expected}"
            );
            assert!(
                rel(k, expected) <= 1e-8,
                "b {b} h {h} r {r}: kinematic {k} vs {expected}"
            );
            // Toward -x the block is symmetric: the same multiplier.
            let sl = statics(&m, Direction::Left).lambda.unwrap();
            assert!(rel(sl, expected) <= 1e-8, "left: {sl} vs {expected}");
        }
    }
}

#[test]
fn vertical_ratio_on_arches_bounds_agree_and_mirror() {
    let mut worst_mirror: f64 = 0.0;
    for (name, shape, portal_ok) in SHAPES {
        for portal in [false, true] {
            if portal && !portal_ok {
                continue;
            }
            let n = if portal { 8 } else { 12 };
            let mut base = arch(shape, 0.3, n, false);
            if portal {
                base += PIERS;
            }
            let crown = scene(&base).arch.expect("arch").shape.crown_extrados(0.3);
            let haunch = voussoir_centroid(&base, 2.0 / 3.0);
            // Asymmetric loads, so that left and right differ.
            let loads = point_load(haunch, Vec2::new(0.0, -6000.0), true)
                + &fill(crown + 0.3, 18_000.0, true);
            let mut previous = None;
            for r in [-0.4, 0.2, 0.45] {
                let text = base.clone() + &loads + &vertical_ratio(r);
                let label = format!("{name} portal={portal} r={r}");
                let m = build(&text);
                let mut w = (0.0, String::new());
                let l = check_bounds_agree(&text, &label, &mut w)
                    .unwrap_or_else(|| panic!("{label}: collapses"));
                let mirrored = m.mirrored();
                for (d, dm) in [
                    (Direction::Left, Direction::Right),
                    (Direction::Right, Direction::Left),
                ] {
                    let s = statics(&m, d);
                    let sm = statics(&mirrored, dm);
                    assert_eq!(s.status, sm.status, "{label}");
                    let k = kinematics(&m, d);
                    let km = kinematics(&mirrored, dm);
                    assert_eq!(k.status, km.status, "{label}");
                    if let (Some(a), Some(b)) = (s.lambda, sm.lambda) {
                        worst_mirror = worst_mirror.max(rel(a, b));
                        assert!(rel(a, b) <= 1e-9, "{label} {d:?}: {a} vs mirrored {b}");
                    }
                    if let (Some(a), Some(b)) = (k.lambda_upper, km.lambda_upper) {
                        assert!(
                            rel(a, b) <= 1e-9,
                            "{label} {d:?}: kinematic {a} vs mirrored {b}"
                        );
                    }
                    if d == Direction::Left {
                        eprintln!(
                            "{label}: right {l:.6}, left {:?}, mirrored right {:?}",
                            s.lambda, sm.lambda
                        );
                    }
                }
                // An upward seismic component lowers lambda (less weight to resist with).
                if let Some(prev) = previous {
                    assert!(l < prev, "{label}: {l} not below {prev} at a smaller r");
                }
                previous = Some(l);
            }
        }
    }
    eprintln!("worst mirror difference {worst_mirror:.2e}");
}

// ---------------------------------------------------------------------------------------------
// 6. Random load sets on random scenes.

/// A random point load.
#[derive(Debug, Clone)]
struct RandomPoint {
    /// Which block, as a fraction of the block count.
    block: f64,
    /// Convex weights of the block polygon's vertices.
    weights: [f64; 4],
    /// How far from the centroid toward that convex combination (0..1).
    shrink: f64,
    /// Force `(fx, -fy)` in fractions of the structure's weight.
    force: (f64, f64),
    seismic: bool,
}

#[derive(Debug, Clone)]
struct RandomLoads {
    points: Vec<RandomPoint>,
    /// (level above the crown extrados, unit weight, seismic)
    fill: Option<(f64, f64, bool)>,
    vertical_ratio: f64,
}

fn random_scene() -> impl Strategy<Value = String> {
    let shape = prop_oneof![
        (
            1.0f64..3.0,
            0.12f64..0.3,
            120.0f64..180.0,
            6usize..13,
            any::<bool>()
        )
            .prop_map(|(r, tr, emb, n, portal)| {
                let emb = if portal { 180.0 } else { emb };
                (
                    format!("shape = \"circular\"\nradius = {r:?}\nembrace_deg = {emb:?}\n"),
                    tr * r,
                    n,
                    portal,
                    r,
                )
            }),
        (
            1.0f64..3.0,
            0.0f64..0.2,
            0.12f64..0.3,
            3usize..7,
            any::<bool>()
        )
            .prop_map(|(r, er, tr, half, portal)| (
                format!(
                    "shape = \"pointed\"\nradius = {r:?}\neccentricity = {:?}\n",
                    er * r
                ),
                tr * r,
                2 * half,
                portal,
                r,
            )),
        (
            2.0f64..6.0,
            0.3f64..0.45,
            30.0f64..75.0,
            0.06f64..0.12,
            6usize..13,
            any::<bool>()
        )
            .prop_map(|(l, rs, b, tl, n, portal)| (
                format!(
                    "shape = \"basket\"\nspan = {l:?}\nrise = {:?}\nside_angle_deg = {b:?}\n",
                    rs * l
                ),
                tl * l,
                n,
                portal,
                0.5 * l,
            )),
    ];
    (
        shape,
        any::<bool>(),
        (0.5f64..1.5, 0.25f64..0.5, 1usize..3),
        prop_oneof![3 => Just(f64::INFINITY), 1 => 0.4f64..1.0],
    )
        .prop_map(|((shape, t, n, portal, size), curved, (h, b, k), mu)| {
            let mut text = arch(&shape, t, n, curved);
            if portal {
                text += &format!(
                    "[piers]\nheight = {:?}\nwidth = {:?}\ncourses = {k}\n",
                    h * size,
                    b * size
                );
            }
            text + &format!("[material]\nfriction = {mu}\n")
        })
}

fn random_loads() -> impl Strategy<Value = RandomLoads> {
    let point = (
        0.0f64..1.0,
        [0.0f64..1.0, 0.0f64..1.0, 0.0f64..1.0, 0.0f64..1.0],
        0.0f64..0.3,
        (-0.05f64..0.05, 0.0f64..0.4),
        any::<bool>(),
    )
        .prop_map(|(block, weights, shrink, force, seismic)| RandomPoint {
            block,
            weights,
            shrink,
            force,
            seismic,
        });
    (
        proptest::collection::vec(point, 0..4),
        proptest::option::of((0.0f64..1.5, 0.0f64..30_000.0, any::<bool>())),
        -0.5f64..0.5,
    )
        .prop_map(|(points, fill, vertical_ratio)| RandomLoads {
            points,
            fill,
            vertical_ratio,
        })
}

/// The scene text of `base` with the random loads placed on its blocks.
fn place_loads(base: &str, s: &Scene, loads: &RandomLoads) -> String {
    let m = voussoir::scene::build(s).expect("base scene builds");
    let a = &m.assembly;
    let total: f64 = a.blocks.iter().map(|b| b.weight).sum();
    let mut text = base.to_string();
    for p in &loads.points {
        let (sel, w, shrink, (fx, fy), seismic) =
            (p.block, p.weights, p.shrink, p.force, p.seismic);
        let i = ((sel * a.blocks.len() as f64) as usize).min(a.blocks.len() - 1);
        let b = &a.blocks[i];
        let ws: f64 = w.iter().sum::<f64>().max(1e-12);
        let mut p = Vec2::zeros();
        for (k, v) in b.polygon.iter().enumerate() {
            p += (w[k % 4] / ws) * v;
        }
        if b.polygon.len() != 4 || w.iter().sum::<f64>() < 1e-12 {
            p = b.centroid;
        }
        let at = b.centroid + shrink * (p - b.centroid);
        text += &point_load(at, Vec2::new(fx * total, -fy * total), seismic);
    }
    if let Some((extra, gamma, seismic)) = loads.fill {
        let crown = s
            .arch
            .as_ref()
            .expect("arch")
            .shape
            .crown_extrados(s.arch.as_ref().expect("arch").thickness);
        text += &fill(crown + extra, gamma, seismic);
    }
    text + &vertical_ratio(loads.vertical_ratio)
}

proptest! {
    #![proptest_config(ProptestConfig {
        cases: 32,
        failure_persistence: None,
        rng_seed: RngSeed::Fixed(0x10ad_5eed),
        ..ProptestConfig::default()
    })]

    #[test]
    fn random_loads_on_random_scenes(base in random_scene(), loads in random_loads()) {
        // The generator's ranges reach a few invalid geometries (e.g. a basket thicker than
        // twice its side radius): those are the scene validator's business, not the loads'.
        let plain = Scene::from_toml_str(&base, "random.toml");
        prop_assume!(plain.is_ok());
        let text = place_loads(&base, &plain.unwrap(), &loads);
        let s = Scene::from_toml_str(&text, "random.toml");
        let s = match s {
            Ok(s) => s,
            Err(e) => return Err(TestCaseError::fail(format!("loaded scene rejected: {e}\n{text}"))),
        };
        let m = voussoir::scene::build(&s).expect("builds");
        let infinite = s.material.friction.is_infinite();
        for d in [Direction::Right, Direction::Left] {
            let st = statics::analyse(&m, &StaticSettings::default().direction(d));
            let st = match st {
                Ok(r) => r,
                Err(e) => return Err(TestCaseError::fail(format!("static analysis failed: {e}\n{text}"))),
            };
            let kin = match kinematic::analyse(&m, &KinematicSettings::default().direction(d)) {
                Ok(r) => r,
                Err(e) => return Err(TestCaseError::fail(format!("kinematic analysis failed: {e}\n{text}"))),
            };
            if let Some(l) = st.lambda {
                prop_assert!(l.is_finite() && l >= 0.0);
            }
            if let Some(l) = kin.lambda_upper {
                prop_assert!(l.is_finite() && l >= 0.0);
            }
            eprintln!(
                "random {d:?} mu={}: static {:?} {:?}, kinematic {:?} {:?}",
                s.material.friction, st.status, st.lambda, kin.status, kin.lambda_upper
            );
            if infinite {
                prop_assert_eq!(st.status, kin.status, "statuses\n{}", text);
                if st.status == Status::Collapse {
                    let (a, b) = (st.lambda.unwrap(), kin.lambda_upper.unwrap());
                    prop_assert!(rel(a, b) <= 1e-6, "static {} vs kinematic {}\n{}", a, b, text);
                }
            } else if let (Some(a), Some(b)) = (st.lambda, kin.lambda_upper) {
                // Rotational mechanisms bound the multiplier from above for any friction.
                prop_assert!(b >= a * (1.0 - 1e-6), "static {} above kinematic {}\n{}", a, b, text);
            }
        }
    }
}

// ---------------------------------------------------------------------------------------------
// 7. Bad input names the key and the value.

const GOOD: &str = "[arch]\nshape = \"circular\"\nradius = 2.0\nthickness = 0.3\nvoussoirs = 12\n";

fn bad_cases() -> Vec<(String, &'static str, &'static str)> {
    vec![
        (
            format!(
                "{GOOD}{}",
                point_load(Vec2::new(5.0, 9.0), Vec2::new(0.0, -1000.0), true)
            ),
            "loads[0].at",
            "[5, 9]",
        ),
        (
            format!(
                "{GOOD}{}{}",
                point_load(Vec2::new(0.0, 2.0), Vec2::new(0.0, -1000.0), true),
                line_load(0.5, 0.25, 1000.0, true)
            ),
            "loads[1].to_x",
            "0.25",
        ),
        (
            format!("{GOOD}{}", line_load(0.5, 0.5, 1000.0, true)),
            "loads[0].to_x",
            "0.5",
        ),
        (
            format!("{GOOD}{}", fill(2.125, 18000.0, true)),
            "fill.level",
            "2.125",
        ),
        (
            format!("{GOOD}{}", vertical_ratio(1.5)),
            "seismic.vertical_ratio",
            "1.5",
        ),
        (
            format!("{GOOD}{}", vertical_ratio(-1.25)),
            "seismic.vertical_ratio",
            "-1.25",
        ),
    ]
}

#[test]
fn bad_loads_name_their_key_and_value() {
    for (text, key, value) in bad_cases() {
        // A scene is refused when read, or when its model is built (a load on no block).
        let e = match Scene::from_toml_str(&text, "bad.toml")
            .and_then(|s| voussoir::scene::build(&s).map(|_| s))
        {
            Ok(_) => panic!("scene should be rejected:\n{text}"),
            Err(e) => e,
        };
        assert_eq!(e.key(), Some(key), "{e}");
        let msg = e.to_string();
        assert!(
            msg.contains("bad.toml") && msg.contains(key) && msg.contains(value),
            "{msg}"
        );
    }
}

#[test]
fn cli_reports_bad_loads_on_stderr() {
    let dir = tempfile::tempdir().expect("temp dir");
    for (k, (text, key, value)) in bad_cases().into_iter().enumerate() {
        let path = dir.path().join(format!("bad{k}.toml"));
        std::fs::write(&path, &text).expect("write scene");
        let out = assert_cmd::Command::cargo_bin("voussoir")
            .expect("binary built")
            .arg("analyze")
            .arg(&path)
            .output()
            .expect("runs");
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(!out.status.success(), "{key}: exit status {:?}", out.status);
        assert!(
            out.stdout.is_empty(),
            "{key}: stdout {:?}",
            String::from_utf8_lossy(&out.stdout)
        );
        assert!(
            stderr.contains(key) && stderr.contains(value),
            "{key}: {stderr}"
        );
        assert!(stderr.contains(&format!("bad{k}.toml")), "{stderr}");
    }
}

// ---------------------------------------------------------------------------------------------
// The bundled load scenes.

#[test]
fn bundled_load_scenes_analyse() {
    for name in ["loaded_portal.toml", "filled_arch.toml"] {
        let path = std::path::PathBuf::from(env!("CARGO_MANIFEST_DIR"))
            .join("data")
            .join(name);
        let s = Scene::from_file(&path).expect("bundled scene is valid");
        let m = voussoir::scene::build(&s).expect("builds");
        assert!(
            m.loads.applied().len() > m.assembly.blocks.len(),
            "{name} has loads"
        );
        let st = statics(&m, Direction::Right);
        let kin = kinematics(&m, Direction::Right);
        assert_eq!(st.status, Status::Collapse, "{name}");
        let (a, b) = (st.lambda.unwrap(), kin.lambda_upper.unwrap());
        eprintln!("{name}: static {a:.6}, kinematic {b:.6}");
        assert!(rel(a, b) <= 1e-6, "{name}: {a} vs {b}");
        let out = assert_cmd::Command::cargo_bin("voussoir")
            .expect("binary built")
            .arg("analyze")
            .arg(&path)
            .output()
            .expect("runs");
        assert!(
            out.status.success(),
            "{name}: {}",
            String::from_utf8_lossy(&out.stderr)
        );
    }
}

// ---------------------------------------------------------------------------------------------
// The continuous model under loads: the limit of infinitely many voussoirs.

/// The continuous model integrates fill and line loads along the extrados and places point
/// loads at their polar angle; the discrete arch with curved voussoirs (the same ring, the same
/// loads per definition) converges to it from above as the voussoirs multiply, on every shape
/// (pointed keystones and basket transitions included) and on a portal.
#[test]
fn continuous_model_is_the_limit_of_the_discrete_arch_under_loads() {
    let pointed = "[arch]\nshape = \"pointed\"\nradius = 2.0\neccentricity = 0.5\nthickness = 0.4\nvoussoirs = 16\nvoussoir_shape = \"curved\"\n[fill]\nlevel = 2.6\n[[loads]]\ntype = \"point\"\nat = [0.02, 1.85]\nforce = [0.0, -4000.0]\n[[loads]]\ntype = \"line\"\nfrom_x = -0.3\nto_x = 1.0\nintensity = 3000.0\nseismic = false\n[seismic]\nvertical_ratio = -0.2\n";
    let basket = "[arch]\nshape = \"basket\"\nspan = 4.0\nrise = 1.4\nthickness = 0.35\nvoussoirs = 15\nvoussoir_shape = \"curved\"\n[piers]\nheight = 1.5\nwidth = 0.9\ncourses = 2\n[fill]\nlevel = 1.9\nunit_weight = 15000.0\nseismic = false\n[[loads]]\ntype = \"point\"\nat = [-0.5, 1.35]\nforce = [500.0, -3000.0]\n[[loads]]\ntype = \"line\"\nfrom_x = -2.5\nto_x = 0.5\nintensity = 2000.0\n";
    let circle = "[arch]\nshape = \"circular\"\nradius = 2.0\nembrace_deg = 150.0\nthickness = 0.3\nvoussoirs = 16\nvoussoir_shape = \"curved\"\n[fill]\nlevel = 2.5\n[[loads]]\ntype = \"point\"\nat = [-0.7, 1.85]\nforce = [0.0, -2500.0]\n[seismic]\nvertical_ratio = 0.25\n";
    let cases = [
        ("pointed", pointed, vec![16, 32, 88]),
        ("basket portal", basket, vec![15, 60, 240]),
        ("segmental", circle, vec![16, 64, 256]),
        ("filled_arch.toml", "", vec![24, 96, 384]),
    ];
    for (label, text, counts) in cases {
        let base = if text.is_empty() {
            Scene::from_file(std::path::Path::new(concat!(
                env!("CARGO_MANIFEST_DIR"),
                "/data/filled_arch.toml"
            )))
            .expect("bundled scene")
        } else {
            scene(text)
        };
        for d in [Direction::Right, Direction::Left] {
            let c = voussoir::analysis::continuous(&base, d).expect("continuous model runs");
            assert_eq!(c.status, Status::Collapse, "{label}");
            let lc = c.lambda_continuous.expect("continuous multiplier");
            let mut last = f64::INFINITY;
            for &n in &counts {
                let s = base
                    .with_override(&format!("arch.voussoirs={n}"))
                    .expect("valid count");
                let m = voussoir::scene::build(&s).expect("builds");
                let l = statics(&m, d).lambda.expect("collapse");
                // The discrete arch can only hinge at its joints: never weaker than the
                // continuum (up to the solvers' accuracy).
                assert!(l >= lc * (1.0 - 1e-7), "{label} {d:?} n = {n}: {l} < {lc}");
                let err = rel(l, lc);
                assert!(
                    err < last,
                    "{label} {d:?}: error {err} at n = {n} after {last}"
                );
                last = err;
            }
            assert!(
                last < 2e-3,
                "{label} {d:?}: still {last} from the continuum"
            );
        }
    }
}

/// Under loads that are not symmetric the multipliers equilibrium allows may all lie above 0:
/// pushed the right way the arch holds a little earthquake, yet without one it falls. Both
/// bounds must say it cannot stand, in both directions, exactly when lambda = 0 has no
/// equilibrium (the phase-one test), and stand again once it is thick enough.
#[test]
fn an_arch_that_cannot_carry_its_loads_without_an_earthquake_cannot_stand() {
    let text = |t: f64| {
        format!(
            "[arch]\nshape = \"circular\"\nradius = 1.0\nthickness = {t}\nvoussoirs = 16\n[[loads]]\ntype = \"point\"\nat = [0.5, 0.866]\nforce = [0.0, -1000.0]\n"
        )
    };
    for (t, stands) in [(0.12, false), (0.13, true)] {
        let m = build(&text(t));
        let st = statics::stands(&m, &StaticSettings::default()).expect("phase one");
        assert_eq!(st.stands, stands, "t = {t}");
        for d in [Direction::Right, Direction::Left] {
            let s = statics(&m, d);
            let k = kinematics(&m, d);
            let expected = if stands {
                Status::Collapse
            } else {
                Status::CannotStand
            };
            assert_eq!(s.status, expected, "t = {t} {d:?} static");
            assert_eq!(k.status, expected, "t = {t} {d:?} kinematic");
        }
    }
}

/// The minimum thickness under loads: the search stays below the thickness at which the
/// crown would rise above the fill, and the static and kinematic searches agree.
#[test]
fn minimum_thickness_under_fill_and_asymmetric_loads() {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/data/filled_arch.toml");
    let s = Scene::from_file(std::path::Path::new(path)).expect("bundled scene");
    let t_max = s.max_thickness();
    let fill = s.fill.as_ref().expect("fill").level;
    assert!(s.arch.as_ref().expect("arch").shape.crown_extrados(t_max) <= fill * (1.0 + 1e-12));
    assert!(s.with_thickness(0.999 * t_max).is_ok());
    let options = voussoir::analysis::Options {
        kinematic: voussoir::analysis::KinematicMode::Exhaustive,
        ..Default::default()
    };
    let t = voussoir::thickness::analyse(&s, &options).expect("thickness search");
    let ts = t.lower.search.min_thickness.expect("static t_min");
    let tk = t
        .kinematic
        .as_ref()
        .and_then(|k| k.min_thickness)
        .expect("kinematic t_min");
    assert!(
        ts < s.arch.as_ref().expect("arch").thickness && rel(ts, tk) < 1e-6,
        "{ts} vs {tk}"
    );
    // At the minimum thickness the arch just stands; a little thinner it does not.
    let stands = |t: f64| {
        statics::stands(
            &build_scene(&s.with_thickness(t).expect("valid")),
            &StaticSettings::default(),
        )
        .expect("phase one")
        .stands
    };
    assert!(stands(ts * (1.0 + 1e-6)) && !stands(ts * (1.0 - 1e-4)));
}

fn build_scene(s: &Scene) -> Model {
    voussoir::scene::build(s).expect("builds")
}

/// Below the springing line of a horseshoe the extrados faces down: the fill and line loads
/// rest on the voussoirs above, once. The fill pieces cover the upward extrados's x-range
/// without overlap, and their total is the area between the level and the extrados polyline
/// computed as one polygon.
#[test]
fn horseshoe_fill_and_line_loads_are_counted_once() {
    let text = "[arch]\nshape = \"circular\"\nradius = 1.0\nembrace_deg = 240.0\nthickness = 0.2\nvoussoirs = 24\n[fill]\nlevel = 1.3\nunit_weight = 10000.0\n[[loads]]\ntype = \"line\"\nfrom_x = -2.0\nto_x = 2.0\nintensity = 1000.0\nseismic = false\n";
    let m = build(text);
    let fills: Vec<&voussoir::model::AppliedLoad> = m
        .loads
        .applied()
        .iter()
        .filter(|l| l.source == voussoir::model::LoadSource::Fill)
        .collect();
    let mut ranges: Vec<(f64, f64)> = fills
        .iter()
        .map(|l| {
            let r = l.region.as_ref().expect("region");
            let xs = r.iter().map(|p| p.x);
            (
                xs.clone().fold(f64::INFINITY, f64::min),
                xs.fold(f64::NEG_INFINITY, f64::max),
            )
        })
        .collect();
    ranges.sort_by(|a, b| a.0.total_cmp(&b.0));
    for w in ranges.windows(2) {
        assert!(w[1].0 >= w[0].1 - 1e-12, "fill pieces overlap: {w:?}");
    }
    // The upward extrados polyline: the voussoirs' extrados corners running left to right.
    let mut top: Vec<Vec2> = Vec::new();
    for b in &m.assembly.blocks {
        let (p, q) = (b.polygon[1], b.polygon[2]);
        if q.x > p.x {
            if top.last().is_none_or(|l| (l - p).norm() > 1e-12) {
                top.push(p);
            }
            top.push(q);
        }
    }
    let (x0, x1) = (top[0].x, top[top.len() - 1].x);
    assert!((x0 - ranges[0].0).abs() < 1e-12 && (x1 - ranges[ranges.len() - 1].1).abs() < 1e-12);
    let mut poly = top.clone();
    poly.push(Vec2::new(x1, 1.3));
    poly.push(Vec2::new(x0, 1.3));
    let (area, _) = polygon_area_centroid(&poly);
    let total: f64 = fills.iter().map(|l| -l.force.y).sum();
    assert!(
        rel(total, 10000.0 * area) < 1e-12,
        "{total} vs {}",
        10000.0 * area
    );
    // The line load: 1 kN/m over the upward extrados's width, no more.
    let line: f64 = m
        .loads
        .applied()
        .iter()
        .filter(|l| l.source == voussoir::model::LoadSource::Load(0))
        .map(|l| -l.force.y)
        .sum();
    assert!(
        rel(line, 1000.0 * (x1 - x0)) < 1e-12,
        "{line} vs {}",
        1000.0 * (x1 - x0)
    );
}

/// A line load that touches no block, and loads too large to add up, are errors naming their
/// key, not silently dropped or overflowing.
#[test]
fn loads_that_miss_or_overflow_are_refused() {
    let base = "[arch]\nshape = \"circular\"\nradius = 1.0\nthickness = 0.15\nvoussoirs = 16\n";
    for (extra, key) in [
        (
            "[[loads]]\ntype = \"line\"\nfrom_x = 5.0\nto_x = 6.0\nintensity = 100.0\n",
            "loads[0].from_x",
        ),
        (
            "[[loads]]\ntype = \"point\"\nat = [0.0, 1.0]\nforce = [1e308, -1e308]\n",
            "loads[0].force",
        ),
        (
            "[[loads]]\ntype = \"line\"\nfrom_x = -1.0\nto_x = 1.0\nintensity = 1e300\n",
            "loads[0].intensity",
        ),
        ("[fill]\nlevel = 1e300\n", "fill.level"),
        (
            "[fill]\nlevel = 1.5\nunit_weight = 1e300\n",
            "fill.unit_weight",
        ),
    ] {
        let e = Scene::from_toml_str(&format!("{base}{extra}"), "t.toml")
            .and_then(|s| voussoir::scene::build(&s).map(|_| s))
            .expect_err(extra);
        assert_eq!(e.key(), Some(key), "{e}");
    }
}

// ---------------------------------------------------------------------------------------------
// An entry of [[loads]] set by `--set loads[N].KEY=VALUE` (and so by sweeps, the Python
// package and the page): the same scene as the file written with that value.

#[test]
fn set_reaches_an_entry_of_loads() {
    let base = arch(SEMICIRCLE, 0.3, 16, false)
        + "[material]\nunit_weight = 20000.0\ndepth = 1.0\n"
        + &point_load(Vec2::new(0.9, 1.9), Vec2::new(0.0, -3000.0), true)
        + &line_load(-1.0, 1.0, 2000.0, false);
    let s = scene(&base);
    let lambda = |s: &Scene| lambda_static(&voussoir::scene::build(s).expect("builds"));
    // A new intensity, by override and by file.
    let by_set = s
        .with_override("loads[1].intensity=5000")
        .expect("override");
    let by_file = scene(&base.replace("intensity = 2000.0", "intensity = 5000.0"));
    assert_eq!(lambda(&by_set), lambda(&by_file));
    assert!(
        lambda(&by_set) < lambda(&s),
        "a heavier deck load lowers lambda here"
    );
    // A line load of intensity 0 is no load: the scene without that entry.
    let zero = s.with_override("loads[1].intensity=0").expect("override");
    let without = scene(
        &(arch(SEMICIRCLE, 0.3, 16, false)
            + "[material]\nunit_weight = 20000.0\ndepth = 1.0\n"
            + &point_load(Vec2::new(0.9, 1.9), Vec2::new(0.0, -3000.0), true)),
    );
    assert!(rel(lambda(&zero), lambda(&without)) <= 1e-12);
    // A pair, whole.
    let moved = s
        .with_override("loads[0].force=[0.0, -6000.0]")
        .expect("override");
    let by_file = scene(&base.replace("force = [0.0, -3000.0]", "force = [0.0, -6000.0]"));
    assert_eq!(lambda(&moved), lambda(&by_file));
    // Errors name the entry.
    let err = s
        .with_override("loads[2].intensity=1")
        .expect_err("no third load");
    assert!(err.to_string().contains("has 2 [[loads]]"), "{err}");
    let err = s
        .with_override("loads[x].intensity=1")
        .expect_err("bad index");
    assert!(err.to_string().contains("loads[N].KEY"), "{err}");
    let err = s
        .with_override("loads[1].colour=1")
        .expect_err("unknown key");
    assert_eq!(err.key(), Some("loads[1].colour"), "{err}");
    let err = s
        .with_override("loads[1].intensity=-5")
        .expect_err("negative");
    assert_eq!(err.key(), Some("loads[1].intensity"), "{err}");
}

/// A point load in a curved voussoir whose joints are not radial (vertical, or horizontal
/// beds) belongs to that voussoir: its mirror image, loaded the other way, gives the same
/// multiplier. The joint lines of such a voussoir meet in a wedge that crosses the ring again
/// on its far side, where a point of the far voussoir was once taken for one of this one (the
/// springing voussoir on the left held the load at (1.055, 0.307) of a 9-voussoir ring with
/// 30 deg beds, and the arch "could not stand").
#[test]
fn point_loads_in_curved_voussoirs_with_non_radial_joints_are_mirror_symmetric() {
    for joints in [
        "joints = \"vertical\"\n",
        "joints = \"horizontal_bed\"\nhorizontal_bed_deg = 30.0\n",
        "joints = \"horizontal_bed\"\nhorizontal_bed_deg = 60.0\n",
    ] {
        // Angles (at r = 1.099) off every joint: a point on a joint belongs to the first
        // voussoir in chain order, which its mirror image does not.
        for angle_deg in [8.0_f64, 16.0, 25.0, 50.0, 70.0] {
            let (s, c) = angle_deg.to_radians().sin_cos();
            let lambda = |x: f64, d: Direction| {
                let text = format!(
                    "[arch]\nshape = \"circular\"\nradius = 1.0\nthickness = 0.2\nvoussoirs = 9\nvoussoir_shape = \"curved\"\n{joints}{}",
                    point_load(Vec2::new(x * 1.099, 1.099 * s), Vec2::new(0.0, -3000.0), true)
                );
                let r = statics(&build(&text), d);
                assert_eq!(r.status, Status::Collapse, "{text}");
                r.lambda.expect("collapse")
            };
            let (right, left) = (lambda(c, Direction::Right), lambda(-c, Direction::Left));
            assert!(
                rel(right, left) <= 1e-9,
                "{joints} at {angle_deg} deg: {right} vs mirrored {left}"
            );
        }
    }
}

/// A point load on a joint is shared equally by the blocks that meet there, so a structure
/// and its mirror image carry it alike: on an 8-voussoir semicircle (a joint at the crown)
/// and a 6-voussoir pointed arch, loads at the extrados and intrados ends of every joint,
/// and at the crown, give the same multiplier as their mirror images loaded the other way,
/// by both bounds. Before, the whole load went to the first block in chain order, and the
/// two differed.
#[test]
fn point_loads_on_joints_are_shared_and_mirror_symmetric() {
    for (shape, n) in [(SEMICIRCLE, 8), (POINTED, 6)] {
        let base = arch(shape, 0.3, n, false);
        let model = build(&base);
        // Both ends of every interior joint of the ring (the springings are supports).
        let ends: Vec<Vec2> = model
            .assembly
            .joints
            .iter()
            .filter(|j| j.from.is_some() && j.to.is_some())
            .flat_map(|j| [j.p1, j.p2])
            .collect();
        assert_eq!(ends.len(), 2 * (n - 1), "{shape}");
        for p in ends {
            let text = |x: f64| {
                format!(
                    "{base}{}",
                    point_load(Vec2::new(x, p.y), Vec2::new(0.0, -4000.0), true)
                )
            };
            let m = build(&text(p.x));
            // Two equal halves, one on each block of the joint, at the point itself.
            let shares: Vec<_> = m
                .loads
                .applied()
                .iter()
                .filter(|a| a.source == voussoir::model::LoadSource::Load(0))
                .collect();
            assert_eq!(shares.len(), 2, "{shape} at {p:?}");
            assert_ne!(shares[0].block, shares[1].block);
            for a in &shares {
                assert!(rel(a.force.y, -2000.0) <= 1e-12, "{shape} at {p:?}: {a:?}");
                assert!(rel(a.seismic_weight, 2000.0) <= 1e-12);
                assert_eq!(a.point, p);
            }
            let mirror = build(&text(-p.x));
            for (d, dm) in [
                (Direction::Right, Direction::Left),
                (Direction::Left, Direction::Right),
            ] {
                let (s, sm) = (statics(&m, d), statics(&mirror, dm));
                assert_eq!(s.status, sm.status, "{shape} at {p:?}");
                if let (Some(a), Some(b)) = (s.lambda, sm.lambda) {
                    assert!(
                        rel(a, b) <= 1e-9,
                        "{shape} at {p:?} {d:?}: static {a} vs mirrored {b}"
                    );
                }
                let (k, km) = (kinematics(&m, d), kinematics(&mirror, dm));
                if let (Some(a), Some(b)) = (k.lambda_upper, km.lambda_upper) {
                    assert!(
                        rel(a, b) <= 1e-9,
                        "{shape} at {p:?} {d:?}: kinematic {a} vs mirrored {b}"
                    );
                }
            }
        }
    }
}
