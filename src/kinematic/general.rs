//! The general kinematic program: an upper bound of the collapse multiplier of any assembly of
//! rigid blocks (walls, lintels, arcades, spandrels; chains too), by a linear program over the
//! blocks' velocities, and the certificate of its mechanism by virtual work.
//!
//! # The program
//! Unknowns: the twist of every block, its velocity `u_i` at its centroid `c_i` and its rate of
//! rotation `omega_i` (written `W_i = omega_i L` with `L` the structure's size, so that every
//! unknown is a velocity), and one dissipation `t_k` per tie rod. The velocity of a point `q`
//! of block i is `v_i(q) = u_i + omega_i (q - c_i)^perp`; the ground does not move.
//!
//! At joint j (ends `p1`, `p2`, unit tangent `u` from p1 to p2, normal `n` from `from` into
//! `to`; `crate::assembly`) the relative velocity of `to` with respect to `from`,
//! `dv(q) = v_to(q) - v_from(q)`, gives the opening rates `dn1 = n . dv(p1)`,
//! `dn2 = n . dv(p2)` at its two ends and the slip rate `dt = u . dv` (the same at every
//! point of the joint, since the blocks are rigid). These are linear in the twists; they are
//! written as expressions of them rather than as unknowns of their own, which keeps the
//! program as small as the static one (three unknowns per block instead of three per joint).
//!
//! The static program's joint model (`crate::interaction::contact`) holds the end forces
//! `c1, c2 >= 0` and the shear `V` in the cone `K = {c1, c2 >= 0, mu (c1 + c2) >= |V|}`. Its
//! power in a mechanism is `c1 dn1 + c2 dn2 + V dt`, and the mechanisms in which every force
//! of `K` does non-negative work are the dual cone `K* = {dn1 >= mu |dt|, dn2 >= mu |dt|}`:
//! no interpenetration at either end, and the associative (normality) flow rule of Coulomb
//! friction, slip with dilatancy. With `mu = inf` (no sliding) `K*` is `dn1, dn2 >= 0`,
//! `dt = 0`. Each `|dt|` is written as its two signs, so a joint with finite friction gives
//! four half-planes and the program is linear.
//!
//! Ties (`crate::interaction::tie`) dissipate `max(C de, P de)` at the elongation rate `de`
//! (the support function of `[P, C]`): `t_k >= C de_k`, `t_k >= P de_k`. Bonded strips
//! (`crate::interaction::strip`) dissipate `F max(dn, 0) = F dn` at their reinforced end,
//! which admissibility keeps opening or closed (`dn >= 0`), so their dissipation is linear.
//! The fill's passive faces (`crate::interaction::passive`) dissipate `P max(v_in, 0)` at the
//! rate `v_in` their point moves into the fill: `t_k >= P v_in`, `t_k >= 0`.
//!
//! The action's power `A` (the power of what lambda multiplies, [`crate::model::LoadCase::variable`]) is
//! normalised, `A = 1`, and the work balance `G + D` (`G = -` the power of the permanent loads
//! [`crate::model::LoadCase::permanent`], `D` the dissipation of ties and strips) is minimised:
//!
//! `lambda_upper = min { G(w) + D(w) : w admissible, A(w) = 1 }`.
//!
//! # The theorem
//! For any admissible mechanism and any statically admissible set of forces at `lambda`,
//! the virtual-work equation reads `lambda A = G + D_ties,strips(forces) - sum_j (c1 dn1 + c2
//! dn2 + V dt) <= G + D` (each joint's term is >= 0 by the choice of `K*`, each tie's and
//! strip's power is at most its dissipation); so `lambda <= (G + D)/A` whenever `A > 0`: the
//! kinematic (unsafe) theorem of limit analysis for associative joints (Drucker, Greenberg &
//! Prager, 1952; for masonry blocks Livesley, 1978, and Gilbert, Casapulla & Ahmed, 2006, who
//! solve exactly this pair of programs). The program is the linear-programming dual of the
//! static one (`crate::statics::problem`): with rigid joints both are linear, so by strong
//! duality `lambda_upper` equals the static `lambda` exactly whenever both exist, for finite
//! friction too — as long as friction is associative. With real (non-associative) friction,
//! joints slide without dilating, the set of admissible mechanisms is larger than `K*`'s and
//! the static multiplier is itself an upper bound of the real collapse (docs/friction.md):
//! neither number is then a bound from below.
//!
//! # Statuses
//! As for the chain search (`crate::kinematic` module docs): the multipliers equilibrium allows
//! form the interval `[max_{A<0} (G+D)/A, min_{A>0} (G+D)/A]`. The program with `A = 1` gives
//! the top; with `A = -1` (solved unless the structure is its own mirror image under
//! self-weight alone, when the interval is symmetric about 0) its minimum `m` gives the bottom
//! `-m`. An infeasible program (no admissible mechanism is driven by the load) leaves that end
//! open; an unbounded one means that a mechanism with `A = 0` and `G + D < 0` exists: gravity
//! alone drives it, and the structure cannot stand.
//!
//! # Certificate
//! The solver's objective is not trusted. The block twists are read back, the opening and
//! slip rates recomputed at every joint, and their admissibility checked: every end opens or
//! stays closed and every slip obeys the flow rule, to [`ADMISSIBLE_REL_TOL`] of the largest
//! relative velocity (the interior point stops a hair outside its cones). Then
//! `lambda = (G + D)/A` is recomputed by virtual work from the twists and the load case
//! (`kinematic::work`), and that is the `lambda_upper` reported. A mechanism that fails the check
//! gives no bound (an error saying which joint fails).
//!
//! # Limits
//! - Rigid joints: a finite compressive strength (the crushing cones) is ignored, so the
//!   multiplier is the rigid structure's, an upper bound of the crushing one (crushing only
//!   shrinks the static set); the analysis layer says so.
//! - Associative friction (above). Small displacements: the mechanism is a velocity field on
//!   the undeformed geometry.

use super::{work, Family, Hinge, KinematicError, KinematicResult, KinematicSettings};
use super::{Mechanism, Search, Status, Sums, Twist};
use crate::assembly::{Assembly, JointEnd};
use crate::geometry::{cross, Vec2};
use crate::model::Model;
use crate::statics::{conic, Refinement};
use clarabel::algebra::CscMatrix;
use clarabel::solver::{SolverStatus, SupportedConeT};
use std::time::Instant;

/// Relative tolerance of the certificate's admissibility check: an opening rate (or a flow
/// rule's slack) above `-ADMISSIBLE_REL_TOL` times the largest relative velocity of the
/// mechanism counts as admissible. The interior point's solutions violate their cones by about
/// its feasibility tolerance (`SOLVER_TOL`); a violation of this size changes the multiplier
/// by as little.
pub const ADMISSIBLE_REL_TOL: f64 = 1e-8;

/// Relative rate (of the largest relative velocity) below which a joint end counts as closed,
/// or a joint as not slipping, when the mechanism's hinges, open and sliding joints are named.
pub const MOVES_REL_TOL: f64 = 1e-6;

/// Clarabel's gap and feasibility tolerances for the kinematic program (dimensionless). At the
/// static program's 1e-10 the optimum of a 1,000-block wall stopped 9e-8 above the static
/// multiplier (the dual residual's share of the objective grows with the number of joints);
/// at 1e-12 the two meet to 1e-9 for 10% more time (benches/general_kinematic.rs).
const SOLVER_TOL: f64 = 1e-12;

/// The program for one normalisation of the action's power (`A = norm`, +1 or -1).
struct Program {
    q: Vec<f64>,
    a: CscMatrix<f64>,
    b: Vec<f64>,
    cones: Vec<SupportedConeT<f64>>,
    /// Length scale (m).
    length_scale: f64,
}

/// The outcome of one program.
enum Solved {
    /// Solved: the block twists (about the origin) of the optimal mechanism, the interior
    /// point's iterations, and the solver's status when it stopped short of its tolerances
    /// (then the mechanism, once certified, still bounds lambda from above, but need not be
    /// the least one).
    Optimal {
        twists: Vec<Twist>,
        iterations: u32,
        stopped: Option<String>,
    },
    /// No admissible mechanism with this sign of the action's power.
    Infeasible,
    /// Unbounded below: some admissible mechanism with `A = 0` has `G + D < 0` (gravity
    /// alone drives it).
    Unbounded,
}

/// Rows of the program in the making: entries `(row, column, value)` of the zero cone's rows
/// and of the nonnegative cone's rows, with their right-hand sides (`b - a.x` in the cone).
#[derive(Default)]
struct Builder {
    eq: Vec<(usize, usize, f64)>,
    b_eq: Vec<f64>,
    ineq: Vec<(usize, usize, f64)>,
    b_ineq: Vec<f64>,
}

impl Builder {
    /// The row `expr = rhs`.
    fn equal(&mut self, expr: &[(usize, f64)], rhs: f64) {
        let row = self.b_eq.len();
        self.eq.extend(expr.iter().map(|&(c, v)| (row, c, v)));
        self.b_eq.push(rhs);
    }

    /// The row `expr >= 0` (Clarabel's `s = 0 - (-expr) >= 0`).
    fn nonnegative(&mut self, expr: &[(usize, f64)]) {
        let row = self.b_ineq.len();
        self.ineq.extend(expr.iter().map(|&(c, v)| (row, c, -v)));
        self.b_ineq.push(0.0);
    }
}

/// `dir . v(point)` of block `block` (nothing for the ground) times `sign`, as entries on the
/// twist columns `3 i + (0, 1, 2)` = `(u_x, u_y, W = omega L)`: `dir . u + W (r x dir)` with
/// `r = (point - c_i)/L` — the transpose of the static program's force on a block
/// (`crate::interaction::Rows::force_on`), which makes the two programs exact duals.
fn velocity_along(
    expr: &mut Vec<(usize, f64)>,
    centroids: &[Vec2],
    length_scale: f64,
    block: Option<usize>,
    dir: Vec2,
    point: Vec2,
    sign: f64,
) {
    let Some(i) = block else { return };
    let r = (point - centroids[i]) / length_scale;
    expr.push((3 * i, sign * dir.x));
    expr.push((3 * i + 1, sign * dir.y));
    expr.push((3 * i + 2, sign * cross(r, dir)));
}

impl Program {
    /// The program of `model` with the action toward `sign` and its power normalised to
    /// `norm`.
    fn new(model: &Model, sign: f64, norm: f64) -> Program {
        Program::sparse(model, sign, norm, 0.0)
    }

    /// The program with `sparsity` times a generic positive weighting of the opening rates
    /// `dn` of every joint end added to the objective: among mechanisms of equal `G + D` (a
    /// degenerate optimum, where an interior point returns the centre of the optimal face, a
    /// blend of mechanisms) it picks one vertex, the mechanism that opens least; 0 is the
    /// program itself.
    fn sparse(model: &Model, sign: f64, norm: f64, sparsity: f64) -> Program {
        let assembly = &model.assembly;
        let loads = &model.loads;
        let nb = assembly.blocks.len();
        let ls = assembly.size();
        let fs = loads.force_scale();
        let centroids: Vec<Vec2> = (0..nb).map(|i| loads.reference(i)).collect();
        let nt = model.ties.len();
        let columns = 3 * nb + nt + model.passive.len();
        let rel = |expr: &mut Vec<(usize, f64)>, j: usize, dir: Vec2, point: Vec2, f: f64| {
            let jt = &assembly.joints[j];
            velocity_along(expr, &centroids, ls, jt.to, dir, point, f);
            velocity_along(expr, &centroids, ls, jt.from, dir, point, -f);
        };
        let mut rows = Builder::default();
        // The objective: G = -(power of the permanent loads), and the strips' dissipation.
        let mut q = vec![0.0; columns];
        // The normalisation: the action's power.
        let mut action = Vec::with_capacity(3 * nb);
        for i in 0..nb {
            let p = loads.permanent(i);
            let s = loads.variable(i, sign);
            for (k, (pv, sv)) in [
                (p.force.x / fs, s.force.x / fs),
                (p.force.y / fs, s.force.y / fs),
                (p.moment / (fs * ls), s.moment / (fs * ls)),
            ]
            .into_iter()
            .enumerate()
            {
                q[3 * i + k] = -pv;
                if sv != 0.0 {
                    action.push((3 * i + k, sv));
                }
            }
        }
        rows.equal(&action, norm);
        // The joints: no interpenetration at either end, the flow rule of Coulomb friction.
        for (j, jt) in assembly.joints.iter().enumerate() {
            let (n, u) = (jt.normal(), jt.tangent());
            let mut dt = Vec::new();
            rel(&mut dt, j, u, jt.midpoint(), 1.0);
            for (e, end) in [jt.p1, jt.p2].into_iter().enumerate() {
                let mut dn = Vec::new();
                rel(&mut dn, j, n, end, 1.0);
                if sparsity > 0.0 {
                    // A generic weight in [1, 2) per joint end (a fixed hash, so runs repeat).
                    let h = ((2 * j + e) as f64 * 12.9898 + 78.233).sin() * 43758.5453;
                    let w = sparsity * (1.0 + h - h.floor());
                    for &(c, v) in &dn {
                        q[c] += w * v;
                    }
                }
                if jt.friction.is_finite() && jt.friction > 0.0 {
                    for s in [1.0, -1.0] {
                        let mut row = dn.clone();
                        row.extend(dt.iter().map(|&(c, v)| (c, s * jt.friction * v)));
                        rows.nonnegative(&row);
                    }
                } else {
                    rows.nonnegative(&dn);
                }
            }
            if jt.friction.is_infinite() {
                rows.equal(&dt, 0.0);
            }
        }
        // Ties: t_k >= C de_k and t_k >= P de_k (over the force scale).
        for (k, t) in model.ties.iter().enumerate() {
            let col = 3 * nb + k;
            q[col] = 1.0;
            let e = t.direction();
            let mut de = Vec::new();
            velocity_along(&mut de, &centroids, ls, t.to.block, e, t.to.point, 1.0);
            velocity_along(&mut de, &centroids, ls, t.from.block, e, t.from.point, -1.0);
            for force in [t.capacity, t.prestress] {
                let mut row = vec![(col, 1.0)];
                row.extend(de.iter().map(|&(c, v)| (c, -force / fs * v)));
                rows.nonnegative(&row);
            }
        }
        // Strips: F dn at the reinforced end (dn >= 0 by the joint's rows).
        for s in &model.strips {
            let jt = &assembly.joints[s.joint];
            let mut dn = Vec::new();
            rel(&mut dn, s.joint, jt.normal(), s.point(assembly), 1.0);
            for (c, v) in dn {
                q[c] += s.capacity / fs * v;
            }
        }
        // The fill's passive faces: t_k >= P (into . v(point)) and t_k >= 0 (over the force
        // scale), the support function of the reaction's interval [0, P].
        for (k, p) in model.passive.iter().enumerate() {
            let col = 3 * nb + nt + k;
            q[col] = 1.0;
            let mut vin = Vec::new();
            let into = Vec2::new(p.into, 0.0);
            velocity_along(&mut vin, &centroids, ls, Some(p.block), into, p.point, 1.0);
            let mut row = vec![(col, 1.0)];
            row.extend(vin.iter().map(|&(c, v)| (c, -p.cap / fs * v)));
            rows.nonnegative(&row);
            rows.nonnegative(&[(col, 1.0)]);
        }
        // Clarabel's form: the zero cone's rows, then the nonnegative cone's.
        let neq = rows.b_eq.len();
        let nineq = rows.b_ineq.len();
        let (mut r, mut c, mut v) = (Vec::new(), Vec::new(), Vec::new());
        for &(row, col, val) in &rows.eq {
            r.push(row);
            c.push(col);
            v.push(val);
        }
        for &(row, col, val) in &rows.ineq {
            r.push(neq + row);
            c.push(col);
            v.push(val);
        }
        let a = CscMatrix::new_from_triplets(neq + nineq, columns, r, c, v);
        let mut b = rows.b_eq;
        b.extend(rows.b_ineq);
        let mut cones = vec![SupportedConeT::ZeroConeT(neq)];
        if nineq > 0 {
            cones.push(SupportedConeT::NonnegativeConeT(nineq));
        }
        Program {
            q,
            a,
            b,
            cones,
            length_scale: ls,
        }
    }

    /// Solve; the twists `[omega, vx0, vy0]` about the origin of each block. Clarabel solves
    /// it under `refinement` as it does the static programs ([`crate::statics::conic::solve`]: a
    /// large program without iterative refinement first, and again with it when that solve
    /// does not end solved or infeasible, the iterations of both counted).
    fn solve(&self, model: &Model, refinement: Refinement) -> Result<Solved, KinematicError> {
        let n = self.q.len();
        let program = conic::Conic {
            p: &CscMatrix::zeros((n, n)),
            q: &self.q,
            a: &self.a,
            b: &self.b,
            cones: &self.cones,
        };
        let knobs = conic::Knobs {
            tol_gap: SOLVER_TOL,
            tol_feas: SOLVER_TOL,
            max_iter: 200,
            linear_solver: None,
            refinement,
        };
        let sol = conic::solve(&program, &knobs).map_err(KinematicError::General)?;
        let twists = |x: &[f64]| -> Vec<Twist> {
            (0..model.assembly.blocks.len())
                .map(|i| {
                    let c = model.loads.reference(i);
                    let omega = x[3 * i + 2] / self.length_scale;
                    // v(q) = u + omega (q - c)^perp = (u_x + omega c_y - omega q_y, ...)
                    [omega, x[3 * i] + omega * c.y, x[3 * i + 1] - omega * c.x]
                })
                .collect()
        };
        match sol.status {
            SolverStatus::Solved | SolverStatus::AlmostSolved => Ok(Solved::Optimal {
                twists: twists(&sol.x),
                iterations: sol.iterations,
                stopped: None,
            }),
            // Out of iterations or of progress: the last iterate is no optimum, but any
            // admissible mechanism bounds lambda from above, so the certificate decides.
            SolverStatus::MaxIterations
            | SolverStatus::MaxTime
            | SolverStatus::InsufficientProgress
                if sol.x.iter().all(|x| x.is_finite()) =>
            {
                Ok(Solved::Optimal {
                    twists: twists(&sol.x),
                    iterations: sol.iterations,
                    stopped: Some(format!("{:?}", sol.status)),
                })
            }
            SolverStatus::PrimalInfeasible | SolverStatus::AlmostPrimalInfeasible => {
                Ok(Solved::Infeasible)
            }
            SolverStatus::DualInfeasible | SolverStatus::AlmostDualInfeasible => {
                Ok(Solved::Unbounded)
            }
            other => Err(KinematicError::General(format!(
                "the kinematic program stopped at {other:?} after {} iterations",
                sol.iterations
            ))),
        }
    }
}

/// What a mechanism does at one joint: the opening rates at its ends and its slip rate (SI,
/// `to` relative to `from`).
#[derive(Debug, Clone, Copy)]
pub struct JointRates {
    pub dn1: f64,
    pub dn2: f64,
    pub dt: f64,
}

/// The opening and slip rates of every joint for block twists `twists` (about the origin;
/// the ground does not move).
pub fn joint_rates(assembly: &Assembly, twists: &[Twist]) -> Vec<JointRates> {
    let v = |b: Option<usize>, q: Vec2| b.map_or(Vec2::zeros(), |i| super::velocity(twists[i], q));
    assembly
        .joints
        .iter()
        .map(|jt| {
            let dv = |q: Vec2| v(jt.to, q) - v(jt.from, q);
            JointRates {
                dn1: dv(jt.p1).dot(&jt.normal()),
                dn2: dv(jt.p2).dot(&jt.normal()),
                dt: dv(jt.midpoint()).dot(&jt.tangent()),
            }
        })
        .collect()
}

/// The virtual work of a mechanism: `(A, G, D)`, the action's power, minus the permanent
/// loads' power, and the ties' and strips' dissipation, from the block twists `twists` (about
/// the origin) and the model's loads, the action toward `sign`.
pub fn virtual_work(model: &Model, twists: &[Twist], sign: f64) -> (f64, f64, f64) {
    let (mut a, mut g) = (0.0, 0.0);
    for (i, t) in twists.iter().enumerate() {
        let (da, dg) = work(*t, Sums::of_block(&model.loads, i, sign));
        a += da;
        g += dg;
    }
    let v = |b: Option<usize>, q: Vec2| b.map_or(Vec2::zeros(), |i| super::velocity(twists[i], q));
    let ties: f64 = model
        .ties
        .iter()
        .map(|t| t.dissipation(t.elongation_rate(v)))
        .sum();
    let strips: f64 = model
        .strips
        .iter()
        .map(|s| {
            let jt = &model.assembly.joints[s.joint];
            let p = s.point(&model.assembly);
            s.dissipation((v(jt.to, p) - v(jt.from, p)).dot(&jt.normal()))
        })
        .sum();
    let passive: f64 = model
        .passive
        .iter()
        .map(|p| p.dissipation(v(Some(p.block), p.point).x))
        .sum();
    (a, g, ties + strips + passive)
}

/// A mechanism checked by its certificate.
#[derive(Debug, Clone)]
pub struct Checked {
    /// Block twists `[omega, vx0, vy0]` about the origin.
    pub twists: Vec<Twist>,
    pub rates: Vec<JointRates>,
    /// `(A, G, D)` by virtual work.
    pub work: (f64, f64, f64),
    /// The largest relative velocity at a joint.
    pub largest: f64,
}

/// Check that block twists `twists` are an admissible mechanism of `model` (see the module
/// docs, "Certificate"), and value it by virtual work; why not, naming the joint, otherwise.
pub fn check(model: &Model, twists: Vec<Twist>, sign: f64) -> Result<Checked, String> {
    let assembly = &model.assembly;
    if twists.len() != assembly.blocks.len() || twists.iter().flatten().any(|x| !x.is_finite()) {
        return Err("the mechanism's velocities are not finite numbers".into());
    }
    let rates = joint_rates(assembly, &twists);
    let largest = rates.iter().fold(0.0_f64, |m, r| {
        m.max(r.dn1.abs()).max(r.dn2.abs()).max(r.dt.abs())
    });
    // NaN-safe: a NaN rate fails too.
    if largest.is_nan() || largest <= 0.0 {
        return Err("no joint moves: the solution is no mechanism".into());
    }
    let tol = ADMISSIBLE_REL_TOL * largest;
    for (j, (jt, r)) in assembly.joints.iter().zip(&rates).enumerate() {
        let slip = if jt.friction.is_finite() {
            jt.friction * r.dt.abs()
        } else if r.dt.abs() > tol {
            return Err(format!(
                "joint {j} slips at {:.3e} of the largest relative velocity, but its friction is infinite",
                r.dt.abs() / largest
            ));
        } else {
            0.0
        };
        for (end, dn) in [("p1", r.dn1), ("p2", r.dn2)] {
            if dn - slip < -tol * (1.0 + jt.friction.min(1e6)) {
                return Err(format!(
                    "joint {j} at {end}: opening rate {:.3e} below the flow rule's mu |dt| = {:.3e} (relative to the largest relative velocity)",
                    dn / largest,
                    slip / largest
                ));
            }
        }
    }
    let work = virtual_work(model, &twists, sign);
    Ok(Checked {
        twists,
        rates,
        work,
        largest,
    })
}

impl Checked {
    /// The mechanism in the report's form: hinges (a joint one end of which stays closed
    /// while the other opens), joints that open completely, sliding joints, and the block
    /// velocities at their centroids scaled so the fastest moves at 1.
    fn mechanism(&self, assembly: &Assembly, lambda: f64) -> Mechanism {
        let eps = MOVES_REL_TOL * self.largest;
        let mut hinges = Vec::new();
        let mut open = Vec::new();
        let mut sliding = Vec::new();
        for (j, r) in self.rates.iter().enumerate() {
            match (r.dn1 > eps, r.dn2 > eps) {
                (false, true) => hinges.push(Hinge::at(assembly, j, JointEnd::P1)),
                (true, false) => hinges.push(Hinge::at(assembly, j, JointEnd::P2)),
                (true, true) => open.push(j),
                (false, false) => {}
            }
            if r.dt.abs() > eps {
                sliding.push(j);
            }
        }
        let mut velocities: Vec<[f64; 3]> = assembly
            .blocks
            .iter()
            .zip(&self.twists)
            .map(|(b, t)| {
                let v = super::velocity(*t, b.centroid);
                [v.x, v.y, t[0]]
            })
            .collect();
        let vmax = velocities
            .iter()
            .fold(0.0_f64, |m, v| m.max(v[0].hypot(v[1])));
        if vmax > 0.0 {
            for v in &mut velocities {
                v.iter_mut().for_each(|x| *x /= vmax);
            }
        }
        Mechanism {
            family: Family::General,
            hinges,
            open,
            sliding,
            velocities,
            lambda,
        }
    }
}

/// The least `(G + D)/A` over the admissible mechanisms of `model` with `A = 1` (the action
/// toward `sign`), certified by virtual work as in [`analyse_general`], without the other end
/// of the interval: what an incremental analysis needs at each configuration
/// (`crate::assess::incremental`), where the displaced structure's multiplier may be of any
/// sign.
pub(crate) enum Least {
    /// The certified mechanism (block twists about the origin) and its multiplier.
    Mechanism(Vec<Twist>, f64),
    /// No admissible mechanism is driven by the action.
    Nothing,
    /// An admissible mechanism with `A = 0` is driven by the permanent loads alone.
    Falls,
}

/// Weight of the opening rates in the objective of the program that picks one mechanism of a
/// degenerate optimum ([`Program::sparse`]): small beside the work balance (about 1 with the
/// action's power normalised), large beside the solver's tolerance.
const SPARSITY: f64 = 1e-5;

/// See [`Least`]. With `one`, the mechanism is one vertex of the optimal face (the one that
/// opens least, [`Program::sparse`]) rather than the interior point's blend of every optimal
/// mechanism; the multiplier is the program's least either way.
pub(crate) fn least_mechanism(
    model: &Model,
    sign: f64,
    one: bool,
) -> Result<Least, KinematicError> {
    model.validate()?;
    let certified = |twists: Vec<Twist>| -> Result<(Vec<Twist>, f64), KinematicError> {
        let c = check(model, twists, sign).map_err(KinematicError::NotCertified)?;
        let (a, g, d) = c.work;
        if a <= 0.0 {
            return Err(KinematicError::NotCertified(format!(
                "the optimal mechanism's action power is {a:.3e}, not positive"
            )));
        }
        Ok((c.twists, (g + d) / a))
    };
    match Program::new(model, sign, 1.0).solve(model, Refinement::Auto)? {
        Solved::Optimal { twists, .. } => {
            let (twists, lambda) = certified(twists)?;
            if !one {
                return Ok(Least::Mechanism(twists, lambda));
            }
            // Best effort: a vertex that fails its certificate (the perturbed program is
            // solved less accurately on a badly scaled assembly) leaves the blend.
            match Program::sparse(model, sign, 1.0, SPARSITY).solve(model, Refinement::Auto) {
                Ok(Solved::Optimal { twists: t, .. }) => match certified(t) {
                    Ok((t, _)) => Ok(Least::Mechanism(t, lambda)),
                    Err(_) => Ok(Least::Mechanism(twists, lambda)),
                },
                _ => Ok(Least::Mechanism(twists, lambda)),
            }
        }
        Solved::Infeasible => Ok(Least::Nothing),
        Solved::Unbounded => Ok(Least::Falls),
    }
}

/// The least multiplier equilibrium allows is above this (a round-off allowance on the
/// dimensionless work balance): the structure cannot stand at lambda = 0.
const NEEDED_TOL: f64 = 1e-9;

/// The general kinematic upper bound of `model` (module docs), the action toward
/// `settings.direction`. `Collapse` with the certified `lambda_upper` and its mechanism,
/// `NoCollapse` when no admissible mechanism is driven by the action, `CannotStand` when
/// one moves under the permanent loads alone. Errors: an invalid model, a solver that does
/// not converge, or a mechanism that fails its certificate ([`KinematicError::NotCertified`]).
pub fn analyse_general(
    model: &Model,
    settings: &KinematicSettings,
) -> Result<KinematicResult, KinematicError> {
    let start = Instant::now();
    model.validate()?;
    let sign = settings.direction.sign();
    let assembly = &model.assembly;
    let upper = Program::new(model, sign, 1.0).solve(model, settings.refinement)?;
    if let Solved::Unbounded = upper {
        return Ok(cannot_stand(model, settings, start, 1));
    }
    // The bottom of the interval: symmetric about 0 for a structure that is its own mirror
    // image under self-weight alone (the mirror of a mechanism driven by the action is one
    // driven against it, with the same G), so only the other structures need the program.
    let symmetric = crate::statics::symmetric_self_weight(model);
    let lower = if symmetric {
        Solved::Infeasible
    } else {
        Program::new(model, sign, -1.0).solve(model, settings.refinement)?
    };
    let programs: u64 = if symmetric { 1 } else { 2 };
    let mut iterations = 0;
    let mut stopped = Vec::new();
    // Certify a program's optimum: its mechanism and multiplier (G + D)/A, whose action power
    // must have the sign `norm` asked for (None when the program has no optimum).
    let mut certified =
        |solved: Solved, norm: f64| -> Result<Option<(Checked, f64)>, KinematicError> {
            let Solved::Optimal {
                twists,
                iterations: it,
                stopped: why,
            } = solved
            else {
                return Ok(None);
            };
            iterations += it;
            stopped.extend(why);
            let c = check(model, twists, sign).map_err(KinematicError::NotCertified)?;
            let (a, g, d) = c.work;
            if a * norm <= 0.0 {
                return Err(KinematicError::NotCertified(format!(
                "the optimal mechanism's action power is {a:.3e}, not of the sign {norm} asked for"
            )));
            }
            Ok(Some((c, (g + d) / a)))
        };
    if let Solved::Unbounded = lower {
        return Ok(cannot_stand(model, settings, start, programs));
    }
    // The least multiplier equilibrium allows, max (G + D)/A over A < 0, and its mechanism;
    // the greatest, min (G + D)/A over A > 0.
    let (witness, needed) = certified(lower, -1.0)?.unzip();
    let (best, mechanism) = match certified(upper, 1.0)? {
        Some((c, lambda)) => (Some(lambda), Some(c.mechanism(assembly, lambda))),
        None => (None, None),
    };
    let needed_mechanism = witness.map(|c| {
        let l = needed.unwrap_or(f64::NAN);
        c.mechanism(assembly, l)
    });
    let (status, mechanism) = match (best, needed) {
        (Some(b), Some(n)) if n > b + NEEDED_TOL * b.abs().max(1.0) => {
            (Status::CannotStand, needed_mechanism)
        }
        (_, Some(n)) if n > NEEDED_TOL => (Status::CannotStand, needed_mechanism),
        (Some(b), _) if b < 0.0 => (Status::CannotStand, mechanism),
        (Some(_), _) => (Status::Collapse, mechanism),
        (None, _) => (Status::NoCollapse, None),
    };
    let mut note = match (status, best) {
        (Status::Collapse, Some(b)) => format!(
            "general: the least (G + D)/A over the admissible mechanisms of all {} blocks and {} joints (rocking, opening and sliding with associative friction), certified by virtual work from the block velocities: lambda = {b:.10}; admissible to {ADMISSIBLE_REL_TOL:.0e} of the largest relative velocity",
            assembly.blocks.len(),
            assembly.joints.len()
        ),
        (Status::NoCollapse, _) => "general: no admissible mechanism is driven by the action".to_string(),
        _ => "general: a mechanism moves under the permanent loads alone (the interval of multipliers equilibrium allows is empty or lies above 0)".to_string(),
    };
    note += &format!(
        "; {programs} program{} ({iterations} interior-point iterations)",
        if programs == 1 { "" } else { "s" }
    );
    if !stopped.is_empty() {
        note += &format!(
            "; the solver stopped short of its tolerances ({}): the certified mechanism bounds lambda from above but need not be the least one",
            stopped.join(", ")
        );
    }
    Ok(KinematicResult {
        status,
        lambda_upper: if status == Status::Collapse {
            best
        } else {
            None
        },
        lambda_signed: best,
        lambda_needed: needed,
        mechanism,
        direction: settings.direction,
        candidates: programs,
        admissible: programs,
        wall_time_s: start.elapsed().as_secs_f64(),
        search: Search::General,
        searched_joints: assembly.joints.len(),
        note: Some(note),
    })
}

/// The result when a program is unbounded below: an admissible mechanism on which the action
/// does no work and the permanent loads do positive work exists (Farkas), so the structure
/// cannot stand; `programs` were solved.
fn cannot_stand(
    model: &Model,
    settings: &KinematicSettings,
    start: Instant,
    programs: u64,
) -> KinematicResult {
    KinematicResult {
        status: Status::CannotStand,
        lambda_upper: None,
        lambda_signed: None,
        lambda_needed: None,
        mechanism: None,
        direction: settings.direction,
        candidates: programs,
        admissible: 0,
        wall_time_s: start.elapsed().as_secs_f64(),
        search: Search::General,
        searched_joints: model.assembly.joints.len(),
        note: Some("general: the kinematic program is unbounded below: an admissible mechanism on which the action does no work is driven by the permanent loads alone, so the structure cannot stand".to_string()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::statics::conic::{tests::arch, STALL_UNREFINED};
    use crate::statics::{analyse, StaticSettings};

    /// The general program's retry of a solve that does not end solved without Clarabel's
    /// iterative refinement (the hook stops it after 4 iterations): the mechanism is the
    /// refined solve's, bit for bit, its iterations those of both solves, and it is certified
    /// by virtual work at the static multiplier (associative friction: the two bounds meet).
    #[test]
    fn a_stalled_unrefined_solve_is_repeated_with_the_refinement() {
        let model = arch();
        let optimum = |solved: Result<Solved, KinematicError>| match solved.expect("solved") {
            Solved::Optimal {
                twists,
                iterations,
                stopped,
            } => (twists, iterations, stopped),
            _ => panic!("the general program has an optimum"),
        };
        let program = Program::new(&model, 1.0, 1.0);
        let (twists, iterations, stopped) = optimum(program.solve(&model, Refinement::Always));
        assert!(
            stopped.is_none() && iterations > 4,
            "{iterations} {stopped:?}"
        );
        STALL_UNREFINED.set(Some(4));
        let retried = program.solve(&model, Refinement::Auto);
        STALL_UNREFINED.set(None);
        let (retried, retried_iterations, stopped) = optimum(retried);
        assert!(stopped.is_none(), "{stopped:?}");
        assert_eq!(retried, twists);
        assert_eq!(retried_iterations, 4 + iterations);
        let c = check(&model, retried, 1.0).expect("an admissible mechanism");
        let (a, g, d) = c.work;
        let upper = (g + d) / a;
        let lower = analyse(&model, &StaticSettings::default())
            .expect("static program")
            .lambda
            .expect("a collapse");
        assert!(
            lower <= upper + 1e-9 * upper.abs() && upper - lower <= 1e-6 * upper.abs(),
            "static {lower}, kinematic {upper}"
        );
    }
}
