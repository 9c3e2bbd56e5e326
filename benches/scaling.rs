//! How the cost of each method grows with the size of the model, with fitted exponents
//! (least squares on log-log): the exhaustive hinge search against n, the continuous model,
//! DEM time steps per second against the block count, and a sweep of 96,641 cases on 1, 2, 4,
//! 8 and 16 threads (as many as the machine has cores; `VOUSSOIR_BENCH_THREADS=1,2,16` names
//! others). Run with `cargo bench --bench scaling`; prints Markdown tables (the figures of
//! docs/performance.md). `cargo bench --bench scaling -- sweep` prints the sweep's table
//! alone; `benches/sweep_scaling.sh` times the same sweep through the CLI, process and file
//! included. The static solve has its own bench (`static_solve`).

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
    // `cargo bench --bench scaling -- sweep`: the sweep table alone.
    if std::env::args().skip(1).any(|a| a == "sweep") {
        sweep_on_every_core();
        return;
    }
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

    // 4. A sweep near the largest allowed, through the CLI's pipeline, on 1 to 16 threads.
    sweep_on_every_core();
}

/// Thread counts of the sweep table: 1, 2, 4, 8, 16 up to the machine's cores (more threads
/// than cores measure the scheduler, not the sweep), or the counts in VOUSSOIR_BENCH_THREADS
/// (`1,2,16`).
fn thread_counts() -> Vec<usize> {
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
    if let Ok(list) = std::env::var("VOUSSOIR_BENCH_THREADS") {
        let given: Vec<usize> = list
            .split(',')
            .filter_map(|t| t.trim().parse().ok())
            .filter(|&t| t > 0)
            .collect();
        if !given.is_empty() {
            return given;
        }
    }
    let mut counts: Vec<usize> = [1, 2, 4, 8, 16]
        .into_iter()
        .filter(|&t| t <= cores)
        .collect();
    if !counts.contains(&cores) && cores < 16 {
        counts.push(cores);
    }
    counts
}

/// Issue 28's "sweeps on every core": the whole pipeline of `voussoir sweep` (the plan, the
/// cases built and solved, the CSV, the rows freed) on a pool of 1, 2, 4, ... threads, with
/// the time of each phase. Targets: at least 1.8x on 2 threads and 10x on 16 against one.
fn sweep_on_every_core() {
    let base = semicircle(32);
    let vars = vec![
        sweep::parse_variation("t/R=0.1:0.5:0.001").expect("variation"),
        sweep::parse_variation("arch.embrace_deg=120:240:0.5").expect("variation"),
    ];
    let options = Options::default();
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
    println!(
        "Sweep of {} cases (`voussoir sweep data/semicircular.toml --vary t/R=0.1:0.5:0.001 --vary arch.embrace_deg=120:240:0.5`, the CLI's pipeline without process start and file), {cores} cores, median of 3\n",
        sweep::case_count(&vars).unwrap_or(0)
    );
    println!("| threads | plan s | cases s | csv s | free s | wall s | cases/s | speed-up | collapse | cannot_stand | error |");
    println!("|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|");
    let mut first = None;
    for th in thread_counts() {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(th)
            .build()
            .expect("thread pool");
        let mut runs: Vec<[f64; 5]> = Vec::new();
        let mut counts = [0; 3];
        for _ in 0..3 {
            pool.install(|| {
                let t0 = Instant::now();
                let plan = sweep::Sweep::new(&base, vars.clone()).expect("valid sweep");
                let t1 = Instant::now();
                let rows = plan.run(&options, false, &|| {});
                let t2 = Instant::now();
                let mut csv = Vec::new();
                sweep::write_csv(&mut csv, plan.variations(), &rows).expect("csv");
                let t3 = Instant::now();
                sweep::free_rows(rows);
                let t4 = Instant::now();
                let s = |a: Instant, b: Instant| (b - a).as_secs_f64();
                runs.push([s(t0, t1), s(t1, t2), s(t2, t3), s(t3, t4), s(t0, t4)]);
                // The statuses, read back from the CSV (outside the times).
                let text = String::from_utf8_lossy(&csv);
                let count = |st: &str| text.matches(&format!(",{st},")).count();
                counts = [count("collapse"), count("cannot_stand"), count("error")];
            });
        }
        runs.sort_by(|a, b| a[4].total_cmp(&b[4]));
        let [plan, cases, csv, free, wall] = runs[runs.len() / 2];
        let one = *first.get_or_insert(wall);
        let n = sweep::case_count(&vars).unwrap_or(0) as f64;
        println!(
            "| {th} | {plan:.3} | {cases:.3} | {csv:.3} | {free:.3} | {wall:.3} | {:.0} | {:.2}x | {} | {} | {} |",
            n / wall,
            one / wall,
            counts[0],
            counts[1],
            counts[2]
        );
    }
    println!("\nTargets (issue 28): speed-up >= 1.8x on 2 threads, >= 10x on 16 (an idle machine of 16 cores).");
}
