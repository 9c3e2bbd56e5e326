//! The general kinematic program (`voussoir::kinematic::analyse_general`) against the static
//! program (`voussoir::statics::analyse_full`) on the same running-bond walls of about 100,
//! 1,000 and 10,000 blocks (friction 0.6): wall time and peak memory of each.
//!
//! Peak memory is the peak resident set (`VmHWM` of `/proc/self/status`, Linux), which only
//! grows, so each measurement runs in a process of its own (this binary started again with
//! `VOUSSOIR_BENCH_CHILD=method:blocks`); the peak of a process that only builds the model is
//! printed beside them, the difference being what the program itself needs.
//!
//! Run with `cargo bench --bench general_kinematic` (100 and 1,000 blocks), or
//! `cargo bench --bench general_kinematic -- 10000` to add the 10,000-block wall (`static`
//! among the arguments leaves the general program out). Each row is one program: `static` is
//! `analyse_full` as it is, `static_refined` the same with Clarabel's iterative refinement
//! always on (`Refinement::Always`, as before issue 28's item 4: the walls of 1,008 and
//! 10,050 blocks are solved without it now), `general_refined` likewise for the general
//! program (whose 10,050-block wall is solved without it now); `static_before` (asked for by name only) what
//! it ran before it recognised the wall (numbered course by course) as its own mirror image:
//! the same program, then the phase-one program at lambda = 0. CPU time beside the wall
//! time, since the machine is shared.
//!
//! Two diagnostics of the static program (issue 28, docs/performance.md "Large assemblies"):
//! `VOUSSOIR_BENCH_CHILD=probe:N` prints the size of the KKT matrix Clarabel factors and of its
//! factor, a factorisation's and a solve's time, and the program solved with Clarabel's
//! settings varied, the force unit changed and the friction cones written by their extreme
//! rays (`PROBE_SOLVE=0`: the factor only; `PROBE_ONLY=default`: one variant), and the
//! factor's size and time under a nested-dissection ordering of the blocks (qdldl given the
//! permutation) beside Clarabel's AMD;
//! `VOUSSOIR_BENCH_CHILD=export:N` writes the program as an MPS file
//! (`VOUSSOIR_EXPORT_MPS`, default `/tmp/wall.mps`) for HiGHS (`benches/highs_wall.py`).

mod common;
use common::median;
use voussoir::assembly::{Assembly, Block, BlockKind, Joint, JointKind};
use voussoir::geometry::{polygon_area_centroid, Vec2};
use voussoir::kinematic::{self, KinematicSettings};
use voussoir::model::Model;
use voussoir::statics::{self, StaticSettings};

/// A running-bond wall of `courses` courses of `per` units 0.4 x 0.2 m (half units at both
/// ends of every other course) on the ground, its joints written directly: beds (normal up)
/// and head joints (normal toward +x). Friction `mu`.
fn wall(courses: usize, per: usize, mu: f64) -> Assembly {
    let (b, h) = (0.4, 0.2);
    let mut rows: Vec<Vec<f64>> = Vec::new();
    let mut blocks = Vec::new();
    let mut index: Vec<Vec<usize>> = Vec::new();
    for c in 0..courses {
        let xs: Vec<f64> = if c % 2 == 0 {
            (0..=per).map(|k| k as f64 * b).collect()
        } else {
            std::iter::once(0.0)
                .chain((0..per).map(|k| (k as f64 + 0.5) * b))
                .chain(std::iter::once(per as f64 * b))
                .collect()
        };
        let (y0, y1) = (c as f64 * h, (c + 1) as f64 * h);
        let mut ids = Vec::new();
        for w in xs.windows(2) {
            let polygon = vec![
                Vec2::new(w[0], y0),
                Vec2::new(w[1], y0),
                Vec2::new(w[1], y1),
                Vec2::new(w[0], y1),
            ];
            let (area, centroid) = polygon_area_centroid(&polygon);
            ids.push(blocks.len());
            blocks.push(Block {
                polygon,
                area,
                centroid,
                weight: 20000.0 * area,
                kind: BlockKind::Other,
            });
        }
        rows.push(xs);
        index.push(ids);
    }
    let joint = |p1: Vec2, p2: Vec2, from, to| Joint {
        p1,
        p2,
        from,
        to,
        friction: mu,
        kind: JointKind::Other,
    };
    let mut joints = Vec::new();
    for (c, xs) in rows.iter().enumerate() {
        let (y0, y1) = (c as f64 * h, (c + 1) as f64 * h);
        // Head joints.
        for k in 1..xs.len() - 1 {
            joints.push(joint(
                Vec2::new(xs[k], y0),
                Vec2::new(xs[k], y1),
                Some(index[c][k - 1]),
                Some(index[c][k]),
            ));
        }
        // Beds: on the ground, or on the course below (overlaps of the two rows of units).
        for (k, w) in xs.windows(2).enumerate() {
            if c == 0 {
                joints.push(joint(
                    Vec2::new(w[1], y0),
                    Vec2::new(w[0], y0),
                    None,
                    Some(index[c][k]),
                ));
                continue;
            }
            for (m, v) in rows[c - 1].windows(2).enumerate() {
                let (lo, hi) = (w[0].max(v[0]), w[1].min(v[1]));
                if hi - lo > 1e-9 {
                    joints.push(joint(
                        Vec2::new(hi, y0),
                        Vec2::new(lo, y0),
                        Some(index[c - 1][m]),
                        Some(index[c][k]),
                    ));
                }
            }
        }
    }
    Assembly { blocks, joints }
}

/// Courses and units per course of the wall of about `n` blocks.
fn size(n: usize) -> (usize, usize) {
    match n {
        100 => (10, 10),
        1000 => (32, 31),
        _ => (100, 100),
    }
}

fn model(n: usize) -> Model {
    let (c, p) = size(n);
    Model::self_weight(wall(c, p, 0.6))
}

/// Peak resident set of this process (MiB), from `/proc/self/status`.
fn peak_mib() -> f64 {
    std::fs::read_to_string("/proc/self/status")
        .ok()
        .and_then(|s| {
            s.lines()
                .find(|l| l.starts_with("VmHWM:"))
                .and_then(|l| l.split_whitespace().nth(1))
                .and_then(|kb| kb.parse::<f64>().ok())
        })
        .map_or(f64::NAN, |kb| kb / 1024.0)
}

/// Solve `min q'x` subject to `A x + s = b`, `s` in `cones`, by Clarabel at voussoir's
/// tolerances with `set` applied to its settings (`PROBE_VERBOSE` prints its log), and print
/// the status, lambda (column 0), the iterations and the time under `name`.
fn solve_timed(
    name: &str,
    q: &[f64],
    a: &clarabel::algebra::CscMatrix<f64>,
    b: &[f64],
    cones: &[clarabel::solver::SupportedConeT<f64>],
    set: &dyn Fn(&mut clarabel::solver::DefaultSettings<f64>),
) {
    use clarabel::solver::{DefaultSettingsBuilder, DefaultSolver, IPSolver};
    let mut s = DefaultSettingsBuilder::default()
        .verbose(std::env::var("PROBE_VERBOSE").is_ok())
        .tol_gap_abs(1e-10)
        .tol_gap_rel(1e-10)
        .tol_feas(1e-10)
        .max_iter(200)
        .build()
        .expect("settings");
    set(&mut s);
    let t = std::time::Instant::now();
    let p = clarabel::algebra::CscMatrix::zeros((a.n, a.n));
    let mut solver = DefaultSolver::new(&p, q, a, b, cones, s).expect("Clarabel setup");
    solver.solve();
    let sol = &solver.solution;
    eprintln!(
        "{name}: {:?} lambda {:.12} after {} iterations, {:.3} s",
        sol.status,
        sol.x[0],
        sol.iterations,
        t.elapsed().as_secs_f64()
    );
}

/// A change to Clarabel's settings.
type Variant = Box<dyn Fn(&mut clarabel::solver::DefaultSettings<f64>)>;

/// The static program of `m` as `analyse_full` gives it to Clarabel (the action toward +x).
fn static_program(m: &Model) -> statics::StaticProblem {
    let objective = statics::Objective::MaxLambda {
        sign: 1.0,
        cap: None,
    };
    statics::StaticProblem::new(&m.assembly, &m.loads, objective)
}

/// The KKT matrix Clarabel factors for `p` (upper triangle of `[I A'; A -I]`): its factor's
/// nonzeros under Clarabel's AMD ordering; then the program solved with Clarabel's settings
/// varied, and the phase-one program, each timed.
fn probe(m: &Model) {
    use clarabel::algebra::CscMatrix;
    use clarabel::qdldl::{QDLDLFactorisation, QDLDLSettingsBuilder};
    let p = static_program(m);
    let (n, rows) = (p.a.n, p.a.m);
    let mut tr = (Vec::new(), Vec::new(), Vec::new());
    for j in 0..n {
        tr.0.push(j);
        tr.1.push(j);
        tr.2.push(1.0);
        for k in p.a.colptr[j]..p.a.colptr[j + 1] {
            tr.0.push(j);
            tr.1.push(n + p.a.rowval[k]);
            tr.2.push(p.a.nzval[k]);
        }
    }
    for i in 0..rows {
        tr.0.push(n + i);
        tr.1.push(n + i);
        tr.2.push(-1.0);
    }
    let kkt = CscMatrix::new_from_triplets(n + rows, n + rows, tr.0, tr.1, tr.2);
    for scale in [1.5, 1e9] {
        let t = std::time::Instant::now();
        let opts = QDLDLSettingsBuilder::default()
            .logical(true)
            .amd_dense_scale(scale)
            .build()
            .expect("settings");
        let f = QDLDLFactorisation::<f64>::new(&kkt, Some(opts)).expect("the KKT factor");
        eprintln!(
            "KKT {} x {}, nnz(K) {}, nnz(L) {} (amd dense scale {scale}; {:.3} s)",
            n + rows,
            n + rows,
            f.nnzA(),
            f.nnzL(),
            t.elapsed().as_secs_f64()
        );
    }
    // qdldl's factor of the KKT matrix under `perm` (None: AMD), the time of its first
    // factorisation and the average of ten more.
    let factor = |perm: Option<Vec<usize>>| {
        let mut opts = QDLDLSettingsBuilder::default()
            .amd_dense_scale(1.5)
            .Dsigns((0..n + rows).map(|i| if i < n { 1 } else { -1 }).collect())
            .build()
            .expect("settings");
        opts.perm = perm;
        let t = std::time::Instant::now();
        let mut f = QDLDLFactorisation::<f64>::new(&kkt, Some(opts)).expect("the KKT factor");
        let t1 = t.elapsed().as_secs_f64();
        let t = std::time::Instant::now();
        for _ in 0..10 {
            f.refactor().expect("the KKT factor");
        }
        (f, t1, t.elapsed().as_secs_f64() / 10.0)
    };
    {
        let (mut f, t1, t2) = factor(None);
        let mut x = vec![1.0; n + rows];
        let t = std::time::Instant::now();
        for _ in 0..10 {
            f.solve(&mut x);
        }
        eprintln!(
            "numeric: new {t1:.4} s, refactor {t2:.4} s, solve {:.5} s",
            t.elapsed().as_secs_f64() / 10.0
        );
    }
    {
        // The same matrix under a nested-dissection ordering of the blocks (each joint's
        // unknowns and rows first, then the blocks' equilibrium rows, separators last).
        let (f, t1, t2) = factor(Some(nested_dissection(m, &p)));
        eprintln!(
            "nested dissection: nnz(L) {}, new {t1:.4} s, refactor {t2:.4} s",
            f.nnzL()
        );
    }
    if std::env::var("PROBE_SOLVE").is_ok_and(|v| v == "0") {
        return;
    }
    let variants: Vec<(&str, Variant)> = vec![
        ("default", Box::new(|_| {})),
        (
            "no equilibration",
            Box::new(|s| s.equilibrate_enable = false),
        ),
        (
            "no refinement",
            Box::new(|s| s.iterative_refinement_enable = false),
        ),
        ("no presolve", Box::new(|s| s.presolve_enable = false)),
        ("step 0.995", Box::new(|s| s.max_step_fraction = 0.995)),
        ("step 0.999", Box::new(|s| s.max_step_fraction = 0.999)),
        ("step 0.95", Box::new(|s| s.max_step_fraction = 0.95)),
        (
            "static reg 1e-10",
            Box::new(|s| s.static_regularization_constant = 1e-10),
        ),
        (
            "static reg 1e-6",
            Box::new(|s| s.static_regularization_constant = 1e-6),
        ),
        (
            "refine reltol 1e-10",
            Box::new(|s| {
                s.iterative_refinement_reltol = 1e-10;
                s.iterative_refinement_abstol = 1e-10;
            }),
        ),
        (
            "refine max 1",
            Box::new(|s| s.iterative_refinement_max_iter = 1),
        ),
        ("equilibrate 50", Box::new(|s| s.equilibrate_max_iter = 50)),
    ];
    let only = std::env::var("PROBE_ONLY").ok();
    for (name, set) in &variants {
        if only.as_deref().is_some_and(|o| o != *name) {
            continue;
        }
        solve_timed(name, &p.q, &p.a, &p.b, &p.cones, set);
    }
    if only.is_some() {
        return;
    }
    for k in [10.0, 100.0, 1000.0, 10000.0] {
        // The force unit divided by k: the forces and the right-hand side times k, and the
        // action's coefficients (lambda's column) too; lambda itself unchanged.
        let mut a = p.a.clone();
        for v in &mut a.nzval[a.colptr[0]..a.colptr[1]] {
            *v *= k;
        }
        let b: Vec<f64> = p.b.iter().map(|v| v * k).collect();
        let name = format!("force unit / {k}");
        solve_timed(&name, &p.q, &a, &b, &p.cones, &|_| {});
    }
    {
        // The friction cone by its four extreme rays: (c1, c2, V) = a (1, 0, mu) +
        // b (1, 0, -mu) + c (0, 1, mu) + d (0, 1, -mu), a, b, c, d >= 0; the equilibrium rows
        // only, and the rays' bounds.
        let eq = p.equality_rows;
        let nj = m.assembly.joints.len();
        let (mut r, mut c, mut v) = (Vec::new(), Vec::new(), Vec::new());
        let col_entries = |col: usize| {
            (p.a.colptr[col]..p.a.colptr[col + 1])
                .filter(|&k| p.a.rowval[k] < eq)
                .map(|k| (p.a.rowval[k], p.a.nzval[k]))
                .collect::<Vec<_>>()
        };
        for (row, val) in col_entries(0) {
            r.push(row);
            c.push(0);
            v.push(val);
        }
        for j in 0..nj {
            let mu = m.assembly.joints[j].friction;
            let (c1, c2, vv) = (
                col_entries(statics::column(j, 0)),
                col_entries(statics::column(j, 1)),
                col_entries(statics::column(j, 2)),
            );
            for (ray, (cn, sv)) in [(&c1, mu), (&c1, -mu), (&c2, mu), (&c2, -mu)]
                .iter()
                .enumerate()
            {
                let col = 1 + 4 * j + ray;
                for &(row, val) in cn.iter() {
                    r.push(row);
                    c.push(col);
                    v.push(val);
                }
                for &(row, val) in vv.iter() {
                    r.push(row);
                    c.push(col);
                    v.push(sv * val);
                }
                r.push(eq + 4 * j + ray);
                c.push(col);
                v.push(-1.0);
            }
        }
        let nvar = 1 + 4 * nj;
        let a = CscMatrix::new_from_triplets(eq + 4 * nj, nvar, r, c, v);
        let mut b = p.b[..eq].to_vec();
        b.extend(std::iter::repeat_n(0.0, 4 * nj));
        let mut q = vec![0.0; nvar];
        q[0] = -1.0;
        let cones = vec![
            clarabel::solver::SupportedConeT::ZeroConeT(eq),
            clarabel::solver::SupportedConeT::NonnegativeConeT(4 * nj),
        ];
        solve_timed("rays", &q, &a, &b, &cones, &|_| {});
    }
    let t = std::time::Instant::now();
    let st = statics::stands(m, &StaticSettings::default()).expect("phase one");
    eprintln!(
        "phase one: stands {} in {:.3} s",
        st.stands,
        t.elapsed().as_secs_f64()
    );
}

/// A nested-dissection ordering of the KKT matrix `[I A'; A -I]` of `p` (the wall `m`):
/// the blocks bisected recursively by the median of their centroids across the longer side,
/// the blocks of the smaller side that touch the other side being the separator, numbered
/// after both halves; in the KKT matrix each joint's unknowns and rows come first (they
/// touch only the two blocks' rows), then the equilibrium rows of the blocks in that order,
/// the multiplier last. Returns `perm` (new position -> KKT index).
fn nested_dissection(m: &Model, p: &statics::StaticProblem) -> Vec<usize> {
    let a = &m.assembly;
    let nb = a.blocks.len();
    let mut adj = vec![Vec::new(); nb];
    for j in &a.joints {
        if let (Some(f), Some(t)) = (j.from, j.to) {
            adj[f].push(t);
            adj[t].push(f);
        }
    }
    // Parts of at most this many blocks are not dissected further.
    let leaf = 4;
    let mut order = Vec::with_capacity(nb);
    let mut side = vec![0u32; nb];
    let mut label = 1u32;
    fn recurse(
        set: Vec<usize>,
        a: &voussoir::assembly::Assembly,
        adj: &[Vec<usize>],
        side: &mut [u32],
        label: &mut u32,
        leaf: usize,
        order: &mut Vec<usize>,
    ) {
        if set.len() <= leaf {
            order.extend(set);
            return;
        }
        let (mut lo, mut hi) = (Vec2::new(f64::MAX, f64::MAX), Vec2::new(f64::MIN, f64::MIN));
        for &i in &set {
            let c = a.blocks[i].centroid;
            lo = Vec2::new(lo.x.min(c.x), lo.y.min(c.y));
            hi = Vec2::new(hi.x.max(c.x), hi.y.max(c.y));
        }
        let key = |i: usize| {
            let c = a.blocks[i].centroid;
            if hi.x - lo.x >= hi.y - lo.y {
                c.x
            } else {
                c.y
            }
        };
        let mut sorted = set.clone();
        sorted.sort_by(|&i, &j| key(i).total_cmp(&key(j)));
        let half = sorted.len() / 2;
        let (left, right) = sorted.split_at(half);
        let (l, r) = (*label, *label + 1);
        *label += 2;
        for &i in left {
            side[i] = l;
        }
        for &i in right {
            side[i] = r;
        }
        let touches = |i: usize, other: u32, side: &[u32]| adj[i].iter().any(|&k| side[k] == other);
        let sep_l: Vec<usize> = left
            .iter()
            .copied()
            .filter(|&i| touches(i, r, side))
            .collect();
        let sep_r: Vec<usize> = right
            .iter()
            .copied()
            .filter(|&i| touches(i, l, side))
            .collect();
        let sep = if sep_l.len() <= sep_r.len() {
            sep_l
        } else {
            sep_r
        };
        let in_sep: std::collections::HashSet<usize> = sep.iter().copied().collect();
        let left: Vec<usize> = left
            .iter()
            .copied()
            .filter(|i| !in_sep.contains(i))
            .collect();
        let right: Vec<usize> = right
            .iter()
            .copied()
            .filter(|i| !in_sep.contains(i))
            .collect();
        for &i in &sep {
            side[i] = 0;
        }
        recurse(left, a, adj, side, label, leaf, order);
        recurse(right, a, adj, side, label, leaf, order);
        order.extend(sep);
    }
    recurse(
        (0..nb).collect(),
        a,
        &adj,
        &mut side,
        &mut label,
        leaf,
        &mut order,
    );
    let (n, rows) = (p.a.n, p.a.m);
    // Rows of A by the joint whose columns they touch (inequality rows), or by block.
    let joint_of_column = |c: usize| (c >= 1 && c < 1 + 3 * a.joints.len()).then(|| (c - 1) / 3);
    let mut joint_rows = vec![Vec::new(); a.joints.len()];
    let mut row_joint = vec![None; rows];
    for c in 0..n {
        for k in p.a.colptr[c]..p.a.colptr[c + 1] {
            let r = p.a.rowval[k];
            if r >= p.equality_rows && row_joint[r].is_none() {
                row_joint[r] = joint_of_column(c);
            }
        }
    }
    for (r, j) in row_joint.iter().enumerate() {
        if let Some(j) = j {
            joint_rows[*j].push(r);
        }
    }
    let mut perm = Vec::with_capacity(n + rows);
    for (j, jr) in joint_rows.iter().enumerate() {
        perm.extend(jr.iter().map(|r| n + r));
        perm.extend((0..3).map(|k| statics::column(j, k)));
    }
    for &i in &order {
        perm.extend((0..3).map(|k| n + 3 * i + k));
    }
    // Whatever is left (the multiplier, rows of no joint) last.
    let mut seen = vec![false; n + rows];
    for &i in &perm {
        seen[i] = true;
    }
    perm.extend((0..n + rows).filter(|&i| !seen[i]));
    assert_eq!(perm.len(), n + rows);
    perm
}

/// Write `p` (`min q'x` subject to `A x + s = b`, `s` in the zero cone for the equilibrium rows
/// and in the nonnegative cone for the others, `x` free) as a free-format MPS file: `E` rows
/// `A x = b`, `L` rows `A x <= b`, every column free. Values in Rust's shortest round-trip form,
/// so the file holds exactly Clarabel's program. Only for a program without second-order cones.
fn write_mps(p: &statics::StaticProblem, path: &str) -> std::io::Result<()> {
    use std::io::Write;
    assert_eq!(p.cone_rows, 0, "an LP only");
    let mut f = std::io::BufWriter::new(std::fs::File::create(path)?);
    let m = p.a.m;
    writeln!(f, "NAME wall\nROWS\n N obj")?;
    for i in 0..m {
        let kind = if i < p.equality_rows { 'E' } else { 'L' };
        writeln!(f, " {kind} r{i}")?;
    }
    writeln!(f, "COLUMNS")?;
    for j in 0..p.a.n {
        if p.q[j] != 0.0 {
            writeln!(f, " x{j} obj {:?}", p.q[j])?;
        }
        for k in p.a.colptr[j]..p.a.colptr[j + 1] {
            writeln!(f, " x{j} r{} {:?}", p.a.rowval[k], p.a.nzval[k])?;
        }
    }
    writeln!(f, "RHS")?;
    for (i, &b) in p.b.iter().enumerate() {
        if b != 0.0 {
            writeln!(f, " rhs r{i} {b:?}")?;
        }
    }
    writeln!(f, "BOUNDS")?;
    for j in 0..p.a.n {
        writeln!(f, " FR bnd x{j}")?;
    }
    writeln!(f, "ENDATA")
}

/// CPU time of this process so far (s, user and system), from `/proc/self/stat` (ticks of
/// 1/100 s): on the shared machine it varies less with the load than the wall time.
fn cpu_s() -> f64 {
    std::fs::read_to_string("/proc/self/stat")
        .ok()
        .and_then(|s| {
            // The fields after the command name (which ends with ')'); utime and stime are the
            // 14th and 15th of the line, the 12th and 13th after it.
            let rest = s.rsplit_once(')')?.1;
            let f: Vec<&str> = rest.split_whitespace().collect();
            Some((f.get(11)?.parse::<f64>().ok()? + f.get(12)?.parse::<f64>().ok()?) / 100.0)
        })
        .unwrap_or(f64::NAN)
}

/// One measurement in this process: `method` (`build`, `static`, `general`) on the wall of
/// about `n` blocks; prints `seconds lambda peak_MiB`.
fn child(method: &str, n: usize) {
    let m = model(n);
    // The largest wall once, untimed warm-up left out; the others the median of five.
    let timed = |f: &mut dyn FnMut() -> Option<f64>| {
        if n >= 10_000 {
            let t = std::time::Instant::now();
            let l = f();
            (t.elapsed().as_secs_f64(), l)
        } else {
            median(5, f)
        }
    };
    let cpu0 = cpu_s();
    let (t, lambda) = match method {
        "static" => timed(&mut || {
            let r = statics::analyse_full(&m, &StaticSettings::default()).ok()?;
            eprintln!("{} after {} iterations", r.solver_status, r.iterations);
            r.lambda
        }),
        // What `analyse_full` did before it recognised the wall as its own mirror image:
        // the static program, then the phase-one program at lambda = 0.
        "static_before" => timed(&mut || {
            let r = statics::analyse_full(&m, &StaticSettings::default()).ok()?;
            let st = statics::stands(&m, &StaticSettings::default()).ok()?;
            eprintln!(
                "{} after {} iterations; stands {}",
                r.solver_status, r.iterations, st.stands
            );
            r.lambda
        }),
        "static_refined" => timed(&mut || {
            let settings = StaticSettings {
                refinement: statics::Refinement::Always,
                ..StaticSettings::default()
            };
            let r = statics::analyse_full(&m, &settings).ok()?;
            eprintln!("{} after {} iterations", r.solver_status, r.iterations);
            r.lambda
        }),
        "static12" => timed(&mut || {
            let r = statics::analyse_full(&m, &StaticSettings::default().tolerance(1e-12)).ok()?;
            eprintln!("{} after {} iterations", r.solver_status, r.iterations);
            r.lambda
        }),
        "general_refined" => timed(&mut || {
            let settings = KinematicSettings {
                refinement: statics::Refinement::Always,
                ..KinematicSettings::default()
            };
            let r = kinematic::analyse_general(&m, &settings).ok()?;
            eprintln!("{}", r.note.as_deref().unwrap_or(""));
            r.lambda_upper
        }),
        "general" => timed(&mut || {
            let r = kinematic::analyse_general(&m, &KinematicSettings::default()).ok()?;
            eprintln!("{}", r.note.as_deref().unwrap_or(""));
            r.lambda_upper
        }),
        "probe" => {
            probe(&m);
            (0.0, None)
        }
        "export" => {
            // The static program exactly as Clarabel receives it, for HiGHS
            // (benches/highs_wall.py): path in VOUSSOIR_EXPORT_MPS.
            let path = std::env::var("VOUSSOIR_EXPORT_MPS").unwrap_or("/tmp/wall.mps".into());
            let p = static_program(&m);
            write_mps(&p, &path).expect("write the MPS file");
            eprintln!("wrote {path}");
            (0.0, None)
        }
        _ => (0.0, None),
    };
    // CPU time per measured run (the smaller walls run six times: a warm-up and five).
    let runs = if n >= 10_000 { 1.0 } else { 6.0 };
    let cpu = (cpu_s() - cpu0) / runs;
    println!("{t} {} {} {cpu}", lambda.unwrap_or(f64::NAN), peak_mib());
}

fn main() {
    if let Ok(spec) = std::env::var("VOUSSOIR_BENCH_CHILD") {
        let (method, n) = spec.split_once(':').expect("method:blocks");
        child(method, n.parse().expect("blocks"));
        return;
    }
    let mut sizes = vec![100, 1000];
    if std::env::args().any(|a| a == "10000") {
        sizes.push(10_000);
    }
    // `static` leaves the general kinematic program out (it is 4 to 8 times slower).
    let mut methods = vec!["static_refined", "static"];
    if std::env::args().any(|a| a == "static_before") {
        methods.insert(0, "static_before");
    }
    if !std::env::args().any(|a| a == "static") {
        methods.extend(["general_refined", "general"]);
    }
    let exe = std::env::current_exe().expect("this bench");
    let run = |method: &str, n: usize| -> ([f64; 4], String) {
        let out = std::process::Command::new(&exe)
            .env("VOUSSOIR_BENCH_CHILD", format!("{method}:{n}"))
            .output()
            .expect("child run");
        let text = String::from_utf8_lossy(&out.stdout);
        let v: Vec<f64> = text
            .split_whitespace()
            .map(|x| x.parse().unwrap_or(f64::NAN))
            .collect();
        let note = String::from_utf8_lossy(&out.stderr);
        let note = note.lines().last().unwrap_or("").to_string();
        match v.as_slice() {
            [t, l, p, c] => ([*t, *l, *p, *c], note),
            _ => panic!("child {method}:{n}: {text} {note}"),
        }
    };
    println!(
        "{:>7} {:>7} {:>14} {:>16} {:>10} {:>10} {:>9}  solver",
        "blocks", "joints", "program", "lambda", "wall s", "CPU s", "peak MiB"
    );
    for n in sizes {
        let m = model(n);
        let ([_, _, base, _], _) = run("build", n);
        println!(
            "{:>7} {:>7} {:>14} {:>16} {:>10} {:>10} {base:>9.1}",
            m.assembly.blocks.len(),
            m.assembly.joints.len(),
            "model only",
            "",
            "",
            ""
        );
        for method in &methods {
            let ([t, l, p, c], note) = run(method, n);
            println!(
                "{:>7} {:>7} {method:>14} {l:>16.12} {t:>10.4} {c:>10.3} {p:>9.1}  {note}",
                m.assembly.blocks.len(),
                m.assembly.joints.len(),
            );
        }
    }
}
