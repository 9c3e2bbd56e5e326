//! Every knob of the DEM time stepping, gathered in one struct (in the manner of rapier's
//! `IntegrationParameters`), with defaults derived from the geometry of the assembly so that
//! no scene needs tuning, overridable from the scene's `[dem]` table and by builder setters.
//! They live beside `crate::dem`, not inside it, so a scene checks its `[dem]` knobs (each
//! against [`allowed_range`]) without importing the simulation.
//!
//! The defaults are chosen from three scales of the structure: its size `L`
//! (`Assembly::size`), its total weight `W` and the gravity time `T = sqrt(L / g)`:
//!
//! | knob                    | default                     | why |
//! |-------------------------|-----------------------------|-----|
//! | `normal_stiffness`      | `W / (3e-5 t)` (N/m per contact point), `t` the shortest joint | the whole weight on one contact point would press it in by `3e-5 t`. The DEM multiplier converges to the rigid-block one as `1/kn` (the elastic sag before the hinges form softens the arch): on a 16-voussoir semicircle with t/R = 0.15 the offset is -18% at `W/(3e-3 t)`, -3.5% at `W/(3e-4 t)`, -0.9% at this default |
//! | `shear_stiffness`       | `normal_stiffness`          | the joints of dry masonry are about as stiff in shear as in compression (UDEC practice: `ks` between `kn/2` and `kn`) |
//! | `contact_damping`       | 0.3 of critical             | kills the contact rattling within a few contact periods without slowing rigid-body motion (a dashpot only acts on relative velocity at a touching point) |
//! | `local_damping`         | 0.5                         | Cundall's non-viscous local damping: every block force is reduced by `alpha |F| sign(v)`; it removes energy from every mode at any frequency and can never hold a block that is out of balance (the damping force is below the unbalanced force), so it settles quasi-statically without moving the collapse threshold |
//! | `hold_damping`          | 0.5                         | the same local damping once the load is held: with 0 the residual vibration of a structure just below its threshold kicks it into the mechanism (DEM multiplier 0.5-1% low); a mechanism slowed to a steady creep by the damping is caught by the creep test of the protocol |
//! | `time_step_factor`      | 0.9                         | fraction of the explicit stability limit `2 / omega_max (sqrt(1 + z^2) - z)` of the stiffest block (a Gershgorin bound over all its possible contacts, with the damping ratio `z` its dashpots give that mode) |
//! | `ramp_time`             | `0.3 T`                     | the permanent loads (settling) and the seismic ones are applied over a linear ramp, so there is no dynamic overshoot of a step load |
//! | `max_time`              | `40 T`                      | longest run after the ramp before a run is declared undecided |
//! | `collapse_displacement` | `0.01 L`                    | a run collapses when a block point has moved by more than this since the start of the run: 300 times the elastic overlaps, and the arch mechanisms soften geometrically, so a mechanism that has moved this far does not come back |
//! | `rest_velocity`         | `1e-5 sqrt(g L)`            | a run is at rest when, the load held for one ramp time, no block point moves faster than this ... |
//! | `rest_force`            | `1e-5`                      | ... and no block has an unbalanced force (or moment / its radius) above this fraction of its load scale (its weight plus the magnitudes of the other loads it carries) |
//! | `infinite_friction`     | 1000                        | the Coulomb coefficient used for `friction = inf` |
//! | `contact_tolerance`     | `1e-3 t`                    | corner rounding: a vertex pressing into an edge still touches it this far beyond the edge's end; also the window for choosing the edge near a corner. Several times the elastic overlaps, and small against any joint |
//! | `max_lambda`            | 10                          | above this multiplier (84 deg tilt) the structure is said not to collapse |
//! | `integrator`            | `"auto"`                    | the time stepping: `"explicit"`, penalty contacts with explicit steps at the stability limit, or `"moreau"`, rigid contacts by Moreau-Jean time stepping (`crate::dem` `moreau` module, docs/dem.md) at steps of `3e-3 T`; `"auto"` takes `"moreau"` for the collapse search of a chain without ties, strips or fill and with none of the explicit stepping's knobs named, even at its default value (the rigid stepping holds the exact threshold there, 10 to 24 times faster), `"explicit"` otherwise ([`Integrator::Auto`]) |

use crate::assembly::Assembly;
use crate::error::SceneError;
use crate::model::Model;
use toml::{Table, Value};

/// Overlap, as a fraction of the shortest joint, that the whole weight would cause on a
/// single contact point with the default normal stiffness.
pub const STIFFNESS_OVERLAP: f64 = 3e-5;

/// The most time steps one run may plan (its longest possible length over the time step)
/// unless the caller lifts it (`IntegrationParameters::max_steps`, the CLI's `--max-steps`).
/// The default runs plan 0.2 to 3 million steps; 5e7 steps is about 15 s of wall time for one
/// block and 2 minutes for 20 (docs/dem.md), so a `dem.time_step = 1e-9`, a record with
/// `DT = 1e9` or contacts a million times too stiff are refused before they run for hours.
pub const DEFAULT_MAX_STEPS: u64 = 50_000_000;

/// Stiffer contacts than this (N/m) are not a model of masonry joints (the defaults are
/// 1e8 to 1e11) and their products overflow nothing but make the time step vanish.
pub const MAX_STIFFNESS: f64 = 1e16;

/// How the DEM advances in time (`[dem] integrator`, the CLI's `--integrator`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Integrator {
    /// The default: [`Integrator::Moreau`] for the collapse search of a chain (an arch, a
    /// portal of voussoirs between two supports) without ties, strips or passive fill and with
    /// none of the explicit stepping's own knobs named (even at its default value), where the
    /// rigid stepping brackets the exact threshold 10 to 30 times faster (docs/dem.md);
    /// [`Integrator::Explicit`] for everything else: other assemblies (walls, where the two
    /// differ and the rigid contact solve may not settle), records and pulses (where the two
    /// differ near collapse), and the direct [`crate::dem::Simulation`].
    /// [`IntegrationParameters::resolved`] decides.
    #[default]
    Auto,
    /// Penalty springs and dashpots at the contacts, symplectic Euler at a step under the
    /// stability limit of the stiffest contact (about 1e-5 s).
    Explicit,
    /// Rigid contacts: Moreau-Jean non-smooth contact dynamics, velocity-level impulses with
    /// Signorini, Coulomb and Newton's impact law, solved by projected Gauss-Seidel at each
    /// step of [`MOREAU_STEP_SHARE`] of the gravity time (about 1e-3 s).
    Moreau,
}

impl Integrator {
    /// Every integrator, as the scene and the command line name them.
    pub const NAMES: &'static [&'static str] = &["auto", "explicit", "moreau"];

    /// `auto`, `explicit` or `moreau`.
    pub fn name(self) -> &'static str {
        match self {
            Integrator::Auto => "auto",
            Integrator::Explicit => "explicit",
            Integrator::Moreau => "moreau",
        }
    }

    /// The integrator named `name` (case-insensitive), if any.
    pub fn parse(name: &str) -> Option<Integrator> {
        match name.trim().to_ascii_lowercase().as_str() {
            "auto" => Some(Integrator::Auto),
            "explicit" => Some(Integrator::Explicit),
            "moreau" => Some(Integrator::Moreau),
            _ => None,
        }
    }
}

/// The Moreau-Jean time step, as a share of the gravity time `sqrt(L / g)` of the structure
/// (`L` its size): 3e-3, about 1e-3 s for a structure 1 m across, a few hundredths of a
/// degree of a rocking block's rotation per step at the speeds that overturn it.
pub const MOREAU_STEP_SHARE: f64 = 3e-3;

/// The longest Moreau-Jean step allowed, as a share of the gravity time: beyond it a block
/// moves by a sizeable part of itself in one step and contacts are found too late.
pub const MOREAU_MAX_STEP_SHARE: f64 = 0.05;

/// A knob's value as an error shows it: plainly, or in exponent form when very large or
/// small (so 1e308 is not echoed as 309 digits).
pub fn show_value(v: f64) -> String {
    if v != 0.0 && v.is_finite() && !(1e-4..1e6).contains(&v.abs()) {
        format!("{v:e}")
    } else {
        v.to_string()
    }
}

/// The range of each numeric `[dem]` knob, as a test of the value and the words of the error.
/// The same ranges hold for the `[dem]` table and for the builder setters
/// ([`IntegrationParameters::check`]), so a value that would overflow a contact force (1e308)
/// is refused by name instead of turning into a NaN in the time stepping.
pub fn allowed_range(key: &str, v: f64) -> Result<f64, &'static str> {
    let (ok, words) = match key {
        "gravity" => (
            (0.01..=1000.0).contains(&v),
            "must be >= 0.01 and <= 1000 m/s^2 (g is 9.81)",
        ),
        "normal_stiffness" | "shear_stiffness" => (
            v > 0.0 && v <= MAX_STIFFNESS,
            "must be > 0 and <= 1e16 N/m (the defaults are 1e8 to 1e11)",
        ),
        "contact_damping" => (
            (0.0..=2.0).contains(&v),
            "must be >= 0 and <= 2 (fraction of critical)",
        ),
        "local_damping" | "hold_damping" => ((0.0..1.0).contains(&v), "must be >= 0 and < 1"),
        "time_step_factor" => (v > 0.0 && v <= 1.0, "must be > 0 and <= 1"),
        "rest_force" => (
            v > 0.0 && v < 1.0,
            "must be > 0 and < 1 (fraction of block weight)",
        ),
        "infinite_friction" => (
            v > 0.0 && v <= 1e6,
            "must be > 0 and <= 1e6 (a Coulomb coefficient)",
        ),
        "max_lambda" => (
            v > 0.0 && v <= 100.0,
            "must be > 0 and <= 100 (lambda = 10 is a tilt of 84 degrees)",
        ),
        "initial_guess" => (
            v > 0.0 && v <= 100.0,
            "must be > 0 and <= 100 (and at most dem.max_lambda)",
        ),
        _ => (v.is_finite() && v > 0.0, "must be a finite number > 0"),
    };
    if ok && v.is_finite() {
        Ok(v)
    } else {
        Err(words)
    }
}

/// Time-stepping knobs of the DEM (SI units). Build with [`IntegrationParameters::for_model`]
/// or [`IntegrationParameters::for_assembly`], then adjust with the setters or a `[dem]` table
/// ([`IntegrationParameters::apply_table`]; the analysis layer does both for a scene).
#[derive(Debug, Clone, PartialEq)]
pub struct IntegrationParameters {
    /// Gravitational acceleration g (m/s^2). Default 9.81. The multiplier does not depend on
    /// it; it only sets the time scale.
    pub gravity: f64,
    /// Normal penalty stiffness of one vertex-to-edge contact (N/m). Default `W / (3e-5 t)`
    /// with `t` the shortest joint.
    pub normal_stiffness: f64,
    /// Shear penalty stiffness of one contact (N/m). Default: the normal stiffness.
    pub shear_stiffness: f64,
    /// Viscous damping of each contact, as a fraction of the critical damping of the two
    /// touching masses on the normal spring (also used in shear). Default 0.3.
    pub contact_damping: f64,
    /// Cundall's local damping coefficient alpha in [0, 1) while a load is ramped in.
    /// Default 0.5.
    pub local_damping: f64,
    /// Cundall's local damping coefficient once the load is held. Default 0.5 (the same):
    /// with less, the residual vibration of a structure just below its threshold can kick it
    /// into the mechanism and the DEM multiplier drops (by ~0.5-1% with 0).
    pub hold_damping: f64,
    /// Fraction of the explicit stability limit used as the time step. Default 0.9.
    pub time_step_factor: f64,
    /// An explicit time step (s) instead of the one from `time_step_factor`.
    pub time_step: Option<f64>,
    /// Duration of the linear ramp of the permanent loads (settling) and of the seismic
    /// ones (s).
    /// Default `0.3 sqrt(L/g)`.
    pub ramp_time: f64,
    /// Longest time a run may last after its ramp before it is declared undecided (s).
    /// Default `40 sqrt(L/g)`.
    pub max_time: f64,
    /// Displacement (m) of any block point since the start of a run beyond which the run
    /// has collapsed. Default `0.01 L`.
    pub collapse_displacement: f64,
    /// Largest speed (m/s) of any block point for the run to count as at rest. Default
    /// `1e-5 sqrt(g L)`.
    pub rest_velocity: f64,
    /// Largest unbalanced force of any block, as a fraction of its load scale (its weight
    /// plus the magnitudes of the other loads it carries), for the run to count as at rest.
    /// Default 1e-5.
    pub rest_force: f64,
    /// Friction coefficient used for joints with `friction = inf`. Default 1000.
    pub infinite_friction: f64,
    /// Corner rounding (m): how far beyond an edge's end a vertex pressing into it still
    /// touches it. Default `1e-3 t` with `t` the shortest joint.
    pub contact_tolerance: f64,
    /// Largest multiplier tried; beyond it the structure is said not to collapse. Default 10.
    pub max_lambda: f64,
    /// Where the bracket search starts (e.g. the static lambda_lower). `None`: the function
    /// solves the static program itself for it.
    pub initial_guess: Option<f64>,
    /// Record block positions every this many seconds of simulated time (for
    /// `write_snapshots`); `None` records nothing. Default `None`.
    pub snapshot_interval: Option<f64>,
    /// The most time steps one run may plan (its longest possible length over the time
    /// step); a run planning more is refused before it starts. Default
    /// [`DEFAULT_MAX_STEPS`]; not a `[dem]` key (the CLI's `--max-steps` sets it).
    pub max_steps: u64,
    /// How the blocks are advanced in time. Default [`Integrator::Auto`], which
    /// [`IntegrationParameters::resolved`] turns into one of the other two.
    pub integrator: Integrator,
    /// Whether a knob only the explicit stepping reads was named (by its setter or its
    /// `[dem]` key), whatever its value: [`Integrator::Auto`] then takes the explicit
    /// stepping, also for a value equal to the default (a study that varies the contacts'
    /// stiffness from its default keeps one stepping on every row). Default false.
    pub explicit_knobs_named: bool,
}

/// The `[dem]` keys only the explicit stepping reads: naming any of them (whatever its
/// value) makes [`Integrator::Auto`] take the explicit stepping.
const EXPLICIT_KNOBS: &[&str] = &[
    "normal_stiffness",
    "shear_stiffness",
    "contact_damping",
    "local_damping",
    "hold_damping",
    "time_step_factor",
];

/// What a DEM run is for, which decides [`Integrator::Auto`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Purpose {
    /// The bracket search of the collapse multiplier (`voussoir dem`, `analyze --dem`).
    CollapseSearch,
    /// A record, a pulse or an incremental dynamic analysis (`dem --record`, `--pulse`, `ida`).
    GroundMotion,
}

/// Whether the rigid stepping is validated for `model`'s collapse search: a chain of blocks
/// between two supports (an arch, a portal of voussoirs and pier courses) with no ties,
/// strips or passive fill (elastic bars the rigid stepping refuses).
fn rigid_suits(model: &Model) -> bool {
    model.assembly.is_chain()
        && model.ties.is_empty()
        && model.strips.is_empty()
        && model.passive.is_empty()
}

/// Every key the `[dem]` table accepts.
pub const DEM_KEYS: &[&str] = &[
    "gravity",
    "normal_stiffness",
    "shear_stiffness",
    "contact_damping",
    "local_damping",
    "hold_damping",
    "time_step_factor",
    "time_step",
    "ramp_time",
    "max_time",
    "collapse_displacement",
    "rest_velocity",
    "rest_force",
    "infinite_friction",
    "contact_tolerance",
    "max_lambda",
    "initial_guess",
    "snapshot_interval",
    "integrator",
];

impl IntegrationParameters {
    /// Defaults derived from the size and weight of `assembly` under its self-weight (see
    /// the module docs).
    pub fn for_assembly(assembly: &Assembly) -> Self {
        Self::for_model(&Model::self_weight(assembly.clone()))
    }

    /// Defaults derived from the size of the model's assembly and the magnitude of its loads
    /// ([`crate::model::LoadCase::force_scale`], the total weight under self-weight alone), so
    /// a heavy fill stiffens the contacts in proportion.
    pub fn for_model(model: &Model) -> Self {
        let assembly = &model.assembly;
        let gravity = 9.81;
        let size = assembly.size().max(f64::MIN_POSITIVE);
        let weight = model.loads.force_scale().max(f64::MIN_POSITIVE);
        let t = (size / gravity).sqrt();
        // The shortest joint: the lever arm every hinge has to work with.
        let joint = assembly
            .joints
            .iter()
            .map(|j| j.length())
            .fold(f64::INFINITY, f64::min)
            .min(size);
        let kn = weight / (STIFFNESS_OVERLAP * joint);
        IntegrationParameters {
            gravity,
            normal_stiffness: kn,
            shear_stiffness: kn,
            contact_damping: 0.3,
            local_damping: 0.5,
            hold_damping: 0.5,
            time_step_factor: 0.9,
            time_step: None,
            ramp_time: 0.3 * t,
            max_time: 40.0 * t,
            collapse_displacement: 0.01 * size,
            rest_velocity: 1e-5 * (gravity * size).sqrt(),
            rest_force: 1e-5,
            infinite_friction: 1000.0,
            contact_tolerance: 1e-3 * joint,
            max_lambda: 10.0,
            initial_guess: None,
            snapshot_interval: None,
            max_steps: DEFAULT_MAX_STEPS,
            integrator: Integrator::Auto,
            explicit_knobs_named: false,
        }
    }

    /// These parameters with [`Integrator::Auto`] decided for a run on `model` for
    /// `purpose` (the rule is [`Integrator::Auto`]'s); any other integrator is kept.
    pub fn resolved(&self, model: &Model, purpose: Purpose) -> IntegrationParameters {
        let mut p = self.clone();
        if p.integrator == Integrator::Auto {
            p.integrator = if purpose == Purpose::CollapseSearch
                && rigid_suits(model)
                && !self.explicit_knobs_set(model)
            {
                Integrator::Moreau
            } else {
                Integrator::Explicit
            };
        }
        p
    }

    /// Whether a knob only the explicit stepping reads (the contacts' stiffness and damping,
    /// Cundall's damping, the share of the stability limit) was named by its setter or its
    /// `[dem]` key, or differs from its default for `model` (a field written directly): set
    /// by the scene or the caller, which asks for the explicit stepping.
    fn explicit_knobs_set(&self, model: &Model) -> bool {
        let d = IntegrationParameters::for_model(model);
        self.explicit_knobs_named
            || self.normal_stiffness != d.normal_stiffness
            || self.shear_stiffness != d.shear_stiffness
            || self.contact_damping != d.contact_damping
            || self.local_damping != d.local_damping
            || self.hold_damping != d.hold_damping
            || self.time_step_factor != d.time_step_factor
    }

    /// Every knob within [`allowed_range`], and the start of the search at most
    /// `max_lambda`: the first knob out of range as `(dem.KEY, value, allowed)`.
    pub fn check(&self) -> Result<(), (String, f64, &'static str)> {
        let mut knobs = vec![
            ("gravity", self.gravity),
            ("normal_stiffness", self.normal_stiffness),
            ("shear_stiffness", self.shear_stiffness),
            ("contact_damping", self.contact_damping),
            ("local_damping", self.local_damping),
            ("hold_damping", self.hold_damping),
            ("time_step_factor", self.time_step_factor),
            ("ramp_time", self.ramp_time),
            ("max_time", self.max_time),
            ("collapse_displacement", self.collapse_displacement),
            ("rest_velocity", self.rest_velocity),
            ("rest_force", self.rest_force),
            ("infinite_friction", self.infinite_friction),
            ("contact_tolerance", self.contact_tolerance),
            ("max_lambda", self.max_lambda),
        ];
        knobs.extend(self.time_step.map(|v| ("time_step", v)));
        knobs.extend(self.initial_guess.map(|v| ("initial_guess", v)));
        knobs.extend(self.snapshot_interval.map(|v| ("snapshot_interval", v)));
        for (key, v) in knobs {
            allowed_range(key, v).map_err(|words| (format!("dem.{key}"), v, words))?;
        }
        Ok(())
    }

    /// Apply the entries of a `[dem]` table (`origin` names it in errors).
    pub fn apply_table(&mut self, table: &Table, origin: &str) -> Result<(), SceneError> {
        for (key, value) in table {
            self.set(key, value, origin)?;
        }
        Ok(())
    }

    /// Set one knob by its `[dem]` key, with the scene's validation.
    pub fn set(&mut self, key: &str, value: &Value, origin: &str) -> Result<(), SceneError> {
        let full = format!("dem.{key}");
        let number = || -> Result<f64, SceneError> {
            match value {
                Value::Float(x) => Ok(*x),
                Value::Integer(i) => Ok(*i as f64),
                Value::String(s) if s.trim().eq_ignore_ascii_case("inf") => Ok(f64::INFINITY),
                v => Err(SceneError::WrongType {
                    origin: origin.to_string(),
                    key: full.clone(),
                    value: v.to_string(),
                    expected: "a number".to_string(),
                }),
            }
        };
        let out_of_range = |v: f64, allowed: &str| SceneError::OutOfRange {
            origin: origin.to_string(),
            key: full.clone(),
            value: show_value(v),
            allowed: allowed.to_string(),
        };
        let checked = |v: f64| allowed_range(key, v).map_err(|words| out_of_range(v, words));
        match key {
            "gravity" => self.gravity = checked(number()?)?,
            "normal_stiffness" => self.normal_stiffness = checked(number()?)?,
            "shear_stiffness" => self.shear_stiffness = checked(number()?)?,
            "contact_damping" => self.contact_damping = checked(number()?)?,
            "local_damping" => self.local_damping = checked(number()?)?,
            "hold_damping" => self.hold_damping = checked(number()?)?,
            "time_step_factor" => self.time_step_factor = checked(number()?)?,
            "time_step" => self.time_step = Some(checked(number()?)?),
            "ramp_time" => self.ramp_time = checked(number()?)?,
            "max_time" => self.max_time = checked(number()?)?,
            "collapse_displacement" => self.collapse_displacement = checked(number()?)?,
            "rest_velocity" => self.rest_velocity = checked(number()?)?,
            "rest_force" => self.rest_force = checked(number()?)?,
            "infinite_friction" => self.infinite_friction = checked(number()?)?,
            "contact_tolerance" => self.contact_tolerance = checked(number()?)?,
            "max_lambda" => self.max_lambda = checked(number()?)?,
            "initial_guess" => self.initial_guess = Some(checked(number()?)?),
            "snapshot_interval" => self.snapshot_interval = Some(checked(number()?)?),
            "integrator" => {
                let wrong = |v: &Value| SceneError::WrongType {
                    origin: origin.to_string(),
                    key: full.clone(),
                    value: v.to_string(),
                    expected: format!("one of {}", Integrator::NAMES.join(", ")),
                };
                self.integrator = match value {
                    Value::String(s) => Integrator::parse(s).ok_or_else(|| wrong(value))?,
                    v => return Err(wrong(v)),
                }
            }
            _ => {
                return Err(SceneError::UnknownKey {
                    origin: origin.to_string(),
                    key: full,
                    hint: format!(
                        "{} (allowed in [dem]: {})",
                        crate::error::did_you_mean(key, DEM_KEYS),
                        DEM_KEYS.join(", ")
                    ),
                })
            }
        }
        if EXPLICIT_KNOBS.contains(&key) {
            self.explicit_knobs_named = true;
        }
        Ok(())
    }

    /// Set a knob from a `KEY=VALUE` text (CLI `--set dem.KEY=VALUE` style, with or without
    /// the `dem.` prefix).
    pub fn with_override(mut self, assignment: &str) -> Result<Self, SceneError> {
        let (key, value) = crate::overrides::parse_assignment(assignment)?;
        let key = key.strip_prefix("dem.").unwrap_or(&key).to_string();
        self.set(&key, &value, "--set")?;
        Ok(self)
    }

    pub fn gravity(mut self, g: f64) -> Self {
        self.gravity = g;
        self
    }
    pub fn normal_stiffness(mut self, k: f64) -> Self {
        self.normal_stiffness = k;
        self.explicit_knobs_named = true;
        self
    }
    pub fn shear_stiffness(mut self, k: f64) -> Self {
        self.shear_stiffness = k;
        self.explicit_knobs_named = true;
        self
    }
    pub fn contact_damping(mut self, ratio: f64) -> Self {
        self.contact_damping = ratio;
        self.explicit_knobs_named = true;
        self
    }
    pub fn local_damping(mut self, alpha: f64) -> Self {
        self.local_damping = alpha;
        self.explicit_knobs_named = true;
        self
    }
    pub fn hold_damping(mut self, alpha: f64) -> Self {
        self.hold_damping = alpha;
        self.explicit_knobs_named = true;
        self
    }
    pub fn time_step_factor(mut self, f: f64) -> Self {
        self.time_step_factor = f;
        self.explicit_knobs_named = true;
        self
    }
    pub fn time_step(mut self, dt: Option<f64>) -> Self {
        self.time_step = dt;
        self
    }
    pub fn ramp_time(mut self, t: f64) -> Self {
        self.ramp_time = t;
        self
    }
    pub fn max_time(mut self, t: f64) -> Self {
        self.max_time = t;
        self
    }
    pub fn collapse_displacement(mut self, d: f64) -> Self {
        self.collapse_displacement = d;
        self
    }
    pub fn rest_velocity(mut self, v: f64) -> Self {
        self.rest_velocity = v;
        self
    }
    pub fn rest_force(mut self, f: f64) -> Self {
        self.rest_force = f;
        self
    }
    pub fn infinite_friction(mut self, mu: f64) -> Self {
        self.infinite_friction = mu;
        self
    }
    pub fn contact_tolerance(mut self, d: f64) -> Self {
        self.contact_tolerance = d;
        self
    }
    pub fn max_lambda(mut self, l: f64) -> Self {
        self.max_lambda = l;
        self
    }
    pub fn initial_guess(mut self, l: Option<f64>) -> Self {
        self.initial_guess = l;
        self
    }
    pub fn snapshot_interval(mut self, dt: Option<f64>) -> Self {
        self.snapshot_interval = dt;
        self
    }
    pub fn integrator(mut self, integrator: Integrator) -> Self {
        self.integrator = integrator;
        self
    }

    pub fn max_steps(mut self, n: u64) -> Self {
        self.max_steps = n;
        self
    }
}
