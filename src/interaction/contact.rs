//! Contact: the plane joints between blocks (or a block and the ground) of no-tension masonry
//! with Coulomb friction (Livesley, 1978; Gilbert, Casapulla & Ahmed, 2006).
//!
//! Static rows: three unknowns per joint, the compressive forces `c1, c2 >= 0` at its ends
//! p1, p2 and its shear `V`, so that `N = c1 + c2`, `M = (c2 - c1) L/2`; the force `from`
//! exerts on `to` is `c1 n + c2 n + V u` at p1, p2 and the midpoint. No tension and the
//! resultant inside the joint are `c1, c2 >= 0` (left out when [`super::crushing`] cones
//! imply them); a finite friction coefficient adds the two half-planes
//! `mu (c1 + c2) -+ V >= 0` (the planar Coulomb cone, associative: at the limit the
//! mechanism slides and dilates, so a sliding joint dissipates nothing).
//!
//! A second shear law, [`ShearLimit::Fixed`], bounds each joint's shear by a fixed capacity
//! `|V| <= S_j` instead of `mu N` (a Tresca-like cohesion, `S_j = mu N_prev` from an earlier
//! solution): its normality rule is pure slip with no opening, so a program with fixed
//! capacities has the mechanisms of real (non-dilatant) joints. The non-associative
//! multiplier (`crate::statics::non_associative`; Gilbert, Casapulla & Ahmed 2006) solves a
//! sequence of such programs.
//!
//! Work rate: hinging and opening joints dissipate nothing; the associative sliding joint
//! neither (dilatancy), so contacts add nothing to the virtual-work equation of the
//! kinematic searches, whose mechanisms do not slide.

use super::Rows;
use crate::assembly::Assembly;

/// Column of the contact unknown `which` (0 = c1, 1 = c2, 2 = V) of joint `joint`, the
/// contact's columns starting at `first`.
pub fn column_from(first: usize, joint: usize, which: usize) -> usize {
    first + 3 * joint + which
}

/// How the contacts' shear is bounded, for the joints with finite friction (joints with
/// `friction = inf` have no shear row under either law).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub enum ShearLimit<'a> {
    /// Coulomb's `|V| <= mu N`, the associative joint (it dilates when it slips).
    #[default]
    Coulomb,
    /// A fixed capacity per joint, `|V| <= capacity[j]` (N, in joint order; joints with
    /// infinite friction ignore theirs): slip without opening. A capacity that is not a
    /// finite number >= 0 is read as 0.
    Fixed(&'a [f64]),
}

/// The contacts' part of the static program: their unknowns, their forces on the blocks, no
/// tension (unless `implied`, by the crushing cones) and friction (the law `shear`). Returns
/// the first column and the joints with friction rows, in row order.
pub fn static_rows(
    assembly: &Assembly,
    rows: &mut Rows,
    implied: bool,
    shear: ShearLimit<'_>,
) -> (usize, Vec<usize>) {
    let first = rows.add_columns(3 * assembly.joints.len());
    let col = |j, which| column_from(first, j, which);
    for (j, jt) in assembly.joints.iter().enumerate() {
        let (n, u, m) = (jt.normal(), jt.tangent(), jt.midpoint());
        for (side, s) in [(jt.to, 1.0), (jt.from, -1.0)] {
            for (which, point, dir) in [(0, jt.p1, n), (1, jt.p2, n), (2, m, u)] {
                rows.force_on(side, col(j, which), dir, point, s);
            }
        }
    }
    if !implied {
        for j in 0..assembly.joints.len() {
            rows.nonnegative(vec![(col(j, 0), -1.0)], 0.0, true);
            rows.nonnegative(vec![(col(j, 1), -1.0)], 0.0, true);
        }
    }
    let mut friction = Vec::new();
    for (j, jt) in assembly.joints.iter().enumerate() {
        if jt.friction.is_finite() {
            for sv in [1.0, -1.0] {
                match shear {
                    ShearLimit::Coulomb => {
                        let mu = jt.friction;
                        rows.nonnegative(
                            vec![(col(j, 0), -mu), (col(j, 1), -mu), (col(j, 2), sv)],
                            0.0,
                            true,
                        );
                    }
                    ShearLimit::Fixed(capacity) => {
                        let s = fixed_capacity(capacity, j);
                        rows.nonnegative(vec![(col(j, 2), sv)], s / rows.force_scale, true);
                    }
                }
            }
            friction.push(j);
        }
    }
    (first, friction)
}

/// Joint `k`'s fixed shear capacity in `capacity` (N) of [`ShearLimit::Fixed`]: missing,
/// negative or not finite is 0 (the full program and the chain's read it alike).
pub(crate) fn fixed_capacity(capacity: &[f64], k: usize) -> f64 {
    let s = capacity.get(k).copied().unwrap_or(0.0);
    if s.is_finite() {
        s.max(0.0)
    } else {
        0.0
    }
}
