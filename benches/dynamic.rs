//! The DEM under ground motion (issue 15's benchmark): a 20-voussoir semicircle under a 30 s
//! synthetic record at the stable time step, one core, then an incremental dynamic analysis of
//! the same record. Prints steps/s and wall times; run with `cargo bench --bench dynamic`.
//! Targets: the 30 s record in under 10 s, the IDA within a minute.
//!
//! Issue 28's rest test (`dem::rest`): the record (peak 0.1 g) stays below the arch's static
//! threshold (0.149 g), so with the test nothing is integrated; the bench times the static
//! solves of the threshold and the rest of the run apart (the target: under 1 ms beyond the
//! static solve), the median of 200 repetitions, with and without the time history; then the
//! record scaled to 1.6 (above the threshold from 7.3 s) and the IDA, with and without the
//! test. `--quick` (or `VOUSSOIR_BENCH_QUICK=1`) leaves out the runs without the test.
//!
//! Issue 28's rigid-contact stepping (`dem.integrator = "moreau"`, `dem::moreau`): the record
//! scaled to 1.6 (the arch rocks from 7.3 s and survives) and to 2.1 (the explicit stepping
//! collapses, the rigid one survives: docs/dem.md), integrated over the whole 30 s (rest test
//! off) and with the rest test, by the explicit and the Moreau-Jean stepping; the target is
//! the 30 s record that rocks in under 1 s.
//! `VOUSSOIR_BENCH_MOREAU=1` runs only this part.
//!
//! The record is synthetic (no network, no bundled data): a sum of sines of 1-8 Hz under a
//! trapezoidal envelope (2 s rise, 20 s strong motion, 8 s decay), sampled every 0.01 s as a
//! PEER record is, and scaled to a peak of 0.1 g.

use voussoir::analysis;
use voussoir::dem::dynamic::DynamicSettings;
use voussoir::dem::record::{Excitation, GroundInput, GroundMotion};
use voussoir::scene::Scene;

fn record() -> GroundMotion {
    let dt = 0.01;
    let n = 3000;
    let time: Vec<f64> = (0..=n).map(|i| i as f64 * dt).collect();
    let envelope = |t: f64| (t / 2.0).min(1.0).min(((30.0 - t) / 8.0).max(0.0));
    let freqs = [1.1, 1.9, 2.7, 3.6, 5.2, 7.9];
    let raw: Vec<f64> = time
        .iter()
        .map(|&t| {
            envelope(t)
                * freqs
                    .iter()
                    .enumerate()
                    .map(|(k, f)| {
                        (2.0 * std::f64::consts::PI * f * t + k as f64).sin() / (1.0 + k as f64)
                    })
                    .sum::<f64>()
        })
        .collect();
    let peak = raw.iter().fold(0.0_f64, |m, a| m.max(a.abs()));
    let scale = 0.1 * 9.80665 / peak;
    GroundMotion {
        time,
        accel: raw.iter().map(|a| a * scale).collect(),
        source: "synthetic 30 s record, peak 0.1 g".into(),
    }
}

fn main() {
    let scene = Scene::from_toml_str(
        "[arch]\nshape = \"circular\"\nradius = 1.0\nthickness = 0.15\nvoussoirs = 20\n\
         [material]\nfriction = 0.8\n",
        "bench",
    )
    .expect("valid scene");
    let motion: GroundInput = Excitation::Record(record()).into();
    let settings = DynamicSettings {
        history_every: None,
        ..DynamicSettings::default()
    };
    let quick = std::env::args().any(|a| a == "--quick")
        || std::env::var("VOUSSOIR_BENCH_QUICK").is_ok_and(|v| v == "1");
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .expect("thread pool");
    println!(
        "DEM under ground motion: semicircle R = 1 m, t/R = 0.15, n = 20, mu = 0.8; {}\n",
        motion.main.describe()
    );
    if std::env::var("VOUSSOIR_BENCH_MOREAU").is_ok_and(|v| v == "1") {
        integrators(&scene, &motion, &settings, &pool, quick);
        return;
    }
    // The rest test alone: its static solves, then the run beyond them.
    let model = voussoir::scene::build(&scene).expect("model");
    let params = analysis::dem_parameters(&scene, &model).expect("parameters");
    let median = |mut v: Vec<f64>| {
        v.sort_by(f64::total_cmp);
        v[v.len() / 2]
    };
    let reps = 200;
    let mut solve = Vec::new();
    let mut beyond = Vec::new();
    let mut beyond_history = Vec::new();
    for _ in 0..reps {
        let t = std::time::Instant::now();
        let r = voussoir::dem::rest::rest_test(&model, &params);
        solve.push(t.elapsed().as_secs_f64());
        assert_eq!(r.name(), "applied");
        for (history, out) in [(None, &mut beyond), (Some(0.01), &mut beyond_history)] {
            let s = DynamicSettings {
                history_every: history,
                ..DynamicSettings::default()
            };
            let r = voussoir::dem::dynamic::respond_input(&model, &params, &motion, &s)
                .expect("dynamic run");
            assert_eq!(
                r.integration_start, None,
                "the record stays below the threshold"
            );
            // respond_input's own clock: the run beyond the static solves.
            out.push(r.wall_time_s);
        }
    }
    let th = voussoir::dem::rest::rest_test(&model, &params);
    let th = th.threshold().expect("applied");
    println!(
        "rest test: thresholds lambda = {:.6} (+x), {:.6} (-x); median of {reps}: static solves {:.3} ms, the 30 s run beyond them {:.4} ms without the history, {:.4} ms with it (0.01 s)\n",
        th.lambda_right,
        th.lambda_left,
        1e3 * median(solve),
        1e3 * median(beyond),
        1e3 * median(beyond_history)
    );
    println!("| run | rest test | collapsed | integration from (s) | steps | steps/s | wall s |");
    println!("|---|---|---|---:|---:|---:|---:|");
    // With the rest test, then (unless quick) without it.
    let modes: &[bool] = if quick { &[true] } else { &[true, false] };
    let with_rest = |rest: bool| DynamicSettings {
        rest_test: rest,
        ..settings.clone()
    };
    for scale in [1.0, 1.6] {
        for &rest in modes {
            let settings = with_rest(rest);
            let m = motion.scaled(scale);
            let r = pool
                .install(|| analysis::dem_dynamic(&scene, &m, &settings))
                .expect("dynamic run");
            let res = &r.result;
            println!(
                "| 30 s record (+{} s tail), scale {scale} | {} | {} | {} | {} | {:.0} | {:.4} |",
                settings.tail,
                res.rest_test.name(),
                res.collapsed,
                res.integration_start
                    .map_or("never".to_string(), |t| format!("{t:.3}")),
                res.steps,
                res.steps as f64 / res.wall_time_s,
                res.wall_time_s
            );
        }
    }
    for &rest in modes {
        let settings = with_rest(rest);
        let (_, ida) = pool
            .install(|| analysis::dem_ida(&scene, &motion, &settings, 0.05))
            .expect("IDA");
        println!(
            "| IDA to 5 % ({} runs, {} never integrated): collapse scale in [{:.3}, {}] | {} | - | - | {} | {:.0} | {:.2} |",
            ida.runs.len(),
            ida.integration_starts.iter().filter(|s| s.is_none()).count(),
            ida.scale_survives,
            ida.scale_collapses
                .map_or("none".to_string(), |s| format!("{s:.3}")),
            ida.rest_test.name(),
            ida.steps,
            ida.steps as f64 / ida.wall_time_s,
            ida.wall_time_s
        );
    }
    integrators(&scene, &motion, &settings, &pool, quick);
}

/// The explicit and the Moreau-Jean stepping side by side (issue 28, item 2); `quick` leaves
/// out the explicit runs without the rest test.
fn integrators(
    scene: &Scene,
    motion: &GroundInput,
    settings: &DynamicSettings,
    pool: &rayon::ThreadPool,
    quick: bool,
) {
    println!("\nRigid-contact stepping (issue 28):\n");
    println!("| integrator | scale | rest test | status | peak displacement (m) | time step (s) | steps | wall s |");
    println!("|---|---:|---|---|---:|---:|---:|---:|");
    for scale in [1.6, 2.1] {
        for integrator in ["explicit", "moreau"] {
            for rest in [false, true] {
                if quick && integrator == "explicit" && !rest {
                    continue;
                }
                let s = scene
                    .with_overrides(&[format!("dem.integrator={integrator}")])
                    .expect("integrator");
                let settings = DynamicSettings {
                    rest_test: rest,
                    ..settings.clone()
                };
                let m = motion.scaled(scale);
                let r = pool
                    .install(|| analysis::dem_dynamic(&s, &m, &settings))
                    .expect("dynamic run");
                let res = &r.result;
                println!(
                    "| {integrator} | {scale} | {} | {} | {:.5} | {:.3e} | {} | {:.3} |",
                    res.rest_test.name(),
                    res.status(),
                    res.peak_displacement,
                    res.time_step,
                    res.steps,
                    res.wall_time_s
                );
            }
        }
    }
}
