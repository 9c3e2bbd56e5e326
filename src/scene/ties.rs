//! `[[ties]]`: tie rods, read from the scene and anchored on the built assembly.
//!
//! ```toml
//! [[ties]]
//! from = [-1.1, 1.0]     # m: anchored on the block containing this point
//! to = [1.1, 1.0]        # m: on another block, a fixed block, or the ground (at or below the structure's base)
//! capacity = 40000.0     # N: the force at which it yields
//! prestress = 0.0        # N, default 0, at most capacity: carried at lambda = 0
//! ultimate_strain = 0.075 # default 7.5 % (B450C's A_gt): the stretch over its length at which it breaks
//! ```

use super::placement::Placement;
use super::{short, Section, MAX_FORCE, MAX_LENGTH};
use crate::error::SceneError;
use crate::geometry::Vec2;

use crate::model::{Anchor, Tie, DEFAULT_ULTIMATE_STRAIN};
use toml::Table;

/// A tie as the user wrote it.
#[derive(Debug, Clone, PartialEq)]
pub struct TieSpec {
    pub from: [f64; 2],
    pub to: [f64; 2],
    /// The yield force (N); None for `capacity = "design"`, sized by `voussoir retrofit`.
    pub capacity: Option<f64>,
    pub prestress: f64,
    /// Cost per newton of capacity in a retrofit design (default 1).
    pub cost: f64,
    /// The strain at which it breaks (default [`DEFAULT_ULTIMATE_STRAIN`]); the capacity
    /// curve of `assess` drops the tie past it.
    pub ultimate_strain: f64,
}

const TIE_KEYS: &[&str] = &[
    "from",
    "to",
    "capacity",
    "prestress",
    "cost",
    "ultimate_strain",
];

/// The `[[ties]]` list of a scene (empty when absent).
pub(super) fn parse_ties(table: &Table, origin: &str) -> Result<Vec<TieSpec>, SceneError> {
    let items = super::entries(table, "ties", origin)?;
    let mut ties = Vec::with_capacity(items.len());
    for (k, t) in items.into_iter().enumerate() {
        let mut s = Section::new(format!("ties[{k}]"), t, origin);
        s.check_known(TIE_KEYS, "")?;
        let point = |s: &mut Section, key: &'static str, what: &str| {
            let p = s.pair(key, what)?;
            if p.iter().any(|c| c.abs() > MAX_LENGTH) {
                return Err(s.out_of_range(
                    key,
                    format!("[{}, {}]", short(p[0]), short(p[1])),
                    &format!("coordinates must lie within +-{MAX_LENGTH:e} m"),
                ));
            }
            Ok(p)
        };
        let from = point(
            &mut s,
            "from",
            "anchor point [x, y] in metres, inside a block",
        )?;
        let to = point(
            &mut s,
            "to",
            "anchor point [x, y] in metres, inside another block or at or below the structure's base (the ground)",
        )?;
        if from == to {
            return Err(s.out_of_range(
                "to",
                format!("[{}, {}]", to[0], to[1]),
                "must differ from `from`: a tie has a length",
            ));
        }
        let capacity =
            super::capacity_or_design(&mut s, "capacity", "the force at which the tie yields")?;
        let prestress = s.opt_f64("prestress")?.unwrap_or(0.0);
        let most = capacity.unwrap_or(MAX_FORCE);
        if !(prestress.is_finite() && (0.0..=most).contains(&prestress)) {
            return Err(s.out_of_range(
                "prestress",
                short(prestress),
                &format!("must be from 0 to the capacity, {} N", short(most)),
            ));
        }
        let cost = super::design_cost(&mut s)?;
        let ultimate_strain = s
            .opt_f64("ultimate_strain")?
            .unwrap_or(DEFAULT_ULTIMATE_STRAIN);
        if ultimate_strain.is_nan() || ultimate_strain <= 0.0 {
            return Err(s.out_of_range(
                "ultimate_strain",
                short(ultimate_strain),
                "must be a number > 0, or inf (the stretch over the tie's length at which it breaks; 0.075 for B450C bars)",
            ));
        }
        s.finish("")?;
        ties.push(TieSpec {
            from,
            to,
            capacity,
            prestress,
            cost,
            ultimate_strain,
        });
    }
    Ok(ties)
}

/// The ties of a scene anchored on the placement's assembly: each anchor on the block that
/// holds its point ([`Placement::locate_all`], all anchors in one pass), or the ground when the point lies in a fixed block
/// ([`Placement::fixed_at`]) or at or below the structure's base (its lowest point, within the placement's tolerance); any other point is
/// an error naming the key.
pub(super) fn anchor_ties(
    specs: &[TieSpec],
    placement: &Placement,
    origin: &str,
) -> Result<Vec<Tie>, SceneError> {
    if specs.is_empty() {
        return Ok(Vec::new());
    }
    let assembly = placement.assembly();
    let tol = placement.tolerance();
    let error = |k: usize, key: &str, p: [f64; 2], allowed: String| SceneError::OutOfRange {
        origin: origin.to_string(),
        key: format!("ties[{k}].{key}"),
        value: format!("[{}, {}]", short(p[0]), short(p[1])),
        allowed,
    };
    // Every anchor located in one pass over the blocks, which also finds the base (the
    // lowest point of the structure).
    let points: Vec<Vec2> = specs
        .iter()
        .flat_map(|s| [s.from, s.to])
        .map(|p| Vec2::new(p[0], p[1]))
        .collect();
    let (located, base) = placement.locate_all(&points);
    let mut ties = Vec::with_capacity(specs.len());
    for (k, spec) in specs.iter().enumerate() {
        let anchor = |key: &str,
                      p: [f64; 2],
                      located: Option<usize>|
         -> Result<Anchor, SceneError> {
            let point = Vec2::new(p[0], p[1]);
            let block = match located {
                Some(b) => Some(b),
                None if point.y <= base + tol => None,
                // A point of a fixed block (`[blocks] fixed`) is a point of the ground.
                None if placement.fixed_at(point).is_some() => None,
                None => {
                    return Err(error(
                        k,
                        key,
                        p,
                        format!(
                            "the point lies outside every block and above the ground (the structure's base is at y = {}): an anchor is a point of a block, of a fixed block, or of the ground at or below the base",
                            short(base)
                        ),
                    ))
                }
            };
            Ok(Anchor { block, point })
        };
        let (from, to) = (
            anchor("from", spec.from, located[2 * k])?,
            anchor("to", spec.to, located[2 * k + 1])?,
        );
        // A capacity to be designed starts at its least value, the prestress; the retrofit
        // design sizes it (a plain analysis refuses it, `super::build`).
        let tie = Tie {
            from,
            to,
            capacity: spec.capacity.unwrap_or(spec.prestress),
            prestress: spec.prestress,
            ultimate_strain: spec.ultimate_strain,
        };
        if let Some(problem) = tie.problem(assembly.blocks.len()) {
            return Err(error(
                k,
                "to",
                spec.to,
                format!("the tie is not well placed: {problem}"),
            ));
        }
        ties.push(tie);
    }
    Ok(ties)
}
