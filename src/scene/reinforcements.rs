//! `[[reinforcements]]`: bonded strips (FRP, FRCM) on the intrados or the extrados of the
//! arch, across a range of its joints; each crossed joint gets a
//! [`crate::model::Strip`] at that face's end.
//!
//! ```toml
//! [[reinforcements]]
//! face = "intrados"           # or "extrados"
//! from_joint = 0              # arch joints, 0 = the left springing, n = the right one
//! to_joint = 12
//! tensile_capacity = 15000.0  # N at each joint it crosses (the strip's debonding force), or "design"
//! cost = 1.0                  # default 1: cost per N of capacity in a retrofit design
//! ```

use super::Section;
use crate::assembly::{Assembly, JointEnd, JointKind};
use crate::error::SceneError;
use crate::model::Strip;
use toml::Table;

/// A strip as the user wrote it.
#[derive(Debug, Clone, PartialEq)]
pub struct ReinforcementSpec {
    /// The face: the intrados (joint end p1) or the extrados (p2).
    pub face: JointEnd,
    pub from_joint: usize,
    pub to_joint: usize,
    /// Tensile capacity at each crossed joint (N); None for `tensile_capacity = "design"`,
    /// sized by `voussoir retrofit`.
    pub tensile_capacity: Option<f64>,
    /// Cost per newton of capacity in a retrofit design (default 1).
    pub cost: f64,
}

const KEYS: &[&str] = &["face", "from_joint", "to_joint", "tensile_capacity", "cost"];

/// The `[[reinforcements]]` list of a scene (empty when absent).
pub(super) fn parse(table: &Table, origin: &str) -> Result<Vec<ReinforcementSpec>, SceneError> {
    let items = super::entries(table, "reinforcements", origin)?;
    let mut out = Vec::with_capacity(items.len());
    for (k, t) in items.into_iter().enumerate() {
        let mut s = Section::new(format!("reinforcements[{k}]"), t, origin);
        s.check_known(KEYS, "")?;
        let face = match s.string("face", None)?.as_str() {
            "intrados" => JointEnd::P1,
            "extrados" => JointEnd::P2,
            other => {
                return Err(s.out_of_range(
                    "face",
                    format!("\"{other}\""),
                    "must be \"intrados\" or \"extrados\"",
                ))
            }
        };
        let from_joint = s.index("from_joint", "the first arch joint the strip crosses")?;
        let to_joint = s.index("to_joint", "the last arch joint the strip crosses")?;
        if to_joint < from_joint {
            return Err(s.out_of_range(
                "to_joint",
                to_joint,
                &format!("must be at least from_joint = {from_joint}"),
            ));
        }
        let tensile_capacity = super::capacity_or_design(
            &mut s,
            "tensile_capacity",
            "the strip's tensile (debonding) force at each joint it crosses",
        )?;
        let cost = super::design_cost(&mut s)?;
        s.finish("")?;
        out.push(ReinforcementSpec {
            face,
            from_joint,
            to_joint,
            tensile_capacity,
            cost,
        });
    }
    Ok(out)
}

/// The strips of `specs` on the arch joints of `assembly` (`JointKind::Arch`); an error
/// naming the key when a joint does not exist, or when the structure has no arch joints
/// (the user's own blocks).
pub(super) fn strips(
    specs: &[ReinforcementSpec],
    assembly: &Assembly,
    origin: &str,
) -> Result<Vec<Strip>, SceneError> {
    let arch: Vec<(usize, usize)> = assembly
        .joints
        .iter()
        .enumerate()
        .filter_map(|(i, j)| match j.kind {
            JointKind::Arch(a) => Some((a, i)),
            _ => None,
        })
        .collect();
    let mut out = Vec::new();
    for (k, spec) in specs.iter().enumerate() {
        let last = arch.iter().map(|&(a, _)| a).max();
        for (key, joint) in [("from_joint", spec.from_joint), ("to_joint", spec.to_joint)] {
            if last.is_none_or(|last| joint > last) {
                return Err(SceneError::OutOfRange {
                    origin: origin.to_string(),
                    key: format!("reinforcements[{k}].{key}"),
                    value: joint.to_string(),
                    allowed: match last {
                        Some(last) => format!(
                            "an arch joint from 0 (the left springing) to {last} (the right one)"
                        ),
                        None => "an arch joint, but this structure has none: strips need the parametric [arch]".into(),
                    },
                });
            }
        }
        for &(a, i) in &arch {
            if (spec.from_joint..=spec.to_joint).contains(&a) {
                out.push(Strip {
                    joint: i,
                    end: spec.face,
                    // A capacity to be designed starts at 0; the retrofit design sizes it
                    // (a plain analysis refuses it, `super::build`).
                    capacity: spec.tensile_capacity.unwrap_or(0.0),
                    source: k,
                });
            }
        }
    }
    Ok(out)
}
