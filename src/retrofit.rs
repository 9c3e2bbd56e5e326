//! Retrofit design: the smallest tie rods that make a structure carry a target multiplier.
//!
//! The scene's ties whose `capacity` is `"design"` are sized by one program
//! ([`crate::statics::design`]): the least total capacity, weighted by each tie's `cost`,
//! for which the static program carries lambda = target in both directions of a seismic
//! action (the one direction of a live action's adequacy factor). The structure is then
//! analysed again with those capacities, by the same analysis as `voussoir analyze` (static
//! and certified kinematic bounds), in each direction; and each needed capacity is matched
//! with the smallest standard steel bar that carries it at the design strength
//! `material.tie_design_strength` (default 391 MPa: B450C, 450 MPa over 1.15). A target no
//! capacities reach is reported with the best multiplier reachable.

use crate::analysis::{self, Options, SceneAnalysis};
use crate::error::AnalysisError;
use crate::model::Action;
use crate::outcome::{Direction, LAMBDA_CAP};
use crate::scene::Scene;
use crate::statics::design::{self, Design, DesignedTie};

/// Standard diameters of reinforcing bars (mm), EN 10080 / B450C.
pub const BAR_DIAMETERS_MM: &[f64] = &[
    6.0, 8.0, 10.0, 12.0, 14.0, 16.0, 18.0, 20.0, 22.0, 24.0, 26.0, 28.0, 30.0, 32.0, 36.0, 40.0,
];

/// A capacity below this fraction of the structure's force scale is no tie at all.
const NOT_NEEDED: f64 = 1e-7;

/// A steel bar that carries a designed capacity.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct Bar {
    pub diameter_mm: f64,
    /// Its capacity at the design strength, `pi d^2 / 4 f_yd` (N).
    pub capacity: f64,
}

/// The smallest standard bar whose capacity at the design strength `fyd` (Pa) reaches
/// `force` (N); None above the largest.
pub fn bar_for(force: f64, fyd: f64) -> Option<Bar> {
    BAR_DIAMETERS_MM.iter().find_map(|&d| {
        let area = std::f64::consts::PI * (d * 1e-3).powi(2) / 4.0;
        let capacity = area * fyd;
        (capacity >= force).then_some(Bar {
            diameter_mm: d,
            capacity,
        })
    })
}

/// One designed tie.
#[derive(Debug, Clone, PartialEq)]
pub struct TieDesign {
    /// Index of the tie in the scene's `[[ties]]`.
    pub index: usize,
    /// The least capacity it needs (N); 0 when not needed.
    pub capacity: f64,
    pub needed: bool,
    pub cost: f64,
    /// The smallest standard bar that carries `capacity` (None when not needed, or above
    /// the largest bar).
    pub bar: Option<Bar>,
}

/// The outcome of a retrofit design.
#[derive(Debug)]
pub struct Retrofit {
    pub target: f64,
    /// Whether capacities reach the target.
    pub feasible: bool,
    /// The designed ties (all of them, needed or not), in the scene's order.
    pub ties: Vec<TieDesign>,
    /// The analysis with the designed capacities, one per direction (feasible designs).
    pub analyses: Vec<(Direction, SceneAnalysis)>,
    /// The largest multiplier any capacities reach in every direction (infeasible designs;
    /// None when the structure cannot stand whatever the ties).
    pub best_reachable: Option<f64>,
    /// The design strength of the bars (Pa).
    pub design_strength: f64,
}

impl Retrofit {
    /// The least of the re-analysed static multipliers over the directions.
    pub fn lambda(&self) -> Option<f64> {
        self.analyses
            .iter()
            .map(|(_, a)| a.lower.lambda)
            .try_fold(f64::INFINITY, |m, l| l.map(|l| m.min(l)))
            .filter(|m| m.is_finite())
    }

    /// The least of the re-analysed governing multipliers over the directions
    /// ([`SceneAnalysis::lambda_governing`]: the non-associative one where joints slide,
    /// docs/friction.md). The design itself is the static (associative) program's, so with
    /// sliding joints this may fall short of the target: the report says so.
    pub fn lambda_governing(&self) -> Option<f64> {
        self.analyses
            .iter()
            .map(|(_, a)| a.lambda_governing())
            .try_fold(f64::INFINITY, |m, l| l.map(|l| m.min(l)))
            .filter(|m| m.is_finite())
    }
}

/// Design the scene's `"design"` ties for lambda >= `target` (both directions of a seismic
/// action), then analyse the retrofitted structure with `options` (its direction is set per
/// direction here).
pub fn design(scene: &Scene, target: f64, options: &Options) -> Result<Retrofit, AnalysisError> {
    options.validate()?;
    if !(target.is_finite() && target > 0.0 && target < LAMBDA_CAP) {
        return Err(AnalysisError::Settings {
            setting: "target lambda".into(),
            value: target.to_string(),
            allowed: format!("a number > 0 and below {LAMBDA_CAP}"),
        });
    }
    let mut model = crate::scene::build_for_design(scene)?;
    let designed: Vec<DesignedTie> = scene
        .ties
        .iter()
        .enumerate()
        .filter(|(_, t)| t.capacity.is_none())
        .map(|(tie, t)| DesignedTie { tie, cost: t.cost })
        .collect();
    if designed.is_empty() {
        return Err(AnalysisError::Settings {
            setting: "ties[].capacity".into(),
            value: "a number for every tie".into(),
            allowed: "\"design\" for at least one [[ties]] entry: those are the ties a retrofit design sizes".into(),
        });
    }
    let directions: &[Direction] = match model.loads.action() {
        Action::Seismic => &[Direction::Right, Direction::Left],
        // The adequacy factor has no direction.
        Action::Live => &[Direction::Right],
    };
    let signs: Vec<f64> = directions.iter().map(|d| d.sign()).collect();
    let fyd = scene.material.tie_design_strength;
    let settings = &options.static_settings;
    match design::smallest_capacities(&model, &designed, target, &signs, settings)? {
        Design::Capacities(capacities) => {
            let floor = NOT_NEEDED * model.loads.force_scale();
            let mut ties = Vec::with_capacity(designed.len());
            for (dt, &c) in designed.iter().zip(&capacities) {
                let needed = c > floor;
                let capacity = if needed { c } else { 0.0 };
                let tie = &mut model.ties[dt.tie];
                tie.capacity = capacity.max(tie.prestress);
                ties.push(TieDesign {
                    index: dt.tie,
                    capacity,
                    needed,
                    cost: dt.cost,
                    bar: if needed { bar_for(capacity, fyd) } else { None },
                });
            }
            let mut analyses = Vec::with_capacity(directions.len());
            for &d in directions {
                let mut o = options.clone();
                o.static_settings = o.static_settings.direction(d);
                analyses.push((d, analysis::analyse_model(scene, model.clone(), &o)?));
            }
            Ok(Retrofit {
                target,
                feasible: true,
                ties,
                analyses,
                best_reachable: None,
                design_strength: fyd,
            })
        }
        Design::Infeasible => Ok(Retrofit {
            target,
            feasible: false,
            ties: designed
                .iter()
                .map(|dt| TieDesign {
                    index: dt.tie,
                    capacity: 0.0,
                    needed: false,
                    cost: dt.cost,
                    bar: None,
                })
                .collect(),
            analyses: Vec::new(),
            best_reachable: design::best_reachable(&model, &designed, &signs, settings)?,
            design_strength: fyd,
        }),
    }
}
