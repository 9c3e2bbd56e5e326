//! Drawings: the blocks to scale with their thrust line (the points where the resultant
//! crosses each joint, `p_mid + e u` with `e = M/N`, from `crate::assembly::thrust_points`),
//! hinges, loads and mechanism, as SVG (`svg`), and the line charts of studies, sweeps and the
//! assessment (`chart`). Named for what it holds: pictures, not the thrust line itself.

pub mod chart;
pub mod svg;

pub use crate::assembly::thrust_points;
