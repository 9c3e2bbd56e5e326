//! The non-associative multiplier against the associative solve (issue 25, docs/friction.md):
//! iterations and wall time of `statics::analyse_non_associative` (all three starts) against
//! `statics::analyse` (the chain's active set on arches) and the full conic program, on
//! semicircles of 64 and 1000 voussoirs that slide at their springings (t/R = 0.25, mu = 0.4)
//! and a 200-block running-bond wall (mu = 0.6). Median of a few runs; run with
//! `cargo bench --bench non_associative`.

mod common;

use voussoir::model::Model;
use voussoir::scene::Scene;
use voussoir::statics::{self, NonAssociativeSettings, Program, StaticSettings};

fn scene(text: &str) -> Scene {
    match Scene::from_toml_str(text, "bench") {
        Ok(s) => s,
        Err(e) => panic!("bench scene: {e}"),
    }
}

/// A running-bond wall of `courses` courses of `per` blocks 0.4 x 0.2 m (half blocks at the
/// ends of every other course).
fn wall(courses: usize, per: usize, mu: f64) -> Scene {
    let (b, h) = (0.4, 0.2);
    let mut polys = Vec::new();
    for c in 0..courses {
        let y0 = c as f64 * h;
        let mut xs: Vec<f64> = (0..=per).map(|k| k as f64 * b).collect();
        if c % 2 == 1 {
            xs = std::iter::once(0.0)
                .chain((0..per).map(|k| (k as f64 + 0.5) * b))
                .chain(std::iter::once(per as f64 * b))
                .collect();
        }
        for w in xs.windows(2) {
            let (x0, x1, y1) = (w[0], w[1], y0 + h);
            polys.push(format!(
                "[[{x0}, {y0}], [{x1}, {y0}], [{x1}, {y1}], [{x0}, {y1}]]"
            ));
        }
    }
    scene(&format!(
        "[blocks]\npolygons = [{}]\n[material]\nfriction = {mu}\n",
        polys.join(", ")
    ))
}

fn model(s: &Scene) -> Model {
    match voussoir::scene::build(s) {
        Ok(m) => m,
        Err(e) => panic!("bench model: {e}"),
    }
}

fn main() {
    let arch = |n: usize| {
        scene(&format!(
            "[arch]\nshape = \"circular\"\nradius = 1.0\nthickness = 0.25\nvoussoirs = {n}\n[material]\nfriction = 0.4\n"
        ))
    };
    let cases = [
        ("semicircle, 64 voussoirs", arch(64), 5),
        ("semicircle, 1000 voussoirs", arch(1000), 3),
        (
            "running-bond wall, 10 x 20 (205 blocks)",
            wall(10, 20, 0.6),
            3,
        ),
    ];
    println!(
        "{:<42} {:>7} {:>11} {:>11} {:>11} {:>10} {:>7} {:>9} {:>9}",
        "case",
        "blocks",
        "assoc ms",
        "full ms",
        "non-assoc",
        "lambda_a",
        "lam_na",
        "programs",
        "x assoc"
    );
    let settings = StaticSettings::default();
    let na_settings = NonAssociativeSettings::default();
    for (name, s, reps) in cases {
        let m = model(&s);
        let (t_assoc, a) = common::median(reps, || statics::analyse(&m, &settings));
        let a = match a {
            Ok(a) => a,
            Err(e) => panic!("{name}: {e}"),
        };
        let full = settings.clone().program(Program::Full);
        let (t_full, _) = common::median(reps, || statics::analyse(&m, &full));
        let (t_na, na) = common::median(reps, || {
            statics::analyse_non_associative(&m, &settings, &a, &na_settings)
        });
        let na = match na {
            Ok(n) => n,
            Err(e) => panic!("{name}: {e}"),
        };
        println!(
            "{:<42} {:>7} {:>11.3} {:>11.3} {:>11.3} {:>10.6} {:>7} {:>9} {:>9.1}",
            name,
            m.assembly.blocks.len(),
            1e3 * t_assoc,
            1e3 * t_full,
            1e3 * t_na,
            a.lambda.unwrap_or(f64::NAN),
            na.lambda.map_or("none".to_string(), |l| format!("{l:.5}")),
            na.iterations,
            t_na / t_assoc
        );
        for st in &na.starts {
            println!(
                "    start {:<15} lambda {:>10} programs {:>4} converged {}",
                st.start.as_str(),
                st.lambda.map_or("none".to_string(), |l| format!("{l:.6}")),
                st.iterations,
                st.converged
            );
        }
    }
}
