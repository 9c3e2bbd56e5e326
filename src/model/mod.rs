//! The structural model an analysis works on: an [`Assembly`] of blocks and joints and the
//! [`LoadCase`] it carries, built from a scene in exactly one place (`crate::scene::build`), or
//! by hand.
//!
//! Data flows one way: scene -> `scene::build` -> [`Model`] -> static / kinematic / DEM
//! analyses -> reports. The analyses never read a scene.

pub mod action;
pub mod loads;

pub use action::Action;
pub use loads::{AppliedLoad, LoadCase, LoadSource, SeismicMass, Spread, SpreadLoad, Wrench};

use crate::assembly::{Assembly, JointForce};

/// Blocks and joints with their loads.
#[derive(Debug, Clone)]
pub struct Model {
    pub assembly: Assembly,
    pub loads: LoadCase,
    /// Compressive strength of the joints ([`Strength::rigid`] is Heyman's infinite strength).
    pub strength: Strength,
}

/// Finite compressive strength of the joints: a rectangular stress block of intensity `fc`
/// over the out-of-plane depth `d` (RING's crushing model; Gilbert, 2007). A joint of length
/// `L` then carries a resultant `N` at eccentricity `e` from its midpoint only if
/// `N <= fc d L` and `|N e| <= N L/2 - N^2/(2 fc d)`: the compressed zone `a = N/(fc d)` lies
/// inside the joint, and the resultant at its centre, `a/2` from the joint's end.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Strength {
    /// Compressive strength fc (Pa); `f64::INFINITY` for rigid (uncrushable) joints.
    pub compressive: f64,
    /// Out-of-plane depth d (m) over which the stress block acts.
    pub depth: f64,
}

impl Strength {
    /// Infinite compressive strength (Heyman's assumption).
    pub fn rigid() -> Strength {
        Strength {
            compressive: f64::INFINITY,
            depth: 1.0,
        }
    }

    /// Whether the strength is finite (the static program then has second-order cones).
    pub fn is_finite(&self) -> bool {
        self.compressive.is_finite()
    }

    /// The force per unit joint length a fully compressed joint carries, `fc d` (N/m);
    /// infinite for rigid joints.
    pub fn line_capacity(&self) -> f64 {
        self.compressive * self.depth
    }

    /// Width `a = N/(fc d)` of the compressed zone under a resultant `n` (m); 0 when rigid.
    pub fn compressed_zone(&self, n: f64) -> f64 {
        if self.is_finite() {
            n.max(0.0) / self.line_capacity()
        } else {
            0.0
        }
    }
}

impl Default for Strength {
    fn default() -> Self {
        Strength::rigid()
    }
}

impl Model {
    /// An assembly under its self-weight alone (the seed paper's load model).
    pub fn self_weight(assembly: Assembly) -> Model {
        let loads = LoadCase::self_weight(&assembly);
        Model {
            assembly,
            loads,
            strength: Strength::rigid(),
        }
    }

    /// The same model with joints of compressive strength `strength`.
    pub fn with_strength(mut self, strength: Strength) -> Model {
        self.strength = strength;
        self
    }

    /// Check the assembly ([`Assembly::validate`]) and its load case against it.
    pub fn validate(&self) -> Result<(), crate::error::AnalysisError> {
        self.assembly.validate()?;
        self.loads.validate(&self.assembly)?;
        let s = &self.strength;
        if s.compressive.is_nan() || s.compressive <= 0.0 || !(s.depth.is_finite() && s.depth > 0.0)
        {
            return Err(crate::error::AnalysisError::Other(format!(
                "compressive strength {} Pa over depth {} m: the strength must be > 0 (inf for \
                 rigid joints) and the depth a finite number > 0",
                s.compressive, s.depth
            )));
        }
        Ok(())
    }

    /// The same model mirrored about x = 0.
    pub fn mirrored(&self) -> Model {
        Model {
            assembly: self.assembly.mirrored(),
            loads: self.loads.mirrored(),
            strength: self.strength,
        }
    }
}

/// Largest out-of-balance force (N) of any block under joint forces `forces` and the loads
/// of `loads` with the action times `lambda` (seismic forces in direction `sign`) (moments divided by
/// the structure's size so they are forces too).
pub fn equilibrium_residual(
    assembly: &Assembly,
    loads: &LoadCase,
    forces: &[JointForce],
    lambda: f64,
    sign: f64,
) -> f64 {
    let size = assembly.size();
    let mut res: Vec<[f64; 3]> = (0..assembly.blocks.len())
        .map(|i| {
            let p = loads.permanent(i);
            let s = loads.variable(i, sign);
            [
                p.force.x + lambda * s.force.x,
                p.force.y + lambda * s.force.y,
                (p.moment + lambda * s.moment) / size,
            ]
        })
        .collect();
    for (jt, f) in assembly.joints.iter().zip(forces) {
        let force = f.n * jt.normal() + f.v * jt.tangent();
        let mid = jt.midpoint();
        for (side, s) in [(jt.to, 1.0), (jt.from, -1.0)] {
            if let Some(b) = side {
                let g = loads.reference(b);
                res[b][0] += s * force.x;
                res[b][1] += s * force.y;
                // The couple of a resultant offset toward p2 turns clockwise: u x n = -1.
                res[b][2] += s * (crate::geometry::cross(mid - g, force) - f.m) / size;
            }
        }
    }
    res.iter()
        .flat_map(|r| r.iter())
        .fold(0.0_f64, |acc, x| acc.max(x.abs()))
}
