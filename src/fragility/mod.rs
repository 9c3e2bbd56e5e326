//! Fragility curves of a structure with uncertain inputs (`voussoir fragility`,
//! docs/fragility.md).
//!
//! The scene's `[uncertain]` inputs ([`crate::scene::uncertain`]) are sampled by Latin
//! hypercube from a seed ([`crate::sampling`]); each sample is the scene with those values
//! set, validated as `--set` validates them. A sample the scene refuses (a thickness below
//! 0 or above the shape's largest, a friction below 0, ...) is **refused**, not truncated:
//! the run stops with an error naming the sample, the key and the value, before any analysis,
//! because truncating at a range the scene's validation knows (and which may depend on other
//! values) would pile probability onto its ends unseen.
//!
//! **The capacity route.** Each sample is assessed at the site (`analysis::assess_directions`:
//! both directions, NTC 2018 / Circolare 2019 C8.7.1, docs/assessment.md), and its capacity
//! is the largest `ag` its **nonlinear kinematic check** passes in the worse direction
//! (`Check::ag_max`, a grid of 0.005 g then bisection to round-off): the `ag` at which it
//! fails. The site's other parameters are held (`Site::with_ag`: soil, topography, `F0`,
//! `Tc*`, `q`, `FC`, `Z`, `H`, `T1` as given, or for a site given by its coordinates, the
//! `F0` and `Tc*` of its return period), while `S` and `TD` follow `ag` by their formulas.
//! The fragility is the distribution of the capacities, `P(fail | ag = a) = P(C < a)`,
//! fitted by a lognormal ([`fit`]); a sample that passes even at 2 g is a capacity above
//! 2 g (censored in the fit), one that fails at any `ag` (its capacity is not positive), or
//! that cannot stand under its permanent loads at all, a capacity below 0.005 g. A sample that cannot be assessed
//! (joints slide at collapse, no rotational mechanism) has no capacity in this model: it is
//! listed with its reason and left out of the fit, and the result says how many.

pub mod dynamic;

pub mod fit;

use crate::analysis::{self, AssessOptions, Options};
use crate::assess::{AG_GRID_FIRST, AG_SEARCH_MAX};
use crate::error::AnalysisError;
use crate::outcome::Direction;
use crate::sampling::{impose_rank_correlation, latin_hypercube};
use crate::scene::uncertain::{correlation_matrix, RankCorrelation, UncertainInput};
use crate::scene::Scene;
use rayon::prelude::*;
use toml::Value;

pub use dynamic::{
    dynamic_fragility, dynamic_route, dynamic_route_with_progress, dynamic_run_count, dynamic_runs,
    dynamic_samples, dynamic_samples_from_runs, read_records, DynamicFragility, DynamicSample,
    Stripe,
};
pub use fit::{FitError, LognormalFit, Observation};

/// Settings of a fragility analysis.
#[derive(Debug, Clone)]
pub struct Settings {
    /// Samples (>= 1).
    pub samples: usize,
    /// Seed of the Latin hypercube.
    pub seed: u64,
    /// The confidence level of the fit's bounds (0.95).
    pub confidence: f64,
    /// How each sample is analysed and assessed.
    pub options: Options,
    pub assess: AssessOptions,
}

impl Default for Settings {
    fn default() -> Self {
        Settings {
            samples: 100,
            seed: 1,
            confidence: fit::CONFIDENCE,
            options: Options::default(),
            assess: AssessOptions::default(),
        }
    }
}

/// The most samples a fragility analysis takes.
pub const MAX_SAMPLES: usize = 1_000_000;

/// What one sample's assessment gave.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub enum Capacity {
    /// It fails above this `ag` (g), in this direction.
    At { ag: f64, direction: Direction },
    /// It passes even at [`AG_SEARCH_MAX`].
    Above,
    /// It fails at any `ag` (or cannot stand): a capacity below this `ag`, the search's
    /// first grid point.
    Below(f64),
    /// It could not be assessed (why).
    NotAssessed(String),
}

impl Capacity {
    /// The observation of the fit it is, if any.
    pub fn observation(&self) -> Option<Observation> {
        match *self {
            Capacity::At { ag, .. } => Some(Observation::Exact(ag)),
            Capacity::Above => Some(Observation::Above(AG_SEARCH_MAX)),
            Capacity::Below(ag) => Some(Observation::Below(ag)),
            Capacity::NotAssessed(_) => None,
        }
    }

    /// The capacity in g, where one was found.
    pub fn ag(&self) -> Option<f64> {
        match self {
            Capacity::At { ag, .. } => Some(*ag),
            _ => None,
        }
    }
}

/// One sample: its input values (in the order of the scene's `[uncertain]`) and capacity.
/// Serialisable, so that a chunk of samples computed elsewhere ([`capacity_samples`], Python's
/// `fragility(..., client=)`) comes back to [`capacity_fragility`].
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Sample {
    pub values: Vec<f64>,
    pub capacity: Capacity,
}

/// The capacity-route fragility of a scene.
#[derive(Debug, Clone)]
pub struct CapacityFragility {
    pub inputs: Vec<UncertainInput>,
    /// The rank correlations imposed between the inputs (empty: independent).
    pub correlation: Vec<RankCorrelation>,
    pub seed: u64,
    pub samples: Vec<Sample>,
    /// The site (its `ag` is the scene's; the capacities search `ag`).
    pub site: crate::spectrum::Site,
    /// The lognormal fit of the capacities (an error when none can be made).
    pub fit: Result<LognormalFit, FitError>,
}

impl CapacityFragility {
    /// Samples that could not be assessed.
    pub fn not_assessed(&self) -> usize {
        self.samples
            .iter()
            .filter(|s| matches!(s.capacity, Capacity::NotAssessed(_)))
            .count()
    }

    /// The empirical fragility: each found capacity (sorted) with the share of the assessed
    /// samples whose capacity is at most it, `i / n` (the censored ones counted in `n`).
    pub fn empirical(&self) -> Vec<(f64, f64)> {
        let assessed = self.samples.len() - self.not_assessed();
        let below = self
            .samples
            .iter()
            .filter(|s| matches!(s.capacity, Capacity::Below(_)))
            .count();
        let mut ags: Vec<f64> = self
            .samples
            .iter()
            .filter_map(|s| s.capacity.ag())
            .collect();
        ags.sort_by(f64::total_cmp);
        ags.iter()
            .enumerate()
            .map(|(i, &a)| (a, (below + i + 1) as f64 / assessed as f64))
            .collect()
    }
}

/// The Latin hypercube values of `n` samples of `inputs` from `seed`: `values[i][k]` is
/// input `k` of sample `i` (`sampling::latin_hypercube` through each input's quantile), with
/// the rank correlations `correlation` imposed by reordering (none: independent inputs, the
/// samples exactly as without the key).
pub fn sample_values(
    inputs: &[UncertainInput],
    correlation: &[RankCorrelation],
    n: usize,
    seed: u64,
) -> Vec<Vec<f64>> {
    let mut u = latin_hypercube(inputs.len(), n, seed);
    if !correlation.is_empty() {
        impose_rank_correlation(&mut u, &correlation_matrix(inputs, correlation));
    }
    u.into_iter()
        .map(|u| {
            u.iter()
                .zip(inputs)
                .map(|(&u, input)| input.dist.quantile(u))
                .collect()
        })
        .collect()
}

/// The values of every sample of `scene`'s `[uncertain]` inputs under `settings` (its
/// samples and seed): [`sample_values`] of the scene's inputs and correlations.
fn values_of(scene: &Scene, settings: &Settings) -> Vec<Vec<f64>> {
    sample_values(
        &scene.uncertain,
        &scene.uncertain_correlation,
        settings.samples,
        settings.seed,
    )
}

/// Every sample's scene of `scene` under `settings` built and checked, nothing run: what a
/// cluster's client checks before it sends out work that would meet a refused sample hours
/// later (samples are refused, never truncated: module docs).
pub fn check_samples(scene: &Scene, settings: &Settings) -> Result<(), AnalysisError> {
    check(scene, settings)?;
    sample_scenes(scene, &values_of(scene, settings), 0).map(|_| ())
}

/// The scenes of the samples, each validated; the first sample the scene refuses is an
/// error naming it, its values and the scene's reason (samples are refused, never truncated:
/// module docs).
/// `first` is the number of the first of them (a chunk of the samples starts anywhere).
fn sample_scenes(
    scene: &Scene,
    values: &[Vec<f64>],
    first: usize,
) -> Result<Vec<Scene>, AnalysisError> {
    let inputs = &scene.uncertain;
    // Each key first, at its distribution's centre: a key the scene does not have is the
    // table's error, not a sample's.
    for input in inputs {
        let centre = input.dist.quantile(0.5);
        scene
            .with_values(&[(input.key.as_str(), Value::Float(centre))])
            .map_err(|e| {
                AnalysisError::Other(format!(
                    "{}: [uncertain] \"{}\" = {} (at its median {centre}): {e}",
                    scene.origin,
                    input.key,
                    input.dist.name()
                ))
            })?;
    }
    values
        .par_iter()
        .enumerate()
        .map(|(i, v)| {
            sample_scene(scene, v).map_err(|e| refused(scene, first + i, v, &e.to_string()))
        })
        .collect()
}

/// The scene of one sample.
fn sample_scene(scene: &Scene, values: &[f64]) -> Result<Scene, crate::error::SceneError> {
    let pairs: Vec<(&str, Value)> = scene
        .uncertain
        .iter()
        .zip(values)
        .map(|(input, &x)| (input.key.as_str(), Value::Float(x)))
        .collect();
    scene.with_values(&pairs)
}

/// The error of a sample the scene refuses.
fn refused(scene: &Scene, i: usize, values: &[f64], why: &str) -> AnalysisError {
    let set: Vec<String> = scene
        .uncertain
        .iter()
        .zip(values)
        .map(|(input, x)| format!("{} = {x}", input.key))
        .collect();
    AnalysisError::Other(format!(
        "{}: sample {i} ({}) is outside what the scene accepts: {why}. Samples are refused, not truncated (docs/fragility.md): narrow the distribution, or use a uniform or lognormal one inside the key's range",
        scene.origin,
        set.join(", ")
    ))
}

/// Check the settings and the scene (a `[site]`, a seismic action).
fn check(scene: &Scene, settings: &Settings) -> Result<(), AnalysisError> {
    settings.options.validate()?;
    analysis::seismic_only(scene, "a fragility analysis")?;
    if settings.samples == 0 || settings.samples > MAX_SAMPLES {
        return Err(AnalysisError::Settings {
            setting: "--samples".into(),
            value: settings.samples.to_string(),
            allowed: format!("from 1 to {MAX_SAMPLES}"),
        });
    }
    if !(settings.confidence > 0.0 && settings.confidence < 1.0) {
        return Err(AnalysisError::Settings {
            setting: "confidence".into(),
            value: settings.confidence.to_string(),
            allowed: "a level between 0 and 1 (0.95)".into(),
        });
    }
    Ok(())
}

/// The capacity-route fragility of `scene` at its `[site]` (module docs).
pub fn capacity_route(
    scene: &Scene,
    settings: &Settings,
) -> Result<CapacityFragility, AnalysisError> {
    let samples = capacity_samples(scene, settings, 0..settings.samples)?;
    capacity_fragility(scene, settings, samples)
}

/// The site the capacity route searches, or the error that says it is missing.
fn site_of(scene: &Scene) -> Result<crate::spectrum::Site, AnalysisError> {
    scene.site.clone().ok_or_else(|| {
        AnalysisError::Other(format!(
            "{}: no [site] table: the capacity route searches the site's ag with its other parameters held; give one in the scene or with --site ag=0.25 --site soil=B --site F0=2.4 --site Tc_star=0.3 (docs/fragility.md)",
            scene.origin
        ))
    })
}

/// The samples `range` (a chunk of `0..settings.samples`) of the capacity route, each with
/// its capacity: the same values and capacities as those samples of [`capacity_route`], so
/// the chunks of a cluster, concatenated in order, give [`capacity_fragility`] the local
/// answer.
pub fn capacity_samples(
    scene: &Scene,
    settings: &Settings,
    range: std::ops::Range<usize>,
) -> Result<Vec<Sample>, AnalysisError> {
    check(scene, settings)?;
    site_of(scene)?;
    check_range(&range, settings.samples)?;
    let mut values = values_of(scene, settings);
    let values: Vec<Vec<f64>> = values.drain(range.clone()).collect();
    let scenes = sample_scenes(scene, &values, range.start)?;
    let capacities: Vec<Result<Capacity, AnalysisError>> = scenes
        .par_iter()
        .map(|s| capacity_of(s, settings))
        .collect();
    let mut samples = Vec::with_capacity(values.len());
    for (i, (v, c)) in values.into_iter().zip(capacities).enumerate() {
        // A sample the scene's build refuses (a load outside every block, a thickness the
        // shape cannot take) is outside the keys' range like one the reader refuses.
        let capacity = match c {
            Ok(c) => c,
            Err(AnalysisError::Scene(e)) => {
                return Err(refused(scene, range.start + i, &v, &e.to_string()))
            }
            Err(e) => return Err(e),
        };
        samples.push(Sample {
            values: v,
            capacity,
        });
    }
    Ok(samples)
}

/// The capacity-route fragility from all `settings.samples` samples of
/// [`capacity_samples`], in order: the lognormal fitted to their capacities.
pub fn capacity_fragility(
    scene: &Scene,
    settings: &Settings,
    samples: Vec<Sample>,
) -> Result<CapacityFragility, AnalysisError> {
    check(scene, settings)?;
    let site = site_of(scene)?;
    if samples.len() != settings.samples {
        return Err(AnalysisError::Other(format!(
            "{}: {} samples given for a fragility of {}",
            scene.origin,
            samples.len(),
            settings.samples
        )));
    }
    let observations: Vec<Observation> = samples
        .iter()
        .filter_map(|s| s.capacity.observation())
        .collect();
    let fit = fit::fit(&observations, settings.confidence);
    Ok(CapacityFragility {
        inputs: scene.uncertain.clone(),
        correlation: scene.uncertain_correlation.clone(),
        seed: settings.seed,
        samples,
        site,
        fit,
    })
}

/// A chunk's range must lie in `0..samples` and hold at least one sample.
fn check_range(range: &std::ops::Range<usize>, samples: usize) -> Result<(), AnalysisError> {
    if range.start >= range.end || range.end > samples {
        return Err(AnalysisError::Settings {
            setting: "sample range".into(),
            value: format!("{}..{}", range.start, range.end),
            allowed: format!("a non-empty range within 0..{samples}"),
        });
    }
    Ok(())
}

/// One sample's capacity: the least over the directions of the largest `ag` its nonlinear
/// check passes. Errors of the scene propagate (the caller refuses the sample); an
/// assessment that finds no capacity curve is [`Capacity::NotAssessed`].
fn capacity_of(scene: &Scene, settings: &Settings) -> Result<Capacity, AnalysisError> {
    let a = match analysis::assess_directions(scene, &settings.options, &settings.assess, None) {
        Ok(a) => a,
        Err(AnalysisError::Scene(e)) => return Err(AnalysisError::Scene(e)),
        Err(e) => {
            // A structure that cannot stand under its permanent loads fails at every ag: its
            // capacity is below any (left out, it would move the curve to the right). Asked
            // only of the samples that failed, so the others pay nothing for it.
            let stands = analysis::analyse(scene, &settings.options)
                .map(|a| a.lower.status != crate::outcome::Status::CannotStand)
                .unwrap_or(true);
            return Ok(if stands {
                Capacity::NotAssessed(e.to_string())
            } else {
                Capacity::Below(AG_GRID_FIRST)
            });
        }
    };
    let mut worst: Option<Capacity> = None;
    for d in &a.directions {
        let v = &d.verdict;
        let c = match v.nonlinear.ag_max {
            Some(ag) if ag > 0.0 => Capacity::At {
                ag,
                direction: d.capacity.direction,
            },
            // It fails at any ag (its capacity is not positive): below every ag, censored.
            Some(_) => Capacity::Below(AG_GRID_FIRST),
            // It passes at the largest ag searched (`largest_passing_ag`).
            None => Capacity::Above,
        };
        let rank = |c: &Capacity| match c {
            Capacity::Below(_) => 0.0,
            Capacity::At { ag, .. } => *ag,
            _ => f64::INFINITY,
        };
        worst = Some(match worst {
            Some(w) if rank(&w) <= rank(&c) => w,
            _ => c,
        });
    }
    Ok(worst.unwrap_or_else(|| Capacity::NotAssessed("no direction assessed".into())))
}
