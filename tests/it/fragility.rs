//! `voussoir fragility` (issue 30, docs/fragility.md): the maximum-likelihood fit against a
//! direct numerical maximisation written here, the recovery of a known lognormal within the
//! fit's bounds, the Latin hypercube's strata, reproducibility from a seed, the step of a
//! structure whose inputs are certain, and the refusal of samples outside a key's range.

use crate::common::{data, scene_file, voussoir};
use voussoir::analysis::{self, AssessOptions, Options};
use voussoir::fragility::{self, fit, Capacity, Observation, Settings};
use voussoir::sampling::{latin_hypercube, Stream};
use voussoir::scene::Scene;

/// `Phi(x)`, written here from erfc (not the library's).
fn phi(x: f64) -> f64 {
    0.5 * libm::erfc(-x / std::f64::consts::SQRT_2)
}

/// The binomial log-likelihood of stripes `(x, n, z)` (Baker 2015 eq. 11 without its
/// constant), written here.
fn log_likelihood(stripes: &[(f64, u64, u64)], mu: f64, beta: f64) -> f64 {
    stripes
        .iter()
        .map(|&(x, n, z)| {
            let p = phi((x.ln() - mu) / beta);
            z as f64 * p.ln() + (n - z) as f64 * (1.0 - p).ln()
        })
        .sum()
}

/// The maximum of a unimodal `f` on `[a, b]` by golden-section search, to round-off.
fn golden(f: impl Fn(f64) -> f64, mut a: f64, mut b: f64) -> f64 {
    let r = (5f64.sqrt() - 1.0) / 2.0;
    let mut c = b - r * (b - a);
    let mut d = a + r * (b - a);
    let (mut fc, mut fd) = (f(c), f(d));
    for _ in 0..200 {
        if fc > fd {
            b = d;
            d = c;
            fd = fc;
            c = b - r * (b - a);
            fc = f(c);
        } else {
            a = c;
            c = d;
            fc = fd;
            d = a + r * (b - a);
            fd = f(d);
        }
        if (b - a).abs() < 1e-15 * (1.0 + a.abs()) {
            break;
        }
    }
    0.5 * (a + b)
}

/// Synthetic multiple-stripe counts: at each stripe `runs` records, each collapsing with the
/// probability of the lognormal `(median, beta)`, drawn from a seeded stream.
fn synthetic(median: f64, beta: f64, runs: u64, seed: u64) -> Vec<(f64, u64, u64)> {
    let mut stream = Stream::new(seed);
    [0.05, 0.1, 0.15, 0.2, 0.3, 0.4, 0.5, 0.7, 0.9, 1.2]
        .iter()
        .map(|&x| {
            let p = phi((x / median).ln() / beta);
            let z = (0..runs).filter(|_| stream.uniform() < p).count() as u64;
            (x, runs, z)
        })
        .collect()
}

fn observations(stripes: &[(f64, u64, u64)]) -> Vec<Observation> {
    stripes
        .iter()
        .map(|&(at, runs, collapses)| Observation::Counts {
            at,
            runs,
            collapses,
        })
        .collect()
}

#[test]
fn the_likelihood_fit_equals_a_direct_maximisation_and_recovers_the_lognormal() {
    let (median, beta) = (0.35, 0.45);
    for (seed, runs) in [(1, 40), (2, 100), (3, 400)] {
        let stripes = synthetic(median, beta, runs, seed);
        let f = fit::fit(&observations(&stripes), 0.95).expect("fit");
        // Direct maximisation: for each beta the best mu by golden section, then the best
        // beta of those.
        let best_mu = |b: f64| golden(|m| log_likelihood(&stripes, m, b), -5.0, 2.0);
        let b = golden(|b| log_likelihood(&stripes, best_mu(b), b), 0.02, 3.0);
        let m = best_mu(b);
        assert!(
            (f.median.ln() - m).abs() < 1e-6 && (f.beta - b).abs() < 1e-6,
            "seed {seed}: fit ({}, {}) against direct ({}, {b})",
            f.median,
            f.beta,
            m.exp()
        );
        assert!(f.median_bounds[0] < f.median && f.median < f.median_bounds[1]);
        assert!(f.beta_bounds[0] < f.beta && f.beta < f.beta_bounds[1]);
    }
    // The bounds recover the lognormal as often as their level says: over 400 data sets of
    // 10 stripes x 100 records, the 95 % bounds hold the true median and beta in 95 % of
    // them (a binomial count of 400 at 0.95 lies within 361..394 with probability
    // 0.9999). One data set's bounds miss the truth one time in twenty by design, so the
    // frequency, not one set, is what tests them.
    let (mut median_in, mut beta_in) = (0, 0);
    let sets = 400;
    for seed in 0..sets {
        let f = fit::fit(
            &observations(&synthetic(median, beta, 100, 1000 + seed)),
            0.95,
        )
        .expect("fit");
        median_in += usize::from(f.median_bounds[0] <= median && median <= f.median_bounds[1]);
        beta_in += usize::from(f.beta_bounds[0] <= beta && beta <= f.beta_bounds[1]);
    }
    assert!(
        (361..=394).contains(&median_in),
        "median covered {median_in} / {sets}"
    );
    assert!(
        (361..=394).contains(&beta_in),
        "beta covered {beta_in} / {sets}"
    );
    let wide = fit::fit(&observations(&synthetic(median, beta, 40, 1)), 0.95).expect("fit");
    let narrow = fit::fit(&observations(&synthetic(median, beta, 400, 3)), 0.95).expect("fit");
    assert!(
        narrow.beta_bounds[1] - narrow.beta_bounds[0] < wide.beta_bounds[1] - wide.beta_bounds[0]
    );
}

#[test]
fn censored_capacities_fit_the_censored_likelihood() {
    // Capacities of a known lognormal, those above 0.5 known only to lie above it.
    let (median, beta) = (0.3, 0.5);
    let mut obs = Vec::new();
    let mut exact = Vec::new();
    for u in latin_hypercube(1, 400, 5) {
        let x = median * (beta * voussoir::sampling::normal_quantile(u[0])).exp();
        if x > 0.5 {
            obs.push(Observation::Above(0.5));
        } else {
            obs.push(Observation::Exact(x));
            exact.push(x);
        }
    }
    let f = fit::fit(&obs, 0.95).expect("fit");
    let above = (obs.len() - exact.len()) as f64;
    let ll = |m: f64, b: f64| {
        exact
            .iter()
            .map(|x| -b.ln() - 0.5 * ((x.ln() - m) / b).powi(2))
            .sum::<f64>()
            + above * phi(-(0.5f64.ln() - m) / b).ln()
    };
    let best_mu = |b: f64| golden(|m| ll(m, b), -5.0, 2.0);
    let b = golden(|b| ll(best_mu(b), b), 0.02, 3.0);
    assert!((f.median.ln() - best_mu(b)).abs() < 1e-6 && (f.beta - b).abs() < 1e-6);
    assert!(f.median_bounds[0] <= median && median <= f.median_bounds[1]);
    assert!(f.beta_bounds[0] <= beta && beta <= f.beta_bounds[1]);
}

#[test]
fn every_stratum_of_every_variable_is_hit_exactly_once() {
    for (vars, n, seed) in [(1, 1, 0), (3, 10, 7), (5, 1000, 42)] {
        let u = latin_hypercube(vars, n, seed);
        assert_eq!(u.len(), n);
        for v in 0..vars {
            let mut strata: Vec<usize> = u.iter().map(|row| (row[v] * n as f64) as usize).collect();
            strata.sort_unstable();
            assert_eq!(strata, (0..n).collect::<Vec<_>>(), "variable {v}, n {n}");
        }
    }
    // Through the distributions: the samples of data/fragility_portal.toml's inputs, mapped
    // back by each one's CDF, hit each stratum once too.
    let scene = Scene::from_file(&data("fragility_portal.toml")).expect("scene");
    let n = 64;
    let values = fragility::sample_values(&scene.uncertain, &scene.uncertain_correlation, n, 3);
    for (k, input) in scene.uncertain.iter().enumerate() {
        let cdf = |x: f64| match input.dist {
            voussoir::sampling::Distribution::Normal { mean, cov } => {
                phi((x - mean) / (cov * mean.abs()))
            }
            voussoir::sampling::Distribution::Uniform { low, high } => (x - low) / (high - low),
            voussoir::sampling::Distribution::Lognormal { median, beta } => {
                phi((x / median).ln() / beta)
            }
        };
        let mut strata: Vec<usize> = values
            .iter()
            .map(|v| (cdf(v[k]) * n as f64) as usize)
            .collect();
        strata.sort_unstable();
        assert_eq!(strata, (0..n).collect::<Vec<_>>(), "{}", input.key);
    }
}

fn settings(samples: usize, seed: u64) -> Settings {
    Settings {
        samples,
        seed,
        ..Settings::default()
    }
}

#[test]
fn the_same_seed_gives_the_same_samples_and_curve() {
    let scene = Scene::from_file(&data("fragility_portal.toml")).expect("scene");
    let a = fragility::capacity_route(&scene, &settings(24, 9)).expect("fragility");
    let b = fragility::capacity_route(&scene, &settings(24, 9)).expect("fragility");
    assert_eq!(a.samples, b.samples);
    assert_eq!(a.fit, b.fit);
    let c = fragility::capacity_route(&scene, &settings(24, 10)).expect("fragility");
    assert_ne!(a.samples, c.samples);
    // Each sample's capacity is the assessment of its own scene, as `assess` gives it.
    let s = &a.samples[5];
    let pairs: Vec<(&str, toml::Value)> = scene
        .uncertain
        .iter()
        .zip(&s.values)
        .map(|(i, &x)| (i.key.as_str(), toml::Value::Float(x)))
        .collect();
    let one = scene.with_values(&pairs).expect("sample scene");
    let assessed =
        analysis::assess_directions(&one, &Options::default(), &AssessOptions::default(), None)
            .expect("assess");
    let least = assessed
        .directions
        .iter()
        .filter_map(|d| d.verdict.nonlinear.ag_max)
        .fold(f64::INFINITY, f64::min);
    assert_eq!(s.capacity.ag(), Some(least));
}

#[test]
fn certain_inputs_give_a_step_at_the_largest_passing_ag() {
    let portal = std::fs::read_to_string(data("fragility_portal.toml")).expect("read");
    let certain = portal
        .split("[uncertain]")
        .next()
        .expect("head")
        .to_string();
    // Without [uncertain], and with distributions of no spread.
    let degenerate = format!(
        "{certain}[uncertain]\n\"arch.thickness\" = {{ dist = \"normal\", mean = 0.2, cov = 0.0 }}\n\"piers.width\" = {{ dist = \"uniform\", low = 0.4, high = 0.4 }}\n"
    );
    let reference = Scene::from_toml_str(&certain, "certain").expect("scene");
    let assessed = analysis::assess_directions(
        &reference,
        &Options::default(),
        &AssessOptions::default(),
        None,
    )
    .expect("assess");
    let ag_max = assessed
        .directions
        .iter()
        .filter_map(|d| d.verdict.nonlinear.ag_max)
        .fold(f64::INFINITY, f64::min);
    assert!(ag_max.is_finite() && ag_max > 0.0);
    for text in [certain.clone(), degenerate] {
        let scene = Scene::from_toml_str(&text, "certain").expect("scene");
        let f = fragility::capacity_route(&scene, &settings(12, 4)).expect("fragility");
        assert!(f.samples.iter().all(|s| s.capacity.ag() == Some(ag_max)));
        let fit = f.fit.clone().expect("fit");
        assert_eq!(fit.beta, 0.0);
        assert_eq!(fit.median, ag_max);
        // The step: nothing fails at the largest passing ag, everything just above it.
        assert_eq!(fit.probability(ag_max), 0.0);
        assert_eq!(fit.probability(ag_max * (1.0 + 1e-12)), 1.0);
        assert_eq!(fit.probability(0.5 * ag_max), 0.0);
        let empirical = f.empirical();
        assert!(empirical.iter().all(|&(a, _)| a == ag_max));
        assert_eq!(empirical.last().map(|p| p.1), Some(1.0));
    }
}

#[test]
fn a_sample_outside_the_keys_range_is_refused_with_its_key_and_value() {
    let portal = std::fs::read_to_string(data("fragility_portal.toml")).expect("read");
    let head = portal.split("[uncertain]").next().expect("head");
    // A coefficient of variation of 2: some thicknesses are negative.
    let wide = format!(
        "{head}[uncertain]\n\"arch.thickness\" = {{ dist = \"normal\", mean = 0.2, cov = 2.0 }}\n"
    );
    let scene = Scene::from_toml_str(&wide, "wide").expect("scene");
    let e = fragility::capacity_route(&scene, &settings(20, 1))
        .expect_err("refused")
        .to_string();
    assert!(
        e.contains("arch.thickness = -") && e.contains("refused, not truncated"),
        "{e}"
    );
    // The same refusal from the check a cluster's client makes before it sends out runs.
    let checked = fragility::check_samples(&scene, &settings(20, 1))
        .expect_err("refused")
        .to_string();
    assert_eq!(checked, e);
    // A key the scene does not have.
    let typo = format!(
        "{head}[uncertain]\n\"arch.thicknes\" = {{ dist = \"uniform\", low = 0.1, high = 0.2 }}\n"
    );
    let scene = Scene::from_toml_str(&typo, "typo").expect("scene");
    let e = fragility::capacity_route(&scene, &settings(5, 1))
        .expect_err("refused")
        .to_string();
    assert!(
        e.contains("\"arch.thicknes\"") && e.contains("thickness"),
        "{e}"
    );
    // Bad distributions are errors of the scene, naming the entry.
    for (entry, words) in [
        ("{ dist = \"gamma\", mean = 1.0 }", "dist"),
        ("{ dist = \"normal\", mean = 0.2 }", "cov"),
        ("{ dist = \"uniform\", low = 0.3, high = 0.2 }", "high"),
        (
            "{ dist = \"lognormal\", median = -1.0, beta = 0.1 }",
            "median",
        ),
        (
            "{ dist = \"normal\", mean = 0.2, cov = 0.1, sd = 3.0 }",
            "sd",
        ),
    ] {
        let text = format!("{head}[uncertain]\n\"arch.thickness\" = {entry}\n");
        let e = Scene::from_toml_str(&text, "bad")
            .expect_err("bad")
            .to_string();
        assert!(
            e.contains("uncertain.\"arch.thickness\"") && e.contains(words),
            "{e}"
        );
    }
}

#[test]
fn samples_that_cannot_stand_fail_at_every_ag_and_sliding_ones_are_left_out() {
    let portal = std::fs::read_to_string(data("fragility_portal.toml")).expect("read");
    let head = portal.split("[uncertain]").next().expect("head");
    // Low friction: some samples cannot stand at all, some slide at collapse (no rotational
    // capacity curve).
    let text = format!(
        "{head}[uncertain]\n\"material.friction\" = {{ dist = \"uniform\", low = 0.05, high = 0.9 }}\n"
    );
    let scene = Scene::from_toml_str(&text, "friction").expect("scene");
    let f = fragility::capacity_route(&scene, &settings(16, 2)).expect("fragility");
    let mut kinds = [0; 3];
    for s in &f.samples {
        let one = scene
            .with_values(&[("material.friction", toml::Value::Float(s.values[0]))])
            .expect("sample scene");
        let stands = analysis::analyse(&one, &Options::default())
            .expect("analyse")
            .lower
            .status
            != voussoir::outcome::Status::CannotStand;
        match &s.capacity {
            Capacity::Below(_) => {
                assert!(!stands, "friction {}", s.values[0]);
                kinds[0] += 1;
            }
            Capacity::NotAssessed(why) => {
                assert!(
                    stands && (why.contains("slid") || why.contains("non-associative")),
                    "{why}"
                );
                kinds[1] += 1;
            }
            Capacity::At { .. } | Capacity::Above => {
                assert!(stands);
                kinds[2] += 1;
            }
        }
    }
    assert_eq!(f.not_assessed(), kinds[1]);
    assert!(kinds[0] > 0 && kinds[2] > 0, "{kinds:?}");
}

#[test]
fn the_command_writes_its_table_chart_and_json() {
    let dir = tempfile::tempdir().expect("dir");
    let csv = dir.path().join("f.csv");
    let svg = dir.path().join("f.svg");
    let out = voussoir()
        .arg("fragility")
        .arg(data("fragility_portal.toml"))
        .args(["--samples", "20", "--seed", "3", "--json", "--csv"])
        .arg(&csv)
        .arg("--svg")
        .arg(&svg)
        .output()
        .expect("run");
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let json: serde_json::Value = serde_json::from_slice(&out.stdout).expect("json");
    assert_eq!(json["route"], "capacity");
    assert_eq!(json["sample_count"], 20);
    assert_eq!(json["samples"].as_array().map(Vec::len), Some(20));
    let median = json["median"].as_f64().expect("median");
    let bounds = json["median_bounds"].as_array().expect("bounds");
    assert!(bounds[0].as_f64() < Some(median) && Some(median) < bounds[1].as_f64());
    let table = std::fs::read_to_string(&csv).expect("csv");
    assert_eq!(table.lines().count(), 21);
    assert!(table.starts_with("sample,arch.thickness,material.unit_weight,piers.width,outcome"));
    let chart = std::fs::read_to_string(&svg).expect("svg");
    roxmltree::Document::parse(&chart).expect("well-formed SVG");
    // The --site override reaches the site; a scene without [site] is refused.
    let (_dir, plain) = scene_file(&std::fs::read_to_string(data("portal.toml")).expect("read"));
    let out = voussoir()
        .arg("fragility")
        .arg(&plain)
        .args(["--samples", "3"])
        .output()
        .expect("run");
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("[site]"));
}

#[test]
fn the_dynamic_route_counts_the_dem_runs_of_each_sample() {
    let scene = Scene::from_file(&data("fragility_portal.toml")).expect("scene");
    let record = voussoir::dem::record::read(
        &data("records/synthetic_10s.AT2"),
        voussoir::dem::record::AccelUnit::G,
        None,
    )
    .expect("record");
    let stripes = [0.1, 0.6];
    let dynamic = voussoir::dem::dynamic::DynamicSettings::default();
    let route = || {
        fragility::dynamic_route(
            &scene,
            &settings(2, 7),
            std::slice::from_ref(&record),
            &stripes,
            &dynamic,
        )
        .expect("dynamic route")
    };
    let f = route();
    assert_eq!(f.samples.len(), 2);
    for (j, stripe) in f.stripes.iter().enumerate() {
        assert_eq!(stripe.runs, 2);
        let counted = f.samples.iter().filter(|s| s.collapsed[j][0]).count() as u64;
        assert_eq!(stripe.collapses, counted);
    }
    // A run is the DEM of the sample's own scene under the record scaled to the stripe.
    let s = &f.samples[1];
    let pairs: Vec<(&str, toml::Value)> = scene
        .uncertain
        .iter()
        .zip(&s.values)
        .map(|(i, &x)| (i.key.as_str(), toml::Value::Float(x)))
        .collect();
    let one = scene.with_values(&pairs).expect("sample scene");
    for (j, &pga) in stripes.iter().enumerate() {
        let g = voussoir::dem::record::STANDARD_GRAVITY;
        let ground: voussoir::dem::record::GroundInput =
            voussoir::dem::record::Excitation::Record(record.scaled(pga * g / record.pga())).into();
        let run = analysis::dem_dynamic(&one, &ground, &dynamic).expect("dem");
        assert_eq!(
            s.collapsed[j][0],
            run.result.collapsed || run.result.cannot_stand
        );
    }
    // The same seed, the same runs; and the same again from chunks computed apart (a
    // cluster's), each through JSON as Python's `fragility(..., client=)` carries them.
    assert_eq!(route().samples, f.samples);
    let mut chunks: Vec<fragility::DynamicSample> = Vec::new();
    for range in [0..1, 1..2] {
        let part = fragility::dynamic_samples(
            &scene,
            &settings(2, 7),
            std::slice::from_ref(&record),
            &stripes,
            &dynamic,
            range,
        )
        .expect("chunk");
        let text = serde_json::to_string(&part).expect("json");
        chunks.extend(serde_json::from_str::<Vec<fragility::DynamicSample>>(&text).expect("json"));
    }
    let joined = fragility::dynamic_fragility(&scene, &settings(2, 7), &[record], &stripes, chunks)
        .expect("from chunks");
    assert_eq!(joined.samples, f.samples);
    assert_eq!(joined.stripes, f.stripes);
    assert_eq!(joined.fit, f.fit);
}

#[test]
fn the_runs_of_the_dynamic_route_are_numbered_sample_stripe_record_and_join_to_its_samples() {
    // What Python's `fragility(..., records=, client=)` does: one DEM run per case on the
    // workers, carried as JSON, joined in order into the samples and fitted here.
    let scene = Scene::from_file(&data("fragility_portal.toml")).expect("scene");
    let full = voussoir::dem::record::read(
        &data("records/synthetic_10s.AT2"),
        voussoir::dem::record::AccelUnit::G,
        None,
    )
    .expect("record");
    // A second record that differs: a 20 ms triangle, far too short an impulse to bring
    // the portal down at any stripe.
    let short = voussoir::dem::record::GroundMotion {
        time: vec![0.0, 0.01, 0.02],
        accel: vec![0.0, 1.0, 0.0],
        source: "a 20 ms triangle".into(),
    };
    let records = [full, short];
    let stripes = [0.1, 0.6];
    let s = settings(2, 7);
    let dynamic = voussoir::dem::dynamic::DynamicSettings::default();
    let total = fragility::dynamic_run_count(&scene, &s, &records, &stripes).expect("count");
    assert_eq!(total, 2 * 2 * 2);
    // The whole route, counting its runs as the CLI's progress bar does.
    let done = std::sync::atomic::AtomicUsize::new(0);
    let whole =
        fragility::dynamic_route_with_progress(&scene, &s, &records, &stripes, &dynamic, &|| {
            done.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
        })
        .expect("route");
    assert_eq!(done.into_inner(), total);
    // Each run alone, through JSON: run k is sample k / 4, stripe (k / 2) % 2, record k % 2,
    // the DEM of that sample's own scene under that record scaled to that stripe.
    let mut flags: Vec<bool> = Vec::new();
    for k in 0..total {
        let part = fragility::dynamic_runs(&scene, &s, &records, &stripes, &dynamic, k..k + 1)
            .expect("run");
        let text = serde_json::to_string(&part).expect("json");
        flags.extend(serde_json::from_str::<Vec<bool>>(&text).expect("json"));
        let (i, j, r) = (k / 4, (k / 2) % 2, k % 2);
        assert_eq!(flags[k], whole.samples[i].collapsed[j][r], "run {k}");
        let pairs: Vec<(&str, toml::Value)> = scene
            .uncertain
            .iter()
            .zip(&whole.samples[i].values)
            .map(|(u, &x)| (u.key.as_str(), toml::Value::Float(x)))
            .collect();
        let one = scene.with_values(&pairs).expect("sample scene");
        let g = voussoir::dem::record::STANDARD_GRAVITY;
        let ground: voussoir::dem::record::GroundInput = voussoir::dem::record::Excitation::Record(
            records[r].scaled(stripes[j] * g / records[r].pga()),
        )
        .into();
        let run = analysis::dem_dynamic(&one, &ground, &dynamic).expect("dem");
        assert_eq!(
            flags[k],
            run.result.collapsed || run.result.cannot_stand,
            "run {k}"
        );
    }
    // The numbering is seen: the records give different outcomes at the strong stripe.
    assert_ne!(
        flags[2], flags[3],
        "the two records should differ at 0.6 g: {flags:?}"
    );
    // Chunks across samples join to the same samples and fit.
    let mut chunked: Vec<bool> = Vec::new();
    for range in [0..3, 3..8] {
        chunked.extend(
            fragility::dynamic_runs(&scene, &s, &records, &stripes, &dynamic, range)
                .expect("chunk"),
        );
    }
    assert_eq!(chunked, flags);
    let samples =
        fragility::dynamic_samples_from_runs(&scene, &s, &records, &stripes, &flags).expect("join");
    assert_eq!(samples, whole.samples);
    let joined =
        fragility::dynamic_fragility(&scene, &s, &records, &stripes, samples).expect("fit");
    assert_eq!(joined.stripes, whole.stripes);
    assert_eq!(joined.fit, whole.fit);
    // A range outside the runs, an empty one, or too few outcomes: refused, saying what.
    for range in [6..9, 4..4] {
        let e = fragility::dynamic_runs(&scene, &s, &records, &stripes, &dynamic, range)
            .expect_err("refused")
            .to_string();
        assert!(e.contains("run range") && e.contains("0..8"), "{e}");
    }
    let e = fragility::dynamic_samples_from_runs(&scene, &s, &records, &stripes, &flags[..7])
        .expect_err("refused")
        .to_string();
    assert!(
        e.contains("7 run outcomes given for a fragility of 8 runs"),
        "{e}"
    );
}

#[test]
fn chunks_computed_apart_give_the_local_samples_and_fit() {
    // What Python's `fragility(..., client=)` does: the samples in chunks (on a cluster's
    // workers), carried as JSON, joined in order and fitted here.
    let scene = Scene::from_file(&data("fragility_portal.toml")).expect("scene");
    let s = settings(24, 9);
    let whole = fragility::capacity_route(&scene, &s).expect("fragility");
    let mut samples: Vec<fragility::Sample> = Vec::new();
    for range in [0..7, 7..16, 16..24] {
        let part = fragility::capacity_samples(&scene, &s, range.clone()).expect("chunk");
        assert_eq!(part.len(), range.len());
        let text = serde_json::to_string(&part).expect("json");
        samples.extend(serde_json::from_str::<Vec<fragility::Sample>>(&text).expect("json"));
    }
    let joined = fragility::capacity_fragility(&scene, &s, samples.clone()).expect("fit");
    assert_eq!(joined.samples, whole.samples);
    assert_eq!(joined.fit, whole.fit);
    // A chunk outside the samples, an empty one, or too few samples for the fit: refused.
    for range in [20..25, 5..5] {
        let e = fragility::capacity_samples(&scene, &s, range)
            .expect_err("refused")
            .to_string();
        assert!(e.contains("sample range") && e.contains("0..24"), "{e}");
    }
    samples.pop();
    let e = fragility::capacity_fragility(&scene, &s, samples)
        .expect_err("refused")
        .to_string();
    assert!(e.contains("23 samples given for a fragility of 24"), "{e}");
}

/// `data/fragility_portal.toml` with `extra` appended to its `[uncertain]` table.
fn portal_with(extra: &str) -> Result<Scene, voussoir::error::SceneError> {
    let portal = std::fs::read_to_string(data("fragility_portal.toml")).expect("read");
    Scene::from_toml_str(&format!("{portal}{extra}\n"), "correlated")
}

/// Correlated inputs (Iman and Conover's reordering): the samples' rank correlation is the
/// one asked for, within a rank correlation's sampling error `1 / sqrt(n)`; every input keeps
/// the very values of its independent Latin hypercube (so every stratum once); and two inputs
/// that both raise the capacity, correlated positively, widen the fragility's dispersion,
/// negatively narrow it.
#[test]
fn correlated_inputs_keep_their_strata_and_take_the_rank_correlation() {
    let n = 400;
    let pair = |rank: f64| {
        format!(
            "correlation = [{{ between = [\"arch.thickness\", \"piers.width\"], rank = {rank:?} }}]"
        )
    };
    let independent = portal_with("").expect("scene");
    let free = fragility::sample_values(&independent.uncertain, &[], n, 5);
    let keys: Vec<&str> = independent
        .uncertain
        .iter()
        .map(|u| u.key.as_str())
        .collect();
    let (t, w) = (
        keys.iter().position(|k| *k == "arch.thickness").expect("t"),
        keys.iter().position(|k| *k == "piers.width").expect("w"),
    );
    let column = |v: &[Vec<f64>], k: usize| -> Vec<f64> { v.iter().map(|row| row[k]).collect() };
    let mut betas = Vec::new();
    for rank in [-0.8, 0.0, 0.8] {
        let scene = portal_with(&pair(rank)).expect("scene");
        assert_eq!(scene.uncertain_correlation.len(), 1);
        let values = fragility::sample_values(&scene.uncertain, &scene.uncertain_correlation, n, 5);
        let rho = voussoir::sampling::spearman(&column(&values, t), &column(&values, w));
        assert!(
            (rho - rank).abs() < 1.0 / (n as f64).sqrt(),
            "rank {rank}: the samples' Spearman correlation is {rho}"
        );
        for (k, key) in keys.iter().enumerate() {
            let (mut a, mut b) = (column(&free, k), column(&values, k));
            a.sort_by(f64::total_cmp);
            b.sort_by(f64::total_cmp);
            assert_eq!(a, b, "{key}: the same values, reordered");
        }
        let f = fragility::capacity_route(&scene, &settings(n, 5)).expect("fragility");
        betas.push(f.fit.expect("a fit").beta);
    }
    assert!(
        betas[0] < betas[1] && betas[1] < betas[2],
        "dispersion against the correlation of two inputs that both raise the capacity: {betas:?}"
    );
    // No correlation key: the samples of the independent inputs, value for value.
    let none = portal_with("").expect("scene");
    assert_eq!(
        fragility::sample_values(&none.uncertain, &none.uncertain_correlation, n, 5),
        free
    );
}

/// Correlations that name no input, an input twice, a pair twice, a rank of 1, or a set that
/// cannot hold together are refused, naming the key.
#[test]
fn impossible_correlations_are_refused_naming_the_key() {
    for (extra, key, words) in [
        (
            "correlation = [{ between = [\"arch.thicknes\", \"piers.width\"], rank = 0.5 }]",
            "uncertain.correlation[0].between",
            "arch.thickness",
        ),
        (
            "correlation = [{ between = [\"piers.width\", \"piers.width\"], rank = 0.5 }]",
            "uncertain.correlation[0].between",
            "two different inputs",
        ),
        (
            "correlation = [{ between = [\"arch.thickness\", \"piers.width\"], rank = 1.0 }]",
            "uncertain.correlation[0].rank",
            "strictly between -1 and 1",
        ),
        (
            "correlation = [{ between = [\"arch.thickness\", \"piers.width\"], rank = 0.5 }, \
             { between = [\"piers.width\", \"arch.thickness\"], rank = 0.2 }]",
            "uncertain.correlation[1].between",
            "each pair once",
        ),
        (
            "correlation = [\
             { between = [\"arch.thickness\", \"piers.width\"], rank = 0.9 }, \
             { between = [\"arch.thickness\", \"material.unit_weight\"], rank = 0.9 }, \
             { between = [\"piers.width\", \"material.unit_weight\"], rank = -0.9 }]",
            "uncertain.correlation",
            "positive definite",
        ),
        (
            "correlation = [{ between = [\"arch.thickness\", \"piers.width\"], rho = 0.5 }]",
            "uncertain.correlation[0].rho",
            "between and rank",
        ),
        (
            "correlation = { between = [\"arch.thickness\", \"piers.width\"], rank = 0.5 }",
            "uncertain.correlation",
            "an array of pairs",
        ),
    ] {
        let e = portal_with(extra).expect_err(extra).to_string();
        assert!(e.contains(key) && e.contains(words), "{extra}\n-> {e}");
    }
}
