//! The smallest capacities of tie rods and bonded strips that give a target multiplier: a
//! linear (conic, with crushing) program, the static program with each designed element's
//! capacity an unknown `C_i >= 0` (a tie's tension `P_i <= T_i <= C_i`; a strip's tension
//! `0 <= S_ij <= C_i` at every joint j it crosses, one capacity per `[[reinforcements]]`
//! entry), lambda fixed at the target in every direction asked for (one copy of the
//! equilibrium and joint unknowns per direction, the capacities shared), minimising
//! `sum cost_i C_i`.
//!
//! By the static theorem every feasible point is a set of capacities with which the structure
//! carries the target in each direction (lambda_c >= target), and the optimum is the cheapest
//! such set; at the optimum no positive capacity can be lowered alone (the cost would drop),
//! so each needed element is needed at the value found. When the target cannot be reached with
//! any capacities the program is infeasible; [`best_reachable`] then gives the largest
//! multiplier that capacities without bound reach in every direction.

use super::problem::{program_rows, DesignColumns, StaticProblem};
use super::{run, StaticSettings, LAMBDA_CAP};
use crate::error::AnalysisError;
use crate::interaction::Rows;
use crate::model::Model;
use clarabel::solver::SolverStatus;

/// What a design sizes: a tie, or every joint a bonded strip crosses (one capacity).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Element {
    /// Index in `Model::ties`.
    Tie(usize),
    /// Index of the `[[reinforcements]]` entry (`Strip::source`): its strips at every joint
    /// it crosses share the one capacity.
    Strip(usize),
}

/// An element whose capacity is designed, and its cost per newton of capacity.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Designed {
    pub element: Element,
    pub cost: f64,
}

/// The outcome of a design.
#[derive(Debug, Clone, PartialEq)]
pub enum Design {
    /// The least capacities (N), one per designed element, in their order.
    Capacities(Vec<f64>),
    /// No capacities reach the target.
    Infeasible,
}

/// The program of a design over the directions `signs`, with `objective` choosing what is
/// minimised: the cost of the capacities at lambda = `target`, or `-lambda` (target None).
/// Columns: 0 lambda, 1..=d the capacities over the force scale, then each direction's own.
fn program(
    model: &Model,
    designed: &[Designed],
    signs: &[f64],
    target: Option<f64>,
) -> (StaticProblem, usize) {
    let (assembly, loads) = (&model.assembly, &model.loads);
    let fs = loads.force_scale();
    let d = designed.len();
    let mut all = Rows::new(assembly, fs, false);
    all.add_columns(d);
    let mut ties = vec![None; model.ties.len()];
    let mut strips = vec![None; model.strips.len()];
    for (i, t) in designed.iter().enumerate() {
        match t.element {
            Element::Tie(k) => ties[k] = Some(1 + i),
            Element::Strip(source) => {
                for (s, column) in model.strips.iter().zip(strips.iter_mut()) {
                    if s.source == source {
                        *column = Some(1 + i);
                    }
                }
            }
        }
    }
    let design = DesignColumns {
        ties: &ties,
        strips: &strips,
    };
    for &sign in signs {
        let mut rows = Rows::new(assembly, fs, false);
        rows.add_columns(d);
        program_rows(
            assembly,
            loads,
            model.strength,
            &model.ties,
            &model.strips,
            &model.passive,
            sign,
            design,
            crate::interaction::contact::ShearLimit::Coulomb,
            &mut rows,
        );
        all.append_copy(rows, 1 + d);
    }
    // The capacities are >= 0.
    for i in 0..d {
        all.nonnegative(vec![(1 + i, -1.0)], 0.0, false);
    }
    let mut q = vec![0.0; all.columns()];
    match target {
        Some(t) => {
            all.fix_column(0, t);
            for (i, dt) in designed.iter().enumerate() {
                q[1 + i] = dt.cost;
            }
        }
        None => {
            all.nonnegative(vec![(0, 1.0)], LAMBDA_CAP, false);
            q[0] = -1.0;
        }
    }
    (
        StaticProblem::assemble_with(all, q, Vec::new(), Vec::new()),
        d,
    )
}

/// The least-cost capacities of the `designed` ties and strips (the others keep theirs) for which the
/// static program carries lambda = `target` toward every sign of `signs`.
pub fn smallest_capacities(
    model: &Model,
    designed: &[Designed],
    target: f64,
    signs: &[f64],
    settings: &StaticSettings,
) -> Result<Design, AnalysisError> {
    model.validate()?;
    let (p, d) = program(model, designed, signs, Some(target));
    let sol = run(&p, settings)?;
    match sol.status {
        SolverStatus::Solved | SolverStatus::AlmostSolved => Ok(Design::Capacities(
            (0..d)
                .map(|i| sol.x[1 + i].max(0.0) * p.force_scale)
                .collect(),
        )),
        SolverStatus::PrimalInfeasible | SolverStatus::AlmostPrimalInfeasible => {
            Ok(Design::Infeasible)
        }
        other => Err(AnalysisError::SolverFailed {
            status: format!("{other:?} (retrofit design)"),
            iterations: sol.iterations,
        }),
    }
}

/// The largest multiplier the static program carries toward every sign of `signs` when the
/// `designed` ties and strips may take any capacity (at most [`LAMBDA_CAP`]); None when the structure
/// cannot stand.
pub fn best_reachable(
    model: &Model,
    designed: &[Designed],
    signs: &[f64],
    settings: &StaticSettings,
) -> Result<Option<f64>, AnalysisError> {
    model.validate()?;
    let (p, _) = program(model, designed, signs, None);
    let sol = run(&p, settings)?;
    match sol.status {
        SolverStatus::Solved | SolverStatus::AlmostSolved => Ok(Some(sol.x[0])),
        SolverStatus::PrimalInfeasible | SolverStatus::AlmostPrimalInfeasible => Ok(None),
        other => Err(AnalysisError::SolverFailed {
            status: format!("{other:?} (best reachable multiplier)"),
            iterations: sol.iterations,
        }),
    }
}
