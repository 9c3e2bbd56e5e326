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
