//! Wall time of a full DEM bracket to 1% (`voussoir dem --tolerance 0.01`): a 20- and a
//! 32-voussoir semicircle and a portal, default settings (`dem.integrator = "auto"`, the rigid
//! stepping on these chains) and with the explicit stepping, one core. Prints a table.
//! Run with `cargo bench --bench dem`.

use std::time::Instant;
use voussoir::dem;
use voussoir::scene::Scene;
use voussoir::statics;

fn main() {
    let cases = [
        (
            "semicircle n=20 t/R=0.15",
            "[arch]\nshape = \"circular\"\nradius = 1.0\nthickness = 0.15\nvoussoirs = 20\n\
             [material]\nfriction = 0.8\n",
        ),
        (
            "semicircle n=32 t/R=0.15",
            "[arch]\nshape = \"circular\"\nradius = 1.0\nthickness = 0.15\nvoussoirs = 32\n\
             [material]\nfriction = 0.8\n",
        ),
        (
            "portal n=16 h=1 b=0.4 k=4",
            "[arch]\nshape = \"circular\"\nradius = 1.0\nthickness = 0.15\nvoussoirs = 16\n\
             [piers]\nheight = 1.0\nwidth = 0.4\ncourses = 4\n[material]\nfriction = 0.8\n",
        ),
    ];
    println!(
        "{:<28} {:>9} {:>6} {:>9} {:>9} {:>9} {:>8} {:>5} {:>9} {:>9} {:>8}",
        "case",
        "stepping",
        "blocks",
        "lower",
        "stands",
        "collapses",
        "diff%",
        "runs",
        "steps",
        "dt_s",
        "wall_s"
    );
    for (name, text) in cases {
        let Ok(scene) = Scene::from_toml_str(text, name) else {
            eprintln!("{name}: bad scene");
            continue;
        };
        let m = match voussoir::scene::build(&scene) {
            Ok(m) => m,
            Err(e) => {
                eprintln!("{name}: {e}");
                continue;
            }
        };
        let Ok(defaults) = voussoir::analysis::dem_parameters(&scene, &m) else {
            eprintln!("{name}: bad [dem]");
            continue;
        };
        for p in [
            defaults.clone(),
            defaults.clone().integrator(dem::Integrator::Explicit),
        ] {
            let clock = Instant::now();
            // The static bound starts the bracket, as the CLI does; its time is included.
            let lower = statics::analyse(&m, &statics::StaticSettings::default())
                .ok()
                .and_then(|r| r.lambda);
            let r = match dem::collapse_multiplier(&m, &p.initial_guess(lower), 0.01, &mut |_| {}) {
                Ok(r) => r,
                Err(e) => {
                    eprintln!("{name}: {e}");
                    continue;
                }
            };
            let wall = clock.elapsed().as_secs_f64();
            let f = |x: Option<f64>| x.map_or("-".to_string(), |v| format!("{v:.5}"));
            let diff = match (r.lambda_dem, lower) {
                (Some(d), Some(l)) => format!("{:+.2}", 100.0 * (d / l - 1.0)),
                _ => "-".to_string(),
            };
            println!(
                "{:<28} {:>9} {:>6} {:>9} {:>9} {:>9} {:>8} {:>5} {:>9} {:>9.2e} {:>8.2}",
                name,
                r.params.integrator.name(),
                m.assembly.blocks.len(),
                f(lower),
                f(r.lambda_stands),
                f(r.lambda_collapses),
                diff,
                r.runs.len(),
                r.steps,
                r.time_step,
                wall
            );
        }
    }
}
