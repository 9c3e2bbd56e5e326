//! Retrofit design: the smallest tie rods and bonded strips that make a structure carry a
//! target multiplier.
//!
//! The scene's ties whose `capacity` is `"design"` and strips (`[[reinforcements]]`) whose
//! `tensile_capacity` is `"design"` are sized by one program ([`crate::statics::design`]): the
//! least total capacity, weighted by each element's `cost`, for which the static program
//! carries lambda = target in both directions of a seismic action (the one direction of a
//! live action's adequacy factor). A strip's capacity is its debonding force at each joint it
//! crosses (one value for the whole strip, as the scene gives it). The structure is then
//! analysed again with those capacities, by the same analysis as `voussoir analyze` (static
//! and certified kinematic bounds), in each direction; and each needed tie capacity is
//! matched with the smallest standard steel bar that carries it at the design strength
//! `material.tie_design_strength` (default 391 MPa: B450C, 450 MPa over 1.15). A strip gets
//! no bar: the debonding force is the strip system's (its product, its width, the bond to the
//! masonry, CNR-DT 200), which the engineer chooses to reach it. A target no capacities reach
//! is reported with the best multiplier reachable.

use crate::analysis::{self, Options, SceneAnalysis};
use crate::error::AnalysisError;
use crate::model::Action;
use crate::outcome::{Direction, LAMBDA_CAP};
use crate::scene::Scene;
use crate::statics::design::{self, Design, Designed, Element};

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

/// One designed bonded strip (a `[[reinforcements]]` entry).
#[derive(Debug, Clone, PartialEq)]
pub struct StripDesign {
    /// Index of the strip in the scene's `[[reinforcements]]`.
    pub index: usize,
    /// The least debonding force it needs at each joint it crosses (N); 0 when not needed.
    pub capacity: f64,
    pub needed: bool,
    pub cost: f64,
}

/// The outcome of a retrofit design.
#[derive(Debug)]
pub struct Retrofit {
    pub target: f64,
    /// Whether capacities reach the target.
    pub feasible: bool,
    /// The designed ties (all of them, needed or not), in the scene's order.
    pub ties: Vec<TieDesign>,
    /// The designed strips (all of them, needed or not), in the scene's order.
    pub strips: Vec<StripDesign>,
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

/// Design the scene's `"design"` ties and strips for lambda >= `target` (both directions of
/// a seismic action), then analyse the retrofitted structure with `options` (its direction is
/// set per direction here).
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
    let ties = (scene.ties.iter().enumerate())
        .filter(|(_, t)| t.capacity.is_none())
        .map(|(k, t)| Designed {
            element: Element::Tie(k),
            cost: t.cost,
        });
    let strips = (scene.reinforcements.iter().enumerate())
        .filter(|(_, r)| r.tensile_capacity.is_none())
        .map(|(k, r)| Designed {
            element: Element::Strip(k),
            cost: r.cost,
        });
    let designed: Vec<Designed> = ties.chain(strips).collect();
    if designed.is_empty() {
        return Err(AnalysisError::Settings {
            setting: "ties[].capacity, reinforcements[].tensile_capacity".into(),
            value: "a number for every tie and strip".into(),
            allowed: "\"design\" for at least one [[ties]] capacity or [[reinforcements]] tensile_capacity: those are what a retrofit design sizes".into(),
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
    let (capacities, feasible) =
        match design::smallest_capacities(&model, &designed, target, &signs, settings)? {
            Design::Capacities(c) => (c, true),
            Design::Infeasible => (vec![0.0; designed.len()], false),
        };
    let floor = NOT_NEEDED * model.loads.force_scale();
    let (mut ties, mut strips) = (Vec::new(), Vec::new());
    for (d, &c) in designed.iter().zip(&capacities) {
        let needed = c > floor;
        let capacity = if needed { c } else { 0.0 };
        match d.element {
            Element::Tie(index) => {
                let tie = &mut model.ties[index];
                tie.capacity = capacity.max(tie.prestress);
                ties.push(TieDesign {
                    index,
                    capacity,
                    needed,
                    cost: d.cost,
                    bar: if needed { bar_for(capacity, fyd) } else { None },
                });
            }
            Element::Strip(index) => {
                for s in model.strips.iter_mut().filter(|s| s.source == index) {
                    s.capacity = capacity;
                }
                strips.push(StripDesign {
                    index,
                    capacity,
                    needed,
                    cost: d.cost,
                });
            }
        }
    }
    if !feasible {
        return Ok(Retrofit {
            target,
            feasible,
            ties,
            strips,
            analyses: Vec::new(),
            best_reachable: design::best_reachable(&model, &designed, &signs, settings)?,
            design_strength: fyd,
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
        feasible,
        ties,
        strips,
        analyses,
        best_reachable: None,
        design_strength: fyd,
    })
}

/// A retrofit design for a site: the least capacities whose structure passes the NTC 2018
/// check there ([`design_for_site`]).
#[derive(Debug)]
pub struct SiteRetrofit {
    /// The design at the multiplier found (its `target`), or the infeasible design at the
    /// largest multiplier tried.
    pub design: Retrofit,
    /// The assessment of the designed structure at the site (None when no capacities make
    /// it pass).
    pub assessment: Option<analysis::Assessment>,
    /// The least target multiplier whose design passed (the bisection's upper end), and the
    /// largest that failed (its lower end; None when the structure passes without new ties).
    pub bracket: (Option<f64>, f64),
    /// Designs and assessments computed.
    pub evaluations: usize,
}

/// Relative width of the final bracket of the multiplier a site needs.
pub const SITE_TARGET_TOLERANCE: f64 = 1e-3;

/// The scene with the designed ties' and strips' capacities written in (so that every
/// analysis of a scene, the assessment first, reads the retrofitted structure).
pub fn designed_scene(scene: &Scene, r: &Retrofit) -> Scene {
    let mut s = scene.clone();
    for t in &r.ties {
        if let Some(spec) = s.ties.get_mut(t.index) {
            spec.capacity = Some(t.capacity.max(spec.prestress));
        }
    }
    for t in &r.strips {
        if let Some(spec) = s.reinforcements.get_mut(t.index) {
            spec.tensile_capacity = Some(t.capacity);
        }
    }
    s
}

/// Design the scene's `"design"` ties so that the retrofitted structure passes the NTC 2018
/// kinematic check at the scene's `[site]` (both directions, each by the linear or the
/// nonlinear check, [`crate::assess::RULE`]).
///
/// The verdict is not a linear function of the capacities (the governing mechanism, its
/// participating mass and its capacity curve change with them), so the design searches the
/// least target multiplier lambda* whose least-capacity design ([`fn@design`]) passes `assess`:
/// first lambda* = its least value (the structure as it is), then a growing target until one
/// passes (or no capacities reach it), then bisection to [`SITE_TARGET_TOLERANCE`]. A stiffer
/// design passing at a lower target than a weaker one would escape the bisection: the
/// passing design it returns is checked, so it passes, but it is the least only where the
/// verdict grows with the target, as it did on every portal tried (docs/retrofit.md).
pub fn design_for_site(
    scene: &Scene,
    options: &Options,
    assess: &analysis::AssessOptions,
) -> Result<SiteRetrofit, AnalysisError> {
    if !scene.reinforcements.is_empty() {
        // `assess` refuses strips (`AssessError::Strips`): no verdict to design for.
        return Err(AnalysisError::Other(format!(
            "{}: reinforcements[0]: a site design needs the NTC 2018 verdict of `voussoir assess`, whose capacity curve does not follow bonded strips (a rigid-plastic strip debonds at the first opening of its joint; docs/assessment.md); design the strips for a multiplier instead (--target-lambda)",
            scene.origin
        )));
    }
    if scene.site.is_none() {
        return Err(AnalysisError::Other(format!(
            "{}: no [site] table: give one in the scene or with --site ag=0.25 --site soil=B --site F0=2.4 --site Tc_star=0.3 (or --site latitude=42.35 --site longitude=13.40 --site soil=B for the national hazard grid, docs/assessment.md)",
            scene.origin
        )));
    }
    let mut evaluations = 0;
    // The verdict of the least-capacity design for `target`: the design, and its assessment
    // when feasible.
    let mut trial =
        |target: f64| -> Result<(Retrofit, Option<analysis::Assessment>), AnalysisError> {
            evaluations += 1;
            let r = design(scene, target, options)?;
            if !r.feasible {
                return Ok((r, None));
            }
            let a = analysis::assess_directions(&designed_scene(scene, &r), options, assess, None)
                .map_err(|e| {
                    AnalysisError::Other(format!(
                        "assessing the design for lambda >= {target:.6}: {e}"
                    ))
                })?;
            Ok((r, Some(a)))
        };
    let passes = |a: &Option<analysis::Assessment>| a.as_ref().is_some_and(|a| a.passes());
    // The structure as it is: the least target (every designed capacity 0).
    let start = LAMBDA_FLOOR;
    let (r, a) = trial(start)?;
    if passes(&a) {
        return Ok(SiteRetrofit {
            design: r,
            assessment: a,
            bracket: (None, start),
            evaluations,
        });
    }
    let mut lo = r.lambda().unwrap_or(start).max(start);
    let mut hi = (2.0 * lo).max(0.05);
    let mut found = None;
    while hi < LAMBDA_CAP {
        let (r, a) = trial(hi)?;
        if !r.feasible {
            // Past what the ties can reach: the strongest design they allow is the last
            // chance (just below the reachable multiplier, so that it is feasible).
            let reach = r
                .best_reachable
                .map(|b| b * (1.0 - 1e-6))
                .filter(|&b| b > lo);
            let last = match reach {
                Some(b) => Some((b, trial(b)?)),
                None => None,
            };
            match last {
                Some((b, (r, a))) if passes(&a) => {
                    hi = b;
                    found = Some((r, a));
                    break;
                }
                _ => {
                    return Ok(SiteRetrofit {
                        design: r,
                        assessment: None,
                        bracket: (Some(lo), hi),
                        evaluations,
                    })
                }
            }
        }
        if passes(&a) {
            found = Some((r, a));
            break;
        }
        lo = hi;
        hi *= 1.5;
    }
    let Some(mut best) = found else {
        return Err(AnalysisError::Other(format!(
            "no design up to lambda = {LAMBDA_CAP} passes at the site"
        )));
    };
    while hi - lo > SITE_TARGET_TOLERANCE * hi {
        let mid = 0.5 * (lo + hi);
        let (r, a) = trial(mid)?;
        if passes(&a) {
            hi = mid;
            best = (r, a);
        } else {
            lo = mid;
        }
    }
    Ok(SiteRetrofit {
        design: best.0,
        assessment: best.1,
        bracket: (Some(lo), hi),
        evaluations,
    })
}

/// The least target multiplier a site design tries: the structure as it is, every designed
/// capacity 0 (a design needs a positive target).
const LAMBDA_FLOOR: f64 = 1e-6;
