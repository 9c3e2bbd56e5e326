//! The analyses a hand-in report needs (`voussoir report`, docs/report.md): the analysis of
//! the scene by both bounds (and the DEM's bracket when asked), the minimum thickness and
//! the geometric safety factor, the seismic assessment of both directions when the scene has
//! a `[site]`, and the sensitivity of the governing multiplier to the thickness and the
//! friction coefficient (each -10 % and +10 %).
//!
//! Nothing here is new policy: each number comes from the function the single-purpose
//! command calls ([`analysis::analyse`] for `analyze` and `analyze --dem`,
//! [`thickness::analyse`] for `min-thickness`, [`analysis::assess_directions`] for
//! `assess`), with the same default options, so the report's numbers are those commands'.
//! What cannot be computed for a scene (a minimum thickness of the user's own blocks, an
//! assessment of a structure that cannot stand) is kept as the refusal's words, which the
//! report prints where the number would be.

use crate::analysis::{self, AssessOptions, Assessment, Options, SceneAnalysis};
use crate::error::AnalysisError;
use crate::outcome::Status;
use crate::scene::Scene;
use crate::thickness::{self, ThicknessAnalysis};
use rayon::prelude::*;
use std::time::Instant;

/// The factors of the sensitivity table: -10 % and +10 % of the scene's value.
pub const SENSITIVITY_FACTORS: [f64; 2] = [0.9, 1.1];

/// What the report runs besides the default analyses.
#[derive(Debug, Clone, Copy, Default)]
pub struct DossierOptions {
    /// Also run the DEM's bracket of the collapse multiplier (`analyze --dem`).
    pub dem: bool,
}

/// One varied analysis of the sensitivity table.
#[derive(Debug, Clone)]
pub struct Sensitivity {
    /// The scene key varied (`arch.thickness`, `material.friction`).
    pub key: &'static str,
    /// The scene's own value of the key.
    pub base: f64,
    /// The factor applied to it ([`SENSITIVITY_FACTORS`]).
    pub factor: f64,
    /// The analysis at `base * factor`, or why there is none (a thickness the shape does not
    /// admit, say).
    pub result: Result<Varied, String>,
}

impl Sensitivity {
    /// The varied value, `base * factor`.
    pub fn value(&self) -> f64 {
        self.base * self.factor
    }
}

/// What the sensitivity table keeps of a varied analysis.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Varied {
    pub status: Status,
    pub lambda_lower: Option<f64>,
    pub lambda_upper: Option<f64>,
    /// The governing multiplier ([`SceneAnalysis::lambda_governing`]).
    pub lambda_governing: Option<f64>,
}

/// Everything the report prints, computed.
#[derive(Debug)]
pub struct Dossier {
    pub analysis: SceneAnalysis,
    /// The minimum thickness (`min-thickness`), or why there is none.
    pub thickness: Result<ThicknessAnalysis, String>,
    /// The seismic assessment (`assess`, both directions) when the scene has a `[site]`, or
    /// why it could not be made.
    pub assessment: Option<Result<Assessment, String>>,
    /// The sensitivity table, key by key, factor by factor; empty rows are left out (no
    /// thickness on the user's blocks, no friction limit with `friction = inf`).
    pub sensitivity: Vec<Sensitivity>,
    /// Why a key of the sensitivity table was not varied, `(key, words)`.
    pub sensitivity_skipped: Vec<(&'static str, String)>,
    /// Wall time of all the analyses (s).
    pub wall_time_s: f64,
}

/// The keys the sensitivity table varies and the scene's value of each, or why a key is not
/// varied.
fn sensitivity_keys(scene: &Scene) -> Vec<(&'static str, Result<f64, String>)> {
    let thickness = match &scene.arch {
        Some(a) => Ok(a.thickness),
        None => Err("the structure is the user's own blocks, with no thickness to vary".into()),
    };
    let mu = scene.material.friction;
    let friction = if mu.is_finite() {
        Ok(mu)
    } else {
        Err("friction = inf: the joints do not slide, so there is no coefficient to vary".into())
    };
    vec![
        ("arch.thickness", thickness),
        ("material.friction", friction),
    ]
}

/// Run every analysis of the report on `scene`.
pub fn run(scene: &Scene, options: &DossierOptions) -> Result<Dossier, AnalysisError> {
    let start = Instant::now();
    let direction = analysis::direction_for(scene, None)?;
    let base = Options {
        static_settings: crate::statics::StaticSettings::default().direction(direction),
        ..Options::default()
    };
    let with_dem = Options {
        dem: options.dem,
        ..base.clone()
    };
    // The main analysis fails the report (as it fails `analyze`); the others are parts of
    // it and say why they are missing.
    let analysis = analysis::analyse(scene, &with_dem)?;
    let mut sensitivity_skipped = Vec::new();
    let mut cases = Vec::new();
    for (key, value) in sensitivity_keys(scene) {
        match value {
            Ok(base) => cases.extend(SENSITIVITY_FACTORS.iter().map(|&f| (key, base, f))),
            Err(why) => sensitivity_skipped.push((key, why)),
        }
    }
    let ((thickness, assessment), sensitivity) = rayon::join(
        || {
            rayon::join(
                || thickness::analyse(scene, &base).map_err(|e| e.to_string()),
                || {
                    scene.site.as_ref().map(|_| {
                        analysis::assess_directions(
                            scene,
                            &Options::default(),
                            &AssessOptions::default(),
                            None,
                        )
                        .map_err(|e| e.to_string())
                    })
                },
            )
        },
        || {
            cases
                .par_iter()
                .map(|&(key, base_value, factor)| Sensitivity {
                    key,
                    base: base_value,
                    factor,
                    result: varied(scene, &base, key, base_value * factor),
                })
                .collect::<Vec<_>>()
        },
    );
    Ok(Dossier {
        analysis,
        thickness,
        assessment,
        sensitivity,
        sensitivity_skipped,
        wall_time_s: start.elapsed().as_secs_f64(),
    })
}

/// The scene with `key` set to `value`, analysed as `analyze` does.
fn varied(scene: &Scene, options: &Options, key: &str, value: f64) -> Result<Varied, String> {
    let s = scene
        .with_value(key, toml::Value::Float(value))
        .map_err(|e| e.to_string())?;
    let a = analysis::analyse(&s, options).map_err(|e| e.to_string())?;
    Ok(Varied {
        status: a.lower.status,
        lambda_lower: a.lower.lambda,
        lambda_upper: a.lambda_upper(),
        lambda_governing: a.lambda_governing(),
    })
}
