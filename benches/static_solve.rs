//! Cost of the full static program (three unknowns per joint, Clarabel) against the number of voussoirs (semicircle,
//! t/R = 0.15, n = 16 .. 2000), split into its parts, with fitted growth exponents; then, at
//! n = 1000, Clarabel settings that trade work for robustness. Run with
//! `cargo bench --bench static_solve`. One thread; each figure is the median of repeated runs.
//!
//! A plain table (`harness = false`) rather than criterion: the quantities are milliseconds
//! to seconds, a median of a few runs is stable enough, the exponents need our own fit, and
//! criterion would add a dependency tree to build for every CI run.

use std::time::Instant;

use clarabel::solver::{DefaultSettingsBuilder, DefaultSolver, IPSolver};
use voussoir::convergence::loglog_slope;
use voussoir::scene::Scene;
use voussoir::statics::{self, Objective, StaticProblem, StaticSettings};

fn semicircle(n: usize) -> Scene {
    Scene::from_toml_str(
        &format!("[arch]\nshape = \"circular\"\nradius = 1.0\nthickness = 0.15\nvoussoirs = {n}\n"),
        "bench",
    )
    .expect("valid scene")
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

/// Clarabel's settings as `statics::analyse` makes them, adjusted by `f`.
fn settings(
    linear_solver: &str,
    f: impl Fn(&mut DefaultSettingsBuilder<f64>),
) -> clarabel::solver::DefaultSettings<f64> {
    let d = StaticSettings::default();
    let mut b = DefaultSettingsBuilder::default();
    b.verbose(false)
        .tol_gap_abs(d.tol_gap)
        .tol_gap_rel(d.tol_gap)
        .tol_feas(d.tol_feas)
        .max_iter(d.max_iter)
        .direct_solve_method(linear_solver.to_string());
    f(&mut b);
    b.build().expect("valid settings")
}

/// n, statics::analyse time, time per iteration, iterations, setup time.
type Row = (f64, f64, f64, f64, f64);

struct Split {
    assembly: f64,
    build: f64,
    setup: f64,
    solve: f64,
    iterations: u32,
    lambda: f64,
    nnz_kkt: usize,
    nnz_l: usize,
}

/// One solve, timed part by part: assembly, program, Clarabel's setup (equilibration, KKT
/// assembly, AMD ordering, symbolic factorisation), and its iterations.
fn split(scene: &Scene, s: clarabel::solver::DefaultSettings<f64>) -> Split {
    let t0 = Instant::now();
    let m = voussoir::scene::build(scene).expect("valid model");
    let t1 = Instant::now();
    let p = StaticProblem::new(
        &m.assembly,
        &m.loads,
        Objective::MaxLambda {
            sign: 1.0,
            cap: None,
        },
    );
    let t2 = Instant::now();
    let mut solver = DefaultSolver::new(&p.p, &p.q, &p.a, &p.b, &p.cones, s).expect("solver setup");
    let t3 = Instant::now();
    solver.solve();
    let t4 = Instant::now();
    Split {
        assembly: (t1 - t0).as_secs_f64(),
        build: (t2 - t1).as_secs_f64(),
        setup: (t3 - t2).as_secs_f64(),
        solve: (t4 - t3).as_secs_f64(),
        iterations: solver.solution.iterations,
        lambda: solver.solution.x[0],
        nnz_kkt: solver.info.linsolver.nnzA,
        nnz_l: solver.info.linsolver.nnzL,
    }
}

fn main() {
    let ns = [16usize, 32, 64, 128, 256, 512, 1000, 2000];
    println!("Static solve, semicircle t/R = 0.15 (median of repeated runs, one thread)\n");
    println!("| n | lambda_lower | iter | KKT nnz | L nnz | assembly ms | build ms | setup ms | iterations ms | ms/iter | statics::analyse_full ms |");
    println!("|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|");
    let mut rows = Vec::new();
    for n in ns {
        let scene = semicircle(n);
        let reps = (4000 / n).clamp(5, 60);
        let mut parts = Vec::new();
        for _ in 0..reps {
            parts.push(split(&scene, settings("qdldl", |_| {})));
        }
        let m = |f: fn(&Split) -> f64| median(parts.iter().map(f).collect());
        let (asm, build, setup, solve) = (
            m(|s| s.assembly),
            m(|s| s.build),
            m(|s| s.setup),
            m(|s| s.solve),
        );
        let it = parts[0].iterations;
        let full = median(
            (0..reps)
                .map(|_| {
                    let t = Instant::now();
                    let m = voussoir::scene::build(&scene).expect("valid model");
                    statics::analyse_full(&m, &StaticSettings::default()).expect("solves");
                    t.elapsed().as_secs_f64()
                })
                .collect(),
        );
        println!(
            "| {n} | {:.6} | {it} | {} | {} | {:.3} | {:.3} | {:.3} | {:.3} | {:.4} | {:.3} |",
            parts[0].lambda,
            parts[0].nnz_kkt,
            parts[0].nnz_l,
            asm * 1e3,
            build * 1e3,
            setup * 1e3,
            solve * 1e3,
            solve * 1e3 / it as f64,
            full * 1e3
        );
        rows.push((n as f64, full, solve / it as f64, it as f64, setup));
    }
    let fit = |f: fn(&Row) -> f64| {
        let pts: Vec<(f64, f64)> = rows
            .iter()
            .filter(|r| r.0 >= 64.0)
            .map(|r| (r.0, f(r)))
            .collect();
        loglog_slope(&pts).map_or("-".to_string(), |e| format!("{e:.2}"))
    };
    println!(
        "\nfitted exponents (n >= 64, least squares on log-log): statics::analyse_full n^{}, ms per iteration n^{}, iterations n^{}, setup n^{}",
        fit(|r| r.1),
        fit(|r| r.2),
        fit(|r| r.3),
        fit(|r| r.4)
    );

    // What Clarabel's robustness machinery costs at n = 1000. The defaults stay: iterative
    // refinement and static regularisation protect the solves near the minimum thickness.
    println!("\nClarabel settings at n = 1000 (setup + iterations, median)\n");
    println!("| setting | iter | lambda | ms |");
    println!("|---|---:|---:|---:|");
    let scene = semicircle(1000);
    type Tweak = fn(&mut DefaultSettingsBuilder<f64>);
    let tweaks: [(&str, &str, Tweak); 6] = [
        (
            "default (qdldl, IR reltol 1e-13, reg 1e-8)",
            "qdldl",
            |_| {},
        ),
        ("no iterative refinement", "qdldl", |b| {
            b.iterative_refinement_enable(false);
        }),
        ("IR tolerance 1e-10", "qdldl", |b| {
            b.iterative_refinement_reltol(1e-10)
                .iterative_refinement_abstol(1e-10);
        }),
        ("static regularisation 1e-10", "qdldl", |b| {
            b.static_regularization_constant(1e-10);
        }),
        ("no equilibration", "qdldl", |b| {
            b.equilibrate_enable(false);
        }),
        ("no presolve", "qdldl", |b| {
            b.presolve_enable(false);
        }),
    ];
    for (name, ls, f) in tweaks {
        let parts: Vec<Split> = (0..9).map(|_| split(&scene, settings(ls, f))).collect();
        println!(
            "| {name} | {} | {:.12} | {:.3} |",
            parts[0].iterations,
            parts[0].lambda,
            median(parts.iter().map(|s| s.setup + s.solve).collect()) * 1e3
        );
    }

    reduced_against_full();
}

/// The chain's reduced program (four unknowns, `statics::analyse_chain`) against the full one.
fn reduced_against_full() {
    println!("\nReduced chain program (lambda, H, V, M0) against the full program, semicircle t/R = 0.15 (median, one thread)\n");
    println!(
        "| n | lambda full | lambda reduced (exact vertex) | full ms | reduced ms | speed-up |"
    );
    println!("|---:|---:|---:|---:|---:|---:|");
    let settings = voussoir::statics::StaticSettings::default();
    for n in [16usize, 64, 256, 1000, 4000, 20000] {
        let m = voussoir::scene::build(&semicircle(n)).expect("valid model");
        let reps = if n >= 4000 { 3 } else { 9 };
        let time = |f: &dyn Fn() -> f64| -> (f64, f64) {
            let mut ts = Vec::new();
            let mut l = 0.0;
            for _ in 0..reps {
                let t = Instant::now();
                l = f();
                ts.push(t.elapsed().as_secs_f64());
            }
            (l, median(ts))
        };
        let (lf, tf) = time(&|| {
            voussoir::statics::analyse_full(&m, &settings)
                .expect("full")
                .lambda
                .unwrap_or(f64::NAN)
        });
        let (lr, tr) = time(&|| {
            voussoir::statics::analyse_chain(&m, &settings)
                .expect("reduced")
                .lambda
                .unwrap_or(f64::NAN)
        });
        println!(
            "| {n} | {lf:.12} | {lr:.12} | {:.3} | {:.3} | {:.0}x |",
            tf * 1e3,
            tr * 1e3,
            tf / tr
        );
    }
}
