//! Timing shared by the benchmarks.

use std::time::Instant;

/// Best of `reps` wall times (s) of `f`, after one untimed run, and the last result of `f`.
#[allow(dead_code)] // not every bench that includes this module uses it
pub fn time<T>(reps: usize, mut f: impl FnMut() -> T) -> (f64, T) {
    let mut best = f64::INFINITY;
    let mut out = f();
    for _ in 0..reps {
        let t = Instant::now();
        out = f();
        best = best.min(t.elapsed().as_secs_f64());
    }
    (best, out)
}

/// Median wall time (s) of `reps` runs of `f` (after one warm-up run), and its last result.
#[allow(dead_code)] // not every bench that includes this module uses it
pub fn median<T>(reps: usize, mut f: impl FnMut() -> T) -> (f64, T) {
    let mut out = f();
    let mut v = Vec::new();
    for _ in 0..reps.max(1) {
        let t = Instant::now();
        out = f();
        v.push(t.elapsed().as_secs_f64());
    }
    v.sort_by(f64::total_cmp);
    (v[v.len() / 2], out)
}

/// A running-bond wall of `courses` courses of `per` blocks 0.4 x 0.2 m (half blocks at the
/// ends of every other course), as polygons.
#[allow(dead_code)] // not every bench that includes this module uses it
pub fn running_bond_wall(courses: usize, per: usize) -> Vec<Vec<[f64; 2]>> {
    let (b, h) = (0.4, 0.2);
    let mut out = Vec::new();
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
            out.push(vec![[w[0], y0], [w[1], y0], [w[1], y0 + h], [w[0], y0 + h]]);
        }
    }
    out
}
