//! The non-associative multiplier against the associative solve (issue 25, docs/friction.md):
//! iterations and wall time of `statics::analyse_non_associative` (all three starts) against
//! `statics::analyse` (the chain's active set on arches) and the full conic program, on
//! semicircles of 64 and 1000 voussoirs that slide at their springings (t/R = 0.25, mu = 0.4:
//! not friction-exact, one joint slips in the associative mechanism, so `analyze` iterates),
//! a 200-block running-bond wall (mu = 0.6) and the 3-bay arcade of `data/arcade.toml` with
//! mu = 0.4 (314 blocks; one run, it takes minutes). `slip` is the number of joints that slip
//! in the associative mechanism. On the wall and the arcade the warm-started dual simplex path
//! (`NonAssociativeSettings::simplex`, off by default) is timed too, one run. Median of a few
//! runs; run with
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

/// The running-bond wall of `courses` courses of `per` blocks ([`common::running_bond_wall`])
/// with friction `mu`.
fn wall(courses: usize, per: usize, mu: f64) -> Scene {
    let polys: Vec<String> = common::running_bond_wall(courses, per)
        .iter()
        .map(|p| {
            let pts: Vec<String> = p.iter().map(|[x, y]| format!("[{x}, {y}]")).collect();
            format!("[{}]", pts.join(", "))
        })
        .collect();
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

/// `data/arcade.toml` (three bays, spandrel wall) with friction `mu`.
fn arcade(mu: f64) -> Scene {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/data/arcade.toml");
    let text = match std::fs::read_to_string(path) {
        Ok(t) => t,
        Err(e) => panic!("{path}: {e}"),
    };
    scene(&text.replace("friction = inf", &format!("friction = {mu}")))
}

/// The median wall time of `reps` runs (after one more, untimed), or of one run when `reps`
/// is 1.
fn timed<T>(reps: usize, mut f: impl FnMut() -> T) -> (f64, T) {
    if reps == 1 {
        let t = std::time::Instant::now();
        let out = f();
        return (t.elapsed().as_secs_f64(), out);
    }
    common::median(reps, f)
}

/// One line per start of the iteration, indented by `indent`.
fn print_starts(indent: &str, starts: &[statics::StartOutcome]) {
    for st in starts {
        println!(
            "{indent}start {:<15} lambda {:>10} programs {:>4} settled by {}",
            st.start.as_str(),
            st.lambda.map_or("none".to_string(), |l| format!("{l:.6}")),
            st.iterations,
            st.settled_by
                .map_or("nothing (not converged)", |b| b.as_str())
        );
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
        ("3-bay arcade, mu = 0.4", arcade(0.4), 1),
    ];
    println!(
        "{:<42} {:>7} {:>5} {:>11} {:>11} {:>11} {:>10} {:>7} {:>9} {:>9}",
        "case",
        "blocks",
        "slip",
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
        let (t_assoc, a) = timed(reps, || statics::analyse(&m, &settings));
        let a = match a {
            Ok(a) => a,
            Err(e) => panic!("{name}: {e}"),
        };
        let full = settings.clone().program(Program::Full);
        let (t_full, _) = timed(reps, || statics::analyse(&m, &full));
        let (t_na, na) = timed(reps, || {
            statics::analyse_non_associative(&m, &settings, &a, &na_settings)
        });
        let na = match na {
            Ok(n) => n,
            Err(e) => panic!("{name}: {e}"),
        };
        println!(
            "{:<42} {:>7} {:>5} {:>11.3} {:>11.3} {:>11.3} {:>10.6} {:>7} {:>9} {:>9.1}",
            name,
            m.assembly.blocks.len(),
            a.friction(&m.assembly).slipping.len(),
            1e3 * t_assoc,
            1e3 * t_full,
            1e3 * t_na,
            a.lambda.unwrap_or(f64::NAN),
            na.lambda.map_or("none".to_string(), |l| format!("{l:.5}")),
            na.iterations,
            t_na / t_assoc
        );
        print_starts("    ", &na.starts);
        // One run of a variant of the iteration, printed against the associative solve.
        let variant = |label: &str, na: NonAssociativeSettings| {
            let (t, out) = timed(1, || {
                statics::analyse_non_associative(&m, &settings, &a, &na)
            });
            let out = match out {
                Ok(n) => n,
                Err(e) => panic!("{name}, {label}: {e}"),
            };
            println!(
                "    {label}: {:.3} ms, lambda {}, {} programs, {:.1} x assoc",
                1e3 * t,
                out.lambda.map_or("none".to_string(), |l| format!("{l:.6}")),
                out.iterations,
                t / t_assoc
            );
            print_starts("        ", &out.starts);
        };
        // The relaxation alone (`NonAssociativeSettings::mechanism_step` off).
        variant(
            "relaxation only",
            NonAssociativeSettings {
                mechanism_step: false,
                ..na_settings.clone()
            },
        );
        if !name.starts_with("semicircle") && std::env::var_os("VOUSSOIR_BENCH_SIMPLEX").is_some() {
            // The warm-started dual simplex path (`NonAssociativeSettings::simplex`; minutes
            // on the arcade: only with VOUSSOIR_BENCH_SIMPLEX set).
            variant(
                "simplex path",
                NonAssociativeSettings {
                    simplex: true,
                    ..na_settings.clone()
                },
            );
        }
    }
}
