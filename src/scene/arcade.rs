//! Arcades (`[arcade]`): several equal bays side by side, each the scene's `[arch]` ring, on
//! the two outer piers of `[piers]` and `bays - 1` interior columns.
//!
//! Geometry (docs/geometry.md, "Arcades"): the columns are rectangular, `column_width` wide,
//! with the height and the number of courses of the piers; each column's faces are flush with
//! the intrados springing points of the two arches it carries, as a pier's inner face is. The
//! bays repeat at the pitch `s_i + column_width` (`s_i` the intrados span, the distance between
//! the intrados springing points) and the arcade is centred on x = 0: the middle of the middle
//! bay for an odd number of bays, the axis of the middle column for an even one. So one bay is
//! the portal of `[arch]` and `[piers]` exactly (the same assembly, built by the same code), and
//! a symmetric ring on equal piers gives a mirror-symmetric arcade to the last bit (bay k sits
//! at `(k - (bays - 1)/2) * pitch`, exactly the negative of bay `bays - 1 - k`).
//!
//! The two springing joints on a column top are the whole springing joints of the two arches
//! (from the intrados point to the extrados point): a column must be at least as wide as the two
//! springing joints side by side, or the springers would overlap. The part of the column top
//! between the two springers is exposed (a line load may rest on it, as on a pier top).
//!
//! Block order (no chain: the columns join three blocks): the left pier's courses from its base,
//! the voussoirs of bay 0 from the left, the courses of column 0 from its top, the voussoirs of
//! bay 1, ..., the voussoirs of the last bay, the right pier's courses from its top.

use super::piers::{self, Pier, PierProfile, Piers};
use super::{ArchSpec, Section};
use crate::assembly::{Block, BlockKind, Joint, JointKind};
use crate::error::SceneError;
use crate::geometry::{polygon_area_centroid, ArchGeometry, Vec2};

/// Largest number of bays: far beyond any arcade analysed as one piece of masonry; keeps a
/// scene's block count bounded (`bays` rings of up to [`super::MAX_VOUSSOIRS`] voussoirs).
pub const MAX_BAYS: usize = 50;

/// The keys of `[arcade]`.
pub(super) const ARCADE_KEYS: &[&str] = &["bays", "column_width"];

/// `[arcade]`: equal bays side by side.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct ArcadeSpec {
    /// Number of bays (1..=[`MAX_BAYS`]).
    pub bays: usize,
    /// Width of the interior columns (m).
    pub column_width: f64,
}

/// Read `[arcade]`; `arch` and `piers` are the scene's (an arcade needs piers of one height
/// and one number of courses, which the columns take).
pub(super) fn parse(
    mut s: Section,
    arch: &ArchSpec,
    piers: Option<&Piers>,
) -> Result<ArcadeSpec, SceneError> {
    s.check_known(ARCADE_KEYS, "")?;
    let bays = s.count("bays", None, 1, "number of bays (a whole number from 1)")?;
    if bays > MAX_BAYS {
        return Err(s.out_of_range(
            "bays",
            bays,
            &format!("must be a whole number from 1 to {MAX_BAYS}"),
        ));
    }
    let column_width = s.length("column_width", "width of the interior columns in metres")?;
    s.finish("")?;
    let Some(piers) = piers else {
        return Err(s.out_of_range(
            "bays",
            bays,
            "an arcade stands on piers: give [piers] (the two outer piers; the interior columns take their height and courses)",
        ));
    };
    if piers.left.height != piers.right.height {
        return Err(SceneError::OutOfRange {
            origin: s.origin.to_string(),
            key: "piers.right.height".into(),
            value: piers.right.height.to_string(),
            allowed: format!(
                "the interior columns of an arcade take the piers' height: both piers must have the same height (the left one is {} m)",
                piers.left.height
            ),
        });
    }
    if piers.left.courses != piers.right.courses {
        return Err(SceneError::OutOfRange {
            origin: s.origin.to_string(),
            key: "piers.right.courses".into(),
            value: piers.right.courses.to_string(),
            allowed: format!(
                "the interior columns of an arcade take the piers' courses: both piers must have the same number (the left one has {})",
                piers.left.courses
            ),
        });
    }
    if bays > 1 {
        if let Ok(g) = arch.geometry() {
            let n = g.voussoirs();
            let need = (g.joints[0].0.x - g.joints[0].1.x) + (g.joints[n].1.x - g.joints[n].0.x);
            if column_width < need {
                return Err(s.out_of_range(
                    "column_width",
                    column_width,
                    &format!(
                        "a column carries the springing joints of two arches side by side: it must be at least {need} m wide (two springing joints of the ring)"
                    ),
                ));
            }
        }
    }
    Ok(ArcadeSpec { bays, column_width })
}

impl ArcadeSpec {
    /// The x offset of bay `k`'s centre for a ring whose intrados springing points are
    /// `x_left` and `x_right` (about its own centre): bays at the pitch intrados span +
    /// column width, centred on x = 0.
    pub fn offset(&self, k: usize, x_left: f64, x_right: f64) -> f64 {
        let pitch = (x_right - x_left) + self.column_width;
        (k as f64 - 0.5 * (self.bays - 1) as f64) * pitch
    }

    /// The arcade in words: `3 bays on columns 0.5 m wide`.
    pub fn describe(&self) -> String {
        if self.bays == 1 {
            "an arcade of 1 bay".to_string()
        } else {
            format!(
                "an arcade of {} bays on interior columns {} m wide",
                self.bays,
                crate::geometry::trim(self.column_width)
            )
        }
    }
}

/// A ring translated by `dx` along x.
pub(super) fn shifted(g: &ArchGeometry, dx: f64) -> ArchGeometry {
    let d = Vec2::new(dx, 0.0);
    let mut out = g.clone();
    for j in &mut out.joints {
        j.0 += d;
        j.1 += d;
    }
    for a in &mut out.arcs {
        a.centre += d;
    }
    out
}

/// What the arcade's assembly is made of, for the placement and the spandrel: its rings
/// (each with the assembly index of its voussoir 0), the blocks under the springing line's
/// exposed tops, the outer faces of the piers' tops.
pub(super) struct ArcadeParts {
    pub blocks: Vec<Block>,
    pub joints: Vec<Joint>,
    /// The rings, left to right, each with the index of its voussoir 0 in `blocks`.
    pub rings: Vec<(ArchGeometry, usize)>,
    /// Exposed tops `(block, x_from, x_to)` at y = 0: pier tops outside the springings, column
    /// tops between the two springers.
    pub tops: Vec<(usize, f64, f64)>,
}

/// The blocks and joints of an arcade of `arcade.bays >= 2` bays of the ring `g` (unit weight
/// times depth `gamma`, friction `mu`) on `piers` (see the module docs for their order).
pub(super) fn assemble(
    g: &ArchGeometry,
    curved: bool,
    piers: &Piers,
    arcade: &ArcadeSpec,
    gamma: f64,
    mu: f64,
) -> ArcadeParts {
    let n = g.voussoirs();
    let (xi_l, xi_r) = (g.joints[0].0.x, g.joints[n].0.x);
    let bays = arcade.bays;
    let mut blocks: Vec<Block> = Vec::new();
    let mut joints: Vec<Joint> = Vec::new();
    let mut rings = Vec::new();
    let mut tops = Vec::new();
    let joint = |p1, p2, from, to, kind| Joint {
        p1,
        p2,
        from,
        to,
        friction: mu,
        kind,
    };
    let column = Pier {
        height: piers.left.height,
        courses: piers.left.courses,
        profile: PierProfile::Rectangular {
            width: arcade.column_width,
        },
    };
    // Left pier, base to top: its bed joints run from the inner face outward (n up).
    let ring0 = shifted(g, arcade.offset(0, xi_l, xi_r));
    let (xi0, xe0) = (ring0.joints[0].0.x, ring0.joints[0].1.x);
    for (c, course) in piers::courses(&piers.left, xi0, -1.0)
        .into_iter()
        .enumerate()
    {
        let below = c.checked_sub(1).map(|_| blocks.len() - 1);
        blocks.push(rect_block(course.polygon, gamma, BlockKind::LeftPier(c)));
        joints.push(joint(
            course.bed.0,
            course.bed.1,
            below,
            Some(blocks.len() - 1),
            JointKind::LeftPier(c),
        ));
    }
    let b = piers.left.top_width();
    let mut under = blocks.len() - 1; // the block the next springing rests on
    if xe0 > xi0 - b {
        tops.push((under, xi0 - b, xe0));
    }
    for k in 0..bays {
        let ring = shifted(g, arcade.offset(k, xi_l, xi_r));
        let first = blocks.len();
        // Springing joint 0: on the left pier's top (clipped to it), or on a column's top.
        let (p1, p2) = if k == 0 {
            (Vec2::new(xi0, 0.0), Vec2::new(xe0.max(xi0 - b), 0.0))
        } else {
            (ring.joints[0].0, ring.joints[0].1)
        };
        joints.push(joint(
            p1,
            p2,
            Some(under),
            Some(first),
            JointKind::Bay(k, 0),
        ));
        for j in 0..n {
            blocks.push(voussoir_block(
                &ring,
                j,
                curved,
                gamma,
                BlockKind::BayVoussoir(k, j),
            ));
            if j + 1 < n {
                let (p1, p2) = ring.joints[j + 1];
                joints.push(joint(
                    p1,
                    p2,
                    Some(first + j),
                    Some(first + j + 1),
                    JointKind::Bay(k, j + 1),
                ));
            }
        }
        let last = first + n - 1;
        let (xir, xer) = (ring.joints[n].0.x, ring.joints[n].1.x);
        if k + 1 < bays {
            // Column k, top to base: beds from its left face to its right face (n down).
            let top = blocks.len();
            joints.push(joint(
                ring.joints[n].0,
                ring.joints[n].1,
                Some(last),
                Some(top),
                JointKind::Bay(k, n),
            ));
            let kc = column.courses;
            stack_top_down(
                &mut blocks,
                &mut joints,
                piers::courses(&column, xir, 1.0),
                (gamma, mu),
                |c| (BlockKind::Column(k, c), JointKind::Column(k, c)),
            );
            let next = shifted(g, arcade.offset(k + 1, xi_l, xi_r));
            let xe_next = next.joints[0].1.x;
            if xe_next > xer {
                tops.push((top, xer, xe_next));
            }
            under = top;
            debug_assert_eq!(top + kc, blocks.len());
        } else {
            // The right pier, top to base.
            let br = piers.right.top_width();
            let pier_top = blocks.len();
            joints.push(joint(
                Vec2::new(xir, 0.0),
                Vec2::new(xer.min(xir + br), 0.0),
                Some(last),
                Some(pier_top),
                JointKind::Bay(k, n),
            ));
            if xer < xir + br {
                tops.push((pier_top, xer, xir + br));
            }
            stack_top_down(
                &mut blocks,
                &mut joints,
                piers::courses(&piers.right, xir, 1.0),
                (gamma, mu),
                |c| (BlockKind::RightPier(c), JointKind::RightPier(c)),
            );
        }
        rings.push((ring, first));
    }
    ArcadeParts {
        blocks,
        joints,
        rings,
        tops,
    }
}

/// Stack `courses` (from the base up) as blocks from the top down, each with its bed joint
/// under it (from the course to the one below, or to the ground for course 0: the bed runs
/// from the left face to the right one, so its normal points down), kinds by `kinds(course)`;
/// `(gamma, mu)` the unit weight times depth and the friction.
fn stack_top_down(
    blocks: &mut Vec<Block>,
    joints: &mut Vec<Joint>,
    courses: Vec<piers::Course>,
    (gamma, mu): (f64, f64),
    kinds: impl Fn(usize) -> (BlockKind, JointKind),
) {
    for (c, course) in courses.into_iter().enumerate().rev() {
        let (block, joint) = kinds(c);
        blocks.push(rect_block(course.polygon, gamma, block));
        let here = blocks.len() - 1;
        joints.push(Joint {
            p1: course.bed.0,
            p2: course.bed.1,
            from: Some(here),
            to: (c > 0).then_some(here + 1),
            friction: mu,
            kind: joint,
        });
    }
}

/// Voussoir `j` of the ring `g` as a block of kind `kind`: its quadrilateral, with the area
/// and centroid of the quadrilateral or (`curved`) of the exact annular piece.
pub(super) fn voussoir_block(
    g: &ArchGeometry,
    j: usize,
    curved: bool,
    gamma: f64,
    kind: BlockKind,
) -> Block {
    let (area, centroid) = g.voussoir_area_centroid(j, curved);
    Block {
        polygon: g.quad(j).to_vec(),
        area,
        centroid,
        weight: gamma * area,
        kind,
    }
}

pub(crate) fn rect_block(polygon: Vec<Vec2>, gamma: f64, kind: BlockKind) -> Block {
    let (area, centroid) = polygon_area_centroid(&polygon);
    Block {
        polygon,
        area,
        centroid,
        weight: gamma * area,
        kind,
    }
}
