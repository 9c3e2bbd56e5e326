//! Whether the static multiplier is exact with finite friction (docs/friction.md).
//!
//! The static program bounds the joint shear by Coulomb's `|V| <= mu N`, and its duals are
//! the collapse mechanism of the associative (normality) joint: a joint that slips in it also
//! opens, by `mu` times its slip. Real joints slide without opening, and the multiplier of the
//! associative joint is then an upper bound of the real (non-associative) collapse multiplier,
//! not a safe lower bound. When no joint in contact slips in the associative mechanism, that
//! mechanism is also one of the non-associative joint (hinges and separations only, no
//! dilatancy): the associative collapse state is a collapse state of real joints too, and the
//! multiplier is exact in that sense. It does not exclude lower collapse states of real
//! joints, which need not be unique (docs/friction.md: a running-bond wall whose head joints
//! carry no compression collapses at 0.536 with real joints, 1.0 rocking as one body).

use super::StaticResult;
use crate::assembly::Assembly;
use crate::geometry::Vec2;
use crate::outcome::Status;

/// Tangential slip (relative to the fastest centroid's speed, which the mechanism scales to 1)
/// above which a joint slips in the mechanism: the interior point's duals carry round-off
/// of about 1e-9 in a rocking mechanism, a sliding one slips at a sizeable fraction of 1.
pub const SLIP_TOL: f64 = 1e-6;

/// What finite friction makes of the static multiplier.
#[derive(Debug, Clone, PartialEq)]
pub struct FrictionCheck {
    /// Whether some joint has finite friction.
    pub finite: bool,
    /// Whether the multiplier (or the status) is that of real joints, which slide without
    /// opening: true with infinite friction, when the structure cannot stand (no equilibrium
    /// exists for either joint), and at collapse when no joint in contact slips in the
    /// mechanism; false at collapse when some does, and for a no-collapse verdict with finite
    /// friction (no mechanism shows it holds for real joints).
    pub exact: bool,
    /// The joints in contact (not fully open) that slip in the collapse mechanism, in joint
    /// order.
    pub slipping: Vec<usize>,
    /// The multiplier of the associative joint: the static multiplier, whenever there is one
    /// (exact or not, so that it can always be compared with `lambda_lower`).
    pub lambda_associative: Option<f64>,
    /// Exact at collapse with finite friction, in an assembly that is not a chain (a wall, a
    /// stack): the collapse state is one of real joints, but joints that may carry little or
    /// no compression (a wall's head joints) can give real joints lower ones, so the
    /// multiplier is not called a lower bound (docs/friction.md). False otherwise; on a chain
    /// every joint carries the thrust.
    pub lower_states_possible: bool,
}

impl FrictionCheck {
    /// Whether the static multiplier is the real one's safe side: exact, and no lower
    /// collapse state of real joints possible (docs/friction.md). False: the associative
    /// multiplier (joints slide), or an exact one in a wall, neither proved a lower bound.
    pub fn is_lower_bound(&self) -> bool {
        self.exact && !self.lower_states_possible
    }
}

impl StaticResult {
    /// Whether this result is exact with finite friction ([`FrictionCheck`]): every front end
    /// asks this.
    pub fn friction(&self, assembly: &Assembly) -> FrictionCheck {
        let finite = assembly.joints.iter().any(|j| j.friction.is_finite());
        let slipping = if finite && self.status == Status::Collapse {
            slipping_joints(assembly, &self.mechanism, &self.open)
        } else {
            Vec::new()
        };
        let exact = !finite
            || match self.status {
                Status::Collapse => slipping.is_empty(),
                Status::CannotStand => true,
                Status::NoCollapse => false,
            };
        FrictionCheck {
            finite,
            exact,
            slipping,
            lambda_associative: self.lambda,
            lower_states_possible: finite
                && exact
                && self.status == Status::Collapse
                && !assembly.is_single_thrust_path(),
        }
    }
}

/// The joints with finite friction, not in `open`, whose two sides slip past each other in the
/// mechanism `velocities` (block `[vx, vy, omega]`, the fastest centroid at speed 1) faster
/// than [`SLIP_TOL`]. The tangential relative velocity of two rigid bodies is the same at
/// every point of the joint's line, so the midpoint's tells.
pub fn slipping_joints(assembly: &Assembly, velocities: &[[f64; 3]], open: &[usize]) -> Vec<usize> {
    if velocities.len() != assembly.blocks.len() {
        return Vec::new();
    }
    let at = |b: Option<usize>, q: Vec2| -> Vec2 {
        b.map_or_else(Vec2::zeros, |b| {
            let [vx, vy, w] = velocities[b];
            let r = q - assembly.blocks[b].centroid;
            Vec2::new(vx - w * r.y, vy + w * r.x)
        })
    };
    assembly
        .joints
        .iter()
        .enumerate()
        .filter(|(k, j)| j.friction.is_finite() && !open.contains(k))
        .filter(|(_, j)| {
            let q = j.midpoint();
            (at(j.to, q) - at(j.from, q)).dot(&j.tangent()).abs() > SLIP_TOL
        })
        .map(|(k, _)| k)
        .collect()
}
