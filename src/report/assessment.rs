//! The printers of `voussoir assess`: its JSON report ([`AssessmentReport`], a contract for
//! scripts: later versions add fields, never rename them) and its text summary
//! ([`assessment_summary`]).

use crate::analysis::SiteAssessment;
use crate::assembly::Hinge;
use crate::assess::{CapacityPoint, Check, ParticipatingMass};
use crate::outcome::Direction;
use crate::report::SceneReport;
use crate::scene::Scene;
use crate::spectrum::Site;
use serde::Serialize;
use std::fmt::Write;

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

/// `voussoir assess --json`.
#[derive(Debug, Serialize)]
pub struct AssessmentReport {
    pub scene: SceneReport,
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
    /// Both checks pass.
    pub passes: bool,
    /// The capacity curve from rest to `d_k0`.
    pub capacity_curve: Vec<CapacityPoint>,
}

impl AssessmentReport {
    pub fn new(scene: &Scene, a: &SiteAssessment) -> Self {
        let (c, v) = (&a.capacity, &a.verdict);
        let k = a.analysis.upper.as_ref().ok();
        let mech = k.and_then(|k| k.mechanism.as_ref());
        AssessmentReport {
            scene: SceneReport::new(scene, &a.analysis.model),
            direction: c.direction,
            lambda_lower: a.analysis.lower.lambda,
            lambda_upper: a.analysis.lambda_upper(),
            mechanism: MechanismReport {
                hinges: mech.map(|m| m.hinges.clone()).unwrap_or_default(),
                bodies: c
                    .linkage
                    .bodies()
                    .iter()
                    .map(|r| [r.start, r.end.saturating_sub(1)])
                    .collect(),
                lambda: mech.map_or(f64::NAN, |m| m.lambda),
            },
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
            capacity_curve: c.curve.clone(),
        }
    }
}

fn verdict_word(c: &Check) -> &'static str {
    if c.passes {
        "passes"
    } else {
        "FAILS"
    }
}

fn ag_max(c: &Check) -> String {
    match c.ag_max {
        Some(ag) => format!("{ag:.4} g"),
        None => format!("more than {} g", crate::assess::AG_SEARCH_MAX),
    }
}

/// The text `voussoir assess` prints.
pub fn assessment_summary(scene: &Scene, a: &SiteAssessment) -> String {
    let (c, v, s) = (&a.capacity, &a.verdict, &a.site);
    let sp = &v.spectrum;
    let mut t = String::new();
    let _ = writeln!(t, "Scene: {}", scene.origin);
    let _ = writeln!(
        t,
        "Governing mechanism: alpha0 = lambda = {:.6} (static lower bound {}), bodies {}",
        c.alpha0,
        a.analysis
            .lower
            .lambda
            .map_or("none".to_string(), |l| format!("{l:.6}")),
        c.linkage
            .bodies()
            .iter()
            .map(|r| format!("blocks {}-{}", r.start, r.end.saturating_sub(1)))
            .collect::<Vec<_>>()
            .join(", ")
    );
    let m = &c.mass;
    let _ = writeln!(
        t,
        "Participating mass: M* = {:.1} kg, e* = {:.4} (of {:.1} N of seismic weight on the moving blocks)",
        m.m_star, m.e_star, m.seismic_weight
    );
    let _ = writeln!(
        t,
        "Capacity curve ({} points): control point = centroid of block {}, d_k0 = {:.2} mm, d0* = {:.2} mm",
        c.curve.len(),
        c.control_block,
        1e3 * c.d_k0,
        1e3 * c.d0_star
    );
    let _ = writeln!(
        t,
        "  a0* = alpha0 g/(e* FC) = {:.4} m/s^2 (FC = {}), du* = {:.2} mm, ds* = {:.2} mm, as* = {:.4} m/s^2, Ts = {:.3} s",
        c.a0_star,
        s.fc,
        1e3 * v.du_star,
        1e3 * v.ds_star,
        v.as_star,
        v.ts
    );
    let _ = writeln!(
        t,
        "Site: ag = {} g, soil {}, topography {}, F0 = {}, Tc* = {} s, q = {}{}",
        s.ag,
        s.soil.as_str(),
        s.topography.as_str(),
        s.f0,
        s.tc_star,
        s.q,
        if s.elevated() {
            format!(
                ", Z = {} m of H = {} m, T1 = {} s",
                s.z,
                s.h.unwrap_or(f64::NAN),
                s.t1.unwrap_or(f64::NAN)
            )
        } else {
            String::new()
        }
    );
    let _ = writeln!(
        t,
        "  spectrum: S = SS ST = {:.3} x {:.2}, TB = {:.3} s, TC = {:.3} s, TD = {:.3} s",
        sp.ss, sp.st, sp.tb, sp.tc, sp.td
    );
    let (lin, nonlin) = if s.elevated() {
        (
            "a0* >= max(ag S/q, Se(T1) psi gamma/q)",
            "du* >= max(SDe(Ts), amplified at Z)",
        )
    } else {
        ("a0* >= ag S/q", "du* >= SDe(Ts)")
    };
    let _ = writeln!(
        t,
        "Linear check ({lin}): {:.4} vs {:.4} m/s^2, ratio {:.3}: {}; largest passing ag = {}",
        v.linear.capacity,
        v.linear.demand,
        v.linear.ratio,
        verdict_word(&v.linear),
        ag_max(&v.linear)
    );
    let _ = writeln!(
        t,
        "Nonlinear check ({nonlin}): {:.2} vs {:.2} mm, ratio {:.3}: {}; largest passing ag = {}",
        1e3 * v.nonlinear.capacity,
        1e3 * v.nonlinear.demand,
        v.nonlinear.ratio,
        verdict_word(&v.nonlinear),
        ag_max(&v.nonlinear)
    );
    let _ = writeln!(
        t,
        "(The capacity curve keeps the hinges at their joints, as the code method does; past about a third of d_k0 a real arch may move a hinge: docs/assessment.md)"
    );
    let _ = writeln!(
        t,
        "Verdict: {}",
        if v.passes() {
            "the mechanism passes both checks"
        } else {
            "the mechanism does not pass"
        }
    );
    t
}
