//! Assemblies: rigid blocks and the plane joints (interfaces) between them or between a
//! block and the ground (a support). Analyses take an `Assembly`, never a scene, so any
//! structure made of blocks and joints can be analysed, not only the arch-and-pier chains a
//! scene builds.
//!
//! Sign convention of a joint: `u = (p2 - p1)/|p2 - p1|` runs along the joint, and the normal
//! `n = (u_y, -u_x)` points from the block `from` into the block `to`. The force that `from`
//! exerts on `to` is `N n + V u` with `N >= 0` (compression), and its moment about the joint
//! midpoint is `M`, positive when the resultant sits toward `p2` (`e = M/N`).

use crate::error::AnalysisError;
use crate::geometry::{self, Vec2};

/// What a block is, for labels and drawings.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum BlockKind {
    /// An arch voussoir, numbered from the left springing.
    Voussoir(usize),
    /// A course of the left pier, numbered from the base.
    LeftPier(usize),
    /// A course of the right pier, numbered from the base.
    RightPier(usize),
    /// Any other block (assemblies built by hand).
    Other,
    /// A block of the user's own (`[blocks]`), by its index in the source (from 0).
    User(usize),
    /// A voussoir of an arcade (`[arcade]`, two bays or more): the bay from the left (from 0)
    /// and the voussoir from the bay's left springing.
    BayVoussoir(usize, usize),
    /// A course of an arcade's interior column: the column from the left (from 0; column k
    /// stands between bays k and k + 1) and the course from the base.
    Column(usize, usize),
    /// A piece of the spandrel wall (`[spandrel]`): the course from the springing line (from
    /// 0) and the piece from the left within it.
    Spandrel(usize, usize),
}

/// A rigid block.
#[derive(Debug, Clone)]
pub struct Block {
    /// Outline (convex polygon, counter-clockwise or clockwise).
    pub polygon: Vec<Vec2>,
    /// Area (m^2); for curved voussoirs the exact annular area, not the polygon's.
    pub area: f64,
    /// Centroid (m), where the weight and the seismic load act.
    pub centroid: Vec2,
    /// Weight W = unit weight * depth * area (N).
    pub weight: f64,
    pub kind: BlockKind,
}

/// What a joint is, for labels.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum JointKind {
    /// Arch joint j (0 = left springing, n = right springing).
    Arch(usize),
    /// Left pier joint, numbered from the base (0 = the base on the ground).
    LeftPier(usize),
    /// Right pier joint, numbered from the base.
    RightPier(usize),
    Other,
    /// A joint found between the user's blocks (`[blocks]`), named by their indices in the
    /// source, the lower first; `None` is the ground.
    Between(usize, Option<usize>),
    /// A support of the user's block `a` on the fixed block `f` (`[blocks] fixed`), both
    /// named by their indices in the source: a joint to the ground (`from` or `to` None)
    /// that lies on a block that does not move.
    Fixed(usize, usize),
    /// Arch joint j of bay k of an arcade (two bays or more): `(k, j)`.
    Bay(usize, usize),
    /// Bed joint of an arcade's interior column: `(column, course)`, the course above it
    /// counted from the base (0: the column's base on the ground).
    Column(usize, usize),
    /// A joint of the spandrel wall, between the blocks `(from, to)` of the assembly (a
    /// voussoir, pier or column course, or a wall piece, and a wall piece).
    Spandrel(usize, usize),
}

/// A plane joint between two blocks, or a block and the ground (`None`).
#[derive(Debug, Clone)]
pub struct Joint {
    pub p1: Vec2,
    pub p2: Vec2,
    /// The block on the `-n` side (`None` = ground).
    pub from: Option<usize>,
    /// The block on the `+n` side (`None` = ground).
    pub to: Option<usize>,
    /// Coulomb friction coefficient (`inf` = no sliding).
    pub friction: f64,
    pub kind: JointKind,
}

impl Joint {
    pub fn length(&self) -> f64 {
        (self.p2 - self.p1).norm()
    }
    /// Unit vector from p1 to p2.
    pub fn tangent(&self) -> Vec2 {
        (self.p2 - self.p1) / self.length()
    }
    /// Unit normal, pointing from `from` into `to`.
    pub fn normal(&self) -> Vec2 {
        let u = self.tangent();
        Vec2::new(u.y, -u.x)
    }
    pub fn midpoint(&self) -> Vec2 {
        0.5 * (self.p1 + self.p2)
    }
    /// Whether the joint lies on the ground.
    pub fn is_support(&self) -> bool {
        self.from.is_none() || self.to.is_none()
    }
}

/// Blocks and joints.
#[derive(Debug, Clone)]
pub struct Assembly {
    pub blocks: Vec<Block>,
    pub joints: Vec<Joint>,
}

impl Assembly {
    /// Check that the assembly is well formed: indices in range, joints of positive length,
    /// each joint's `to` block on the `+n` side, positive weights.
    pub fn validate(&self) -> Result<(), AnalysisError> {
        let nb = self.blocks.len();
        if nb == 0 {
            return Err(AnalysisError::Assembly("no blocks".into()));
        }
        for (i, b) in self.blocks.iter().enumerate() {
            if !(b.weight.is_finite() && b.weight > 0.0 && b.area > 0.0) {
                return Err(AnalysisError::Assembly(format!(
                    "block {i} has weight {} and area {}: both must be positive",
                    b.weight, b.area
                )));
            }
            if !is_convex(&b.polygon) {
                return Err(AnalysisError::Assembly(format!(
                    "block {i} ({:?}) is not a convex polygon: its outline folds over itself",
                    b.kind
                )));
            }
        }
        for (j, jt) in self.joints.iter().enumerate() {
            if jt.length().is_nan() || jt.length() <= 0.0 {
                return Err(AnalysisError::Assembly(format!(
                    "joint {j} has zero length"
                )));
            }
            if jt.from.is_none() && jt.to.is_none() {
                return Err(AnalysisError::Assembly(format!(
                    "joint {j} joins the ground to the ground"
                )));
            }
            for (side, sign) in [(jt.from, -1.0), (jt.to, 1.0)] {
                if let Some(b) = side {
                    if b >= nb {
                        return Err(AnalysisError::Assembly(format!(
                            "joint {j} refers to block {b}, but there are {nb} blocks"
                        )));
                    }
                    let d = (self.blocks[b].centroid - jt.midpoint()).dot(&jt.normal());
                    if sign * d <= 0.0 {
                        return Err(AnalysisError::Assembly(format!(
                            "joint {j}: block {b} lies on the wrong side of the joint normal"
                        )));
                    }
                }
            }
            if jt.friction.is_nan() || jt.friction < 0.0 {
                return Err(AnalysisError::Assembly(format!(
                    "joint {j} has friction {}",
                    jt.friction
                )));
            }
        }
        Ok(())
    }

    /// Total weight (N).
    pub fn total_weight(&self) -> f64 {
        self.blocks.iter().map(|b| b.weight).sum()
    }

    /// Largest extent of the assembly's bounding box (m).
    pub fn size(&self) -> f64 {
        let mut lo = Vec2::repeat(f64::INFINITY);
        let mut hi = Vec2::repeat(f64::NEG_INFINITY);
        for p in self.blocks.iter().flat_map(|b| b.polygon.iter()) {
            lo = lo.inf(p);
            hi = hi.sup(p);
        }
        (hi - lo).max()
    }

    /// Whether blocks and joints form a chain between two supports, in order: joint k joins
    /// block k - 1 (or the ground for k = 0) to block k (or the ground for the last joint).
    pub fn is_chain(&self) -> bool {
        let nb = self.blocks.len();
        self.joints.len() == nb + 1
            && self.joints.iter().enumerate().all(|(k, j)| {
                j.from == k.checked_sub(1) && j.to == if k < nb { Some(k) } else { None }
            })
    }

    /// Whether every joint carries the one thrust of the structure: a chain between two
    /// supports, or a single block. Elsewhere (a wall, a stack) a joint may carry little or no
    /// compression, and real (non-associative) joints may have collapse states below an exact
    /// associative one (`statics::FrictionCheck::lower_states_possible`, docs/friction.md).
    pub fn is_single_thrust_path(&self) -> bool {
        self.is_chain() || self.blocks.len() < 2
    }

    /// The same assembly mirrored about x = 0 (block and joint order reversed, so a chain
    /// stays a chain from left to right; p1/p2 keep their meaning).
    pub fn mirrored(&self) -> Assembly {
        let nb = self.blocks.len();
        let flip = |b: Option<usize>| b.map(|i| nb - 1 - i);
        let blocks = self
            .blocks
            .iter()
            .rev()
            .map(|b| Block {
                polygon: b
                    .polygon
                    .iter()
                    .rev()
                    .map(|p| geometry::mirror(*p))
                    .collect(),
                centroid: geometry::mirror(b.centroid),
                ..b.clone()
            })
            .collect();
        let joints = self
            .joints
            .iter()
            .rev()
            .map(|j| Joint {
                p1: geometry::mirror(j.p1),
                p2: geometry::mirror(j.p2),
                // Mirroring reverses the normal (u_y, -u_x) relative to the blocks.
                from: flip(j.to),
                to: flip(j.from),
                ..j.clone()
            })
            .collect();
        Assembly { blocks, joints }
    }
}

pub use crate::geometry::is_convex;

/// Which end of a joint a hinge sits at.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum JointEnd {
    /// The intrados end (arch) or inner face (pier).
    P1,
    /// The extrados end (arch) or outer face (pier).
    P2,
}

/// A hinge: a joint whose resultant (or rotation centre) sits at one of its ends — or, with a
/// finite compressive strength, at the centre of the compressed zone next to that end.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct Hinge {
    pub joint: usize,
    pub end: JointEnd,
    /// The hinge point (m): the joint's end, or `offset` inside it.
    pub x: f64,
    pub y: f64,
    /// Distance (m) of the hinge point from the joint's end `end`: `a/2` with crushing, 0 for
    /// rigid joints.
    pub offset: f64,
    /// Width `a = N/(fc d)` (m) of the compressed zone at the hinge; 0 for rigid joints.
    pub compressed_zone: f64,
}

impl Hinge {
    pub fn at(assembly: &Assembly, joint: usize, end: JointEnd) -> Hinge {
        let j = &assembly.joints[joint];
        let p = match end {
            JointEnd::P1 => j.p1,
            JointEnd::P2 => j.p2,
        };
        Hinge {
            joint,
            end,
            x: p.x,
            y: p.y,
            offset: 0.0,
            compressed_zone: 0.0,
        }
    }

    /// A crushing hinge: the resultant at the centre of a compressed zone of width
    /// `compressed_zone` (m) that starts at the end `end` of joint `joint`.
    pub fn crushing(
        assembly: &Assembly,
        joint: usize,
        end: JointEnd,
        compressed_zone: f64,
    ) -> Hinge {
        let j = &assembly.joints[joint];
        let offset = 0.5 * compressed_zone;
        let p = match end {
            JointEnd::P1 => j.p1 + offset * j.tangent(),
            JointEnd::P2 => j.p2 - offset * j.tangent(),
        };
        Hinge {
            joint,
            end,
            x: p.x,
            y: p.y,
            offset,
            compressed_zone,
        }
    }
}

/// Internal force of a joint: the force `N n + V u` that `from` exerts on `to`, with moment `M`
/// about the midpoint.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct JointForce {
    pub n: f64,
    pub v: f64,
    pub m: f64,
}

/// The thrust-line point of each joint, `p_mid + (M/N) u` (None where the joint carries no
/// force).
pub fn thrust_points(assembly: &Assembly, forces: &[JointForce]) -> Vec<Option<Vec2>> {
    assembly
        .joints
        .iter()
        .zip(forces)
        .map(|(j, f)| (f.n > 0.0).then(|| j.midpoint() + (f.m / f.n) * j.tangent()))
        .collect()
}
