//! The lognormal fragility function fitted by maximum likelihood, with confidence bounds.
//!
//! A fragility function `P(collapse | IM = x) = Phi((ln x - ln theta) / beta)` (median
//! `theta`, dispersion `beta`) is fitted to observations of four kinds, each a term of the
//! log-likelihood `l(mu, beta)` with `mu = ln theta` and `s = (ln x - mu) / beta`:
//!
//! - a capacity `x` observed exactly (the capacity route: the `ag` at which a sample fails):
//!   `-ln beta - s^2 / 2`;
//! - a capacity only known to lie above `x` (a sample that passes at the largest `ag`
//!   searched): `ln Phi(-s)`;
//! - a capacity only known to lie below `x`: `ln Phi(s)`;
//! - `z` collapses out of `n` runs at intensity `x` (a stripe of the multiple-stripe
//!   analysis): `z ln Phi(s) + (n - z) ln Phi(-s)` (the binomial likelihood of Baker 2015,
//!   eq. 11, without its constant).
//!
//! With exact capacities only, the maximum is the closed form `mu = mean(ln x)`,
//! `beta^2 = mean((ln x - mu)^2)`. Otherwise Newton's method with the exact gradient and
//! Hessian (chain rule through `s`, below) and a backtracking line search climbs from a
//! starting point, falling back to the gradient where the Hessian is not negative definite.
//!
//! **Confidence bounds** come from the observed information matrix: its inverse, the
//! negative inverse Hessian of `l` at the optimum, is the asymptotic covariance of
//! `(mu, beta)`; the bounds are `theta exp(-+ z sigma_mu)` and, on `ln beta` by the delta
//! method (so they stay positive), `beta exp(-+ z sigma_beta / beta)`, with `z` the normal
//! quantile of the confidence level (1.96 at 95 %).
//!
//! Source: J. W. Baker, "Efficient analytical fragility function fitting using dynamic
//! structural analysis", Earthquake Spectra 31(1), 579-599, 2015 (the likelihood, eq. 11-12,
//! and the multiple-stripe analysis it is fitted to).

use crate::sampling::{normal_cdf, normal_pdf, normal_quantile};

/// One observation of the fit (module docs).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Observation {
    /// A capacity observed exactly.
    Exact(f64),
    /// A capacity above this value.
    Above(f64),
    /// A capacity below this value.
    Below(f64),
    /// `collapses` out of `runs` at intensity `at`.
    Counts { at: f64, runs: u64, collapses: u64 },
}

/// A fitted lognormal fragility function.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct LognormalFit {
    /// Median `theta` (the intensity of 50 % collapse probability).
    pub median: f64,
    /// Dispersion `beta` (the standard deviation of `ln` capacity); 0 for a step.
    pub beta: f64,
    /// Confidence bounds on the median and on beta at `confidence` (from the observed
    /// information matrix); equal to the estimate when beta is 0.
    pub median_bounds: [f64; 2],
    pub beta_bounds: [f64; 2],
    pub confidence: f64,
    /// The log-likelihood at the optimum (without constants).
    pub log_likelihood: f64,
}

impl LognormalFit {
    /// `P(collapse | IM = x)`; with beta = 0 a step: 0 up to the median, 1 above it.
    pub fn probability(&self, x: f64) -> f64 {
        if self.beta == 0.0 {
            return if x > self.median { 1.0 } else { 0.0 };
        }
        if x <= 0.0 {
            return 0.0;
        }
        normal_cdf((x / self.median).ln() / self.beta)
    }
}

/// Why no fit exists.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum FitError {
    #[error("no observation to fit")]
    Empty,
    #[error("an observation is not a positive intensity with collapses <= runs: {0}")]
    Invalid(String),
    /// Every run collapsed, or none did, or the stripes separate perfectly (all below one
    /// intensity survive, all above collapse): the likelihood has no maximum (the median
    /// or beta runs to a bound).
    #[error("the likelihood has no maximum: {0}")]
    Unbounded(String),
    #[error("Newton's method did not converge in {0} iterations")]
    NoConvergence(usize),
}

/// The default confidence level of the bounds.
pub const CONFIDENCE: f64 = 0.95;

/// `phi(t) / Phi(t)`, accurate far in the lower tail (where both underflow) by the
/// asymptotic series of Mills' ratio.
fn inverse_mills(t: f64) -> f64 {
    if t > -30.0 {
        normal_pdf(t) / normal_cdf(t)
    } else {
        let t2 = t * t;
        -t / (1.0 - 1.0 / t2 + 3.0 / (t2 * t2))
    }
}

/// `ln Phi(t)`, accurate far in the lower tail.
fn ln_cdf(t: f64) -> f64 {
    if t > -30.0 {
        normal_cdf(t).ln()
    } else {
        let t2 = t * t;
        -0.5 * t2 - (-t).ln() - 0.5 * (2.0 * std::f64::consts::PI).ln()
            + (1.0 - 1.0 / t2 + 3.0 / (t2 * t2)).ln()
    }
}

/// The log-likelihood (without constants) of `(mu, beta)`, beta > 0.
pub fn log_likelihood(obs: &[Observation], mu: f64, beta: f64) -> f64 {
    obs.iter()
        .map(|o| match *o {
            Observation::Exact(x) => {
                let s = (x.ln() - mu) / beta;
                -beta.ln() - 0.5 * s * s
            }
            Observation::Above(x) => ln_cdf(-(x.ln() - mu) / beta),
            Observation::Below(x) => ln_cdf((x.ln() - mu) / beta),
            Observation::Counts {
                at,
                runs,
                collapses,
            } => {
                let s = (at.ln() - mu) / beta;
                let z = collapses as f64;
                let rest = (runs - collapses) as f64;
                let mut l = 0.0;
                if z > 0.0 {
                    l += z * ln_cdf(s);
                }
                if rest > 0.0 {
                    l += rest * ln_cdf(-s);
                }
                l
            }
        })
        .sum()
}

/// Gradient and Hessian of the log-likelihood in `(mu, beta)`.
fn derivatives(obs: &[Observation], mu: f64, beta: f64) -> ([f64; 2], [[f64; 2]; 2]) {
    // d ln Phi(t)/dt = r(t), d2 = -t r - r^2.
    let r1 = |t: f64| inverse_mills(t);
    let r2 = |t: f64| {
        let r = inverse_mills(t);
        -t * r - r * r
    };
    let (mut g, mut h) = ([0.0; 2], [[0.0; 2]; 2]);
    for o in obs {
        let (x, dl, d2l, exact) = match *o {
            Observation::Exact(x) => {
                let s = (x.ln() - mu) / beta;
                (x, -s, -1.0, true)
            }
            Observation::Above(x) => {
                let s = (x.ln() - mu) / beta;
                (x, -r1(-s), r2(-s), false)
            }
            Observation::Below(x) => {
                let s = (x.ln() - mu) / beta;
                (x, r1(s), r2(s), false)
            }
            Observation::Counts {
                at,
                runs,
                collapses,
            } => {
                let s = (at.ln() - mu) / beta;
                let z = collapses as f64;
                let rest = (runs - collapses) as f64;
                let (mut d1, mut d2) = (0.0, 0.0);
                if z > 0.0 {
                    d1 += z * r1(s);
                    d2 += z * r2(s);
                }
                if rest > 0.0 {
                    d1 -= rest * r1(-s);
                    d2 += rest * r2(-s);
                }
                (at, d1, d2, false)
            }
        };
        let s = (x.ln() - mu) / beta;
        // s_mu = -1/beta, s_beta = -s/beta, s_mumu = 0, s_mubeta = 1/beta^2,
        // s_betabeta = 2 s / beta^2.
        let b2 = beta * beta;
        g[0] += -dl / beta;
        g[1] += -dl * s / beta;
        h[0][0] += d2l / b2;
        h[0][1] += d2l * s / b2 + dl / b2;
        h[1][1] += d2l * s * s / b2 + dl * 2.0 * s / b2;
        if exact {
            g[1] -= 1.0 / beta;
            h[1][1] += 1.0 / b2;
        }
    }
    h[1][0] = h[0][1];
    (g, h)
}

fn check(obs: &[Observation]) -> Result<(), FitError> {
    if obs.is_empty() {
        return Err(FitError::Empty);
    }
    for o in obs {
        let ok = match *o {
            Observation::Exact(x) | Observation::Above(x) | Observation::Below(x) => {
                x.is_finite() && x > 0.0
            }
            Observation::Counts {
                at,
                runs,
                collapses,
            } => at.is_finite() && at > 0.0 && collapses <= runs,
        };
        if !ok {
            return Err(FitError::Invalid(format!("{o:?}")));
        }
    }
    Ok(())
}

/// The maximum-likelihood lognormal fit of `obs`, with bounds at `confidence` (module docs).
pub fn fit(obs: &[Observation], confidence: f64) -> Result<LognormalFit, FitError> {
    check(obs)?;
    let exact: Vec<f64> = obs
        .iter()
        .filter_map(|o| match o {
            Observation::Exact(x) => Some(x.ln()),
            _ => None,
        })
        .collect();
    let z = normal_quantile(0.5 + 0.5 * confidence);
    if exact.len() == obs.len() {
        let n = exact.len() as f64;
        let mu = exact.iter().sum::<f64>() / n;
        let var = exact.iter().map(|y| (y - mu).powi(2)).sum::<f64>() / n;
        let beta = var.sqrt();
        // Round-off of equal capacities is no dispersion: a step, at the largest of them (so
        // that no sample fails at its own capacity).
        if beta <= 1e-12 * mu.abs().max(1.0) {
            let median = obs
                .iter()
                .filter_map(|o| match o {
                    Observation::Exact(x) => Some(*x),
                    _ => None,
                })
                .fold(f64::NEG_INFINITY, f64::max);
            return Ok(LognormalFit {
                median,
                beta: 0.0,
                median_bounds: [median; 2],
                beta_bounds: [0.0; 2],
                confidence,
                log_likelihood: f64::INFINITY,
            });
        }
        return Ok(bounded(obs, mu, beta, z, confidence));
    }
    unbounded(obs)?;
    let (mut mu, mut beta) = start(obs);
    const ITERATIONS: usize = 200;
    for _ in 0..ITERATIONS {
        let (g, h) = derivatives(obs, mu, beta);
        let l0 = log_likelihood(obs, mu, beta);
        // Newton step where -H is positive definite, else the gradient scaled to beta.
        let det = h[0][0] * h[1][1] - h[0][1] * h[1][0];
        let newton = h[0][0] < 0.0 && det > 0.0;
        let (mut dmu, mut dbeta) = if newton {
            (
                -(h[1][1] * g[0] - h[0][1] * g[1]) / det,
                -(-h[1][0] * g[0] + h[0][0] * g[1]) / det,
            )
        } else {
            let norm = (g[0] * g[0] + g[1] * g[1]).sqrt().max(1e-300);
            (0.5 * beta * g[0] / norm, 0.5 * beta * g[1] / norm)
        };
        // Keep beta positive, and climb.
        let mut t = 1.0;
        while beta + t * dbeta <= 0.0 {
            t *= 0.5;
        }
        let mut moved = false;
        for _ in 0..60 {
            let l1 = log_likelihood(obs, mu + t * dmu, beta + t * dbeta);
            if l1 >= l0 {
                moved = true;
                break;
            }
            t *= 0.5;
        }
        if !moved {
            t = 0.0;
        }
        dmu *= t;
        dbeta *= t;
        mu += dmu;
        beta += dbeta;
        let small = dmu.abs() <= 1e-14 * mu.abs().max(1.0) && dbeta.abs() <= 1e-14 * beta;
        let flat = g[0].abs() + g[1].abs() <= 1e-12 * (1.0 + l0.abs());
        if (small || !moved) && newton {
            if !(beta.is_finite() && beta > 0.0) {
                break;
            }
            return Ok(bounded(obs, mu, beta, z, confidence));
        }
        if flat && newton {
            return Ok(bounded(obs, mu, beta, z, confidence));
        }
    }
    Err(FitError::NoConvergence(ITERATIONS))
}

/// The fit at the optimum `(mu, beta)` with its bounds.
fn bounded(obs: &[Observation], mu: f64, beta: f64, z: f64, confidence: f64) -> LognormalFit {
    let (_, h) = derivatives(obs, mu, beta);
    let det = h[0][0] * h[1][1] - h[0][1] * h[1][0];
    // Covariance = (-H)^-1.
    let var_mu = -h[1][1] / det;
    let var_beta = -h[0][0] / det;
    let (sm, sb) = (var_mu.max(0.0).sqrt(), var_beta.max(0.0).sqrt());
    let median = mu.exp();
    LognormalFit {
        median,
        beta,
        median_bounds: [(mu - z * sm).exp(), (mu + z * sm).exp()],
        beta_bounds: [beta * (-z * sb / beta).exp(), beta * (z * sb / beta).exp()],
        confidence,
        log_likelihood: log_likelihood(obs, mu, beta),
    }
}

/// Refuse data whose likelihood has no maximum: no collapse anywhere, collapse everywhere, or
/// a perfect separation (every observation that says "collapsed at x" lies above every one
/// that says "survived at x").
fn unbounded(obs: &[Observation]) -> Result<(), FitError> {
    // An intensity at which something collapsed (a capacity below it) and one at which
    // something survived (a capacity above it).
    let (mut lowest_collapse, mut highest_survival) = (f64::INFINITY, 0.0_f64);
    let mut any_exact = false;
    for o in obs {
        match *o {
            Observation::Exact(_) => any_exact = true,
            Observation::Above(x) => highest_survival = highest_survival.max(x),
            Observation::Below(x) => lowest_collapse = lowest_collapse.min(x),
            Observation::Counts {
                at,
                runs,
                collapses,
            } => {
                if collapses > 0 {
                    lowest_collapse = lowest_collapse.min(at);
                }
                if collapses < runs {
                    highest_survival = highest_survival.max(at);
                }
            }
        }
    }
    if any_exact {
        return Ok(());
    }
    if lowest_collapse.is_infinite() {
        return Err(FitError::Unbounded(
            "no run collapsed: the median lies above every intensity tried".into(),
        ));
    }
    if highest_survival == 0.0 {
        return Err(FitError::Unbounded(
            "every run collapsed: the median lies below every intensity tried".into(),
        ));
    }
    if lowest_collapse > highest_survival {
        return Err(FitError::Unbounded(format!(
            "every run survived up to {highest_survival} and collapsed from {lowest_collapse}: the dispersion runs to 0 (add stripes between them)"
        )));
    }
    if lowest_collapse == highest_survival {
        return Err(FitError::Unbounded(format!(
            "only the stripe at {lowest_collapse} has both collapses and survivals (every one below survives, every one above collapses): the likelihood's maximum is a step there, the dispersion runs to 0 (add stripes around it)"
        )));
    }
    Ok(())
}

/// A starting point: the mean and spread of `ln x` over the observations, each weighted by
/// what it says (the collapse fractions' crossing of one half for counts).
fn start(obs: &[Observation]) -> (f64, f64) {
    let logs: Vec<f64> = obs
        .iter()
        .map(|o| match *o {
            Observation::Exact(x) | Observation::Above(x) | Observation::Below(x) => x.ln(),
            Observation::Counts { at, .. } => at.ln(),
        })
        .collect();
    let n = logs.len() as f64;
    let mean = logs.iter().sum::<f64>() / n;
    let spread = (logs.iter().map(|y| (y - mean).powi(2)).sum::<f64>() / n).sqrt();
    (mean, spread.max(0.1))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn exact_capacities_give_the_sample_moments_of_ln_x() {
        let xs = [0.1, 0.2, 0.15, 0.3, 0.12];
        let obs: Vec<_> = xs.iter().map(|&x| Observation::Exact(x)).collect();
        let f = fit(&obs, 0.95).expect("fit");
        let logs: Vec<f64> = xs.iter().map(|x: &f64| x.ln()).collect();
        let mu = logs.iter().sum::<f64>() / 5.0;
        let beta = (logs.iter().map(|y| (y - mu).powi(2)).sum::<f64>() / 5.0).sqrt();
        assert!((f.median - mu.exp()).abs() < 1e-14);
        assert!((f.beta - beta).abs() < 1e-14);
        // The observed information of exact data: var(mu) = beta^2/n, var(beta) = beta^2/2n.
        let z = normal_quantile(0.975);
        let upper = (mu + z * beta / 5f64.sqrt()).exp();
        assert!((f.median_bounds[1] - upper).abs() < 1e-10 * upper);
        let (g, _) = derivatives(&obs, mu, beta);
        assert!(g[0].abs() < 1e-9 && g[1].abs() < 1e-9, "{g:?}");
    }

    #[test]
    fn the_gradient_and_hessian_match_finite_differences() {
        let obs = [
            Observation::Counts {
                at: 0.1,
                runs: 10,
                collapses: 2,
            },
            Observation::Counts {
                at: 0.3,
                runs: 10,
                collapses: 7,
            },
            Observation::Above(0.5),
            Observation::Below(0.05),
            Observation::Exact(0.2),
        ];
        let (mu, beta) = (-1.7, 0.6);
        let (g, h) = derivatives(&obs, mu, beta);
        let e = 1e-5;
        let l = |m: f64, b: f64| log_likelihood(&obs, m, b);
        let gm = (l(mu + e, beta) - l(mu - e, beta)) / (2.0 * e);
        let gb = (l(mu, beta + e) - l(mu, beta - e)) / (2.0 * e);
        assert!((g[0] - gm).abs() < 1e-6 && (g[1] - gb).abs() < 1e-6);
        let d = |f: &dyn Fn(f64, f64) -> [f64; 2], m: f64, b: f64| f(m, b);
        let grad = |m: f64, b: f64| derivatives(&obs, m, b).0;
        let hmm = (d(&grad, mu + e, beta)[0] - d(&grad, mu - e, beta)[0]) / (2.0 * e);
        let hmb = (d(&grad, mu, beta + e)[0] - d(&grad, mu, beta - e)[0]) / (2.0 * e);
        let hbb = (d(&grad, mu, beta + e)[1] - d(&grad, mu, beta - e)[1]) / (2.0 * e);
        assert!((h[0][0] - hmm).abs() < 1e-5, "{} {hmm}", h[0][0]);
        assert!((h[0][1] - hmb).abs() < 1e-5, "{} {hmb}", h[0][1]);
        assert!((h[1][1] - hbb).abs() < 1e-5, "{} {hbb}", h[1][1]);
    }

    #[test]
    fn data_without_a_maximum_are_refused() {
        let c = |at, collapses| Observation::Counts {
            at,
            runs: 5,
            collapses,
        };
        assert!(matches!(
            fit(&[c(0.1, 0), c(0.2, 0)], 0.95),
            Err(FitError::Unbounded(_))
        ));
        assert!(matches!(
            fit(&[c(0.1, 5), c(0.2, 5)], 0.95),
            Err(FitError::Unbounded(_))
        ));
        assert!(matches!(
            fit(&[c(0.1, 0), c(0.2, 5)], 0.95),
            Err(FitError::Unbounded(_))
        ));
        assert!(fit(&[c(0.1, 1), c(0.2, 4)], 0.95).is_ok());
    }
}
