//! What the CLI prints, one file per format: the JSON contract ([`json`]), the thrust-line
//! CSV ([`csv`]), the human summaries and titles ([`summary`]) and the animation of a dynamic
//! run ([`animation`]).

pub mod animation;
pub mod assessment;
pub mod csv;
pub mod json;
pub mod summary;

pub use self::csv::write_thrust_csv;
pub use crate::geometry::trim;
pub use json::*;
pub use summary::*;
