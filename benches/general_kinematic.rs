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
//! `cargo bench --bench general_kinematic -- 10000` to add the 10,000-block wall.

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
    let (t, lambda) = match method {
        "static" => timed(&mut || {
            let r = statics::analyse_full(&m, &StaticSettings::default()).ok()?;
            eprintln!("{} after {} iterations", r.solver_status, r.iterations);
            r.lambda
        }),
        "static12" => timed(&mut || {
            let r = statics::analyse_full(&m, &StaticSettings::default().tolerance(1e-12)).ok()?;
            eprintln!("{} after {} iterations", r.solver_status, r.iterations);
            r.lambda
        }),
        "general" => timed(&mut || {
            let r = kinematic::analyse_general(&m, &KinematicSettings::default()).ok()?;
            eprintln!("{}", r.note.as_deref().unwrap_or(""));
            r.lambda_upper
        }),
        _ => (0.0, None),
    };
    println!("{t} {} {}", lambda.unwrap_or(f64::NAN), peak_mib());
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
    let exe = std::env::current_exe().expect("this bench");
    let run = |method: &str, n: usize| -> (f64, f64, f64) {
        let out = std::process::Command::new(&exe)
            .env("VOUSSOIR_BENCH_CHILD", format!("{method}:{n}"))
            .output()
            .expect("child run");
        let text = String::from_utf8_lossy(&out.stdout);
        let v: Vec<f64> = text
            .split_whitespace()
            .map(|x| x.parse().unwrap_or(f64::NAN))
            .collect();
        match v.as_slice() {
            [t, l, p] => (*t, *l, *p),
            _ => panic!(
                "child {method}:{n}: {text} {}",
                String::from_utf8_lossy(&out.stderr)
            ),
        }
    };
    println!(
        "{:>7} {:>7} {:>16} {:>16} {:>10} {:>10} {:>9} {:>9} {:>9} {:>9}",
        "blocks",
        "joints",
        "lambda static",
        "lambda general",
        "static s",
        "general s",
        "ratio",
        "model MiB",
        "static",
        "general"
    );
    for n in sizes {
        let m = model(n);
        let (_, _, base) = run("build", n);
        let (ts, ls, ps) = run("static", n);
        let (tg, lg, pg) = run("general", n);
        println!(
            "{:>7} {:>7} {ls:>16.12} {lg:>16.12} {ts:>10.4} {tg:>10.4} {:>9.2} {base:>9.1} {ps:>9.1} {pg:>9.1}",
            m.assembly.blocks.len(),
            m.assembly.joints.len(),
            tg / ts,
        );
    }
}
