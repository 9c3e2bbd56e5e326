//! The static program of a chain in its redundants: a chain of blocks between two supports is
//! statically indeterminate to degree three, so given the force `(H, V)` and moment `M0` the
//! ground exerts on the first block, and `lambda`, the force through every joint follows from
//! running sums of the block loads (Heyman, *The Stone Skeleton*, 1995: the thrust line of an
//! arch is fixed by three quantities; Livesley, 1978, for the LP). The program has four
//! unknowns `x = [lambda, H, V, M0]` and, per joint, two no-tension rows (the moment of the
//! transmitted force about each end of the joint has the sign that keeps the resultant on the
//! joint) and, with finite friction, two Coulomb rows — instead of the full program's three
//! unknowns per joint and three equilibrium rows per block.
//!
//! Joint k carries the force `F_k = F_0 + sum_{i<k} (P_i + lambda S_i)` from block k - 1 to
//! block k, with moment `M_k = M_0 + sum_{i<k} (m(P_i) + lambda m(S_i))` about a reference
//! point (the structure's first joint midpoint, so moments stay well conditioned far from the
//! origin); `P_i`, `S_i` are block i's permanent and seismic (per unit lambda) loads from the
//! [`LoadCase`]. The moment about a point q is `M_q = M_k - (q - ref) x F_k`; for a resultant
//! at distance e from the joint midpoint along u, `M_q = (a - e) N` with `q = mid + a u`, so
//! the no-tension rows are `M_{p2} >= 0` and `-M_{p1} >= 0` (their sum is `N L >= 0`), and
//! Coulomb's `mu N -+ V >= 0`. The duals of the rows are the joints' relative motions: a
//! rotation about p2 (or p1) for a no-tension row, a dilatant slip for a friction row; summed
//! from the ground, they are the blocks' velocities in the collapse mechanism.
//!
//! **Tie rods** (issue 24) keep this structure: a tie's tension `T` (between its prestress
//! and its capacity) pulls its `from` block along `e` and its `to` block back, so it is one
//! more load on those blocks, and every joint past an anchored block carries `T` times that
//! pull in its running sum. Each tie adds one unknown `T_t` (over the force scale) and its two
//! bounds as rows; the active set then works in `4 + ties` unknowns, and returns among the
//! optimal equilibria the one whose ties carry least (a small weight on the tensions in the
//! objective, its optimum checked to be the largest multiplier's). **Bonded strips** need no
//! unknown without crushing: a strip's tension `0 <= S <= F` at a joint end only adds to that
//! end's contact force and to the contact's normal force (the joint transmits the same total
//! force), so `S = F` satisfies every row any `S` does, and a strip is `F` added to the
//! constants of its end's no-tension row and of the joint's Coulomb rows; the reported
//! tension is the least the joint's equilibrium asks for. With crushing (cones bound the
//! contact force from above) ties and strips are declined ([`declines`]).
//!
//! Lengths are divided by the structure's size and forces by the loads' scale, as in the full
//! program, and Clarabel solves it (a linear program over the nonnegative cone).

use super::{check_almost_solved, solve_conic, ModelSize, StaticResult, StaticSettings};
use crate::assembly::{Assembly, JointForce};
use crate::error::AnalysisError;
use crate::geometry::{cross, Vec2};
use crate::interaction::contact::fixed_capacity;
use crate::model::{LoadCase, Model};
use crate::outcome::{Status, LAMBDA_CAP};
use clarabel::algebra::CscMatrix;
use clarabel::solver::{SolverStatus, SupportedConeT};
use std::time::Instant;

mod fixed_shear;
mod working_set;

pub(super) use fixed_shear::FixedShearChain;

/// The joint force as an affine function of `x = [lambda, H, V, M0]` (SI units):
/// `F = F0 + base + lambda * per`, moment about the reference point likewise.
#[derive(Debug, Clone, Copy, Default)]
struct Affine {
    base: [f64; 3],
    per: [f64; 3],
}

/// The optimum found by the active-set method: the vertex, the multipliers of its real rows
/// `(row, multiplier)`, and the number of pivots.
struct ActiveSet {
    x: Vec<f64>,
    duals: Vec<(usize, f64)>,
    pivots: u32,
    /// The optimal basis (rows of the program, then the artificial ones) and the multipliers
    /// of its rows: a dual feasible start for the same program with other constants
    /// ([`ChainProgram::gradient_active_set`]'s warm start).
    warm: Warm,
}

/// A basis of the dual active set and its rows' multipliers, `y >= 0` with the objective's
/// gradient `-sum y_i a_i`: it stays dual feasible when only the rows' constants change, so
/// the dual simplex may start from it (the textbook warm start of the dual simplex).
#[derive(Debug, Clone, Default)]
struct Warm {
    basis: Vec<usize>,
    y: Vec<f64>,
}

/// Solve `G d = rhs` (`transpose`: `G^T d = rhs`) for the 4 x 4 matrix whose rows are
/// `rows`: a basis of the active-set methods. None when singular or not finite.
fn solve_basis(rows: [[f64; 4]; 4], transpose: bool, rhs: [f64; 4]) -> Option<[f64; 4]> {
    let mut a = nalgebra::Matrix4::<f64>::zeros();
    for (r, row) in rows.iter().enumerate() {
        for (c, &v) in row.iter().enumerate() {
            if transpose {
                a[(c, r)] = v;
            } else {
                a[(r, c)] = v;
            }
        }
    }
    let x = a.lu().solve(&nalgebra::Vector4::from(rhs))?;
    x.iter()
        .all(|v| v.is_finite())
        .then(|| [x[0], x[1], x[2], x[3]])
}

/// A basis of the active set in `n` unknowns, factored once per pivot for both of the
/// pivot's solves (`G x = rhs` and `G^T w = a_r`): the four redundants' 4 x 4 by
/// [`solve_basis`] (as the method always solved it), a larger one (the ties' tensions besides)
/// by an LU factorisation with partial pivoting, `P G = L U`, in buffers reused from pivot to
/// pivot.
struct Basis {
    n: usize,
    /// The rows of `G` (row after row), then its factors in place (`L` unit lower, `U` upper).
    lu: Vec<f64>,
    /// `perm[i]`: the row of `G` in row `i` of the factors.
    perm: Vec<usize>,
    /// Whether the factorisation found `G` regular.
    regular: bool,
}

impl Basis {
    fn new(n: usize) -> Basis {
        Basis {
            n,
            lu: vec![0.0; n * n],
            perm: (0..n).collect(),
            regular: false,
        }
    }

    /// The rows of `G` to fill (row after row); [`Basis::factor`] next.
    fn rows_mut(&mut self) -> &mut [f64] {
        &mut self.lu
    }

    /// Factor the rows filled in (nothing to do for the 4 x 4, solved afresh each time).
    fn factor(&mut self) {
        let n = self.n;
        self.regular = true;
        if n == 4 {
            return;
        }
        let a = &mut self.lu;
        for (i, p) in self.perm.iter_mut().enumerate() {
            *p = i;
        }
        for k in 0..n {
            let p = (k..n)
                .max_by(|&i, &j| a[i * n + k].abs().total_cmp(&a[j * n + k].abs()))
                .unwrap_or(k);
            let pivot = a[p * n + k];
            if pivot == 0.0 || !pivot.is_finite() {
                self.regular = false;
                return;
            }
            if p != k {
                for c in 0..n {
                    a.swap(p * n + c, k * n + c);
                }
                self.perm.swap(p, k);
            }
            for i in k + 1..n {
                let f = a[i * n + k] / pivot;
                a[i * n + k] = f;
                for c in k + 1..n {
                    a[i * n + c] -= f * a[k * n + c];
                }
            }
        }
    }

    /// `G x = rhs` (`transpose`: `G^T x = rhs`); None when singular or not finite.
    fn solve(&self, transpose: bool, rhs: &[f64]) -> Option<Vec<f64>> {
        let (n, a) = (self.n, &self.lu);
        if !self.regular {
            return None;
        }
        if n == 4 {
            let r = |i: usize| [a[4 * i], a[4 * i + 1], a[4 * i + 2], a[4 * i + 3]];
            let rhs = [rhs[0], rhs[1], rhs[2], rhs[3]];
            return solve_basis([r(0), r(1), r(2), r(3)], transpose, rhs).map(|x| x.to_vec());
        }
        let mut x = vec![0.0; n];
        if transpose {
            // G^T = U^T L^T P: U^T z = rhs, L^T v = z, x = P^T v.
            let mut z = rhs.to_vec();
            for i in 0..n {
                let s: f64 = (0..i).map(|k| a[k * n + i] * z[k]).sum();
                z[i] = (z[i] - s) / a[i * n + i];
            }
            for i in (0..n).rev() {
                let s: f64 = (i + 1..n).map(|k| a[k * n + i] * z[k]).sum();
                z[i] -= s;
            }
            for (i, &p) in self.perm.iter().enumerate() {
                x[p] = z[i];
            }
        } else {
            // L U x = P rhs.
            for i in 0..n {
                let s: f64 = (0..i).map(|k| a[i * n + k] * x[k]).sum();
                x[i] = rhs[self.perm[i]] - s;
            }
            for i in (0..n).rev() {
                let s: f64 = (i + 1..n).map(|k| a[i * n + k] * x[k]).sum();
                x[i] = (x[i] - s) / a[i * n + i];
            }
        }
        x.iter().all(|v| v.is_finite()).then_some(x)
    }
}

/// The weight of the ties' tensions in the objective of the active set on a tied chain
/// (`lambda - TIE_WEIGHT sum T'`, tensions over the force scale): small enough that it only
/// picks, among the equilibria at the largest multiplier, the one whose ties carry least
/// (the optimum is checked to be the largest multiplier's at the end).
const TIE_WEIGHT: f64 = 1e-9;

/// The direction `d` of a friction row `d . F + constant >= 0` (F the joint's force), for the
/// side `sv` (+1: `V <= limit`, -1: `V >= -limit`): Coulomb's `mu N - sv V` reads
/// `d = mu n - sv u`; a fixed capacity `S - sv V` reads `d = -sv u` (no normal part). The
/// same direction is the relative motion the row's dual stands for (slip with dilatancy
/// `mu`, or without).
fn friction_direction(mu: f64, n: Vec2, u: Vec2, sv: f64, fixed: bool) -> Vec2 {
    if fixed {
        -sv * u
    } else {
        mu * n - sv * u
    }
}

/// The dual simplex ratio test: of the basis rows with `w_k > 0`, the one whose multiplier
/// `y_k` reaches 0 first as the entering row's multiplier `t` grows (`y_k - t w_k`), and `t`.
fn ratio_test(y: &[f64], w: &[f64]) -> Option<(usize, f64)> {
    let mut leave: Option<(usize, f64)> = None;
    for k in 0..y.len().min(w.len()) {
        if w[k] > 1e-14 {
            let t = y[k] / w[k];
            if leave.is_none_or(|(_, best)| t < best) {
                leave = Some((k, t));
            }
        }
    }
    leave
}

/// The chain program as Clarabel takes it.
struct ConicForm {
    /// The number of unknowns (four redundants and one tension per tie).
    dim: usize,
    a: CscMatrix<f64>,
    b: Vec<f64>,
    cones: Vec<SupportedConeT<f64>>,
    q: Vec<f64>,
}

impl ConicForm {
    /// Clarabel's solution of the program under `settings`.
    fn solve(&self, settings: &StaticSettings) -> Result<super::RawSolution, AnalysisError> {
        solve_conic(
            &CscMatrix::zeros((self.dim, self.dim)),
            &self.q,
            &self.a,
            &self.b,
            &self.cones,
            settings,
        )
    }
}

/// How the active-set method ended.
enum Outcome {
    /// The optimum, at a vertex of four tight rows.
    Optimal(ActiveSet),
    /// No point satisfies the rows (with the cap): a violated row is a combination of tight
    /// rows with non-positive weights (Farkas' lemma), none of them the artificial box.
    Infeasible { pivots: u32 },
    /// The box binds, a basis is singular or the iterations ran out: the interior point decides.
    Failed,
}

impl Outcome {
    fn optimal(self) -> Option<ActiveSet> {
        match self {
            Outcome::Optimal(a) => Some(a),
            _ => None,
        }
    }
}

/// The reduced program of a chain, with what is needed to read its solution back.
#[derive(Clone)]
struct ChainProgram {
    /// Per joint, the running sums of the loads before it.
    sums: Vec<Affine>,
    reference: Vec2,
    length_scale: f64,
    force_scale: f64,
    /// Joints with friction rows, in row order (after the two no-tension rows of every joint).
    friction_joints: Vec<usize>,
    rows: usize,
    /// Every row as `g(x) = coef . x + c >= 0`, for the exact vertex step.
    dense: Vec<([f64; 4], f64)>,
    /// Per joint, `(r, kappa)` of the crushing cones: the no-tension rows are `g2 = c1 / r`
    /// and `g1 = c2 / r` with `r = ls / L` (c1, c2 the end forces over the force scale, as in
    /// the full program), and the cones are the full program's, `2 c kappa >= (c1 + c2)^2`
    /// with `kappa = fc d L / fs`. Empty for rigid joints (a linear program).
    kappa: Vec<(f64, f64)>,
    /// The number of tie rods, each an unknown after the four redundants (its tension over
    /// the force scale, `x[4 + t]`).
    ties: usize,
    /// Per row, the coefficients of the ties' tensions (`ties` per row, row after row; empty
    /// without ties).
    tie_coef: Vec<f64>,
    /// Per joint and tie (`ties` per joint), the force and the moment about the reference
    /// point a unit tension adds to the joint's force: the tie's pull on the blocks before
    /// the joint.
    tie_sums: Vec<[f64; 3]>,
    /// Per joint, the bonded strips' capacities at its ends p1 and p2 (N; empty without
    /// strips).
    strip_ends: Vec<[f64; 2]>,
    /// Whether the friction rows bound the shear by fixed capacities, `S_j -+ V >= 0`
    /// ([`ChainProgram::with_capacities`]), instead of Coulomb's `mu N -+ V >= 0`: their
    /// duals are then slips without opening.
    fixed_shear: bool,
}

impl ChainProgram {
    fn new(model: &Model, sign: f64, cap: Option<f64>) -> ChainProgram {
        Self::with_capacities(model, sign, cap, None)
    }

    /// The program with each friction row `mu N -+ V >= 0` replaced, when `capacity` is
    /// given, by a fixed shear capacity `S_j -+ V >= 0` (N, joint order; a capacity that is
    /// not a finite number >= 0 is read as 0, as the full program's
    /// `interaction::contact::ShearLimit::Fixed` reads it): the same half-planes in the four
    /// unknowns, with a constant right-hand side. Strips are left out of the fixed rows'
    /// constants (their tension adds to the normal force, which these rows no longer read).
    fn with_capacities(
        model: &Model,
        sign: f64,
        cap: Option<f64>,
        capacity: Option<&[f64]>,
    ) -> ChainProgram {
        let (assembly, loads, strength) = (&model.assembly, &model.loads, model.strength);
        let nj = assembly.joints.len();
        let ls = assembly.size();
        let fs = loads.force_scale();
        let reference = assembly.joints[0].midpoint();
        // Running sums of the block loads (force and moment about the reference).
        let mut sums = Vec::with_capacity(nj);
        let mut acc = Affine::default();
        for k in 0..nj {
            sums.push(acc);
            if k < assembly.blocks.len() {
                let g = loads.reference(k);
                let p = loads.permanent(k).moved(g, reference);
                let s = loads.variable(k, sign).moved(g, reference);
                for (c, v) in [p.force.x, p.force.y, p.moment].into_iter().enumerate() {
                    acc.base[c] += v;
                }
                for (c, v) in [s.force.x, s.force.y, s.moment].into_iter().enumerate() {
                    acc.per[c] += v;
                }
            }
        }
        // A tie's pull on the blocks before a joint (per unit tension): `+e` at its `from`
        // anchor, `-e` at its `to` anchor, each once the joint lies past the anchored block
        // (a ground anchor pulls on no block).
        let nt = model.ties.len();
        let mut tie_sums = vec![[0.0; 3]; nj * nt];
        for (t, tie) in model.ties.iter().enumerate() {
            let e = tie.direction();
            for (anchor, s) in [(tie.from, 1.0), (tie.to, -1.0)] {
                let Some(b) = anchor.block else { continue };
                let m = s * cross(anchor.point - reference, e);
                for k in b + 1..nj {
                    let c = &mut tie_sums[k * nt + t];
                    c[0] += s * e.x;
                    c[1] += s * e.y;
                    c[2] += m;
                }
            }
        }
        // A strip's tension at a joint end, `0 <= S <= F`, adds to that end's contact force
        // and to the contact's normal force (Coulomb's rows) and to nothing else (it pulls the
        // joint's two sides together, so the force the joint transmits is unchanged): without
        // crushing, `S = F` satisfies every row that any `S` does, so a strip is its
        // capacity added to those rows' constants ([`declines`] keeps strips with crushing,
        // whose cones bound the contact force from above, in the full program).
        let mut strip_ends = Vec::new();
        if !model.strips.is_empty() {
            strip_ends = vec![[0.0; 2]; nj];
            for st in &model.strips {
                let end = match st.end {
                    crate::assembly::JointEnd::P1 => 0,
                    crate::assembly::JointEnd::P2 => 1,
                };
                strip_ends[st.joint][end] += st.capacity;
            }
        }
        // Rows `g(x) = coef . x + c >= 0` (Clarabel's sparse form is built from them only
        // when the interior point runs: the active-set method reads them directly), with the
        // ties' coefficients in `tie_coef`.
        let mut dense = Vec::with_capacity(2 * nj);
        let mut tie_coef = Vec::with_capacity(2 * nj * nt);
        let push_row = |coef: [f64; 4], c: f64, dense: &mut Vec<([f64; 4], f64)>| {
            dense.push((coef, c));
        };
        // Dimensionless: x = [lambda, H / fs, V / fs, M0 / (fs ls), T_t / fs...].
        let moment_row = |k: usize, q: Vec2, sgn: f64, tie_coef: &mut Vec<f64>| {
            let d = (q - reference) / ls;
            let s = &sums[k];
            // M_q / (fs ls) = M0' - d.x V' + d.y H' + (base_m - d.x base_y + d.y base_x)/(fs ls)
            //                 + lambda (per_m - d.x per_y + d.y per_x)/(fs ls)
            //                 + sum_t T_t' (m_t / ls - d.x fy_t + d.y fx_t).
            let base = (s.base[2] / ls - d.x * s.base[1] + d.y * s.base[0]) / fs;
            let per = (s.per[2] / ls - d.x * s.per[1] + d.y * s.per[0]) / fs;
            for c in &tie_sums[k * nt..(k + 1) * nt] {
                tie_coef.push(sgn * (c[2] / ls - d.x * c[1] + d.y * c[0]));
            }
            ([sgn * per, sgn * d.y, -sgn * d.x, sgn], sgn * base)
        };
        for (k, jt) in assembly.joints.iter().enumerate() {
            // Row 2k is `c1 L / (fs ls)` (the contact force at p1), row 2k + 1 is c2's.
            let shift = |c: f64, end: usize| match strip_ends.get(k) {
                Some(f) => c + f[end] * jt.length() / (fs * ls),
                None => c,
            };
            let (c2, k2) = moment_row(k, jt.p2, 1.0, &mut tie_coef);
            push_row(c2, shift(k2, 0), &mut dense);
            let (c1, k1) = moment_row(k, jt.p1, -1.0, &mut tie_coef);
            push_row(c1, shift(k1, 1), &mut dense);
        }
        let mut friction_joints = Vec::new();
        for (k, jt) in assembly.joints.iter().enumerate() {
            if !jt.friction.is_finite() {
                continue;
            }
            let (n, u, mu) = (jt.normal(), jt.tangent(), jt.friction);
            let s = &sums[k];
            let shift = |c: f64| match strip_ends.get(k) {
                Some(f) => c + mu * (f[0] + f[1]) / fs,
                None => c,
            };
            for sv in [1.0, -1.0] {
                // mu N - sv V with N = F.n, V = F.u: the direction d = mu n - sv u; with a
                // fixed capacity, S - sv V: d = -sv u and the constant S.
                let d = friction_direction(mu, n, u, sv, capacity.is_some());
                let base = (d.x * s.base[0] + d.y * s.base[1]) / fs;
                let per = (d.x * s.per[0] + d.y * s.per[1]) / fs;
                for c in &tie_sums[k * nt..(k + 1) * nt] {
                    tie_coef.push(d.x * c[0] + d.y * c[1]);
                }
                let constant = match capacity {
                    Some(cap) => base + fixed_capacity(cap, k) / fs,
                    None => shift(base),
                };
                push_row([per, d.x, d.y, 0.0], constant, &mut dense);
            }
            friction_joints.push(k);
        }
        // Each tie's bounds: `C / fs - T' >= 0`, then `T' - P / fs >= 0`.
        for (t, tie) in model.ties.iter().enumerate() {
            for (sign, c) in [(-1.0, tie.capacity / fs), (1.0, -tie.prestress / fs)] {
                tie_coef.extend((0..nt).map(|i| if i == t { sign } else { 0.0 }));
                push_row([0.0; 4], c, &mut dense);
            }
        }
        if let Some(cap) = cap {
            // lambda <= cap.
            tie_coef.extend(std::iter::repeat_n(0.0, nt));
            push_row([-1.0, 0.0, 0.0, 0.0], cap, &mut dense);
        }
        let m = dense.len();
        let kappa = if strength.is_finite() {
            let capacity = strength.line_capacity();
            assembly
                .joints
                .iter()
                .map(|jt| (ls / jt.length(), capacity * jt.length() / fs))
                .collect()
        } else {
            Vec::new()
        };
        ChainProgram {
            sums,
            reference,
            length_scale: ls,
            force_scale: fs,
            friction_joints,
            rows: m,
            dense,
            kappa,
            ties: nt,
            tie_coef,
            tie_sums,
            strip_ends,
            fixed_shear: capacity.is_some(),
        }
    }

    /// Clarabel's form of the program: minimise `-lambda` subject to `A x + s = b`, `s >= 0`,
    /// with each row `g(x) = coef . x + c >= 0` stored as `-coef . x + s = c`. Built column by
    /// column (four columns), so no sort.
    /// With finite strength, the crushing cones follow the linear rows, two per joint (of
    /// `c1 = r g2` and `c2 = r g1`), each as in the full program
    /// `s = [c + 1, c - 1, sqrt2 (c1 + c2) / sqrt(kappa)]` in `SecondOrderConeT(3)`.
    /// The no-tension rows follow from the cones and are then left out (as in the full
    /// program).
    fn conic(&self) -> ConicForm {
        let linear: Vec<usize> = (self.no_tension_rows_implied()..self.dense.len()).collect();
        let crush: Vec<usize> = (0..self.kappa.len()).collect();
        self.conic_of(&linear, &crush)
    }

    /// Clarabel's form of a program made of some of the rows: the linear rows `linear`
    /// (indices into `dense`), then the two crushing cones of each joint in `crush` (which
    /// imply that joint's no-tension rows, so `linear` should not repeat them). With every
    /// row, [`Self::conic`]; with fewer, a relaxation ([`working_set`]).
    fn conic_of(&self, linear: &[usize], crush: &[usize]) -> ConicForm {
        let mut rows: Vec<([f64; 4], f64)> = linear.iter().map(|&i| self.dense[i]).collect();
        let lin = rows.len();
        let scaled = |(coef, c): ([f64; 4], f64), f: f64| (coef.map(|v| f * v), f * c);
        for &k in crush {
            let (r, kappa) = self.kappa[k];
            let (g2, g1) = (self.dense[2 * k], self.dense[2 * k + 1]);
            let w = std::f64::consts::SQRT_2 * r / kappa.sqrt();
            let mut sum = ([0.0; 4], w * (g1.1 + g2.1));
            for c in 0..4 {
                sum.0[c] = w * (g1.0[c] + g2.0[c]);
            }
            for g in [g2, g1] {
                let (coef, c) = scaled(g, r);
                rows.push((coef, c + 1.0));
                rows.push((coef, c - 1.0));
                rows.push(sum);
            }
        }
        let m = rows.len();
        let nt = self.ties;
        let mut colptr = Vec::with_capacity(5 + nt);
        let mut rowval = Vec::with_capacity(4 * m);
        let mut nzval = Vec::with_capacity(4 * m);
        colptr.push(0);
        for col in 0..4 {
            for (r, (coef, _)) in rows.iter().enumerate() {
                if coef[col] != 0.0 {
                    rowval.push(r);
                    nzval.push(-coef[col]);
                }
            }
            colptr.push(rowval.len());
        }
        // The ties' columns: linear rows only (ties with crushing go to the full program).
        for t in 0..nt {
            for (r, &i) in linear.iter().enumerate() {
                let v = self.tie_coef[i * nt + t];
                if v != 0.0 {
                    rowval.push(r);
                    nzval.push(-v);
                }
            }
            colptr.push(rowval.len());
        }
        let mut q = vec![0.0; 4 + nt];
        q[0] = -1.0;
        let mut cones = Vec::new();
        if lin > 0 {
            cones.push(SupportedConeT::NonnegativeConeT(lin));
        }
        cones.extend((0..2 * crush.len()).map(|_| SupportedConeT::SecondOrderConeT(3)));
        ConicForm {
            dim: 4 + nt,
            a: CscMatrix::new(m, 4 + nt, colptr, rowval, nzval),
            b: rows.iter().map(|&(_, c)| c).collect(),
            cones,
            q,
        }
    }

    /// Value of row `i` at `x`, and the sum of the magnitudes of its terms (its scale).
    fn row_value(&self, i: usize, x: &[f64]) -> (f64, f64) {
        self.row_value_split(i, &[x[0], x[1], x[2], x[3]], &x[4..])
    }

    /// [`Self::row_value`] with `x` split into the redundants `x4` and the tensions `xt`
    /// (split once by the active set's scan of every row).
    #[inline(always)]
    fn row_value_split(&self, i: usize, x4: &[f64; 4], xt: &[f64]) -> (f64, f64) {
        let (coef, c) = &self.dense[i];
        let mut g: f64 = coef.iter().zip(x4).map(|(a, b)| a * b).sum::<f64>();
        let mut size: f64 = coef.iter().zip(x4).map(|(a, b)| (a * b).abs()).sum::<f64>();
        let nt = self.ties;
        if nt > 0 {
            for (a, b) in self.tie_coef[i * nt..(i + 1) * nt].iter().zip(xt) {
                g += a * b;
                size += (a * b).abs();
            }
        }
        (g + c, size + c.abs())
    }

    /// The exact vertex of the optimum near the interior-point solution `x`. Rows come in
    /// families along the chain (the p2 rows, the p1 rows, each friction side); on a long
    /// chain neighbouring rows are nearly parallel and nearly active together, so the
    /// candidates are the rows whose slack is a local minimum along their family, with their
    /// neighbours. Every choice of four candidates whose 4 x 4 system is regular gives a
    /// vertex; taken in decreasing lambda, the first that satisfies every row to round-off is
    /// the optimum (no feasible vertex has a larger lambda). None when no candidate vertex is
    /// feasible (then the interior-point solution stands).
    fn vertex(&self, x: &[f64], tolerance: f64) -> Option<Vec<f64>> {
        let nj = self.sums.len();
        let nf = self.friction_joints.len();
        let slack: Vec<f64> = (0..self.dense.len())
            .map(|i| {
                let (g, size) = self.row_value(i, x);
                g / size.max(1e-300)
            })
            .collect();
        // Families `(first row, length)`, rows two apart: the p2 rows (2k), the p1 rows
        // (2k + 1) over joints k, and the two sides of the friction rows (2 nj + 2f + side).
        let families = [(0, nj), (1, nj), (2 * nj, nf), (2 * nj + 1, nf)];
        let mut minima: Vec<(f64, usize, usize)> = Vec::new();
        for (family, &(start, len)) in families.iter().enumerate() {
            let row = |k: usize| start + 2 * k;
            for k in 0..len {
                let here = slack[row(k)];
                let left = if k > 0 {
                    slack[row(k - 1)]
                } else {
                    f64::INFINITY
                };
                let right = if k + 1 < len {
                    slack[row(k + 1)]
                } else {
                    f64::INFINITY
                };
                if here <= left && here <= right {
                    minima.push((here, family, k));
                }
            }
        }
        minima.sort_by(|a, b| a.0.total_cmp(&b.0));
        // The smallest local minima and their neighbours in the same family.
        let mut candidates: Vec<usize> = Vec::new();
        for &(_, family, k) in minima.iter().take(6) {
            let (start, len) = families[family];
            for kk in k.saturating_sub(1)..(k + 2).min(len) {
                let row = start + 2 * kk;
                if !candidates.contains(&row) {
                    candidates.push(row);
                }
            }
        }
        if self.dense.len() > 2 * nj + 2 * nf {
            // The lambda cap row.
            candidates.push(self.dense.len() - 1);
        }
        let c = candidates.len();
        let mut vertices: Vec<Vec<f64>> = Vec::new();
        for i in 0..c {
            for j in i + 1..c {
                for k in j + 1..c {
                    for l in k + 1..c {
                        let rows = [candidates[i], candidates[j], candidates[k], candidates[l]];
                        let mut m = nalgebra::Matrix4::<f64>::zeros();
                        let mut rhs = nalgebra::Vector4::<f64>::zeros();
                        for (r, &row) in rows.iter().enumerate() {
                            let (coef, cst) = self.dense[row];
                            for (col, v) in coef.into_iter().enumerate() {
                                m[(r, col)] = v;
                            }
                            rhs[r] = -cst;
                        }
                        let lu = m.lu();
                        if lu.determinant().abs() < 1e-14 {
                            continue;
                        }
                        if let Some(v) = lu.solve(&rhs) {
                            if v.iter().all(|x| x.is_finite()) {
                                vertices.push(v.iter().copied().collect());
                            }
                        }
                    }
                }
            }
        }
        vertices.sort_by(|a, b| b[0].total_cmp(&a[0]));
        let tol = 1e-12;
        vertices.into_iter().find(|v| {
            // A sanity check only: the vertex lies where the interior-point solution, accurate
            // to about the solver's tolerance, said it would.
            (v[0] - x[0]).abs() <= (1e-6_f64).max(100.0 * tolerance) * x[0].abs().max(1e-3)
                && (0..self.dense.len()).all(|i| {
                    let (g, size) = self.row_value(i, v);
                    g >= -tol * size.max(1e-300)
                })
        })
    }

    /// The optimum by a dual active-set (dual simplex) method on the four unknowns (and one
    /// per tie, whose rows the basis then counts too): a basis of four tight rows whose multipliers are non-negative (so no mechanism of the basis can
    /// raise lambda) is kept while the most violated row enters and the row the ratio test
    /// picks leaves. It starts from an artificial box (`lambda <= LAMBDA_CAP`, the redundants
    /// bounded far beyond any equilibrium), so the first basis is dual feasible; every
    /// iteration solves one 4 x 4 system and scans the rows once. At the end the vertex
    /// satisfies every row (to round-off) and its multipliers are non-negative: by LP duality
    /// it is the optimum, the vertex of the four active rows. Returns the vertex and the
    /// multipliers of its real rows ([`Outcome::Optimal`]), a proof that no point satisfies the
    /// rows ([`Outcome::Infeasible`]), or [`Outcome::Failed`] (the box binds, a basis is
    /// singular, or the iterations run out): the interior-point solve then decides.
    ///
    /// `objective` = +1 maximises lambda; -1 minimises it (the least multiplier equilibrium
    /// allows, whose sign says whether the structure stands at lambda = 0). `cap` bounds
    /// `objective * lambda` from above (`LAMBDA_CAP` for an analysis; 0 for the stand test,
    /// which then asks whether lambda = 0 is reachable from below).
    fn active_set(&self, objective: f64, cap: f64) -> Outcome {
        // The ties' tensions are not unique at the optimum when a tie neither yields nor
        // governs: the least are sought (weighted), and the largest multiplier alone when the
        // weighted optimum is not its.
        if objective > 0.0 && self.ties > 0 {
            if let found @ (Outcome::Optimal(_) | Outcome::Infeasible { .. }) =
                self.weighted_active_set(objective, cap, TIE_WEIGHT)
            {
                return found;
            }
        }
        self.weighted_active_set(objective, cap, 0.0)
    }

    /// [`Self::active_set`] maximising `objective lambda - weight sum T'` (the ties'
    /// tensions over the force scale), in `4 + ties` unknowns; with a weight, the optimum is
    /// returned only when it is also the largest `objective lambda` (its basis's multipliers
    /// for that objective alone are non-negative), [`Outcome::Failed`] otherwise.
    fn weighted_active_set(&self, objective: f64, cap: f64, weight: f64) -> Outcome {
        self.gradient_active_set(objective, cap, weight, [0.0; 3], None)
    }

    /// [`Self::weighted_active_set`] maximising
    /// `objective lambda + gradient . (H', V', M0') - weight sum T'`: the first basis takes, for each redundant, the artificial bound the
    /// gradient pushes against (multiplier `|gradient|`), so it is dual feasible for any
    /// gradient. The least-friction equilibrium of the non-associative iteration
    /// ([`FixedShearChain`]) minimises `sum mu N`, linear in the redundants, this way.
    /// `warm`, the optimal basis of the same program (same rows and objective) with other
    /// constants, starts the method from that basis instead: still dual feasible, it needs
    /// only the pivots the new constants call for.
    fn gradient_active_set(
        &self,
        objective: f64,
        cap: f64,
        weight: f64,
        gradient: [f64; 3],
        warm: Option<&Warm>,
    ) -> Outcome {
        const BOX: f64 = 1e6;
        const MAX_ITER: usize = 500;
        let m = self.dense.len();
        let nt = self.ties;
        let n = 4 + nt;
        // Rows: the program's, then the box: objective * lambda <= cap, +-H, +-V, +-M0 <= BOX.
        // Row `i`'s coefficients into `out`; returns its constant.
        let row = |i: usize, out: &mut [f64]| -> f64 {
            out.fill(0.0);
            if i < m {
                let (a, c) = self.dense[i];
                out[..4].copy_from_slice(&a);
                out[4..].copy_from_slice(&self.tie_coef[i * nt..(i + 1) * nt]);
                return c;
            }
            let k = i - m;
            if k == 0 {
                out[0] = -objective;
                return cap;
            }
            let (col, s) = (k.div_ceil(2), if k % 2 == 1 { -1.0 } else { 1.0 });
            out[col] = s;
            BOX
        };
        // The basis rows' coefficients into `g` (factored), and minus their constants.
        let mut g = Basis::new(n);
        let mut rhs = vec![0.0; n];
        let mut matrix = |basis: &[usize], g: &mut Basis| {
            for (r, &i) in basis.iter().enumerate() {
                rhs[r] = -row(i, &mut g.rows_mut()[r * n..(r + 1) * n]);
            }
            g.factor();
            rhs.clone()
        };
        // The cap and the upper bounds of H, V, M0: multipliers (1, 0, 0, 0); each tie at its
        // prestress (`T' - P' >= 0`), multiplier `weight`: the objective is
        // `-sum y_i a_i` over them.
        let first_tie = 2 * self.sums.len() + 2 * self.friction_joints.len();
        // Box row `m + 2c - 1` bounds redundant c from above, `m + 2c` from below.
        let side = |c: usize| {
            if gradient[c - 1] >= 0.0 {
                2 * c - 1
            } else {
                2 * c
            }
        };
        let mut basis = vec![m, m + side(1), m + side(2), m + side(3)];
        basis.extend((0..nt).map(|t| first_tie + 2 * t + 1));
        let warm = warm.filter(|w| w.basis.len() == n && w.y.len() == n);
        if let Some(w) = warm {
            basis.clone_from(&w.basis);
        }
        let mut in_basis = vec![false; m];
        for &i in &basis {
            if i < m {
                in_basis[i] = true;
            }
        }
        let mut y = vec![0.0; n];
        y[0] = 1.0;
        for (yc, g) in y[1..4].iter_mut().zip(gradient) {
            *yc = g.abs();
        }
        y[4..].fill(weight);
        if let Some(w) = warm {
            y.clone_from(&w.y);
        }
        let mut a_r = vec![0.0; n];
        for pivots in 0..MAX_ITER {
            let rhs = matrix(&basis, &mut g);
            let Some(x) = g.solve(false, &rhs) else {
                return Outcome::Failed;
            };
            // The most violated row, relative to the size of its terms.
            let mut worst: Option<(usize, f64)> = None;
            let (x4, xt) = ([x[0], x[1], x[2], x[3]], &x[4..]);
            let mut consider = |i: usize, g: f64, size: f64| {
                let v = g / size.max(1e-300);
                if v < -1e-13 && worst.is_none_or(|(_, w)| v < w) {
                    worst = Some((i, v));
                }
            };
            if nt == 0 {
                // The redundants alone: the hot loop of every untied chain.
                for (i, (a, c)) in self.dense.iter().enumerate() {
                    if in_basis[i] {
                        continue;
                    }
                    let g: f64 = a.iter().zip(&x4).map(|(p, q)| p * q).sum::<f64>() + c;
                    let size: f64 =
                        a.iter().zip(&x4).map(|(p, q)| (p * q).abs()).sum::<f64>() + c.abs();
                    consider(i, g, size);
                }
            } else {
                for (i, _) in in_basis.iter().enumerate().filter(|(_, &b)| !b) {
                    let (g, size) = self.row_value_split(i, &x4, xt);
                    consider(i, g, size);
                }
            }
            let Some((r, _)) = worst else {
                // Primal feasible with non-negative multipliers: optimal. With a weight on
                // the tensions, the multipliers for `objective lambda` alone on this basis
                // must be non-negative too (then it is that objective's optimum as well).
                if weight > 0.0 {
                    let mut pure = vec![0.0; n];
                    pure[0] = -objective;
                    match g.solve(true, &pure) {
                        Some(p) if p.iter().all(|&v| v >= -1e-12) => y = p,
                        _ => return Outcome::Failed,
                    }
                }
                // The box must not bind (but the cap may: then lambda is capped, i.e. no
                // collapse).
                let binding_box = basis.iter().zip(&y).any(|(&i, &yi)| i > m && yi > 1e-12);
                if binding_box {
                    return Outcome::Failed;
                }
                let duals = basis
                    .iter()
                    .zip(&y)
                    .filter(|(&i, _)| i < m)
                    .map(|(&i, &yi)| (i, f64::max(yi, 0.0)))
                    .collect();
                return Outcome::Optimal(ActiveSet {
                    x,
                    duals,
                    pivots: pivots as u32,
                    warm: Warm { basis, y },
                });
            };
            // Ratio test: a_r = sum w_i a_i over the basis; y'_i = y_i - t w_i, y'_r = t.
            row(r, &mut a_r);
            let Some(w) = g.solve(true, &a_r) else {
                return Outcome::Failed;
            };
            let leave = ratio_test(&y, &w);
            // No row can leave (every w_i <= 0): row r is violated at x, and since a_r =
            // sum w_i a_i and the basis rows are tight at x, any x' has g_r(x') = g_r(x) +
            // sum w_i g_i(x'), below g_r(x) < 0 wherever the basis rows hold: no point satisfies
            // every row (Farkas). The proof leans on the artificial box if a box row has w < 0.
            let Some((l, t)) = leave else {
                let leans_on_box = basis.iter().zip(&w).any(|(&i, &wi)| i > m && wi < -1e-14);
                return if leans_on_box {
                    Outcome::Failed
                } else {
                    Outcome::Infeasible {
                        pivots: pivots as u32,
                    }
                };
            };
            for k in 0..n {
                y[k] -= t * w[k];
            }
            y[l] = t;
            if basis[l] < m {
                in_basis[basis[l]] = false;
            }
            in_basis[r] = true;
            basis[l] = r;
        }
        Outcome::Failed
    }

    /// The program's size, for the report.
    fn size(&self) -> ModelSize {
        let cone_rows = 6 * self.kappa.len();
        let inequality_rows = self.rows - self.no_tension_rows_implied();
        ModelSize {
            variables: 4 + self.ties,
            constraints: inequality_rows + cone_rows,
            equality_rows: 0,
            inequality_rows,
            friction_rows: 2 * self.friction_joints.len(),
            cone_rows,
        }
    }

    /// How many leading rows (the no-tension rows) the conic form leaves out because the
    /// crushing cones imply them: all `2 nj` with finite strength, none when rigid.
    fn no_tension_rows_implied(&self) -> usize {
        2 * self.kappa.len()
    }

    /// Fold the duals of the crushing cones (after the linear rows in `z`) into multipliers of
    /// the no-tension rows they are built from, so [`Self::mechanism`] reads them.
    fn fold_cone_duals(&self, z: &[f64]) -> Vec<f64> {
        let linear: Vec<usize> = (self.no_tension_rows_implied()..self.dense.len()).collect();
        let crush: Vec<usize> = (0..self.kappa.len()).collect();
        self.fold_duals_of(z, &linear, &crush)
    }

    /// The duals `z` of [`Self::conic_of`]`(linear, crush)` as multipliers of every row of
    /// `dense` (zero for the rows left out): the cone of the row `g` with partner `h` holds
    /// `s = [r g + 1, r g - 1, w (g + h)]` (`w = sqrt2 r / sqrt(kappa)`), so its dual
    /// `(z0, z1, z2)` acts on `g` with weight `r (z0 + z1) + w z2` and on `h` with `w z2`.
    fn fold_duals_of(&self, z: &[f64], linear: &[usize], crush: &[usize]) -> Vec<f64> {
        let mut y = vec![0.0; self.dense.len()];
        for (&i, &zi) in linear.iter().zip(z) {
            y[i] = zi;
        }
        let m = linear.len();
        for (j, &k) in crush.iter().enumerate() {
            let (r, kappa) = self.kappa[k];
            let w = std::f64::consts::SQRT_2 * r / kappa.sqrt();
            for (c, (g, h)) in [(2 * k, 2 * k + 1), (2 * k + 1, 2 * k)]
                .into_iter()
                .enumerate()
            {
                let base = m + 6 * j + 3 * c;
                let (z0, z1, z2) = (z[base], z[base + 1], z[base + 2]);
                y[g] += r * (z0 + z1) + w * z2;
                y[h] += w * z2;
            }
        }
        y
    }

    /// Joint forces of the solution `x` (SI units): the contact forces, as the full program
    /// reports them, and the ties' and the strips' tensions (N, in their orders). A strip
    /// carries the least tension its joint's equilibrium asks for (what its end would
    /// otherwise carry in tension, and what Coulomb's law needs besides), below its capacity
    /// by the program's rows.
    fn forces(&self, model: &Model, x: &[f64]) -> (Vec<JointForce>, Vec<f64>, Vec<f64>) {
        let assembly = &model.assembly;
        let (fs, ls, nt) = (self.force_scale, self.length_scale, self.ties);
        let (lambda, h, v, m0) = (x[0], x[1] * fs, x[2] * fs, x[3] * fs * ls);
        let ties: Vec<f64> = x[4..4 + nt].iter().map(|t| t * fs).collect();
        // Per joint, the tension at each end (p1, p2) its strips carry.
        let mut strip_ends = vec![[0.0; 2]; self.strip_ends.len()];
        let forces = assembly
            .joints
            .iter()
            .enumerate()
            .map(|(k, jt)| {
                let s = &self.sums[k];
                let mut f = Vec2::new(
                    h + s.base[0] + lambda * s.per[0],
                    v + s.base[1] + lambda * s.per[1],
                );
                let mut mk = m0 + s.base[2] + lambda * s.per[2];
                for (c, t) in self.tie_sums[k * nt..(k + 1) * nt].iter().zip(&ties) {
                    f.x += t * c[0];
                    f.y += t * c[1];
                    mk += t * c[2];
                }
                // Moment about the midpoint is -e N; the convention's M is e N.
                let m_mid = mk - cross(jt.midpoint() - self.reference, f);
                let (n, m, len) = (f.dot(&jt.normal()), -m_mid, jt.length());
                let (mut c1, mut c2) = (0.5 * n - m / len, 0.5 * n + m / len);
                let shear = f.dot(&jt.tangent());
                if let Some(cap) = self.strip_ends.get(k) {
                    // The strips' least tensions: each end's tension, then what friction
                    // needs (`mu (c1 + c2) >= |V|`) from the end with capacity to spare.
                    let mut t = [(-c1).max(0.0).min(cap[0]), (-c2).max(0.0).min(cap[1])];
                    let mu = jt.friction;
                    let mut short = shear.abs() / mu - (c1 + c2 + t[0] + t[1]);
                    for (te, ce) in t.iter_mut().zip(cap) {
                        if short > 0.0 && mu.is_finite() {
                            let more = short.min(ce - *te).max(0.0);
                            *te += more;
                            short -= more;
                        }
                    }
                    c1 += t[0];
                    c2 += t[1];
                    strip_ends[k] = t;
                }
                // As the full program reports them: the end forces c1, c2 clamped to no
                // tension, so a joint that opens shows no round-off tension and no resultant
                // outside it.
                let (c1, c2) = (c1.max(0.0), c2.max(0.0));
                JointForce {
                    n: c1 + c2,
                    v: shear,
                    m: 0.5 * (c2 - c1) * len,
                }
            })
            .collect();
        // Each strip's share of its end's tension, by capacity.
        let strips = model
            .strips
            .iter()
            .map(|st| {
                let end = usize::from(st.end == crate::assembly::JointEnd::P2);
                let (t, cap) = (strip_ends[st.joint][end], self.strip_ends[st.joint][end]);
                if cap > 0.0 {
                    t * st.capacity / cap
                } else {
                    0.0
                }
            })
            .collect();
        (forces, ties, strips)
    }

    /// Block velocities `[vx, vy, omega]` from the duals `z` (see the module docs), scaled so
    /// the fastest centroid moves at 1 and the seismic forces do positive work.
    fn mechanism(
        &self,
        assembly: &Assembly,
        loads: &LoadCase,
        sign: f64,
        z: &[f64],
    ) -> Vec<[f64; 3]> {
        let ls = self.length_scale;
        let rot = |p: Vec2| [1.0, p.y, -p.x];
        let mut rel = vec![[0.0; 3]; assembly.joints.len()];
        for (k, (jt, r)) in assembly.joints.iter().zip(rel.iter_mut()).enumerate() {
            let (z2, z1) = (z[2 * k], z[2 * k + 1]);
            let (a2, a1) = (rot(jt.p2), rot(jt.p1));
            for c in 0..3 {
                r[c] += (z2 * a2[c] - z1 * a1[c]) / ls;
            }
        }
        let nt = 2 * assembly.joints.len();
        for (f, &k) in self.friction_joints.iter().enumerate() {
            let jt = &assembly.joints[k];
            let (n, u, mu) = (jt.normal(), jt.tangent(), jt.friction);
            for (i, sv) in [1.0, -1.0].into_iter().enumerate() {
                let d = friction_direction(mu, n, u, sv, self.fixed_shear);
                let zf = z[nt + 2 * f + i];
                rel[k][1] += zf * d.x;
                rel[k][2] += zf * d.y;
            }
        }
        let mut twist = [0.0; 3];
        let mut v: Vec<[f64; 3]> = Vec::with_capacity(assembly.blocks.len());
        for (b, r) in assembly.blocks.iter().zip(&rel) {
            for (t, rc) in twist.iter_mut().zip(r) {
                *t += rc;
            }
            let g = b.centroid;
            v.push([
                twist[1] - twist[0] * g.y,
                twist[2] + twist[0] * g.x,
                twist[0],
            ]);
        }
        // Orientation: the action (what lambda multiplies) does positive work. Its wrench is
        // reduced to the block's load reference point, the centroid of `v`.
        let power: f64 = (0..v.len())
            .map(|i| {
                let w = loads
                    .variable(i, sign)
                    .moved(loads.reference(i), assembly.blocks[i].centroid);
                w.force.dot(&Vec2::new(v[i][0], v[i][1])) + w.moment * v[i][2]
            })
            .sum();
        let vmax = v
            .iter()
            .fold(0.0_f64, |a, b| a.max((b[0] * b[0] + b[1] * b[1]).sqrt()));
        if vmax > 0.0 {
            let scale = if power < 0.0 { -1.0 } else { 1.0 } / vmax;
            for b in &mut v {
                for c in b.iter_mut() {
                    *c *= scale;
                }
            }
        }
        v
    }
}

/// The least multiplier equilibrium allows on a chain (seismic forces toward `sign`), by the
/// active-set method (with crushing, and `settings.working_set`, the curved active set of
/// [`working_set`] from its basis); None when the method does not finish (or the model is not
/// a chain). The multipliers equilibrium allows form an interval (the program is convex), so
/// the structure stands at lambda = 0 exactly when this is at most 0 (and the largest at
/// least 0).
pub(super) fn least_lambda(model: &Model, settings: &StaticSettings) -> Option<f64> {
    // The conic stand test decides with crushing cones unless the working set may.
    let crushing = model.strength.is_finite();
    if declines(model).is_some() || (crushing && !settings.working_set) {
        return None;
    }
    let sign = settings.direction.sign();
    let program = ChainProgram::new(model, sign, None);
    if crushing {
        return program.least_lambda_crushing();
    }
    let lambda = program.active_set(-1.0, LAMBDA_CAP).optimal()?.x[0];
    lambda.is_finite().then_some(lambda)
}

/// Whether the chain stands under its permanent loads (lambda = 0), by one active-set solve:
/// the largest multiplier with `lambda <= 0` is 0 exactly when lambda = 0 is in the interval of
/// multipliers equilibrium allows. None when the model is not a chain or the method does not
/// decide (the interior point then does).
pub(super) fn stands_at_rest(model: &Model) -> Option<bool> {
    if declines(model).is_some() || model.strength.is_finite() {
        return None;
    }
    let program = ChainProgram::new(model, 1.0, None);
    match program.active_set(1.0, 0.0) {
        // The cap row makes lambda exactly 0 at the vertex when it binds; otherwise lambda is
        // the largest multiplier, below 0.
        Outcome::Optimal(a) => Some(a.x[0] >= -STAND_TOL),
        Outcome::Infeasible { .. } => Some(false),
        Outcome::Failed => None,
    }
}

/// Round-off allowance on lambda when the stand test's vertex sits on its cap `lambda <= 0`.
const STAND_TOL: f64 = 1e-12;

/// The result of the active-set method (see [`ChainProgram::active_set`]) when it decides: the
/// optimum (a negative one cannot stand), or a proof that no multiplier up to the cap has
/// equilibrium (cannot stand); None sends the analysis to the interior point.
fn active_set_result(
    model: &Model,
    program: &ChainProgram,
    settings: &StaticSettings,
) -> Option<StaticResult> {
    let ActiveSet {
        x, duals, pivots, ..
    } = match program.active_set(1.0, LAMBDA_CAP) {
        Outcome::Optimal(a) => a,
        Outcome::Infeasible { pivots } => {
            return Some(StaticResult::unsolved(
                settings,
                pivots,
                "active set: infeasible (no multiplier has equilibrium)".to_string(),
                program.size(),
            ))
        }
        Outcome::Failed => return None,
    };
    let lambda = x[0];
    if !lambda.is_finite() {
        return None;
    }
    let mut z = vec![0.0; program.dense.len()];
    for (i, y) in duals {
        z[i] = y;
    }
    let status = "active set; exact vertex".to_string();
    let unsolved = StaticResult::unsolved(settings, pivots, status, program.size());
    let mut result = program
        .read_point(model, settings, &x, &z, unsolved, true, None)
        .ok()?;
    result.exact_vertex = true;
    Some(result)
}

impl ChainProgram {
    /// `result` with the solution `x` (multipliers `z` of every row of `dense`, read for the
    /// mechanism) read into it; `capped` as in [`StaticResult::read_solution`]. With the
    /// interior point's `solver` status, an AlmostSolved solution is refused when its equilibrium
    /// residual is not small ([`check_almost_solved`]).
    #[allow(clippy::too_many_arguments)]
    fn read_point(
        &self,
        model: &Model,
        settings: &StaticSettings,
        x: &[f64],
        z: &[f64],
        result: StaticResult,
        capped: bool,
        solver: Option<SolverStatus>,
    ) -> Result<StaticResult, AnalysisError> {
        let (assembly, loads) = (&model.assembly, &model.loads);
        let sign = settings.direction.sign();
        let lambda = x[0];
        let (forces, ties, strips) = self.forces(model, x);
        let residual = model.equilibrium_residual(&forces, &ties, &strips, lambda, sign);
        if let Some(status) = solver {
            check_almost_solved(status, residual, self.force_scale, result.iterations)?;
        }
        let mut result = result.read_solution(
            assembly,
            model.strength,
            settings,
            lambda,
            forces,
            residual,
            capped,
            || self.mechanism(assembly, loads, sign, z),
        );
        result.read_interactions(model, &ties, &strips, &[]);
        Ok(result)
    }
}

/// Why the chain program does not represent a model; the dispatcher of [`super::analyse`]
/// then runs the full program.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Declined {
    /// The assembly is not a chain of blocks between two supports.
    NotAChain,
    /// Tie rods with crushing: the chain program takes a tie's tension as one more unknown
    /// of its linear program, but its working set on the crushing laws has the four
    /// redundants alone.
    Ties,
    /// Bonded strips with crushing: without it a strip may be taken at its capacity (see
    /// `ChainProgram::new`), but a crushing cone bounds the contact force the strip adds
    /// to.
    Strips,
    /// The fill's passive reactions are forces from the ground on single blocks, unknowns
    /// the chain's three redundants do not describe.
    Passive,
}

impl Declined {
    pub fn words(self) -> &'static str {
        match self {
            Declined::NotAChain => {
                "the reduced static program needs a chain of blocks between two supports"
            }
            Declined::Ties => {
                "the reduced static program does not model tie rods with a finite compressive strength"
            }
            Declined::Strips => {
                "the reduced static program does not model bonded strips with a finite compressive strength"
            }
            Declined::Passive => {
                "the reduced static program does not model the fill's passive resistance"
            }
        }
    }
}

/// Whether the chain program represents `model` (crushing included, by its conic form).
pub fn declines(model: &Model) -> Option<Declined> {
    if !model.assembly.is_chain() {
        Some(Declined::NotAChain)
    } else if model.strength.is_finite() && !model.ties.is_empty() {
        Some(Declined::Ties)
    } else if model.strength.is_finite() && !model.strips.is_empty() {
        Some(Declined::Strips)
    } else if !model.passive.is_empty() {
        Some(Declined::Passive)
    } else {
        None
    }
}

/// Static analysis of a chain (joint k joins block k - 1, or the ground, to block k, or the
/// ground) by its reduced program in four unknowns (and one per tie rod): the same answer as
/// [`super::analyse`] (the same statuses, multiplier, joint forces, hinges and mechanism), at
/// a fraction of the cost on long chains. Errors when the model is not such a chain, or has
/// ties or strips with crushing ([`declines`]).
pub fn analyse_chain(
    model: &Model,
    settings: &StaticSettings,
) -> Result<StaticResult, AnalysisError> {
    let start = Instant::now();
    let assembly = &model.assembly;
    model.validate()?;
    if let Some(why) = declines(model) {
        return Err(AnalysisError::Other(why.words().into()));
    }
    let sign = settings.direction.sign();
    let conic_program = model.strength.is_finite();
    let mut program = ChainProgram::new(model, sign, None);
    // The active set and the vertex step are exact for the linear program only; with crushing
    // cones the interior point's solution is the answer.
    if settings.active_set && !conic_program {
        if let Some(r) = active_set_result(model, &program, settings) {
            let mut r = super::stands_at_zero(model, settings, r)?;
            // The wall time covers the stand test at lambda = 0 too.
            r.solve_time_s = start.elapsed().as_secs_f64();
            return Ok(r);
        }
    }
    if conic_program && settings.working_set {
        if let Some(ws) = program.working_set(model, settings)? {
            let status = ws.words(assembly.joints.len());
            if ws.infeasible {
                let mut r = StaticResult::unsolved(settings, ws.iterations, status, program.size());
                r.solve_time_s = start.elapsed().as_secs_f64();
                return Ok(r);
            }
            let unsolved = StaticResult::unsolved(settings, ws.iterations, status, program.size());
            let result =
                program.read_point(model, settings, &ws.x, &ws.z, unsolved, false, None)?;
            let mut r = super::stands_at_zero(model, settings, result)?;
            r.solve_time_s = start.elapsed().as_secs_f64();
            return Ok(r);
        }
    }
    let mut sol = program.conic().solve(settings)?;
    let mut capped = false;
    if matches!(
        sol.status,
        SolverStatus::DualInfeasible | SolverStatus::AlmostDualInfeasible
    ) {
        program = ChainProgram::new(model, sign, Some(LAMBDA_CAP));
        sol = program.conic().solve(settings)?;
        capped = true;
    }
    let size = program.size();
    let mut result =
        StaticResult::unsolved(settings, sol.iterations, format!("{:?}", sol.status), size);
    match sol.status {
        SolverStatus::Solved | SolverStatus::AlmostSolved => {
            if conic_program {
                sol.z = program.fold_cone_duals(&sol.z);
            } else if let Some(v) = (program.ties == 0)
                .then(|| program.vertex(&sol.x, settings.tol_gap.max(settings.tol_feas)))
                .flatten()
            {
                sol.x = v;
                result.solver_status.push_str("; exact vertex");
                result.exact_vertex = true;
            }
            result = program.read_point(
                model,
                settings,
                &sol.x,
                &sol.z,
                result,
                capped,
                Some(sol.status),
            )?;
        }
        SolverStatus::PrimalInfeasible | SolverStatus::AlmostPrimalInfeasible => {
            result.status = Status::CannotStand;
        }
        other => result = result.settle_stalled(model, settings, other)?,
    }
    result = super::stands_at_zero(model, settings, result)?;
    result.solve_time_s = start.elapsed().as_secs_f64();
    Ok(result)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The LU of a larger basis solves `G x = b` and `G^T w = c` to round-off (residuals of
    /// random well-scaled matrices, pivoting needed: a zero leading entry).
    #[test]
    fn basis_solves_both_systems() {
        let mut state = 7u64;
        let mut next = || {
            state = state
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (state >> 11) as f64 / (1u64 << 53) as f64 - 0.5
        };
        for n in [5, 6, 8] {
            for _ in 0..20 {
                let mut basis = Basis::new(n);
                let g: Vec<f64> = (0..n * n).map(|_| next()).collect();
                let mut g = g;
                g[0] = 0.0;
                basis.rows_mut().copy_from_slice(&g);
                basis.factor();
                let b: Vec<f64> = (0..n).map(|_| next()).collect();
                for transpose in [false, true] {
                    let x = basis.solve(transpose, &b).expect("regular");
                    for i in 0..n {
                        let gx: f64 = (0..n)
                            .map(|k| if transpose { g[k * n + i] } else { g[i * n + k] } * x[k])
                            .sum();
                        assert!(
                            (gx - b[i]).abs() <= 1e-10,
                            "n {n}, row {i}: {gx} vs {}",
                            b[i]
                        );
                    }
                }
            }
        }
        // A singular basis (two equal rows) is refused.
        let mut basis = Basis::new(5);
        let mut g: Vec<f64> = (0..25).map(|_| next()).collect();
        for c in 0..5 {
            g[5 + c] = g[c];
        }
        basis.rows_mut().copy_from_slice(&g);
        basis.factor();
        assert!(basis.solve(false, &[1.0; 5]).is_none());
    }
}
