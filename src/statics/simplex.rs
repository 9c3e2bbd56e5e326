//! A bounded dual simplex for the static programs that are linear programs (issue 25): the
//! non-associative iteration's programs with fixed shear capacities on assemblies that are
//! not chains (docs/friction.md), solved again and again with only their bounds changed.
//!
//! **The program.** [`StaticProblem`] is Clarabel's `min q'x, A x + s = b, s in K` with the
//! zero cone (the equilibrium rows) and the nonnegative cone; a second-order cone (crushing)
//! makes it conic and [`BoundedLp::from_problem`] declines it. Every row with a single entry
//! becomes a bound on its column (`a x <= b` of the nonnegative cone: `c >= 0`, the fixed
//! shear capacities `-S <= V <= S`, a tie's, a strip's or a passive reaction's range, the
//! cap `lambda <= LAMBDA_CAP`; `a x = b` of the zero cone: a fixed column), so the program
//! becomes `min c'x, A x = b, l <= x <= u` with only the equilibrium rows left; a row of the
//! nonnegative cone with several entries (a designed tie, the phase-one relaxation) is
//! declined too. The fixed capacities are bounds: from one iteration to the next only `l`
//! and `u` change, so the last optimal basis stays **dual feasible** and the next solve
//! starts from it ([`DualSimplex::update`]; the dual simplex's warm start: a few pivots).
//!
//! **The method** is the bounded dual simplex as Koberstein (2005, *The dual simplex method,
//! techniques for a fast and stable implementation*, PhD thesis, Universität Paderborn,
//! chapter 3, Algorithm 4 without the bound-flipping ratio test) describes it, on the
//! columns `x` and one fixed slack `[0, 0]` per row (the first basis, `B = I`):
//!
//! - *pricing*: the basic variable of largest `delta_i^2 / w_i` leaves, `delta_i` its
//!   primal infeasibility and `w_i = ||e_i' B^-1||^2` its dual steepest-edge weight (Forrest &
//!   Goldfarb 1992), exact here (the rows of the explicit inverse);
//! - *ratio test*: Harris's two passes with a tolerance (Harris 1973; Koberstein §6.2.2):
//!   the largest pivot among the columns whose reduced cost reaches zero within the tolerance
//!   first; a nonbasic free column (reduced cost 0) enters as soon as its pivot is not 0;
//!   no column to enter is a Farkas certificate of the row (checked against the bounds:
//!   infeasible, or, when not certain, undecided);
//! - *basis*: the explicit inverse `B^-1` (dense storage, row-major), updated by the product
//!   form of each pivot over the nonzeros of the new pivot row (Bixby 1992, Maros 2003 §8;
//!   the inverse of a wall's basis is about a quarter full) and recomputed from scratch
//!   (Gauss-Jordan with partial pivoting) every `REFACTOR` pivots and whenever the
//!   residuals of the basic solution grow. Dense storage: the path is for programs up to
//!   [`MAX_ROWS`] rows (the 205-block wall has 615, the 3-bay arcade 942); larger ones stay
//!   with Clarabel. It still costs `O(m^2)`-ish per pivot, more than a sparse LU with
//!   Forrest-Tomlin updates would, and is why the path is slower than Clarabel on the wall
//!   and the arcade (docs/performance.md).
//!
//! **Degeneracy.** Masonry programs are highly degenerate, and the objective has one nonzero
//! (lambda): nearly every reduced cost is zero, and the ratio test would tie everywhere. The
//! costs of the nonbasic columns are perturbed at the start of each solve, away from zero in
//! the direction their bound allows (so the basis stays dual feasible; Koberstein §6.2.2.3,
//! random `xi (1 + |c_j|)` with `xi` in `[0.5, 1] 1e-7`). When the perturbed program is
//! optimal the perturbation is removed, the reduced costs recomputed, and any that is now of
//! the wrong sign is cleaned up by primal simplex pivots on the real costs (Koberstein
//! §6.2.2.3: "the primal simplex method is used to remove the remaining dual
//! infeasibilities"). The answer is returned only when, with the real costs, the basis is
//! primal feasible, dual feasible and the equilibrium residual small (all to `TOL`): an
//! optimal vertex of the real program. Anything else (the iterations running out, a
//! singular basis, a Farkas row the bounds do not confirm, a program unbounded above) is
//! [`LpOutcome::Undecided`], and the caller solves the program with Clarabel: never a wrong
//! number.
//!
//! **The nearest optimum.** A simplex answers a vertex of the optimal face; the
//! non-associative iteration reads the normal forces, and on a wall the vertex jumps between
//! iterations. [`BoundedLp::nearest`] builds, from a program, the program of its optima (the
//! multiplier fixed) nearest a centre in the 1-norm, without a new row: each column `x_k`
//! becomes `centre_k + p_k - q_k`, `p, q >= 0` (docs/friction.md).

use super::problem::StaticProblem;
use crate::sampling::SplitMix64;
use clarabel::solver::SupportedConeT;

/// The most equality rows the dense basis takes (an inverse of 2000 x 2000 is 32 MB).
pub const MAX_ROWS: usize = 2000;
/// Primal and dual feasibility tolerance (the program is dimensionless).
const TOL: f64 = 1e-9;
/// The smallest pivot the ratio tests accept.
const PIVOT_TOL: f64 = 1e-9;
/// Pivots between two recomputations of the inverse.
const REFACTOR: u32 = 200;
/// Size of the cost perturbation.
const PERTURBATION: f64 = 1e-7;

/// `min c'x, A x = b, l <= x <= u`: a linear static program in bounded form.
#[derive(Debug, Clone, PartialEq)]
pub struct BoundedLp {
    /// Rows (the equality rows left).
    pub m: usize,
    /// Columns (the program's unknowns).
    pub n: usize,
    /// `A` by columns: `colptr`, row indices, values.
    colptr: Vec<usize>,
    rowval: Vec<usize>,
    nzval: Vec<f64>,
    pub b: Vec<f64>,
    pub c: Vec<f64>,
    pub lower: Vec<f64>,
    pub upper: Vec<f64>,
    /// Per row of the original zero cone, its row here, or the column it fixed (and the
    /// coefficient), for reading the duals back.
    equality_map: Vec<RowFate>,
    /// Columns written as `centre + p - q` ([`BoundedLp::nearest`]): the column (it holds
    /// `p`) and the centre; `q` is column `n - split.len() + k` for the k-th.
    split: Vec<(usize, f64)>,
}

#[derive(Debug, Clone, Copy, PartialEq)]
enum RowFate {
    Row(usize),
    Bound { column: usize, coef: f64 },
}

/// Why a program does not go to the simplex.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum NotLinear {
    /// Second-order cones (crushing): a conic program.
    Conic,
    /// A row of the nonnegative cone with several entries, or none.
    GeneralRow,
    /// A row of the zero cone with no entry.
    EmptyRow,
    /// More equality rows than [`MAX_ROWS`].
    TooLarge,
}

impl BoundedLp {
    /// The bounded form of `p` (see the module docs), or why it has none.
    pub fn from_problem(p: &StaticProblem) -> Result<BoundedLp, NotLinear> {
        let mut eq_rows = 0;
        let mut nonneg_rows = 0;
        for cone in &p.cones {
            match cone {
                SupportedConeT::ZeroConeT(k) => eq_rows += k,
                SupportedConeT::NonnegativeConeT(k) => nonneg_rows += k,
                _ => return Err(NotLinear::Conic),
            }
        }
        // The zero cone comes first (StaticProblem::assemble_with).
        if !matches!(p.cones.first(), Some(SupportedConeT::ZeroConeT(_))) && eq_rows > 0 {
            return Err(NotLinear::GeneralRow);
        }
        let n = p.q.len();
        let total = eq_rows + nonneg_rows;
        let a = &p.a;
        // Entries per row.
        let mut count = vec![0usize; total];
        for &r in &a.rowval {
            count[r] += 1;
        }
        let mut lower = vec![f64::NEG_INFINITY; n];
        let mut upper = vec![f64::INFINITY; n];
        let mut equality_map = Vec::with_capacity(eq_rows);
        let mut kept = 0;
        for &k in &count[..eq_rows] {
            match k {
                0 => return Err(NotLinear::EmptyRow),
                1 => equality_map.push(RowFate::Bound {
                    column: usize::MAX,
                    coef: 0.0,
                }),
                _ => {
                    equality_map.push(RowFate::Row(kept));
                    kept += 1;
                }
            }
        }
        if kept > MAX_ROWS {
            return Err(NotLinear::TooLarge);
        }
        if count[eq_rows..].iter().any(|&k| k != 1) {
            return Err(NotLinear::GeneralRow);
        }
        let mut colptr = vec![0usize; n + 1];
        let mut rowval = Vec::new();
        let mut nzval = Vec::new();
        for j in 0..n {
            for k in a.colptr[j]..a.colptr[j + 1] {
                let (r, v) = (a.rowval[k], a.nzval[k]);
                let rhs = p.b[r];
                if r >= eq_rows {
                    // v x <= rhs.
                    if v > 0.0 {
                        upper[j] = upper[j].min(rhs / v);
                    } else if v < 0.0 {
                        lower[j] = lower[j].max(rhs / v);
                    } else if rhs < 0.0 {
                        // 0 <= rhs < 0: infeasible; leave it to Clarabel to say so.
                        return Err(NotLinear::GeneralRow);
                    }
                    continue;
                }
                match equality_map[r] {
                    RowFate::Row(i) => {
                        rowval.push(i);
                        nzval.push(v);
                    }
                    RowFate::Bound { .. } => {
                        if v == 0.0 {
                            return Err(NotLinear::EmptyRow);
                        }
                        let x = rhs / v;
                        lower[j] = lower[j].max(x);
                        upper[j] = upper[j].min(x);
                        equality_map[r] = RowFate::Bound { column: j, coef: v };
                    }
                }
            }
            colptr[j + 1] = rowval.len();
        }
        let b = (0..eq_rows)
            .filter_map(|r| match equality_map[r] {
                RowFate::Row(_) => Some(p.b[r]),
                RowFate::Bound { .. } => None,
            })
            .collect();
        Ok(BoundedLp {
            m: kept,
            n,
            colptr,
            rowval,
            nzval,
            b,
            c: p.q.clone(),
            lower,
            upper,
            equality_map,
            split: Vec::new(),
        })
    }

    /// The program of the optimal equilibria of `self` (a program maximising column 0) at
    /// the multiplier `lambda` (column 0 fixed there, a hair below the optimum), nearest
    /// `centre`: each column `k` of `columns` is written `x_k = centre_k + p_k - q_k` with
    /// `p, q >= 0` (so only bounds, the right-hand side and two columns change; no row is
    /// added) and the objective is `sum (primary_k + weight) p_k + (weight - primary_k)
    /// q_k`, that is `sum primary_k x_k + weight sum |x_k - centre_k|` up to a constant.
    /// With `primary = 0` it picks, among the optima, the equilibrium nearest the centre in
    /// the 1-norm; with `primary` the least-friction objective and a small `weight`, the
    /// least-friction equilibrium nearest it. Solving it again with another centre changes
    /// only `b` and the bounds: a warm start.
    pub fn nearest(
        &self,
        lambda: f64,
        columns: &[usize],
        centre: &[f64],
        primary: &[f64],
        weight: f64,
    ) -> BoundedLp {
        let mut lp = self.clone();
        lp.c = vec![0.0; self.n];
        lp.lower[0] = lambda;
        lp.upper[0] = lambda;
        for ((&k, &c), &w) in columns.iter().zip(centre).zip(primary) {
            let (l, u) = (self.lower[k], self.upper[k]);
            let c = c.max(l).min(u);
            // p = x - c >= 0 and q = c - x >= 0 within x's bounds.
            lp.lower[k] = (l - c).max(0.0);
            lp.upper[k] = u - c;
            lp.lower.push((c - u).max(0.0));
            lp.upper.push(c - l);
            lp.c[k] = w + weight;
            lp.c.push(weight - w);
            let (first, end) = (self.colptr[k], self.colptr[k + 1]);
            for t in first..end {
                let (r, v) = (self.rowval[t], self.nzval[t]);
                lp.rowval.push(r);
                lp.nzval.push(-v);
                lp.b[r] -= v * c;
            }
            lp.colptr.push(lp.rowval.len());
            lp.split.push((k, c));
        }
        lp.n = lp.c.len();
        lp
    }

    /// Whether `other` has the same matrix and costs (only `b` and the bounds may differ):
    /// then a basis of one is a dual feasible start for the other.
    fn same_matrix(&self, other: &BoundedLp) -> bool {
        self.m == other.m
            && self.n == other.n
            && self.colptr == other.colptr
            && self.rowval == other.rowval
            && self.nzval == other.nzval
            && self.c == other.c
            && self.equality_map == other.equality_map
    }

    /// Column `j` of `[A I]` (a slack's column is a unit vector) as (row, value) pairs.
    fn column(&self, j: usize) -> ColumnIter<'_> {
        if j < self.n {
            ColumnIter::Structural(
                self.rowval[self.colptr[j]..self.colptr[j + 1]]
                    .iter()
                    .zip(&self.nzval[self.colptr[j]..self.colptr[j + 1]]),
            )
        } else {
            ColumnIter::Slack(Some(j - self.n))
        }
    }

    /// `v . a_j` for column `j` of `[A I]`.
    fn dot(&self, v: &[f64], j: usize) -> f64 {
        self.column(j).map(|(r, a)| v[r] * a).sum()
    }
}

enum ColumnIter<'a> {
    Structural(std::iter::Zip<std::slice::Iter<'a, usize>, std::slice::Iter<'a, f64>>),
    Slack(Option<usize>),
}

impl Iterator for ColumnIter<'_> {
    type Item = (usize, f64);
    fn next(&mut self) -> Option<(usize, f64)> {
        match self {
            ColumnIter::Structural(it) => it.next().map(|(&r, &v)| (r, v)),
            ColumnIter::Slack(s) => s.take().map(|r| (r, 1.0)),
        }
    }
}

/// What a solve found.
#[derive(Debug, Clone, PartialEq)]
pub enum LpOutcome {
    /// An optimal vertex of the real program.
    Optimal(LpSolution),
    /// No `x` satisfies the rows and bounds (a Farkas row, checked against the bounds).
    Infeasible,
    /// The simplex did not decide (why): solve the program another way.
    Undecided(&'static str),
}

/// An optimal vertex, in the program's own columns and rows.
#[derive(Debug, Clone, PartialEq)]
pub struct LpSolution {
    /// The unknowns (the [`StaticProblem`]'s columns).
    pub x: Vec<f64>,
    /// The duals of the zero cone's rows with Clarabel's sign (`q + A' z = 0` on the
    /// columns off their bounds), in the [`StaticProblem`]'s row order.
    pub z: Vec<f64>,
    /// The objective of the program solved (`q'x`; for [`BoundedLp::nearest`] up to its
    /// constant).
    pub objective: f64,
    /// Pivots of this solve (dual and primal).
    pub pivots: u32,
}

#[derive(Debug, Clone, Copy, PartialEq)]
enum State {
    Basic,
    Lower,
    Upper,
    /// Nonbasic free column at 0.
    Zero,
}

/// The dual simplex with its basis and inverse, kept between solves.
#[derive(Debug, Clone)]
pub struct DualSimplex {
    lp: BoundedLp,
    /// Basic column of each row.
    basis: Vec<usize>,
    state: Vec<State>,
    /// Values of all n + m columns.
    x: Vec<f64>,
    /// Working costs (perturbed while solving), all n + m columns.
    cost: Vec<f64>,
    /// Reduced costs.
    d: Vec<f64>,
    /// The explicit inverse, row-major.
    binv: Vec<f64>,
    /// Dual steepest-edge weights `||e_i' B^-1||^2`.
    weight: Vec<f64>,
    /// Pivots since the inverse was computed.
    since_refactor: u32,
    /// The perturbation's random numbers (advanced at every solve).
    rng: SplitMix64,
}

impl DualSimplex {
    /// The simplex on `lp`, with the slack basis (`B = I`).
    pub fn new(lp: BoundedLp) -> DualSimplex {
        let (m, n) = (lp.m, lp.n);
        let mut binv = vec![0.0; m * m];
        for i in 0..m {
            binv[i * m + i] = 1.0;
        }
        let mut state = vec![State::Lower; n + m];
        for s in state.iter_mut().skip(n) {
            *s = State::Basic;
        }
        let mut cost = lp.c.clone();
        cost.resize(n + m, 0.0);
        let mut me = DualSimplex {
            basis: (n..n + m).collect(),
            state,
            x: vec![0.0; n + m],
            d: cost.clone(),
            cost,
            binv,
            weight: vec![1.0; m],
            since_refactor: 0,
            rng: SplitMix64(0x9e37_79b9_7f4a_7c15),
            lp,
        };
        // The slack basis: y = 0, d = c; every nonbasic column on the bound its cost asks for.
        for j in 0..n {
            me.state[j] = me.side(j, me.d[j], State::Lower);
        }
        me
    }

    /// Solve `lp` (the same matrix and costs as the last program, other bounds or
    /// right-hand side) from the last basis; a new program starts from the slack basis.
    pub fn update(&mut self, lp: BoundedLp) {
        if !self.lp.same_matrix(&lp) {
            *self = DualSimplex::new(lp);
            return;
        }
        self.lp.b = lp.b;
        self.lp.lower = lp.lower;
        self.lp.upper = lp.upper;
        self.lp.split = lp.split;
        // Nonbasic columns back on the bound their reduced cost asks for (a column whose
        // bounds were equal may now have two).
        for j in 0..self.lp.n {
            if self.state[j] != State::Basic {
                self.state[j] = self.side(j, self.d[j], self.state[j]);
            }
        }
    }

    /// The bound a nonbasic column `j` of reduced cost `d` sits on, `previous` when either
    /// will do.
    fn side(&self, j: usize, d: f64, previous: State) -> State {
        let (l, u) = self.bounds(j);
        match (l.is_finite(), u.is_finite()) {
            (false, false) => State::Zero,
            (true, false) => State::Lower,
            (false, true) => State::Upper,
            (true, true) => {
                if d > 0.0 {
                    State::Lower
                } else if d < 0.0 || previous == State::Upper {
                    State::Upper
                } else {
                    State::Lower
                }
            }
        }
    }

    fn bounds(&self, j: usize) -> (f64, f64) {
        if j < self.lp.n {
            (self.lp.lower[j], self.lp.upper[j])
        } else {
            (0.0, 0.0)
        }
    }

    /// The value of nonbasic column `j`.
    fn nonbasic_value(&self, j: usize) -> f64 {
        let (l, u) = self.bounds(j);
        match self.state[j] {
            State::Lower => l,
            State::Upper => u,
            _ => 0.0,
        }
    }

    /// `x_N` on their bounds and `x_B = B^-1 (b - N x_N)`.
    fn compute_primal(&mut self) {
        let m = self.lp.m;
        let mut r = self.lp.b.clone();
        for j in 0..self.lp.n + m {
            if self.state[j] == State::Basic {
                continue;
            }
            let v = self.nonbasic_value(j);
            self.x[j] = v;
            if v != 0.0 {
                for (i, a) in self.lp.column(j) {
                    r[i] -= a * v;
                }
            }
        }
        for i in 0..m {
            let row = &self.binv[i * m..(i + 1) * m];
            self.x[self.basis[i]] = row.iter().zip(&r).map(|(a, b)| a * b).sum();
        }
    }

    /// `y = B^-T c_B` and `d = c - A' y`.
    fn compute_dual(&mut self) -> Vec<f64> {
        let m = self.lp.m;
        let mut y = vec![0.0; m];
        for i in 0..m {
            let cb = self.cost[self.basis[i]];
            if cb != 0.0 {
                let row = &self.binv[i * m..(i + 1) * m];
                for (yk, a) in y.iter_mut().zip(row) {
                    *yk += cb * a;
                }
            }
        }
        for j in 0..self.lp.n + m {
            self.d[j] = if self.state[j] == State::Basic {
                0.0
            } else {
                self.cost[j] - self.lp.dot(&y, j)
            };
        }
        y
    }

    /// Recompute the inverse from the basis (Gauss-Jordan, partial pivoting); false when
    /// the basis is singular.
    fn refactor(&mut self) -> bool {
        let m = self.lp.m;
        // B, row-major, and the identity beside it.
        let mut b = vec![0.0; m * m];
        for (k, &j) in self.basis.iter().enumerate() {
            for (i, a) in self.lp.column(j) {
                b[i * m + k] = a;
            }
        }
        let mut inv = vec![0.0; m * m];
        for i in 0..m {
            inv[i * m + i] = 1.0;
        }
        for k in 0..m {
            let (mut p, mut best) = (k, 0.0);
            for i in k..m {
                let v = b[i * m + k].abs();
                if v > best {
                    best = v;
                    p = i;
                }
            }
            if best < 1e-11 {
                return false;
            }
            if p != k {
                for c in 0..m {
                    b.swap(k * m + c, p * m + c);
                    inv.swap(k * m + c, p * m + c);
                }
            }
            let piv = b[k * m + k];
            for c in k..m {
                b[k * m + c] /= piv;
            }
            for c in 0..m {
                inv[k * m + c] /= piv;
            }
            let (bk, ik) = (
                b[k * m..(k + 1) * m].to_vec(),
                inv[k * m..(k + 1) * m].to_vec(),
            );
            for i in 0..m {
                let f = b[i * m + k];
                if i == k || f == 0.0 {
                    continue;
                }
                for (t, s) in b[i * m + k..(i + 1) * m].iter_mut().zip(&bk[k..]) {
                    *t -= f * s;
                }
                for (t, s) in inv[i * m..(i + 1) * m].iter_mut().zip(&ik) {
                    *t -= f * s;
                }
            }
        }
        // The rows of B^-1 belong to the basis positions in column order of B: B^-1 B = I
        // means row k of inv pairs with column k (basis position k).
        self.binv = inv;
        for i in 0..m {
            self.weight[i] = self.binv[i * m..(i + 1) * m].iter().map(|v| v * v).sum();
        }
        self.since_refactor = 0;
        true
    }

    /// `B^-1 a_j`.
    fn ftran(&self, j: usize) -> Vec<f64> {
        let m = self.lp.m;
        let mut out = vec![0.0; m];
        for (k, a) in self.lp.column(j) {
            for (i, o) in out.iter_mut().enumerate() {
                *o += self.binv[i * m + k] * a;
            }
        }
        out
    }

    /// The pivot row `alpha_r = e_r' B^-1 [A I]` on the nonbasic columns (0 on the basic).
    fn pivot_row(&self, r: usize) -> Vec<f64> {
        let m = self.lp.m;
        let rho = &self.binv[r * m..(r + 1) * m];
        (0..self.lp.n + m)
            .map(|j| {
                if self.state[j] == State::Basic {
                    0.0
                } else {
                    self.lp.dot(rho, j)
                }
            })
            .collect()
    }

    /// Replace the basic column of row `r` by `q` (its column `alpha_q = B^-1 a_q`): the
    /// product-form update of the inverse and of the dual steepest-edge weights.
    fn pivot(&mut self, r: usize, q: usize, alpha_q: &[f64], leaving_state: State) {
        let m = self.lp.m;
        let p = self.basis[r];
        let piv = alpha_q[r];
        let row_r: Vec<f64> = self.binv[r * m..(r + 1) * m]
            .iter()
            .map(|v| v / piv)
            .collect();
        // The inverse's rows are sparse (a quarter full on a wall): update over the new pivot
        // row's nonzeros only, and each weight by `||a - f b||^2 = ||a||^2 - 2 f a.b +
        // f^2 ||b||^2` (recomputed exactly at every reinversion).
        let nz: Vec<(usize, f64)> = row_r
            .iter()
            .enumerate()
            .filter(|(_, v)| **v != 0.0)
            .map(|(k, &v)| (k, v))
            .collect();
        let norm_r: f64 = nz.iter().map(|(_, v)| v * v).sum();
        for (i, &f) in alpha_q.iter().enumerate() {
            if i == r || f == 0.0 {
                continue;
            }
            let row = &mut self.binv[i * m..(i + 1) * m];
            let mut dot = 0.0;
            for &(k, v) in &nz {
                dot += row[k] * v;
                row[k] -= f * v;
            }
            self.weight[i] = (self.weight[i] - 2.0 * f * dot + f * f * norm_r).max(1e-12);
        }
        self.weight[r] = norm_r;
        self.binv[r * m..(r + 1) * m].copy_from_slice(&row_r);
        self.basis[r] = q;
        self.state[q] = State::Basic;
        self.state[p] = leaving_state;
        self.d[q] = 0.0;
        self.since_refactor += 1;
    }

    /// The basic solution's largest equation residual `|A x - b|`.
    fn residual(&self) -> f64 {
        let mut r: Vec<f64> = self.lp.b.iter().map(|v| -v).collect();
        for j in 0..self.lp.n + self.lp.m {
            let v = self.x[j];
            if v != 0.0 {
                for (i, a) in self.lp.column(j) {
                    r[i] += a * v;
                }
            }
        }
        r.iter().fold(0.0_f64, |a, v| a.max(v.abs()))
    }

    /// A fresh inverse and basic solution (after drift, or before the final check).
    fn reinvert(&mut self) -> bool {
        if !self.refactor() {
            return false;
        }
        self.compute_primal();
        self.compute_dual();
        true
    }

    /// Perturb the costs of the nonbasic columns away from zero, on the side their bound
    /// allows (their reduced costs move the same way, so the basis stays dual feasible).
    fn perturb(&mut self) {
        for j in 0..self.lp.n {
            let (l, u) = self.bounds(j);
            let dir = match self.state[j] {
                State::Lower if l < u => 1.0,
                State::Upper if l < u => -1.0,
                _ => continue,
            };
            let e =
                dir * PERTURBATION * (0.5 + 0.5 * self.rng.uniform()) * (1.0 + self.lp.c[j].abs());
            self.cost[j] += e;
            self.d[j] += e;
        }
    }

    /// Solve the current program from the current basis.
    pub fn solve(&mut self) -> LpOutcome {
        let (m, n) = (self.lp.m, self.lp.n);
        if self.since_refactor >= REFACTOR && !self.refactor() {
            return LpOutcome::Undecided("singular basis");
        }
        self.cost = self.real_costs();
        self.compute_primal();
        self.compute_dual();
        // A basis that is not dual feasible (after a reinversion's round-off): fix the sides.
        for j in 0..n {
            if self.state[j] != State::Basic {
                self.state[j] = self.side(j, self.d[j], self.state[j]);
            }
        }
        self.compute_primal();
        self.perturb();
        let limit = 20 * (m + n) as u32 + 1000;
        let mut pivots = 0u32;
        let mut perturbed = true;
        let mut checked = false;
        loop {
            if pivots > limit {
                return LpOutcome::Undecided("iteration limit");
            }
            if self.since_refactor >= REFACTOR && !self.reinvert() {
                return LpOutcome::Undecided("singular basis");
            }
            match self.dual_pivot() {
                Step::Pivoted => {
                    pivots += 1;
                    continue;
                }
                Step::Infeasible => return LpOutcome::Infeasible,
                Step::Undecided(why) => return LpOutcome::Undecided(why),
                Step::Done => {}
            }
            // Primal feasible: remove the perturbation, clean up with primal pivots.
            if perturbed {
                self.cost = self.real_costs();
                self.compute_dual();
                perturbed = false;
            }
            match self.primal_cleanup(limit.saturating_sub(pivots)) {
                Ok(k) => pivots += k,
                Err(why) => return LpOutcome::Undecided(why),
            }
            // The final check, with the real costs, from the inverse (a fresh one when the
            // residuals show it has drifted).
            self.cost = self.real_costs();
            self.compute_primal();
            let y = self.compute_dual();
            if (self.residual() > 0.1 * TOL || self.dual_residual(&y) > 0.1 * TOL)
                && !self.reinvert()
            {
                return LpOutcome::Undecided("singular basis");
            }
            let primal_ok = self.primal_infeasibility() <= TOL;
            let dual_ok = self.dual_infeasibility() <= TOL;
            if primal_ok && dual_ok && self.residual() <= TOL {
                return LpOutcome::Optimal(self.solution(pivots));
            }
            if checked {
                return LpOutcome::Undecided("no clean optimum after reinversion");
            }
            checked = true;
        }
    }

    /// The real costs of all n + m columns.
    fn real_costs(&self) -> Vec<f64> {
        let mut c = self.lp.c.clone();
        c.resize(self.lp.n + self.lp.m, 0.0);
        c
    }

    /// The largest `|c_j - a_j . y|` over the basic columns (0 in exact arithmetic).
    fn dual_residual(&self, y: &[f64]) -> f64 {
        self.basis
            .iter()
            .map(|&j| (self.cost[j] - self.lp.dot(y, j)).abs())
            .fold(0.0, f64::max)
    }

    /// The largest bound violation of a basic column.
    fn primal_infeasibility(&self) -> f64 {
        self.basis
            .iter()
            .map(|&j| {
                let (l, u) = self.bounds(j);
                (l - self.x[j]).max(self.x[j] - u).max(0.0)
            })
            .fold(0.0, f64::max)
    }

    /// The largest reduced cost of the wrong sign for the bound its column sits on.
    fn dual_infeasibility(&self) -> f64 {
        (0..self.lp.n + self.lp.m)
            .map(|j| self.dual_violation(j))
            .fold(0.0, f64::max)
    }

    fn dual_violation(&self, j: usize) -> f64 {
        let (l, u) = self.bounds(j);
        if l == u {
            return 0.0;
        }
        let d = self.d[j];
        match self.state[j] {
            State::Basic => 0.0,
            State::Lower => (-d).max(0.0),
            State::Upper => d.max(0.0),
            State::Zero => d.abs(),
        }
    }

    /// One dual simplex pivot, or why there is none.
    fn dual_pivot(&mut self) -> Step {
        let m = self.lp.m;
        // Pricing: dual steepest edge.
        let mut r = usize::MAX;
        let mut best = 0.0;
        let mut below = false;
        for i in 0..m {
            let j = self.basis[i];
            let (l, u) = self.bounds(j);
            let (delta, lo) = if self.x[j] < l - TOL {
                (l - self.x[j], true)
            } else if self.x[j] > u + TOL {
                (self.x[j] - u, false)
            } else {
                continue;
            };
            let score = delta * delta / self.weight[i].max(1e-12);
            if score > best {
                best = score;
                r = i;
                below = lo;
            }
        }
        if r == usize::MAX {
            return Step::Done;
        }
        let alpha_r = self.pivot_row(r);
        // t >= 0 along s (the dual step theta = s t): s = -1 when the leaving column is below
        // its lower bound, +1 above its upper.
        let s = if below { -1.0 } else { 1.0 };
        // Harris pass 1: the largest step with every reduced cost feasible to the tolerance.
        let mut t_max = f64::INFINITY;
        let candidate = |j: usize, sa: f64| -> Option<f64> {
            let (l, u) = self.bounds(j);
            if l == u || sa.abs() < PIVOT_TOL {
                return None;
            }
            match self.state[j] {
                State::Lower if sa > 0.0 => Some(self.d[j].max(0.0)),
                State::Upper if sa < 0.0 => Some((-self.d[j]).max(0.0)),
                State::Zero => Some(0.0),
                _ => None,
            }
        };
        for (j, &a) in alpha_r.iter().enumerate() {
            if let Some(dj) = candidate(j, s * a) {
                t_max = t_max.min((dj + TOL) / a.abs());
            }
        }
        if t_max == f64::INFINITY {
            return self.farkas(r, below, &alpha_r);
        }
        // Pass 2: the largest pivot among the columns whose ratio is within t_max.
        let mut q = usize::MAX;
        let mut big = 0.0;
        for (j, &a) in alpha_r.iter().enumerate() {
            if let Some(dj) = candidate(j, s * a) {
                if dj / a.abs() <= t_max && a.abs() > big {
                    big = a.abs();
                    q = j;
                }
            }
        }
        if q == usize::MAX {
            return Step::Undecided("empty Harris pass");
        }
        let alpha_q = self.ftran(q);
        let piv = alpha_q[r];
        if (piv - alpha_r[q]).abs() > 1e-7 * (1.0 + piv.abs()) || piv.abs() < PIVOT_TOL {
            // The row and the column disagree: the inverse has drifted.
            if !self.reinvert() {
                return Step::Undecided("singular basis");
            }
            return Step::Pivoted;
        }
        // Harris may pick a reduced cost of the wrong sign within the tolerance: shift its
        // cost to make it 0 (the shift goes when the real costs come back).
        if self.dual_violation(q) > 0.0 {
            self.cost[q] -= self.d[q];
            self.d[q] = 0.0;
        }
        // Dual step: d_j -= theta alpha_rj, with theta = d_q / alpha_rq.
        let theta = self.d[q] / alpha_r[q];
        for (j, &a) in alpha_r.iter().enumerate() {
            if a != 0.0 && self.state[j] != State::Basic {
                self.d[j] -= theta * a;
            }
        }
        // Primal step: the leaving column onto its violated bound.
        let p = self.basis[r];
        let (l, u) = self.bounds(p);
        let target = if below { l } else { u };
        let delta = (self.x[p] - target) / piv;
        for (i, &a) in alpha_q.iter().enumerate() {
            if a != 0.0 {
                self.x[self.basis[i]] -= delta * a;
            }
        }
        self.x[q] += delta;
        self.x[p] = target;
        let leaving = if below { State::Lower } else { State::Upper };
        self.pivot(r, q, &alpha_q, leaving);
        self.d[p] = -theta;
        Step::Pivoted
    }

    /// No column may enter for row `r`: the row `x_p = beta - sum alpha_rj x_j` cannot
    /// reach its bound within the bounds of the nonbasic columns (a Farkas certificate), if
    /// the bounds confirm it; otherwise undecided.
    fn farkas(&self, r: usize, below: bool, alpha_r: &[f64]) -> Step {
        let p = self.basis[r];
        let (l, u) = self.bounds(p);
        // The most x_p can move toward its bound: each nonbasic column from its value to
        // the bound that helps.
        let mut reach = self.x[p];
        for (j, &a) in alpha_r.iter().enumerate() {
            if a == 0.0 || self.state[j] == State::Basic {
                continue;
            }
            let (lj, uj) = self.bounds(j);
            // dx_p = -a dx_j; toward l (up) when below, toward u (down) otherwise.
            let want_up = below;
            let dxj_positive = (want_up && a < 0.0) || (!want_up && a > 0.0);
            let room = if dxj_positive {
                uj - self.x[j]
            } else {
                self.x[j] - lj
            };
            if !room.is_finite() {
                return Step::Undecided("a Farkas row with an unbounded column");
            }
            let gain = room * a.abs();
            reach += if want_up { gain } else { -gain };
        }
        let short = if below { l - reach } else { reach - u };
        if short > 1e3 * TOL {
            Step::Infeasible
        } else {
            Step::Undecided("a Farkas row within the tolerance")
        }
    }

    /// Primal simplex pivots on the real costs until no reduced cost has the wrong sign
    /// (Dantzig's rule, Harris's ratio test); the number of pivots.
    fn primal_cleanup(&mut self, limit: u32) -> Result<u32, &'static str> {
        let m = self.lp.m;
        let mut pivots = 0;
        loop {
            let (mut q, mut worst) = (usize::MAX, TOL);
            for j in 0..self.lp.n + m {
                let v = self.dual_violation(j);
                if v > worst {
                    worst = v;
                    q = j;
                }
            }
            if q == usize::MAX {
                return Ok(pivots);
            }
            if pivots >= limit {
                return Err("iteration limit (primal cleanup)");
            }
            if self.since_refactor >= REFACTOR && !self.reinvert() {
                return Err("singular basis");
            }
            // Increase x_q when its reduced cost is negative.
            let dir = if self.d[q] < 0.0 { 1.0 } else { -1.0 };
            let alpha_q = self.ftran(q);
            // x_B(t) = x_B - dir t alpha_q. Harris pass 1.
            let (lq, uq) = self.bounds(q);
            let own = uq - lq;
            let room = |i: usize, tol: f64| -> Option<f64> {
                let a = dir * alpha_q[i];
                if a.abs() < PIVOT_TOL {
                    return None;
                }
                let j = self.basis[i];
                let (l, u) = self.bounds(j);
                if a > 0.0 {
                    l.is_finite().then(|| (self.x[j] - l + tol).max(0.0) / a)
                } else {
                    u.is_finite().then(|| (u - self.x[j] + tol).max(0.0) / -a)
                }
            };
            let mut t_max = f64::INFINITY;
            for i in 0..m {
                if let Some(t) = room(i, TOL) {
                    t_max = t_max.min(t);
                }
            }
            if own <= t_max {
                // A bound flip: x_q crosses to its other bound, no basis change.
                if !own.is_finite() {
                    return Err("unbounded ray in the primal cleanup");
                }
                for (i, &a) in alpha_q.iter().enumerate() {
                    self.x[self.basis[i]] -= dir * own * a;
                }
                self.x[q] += dir * own;
                self.state[q] = if dir > 0.0 {
                    State::Upper
                } else {
                    State::Lower
                };
                pivots += 1;
                continue;
            }
            let mut r = usize::MAX;
            let mut big = 0.0;
            for (i, a) in alpha_q.iter().enumerate() {
                if let Some(t) = room(i, 0.0) {
                    if t <= t_max && a.abs() > big {
                        big = a.abs();
                        r = i;
                    }
                }
            }
            if r == usize::MAX {
                return Err("empty Harris pass (primal cleanup)");
            }
            let a = dir * alpha_q[r];
            let p = self.basis[r];
            let (l, u) = self.bounds(p);
            let (target, leaving) = if a > 0.0 {
                (l, State::Lower)
            } else {
                (u, State::Upper)
            };
            let t = ((self.x[p] - target) / a).max(0.0);
            for (i, &ai) in alpha_q.iter().enumerate() {
                if ai != 0.0 {
                    self.x[self.basis[i]] -= dir * t * ai;
                }
            }
            self.x[q] += dir * t;
            self.x[p] = target;
            let alpha_r = self.pivot_row(r);
            let theta = self.d[q] / alpha_r[q];
            for (j, &ar) in alpha_r.iter().enumerate() {
                if ar != 0.0 && self.state[j] != State::Basic {
                    self.d[j] -= theta * ar;
                }
            }
            self.pivot(r, q, &alpha_q, leaving);
            self.d[p] = -theta;
            pivots += 1;
        }
    }

    /// The optimum in the [`StaticProblem`]'s columns and rows.
    fn solution(&mut self, pivots: u32) -> LpSolution {
        let y = self.compute_dual();
        let n0 = self.lp.n - self.lp.split.len();
        let mut x = self.x[..n0].to_vec();
        for (i, &(k, c)) in self.lp.split.iter().enumerate() {
            x[k] = c + self.x[k] - self.x[n0 + i];
        }
        let z = self
            .lp
            .equality_map
            .iter()
            .map(|fate| match *fate {
                RowFate::Row(i) => -y[i],
                // A fixed column's row: its dual is the column's reduced cost over the
                // coefficient.
                RowFate::Bound { column, coef } => -self.d[column] / coef,
            })
            .collect();
        let objective = self.lp.c.iter().zip(&self.x).map(|(c, v)| c * v).sum();
        LpSolution {
            x,
            z,
            objective,
            pivots,
        }
    }
}

enum Step {
    Pivoted,
    Done,
    Infeasible,
    Undecided(&'static str),
}

/// Solve `p` by the dual simplex from the slack basis (no warm start): the optimum, an
/// infeasible program, or undecided (then solve it with Clarabel); `Err` when it is not a
/// linear program the simplex takes.
pub fn solve(p: &StaticProblem) -> Result<LpOutcome, NotLinear> {
    let lp = BoundedLp::from_problem(p)?;
    Ok(DualSimplex::new(lp).solve())
}
