//! Both bounds at the physical limit (issue 10's benchmark): the static bound with its
//! certified upper bound as `analyze` runs them, the minimum thickness with its kinematic
//! cross-check, and the paper-style sweep with both bounds. Plain `harness = false` program
//! printing Markdown tables; run with `cargo bench --bench limit`. Targets: static + certified
//! n = 64 <= 0.05 ms and n = 1000 <= 0.5 ms (one thread, growth ~ n^1); min-thickness of a
//! 100-joint chain <= 50 ms; the 2,000-case sweep >= 20,000 cases/s on two threads; a live
//! action (the adequacy factor) at n = 64 and 1000 costs about what a seismic one does.

mod common;

use common::median as time;

use voussoir::analysis::{self, Options};
use voussoir::convergence::loglog_slope;
use voussoir::scene::Scene;
use voussoir::sweep;

fn semicircle(n: usize) -> Scene {
    Scene::from_toml_str(
        &format!("[arch]\nshape = \"circular\"\nradius = 1.0\nthickness = 0.15\nvoussoirs = {n}\n"),
        "bench",
    )
    .expect("valid scene")
}

fn main() {
    let one = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .expect("thread pool");

    // 1. Static bound + certified upper bound, from the scene (model build included).
    println!("Static + certified upper bound (`analysis::analyse`, defaults), semicircle t/R = 0.15, one thread, median\n");
    println!(
        "| n | lambda_lower | lambda_upper | upper bound | build ms | analyse ms | total ms |"
    );
    println!("|---:|---:|---:|---|---:|---:|---:|");
    let options = Options::default();
    let mut pts = Vec::new();
    for n in [16usize, 64, 256, 1000, 4000, 20000] {
        let scene = semicircle(n);
        let reps = (20_000 / n).clamp(5, 2000);
        let (tb, _) = time(reps, || voussoir::scene::build(&scene).expect("model"));
        let (ta, a) = one.install(|| time(reps, || analysis::analyse(&scene, &options)));
        let a = a.expect("analysis");
        println!(
            "| {n} | {:.9} | {:.9} | {} | {:.4} | {:.4} | {:.4} |",
            a.lower.lambda.unwrap_or(f64::NAN),
            a.lambda_upper().unwrap_or(f64::NAN),
            a.kinematic_search.map_or("none", |k| k.as_str()),
            tb * 1e3,
            (ta - tb).max(0.0) * 1e3,
            ta * 1e3
        );
        if n >= 64 {
            pts.push((n as f64, ta));
        }
    }
    println!(
        "\nfitted exponent (n >= 64): total ~ n^{}\n",
        loglog_slope(&pts).map_or("-".into(), |e| format!("{e:.2}"))
    );

    // 1b. A live action costs what a seismic one does: the same semicircle with a point load
    //     near quarter span, as a live load (the adequacy factor) and as a permanent load
    //     under the seismic action.
    println!("Live against seismic action (`analysis::analyse`, defaults), semicircle t/R = 0.15 with a 1 kN point load near quarter span, one thread, median\n");
    println!("| n | action | lambda_lower | lambda_upper | upper bound | total ms |");
    println!("|---:|---|---:|---:|---|---:|");
    for n in [64usize, 1000] {
        let bare = voussoir::scene::build(&semicircle(n)).expect("model");
        let at = bare
            .assembly
            .blocks
            .iter()
            .map(|b| b.centroid)
            .min_by(|p, q| (p.x + 0.5).abs().total_cmp(&(q.x + 0.5).abs()))
            .expect("a voussoir");
        let reps = (20_000 / n).clamp(5, 2000);
        for (action, flag) in [("seismic", "seismic = false"), ("live", "live = true")] {
            let text = format!(
                "[arch]\nshape = \"circular\"\nradius = 1.0\nthickness = 0.15\nvoussoirs = {n}\n[action]\nkind = \"{action}\"\n[[loads]]\ntype = \"point\"\nat = [{:?}, {:?}]\nforce = [0.0, -1000.0]\n{flag}\n",
                at.x, at.y
            );
            let scene = Scene::from_toml_str(&text, "bench").expect("valid scene");
            let (ta, a) = one.install(|| time(reps, || analysis::analyse(&scene, &options)));
            let a = a.expect("analysis");
            println!(
                "| {n} | {action} | {:.9} | {:.9} | {} | {:.4} |",
                a.lower.lambda.unwrap_or(f64::NAN),
                a.lambda_upper().unwrap_or(f64::NAN),
                a.kinematic_search.map_or("none", |k| k.as_str()),
                ta * 1e3
            );
        }
    }
    println!();

    // 2. Minimum thickness with its kinematic cross-check.
    println!("Minimum thickness with the kinematic cross-check (`thickness::analyse`, defaults), one thread, median\n");
    println!("| n | joints | t_min static | t_min kinematic | search | static analyses | ms |");
    println!("|---:|---:|---:|---:|---|---:|---:|");
    for n in [16usize, 99, 400] {
        let scene = semicircle(n);
        let (t, r) = one.install(|| time(9, || voussoir::thickness::analyse(&scene, &options)));
        let r = r.expect("thickness");
        println!(
            "| {n} | {} | {:.9} | {:.9} | {} | {} | {:.2} |",
            n + 1,
            r.lower.search.min_thickness.unwrap_or(f64::NAN),
            r.kinematic
                .as_ref()
                .and_then(|k| k.min_thickness)
                .unwrap_or(f64::NAN),
            r.kinematic_search.map_or("none", |k| k.as_str()),
            r.lower.search.evaluations,
            t * 1e3
        );
    }

    // 3. The paper-style sweep with both bounds.
    let base = semicircle(32);
    let vars = [
        sweep::parse_variation("t/R=0.11:0.5:0.01").expect("variation"),
        sweep::parse_variation("arch.embrace_deg=120:240:5").expect("variation"),
        sweep::parse_variation("arch.voussoirs=32,64").expect("variation"),
    ];
    let cases = sweep::cases(&base, &vars);
    println!(
        "\nSweep of {} cases: semicircle t/R 0.11..0.5 x embrace 120..240 deg x n {{32, 64}}, both bounds\n",
        cases.len()
    );
    println!("| threads | wall s (median of 5) | cases/s | collapse | bounds within 1e-9 | cannot_stand | error |");
    println!("|---:|---:|---:|---:|---:|---:|---:|");
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
        let (wall, rows) = pool.install(|| {
            time(5, || {
                sweep::run(&cases, |v, s| sweep::case(v, s, &options, false), &|| {})
            })
        });
        let count = |f: &dyn Fn(&sweep::SweepRow) -> bool| rows.iter().filter(|r| f(r)).count();
        println!(
            "| {th} | {wall:.3} | {:.0} | {} | {} | {} | {} |",
            rows.len() as f64 / wall,
            count(&|r| r.status == "collapse"),
            count(&|r| r.gap().is_some_and(|g| g <= 1e-9)),
            count(&|r| r.status == "cannot_stand"),
            count(&|r| r.status == "error")
        );
    }
}
