//! The structural model an analysis works on: an [`Assembly`] of blocks and joints and the
//! [`LoadCase`] it carries, built from a scene in exactly one place (`crate::scene::build`), or
//! by hand.
//!
//! Data flows one way: scene -> `scene::build` -> [`Model`] -> static / kinematic / DEM
//! analyses -> reports. The analyses never read a scene.

pub mod action;
pub mod loads;

pub use action::Action;
pub use loads::{AppliedLoad, LoadCase, LoadSource, SeismicMass, Spread, SpreadLoad, Wrench};

use crate::assembly::{Assembly, JointForce};
pub use crate::interaction::tie::DEFAULT_ULTIMATE_STRAIN;
pub use crate::interaction::{
    Anchor, Passive, PassiveForce, Strength, Strip, StripForce, Tie, TieForce,
};

/// Blocks and joints with their loads.
#[derive(Debug, Clone)]
pub struct Model {
    pub assembly: Assembly,
    pub loads: LoadCase,
    /// Compressive strength of the joints ([`Strength::rigid`] is Heyman's infinite strength):
    /// the crushing interaction.
    pub strength: Strength,
    /// Tie rods (`crate::interaction::tie`), in the scene's order.
    pub ties: Vec<Tie>,
    /// Bonded strips (`crate::interaction::strip`), one per joint a strip crosses.
    pub strips: Vec<Strip>,
    /// The fill's passive resistance (`crate::interaction::passive`), one per face against
    /// the fill; empty unless `[fill] passive = true`.
    pub passive: Vec<Passive>,
}

impl Model {
    /// An assembly under its self-weight alone (the seed paper's load model).
    pub fn self_weight(assembly: Assembly) -> Model {
        let loads = LoadCase::self_weight(&assembly);
        Model {
            assembly,
            loads,
            strength: Strength::rigid(),
            ties: Vec::new(),
            strips: Vec::new(),
            passive: Vec::new(),
        }
    }

    /// The same model with joints of compressive strength `strength`.
    pub fn with_strength(mut self, strength: Strength) -> Model {
        self.strength = strength;
        self
    }

    /// The same model with tie rods `ties`.
    pub fn with_ties(mut self, ties: Vec<Tie>) -> Model {
        self.ties = ties;
        self
    }

    /// Check the assembly ([`Assembly::validate`]) and its load case against it.
    pub fn validate(&self) -> Result<(), crate::error::AnalysisError> {
        self.assembly.validate()?;
        self.loads.validate(&self.assembly)?;
        let s = &self.strength;
        if s.compressive.is_nan() || s.compressive <= 0.0 || !(s.depth.is_finite() && s.depth > 0.0)
        {
            return Err(crate::error::AnalysisError::Other(format!(
                "compressive strength {} Pa over depth {} m: the strength must be > 0 (inf for \
                 rigid joints) and the depth a finite number > 0",
                s.compressive, s.depth
            )));
        }
        for (k, t) in self.ties.iter().enumerate() {
            if let Some(problem) = t.problem(self.assembly.blocks.len()) {
                return Err(crate::error::AnalysisError::Other(format!(
                    "tie {k}: {problem}"
                )));
            }
        }
        for s in &self.strips {
            if let Some(problem) = s.problem(&self.assembly) {
                return Err(crate::error::AnalysisError::Other(format!(
                    "strip of reinforcement {}: {problem}",
                    s.source
                )));
            }
        }
        for (k, p) in self.passive.iter().enumerate() {
            if let Some(problem) = p.problem(self.assembly.blocks.len()) {
                return Err(crate::error::AnalysisError::Other(format!(
                    "passive face {k}: {problem}"
                )));
            }
        }
        Ok(())
    }

    /// The same model mirrored about x = 0.
    pub fn mirrored(&self) -> Model {
        Model {
            assembly: self.assembly.mirrored(),
            loads: self.loads.mirrored(),
            strength: self.strength,
            ties: self
                .ties
                .iter()
                .map(|t| {
                    let nb = self.assembly.blocks.len();
                    let flip = |a: crate::interaction::Anchor| crate::interaction::Anchor {
                        block: a.block.map(|b| nb - 1 - b),
                        point: crate::geometry::mirror(a.point),
                    };
                    Tie {
                        from: flip(t.from),
                        to: flip(t.to),
                        ..t.clone()
                    }
                })
                .collect(),
            // The mirror numbers joint k as m - 1 - k; p1 and p2 keep their meaning.
            strips: self
                .strips
                .iter()
                .map(|s| Strip {
                    joint: self.assembly.joints.len() - 1 - s.joint,
                    ..*s
                })
                .collect(),
            passive: self
                .passive
                .iter()
                .map(|p| p.mirrored(self.assembly.blocks.len() - 1 - p.block))
                .collect(),
        }
    }

    /// [`equilibrium_residual`] with the ties' forces `ties` and the strips' `strips` (N, in
    /// their orders) as well, and no passive reaction.
    pub fn equilibrium_residual(
        &self,
        forces: &[JointForce],
        ties: &[f64],
        strips: &[f64],
        lambda: f64,
        sign: f64,
    ) -> f64 {
        self.residual_with_passive(forces, ties, strips, &[], lambda, sign)
    }

    /// [`Model::equilibrium_residual`] with the passive reactions `passive` (N, in face
    /// order; missing ones are zero) as well.
    pub fn residual_with_passive(
        &self,
        forces: &[JointForce],
        ties: &[f64],
        strips: &[f64],
        passive: &[f64],
        lambda: f64,
        sign: f64,
    ) -> f64 {
        // A strip's tension is a force between its joint's sides at the reinforced end, along
        // the joint's normal: a tie from a point of `from` just behind the end to the end on
        // `to` (the offset is along the force, so it moves no moment).
        let as_ties = self.strips.iter().map(|s| {
            let j = &self.assembly.joints[s.joint];
            let p = s.point(&self.assembly);
            Tie {
                from: Anchor {
                    block: j.from,
                    point: p - 1e-3 * j.length() * j.normal(),
                },
                to: Anchor {
                    block: j.to,
                    point: p,
                },
                capacity: s.capacity,
                prestress: 0.0,
                ultimate_strain: f64::INFINITY,
            }
        });
        // A passive reaction pushes its block away from the fill: a tie from its point to a
        // point of the ground just out of the fill (the offset is along the force).
        let scale = self.assembly.size();
        let as_ground_ties = self.passive.iter().map(|p| Tie {
            from: Anchor {
                block: Some(p.block),
                point: p.point,
            },
            to: Anchor {
                block: None,
                point: p.point + 1e-3 * scale * p.direction(),
            },
            capacity: p.cap,
            prestress: 0.0,
            ultimate_strain: f64::INFINITY,
        });
        let all: Vec<Tie> = self
            .ties
            .iter()
            .cloned()
            .chain(as_ties)
            .chain(as_ground_ties)
            .collect();
        let passive = (0..self.passive.len()).map(|k| passive.get(k).copied().unwrap_or(0.0));
        let f: Vec<f64> = ties.iter().chain(strips).copied().chain(passive).collect();
        residuals(&self.assembly, &self.loads, forces, &all, &f, lambda, sign)
    }
}

/// Largest out-of-balance force (N) of any block under joint forces `forces` and the loads
/// of `loads` with the action times `lambda` (seismic forces in direction `sign`) (moments divided by
/// the structure's size so they are forces too).
pub fn equilibrium_residual(
    assembly: &Assembly,
    loads: &LoadCase,
    forces: &[JointForce],
    lambda: f64,
    sign: f64,
) -> f64 {
    residuals(assembly, loads, forces, &[], &[], lambda, sign)
}

fn residuals(
    assembly: &Assembly,
    loads: &LoadCase,
    forces: &[JointForce],
    ties: &[Tie],
    tie_forces: &[f64],
    lambda: f64,
    sign: f64,
) -> f64 {
    let size = assembly.size();
    let mut res: Vec<[f64; 3]> = (0..assembly.blocks.len())
        .map(|i| {
            let p = loads.permanent(i);
            let s = loads.variable(i, sign);
            [
                p.force.x + lambda * s.force.x,
                p.force.y + lambda * s.force.y,
                (p.moment + lambda * s.moment) / size,
            ]
        })
        .collect();
    for (jt, f) in assembly.joints.iter().zip(forces) {
        let force = f.n * jt.normal() + f.v * jt.tangent();
        let mid = jt.midpoint();
        for (side, s) in [(jt.to, 1.0), (jt.from, -1.0)] {
            if let Some(b) = side {
                let g = loads.reference(b);
                res[b][0] += s * force.x;
                res[b][1] += s * force.y;
                // The couple of a resultant offset toward p2 turns clockwise: u x n = -1.
                res[b][2] += s * (crate::geometry::cross(mid - g, force) - f.m) / size;
            }
        }
    }
    for (t, &f) in ties.iter().zip(tie_forces) {
        let e = t.direction();
        for (anchor, s) in [(t.from, 1.0), (t.to, -1.0)] {
            if let Some(b) = anchor.block {
                let g = loads.reference(b);
                let force = s * f * e;
                res[b][0] += force.x;
                res[b][1] += force.y;
                res[b][2] += crate::geometry::cross(anchor.point - g, force) / size;
            }
        }
    }
    res.iter()
        .flat_map(|r| r.iter())
        .fold(0.0_f64, |acc, x| acc.max(x.abs()))
}
