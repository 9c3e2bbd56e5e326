//! The JSON report of `voussoir assess` ([`AssessmentReport`], a contract for scripts: later
//! versions add fields, never rename them); its document is
//! [`super::documents::assessment`].

use crate::analysis::Assessment;
use crate::analysis::SiteAssessment;
use crate::assembly::Hinge;
use crate::assess::{CapacityPoint, Check, ParticipatingMass, Satisfied, TieOnCurve, RULE};
use crate::hazard::SiteHazard;
use crate::outcome::Direction;
use crate::report::SceneReport;
use crate::scene::Scene;
use crate::spectrum::Site;
use serde::Serialize;

/// `[site]` as the verdict used it (defaults filled in), keys as in the scene.
#[derive(Debug, Serialize)]
pub struct SiteReport {
    /// Peak ground acceleration on rock (g).
    pub ag: f64,
    pub soil: &'static str,
    pub topography: &'static str,
    #[serde(rename = "F0")]
    pub f0: f64,
    #[serde(rename = "Tc_star")]
    pub tc_star: f64,
    pub q: f64,
    #[serde(rename = "FC")]
    pub fc: f64,
    #[serde(rename = "Z")]
    pub z: f64,
    #[serde(rename = "H")]
    pub h: Option<f64>,
    #[serde(rename = "T1")]
    pub t1: Option<f64>,
    /// Added: the site's coordinates (degrees) and design, present only for a site given by
    /// its coordinates (`ag`, `F0`, `Tc_star` above are then the grid's values there).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub latitude: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub longitude: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub nominal_life: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub use_class: Option<&'static str>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub limit_state: Option<&'static str>,
    /// Added, with the coordinates: how the grid gave `ag`, `F0`, `Tc*` (`C_U`, `V_R`,
    /// `P_VR`, `T_R`, the values, the return periods and the cell's four nodes with their
    /// distances; docs/assessment.md).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub hazard: Option<SiteHazard>,
}

impl SiteReport {
    pub fn new(s: &Site) -> Self {
        SiteReport {
            ag: s.ag,
            soil: s.soil.as_str(),
            topography: s.topography.as_str(),
            f0: s.f0,
            tc_star: s.tc_star,
            q: s.q,
            fc: s.fc,
            z: s.z,
            h: s.h,
            t1: s.t1,
            latitude: s.hazard.as_ref().map(|h| h.latitude),
            longitude: s.hazard.as_ref().map(|h| h.longitude),
            nominal_life: s.hazard.as_ref().map(|h| h.nominal_life),
            use_class: s.hazard.as_ref().map(|h| h.use_class.as_str()),
            limit_state: s.hazard.as_ref().map(|h| h.limit_state.as_str()),
            hazard: s.hazard.clone(),
        }
    }
}

/// The elastic spectrum's parameters.
#[derive(Debug, Serialize)]
pub struct SpectrumReport {
    /// `ag` in m/s^2.
    pub ag_ms2: f64,
    #[serde(rename = "S")]
    pub s: f64,
    #[serde(rename = "SS")]
    pub ss: f64,
    #[serde(rename = "ST")]
    pub st: f64,
    pub eta: f64,
    /// Corner periods (s).
    #[serde(rename = "TB")]
    pub tb: f64,
    #[serde(rename = "TC")]
    pub tc: f64,
    #[serde(rename = "TD")]
    pub td: f64,
}

/// The governing mechanism, as assessed.
#[derive(Debug, Serialize)]
pub struct MechanismReport {
    pub hinges: Vec<Hinge>,
    /// The moving bodies, each as `[first block, last block]`.
    pub bodies: Vec<[usize; 2]>,
    /// Its multiplier from the kinematic analysis.
    pub lambda: f64,
}

/// The assessment of one direction of the load (its own governing mechanism).
#[derive(Debug, Serialize)]
pub struct DirectionReport {
    pub direction: Direction,
    /// The static (lower-bound) collapse multiplier.
    pub lambda_lower: Option<f64>,
    /// The kinematic (upper-bound) collapse multiplier.
    pub lambda_upper: Option<f64>,
    pub mechanism: MechanismReport,
    /// Block whose centroid is the control point.
    pub control_block: usize,
    pub participating_mass: ParticipatingMass,
    /// Multiplier at rest (= the mechanism's lambda).
    pub alpha0: f64,
    /// `a0* = alpha0 g / (e* FC)` (m/s^2).
    pub a0_star: f64,
    /// Control displacement at alpha = 0 (m).
    pub d_k0: f64,
    /// Spectral displacement at alpha = 0 (m).
    pub d0_star: f64,
    /// `du* = 0.4 d0*` (m).
    pub du_star: f64,
    /// `ds* = 0.4 du*` (m).
    pub ds_star: f64,
    /// `as* = a*(ds*)` (m/s^2).
    pub as_star: f64,
    /// Secant period `Ts = 2 pi sqrt(ds*/as*)` (s).
    #[serde(rename = "Ts")]
    pub ts: f64,
    /// Linear check `a0* >= ag S / q` (capacity and demand in m/s^2).
    pub linear_check: Check,
    /// Nonlinear check `du* >= SDe(Ts)` (capacity and demand in m).
    pub nonlinear_check: Check,
    /// The verdict of this direction: either check satisfied ([`crate::assess::RULE`]).
    pub passes: bool,
    /// Which checks are satisfied: `both`, `linear`, `nonlinear` or `neither`.
    pub satisfied: Satisfied,
    /// Both checks satisfied (the stricter reading; before the code's rule was applied this
    /// was `passes`).
    pub both_checks_pass: bool,
    /// The verdict in words, e.g. "passes: linear check satisfied (the nonlinear one is not)".
    pub verdict: &'static str,
    /// Largest `ag` (g) at which this direction passes by the rule: the larger of the two
    /// checks' `ag_max`; None when one passes even at 2 g.
    pub ag_max: Option<f64>,
    /// The capacity curve from rest to `d_k0`.
    pub capacity_curve: Vec<CapacityPoint>,
    /// Added: the tie rods along the curve (`[{index, lengthens, force, breaks_at_d_k}]`,
    /// empty without `[[ties]]`).
    pub ties: Vec<TieOnCurve>,
    /// Added (issue 23): how the curve follows the mechanism: `linkage` (a chain's closed-form
    /// finite kinematics) or `incremental` (re-solved in each displaced configuration).
    pub capacity_curve_method: &'static str,
    /// Added: where the curve ends: `alpha_zero`, or `cannot_stand` (the displaced structure
    /// has no equilibrium under any multiplier beyond `d_k0`: the incremental route only).
    pub capacity_curve_end: &'static str,
    /// Added: kinematic programs the incremental route solved (0 for a linkage).
    pub incremental_programs: usize,
}

impl DirectionReport {
    pub fn new(a: &SiteAssessment) -> Self {
        let (c, v) = (&a.capacity, &a.verdict);
        let k = a.analysis.upper.as_ref().ok();
        let mech = k.and_then(|k| k.mechanism.as_ref());
        DirectionReport {
            direction: c.direction,
            lambda_lower: a.analysis.lower.lambda,
            lambda_upper: a.analysis.lambda_upper(),
            mechanism: MechanismReport {
                hinges: mech.map(|m| m.hinges.clone()).unwrap_or_default(),
                bodies: c
                    .motion
                    .bodies()
                    .iter()
                    .map(|r| [r.start, r.end.saturating_sub(1)])
                    .collect(),
                lambda: mech.map_or(f64::NAN, |m| m.lambda),
            },
            control_block: c.control_block,
            participating_mass: c.mass,
            alpha0: c.alpha0,
            a0_star: c.a0_star,
            d_k0: c.d_k0,
            d0_star: c.d0_star,
            du_star: v.du_star,
            ds_star: v.ds_star,
            as_star: v.as_star,
            ts: v.ts,
            linear_check: v.linear,
            nonlinear_check: v.nonlinear,
            passes: v.passes(),
            satisfied: v.satisfied(),
            both_checks_pass: v.both_pass(),
            verdict: v.text(),
            ag_max: v.ag_max(),
            capacity_curve: c.curve.clone(),
            ties: c.ties.clone(),
            capacity_curve_method: c.motion.name(),
            capacity_curve_end: c.motion.end(),
            incremental_programs: c.motion.programs(),
        }
    }
}

/// The directions assessed, by name.
#[derive(Debug, Serialize)]
pub struct DirectionsReport {
    #[serde(skip_serializing_if = "Option::is_none")]
    pub right: Option<DirectionReport>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub left: Option<DirectionReport>,
}

/// `voussoir assess --json`. The fields before `directions` are those of the governing
/// direction (the worse one), so a script written when only one direction was assessed reads
/// the governing verdict; `directions` holds each direction in full.
#[derive(Debug, Serialize)]
pub struct AssessmentReport {
    pub scene: SceneReport,
    /// The governing direction (the direction of every direction-dependent field below).
    pub direction: Direction,
    /// The static (lower-bound) collapse multiplier.
    pub lambda_lower: Option<f64>,
    /// The kinematic (upper-bound) collapse multiplier.
    pub lambda_upper: Option<f64>,
    pub mechanism: MechanismReport,
    pub site: SiteReport,
    pub spectrum: SpectrumReport,
    /// Block whose centroid is the control point.
    pub control_block: usize,
    pub participating_mass: ParticipatingMass,
    /// Multiplier at rest (= the mechanism's lambda).
    pub alpha0: f64,
    /// `a0* = alpha0 g / (e* FC)` (m/s^2).
    pub a0_star: f64,
    /// Control displacement at alpha = 0 (m).
    pub d_k0: f64,
    /// Spectral displacement at alpha = 0 (m).
    pub d0_star: f64,
    /// `du* = 0.4 d0*` (m).
    pub du_star: f64,
    /// `ds* = 0.4 du*` (m).
    pub ds_star: f64,
    /// `as* = a*(ds*)` (m/s^2).
    pub as_star: f64,
    /// Secant period `Ts = 2 pi sqrt(ds*/as*)` (s).
    #[serde(rename = "Ts")]
    pub ts: f64,
    /// Linear check `a0* >= ag S / q` (capacity and demand in m/s^2).
    pub linear_check: Check,
    /// Nonlinear check `du* >= SDe(Ts)` (capacity and demand in m).
    pub nonlinear_check: Check,
    /// The verdict: every direction assessed passes, each by the linear or the nonlinear
    /// check ([`crate::assess::RULE`]). (Until both directions were assessed this was "both
    /// checks pass, load to the right"; `both_checks_pass` keeps the stricter reading.)
    pub passes: bool,
    /// The capacity curve from rest to `d_k0`.
    pub capacity_curve: Vec<CapacityPoint>,
    /// The governing direction, `right` or `left` (the same as `direction`).
    pub governing: Direction,
    /// The directions assessed: `["right", "left"]`, or the one given with `--direction`.
    pub directions_assessed: Vec<Direction>,
    /// Whether `--direction` restricted the assessment to one direction (the verdict then
    /// covers that direction only).
    pub restricted: bool,
    /// Which checks the governing direction satisfies: `both`, `linear`, `nonlinear`, `neither`.
    pub satisfied: Satisfied,
    /// Both checks satisfied in every direction assessed.
    pub both_checks_pass: bool,
    /// The verdict in words, e.g. "passes: linear check satisfied (the nonlinear one is not)".
    pub verdict: String,
    /// The rule applied to the two checks.
    pub rule: &'static str,
    /// Largest `ag` (g) at which the governing direction passes by the rule.
    pub ag_max: Option<f64>,
    /// Each direction assessed, in full.
    pub directions: DirectionsReport,
}

impl AssessmentReport {
    pub fn new(scene: &Scene, all: &Assessment) -> Self {
        let a = all.governing();
        let v = &a.verdict;
        let g = DirectionReport::new(a);
        let mut directions = DirectionsReport {
            right: None,
            left: None,
        };
        for d in &all.directions {
            let r = DirectionReport::new(d);
            match d.capacity.direction {
                Direction::Right => directions.right = Some(r),
                Direction::Left => directions.left = Some(r),
            }
        }
        AssessmentReport {
            scene: SceneReport::new(scene, &a.analysis.model),
            direction: g.direction,
            lambda_lower: g.lambda_lower,
            lambda_upper: g.lambda_upper,
            mechanism: g.mechanism,
            site: SiteReport::new(&a.site),
            spectrum: SpectrumReport {
                ag_ms2: v.spectrum.ag,
                s: v.spectrum.s,
                ss: v.spectrum.ss,
                st: v.spectrum.st,
                eta: v.spectrum.eta,
                tb: v.spectrum.tb,
                tc: v.spectrum.tc,
                td: v.spectrum.td,
            },
            control_block: g.control_block,
            participating_mass: g.participating_mass,
            alpha0: g.alpha0,
            a0_star: g.a0_star,
            d_k0: g.d_k0,
            d0_star: g.d0_star,
            du_star: g.du_star,
            ds_star: g.ds_star,
            as_star: g.as_star,
            ts: g.ts,
            linear_check: g.linear_check,
            nonlinear_check: g.nonlinear_check,
            passes: all.passes(),
            capacity_curve: g.capacity_curve,
            governing: g.direction,
            directions_assessed: all
                .directions
                .iter()
                .map(|d| d.capacity.direction)
                .collect(),
            restricted: all.restricted,
            satisfied: g.satisfied,
            both_checks_pass: all.directions.iter().all(|d| d.verdict.both_pass()),
            verdict: verdict_line(all),
            rule: RULE,
            ag_max: g.ag_max,
            directions,
        }
    }
}

pub(crate) fn direction_words(d: Direction) -> &'static str {
    match d {
        Direction::Right => "load toward the right",
        Direction::Left => "load toward the left",
    }
}

/// The verdict over the directions, in one line.
pub(crate) fn verdict_line(all: &Assessment) -> String {
    let g = all.governing();
    let d = direction_words(g.capacity.direction);
    if all.restricted {
        format!(
            "{}; {d} only (--direction excluded the other)",
            g.verdict.text()
        )
    } else {
        format!("{}; governing direction: {d}", g.verdict.text())
    }
}

pub(crate) fn verdict_word(c: &Check) -> &'static str {
    if c.passes {
        "satisfied"
    } else {
        "NOT satisfied"
    }
}

pub(crate) fn ag_text(ag: Option<f64>) -> String {
    match ag {
        Some(ag) => format!("{ag:.4} g"),
        None => format!("more than {} g", crate::assess::AG_SEARCH_MAX),
    }
}
