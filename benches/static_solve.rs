//! Static solve time against the number of voussoirs (semicircle, t/R = 0.15).
//! Run with `cargo bench --bench static_solve`; prints a table (median of repeated solves,
//! one thread).

use std::time::Instant;
use voussoir::assembly::Assembly;
use voussoir::lp::{self, StaticSettings};
use voussoir::scene::Scene;

fn main() {
    println!("| n voussoirs | lambda_lower | iterations | median solve (ms) | min (ms) |");
    println!("|---:|---:|---:|---:|---:|");
    for n in [16usize, 64, 256, 1000, 2000] {
        let scene = Scene::from_toml_str(
            &format!(
                "[arch]\nshape = \"circular\"\nradius = 1.0\nthickness = 0.15\nvoussoirs = {n}\n"
            ),
            "bench",
        )
        .expect("valid scene");
        let reps = (20_000 / n).clamp(5, 200);
        let mut times = Vec::with_capacity(reps);
        let mut last = None;
        for _ in 0..reps {
            let t0 = Instant::now();
            let a = Assembly::from_scene(&scene);
            let r = lp::analyse(&a, &StaticSettings::default()).expect("solves");
            times.push(t0.elapsed().as_secs_f64());
            last = Some(r);
        }
        times.sort_by(f64::total_cmp);
        let r = last.expect("ran");
        println!(
            "| {n} | {:.6} | {} | {:.3} | {:.3} |",
            r.lambda.unwrap_or(f64::NAN),
            r.iterations,
            times[reps / 2] * 1e3,
            times[0] * 1e3
        );
    }
}
