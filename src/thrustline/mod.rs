//! Thrust lines: the points where the resultant crosses each joint (`p_mid + e u`, with
//! `e = M/N`), written as CSV, and drawn with the blocks as SVG (`svg`), and line charts of parametric studies (`chart`).

pub mod chart;
pub mod svg;

use crate::assembly::{Assembly, JointForce};
use crate::geometry::Vec2;

/// The thrust-line point of each joint (None where the joint carries no force).
pub fn thrust_points(assembly: &Assembly, forces: &[JointForce]) -> Vec<Option<Vec2>> {
    assembly
        .joints
        .iter()
        .zip(forces)
        .map(|(j, f)| (f.n > 0.0).then(|| j.midpoint() + (f.m / f.n) * j.tangent()))
        .collect()
}
