//! Load placement: where the loads of `[[loads]]` and `[fill]` and the anchors of `[[ties]]`
//! act on a built assembly, one path for the parametric arch (and piers) and for the user's
//! blocks. A [`Placement`] knows which block holds a point (and which lies nearest, for the
//! error), and the structure's roof: its upward-facing edges, left end first, straight or arcs
//! of the extrados. [`place`] turns the scene's loads, vehicles, fill and ties into the load case and the
//! anchored ties through it; [`Placement::new`] builds it for either [`Structure`].
//!
//! The scene-key contract:
//! - a point load acts on the block whose outline contains `at` (within the placement's
//!   tolerance); on a joint (or a corner where several blocks meet), an equal share of it on
//!   each block that holds the point, so that a structure and its mirror image carry it alike.
//!   How a load on a joint divides is part of the model, as it was when the whole load went to
//!   the first block in chain order: a joint with finite friction or one near opening passes
//!   only so much of a difference on, so another split can give another multiplier. A curved
//!   voussoir's outline is its annular piece, a polygon voussoir's its quadrilateral (its
//!   extrados the chord between its corners);
//! - the roof: over the arch, every extrados edge that faces up (its corners run left to right:
//!   below the springing line of a horseshoe arch the extrados faces down, and the load above it
//!   rests on the voussoirs higher up) and, on a portal, the exposed part of each pier top
//!   (outside the arch's springing); over the user's blocks, every edge of a (counter-clockwise)
//!   outline that runs toward -x by more than the tolerance;
//! - a line load of intensity `q` over `[from_x, to_x]`: over the arch, `q * overlap` on every
//!   roof edge, where `overlap` is the overlap of `[from_x, to_x]` with the edge's x-range, at
//!   the edge's point at the overlap's mid x; over the user's blocks the load rests on the top
//!   of the structure: the range is cut at the ends of the roof edges, and each piece's load
//!   `q * length` acts on the highest roof edge above it, at that edge's point over the piece's
//!   mid x (an edge hidden under another block carries nothing, as the top edge above it is
//!   higher);
//! - a fill up to `level` weighs `unit_weight * depth * area` at its region's centroid, carried
//!   by the block under the region. Over the arch the region of voussoir i lies above its
//!   extrados edge (the chord for polygon voussoirs, the arc for curved ones), below the level,
//!   between the verticals through its two extrados corners (pier tops carry no fill); over the
//!   user's blocks it lies, for each piece between consecutive ends of the roof edges, between
//!   the highest edge and the level (where the edge lies below it). Over an arch written as
//!   blocks the pieces are its extrados chords, so the fill is the parametric arch's; unlike
//!   there, a pier top or any other block top under the level is filled too;
//! - a seismic load is also a seismic mass of weight `|force_y|` (point), `q * overlap` (line)
//!   or its own weight (fill) at the same point;
//! - with `[fill] passive = true`, the faces against the fill take the fill's passive reaction
//!   ([`Placement::passive_faces`]): over the arch every extrados edge under the level, over
//!   the user's blocks every face with fill just outside it;
//! - a tie's anchor is the block that holds its point, as a point load's is (or the ground:
//!   [`super::ties::anchor_ties`]);
//! - a load standing on the structure: a vertical point load outside every block but in the
//!   fill (above the top of the structure at its x, not above the fill's road surface), and
//!   each axle of `[[vehicles]]` (on the road surface over a fill, on the top otherwise):
//!   the top at x is the highest roof edge over x (over a joint, the first in the roof's
//!   order, the block a point load there would rest on); the load is spread through the depth
//!   of fill between it and the top by the fill's law ([`super::spread`]): at an angle, a line
//!   load `F / w` over the width `w` under it, placed as any line load (and kept whole for the
//!   continuous model); by Boussinesq, Flamant's share on each roof piece at its centroid;
//!   with no depth or no spread, a point load at the top. What falls past the ends of the top
//!   rests on the ground. An axle off the top is an error naming `vehicles[k].at`;
//! - a vehicle's distributed part beyond its axles (LM71's `qvk`) is a line load from its gap
//!   past the outer axles to the ends of the top, on each side.

use super::spread::{self, Law};
use super::vehicles::VehicleSpec;
use super::{ties, LoadSpec, Scene};
use crate::assembly::{Assembly, BlockKind};
use crate::error::SceneError;
use crate::geometry::{circular_segment, cross, polygon_area_centroid, ArchGeometry, Vec2};
use crate::model::{AppliedLoad, LoadCase, LoadSource, Passive, Spread, SpreadLoad, Tie};

/// Where the parametric arch's blocks sit in its assembly (see `scene::build`).
pub(super) struct ArchLayout {
    /// The rings (one, or one per bay of an arcade) left to right, each with the index of its
    /// voussoir 0 in the assembly.
    pub rings: Vec<(ArchGeometry, usize)>,
    pub curved: bool,
    /// Exposed pier (and column) tops `(block, x_from, x_to)` at y = 0.
    pub pier_tops: Vec<(usize, f64, f64)>,
    /// Whether a spandrel wall (`[spandrel]`) covers the rings: its pieces' tops are then the
    /// roof, and loads rest on the highest roof edge, as over the user's blocks.
    pub spandrel: bool,
}

/// The structure a placement places on.
pub(super) enum Structure {
    /// The parametric arch (and piers), blocks in chain order.
    Arch(ArchLayout),
    /// The user's blocks: convex counter-clockwise outlines, in source order by their kind,
    /// detected with the joint tolerance `tolerance` (m), and the fixed blocks `fixed`
    /// (source index, counter-clockwise outline of any shape), which carry what rests on them
    /// to the ground.
    Blocks {
        tolerance: f64,
        fixed: Vec<(usize, Vec<Vec2>)>,
    },
}

/// An upward-facing edge of a structure's top: its block (None: a fixed block), its ends from
/// left to right
/// (`a.x < b.x`), and the arc `(centre, radius)` it lies on (a curved voussoir's extrados) or
/// None (straight).
struct RoofEdge {
    block: Option<usize>,
    a: Vec2,
    b: Vec2,
    arc: Option<(Vec2, f64)>,
}

impl RoofEdge {
    /// The edge's point at abscissa `x` within its x-range.
    fn at(&self, x: f64) -> Vec2 {
        edge_point(self.a, self.b, self.arc, x)
    }
}

/// A line load's share: `length` of the loaded range on `block`, acting at `point`.
struct Piece {
    block: usize,
    point: Vec2,
    length: f64,
}

/// A fill region over `block`: its area, centroid and outline.
struct FillRegion {
    block: usize,
    area: f64,
    centroid: Vec2,
    outline: Vec<Vec2>,
}

/// How loads find the blocks of an assembly: the blocks that hold points, the roof that
/// carries line loads and fill (see the module docs).
pub(super) struct Placement<'a> {
    assembly: &'a Assembly,
    /// How far outside a block's outline a point may lie and still be on it (m).
    tol: f64,
    roof: Vec<RoofEdge>,
    structure: Structure,
}

impl<'a> Placement<'a> {
    /// The placement on `assembly`, the blocks of `structure`.
    pub(super) fn new(assembly: &'a Assembly, structure: Structure) -> Self {
        match structure {
            Structure::Arch(layout) => Self::arch(assembly, layout),
            Structure::Blocks { tolerance, fixed } => Self::blocks(assembly, tolerance, fixed),
        }
    }

    /// The placement on the parametric arch's assembly, laid out as `layout`.
    fn arch(assembly: &'a Assembly, layout: ArchLayout) -> Self {
        let tol = 1e-9 * assembly.size();
        if layout.spandrel {
            // The wall covers the rings: its pieces' tops are the roof.
            let mut roof = Vec::new();
            for (block, b) in assembly.blocks.iter().enumerate() {
                if matches!(b.kind, BlockKind::Spandrel(..)) {
                    roof.extend(upward_edges(Some(block), &b.polygon, tol));
                }
            }
            return Placement {
                assembly,
                tol,
                roof,
                structure: Structure::Arch(layout),
            };
        }
        let piers = layout.pier_tops.iter().map(|&(block, x0, x1)| RoofEdge {
            block: Some(block),
            a: Vec2::new(x0, 0.0),
            b: Vec2::new(x1, 0.0),
            arc: None,
        });
        let voussoirs = layout.rings.iter().flat_map(|(g, first)| {
            (0..g.voussoirs()).filter_map(move |j| {
                let (a, b) = (g.joints[j].1, g.joints[j + 1].1);
                (b.x > a.x).then(|| RoofEdge {
                    block: Some(first + j),
                    a,
                    b,
                    arc: layout.curved.then(|| extrados_arc(g, j)),
                })
            })
        });
        let roof = piers.chain(voussoirs).collect();
        Placement {
            assembly,
            tol,
            roof,
            structure: Structure::Arch(layout),
        }
    }

    /// Whether loads rest on the highest roof edge over each point (the user's blocks, a
    /// spandrel wall) rather than on every roof edge they overlap (the rings' extrados).
    fn on_top(&self) -> bool {
        match &self.structure {
            Structure::Arch(layout) => layout.spandrel,
            Structure::Blocks { .. } => true,
        }
    }

    /// The placement on the user's blocks (`assembly`, as detected with the joint tolerance
    /// `tol`, in metres) and the fixed blocks `fixed`: their tops are roof too, so a load or
    /// fill over them rests on them (and is carried to the ground), not on a block below.
    fn blocks(assembly: &'a Assembly, tol: f64, fixed: Vec<(usize, Vec<Vec2>)>) -> Self {
        let mut roof = Vec::new();
        let outlines = assembly
            .blocks
            .iter()
            .enumerate()
            .map(|(i, b)| (Some(i), &b.polygon))
            .chain(fixed.iter().map(|(_, p)| (None, p)));
        for (block, polygon) in outlines {
            roof.extend(upward_edges(block, polygon, tol));
        }
        Placement {
            assembly,
            tol,
            roof,
            structure: Structure::Blocks {
                tolerance: tol,
                fixed,
            },
        }
    }

    /// The fixed block (its source index) that holds `p` within the tolerance, if any.
    pub(super) fn fixed_at(&self, p: Vec2) -> Option<usize> {
        match &self.structure {
            Structure::Arch(_) => None,
            Structure::Blocks { fixed, .. } => fixed
                .iter()
                .find(|(_, poly)| {
                    crate::blocks::distance_to_outline(p, poly) <= self.tol
                        || crate::blocks::inside_outline(poly, p)
                })
                .map(|&(f, _)| f),
        }
    }

    pub(super) fn assembly(&self) -> &Assembly {
        self.assembly
    }

    /// How far outside a block a point may lie and still be on it (m).
    pub(super) fn tolerance(&self) -> f64 {
        self.tol
    }

    /// Every block that holds `p` (within the tolerance), the first in chain order for the arch (left pier
    /// from its base, the voussoirs from left to right, right pier from its top), in source order
    /// for the user's blocks:
    /// one block inside it, two or more on a joint or a corner where blocks meet. A point load
    /// there is shared equally among them (the module docs), so that a structure and its mirror
    /// image carry it alike.
    pub(super) fn holders(&self, p: Vec2) -> Vec<usize> {
        let order = |i: usize| match self.assembly.blocks[i].kind {
            BlockKind::User(s) => s,
            _ => i,
        };
        let mut found: Vec<usize> = (0..self.assembly.blocks.len())
            .filter(|&i| self.contains(i, p))
            .collect();
        found.sort_by_key(|&i| order(i));
        found
    }

    /// The first of [`Placement::holders`] of each of `points` (a tie's anchors), in one pass over the
    /// blocks, and the lowest y of every block (the structure's base): a block's outline is
    /// tested only for the points inside its bounding box ([`Placement::bounds`]), so a point
    /// costs a box test per block rather than an outline test.
    pub(super) fn locate_all(&self, points: &[Vec2]) -> (Vec<Option<usize>>, f64) {
        let order = |i: usize| match self.assembly.blocks[i].kind {
            BlockKind::User(s) => s,
            _ => i,
        };
        let mut found: Vec<Option<usize>> = vec![None; points.len()];
        let mut base = f64::INFINITY;
        for i in 0..self.assembly.blocks.len() {
            let (lo, hi) = self.bounds(i);
            base = base.min(lo.y);
            let pad = self.pad(i);
            for (&p, f) in points.iter().zip(found.iter_mut()) {
                let in_box = p.x >= lo.x - pad
                    && p.x <= hi.x + pad
                    && p.y >= lo.y - pad
                    && p.y <= hi.y + pad;
                // The first block of least order that holds it, as `holders` orders them.
                if in_box && f.is_none_or(|k| order(i) < order(k)) && self.contains(i, p) {
                    *f = Some(i);
                }
            }
        }
        (found, base)
    }

    /// The bounding box of block `i`'s outline (its least and largest x and y).
    fn bounds(&self, i: usize) -> (Vec2, Vec2) {
        let poly = &self.assembly.blocks[i].polygon;
        let (mut lo, mut hi) = (
            Vec2::new(f64::INFINITY, f64::INFINITY),
            Vec2::new(f64::NEG_INFINITY, f64::NEG_INFINITY),
        );
        for p in poly {
            lo = Vec2::new(lo.x.min(p.x), lo.y.min(p.y));
            hi = Vec2::new(hi.x.max(p.x), hi.y.max(p.y));
        }
        (lo, hi)
    }

    /// How far outside block `i`'s bounding box [`Placement::contains`] may still find a
    /// point (an upper bound, without a square root): what the tolerance adds at the
    /// outline's sharpest corner and, for a curved voussoir (whose exact piece lies in its
    /// quadrilateral and the circular segment of its extrados beyond the chord), that
    /// segment's height.
    ///
    /// The outline test accepts points up to `tol` outside each side, so near a corner of
    /// interior angle `theta` up to `tol / sin(theta/2)` from it. With the sides `a` into the
    /// corner and `b` out of it, `1/sin^2(theta/2) = 2 |a||b| / (|a||b| + a.b)`: at most 2
    /// when `a.b >= 0` (theta >= 90 deg), and at most `4 |a|^2 |b|^2 / (a x b)^2` otherwise
    /// (multiply by `|a||b| - a.b <= 2 |a||b|`); its square root is at most `(1 + x)/2`. The
    /// bound is doubled (a curved voussoir's corners, between a joint and an arc, differ from
    /// its quadrilateral's by half the arc's angle). A side of length 0, or a corner that
    /// folds back (`a x b = 0` with `a.b < 0`), gives an unbounded pad: the box then rejects
    /// nothing. The segment's height `r - sqrt(r^2 - h^2)` (`h` half the chord) is at most
    /// `h^2 / r`.
    fn pad(&self, i: usize) -> f64 {
        let poly = &self.assembly.blocks[i].polygon;
        let m = poly.len();
        let mut corner2: f64 = 2.0;
        for k in 0..m {
            let a = poly[k] - poly[(k + m - 1) % m];
            let b = poly[(k + 1) % m] - poly[k];
            let (aa, bb) = (a.norm_squared(), b.norm_squared());
            if aa == 0.0 || bb == 0.0 {
                return f64::INFINITY;
            }
            let dot = a.dot(&b);
            if dot < 0.0 {
                let c = cross(a, b);
                corner2 = corner2.max(4.0 * aa * bb / (c * c));
            }
        }
        let bulge = match self.ring_voussoir(i) {
            Some((g, j)) => {
                let q = g.quad(j);
                let r = g.arcs[j].radius + 0.5 * g.thickness;
                0.25 * (q[2] - q[1]).norm_squared() / r
            }
            None => 0.0,
        };
        2.0 * (0.5 * (1.0 + corner2)) * self.tol + bulge * (1.0 + 1e-9)
    }

    /// The ring and voussoir of block `i` when it is a curved voussoir of the parametric
    /// arch (whose exact annular piece [`inside_curved`] tests).
    fn ring_voussoir(&self, i: usize) -> Option<(&crate::geometry::ArchGeometry, usize)> {
        match &self.structure {
            Structure::Arch(arch) if arch.curved => arch.rings.iter().find_map(|(g, first)| {
                let j = i.wrapping_sub(*first);
                (j < g.voussoirs()).then_some((g, j))
            }),
            _ => None,
        }
    }

    /// Whether block `i` holds `p` within the tolerance.
    fn contains(&self, i: usize, p: Vec2) -> bool {
        let poly = &self.assembly.blocks[i].polygon;
        match &self.structure {
            Structure::Arch(_) => match self.ring_voussoir(i) {
                Some((g, j)) => inside_curved(g, j, p, self.tol),
                None => inside_convex(poly, p, self.tol, orientation(poly)),
            },
            Structure::Blocks { .. } => inside_convex(poly, p, self.tol, 1.0),
        }
    }

    /// Why no block holds `p`, in words (the error's allowed values).
    fn outside(&self, p: Vec2) -> String {
        if let Some(f) = self.fixed_at(p) {
            return format!(
                "the point lies in the fixed block {f}, which does not move: a load there acts on no block of the structure"
            );
        }
        match self.structure {
            Structure::Arch(_) => {
                let (b, d) = nearest_block(self.assembly, p);
                format!(
                    "the point lies outside every block (the nearest is block {b}, {} at {d:.3e} m; a polygon voussoir's extrados is the chord between its corners)",
                    describe(self.assembly.blocks[b].kind)
                )
            }
            Structure::Blocks { .. } => "the point lies outside every block".into(),
        }
    }

    /// What a line load must rest on, in words (the error's allowed values).
    fn roof_words(&self) -> &'static str {
        match self.structure {
            Structure::Arch(ref a) if a.spandrel => {
                "the loaded length must overlap the top of the spandrel wall"
            }
            Structure::Arch(_) => {
                "the loaded length must overlap the extrados of the arch (or an exposed pier top)"
            }
            Structure::Blocks { .. } => {
                "the loaded length must lie over the top of some block (not of a fixed block)"
            }
        }
    }

    /// The shares of a line load over `[from_x, to_x]` (see the module docs).
    fn line_pieces(&self, from_x: f64, to_x: f64) -> Vec<Piece> {
        self.spans(from_x, to_x)
            .into_iter()
            .filter_map(|(lo, hi, e)| {
                // A piece over a fixed block rests on it.
                Some(Piece {
                    block: e.block?,
                    point: e.at(0.5 * (lo + hi)),
                    length: hi - lo,
                })
            })
            .collect()
    }

    /// The pieces `(x0, x1, edge)` of `[from_x, to_x]` and the roof edges that carry them:
    /// over the rings' extrados every edge it overlaps, elsewhere the highest edge over each
    /// piece between the ends of the edges (see the module docs).
    fn spans(&self, from_x: f64, to_x: f64) -> Vec<(f64, f64, &RoofEdge)> {
        match self.structure {
            Structure::Arch(_) if !self.on_top() => self
                .roof
                .iter()
                .filter_map(|e| {
                    let lo = from_x.max(e.a.x);
                    let hi = to_x.min(e.b.x);
                    (hi > lo).then_some((lo, hi, e))
                })
                .collect(),
            _ => {
                let mut cuts = vec![from_x, to_x];
                for e in &self.roof {
                    cuts.extend(
                        [e.a.x, e.b.x]
                            .into_iter()
                            .filter(|&x| x > from_x && x < to_x),
                    );
                }
                self.under_top(cuts)
            }
        }
    }

    /// The x-range of the structure's top: from the left end of its leftmost roof edge to
    /// the right end of its rightmost (None without a roof).
    fn roof_range(&self) -> Option<(f64, f64)> {
        let lo = self.roof.iter().map(|e| e.a.x).reduce(f64::min)?;
        let hi = self.roof.iter().map(|e| e.b.x).reduce(f64::max)?;
        Some((lo, hi))
    }

    /// The top of the structure over `x`: the point of the highest roof edge there, and that
    /// edge; None where no roof edge lies under x (off the structure). Over a joint (two
    /// edges as high) the first edge in the roof's order, so that a load there rests on the
    /// block a point load there would (the first in chain order).
    fn roof_at(&self, x: f64) -> Option<(Vec2, &RoofEdge)> {
        self.roof
            .iter()
            .filter(|e| e.a.x - self.tol <= x && x <= e.b.x + self.tol)
            .map(|e| (e.at(x.clamp(e.a.x, e.b.x)), e))
            .fold(None, |best: Option<(Vec2, &RoofEdge)>, c| match best {
                Some(b) if b.0.y >= c.0.y => Some(b),
                _ => Some(c),
            })
    }

    /// Where a load standing at `x` stands: on the road surface `surface` (a fill's) where
    /// that lies above the structure's top, on the top at x otherwise; None off the
    /// structure (no roof edge under x).
    pub(super) fn stand(&self, x: f64, surface: Option<f64>) -> Option<Vec2> {
        let (top, _) = self.roof_at(x)?;
        Some(match surface {
            Some(y) if y > top.y => Vec2::new(x, y),
            _ => top,
        })
    }

    /// The x-range of the top as words, for errors.
    fn roof_range_words(&self) -> String {
        match self.roof_range() {
            Some((lo, hi)) => format!("the top of the structure runs from x = {lo} to {hi} m"),
            None => "the structure has no upward-facing top".into(),
        }
    }

    /// Place a downward load `weight` (N) standing at `p` (on the top of the structure or in
    /// the fill above it) on the blocks under it, spread by `law` over the depth between `p`
    /// and the top at its x ([`spread`]): the shares of `load` go into `case`, with a spread
    /// load for the continuous model when the law makes them a uniform line load. False when
    /// no roof edge lies under p (off the structure).
    fn place_standing(
        &self,
        case: &mut LoadCase,
        p: Vec2,
        weight: f64,
        law: Law,
        load: Standing,
    ) -> bool {
        let Some((top, _)) = self.roof_at(p.x) else {
            return false;
        };
        let depth = (p.y - top.y).max(0.0);
        let share = |case: &mut LoadCase, block: usize, point: Vec2, w: f64| {
            case.add(
                AppliedLoad {
                    block,
                    point,
                    force: Vec2::new(0.0, -w),
                    seismic_weight: if load.seismic { w } else { 0.0 },
                    live: false,
                    source: load.source,
                    region: None,
                }
                .live(load.live),
            );
        };
        match law {
            Law::Angle(theta) if spread::width(depth, theta) > self.tol => {
                let w = spread::width(depth, theta);
                let (x0, x1) = (p.x - 0.5 * w, p.x + 0.5 * w);
                let q = weight / w;
                for piece in self.line_pieces(x0, x1) {
                    share(case, piece.block, piece.point, q * piece.length);
                }
                case.add_spread(SpreadLoad {
                    kind: Spread::Line {
                        from_x: x0,
                        to_x: x1,
                        intensity: q,
                    },
                    seismic: load.seismic,
                    live: load.live,
                    source: load.source,
                });
            }
            Law::Boussinesq if depth > self.tol => {
                let (lo, hi) = self.roof_range().unwrap_or((p.x, p.x));
                for (a, b, e) in self.spans(lo, hi) {
                    let (f, m) = spread::boussinesq_share(depth, a - p.x, b - p.x);
                    if let (Some(block), true) = (e.block, f > 0.0) {
                        let u = (m / f).clamp(a - p.x, b - p.x);
                        share(case, block, e.at(p.x + u), weight * f);
                    }
                }
            }
            // No spread (an angle of 0, or no fill between the load and the top): on the top
            // edge under it, or shared equally by the movable blocks whose top edges meet
            // there (a joint at the top), as a point load on a joint is.
            _ => {
                let blocks: Vec<usize> = self
                    .roof
                    .iter()
                    .filter(|e| e.a.x - self.tol <= p.x && p.x <= e.b.x + self.tol)
                    .filter(|e| (e.at(p.x.clamp(e.a.x, e.b.x)).y - top.y).abs() <= self.tol)
                    .filter_map(|e| e.block)
                    .collect();
                let n = blocks.len() as f64;
                for block in blocks {
                    share(case, block, top, weight / n);
                }
            }
        }
        true
    }

    /// The fill regions below `level` (see the module docs).
    fn fill_regions(&self, level: f64) -> Vec<FillRegion> {
        let region = |block, a, b, arc| {
            fill_region(a, b, level, arc).map(|(area, centroid, outline)| FillRegion {
                block,
                area,
                centroid,
                outline,
            })
        };
        match self.structure {
            Structure::Arch(_) if !self.on_top() => self
                .extrados()
                .filter_map(|(block, e)| region(block, e.a, e.b, e.arc))
                .collect(),
            _ => {
                let cuts = self.roof.iter().flat_map(|e| [e.a.x, e.b.x]).collect();
                self.under_top(cuts)
                    .into_iter()
                    .filter_map(|(x0, x1, e)| {
                        let (mut a, mut b) = (e.at(x0), e.at(x1));
                        // Keep the part of the edge below the level.
                        if a.y >= level && b.y >= level {
                            return None;
                        }
                        if a.y > level || b.y > level {
                            let x = a.x + (level - a.y) / (b.y - a.y) * (b.x - a.x);
                            if a.y > level {
                                a = e.at(x);
                            } else {
                                b = e.at(x);
                            }
                        }
                        // Fill over a fixed block rests on it.
                        region(e.block?, a, b, None)
                    })
                    .collect()
            }
        }
    }

    /// The rings' extrados edges among the roof edges, with their voussoirs (pier tops
    /// carry no fill).
    fn extrados(&self) -> impl Iterator<Item = (usize, &RoofEdge)> + '_ {
        self.roof.iter().filter_map(|e| {
            let block = e.block?;
            matches!(
                self.assembly.blocks[block].kind,
                BlockKind::Voussoir(_) | BlockKind::BayVoussoir(..)
            )
            .then_some((block, e))
        })
    }

    /// The faces against a fill of level `level` whose passive pressure per unit depth is
    /// `coefficient` (N/m^3, `m_p K_p gamma d`; see `crate::interaction::passive`): over the
    /// rings, each voussoir's extrados edge (its chord; the horizontal force of a pressure
    /// depends on the ends' heights alone); over the user's blocks or a spandrel wall, each
    /// face of a block with fill just outside it (above the highest roof edge there, below the
    /// level, in no other block), so a block's side beside the fill is one too. Faces that
    /// face straight up or down take no horizontal reaction and are left out.
    pub(super) fn passive_faces(&self, level: f64, coefficient: f64) -> Vec<Passive> {
        match self.structure {
            Structure::Arch(_) if !self.on_top() => self
                .extrados()
                .filter_map(|(block, e)| {
                    // Left to right on an upward-facing edge: rising, its outward normal
                    // points to -x; falling, to +x.
                    let into = if e.b.y > e.a.y { -1.0 } else { 1.0 };
                    Passive::face(block, e.a, e.b, into, level, coefficient)
                })
                .collect(),
            _ => {
                // How far outside a face its test point lies: beyond the joint tolerance (so
                // a neighbour across a joint holds it), a small part of the face.
                let eps = (4.0 * self.tol).max(1e-9 * self.assembly.size());
                let mut faces = Vec::new();
                for (i, b) in self.assembly.blocks.iter().enumerate() {
                    let poly = &b.polygon;
                    let orient = orientation(poly);
                    let m = poly.len();
                    for k in 0..m {
                        let (p, q) = (poly[k], poly[(k + 1) % m]);
                        let d = q - p;
                        let len = d.norm();
                        if len <= self.tol {
                            continue;
                        }
                        // The outward normal of a counter-clockwise outline is (dy, -dx).
                        let n = orient * Vec2::new(d.y, -d.x) / len;
                        if n.x.abs() <= 1e-9 {
                            continue;
                        }
                        let Some(face) = Passive::face(i, p, q, n.x.signum(), level, coefficient)
                        else {
                            continue;
                        };
                        let reach = eps.min(0.1 * (face.b - face.a).norm());
                        let out = 0.5 * (face.a + face.b) + reach * n;
                        if self.in_fill(out, level, i) {
                            faces.push(face);
                        }
                    }
                }
                faces
            }
        }
    }

    /// Whether `p` lies in the fill up to `level`: below it, above the highest roof edge over
    /// its x (the fill rests on the structure's top), and in no block but `own`.
    fn in_fill(&self, p: Vec2, level: f64, own: usize) -> bool {
        if p.y >= level || self.fixed_at(p).is_some() {
            return false;
        }
        let under = self
            .roof
            .iter()
            .filter(|e| e.a.x <= p.x && p.x <= e.b.x)
            .map(|e| e.at(p.x).y)
            .fold(f64::NEG_INFINITY, f64::max);
        // No roof edge over its x: no fill there (the fill rests on the structure's top).
        under.is_finite()
            && under < p.y
            && !(0..self.assembly.blocks.len()).any(|j| j != own && self.contains(j, p))
    }

    /// The pieces `(x0, x1, edge)` between consecutive `cuts` (sorted here), each with the
    /// highest roof edge over its mid x; pieces with no edge over them are left out.
    fn under_top(&self, mut cuts: Vec<f64>) -> Vec<(f64, f64, &RoofEdge)> {
        cuts.sort_by(f64::total_cmp);
        cuts.dedup();
        cuts.windows(2)
            .filter(|w| w[1] - w[0] > 0.0)
            .filter_map(|w| {
                let x = 0.5 * (w[0] + w[1]);
                let top = self
                    .roof
                    .iter()
                    .filter(|e| e.a.x <= x && x <= e.b.x)
                    .max_by(|e, f| e.at(x).y.total_cmp(&f.at(x).y))?;
                Some((w[0], w[1], top))
            })
            .collect()
    }
}

/// The load case of `scene` and its ties, placed on the assembly through `placement`: the
/// self-weight, then `[[loads]]` in order, then `[fill]` (see the module docs).
pub(super) fn place(
    scene: &Scene,
    placement: &Placement,
) -> Result<(LoadCase, Vec<Tie>), SceneError> {
    let origin = &scene.origin;
    let mut case = LoadCase::self_weight(placement.assembly)
        .with_vertical_ratio(scene.seismic.vertical_ratio)
        .with_action(scene.action);
    // The fill's road surface and the law loads standing on it spread by.
    let fill = scene
        .fill
        .as_ref()
        .map(|f| (f.dispersal.surface(f.level), f.dispersal.law()));
    for (k, spec) in scene.loads.iter().enumerate() {
        match *spec {
            LoadSpec::Point {
                at,
                force,
                seismic,
                live,
            } => {
                let p = Vec2::new(at[0], at[1]);
                let force = Vec2::new(force[0], force[1]);
                let holders = placement.holders(p);
                if !holders.is_empty() {
                    // On a joint: an equal share on each block that meets there.
                    let share = 1.0 / holders.len() as f64;
                    for block in holders {
                        case.add(
                            AppliedLoad::point(k, block, p, force * share, seismic).live(live),
                        );
                    }
                    continue;
                }
                // Outside every block: a load standing in the fill (up to its road surface)
                // reaches the structure through it.
                let in_fill = fill.as_ref().is_some_and(|(surface, _)| {
                    p.y <= surface + placement.tol
                        && placement
                            .roof_at(p.x)
                            .is_some_and(|(top, _)| p.y >= top.y - placement.tol)
                });
                if !in_fill {
                    return Err(SceneError::OutOfRange {
                        origin: origin.clone(),
                        key: format!("loads[{k}].at"),
                        value: format!("[{}, {}]", at[0], at[1]),
                        allowed: placement.outside(p),
                    });
                }
                if force.x != 0.0 || force.y > 0.0 {
                    return Err(SceneError::OutOfRange {
                        origin: origin.clone(),
                        key: format!("loads[{k}].force"),
                        value: format!("[{}, {}]", force[0], force[1]),
                        allowed: "a load standing in the fill (its point lies above the structure, below the fill's surface) spreads through it, so it must act straight down: [0, -F]".into(),
                    });
                }
                let law = fill.as_ref().map_or(Law::Angle(0.0), |f| f.1);
                let load = Standing {
                    source: LoadSource::Load(k),
                    live,
                    seismic: seismic && !live,
                };
                placement.place_standing(&mut case, p, -force.y, law, load);
            }
            LoadSpec::Line {
                from_x,
                to_x,
                intensity,
                seismic,
                live,
            } => {
                case.add_spread(SpreadLoad::line(k, from_x, to_x, intensity, seismic).live(live));
                let pieces = placement.line_pieces(from_x, to_x);
                if pieces.is_empty() {
                    return Err(SceneError::OutOfRange {
                        origin: origin.clone(),
                        key: format!("loads[{k}].from_x"),
                        value: format!("{from_x} (to_x = {to_x})"),
                        allowed: placement.roof_words().into(),
                    });
                }
                for Piece {
                    block,
                    point,
                    length,
                } in pieces
                {
                    let w = intensity * length;
                    case.add(AppliedLoad {
                        block,
                        point,
                        force: Vec2::new(0.0, -w),
                        seismic_weight: if seismic { w } else { 0.0 },
                        live,
                        source: LoadSource::Load(k),
                        region: None,
                    });
                }
            }
        }
    }
    if let Some(fill) = &scene.fill {
        let gamma = fill.unit_weight * scene.material.depth;
        case.add_spread(SpreadLoad::fill(fill.level, gamma, fill.seismic));
        let regions = placement.fill_regions(fill.level);
        // A fill over fixed blocks alone weighs on no block, but it may still lie against a
        // block's side (its passive resistance).
        if regions.is_empty() && !placement.roof.iter().any(|e| e.a.y.min(e.b.y) < fill.level) {
            // Over the parametric arch the level is not below the crown (checked as the scene
            // is read), so some voussoir always has a region.
            return Err(SceneError::OutOfRange {
                origin: origin.clone(),
                key: "fill.level".to_string(),
                value: fill.level.to_string(),
                allowed: "the fill's top must lie above the top of some block".into(),
            });
        }
        for r in regions {
            case.add(AppliedLoad::fill(
                r.block,
                gamma * r.area,
                r.centroid,
                r.outline,
                fill.seismic,
            ));
        }
    }
    for (k, v) in scene.vehicles.iter().enumerate() {
        place_vehicle(&mut case, placement, k, v, fill, origin)?;
    }
    let ties = ties::anchor_ties(&scene.ties, placement, origin)?;
    Ok((case, ties))
}

/// Where a load standing on the structure came from, and what it is.
#[derive(Clone, Copy)]
struct Standing {
    source: LoadSource,
    live: bool,
    seismic: bool,
}

/// The loads of vehicle `k`, `v`: each axle standing on the road surface of `fill` (its
/// surface and spread law) or, without a fill, on the top of the structure at its x; the
/// distributed part beyond the axles (LM71's) a line load from its gap past the outer axles to
/// the ends of the structure's top. A vehicle carries no seismic mass.
fn place_vehicle(
    case: &mut LoadCase,
    placement: &Placement,
    k: usize,
    v: &VehicleSpec,
    fill: Option<(f64, Law)>,
    origin: &str,
) -> Result<(), SceneError> {
    let off = |why: String| SceneError::OutOfRange {
        origin: origin.to_string(),
        key: format!("vehicles[{k}].at"),
        value: v.at.to_string(),
        allowed: why,
    };
    let (surface, law) = fill.map_or((None, Law::Angle(0.0)), |(s, l)| (Some(s), l));
    for (p, (x, weight)) in v.axle_positions().enumerate() {
        let standing = placement.stand(x, surface);
        let load = Standing {
            source: LoadSource::Vehicle(k, p),
            live: v.live,
            seismic: false,
        };
        let placed =
            standing.is_some_and(|at| placement.place_standing(case, at, weight, law, load));
        if !placed {
            return Err(off(format!(
                "every axle must stand on the structure: axle {p} (at + {}) lies at x = {x}, off it ({})",
                v.axles[p].0,
                placement.roof_range_words()
            )));
        }
    }
    if let (Some((q, gap)), Some((lo, hi))) = (v.beyond, placement.roof_range()) {
        let (first, last) = v.extent();
        let sides = [(lo, first - gap), (last + gap, hi)];
        for (side, (x0, x1)) in sides.into_iter().enumerate() {
            if x1 <= x0 {
                continue;
            }
            let source = LoadSource::Vehicle(k, v.axles.len() + side);
            for Piece {
                block,
                point,
                length,
            } in placement.line_pieces(x0, x1)
            {
                case.add(
                    AppliedLoad {
                        block,
                        point,
                        force: Vec2::new(0.0, -q * length),
                        seismic_weight: 0.0,
                        live: false,
                        source,
                        region: None,
                    }
                    .live(v.live),
                );
            }
            case.add_spread(SpreadLoad {
                kind: Spread::Line {
                    from_x: x0,
                    to_x: x1,
                    intensity: q,
                },
                seismic: false,
                live: v.live,
                source,
            });
        }
    }
    Ok(())
}

/// Centre and radius of the extrados arc of voussoir `j`.
fn extrados_arc(g: &ArchGeometry, j: usize) -> (Vec2, f64) {
    let arc = g.arcs[j];
    (arc.centre, arc.radius + 0.5 * g.thickness)
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
fn fill_region(
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

/// The upward-facing edges of block `block`'s counter-clockwise outline `polygon`: those that
/// run toward -x by more than `tol`.
fn upward_edges(block: Option<usize>, polygon: &[Vec2], tol: f64) -> Vec<RoofEdge> {
    let m = polygon.len();
    (0..m)
        .filter_map(|k| {
            let (a, c) = (polygon[k], polygon[(k + 1) % m]);
            (a.x - c.x > tol).then_some(RoofEdge {
                block,
                a: c,
                b: a,
                arc: None,
            })
        })
        .collect()
}

/// The sign of a polygon's signed area: 1 counter-clockwise, -1 clockwise.
fn orientation(poly: &[Vec2]) -> f64 {
    let m = poly.len();
    let mut s = 0.0;
    for k in 0..m {
        s += cross(poly[k], poly[(k + 1) % m]);
    }
    s.signum()
}

/// Whether `p` lies in the convex polygon of orientation `orient` ([`orientation`]) or within
/// `tol` of it.
fn inside_convex(poly: &[Vec2], p: Vec2, tol: f64, orient: f64) -> bool {
    let m = poly.len();
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
    // And on the voussoir's side of the arc's centre: joints that are not radial (vertical,
    // horizontal beds) meet in a wedge that crosses the ring a second time on its far side,
    // where the three tests above would take a point of another voussoir for one of this one.
    let towards = centre - arc.centre;
    let near_side = (p - arc.centre).dot(&towards) / towards.norm() >= -tol;
    side(q[0], q[1], centre)
        && side(q[2], q[3], centre)
        && r >= ri - tol
        && r <= re + tol
        && near_side
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
        BlockKind::BayVoussoir(k, j) => format!("voussoir {j} of bay {k}"),
        BlockKind::Column(k, c) => format!("column {k} course {c}"),
        BlockKind::Spandrel(c, k) => format!("spandrel course {c} piece {k}"),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::Scene;

    /// `locate_all` (a box test first, one pass over the blocks) finds exactly the blocks
    /// `holders` (every outline tested) finds, for points inside, on and just outside the
    /// outlines (within and past the tolerance, at the corners and the arcs' bulges) of
    /// polygon and curved voussoirs, radial and horizontal joints, piers and user blocks.
    #[test]
    fn locate_all_finds_what_locate_finds() {
        let arch = |shape: &str, extra: &str| {
            format!(
                "[arch]\nshape = \"{shape}\"\nradius = 1.0\nthickness = 0.2\nvoussoirs = 9\n{extra}\n[piers]\nheight = 1.0\nwidth = 0.4\ncourses = 3\n"
            )
        };
        let scenes = [
            arch("circular", ""),
            arch("circular", "voussoir_shape = \"curved\""),
            arch("circular", "voussoir_shape = \"curved\"\njoints = \"vertical\""),
            arch(
                "circular",
                "voussoir_shape = \"curved\"\njoints = \"horizontal_bed\"\nhorizontal_bed_deg = 30",
            ),
            "[blocks]\npolygons = [[[0, 0], [1, 0], [1, 1], [0, 1]], [[0, 1], [1, 1], [0.02, 1.6]]]\n"
                .to_string(),
        ];
        for text in scenes {
            let scene = Scene::from_toml_str(&text, "t").unwrap_or_else(|e| panic!("{e}"));
            let (assembly, structure) = super::super::build::structure(&scene).expect("builds");
            let placement = Placement::new(&assembly, structure);
            let tol = placement.tolerance();
            let mut points = Vec::new();
            for b in &assembly.blocks {
                let m = b.polygon.len();
                for k in 0..m {
                    let (a, c) = (b.polygon[k], b.polygon[(k + 1) % m]);
                    let out = Vec2::new(c.y - a.y, a.x - c.x) / (c - a).norm();
                    for s in [0.0, 0.3, 0.5, 1.0] {
                        let on = a + s * (c - a);
                        for d in [
                            -1e-3,
                            -tol,
                            0.0,
                            0.5 * tol,
                            0.99 * tol,
                            1.5 * tol,
                            1e-3,
                            0.02,
                        ] {
                            points.push(on + d * out);
                            points.push(on - d * out);
                        }
                    }
                    points.push(b.centroid + 0.999 * (a - b.centroid));
                    points.push(b.centroid + 1.001 * (a - b.centroid));
                }
                points.push(b.centroid);
            }
            let (all, base) = placement.locate_all(&points);
            let lowest = (assembly.blocks.iter())
                .flat_map(|b| b.polygon.iter())
                .fold(f64::INFINITY, |m, p| m.min(p.y));
            assert_eq!(base, lowest);
            for (p, found) in points.iter().zip(&all) {
                assert_eq!(
                    *found,
                    placement.holders(*p).first().copied(),
                    "{text}: at {p:?}"
                );
            }
            assert!(all.iter().any(Option::is_some) && all.iter().any(Option::is_none));
        }
    }
}
