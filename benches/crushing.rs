//! Cost of the static program with finite compressive strength (issues 13 and 28): the
//! semicircle of the acceptance (R = 5 m, t/R = 0.15, unit weight 20 kN/m^3, depth 1 m) at
//! n = 64, 200 and 1000 voussoirs, rigid next to fc = 20 MPa and 1 MPa, on the chain program
//! (`Program::Auto`: the active set when rigid; with crushing, the working set of issue 28 by
//! default, or Clarabel with the cones of every joint when `working_set` is off) and on the
//! full program (Clarabel, with the cones when crushing). Run with
//! `cargo bench --bench crushing`. One thread; each time is the median of repeated runs of
//! `statics::analyse`. The last column is the multiplier's difference from the chain program
//! on all joints (the answer before issue 28).
//!
//! A plain table (`harness = false`), as the other benches.

use std::time::Instant;

use voussoir::scene::Scene;
use voussoir::statics::{self, Program, StaticSettings};

fn semicircle(n: usize, fc: f64) -> Scene {
    Scene::from_toml_str(
        &format!(
            "[arch]\nshape = \"circular\"\nradius = 5.0\nthickness = 0.75\nvoussoirs = {n}\n\
             [material]\nunit_weight = 20000.0\ncompressive_strength = {fc:e}\n"
        ),
        "bench",
    )
    .expect("valid scene")
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

fn main() {
    println!(
        "| n | fc | program | lambda | ms (median) | iterations | solver | lambda - all joints |"
    );
    println!("|---:|---|---|---:|---:|---:|---|---:|");
    for n in [64, 200, 1000] {
        for fc in [f64::INFINITY, 20e6, 1e6] {
            let model = voussoir::scene::build(&semicircle(n, fc)).expect("valid model");
            let all_joints =
                statics::analyse(&model, &StaticSettings::default().working_set(false))
                    .expect("solves")
                    .lambda
                    .unwrap_or(f64::NAN);
            let programs: &[(&str, StaticSettings)] = &[
                ("chain", StaticSettings::default()),
                (
                    "chain, all joints",
                    StaticSettings::default().working_set(false),
                ),
                ("full", StaticSettings::default().program(Program::Full)),
            ];
            for (name, settings) in programs {
                if !fc.is_finite() && *name == "chain, all joints" {
                    continue;
                }
                let runs = if n > 500 { 7 } else { 21 };
                let mut times = Vec::with_capacity(runs);
                let mut last = None;
                for _ in 0..runs {
                    let start = Instant::now();
                    let r = statics::analyse(&model, settings).expect("solves");
                    times.push(start.elapsed().as_secs_f64());
                    last = Some(r);
                }
                let r = last.expect("ran");
                let lambda = r.lambda.unwrap_or(f64::NAN);
                println!(
                    "| {n} | {} | {name} | {lambda:.9} | {:.3} | {} | {} | {:.1e} |",
                    if fc.is_finite() {
                        format!("{} MPa", fc / 1e6)
                    } else {
                        "inf (rigid)".to_string()
                    },
                    1e3 * median(times),
                    r.iterations,
                    r.solver_status,
                    lambda - all_joints,
                );
            }
        }
    }
}
