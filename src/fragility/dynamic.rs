//! The dynamic route: a multiple-stripe analysis of the samples (Baker 2015). Each sample
//! (the scene with its uncertain values set) runs in the DEM
//! (`analysis::dem_dynamic`, docs/dem.md: rigid blocks, Coulomb contacts, the scene's `[dem]`
//! knobs) under each record, scaled so that its peak ground acceleration is each stripe's
//! PGA, and each run collapses or not (the DEM's criterion, `DynamicSettings`); a structure
//! that cannot stand under its permanent loads counts as collapsed at every stripe. At each
//! stripe the collapses of all samples and records are counted, and the lognormal is fitted
//! to the counts by maximum likelihood ([`super::fit`], `Observation::Counts`). So the
//! curve mixes the record-to-record variability with that of the inputs, as a multiple-stripe
//! analysis of a population of structures does.

use super::fit::{self, FitError, LognormalFit, Observation};
use super::{check, check_range, sample_scenes, values_of, Settings};
use crate::analysis;
use crate::dem::dynamic::DynamicSettings;
use crate::dem::record::{GroundInput, GroundMotion, STANDARD_GRAVITY};
use crate::error::AnalysisError;
use crate::scene::uncertain::{RankCorrelation, UncertainInput};
use crate::scene::Scene;
use rayon::prelude::*;

/// One sample's runs: at each stripe, the records under which it collapsed. Serialisable,
/// so that a chunk computed elsewhere ([`dynamic_samples`]) comes back to
/// [`dynamic_fragility`].
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct DynamicSample {
    pub values: Vec<f64>,
    /// `collapsed[j][r]`: whether it collapsed at stripe `j` under record `r`.
    pub collapsed: Vec<Vec<bool>>,
}

/// One stripe's count over every sample and record.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Stripe {
    /// Peak ground acceleration (g).
    pub pga: f64,
    pub runs: u64,
    pub collapses: u64,
}

/// The dynamic-route fragility of a scene.
#[derive(Debug, Clone)]
pub struct DynamicFragility {
    pub inputs: Vec<UncertainInput>,
    /// The rank correlations imposed between the inputs (empty: independent).
    pub correlation: Vec<RankCorrelation>,
    pub seed: u64,
    /// Where each record came from.
    pub records: Vec<String>,
    pub stripes: Vec<Stripe>,
    pub samples: Vec<DynamicSample>,
    pub fit: Result<LognormalFit, FitError>,
}

/// The `.AT2` records of `dir` (any case of the extension), in the order of their names.
pub fn read_records(dir: &std::path::Path) -> Result<Vec<GroundMotion>, AnalysisError> {
    let bad =
        |message: String| AnalysisError::Other(format!("--records {}: {message}", dir.display()));
    let entries = std::fs::read_dir(dir).map_err(|e| bad(e.to_string()))?;
    let mut paths: Vec<std::path::PathBuf> = entries
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| {
            p.extension()
                .and_then(|x| x.to_str())
                .is_some_and(|x| x.eq_ignore_ascii_case("at2"))
        })
        .collect();
    paths.sort();
    if paths.is_empty() {
        return Err(bad("no .AT2 record in the directory".into()));
    }
    paths
        .iter()
        .map(|p| {
            crate::dem::record::read(p, crate::dem::record::AccelUnit::G, None)
                .map_err(AnalysisError::Record)
        })
        .collect()
}

/// The most stripes a dynamic route takes.
pub const MAX_STRIPES: usize = 100;

/// The settings, records and stripes of a dynamic route, checked.
fn check_dynamic(
    scene: &Scene,
    settings: &Settings,
    records: &[GroundMotion],
    stripes: &[f64],
) -> Result<(), AnalysisError> {
    check(scene, settings)?;
    if records.is_empty() {
        return Err(AnalysisError::Settings {
            setting: "--records".into(),
            value: "no record".into(),
            allowed: "a directory with at least one .AT2 record".into(),
        });
    }
    if stripes.is_empty()
        || stripes.len() > MAX_STRIPES
        || stripes
            .iter()
            .any(|&s| !(s.is_finite() && s > 0.0 && s <= 10.0))
    {
        return Err(AnalysisError::Settings {
            setting: "--stripes".into(),
            value: format!("{stripes:?}"),
            allowed: format!("1 to {MAX_STRIPES} peak ground accelerations, each > 0 and <= 10 g"),
        });
    }
    if let Some(r) = records.iter().find(|r| r.pga().is_nan() || r.pga() <= 0.0) {
        return Err(AnalysisError::Other(format!(
            "{}: the record never moves (its PGA is 0), so it cannot be scaled to a stripe",
            r.source
        )));
    }
    Ok(())
}

/// The dynamic-route fragility of `scene` under `records` scaled to each PGA of `stripes`
/// (in g), with the DEM's `dynamic` settings (module docs).
pub fn dynamic_route(
    scene: &Scene,
    settings: &Settings,
    records: &[GroundMotion],
    stripes: &[f64],
    dynamic: &DynamicSettings,
) -> Result<DynamicFragility, AnalysisError> {
    dynamic_route_with_progress(scene, settings, records, stripes, dynamic, &|| {})
}

/// [`dynamic_route`], calling `progress` after each DEM run (from worker threads): the
/// CLI's progress bar over [`dynamic_run_count`] runs, which take hours in a large study.
pub fn dynamic_route_with_progress(
    scene: &Scene,
    settings: &Settings,
    records: &[GroundMotion],
    stripes: &[f64],
    dynamic: &DynamicSettings,
    progress: &(dyn Fn() + Sync),
) -> Result<DynamicFragility, AnalysisError> {
    let total = dynamic_run_count(scene, settings, records, stripes)?;
    let flags = runs_of(
        scene,
        settings,
        records,
        stripes,
        dynamic,
        0..total,
        progress,
    )?;
    let samples = dynamic_samples_from_runs(scene, settings, records, stripes, &flags)?;
    dynamic_fragility(scene, settings, records, stripes, samples)
}

/// The samples `range` (a chunk of `0..settings.samples`) of the dynamic route, each with
/// its runs: the same as those samples of [`dynamic_route`], so the chunks of a cluster,
/// concatenated in order, give [`dynamic_fragility`] the local answer.
pub fn dynamic_samples(
    scene: &Scene,
    settings: &Settings,
    records: &[GroundMotion],
    stripes: &[f64],
    dynamic: &DynamicSettings,
    range: std::ops::Range<usize>,
) -> Result<Vec<DynamicSample>, AnalysisError> {
    check_dynamic(scene, settings, records, stripes)?;
    check_range(&range, settings.samples)?;
    let per_sample = stripes.len() * records.len();
    let runs = range.start * per_sample..range.end * per_sample;
    let flags = dynamic_runs(scene, settings, records, stripes, dynamic, runs)?;
    let values = values_of(scene, settings);
    Ok(samples_of(
        &values[range],
        &flags,
        stripes.len(),
        records.len(),
    ))
}

/// The number of DEM runs of a dynamic route, after its checks: one per sample, stripe and
/// record. Run `k` is sample `k / (stripes records)`, stripe `(k / records) % stripes`,
/// record `k % records` (the order of [`dynamic_runs`]).
pub fn dynamic_run_count(
    scene: &Scene,
    settings: &Settings,
    records: &[GroundMotion],
    stripes: &[f64],
) -> Result<usize, AnalysisError> {
    check_dynamic(scene, settings, records, stripes)?;
    Ok(settings.samples * stripes.len() * records.len())
}

/// The runs `range` (a chunk of `0..`[`dynamic_run_count`], numbered as there) of the
/// dynamic route: whether the structure collapsed (or could not stand) in each. The unit a
/// cluster's worker computes: a sample's runs cost seconds each, so a chunk of whole samples
/// (tens of runs) would leave workers idle at the end of a study (50 samples over 16
/// workers: four rounds, the last a third full). [`dynamic_samples_from_runs`] makes the
/// samples of all of them.
pub fn dynamic_runs(
    scene: &Scene,
    settings: &Settings,
    records: &[GroundMotion],
    stripes: &[f64],
    dynamic: &DynamicSettings,
    range: std::ops::Range<usize>,
) -> Result<Vec<bool>, AnalysisError> {
    runs_of(scene, settings, records, stripes, dynamic, range, &|| {})
}

/// [`dynamic_runs`], calling `progress` after each run.
fn runs_of(
    scene: &Scene,
    settings: &Settings,
    records: &[GroundMotion],
    stripes: &[f64],
    dynamic: &DynamicSettings,
    range: std::ops::Range<usize>,
    progress: &(dyn Fn() + Sync),
) -> Result<Vec<bool>, AnalysisError> {
    let total = dynamic_run_count(scene, settings, records, stripes)?;
    let (nj, nr) = (stripes.len(), records.len());
    if range.start >= range.end || range.end > total {
        return Err(AnalysisError::Settings {
            setting: "run range".into(),
            value: format!("{}..{}", range.start, range.end),
            allowed: format!(
                "a non-empty range within 0..{total} ({} samples x {nj} stripes x {nr} records)",
                settings.samples
            ),
        });
    }
    // The scenes of the samples the runs touch, and only those.
    let first = range.start / (nj * nr);
    let last = (range.end - 1) / (nj * nr);
    let values = values_of(scene, settings);
    let scenes = sample_scenes(scene, &values[first..=last], first)?;
    let dynamic = DynamicSettings {
        history_every: None,
        frames_every: None,
        ..dynamic.clone()
    };
    let where_ = |k: usize| (k / (nj * nr), (k / nr) % nj, k % nr);
    let runs: Vec<Result<bool, AnalysisError>> = range
        .clone()
        .into_par_iter()
        .map(|k| {
            let (i, j, r) = where_(k);
            let record = &records[r];
            let scale = stripes[j] * STANDARD_GRAVITY / record.pga();
            let ground: GroundInput =
                crate::dem::record::Excitation::Record(record.scaled(scale)).into();
            let run = analysis::dem_dynamic(&scenes[i - first], &ground, &dynamic);
            progress();
            let run = run?;
            Ok(run.result.collapsed || run.result.cannot_stand)
        })
        .collect();
    let mut flags = Vec::with_capacity(runs.len());
    for (k, run) in range.zip(runs) {
        match run {
            Ok(c) => flags.push(c),
            Err(e) => {
                let (i, j, r) = where_(k);
                return Err(AnalysisError::Other(format!(
                    "sample {i} under {} at PGA {} g: {e}",
                    records[r].source, stripes[j]
                )));
            }
        }
    }
    Ok(flags)
}

/// All samples of the dynamic route from the outcomes of all its runs (those of
/// [`dynamic_runs`] over `0..`[`dynamic_run_count`], in order, as a cluster's chunks
/// joined): the samples [`dynamic_samples`] gives, for [`dynamic_fragility`].
pub fn dynamic_samples_from_runs(
    scene: &Scene,
    settings: &Settings,
    records: &[GroundMotion],
    stripes: &[f64],
    flags: &[bool],
) -> Result<Vec<DynamicSample>, AnalysisError> {
    let total = dynamic_run_count(scene, settings, records, stripes)?;
    let (nj, nr) = (stripes.len(), records.len());
    if flags.len() != total {
        return Err(AnalysisError::Other(format!(
            "{}: {} run outcomes given for a fragility of {total} runs ({} samples x {nj} stripes x {nr} records)",
            scene.origin,
            flags.len(),
            settings.samples
        )));
    }
    let values = values_of(scene, settings);
    Ok(samples_of(&values, flags, nj, nr))
}

/// The samples with these `values`, their runs' outcomes `flags` in the order of
/// [`dynamic_runs`] (starting at the first of them).
fn samples_of(values: &[Vec<f64>], flags: &[bool], nj: usize, nr: usize) -> Vec<DynamicSample> {
    values
        .iter()
        .enumerate()
        .map(|(i, v)| DynamicSample {
            values: v.clone(),
            collapsed: (0..nj)
                .map(|j| (0..nr).map(|r| flags[(i * nj + j) * nr + r]).collect())
                .collect(),
        })
        .collect()
}

/// The dynamic-route fragility from all `settings.samples` samples of [`dynamic_samples`],
/// in order: the counts at each stripe and the lognormal fitted to them.
pub fn dynamic_fragility(
    scene: &Scene,
    settings: &Settings,
    records: &[GroundMotion],
    stripes: &[f64],
    samples: Vec<DynamicSample>,
) -> Result<DynamicFragility, AnalysisError> {
    check_dynamic(scene, settings, records, stripes)?;
    let (nj, nr) = (stripes.len(), records.len());
    if samples.len() != settings.samples
        || samples
            .iter()
            .any(|s| s.collapsed.len() != nj || s.collapsed.iter().any(|c| c.len() != nr))
    {
        return Err(AnalysisError::Other(format!(
            "{}: the samples given do not match a fragility of {} samples, {nj} stripes and {nr} records",
            scene.origin, settings.samples
        )));
    }
    let ns = samples.len();
    let stripes: Vec<Stripe> = stripes
        .iter()
        .enumerate()
        .map(|(j, &pga)| Stripe {
            pga,
            runs: (ns * nr) as u64,
            collapses: samples
                .iter()
                .map(|s| s.collapsed[j].iter().filter(|&&c| c).count() as u64)
                .sum(),
        })
        .collect();
    let observations: Vec<Observation> = stripes
        .iter()
        .map(|s| Observation::Counts {
            at: s.pga,
            runs: s.runs,
            collapses: s.collapses,
        })
        .collect();
    Ok(DynamicFragility {
        inputs: scene.uncertain.clone(),
        correlation: scene.uncertain_correlation.clone(),
        seed: settings.seed,
        records: records.iter().map(|r| r.source.clone()).collect(),
        stripes,
        samples,
        fit: fit::fit(&observations, settings.confidence),
    })
}
