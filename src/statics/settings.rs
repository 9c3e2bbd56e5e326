//! Settings of the static analysis, gathered in one struct with documented defaults and
//! checked by [`StaticSettings::validate`] where an analysis of a scene starts
//! (`crate::analysis::analyse` and `crate::thickness::analyse`, which the CLI, Python and the
//! page's server call). The program itself ([`crate::statics::analyse`]) takes any tolerance, so
//! the convergence study can measure what a looser one costs in accuracy.

use crate::error::AnalysisError;
pub use crate::outcome::Direction;

/// The range of the solver tolerances (`tol_gap`, `tol_feas`): looser solutions are not safe
/// (lambda may exceed the collapse multiplier), tighter ones are below what double precision
/// gives the interior point.
pub const TOLERANCE_RANGE: (f64, f64) = (1e-14, 1e-6);

/// Settings of the static (lower-bound) conic program.
#[derive(Debug, Clone)]
pub struct StaticSettings {
    /// Direction of the seismic load. Default: right (+x).
    pub direction: Direction,
    /// Clarabel's absolute and relative duality-gap tolerance. Default 1e-10: the program is
    /// made dimensionless (lengths by the structure's size, forces by its weight), so this is
    /// a relative accuracy on lambda.
    pub tol_gap: f64,
    /// Clarabel's primal/dual feasibility tolerance (dimensionless). Default 1e-10, which
    /// keeps the equilibrium residual near 1e-10 of the total weight.
    pub tol_feas: f64,
    /// Clarabel's iteration limit. Default 200.
    pub max_iter: u32,
    /// A joint is a hinge when its resultant lies within `hinge_tolerance * L` of an end
    /// (L = joint length), and slides when `|V| >= (1 - hinge_tolerance) mu N`. Default 1e-6.
    pub hinge_tolerance: f64,
    /// Clarabel's sparse LDL factorisation: "qdldl", the only one built in. Clarabel's
    /// optional faer LDL was measured within the noise of qdldl on semicircles of 16 to 2000
    /// voussoirs and cost a quarter of the clean build, so voussoir no longer builds it
    /// (issue 28; docs/performance.md).
    pub linear_solver: String,
    /// Which static program [`crate::statics::analyse`] solves. Default [`Program::Auto`].
    pub program: Program,
    /// Solve the chain program by its active-set method first (exact, and 20 to 80 times
    /// faster than the interior point); the interior point runs when it does not finish.
    /// Default true; false runs the interior point alone (for cross-checks).
    pub active_set: bool,
    /// With finite compressive strength, solve the chain program by its working set
    /// (`statics::chain`'s `working_set`: the crushing cones of the rigid hinges and the
    /// joints found violated, checked at every joint, so the same optimum); the program on
    /// all joints when it does not finish. Default true; false solves the chain program with
    /// the cones of every joint directly (as before issue 28, for cross-checks).
    pub working_set: bool,
    /// Clarabel's iterative refinement of each KKT solve. Default [`Refinement::Auto`].
    pub refinement: Refinement,
}

/// When Clarabel refines its KKT solves (docs/performance.md, "Large assemblies").
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Refinement {
    /// Off for a program whose KKT matrix (variables plus constraints) has at least
    /// [`LARGE_KKT`] rows, with the solve repeated with it on when the first does not end
    /// solved or infeasible; on (Clarabel's default) below. The refinement only polishes the
    /// search directions: the stopping tests, and so the accuracy of the answer, are the same
    /// either way; on the running-bond walls of 1,008 and 10,050 blocks it was 29 to 39 % of
    /// the CPU time.
    #[default]
    Auto,
    /// Always on (Clarabel's default; every program as before issue 28's item 4).
    Always,
}

/// The size of KKT matrix (variables plus constraints) from which [`Refinement::Auto`] turns
/// the iterative refinement off: below the 1,008-block running-bond wall's 23,528, above the
/// full program of a 2,000-voussoir arch (20,008; long chains near their minimum thickness are
/// the nearly degenerate programs the refinement is kept for) and every static program of the
/// test suite but the two tests of this rule (at most 8,199).
pub const LARGE_KKT: usize = 22_000;

/// The static program to solve.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Program {
    /// The reduced program for chains ([`crate::statics::analyse_chain`], four unknowns, with its
    /// exact vertex step), the full one for any other assembly.
    #[default]
    Auto,
    /// The full program: three unknowns per joint, three equilibrium rows per block.
    Full,
}

impl Default for StaticSettings {
    fn default() -> Self {
        StaticSettings {
            direction: Direction::Right,
            tol_gap: 1e-10,
            tol_feas: 1e-10,
            max_iter: 200,
            hinge_tolerance: 1e-6,
            linear_solver: "qdldl".to_string(),
            program: Program::Auto,
            active_set: true,
            working_set: true,
            refinement: Refinement::Auto,
        }
    }
}

impl StaticSettings {
    pub fn direction(mut self, d: Direction) -> Self {
        self.direction = d;
        self
    }
    /// Set the solver tolerances, and widen the hinge tolerance with them: a solution
    /// accurate to `tol` only locates a resultant at a joint's end to about `tol`.
    pub fn tolerance(mut self, tol: f64) -> Self {
        self.tol_gap = tol;
        self.tol_feas = tol;
        self.hinge_tolerance = self.hinge_tolerance.max(100.0 * tol);
        self
    }
    pub fn active_set(mut self, on: bool) -> Self {
        self.active_set = on;
        self
    }
    pub fn working_set(mut self, on: bool) -> Self {
        self.working_set = on;
        self
    }
    pub fn program(mut self, program: Program) -> Self {
        self.program = program;
        self
    }
    pub fn hinge_tolerance(mut self, tol: f64) -> Self {
        self.hinge_tolerance = tol;
        self
    }

    /// Check every setting, naming the one out of range and what it may be.
    pub fn validate(&self) -> Result<(), AnalysisError> {
        let bad = |setting: &str, value: String, allowed: &str| {
            Err(AnalysisError::Settings {
                setting: setting.to_string(),
                value,
                allowed: allowed.to_string(),
            })
        };
        let (lo, hi) = TOLERANCE_RANGE;
        for (name, tol) in [("tol_gap", self.tol_gap), ("tol_feas", self.tol_feas)] {
            if !(tol.is_finite() && (lo..=hi).contains(&tol)) {
                return bad(
                    &format!("tolerance (the static program's {name})"),
                    tol.to_string(),
                    "from 1e-14 to 1e-6 (looser solutions are not safe: lambda may exceed the collapse multiplier)",
                );
            }
        }
        if self.max_iter == 0 {
            return bad("static max_iter", "0".into(), "at least 1");
        }
        if !(self.hinge_tolerance.is_finite()
            && self.hinge_tolerance > 0.0
            && self.hinge_tolerance <= 0.1)
        {
            return bad(
                "static hinge_tolerance",
                self.hinge_tolerance.to_string(),
                "a number > 0 and at most 0.1 (a fraction of the joint length)",
            );
        }
        if self.linear_solver != "qdldl" {
            return bad(
                "static linear_solver",
                format!("\"{}\"", self.linear_solver),
                "\"qdldl\" (Clarabel's faer LDL is not built in: it measured no faster)",
            );
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn defaults_validate_and_out_of_range_settings_are_named() {
        assert!(StaticSettings::default().validate().is_ok());
        assert!(StaticSettings::default()
            .tolerance(1e-14)
            .validate()
            .is_ok());
        assert!(StaticSettings::default().tolerance(1e-6).validate().is_ok());
        for tol in [1e-5, 1e-15, f64::NAN, f64::INFINITY, 0.0, -1e-10] {
            let e = StaticSettings::default()
                .tolerance(tol)
                .validate()
                .expect_err("refused")
                .to_string();
            assert!(
                e.contains("tolerance") && e.contains("1e-14 to 1e-6"),
                "{e}"
            );
        }
        let s = StaticSettings {
            linear_solver: "mumps".into(),
            ..StaticSettings::default()
        };
        let e = s.validate().expect_err("refused").to_string();
        assert!(
            e.contains("linear_solver") && e.contains("\"mumps\""),
            "{e}"
        );
        // Clarabel's faer LDL is no longer built in (issue 28): asking for it says so.
        let s = StaticSettings {
            linear_solver: "faer".into(),
            ..StaticSettings::default()
        };
        let e = s.validate().expect_err("refused").to_string();
        assert!(e.contains("\"faer\"") && e.contains("not built in"), "{e}");
        let e = StaticSettings::default()
            .hinge_tolerance(0.5)
            .validate()
            .expect_err("refused")
            .to_string();
        assert!(e.contains("hinge_tolerance"), "{e}");
    }
}
