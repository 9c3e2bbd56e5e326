//! The static program in Clarabel's standard form
//! `min q'x  s.t.  A x + s = b,  s in K`, built from an assembly.
//!
//! Variables (dimensionless): `x = [lambda, c1_0, c2_0, V_0, c1_1, ...]`, where `c1, c2 >= 0`
//! are the compressive forces at the ends p1, p2 of each joint and V its shear, divided by the
//! total weight. Lengths are divided by the structure's size. Rows:
//! 1. zero cone, 3 per block: equilibrium of forces and of moments about the block centroid,
//!    `sum_j +-(c1 n + c2 n + V u) + lambda S + P = 0`, with `P` the block's permanent loads
//!    and `S` its seismic forces per unit lambda, both from the [`LoadCase`] (for self-weight
//!    alone `P = -W e_y`, `S = d W e_x`);
//! 2. nonnegative cone: `c1, c2 >= 0` (no tension, resultant inside the joint; implied by
//!    the crushing cones of item 3 and left out with them), then for joints
//!    with finite friction `mu (c1 + c2) - V >= 0` and `mu (c1 + c2) + V >= 0` (the planar
//!    Coulomb cone is a pair of half-planes, so no second-order cone is needed).
//!
//! 3. with a finite compressive strength `fc` over the depth `d` (a rectangular stress block,
//!    [`Strength`]), two rotated second-order cones per joint: with `N = c1 + c2` and
//!    `M = (c2 - c1) L/2`, the crushing condition `|M| <= N L/2 - N^2/(2 fc d)` is exactly
//!    `2 c1 kappa >= N^2` and `2 c2 kappa >= N^2`, `kappa = fc d L / fs` (since
//!    `N L/2 - M = c1 L` and `N L/2 + M = c2 L`), and `N <= fc d L` follows from the two.
//!    Each is given to Clarabel as `SecondOrderConeT(3)`, divided by kappa for scaling:
//!    `||(c - 1, sqrt2 N / sqrt(kappa))|| <= c + 1`, no linearisation.
//!
//! The objective `q = -e_lambda` maximises lambda (Clarabel minimises).
//!
//! A second program, [`Objective::MinTension`], tests whether the structure stands at
//! lambda = 0 (a phase-one program): column 0 becomes a relaxation `tau` added to every
//! inequality row, `c1 + tau >= 0`, `c2 + tau >= 0`, `mu N -+ V + tau >= 0`, with `tau >= -1`,
//! and in the crushing cones `c + tau` stands for `c` (`2 (c + tau) kappa >= N^2`); `tau` is
//! minimised. The structure stands if and only if `tau* <= 0`. Unlike the
//! lambda program, whose feasible set shrinks to a single point at the minimum thickness and
//! defeats interior-point methods there, this program always has a strict interior, so its
//! optimum changes sign cleanly as the thickness crosses the minimum.

use crate::assembly::Assembly;
use crate::interaction::contact::{self, ShearLimit};
use crate::interaction::{crushing, Passive, Rows, Strip, Tie};
use crate::model::{LoadCase, Model, Strength};
use clarabel::algebra::CscMatrix;
use clarabel::solver::SupportedConeT;

/// Problem data, with the scales needed to read the solution back in SI units.
pub struct StaticProblem {
    pub p: CscMatrix<f64>,
    pub q: Vec<f64>,
    pub a: CscMatrix<f64>,
    pub b: Vec<f64>,
    pub cones: Vec<SupportedConeT<f64>>,
    /// Length scale (m).
    pub length_scale: f64,
    /// Force scale (N): [`LoadCase::force_scale`] (the total weight under self-weight).
    pub force_scale: f64,
    /// Joints with friction rows, in row order.
    pub friction_joints: Vec<usize>,
    /// Column of each tie's tension (over the force scale), in tie order.
    pub tie_columns: Vec<usize>,
    /// Column of each strip's tension (over the force scale), in strip order.
    pub strip_columns: Vec<usize>,
    /// Column of each passive reaction (over the force scale), in face order.
    pub passive_columns: Vec<usize>,
    /// Number of equality rows (3 per block).
    pub equality_rows: usize,
    /// Number of inequality rows.
    pub inequality_rows: usize,
    /// Number of second-order-cone rows (3 per crushing cone, 2 cones per joint; 0 when rigid).
    pub cone_rows: usize,
}

/// What the program optimises.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Objective {
    /// Maximise lambda with the load in direction `sign` (+1 right, -1 left); `cap` adds the
    /// row `lambda <= cap`.
    MaxLambda { sign: f64, cap: Option<f64> },
    /// Minimise the tension relaxation `tau` at lambda = 0.
    MinTension,
    /// At the multiplier fixed at `lambda` (load toward `sign`), minimise the joints' friction
    /// capacity `sum mu_j N_j` over the joints with finite friction: the equilibrium with the
    /// least normal forces where they give friction, which the non-associative iteration
    /// takes among the optima of [`Objective::MaxLambda`] (`crate::statics::non_associative`).
    LeastFriction { sign: f64, lambda: f64 },
}

/// Column of a joint unknown: 0 = c1, 1 = c2, 2 = V (the contacts' columns come first, after
/// the multiplier).
pub fn column(joint: usize, which: usize) -> usize {
    contact::column_from(1, joint, which)
}

impl StaticProblem {
    /// Build the program for `assembly` under `loads`, with the seismic load in direction
    /// `sign` (+1 right, -1 left). `lambda_cap`, when given, adds the row `lambda <= cap`.
    /// Rigid joints (infinite compressive strength).
    pub fn new(assembly: &Assembly, loads: &LoadCase, objective: Objective) -> StaticProblem {
        Self::with_strength(assembly, loads, Strength::rigid(), objective)
    }

    /// The program with joints of compressive strength `strength` (crushing cones when finite).
    pub fn with_strength(
        assembly: &Assembly,
        loads: &LoadCase,
        strength: Strength,
        objective: Objective,
    ) -> StaticProblem {
        Self::with_interactions(assembly, loads, strength, &[], &[], &[], objective)
    }

    /// The program with every interaction: the contacts, their crushing cones when
    /// `strength` is finite, the tie rods `ties`, the strips `strips` and the fill's passive
    /// reactions `passive`.
    #[allow(clippy::too_many_arguments)]
    pub fn with_interactions(
        assembly: &Assembly,
        loads: &LoadCase,
        strength: Strength,
        ties: &[Tie],
        strips: &[Strip],
        passive: &[Passive],
        objective: Objective,
    ) -> StaticProblem {
        Self::with_shear_limit(
            assembly,
            loads,
            strength,
            ties,
            strips,
            passive,
            ShearLimit::Coulomb,
            objective,
        )
    }

    /// The program of `model`: its assembly, loads, strength and interactions, the contacts'
    /// shear bounded by `shear`.
    pub fn of_model(model: &Model, shear: ShearLimit<'_>, objective: Objective) -> StaticProblem {
        Self::with_shear_limit(
            &model.assembly,
            &model.loads,
            model.strength,
            &model.ties,
            &model.strips,
            &model.passive,
            shear,
            objective,
        )
    }

    /// [`StaticProblem::with_interactions`] with the contacts' shear bounded by `shear`
    /// (Coulomb's law, or fixed capacities: the non-associative iteration's programs).
    #[allow(clippy::too_many_arguments)]
    pub fn with_shear_limit(
        assembly: &Assembly,
        loads: &LoadCase,
        strength: Strength,
        ties: &[Tie],
        strips: &[Strip],
        passive: &[Passive],
        shear: ShearLimit<'_>,
        objective: Objective,
    ) -> StaticProblem {
        let (sign, lambda_cap, relax) = match objective {
            Objective::MaxLambda { sign, cap } => (sign, cap, false),
            Objective::MinTension => (0.0, None, true),
            Objective::LeastFriction { sign, .. } => (sign, None, false),
        };
        let mut rows = Rows::new(assembly, loads.force_scale(), relax);
        let (friction_joints, tie_columns, strip_columns, passive_columns) = program_rows(
            assembly,
            loads,
            strength,
            ties,
            strips,
            passive,
            sign,
            DesignColumns::default(),
            shear,
            &mut rows,
        );
        if let Some(cap) = lambda_cap {
            rows.nonnegative(vec![(0, 1.0)], cap, false);
        }
        if relax {
            // tau >= -1 keeps the phase-one program bounded.
            rows.nonnegative(vec![(0, -1.0)], 1.0, false);
        }
        if let Objective::LeastFriction { lambda, .. } = objective {
            rows.fix_column(0, lambda);
            let mut q = vec![0.0; rows.columns()];
            for &j in &friction_joints {
                let mu = assembly.joints[j].friction;
                q[column(j, 0)] = mu;
                q[column(j, 1)] = mu;
            }
            let mut p = Self::assemble_with(rows, q, friction_joints, tie_columns);
            p.strip_columns = strip_columns;
            p.passive_columns = passive_columns;
            return p;
        }
        let mut p = Self::assemble(rows, friction_joints, tie_columns, relax);
        p.strip_columns = strip_columns;
        p.passive_columns = passive_columns;
        p
    }

    /// Clarabel's standard form of `rows`, maximising column 0 (or minimising the phase-one
    /// relaxation).
    pub(crate) fn assemble(
        rows: Rows,
        friction_joints: Vec<usize>,
        tie_columns: Vec<usize>,
        relax: bool,
    ) -> StaticProblem {
        let mut q = vec![0.0; rows.columns()];
        q[0] = if relax { 1.0 } else { -1.0 };
        Self::assemble_with(rows, q, friction_joints, tie_columns)
    }
}

/// The columns of the capacities a retrofit design sizes (`crate::statics::design`), by
/// interaction: `ties[k]` for tie k, `strips[k]` for strip k (`Model::strips`); None, or an
/// index past the slice, keeps the interaction's own capacity.
#[derive(Debug, Clone, Copy, Default)]
pub(crate) struct DesignColumns<'a> {
    pub ties: &'a [Option<usize>],
    pub strips: &'a [Option<usize>],
}

/// The rows of the static program, without its objective and its own bounds on column 0: the
/// loads (the action toward `sign` times column 0, the permanent loads on the right-hand
/// side) and every interaction. `design.ties[k]`, when given for tie k, is the column of its
/// capacity, an unknown of a retrofit design (`crate::statics::design`), and
/// `design.strips[k]` that of strip k's; `shear` bounds the
/// contacts' shear ([`ShearLimit`]). Returns the joints with friction rows, the ties' columns,
/// the strips' and the passive reactions'.
#[allow(clippy::too_many_arguments)]
pub(crate) fn program_rows(
    assembly: &Assembly,
    loads: &LoadCase,
    strength: Strength,
    ties: &[Tie],
    strips: &[Strip],
    passive: &[Passive],
    sign: f64,
    design: DesignColumns<'_>,
    shear: ShearLimit<'_>,
    rows: &mut Rows,
) -> (Vec<usize>, Vec<usize>, Vec<usize>, Vec<usize>) {
    let relax = rows.relax;
    let fs = rows.force_scale;
    let ls = rows.length_scale;
    {
        // The loads: the action times lambda (column 0) and the permanent loads (the
        // right-hand side).
        for i in 0..assembly.blocks.len() {
            if !relax {
                let s = loads.variable(i, sign);
                for (k, v) in [s.force.x / fs, s.force.y / fs, s.moment / (fs * ls)]
                    .into_iter()
                    .enumerate()
                {
                    if v != 0.0 {
                        rows.equality.push((3 * i + k, 0, v));
                    }
                }
            }
            let p = loads.permanent(i);
            rows.b_equality[3 * i] = -p.force.x / fs;
            rows.b_equality[3 * i + 1] = -p.force.y / fs;
            rows.b_equality[3 * i + 2] = -p.moment / (fs * ls);
        }
        // The interactions, each in its own file. With crushing cones `c >= 0` follows from
        // the cones (c + 1 >= |c - 1|): the contacts leave those rows out, since a nearly
        // parallel duplicate of a strong material's cone splits its dual between the two
        // and costs the interior point accuracy.
        let (first, friction_joints) =
            contact::static_rows(assembly, rows, strength.is_finite(), shear);
        crushing::static_rows(assembly, strength, rows, first);
        let tie_columns = ties
            .iter()
            .enumerate()
            .map(|(k, t)| match design.ties.get(k).copied().flatten() {
                Some(capacity) => t.static_rows_designed(rows, capacity),
                None => t.static_rows(rows),
            })
            .collect();
        let strip_columns = strips
            .iter()
            .enumerate()
            .map(|(k, s)| match design.strips.get(k).copied().flatten() {
                Some(capacity) => s.static_rows_designed(assembly, rows, capacity),
                None => s.static_rows(assembly, rows),
            })
            .collect();
        let passive_columns = passive.iter().map(|p| p.static_rows(rows)).collect();
        (friction_joints, tie_columns, strip_columns, passive_columns)
    }
}

impl StaticProblem {
    /// Clarabel's standard form of `rows` with the objective `q` (minimised): the zero cone,
    /// the nonnegative cone, the second-order cones, in that order.
    pub(crate) fn assemble_with(
        rows: Rows,
        q: Vec<f64>,
        friction_joints: Vec<usize>,
        tie_columns: Vec<usize>,
    ) -> StaticProblem {
        let nvar = rows.columns();
        let equality_rows = rows.b_equality.len();
        let (mut r, mut c, mut v) = (Vec::new(), Vec::new(), Vec::new());
        for &(row, col, val) in &rows.equality {
            r.push(row);
            c.push(col);
            v.push(val);
        }
        let mut b = rows.b_equality;
        let mut row = equality_rows;
        for (entries, rhs) in rows.nonnegative.iter().chain(rows.cones.iter().flatten()) {
            for &(col, val) in entries {
                r.push(row);
                c.push(col);
                v.push(val);
            }
            b.push(*rhs);
            row += 1;
        }
        let inequality_rows = rows.nonnegative.len();
        let cone_rows = 3 * rows.cones.len();
        let a = csc_from_triplets(row, nvar, &r, &c, &v);
        let mut cones = vec![SupportedConeT::ZeroConeT(equality_rows)];
        if inequality_rows > 0 {
            // None with crushing cones, infinite friction, no tie and no cap.
            cones.push(SupportedConeT::NonnegativeConeT(inequality_rows));
        }
        cones.extend(
            rows.cones
                .iter()
                .map(|_| SupportedConeT::SecondOrderConeT(3)),
        );
        StaticProblem {
            p: CscMatrix::zeros((nvar, nvar)),
            q,
            a,
            b,
            cones,
            length_scale: rows.length_scale,
            force_scale: rows.force_scale,
            friction_joints,
            tie_columns,
            strip_columns: Vec::new(),
            passive_columns: Vec::new(),
            equality_rows,
            inequality_rows,
            cone_rows,
        }
    }

    pub fn variables(&self) -> usize {
        self.q.len()
    }
}

/// The same matrix as `CscMatrix::new_from_triplets` (entries sorted by row within each
/// column, repeated entries summed in insertion order, explicit zeros kept), built in
/// O(nnz): a counting sort by column, then an insertion sort of each column, whose entries
/// arrive nearly sorted (a joint touches two neighbouring blocks; the lambda column is
/// filled in row order). Clarabel's version sorts all triplets by (column, row) with a
/// comparison sort, which cost as much as 2-4% of a whole solve at 1000 voussoirs.
fn csc_from_triplets(
    m: usize,
    n: usize,
    rows: &[usize],
    cols: &[usize],
    vals: &[f64],
) -> CscMatrix<f64> {
    let mut colptr = vec![0usize; n + 1];
    for &c in cols {
        colptr[c + 1] += 1;
    }
    for c in 0..n {
        colptr[c + 1] += colptr[c];
    }
    let mut next = colptr.clone();
    let mut rowval = vec![0usize; vals.len()];
    let mut nzval = vec![0.0; vals.len()];
    for ((&r, &c), &v) in rows.iter().zip(cols).zip(vals) {
        let p = next[c];
        rowval[p] = r;
        nzval[p] = v;
        next[c] += 1;
    }
    // Sort each column by row (stable, so repeated entries keep their insertion order) and
    // sum repeated entries, compacting in place.
    let mut write = 0;
    for c in 0..n {
        let (start, end) = (colptr[c], colptr[c + 1]);
        for k in start + 1..end {
            let (r, v) = (rowval[k], nzval[k]);
            let mut i = k;
            while i > start && rowval[i - 1] > r {
                rowval[i] = rowval[i - 1];
                nzval[i] = nzval[i - 1];
                i -= 1;
            }
            rowval[i] = r;
            nzval[i] = v;
        }
        colptr[c] = write;
        for k in start..end {
            if k > start && rowval[k] == rowval[k - 1] {
                nzval[write - 1] += nzval[k];
            } else {
                rowval[write] = rowval[k];
                nzval[write] = nzval[k];
                write += 1;
            }
        }
    }
    colptr[n] = write;
    rowval.truncate(write);
    nzval.truncate(write);
    CscMatrix::new(m, n, colptr, rowval, nzval)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The O(nnz) builder gives exactly Clarabel's matrix, repeated and zero entries included.
    #[test]
    fn csc_matches_clarabel_triplets() {
        let rows = vec![3, 0, 2, 0, 1, 4, 2, 2, 0, 3];
        let cols = vec![0, 0, 1, 0, 2, 2, 1, 1, 3, 3];
        let vals = vec![1.0, 2.0, 0.0, -4.0, 5.0, 6.0, 7.5, 0.25, 9.0, -1.0];
        let ours = csc_from_triplets(5, 4, &rows, &cols, &vals);
        let theirs = CscMatrix::new_from_triplets(5, 4, rows, cols, vals);
        assert_eq!(ours.colptr, theirs.colptr);
        assert_eq!(ours.rowval, theirs.rowval);
        assert_eq!(ours.nzval, theirs.nzval);
        // Many random triplets with repeats, in no order (a simple LCG, reproducible).
        let mut state = 12345u64;
        let mut next = |k: u64| {
            state = state
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (state >> 33) % k
        };
        let (m, n, nnz) = (40, 30, 2000);
        let rows: Vec<usize> = (0..nnz).map(|_| next(m as u64) as usize).collect();
        let cols: Vec<usize> = (0..nnz).map(|_| next(n as u64) as usize).collect();
        let vals: Vec<f64> = (0..nnz).map(|_| next(1000) as f64 / 7.0 - 50.0).collect();
        let ours = csc_from_triplets(m, n, &rows, &cols, &vals);
        let theirs = CscMatrix::new_from_triplets(m, n, rows, cols, vals);
        assert_eq!(ours.colptr, theirs.colptr);
        assert_eq!(ours.rowval, theirs.rowval);
        assert_eq!(ours.nzval, theirs.nzval);
    }
}
