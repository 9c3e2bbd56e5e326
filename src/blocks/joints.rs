//! Automatic joints between the user's blocks, and the checks that make a set of polygons a
//! structure.
//!
//! Two convex blocks whose interiors do not overlap touch, if at all, along one segment or at
//! one point (the set where they touch is convex). They share a *joint* where an edge of one
//! and an edge of the other lie on the same line, facing each other, and overlap: the joint
//! is the overlap segment. A block edge lying on the ground line `y = ground_y` with the block
//! above it is a support. Everything is compared within a tolerance
//! `tol = relative_tolerance * size` (the largest extent of the blocks that move), so a scene
//! and the same scene in millimetres find the same joints.
//!
//! Fixed blocks (a base, an abutment, rock) are no blocks of the assembly: a joint between a
//! moving block and a fixed one is a support (`from` or `to` None, like the ground), labelled
//! [`JointKind::Fixed`]. A fixed block may be non-convex, so a moving block may share several
//! faces with it (a stepped or V-shaped seat: several supports), and its overlap test cannot
//! be the separating-axis one: see `contact_fixed`. With fixed blocks the ground line is
//! only where `ground_y` puts it.
//!
//! Broad phase: sweep and prune — the blocks' bounding boxes (grown by `tol`) sorted along the
//! structure's longer axis; only pairs whose boxes overlap on both axes are examined (about
//! `n k` pairs for `k` blocks across the structure, instead of `n^2 / 2`). Each fixed block is
//! tried against the moving blocks whose boxes meet its own.
//!
//! Narrow phase for a pair of moving blocks: the separating-axis test on the edge normals of
//! both polygons (convex polygons are disjoint iff some edge normal separates them) gives the
//! largest gap; a gap above `tol` means apart, below `-tol` means overlapping (an error), in
//! between touching. Touching blocks share a joint if two edges are anti-parallel and collinear
//! within `tol` and overlap by more than `tol`; otherwise they touch at a point.
//!
//! Errors name the blocks (by their index in the source, from 0) and coordinates: a
//! self-intersecting or non-convex outline (a fixed block may be non-convex), a block without
//! area, two blocks that overlap, a block that touches the rest only at points, a block that
//! touches nothing, a block below the ground, a group of blocks that reaches neither the ground
//! nor a fixed block, and a fixed block that touches no moving block.
//!
//! The result is ordered for the analyses: a chain between two supports is numbered from the
//! support furthest left (lowest x of its joint, then lowest y) to the other, block k between
//! joints k and k + 1, as `Assembly::is_chain` expects, so the kinematic search runs on it; a
//! chain standing on one support (a column) likewise from its support; any other structure
//! keeps the source order (joints from the lower block index to the higher, supports last in
//! block order). The moving blocks are numbered from 0 in that order; each keeps its source
//! index as its name ([`BlockKind::User`]).

use super::{BlockError, Polygons};
use crate::assembly::{Assembly, Block, BlockKind, Joint, JointKind};
use crate::geometry::{cross, polygon_area_centroid, Vec2};

/// How the joints connect the blocks.
#[derive(Debug, Clone, PartialEq)]
pub enum Topology {
    /// A chain between two supports, numbered from one to the other.
    Chain,
    /// A chain standing on one support, numbered from it.
    Column,
    /// Anything else; the reason it is no chain, in words.
    Other(String),
}

/// A block that does not move (`[blocks] fixed`): a base, an abutment, rock. Its outline may
/// be non-convex; the moving blocks rest on it through support joints.
#[derive(Debug, Clone, PartialEq)]
pub struct FixedBlock {
    /// Its index in the source (from 0).
    pub block: usize,
    /// Its outline (m, counter-clockwise).
    pub polygon: Vec<Vec2>,
    /// The support joints found on it.
    pub supports: usize,
}

/// A structure found from polygons.
#[derive(Debug, Clone)]
pub struct Detected {
    /// The moving blocks (kind [`BlockKind::User`]) and their joints (kind
    /// [`JointKind::Between`], or [`JointKind::Fixed`] on a fixed block).
    pub assembly: Assembly,
    pub topology: Topology,
    /// Support joints: on the ground line and on the fixed blocks.
    pub supports: usize,
    /// The tolerance used (m).
    pub tolerance: f64,
    /// The ground line's y (m); None when there is none (only fixed blocks support).
    pub ground_y: Option<f64>,
    /// The fixed blocks, in the order they were named.
    pub fixed: Vec<FixedBlock>,
}

impl Detected {
    /// Support joints on the ground line.
    pub fn ground_supports(&self) -> usize {
        self.supports - self.fixed.iter().map(|f| f.supports).sum::<usize>()
    }
}

/// What a block touches at a point (kept to explain a block without joints).
#[derive(Debug, Clone, Copy)]
enum Other {
    Block(usize),
    Ground,
    Fixed(usize),
}

/// A joint found between blocks `a` and `b` (indices; `b = None`: a support, on the fixed
/// block `on` (its source index) or on the ground), from `p` to `q`.
#[derive(Debug, Clone, Copy)]
struct Found {
    a: usize,
    b: Option<usize>,
    on: Option<usize>,
    p: Vec2,
    q: Vec2,
}

/// Find the joints of `polygons` (counter-clockwise, metres) and build the assembly: weights
/// `gamma * area` (gamma = unit weight * depth, N/m^3 * m), joints of friction `friction`;
/// the ground is the line `y = ground_y` (default: the lowest vertex).
pub fn detect(
    polygons: &Polygons,
    ground_y: Option<f64>,
    relative_tolerance: f64,
    gamma: f64,
    friction: f64,
) -> Result<Detected, BlockError> {
    detect_with_fixed(polygons, &[], ground_y, relative_tolerance, gamma, friction)
}

/// [`detect`] with the blocks `fixed` (source indices) held fixed: they are no blocks of the
/// assembly, and a joint between a moving block and a fixed one is a support. With fixed
/// blocks the ground line is only where `ground_y` says (None: no ground, the fixed blocks
/// alone support). An error [`BlockError::Fixed`] names a fixed block by its position `k`
/// in `fixed`.
pub fn detect_with_fixed(
    polygons: &Polygons,
    fixed: &[usize],
    ground_y: Option<f64>,
    relative_tolerance: f64,
    gamma: f64,
    friction: f64,
) -> Result<Detected, BlockError> {
    let polys = &polygons.0;
    let n = polys.len();
    if n == 0 {
        return Err(BlockError::Empty("the block list is empty".into()));
    }
    let mut is_fixed = vec![false; n];
    for (k, &f) in fixed.iter().enumerate() {
        if f >= n {
            return Err(BlockError::Fixed {
                index: k,
                block: None,
                message: format!("block {f} does not exist: there are {n} blocks"),
            });
        }
        if is_fixed[f] {
            let first = fixed.iter().position(|&g| g == f).unwrap_or(k);
            return Err(BlockError::Fixed {
                index: k,
                block: Some(f),
                message: format!(
                    "lies in block {f}, as fixed[{first}] does: name each fixed block once"
                ),
            });
        }
        is_fixed[f] = true;
    }
    let movers: Vec<usize> = (0..n).filter(|&i| !is_fixed[i]).collect();
    if movers.is_empty() {
        return Err(BlockError::Structure(format!(
            "all {n} blocks are fixed: nothing is left to move"
        )));
    }
    // The structure's size, and so the tolerance, is that of the blocks that move (a fixed
    // rock may be as large as drawn).
    let size = Polygons(movers.iter().map(|&i| polys[i].clone()).collect()).size();
    let tol = relative_tolerance * size;
    let (lo, _) = polygons.bounds();
    let ground = if fixed.is_empty() {
        Some(ground_y.unwrap_or(lo.y))
    } else {
        ground_y
    };
    let ground_words = match ground {
        Some(g) => format!("the ground y = {g}"),
        None => "a fixed block".to_string(),
    };

    for (i, p) in polys.iter().enumerate() {
        check_outline(i, p, tol, !is_fixed[i])?;
        if is_fixed[i] {
            continue;
        }
        if let Some(v) = ground.and_then(|g| p.iter().find(|v| v.y < g - tol)) {
            return Err(BlockError::Block {
                block: i,
                message: format!(
                    "its vertex ({}, {}) lies below the ground y = {}; blocks rest on the ground, they do not go into it",
                    v.x,
                    v.y,
                    ground.unwrap_or_default()
                ),
            });
        }
    }

    // Broad phase: sweep and prune along the longer axis, over the moving blocks.
    let boxes: Vec<(Vec2, Vec2)> = polys
        .iter()
        .map(|p| {
            let mut lo = Vec2::repeat(f64::INFINITY);
            let mut hi = Vec2::repeat(f64::NEG_INFINITY);
            for v in p {
                lo = lo.inf(v);
                hi = hi.sup(v);
            }
            (lo - Vec2::repeat(tol), hi + Vec2::repeat(tol))
        })
        .collect();
    let apart = |i: usize, j: usize| {
        (0..2).any(|c| boxes[i].0[c] > boxes[j].1[c] || boxes[j].0[c] > boxes[i].1[c])
    };
    let (blo, bhi) = polygons.bounds();
    let axis = if bhi.x - blo.x >= bhi.y - blo.y { 0 } else { 1 };
    let mut order = movers.clone();
    order.sort_by(|&a, &b| boxes[a].0[axis].total_cmp(&boxes[b].0[axis]));
    let mut active: Vec<usize> = Vec::new();
    let mut found: Vec<Found> = Vec::new();
    // Point contacts `(a, other, point)`, kept to explain a block without joints.
    let mut points: Vec<(usize, Other, Vec2)> = Vec::new();
    let overlap = |a: usize, b: usize, by: String, at: Vec2| BlockError::Pair {
        blocks: [a, b],
        message: format!(
            "overlap ({by}, around ({:.6}, {:.6})); blocks may touch but not overlap",
            at.x, at.y
        ),
    };
    for &i in &order {
        let start = boxes[i].0[axis];
        active.retain(|&j| boxes[j].1[axis] >= start);
        for &j in &active {
            if apart(i, j) {
                continue;
            }
            let (a, b) = (i.min(j), i.max(j));
            match contact(&polys[a], &polys[b], tol) {
                Contact::Apart => {}
                Contact::Overlap(at, depth) => {
                    return Err(overlap(a, b, format!("by {depth:.3e} m"), at))
                }
                Contact::Point(at) => points.push((a, Other::Block(b), at)),
                Contact::Joint(p, q) => found.push(Found {
                    a,
                    b: Some(b),
                    on: None,
                    p,
                    q,
                }),
            }
        }
        active.push(i);
    }
    // Supports on the fixed blocks: every face a moving block shares with one (several on a
    // stepped or V-shaped seat).
    let mut fixed_blocks = Vec::with_capacity(fixed.len());
    for (k, &f) in fixed.iter().enumerate() {
        let before = found.len();
        let mut touches = None;
        for &i in &movers {
            if apart(i, f) {
                continue;
            }
            match contact_fixed(&polys[i], &polys[f], tol) {
                FixedContact::Apart => {}
                FixedContact::Overlap(at, area) => {
                    return Err(overlap(
                        i.min(f),
                        i.max(f),
                        format!("an area of {area:.3e} m^2, block {f} being fixed"),
                        at,
                    ))
                }
                FixedContact::Point(at) => {
                    points.push((i, Other::Fixed(f), at));
                    touches = touches.or(Some((i, at)));
                }
                FixedContact::Joints(joints) => {
                    found.extend(joints.into_iter().map(|(p, q)| Found {
                        a: i,
                        b: None,
                        on: Some(f),
                        p,
                        q,
                    }))
                }
            }
        }
        let supports = found.len() - before;
        if supports == 0 {
            let (lo, hi) = (
                boxes[f].0 + Vec2::repeat(tol),
                boxes[f].1 - Vec2::repeat(tol),
            );
            return Err(BlockError::Fixed {
                index: k,
                block: Some(f),
                message: match touches {
                    Some((i, at)) => format!(
                        "the fixed block {f} touches the moving blocks only at a point (block {i} at ({:.6}, {:.6})); a support is a shared edge segment",
                        at.x, at.y
                    ),
                    None => format!(
                        "the fixed block {f} (spanning ({:.6}, {:.6}) to ({:.6}, {:.6})) touches no moving block: no edge of a moving block lies along one of its edges",
                        lo.x, lo.y, hi.x, hi.y
                    ),
                },
            });
        }
        fixed_blocks.push(FixedBlock {
            block: f,
            polygon: polys[f].clone(),
            supports,
        });
    }
    // Supports on the ground line: edges on it with the block above.
    if let Some(ground) = ground {
        for &i in &movers {
            let p = &polys[i];
            let m = p.len();
            let mut on_ground = false;
            for k in 0..m {
                let (a, b) = (p[k], p[(k + 1) % m]);
                let flat = (a.y - ground).abs() <= tol && (b.y - ground).abs() <= tol;
                // Counter-clockwise: an edge running to +x has the block above it.
                if flat && b.x - a.x > tol {
                    found.push(Found {
                        a: i,
                        b: None,
                        on: None,
                        p: a,
                        q: b,
                    });
                    on_ground = true;
                }
            }
            if !on_ground {
                if let Some(v) = p.iter().find(|v| (v.y - ground).abs() <= tol) {
                    points.push((i, Other::Ground, *v));
                }
            }
        }
    }

    // Every block needs a joint; every group of blocks needs a support.
    let mut degree = vec![0usize; n];
    let mut parent: Vec<usize> = (0..n).collect();
    let mut grounded = vec![false; n];
    for f in &found {
        degree[f.a] += 1;
        match f.b {
            Some(b) => {
                degree[b] += 1;
                let (ra, rb) = (root(&mut parent, f.a), root(&mut parent, b));
                parent[ra] = rb;
            }
            None => grounded[f.a] = true,
        }
    }
    if let Some(i) = movers.iter().copied().find(|&i| degree[i] == 0) {
        let touch = points.iter().find_map(|&(a, b, at)| {
            let other = match (a == i, b) {
                (true, Other::Block(b)) => format!("block {b}"),
                (true, Other::Ground) => "the ground".to_string(),
                (true, Other::Fixed(f)) => format!("the fixed block {f}"),
                (false, Other::Block(b)) if b == i => format!("block {a}"),
                _ => return None,
            };
            Some((other, at))
        });
        let (lo, hi) = (
            boxes[i].0 + Vec2::repeat(tol),
            boxes[i].1 - Vec2::repeat(tol),
        );
        let along = match (ground, fixed.is_empty()) {
            (Some(g), true) => format!("another block's edge or the ground y = {g}"),
            (Some(g), false) => {
                format!("another block's edge, a fixed block's or the ground y = {g}")
            }
            (None, _) => "another block's edge or a fixed block's".to_string(),
        };
        return Err(BlockError::Block {
            block: i,
            message: match touch {
                Some((other, at)) => format!(
                    "it touches {other} only at the point ({:.6}, {:.6}); a block needs a joint (a shared edge segment) to carry load",
                    at.x, at.y
                ),
                None => format!(
                    "it touches nothing (its outline spans ({:.6}, {:.6}) to ({:.6}, {:.6})): no edge lies along {along}",
                    lo.x, lo.y, hi.x, hi.y
                ),
            },
        });
    }
    for &i in &movers {
        if grounded[i] {
            let r = root(&mut parent, i);
            grounded[r] = true;
        }
    }
    let mut floating: Vec<usize> = movers
        .iter()
        .copied()
        .filter(|&i| {
            let r = root(&mut parent, i);
            !grounded[r]
        })
        .collect();
    if !floating.is_empty() {
        floating.truncate(12);
        let lowest = floating
            .iter()
            .flat_map(|&i| polys[i].iter())
            .fold(f64::INFINITY, |m, v| m.min(v.y));
        let list: Vec<String> = floating.iter().map(|i| i.to_string()).collect();
        let reach = match (ground, fixed.is_empty()) {
            (Some(_), true) => ground_words.clone(),
            (Some(_), false) => format!("{ground_words} or a fixed block"),
            (None, _) => "a fixed block".to_string(),
        };
        return Err(BlockError::Structure(format!(
            "the structure does not reach {reach}: blocks {} (and any joined to them) rest on nothing; their lowest point is at y = {lowest}",
            list.join(", ")
        )));
    }

    // The moving blocks, renumbered from 0 in source order; a block's kind keeps its source
    // index, which names it.
    let mut local = vec![usize::MAX; n];
    for (k, &i) in movers.iter().enumerate() {
        local[i] = k;
    }
    let blocks: Vec<Block> = movers
        .iter()
        .map(|&i| {
            let p = &polys[i];
            let (area, centroid) = polygon_area_centroid(p);
            Block {
                polygon: p.clone(),
                area,
                centroid,
                weight: gamma * area,
                kind: BlockKind::User(i),
            }
        })
        .collect();
    let found: Vec<Found> = found
        .into_iter()
        .map(|f| Found {
            a: local[f.a],
            b: f.b.map(|b| local[b]),
            ..f
        })
        .collect();
    let supports = found.iter().filter(|f| f.b.is_none()).count();
    let (assembly, topology) = arrange(blocks, &found, friction);
    Ok(Detected {
        assembly,
        topology,
        supports,
        tolerance: tol,
        ground_y: ground,
        fixed: fixed_blocks,
    })
}

fn root(parent: &mut [usize], mut i: usize) -> usize {
    while parent[i] != i {
        parent[i] = parent[parent[i]];
        i = parent[i];
    }
    i
}

/// A self-intersecting or flat outline is an error naming where, and so is a non-convex one
/// when `convex` (a moving block) asks for it.
fn check_outline(i: usize, p: &[Vec2], tol: f64, convex: bool) -> Result<(), BlockError> {
    let m = p.len();
    let fail = |message: String| BlockError::Block { block: i, message };
    // Non-adjacent edges must not meet.
    for k in 0..m {
        for l in k + 2..m {
            if k == 0 && l == m - 1 {
                continue;
            }
            if let Some(x) = segments_cross(p[k], p[(k + 1) % m], p[l], p[(l + 1) % m]) {
                return Err(fail(format!(
                    "its outline intersects itself: edge {k} ({:.6}, {:.6})-({:.6}, {:.6}) crosses edge {l} at ({:.6}, {:.6})",
                    p[k].x,
                    p[k].y,
                    p[(k + 1) % m].x,
                    p[(k + 1) % m].y,
                    x.x,
                    x.y
                )));
            }
        }
    }
    let area2 = super::signed_area2(p);
    let perimeter: f64 = (0..m).map(|k| (p[(k + 1) % m] - p[k]).norm()).sum();
    if area2.abs() <= 2.0 * tol * perimeter {
        return Err(fail(format!(
            "its outline encloses no area (area {:.3e} m^2 for a perimeter of {perimeter:.6} m)",
            0.5 * area2.abs()
        )));
    }
    if !convex {
        return Ok(());
    }
    // Counter-clockwise: every turn to the left.
    for k in 0..m {
        let (a, b, c) = (p[(k + m - 1) % m], p[k], p[(k + 1) % m]);
        let turn = cross(b - a, c - b);
        if turn < -1e-12 * (b - a).norm() * (c - b).norm() {
            return Err(fail(format!(
                "it is not convex: its outline turns inward at vertex ({:.6}, {:.6}); split it into convex blocks (or, if it does not move, name it in `fixed`)",
                b.x, b.y
            )));
        }
    }
    Ok(())
}

/// Where two segments cross (a point common to both), if they do.
pub(super) fn segments_cross(a: Vec2, b: Vec2, c: Vec2, d: Vec2) -> Option<Vec2> {
    let r = b - a;
    let s = d - c;
    let den = cross(r, s);
    let qp = c - a;
    if den == 0.0 {
        // Parallel: they meet only when collinear and overlapping.
        if cross(qp, r) != 0.0 {
            return None;
        }
        let rr = r.dot(&r);
        let t0 = qp.dot(&r) / rr;
        let t1 = (d - a).dot(&r) / rr;
        let (lo, hi) = (t0.min(t1), t0.max(t1));
        return (hi >= 0.0 && lo <= 1.0).then(|| a + lo.max(0.0) * r);
    }
    let t = cross(qp, s) / den;
    let u = cross(qp, r) / den;
    ((0.0..=1.0).contains(&t) && (0.0..=1.0).contains(&u)).then(|| a + t * r)
}

enum Contact {
    Apart,
    /// Overlapping: a point inside both and the penetration depth.
    Overlap(Vec2, f64),
    Point(Vec2),
    Joint(Vec2, Vec2),
}

/// How two convex counter-clockwise polygons meet (module docs).
fn contact(pa: &[Vec2], pb: &[Vec2], tol: f64) -> Contact {
    // Separating axes: the outward normals of both polygons' edges.
    let mut gap = f64::NEG_INFINITY;
    for (p, q) in [(pa, pb), (pb, pa)] {
        let m = p.len();
        for k in 0..m {
            let e = p[(k + 1) % m] - p[k];
            let len = e.norm();
            let nrm = Vec2::new(e.y, -e.x) / len;
            let top = p
                .iter()
                .map(|v| v.dot(&nrm))
                .fold(f64::NEG_INFINITY, f64::max);
            let low = q.iter().map(|v| v.dot(&nrm)).fold(f64::INFINITY, f64::min);
            gap = gap.max(low - top);
        }
    }
    if gap > tol {
        return Contact::Apart;
    }
    if gap < -tol {
        let inside = clip(pa, pb);
        let at = if inside.len() >= 3 {
            polygon_area_centroid(&inside).1
        } else {
            inside.first().copied().unwrap_or(pa[0])
        };
        return Contact::Overlap(at, -gap);
    }
    // Touching: look for collinear, facing, overlapping edges; convex blocks share at most
    // one, the longest (the first of equal ones).
    let best =
        facing_edges(pa, pb, tol)
            .into_iter()
            .fold(None, |best: Option<(f64, Vec2, Vec2)>, e| match best {
                Some((l, _, _)) if e.0 <= l => best,
                _ => Some(e),
            });
    if let Some((_, p, q)) = best {
        return Contact::Joint(p, q);
    }
    match nearest_contact(pa, pb, f64::INFINITY) {
        Some(at) => Contact::Point(at),
        None => Contact::Point(pa[0]),
    }
}

/// Every pair of an edge of `pa` and an edge of `pb` (both counter-clockwise) that lie on one
/// line within `tol`, run opposite ways (so the blocks lie on either side) and overlap by more
/// than `tol`: `(overlap length, start, end)`, the overlap's ends at vertices of either.
fn facing_edges(pa: &[Vec2], pb: &[Vec2], tol: f64) -> Vec<(f64, Vec2, Vec2)> {
    let (ma, mb) = (pa.len(), pb.len());
    let mut out = Vec::new();
    for k in 0..ma {
        let (a0, a1) = (pa[k], pa[(k + 1) % ma]);
        let ea = a1 - a0;
        let la = ea.norm();
        let ua = ea / la;
        for l in 0..mb {
            let (b0, b1) = (pb[l], pb[(l + 1) % mb]);
            let eb = b1 - b0;
            // Facing edges run opposite ways (both outlines counter-clockwise).
            if ua.dot(&eb) >= 0.0 {
                continue;
            }
            if cross(ua, b0 - a0).abs() > tol || cross(ua, b1 - a0).abs() > tol {
                continue;
            }
            // Overlap of b's projection on a: [max(0, min), min(la, max)], ends at vertices.
            let (s0, s1) = ((b1 - a0).dot(&ua), (b0 - a0).dot(&ua));
            let (start, p) = if s0 > 0.0 { (s0, b1) } else { (0.0, a0) };
            let (end, q) = if s1 < la { (s1, b0) } else { (la, a1) };
            let length = end - start;
            if length > tol {
                out.push((length, p, q));
            }
        }
    }
    out
}

/// The vertex of either polygon nearest to the other's outline, if within `within`.
fn nearest_contact(pa: &[Vec2], pb: &[Vec2], within: f64) -> Option<Vec2> {
    let mut at = (f64::INFINITY, None);
    for (p, q) in [(pa, pb), (pb, pa)] {
        for v in p {
            let d = distance_to_polygon(*v, q);
            if d < at.0 {
                at = (d, Some(*v));
            }
        }
    }
    at.1.filter(|_| at.0 <= within)
}

enum FixedContact {
    Apart,
    /// Overlapping: a point inside both and the area they share.
    Overlap(Vec2, f64),
    Point(Vec2),
    /// The shared faces, from start to end.
    Joints(Vec<(Vec2, Vec2)>),
}

/// How a moving block (convex, counter-clockwise) meets a fixed one (counter-clockwise, of
/// any shape). The separating-axis test needs both convex, so the overlap is measured
/// instead: Sutherland-Hodgman clipping of the fixed outline by the convex block's
/// half-planes gives their common region (for a non-convex subject the output may have
/// zero-width bridges along a clipping line, which add no area, so its area and centroid are
/// the common region's). An area above `tol` times the moving block's perimeter (a sliver
/// deeper than `tol` along all of it) is an overlap. Otherwise every facing collinear edge
/// pair ([`facing_edges`]) is a support joint (a block may sit on several faces of one fixed
/// block: a stepped or V-shaped seat), and without one a vertex within `tol` of the other
/// outline is a point contact.
fn contact_fixed(moving: &[Vec2], fixed: &[Vec2], tol: f64) -> FixedContact {
    let common = clip(fixed, moving);
    if common.len() >= 3 {
        let (area, at) = polygon_area_centroid(&common);
        let m = moving.len();
        let perimeter: f64 = (0..m)
            .map(|k| (moving[(k + 1) % m] - moving[k]).norm())
            .sum();
        if area > tol * perimeter {
            return FixedContact::Overlap(at, area);
        }
    }
    let joints = facing_edges(moving, fixed, tol);
    if !joints.is_empty() {
        return FixedContact::Joints(joints.into_iter().map(|(_, p, q)| (p, q)).collect());
    }
    match nearest_contact(moving, fixed, tol) {
        Some(at) => FixedContact::Point(at),
        None => FixedContact::Apart,
    }
}

pub(super) fn distance_to_polygon(v: Vec2, p: &[Vec2]) -> f64 {
    let m = p.len();
    (0..m)
        .map(|k| {
            let (a, b) = (p[k], p[(k + 1) % m]);
            let e = b - a;
            let t = ((v - a).dot(&e) / e.norm_squared()).clamp(0.0, 1.0);
            (a + t * e - v).norm()
        })
        .fold(f64::INFINITY, f64::min)
}

/// The part of polygon `subject` inside convex counter-clockwise `clipper`
/// (Sutherland–Hodgman; for a non-convex subject see [`contact_fixed`]).
fn clip(subject: &[Vec2], clipper: &[Vec2]) -> Vec<Vec2> {
    let mut out = subject.to_vec();
    let m = clipper.len();
    for k in 0..m {
        let (a, b) = (clipper[k], clipper[(k + 1) % m]);
        let inside = |p: Vec2| cross(b - a, p - a) >= 0.0;
        let input = std::mem::take(&mut out);
        let r = input.len();
        for i in 0..r {
            let (p, q) = (input[i], input[(i + 1) % r]);
            match (inside(p), inside(q)) {
                (true, true) => out.push(q),
                (true, false) | (false, true) => {
                    let d = cross(b - a, q - p);
                    if d != 0.0 {
                        let t = cross(b - a, a - p) / d;
                        out.push(p + t * (q - p));
                    }
                    if inside(q) {
                        out.push(q);
                    }
                }
                (false, false) => {}
            }
        }
        if out.is_empty() {
            break;
        }
    }
    out
}

/// Number the blocks and orient the joints for the analyses (module docs).
fn arrange(blocks: Vec<Block>, found: &[Found], friction: f64) -> (Assembly, Topology) {
    let n = blocks.len();
    let mut incident: Vec<Vec<usize>> = vec![Vec::new(); n];
    for (k, f) in found.iter().enumerate() {
        incident[f.a].push(k);
        if let Some(b) = f.b {
            incident[b].push(k);
        }
    }
    let supports: Vec<usize> = (0..found.len()).filter(|&k| found[k].b.is_none()).collect();
    let path_like = incident.iter().all(|inc| inc.len() <= 2);
    let topology = if !path_like {
        let (i, inc) = incident
            .iter()
            .enumerate()
            // The first of the blocks with the most joints.
            .max_by(|a, b| a.1.len().cmp(&b.1.len()).then(b.0.cmp(&a.0)))
            .unwrap_or((0, &incident[0]));
        // The neighbours in index order, the supports last (the fixed blocks, then the
        // ground).
        let mut neighbours: Vec<(bool, Option<usize>, Option<usize>)> = inc
            .iter()
            .map(|&k| match (found[k].a == i, found[k].b) {
                (true, None) => (true, found[k].on, None),
                (true, Some(b)) => (false, None, Some(source(&blocks, b))),
                (false, _) => (false, None, Some(source(&blocks, found[k].a))),
            })
            .collect();
        neighbours.sort_by_key(|&(support, on, b)| (support, on.is_none(), on, b));
        let others: Vec<String> = neighbours
            .iter()
            .map(|&(_, on, b)| match (on, b) {
                (_, Some(b)) => b.to_string(),
                (Some(f), None) => format!("fixed {f}"),
                (None, None) => "ground".to_string(),
            })
            .collect();
        Topology::Other(format!(
            "block {} has {} joints (with {})",
            source(&blocks, i),
            inc.len(),
            others.join(", ")
        ))
    } else if supports.len() == 2 && found.len() == n + 1 {
        Topology::Chain
    } else if supports.len() == 1 && found.len() == n {
        Topology::Column
    } else if found.len() - supports.len() + 1 < n {
        // Fewer joints between blocks than a connected path needs: separate groups.
        Topology::Other(format!(
            "the blocks stand in {} separate groups",
            n - (found.len() - supports.len())
        ))
    } else {
        let on = if found.iter().any(|f| f.on.is_some()) {
            "supports"
        } else {
            "the ground"
        };
        Topology::Other(format!("{} blocks rest on {on}", supports.len()))
    };
    match topology {
        Topology::Chain | Topology::Column => {
            // Walk from the support furthest left.
            let start = supports
                .iter()
                .copied()
                .min_by(|&a, &b| {
                    let (ma, mb) = (mid(&found[a]), mid(&found[b]));
                    ma.x.total_cmp(&mb.x).then(ma.y.total_cmp(&mb.y))
                })
                .unwrap_or(0);
            let mut order = Vec::with_capacity(n);
            let mut joint_order = vec![start];
            let mut block = found[start].a;
            let mut came = start;
            loop {
                order.push(block);
                let next = incident[block].iter().copied().find(|&k| k != came);
                let Some(k) = next else { break };
                joint_order.push(k);
                let f = &found[k];
                let other = if f.a == block { f.b } else { Some(f.a) };
                match other {
                    Some(b) if order.len() < n => {
                        block = b;
                        came = k;
                    }
                    _ => break,
                }
            }
            if order.len() == n {
                let mut position = vec![0; n];
                for (pos, &b) in order.iter().enumerate() {
                    position[b] = pos;
                }
                let joints = joint_order
                    .iter()
                    .enumerate()
                    .map(|(pos, &k)| {
                        let f = &found[k];
                        let from = pos.checked_sub(1).map(|p| order[p]);
                        let to = order.get(pos).copied();
                        let (from_src, to_src) = (from, to);
                        orient(
                            f,
                            from_src.map(|b| position[b]),
                            to_src.map(|b| position[b]),
                            from_src,
                            to_src,
                            &blocks,
                            friction,
                        )
                    })
                    .collect();
                let mut ordered: Vec<Option<Block>> = blocks.into_iter().map(Some).collect();
                let blocks = order.iter().filter_map(|&b| ordered[b].take()).collect();
                return (Assembly { blocks, joints }, topology);
            }
            // A cycle among the blocks: not a chain after all.
            let joints = source_order(found, &blocks, friction);
            (
                Assembly { blocks, joints },
                Topology::Other("the blocks form a ring, not a chain".into()),
            )
        }
        Topology::Other(_) => {
            let joints = source_order(found, &blocks, friction);
            (Assembly { blocks, joints }, topology)
        }
    }
}

/// A block's index in the source (its name).
fn source(blocks: &[Block], i: usize) -> usize {
    match blocks[i].kind {
        BlockKind::User(s) => s,
        _ => i,
    }
}

fn mid(f: &Found) -> Vec2 {
    0.5 * (f.p + f.q)
}

/// Joints between blocks first, by their lower block index, then the supports.
fn source_order(found: &[Found], blocks: &[Block], friction: f64) -> Vec<Joint> {
    let mut idx: Vec<usize> = (0..found.len()).collect();
    idx.sort_by_key(|&k| (found[k].b.is_none(), found[k].a, found[k].b));
    idx.iter()
        .map(|&k| {
            let f = &found[k];
            match f.b {
                Some(b) => orient(f, Some(f.a), Some(b), Some(f.a), Some(b), blocks, friction),
                None => orient(f, None, Some(f.a), None, Some(f.a), blocks, friction),
            }
        })
        .collect()
}

/// A joint from block `from` to block `to` (assembly indices; `from_src`, `to_src` the same
/// blocks' source indices), its ends ordered so that the normal points from `from` into `to`.
fn orient(
    f: &Found,
    from: Option<usize>,
    to: Option<usize>,
    from_src: Option<usize>,
    to_src: Option<usize>,
    blocks: &[Block],
    friction: f64,
) -> Joint {
    let (mut p1, mut p2) = (f.p, f.q);
    let u = p2 - p1;
    let n = Vec2::new(u.y, -u.x);
    let m = 0.5 * (p1 + p2);
    let toward_to = match (to_src, from_src) {
        (Some(t), _) => (blocks[t].centroid - m).dot(&n) > 0.0,
        (None, Some(fr)) => (blocks[fr].centroid - m).dot(&n) < 0.0,
        (None, None) => true,
    };
    if !toward_to {
        std::mem::swap(&mut p1, &mut p2);
    }
    // The label names the two blocks by their source indices, the lower first; a support
    // names the fixed block it rests on.
    let name = |b: Option<usize>| b.map(|b| source(blocks, b));
    let kind = match (name(from_src), name(to_src), f.on) {
        (Some(a), Some(b), _) => JointKind::Between(a.min(b), Some(a.max(b))),
        (Some(a), None, Some(on)) | (None, Some(a), Some(on)) => JointKind::Fixed(a, on),
        (Some(a), None, None) | (None, Some(a), None) => JointKind::Between(a, None),
        (None, None, _) => JointKind::Other,
    };
    Joint {
        p1,
        p2,
        from,
        to,
        friction,
        kind,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rect(x0: f64, y0: f64, x1: f64, y1: f64) -> Vec<Vec2> {
        vec![
            Vec2::new(x0, y0),
            Vec2::new(x1, y0),
            Vec2::new(x1, y1),
            Vec2::new(x0, y1),
        ]
    }

    #[test]
    fn two_stacked_blocks_make_a_column() {
        let p = Polygons(vec![rect(0.0, 1.0, 1.0, 2.0), rect(0.0, 0.0, 1.0, 1.0)]);
        let d = detect(&p, None, 1e-9, 1.0, f64::INFINITY).unwrap();
        assert_eq!(d.topology, Topology::Column);
        assert_eq!(d.assembly.joints.len(), 2);
        d.assembly.validate().unwrap();
        // Numbered from the support: the source's block 1 comes first.
        assert_eq!(d.assembly.blocks[0].kind, BlockKind::User(1));
        assert_eq!(d.assembly.joints[1].kind, JointKind::Between(0, Some(1)));
        // The joint runs over the shared edge, its normal up into the upper block.
        assert!((d.assembly.joints[1].normal() - Vec2::new(0.0, 1.0)).norm() < 1e-15);
    }

    #[test]
    fn corner_contact_only_is_an_error() {
        let p = Polygons(vec![rect(0.0, 0.0, 1.0, 1.0), rect(1.0, 1.0, 2.0, 2.0)]);
        let e = detect(&p, Some(0.0), 1e-9, 1.0, f64::INFINITY).unwrap_err();
        assert!(
            e.to_string()
                .contains("only at the point (1.000000, 1.000000)"),
            "{e}"
        );
    }

    #[test]
    fn partial_overlap_of_edges_is_the_joint() {
        let p = Polygons(vec![rect(0.0, 0.0, 2.0, 1.0), rect(1.5, 1.0, 3.0, 2.0)]);
        let d = detect(&p, Some(0.0), 1e-9, 1.0, f64::INFINITY).unwrap();
        let j = &d.assembly.joints[1];
        assert!((j.length() - 0.5).abs() < 1e-15 && (j.midpoint().x - 1.75).abs() < 1e-15);
    }
}
