//! The chain program with crushing by a working set (issue 28): the crushing laws of only the
//! joints that matter, found by checking every joint at the solution.
//!
//! With finite compressive strength every joint of the chain program holds two rotated
//! second-order cones (`2 c_i kappa >= N^2`, [`crate::interaction::crushing`]), which imply its
//! two no-tension rows (`c_i >= 0`). At the optimum only a few of them bind: the hinges, each
//! at the centre of its compressed zone. Nothing here changes the program: every answer is
//! certified against every row and cone of every joint, and what cannot be certified goes to
//! the program on all joints ([`super::analyse_chain`], Clarabel).
//!
//! 1. **The rigid optimum** by the active-set method (exact, microseconds): its basis rows are
//!    the rigid hinges (and sliding joints); the crushing hinges lie at or next to them.
//! 2. **An active set on the curved rows** ([`ChainProgram::curved_active_set`]): each
//!    no-tension row `c_i >= 0` of a basis joint becomes its crushing law
//!    `h = c_i - N^2 / (2 kappa) >= 0` (the cone, as a concave function of the four
//!    unknowns; friction rows stay linear). Newton's method puts the four basis rows on their
//!    surfaces, their multipliers follow from the objective's gradient, and while a row of any
//!    joint is violated it enters the basis and the ratio test picks the row that leaves (a
//!    dual simplex step on the rows' linearisations). It ends when the point satisfies the
//!    crushing law and the friction rows of every joint (an O(n) check) with non-negative
//!    multipliers: the KKT conditions of a convex program, hence its optimum, to round-off.
//! 3. **Otherwise, Clarabel on a working set** ([`ChainProgram::conic_working_set`]): W is
//!    the rigid basis joints and their neighbours. The relaxed program keeps, for each joint
//!    in W, its two crushing cones (hence its no-tension limits too) and the friction rows
//!    found so far; it drops every row of the joints outside W. Its feasible set contains the
//!    full program's, so its multiplier is at least the true one; it is bounded, since the
//!    cones of the rigid basis joints imply the basis rows and the rigid program with its
//!    basis rows alone has the rigid optimum. At its solution every joint outside W is checked
//!    against its crushing cones (which contain the rigid no-tension limits: a resultant
//!    outside the joint shows as a violated cone) and every friction row left out; in each
//!    run of consecutive violated joints the worst one and its neighbours join W, and it is
//!    solved again. When nothing is violated the solution satisfies the full program and is
//!    optimal for a relaxation of it: it is the full program's optimum. When the relaxed
//!    program has no feasible point, neither has the full one: the structure cannot stand.
//!
//! This is constraint generation (cutting planes) for a convex program, exact because every
//! constraint is checked at the end. When the rigid solve does not finish or hits the cap,
//! a relaxed solve ends otherwise than solved or infeasible, or W grows past [`MAX_JOINTS`]
//! joints or [`MAX_ROUNDS`] solves, the caller solves the program on all joints.

use super::{ChainProgram, Outcome};
use crate::model::Model;
use clarabel::solver::SolverStatus;

/// The most joints the working set may hold before the program on all joints is solved
/// instead: beyond this the relaxed programs are no longer small.
pub(super) const MAX_JOINTS: usize = 96;

/// The most relaxed solves before the program on all joints is solved instead.
pub(super) const MAX_ROUNDS: usize = 16;

/// The solution of the working-set method: the optimum `x`, the multipliers of every row of
/// the chain program (`dense`'s layout, cones folded onto the no-tension rows), the interior
/// point's iterations over all solves (or the pivots of the rigid and curved active sets), the
/// number of conic solves (0 when the curved active set found it) and the joints in the
/// working set.
pub(super) struct WorkingSet {
    pub x: Vec<f64>,
    pub z: Vec<f64>,
    pub iterations: u32,
    pub rounds: usize,
    pub joints: usize,
    /// The relaxed program on the working set has no feasible point (Clarabel's certificate):
    /// then neither has the full program, and `x`, `z` are empty.
    pub infeasible: bool,
}

impl WorkingSet {
    /// How the optimum was found, for the result's `solver_status`.
    pub fn words(&self, joints: usize) -> String {
        if self.infeasible {
            format!(
                "PrimalInfeasible; working set: the crushing cones of {} of {joints} joints admit no equilibrium, {} conic solves",
                self.joints, self.rounds
            )
        } else if self.rounds == 0 {
            format!(
                "active set on the crushing laws: {} hinge joints, all {joints} joints checked",
                self.joints
            )
        } else {
            format!(
                "Solved; working set: the crushing cones of {} of {joints} joints, {} conic solves",
                self.joints, self.rounds
            )
        }
    }
}

/// What the check found at a solution: violated joints (cones) and friction rows.
struct Violations {
    joints: Vec<usize>,
    friction_rows: Vec<usize>,
}

/// Of the items `0..len` (skipping those `skip` says), the worst violated one of every run of
/// consecutive violated items, with its neighbours: `violation(i) > tol` is violated.
fn worst_of_runs(
    len: usize,
    skip: impl Fn(usize) -> bool,
    violation: impl Fn(usize) -> f64,
    tol: f64,
) -> Vec<usize> {
    let mut picked = Vec::new();
    let mut run: Option<(usize, f64)> = None;
    let close = |run: &mut Option<(usize, f64)>, picked: &mut Vec<usize>| {
        if let Some((i, _)) = run.take() {
            picked.extend(i.saturating_sub(1)..(i + 2).min(len));
        }
    };
    for i in 0..len {
        let v = if skip(i) {
            f64::NEG_INFINITY
        } else {
            violation(i)
        };
        if v > tol {
            if run.is_none_or(|(_, w)| v > w) {
                run = Some((i, v));
            }
        } else {
            close(&mut run, &mut picked);
        }
    }
    close(&mut run, &mut picked);
    picked
}

/// The most pivots of the curved active-set method before the working set's conic solves take
/// over.
const MAX_PIVOTS: usize = 60;

/// The most Newton steps that put the curved basis rows back on their surfaces.
const MAX_NEWTON: usize = 40;

/// A row of the curved active-set method at `x`: its value `h`, its gradient and the size of
/// its terms (to judge a violation relative to round-off).
#[derive(Clone, Copy)]
struct Curved {
    h: f64,
    grad: [f64; 4],
    size: f64,
}

impl ChainProgram {
    /// Row `i` of the program with crushing at `x`. A no-tension row `g` of joint k (i < 2 nj;
    /// `g` the row of the end force `c = r g`, `h` its partner) becomes the crushing law of
    /// that end, `c - N^2 / (2 kappa) >= 0` with `N = r (g + h)`: the cone
    /// `2 c kappa >= N^2` of [`crate::interaction::crushing`] written as a concave
    /// function of `x`, whose gradient is `r a_g - (r^2 N' / kappa) (a_g + a_h)`. A friction
    /// row stays linear.
    fn curved(&self, i: usize, x: &[f64]) -> Curved {
        let nj = self.kappa.len();
        let (coef, _) = self.dense[i];
        let (g, size) = self.row_value(i, x);
        if i >= 2 * nj {
            return Curved {
                h: g,
                grad: coef,
                size,
            };
        }
        let (r, kappa) = self.kappa[i / 2];
        let partner = i ^ 1;
        let gp = self.row_value(partner, x).0;
        let n = r * (g + gp);
        let quad = n * n / (2.0 * kappa);
        let (cp, _) = self.dense[partner];
        let mut grad = [0.0; 4];
        for c in 0..4 {
            grad[c] = r * coef[c] - (r * n / kappa) * (coef[c] + cp[c]);
        }
        Curved {
            h: r * g - quad,
            grad,
            size: r * size + quad,
        }
    }

    /// The 4 x 4 system of the basis gradients: solve `G d = rhs` (`transpose`: `G^T d = rhs`).
    fn basis_solve(rows: &[Curved; 4], transpose: bool, rhs: [f64; 4]) -> Option<[f64; 4]> {
        super::solve_basis(rows.map(|r| r.grad), transpose, rhs)
    }

    /// The optimum with crushing by a dual active-set method on the curved rows (the crushing
    /// laws of [`Self::curved`], friction rows), started from the rigid optimum's basis: the
    /// basis rows are put on their surfaces by Newton's method (four equations in four
    /// unknowns), their multipliers follow from `objective e_lambda = -sum y_i grad h_i`
    /// (`objective` +1 maximises lambda, -1 minimises it, as in [`Self::active_set`], whose
    /// optimum `rigid` is with the same objective), and while a
    /// row is violated it enters and the ratio test on the multipliers picks the row that
    /// leaves (the dual simplex step on the rows' linearisations). It stops when every row of
    /// every joint holds (to round-off) with non-negative multipliers: the KKT conditions of
    /// a convex program, so the optimum. None when a Newton solve does not converge, a
    /// multiplier turns negative after it, or the pivots run out: the conic working set then
    /// decides.
    fn curved_active_set(&self, rigid: &super::ActiveSet, objective: f64) -> Option<WorkingSet> {
        let nj = self.kappa.len();
        let m = self.dense.len();
        if rigid.duals.len() != 4 {
            return None;
        }
        let mut basis = [0; 4];
        for (b, &(row, _)) in basis.iter_mut().zip(&rigid.duals) {
            *b = row;
        }
        let mut x = [rigid.x[0], rigid.x[1], rigid.x[2], rigid.x[3]];
        let eval = |basis: &[usize; 4], x: &[f64; 4]| basis.map(|i| self.curved(i, x));
        for pivots in 0..MAX_PIVOTS {
            // Newton's method on the basis rows.
            let mut rows = eval(&basis, &x);
            let mut converged = false;
            for _ in 0..MAX_NEWTON {
                if rows.iter().all(|r| r.h.abs() <= 1e-15 * r.size.max(1e-300)) {
                    converged = true;
                    break;
                }
                let d = Self::basis_solve(&rows, false, rows.map(|r| -r.h))?;
                for c in 0..4 {
                    x[c] += d[c];
                }
                let next = eval(&basis, &x);
                // Quadratic rows: once the step is at round-off, so is the residual.
                let small = d
                    .iter()
                    .zip(&x)
                    .all(|(dc, xc)| dc.abs() <= 1e-15 * xc.abs().max(1.0));
                rows = next;
                if small {
                    converged = rows.iter().all(|r| r.h.abs() <= 1e-12 * r.size.max(1e-300));
                    break;
                }
            }
            if !converged {
                return None;
            }
            // Multipliers: objective * e_lambda = -sum y_i grad h_i.
            let y = Self::basis_solve(&rows, true, [-objective, 0.0, 0.0, 0.0])?;
            if y.iter().any(|&v| v < -1e-12) {
                return None;
            }
            // The most violated row, relative to the size of its terms.
            let mut worst: Option<(usize, f64)> = None;
            for i in 0..m {
                if basis.contains(&i) {
                    continue;
                }
                let c = self.curved(i, &x);
                let v = c.h / c.size.max(1e-300);
                if v < -1e-12 && worst.is_none_or(|(_, w)| v < w) {
                    worst = Some((i, v));
                }
            }
            let Some((r, _)) = worst else {
                let mut z = vec![0.0; m];
                for (&i, &yi) in basis.iter().zip(&y) {
                    let yi = yi.max(0.0);
                    if i >= 2 * nj {
                        z[i] += yi;
                        continue;
                    }
                    // y grad h = y (r - r N / kappa) a_g - y (r N / kappa) a_h: the multipliers
                    // of the no-tension rows g and h the mechanism reads.
                    let (rr, kappa) = self.kappa[i / 2];
                    let g = self.row_value(i, &x).0;
                    let gp = self.row_value(i ^ 1, &x).0;
                    let n = rr * (g + gp);
                    z[i] += yi * (rr - rr * n / kappa);
                    z[i ^ 1] -= yi * rr * n / kappa;
                }
                let joints = basis.iter().filter(|&&i| i < 2 * nj).map(|&i| i / 2);
                let mut joints: Vec<usize> = joints.collect();
                joints.sort_unstable();
                joints.dedup();
                return Some(WorkingSet {
                    x: x.to_vec(),
                    z,
                    iterations: (rigid.pivots as usize + pivots) as u32,
                    rounds: 0,
                    joints: joints.len(),
                    infeasible: false,
                });
            };
            // Ratio test: grad h_r = sum w_i grad h_i; y'_i = y_i - t w_i, y'_r = t.
            let w = Self::basis_solve(&rows, true, self.curved(r, &x).grad)?;
            let (l, _) = super::ratio_test(&y, &w)?;
            basis[l] = r;
        }
        None
    }

    /// How far joint `k`'s crushing cones are violated at `x`, in Clarabel's scaled form
    /// `||(c - 1, sqrt2 N / sqrt(kappa))|| - (c + 1)` (positive when violated; it is the
    /// distance the cone's first entry falls short). Negative inside both cones.
    fn cone_violation(&self, k: usize, x: &[f64]) -> f64 {
        let (r, kappa) = self.kappa[k];
        let g2 = self.row_value(2 * k, x).0;
        let g1 = self.row_value(2 * k + 1, x).0;
        let s2 = std::f64::consts::SQRT_2 * r * (g1 + g2) / kappa.sqrt();
        [g2, g1]
            .into_iter()
            .map(|g| (r * g - 1.0).hypot(s2) - (r * g + 1.0))
            .fold(f64::NEG_INFINITY, f64::max)
    }

    /// The check of step 3 (module docs): the joints outside the working set whose cones are
    /// violated, and the friction rows left out that are, by more than `tol`, as the worst of
    /// each run with its neighbours.
    fn violations(&self, x: &[f64], in_set: &[bool], friction_in: &[bool], tol: f64) -> Violations {
        let nj = self.kappa.len();
        let joints = worst_of_runs(nj, |k| in_set[k], |k| self.cone_violation(k, x), tol);
        let first = 2 * nj;
        let nf = self.friction_joints.len();
        let mut friction_rows = Vec::new();
        for side in 0..2 {
            let row = |f: usize| first + 2 * f + side;
            let rows = worst_of_runs(
                nf,
                |f| friction_in[row(f) - first],
                |f| -self.row_value(row(f), x).0,
                tol,
            );
            friction_rows.extend(rows.into_iter().map(row));
        }
        Violations {
            joints,
            friction_rows,
        }
    }

    /// The least multiplier equilibrium allows with crushing, by the curved active set from
    /// the rigid least multiplier's basis; None when either does not finish (the phase-one
    /// program then decides whether the structure stands at lambda = 0).
    pub(super) fn least_lambda_crushing(&self) -> Option<f64> {
        let Outcome::Optimal(rigid) = self.active_set(-1.0, crate::outcome::LAMBDA_CAP) else {
            return None;
        };
        let least = self.curved_active_set(&rigid, -1.0)?.x[0];
        (least.is_finite() && least > -crate::outcome::LAMBDA_CAP * (1.0 - 1e-6)).then_some(least)
    }

    /// The working-set method of the module docs: the optimum, or a proof that no equilibrium
    /// exists. None sends the caller to the program on all joints (the rigid solve did not
    /// finish, a relaxed solve ended otherwise, lambda reached the cap, or the working set
    /// grew too large); `Err` only for a solver setup error.
    pub(super) fn working_set(
        &self,
        model: &Model,
        settings: &crate::statics::StaticSettings,
    ) -> Result<Option<WorkingSet>, crate::error::AnalysisError> {
        let nj = self.kappa.len();
        if nj == 0 || nj != model.assembly.joints.len() {
            return Ok(None);
        }
        let Outcome::Optimal(rigid) = self.active_set(1.0, crate::outcome::LAMBDA_CAP) else {
            return Ok(None);
        };
        if rigid.x[0] >= crate::outcome::LAMBDA_CAP * (1.0 - 1e-6) {
            return Ok(None);
        }
        if let Some(found) = self.curved_active_set(&rigid, 1.0) {
            return Ok(Some(found));
        }
        self.conic_working_set(&rigid, settings)
    }

    /// Steps 2 to 4 of the module docs: Clarabel on the cones of a working set of joints,
    /// seeded by the rigid optimum's basis joints and their neighbours, grown by the check.
    fn conic_working_set(
        &self,
        rigid: &super::ActiveSet,
        settings: &crate::statics::StaticSettings,
    ) -> Result<Option<WorkingSet>, crate::error::AnalysisError> {
        let nj = self.kappa.len();
        let first_friction = 2 * nj;
        let nf = self.friction_joints.len();
        let mut in_set = vec![false; nj];
        let mut friction_in = vec![false; 2 * nf];
        let add_joint = |k: usize, in_set: &mut [bool]| {
            in_set[k.saturating_sub(1)..(k + 2).min(nj)].fill(true);
        };
        for &(row, _) in &rigid.duals {
            if row < first_friction {
                add_joint(row / 2, &mut in_set);
            } else if row < first_friction + 2 * nf {
                friction_in[row - first_friction] = true;
                add_joint(
                    self.friction_joints[(row - first_friction) / 2],
                    &mut in_set,
                );
            }
        }
        // Violations below this are the interior point's own round-off (its feasibility
        // tolerance, on the same scaled rows).
        let tol = 0.1 * settings.tol_feas;
        let mut iterations = 0;
        for round in 1..=MAX_ROUNDS {
            let crush: Vec<usize> = (0..nj).filter(|&k| in_set[k]).collect();
            if crush.len() > MAX_JOINTS {
                return Ok(None);
            }
            let linear: Vec<usize> = (0..2 * nf)
                .filter(|&i| friction_in[i])
                .map(|i| first_friction + i)
                .collect();
            let sol = self.conic_of(&linear, &crush).solve(settings)?;
            iterations += sol.iterations;
            if sol.status == SolverStatus::PrimalInfeasible {
                // No equilibrium satisfies the crushing laws of the working set alone, so
                // none satisfies those of every joint: the structure cannot stand.
                return Ok(Some(WorkingSet {
                    x: Vec::new(),
                    z: Vec::new(),
                    iterations,
                    rounds: round,
                    joints: crush.len(),
                    infeasible: true,
                }));
            }
            if sol.status != SolverStatus::Solved
                || sol.x[0] >= crate::outcome::LAMBDA_CAP * (1.0 - 1e-6)
                || sol.x.iter().any(|v| !v.is_finite())
            {
                return Ok(None);
            }
            let found = self.violations(&sol.x, &in_set, &friction_in, tol);
            if found.joints.is_empty() && found.friction_rows.is_empty() {
                return Ok(Some(WorkingSet {
                    z: self.fold_duals_of(&sol.z, &linear, &crush),
                    x: sol.x,
                    iterations,
                    rounds: round,
                    joints: crush.len(),
                    infeasible: false,
                }));
            }
            for k in found.joints {
                in_set[k] = true;
            }
            for row in found.friction_rows {
                friction_in[row - first_friction] = true;
            }
        }
        Ok(None)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::statics::StaticSettings;

    fn model(n: usize, fc: f64, friction: f64) -> Model {
        let text = format!(
            "[arch]\nshape = \"circular\"\nradius = 5.0\nthickness = 0.75\nvoussoirs = {n}\n\
             [material]\nunit_weight = 20000.0\ncompressive_strength = {fc:e}\nfriction = {friction}\n"
        );
        let scene = crate::scene::Scene::from_toml_str(&text, "test").expect("valid scene");
        crate::scene::build(&scene).expect("valid model")
    }

    /// Clarabel with the cones of every joint, as `analyse_chain` solves it without the
    /// working set.
    fn all_joints(program: &ChainProgram, settings: &StaticSettings) -> f64 {
        let sol = program.conic().solve(settings).expect("solves");
        assert_eq!(sol.status, SolverStatus::Solved);
        sol.x[0]
    }

    #[test]
    fn both_working_sets_equal_the_program_on_all_joints() {
        // The conic working set is the curved active set's fallback, so the analyses rarely
        // reach it: here both run on the same programs.
        let settings = StaticSettings::default();
        for (n, fc, mu) in [
            (16, 1e6, f64::INFINITY),
            (200, 2e7, f64::INFINITY),
            (200, 1e6, f64::INFINITY),
            (1000, 1e6, f64::INFINITY),
            (64, 1e6, 0.4),
        ] {
            let m = model(n, fc, mu);
            for sign in [1.0, -1.0] {
                let program = ChainProgram::new(&m, sign, None);
                let Outcome::Optimal(rigid) = program.active_set(1.0, crate::outcome::LAMBDA_CAP)
                else {
                    panic!("rigid optimum");
                };
                let curved = program.curved_active_set(&rigid, 1.0).expect("certified");
                let conic = program
                    .conic_working_set(&rigid, &settings)
                    .expect("solves")
                    .expect("certified");
                assert!(!conic.infeasible && conic.rounds >= 1);
                let reference = all_joints(&program, &settings);
                let label = format!("n = {n}, fc = {fc:e}, mu = {mu}, sign {sign}");
                assert!((curved.x[0] - reference).abs() <= 1e-9, "{label}");
                assert!((conic.x[0] - reference).abs() <= 1e-9, "{label}");
                assert!(conic.joints < n / 2 + 4, "{label}: {} joints", conic.joints);
                // Both certified optima lie in every joint's cones.
                for x in [&curved.x, &conic.x] {
                    for k in 0..program.kappa.len() {
                        assert!(program.cone_violation(k, x) <= settings.tol_feas, "{label}");
                    }
                }
            }
        }
    }
}
