//! One analysis of a scene by every method asked for: the static lower bound (always), the
//! discrete kinematic upper bound (the exhaustive search when the chain is small enough,
//! otherwise a local search around the static hinges when the static status is collapse), and
//! the continuous kinematic model (on request). The CLI and the sweeps both call this, so
//! they report the same numbers.

use crate::error::AnalysisError;
use crate::kinematic::{
    self, ContinuousResult, KinematicError, KinematicResult, KinematicSettings, Search,
};
use crate::model::{Action, Model};
use crate::scene::Scene;
use crate::statics::{self, Direction, StaticResult, StaticSettings, Status};

/// Joints up to which `analyze` runs the exhaustive kinematic search by default: its cost
/// candidate count grows as joints^4, its measured cost as about joints^3.6
/// (docs/performance.md: 176 ms at 129 joints on one thread).
pub const KINEMATIC_DEFAULT_MAX_JOINTS: usize = 200;

/// Half-width (joints) of the window around each static hinge searched by the local kinematic
/// search on chains above `kinematic_max_joints`.
pub const KINEMATIC_LOCAL_WINDOW: usize = kinematic::DEFAULT_LOCAL_WINDOW;

/// Relative difference (of `max(1, lambda)`) within which the multiplier of the mechanism of
/// the static hinges certifies the static multiplier: the interior-point optimum of the full
/// program sits up to about 1e-8 below the exact vertex on long chains.
pub const CERTIFY_TOL: f64 = 1e-6;

/// What to run.
#[derive(Debug, Clone)]
pub struct Options {
    pub static_settings: StaticSettings,
    /// Largest chain (joints) searched exhaustively; 0 turns the kinematic analysis off.
    pub kinematic_max_joints: usize,
    /// How the upper bound is found. Default [`KinematicMode::Certified`].
    pub kinematic: KinematicMode,
    /// Run the continuous model.
    pub continuous: bool,
    /// Which friction law the collapse multiplier is given for (docs/friction.md). Default
    /// [`FrictionMode::Auto`].
    pub friction: FrictionMode,
    /// Also run the DEM check (its Coulomb contacts slide without opening), from its own start
    /// (`analyze --dem`): where the associative, the non-associative and the DEM's values sit.
    pub dem: bool,
}

/// Which friction law the collapse multiplier is given for (`--friction`, docs/friction.md).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum FrictionMode {
    /// The non-associative multiplier ([`statics::analyse_non_associative`]) whenever the
    /// associative one is not exact (`friction_exact` false), or is exact where real joints
    /// may have lower collapse states (a wall: `friction_lower_states_possible`); otherwise
    /// (exact in a chain) the associative collapse state is a non-associative one too and
    /// nothing is iterated (docs/friction.md). `min-thickness` gives the associative value
    /// alone in this mode (its search is many analyses).
    #[default]
    Auto,
    /// The associative (static program's) multiplier alone.
    Associative,
    /// The non-associative multiplier always: iterated even when the associative one is exact
    /// (a check), and the minimum thickness of non-associative joints too.
    NonAssociative,
}

impl FrictionMode {
    /// The name `--friction` and the JSON use.
    pub fn as_str(self) -> &'static str {
        match self {
            FrictionMode::Auto => "auto",
            FrictionMode::Associative => "associative",
            FrictionMode::NonAssociative => "non-associative",
        }
    }

    /// The mode named `name` (`auto`, `associative`, `non-associative`), for front ends that
    /// take it as a string (Python, the page).
    pub fn parse(name: &str) -> Result<FrictionMode, AnalysisError> {
        match name {
            "auto" => Ok(FrictionMode::Auto),
            "associative" => Ok(FrictionMode::Associative),
            "non-associative" | "non_associative" => Ok(FrictionMode::NonAssociative),
            other => Err(AnalysisError::Settings {
                setting: "friction".to_string(),
                value: format!("\"{other}\""),
                allowed: "\"auto\", \"associative\" or \"non-associative\"".to_string(),
            }),
        }
    }
}

/// How the kinematic upper bound is found.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum KinematicMode {
    /// The mechanism of the static hinges, valued by virtual work ([`kinematic::certify`]),
    /// when the static solution is a collapse it certifies; otherwise the exhaustive search up
    /// to `kinematic_max_joints` joints, the local search above.
    #[default]
    Certified,
    /// The exhaustive search up to `kinematic_max_joints` joints (an independent check of the
    /// static bound), the certified bound or the local search above.
    Exhaustive,
    /// The general kinematic program ([`kinematic::analyse_general`]) on chains too: every
    /// admissible mechanism of the blocks (rocking, opening, sliding with associative
    /// friction), its optimum certified by virtual work. Assemblies that are not chains get it
    /// whatever the mode.
    General,
}

impl Default for Options {
    fn default() -> Self {
        Options {
            static_settings: StaticSettings::default(),
            kinematic_max_joints: KINEMATIC_DEFAULT_MAX_JOINTS,
            kinematic: KinematicMode::Certified,
            continuous: false,
            friction: FrictionMode::Auto,
            dem: false,
        }
    }
}

/// Largest chain (joints) the exhaustive kinematic search may be asked to take: its cost
/// grows as joints^3.6 (176 ms at 129 joints, docs/performance.md), so 1000 joints is about
/// five minutes on one thread and 2000 about an hour. Above it the certified bound or the
/// local search answer.
pub const MAX_EXHAUSTIVE_JOINTS: usize = 1000;

impl Options {
    pub fn direction(&self) -> Direction {
        self.static_settings.direction
    }

    /// Check every setting (the static program's, and the exhaustive search's size), naming
    /// the one out of range.
    pub fn validate(&self) -> Result<(), AnalysisError> {
        self.static_settings.validate()?;
        if self.kinematic_max_joints > MAX_EXHAUSTIVE_JOINTS {
            return Err(AnalysisError::Settings {
                setting: "kinematic_max_joints (--kinematic-max-joints)".to_string(),
                value: self.kinematic_max_joints.to_string(),
                allowed: format!(
                    "at most {MAX_EXHAUSTIVE_JOINTS}: the exhaustive search's cost grows as joints^3.6 (about five minutes at 1000 joints, an hour at 2000); above the limit the certified bound and the local search answer"
                ),
            });
        }
        Ok(())
    }
}

/// The results of every method run on one scene.
#[derive(Debug, Clone)]
pub struct SceneAnalysis {
    /// The assembly and load case that were analysed.
    pub model: Model,
    pub lower: StaticResult,
    /// The discrete kinematic result, or why it was not run or failed.
    pub upper: Result<KinematicResult, String>,
    /// Which kinematic search ran (also when it failed or found nothing), None when none did.
    pub kinematic_search: Option<Search>,
    /// The continuous model, when asked for (or why it failed).
    pub continuous: Option<Result<ContinuousResult, String>>,
    /// The non-associative multiplier (docs/friction.md), when `options.friction` asks for it:
    /// with [`FrictionMode::Auto`] only when the associative one is not exact (and there is a
    /// collapse); None otherwise.
    pub non_associative: Option<statics::NonAssociative>,
    /// The DEM check of the same model toward the same side, when `options.dem` asks (or why
    /// it failed).
    pub dem: Option<Result<crate::dem::DemResult, String>>,
}

impl SceneAnalysis {
    /// The upper bound, when the kinematic search ran.
    pub fn lambda_upper(&self) -> Option<f64> {
        self.upper.as_ref().ok().and_then(|k| k.lambda_upper)
    }

    /// Relative gap `|lower - upper| / max(1, lower)` when both bounds exist.
    pub fn gap(&self) -> Option<f64> {
        let l = self.lower.lambda?;
        let u = self.lambda_upper()?;
        Some((u - l).abs() / l.abs().max(1.0))
    }

    /// Whether the static multiplier holds for real joints, which slide without opening
    /// ([`statics::FrictionCheck`], docs/friction.md): every front end reads this.
    pub fn friction(&self) -> statics::FrictionCheck {
        self.lower.friction(&self.model.assembly)
    }

    /// The non-associative multiplier, when it was computed and converged (docs/friction.md).
    pub fn lambda_non_associative(&self) -> Option<f64> {
        self.non_associative.as_ref().and_then(|n| n.lambda)
    }

    /// The multiplier that governs downstream (the page's large number, `assess`, `retrofit`):
    /// the non-associative one when it exists, the static (associative) one otherwise.
    pub fn lambda_governing(&self) -> Option<f64> {
        self.lambda_non_associative().or(self.lower.lambda)
    }

    /// Whether sliding governs: finite friction somewhere, and the static bound is below the
    /// rotational upper bound. A local search's bound may exceed the least rotational
    /// multiplier, so then the static solution must also slide somewhere.
    pub fn sliding_governs(&self) -> bool {
        let finite = self
            .model
            .assembly
            .joints
            .iter()
            .any(|j| j.friction.is_finite());
        // With crushing the searches' hinges are rigid (their multiplier is the rigid
        // structure's): only the static solution's own sliding joints say that sliding governs.
        let local = self.upper.as_ref().is_ok_and(|k| k.search == Search::Local)
            || self.model.strength.is_finite();
        if self.kinematic_search == Some(Search::General) {
            // The general program's mechanisms slide too, so its bound is no rotational one
            // (it equals the static bound): the static solution's own sliding joints say
            // whether sliding governs.
            return finite
                && self.lower.status == Status::Collapse
                && !self.lower.sliding.is_empty();
        }
        match (self.lower.status, self.lower.lambda, self.lambda_upper()) {
            (Status::Collapse, Some(l), Some(u)) => {
                finite && l < u * (1.0 - 1e-6) && !(local && self.lower.sliding.is_empty())
            }
            (Status::Collapse, Some(_), None) => finite && !self.lower.sliding.is_empty(),
            (Status::CannotStand, _, _) => {
                finite
                    && self
                        .upper
                        .as_ref()
                        .is_ok_and(|k| k.status != Status::CannotStand)
            }
            _ => false,
        }
    }
}

/// Refuse `what` unless the scene's action is seismic: the methods and options that need a
/// ground motion (its direction, a site's spectrum, a time history) have no meaning when
/// lambda multiplies live loads.
pub fn seismic_only(scene: &Scene, what: &str) -> Result<(), AnalysisError> {
    match scene.action {
        Action::Seismic => Ok(()),
        Action::Live => Err(AnalysisError::NotForAction {
            origin: scene.origin.clone(),
            what: what.to_string(),
            action: scene.action.to_string(),
            why: "lambda multiplies the live loads, not a ground motion (the adequacy factor)"
                .to_string(),
        }),
    }
}

/// The direction to analyse `scene` in: `asked` (a front end's `--direction`), or toward +x
/// when none was asked. A live action has no direction, so asking for one is refused.
pub fn direction_for(scene: &Scene, asked: Option<Direction>) -> Result<Direction, AnalysisError> {
    match asked {
        Some(d) => {
            seismic_only(scene, "--direction (the direction of the ground motion)")?;
            Ok(d)
        }
        None => Ok(Direction::Right),
    }
}

/// Analyse a scene.
pub fn analyse(scene: &Scene, options: &Options) -> Result<SceneAnalysis, AnalysisError> {
    options.validate()?;
    if options.direction() == Direction::Left {
        seismic_only(
            scene,
            "direction = left (the direction of the ground motion)",
        )?;
    }
    let model = crate::scene::build(scene)?;
    analyse_model(scene, model, options)
}

/// [`analyse`] of a model already built from `scene` (a retrofit design's, whose tie
/// capacities it set).
pub fn analyse_model(
    scene: &Scene,
    model: Model,
    options: &Options,
) -> Result<SceneAnalysis, AnalysisError> {
    options.validate()?;
    let lower = statics::analyse(&model, &options.static_settings)?;
    let (mut upper, kinematic_search) = upper_bound(&model, &lower, options);
    if model.strength.is_finite() && kinematic_search != Some(Search::Certified) {
        // The searches enumerate hinges at the joint ends: say so, since their multiplier is
        // the rigid structure's (an upper bound, as crushing only lowers it).
        upper = upper.map(|mut k| {
            let rigid = format!(
                "rigid hinges: this search ignores the compressive strength ({:e} Pa), so its multiplier is the rigid structure's, an upper bound of the crushing one",
                model.strength.compressive
            );
            k.note = Some(match k.note.take() {
                Some(n) if !n.is_empty() => format!("{n}; {rigid}"),
                _ => rigid,
            });
            k
        });
    }
    let continuous = options
        .continuous
        .then(|| continuous_of(scene, &model, options.direction()).map_err(|e| e.to_string()));
    let non_associative = non_associative_of(&model, &lower, options)?;
    let dem = options.dem.then(|| {
        // The DEM loads toward +x: the mirror image stands for a load toward the left.
        let simulated = match options.direction() {
            Direction::Right => model.clone(),
            Direction::Left => model.mirrored(),
        };
        dem_of(
            scene,
            &simulated,
            lower.lambda,
            &DemOptions::default(),
            &mut |_| {},
        )
        .map_err(|e| e.to_string())
    });
    Ok(SceneAnalysis {
        model,
        lower,
        upper,
        kinematic_search,
        continuous,
        non_associative,
        dem,
    })
}

/// The most blocks of an assembly whose exact answer `FrictionMode::Auto` still iterates for
/// lower collapse states of real joints (`friction_lower_states_possible`). Every program of
/// the iteration is the full conic program of the wall: measured (session 12, load about 3),
/// a running-bond wall of 205 blocks took 1.1 s in all (29 programs), one of 984 blocks 200 s
/// (206 programs), and one of 10,050 blocks would take hours; above this size the exact value
/// is kept, said not searched, and `--friction non-associative` searches on request. With the
/// mechanism step (session 14) a 972-block wall (mu = 1000) took 11.6 s (16 programs) and
/// found 0.583406 where the exact value is 3.333; the limit stays, because a wall where no
/// step verifies still costs the relaxation's hundreds of programs.
pub const AUTO_SEARCH_MAX_BLOCKS: usize = 400;

/// The non-associative multiplier of `model`, whose static result is `lower`, as
/// `options.friction` asks (see [`FrictionMode`]): the associative value as it is when that is
/// exact in a chain (unless forced), the iteration of [`statics::analyse_non_associative`]
/// otherwise;
/// None when not asked for, with infinite friction, or with no collapse.
fn non_associative_of(
    model: &Model,
    lower: &StaticResult,
    options: &Options,
) -> Result<Option<statics::NonAssociative>, AnalysisError> {
    let check = lower.friction(&model.assembly);
    if options.friction == FrictionMode::Associative
        || !check.finite
        || lower.status != Status::Collapse
    {
        return Ok(None);
    }
    // An exact value is the non-associative one too, unless real joints may have lower
    // collapse states (a wall: `lower_states_possible`), which the iteration searches for,
    // up to AUTO_SEARCH_MAX_BLOCKS blocks (said in words above it).
    if check.exact && options.friction == FrictionMode::Auto {
        let blocks = model.assembly.blocks.len();
        if !check.lower_states_possible || blocks > AUTO_SEARCH_MAX_BLOCKS {
            let mut na = statics::NonAssociative::exact(lower);
            na.unsearched = check.lower_states_possible;
            return Ok(Some(na));
        }
    }
    statics::analyse_non_associative(
        model,
        &options.static_settings,
        lower,
        &statics::NonAssociativeSettings::default(),
    )
    .map(Some)
}

/// The kinematic upper bound of `model` given its static solution `lower`, per `options`
/// (see [`KinematicMode`]), or why there is none; and which search gave it.
fn upper_bound(
    model: &Model,
    lower: &StaticResult,
    options: &Options,
) -> (Result<KinematicResult, String>, Option<Search>) {
    let joints = model.assembly.joints.len();
    if options.kinematic_max_joints == 0 {
        return (Err("kinematic search turned off".to_string()), None);
    }
    if options.kinematic == KinematicMode::General || not_a_chain(&model.assembly).is_some() {
        // The chain searches enumerate the mechanisms of a chain; any other assembly (a wall,
        // a lintel, an arcade) takes the general program, as a chain does when asked.
        return general(model, options);
    }
    let settings = KinematicSettings {
        direction: options.direction(),
        max_joints: options.kinematic_max_joints,
        ..KinematicSettings::default()
    };
    let small = joints <= options.kinematic_max_joints;
    let finite = model.assembly.joints.iter().any(|j| j.friction.is_finite());
    let certified = options.kinematic == KinematicMode::Certified;
    if certified && lower.status == Status::CannotStand && !finite {
        // Without sliding, the static program's infeasibility at lambda = 0 is itself the
        // proof (Farkas: some mechanism moves under the permanent loads alone); the
        // exhaustive search would only name that mechanism.
        return (
            Err("no kinematic search: the static program proves that the structure cannot stand (--kinematic exhaustive names the mechanism)".to_string()),
            None,
        );
    }
    // The certified bound: the mechanism of the static hinges (linear cost), tried first
    // unless the exhaustive search is asked for and the chain is small enough for it.
    let mut not_certified = String::new();
    if lower.status == Status::Collapse && (certified || !small) {
        match certify_static(model, lower, &settings) {
            Ok(k) => return (Ok(k), Some(Search::Certified)),
            Err(why) => not_certified = why,
        }
    }
    let exhaustive_asked = options.kinematic == KinematicMode::Exhaustive && small;
    if !model.passive.is_empty() && !exhaustive_asked {
        // A passive face whose reaction lies strictly inside its interval at collapse does not
        // move horizontally in the collapse mechanism: one more constraint, met by a fifth
        // hinge, outside the four-hinge families the chain searches enumerate. The general
        // program (the static program's exact dual) takes any mechanism.
        let (k, search) = general(model, options);
        let k = k.map(|mut k| {
            if !not_certified.is_empty() {
                k.note = Some(format!(
                    "{} (the static hinges' mechanism was not certified: {not_certified})",
                    k.note.unwrap_or_default()
                ));
            }
            k
        });
        return (k, search);
    }
    if small {
        let k = kinematic::analyse(model, &settings).map_err(|e| e.to_string());
        return (k, Some(Search::Exhaustive));
    }
    let too_many = format!(
        "{joints} joints is more than {} (the exhaustive search examines a number of candidates growing as joints^4 and costs about joints^3.6; raise --kinematic-max-joints to run it)",
        options.kinematic_max_joints
    );
    if lower.status != Status::Collapse {
        return (
            Err(format!(
                "kinematic search skipped: {too_many}; no local search, as the static status is not collapse"
            )),
            None,
        );
    }
    // Too large for the exhaustive search, and not certified (a degenerate or sliding static
    // solution): any admissible mechanism still bounds lambda_c from above, and the static
    // hinges say where the governing one is.
    let k = kinematic::analyse_local(model, lower, &settings, KINEMATIC_LOCAL_WINDOW)
        .map(|mut k| {
            k.note = Some(format!(
                "{} (not certified: {not_certified})",
                k.note.unwrap_or_default()
            ));
            k
        })
        .map_err(|e| format!("exhaustive kinematic search skipped: {too_many}; {e}"));
    let search = k.as_ref().map_or(Search::Local, |k| k.search);
    (k, Some(search))
}

/// The general kinematic program's upper bound ([`kinematic::analyse_general`]), or why there
/// is none (a solver that did not converge, a mechanism that failed its certificate).
fn general(model: &Model, options: &Options) -> (Result<KinematicResult, String>, Option<Search>) {
    let settings = KinematicSettings {
        direction: options.direction(),
        ..KinematicSettings::default()
    };
    let k = kinematic::analyse_general(model, &settings).map_err(|e| format!("none: {e}"));
    (k, Some(Search::General))
}

/// Why an assembly is neither a chain between two supports nor a column on one, in words
/// (None when it is one of them).
pub fn not_a_chain(assembly: &crate::assembly::Assembly) -> Option<String> {
    if assembly.is_chain() || kinematic::discrete::is_column(assembly) {
        return None;
    }
    let mut count = vec![0usize; assembly.blocks.len()];
    let mut supports = 0;
    for j in &assembly.joints {
        for b in [j.from, j.to].into_iter().flatten() {
            if let Some(c) = count.get_mut(b) {
                *c += 1;
            }
        }
        supports += usize::from(j.is_support());
    }
    let name = |i: usize| match assembly.blocks[i].kind {
        crate::assembly::BlockKind::User(s) => format!("block {s}"),
        _ => format!("block {i}"),
    };
    // The first of the blocks with the most joints.
    let most = count
        .iter()
        .enumerate()
        .max_by(|a, b| a.1.cmp(b.1).then(b.0.cmp(&a.0)));
    Some(match most {
        Some((i, &c)) if c > 2 => format!("{} has {c} joints", name(i)),
        _ => format!("{supports} joints rest on the ground"),
    })
}

/// The mechanism of the static hinges ([`kinematic::certify`]) when its multiplier meets the
/// static one within [`CERTIFY_TOL`]; otherwise why not.
fn certify_static(
    model: &Model,
    lower: &StaticResult,
    settings: &KinematicSettings,
) -> Result<KinematicResult, String> {
    let k = if model.strength.is_finite() {
        // Hinges at the centres of the compressed zones (see kinematic::certify_crushing).
        kinematic::certify_crushing(model, lower, settings)
    } else {
        kinematic::certify(model, lower, settings)
    }
    .map_err(|e| e.to_string())?;
    match (k.lambda_upper, lower.lambda) {
        (Some(u), Some(l)) if (u - l).abs() <= CERTIFY_TOL * l.abs().max(1.0) => Ok(k),
        (u, _) => Err(format!(
            "the mechanism of the static hinges gives {u:?}, not the static value"
        )),
    }
}

/// The continuous kinematic model of a scene (hinges anywhere on the ring), load toward
/// `direction`.
pub fn continuous(scene: &Scene, direction: Direction) -> Result<ContinuousResult, KinematicError> {
    continuous_of(scene, &crate::scene::build(scene)?, direction)
}

fn continuous_of(
    scene: &Scene,
    model: &Model,
    direction: Direction,
) -> Result<ContinuousResult, KinematicError> {
    let arch = scene.parametric("the continuous model")?;
    if scene.arcade.as_ref().is_some_and(|a| a.bays > 1) || scene.spandrel.is_some() {
        // Its continuum is one ring on its piers: several rings, or a wall over them, are not
        // that chain.
        return Err(KinematicError::Continuous(
            "it models one ring (on its piers) as a continuum; an arcade of several bays or a spandrel wall is no such chain (the static program and the DEM apply)".to_string(),
        ));
    }
    let boussinesq = scene
        .fill
        .as_ref()
        .is_some_and(|f| f.dispersal.law() == crate::scene::spread::Law::Boussinesq);
    let standing = !scene.vehicles.is_empty()
        || scene
            .loads
            .iter()
            .any(|l| matches!(l, crate::scene::LoadSpec::Point { .. }));
    if boussinesq && standing {
        // The Boussinesq spread reaches the voussoirs as one resultant per extrados edge;
        // the continuous model would take each as a point load, not the spread stress.
        return Err(KinematicError::Continuous(
            "a point load or an axle spread by spread = \"boussinesq\" reaches the voussoirs as one resultant per extrados edge, which the continuous model cannot place along the ring (spread_deg spreads a uniform load, which it takes)".to_string(),
        ));
    }
    if !arch.joints.is_radial() {
        // Its sections are radial cuts of the ring: with other joints the discrete arch is
        // not a subdivision of that continuum, so the model does not bound it.
        return Err(KinematicError::Continuous(format!(
            "it cuts the ring along radial sections, so it does not apply to arch.joints = \"{}\" (the static program, the discrete searches and the DEM do)",
            arch.joints.name()
        )));
    }
    kinematic::continuous(model, arch.shape.as_ref(), arch.thickness, direction)
}

/// The continuous model's minimum thickness of a scene (all else fixed, lambda = 0).
pub fn continuous_min_thickness(scene: &Scene) -> Result<kinematic::MinThickness, KinematicError> {
    let thickness = scene.parametric("the continuous model")?.thickness;
    scene.thickness_may_vary()?;
    kinematic::continuous_min_thickness(thickness, scene.max_thickness(), |t| {
        continuous(&scene.with_thickness(t)?, Direction::Right)
    })
}

/// How the DEM check of a scene runs (the stepping knobs come from the scene's `[dem]` table
/// and the geometry, see [`crate::dem::IntegrationParameters`]).
#[derive(Debug, Clone)]
pub struct DemOptions {
    /// Relative width of the final bracket `[lambda_stands, lambda_collapses]`. Default 0.01.
    pub tolerance: f64,
    /// Record block positions during the runs (for snapshots and drawings), every third of the
    /// load ramp unless the scene sets `dem.snapshot_interval`. Default false.
    pub snapshots: bool,
    /// Start the bracket search at the static lower bound (the fast mode: the first bracket
    /// around it usually verifies it, so the DEM confirms the static value rather than
    /// measuring its own threshold). Default false: the search starts at the scene's
    /// `dem.initial_guess`, or [`crate::dem::DEFAULT_INITIAL_GUESS`], independent of the
    /// static bound.
    pub from_static: bool,
    /// The most time steps one run may take, instead of
    /// [`crate::dem::DEFAULT_MAX_STEPS`]. Default `None`.
    pub max_steps: Option<u64>,
}

impl Default for DemOptions {
    fn default() -> Self {
        DemOptions {
            tolerance: 0.01,
            snapshots: false,
            from_static: false,
            max_steps: None,
        }
    }
}

/// A DEM check with the static bounds it is compared with.
#[derive(Debug, Clone)]
pub struct DemAnalysis {
    pub model: Model,
    /// The static analysis of the same model.
    pub lower: StaticResult,
    /// The static lower bound of the shapes the DEM simulates ([`crate::dem::simulated_model`]:
    /// curved voussoirs as their chord polygons); `lower.lambda` when they are the model's own.
    pub lower_simulated: Option<f64>,
    /// Whether the DEM simulates other shapes than the model's (curved voussoirs as chord
    /// polygons).
    pub chord_polygons: bool,
    pub result: crate::dem::DemResult,
}

/// Check a scene's collapse multiplier with the DEM, from its own start (or from the static
/// bound with `options.from_static`), and the static bounds to compare it with.
pub fn dem(
    scene: &Scene,
    options: &DemOptions,
    progress: &mut dyn FnMut(f64),
) -> Result<DemAnalysis, AnalysisError> {
    let model = crate::scene::build(scene)?;
    let lower = statics::analyse(&model, &StaticSettings::default())?;
    let (lower_simulated, chord_polygons) = simulated_static(&model, lower.lambda)?;
    let mut result = dem_of(scene, &model, lower.lambda, options, progress)?;
    result
        .warnings
        .extend(dem_disagreement(&result, lower.status, lower_simulated));
    Ok(DemAnalysis {
        model,
        lower,
        lower_simulated,
        chord_polygons,
        result,
    })
}

/// A warning when the DEM's status contradicts the static program's (`lower`, with the
/// static bound of the shapes simulated `lambda_lower`): a structure the static program finds
/// standing that the DEM cannot settle, or the other way round, points at the `[dem]` knobs
/// (soft contacts, a gravity or time scale the defaults do not fit), not at the structure;
/// and when both collapse but the multipliers differ by more than 20%.
pub fn dem_disagreement(
    d: &crate::dem::DemResult,
    lower: Status,
    lambda_lower: Option<f64>,
) -> Option<String> {
    let static_words = match (lower, lambda_lower) {
        (Status::Collapse, Some(l)) => format!("collapses at lambda_lower = {l:.6}"),
        (Status::NoCollapse, _) => "never collapses".to_string(),
        _ => "cannot stand".to_string(),
    };
    let contradiction = if d.cannot_stand {
        lower != Status::CannotStand
    } else if d.no_collapse {
        lower == Status::Collapse && lambda_lower.is_some_and(|l| l <= d.params.max_lambda)
    } else {
        lower == Status::CannotStand
            || (lower == Status::NoCollapse && d.lambda_collapses.is_some())
    };
    let dem_words = if d.cannot_stand {
        "cannot stand".to_string()
    } else if d.no_collapse {
        format!(
            "does not collapse up to dem.max_lambda = {}",
            d.params.max_lambda
        )
    } else {
        "collapses".to_string()
    };
    if contradiction {
        return Some(format!(
            "the DEM says the structure {dem_words}, the static program that it {static_words}: they contradict each other; check the [dem] knobs (dem.normal_stiffness, dem.gravity, dem.max_time) before trusting either"
        ));
    }
    // Both collapse, but far apart: the documented offsets are under 3% on rocking and 12%
    // where Coulomb sliding mixes with rocking (docs/dem.md).
    match (d.lambda_dem, lambda_lower, lower) {
        (Some(dem), Some(l), Status::Collapse) if l > 0.0 && ((dem - l) / l).abs() > 0.2 => {
            Some(format!(
                "the DEM's multiplier {dem:.6} differs from the static lower bound {l:.6} by {:+.1}%, far beyond the offsets documented for rigid blocks (docs/dem.md); check the [dem] knobs (dem.normal_stiffness, dem.gravity) before trusting either",
                100.0 * (dem - l) / l
            ))
        }
        _ => None,
    }
}

/// The time step of a scene's DEM (s), the most time steps one run may take (see
/// [`crate::dem::plan`]; `motion`: seconds of ground motion and tail of a dynamic run),
/// refused above `max_steps` (default [`crate::dem::DEFAULT_MAX_STEPS`]) before anything runs,
/// and the time stepping the runs use (`dem.integrator`).
pub fn dem_plan(
    scene: &Scene,
    motion: Option<f64>,
    max_steps: Option<u64>,
) -> Result<(f64, u64, crate::dem::Integrator), AnalysisError> {
    let model = crate::scene::build(scene)?;
    let mut params = dem_parameters(scene, &model)?;
    if let Some(n) = max_steps {
        params.max_steps = n;
    }
    crate::dem::plan(&model, &params, motion).map_err(|e| AnalysisError::Other(e.to_string()))
}

/// The static lower bound of the shapes the DEM simulates for `model`, whose own static bound
/// is `lambda_lower`, and whether those shapes differ from the model's (curved voussoirs are
/// simulated as their chord polygons, [`crate::dem::simulated_model`]).
pub fn simulated_static(
    model: &Model,
    lambda_lower: Option<f64>,
) -> Result<(Option<f64>, bool), AnalysisError> {
    match crate::dem::simulated_model(model) {
        None => Ok((lambda_lower, false)),
        Some(m) => Ok((
            statics::analyse(&m, &StaticSettings::default())?.lambda,
            true,
        )),
    }
}

/// The DEM check of `model` (built from `scene`). The bracket search starts at the static
/// multiplier `lambda_lower` with `options.from_static` (when there is one), otherwise at the
/// scene's `dem.initial_guess` or [`crate::dem::DEFAULT_INITIAL_GUESS`].
pub fn dem_of(
    scene: &Scene,
    model: &Model,
    lambda_lower: Option<f64>,
    options: &DemOptions,
    progress: &mut dyn FnMut(f64),
) -> Result<crate::dem::DemResult, AnalysisError> {
    use crate::dem::GuessSource;
    let mut params = dem_parameters(scene, model)?;
    let (guess, source) = match (options.from_static, lambda_lower.filter(|l| *l > 0.0)) {
        // The search never looks above max_lambda: a static value beyond it starts there.
        (true, Some(l)) => (l.min(params.max_lambda), GuessSource::Static),
        _ => match params.initial_guess {
            Some(g) => (g, GuessSource::Given),
            None => (crate::dem::DEFAULT_INITIAL_GUESS, GuessSource::Default),
        },
    };
    params = params.initial_guess(Some(guess));
    if let Some(n) = options.max_steps {
        params.max_steps = n;
    }
    if options.snapshots && params.snapshot_interval.is_none() {
        let every = params.ramp_time / 3.0;
        params = params.snapshot_interval(Some(every));
    }
    let mut result = crate::dem::collapse_multiplier(model, &params, options.tolerance, progress)
        .map_err(|e| AnalysisError::Other(e.to_string()))?;
    // The search was handed its start; say where that start came from.
    result.guess_source = source;
    Ok(result)
}

/// A dynamic DEM run of a scene under a ground motion.
#[derive(Debug, Clone)]
pub struct DynamicAnalysis {
    pub model: Model,
    pub ground: crate::dem::record::GroundInput,
    pub result: crate::dem::dynamic::DynamicResult,
}

/// Run a scene's blocks under the ground motion `ground` (see [`crate::dem::dynamic`]), with
/// the scene's `[dem]` knobs.
pub fn dem_dynamic(
    scene: &Scene,
    ground: &crate::dem::record::GroundInput,
    settings: &crate::dem::dynamic::DynamicSettings,
) -> Result<DynamicAnalysis, AnalysisError> {
    seismic_only(scene, "a ground motion (dem --record / --pulse)")?;
    let model = crate::scene::build(scene)?;
    let params = dem_parameters(scene, &model)?;
    let result = crate::dem::dynamic::respond_input(&model, &params, ground, settings)
        .map_err(|e| AnalysisError::Other(e.to_string()))?;
    Ok(DynamicAnalysis {
        model,
        ground: ground.clone(),
        result,
    })
}

/// Scale a ground motion up until the scene's blocks collapse (see [`crate::dem::dynamic::ida`]),
/// to a relative `tolerance`, trying scales up to 1000.
pub fn dem_ida(
    scene: &Scene,
    ground: &crate::dem::record::GroundInput,
    settings: &crate::dem::dynamic::DynamicSettings,
    tolerance: f64,
) -> Result<(Model, crate::dem::dynamic::IdaResult), AnalysisError> {
    seismic_only(scene, "an incremental dynamic analysis (dem --ida)")?;
    let model = crate::scene::build(scene)?;
    let params = dem_parameters(scene, &model)?;
    let r = crate::dem::dynamic::ida_input(&model, &params, ground, settings, tolerance, 1000.0)
        .map_err(|e| AnalysisError::Other(e.to_string()))?;
    Ok((model, r))
}

/// One point of a pulse curve: the minimum collapse amplitude of a pulse of one shape and
/// period, bracketed (m/s^2).
#[derive(Debug, Clone)]
pub struct PulseCurvePoint {
    pub shape: crate::dem::record::PulseShape,
    pub period: f64,
    pub bracket: crate::dem::dynamic::AmplitudeBracket,
}

/// A minimum-amplitude-against-period curve of pulses for a scene.
#[derive(Debug, Clone)]
pub struct PulseCurve {
    pub model: Model,
    /// The static lower bound the amplitude search starts from (`lambda g`; 0.1 g when there
    /// is none), and the relative bracket width asked for.
    pub lambda_lower: Option<f64>,
    pub start_amplitude: f64,
    pub tolerance: f64,
    pub points: Vec<PulseCurvePoint>,
    pub wall_time_s: f64,
    /// The collapse criterion of the runs.
    pub criterion: crate::dem::dynamic::Criterion,
}

/// The largest pulse amplitude a curve tries, in multiples of g.
pub const PULSE_CURVE_MAX_G: f64 = 50.0;

/// The pulse periods (s) of a pulse curve when none are given: from short pulses, which need
/// many times the static multiplier, to long ones, which tend to it.
pub const PULSE_CURVE_PERIODS: &[f64] = &[0.1, 0.15, 0.25, 0.4, 0.6, 1.0, 1.5, 2.5];

/// The minimum amplitude of one-cycle sine and rectangular pulses (`shapes`) that brings the
/// scene's blocks down, at each of `periods` (s), to a relative `tolerance`, with
/// [`crate::dem::dynamic::minimum_amplitude`]. Every search starts at the static collapse
/// multiplier times g: no pulse below it can form a mechanism of rigid blocks (a long
/// rectangular pulse tends to it), so the search mostly doubles up from there; the DEM's
/// elastic contacts, loaded at once by a rectangular pulse, can collapse slightly below it,
/// and the search then halves down.
/// `progress` receives the fraction of points done.
pub fn dem_pulse_curve(
    scene: &Scene,
    shapes: &[crate::dem::record::PulseShape],
    periods: &[f64],
    settings: &crate::dem::dynamic::DynamicSettings,
    tolerance: f64,
    progress: &mut dyn FnMut(f64),
) -> Result<PulseCurve, AnalysisError> {
    use crate::dem::record::Pulse;
    seismic_only(scene, "a pulse curve (dem --pulse-curve)")?;
    let clock = std::time::Instant::now();
    if let Some(t) = periods.iter().find(|t| !(t.is_finite() && **t > 0.0)) {
        return Err(crate::error::RecordError::Flag {
            flag: "--periods".to_string(),
            value: t.to_string(),
            message: "a pulse period must be a finite number of seconds > 0".to_string(),
        }
        .into());
    }
    let model = crate::scene::build(scene)?;
    let params = dem_parameters(scene, &model)?;
    let lower = statics::analyse(&model, &StaticSettings::default())?;
    let lambda_lower = lower.lambda.filter(|l| *l > 0.0);
    let g = params.gravity;
    let start = lambda_lower.unwrap_or(0.1) * g;
    let mut points = Vec::new();
    let total = (shapes.len() * periods.len()).max(1);
    for &shape in shapes {
        for &period in periods {
            let bracket = crate::dem::dynamic::minimum_amplitude(
                &model,
                &params,
                &|a, t| {
                    Pulse {
                        shape,
                        amplitude: a,
                        period,
                    }
                    .at(t)
                },
                period,
                settings,
                start,
                tolerance,
                PULSE_CURVE_MAX_G * g,
                crate::dem::dynamic::PULSE_SCAN_RATIO,
            )
            .map_err(|e| AnalysisError::Other(e.to_string()))?;
            points.push(PulseCurvePoint {
                shape,
                period,
                bracket,
            });
            progress(points.len() as f64 / total as f64);
        }
    }
    Ok(PulseCurve {
        model,
        lambda_lower,
        start_amplitude: start,
        tolerance,
        points,
        wall_time_s: clock.elapsed().as_secs_f64(),
        criterion: settings.criterion,
    })
}

/// The DEM's stepping knobs for a scene: the defaults of its geometry, then its `[dem]` table.
pub fn dem_parameters(
    scene: &Scene,
    model: &Model,
) -> Result<crate::dem::IntegrationParameters, crate::error::SceneError> {
    let mut p = crate::dem::IntegrationParameters::for_model(model);
    p.apply_table(&scene.dem, &scene.origin)?;
    Ok(p)
}

/// How `assess` builds the capacity curve.
#[derive(Debug, Clone)]
pub struct AssessOptions {
    /// Points of the capacity curve (>= 3). Default 200.
    pub points: usize,
    /// Control block; default the block whose centroid moves most horizontally.
    pub control_block: Option<usize>,
    /// Follow a chain's mechanism by the incremental analysis too (`--incremental`); other
    /// mechanisms always take it ([`crate::assess::incremental`]).
    pub incremental: bool,
}

impl Default for AssessOptions {
    fn default() -> Self {
        AssessOptions {
            points: 200,
            control_block: None,
            incremental: false,
        }
    }
}

/// The seismic assessment of a scene: its analysis, the capacity of its governing mechanism
/// and the verdict at its `[site]`.
#[derive(Debug, Clone)]
pub struct SiteAssessment {
    pub analysis: SceneAnalysis,
    pub site: crate::spectrum::Site,
    pub capacity: crate::assess::Capacity,
    pub verdict: crate::assess::Verdict,
}

/// Assess a scene at its `[site]` (NTC 2018 / Circolare 2019 C8.7.1: linear and nonlinear
/// kinematic analysis of the governing mechanism, see [`crate::assess`]).
pub fn assess(
    scene: &Scene,
    options: &Options,
    assess: &AssessOptions,
) -> Result<SiteAssessment, AnalysisError> {
    seismic_only(scene, "a seismic assessment (assess)")?;
    let site = scene.site.clone().ok_or_else(|| {
        AnalysisError::Other(format!(
            "{}: no [site] table: give one in the scene or with --site ag=0.25 --site soil=B --site F0=2.4 --site Tc_star=0.3 (or --site latitude=42.35 --site longitude=13.40 --site soil=B for the national hazard grid, docs/assessment.md)",
            scene.origin
        ))
    })?;
    let analysis = analyse(scene, options)?;
    let mechanism = match &analysis.upper {
        Ok(k) if k.status == Status::Collapse => k.mechanism.clone().ok_or_else(|| {
            AnalysisError::Other("the kinematic analysis names no mechanism".into())
        })?,
        Ok(k) => {
            return Err(AnalysisError::Other(format!(
                "no mechanism to assess: the kinematic status is {}",
                k.status.as_str()
            )))
        }
        Err(why) => {
            return Err(AnalysisError::Other(format!(
                "no mechanism to assess: {why}"
            )))
        }
    };
    let settings = crate::assess::CapacitySettings {
        points: assess.points,
        control_block: assess.control_block,
        fc: site.fc,
        incremental: assess.incremental,
    };
    let capacity =
        crate::assess::capacity(&analysis.model, &mechanism, options.direction(), &settings)
            .map_err(|e| {
                // Sliding explains a missing curve better than the curve's own failure: a
                // sliding mechanism has none (rotation_governs words it the same way).
                let sliding = analysis.lower.sliding.len();
                AnalysisError::Other(if sliding > 0 {
                    format!("{sliding} joint(s) slide at collapse: sliding governs, and a sliding mechanism has no capacity curve in this model ({e})")
                } else {
                    e.to_string()
                })
            })?;
    let verdict = crate::assess::verdict(&analysis.model, &capacity, &site);
    Ok(SiteAssessment {
        analysis,
        site,
        capacity,
        verdict,
    })
}

/// The assessment of a scene in each direction assessed, and which one governs.
#[derive(Debug, Clone)]
pub struct Assessment {
    /// One assessment per direction: right then left, or the one direction asked for.
    pub directions: Vec<SiteAssessment>,
    /// Index into `directions` of the governing (worse) direction.
    pub governing: usize,
    /// Whether the caller restricted the assessment to one direction (then the verdict covers
    /// that direction only).
    pub restricted: bool,
}

impl Assessment {
    /// The governing direction's assessment.
    pub fn governing(&self) -> &SiteAssessment {
        &self.directions[self.governing]
    }

    /// The verdict over the directions assessed: every one must pass.
    pub fn passes(&self) -> bool {
        self.directions.iter().all(|a| a.verdict.passes())
    }
}

fn direction_name(d: Direction) -> &'static str {
    match d {
        Direction::Right => "right",
        Direction::Left => "left",
    }
}

/// Relative margin (of `max(1, lambda)`) by which the static lower bound may sit below the
/// assessed mechanism's `alpha0` (the interior-point optimum's round-off, as
/// [`CERTIFY_TOL`]).
pub const GOVERNS_TOL: f64 = 1e-6;

/// Whether the assessed mechanism is the governing one: the governing multiplier
/// ([`SceneAnalysis::lambda_governing`]: the non-associative one when it was computed, the
/// static one otherwise; docs/friction.md) must reach its `alpha0`. It does not when the
/// structure cannot stand, when joints slide at collapse
/// (finite friction), or when a finite compressive strength lowers the multiplier but the
/// mechanism came from a search with rigid hinges (its hinges at the joint ends): the
/// rotational capacity curve would then start above the true collapse multiplier and
/// overstate the capacity, so there is no assessment.
pub fn rotation_governs(a: &SiteAssessment) -> Result<(), String> {
    let lower = &a.analysis.lower;
    let alpha0 = a.capacity.alpha0;
    let dir = direction_name(a.capacity.direction);
    let lambda = match (lower.status, a.analysis.lambda_governing()) {
        (Status::CannotStand, _) | (_, None) => {
            return Err(format!(
                "load toward the {dir}: the static program finds no equilibrium (the structure cannot stand, or no lower bound), while the rotational mechanism has alpha0 = {alpha0:.6}: its capacity curve would be that of a structure that does not exist, so there is no assessment"
            ))
        }
        (_, Some(l)) => l,
    };
    if lambda >= alpha0 - GOVERNS_TOL * alpha0.abs().max(1.0) {
        return Ok(());
    }
    let non_associative = a.analysis.lambda_non_associative().is_some();
    let why = if non_associative && a.analysis.lambda_non_associative() < lower.lambda {
        "the non-associative multiplier (joints that slide without opening) is below it: that collapse governs, and it has no rotational capacity curve in this model".to_string()
    } else if !lower.sliding.is_empty() {
        format!(
            "{} joint(s) slide at collapse: sliding governs, and a sliding mechanism has no capacity curve in this model",
            lower.sliding.len()
        )
    } else if a.analysis.model.strength.is_finite() {
        "the compressive strength lowers the multiplier, but the mechanism search kept rigid hinges at the joint ends (the static solution's crushing hinges do not form a four-hinge mechanism)".to_string()
    } else {
        "the mechanism found by the kinematic search is not the one the static bound reaches"
            .to_string()
    };
    Err(format!(
        "load toward the {dir}: the {} lambda = {lambda:.6} is below the rotational mechanism's alpha0 = {alpha0:.6} ({:.1} % lower): {why}. Its capacity curve would overstate the capacity, so there is no assessment",
        if non_associative { "non-associative multiplier" } else { "static lower bound" },
        100.0 * (alpha0 - lambda) / alpha0
    ))
}

/// Assess `scene` at its `[site]` with the load toward the right and toward the left (or only
/// toward `only`), each with its own governing mechanism, and let the worse govern. A
/// direction that cannot be assessed (no mechanism with a capacity curve) fails the whole
/// assessment unless the other was excluded with `only`: a verdict of one direction is not a
/// verdict of the structure.
pub fn assess_directions(
    scene: &Scene,
    options: &Options,
    settings: &AssessOptions,
    only: Option<Direction>,
) -> Result<Assessment, AnalysisError> {
    let wanted: Vec<Direction> = match only {
        Some(d) => vec![d],
        None => vec![Direction::Right, Direction::Left],
    };
    let runs: Vec<_> = wanted
        .iter()
        .map(|&d| {
            let mut o = options.clone();
            o.static_settings = o.static_settings.clone().direction(d);
            let a = assess(scene, &o, settings)?;
            rotation_governs(&a).map_err(AnalysisError::Other)?;
            Ok(a)
        })
        .collect();
    let mut directions = Vec::with_capacity(runs.len());
    let mut failed = None;
    for (d, r) in wanted.iter().zip(runs) {
        match r {
            Ok(a) => directions.push(a),
            Err(e) if failed.is_none() => failed = Some((*d, e)),
            Err(_) => {}
        }
    }
    if let Some((d, e)) = failed {
        // Both failed (or the only one asked for): the error as it is.
        let Some(other) = directions.first() else {
            return Err(e);
        };
        let other = direction_name(other.capacity.direction);
        return Err(AnalysisError::Other(format!(
            "the load toward the {} cannot be assessed: {e}. The load toward the {other} can, but a verdict needs both directions: give --direction {other} to assess that one alone (its verdict then covers that direction only)",
            direction_name(d)
        )));
    }
    let verdicts: Vec<&crate::assess::Verdict> = directions.iter().map(|a| &a.verdict).collect();
    let governing = crate::assess::governing_index(&verdicts);
    Ok(Assessment {
        directions,
        governing,
        restricted: only.is_some(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn options_name_the_setting_out_of_range() {
        assert!(Options::default().validate().is_ok());
        let big = Options {
            kinematic_max_joints: MAX_EXHAUSTIVE_JOINTS + 1,
            ..Options::default()
        };
        let e = big.validate().expect_err("refused").to_string();
        assert!(
            e.contains("--kinematic-max-joints") && e.contains("1001"),
            "{e}"
        );
        let loose = Options {
            static_settings: StaticSettings::default().tolerance(1e-3),
            ..Options::default()
        };
        let e = loose.validate().expect_err("refused").to_string();
        assert!(e.contains("tolerance"), "{e}");
    }
}
