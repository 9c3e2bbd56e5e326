//! Speed against accuracy (`voussoir convergence`): how the collapse multiplier and the cost of
//! each method change with the discretisation and the solver settings, for one scene.
//!
//! Three studies:
//! 1. **Refinement**: the arch is cut into n = 8, 16, 32, ... voussoirs (doubling, up to
//!    [`ConvergenceSettings::max_voussoirs`]); for each n the static lower bound (the conic
//!    program of [`crate::statics`]) and, where the chain is small enough, the discrete kinematic
//!    upper bound are computed and compared with the continuous model ([`crate::analysis::
//!    continuous`], hinges anywhere: the limit n -> infinity). A discrete arch can only
//!    hinge at its joints, so it is stronger than the continuum and its multiplier falls
//!    toward the continuous one as n grows. Where the optimal hinge sections are interior
//!    points of a smooth function of the section angle, the gap is quadratic in the joint
//!    spacing (the multiplier is stationary at the optimum), so the error should fall about
//!    as n^-2; the fitted order is reported ([`Convergence::order_lower`]).
//! 2. **Solver tolerance**: the static program at the scene's own n with Clarabel's gap and
//!    feasibility tolerances at 1e-4 .. 1e-10, against the tightest.
//! 3. **DEM settings** (on a small copy of the scene, [`ConvergenceSettings::dem_voussoirs`]):
//!    the DEM bracket (see [`crate::dem::collapse_multiplier`]) at a few bracket tolerances,
//!    time steps and contact stiffnesses, against the static multiplier of the same
//!    discretisation (for rigid blocks with associative joints the static and kinematic
//!    bounds coincide, so that is the exact multiplier the DEM should find). The DEM starts
//!    from a neutral guess ([`ConvergenceSettings::dem_start`]), not from the static value,
//!    so its bracket is its own.
//!
//! Wall times are measured one method at a time on one thread (the kinematic search is told
//! not to use rayon), so they compare.

use std::time::Instant;

use crate::analysis::KINEMATIC_DEFAULT_MAX_JOINTS;
use crate::dem::{self, IntegrationParameters};
use crate::kinematic::{self, KinematicSettings};
use crate::model::Model;
use crate::scene::Scene;
use crate::statics::{self, Direction, StaticSettings, Status};

/// Errors of the convergence study (a failed row is recorded in the row, not here).
#[derive(Debug, thiserror::Error)]
pub enum ConvergenceError {
    #[error("convergence settings: {0}")]
    Settings(String),
    #[error(transparent)]
    Scene(#[from] crate::error::SceneError),
}

/// What to run.
#[derive(Debug, Clone)]
pub struct ConvergenceSettings {
    /// Direction of the load. Default right.
    pub direction: Direction,
    /// Smallest voussoir count of the refinement. Default 8.
    pub min_voussoirs: usize,
    /// Largest voussoir count of the refinement (the counts double from `min_voussoirs`).
    /// Default 1024.
    pub max_voussoirs: usize,
    /// Largest chain (joints) searched kinematically. Default
    /// [`KINEMATIC_DEFAULT_MAX_JOINTS`]; 0 turns the search off.
    pub kinematic_max_joints: usize,
    /// Run the continuous model (the reference of the errors). Default true.
    pub continuous: bool,
    /// Clarabel tolerances tried at the scene's own voussoir count; empty skips the study.
    /// Default 1e-4, 1e-6, 1e-8, 1e-10.
    pub solver_tolerances: Vec<f64>,
    /// Run the DEM study. Default true.
    pub dem: bool,
    /// Voussoirs of the scene the DEM study runs on (at most the scene's own count; it must
    /// stay small: the DEM costs about a second per bracket at 20 blocks). Default 16.
    pub dem_voussoirs: usize,
    /// The DEM settings tried.
    pub dem_cases: Vec<DemCase>,
    /// Where each DEM bracket search starts. Default 0.2 (the DEM's own default when it has
    /// no static value), so the bracket does not merely confirm the static multiplier.
    pub dem_start: f64,
}

/// One DEM setting of the study: factors on the defaults of [`IntegrationParameters`].
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct DemCase {
    /// Relative width of the final bracket.
    pub tolerance: f64,
    /// Fraction of the explicit stability limit used as the time step (default 0.9).
    pub time_step_factor: f64,
    /// Factor on the default normal and shear contact stiffness.
    pub stiffness_factor: f64,
}

impl DemCase {
    pub fn new(tolerance: f64, time_step_factor: f64, stiffness_factor: f64) -> Self {
        DemCase {
            tolerance,
            time_step_factor,
            stiffness_factor,
        }
    }
}

impl Default for ConvergenceSettings {
    fn default() -> Self {
        ConvergenceSettings {
            direction: Direction::Right,
            min_voussoirs: 8,
            max_voussoirs: 1024,
            kinematic_max_joints: KINEMATIC_DEFAULT_MAX_JOINTS,
            continuous: true,
            solver_tolerances: vec![1e-4, 1e-6, 1e-8, 1e-10],
            dem: true,
            dem_voussoirs: 16,
            dem_cases: vec![
                DemCase::new(0.04, 0.9, 1.0),
                DemCase::new(0.01, 0.9, 1.0),
                DemCase::new(0.0025, 0.9, 1.0),
                DemCase::new(0.0025, 0.45, 1.0),
                DemCase::new(0.0025, 0.9, 0.1),
                DemCase::new(0.0025, 0.9, 10.0),
            ],
            dem_start: 0.2,
        }
    }
}

impl ConvergenceSettings {
    /// The voussoir counts of the refinement: `min_voussoirs` doubled up to `max_voussoirs`.
    pub fn voussoir_counts(&self) -> Vec<usize> {
        let mut v = Vec::new();
        let mut n = self.min_voussoirs.max(1);
        while n <= self.max_voussoirs {
            v.push(n);
            n = n.saturating_mul(2);
        }
        v
    }

    fn check(&self) -> Result<(), ConvergenceError> {
        let bad = |m: String| Err(ConvergenceError::Settings(m));
        if self.min_voussoirs == 0 || self.min_voussoirs > self.max_voussoirs {
            return bad(format!(
                "voussoir range {}..{}: need 1 <= min <= max",
                self.min_voussoirs, self.max_voussoirs
            ));
        }
        if self.max_voussoirs > crate::scene::MAX_VOUSSOIRS {
            return bad(format!(
                "max_voussoirs = {}: at most {}",
                self.max_voussoirs,
                crate::scene::MAX_VOUSSOIRS
            ));
        }
        for &t in &self.solver_tolerances {
            if !(t.is_finite() && t > 0.0 && t < 1e-2) {
                return bad(format!("solver tolerance {t}: must be > 0 and < 1e-2"));
            }
        }
        if self.dem {
            if self.dem_voussoirs == 0 {
                return bad("dem_voussoirs = 0".into());
            }
            if !(self.dem_start.is_finite() && self.dem_start > 0.0) {
                return bad(format!("dem_start = {}: must be > 0", self.dem_start));
            }
            for c in &self.dem_cases {
                let ok = c.tolerance > 0.0
                    && c.tolerance < 1.0
                    && c.time_step_factor > 0.0
                    && c.time_step_factor <= 1.0
                    && c.stiffness_factor.is_finite()
                    && c.stiffness_factor > 0.0;
                if !ok {
                    return bad(format!("DEM case {c:?}: tolerance in (0, 1), time step factor in (0, 1], stiffness factor > 0"));
                }
            }
        }
        Ok(())
    }
}

/// One voussoir count of the refinement.
#[derive(Debug, Clone, serde::Serialize)]
pub struct RefinementRow {
    pub voussoirs: usize,
    pub joints: usize,
    /// "collapse", "no_collapse", "cannot_stand" or "error".
    pub status: String,
    pub lambda_lower: Option<f64>,
    /// Wall time of the static program (assembly, build and solve), s.
    pub lower_time_s: f64,
    pub lower_iterations: u32,
    pub lambda_upper: Option<f64>,
    /// Wall time of the kinematic search (None when it did not run), s.
    pub upper_time_s: Option<f64>,
    /// Why there is no upper bound (skipped for size, or the error).
    pub upper_note: Option<String>,
    /// `(lambda_lower - lambda_continuous) / lambda_continuous`.
    pub error_lower: Option<f64>,
    /// `(lambda_upper - lambda_continuous) / lambda_continuous`.
    pub error_upper: Option<f64>,
    /// The scene error for this count (e.g. too few voussoirs for the embrace).
    pub error: Option<String>,
}

/// One Clarabel tolerance.
#[derive(Debug, Clone, serde::Serialize)]
pub struct ToleranceRow {
    pub tolerance: f64,
    pub voussoirs: usize,
    pub status: String,
    pub lambda_lower: Option<f64>,
    /// `|lambda - lambda at the tightest tolerance| / lambda at the tightest tolerance`.
    pub difference: Option<f64>,
    /// Largest out-of-balance force of a block over the total weight.
    pub residual_over_weight: Option<f64>,
    pub iterations: u32,
    pub time_s: f64,
    pub error: Option<String>,
}

/// One DEM setting.
#[derive(Debug, Clone, serde::Serialize)]
pub struct DemRow {
    #[serde(flatten)]
    pub case: DemCase,
    pub voussoirs: usize,
    /// The time stepping that ran (`explicit` or `moreau`: the study names the explicit
    /// stepping's knobs, so `auto` takes the explicit one; `dem.integrator = "moreau"` in the
    /// scene forces the rigid one, whose step and contacts these rows' factors do not touch).
    pub integrator: &'static str,
    pub time_step_s: f64,
    pub normal_stiffness: f64,
    pub lambda_stands: Option<f64>,
    pub lambda_collapses: Option<f64>,
    pub lambda_dem: Option<f64>,
    /// The static multiplier of the same discretisation, the exact value for rigid blocks.
    pub lambda_static: Option<f64>,
    /// `(lambda_dem - lambda_static) / lambda_static`.
    pub error: Option<f64>,
    /// Whether `lambda_stands <= lambda_static <= lambda_collapses`.
    pub brackets_static: Option<bool>,
    pub runs: usize,
    pub steps: u64,
    /// Time steps per second of wall time.
    pub steps_per_s: f64,
    pub time_s: f64,
    pub error_message: Option<String>,
}

/// The whole study.
#[derive(Debug, Clone, serde::Serialize)]
pub struct Convergence {
    pub origin: String,
    pub direction: Direction,
    /// The continuous model's multiplier (the reference of the errors).
    pub lambda_continuous: Option<f64>,
    pub continuous_time_s: Option<f64>,
    /// Why there is no continuous value.
    pub continuous_note: Option<String>,
    pub refinement: Vec<RefinementRow>,
    /// Least-squares slope of log|error_lower| against log n over the rows with an error:
    /// the order of convergence (about -2 expected).
    pub order_lower: Option<f64>,
    /// The same for the upper bound.
    pub order_upper: Option<f64>,
    /// Least-squares slope of log(static time) against log n over rows with n >= 64.
    pub lower_time_exponent: Option<f64>,
    pub tolerances: Vec<ToleranceRow>,
    /// Where the DEM bracket searches started.
    pub dem_start: f64,
    pub dem: Vec<DemRow>,
}

/// Least-squares slope of `ln y` against `ln x` over the points with `x, y > 0` finite; None
/// with fewer than two such points or all x equal.
pub fn loglog_slope(points: &[(f64, f64)]) -> Option<f64> {
    let p: Vec<(f64, f64)> = points
        .iter()
        .filter(|(x, y)| x.is_finite() && y.is_finite() && *x > 0.0 && *y > 0.0)
        .map(|(x, y)| (x.ln(), y.ln()))
        .collect();
    if p.len() < 2 {
        return None;
    }
    let n = p.len() as f64;
    let (mx, my) = p
        .iter()
        .fold((0.0, 0.0), |(a, b), (x, y)| (a + x / n, b + y / n));
    let (sxy, sxx) = p.iter().fold((0.0, 0.0), |(a, b), (x, y)| {
        (a + (x - mx) * (y - my), b + (x - mx) * (x - mx))
    });
    (sxx > 0.0).then(|| sxy / sxx)
}

fn status_word(s: Status) -> String {
    s.as_str().to_string()
}

fn rel(value: Option<f64>, reference: Option<f64>) -> Option<f64> {
    match (value, reference) {
        (Some(v), Some(r)) if r != 0.0 => Some((v - r) / r),
        _ => None,
    }
}

/// `scene` with `n` voussoirs.
fn with_voussoirs(scene: &Scene, n: usize) -> Result<Scene, crate::error::SceneError> {
    scene.with_value("arch.voussoirs", toml::Value::Integer(n as i64))
}

/// Run the study. `progress` is called with a short description before each step.
pub fn run(
    scene: &Scene,
    settings: &ConvergenceSettings,
    progress: &mut dyn FnMut(&str),
) -> Result<Convergence, ConvergenceError> {
    settings.check()?;
    scene.parametric("the convergence study")?;
    let static_settings = StaticSettings::default().direction(settings.direction);

    let (lambda_continuous, continuous_time_s, continuous_note) = if settings.continuous {
        progress("continuous model");
        let clock = Instant::now();
        match crate::analysis::continuous(scene, settings.direction) {
            Ok(c) => {
                let t = clock.elapsed().as_secs_f64();
                let note = c
                    .lambda_continuous
                    .is_none()
                    .then(|| format!("continuous model: {}", c.status.as_str()));
                (c.lambda_continuous, Some(t), note)
            }
            Err(e) => (None, None, Some(e.to_string())),
        }
    } else {
        (None, None, Some("continuous model not run".to_string()))
    };

    let mut refinement = Vec::new();
    for n in settings.voussoir_counts() {
        progress(&format!("n = {n}"));
        refinement.push(refine_row(
            scene,
            n,
            settings,
            &static_settings,
            lambda_continuous,
        ));
    }

    let mut tolerances = Vec::new();
    if !settings.solver_tolerances.is_empty() {
        let model = crate::scene::build(scene)?;
        let mut tols = settings.solver_tolerances.clone();
        tols.sort_by(|a, b| b.total_cmp(a));
        for tol in tols {
            progress(&format!("tolerance {tol:e}"));
            let clock = Instant::now();
            // The study is of the interior-point solver's tolerance, so it runs the full
            // program: the chain program's exact vertex step removes the tolerance's effect on
            // lambda wherever it finds the vertex.
            let r = statics::analyse(
                &model,
                &static_settings
                    .clone()
                    .tolerance(tol)
                    .program(statics::Program::Full),
            );
            let time_s = clock.elapsed().as_secs_f64();
            tolerances.push(match r {
                Ok(r) => ToleranceRow {
                    tolerance: tol,
                    voussoirs: scene.parametric("the convergence study")?.voussoirs,
                    status: status_word(r.status),
                    lambda_lower: r.lambda,
                    difference: None,
                    residual_over_weight: r
                        .lambda
                        .map(|_| r.equilibrium_residual / model.loads.force_scale()),
                    iterations: r.iterations,
                    time_s,
                    error: None,
                },
                Err(e) => ToleranceRow {
                    tolerance: tol,
                    voussoirs: scene.parametric("the convergence study")?.voussoirs,
                    status: "error".into(),
                    lambda_lower: None,
                    difference: None,
                    residual_over_weight: None,
                    iterations: 0,
                    time_s,
                    error: Some(e.to_string()),
                },
            });
        }
        // The tightest tolerance is the reference.
        let best = tolerances.last().and_then(|r| r.lambda_lower);
        for r in &mut tolerances {
            r.difference = rel(r.lambda_lower, best).map(f64::abs);
        }
    }

    let mut dem_rows = Vec::new();
    if settings.dem && !settings.dem_cases.is_empty() {
        let n = settings
            .dem_voussoirs
            .min(scene.parametric("the convergence study")?.voussoirs);
        let small = with_voussoirs(scene, n)?;
        let model = crate::scene::build(&small)?;
        let lambda_static = statics::analyse(&model, &static_settings)
            .ok()
            .and_then(|r| r.lambda);
        let base = crate::analysis::dem_parameters(&small, &model)?;
        for case in &settings.dem_cases {
            progress(&format!(
                "DEM n = {n}, tolerance {}, time step x{}, stiffness x{}",
                case.tolerance, case.time_step_factor, case.stiffness_factor
            ));
            dem_rows.push(dem_row(
                &model,
                &base,
                case,
                n,
                lambda_static,
                settings.dem_start,
            ));
        }
    }

    let err_points = |f: fn(&RefinementRow) -> Option<f64>| -> Vec<(f64, f64)> {
        refinement
            .iter()
            .filter_map(|r| f(r).map(|e| (r.voussoirs as f64, e.abs())))
            .collect()
    };
    let order_lower = loglog_slope(&err_points(|r| r.error_lower));
    let order_upper = loglog_slope(&err_points(|r| r.error_upper));
    let time_points: Vec<(f64, f64)> = refinement
        .iter()
        .filter(|r| r.voussoirs >= 64 && r.lambda_lower.is_some())
        .map(|r| (r.voussoirs as f64, r.lower_time_s))
        .collect();
    Ok(Convergence {
        origin: scene.origin.clone(),
        direction: settings.direction,
        lambda_continuous,
        continuous_time_s,
        continuous_note,
        refinement,
        order_lower,
        order_upper,
        lower_time_exponent: loglog_slope(&time_points),
        tolerances,
        dem_start: settings.dem_start,
        dem: dem_rows,
    })
}

fn refine_row(
    scene: &Scene,
    n: usize,
    settings: &ConvergenceSettings,
    static_settings: &StaticSettings,
    reference: Option<f64>,
) -> RefinementRow {
    let mut row = RefinementRow {
        voussoirs: n,
        joints: 0,
        status: "error".into(),
        lambda_lower: None,
        lower_time_s: 0.0,
        lower_iterations: 0,
        lambda_upper: None,
        upper_time_s: None,
        upper_note: None,
        error_lower: None,
        error_upper: None,
        error: None,
    };
    let s = match with_voussoirs(scene, n) {
        Ok(s) => s,
        Err(e) => {
            row.error = Some(e.to_string());
            return row;
        }
    };
    let clock = Instant::now();
    let model = match crate::scene::build(&s) {
        Ok(m) => m,
        Err(e) => {
            row.error = Some(e.to_string());
            return row;
        }
    };
    let assembly = &model.assembly;
    let lower = statics::analyse(&model, static_settings);
    row.lower_time_s = clock.elapsed().as_secs_f64();
    row.joints = assembly.joints.len();
    match lower {
        Ok(r) => {
            row.status = status_word(r.status);
            row.lambda_lower = r.lambda;
            row.lower_iterations = r.iterations;
        }
        Err(e) => row.error = Some(e.to_string()),
    }
    if settings.kinematic_max_joints == 0 {
        row.upper_note = Some("kinematic search turned off".into());
    } else if row.joints > settings.kinematic_max_joints {
        row.upper_note = Some(format!(
            "skipped: {} joints > {} (candidates grow as joints^4, cost as about joints^3.6)",
            row.joints, settings.kinematic_max_joints
        ));
    } else {
        let ks = KinematicSettings {
            direction: settings.direction,
            max_joints: settings.kinematic_max_joints,
            parallel: false,
            ..KinematicSettings::default()
        };
        let clock = Instant::now();
        let k = kinematic::analyse(&model, &ks);
        row.upper_time_s = Some(clock.elapsed().as_secs_f64());
        match k {
            Ok(k) => {
                row.lambda_upper = k.lambda_upper;
                if k.lambda_upper.is_none() {
                    row.upper_note = Some(k.status.as_str().to_string());
                }
            }
            Err(e) => row.upper_note = Some(e.to_string()),
        }
    }
    row.error_lower = rel(row.lambda_lower, reference);
    row.error_upper = rel(row.lambda_upper, reference);
    row
}

fn dem_row(
    model: &Model,
    base: &IntegrationParameters,
    case: &DemCase,
    n: usize,
    lambda_static: Option<f64>,
    start: f64,
) -> DemRow {
    let params = base
        .clone()
        .time_step_factor(case.time_step_factor)
        .normal_stiffness(base.normal_stiffness * case.stiffness_factor)
        .shear_stiffness(base.shear_stiffness * case.stiffness_factor)
        .initial_guess(Some(start));
    // The stepping `auto` takes for this search (the one `collapse_multiplier` runs).
    let integrator = params
        .resolved(model, dem::Purpose::CollapseSearch)
        .integrator
        .name();
    let clock = Instant::now();
    let r = dem::collapse_multiplier(model, &params, case.tolerance, &mut |_| {});
    let time_s = clock.elapsed().as_secs_f64();
    match r {
        Ok(r) => DemRow {
            case: case.clone(),
            voussoirs: n,
            integrator,
            time_step_s: r.time_step,
            normal_stiffness: params.normal_stiffness,
            lambda_stands: r.lambda_stands,
            lambda_collapses: r.lambda_collapses,
            lambda_dem: r.lambda_dem,
            lambda_static,
            error: rel(r.lambda_dem, lambda_static),
            brackets_static: match (r.lambda_stands, r.lambda_collapses, lambda_static) {
                (Some(a), Some(b), Some(s)) => Some(a <= s && s <= b),
                _ => None,
            },
            runs: r.runs.len(),
            steps: r.steps,
            steps_per_s: r.steps as f64 / time_s.max(1e-9),
            time_s,
            error_message: None,
        },
        Err(e) => DemRow {
            case: case.clone(),
            voussoirs: n,
            integrator,
            time_step_s: 0.0,
            normal_stiffness: params.normal_stiffness,
            lambda_stands: None,
            lambda_collapses: None,
            lambda_dem: None,
            lambda_static,
            error: None,
            brackets_static: None,
            runs: 0,
            steps: 0,
            steps_per_s: 0.0,
            time_s,
            error_message: Some(e.to_string()),
        },
    }
}

impl Convergence {
    /// The refinement table as CSV (one row per voussoir count).
    pub fn write_csv<W: std::io::Write>(&self, w: W) -> Result<(), csv::Error> {
        let mut out = csv::Writer::from_writer(w);
        out.write_record([
            "voussoirs",
            "joints",
            "status",
            "lambda_lower",
            "lower_time_s",
            "lower_iterations",
            "lambda_upper",
            "upper_time_s",
            "lambda_continuous",
            "error_lower",
            "error_upper",
            "note",
        ])?;
        let f = |v: Option<f64>| v.map_or(String::new(), |x| format!("{x:.10e}"));
        for r in &self.refinement {
            out.write_record([
                r.voussoirs.to_string(),
                r.joints.to_string(),
                r.status.clone(),
                f(r.lambda_lower),
                format!("{:.6e}", r.lower_time_s),
                r.lower_iterations.to_string(),
                f(r.lambda_upper),
                f(r.upper_time_s),
                f(self.lambda_continuous),
                f(r.error_lower),
                f(r.error_upper),
                r.error
                    .clone()
                    .or_else(|| r.upper_note.clone())
                    .unwrap_or_default(),
            ])?;
        }
        out.flush()?;
        Ok(())
    }
}
