//! The spandrel wall (`[spandrel]`): the masonry above the ring(s) of a portal or an arcade, up
//! to `level`, as real blocks in running bond, joined to the rings along the voussoirs'
//! extrados chords and to the piers' and columns' tops.
//!
//! The wall spans from the outer face of the left pier's top to that of the right pier, from
//! the springing line y = 0 to `level`, less the rings and their openings: its floor is the
//! exposed pier and column tops (y = 0) and the extrados chords of the voussoirs (the polygon
//! voussoirs' extrados). The blocks are made course by course:
//!
//! 1. **Courses.** Bed lines at y = k `course_height` from the springing line; a top course
//!    thinner than half a course joins the course below (so every course is from 1/2 to 3/2
//!    of `course_height` high). A bed line that passes less than a quarter course above an
//!    extrados vertex is lowered to the lowest such vertex (at most twice, never closer than
//!    half a course to the line below): otherwise the part of the course under the line, over
//!    the chord that rises from that vertex, would be a sliver.
//! 2. **Convex pieces.** In a course the floor is `max(extrados, bed line)`. The region above an
//!    arch's extrados is not convex: at every extrados vertex that lies inside the course the
//!    floor turns concave, and the course is cut there by a vertical joint, so every piece rests
//!    on one chord of the ring (or on a chord and the bed line or a pier or column top beside it,
//!    where the floor stays convex). Every piece is a convex polygon: vertical sides, a flat top,
//!    a convex floor.
//! 3. **Running bond.** Head joints at `x = i unit_length` in even courses (counted from the
//!    springing line) and `x = (i + 1/2) unit_length` in odd ones, measured from the axis x = 0
//!    of the portal or arcade, so the bond is mirror-symmetric. A head joint closer than a
//!    quarter unit to a cut of step 2 or to the end of the course's region is left out, so no
//!    piece of the bond is narrower than a quarter unit; pieces between two cuts of step 2 are
//!    as wide as the ring's chords make them.
//!
//! Joints (each the whole common segment): between a piece and the voussoir (or pier or column
//! course) whose extrados chord (or top) it rests on, between neighbouring pieces of a course
//! (their common vertical side), and between a piece and each piece of the course below that
//! its flat floor overlaps. The two ends of the wall are free faces, as is its top. The pieces
//! weigh `unit_weight * depth * area` of `[material]`, at their centroids.
//!
//! Curved voussoirs are refused with a spandrel: their exact extrados arcs bulge above the
//! chords the pieces rest on, so the wall and the ring would overlap.

use super::{ArchSpec, Section, VoussoirShape};
use crate::assembly::{Block, BlockKind, Joint, JointKind};
use crate::error::SceneError;
use crate::geometry::{polygon_area_centroid, ArchGeometry, Vec2};

/// The keys of `[spandrel]`.
pub(super) const SPANDREL_KEYS: &[&str] = &["level", "course_height", "unit_length"];

/// Most courses a spandrel may have (the wall's height over `course_height`).
pub const MAX_COURSES: usize = 1000;

/// `[spandrel]`: a wall in running bond above the ring(s), up to `level`.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct SpandrelSpec {
    /// y of the wall's top (m).
    pub level: f64,
    /// Height of a course (m).
    pub course_height: f64,
    /// Length of a unit (m).
    pub unit_length: f64,
}

impl SpandrelSpec {
    /// The wall in words.
    pub fn describe(&self) -> String {
        let n = crate::geometry::trim;
        format!(
            "a spandrel wall up to y = {} m in running bond, courses {} m high, units {} m long",
            n(self.level),
            n(self.course_height),
            n(self.unit_length)
        )
    }
}

/// Read `[spandrel]` over `arch` (the portal's or the arcade's ring, on piers when `piers`).
pub(super) fn parse(
    mut s: Section,
    arch: &ArchSpec,
    piers: Option<&super::Piers>,
) -> Result<SpandrelSpec, SceneError> {
    s.check_known(SPANDREL_KEYS, "")?;
    let level = s.length("level", "y of the wall's top in metres")?;
    let course_height = s.length("course_height", "height of a course in metres")?;
    let unit_length = s.length("unit_length", "length of a unit in metres")?;
    s.finish("")?;
    let crown = arch.shape.crown_extrados(arch.thickness);
    if level <= crown {
        return Err(s.out_of_range(
            "level",
            level,
            &format!("must be above the crown extrados, y = {crown}"),
        ));
    }
    if level / course_height > MAX_COURSES as f64 {
        return Err(s.out_of_range(
            "course_height",
            course_height,
            &format!(
                "the wall (up to y = {level} m) would have more than {MAX_COURSES} courses: at least {} m",
                level / MAX_COURSES as f64
            ),
        ));
    }
    if arch.voussoir_shape == VoussoirShape::Curved {
        return Err(SceneError::OutOfRange {
            origin: s.origin.to_string(),
            key: "arch.voussoir_shape".into(),
            value: "\"curved\"".into(),
            allowed: "a spandrel rests on the voussoirs' extrados chords: use voussoir_shape = \"polygon\" (curved voussoirs bulge above the chords, into the wall)".into(),
        });
    }
    let Some(piers) = piers else {
        return Err(s.out_of_range(
            "level",
            level,
            "a spandrel wall stands on piers: give [piers] (its ends are the outer faces of the piers' tops; over a bare arch use [fill])",
        ));
    };
    if let Ok(g) = arch.geometry() {
        let n = g.voussoirs();
        for (side, pier, springing) in [
            ("left", &piers.left, g.joints[0].0.x - g.joints[0].1.x),
            ("right", &piers.right, g.joints[n].1.x - g.joints[n].0.x),
        ] {
            if pier.top_width() < springing {
                return Err(SceneError::OutOfRange {
                    origin: s.origin.to_string(),
                    key: format!("piers.{side}"),
                    value: format!("top width {} m", pier.top_width()),
                    allowed: format!("a spandrel wall stands on the pier tops beside the springers: the {side} pier's top must be at least as wide as the springing joint, {springing} m"),
                });
            }
        }
    }
    Ok(SpandrelSpec {
        level,
        course_height,
        unit_length,
    })
}

/// What a stretch of a piece's floor rests on.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Rest {
    /// A block of the portal or arcade (a voussoir's extrados chord, a pier or column top).
    Block(usize),
    /// The bed line: the pieces of the course below.
    Below,
}

/// A straight stretch of floor from `a` to `b` (`a.x < b.x`).
#[derive(Debug, Clone, Copy)]
struct Stretch {
    a: Vec2,
    b: Vec2,
    rest: Rest,
}

impl Stretch {
    fn y_at(&self, x: f64) -> f64 {
        if self.b.x == self.a.x {
            return self.a.y.max(self.b.y);
        }
        let s = ((x - self.a.x) / (self.b.x - self.a.x)).clamp(0.0, 1.0);
        self.a.y + s * (self.b.y - self.a.y)
    }
    fn slope(&self) -> f64 {
        (self.b.y - self.a.y) / (self.b.x - self.a.x)
    }
}

/// A piece being made: its floor stretches, left to right, and its top.
struct Piece {
    course: usize,
    floor: Vec<Stretch>,
    top: f64,
}

impl Piece {
    fn x0(&self) -> f64 {
        self.floor[0].a.x
    }
    fn x1(&self) -> f64 {
        self.floor[self.floor.len() - 1].b.x
    }
    /// Counter-clockwise outline: the floor left to right, then the top right to left.
    fn outline(&self) -> Vec<Vec2> {
        let mut pts = vec![self.floor[0].a];
        for s in &self.floor {
            pts.push(s.b);
        }
        pts.push(Vec2::new(self.x1(), self.top));
        pts.push(Vec2::new(self.x0(), self.top));
        simplify(pts)
    }
}

/// Drop repeated and collinear vertices of a closed outline.
fn simplify(pts: Vec<Vec2>) -> Vec<Vec2> {
    let scale = pts
        .iter()
        .map(|p| p.norm())
        .fold(1.0_f64, f64::max)
        .max(1e-300);
    let eps = 1e-12 * scale;
    let mut out: Vec<Vec2> = Vec::with_capacity(pts.len());
    for p in pts {
        if out.last().is_none_or(|q| (p - *q).norm() > eps) {
            out.push(p);
        }
    }
    while out.len() > 1 && (out[0] - out[out.len() - 1]).norm() <= eps {
        out.pop();
    }
    loop {
        let m = out.len();
        if m < 4 {
            break;
        }
        let Some(k) = (0..m).find(|&k| {
            let (a, b, c) = (out[(k + m - 1) % m], out[k], out[(k + 1) % m]);
            let turn = crate::geometry::cross(b - a, c - b);
            turn.abs() <= 1e-12 * (b - a).norm() * (c - b).norm()
        }) else {
            break;
        };
        out.remove(k);
    }
    out
}

/// The spandrel's blocks and joints, to be appended to a portal's or arcade's assembly whose
/// rings are `rings` (each with the index of its voussoir 0) and whose exposed tops at y = 0
/// are `tops` (`(block, x_from, x_to)`); the wall spans `x_left..x_right`; `first` is the index
/// its first block will have. Unit weight times depth `gamma`, friction `mu`.
#[allow(clippy::too_many_arguments)]
pub(super) fn build(
    spec: &SpandrelSpec,
    rings: &[(ArchGeometry, usize)],
    tops: &[(usize, f64, f64)],
    x_left: f64,
    x_right: f64,
    first: usize,
    gamma: f64,
    mu: f64,
) -> (Vec<Block>, Vec<Joint>) {
    // The floor: the exposed tops and every extrados chord, left to right.
    let mut floor: Vec<Stretch> = tops
        .iter()
        .map(|&(block, a, b)| Stretch {
            a: Vec2::new(a, 0.0),
            b: Vec2::new(b, 0.0),
            rest: Rest::Block(block),
        })
        .collect();
    let mut vertices = Vec::new();
    for (g, v0) in rings {
        let n = g.voussoirs();
        for j in 0..n {
            floor.push(Stretch {
                a: g.joints[j].1,
                b: g.joints[j + 1].1,
                rest: Rest::Block(v0 + j),
            });
            if j > 0 {
                vertices.push(g.joints[j].1.y);
            }
        }
    }
    floor.retain(|s| s.b.x > s.a.x);
    floor.sort_by(|s, t| s.a.x.total_cmp(&t.a.x));
    let size = (x_right - x_left).max(spec.level);
    let eps = 1e-12 * size;

    let lines = bed_lines(spec, &vertices);
    let u = spec.unit_length;
    let mut pieces: Vec<Piece> = Vec::new();
    let mut courses: Vec<std::ops::Range<usize>> = Vec::new();
    for c in 0..lines.len() - 1 {
        let (ya, yb) = (lines[c], lines[c + 1]);
        let start = pieces.len();
        // Breakpoints: the floor's vertices and its crossings of the two bed lines.
        let mut xs = vec![x_left, x_right];
        for s in &floor {
            xs.push(s.a.x);
            xs.push(s.b.x);
            for y in [ya, yb] {
                if (s.a.y - y) * (s.b.y - y) < 0.0 {
                    xs.push(s.a.x + (y - s.a.y) / (s.b.y - s.a.y) * (s.b.x - s.a.x));
                }
            }
        }
        xs.retain(|&x| x >= x_left && x <= x_right);
        xs.sort_by(f64::total_cmp);
        xs.dedup_by(|a, b| (*a - *b).abs() <= eps);
        // Elementary stretches of this course's floor max(extrados, ya) where it lies below yb.
        let mut runs: Vec<Vec<Stretch>> = Vec::new();
        let mut run: Vec<Stretch> = Vec::new();
        for w in xs.windows(2) {
            let (x0, x1) = (w[0], w[1]);
            let mid = 0.5 * (x0 + x1);
            let Some(s) = floor.iter().find(|s| s.a.x <= mid && mid <= s.b.x) else {
                // No floor here (cannot happen within the wall): end the run.
                runs.extend((!run.is_empty()).then(|| std::mem::take(&mut run)));
                continue;
            };
            let on_floor = s.y_at(mid) >= ya - eps;
            let stretch = if on_floor {
                Stretch {
                    a: Vec2::new(x0, s.y_at(x0).max(ya)),
                    b: Vec2::new(x1, s.y_at(x1).max(ya)),
                    rest: s.rest,
                }
            } else {
                Stretch {
                    a: Vec2::new(x0, ya),
                    b: Vec2::new(x1, ya),
                    rest: Rest::Below,
                }
            };
            let open = stretch.a.y.max(stretch.b.y) < yb - eps
                || 0.5 * (stretch.a.y + stretch.b.y) < yb - eps;
            if open {
                // A stretch that touches yb at an end closes the run there.
                let touches_left = stretch.a.y >= yb - eps;
                if touches_left && !run.is_empty() {
                    runs.push(std::mem::take(&mut run));
                }
                let touches_right = stretch.b.y >= yb - eps;
                run.push(stretch);
                if touches_right {
                    runs.push(std::mem::take(&mut run));
                }
            } else if !run.is_empty() {
                runs.push(std::mem::take(&mut run));
            }
        }
        runs.extend((!run.is_empty()).then_some(run));
        for run in runs {
            // Cuts: where the floor turns concave (an extrados vertex inside the course).
            let mut cuts = vec![run[0].a.x];
            for w in run.windows(2) {
                if w[0].slope() > w[1].slope() + 1e-9 {
                    cuts.push(w[0].b.x);
                }
            }
            let (lo, hi) = (run[0].a.x, run[run.len() - 1].b.x);
            cuts.push(hi);
            // Running bond: head joints at least a quarter unit from every other cut.
            let shift = if c % 2 == 0 { 0.0 } else { 0.5 };
            let mut heads = Vec::new();
            let mut i = ((lo / u) - shift).floor() as i64;
            loop {
                let x = (i as f64 + shift) * u;
                if x >= hi {
                    break;
                }
                if x > lo && cuts.iter().all(|&k| (x - k).abs() >= 0.25 * u) {
                    heads.push(x);
                }
                i += 1;
            }
            cuts.extend(heads);
            cuts.sort_by(f64::total_cmp);
            for w in cuts.windows(2) {
                let (x0, x1) = (w[0], w[1]);
                if x1 - x0 <= eps {
                    continue;
                }
                let floor: Vec<Stretch> = run
                    .iter()
                    .filter(|s| s.b.x > x0 + eps && s.a.x < x1 - eps)
                    .map(|s| Stretch {
                        a: Vec2::new(s.a.x.max(x0), s.y_at(s.a.x.max(x0))),
                        b: Vec2::new(s.b.x.min(x1), s.y_at(s.b.x.min(x1))),
                        rest: s.rest,
                    })
                    .collect();
                if !floor.is_empty() {
                    pieces.push(Piece {
                        course: c,
                        floor,
                        top: yb,
                    });
                }
            }
        }
        courses.push(start..pieces.len());
    }

    // Blocks.
    let mut blocks = Vec::with_capacity(pieces.len());
    let mut in_course = 0;
    for (k, p) in pieces.iter().enumerate() {
        if k > 0 && pieces[k - 1].course != p.course {
            in_course = 0;
        }
        let polygon = p.outline();
        let (area, centroid) = polygon_area_centroid(&polygon);
        blocks.push(Block {
            polygon,
            area,
            centroid,
            weight: gamma * area,
            kind: BlockKind::Spandrel(p.course, in_course),
        });
        in_course += 1;
    }
    // Joints.
    let mut joints = Vec::new();
    let mut joint = |p1: Vec2, p2: Vec2, from: usize, to: usize| {
        if (p2 - p1).norm() > eps {
            joints.push(Joint {
                p1,
                p2,
                from: Some(from),
                to: Some(to),
                friction: mu,
                kind: JointKind::Spandrel(from, to),
            });
        }
    };
    for (k, p) in pieces.iter().enumerate() {
        let me = first + k;
        // The floor, stretch by stretch (merged where it rests on one block): p1 the right
        // end, p2 the left one, so the normal points up into the piece.
        let mut m = 0;
        while m < p.floor.len() {
            let mut e = m;
            while e + 1 < p.floor.len() && p.floor[e + 1].rest == p.floor[m].rest {
                e += 1;
            }
            let (a, b) = (p.floor[m].a, p.floor[e].b);
            match p.floor[m].rest {
                Rest::Block(v) => joint(b, a, v, me),
                Rest::Below => {
                    for q in courses[p.course - 1].clone() {
                        let (lo, hi) = (a.x.max(pieces[q].x0()), b.x.min(pieces[q].x1()));
                        if hi - lo > eps {
                            joint(Vec2::new(hi, a.y), Vec2::new(lo, a.y), first + q, me);
                        }
                    }
                }
            }
            m = e + 1;
        }
        // The head joint with the next piece of the course, when they touch.
        if let Some(next) = pieces.get(k + 1) {
            if next.course == p.course && (next.x0() - p.x1()).abs() <= eps {
                let bottom = p.floor[p.floor.len() - 1].b;
                joint(bottom, Vec2::new(bottom.x, p.top), me, me + 1);
            }
        }
    }
    (blocks, joints)
}

/// The bed lines from the springing line to `level` (see the module docs, step 1), given the
/// heights of the rings' interior extrados vertices.
fn bed_lines(spec: &SpandrelSpec, vertices: &[f64]) -> Vec<f64> {
    let h = spec.course_height;
    let full = (spec.level / h + 1e-9).floor() as usize;
    let mut lines: Vec<f64> = (0..=full).map(|k| k as f64 * h).collect();
    let rest = spec.level - lines[lines.len() - 1];
    if rest > 1e-9 * h {
        if rest < 0.5 * h && lines.len() > 1 {
            lines.pop();
        }
        lines.push(spec.level);
    } else {
        let last = lines.len() - 1;
        lines[last] = spec.level;
    }
    // Lower a bed line that passes just above an extrados vertex onto the lowest such one.
    let top = lines.len() - 1;
    for c in 1..top {
        for _ in 0..2 {
            let y = lines[c];
            let below = vertices
                .iter()
                .copied()
                .filter(|&v| v < y && v > y - 0.25 * h && v >= lines[c - 1] + 0.5 * h)
                .fold(f64::INFINITY, f64::min);
            if below.is_finite() {
                lines[c] = below;
            } else {
                break;
            }
        }
    }
    lines
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bed_lines_merge_a_thin_top_course_and_dodge_vertices() {
        let spec = SpandrelSpec {
            level: 1.1,
            course_height: 0.25,
            unit_length: 0.5,
        };
        // 4 full courses and 0.1 left: the top course is 0.35 high.
        let lines = bed_lines(&spec, &[]);
        assert_eq!(lines.len(), 5);
        assert!((lines[4] - 1.1).abs() < 1e-15 && (lines[3] - 0.75).abs() < 1e-15);
        // A vertex 0.05 below the line at 0.5 pulls it down; one 0.1 below does not.
        let lines = bed_lines(&spec, &[0.45, 0.65]);
        assert_eq!(lines[2], 0.45);
        assert!((lines[3] - 0.75).abs() < 1e-15);
    }
}
