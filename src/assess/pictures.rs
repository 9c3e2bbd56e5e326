//! The charts of an assessment, as data for [`crate::thrustline::chart`]: the capacity curve
//! (alpha against the control displacement `d_k`) and the ADRS plot (spectral acceleration
//! against spectral displacement: the capacity `a*(d*)` against the elastic demand spectrum
//! `(SDe(T), Se(T))`, with `du*`, the secant to `(ds*, as*)` that defines `Ts`, and the demand
//! `SDe(Ts)`).

use super::{Capacity, Verdict};
use crate::thrustline::chart::{Chart, Series};

/// Alpha against `d_k` (mm).
pub fn capacity_chart(capacity: &Capacity, title: &str) -> Chart {
    let points = capacity
        .curve
        .iter()
        .map(|p| (1e3 * p.d_k, p.alpha))
        .collect();
    Chart {
        title: format!(
            "{title}: capacity curve, alpha0 = {:.4}, d_k0 = {:.1} mm (control: block {})",
            capacity.alpha0,
            1e3 * capacity.d_k0,
            capacity.control_block
        ),
        x_label: "control displacement d_k (mm)".into(),
        y_label: "multiplier alpha".into(),
        legend_title: None,
        series: vec![Series {
            name: "alpha(d_k)".into(),
            points,
        }],
    }
}

/// Periods (s) at which the demand spectrum is drawn: up to `TE` (where the displacement
/// spectrum stops growing), finely enough to show its corners.
fn periods(verdict: &Verdict, d_max: f64) -> Vec<f64> {
    let sp = &verdict.spectrum;
    let n = 400;
    (0..=n)
        .map(|i| sp.te * i as f64 / n as f64)
        .chain([sp.tb, sp.tc, sp.td])
        .filter(|t| sp.sde(*t) <= d_max)
        .collect()
}

/// The ADRS plot: `a*` (m/s^2) against `d*` (mm), capacity and demand.
pub fn adrs_chart(capacity: &Capacity, verdict: &Verdict, title: &str) -> Chart {
    let sp = &verdict.spectrum;
    let demand_ts = verdict.nonlinear.demand;
    let d_max = 1.5 * capacity.d0_star.max(demand_ts);
    let mut ts: Vec<f64> = periods(verdict, d_max);
    ts.sort_by(f64::total_cmp);
    let demand = ts.iter().map(|&t| (1e3 * sp.sde(t), sp.se(t))).collect();
    let cap = capacity
        .curve
        .iter()
        .map(|p| (1e3 * p.d_star, p.a_star))
        .collect();
    let a_top = capacity.a0_star.max(sp.se(verdict.ts)) * 1.1;
    // The secant of period Ts, from the origin through (ds*, as*).
    let slope = verdict.as_star / verdict.ds_star;
    let secant_end = (a_top / slope).min(d_max);
    Chart {
        title: format!(
            "{title}: du* = {:.1} mm vs demand {:.1} mm (Ts = {:.3} s); a0* = {:.3} vs {:.3} m/s^2",
            1e3 * verdict.du_star,
            1e3 * verdict.nonlinear.demand,
            verdict.ts,
            capacity.a0_star,
            verdict.linear.demand
        ),
        x_label: "spectral displacement d* (mm)".into(),
        y_label: "spectral acceleration a* (m/s^2)".into(),
        legend_title: None,
        series: vec![
            Series {
                name: "capacity a*(d*)".into(),
                points: cap,
            },
            Series {
                name: "elastic demand (SDe, Se)".into(),
                points: demand,
            },
            Series {
                name: format!("du* = {:.1} mm", 1e3 * verdict.du_star),
                points: vec![(1e3 * verdict.du_star, 0.0), (1e3 * verdict.du_star, a_top)],
            },
            Series {
                name: format!("secant of Ts = {:.3} s", verdict.ts),
                points: vec![(0.0, 0.0), (1e3 * secant_end, slope * secant_end)],
            },
            Series {
                name: format!("nonlinear demand = {:.1} mm", 1e3 * demand_ts),
                points: vec![(1e3 * demand_ts, 0.0), (1e3 * demand_ts, sp.se(verdict.ts))],
            },
        ],
    }
}
