//! Spectrum-compatible artificial accelerograms for the dynamic checks (`voussoir records`):
//! records whose mean 5 %-damped elastic response spectrum matches the NTC 2018 elastic
//! spectrum of a site ([`crate::spectrum`]) within the code's tolerance, written as PEER
//! `.AT2` files that [`crate::dem::record`] reads.
//!
//! Method (docs/records.md):
//! - each record is a sum of sinusoids with random phases under an intensity envelope,
//!   `a(t) = e(t) sum_k A_k sin(2 pi f_k t + phi_k)` on the frequencies `f_k = k / D` of the
//!   record's duration `D` (Gasparini & Vanmarcke 1976, "SIMQKE: a program for artificial
//!   motion generation", MIT Dept. of Civil Engineering R76-4): with many terms and
//!   independent uniform phases the stationary part is a Gaussian process whose power
//!   spectral density is `A_k^2 / (2 df)` (Shinozuka & Jan 1972, J. Sound Vib. 25:111-128);
//! - the envelope is trapezoidal with a quadratic rise (SIMQKE's): `(t/t1)^2` up to
//!   `t1 = 0.1 D`, 1 up to `t2 = 0.5 D`, then linear down to 0 at `D`; with the duration
//!   `D = 25 s` this is the 10 s pseudo-stationary part preceded and followed by a rise and a
//!   decay, 25 s in all, that NTC 2018 §3.2.3.6 asks for when no specific study sets it;
//! - the amplitudes start from a flat spectrum and are corrected iteratively: each `A_k` is
//!   multiplied by the ratio of the target to the record's response spectrum at the period
//!   `1/f_k` (interpolated in log period between the matching periods), the SIMQKE iteration;
//! - after each synthesis a baseline correction `e(t) (c0 + c1 t)` is subtracted, with `c0`,
//!   `c1` such that the ground velocity and displacement return to zero at the end (the
//!   integrals are those of the linearly interpolated record, so the correction is exact);
//! - response spectra are pseudo-accelerations `omega^2 max |u|` of a linear oscillator with
//!   5 % damping, computed by the exact recurrence for a piecewise-linear excitation
//!   (Nigam & Jennings 1969, "Calculation of response spectra from strong-motion
//!   earthquake records", BSSA 59:909-922).
//!
//! The code's tolerance (NTC 2018 §3.2.3.6): the mean spectral ordinate of the records, at
//! 5 % damping, may not fall more than 10 % below the elastic spectrum at any period of the
//! larger of 0.15 s - 2.0 s and 0.15 s - 2T, `T` the structure's fundamental period (for the
//! ultimate limit states). [`generate`] checks it on a dense grid of periods and refuses to
//! return records that miss it ([`RecordsError::Tolerance`]).
//!
//! The random numbers are a SplitMix64 stream (Steele, Lea & Flood 2014, "Fast splittable
//! pseudorandom number generators", OOPSLA), written here so that a seed gives the same records
//! on every platform and every version of any dependency.

pub use crate::error::RecordsError;
use crate::sampling::SplitMix64;
use crate::spectrum::{Site, Spectrum, G};
use std::f64::consts::PI;

/// Damping ratio of the response spectra (NTC 2018 §3.2.3.6: 5 %).
pub const DAMPING: f64 = 0.05;
/// The largest shortfall of the mean spectrum below the target (NTC 2018 §3.2.3.6: 10 %).
pub const TOLERANCE: f64 = 0.10;
/// Lower end of the period range of the check (s).
pub const CHECK_FROM: f64 = 0.15;
/// Upper end of the period range of the check without a structural period (s).
pub const CHECK_TO: f64 = 2.0;
/// The duration of a record that NTC 2018 §3.2.3.6 asks for when no specific study sets it
/// (s): a 10 s pseudo-stationary part with a rise before and a decay after.
pub const CODE_DURATION: f64 = 25.0;
/// Default time step of the records (s).
pub const DEFAULT_DT: f64 = 0.01;
/// Highest frequency of the records (Hz): spectral ordinates below 0.04 s are the PGA.
const MAX_FREQUENCY: f64 = 25.0;
/// Each record is matched until its spectrum is within this fraction of the target at every
/// matching period, or for [`MAX_ITERATIONS`] corrections (the best iteration is kept).
const MATCH_TOLERANCE: f64 = 0.03;
const MAX_ITERATIONS: usize = 40;
/// Number of periods of the check grid (log-spaced, plus the spectrum's corner periods).
const CHECK_POINTS: usize = 200;
/// Number of periods the amplitudes are corrected at (log-spaced).
const MATCH_POINTS: usize = 120;

/// What the generator is asked for.
#[derive(Debug, Clone, PartialEq)]
pub struct Request {
    /// Number of records (1 to 100).
    pub count: usize,
    /// Duration of each record (s, 5 to 300).
    pub duration: f64,
    /// Time step (s, 0.001 to 0.02).
    pub dt: f64,
    /// Seed of the random phases.
    pub seed: u64,
    /// The structure's fundamental period `T` (s), which stretches the check range to
    /// 0.15 s - 2T when 2T > 2 s.
    pub period: Option<f64>,
}

/// The records and their check.
#[derive(Debug, Clone, PartialEq)]
pub struct Records {
    /// Ground accelerations (m/s^2), one vector per record, sampled every `dt` from t = 0.
    pub accel: Vec<Vec<f64>>,
    pub dt: f64,
    /// The target spectrum.
    pub spectrum: Spectrum,
    /// The check's periods (s), the target `Se` and the records' mean pseudo-acceleration
    /// (m/s^2) there.
    pub periods: Vec<f64>,
    pub target: Vec<f64>,
    pub mean: Vec<f64>,
    /// Each record's pseudo-acceleration at the check's periods (m/s^2).
    pub each: Vec<Vec<f64>>,
    /// The check range (s).
    pub range: (f64, f64),
    /// The smallest and largest ratio mean / target over the range, and their periods.
    pub worst_low: (f64, f64),
    pub worst_high: (f64, f64),
}

/// The check range of NTC 2018 §3.2.3.6 (ultimate limit states): the larger of 0.15 - 2.0 s
/// and 0.15 s - 2T.
pub fn check_range(period: Option<f64>) -> (f64, f64) {
    (
        CHECK_FROM,
        period.map_or(CHECK_TO, |t| (2.0 * t).max(CHECK_TO)),
    )
}

/// `n` periods spaced evenly in log from `from` to `to` (both included).
fn log_grid(from: f64, to: f64, n: usize) -> Vec<f64> {
    let (a, b) = (from.ln(), to.ln());
    (0..n)
        .map(|i| (a + (b - a) * i as f64 / (n - 1) as f64).exp())
        .collect()
}

/// The intensity envelope at `t` of a record of duration `d` (SIMQKE's trapezoid).
pub fn envelope(t: f64, d: f64) -> f64 {
    let (t1, t2) = (0.1 * d, 0.5 * d);
    if t <= 0.0 || t >= d {
        0.0
    } else if t < t1 {
        (t / t1).powi(2)
    } else if t <= t2 {
        1.0
    } else {
        (d - t) / (d - t2)
    }
}

/// Pseudo-spectral accelerations `omega^2 max|u|` (m/s^2) of a linear oscillator with damping
/// ratio `zeta` under the ground acceleration `accel` (m/s^2, sampled every `dt`, linear in
/// between), at each of `periods` (s); the exact recurrence of Nigam & Jennings (1969),
/// with the coefficients of Chopra, "Dynamics of Structures" (4th ed. 2012), Table 5.2.1.
pub fn response_spectrum(accel: &[f64], dt: f64, periods: &[f64], zeta: f64) -> Vec<f64> {
    periods
        .iter()
        .map(|&t| {
            let w = 2.0 * PI / t;
            let root = (1.0 - zeta * zeta).sqrt();
            let wd = w * root;
            let e = (-zeta * w * dt).exp();
            let (s, c) = (wd * dt).sin_cos();
            // Free vibration over one step.
            let (a_u, b_u) = (e * (zeta / root * s + c), e * s / wd);
            let (a_v, b_v) = (-e * w / root * s, e * (c - zeta / root * s));
            // The response to a force linear over the step (p = -a per unit mass,
            // stiffness k = w^2): Chopra's Table 5.2.1 coefficients, the exact recurrence of
            // Nigam & Jennings (1969) in the form of "interpolation of excitation".
            let k = w * w;
            let wdt = w * dt;
            let c_u = (2.0 * zeta / wdt
                + e * (((1.0 - 2.0 * zeta * zeta) / (wd * dt) - zeta / root) * s
                    - (1.0 + 2.0 * zeta / wdt) * c))
                / k;
            let d_u = (1.0 - 2.0 * zeta / wdt
                + e * ((2.0 * zeta * zeta - 1.0) / (wd * dt) * s + 2.0 * zeta / wdt * c))
                / k;
            let c_v = (-1.0 / dt + e * ((w / root + zeta / (dt * root)) * s + c / dt)) / k;
            let d_v = (1.0 - e * (zeta / root * s + c)) / (k * dt);
            let (mut u, mut v, mut peak) = (0.0_f64, 0.0_f64, 0.0_f64);
            for pair in accel.windows(2) {
                let (p0, p1) = (-pair[0], -pair[1]);
                let un = a_u * u + b_u * v + c_u * p0 + d_u * p1;
                v = a_v * u + b_v * v + c_v * p0 + d_v * p1;
                u = un;
                peak = peak.max(u.abs());
            }
            k * peak
        })
        .collect()
}

/// Ground velocity and displacement at the end of a record linear between samples.
fn end_motion(accel: &[f64], dt: f64) -> (f64, f64) {
    let (mut v, mut d) = (0.0, 0.0);
    for pair in accel.windows(2) {
        d += dt * v + dt * dt * (2.0 * pair[0] + pair[1]) / 6.0;
        v += dt * (pair[0] + pair[1]) / 2.0;
    }
    (v, d)
}

/// Subtract `e(t) (c0 + c1 t)` so that the record ends at rest where it started: zero
/// velocity and zero displacement at `t = D` (two linear conditions on `c0`, `c1`).
fn baseline_correct(accel: &mut [f64], basis: &[Vec<f64>; 2], ends: &[(f64, f64); 2], dt: f64) {
    let (v, d) = end_motion(accel, dt);
    let [(v0, d0), (v1, d1)] = *ends;
    let det = v0 * d1 - v1 * d0;
    if det.abs() < f64::MIN_POSITIVE {
        return;
    }
    let c0 = (v * d1 - v1 * d) / det;
    let c1 = (v0 * d - v * d0) / det;
    for (i, a) in accel.iter_mut().enumerate() {
        *a -= c0 * basis[0][i] + c1 * basis[1][i];
    }
}

/// Linear interpolation of `values` (at increasing `xs`) at `x`, held constant outside.
fn interpolate(xs: &[f64], values: &[f64], x: f64) -> f64 {
    if x <= xs[0] {
        return values[0];
    }
    let last = xs.len() - 1;
    if x >= xs[last] {
        return values[last];
    }
    let k = xs.partition_point(|&v| v <= x).max(1) - 1;
    let f = (x - xs[k]) / (xs[k + 1] - xs[k]);
    values[k] + f * (values[k + 1] - values[k])
}

fn flag(flag: &'static str, value: impl ToString, allowed: &str) -> RecordsError {
    RecordsError::Flag {
        flag,
        value: value.to_string(),
        allowed: allowed.to_string(),
    }
}

impl Request {
    /// Refuse values outside the ranges documented on the fields.
    pub fn validate(&self) -> Result<(), RecordsError> {
        if !(1..=100).contains(&self.count) {
            return Err(flag("--count", self.count, "from 1 to 100 records"));
        }
        if !(self.duration.is_finite() && (5.0..=300.0).contains(&self.duration)) {
            return Err(flag(
                "--duration",
                self.duration,
                "a duration in s from 5 to 300 (NTC 2018 §3.2.3.6 asks for 25 s absent specific studies)",
            ));
        }
        if !(self.dt.is_finite() && (0.001..=0.02).contains(&self.dt)) {
            return Err(flag(
                "--dt",
                self.dt,
                "a time step in s from 0.001 to 0.02 (records carry frequencies up to 25 Hz)",
            ));
        }
        if let Some(t) = self.period {
            if !(t.is_finite() && t > 0.0 && t <= 10.0) {
                return Err(flag("--period", t, "a period in s, above 0 and at most 10"));
            }
            // The longest period matched must be resolved by the record.
            if 3.0 * t > self.duration {
                return Err(flag(
                    "--period",
                    t,
                    &format!(
                        "at most a third of the duration {} s (the check runs to 2T)",
                        self.duration
                    ),
                ));
            }
        }
        Ok(())
    }
}

/// Generate the records of `request` for the elastic spectrum of `site` and check the mean
/// spectrum against NTC 2018 §3.2.3.6 (see the module documentation).
pub fn generate(site: &Site, request: &Request) -> Result<Records, RecordsError> {
    request.validate()?;
    let spectrum = site.spectrum();
    let (dt, duration) = (request.dt, request.duration);
    let n = (duration / dt).round() as usize + 1;
    let times: Vec<f64> = (0..n).map(|i| i as f64 * dt).collect();
    let env: Vec<f64> = times.iter().map(|&t| envelope(t, duration)).collect();
    let range = check_range(request.period);
    // Matching periods: from the period of the highest frequency to beyond the check range
    // (shorter periods follow the peak ground acceleration, which no one frequency sets).
    let match_periods = log_grid(1.0 / MAX_FREQUENCY, 1.5 * range.1, MATCH_POINTS);
    let match_target: Vec<f64> = match_periods.iter().map(|&t| spectrum.se(t)).collect();
    let df = 1.0 / duration;
    let f_max = MAX_FREQUENCY.min(0.4 / dt);
    let f_min = 1.0 / (2.0 * range.1);
    let freqs: Vec<f64> = (1..)
        .map(|k| k as f64 * df)
        .skip_while(|&f| f < f_min)
        .take_while(|&f| f <= f_max)
        .collect();
    let basis = [
        env.clone(),
        env.iter().zip(&times).map(|(e, t)| e * t).collect(),
    ];
    let ends = [end_motion(&basis[0], dt), end_motion(&basis[1], dt)];
    let mut rng = SplitMix64(request.seed);
    let mut accel = Vec::with_capacity(request.count);
    for _ in 0..request.count {
        let phases: Vec<f64> = freqs.iter().map(|_| 2.0 * PI * rng.uniform()).collect();
        accel.push(match_one(
            &freqs,
            &phases,
            &env,
            dt,
            (&basis, &ends),
            (&match_periods, &match_target),
        ));
    }
    check(accel, dt, spectrum, range)
}

/// One record: the SIMQKE iteration on the amplitudes, keeping the best one.
fn match_one(
    freqs: &[f64],
    phases: &[f64],
    env: &[f64],
    dt: f64,
    (basis, ends): (&[Vec<f64>; 2], &[(f64, f64); 2]),
    (periods, target): (&[f64], &[f64]),
) -> Vec<f64> {
    let log_periods: Vec<f64> = periods.iter().map(|t| t.ln()).collect();
    let mut amplitudes = vec![1.0; freqs.len()];
    let mut best: Option<(f64, Vec<f64>)> = None;
    for _ in 0..MAX_ITERATIONS {
        let mut a = synthesize(freqs, phases, &amplitudes, env, dt);
        baseline_correct(&mut a, basis, ends, dt);
        let sa = response_spectrum(&a, dt, periods, DAMPING);
        let ratios: Vec<f64> = target.iter().zip(&sa).map(|(t, s)| t / s).collect();
        let miss = ratios
            .iter()
            .map(|r| (1.0 / r - 1.0).abs())
            .fold(0.0, f64::max);
        if best.as_ref().is_none_or(|(m, _)| miss < *m) {
            best = Some((miss, a));
        }
        if miss < MATCH_TOLERANCE {
            break;
        }
        for (amp, f) in amplitudes.iter_mut().zip(freqs) {
            *amp *= interpolate(&log_periods, &ratios, (1.0 / f).ln());
        }
    }
    best.map(|(_, a)| a).unwrap_or_default()
}

/// `e(t) sum_k A_k sin(2 pi f_k t + phi_k)` at `t = i dt`; each sinusoid is advanced by a
/// rotation per step (one complex product instead of a sine per sample).
fn synthesize(freqs: &[f64], phases: &[f64], amplitudes: &[f64], env: &[f64], dt: f64) -> Vec<f64> {
    let mut a = vec![0.0; env.len()];
    for ((&f, &phi), &amp) in freqs.iter().zip(phases).zip(amplitudes) {
        let (sd, cd) = (2.0 * PI * f * dt).sin_cos();
        let (mut s, mut c) = phi.sin_cos();
        for (k, x) in a.iter_mut().enumerate() {
            *x += amp * s;
            (s, c) = (s * cd + c * sd, c * cd - s * sd);
            // Renormalise now and then so rounding cannot grow the amplitude.
            if k % 256 == 255 {
                let r = (s * s + c * c).sqrt();
                (s, c) = (s / r, c / r);
            }
        }
    }
    for (x, e) in a.iter_mut().zip(env) {
        *x *= e;
    }
    a
}

/// The check of NTC 2018 §3.2.3.6 on the mean spectrum.
fn check(
    accel: Vec<Vec<f64>>,
    dt: f64,
    spectrum: Spectrum,
    range: (f64, f64),
) -> Result<Records, RecordsError> {
    let mut periods = log_grid(range.0, range.1, CHECK_POINTS);
    // The corners of the spectrum, where a dip would hide between grid points.
    for t in [spectrum.tb, spectrum.tc, spectrum.td] {
        if t > range.0 && t < range.1 {
            periods.push(t);
        }
    }
    periods.sort_by(f64::total_cmp);
    let each: Vec<Vec<f64>> = accel
        .iter()
        .map(|a| response_spectrum(a, dt, &periods, DAMPING))
        .collect();
    let mean: Vec<f64> = (0..periods.len())
        .map(|i| each.iter().map(|s| s[i]).sum::<f64>() / each.len() as f64)
        .collect();
    let target: Vec<f64> = periods.iter().map(|&t| spectrum.se(t)).collect();
    let ratio = |i: usize| mean[i] / target[i];
    let low = (0..periods.len())
        .min_by(|&i, &j| ratio(i).total_cmp(&ratio(j)))
        .unwrap_or(0);
    let high = (0..periods.len())
        .max_by(|&i, &j| ratio(i).total_cmp(&ratio(j)))
        .unwrap_or(0);
    let worst_low = (periods[low], ratio(low));
    if worst_low.1 < 1.0 - TOLERANCE {
        return Err(RecordsError::Tolerance {
            period: worst_low.0,
            shortfall_pct: 100.0 * (1.0 - worst_low.1),
        });
    }
    Ok(Records {
        accel,
        dt,
        spectrum,
        worst_high: (periods[high], ratio(high)),
        periods,
        target,
        mean,
        each,
        range,
        worst_low,
    })
}

/// A record as the text of a PEER NGA `.AT2` file: four header lines (the second says what
/// it is), then the accelerations in g, five to a line.
pub fn at2_text(accel: &[f64], dt: f64, title: &str) -> String {
    let mut out = String::with_capacity(accel.len() * 16 + 256);
    out.push_str(
        "PEER NGA STRONG MOTION DATABASE RECORD (format); artificial record by voussoir\n",
    );
    out.push_str(title);
    out.push('\n');
    out.push_str("ACCELERATION TIME HISTORY IN UNITS OF G\n");
    out.push_str(&format!("NPTS= {:7}, DT= {:.6} SEC\n", accel.len(), dt));
    for line in accel.chunks(5) {
        let cells: Vec<String> = line.iter().map(|a| format!("{:16.7E}", a / G)).collect();
        out.push_str(&cells.concat());
        out.push('\n');
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A ground acceleration `a0` held from t = 0: the oscillator's first peak is
    /// `a0/w^2 (1 + exp(-zeta pi / sqrt(1 - zeta^2)))` at `t = pi / wd` (the step response in
    /// closed form); the recurrence, exact for a piecewise-linear input, meets it where a
    /// sample falls on the peak.
    #[test]
    fn the_step_response_peaks_where_the_closed_form_says() {
        let (t, zeta, a0) = (0.5_f64, DAMPING, 3.0);
        let w = 2.0 * PI / t;
        let wd = w * (1.0 - zeta * zeta).sqrt();
        // A step that puts a sample on the peak time pi/wd.
        let steps = 400;
        let dt = PI / wd / steps as f64;
        let accel = vec![a0; steps + 1];
        let sa = response_spectrum(&accel, dt, &[t], zeta)[0];
        let peak = a0 / (w * w) * (1.0 + (-zeta * PI / (1.0 - zeta * zeta).sqrt()).exp());
        assert!((sa / (w * w) - peak).abs() < 1e-12 * peak, "{sa} vs {peak}");
    }
}
