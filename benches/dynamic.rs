//! The DEM under ground motion (issue 15's benchmark): a 20-voussoir semicircle under a 30 s
//! synthetic record at the stable time step, one core, then an incremental dynamic analysis of
//! the same record. Prints steps/s and wall times; run with `cargo bench --bench dynamic`.
//! Targets: the 30 s record in under 10 s, the IDA within a minute.
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
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .expect("thread pool");
    println!(
        "DEM under ground motion: semicircle R = 1 m, t/R = 0.15, n = 20, mu = 0.8; {}\n",
        motion.main.describe()
    );
    println!("| run | collapsed | steps | time step (s) | steps/s | wall s |");
    println!("|---|---|---:|---:|---:|---:|");
    let r = pool
        .install(|| analysis::dem_dynamic(&scene, &motion, &settings))
        .expect("dynamic run");
    let res = &r.result;
    println!(
        "| 30 s record (+{} s tail), scale 1 | {} | {} | {:.2e} | {:.0} | {:.2} |",
        settings.tail,
        res.collapsed,
        res.steps,
        res.time_step,
        res.steps as f64 / res.wall_time_s,
        res.wall_time_s
    );
    let (_, ida) = pool
        .install(|| analysis::dem_ida(&scene, &motion, &settings, 0.05))
        .expect("IDA");
    println!(
        "| IDA to 5 % ({} runs): collapse scale in [{:.3}, {}] | - | {} | - | {:.0} | {:.2} |",
        ida.runs.len(),
        ida.scale_survives,
        ida.scale_collapses
            .map_or("none".to_string(), |s| format!("{s:.3}")),
        ida.steps,
        ida.steps as f64 / ida.wall_time_s,
        ida.wall_time_s
    );
}
