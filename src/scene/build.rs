//! The one place a scene becomes a model: the blocks and joints of the arch (and piers), then
//! the loads of `[[loads]]`, `[fill]` and `[seismic]` placed on those blocks.
//!
//! Load placement (the scene-key contract of the load-case issue):
//! - a point load acts on the block whose outline contains `at` (the first such block in chain
//!   order when the point lies on a joint);
//! - a line load of intensity `q` over `[from_x, to_x]` puts `q * overlap` on every voussoir,
//!   where `overlap` is the overlap of `[from_x, to_x]` with the x-range of its extrados edge,
//!   at the point of that edge at the overlap's mid x; on a portal the exposed part of each
//!   pier top (outside the arch's springing) is loaded the same way. Only extrados edges that
//!   face up (their corners run left to right) carry line loads and fill: below the springing
//!   line of a horseshoe arch the extrados faces down, and the load above it rests on the
//!   voussoirs higher up;
//! - the fill over voussoir i is the region above its extrados edge (the chord for polygon
//!   voussoirs, the arc for curved ones), below `y = level`, between the verticals through its
//!   two extrados corners; its weight `unit_weight * depth * area` acts at the region's
//!   centroid;
//! - a seismic load is also a seismic mass of weight `|force_y|` (point), `q * overlap`
//!   (line) or its own weight (fill) at the same point.

use super::{piers, LoadSpec, Scene, VoussoirShape};
use crate::assembly::{Assembly, Block, BlockKind, Joint, JointKind};
use crate::error::SceneError;
use crate::geometry::{circular_segment, cross, polygon_area_centroid, ArchGeometry, Vec2};
use crate::model::{AppliedLoad, LoadCase, LoadSource, Model, SpreadLoad};

thread_local! {
    /// Models built on this thread ([`build`] calls): see [`builds_on_this_thread`].
    static BUILDS: std::cell::Cell<u64> = const { std::cell::Cell::new(0) };
}

/// How many models [`build`] has built on the calling thread so far: a test counts the builds
/// an analysis makes (one per analysis, one per step of a thickness search), and the counter
/// costs one increment per build.
pub fn builds_on_this_thread() -> u64 {
    BUILDS.with(std::cell::Cell::get)
}

/// Build the assembly and load case of a scene: the one place a scene becomes a model, run
/// once per analysis (a [`Scene`] holds values only). A tie whose capacity is `"design"` is
/// refused: only a retrofit design sizes it ([`build_for_design`]).
pub fn build(scene: &Scene) -> Result<Model, SceneError> {
    if let Some(k) = scene.ties.iter().position(|t| t.capacity.is_none()) {
        return Err(SceneError::OutOfRange {
            origin: scene.origin.clone(),
            key: format!("ties[{k}].capacity"),
            value: "\"design\"".into(),
            allowed: "a number in N for an analysis: a capacity to be designed is sized by `voussoir retrofit` (run that, or give the capacity)".into(),
        });
    }
    build_model(scene)
}

/// [`build`] for a retrofit design: the ties whose capacity is `"design"` get their
/// prestress as capacity for now; the design sizes them.
pub fn build_for_design(scene: &Scene) -> Result<Model, SceneError> {
    build_model(scene)
}

fn build_model(scene: &Scene) -> Result<Model, SceneError> {
    BUILDS.with(|b| b.set(b.get() + 1));
    let strength = crate::model::Strength {
        compressive: scene.material.compressive_strength,
        depth: scene.material.depth,
    };
    let a = match (&scene.arch, &scene.blocks) {
        (Some(a), _) => a,
        (None, Some(b)) => {
            let mut model = super::user_blocks::build_model(
                b,
                &scene.loads,
                scene.fill.as_ref(),
                scene.material.depth,
                scene.seismic.vertical_ratio,
                strength,
                &scene.origin,
            )?;
            model.loads = model.loads.with_action(scene.action);
            let tol = b.detected.tolerance;
            model.ties = super::ties::anchor_ties(
                &scene.ties,
                &model.assembly,
                |p| super::user_blocks::first_containing(&model.assembly, p, tol),
                tol,
                &scene.origin,
            )?;
            return Ok(model);
        }
        (None, None) => {
            return Err(SceneError::MissingKey {
                origin: scene.origin.clone(),
                key: "arch".into(),
                what: "the [arch] table or [blocks]".into(),
            })
        }
    };
    let (assembly, arch) = build_assembly(scene, a)?;
    let loads = build_loads(scene, &assembly, &arch)?;
    let tol = 1e-9 * assembly.size();
    let ties = super::ties::anchor_ties(
        &scene.ties,
        &assembly,
        |p| containing_block(&assembly, &arch, p, tol),
        tol,
        &scene.origin,
    )?;
    Ok(Model {
        assembly,
        loads,
        strength,
        ties,
        strips: Vec::new(),
    })
}

/// Where the arch's blocks sit in the assembly, for placing loads.
struct ArchPlacement {
    geometry: ArchGeometry,
    /// Index of voussoir 0 in the assembly.
    first: usize,
    curved: bool,
    /// Exposed pier tops `(block, x_from, x_to)` at y = 0.
    pier_tops: Vec<(usize, f64, f64)>,
}

/// The blocks and joints of a scene: the left pier courses from the base up, the voussoirs
/// from left to right, the right pier courses from the top down (a chain).
fn build_assembly(
    scene: &Scene,
    a: &super::ArchSpec,
) -> Result<(Assembly, ArchPlacement), SceneError> {
    let g = a.geometry().map_err(|why| SceneError::OutOfRange {
        origin: scene.origin.clone(),
        key: "arch.joints".into(),
        value: format!("\"{}\"", a.joints.name()),
        allowed: why,
    })?;
    let gamma = scene.material.unit_weight * scene.material.depth;
    let mu = scene.material.friction;
    let curved = a.voussoir_shape == VoussoirShape::Curved;
    let n = g.voussoirs();

    let mut blocks = Vec::new();
    let mut joints = Vec::new();
    let (kl, kr) = scene
        .piers
        .as_ref()
        .map_or((0, 0), |p| (p.left.courses, p.right.courses));
    let chain_joint = |p1, p2, idx: usize, last: usize, kind| Joint {
        p1,
        p2,
        from: idx.checked_sub(1),
        to: (idx < last).then_some(idx),
        friction: mu,
        kind,
    };
    let total_blocks = n + kl + kr;
    let mut pier_tops = Vec::new();

    // Left pier, base to top.
    let (xi, xe) = (g.joints[0].0.x, g.joints[0].1.x);
    let (xi_r, xe_r) = (g.joints[n].0.x, g.joints[n].1.x);
    if let Some(p) = &scene.piers {
        for (c, course) in piers::courses(&p.left, xi, -1.0).into_iter().enumerate() {
            blocks.push(rect_block(course.polygon, gamma, BlockKind::LeftPier(c)));
            let idx = joints.len();
            joints.push(chain_joint(
                course.bed.0,
                course.bed.1,
                idx,
                total_blocks,
                JointKind::LeftPier(c),
            ));
        }
        let b = p.left.top_width();
        if xe > xi - b {
            pier_tops.push((kl - 1, xi - b, xe));
        }
    }
    let first = blocks.len();
    // Arch joints and voussoirs.
    for j in 0..=n {
        let (mut p1, mut p2) = g.joints[j];
        if let Some(p) = &scene.piers {
            // The arch rests on the pier top only where the springing joint lies on it.
            if j == 0 {
                p2 = Vec2::new(xe.max(xi - p.left.top_width()), 0.0);
                p1 = Vec2::new(xi, 0.0);
            } else if j == n {
                p1 = Vec2::new(xi_r, 0.0);
                p2 = Vec2::new(xe_r.min(xi_r + p.right.top_width()), 0.0);
            }
        }
        let idx = joints.len();
        joints.push(chain_joint(p1, p2, idx, total_blocks, JointKind::Arch(j)));
        if j < n {
            let (area, centroid) = g.voussoir_area_centroid(j, curved);
            blocks.push(Block {
                polygon: g.quad(j).to_vec(),
                area,
                centroid,
                weight: gamma * area,
                kind: BlockKind::Voussoir(j),
            });
        }
    }
    // Right pier, top to base.
    if let Some(p) = &scene.piers {
        let b = p.right.top_width();
        if xe_r < xi_r + b {
            pier_tops.push((blocks.len(), xe_r, xi_r + b));
        }
        let courses = piers::courses(&p.right, xi_r, 1.0);
        for (c, course) in courses.into_iter().enumerate().rev() {
            blocks.push(rect_block(course.polygon, gamma, BlockKind::RightPier(c)));
            let idx = joints.len();
            joints.push(chain_joint(
                course.bed.0,
                course.bed.1,
                idx,
                total_blocks,
                JointKind::RightPier(c),
            ));
        }
    }
    let placement = ArchPlacement {
        geometry: g,
        first,
        curved,
        pier_tops,
    };
    Ok((Assembly { blocks, joints }, placement))
}

fn rect_block(polygon: Vec<Vec2>, gamma: f64, kind: BlockKind) -> Block {
    let (area, centroid) = polygon_area_centroid(&polygon);
    Block {
        polygon,
        area,
        centroid,
        weight: gamma * area,
        kind,
    }
}

fn build_loads(
    scene: &Scene,
    assembly: &Assembly,
    arch: &ArchPlacement,
) -> Result<LoadCase, SceneError> {
    let mut case = LoadCase::self_weight(assembly)
        .with_vertical_ratio(scene.seismic.vertical_ratio)
        .with_action(scene.action);
    let size = assembly.size();
    for (k, spec) in scene.loads.iter().enumerate() {
        match *spec {
            LoadSpec::Point {
                at,
                force,
                seismic,
                live,
            } => {
                let p = Vec2::new(at[0], at[1]);
                let block = containing_block(assembly, arch, p, 1e-9 * size).ok_or_else(|| {
                    let (b, d) = nearest_block(assembly, p);
                    SceneError::OutOfRange {
                        origin: scene.origin.clone(),
                        key: format!("loads[{k}].at"),
                        value: format!("[{}, {}]", at[0], at[1]),
                        allowed: format!(
                            "the point lies outside every block (the nearest is block {b}, {} at {d:.3e} m; a polygon voussoir's extrados is the chord between its corners)",
                            describe(assembly.blocks[b].kind)
                        ),
                    }
                })?;
                let force = Vec2::new(force[0], force[1]);
                case.add(AppliedLoad::point(k, block, p, force, seismic).live(live));
            }
            LoadSpec::Line {
                from_x,
                to_x,
                intensity,
                seismic,
                live,
            } => {
                case.add_spread(SpreadLoad::line(k, from_x, to_x, intensity, seismic).live(live));
                let mut carried = false;
                for LoadedEdge { block, a, b, arc } in loaded_edges(arch) {
                    // The edges run left to right (a.x < b.x).
                    let lo = from_x.max(a.x);
                    let hi = to_x.min(b.x);
                    if hi <= lo {
                        continue;
                    }
                    let x = 0.5 * (lo + hi);
                    let w = intensity * (hi - lo);
                    case.add(AppliedLoad {
                        block,
                        point: edge_point(a, b, arc, x),
                        force: Vec2::new(0.0, -w),
                        seismic_weight: if seismic { w } else { 0.0 },
                        live,
                        source: LoadSource::Load(k),
                        region: None,
                    });
                    carried = true;
                }
                if !carried {
                    return Err(SceneError::OutOfRange {
                        origin: scene.origin.clone(),
                        key: format!("loads[{k}].from_x"),
                        value: format!("{from_x} (to_x = {to_x})"),
                        allowed: "the loaded length must overlap the extrados of the arch (or an exposed pier top)".into(),
                    });
                }
            }
        }
    }
    if let Some(fill) = &scene.fill {
        let gamma = fill.unit_weight * scene.material.depth;
        case.add_spread(SpreadLoad::fill(fill.level, gamma, fill.seismic));
        let g = &arch.geometry;
        for j in 0..g.voussoirs() {
            let (a, b) = (g.joints[j].1, g.joints[j + 1].1);
            if b.x <= a.x {
                // The extrados faces down here (a horseshoe below its springing line): the
                // fill above it is the fill above the voussoirs higher up, counted there.
                continue;
            }
            let Some((area, centroid, region)) =
                fill_region(a, b, fill.level, arch.curved.then(|| extrados_arc(g, j)))
            else {
                continue;
            };
            case.add(AppliedLoad::fill(
                arch.first + j,
                gamma * area,
                centroid,
                region,
                fill.seismic,
            ));
        }
    }
    Ok(case)
}

/// Centre and radius of the extrados arc of voussoir `j`.
fn extrados_arc(g: &ArchGeometry, j: usize) -> (Vec2, f64) {
    let arc = g.arcs[j];
    (arc.centre, arc.radius + 0.5 * g.thickness)
}

/// An edge that carries line loads: its block, its ends from left to right, and the arc it
/// lies on (curved voussoirs) or None (a chord or a pier top).
struct LoadedEdge {
    block: usize,
    a: Vec2,
    b: Vec2,
    arc: Option<(Vec2, f64)>,
}

/// The edges that carry line loads: the exposed pier tops and every upward-facing extrados.
fn loaded_edges(arch: &ArchPlacement) -> Vec<LoadedEdge> {
    let g = &arch.geometry;
    let piers = arch.pier_tops.iter().map(|&(block, x0, x1)| LoadedEdge {
        block,
        a: Vec2::new(x0, 0.0),
        b: Vec2::new(x1, 0.0),
        arc: None,
    });
    let voussoirs = (0..g.voussoirs()).filter_map(|j| {
        let (a, b) = (g.joints[j].1, g.joints[j + 1].1);
        // A downward-facing extrados (a horseshoe below its springing line) carries no line
        // load: the load rests on the voussoirs above it.
        (b.x > a.x).then(|| LoadedEdge {
            block: arch.first + j,
            a,
            b,
            arc: arch.curved.then(|| extrados_arc(g, j)),
        })
    });
    piers.chain(voussoirs).collect()
}

/// The point of the extrados edge from `a` to `b` (a chord, or the arc `(centre, radius)`
/// bulging away from its centre) at abscissa `x` within the edge's x-range.
fn edge_point(a: Vec2, b: Vec2, arc: Option<(Vec2, f64)>, x: f64) -> Vec2 {
    if let Some((c, r)) = arc {
        // The arc point at x on the far side of the chord from the centre.
        let dy = (r * r - (x - c.x).powi(2)).max(0.0).sqrt();
        let candidates = [Vec2::new(x, c.y + dy), Vec2::new(x, c.y - dy)];
        let mid = 0.5 * (a + b);
        let out = mid - c;
        return if (candidates[0] - c).dot(&out) >= (candidates[1] - c).dot(&out) {
            candidates[0]
        } else {
            candidates[1]
        };
    }
    if a.x == b.x {
        return 0.5 * (a + b);
    }
    let s = (x - a.x) / (b.x - a.x);
    a + s * (b - a)
}

/// Area, centroid and outline of the region above the extrados edge from `a` to `b` (chord,
/// or arc when `arc` is given), below `y = level`, between the verticals through `a` and `b`.
/// None when the region is empty (a vertical edge).
pub(super) fn fill_region(
    a: Vec2,
    b: Vec2,
    level: f64,
    arc: Option<(Vec2, f64)>,
) -> Option<(f64, Vec2, Vec<Vec2>)> {
    if a.x == b.x {
        return None;
    }
    let trapezoid = vec![a, b, Vec2::new(b.x, level), Vec2::new(a.x, level)];
    let (at, ct) = polygon_area_centroid(&trapezoid);
    let (mut area, mut moment) = (at, at * ct);
    let mut outline = trapezoid;
    if let Some((c, r)) = arc {
        // The circular segment between chord and arc lies on the side away from the centre:
        // it takes area from the fill when above the chord, adds it when below.
        let (as_, cs) = circular_segment(c, r, a, b);
        let chord_y = edge_point(a, b, None, cs.x).y;
        let sign = if cs.y > chord_y { -1.0 } else { 1.0 };
        area += sign * as_;
        moment += sign * as_ * cs;
        // Outline for drawings: the arc sampled from b back to a, then the level line.
        let (ta, tb) = ((a - c).y.atan2((a - c).x), (b - c).y.atan2((b - c).x));
        let mut d = tb - ta;
        if d > std::f64::consts::PI {
            d -= 2.0 * std::f64::consts::PI;
        } else if d < -std::f64::consts::PI {
            d += 2.0 * std::f64::consts::PI;
        }
        let steps = 8;
        outline = (0..=steps)
            .map(|i| {
                let t = ta + d * i as f64 / steps as f64;
                c + r * Vec2::new(t.cos(), t.sin())
            })
            .collect();
        outline.push(Vec2::new(b.x, level));
        outline.push(Vec2::new(a.x, level));
    }
    if area <= 0.0 {
        return None;
    }
    Some((area, moment / area, outline))
}

/// The first block (chain order) whose outline contains `p` within `tol`.
fn containing_block(assembly: &Assembly, arch: &ArchPlacement, p: Vec2, tol: f64) -> Option<usize> {
    (0..assembly.blocks.len()).find(|&i| {
        let poly = &assembly.blocks[i].polygon;
        let j = i.wrapping_sub(arch.first);
        if arch.curved && j < arch.geometry.voussoirs() {
            inside_curved(&arch.geometry, j, p, tol)
        } else {
            inside_convex(poly, p, tol)
        }
    })
}

/// Whether `p` lies in the convex polygon (either orientation) or within `tol` of it.
fn inside_convex(poly: &[Vec2], p: Vec2, tol: f64) -> bool {
    let m = poly.len();
    let orient = {
        let mut s = 0.0;
        for k in 0..m {
            s += cross(poly[k], poly[(k + 1) % m]);
        }
        s.signum()
    };
    (0..m).all(|k| {
        let (a, b) = (poly[k], poly[(k + 1) % m]);
        let e = b - a;
        let len = e.norm();
        len == 0.0 || orient * cross(e, p - a) / len >= -tol
    })
}

/// Whether `p` lies in the exact annular piece of curved voussoir `j`.
fn inside_curved(g: &ArchGeometry, j: usize, p: Vec2, tol: f64) -> bool {
    let q = g.quad(j);
    let arc = g.arcs[j];
    let (ri, re) = (
        arc.radius - 0.5 * g.thickness,
        arc.radius + 0.5 * g.thickness,
    );
    let r = (p - arc.centre).norm();
    // Between the two joint lines (the quad's sides p1(j)-p2(j) and p2(j+1)-p1(j+1)), and
    // between the intrados and extrados circles.
    let side = |a: Vec2, b: Vec2, inner: Vec2| {
        let e = b - a;
        let s = cross(e, inner - a).signum();
        s * cross(e, p - a) / e.norm() >= -tol
    };
    let centre = 0.25 * (q[0] + q[1] + q[2] + q[3]);
    side(q[0], q[1], centre) && side(q[2], q[3], centre) && r >= ri - tol && r <= re + tol
}

/// The block nearest to `p` (by distance to its outline's vertices and edges) and that
/// distance.
fn nearest_block(assembly: &Assembly, p: Vec2) -> (usize, f64) {
    let mut best = (0, f64::INFINITY);
    for (i, b) in assembly.blocks.iter().enumerate() {
        let m = b.polygon.len();
        for k in 0..m {
            let (a, c) = (b.polygon[k], b.polygon[(k + 1) % m]);
            let e = c - a;
            let s = if e.norm_squared() > 0.0 {
                ((p - a).dot(&e) / e.norm_squared()).clamp(0.0, 1.0)
            } else {
                0.0
            };
            let d = (a + s * e - p).norm();
            if d < best.1 {
                best = (i, d);
            }
        }
    }
    best
}

/// A block's kind in words.
fn describe(kind: BlockKind) -> String {
    match kind {
        BlockKind::Voussoir(j) => format!("voussoir {j}"),
        BlockKind::LeftPier(c) => format!("left pier course {c}"),
        BlockKind::RightPier(c) => format!("right pier course {c}"),
        BlockKind::Other => "a block".to_string(),
        BlockKind::User(i) => format!("block {i}"),
    }
}
