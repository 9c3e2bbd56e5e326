//! Thrust lines: the points where the resultant crosses each joint (`p_mid + e u`, with
//! `e = M/N`), written as CSV, and drawn with the blocks as SVG (`svg`), and line charts of parametric studies (`chart`).

pub mod chart;
pub mod svg;

pub use crate::assembly::thrust_points;
