//! Uncertain inputs: their distributions, the standard normal distribution, a seeded random
//! stream and Latin hypercube samples (`voussoir fragility`, docs/fragility.md).
//!
//! - **Distributions** of the scene's `[uncertain]` table ([`Distribution`]):
//!   `normal` (`mean`, `cov`: standard deviation `sigma = cov |mean|`),
//!   `uniform` (`low`, `high`), `lognormal` (`median`, `beta`: `ln X` is normal with mean
//!   `ln median` and standard deviation `beta`). Each is sampled through its quantile
//!   function `x = F^-1(u)`: `mean + sigma Phi^-1(u)`, `low + (high - low) u`,
//!   `median exp(beta Phi^-1(u))`.
//! - **The standard normal** CDF `Phi(x) = erfc(-x / sqrt 2) / 2` (libm's erfc, accurate to
//!   the last bits in both tails) and its quantile by Acklam's rational approximation
//!   (relative error 1.15e-9) polished by one Halley step on `Phi` (P. J. Acklam, "An
//!   algorithm for computing the inverse normal cumulative distribution function", 2003; the
//!   refinement is his), which brings it to round-off.
//! - **Latin hypercube sampling** (McKay, Beckman and Conover, "A comparison of three methods
//!   for selecting values of input variables in the analysis of output from a computer
//!   code", Technometrics 21(2), 1979): for `n` samples each variable's `(0, 1)` is cut into
//!   `n` equal strata; a random permutation `pi` assigns sample `i` the stratum `pi(i)`, and
//!   `u_i = (pi(i) + v_i) / n` with `v_i` uniform in the stratum. So every stratum of every
//!   variable is hit exactly once, and the variables are paired at random (independent
//!   inputs: no correlation is imposed).
//! - **Rank correlation** between inputs, when the scene asks for it (Iman and Conover, "A
//!   distribution-free approach to inducing rank correlation among input variables", Comm.
//!   Statist. Simul. Comput. 11(3), 1982): each variable's Latin hypercube values are
//!   *reordered*, never changed, so every stratum is still hit once and every marginal is
//!   kept exactly. The van der Waerden scores `a_m = Phi^-1(m / (n + 1))` are laid out in the
//!   order of each variable's values (matrix `R`, its sample correlation `T = Q Q^T`), turned
//!   into `R* = R Q^-T P^T` whose correlation is the target `C = P P^T`, and each variable's
//!   values are put in the order of its column of `R*`. The target is a rank (Spearman)
//!   correlation `rho`; the scores, normal, are given the Pearson correlation
//!   `2 sin(pi rho / 6)` whose normal variables have rank correlation `rho` (Pearson, 1907;
//!   Kruskal, 1958), so the samples' Spearman correlation approaches `rho` as `n` grows.
//! - **The stream**: ChaCha8 (`rand_chacha`) seeded by `seed_from_u64(seed)`; its output
//!   for a seed is specified by the algorithm, so a seed gives the same samples on every
//!   platform. The order of draws is fixed: variable by variable, first the Fisher-Yates
//!   shuffle of its permutation (`n - 1` draws), then its `n` offsets.

use rand_chacha::rand_core::{RngCore, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// A distribution of an uncertain input.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Distribution {
    /// Normal of mean `mean` and standard deviation `cov |mean|`.
    Normal { mean: f64, cov: f64 },
    /// Uniform on `[low, high]`.
    Uniform { low: f64, high: f64 },
    /// Lognormal of median `median` and logarithmic standard deviation `beta`.
    Lognormal { median: f64, beta: f64 },
}

impl Distribution {
    /// Its name as the scene writes it (`dist = "normal"`).
    pub fn name(&self) -> &'static str {
        match self {
            Distribution::Normal { .. } => "normal",
            Distribution::Uniform { .. } => "uniform",
            Distribution::Lognormal { .. } => "lognormal",
        }
    }

    /// The value at probability `u` in (0, 1): the quantile function `F^-1(u)`.
    pub fn quantile(&self, u: f64) -> f64 {
        match *self {
            Distribution::Normal { mean, cov } => mean + cov * mean.abs() * normal_quantile(u),
            Distribution::Uniform { low, high } => low + (high - low) * u,
            Distribution::Lognormal { median, beta } => median * (beta * normal_quantile(u)).exp(),
        }
    }

    /// Whether it has no spread (every sample the same value).
    pub fn certain(&self) -> bool {
        match *self {
            Distribution::Normal { mean, cov } => cov * mean == 0.0,
            Distribution::Uniform { low, high } => low == high,
            Distribution::Lognormal { beta, .. } => beta == 0.0,
        }
    }

    /// Its parameters in words, as the scene gives them: `mean = 0.3, cov = 0.1`.
    pub fn parameters(&self) -> String {
        match *self {
            Distribution::Normal { mean, cov } => format!("mean = {mean}, cov = {cov}"),
            Distribution::Uniform { low, high } => format!("low = {low}, high = {high}"),
            Distribution::Lognormal { median, beta } => {
                format!("median = {median}, beta = {beta}")
            }
        }
    }
}

/// The standard normal density `phi(x)`.
pub fn normal_pdf(x: f64) -> f64 {
    (-0.5 * x * x).exp() / (2.0 * std::f64::consts::PI).sqrt()
}

/// The standard normal CDF `Phi(x)`.
pub fn normal_cdf(x: f64) -> f64 {
    0.5 * libm::erfc(-x / std::f64::consts::SQRT_2)
}

/// The standard normal quantile `Phi^-1(p)`, p in (0, 1) (infinite at 0 and 1, NaN outside).
pub fn normal_quantile(p: f64) -> f64 {
    if !(0.0..=1.0).contains(&p) {
        return f64::NAN;
    }
    if p == 0.0 {
        return f64::NEG_INFINITY;
    }
    if p == 1.0 {
        return f64::INFINITY;
    }
    const A: [f64; 6] = [
        -3.969683028665376e+01,
        2.209460984245205e+02,
        -2.759285104469687e+02,
        1.383_577_518_672_69e2,
        -3.066479806614716e+01,
        2.506628277459239e+00,
    ];
    const B: [f64; 5] = [
        -5.447609879822406e+01,
        1.615858368580409e+02,
        -1.556989798598866e+02,
        6.680131188771972e+01,
        -1.328068155288572e+01,
    ];
    const C: [f64; 6] = [
        -7.784894002430293e-03,
        -3.223964580411365e-01,
        -2.400758277161838e+00,
        -2.549732539343734e+00,
        4.374664141464968e+00,
        2.938163982698783e+00,
    ];
    const D: [f64; 4] = [
        7.784695709041462e-03,
        3.224671290700398e-01,
        2.445134137142996e+00,
        3.754408661907416e+00,
    ];
    const LOW: f64 = 0.02425;
    let tail = |q: f64| {
        (((((C[0] * q + C[1]) * q + C[2]) * q + C[3]) * q + C[4]) * q + C[5])
            / ((((D[0] * q + D[1]) * q + D[2]) * q + D[3]) * q + 1.0)
    };
    let x = if p < LOW {
        tail((-2.0 * p.ln()).sqrt())
    } else if p > 1.0 - LOW {
        -tail((-2.0 * (1.0 - p).ln()).sqrt())
    } else {
        let q = p - 0.5;
        let r = q * q;
        (((((A[0] * r + A[1]) * r + A[2]) * r + A[3]) * r + A[4]) * r + A[5]) * q
            / (((((B[0] * r + B[1]) * r + B[2]) * r + B[3]) * r + B[4]) * r + 1.0)
    };
    // One Halley step on Phi(x) - p (Acklam's refinement).
    let e = normal_cdf(x) - p;
    let u = e * (2.0 * std::f64::consts::PI).sqrt() * (0.5 * x * x).exp();
    x - u / (1.0 + 0.5 * x * u)
}

/// A seeded stream of uniform numbers (ChaCha8: the same numbers for a seed on every
/// platform).
pub struct Stream(ChaCha8Rng);

impl Stream {
    pub fn new(seed: u64) -> Stream {
        Stream(ChaCha8Rng::seed_from_u64(seed))
    }

    /// A uniform number in the open interval (0, 1): the top 53 bits of the next word, centred
    /// in their cell (so never 0 or 1, whose quantiles are infinite).
    pub fn uniform(&mut self) -> f64 {
        ((self.0.next_u64() >> 11) as f64 + 0.5) * (1.0 / (1u64 << 53) as f64)
    }

    /// A uniform index in `0..=k`.
    fn index(&mut self, k: usize) -> usize {
        ((self.uniform() * (k + 1) as f64) as usize).min(k)
    }
}

/// `n` Latin hypercube samples of `variables` independent uniform variables on (0, 1), from
/// `seed`: `u[i][v]` is variable `v` of sample `i`, and for each `v` the strata
/// `floor(n u[i][v])` over `i` are `0..n` each exactly once (module docs).
pub fn latin_hypercube(variables: usize, n: usize, seed: u64) -> Vec<Vec<f64>> {
    let mut stream = Stream::new(seed);
    let mut u = vec![vec![0.0; variables]; n];
    for v in 0..variables {
        let mut strata: Vec<usize> = (0..n).collect();
        for i in (1..n).rev() {
            let j = stream.index(i);
            strata.swap(i, j);
        }
        for (i, row) in u.iter_mut().enumerate() {
            // The offset inside the stratum; the product stays below 1 (`uniform` < 1).
            let x = (strata[i] as f64 + stream.uniform()) / n as f64;
            row[v] = x.min(1.0 - f64::EPSILON / 2.0);
        }
    }
    u
}

/// The Pearson correlation of two standard normal variables whose rank (Spearman)
/// correlation is `rho`: `2 sin(pi rho / 6)` (module docs).
pub fn pearson_of_rank(rho: f64) -> f64 {
    2.0 * (std::f64::consts::PI * rho / 6.0).sin()
}

/// The lower Cholesky factor of the Pearson form of the rank correlation matrix `rank`
/// ([`pearson_of_rank`] of each entry: the correlation of the normal scores that
/// [`impose_rank_correlation`] imposes), None when that is not positive definite (the
/// correlations cannot hold together).
pub fn rank_correlation_factor(rank: &[Vec<f64>]) -> Option<Vec<Vec<f64>>> {
    let pearson: Vec<Vec<f64>> = rank
        .iter()
        .map(|row| row.iter().map(|&r| pearson_of_rank(r)).collect())
        .collect();
    cholesky(&pearson)
}

/// The lower Cholesky factor `L` of the symmetric matrix `a` (`a = L L^T`), None when `a` is
/// not positive definite (a pivot at or below `1e-12` times the diagonal's largest entry).
pub fn cholesky(a: &[Vec<f64>]) -> Option<Vec<Vec<f64>>> {
    let k = a.len();
    let scale = (0..k).map(|i| a[i][i].abs()).fold(0.0, f64::max);
    let mut l = vec![vec![0.0; k]; k];
    for i in 0..k {
        for j in 0..=i {
            let dot: f64 = (0..j).map(|m| l[i][m] * l[j][m]).sum();
            if i == j {
                let pivot = a[i][i] - dot;
                // NaN fails this test too.
                if pivot.is_nan() || pivot <= 1e-12 * scale {
                    return None;
                }
                l[i][i] = pivot.sqrt();
            } else {
                l[i][j] = (a[i][j] - dot) / l[j][j];
            }
        }
    }
    Some(l)
}

/// The order of `x` as ranks: `rank[i]` is the place of `x[i]` among the sorted values
/// (ties broken by index).
fn ranks(x: impl Iterator<Item = f64>) -> Vec<usize> {
    let x: Vec<f64> = x.collect();
    let mut order: Vec<usize> = (0..x.len()).collect();
    order.sort_by(|&a, &b| x[a].total_cmp(&x[b]).then(a.cmp(&b)));
    let mut rank = vec![0; x.len()];
    for (place, &i) in order.iter().enumerate() {
        rank[i] = place;
    }
    rank
}

/// Reorder each column of `u` (`u[i][v]`: variable `v` of sample `i`) so that the columns'
/// rank correlation approaches `target` (Spearman, `k x k`, unit diagonal), by Iman and
/// Conover's method (module docs). Each column keeps its values; only their order across the
/// samples changes, and no random number is drawn (the columns' own order is the random
/// pairing the method starts from). The Pearson form of `target` must be positive definite
/// (the scene checks it: [`rank_correlation_factor`]); when the
/// samples' own score correlation is not (fewer samples than variables), it is taken as
/// the identity.
pub fn impose_rank_correlation(u: &mut [Vec<f64>], target: &[Vec<f64>]) {
    let (n, k) = (u.len(), target.len());
    if n < 2 || k < 2 {
        return;
    }
    let Some(p) = rank_correlation_factor(target) else {
        return;
    };
    let scores: Vec<f64> = (1..=n)
        .map(|m| normal_quantile(m as f64 / (n + 1) as f64))
        .collect();
    let ranked: Vec<Vec<usize>> = (0..k).map(|v| ranks(u.iter().map(|row| row[v]))).collect();
    let r: Vec<Vec<f64>> = (0..n)
        .map(|i| (0..k).map(|v| scores[ranked[v][i]]).collect())
        .collect();
    // The scores' sample correlation: every column holds the same scores (mean 0, as they
    // are symmetric), so T = R^T R / sum a^2.
    let norm: f64 = scores.iter().map(|a| a * a).sum();
    let t: Vec<Vec<f64>> = (0..k)
        .map(|a| {
            (0..k)
                .map(|b| r.iter().map(|row| row[a] * row[b]).sum::<f64>() / norm)
                .collect()
        })
        .collect();
    let q = cholesky(&t);
    // R* = R Q^-T P^T, row by row: r* = P (Q^-1 r), Q^-1 r by forward substitution.
    let target_scores: Vec<Vec<f64>> = r
        .iter()
        .map(|row| {
            let mut y = row.clone();
            if let Some(q) = &q {
                for a in 0..k {
                    let dot: f64 = (0..a).map(|b| q[a][b] * y[b]).sum();
                    y[a] = (y[a] - dot) / q[a][a];
                }
            }
            (0..k)
                .map(|a| (0..=a).map(|b| p[a][b] * y[b]).sum())
                .collect()
        })
        .collect();
    for v in 0..k {
        let mut sorted: Vec<f64> = u.iter().map(|row| row[v]).collect();
        sorted.sort_by(f64::total_cmp);
        let order = ranks(target_scores.iter().map(|row| row[v]));
        for (row, &place) in u.iter_mut().zip(&order) {
            row[v] = sorted[place];
        }
    }
}

/// Spearman's rank correlation of two equally long samples without ties: the Pearson
/// correlation of their ranks.
pub fn spearman(x: &[f64], y: &[f64]) -> f64 {
    let n = x.len().min(y.len());
    if n < 2 {
        return f64::NAN;
    }
    let (rx, ry) = (ranks(x[..n].iter().copied()), ranks(y[..n].iter().copied()));
    let mean = (n - 1) as f64 / 2.0;
    let (mut sxy, mut sxx, mut syy) = (0.0, 0.0, 0.0);
    for i in 0..n {
        let (a, b) = (rx[i] as f64 - mean, ry[i] as f64 - mean);
        sxy += a * b;
        sxx += a * a;
        syy += b * b;
    }
    sxy / (sxx * syy).sqrt()
}

/// The SplitMix64 generator: a 64-bit state advanced by a constant, mixed on output (the
/// artificial records' noise, `records`, and the simplex's cost perturbation,
/// `statics::simplex`: small, fast and reproducible where ChaCha8 is not needed).
#[derive(Debug, Clone)]
pub(crate) struct SplitMix64(pub(crate) u64);

impl SplitMix64 {
    fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// Uniform on [0, 1) with 53 random bits.
    pub(crate) fn uniform(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_quantile_inverts_the_cdf_to_round_off() {
        for &p in &[
            1e-12,
            1e-6,
            0.01,
            0.02425,
            0.1,
            0.3,
            0.5,
            0.7,
            0.975,
            1.0 - 1e-9,
        ] {
            let x = normal_quantile(p);
            assert!(
                (normal_cdf(x) - p).abs() <= 1e-15_f64.max(1e-13 * p),
                "{p}: {x}"
            );
        }
        // Known values: Phi^-1(0.975) = 1.959963984540054.
        assert!((normal_quantile(0.975) - 1.959963984540054).abs() < 1e-13);
        assert_eq!(normal_quantile(0.5), 0.0);
    }

    #[test]
    fn each_stratum_is_hit_once_and_a_seed_repeats() {
        let n = 37;
        let u = latin_hypercube(3, n, 11);
        for v in 0..3 {
            let mut hit = vec![0; n];
            for row in &u {
                assert!(row[v] > 0.0 && row[v] < 1.0);
                hit[(row[v] * n as f64) as usize] += 1;
            }
            assert!(hit.iter().all(|&h| h == 1), "variable {v}: {hit:?}");
        }
        assert_eq!(u, latin_hypercube(3, n, 11));
        assert_ne!(u, latin_hypercube(3, n, 12));
    }

    #[test]
    fn quantiles_of_the_three_distributions() {
        let n = Distribution::Normal {
            mean: 0.3,
            cov: 0.1,
        };
        assert!((n.quantile(0.975) - (0.3 + 0.03 * 1.959963984540054)).abs() < 1e-14);
        let u = Distribution::Uniform {
            low: 0.5,
            high: 0.8,
        };
        assert!((u.quantile(0.25) - 0.575).abs() < 1e-15);
        let l = Distribution::Lognormal {
            median: 18000.0,
            beta: 0.1,
        };
        assert!((l.quantile(0.5) - 18000.0).abs() < 1e-9);
        assert!(Distribution::Normal {
            mean: 1.0,
            cov: 0.0
        }
        .certain());
    }

    #[test]
    fn iman_conover_reaches_the_rank_correlation_and_keeps_every_value() {
        let n = 2000;
        let target = vec![
            vec![1.0, 0.6, -0.3],
            vec![0.6, 1.0, 0.0],
            vec![-0.3, 0.0, 1.0],
        ];
        let plain = latin_hypercube(3, n, 11);
        let mut u = plain.clone();
        impose_rank_correlation(&mut u, &target);
        for v in 0..3 {
            let mut a: Vec<f64> = plain.iter().map(|r| r[v]).collect();
            let mut b: Vec<f64> = u.iter().map(|r| r[v]).collect();
            a.sort_by(f64::total_cmp);
            b.sort_by(f64::total_cmp);
            assert_eq!(a, b, "variable {v} keeps its values (so its strata)");
        }
        // The standard error of a rank correlation of n samples is about 1 / sqrt(n) = 0.022;
        // the method removes most of the sampling error, so the target is met well within it.
        for (a, b) in [(0, 1), (0, 2), (1, 2)] {
            let x: Vec<f64> = u.iter().map(|r| r[a]).collect();
            let y: Vec<f64> = u.iter().map(|r| r[b]).collect();
            let rho = spearman(&x, &y);
            assert!(
                (rho - target[a][b]).abs() < 1.0 / (n as f64).sqrt(),
                "{a}-{b}: {rho} against {}",
                target[a][b]
            );
        }
        // Deterministic: the same samples reorder the same way.
        let mut again = plain.clone();
        impose_rank_correlation(&mut again, &target);
        assert_eq!(u, again);
    }

    #[test]
    fn cholesky_refuses_what_is_not_positive_definite() {
        let a = vec![vec![4.0, 2.0], vec![2.0, 3.0]];
        let l = cholesky(&a).expect("positive definite");
        for i in 0..2 {
            for j in 0..2 {
                let back: f64 = (0..2).map(|m| l[i][m] * l[j][m]).sum();
                assert!((back - a[i][j]).abs() < 1e-14);
            }
        }
        let bad = vec![
            vec![1.0, 0.9, 0.9],
            vec![0.9, 1.0, -0.9],
            vec![0.9, -0.9, 1.0],
        ];
        assert!(cholesky(&bad).is_none());
        // Rank and Pearson correlations of normals: 0 and 1 map to themselves, and a rank
        // correlation of 0.5 is a Pearson one of 2 sin(pi / 12).
        assert_eq!(pearson_of_rank(0.0), 0.0);
        assert!((pearson_of_rank(1.0) - 1.0).abs() < 1e-15);
        assert!((pearson_of_rank(0.5) - 0.517_638_090_205_041_5).abs() < 1e-15);
    }

    #[test]
    fn splitmix64_matches_its_reference_stream() {
        // The first outputs of SplitMix64 from seed 0 (Vigna's reference splitmix64.c).
        let mut r = SplitMix64(0);
        assert_eq!(r.next_u64(), 0xE220_A839_7B1D_CDAF);
        assert_eq!(r.next_u64(), 0x6E78_9E6A_A1B9_65F4);
    }
}
