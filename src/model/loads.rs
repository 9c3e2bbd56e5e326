//! Load cases: every force an analysis applies to the blocks, resolved per block.
//!
//! A block carries two kinds of load:
//! - **permanent** forces (self-weight, fill, point and line loads), each a force with its
//!   point of application, kept per block as their resultant: a [`Wrench`] (force and moment
//!   about the block's centroid);
//! - **seismic masses**: the self-weight of the block and every load marked `seismic`, whose
//!   weight `m g` also takes the seismic body force `lambda m g (d, r)` (d = +-1 the horizontal
//!   direction of the ground motion, r the vertical ratio). All seismic forces are parallel,
//!   so a block's seismic masses act as one weight at their centre ([`SeismicMass`]).
//!
//! - **live loads** (`live = true`): kept apart per block, so that the [`Action`] decides what
//!   they are.
//!
//! What the collapse multiplier `lambda` multiplies is the load case's [`Action`]: under
//! [`Action::Seismic`] (the default) the seismic forces only, the live loads then being
//! permanent ones; under [`Action::Live`] the live loads only, with no seismic force at all.
//! The permanent forces stay as they are. With self-weight alone (r = 0) and a seismic action
//! this is the load model of the seed paper: `W` down and `lambda W` across at every centroid.
//! Methods read [`LoadCase::permanent`] and [`LoadCase::variable`] (what lambda multiplies),
//! never the seismic masses directly, so a new action is one more arm there.
//!
//! Every analysis (static program, kinematic searches, DEM, drawings) reads its loads from a
//! [`LoadCase`] and from nowhere else.

use super::Action;
use crate::assembly::Assembly;
use crate::geometry::{cross, Vec2};

/// A force system in the plane reduced to a point: the resultant force and its moment
/// (counter-clockwise positive) about that point.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Wrench {
    pub force: Vec2,
    pub moment: f64,
}

impl Wrench {
    /// The force `force` acting at `point`, reduced to `about`.
    pub fn of_force(force: Vec2, point: Vec2, about: Vec2) -> Wrench {
        Wrench {
            force,
            moment: cross(point - about, force),
        }
    }

    /// The same force system reduced to `to` instead of `from`.
    pub fn moved(&self, from: Vec2, to: Vec2) -> Wrench {
        Wrench {
            force: self.force,
            moment: self.moment + cross(from - to, self.force),
        }
    }
}

impl std::ops::Add for Wrench {
    type Output = Wrench;
    fn add(self, o: Wrench) -> Wrench {
        Wrench {
            force: self.force + o.force,
            moment: self.moment + o.moment,
        }
    }
}

/// Seismic masses of a block, as one weight (N) at their centre.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SeismicMass {
    /// Sum of the weights `m g` of the block's seismic masses (N).
    pub weight: f64,
    /// Their centre (m); the block's centroid when it has no seismic mass.
    pub centre: Vec2,
}

/// Where an applied load came from, for reports and drawings.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case", tag = "type", content = "index")]
pub enum LoadSource {
    /// The block's own weight.
    SelfWeight,
    /// Entry k of the scene's `[[loads]]` list.
    Load(usize),
    /// The scene's `[fill]`.
    Fill,
    /// Part `p` of entry k of the scene's `[[vehicles]]`: its axle p, or (p at or past the
    /// axle count) the distributed load beyond its axles (LM71's), one part per side.
    Vehicle(usize, usize),
}

impl std::fmt::Display for LoadSource {
    /// The scene's name of the load: `self-weight`, `loads[k]`, `fill`, `vehicles[k] part p`.
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            LoadSource::SelfWeight => write!(f, "self-weight"),
            LoadSource::Load(k) => write!(f, "loads[{k}]"),
            LoadSource::Fill => write!(f, "fill"),
            LoadSource::Vehicle(k, p) => write!(f, "vehicles[{k}] part {p}"),
        }
    }
}

/// One load as applied to one block.
#[derive(Debug, Clone, PartialEq)]
pub struct AppliedLoad {
    pub block: usize,
    /// Point of application (m).
    pub point: Vec2,
    /// Permanent force (N).
    pub force: Vec2,
    /// Weight (N) of the seismic mass attached to this load (0 when not seismic).
    pub seismic_weight: f64,
    /// Whether the load is live (`live = true` in the scene): under a live action
    /// ([`Action::Live`]) lambda multiplies it and it is not a permanent load; under a
    /// seismic action it is a permanent load like any other. A live load carries no seismic
    /// mass.
    pub live: bool,
    pub source: LoadSource,
    /// For fill: the outline of the filled region over the block (for drawings).
    pub region: Option<Vec<Vec2>>,
}

impl AppliedLoad {
    /// The point load `loads[k]` of a scene: `force` (N) at `point`, carried by `block`, with
    /// the seismic mass `|force_y| / g` when `seismic` (an upward force too: docs/geometry.md).
    pub fn point(k: usize, block: usize, point: Vec2, force: Vec2, seismic: bool) -> Self {
        AppliedLoad {
            block,
            point,
            force,
            seismic_weight: if seismic { force.y.abs() } else { 0.0 },
            live: false,
            source: LoadSource::Load(k),
            region: None,
        }
    }

    /// The fill's weight `weight` (N) over `block`, at the centroid `point` of its region
    /// `region` (kept for drawings), with a seismic mass of that weight when `seismic`.
    pub fn fill(block: usize, weight: f64, point: Vec2, region: Vec<Vec2>, seismic: bool) -> Self {
        AppliedLoad {
            block,
            point,
            force: Vec2::new(0.0, -weight),
            seismic_weight: if seismic { weight } else { 0.0 },
            live: false,
            source: LoadSource::Fill,
            region: Some(region),
        }
    }

    /// The same load marked live (see [`AppliedLoad::live`]): it then carries no seismic mass.
    pub fn live(mut self, live: bool) -> Self {
        self.live = live;
        if live {
            self.seismic_weight = 0.0;
        }
        self
    }
}

impl SpreadLoad {
    /// The line load `loads[k]` of a scene, kept whole: `intensity` (N/m, downward) over
    /// `from_x..to_x`.
    pub fn line(k: usize, from_x: f64, to_x: f64, intensity: f64, seismic: bool) -> Self {
        SpreadLoad {
            kind: Spread::Line {
                from_x,
                to_x,
                intensity,
            },
            seismic,
            live: false,
            source: LoadSource::Load(k),
        }
    }

    /// A fill of weight density `density` (N/m^2 in the plane) up to `y = level`, kept whole.
    pub fn fill(level: f64, density: f64, seismic: bool) -> Self {
        SpreadLoad {
            kind: Spread::Fill { level, density },
            seismic,
            live: false,
            source: LoadSource::Fill,
        }
    }

    /// The same load marked live (see [`AppliedLoad::live`]): it then is no seismic mass.
    pub fn live(mut self, live: bool) -> Self {
        self.live = live;
        if live {
            self.seismic = false;
        }
        self
    }
}

/// A load spread along the extrados of an arch ring, as the scene gave it. The blocks carry
/// its resultants (in [`LoadCase::applied`]); this whole description is kept for the
/// continuous model, whose sections can fall anywhere along the ring.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SpreadLoad {
    pub kind: Spread,
    /// Whether the load is also a seismic mass.
    pub seismic: bool,
    /// Whether the load is live (multiplied by lambda under [`Action::Live`]).
    pub live: bool,
    pub source: LoadSource,
}

/// What a spread load is.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Spread {
    /// `intensity` (N per metre of x, downward) over `from_x..to_x`, on the extrados.
    Line {
        from_x: f64,
        to_x: f64,
        intensity: f64,
    },
    /// Material of weight density `density` (N/m^2 in the plane: unit weight times depth)
    /// from the extrados up to `y = level`.
    Fill { level: f64, density: f64 },
}

/// The loads of every block of an assembly, and what lambda multiplies.
#[derive(Debug, Clone, PartialEq)]
pub struct LoadCase {
    /// What lambda multiplies (see [`Action`]).
    action: Action,
    /// Resultant of every load of each block (live ones too), about its centroid: the
    /// permanent forces under [`Action::Seismic`], accumulated in the order the loads were
    /// added.
    permanent: Vec<Wrench>,
    /// The same, live loads aside: the permanent forces under [`Action::Live`].
    fixed: Vec<Wrench>,
    /// Resultant of the live loads of each block, about its centroid: the action under
    /// [`Action::Live`], permanent forces under [`Action::Seismic`].
    live: Vec<Wrench>,
    /// Seismic masses of each block.
    seismic: Vec<SeismicMass>,
    /// Block centroids (the reference points of `permanent`).
    centroids: Vec<Vec2>,
    /// Vertical seismic component per unit horizontal one: the seismic force on a weight
    /// `m g` is `lambda m g (d, vertical_ratio)`.
    vertical_ratio: f64,
    /// Every load as applied, self-weights first, in the order they were added.
    applied: Vec<AppliedLoad>,
    /// Loads spread along the ring's extrados, whole (see [`SpreadLoad`]).
    spread: Vec<SpreadLoad>,
}

impl LoadCase {
    /// Self-weight only: each block's weight `W` down at its centroid, and a seismic mass of
    /// weight `W` there (the seed paper's load model).
    pub fn self_weight(assembly: &Assembly) -> LoadCase {
        let centroids: Vec<Vec2> = assembly.blocks.iter().map(|b| b.centroid).collect();
        let permanent: Vec<Wrench> = assembly
            .blocks
            .iter()
            .map(|b| Wrench {
                force: Vec2::new(0.0, -b.weight),
                moment: 0.0,
            })
            .collect();
        let seismic = assembly
            .blocks
            .iter()
            .map(|b| SeismicMass {
                weight: b.weight,
                centre: b.centroid,
            })
            .collect();
        let applied = assembly
            .blocks
            .iter()
            .enumerate()
            .map(|(i, b)| AppliedLoad {
                block: i,
                point: b.centroid,
                force: Vec2::new(0.0, -b.weight),
                seismic_weight: b.weight,
                live: false,
                source: LoadSource::SelfWeight,
                region: None,
            })
            .collect();
        LoadCase {
            action: Action::Seismic,
            live: vec![Wrench::default(); assembly.blocks.len()],
            fixed: permanent.clone(),
            permanent,
            seismic,
            centroids,
            vertical_ratio: 0.0,
            applied,
            spread: Vec::new(),
        }
    }

    /// The same load case with lambda multiplying `action`.
    pub fn with_action(mut self, action: Action) -> LoadCase {
        self.action = action;
        self
    }

    /// What lambda multiplies.
    pub fn action(&self) -> Action {
        self.action
    }

    /// Whether any load is live.
    pub fn has_live(&self) -> bool {
        self.applied.iter().any(|a| a.live)
    }

    /// Record a load spread along the ring's extrados (its resultants are added per block
    /// with [`LoadCase::add`]).
    pub fn add_spread(&mut self, load: SpreadLoad) {
        self.spread.push(load);
    }

    /// The loads spread along the ring's extrados.
    pub fn spread(&self) -> &[SpreadLoad] {
        &self.spread
    }

    /// Add a permanent force `force` at `point` on `block`; when `seismic_weight > 0`, a
    /// seismic mass of that weight at the same point.
    ///
    /// # Panics
    /// When `block` is out of range (a programming error: builders resolve blocks first).
    pub fn add(&mut self, load: AppliedLoad) {
        let i = load.block;
        let g = self.centroids[i];
        let w = Wrench::of_force(load.force, load.point, g);
        self.permanent[i] = self.permanent[i] + w;
        if load.live {
            self.live[i] = self.live[i] + w;
        } else {
            self.fixed[i] = self.fixed[i] + w;
        }
        let s = &mut self.seismic[i];
        let w = s.weight + load.seismic_weight;
        if w > 0.0 && load.seismic_weight > 0.0 {
            s.centre = (s.weight * s.centre + load.seismic_weight * load.point) / w;
            s.weight = w;
        }
        self.applied.push(load);
    }

    /// The same load case with the vertical seismic ratio `r` (seismic force
    /// `lambda m g (d, r)`).
    pub fn with_vertical_ratio(mut self, r: f64) -> LoadCase {
        self.vertical_ratio = r;
        self
    }

    pub fn vertical_ratio(&self) -> f64 {
        self.vertical_ratio
    }

    /// Number of blocks.
    pub fn len(&self) -> usize {
        self.permanent.len()
    }

    pub fn is_empty(&self) -> bool {
        self.permanent.is_empty()
    }

    /// Resultant permanent force of block `i`, about its centroid: every load lambda does
    /// not multiply (the live loads too under a seismic action).
    pub fn permanent(&self, i: usize) -> Wrench {
        match self.action {
            Action::Seismic => self.permanent[i],
            Action::Live => self.fixed[i],
        }
    }

    /// The action on block `i` per unit lambda, about its centroid: the seismic force toward
    /// `sign` (+1 for ground motion toward +x, -1 toward -x) under [`Action::Seismic`], the
    /// live loads under [`Action::Live`] (`sign` has no meaning for them and is ignored).
    /// Every method reads what lambda multiplies from here.
    pub fn variable(&self, i: usize, sign: f64) -> Wrench {
        match self.action {
            Action::Seismic => self.seismic(i, sign),
            Action::Live => self.live[i],
        }
    }

    /// Whether an applied load is multiplied by lambda under this load case's action, as a
    /// force (live loads under [`Action::Live`]); seismic masses are multiplied through
    /// [`LoadCase::variable_direction`] instead.
    pub fn is_variable(&self, load: &AppliedLoad) -> bool {
        self.action == Action::Live && load.live
    }

    /// The force per unit lambda and unit seismic weight: the seismic direction
    /// ([`LoadCase::seismic_direction`]) under [`Action::Seismic`], zero under
    /// [`Action::Live`] (no mass is shaken).
    pub fn variable_direction(&self, sign: f64) -> Vec2 {
        match self.action {
            Action::Seismic => self.seismic_direction(sign),
            Action::Live => Vec2::zeros(),
        }
    }

    /// Seismic masses of block `i`.
    pub fn seismic_mass(&self, i: usize) -> SeismicMass {
        self.seismic[i]
    }

    /// The seismic body force per unit weight and unit lambda: `(sign, vertical_ratio)`,
    /// `sign` = +1 for ground motion toward +x, -1 toward -x.
    pub fn seismic_direction(&self, sign: f64) -> Vec2 {
        Vec2::new(sign, self.vertical_ratio)
    }

    /// Seismic force on block `i` per unit lambda (`sign` as in
    /// [`LoadCase::seismic_direction`]), about its centroid.
    pub fn seismic(&self, i: usize, sign: f64) -> Wrench {
        let s = self.seismic[i];
        Wrench::of_force(
            s.weight * self.seismic_direction(sign),
            s.centre,
            self.centroids[i],
        )
    }

    /// The reference point (block centroid) the wrenches of block `i` are reduced to.
    pub fn reference(&self, i: usize) -> Vec2 {
        self.centroids[i]
    }

    /// Every load as applied (self-weights first).
    pub fn applied(&self) -> &[AppliedLoad] {
        &self.applied
    }

    /// Total downward permanent force (N): the sum of the vertical components, sign
    /// reversed.
    pub fn permanent_weight(&self) -> f64 {
        -(0..self.len())
            .map(|i| self.permanent(i).force.y)
            .sum::<f64>()
    }

    /// Sum of the magnitudes of the live loads (N): what lambda multiplies under a live
    /// action.
    pub fn live_magnitude(&self) -> f64 {
        self.applied
            .iter()
            .filter(|a| a.live)
            .map(|a| a.force.norm())
            .sum()
    }

    /// Total weight of the seismic masses (N).
    pub fn seismic_weight(&self) -> f64 {
        self.seismic.iter().map(|s| s.weight).sum()
    }

    /// A force scale (N) for dimensionless programs: the larger of the summed magnitudes of
    /// the permanent forces and the seismic weight. For self-weight alone, the total weight.
    pub fn force_scale(&self) -> f64 {
        let (p, l): (f64, f64) = match self.action {
            Action::Seismic => (self.permanent.iter().map(|w| w.force.norm()).sum(), 0.0),
            Action::Live => (
                self.fixed.iter().map(|w| w.force.norm()).sum(),
                self.live.iter().map(|w| w.force.norm()).sum(),
            ),
        };
        (p + l).max(self.seismic_weight())
    }

    /// Whether the loads are self-weight alone with no vertical seismic component.
    pub fn is_self_weight_only(&self) -> bool {
        self.action == Action::Seismic
            && self.vertical_ratio == 0.0
            && self
                .applied
                .iter()
                .all(|a| a.source == LoadSource::SelfWeight)
    }

    /// The same load case for the mirrored assembly ([`Assembly::mirrored`]): block order
    /// reversed and x negated.
    pub fn mirrored(&self) -> LoadCase {
        let nb = self.len();
        let m = crate::geometry::mirror;
        let flip = |ws: &[Wrench]| -> Vec<Wrench> {
            ws.iter()
                .rev()
                .map(|w| Wrench {
                    force: m(w.force),
                    moment: -w.moment,
                })
                .collect()
        };
        LoadCase {
            action: self.action,
            permanent: flip(&self.permanent),
            fixed: flip(&self.fixed),
            live: flip(&self.live),
            seismic: self
                .seismic
                .iter()
                .rev()
                .map(|s| SeismicMass {
                    weight: s.weight,
                    centre: m(s.centre),
                })
                .collect(),
            centroids: self.centroids.iter().rev().map(|c| m(*c)).collect(),
            vertical_ratio: self.vertical_ratio,
            applied: self
                .applied
                .iter()
                .map(|a| AppliedLoad {
                    block: nb - 1 - a.block,
                    point: m(a.point),
                    force: m(a.force),
                    region: a
                        .region
                        .as_ref()
                        .map(|r| r.iter().rev().map(|p| m(*p)).collect()),
                    ..a.clone()
                })
                .collect(),
            spread: self
                .spread
                .iter()
                .map(|l| SpreadLoad {
                    kind: match l.kind {
                        Spread::Line {
                            from_x,
                            to_x,
                            intensity,
                        } => Spread::Line {
                            from_x: -to_x,
                            to_x: -from_x,
                            intensity,
                        },
                        fill => fill,
                    },
                    ..*l
                })
                .collect(),
        }
    }

    /// The same loads carried by blocks moved rigidly: block `i` turned by `moves[i].1` (rad,
    /// counter-clockwise) about its centroid and its centroid moved by `moves[i].0` (the
    /// convention of a drawing's placements). Every applied load keeps its magnitude and
    /// direction (weights stay vertical) and moves with its point of application; the
    /// resultants are rebuilt from the applied loads. The spread loads are kept as given (they
    /// describe the ring before the motion). For the finite kinematics of a mechanism
    /// (`crate::assess`) and a DEM started from a displaced configuration.
    ///
    /// # Panics
    /// When `moves` has fewer entries than there are blocks (a programming error).
    pub fn moved(&self, moves: &[(Vec2, f64)]) -> LoadCase {
        let place = |block: usize, p: Vec2| {
            let (d, rot) = moves[block];
            let (sn, cs) = rot.sin_cos();
            let c = self.centroids[block];
            let r = p - c;
            c + d + Vec2::new(cs * r.x - sn * r.y, sn * r.x + cs * r.y)
        };
        let centroids: Vec<Vec2> = (0..self.len())
            .map(|i| place(i, self.centroids[i]))
            .collect();
        let applied: Vec<AppliedLoad> = self
            .applied
            .iter()
            .map(|a| AppliedLoad {
                point: place(a.block, a.point),
                region: a
                    .region
                    .as_ref()
                    .map(|r| r.iter().map(|p| place(a.block, *p)).collect()),
                ..a.clone()
            })
            .collect();
        let mut permanent = vec![Wrench::default(); self.len()];
        let mut fixed = vec![Wrench::default(); self.len()];
        let mut live = vec![Wrench::default(); self.len()];
        let mut seismic: Vec<SeismicMass> = centroids
            .iter()
            .map(|c| SeismicMass {
                weight: 0.0,
                centre: *c,
            })
            .collect();
        let mut moment = vec![Vec2::zeros(); self.len()];
        for a in &applied {
            let i = a.block;
            let w = Wrench::of_force(a.force, a.point, centroids[i]);
            permanent[i] = permanent[i] + w;
            if a.live {
                live[i] = live[i] + w;
            } else {
                fixed[i] = fixed[i] + w;
            }
            seismic[i].weight += a.seismic_weight;
            moment[i] += a.seismic_weight * a.point;
        }
        for (s, m) in seismic.iter_mut().zip(&moment) {
            if s.weight > 0.0 {
                s.centre = m / s.weight;
            }
        }
        LoadCase {
            action: self.action,
            permanent,
            fixed,
            live,
            seismic,
            centroids,
            vertical_ratio: self.vertical_ratio,
            applied,
            spread: self.spread.clone(),
        }
    }

    /// Check the load case against its assembly: one entry per block, finite values,
    /// non-negative seismic weights.
    pub fn validate(&self, assembly: &Assembly) -> Result<(), crate::error::AnalysisError> {
        use crate::error::AnalysisError;
        if self.len() != assembly.blocks.len() {
            return Err(AnalysisError::Assembly(format!(
                "the load case has {} blocks, the assembly {}",
                self.len(),
                assembly.blocks.len()
            )));
        }
        if !(self.vertical_ratio.is_finite() && (-1.0..=1.0).contains(&self.vertical_ratio)) {
            return Err(AnalysisError::Assembly(format!(
                "vertical seismic ratio {} is outside -1..1",
                self.vertical_ratio
            )));
        }
        for i in 0..self.len() {
            let p = self.permanent[i];
            let s = self.seismic[i];
            if !(p.force.x.is_finite() && p.force.y.is_finite() && p.moment.is_finite()) {
                return Err(AnalysisError::Assembly(format!(
                    "block {i} has a permanent load that is not finite"
                )));
            }
            if !(s.weight.is_finite() && s.weight >= 0.0) {
                return Err(AnalysisError::Assembly(format!(
                    "block {i} has seismic weight {}",
                    s.weight
                )));
            }
        }
        Ok(())
    }
}
