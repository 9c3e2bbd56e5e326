//! Interactions: what joins the blocks of a model, one file per kind. Each kind gives
//!
//! - its **static rows**: the unknowns it adds to the static program, the forces they put on
//!   the blocks' equilibrium rows, and the cones those unknowns lie in ([`Rows`], the
//!   program in the making; `crate::statics` turns it into Clarabel's standard form);
//! - its **work rate** in a mechanism (the power it dissipates for given block velocities),
//!   which the virtual-work equation of the kinematic searches adds to the work done against
//!   the permanent loads;
//! - its **DEM force** and its **drawing marks**, where the method has them.
//!
//! The kinds:
//! - [`contact`]: the plane joints (no tension, the resultant inside the joint, Coulomb
//!   friction), the interaction every masonry model has (Livesley, 1978; Gilbert, Casapulla &
//!   Ahmed, 2006);
//! - [`crushing`]: a finite compressive strength of the contacts, a rectangular stress block
//!   (RING's model; Gilbert, 2007), as second-order cones on the contacts' unknowns;
//! - [`tie`]: tie rods, a force between two anchor points in tension only, bounded by its
//!   prestress and its capacity;
//! - [`strip`]: bonded strips, a tension at a joint's reinforced end up to the strip's
//!   capacity;
//! - [`passive`]: the fill's passive resistance, a one-sided horizontal reaction on a face
//!   against the fill up to its mobilised passive force.
//!
//! A new interaction is one more file here and one more loop in the methods that take it; a
//! method that cannot represent a kind refuses the model by a typed reason.

pub mod contact;
pub mod crushing;
pub mod passive;
pub mod strip;
pub mod tie;

pub use crushing::Strength;
pub use passive::{Passive, PassiveForce};
pub use strip::{Strip, StripForce};
pub use tie::{Anchor, Tie, TieForce};

use crate::assembly::Assembly;
use crate::geometry::{cross, Vec2};

/// A row of a cone: the entries `(column, a)` and the right-hand side `b`, for `s = b - a.x`.
pub type Row = (Vec<(usize, f64)>, f64);

/// A static program in the making: `A x + s = b` with `s` in the zero cone (the equilibrium
/// rows, three per block: forces along x and y, and the moment about the block's centroid
/// divided by the length scale), the nonnegative cone and a list of three-dimensional
/// second-order cones, in that order; all quantities dimensionless (forces over
/// `force_scale`, lengths over `length_scale`). Column 0 is the multiplier (or, in the
/// phase-one program, the relaxation `tau`, which every relaxable row takes with coefficient
/// -1 so that `row + tau >= 0`).
pub struct Rows {
    /// Length scale (m).
    pub length_scale: f64,
    /// Force scale (N).
    pub force_scale: f64,
    /// Whether this is the phase-one program (relaxable rows take `tau`).
    pub relax: bool,
    columns: usize,
    centroids: Vec<Vec2>,
    /// Equilibrium entries `(row, column, value)` and right-hand side.
    pub(crate) equality: Vec<(usize, usize, f64)>,
    pub(crate) b_equality: Vec<f64>,
    /// Nonnegative rows: `b - a.x >= 0`, entries `(column, a)`.
    pub(crate) nonnegative: Vec<Row>,
    /// Second-order cones: three rows each, `b - a.x` in the cone.
    pub(crate) cones: Vec<[Row; 3]>,
}

impl Rows {
    /// An empty program for `assembly`: column 0 (the multiplier) and three equilibrium rows
    /// per block, with no entries yet.
    pub fn new(assembly: &Assembly, force_scale: f64, relax: bool) -> Rows {
        Rows {
            length_scale: assembly.size(),
            force_scale,
            relax,
            columns: 1,
            centroids: assembly.blocks.iter().map(|b| b.centroid).collect(),
            equality: Vec::new(),
            b_equality: vec![0.0; 3 * assembly.blocks.len()],
            nonnegative: Vec::new(),
            cones: Vec::new(),
        }
    }

    /// `count` new unknowns; the index of the first.
    pub fn add_columns(&mut self, count: usize) -> usize {
        let first = self.columns;
        self.columns += count;
        first
    }

    /// The number of unknowns so far.
    pub fn columns(&self) -> usize {
        self.columns
    }

    /// Unknown `column`, times the unit force `dir` applied at `point` of block `block`,
    /// acts on that block with sign `sign` (+1 or -1); nothing for the ground (`None`).
    pub fn force_on(
        &mut self,
        block: Option<usize>,
        column: usize,
        dir: Vec2,
        point: Vec2,
        sign: f64,
    ) {
        let Some(blk) = block else { return };
        let r = (point - self.centroids[blk]) / self.length_scale;
        self.equality.push((3 * blk, column, sign * dir.x));
        self.equality.push((3 * blk + 1, column, sign * dir.y));
        self.equality
            .push((3 * blk + 2, column, sign * cross(r, dir)));
    }

    /// A row `rhs - sum a x >= 0` of the nonnegative cone; `relaxable` rows take the phase-one
    /// relaxation (`+ tau`).
    pub fn nonnegative(&mut self, mut entries: Vec<(usize, f64)>, rhs: f64, relaxable: bool) {
        if relaxable && self.relax {
            entries.push((0, -1.0));
        }
        self.nonnegative.push((entries, rhs));
    }

    /// A second-order cone `s = b - a.x`, `||(s1, s2)|| <= s0`, three rows.
    pub fn cone(&mut self, rows: [Row; 3]) {
        self.cones.push(rows);
    }

    /// Append the rows of `other` (built for the same assembly and scales), sharing its
    /// first `shared` columns (the multiplier and any unknowns common to both) and giving
    /// its other columns new indices after these: two load directions of one design.
    pub fn append_copy(&mut self, other: Rows, shared: usize) {
        let offset = self.columns - shared;
        let map = |c: usize| if c < shared { c } else { c + offset };
        let row0 = self.b_equality.len();
        self.equality.extend(
            other
                .equality
                .iter()
                .map(|&(r, c, v)| (row0 + r, map(c), v)),
        );
        self.b_equality.extend(other.b_equality);
        let remap = |(entries, rhs): &Row| -> Row {
            (entries.iter().map(|&(c, v)| (map(c), v)).collect(), *rhs)
        };
        self.nonnegative.extend(other.nonnegative.iter().map(remap));
        self.cones.extend(
            other
                .cones
                .iter()
                .map(|c| [remap(&c[0]), remap(&c[1]), remap(&c[2])]),
        );
        self.columns += other.columns - shared;
    }

    /// Fix unknown `column` at `value` (one more equality row).
    pub fn fix_column(&mut self, column: usize, value: f64) {
        let row = self.b_equality.len();
        self.equality.push((row, column, 1.0));
        self.b_equality.push(value);
    }
}
