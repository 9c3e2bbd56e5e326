//! The general kinematic program (`voussoir::kinematic::general`, issue 23 item 3): an upper
//! bound for any assembly, certified by virtual work. By LP duality it equals the static
//! multiplier whenever friction is associative (finite friction included), and on chains it
//! equals the chain search's least multiplier. Checked here on running-bond walls, a lintel
//! portal, every bundled block scene and the chains of `bounds.rs`; the certified mechanism's
//! virtual work is recomputed here from its block velocities; mirror images give the same
//! multiplier in the mirrored direction.

use crate::common;
use voussoir::analysis::{self, KinematicMode, Options};
use voussoir::assembly::{Assembly, Block, BlockKind, Joint, JointKind};
use voussoir::geometry::{polygon_area_centroid, Vec2};
use voussoir::kinematic::{self, KinematicResult, KinematicSettings, Search};
use voussoir::model::Model;
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

/// A rectangle block of unit weight per unit area.
fn rect(x0: f64, y0: f64, x1: f64, y1: f64) -> Block {
    let polygon = vec![
        Vec2::new(x0, y0),
        Vec2::new(x1, y0),
        Vec2::new(x1, y1),
        Vec2::new(x0, y1),
    ];
    let (area, centroid) = polygon_area_centroid(&polygon);
    Block {
        polygon,
        area,
        centroid,
        weight: area,
        kind: BlockKind::Other,
    }
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
        .map(|r| rect(r[0], r[1], r[2], r[3]))
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
