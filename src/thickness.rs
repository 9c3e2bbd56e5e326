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
use crate::model::Model;
use crate::scene::Scene;
use crate::statics::{self, StandResult, StaticSettings, Status};

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
    scene.thickness_may_vary()?;
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
    statics::stands_at_rest(&crate::scene::build(scene)?, settings)
}

/// The static minimum thickness of `scene`.
pub fn min_thickness(
    scene: &Scene,
    settings: &StaticSettings,
) -> Result<MinThickness, AnalysisError> {
    // At lambda = 0 a live action's loads are absent: the minimum thickness would silently
    // be that of the structure without them. Say so instead.
    crate::analysis::seismic_only(
        scene,
        "the minimum thickness (it is found at lambda = 0, where live loads would be absent; give them as permanent loads with kind = \"seismic\" to include them)",
    )?;
    let search = search(scene, DEFAULT_REL_TOL, |s| stands_static(s, settings))?;
    let mut hinges = Vec::new();
    let mut at_minimum = None;
    if let Some(t) = search.min_thickness {
        let model = crate::scene::build(&scene.with_thickness(t)?)?;
        let r = statics::stands(&model, settings)?;
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

/// Relative tolerance of the bisection of the non-associative minimum thickness: every trial
/// is a sequence of programs (docs/friction.md), and the iteration settles to 1e-6.
pub const NON_ASSOCIATIVE_REL_TOL: f64 = 1e-6;

/// Whether `scene` stands with non-associative joints (Coulomb friction, slip without
/// opening; docs/friction.md): the static program finds equilibrium at lambda = 0, and in each
/// direction (one for a mirror-symmetric structure under self-weight) the non-associative
/// multiplier has converged and is >= 0. A direction whose iteration does not converge counts
/// as not standing: no standing is claimed that was not shown.
pub fn stands_non_associative(
    scene: &Scene,
    settings: &StaticSettings,
) -> Result<bool, AnalysisError> {
    let model = crate::scene::build(scene)?;
    if !statics::stands_at_rest(&model, settings)? {
        return Ok(false);
    }
    let directions: &[crate::outcome::Direction] = if statics::symmetric_self_weight(&model) {
        &[crate::outcome::Direction::Right]
    } else {
        &[
            crate::outcome::Direction::Right,
            crate::outcome::Direction::Left,
        ]
    };
    for &d in directions {
        let s = settings.clone().direction(d);
        let r = statics::analyse(&model, &s)?;
        match r.status {
            Status::CannotStand => return Ok(false),
            Status::NoCollapse => continue,
            Status::Collapse => {}
        }
        let friction = r.friction(&model.assembly);
        if friction.is_lower_bound() {
            // No joint slips in the mechanism of a chain: the associative collapse state is a
            // real one, taken as the real multiplier (docs/friction.md).
            if r.lambda.is_some_and(|l| l >= 0.0) {
                continue;
            }
            return Ok(false);
        }
        let na = statics::analyse_non_associative(
            &model,
            &s,
            &r,
            &statics::NonAssociativeSettings::default(),
        )?;
        if !(na.converged && na.lambda.is_some_and(|l| l >= 0.0)) {
            return Ok(false);
        }
    }
    Ok(true)
}

/// The minimum thickness with non-associative joints: the smallest thickness at which
/// [`stands_non_associative`] holds, bisected to [`NON_ASSOCIATIVE_REL_TOL`]. It is at least the
/// static (associative) one, since every non-associative solution is an admissible
/// equilibrium.
pub fn min_thickness_non_associative(
    scene: &Scene,
    settings: &StaticSettings,
) -> Result<ThicknessSearch, AnalysisError> {
    search(scene, NON_ASSOCIATIVE_REL_TOL, |s| {
        stands_non_associative(s, settings)
    })
}

/// The minimum thickness by every method asked for.
#[derive(Debug, Clone)]
pub struct ThicknessAnalysis {
    /// The static search (always run).
    pub lower: MinThickness,
    /// The kinematic minimum thickness: certified from the static one, or by the exhaustive
    /// search (then only up to a chain size).
    pub kinematic: Option<ThicknessSearch>,
    /// Which kinematic search gave `kinematic` (None when it did not run).
    pub kinematic_search: Option<kinematic::Search>,
    /// Why the kinematic value is missing, or what it means here.
    pub kinematic_note: Option<String>,
    /// The continuous model's minimum thickness, when asked (or why it failed).
    pub continuous: Option<Result<crate::kinematic::MinThickness, String>>,
    /// The minimum thickness with non-associative joints
    /// ([`min_thickness_non_associative`]), with `--friction non-associative` and finite
    /// friction; None otherwise.
    pub non_associative: Option<ThicknessSearch>,
}

impl ThicknessAnalysis {
    /// `|t_static - t_kinematic| / t_static` when both exist.
    pub fn gap(&self) -> Option<f64> {
        let a = self.lower.search.min_thickness?;
        let b = self.kinematic.as_ref()?.min_thickness?;
        Some((a - b).abs() / a)
    }
}

/// Relative agreement the certified kinematic thickness must reach with the static one: a few
/// times the bisection's tolerance.
pub const CERTIFY_REL_TOL: f64 = 10.0 * DEFAULT_REL_TOL;

/// The kinematic minimum thickness certified by the static one (the thickness analogue of
/// [`kinematic::certify`]). At the standing end `hi` of the static bracket the largest
/// multiplier in one direction is (almost) zero; the static solution there names the four
/// hinges of the governing mechanism. That mechanism is valued by virtual work on the models at
/// other thicknesses (same joints): `G(t)`, the work done against the permanent loads, changes
/// sign at its own minimum thickness, below which the mechanism proves that the structure
/// cannot stand (upper-bound theorem). The root is found by bisection in a bracket around the
/// static value, independently of the static program, and certifies the static value when the
/// two agree to [`CERTIFY_REL_TOL`]. Errors say why it does not certify; the caller then runs
/// the exhaustive search.
pub fn certify_min_thickness(
    scene: &Scene,
    lower: &MinThickness,
    settings: &StaticSettings,
) -> Result<ThicknessSearch, String> {
    let hi = lower
        .search
        .min_thickness
        .ok_or("no static minimum thickness to certify")?;
    let build = |t: f64| -> Result<Model, String> {
        let s = scene.with_thickness(t).map_err(|e| e.to_string())?;
        crate::scene::build(&s).map_err(|e| e.to_string())
    };
    // The static search keeps its model at t_min (= hi): no need to build it again.
    let built;
    let model = match &lower.at_minimum {
        Some((m, _)) => m,
        None => {
            built = build(hi)?;
            &built
        }
    };
    // The direction whose largest multiplier is (nearly) zero at hi is the one that binds.
    let mut governing: Option<statics::StaticResult> = None;
    for d in [
        crate::outcome::Direction::Right,
        crate::outcome::Direction::Left,
    ] {
        let r =
            statics::analyse(model, &settings.clone().direction(d)).map_err(|e| e.to_string())?;
        if r.status == Status::Collapse
            && governing.as_ref().is_none_or(|g| {
                r.lambda.unwrap_or(f64::INFINITY) < g.lambda.unwrap_or(f64::INFINITY)
            })
        {
            governing = Some(r);
        }
    }
    let around = governing.ok_or("no direction collapses at the static minimum thickness")?;
    let direction = around.direction;
    let ks = KinematicSettings::default().direction(direction);
    let certified = kinematic::certify(model, &around, &ks).map_err(|e| e.to_string())?;
    let mechanism = certified
        .mechanism
        .ok_or("the certified mechanism is missing")?;
    let hinges: Vec<(usize, crate::assembly::JointEnd)> =
        mechanism.hinges.iter().map(|h| (h.joint, h.end)).collect();
    let mut evaluations = 0;
    let mut work = |t: f64| -> Result<f64, String> {
        evaluations += 1;
        let m = build(t)?;
        kinematic::mechanism_work(&m, &hinges, direction)
            .map_err(|e| e.to_string())?
            .map(|(_, g)| g)
            .ok_or_else(|| {
                format!("the mechanism of the static hinges is not admissible at t = {t} m")
            })
    };
    // A bracket around the static value (not centred on it, so the bisection never tries the
    // static value itself), inside the admissible range.
    let (mut lo, mut up) = (
        hi * (1.0 - 1e-4),
        (hi * (1.0 + 3e-4)).min(scene.max_thickness() * (1.0 - 1e-9)),
    );
    let (g_lo, g_up) = (work(lo)?, work(up)?);
    if !(g_lo < 0.0 && g_up > 0.0) {
        return Err(format!(
            "the work of the permanent loads on the mechanism of the static hinges does not change sign near the static minimum thickness (G = {g_lo:.3e} at {lo} m, {g_up:.3e} at {up} m)"
        ));
    }
    // To near round-off, so the reported gap is the static search's own error.
    while up - lo > 1e-13 * up {
        let mid = 0.5 * (lo + up);
        if work(mid)? < 0.0 {
            lo = mid;
        } else {
            up = mid;
        }
    }
    if (up - hi).abs() > CERTIFY_REL_TOL * hi {
        return Err(format!(
            "the mechanism of the static hinges reaches zero at t = {up:.9} m, not at the static {hi:.9} m"
        ));
    }
    Ok(ThicknessSearch {
        outcome: ThicknessOutcome::Found,
        min_thickness: Some(up),
        bracket: Some((lo, up)),
        evaluations,
    })
}

/// The static minimum thickness, and the kinematic one and the continuous one as `options`
/// ask: the kinematic one certified from the static hinges by default
/// ([`certify_min_thickness`]), by the exhaustive search when asked or when that does not
/// certify (chains of at most `kinematic_max_joints` joints; 0: never).
pub fn analyse(
    scene: &Scene,
    options: &crate::analysis::Options,
) -> Result<ThicknessAnalysis, AnalysisError> {
    options.validate()?;
    if options.kinematic == crate::analysis::KinematicMode::General {
        // The kinematic minimum thickness is a root of the chain searches' multiplier in the
        // thickness; the general program answers one structure at a time (analyze, sweep).
        return Err(AnalysisError::Settings {
            setting: "kinematic (--kinematic)".to_string(),
            value: "general".to_string(),
            allowed: "certified or exhaustive: the minimum-thickness search values the chain's mechanisms (the general kinematic program is for analyze and sweep)".to_string(),
        });
    }
    let settings = &options.static_settings;
    let max_joints = options.kinematic_max_joints;
    let lower = min_thickness(scene, settings)?;
    let joints = crate::scene::build(scene)?.assembly.joints.len();
    let mut kinematic = None;
    let mut kinematic_search = None;
    let mut notes = Vec::new();
    let crushing = scene.material.compressive_strength.is_finite();
    if crushing {
        // The certificate and the exhaustive search value mechanisms with hinges at the joint
        // ends: they know rigid joints only.
        notes.push(format!(
            "rigid hinges: the kinematic search ignores the compressive strength ({:e} Pa), so its minimum thickness is the rigid structure's, below the crushing one",
            scene.material.compressive_strength
        ));
    }
    if options.kinematic == crate::analysis::KinematicMode::Certified
        && lower.search.min_thickness.is_some()
        && !crushing
    {
        match certify_min_thickness(scene, &lower, settings) {
            Ok(k) => {
                notes.push(format!(
                    "certified: the mechanism of the static hinges at t_min, valued by virtual work, reaches zero within {:.0e} of it",
                    CERTIFY_REL_TOL
                ));
                kinematic = Some(k);
                kinematic_search = Some(kinematic::Search::Certified);
            }
            Err(why) => notes.push(format!("not certified ({why})")),
        }
    }
    if kinematic.is_none() {
        if max_joints > 0 && joints <= max_joints {
            kinematic = Some(min_thickness_kinematic(scene, max_joints)?);
            kinematic_search = Some(kinematic::Search::Exhaustive);
        } else {
            notes.push(format!(
                "kinematic search skipped: {joints} joints is more than {max_joints}"
            ));
        }
    }
    if kinematic.is_some() && scene.material.friction.is_finite() {
        notes.push(format!(
            "the kinematic search knows rotational mechanisms only: with mu = {} sliding may govern, and then its minimum thickness is the one without sliding",
            scene.material.friction
        ));
    }
    let continuous = options
        .continuous
        .then(|| crate::analysis::continuous_min_thickness(scene).map_err(|e| e.to_string()));
    let finite = crate::scene::build(scene)?
        .assembly
        .joints
        .iter()
        .any(|j| j.friction.is_finite());
    let non_associative =
        if options.friction == crate::analysis::FrictionMode::NonAssociative && finite {
            Some(min_thickness_non_associative(scene, settings)?)
        } else {
            None
        };
    Ok(ThicknessAnalysis {
        non_associative,
        lower,
        kinematic,
        kinematic_search,
        kinematic_note: (!notes.is_empty()).then(|| notes.join("; ")),
        continuous,
    })
}
