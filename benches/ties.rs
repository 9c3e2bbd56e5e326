//! Tie rods (issue 24's benchmark): the static bound and the upper bound of a portal with 0, 1
//! and 4 ties at n = 64 and 1000 voussoirs, each method timed on its own and the whole
//! analysis as `analyze` runs it. Plain `harness = false` program printing a Markdown table;
//! run with `cargo bench --bench ties`. Target: no more than 2x the tie-free time (the chain
//! program takes each tie as one more unknown; figures in docs/performance.md).

mod common;

use common::median as time;

use voussoir::analysis::{self, KinematicMode, Options};
use voussoir::kinematic::{self, KinematicSettings};
use voussoir::scene::Scene;
use voussoir::statics::{self, StaticSettings};

fn main() {
    let one = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .expect("thread pool");
    println!("Tie rods, portal R = 1 m, t = 0.2 m on 1 m piers of 4 courses, ties between the piers at y = -0.05, -0.3, -0.55, -0.8 m of 500 N each, one thread, median: the static bound (`statics::analyse`: the program, and its stand test at lambda = 0), the certified upper bound (`kinematic::certify`, the mechanism of the static hinges valued by virtual work), the exhaustive search (`kinematic::analyse`, n = 64), the scene built (`scene::build`: blocks, loads, tie anchors) and the whole `analysis::analyse` (scene built, both bounds)\n");
    println!("| n | ties | lambda_lower | lambda_upper | static program | pivots | static ms | certified ms | exhaustive ms | build ms | analyse ms |");
    println!("|---:|---:|---:|---:|---|---:|---:|---:|---:|---:|---:|");
    for n in [64usize, 1000] {
        for ties in [0usize, 1, 4] {
            let mut text = format!(
                "[arch]\nshape = \"circular\"\nradius = 1.0\nthickness = 0.2\nvoussoirs = {n}\n[piers]\nheight = 1.0\nwidth = 0.4\ncourses = 4\n"
            );
            for y in [-0.05, -0.3, -0.55, -0.8].iter().take(ties) {
                text.push_str(&format!(
                    "[[ties]]\nfrom = [-1.0, {y}]\nto = [1.0, {y}]\ncapacity = 500.0\n"
                ));
            }
            let scene = Scene::from_toml_str(&text, "bench").expect("valid scene");
            let model = voussoir::scene::build(&scene).expect("model");
            let reps = (20_000 / n).clamp(5, 200);
            let settings = StaticSettings::default();
            let (ts, lower) = one.install(|| time(reps, || statics::analyse(&model, &settings)));
            let lower = lower.expect("static analysis");
            let ks = KinematicSettings::default();
            let (tc, upper) =
                one.install(|| time(reps, || kinematic::certify(&model, &lower, &ks)));
            let upper = upper.expect("certified");
            let exhaustive = if n <= 64 {
                let (te, e) = one.install(|| time(3, || kinematic::analyse(&model, &ks)));
                let e = e.expect("exhaustive search");
                assert!(
                    (e.lambda_upper.unwrap_or(f64::NAN) - upper.lambda_upper.unwrap_or(f64::NAN))
                        .abs()
                        <= 1e-8
                );
                format!("{:.3}", te * 1e3)
            } else {
                "".to_string()
            };
            let (tb, _) = one.install(|| time(reps, || voussoir::scene::build(&scene)));
            let options = Options {
                kinematic: KinematicMode::Certified,
                ..Options::default()
            };
            let (ta, a) = one.install(|| time(reps, || analysis::analyse(&scene, &options)));
            a.expect("analysis");
            println!(
                "| {n} | {ties} | {:.9} | {:.9} | {} | {} | {:.4} | {:.4} | {exhaustive} | {:.4} | {:.4} |",
                lower.lambda.unwrap_or(f64::NAN),
                upper.lambda_upper.unwrap_or(f64::NAN),
                if lower.exact_vertex {
                    "chain (active set)"
                } else {
                    "full (Clarabel)"
                },
                lower.iterations,
                ts * 1e3,
                tc * 1e3,
                tb * 1e3,
                ta * 1e3
            );
        }
    }

    println!("\nRetrofit design (`retrofit::design`, target 0.2 in both directions) of the same portal at n = 64 with 3 candidate ties (y = -0.05, -0.4, -0.8 m; costs 1, 1.5, 0.7), one thread, median\n");
    println!("| n | candidates | needed | lambda re-analysed | design + re-analysis ms |");
    println!("|---:|---:|---:|---:|---:|");
    let mut text = "[arch]\nshape = \"circular\"\nradius = 1.0\nthickness = 0.2\nvoussoirs = 64\n[piers]\nheight = 1.0\nwidth = 0.4\ncourses = 4\n".to_string();
    for (y, cost) in [(-0.05, 1.0), (-0.4, 1.5), (-0.8, 0.7)] {
        text.push_str(&format!(
            "[[ties]]\nfrom = [-1.0, {y}]\nto = [1.0, {y}]\ncapacity = \"design\"\ncost = {cost}\n"
        ));
    }
    let scene = Scene::from_toml_str(&text, "bench").expect("valid scene");
    let (t, r) = one.install(|| {
        time(20, || {
            voussoir::retrofit::design(&scene, 0.2, &Options::default()).expect("design")
        })
    });
    println!(
        "| 64 | 3 | {} | {:.9} | {:.2} |",
        r.ties.iter().filter(|t| t.needed).count(),
        r.lambda().unwrap_or(f64::NAN),
        t * 1e3
    );
}
