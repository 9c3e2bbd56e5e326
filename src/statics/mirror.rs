//! Whether an assembly is its own mirror image, in any numbering: the map from each block and
//! joint to its image about a vertical line.
//!
//! Under self-weight the mirror image of an equilibrium (or of a mechanism) at multiplier
//! `lambda` is one at `-lambda` (the horizontal action changes sign, the weights do not), so a
//! structure that is its own mirror image needs neither the phase-one program at
//! `lambda = 0` nor the kinematic program for the bottom of the interval of multipliers.
//! Parametric scenes number blocks and joints so that the image of block `i` is block
//! `n - 1 - i` about `x = 0`; the user's blocks (a wall read from a drawing, numbered course
//! by course) are matched geometrically here: the axis through the middle of the centroids'
//! extent, each block's image found among the blocks whose centroid lies within the
//! tolerance of its mirrored centroid (a grid of cells as wide as the tolerance, so O(n)),
//! each joint's likewise by its midpoint.
//!
//! What the static program sees of a block is its centroid (the moment reference and the
//! point of its weight) and its weight; of a joint its ends, the blocks on its two sides and
//! its friction. A joint's image may list its ends the other way round: written with the
//! mirrored `p1` first, its normal (pointing from `from` into `to`) is the mirror of the
//! original's reversed, so `from` and `to` swap; written with the mirrored `p2` first they
//! stay. Both describe the same contact (its `c1` and `c2` swap, `V` changes sign), and
//! [`MirrorMap::joints`] records which.

use crate::assembly::{Assembly, JointEnd};
use crate::geometry::Vec2;
use std::collections::HashMap;

/// How an assembly maps onto its own mirror image about the line `x = axis`.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct MirrorMap {
    /// Abscissa of the mirror line (m).
    pub axis: f64,
    /// The image of block `i` is block `blocks[i]`.
    pub blocks: Vec<usize>,
    /// The image of joint `k` is joint `joints[k].0`; `joints[k].1` when its ends are listed
    /// the other way round (the image of `p1` is that joint's `p2`).
    pub joints: Vec<(usize, bool)>,
}

impl MirrorMap {
    /// The mirror image of the point `p`.
    pub fn point(&self, p: Vec2) -> Vec2 {
        Vec2::new(2.0 * self.axis - p.x, p.y)
    }

    /// The image of the end `end` of joint `joint`, as an end of the image joint.
    pub fn end(&self, joint: usize, end: JointEnd) -> JointEnd {
        match (self.joints[joint].1, end) {
            (false, e) => e,
            (true, JointEnd::P1) => JointEnd::P2,
            (true, JointEnd::P2) => JointEnd::P1,
        }
    }

    /// The map of the parametric numbering: block `i` onto `n - 1 - i`, joint `k` onto
    /// `m - 1 - k` with its ends in the same order, about `x = 0`.
    fn reversed(assembly: &Assembly) -> MirrorMap {
        let (nb, nj) = (assembly.blocks.len(), assembly.joints.len());
        MirrorMap {
            axis: 0.0,
            blocks: (0..nb).rev().collect(),
            joints: (0..nj).rev().map(|k| (k, false)).collect(),
        }
    }
}

/// The map of `assembly` onto its own mirror image (blocks: centroid and weight; joints:
/// ends, blocks and friction, to round-off relative to its size), or None when it is not its
/// own mirror image. The parametric numbering (block `i` against block `n - 1 - i` about
/// `x = 0`, as [`Assembly::mirrored`] numbers them) is tried first, without building
/// anything; then any numbering, about the vertical line through the middle of the
/// centroids' extent.
pub(crate) fn mirror_map(assembly: &Assembly) -> Option<MirrorMap> {
    if numbered_symmetric(assembly) {
        return Some(MirrorMap::reversed(assembly));
    }
    geometric_map(assembly)
}

/// The absolute tolerance on positions: round-off relative to the assembly's size.
fn tolerance(assembly: &Assembly) -> f64 {
    1e-9 * assembly.size()
}

fn same_weight(a: f64, b: f64) -> bool {
    (a - b).abs() <= 1e-9 * b
}

fn same_friction(a: f64, b: f64) -> bool {
    a == b || (a - b).abs() <= 1e-12 * b
}

/// Block i against the mirror of block n - 1 - i and joint k against the mirror of joint
/// m - 1 - k about x = 0 (the parametric scenes' numbering).
fn numbered_symmetric(assembly: &Assembly) -> bool {
    use crate::geometry::mirror;
    let (nb, nj) = (assembly.blocks.len(), assembly.joints.len());
    let tol = tolerance(assembly);
    let same = |a: Vec2, b: Vec2| (a - b).norm() <= tol;
    let flip = |b: Option<usize>| b.map(|i| nb - 1 - i);
    let blocks = &assembly.blocks;
    let joints = &assembly.joints;
    (0..nb).all(|i| {
        let (p, q) = (&blocks[nb - 1 - i], &blocks[i]);
        same(mirror(p.centroid), q.centroid) && same_weight(p.weight, q.weight)
    }) && (0..nj).all(|k| {
        let (p, q) = (&joints[nj - 1 - k], &joints[k]);
        same(mirror(p.p1), q.p1)
            && same(mirror(p.p2), q.p2)
            && flip(p.to) == q.from
            && flip(p.from) == q.to
            && same_friction(p.friction, q.friction)
    })
}

/// Points in square cells of side `h`: every point within `h` of a given one lies in the
/// 3 x 3 cells around it.
struct Grid {
    h: f64,
    cells: HashMap<(i64, i64), Vec<usize>>,
}

impl Grid {
    fn new(points: impl Iterator<Item = Vec2>, h: f64) -> Grid {
        let mut cells: HashMap<(i64, i64), Vec<usize>> = HashMap::new();
        for (i, p) in points.enumerate() {
            cells.entry(Self::cell(p, h)).or_default().push(i);
        }
        Grid { h, cells }
    }

    fn cell(p: Vec2, h: f64) -> (i64, i64) {
        ((p.x / h).floor() as i64, (p.y / h).floor() as i64)
    }

    /// The first point near `p` that `accept` takes.
    fn find(&self, p: Vec2, mut accept: impl FnMut(usize) -> bool) -> Option<usize> {
        let (cx, cy) = Self::cell(p, self.h);
        for dx in -1..=1 {
            for dy in -1..=1 {
                if let Some(found) = self
                    .cells
                    .get(&(cx + dx, cy + dy))
                    .and_then(|v| v.iter().copied().find(|&i| accept(i)))
                {
                    return Some(found);
                }
            }
        }
        None
    }
}

/// The mirror map in any numbering, about the line through the middle of the centroids'
/// extent (module docs).
fn geometric_map(assembly: &Assembly) -> Option<MirrorMap> {
    let (blocks, joints) = (&assembly.blocks, &assembly.joints);
    let tol = tolerance(assembly);
    if blocks.is_empty() || tol.is_nan() || tol <= 0.0 {
        return None;
    }
    let (lo, hi) = blocks
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), b| {
            (l.min(b.centroid.x), h.max(b.centroid.x))
        });
    let axis = 0.5 * (lo + hi);
    // A quick test first: the centre of gravity of a symmetric assembly lies on the axis.
    let (w, wx) = blocks.iter().fold((0.0, 0.0), |(w, wx), b| {
        (w + b.weight, wx + b.weight * (b.centroid.x - axis))
    });
    if wx.abs() > tol * w.max(f64::MIN_POSITIVE) {
        return None;
    }
    let mut map = MirrorMap {
        axis,
        blocks: Vec::with_capacity(blocks.len()),
        joints: Vec::with_capacity(joints.len()),
    };
    let near = |a: Vec2, b: Vec2| (a - b).norm() <= tol;
    let grid = Grid::new(blocks.iter().map(|b| b.centroid), tol);
    let mut used = vec![false; blocks.len()];
    for b in blocks {
        let image = map.point(b.centroid);
        let j = grid.find(image, |j| {
            !used[j] && near(blocks[j].centroid, image) && same_weight(b.weight, blocks[j].weight)
        })?;
        used[j] = true;
        map.blocks.push(j);
    }
    let grid = Grid::new(joints.iter().map(|j| j.midpoint()), tol);
    let mut used = vec![false; joints.len()];
    let side = |b: Option<usize>| b.map(|i| map.blocks[i]);
    for jt in joints {
        let (p1, p2) = (map.point(jt.p1), map.point(jt.p2));
        let (from, to) = (side(jt.from), side(jt.to));
        let mut swapped = false;
        let k = grid.find(map.point(jt.midpoint()), |k| {
            let q = &joints[k];
            if used[k] || !same_friction(jt.friction, q.friction) {
                return false;
            }
            // The mirrored p1 first (from and to swap), or the mirrored p2 first.
            if near(p1, q.p1) && near(p2, q.p2) && from == q.to && to == q.from {
                swapped = false;
                true
            } else if near(p1, q.p2) && near(p2, q.p1) && from == q.from && to == q.to {
                swapped = true;
                true
            } else {
                false
            }
        })?;
        used[k] = true;
        map.joints.push((k, swapped));
    }
    Some(map)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::assembly::{Block, BlockKind, Joint, JointKind};

    /// A block from its corners (unit weight 1000 N/m^2).
    fn block(corners: &[(f64, f64)]) -> Block {
        let polygon = corners.iter().map(|&(x, y)| Vec2::new(x, y)).collect();
        crate::scene::arcade::rect_block(polygon, 1000.0, BlockKind::Other)
    }

    /// Two courses of a running bond between x = 2 and x = 4.4, numbered course by course
    /// from the left (not the parametric numbering): 2 units 1.2 wide below, a half, a unit and
    /// a half above; each joint written with its normal from `from` into `to`.
    fn bond() -> Assembly {
        let r = |x0: f64, x1: f64, y0: f64| [(x0, y0), (x1, y0), (x1, y0 + 0.5), (x0, y0 + 0.5)];
        let blocks = vec![
            block(&r(2.0, 3.2, 0.0)),
            block(&r(3.2, 4.4, 0.0)),
            block(&r(2.0, 2.6, 0.5)),
            block(&r(2.6, 3.8, 0.5)),
            block(&r(3.8, 4.4, 0.5)),
        ];
        // (p1, p2, from, to), friction 0.6.
        let ground = None;
        let joints = [
            // Beds on the ground (normal up: p1 right of p2).
            ((3.2, 0.0), (2.0, 0.0), ground, Some(0)),
            ((4.4, 0.0), (3.2, 0.0), ground, Some(1)),
            // Head joints (normal toward +x: p1 below p2).
            ((3.2, 0.0), (3.2, 0.5), Some(0), Some(1)),
            ((2.6, 0.5), (2.6, 1.0), Some(2), Some(3)),
            ((3.8, 0.5), (3.8, 1.0), Some(3), Some(4)),
            // Beds between the courses.
            ((2.6, 0.5), (2.0, 0.5), Some(0), Some(2)),
            ((3.2, 0.5), (2.6, 0.5), Some(0), Some(3)),
            ((3.8, 0.5), (3.2, 0.5), Some(1), Some(3)),
            ((4.4, 0.5), (3.8, 0.5), Some(1), Some(4)),
        ]
        .into_iter()
        .map(|(p1, p2, from, to)| Joint {
            p1: Vec2::new(p1.0, p1.1),
            p2: Vec2::new(p2.0, p2.1),
            from,
            to,
            friction: 0.6,
            kind: JointKind::Other,
        })
        .collect();
        Assembly { blocks, joints }
    }

    #[test]
    fn a_wall_numbered_course_by_course_is_its_own_mirror_image() {
        let a = bond();
        assert!(!numbered_symmetric(&a));
        let map = mirror_map(&a).expect("symmetric");
        assert!((map.axis - 3.2).abs() < 1e-12);
        assert_eq!(map.blocks, vec![1, 0, 4, 3, 2]);
        // Every image is the joint the mirror makes of it: the same contact between the
        // images of its blocks, its ends at the images of the original's.
        for (k, &(m, swapped)) in map.joints.iter().enumerate() {
            let (j, q) = (&a.joints[k], &a.joints[m]);
            let (i1, i2) = (map.point(j.p1), map.point(j.p2));
            let (q1, q2) = if swapped { (q.p2, q.p1) } else { (q.p1, q.p2) };
            assert!(
                (i1 - q1).norm() < 1e-12 && (i2 - q2).norm() < 1e-12,
                "joint {k}"
            );
            let side = |b: Option<usize>| b.map(|i| map.blocks[i]);
            let mut pair = [side(j.from), side(j.to)];
            pair.sort();
            let mut other = [q.from, q.to];
            other.sort();
            assert_eq!(pair, other, "joint {k}");
            // The image's normal is the mirror of the original's (with from, to in the same
            // roles) or its reverse (with them swapped).
            let n = j.normal();
            let image_n = Vec2::new(-n.x, n.y);
            let flips = side(j.from) == q.to;
            let sign = if flips { -1.0 } else { 1.0 };
            assert!((q.normal() - sign * image_n).norm() < 1e-12, "joint {k}");
            assert_eq!(map.end(k, JointEnd::P1) == JointEnd::P2, swapped);
        }
        // The image of the image is the original.
        for (i, &j) in map.blocks.iter().enumerate() {
            assert_eq!(map.blocks[j], i);
        }
        for (k, &(m, _)) in map.joints.iter().enumerate() {
            assert_eq!(map.joints[m].0, k);
        }
    }

    #[test]
    fn anything_off_its_image_is_not_symmetric() {
        // A heavier block, a moved joint end, a different friction, a missing joint.
        let mut a = bond();
        a.blocks[4].weight *= 1.001;
        assert!(mirror_map(&a).is_none());
        let mut a = bond();
        a.joints[4].p2.x += 1e-3;
        assert!(mirror_map(&a).is_none());
        let mut a = bond();
        a.joints[8].friction = 0.5;
        assert!(mirror_map(&a).is_none());
        let mut a = bond();
        a.joints.remove(3);
        assert!(mirror_map(&a).is_none());
        // A joint between the wrong blocks (the image of 1 -> 3 is 0 -> 3, which exists; the
        // pair 1 -> 4 turned into 0 -> 4 has no image).
        let mut a = bond();
        a.joints[8].from = Some(0);
        assert!(mirror_map(&a).is_none());
    }

    #[test]
    fn any_numbering_and_either_joint_orientation_gives_the_same_map() {
        // The bond with its blocks and joints renumbered, and some joints written the other
        // way round (ends and sides swapped: the same contact): the map found is the
        // original's conjugated by the renumbering.
        let a = bond();
        let reference = mirror_map(&a).expect("symmetric");
        let block_order = [3usize, 0, 4, 2, 1]; // new block b is old block_order[b]
        let joint_order = [5usize, 2, 8, 0, 7, 3, 1, 6, 4];
        let mut new_of = [0usize; 5];
        for (b, &old) in block_order.iter().enumerate() {
            new_of[old] = b;
        }
        let renumber = |b: Option<usize>| b.map(|i| new_of[i]);
        let blocks = block_order.iter().map(|&i| a.blocks[i].clone()).collect();
        let joints = joint_order
            .iter()
            .enumerate()
            .map(|(k, &old)| {
                let j = &a.joints[old];
                let mut j = Joint {
                    from: renumber(j.from),
                    to: renumber(j.to),
                    ..j.clone()
                };
                if k % 2 == 1 {
                    std::mem::swap(&mut j.p1, &mut j.p2);
                    std::mem::swap(&mut j.from, &mut j.to);
                }
                j
            })
            .collect();
        let b = Assembly { blocks, joints };
        let map = mirror_map(&b).expect("still symmetric");
        assert_eq!(map.axis, reference.axis);
        for (i, &j) in map.blocks.iter().enumerate() {
            assert_eq!(block_order[j], reference.blocks[block_order[i]]);
        }
        for (k, &(m, _)) in map.joints.iter().enumerate() {
            assert_eq!(joint_order[m], reference.joints[joint_order[k]].0);
        }
    }
}
