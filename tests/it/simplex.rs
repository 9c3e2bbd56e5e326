//! The dual simplex of `statics::simplex` (issue 25's warm-started programs on assemblies
//! that are not chains) against Clarabel on the very same static programs: the fixed-shear
//! programs of the non-associative iteration on a running-bond wall, an arcade, portals, two
//! blocks side by side and a tied portal, cold and warm-started from one program to the next.

use crate::common::*;
#[allow(dead_code)] // the benches' scene builders; only the wall is used here
#[path = "../../benches/common/mod.rs"]
mod bench_common;
use clarabel::solver::{DefaultSettingsBuilder, DefaultSolver, IPSolver, SolverStatus};
use voussoir::interaction::contact::ShearLimit;
use voussoir::model::Model;
use voussoir::scene::Scene;
use voussoir::statics::simplex::{self, BoundedLp, DualSimplex, LpOutcome};
use voussoir::statics::{self, Objective, StaticProblem, StaticSettings, LAMBDA_CAP};

/// Clarabel on `p` at a tight tolerance: its status and `q'x`.
fn clarabel(p: &StaticProblem) -> (SolverStatus, f64, Vec<f64>) {
    let settings = DefaultSettingsBuilder::default()
        .verbose(false)
        .tol_gap_abs(1e-12)
        .tol_gap_rel(1e-12)
        .tol_feas(1e-12)
        .max_iter(400)
        .build()
        .expect("settings");
    let mut solver =
        DefaultSolver::new(&p.p, &p.q, &p.a, &p.b, &p.cones, settings).expect("Clarabel setup");
    solver.solve();
    let s = &solver.solution;
    let obj = p.q.iter().zip(&s.x).map(|(a, b)| a * b).sum();
    (s.status, obj, s.x.clone())
}

/// The largest violation of `A x + s = b, s in K` by `x` (zero cone, then nonnegative).
fn violation(p: &StaticProblem, x: &[f64]) -> f64 {
    let mut ax = vec![0.0; p.b.len()];
    for (j, xj) in x.iter().enumerate().take(p.a.n) {
        for k in p.a.colptr[j]..p.a.colptr[j + 1] {
            ax[p.a.rowval[k]] += p.a.nzval[k] * xj;
        }
    }
    ax.iter()
        .zip(&p.b)
        .enumerate()
        .map(|(i, (a, b))| {
            if i < p.equality_rows {
                (a - b).abs()
            } else {
                (a - b).max(0.0)
            }
        })
        .fold(0.0, f64::max)
}

fn program(m: &Model, capacity: &[f64], objective: Objective) -> StaticProblem {
    StaticProblem::with_shear_limit(
        &m.assembly,
        &m.loads,
        m.strength,
        &m.ties,
        &m.strips,
        &m.passive,
        ShearLimit::Fixed(capacity),
        objective,
    )
}

fn polygons(rects: &[[f64; 4]], mu: f64, extra: &str) -> Scene {
    scene(&format!(
        "[blocks]\npolygons = {}\n[material]\nfriction = {mu}\n{extra}",
        rect_polygons(rects)
    ))
}

/// A running-bond wall of `courses` courses of `per` blocks 0.4 x 0.2 m (the benches' wall).
fn wall(courses: usize, per: usize, mu: f64) -> Scene {
    let rects: Vec<[f64; 4]> = bench_common::running_bond_wall(courses, per)
        .iter()
        .map(|p| [p[0][0], p[0][1], p[2][0], p[2][1]])
        .collect();
    polygons(&rects, mu, "")
}

/// `data/arcade.toml` with two bays of 8 voussoirs and friction 0.4.
fn two_bay_arcade() -> Model {
    let arcade = std::fs::read_to_string(data("arcade.toml")).expect("bundled arcade");
    model_of(&scene(
        &arcade
            .replace("friction = inf", "friction = 0.4")
            .replace("bays = 3", "bays = 2")
            .replace("voussoirs = 16", "voussoirs = 8"),
    ))
}

fn cases() -> Vec<(&'static str, Model)> {
    let portal = [
        [0.0, 0.0, 0.6, 1.2],
        [1.8, 0.0, 2.4, 1.2],
        [0.0, 1.2, 2.4, 1.6],
    ];
    vec![
        ("wall 6 x 8", model_of(&wall(6, 8, 0.6))),
        (
            "wall 3 x 2",
            model_of(&polygons(&running_bond_wall_rects(), 0.7, "")),
        ),
        ("lintel portal", model_of(&polygons(&portal, 0.55, ""))),
        (
            "tied lintel portal",
            model_of(&polygons(
                &portal,
                0.4,
                "[[ties]]\nfrom = [0.3, 1.0]\nto = [2.1, 1.0]\ncapacity = 3000.0\n",
            )),
        ),
        (
            "two blocks side by side",
            model_of(&polygons(
                &[[-0.5, 0.0, 0.0, 2.0], [0.0, 0.0, 0.5, 2.0]],
                0.6,
                "",
            )),
        ),
        (
            "stepped buttresses",
            model_of(
                &Scene::from_file(&data("blocks_stepped_buttresses.toml"))
                    .expect("bundled scene")
                    .with_overrides(&["material.friction=0.4".to_string()])
                    .expect("override"),
            ),
        ),
        ("2-bay arcade", two_bay_arcade()),
    ]
}

/// Solve `lp` in the simplex kept in `slot` (a warm start from its last basis when there is
/// one).
fn warm_solve(slot: &mut Option<DualSimplex>, lp: BoundedLp) -> LpOutcome {
    match slot {
        Some(w) => {
            w.update(lp);
            w.solve()
        }
        None => slot.insert(DualSimplex::new(lp)).solve(),
    }
}

/// The simplex alone against Clarabel (at 1e-12) on the non-associative iteration's
/// programs: capacities `mu N` from the associative solution, scaled up and down unevenly
/// joint by joint, each program solved from the slack basis (cold) and from the last
/// program's basis (warm). Where Clarabel finds an optimum the simplex finds the same
/// multiplier to 1e-9 (relative), with its unknowns satisfying every row to 1e-9, or says
/// it cannot decide (then the caller asks Clarabel): never another number. Where Clarabel
/// finds the program infeasible the simplex never answers an optimum. The least-friction
/// programs (the multiplier fixed a hair below the optimum) likewise, where Clarabel solves
/// them to its tolerance. The warm solves take fewer pivots than the cold ones.
#[test]
fn the_simplex_gives_clarabels_optimum_cold_and_warm() {
    let (mut optimal, mut undecided, mut infeasible) = (0, 0, 0);
    let (mut warm_pivots, mut cold_pivots) = (0, 0);
    let mut worst: f64 = 0.0;
    for (name, m) in cases() {
        let s = StaticSettings::default();
        let a = statics::analyse(&m, &s).expect("static");
        let n: Vec<f64> = a.forces.expect("collapse").iter().map(|f| f.n).collect();
        let mu: Vec<f64> = m.assembly.joints.iter().map(|j| j.friction).collect();
        let (mut warm, mut warm_least) = (None, None);
        for (i, scale) in [1.0, 0.9, 1.1, 0.7, 1.3, 1.0].into_iter().enumerate() {
            let capacity: Vec<f64> = n
                .iter()
                .zip(&mu)
                .enumerate()
                .map(|(k, (n, mu))| mu * n * scale * (1.0 + 0.05 * ((k + i) % 3) as f64))
                .collect();
            let cap = Some(LAMBDA_CAP);
            let p = program(&m, &capacity, Objective::MaxLambda { sign: 1.0, cap });
            let (status, obj, _) = clarabel(&p);
            let lp = BoundedLp::from_problem(&p).expect("a linear program");
            let cold = DualSimplex::new(lp.clone()).solve();
            let hot = warm_solve(&mut warm, lp);
            for (what, out) in [("cold", &cold), ("warm", &hot)] {
                let case = format!("{name}, scale {scale}, {what}: {out:?} vs Clarabel {status:?}");
                match (status, out) {
                    (
                        SolverStatus::Solved | SolverStatus::AlmostSolved,
                        LpOutcome::Optimal(sol),
                    ) => {
                        let diff = (sol.objective - obj).abs() / obj.abs().max(1.0);
                        assert!(diff <= 1e-9, "{case}: {} vs {obj}", sol.objective);
                        assert!((sol.x[0] + sol.objective).abs() <= 1e-15, "{case}");
                        assert!(violation(&p, &sol.x) <= 1e-9, "{case}");
                        worst = worst.max(diff);
                        optimal += 1;
                    }
                    (SolverStatus::PrimalInfeasible, LpOutcome::Infeasible) => infeasible += 1,
                    (_, LpOutcome::Undecided(_)) => undecided += 1,
                    _ => panic!("{case}"),
                }
            }
            if let (LpOutcome::Optimal(c), LpOutcome::Optimal(w)) = (&cold, &hot) {
                if i > 0 {
                    cold_pivots += c.pivots;
                    warm_pivots += w.pivots;
                }
            }
            // The least-friction program at the multiplier found.
            let LpOutcome::Optimal(sol) = &hot else {
                continue;
            };
            let lambda = sol.x[0];
            let below = lambda - 1e-9 * lambda.abs().max(1.0);
            let p2 = program(
                &m,
                &capacity,
                Objective::LeastFriction {
                    sign: 1.0,
                    lambda: below,
                },
            );
            let (st2, obj2, _) = clarabel(&p2);
            let lp2 = BoundedLp::from_problem(&p2).expect("a linear program");
            match (st2, warm_solve(&mut warm_least, lp2)) {
                (SolverStatus::Solved, LpOutcome::Optimal(sol)) => {
                    let diff = (sol.objective - obj2).abs() / obj2.abs().max(1.0);
                    assert!(
                        diff <= 1e-9,
                        "{name} least friction: {} vs {obj2}",
                        sol.objective
                    );
                    assert!(violation(&p2, &sol.x) <= 1e-9, "{name} least friction");
                    worst = worst.max(diff);
                    optimal += 1;
                }
                // Clarabel short of its tolerance (AlmostSolved) is no reference to 1e-9.
                (_, LpOutcome::Optimal(sol)) => {
                    assert!(violation(&p2, &sol.x) <= 1e-9, "{name} least friction");
                }
                (_, LpOutcome::Undecided(_)) => undecided += 1,
                (st, out) => panic!("{name} least friction: {out:?} vs Clarabel {st:?}"),
            }
        }
    }
    println!(
        "{optimal} optima (largest difference {worst:.1e}), {infeasible} infeasible, {undecided} undecided; warm {warm_pivots} pivots, cold {cold_pivots}"
    );
    assert!(infeasible >= 1, "no infeasible program met");
    assert!(
        undecided * 10 <= optimal,
        "{undecided} undecided of {optimal}"
    );
    assert!(
        warm_pivots * 2 < cold_pivots,
        "warm {warm_pivots}, cold {cold_pivots}"
    );
}

/// A program unbounded above (lambda in no row: the load toward `sign = 0`, no cap): the
/// simplex does not answer an optimum (Clarabel says dual infeasible).
#[test]
fn an_unbounded_program_is_not_answered() {
    let m = model_of(&polygons(&running_bond_wall_rects(), 0.7, ""));
    let capacity = vec![1e3; m.assembly.joints.len()];
    let p = program(
        &m,
        &capacity,
        Objective::MaxLambda {
            sign: 0.0,
            cap: None,
        },
    );
    let (status, _, _) = clarabel(&p);
    assert!(
        matches!(
            status,
            SolverStatus::DualInfeasible | SolverStatus::AlmostDualInfeasible
        ),
        "{status:?}"
    );
    let out = simplex::solve(&p).expect("a linear program");
    assert!(matches!(out, LpOutcome::Undecided(_)), "{out:?}");
}

/// The second program of the simplex path: among the optima of the first, the equilibrium
/// nearest a centre (`BoundedLp::nearest`). With the first program's own optimum as the
/// centre it returns that optimum (distance 0); with another centre, an optimum at the
/// multiplier fixed a hair below, at least as near the centre as the first program's vertex.
#[test]
fn the_nearest_optimum_is_an_optimum_and_nearest() {
    let m = model_of(&wall(6, 8, 0.6));
    let a = statics::analyse(&m, &StaticSettings::default()).expect("static");
    let n: Vec<f64> = a.forces.expect("collapse").iter().map(|f| f.n).collect();
    let capacity: Vec<f64> = n.iter().map(|n| 0.6 * n).collect();
    let cap = Some(LAMBDA_CAP);
    let p = program(&m, &capacity, Objective::MaxLambda { sign: 1.0, cap });
    let lp = BoundedLp::from_problem(&p).expect("linear");
    let LpOutcome::Optimal(first) = DualSimplex::new(lp.clone()).solve() else {
        panic!("no optimum")
    };
    let lambda = first.x[0];
    let below = lambda - 1e-9 * lambda.abs().max(1.0);
    let columns: Vec<usize> = (0..m.assembly.joints.len())
        .flat_map(|j| [statics::column(j, 0), statics::column(j, 1)])
        .collect();
    let zero = vec![0.0; columns.len()];
    let distance = |x: &[f64], centre: &[f64]| -> f64 {
        columns
            .iter()
            .zip(centre)
            .map(|(&k, c)| (x[k] - c).abs())
            .sum()
    };
    // The first optimum as the centre.
    let own: Vec<f64> = columns.iter().map(|&k| first.x[k]).collect();
    let near = lp.nearest(lambda, &columns, &own, &zero, 1.0);
    let LpOutcome::Optimal(s) = DualSimplex::new(near).solve() else {
        panic!("no optimum")
    };
    assert!(distance(&s.x, &own) <= 1e-9, "{}", distance(&s.x, &own));
    assert!(violation(&p, &s.x) <= 1e-9);
    // The centred resultants of the associative normal forces as the centre.
    let fs = m.loads.force_scale();
    let centre: Vec<f64> = n
        .iter()
        .flat_map(|n| [0.5 * n / fs, 0.5 * n / fs])
        .collect();
    let near = lp.nearest(below, &columns, &centre, &zero, 1.0);
    let LpOutcome::Optimal(s) = DualSimplex::new(near).solve() else {
        panic!("no optimum")
    };
    assert!(violation(&p, &s.x) <= 1e-9);
    assert!((s.x[0] - below).abs() <= 1e-15);
    let (d_near, d_vertex) = (distance(&s.x, &centre), distance(&first.x, &centre));
    println!("distance to the centre: nearest {d_near:.6}, vertex {d_vertex:.6}");
    assert!(d_near <= d_vertex + 1e-6, "{d_near} > {d_vertex}");
}

/// The non-associative multiplier of `m` toward the right by the simplex path
/// (`NonAssociativeSettings::simplex`: every fixed-shear program by the warm-started dual
/// simplex) and by the full
/// conic program (`Program::Full`, Clarabel for every iterate), from the same associative
/// result.
fn both_paths(
    m: &Model,
) -> (
    statics::StaticResult,
    statics::NonAssociative,
    statics::NonAssociative,
) {
    let s = StaticSettings::default();
    let a = statics::analyse(m, &s).expect("static program");
    let na = statics::NonAssociativeSettings {
        simplex: true,
        ..statics::NonAssociativeSettings::default()
    };
    let lp = statics::analyse_non_associative(m, &s, &a, &na).expect("simplex path");
    let full = s.clone().program(statics::Program::Full);
    let full = statics::analyse_non_associative(m, &full, &a, &na).expect("full path");
    (a, lp, full)
}

/// The simplex path against the full program's on assemblies that are not chains (walls in
/// running bond, a tied portal, a 2-bay arcade). The two paths solve the same programs to
/// the same optimum (the test above), but a simplex returns a vertex of the optimal face and
/// the interior point a point inside it, so the iteration, which reads the normal forces,
/// takes other paths and may settle on another of the problem's several solutions
/// (docs/friction.md). What holds: the simplex path converges in every case (the full path
/// does not on the arcade: none of its starts settles in 100 iterations); its value is a
/// solution (equilibrium, Coulomb's law, at most the associative value) within 1 % of the
/// full path's (measured: equal to 4e-10 on the walls and the portal, 0.4 % below the full
/// path's last iterates on the arcade); and `Program::Full` keeps Clarabel for every
/// iterate.
#[test]
fn the_simplex_path_converges_on_a_solution_near_the_full_programs() {
    let portal = [
        [0.0, 0.0, 0.6, 1.2],
        [1.8, 0.0, 2.4, 1.2],
        [0.0, 1.2, 2.4, 1.6],
    ];
    let cases = [
        (
            "wall 3 x 2",
            model_of(&polygons(&running_bond_wall_rects(), 0.7, "")),
        ),
        (
            "tied lintel portal",
            model_of(&polygons(
                &portal,
                0.4,
                "[[ties]]\nfrom = [0.3, 1.0]\nto = [2.1, 1.0]\ncapacity = 3000.0\n",
            )),
        ),
        ("wall 6 x 8", model_of(&wall(6, 8, 0.6))),
        ("2-bay arcade", two_bay_arcade()),
    ];
    for (name, m) in cases {
        let t = std::time::Instant::now();
        let (a, lp, full) = both_paths(&m);
        let associative = a.lambda.expect("collapse");
        println!(
            "{name}: associative {associative:.6}, simplex path {:?} ({} programs), full {:?} ({} programs), {:.1} s",
            lp.lambda,
            lp.iterations,
            full.lambda,
            full.iterations,
            t.elapsed().as_secs_f64()
        );
        for (c, f) in lp.starts.iter().zip(&full.starts) {
            println!(
                "    {:<15} simplex {:?} {} {} | full {:?} {} {}",
                c.start.as_str(),
                c.lambda,
                c.iterations,
                c.converged(),
                f.lambda,
                f.iterations,
                f.converged()
            );
        }
        let l = lp
            .lambda
            .unwrap_or_else(|| panic!("{name}: simplex {:?}", lp.starts));
        assert!(
            l <= associative + 1e-9 * associative.max(1.0),
            "{name}: {l} > {associative}"
        );
        // Where the full path converges, its value; where it does not (the arcade: no start
        // settles in 100 iterations), the lowest of its last iterates.
        let f = full.lambda.unwrap_or_else(|| {
            full.starts
                .iter()
                .filter_map(|s| s.lambda)
                .fold(f64::INFINITY, f64::min)
        });
        assert!(
            (l - f).abs() <= 0.01 * f.abs(),
            "{name}: simplex {l}, full {f}"
        );
        let r = lp.result.as_ref().expect("the retained solution");
        assert!(
            r.solver_status.contains("dual simplex"),
            "{}",
            r.solver_status
        );
        if let Some(rf) = full.result.as_ref() {
            assert!(
                !rf.solver_status.contains("dual simplex"),
                "{}",
                rf.solver_status
            );
        }
        let fs = m.loads.force_scale();
        assert!(r.equilibrium_residual <= 1e-9 * fs, "{name}: residual");
        for (j, f) in m.assembly.joints.iter().zip(r.forces.iter().flatten()) {
            assert!(f.n >= 0.0);
            assert!(
                f.v.abs() <= j.friction * f.n + 1e-6 * fs,
                "{name}: |V| {} > mu N {}",
                f.v.abs(),
                j.friction * f.n
            );
        }
    }
}
