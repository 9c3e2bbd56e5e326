//! Moving loads (issue 29's benchmark): a 200-position roll of a two-axle tandem over a
//! 64-voussoir filled semicircular arch, both bounds at every position (the static program
//! and the certified mechanism of its hinges), the axles spread through the fill at 2:1, and
//! the critical position refined by golden section and analysed again, as `analyze --roll`
//! runs it. Plain `harness = false` program printing a Markdown table; run with
//! `cargo bench --bench roll`. Target: well under a second.

mod common;

use common::median as time;

use voussoir::analysis::Options;
use voussoir::roll::{self, RollSpec, Target};
use voussoir::scene::Scene;

fn main() {
    let text = "[arch]\nshape = \"circular\"\nradius = 3.0\nthickness = 0.45\nvoussoirs = 64\n\
        [fill]\nlevel = 3.725\nunit_weight = 18000.0\nspread_deg = 26.6\n\
        [action]\nkind = \"live\"\n\
        [[vehicles]]\nname = \"tandem\"\naxles = [[0.0, 150000.0], [1.2, 150000.0]]\nat = 0.0\n";
    let scene = Scene::from_toml_str(text, "bench").expect("valid scene");
    // 200 positions of the first axle, the tandem on the arch throughout.
    let (from, step) = (-3.2, 0.026);
    let spec = RollSpec {
        target: Target::Vehicle(0),
        from,
        to: from + 199.0 * step,
        step,
        refine: true,
    };
    let threads = rayon::current_num_threads();
    let one = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .expect("thread pool");
    println!("Roll of a two-axle tandem (2 x 150 kN at 1.2 m) over a filled semicircle, R = 3 m, t = 0.45 m, 64 voussoirs, spread 26.6 deg, 200 positions, both bounds at each, median of 5\n");
    println!("| threads | positions | critical x (m) | lambda | bounds agree everywhere | total ms | ms per position |");
    println!("|---:|---:|---:|---:|---|---:|---:|");
    for (label, pool) in [
        (1, &one),
        (
            threads,
            &rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .expect("thread pool"),
        ),
    ] {
        let (t, r) = pool.install(|| time(5, || roll::roll(&scene, &spec, &Options::default())));
        let r = r.expect("roll");
        assert_eq!(r.points.len(), 200);
        let agree = r
            .points
            .iter()
            .all(|p| match (p.lambda_lower, p.lambda_upper) {
                (Some(l), Some(u)) => (l - u).abs() <= 1e-6 * l.max(1.0),
                _ => false,
            });
        let c = r.critical.as_ref().expect("critical position");
        println!(
            "| {label} | {} | {:.4} | {:.6} | {agree} | {:.1} | {:.3} |",
            r.points.len(),
            c.position,
            c.analysis.lower.lambda.unwrap_or(f64::NAN),
            t * 1e3,
            t * 1e3 / r.points.len() as f64
        );
    }
}
