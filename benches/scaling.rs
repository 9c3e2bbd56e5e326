//! How the cost of each method grows with the size of the model, with fitted exponents
//! (least squares on log-log): the exhaustive hinge search against n, the continuous model,
//! DEM time steps per second against the block count, and a sweep of 1000 cases on one and on
//! all cores. Run with `cargo bench --bench scaling`; prints Markdown tables (the figures of
//! docs/performance.md). The static solve has its own bench (`static_solve`).

use std::time::Instant;

use voussoir::analysis::Options;
use voussoir::convergence::loglog_slope;
use voussoir::dem::{IntegrationParameters, Simulation};
use voussoir::kinematic::{self, KinematicSettings};
use voussoir::scene::Scene;
use voussoir::sweep;

fn scene(text: &str) -> Scene {
    Scene::from_toml_str(text, "bench").expect("valid scene")
}

fn semicircle(n: usize) -> Scene {
    scene(&format!(
        "[arch]\nshape = \"circular\"\nradius = 1.0\nthickness = 0.15\nvoussoirs = {n}\n"
    ))
}

/// Median wall time (s) of `reps` runs of `f`, and its last result.
fn time<T>(reps: usize, mut f: impl FnMut() -> T) -> (f64, T) {
    let mut v = Vec::new();
    let mut out = None;
    for _ in 0..reps.max(1) {
        let t = Instant::now();
        out = Some(f());
        v.push(t.elapsed().as_secs_f64());
    }
    v.sort_by(f64::total_cmp);
    (v[v.len() / 2], out.expect("ran at least once"))
}

fn exponent(points: &[(f64, f64)]) -> String {
    loglog_slope(points).map_or("-".into(), |e| format!("{e:.2}"))
}

fn main() {
    // 1. Exhaustive hinge search (one thread, so the exponent is the algorithm's).
    println!("Discrete kinematic search, semicircle t/R = 0.15, one thread\n");
    println!("| n | joints | candidates | lambda_upper | ms |");
    println!("|---:|---:|---:|---:|---:|");
    let mut pts = Vec::new();
    for n in [8usize, 16, 32, 64, 128] {
        let m = voussoir::scene::build(&semicircle(n)).expect("valid model");
        let a = &m.assembly;
        let ks = KinematicSettings {
            parallel: false,
            ..KinematicSettings::default()
        };
        let (t, r) = time(if n <= 32 { 9 } else { 3 }, || kinematic::analyse(&m, &ks));
        let r = r.expect("kinematic search");
        println!(
            "| {n} | {} | {} | {:.6} | {:.3} |",
            a.joints.len(),
            r.candidates,
            r.lambda_upper.unwrap_or(f64::NAN),
            t * 1e3
        );
        pts.push((a.joints.len() as f64, t));
    }
    let big: Vec<_> = pts.iter().copied().filter(|p| p.0 >= 30.0).collect();
    println!(
        "\nfitted exponent (joints >= 33): time ~ joints^{}\n",
        exponent(&big)
    );

    // 2. The continuous model: its cost does not depend on n (hinges anywhere).
    println!("Continuous model (independent of n)\n");
    println!("| geometry | lambda_continuous | evaluations | ms |");
    println!("|---|---:|---:|---:|");
    for (label, text) in [
        ("semicircle t/R = 0.15", "[arch]\nshape='circular'\nradius=1.0\nthickness=0.15\nvoussoirs=16\n"),
        ("pointed e/R = 0.25, t/R = 0.2", "[arch]\nshape='pointed'\nradius=1.0\neccentricity=0.25\nthickness=0.2\nvoussoirs=16\n"),
        ("basket rise/span = 0.35", "[arch]\nshape='basket'\nspan=2.0\nrise=0.7\nthickness=0.2\nvoussoirs=16\n"),
        ("portal, 4 courses", "[arch]\nshape='circular'\nradius=1.0\nthickness=0.2\nvoussoirs=16\n[piers]\nheight=1.0\nwidth=0.4\ncourses=4\n"),
    ] {
        let s = scene(text);
        let (t, r) = time(21, || voussoir::analysis::continuous(&s, voussoir::outcome::Direction::Right));
        let r = r.expect("continuous model");
        println!(
            "| {label} | {:.6} | {} | {:.3} |",
            r.lambda_continuous.unwrap_or(f64::NAN),
            r.evaluations,
            t * 1e3
        );
    }

    // 3. DEM time steps per second against the number of blocks (settled arch under
    // gravity and lambda = 0.05: every joint in contact, the normal working state).
    println!("\nDEM steps per second, semicircle t/R = 0.15 under gravity + 0.05 W, one thread\n");
    println!("| blocks | active contacts | time step (s) | steps/s | block-steps/s |");
    println!("|---:|---:|---:|---:|---:|");
    let mut pts = Vec::new();
    for n in [8usize, 16, 32, 64, 128, 256] {
        let m = voussoir::scene::build(&semicircle(n)).expect("valid model");
        let a = &m.assembly;
        let p = IntegrationParameters::for_assembly(a);
        let mut sim = Simulation::new(&m, &p).expect("simulation");
        sim.set_load(1.0, 0.05);
        let steps = (400_000 / n).max(2000);
        let (t, _) = time(3, || {
            for _ in 0..steps {
                sim.step();
            }
        });
        let rate = steps as f64 / t;
        println!(
            "| {} | {} | {:.2e} | {:.0} | {:.2e} |",
            a.blocks.len(),
            sim.active_contacts(),
            sim.time_step(),
            rate,
            rate * a.blocks.len() as f64
        );
        pts.push((a.blocks.len() as f64, 1.0 / rate));
    }
    println!(
        "\nfitted exponent: time per step ~ blocks^{} (the explicit step is O(blocks); the stable time step also shrinks with the joint length, so a run of fixed duration costs more)\n",
        exponent(&pts)
    );

    // 4. A sweep of 1000 cases (static + kinematic, as `voussoir sweep` runs them).
    println!("Sweep of 1000 cases: semicircle, n = 32, t/R 0.10..0.30 (40) x embrace 120..240 deg (25)\n");
    println!("| threads | wall s | cases/s | collapse | cannot_stand | error |");
    println!("|---:|---:|---:|---:|---:|---:|");
    let base = semicircle(32);
    let vars = [
        sweep::parse_variation("t/R=0.1:0.295:0.005").expect("variation"),
        sweep::parse_variation("arch.embrace_deg=120:240:5").expect("variation"),
    ];
    let cases = sweep::cases(&base, &vars);
    let options = Options::default();
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
    let mut threads = vec![1];
    if cores > 1 {
        threads.push(cores);
    }
    for th in threads {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(th)
            .build()
            .expect("thread pool");
        let t = Instant::now();
        let rows =
            pool.install(|| sweep::run(&cases, |v, s| sweep::case(v, s, &options, false), &|| {}));
        let wall = t.elapsed().as_secs_f64();
        let count = |st: &str| rows.iter().filter(|r| r.status == st).count();
        println!(
            "| {th} | {wall:.2} | {:.0} | {} | {} | {} |",
            rows.len() as f64 / wall,
            count("collapse"),
            count("cannot_stand"),
            count("error")
        );
    }
}
