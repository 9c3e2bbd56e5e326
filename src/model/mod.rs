//! The structural model an analysis works on: an [`Assembly`] of blocks and joints and the
//! [`LoadCase`] it carries, built from a scene in exactly one place (`crate::scene::build`), or
//! by hand.
//!
//! Data flows one way: scene -> `scene::build` -> [`Model`] -> static / kinematic / DEM
//! analyses -> reports. The analyses never read a scene.

pub mod loads;

pub use loads::{AppliedLoad, LoadCase, LoadSource, SeismicMass, Spread, SpreadLoad, Wrench};

use crate::assembly::{Assembly, JointForce};

/// Blocks and joints with their loads.
#[derive(Debug, Clone)]
pub struct Model {
    pub assembly: Assembly,
    pub loads: LoadCase,
}

impl Model {
    /// An assembly under its self-weight alone (the seed paper's load model).
    pub fn self_weight(assembly: Assembly) -> Model {
        let loads = LoadCase::self_weight(&assembly);
        Model { assembly, loads }
    }

    /// Check the assembly ([`Assembly::validate`]) and its load case against it.
    pub fn validate(&self) -> Result<(), crate::error::AnalysisError> {
        self.assembly.validate()?;
        self.loads.validate(&self.assembly)
    }

    /// The same model mirrored about x = 0.
    pub fn mirrored(&self) -> Model {
        Model {
            assembly: self.assembly.mirrored(),
            loads: self.loads.mirrored(),
        }
    }
}

/// Largest out-of-balance force (N) of any block under joint forces `forces` and the loads
/// of `loads` with the seismic forces times `lambda` in direction `sign` (moments divided by
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
            let s = loads.seismic(i, sign);
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
