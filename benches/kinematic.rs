//! Timings of the kinematic searches: exhaustive discrete search (semicircle, n = 32, 64,
//! 128; a 4-course portal) and the continuous model per geometry. Prints a table; run with
//! `cargo bench --bench kinematic`. Targets: n = 128 under 0.2 s, continuous under 1 ms.

mod common;
use common::time;
use voussoir::kinematic::{self, KinematicSettings};
use voussoir::scene::Scene;

fn scene(text: &str) -> Scene {
    match Scene::from_toml_str(text, "bench") {
        Ok(s) => s,
        Err(e) => panic!("bench scene: {e}"),
    }
}

fn main() {
    println!(
        "{:<40} {:>6} {:>12} {:>12} {:>10} {:>10}",
        "discrete exhaustive search", "joints", "candidates", "lambda", "best ms", "1 thread"
    );
    let cases = [
        ("semicircle t/R=0.15 n=32", "[arch]\nshape='circular'\nradius=1.0\nthickness=0.15\nvoussoirs=32\n"),
        ("semicircle t/R=0.15 n=64", "[arch]\nshape='circular'\nradius=1.0\nthickness=0.15\nvoussoirs=64\n"),
        ("semicircle t/R=0.15 n=128", "[arch]\nshape='circular'\nradius=1.0\nthickness=0.15\nvoussoirs=128\n"),
        ("portal semicircle n=32, 4 courses", "[arch]\nshape='circular'\nradius=1.0\nthickness=0.2\nvoussoirs=32\n[piers]\nheight=1.0\nwidth=0.4\ncourses=4\n"),
        ("portal semicircle n=128, 4 courses", "[arch]\nshape='circular'\nradius=1.0\nthickness=0.2\nvoussoirs=128\n[piers]\nheight=1.0\nwidth=0.4\ncourses=4\n"),
    ];
    for (label, text) in cases {
        let asm = voussoir::scene::build(&scene(text)).expect("valid model");
        let par = KinematicSettings::default();
        let seq = KinematicSettings {
            parallel: false,
            ..KinematicSettings::default()
        };
        let (tp, r) = time(3, || kinematic::analyse(&asm, &par));
        let (ts, _) = time(1, || kinematic::analyse(&asm, &seq));
        match r {
            Ok(r) => println!(
                "{label:<40} {:>6} {:>12} {:>12.8} {:>10.2} {:>10.2}",
                asm.assembly.joints.len(),
                r.candidates,
                r.lambda_upper.unwrap_or(f64::NAN),
                1e3 * tp,
                1e3 * ts
            ),
            Err(e) => println!("{label:<40} error: {e}"),
        }
    }
    println!();
    println!(
        "{:<40} {:>8} {:>7} {:>6} {:>12} {:>10} {:>10}",
        "continuous model", "sections", "refined", "evals", "lambda", "best ms", "1 thread"
    );
    // The continuous model uses the rayon pool (coarse search and refinement); its
    // single-thread time is measured in a pool of one thread.
    let one = match rayon::ThreadPoolBuilder::new().num_threads(1).build() {
        Ok(p) => p,
        Err(e) => panic!("rayon pool: {e}"),
    };
    let geoms = [
        ("semicircle t/R=0.15", "[arch]\nshape='circular'\nradius=1.0\nthickness=0.15\nvoussoirs=16\n"),
        ("segmental 120 deg t/R=0.1", "[arch]\nshape='circular'\nradius=1.0\nembrace_deg=120\nthickness=0.1\nvoussoirs=16\n"),
        ("horseshoe 220 deg t/R=0.3", "[arch]\nshape='circular'\nradius=1.0\nembrace_deg=220\nthickness=0.3\nvoussoirs=16\n"),
        ("pointed e/R=0.25 t/R=0.2", "[arch]\nshape='pointed'\nradius=1.0\neccentricity=0.25\nthickness=0.2\nvoussoirs=16\n"),
        ("basket rise/span=0.35 t=0.2", "[arch]\nshape='basket'\nspan=2.0\nrise=0.7\nthickness=0.2\nvoussoirs=16\n"),
        ("portal semicircle, 4 courses", "[arch]\nshape='circular'\nradius=1.0\nthickness=0.2\nvoussoirs=16\n[piers]\nheight=1.0\nwidth=0.4\ncourses=4\n"),
        ("portal pointed, 1 course", "[arch]\nshape='pointed'\nradius=1.0\neccentricity=0.25\nthickness=0.2\nvoussoirs=16\n[piers]\nheight=1.5\nwidth=0.5\ncourses=1\n"),
        ("portal basket, 4 courses", "[arch]\nshape='basket'\nspan=2.0\nrise=0.7\nthickness=0.2\nvoussoirs=16\n[piers]\nheight=1.0\nwidth=0.4\ncourses=4\n"),
    ];
    for (label, text) in geoms {
        let s = scene(text);
        let (t, r) = time(20, || {
            voussoir::analysis::continuous(&s, voussoir::outcome::Direction::Right)
        });
        let (t1, _) = one.install(|| {
            time(20, || {
                voussoir::analysis::continuous(&s, voussoir::outcome::Direction::Right)
            })
        });
        match r {
            Ok(r) => println!(
                "{label:<40} {:>8} {:>7} {:>6} {:>12.8} {:>10.3} {:>10.3}",
                r.coarse_sections,
                r.refined,
                r.evaluations,
                r.lambda_signed.unwrap_or(f64::NAN),
                1e3 * t,
                1e3 * t1
            ),
            Err(e) => println!("{label:<40} error: {e}"),
        }
    }
    let s = scene("[arch]\nshape='circular'\nradius=1.0\nthickness=0.2\nvoussoirs=16\n");
    let (t, m) = time(1, || voussoir::analysis::continuous_min_thickness(&s));
    if let Ok(m) = m {
        println!(
            "\ncontinuous minimum thickness, semicircle: t/R = {:.6} ({} analyses, {:.1} ms)",
            m.thickness,
            m.iterations,
            1e3 * t
        );
    }
}
