//! Minimum thickness: the smallest arch thickness t (every other parameter fixed, lambda = 0)
//! for which the structure can carry its own weight — Heyman's geometric factor of safety is
//! the ratio of the actual thickness to it (Heyman, *The Stone Skeleton*, 1995, ch. 3).
//!
//! The search does not assume that "stands" is monotone in t over the whole admissible range
//! (for portals it need not be): it scans a geometric grid from the top down to find the
//! smallest standing grid point, then bisects the interval below it to a relative tolerance.

use crate::assembly::Hinge;
use crate::error::AnalysisError;
use crate::kinematic::{self, KinematicSettings};
use crate::lp::{self, StandResult, StaticSettings, Status};
use crate::model::Model;
use crate::scene::Scene;

/// Relative tolerance of the bisection on t.
pub const DEFAULT_REL_TOL: f64 = 1e-9;

/// How the search ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum ThicknessOutcome {
    /// A minimum thickness was bracketed and bisected.
    Found,
    /// No admissible thickness lets the structure stand (e.g. friction too low, piers too
    /// slender).
    NeverStands,
    /// The structure stands at every thickness down to the smallest tried.
    StandsAtEveryThickness,
}

/// Result of a thickness search.
#[derive(Debug, Clone)]
pub struct ThicknessSearch {
    pub outcome: ThicknessOutcome,
    /// The minimum thickness (m), when found: the standing end of the final bracket.
    pub min_thickness: Option<f64>,
    /// Final bracket `[does not stand, stands]` (m).
    pub bracket: Option<(f64, f64)>,
    /// Number of analyses run.
    pub evaluations: usize,
}

/// Find the smallest thickness for which `stands` holds, to relative tolerance `rel_tol`.
pub fn search<F>(
    scene: &Scene,
    rel_tol: f64,
    mut stands: F,
) -> Result<ThicknessSearch, AnalysisError>
where
    F: FnMut(&Scene) -> Result<bool, AnalysisError>,
{
    scene.parametric("the minimum-thickness search")?;
    let t_max = scene.max_thickness();
    let mut evaluations = 0;
    let mut test = |t: f64| -> Result<bool, AnalysisError> {
        evaluations += 1;
        let trial = scene.with_thickness(t).map_err(|e| {
            AnalysisError::Other(format!(
                "the minimum-thickness search tried t = {t} m, where the scene does not hold: {e}"
            ))
        })?;
        stands(&trial)
    };
    // Geometric grid from just below the admissible maximum down to 1e-6 of it.
    const GRID: usize = 40;
    let top = t_max * (1.0 - 1e-6);
    // Not below the thinnest ring a scene admits (absolute and relative to the arch's size).
    let bottom = (t_max * 1e-6)
        .max(crate::scene::MIN_LENGTH)
        .max(2.0 * crate::scene::MIN_RELATIVE_THICKNESS * scene.arch_size())
        * (1.0 + 1e-9);
    let ratio = (bottom / top).powf(1.0 / (GRID - 1) as f64);
    let mut lowest_standing = None;
    let mut below = None;
    for k in 0..GRID {
        let t = (top * ratio.powi(k as i32)).max(bottom);
        if test(t)? {
            lowest_standing = Some(t);
        } else if lowest_standing.is_some() {
            below = Some(t);
            break;
        }
    }
    let Some(mut hi) = lowest_standing else {
        return Ok(ThicknessSearch {
            outcome: ThicknessOutcome::NeverStands,
            min_thickness: None,
            bracket: None,
            evaluations,
        });
    };
    let Some(mut lo) = below else {
        return Ok(ThicknessSearch {
            outcome: ThicknessOutcome::StandsAtEveryThickness,
            min_thickness: None,
            bracket: None,
            evaluations,
        });
    };
    while hi - lo > rel_tol * hi {
        let mid = 0.5 * (lo + hi);
        if test(mid)? {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    Ok(ThicknessSearch {
        outcome: ThicknessOutcome::Found,
        min_thickness: Some(hi),
        bracket: Some((lo, hi)),
        evaluations,
    })
}

/// Static minimum thickness with the hinges of the thrust line at that thickness.
#[derive(Debug, Clone)]
pub struct MinThickness {
    pub search: ThicknessSearch,
    /// Hinges of the thrust line at the minimum thickness (static solution there).
    pub hinges: Vec<Hinge>,
    /// The scene's own thickness divided by the minimum thickness.
    pub safety_factor: Option<f64>,
    /// The static analysis at the minimum thickness.
    pub at_minimum: Option<(Model, StandResult)>,
}

/// Whether the static program finds equilibrium at lambda = 0.
pub fn stands_static(scene: &Scene, settings: &StaticSettings) -> Result<bool, AnalysisError> {
    Ok(lp::stands(&crate::scene::build(scene)?, settings)?.stands)
}

/// The static minimum thickness of `scene`.
pub fn min_thickness(
    scene: &Scene,
    settings: &StaticSettings,
) -> Result<MinThickness, AnalysisError> {
    let search = search(scene, DEFAULT_REL_TOL, |s| stands_static(s, settings))?;
    let mut hinges = Vec::new();
    let mut at_minimum = None;
    if let Some(t) = search.min_thickness {
        let model = crate::scene::build(&scene.with_thickness(t)?)?;
        let r = lp::stands(&model, settings)?;
        hinges = r.hinges.clone();
        at_minimum = Some((model, r));
    }
    let thickness = scene.parametric("the minimum-thickness search")?.thickness;
    let safety_factor = search.min_thickness.map(|t| thickness / t);
    Ok(MinThickness {
        search,
        hinges,
        safety_factor,
        at_minimum,
    })
}

/// The kinematic minimum thickness: the thickness at which the discrete upper bound reaches
/// zero (the smallest t at which no admissible mechanism moves under self-weight alone).
pub fn min_thickness_kinematic(
    scene: &Scene,
    max_joints: usize,
) -> Result<ThicknessSearch, AnalysisError> {
    let settings = KinematicSettings {
        max_joints,
        ..KinematicSettings::default()
    };
    search(scene, DEFAULT_REL_TOL, |s| {
        let k = kinematic::analyse(&crate::scene::build(s)?, &settings)
            .map_err(|e| AnalysisError::Other(e.to_string()))?;
        Ok(k.status != Status::CannotStand)
    })
}

/// The minimum thickness by every method asked for.
#[derive(Debug, Clone)]
pub struct ThicknessAnalysis {
    /// The static search (always run).
    pub lower: MinThickness,
    /// The kinematic search (exhaustive, so only up to a chain size).
    pub kinematic: Option<ThicknessSearch>,
    /// Why the kinematic value is missing, or what it means here.
    pub kinematic_note: Option<String>,
    /// The continuous model's minimum thickness, when asked (or why it failed).
    pub continuous: Option<Result<crate::kinematic::MinThickness, String>>,
}

impl ThicknessAnalysis {
    /// `|t_static - t_kinematic| / t_static` when both exist.
    pub fn gap(&self) -> Option<f64> {
        let a = self.lower.search.min_thickness?;
        let b = self.kinematic.as_ref()?.min_thickness?;
        Some((a - b).abs() / a)
    }
}

/// The static minimum thickness, the kinematic one when the chain has at most
/// `kinematic_max_joints` joints (0: never), and the continuous one when `continuous`.
pub fn analyse(
    scene: &Scene,
    settings: &StaticSettings,
    kinematic_max_joints: usize,
    continuous: bool,
) -> Result<ThicknessAnalysis, AnalysisError> {
    let lower = min_thickness(scene, settings)?;
    let joints = crate::scene::build(scene)?.assembly.joints.len();
    let (kinematic, kinematic_note) = if kinematic_max_joints > 0 && joints <= kinematic_max_joints
    {
        let note = scene.material.friction.is_finite().then(|| {
            format!(
                "the kinematic search knows rotational mechanisms only: with mu = {} sliding may govern, and then its minimum thickness is the one without sliding",
                scene.material.friction
            )
        });
        (
            Some(min_thickness_kinematic(scene, kinematic_max_joints)?),
            note,
        )
    } else {
        (
            None,
            Some(format!(
                "kinematic search skipped: {joints} joints is more than {kinematic_max_joints}"
            )),
        )
    };
    let continuous = continuous
        .then(|| crate::analysis::continuous_min_thickness(scene).map_err(|e| e.to_string()));
    Ok(ThicknessAnalysis {
        lower,
        kinematic,
        kinematic_note,
        continuous,
    })
}
