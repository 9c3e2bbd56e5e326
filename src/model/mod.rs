//! The structural model an analysis works on: an [`Assembly`] of blocks and joints and the
//! [`LoadCase`] it carries, built from a scene in exactly one place ([`build`]).
//!
//! Data flows one way: scene -> [`build`] -> [`Model`] -> static / kinematic / DEM analyses ->
//! reports. The analyses never read a scene.

mod build;
pub mod loads;

pub use build::build;
pub use loads::{AppliedLoad, LoadCase, LoadSource, SeismicMass, Wrench};

use crate::assembly::Assembly;

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

    /// The same model mirrored about x = 0.
    pub fn mirrored(&self) -> Model {
        Model {
            assembly: self.assembly.mirrored(),
            loads: self.loads.mirrored(),
        }
    }
}
