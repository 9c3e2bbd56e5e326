//! The non-associative iteration's programs on a chain (issue 25, docs/friction.md) by the
//! active-set method instead of the full conic program.
//!
//! Each program of the iteration of Gilbert, Casapulla & Ahmed (2006) is the static program
//! with every Coulomb row `mu N -+ V >= 0` replaced by a fixed capacity `S_j -+ V >= 0`
//! (`interaction::contact::ShearLimit::Fixed`). On a chain the shear `V` of every joint is
//! affine in the four unknowns `[lambda, H, V, M0]` ([`super`]), so the fixed rows are the
//! same half-planes as the rigid chain's, with a constant right-hand side: the chain program
//! keeps its structure, and its dual active set (exact, one 4 x 4 solve and one scan of the
//! rows per pivot) solves it. Only the constants of the friction rows change from one
//! iteration to the next ([`FixedShearChain::solve`] updates them in place).
//!
//! The three programs the iteration asks for, each the full program's on the same model:
//!
//! - the largest multiplier with the capacities (`Objective::MaxLambda`, capped at
//!   [`LAMBDA_CAP`]): the active set's optimum, an exact vertex; its duals are the mechanism,
//!   whose friction duals are slips without opening (`friction_direction`);
//! - the equilibrium of least friction capacity `sum mu N` at a multiplier fixed a hair below
//!   that one (`Objective::LeastFriction`): the multiplier's column folded into the rows'
//!   constants, and `sum mu N`, linear in `H, V` (`N_j = F_j . n_j`), minimised by the active
//!   set with that gradient ([`ChainProgram::gradient_active_set`]);
//! - the most central equilibrium under the permanent loads, the start `at_rest`
//!   (`Objective::MinTension`, the phase-one program: the least `tau` with every no-tension
//!   and Coulomb row relaxed by `+ tau`, in units of the force scale, and `tau >= -1`):
//!   `tau` is a fifth unknown, carried by the active set's extra column (the one a tie's
//!   tension takes), and lambda is 0.
//!
//! Where the active set does not decide (a singular basis, the artificial box binding, the
//! iterations running out) the caller solves the full program, as [`super::analyse_chain`]
//! does; the models it does not take (not a chain, crushing, ties, strips, passive
//! resistance) go to the full program from the start ([`FixedShearChain::new`]). The
//! optimum of a linear program is unique in its multiplier, so each program's multiplier is
//! the full program's (checked on a grid of capacities in `tests/it/non_associative.rs`);
//! where an optimal face holds several equilibria the active set returns a vertex of it,
//! the interior point a point inside, and the next capacities can differ.

use super::{declines, fixed_capacity, ActiveSet, ChainProgram, Outcome, Warm};
use crate::assembly::JointForce;
use crate::model::Model;
use crate::outcome::LAMBDA_CAP;
use crate::statics::{Program, StaticResult, StaticSettings};
use std::time::Instant;

/// A chain program with fixed shear capacities, kept from one iteration to the next.
#[derive(Clone)]
pub(in crate::statics) struct FixedShearChain {
    program: ChainProgram,
    /// The first friction row in the program's rows.
    first: usize,
    /// Per friction row (two per joint with finite friction), its constant with a zero
    /// capacity.
    base: Vec<f64>,
    /// The last optimal bases of the largest-multiplier and the least-friction programs:
    /// only the constants change between iterations, so each stays dual feasible and the
    /// next solve starts from it.
    warm: Option<Warm>,
    warm_least: Option<Warm>,
}

/// The dual active set maximising `objective lambda + gradient . (H', V', M0')` on `p` (no
/// ties), from `warm` when given and from the artificial box when that does not finish.
fn solve_warm(p: &ChainProgram, cap: f64, gradient: [f64; 3], warm: &mut Option<Warm>) -> Outcome {
    let solve = |from: Option<&Warm>| p.gradient_active_set(1.0, cap, 0.0, gradient, from);
    // A warm solve that decides stands; one that fails is done again from the box.
    let found = warm
        .as_ref()
        .map(|w| solve(Some(w)))
        .filter(|found| matches!(found, Outcome::Optimal(_) | Outcome::Infeasible { .. }))
        .unwrap_or_else(|| solve(None));
    *warm = match &found {
        Outcome::Optimal(a) => Some(a.warm.clone()),
        _ => None,
    };
    found
}

/// One program of the iteration solved on the chain: its multiplier, the joint forces of the
/// equilibrium the iteration reads, and the result (forces, hinges, mechanism).
pub(in crate::statics) struct FixedShearSolution {
    pub lambda: f64,
    pub forces: Vec<JointForce>,
    pub result: StaticResult,
}

/// The upper bound of the phase-one program's `tau`, an artificial row that never binds (the
/// least `tau` is at most 1 for any equilibrium that exists; `tau >= -1` is the program's own).
const TAU_BOX: f64 = 1e6;

impl FixedShearChain {
    /// The chain program of `model` with fixed capacities, or None when the active set does
    /// not take it: not a chain, crushing (the program is conic), ties or strips (left to the
    /// full program, whose rows for them are not repeated here), or `settings` asking for the
    /// full program or no active set.
    pub fn new(model: &Model, settings: &StaticSettings) -> Option<FixedShearChain> {
        let plain =
            model.strength.is_finite() || !model.ties.is_empty() || !model.strips.is_empty();
        if settings.program != Program::Auto || !settings.active_set || plain {
            return None;
        }
        if declines(model).is_some() {
            return None;
        }
        let zero = vec![0.0; model.assembly.joints.len()];
        let sign = settings.direction.sign();
        let program = ChainProgram::with_capacities(model, sign, None, Some(&zero));
        let first = 2 * program.sums.len();
        let rows = 2 * program.friction_joints.len();
        let base = program.dense[first..first + rows]
            .iter()
            .map(|r| r.1)
            .collect();
        Some(FixedShearChain {
            program,
            first,
            base,
            warm: None,
            warm_least: None,
        })
    }

    /// Put `capacity` (N, joint order) into the friction rows' constants.
    fn set_capacities(&mut self, capacity: &[f64]) {
        let fs = self.program.force_scale;
        for (f, &k) in self.program.friction_joints.iter().enumerate() {
            let s = fixed_capacity(capacity, k) / fs;
            for side in 0..2 {
                let i = 2 * f + side;
                self.program.dense[self.first + i].1 = self.base[i] + s;
            }
        }
    }

    /// The largest multiplier with the shear capacities `capacity` and, with
    /// `least_friction`, the equilibrium of least `sum mu N` a hair below it. `Some(None)`:
    /// no multiplier has equilibrium with these capacities (a Farkas certificate); None: the
    /// active set did not decide, and the full program should.
    pub fn solve(
        &mut self,
        model: &Model,
        settings: &StaticSettings,
        capacity: &[f64],
        least_friction: bool,
    ) -> Option<Option<FixedShearSolution>> {
        let start = Instant::now();
        self.set_capacities(capacity);
        let found = solve_warm(&self.program, LAMBDA_CAP, [0.0; 3], &mut self.warm);
        let ActiveSet {
            x, duals, pivots, ..
        } = match found {
            Outcome::Optimal(a) => a,
            Outcome::Infeasible { .. } => return Some(None),
            Outcome::Failed => return None,
        };
        let lambda = x[0];
        if !lambda.is_finite() {
            return None;
        }
        let mut pivots = pivots;
        // As the full program's second program: the multiplier 1e-9 (relative) below.
        let point = if least_friction {
            let below = lambda - 1e-9 * lambda.abs().max(1.0);
            let least = self.least_friction(model, below)?;
            pivots += least.pivots;
            least.x
        } else {
            x
        };
        let p = &self.program;
        let mut z = vec![0.0; p.dense.len()];
        for (i, y) in duals {
            z[i] = y;
        }
        let sign = settings.direction.sign();
        let (forces, ties, strips) = p.forces(model, &point);
        let residual = model.equilibrium_residual(&forces, &ties, &strips, point[0], sign);
        let status = "active set; exact vertex (fixed shear capacities)".to_string();
        let unsolved = StaticResult::unsolved(settings, pivots, status, p.size());
        let mut result =
            unsolved.read_iterate(model, settings, lambda, forces.clone(), residual, || {
                p.mechanism(&model.assembly, &model.loads, sign, &z)
            });
        result.exact_vertex = true;
        result.solve_time_s = start.elapsed().as_secs_f64();
        Some(Some(FixedShearSolution {
            lambda,
            forces,
            result,
        }))
    }

    /// The equilibrium with the least `sum mu N` over the joints with finite friction at the
    /// multiplier `lambda` (the capacities already set): lambda folded into the constants
    /// (its column then zero, the cap row `lambda <= lambda` fixes it), and the gradient of
    /// `-sum mu N` in `H', V'` (`N_j = F_j . n_j`; M0 moves no normal force).
    fn least_friction(&mut self, model: &Model, lambda: f64) -> Option<ActiveSet> {
        let mut p = self.program.clone();
        for (coef, c) in &mut p.dense {
            *c += coef[0] * lambda;
            coef[0] = 0.0;
        }
        // N / fs = n . (H', V') + constants, so d(sum mu N / fs) = sum mu n.
        let mut gradient = [0.0; 3];
        for &k in &p.friction_joints {
            let jt = &model.assembly.joints[k];
            let n = jt.normal();
            gradient[0] -= jt.friction * n.x;
            gradient[1] -= jt.friction * n.y;
        }
        solve_warm(&p, lambda, gradient, &mut self.warm_least).optimal()
    }

    /// The normal forces (N, joint order) of the phase-one program's equilibrium at lambda =
    /// 0 (see the module docs): `Some(Some(n))` when the chain stands (`tau <= 0`),
    /// `Some(None)` when it does not, None when the active set does not decide.
    pub fn at_rest(model: &Model) -> Option<Option<Vec<f64>>> {
        let mut p = ChainProgram::new(model, 1.0, None);
        let nj = p.sums.len();
        let ls = p.length_scale;
        // tau's coefficient: the no-tension rows hold `c L / ls` (c the end force over the
        // force scale), the Coulomb rows `mu N -+ V` over the force scale.
        let mut tau = Vec::with_capacity(p.dense.len() + 2);
        for jt in &model.assembly.joints[..nj] {
            tau.push(jt.length() / ls);
            tau.push(jt.length() / ls);
        }
        tau.resize(p.dense.len(), 1.0);
        for (coef, _) in &mut p.dense {
            coef[0] = 0.0;
        }
        // `TAU_BOX - tau >= 0`, then `tau + 1 >= 0` (the layout of a tie's two bounds).
        p.dense.push(([0.0; 4], TAU_BOX));
        tau.push(-1.0);
        p.dense.push(([0.0; 4], 1.0));
        tau.push(1.0);
        p.rows = p.dense.len();
        p.ties = 1;
        p.tie_coef = tau;
        p.tie_sums = vec![[0.0; 3]; nj];
        // Maximise lambda - tau with lambda <= 0 and lambda in no other row: lambda = 0.
        let x = match p.weighted_active_set(1.0, 0.0, 1.0) {
            Outcome::Optimal(a) => a.x,
            _ => return None,
        };
        if !x.iter().all(|v| v.is_finite()) {
            return None;
        }
        if x[4] > 0.0 {
            return Some(None);
        }
        let (forces, _, _) = p.forces(model, &x);
        Some(Some(forces.iter().map(|f| f.n).collect()))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::{build, Scene};

    /// The warm start (the last optimal basis, the friction rows' constants changed) reaches
    /// the multiplier of a start from the artificial box: on a semicircle that slides at a
    /// springing, capacities scaled up and down from the associative normal forces, unevenly
    /// joint by joint, solved in turn from one program and each afresh. The warm solves take
    /// fewer pivots in all.
    #[test]
    fn a_warm_start_reaches_the_cold_optimum() {
        let text = "[arch]\nshape = \"circular\"\nradius = 1.0\nthickness = 0.25\nvoussoirs = 40\n[material]\nfriction = 0.4\n";
        let model = build(&Scene::from_toml_str(text, "test").expect("scene")).expect("model");
        let settings = StaticSettings::default();
        let associative = crate::statics::analyse(&model, &settings).expect("static program");
        let n: Vec<f64> = associative
            .forces
            .expect("collapse forces")
            .iter()
            .map(|f| f.n)
            .collect();
        let mut warm = FixedShearChain::new(&model, &settings).expect("a chain");
        let (mut warm_pivots, mut cold_pivots, mut infeasible) = (0, 0, 0);
        for (i, scale) in [1.0, 0.9, 1.1, 0.7, 1.3, 0.5, 1.0].into_iter().enumerate() {
            let capacity: Vec<f64> = n
                .iter()
                .enumerate()
                .map(|(k, n)| 0.4 * n * scale * (1.0 + 0.05 * ((k + i) % 3) as f64))
                .collect();
            let mut cold = FixedShearChain::new(&model, &settings).expect("a chain");
            for least in [false, true] {
                let w = warm.solve(&model, &settings, &capacity, least);
                let c = cold.solve(&model, &settings, &capacity, least);
                let (w, c) = match (w, c) {
                    (Some(Some(w)), Some(Some(c))) => (w, c),
                    // No multiplier has equilibrium with these capacities: both say so.
                    (Some(None), Some(None)) => {
                        infeasible += 1;
                        continue;
                    }
                    (w, c) => panic!(
                        "scale {scale}, least {least}: warm {:?}, cold {:?}",
                        w.map(|s| s.map(|s| s.lambda)),
                        c.map(|s| s.map(|s| s.lambda))
                    ),
                };
                let scale_n = c.forces.iter().fold(0.0_f64, |a, f| a.max(f.n));
                assert!(
                    (w.lambda - c.lambda).abs() <= 1e-12 * c.lambda.abs().max(1.0),
                    "scale {scale}, least {least}: warm {} cold {}",
                    w.lambda,
                    c.lambda
                );
                for (fw, fc) in w.forces.iter().zip(&c.forces) {
                    assert!((fw.n - fc.n).abs() <= 1e-9 * scale_n, "{fw:?} vs {fc:?}");
                }
                if i > 0 {
                    warm_pivots += w.result.iterations;
                    cold_pivots += c.result.iterations;
                }
            }
        }
        println!("warm {warm_pivots} pivots, cold {cold_pivots}, {infeasible} infeasible");
        assert!(infeasible <= 4, "{infeasible} of 14 programs infeasible");
        assert!(
            warm_pivots < cold_pivots,
            "warm {warm_pivots} pivots, cold {cold_pivots}"
        );
    }
}
