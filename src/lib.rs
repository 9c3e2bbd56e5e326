//! voussoir: the seismic collapse multiplier of masonry arches and portals (static lower
//! bound, kinematic upper bound, DEM), the library behind the `voussoir` command line, the
//! Python package and the page of `voussoir serve` (docs/architecture.md).

// No unsafe code anywhere in the crate, and none can be added without removing this line.
#![forbid(unsafe_code)]

pub mod analysis;
pub mod assembly;
pub mod assess;
pub mod blocks;
pub mod convergence;
pub mod dem;
pub mod dem_settings;
pub mod dossier;
pub mod drawing;
pub mod error;
pub mod fragility;
pub mod geometry;
pub mod hazard;
pub mod interaction;
pub mod kinematic;
pub mod model;
pub mod outcome;
pub mod overrides;
pub mod records;
pub mod report;
pub mod retrofit;
pub mod roll;
pub mod sampling;
pub mod scene;
#[cfg(feature = "serve")]
pub mod serve;
pub mod spectrum;
pub mod statics;
pub mod study;
pub mod sweep;
pub mod thickness;
pub mod validation;
