//! Timing shared by the benchmarks.

use std::time::Instant;

/// Best of `reps` wall times (s) of `f`, after one untimed run, and the last result of `f`.
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
