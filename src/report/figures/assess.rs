//! The charts of an assessment, as data for [`crate::drawing::chart`]: the capacity curves
//! (the multiplier α against the control displacement `dₖ`, one curve per direction
//! assessed) and the ADRS plot of the governing direction (spectral acceleration against
//! spectral displacement: the capacity `a*(d*)` against the elastic demand spectrum
//! `(SDe(T), Se(T))`, with `du*`, the secant to `(ds*, as*)` that defines `Ts`, the demand
//! `SDe(Ts)` and the linear demand). The curves are drawn as lines; only their significant
//! points (rest, `ds*`, `du*`, the end at α = 0) carry markers. Labels use the engineer's
//! symbols (α₀, dₖ, m/s²), not the JSON keys.

use crate::assess::{Capacity, Verdict};
use crate::drawing::chart::{Chart, Series};
use crate::outcome::Direction;

/// The point of the curve at spectral displacement `d` (linear between the curve's points):
/// `(d_k, alpha, d*, a*)`, None outside the curve.
fn at_d_star(capacity: &Capacity, d: f64) -> Option<(f64, f64, f64, f64)> {
    let c = &capacity.curve;
    let i = c
        .windows(2)
        .position(|w| w[0].d_star <= d && d <= w[1].d_star)?;
    let (p, q) = (&c[i], &c[i + 1]);
    let f = if q.d_star > p.d_star {
        (d - p.d_star) / (q.d_star - p.d_star)
    } else {
        0.0
    };
    let lerp = |a: f64, b: f64| a + f * (b - a);
    Some((
        lerp(p.d_k, q.d_k),
        lerp(p.alpha, q.alpha),
        d,
        lerp(p.a_star, q.a_star),
    ))
}

/// The capacity curves α(dₖ) (dₖ in mm) of every direction assessed (`directions`: each
/// direction's capacity and verdict; `governing` indexes the governing one, drawn first), each
/// marked at rest (α₀), at `du*` and at α = 0 (`dₖ0`).
pub fn capacity_chart(
    directions: &[(&Capacity, &Verdict)],
    governing: usize,
    title: &str,
) -> Chart {
    let order = std::iter::once(governing).chain((0..directions.len()).filter(|i| *i != governing));
    let series = order
        .filter_map(|i| directions.get(i).map(|d| (i, d)))
        .map(|(i, (c, v))| {
            let points = c.curve.iter().map(|p| (1e3 * p.d_k, p.alpha)).collect();
            let mut marks = vec![(0.0, c.alpha0)];
            if let Some((dk, alpha, _, _)) = at_d_star(c, v.du_star) {
                marks.push((1e3 * dk, alpha));
            }
            marks.push((1e3 * c.d_k0, 0.0));
            let governing = if i == governing && directions.len() > 1 {
                " (governing)"
            } else {
                ""
            };
            Series::line(
                format!(
                    "{}{governing}: α₀ = {:.4}",
                    match c.direction {
                        Direction::Right => "right",
                        Direction::Left => "left",
                    },
                    c.alpha0
                ),
                points,
                marks,
            )
        })
        .collect();
    Chart {
        title: format!(
            "{title}: capacity curves (control point: centroid of {})",
            directions
                .iter()
                .map(|(c, _)| format!(
                    "block {} {}",
                    c.control_block,
                    match c.direction {
                        Direction::Right => "right",
                        Direction::Left => "left",
                    }
                ))
                .collect::<Vec<_>>()
                .join(", ")
        ),
        x_label: "control displacement dₖ (mm)   ● at rest (α₀), at du* = 0.4 d0*, at α = 0 (dₖ₀)"
            .into(),
        y_label: "load multiplier α (horizontal force / weight)".into(),
        legend_title: None,
        series,
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

/// The ADRS plot of one direction: `a*` (m/s²) against `d*` (mm), capacity and demand.
/// `direction_note` follows the title (e.g. "load to the left, governing").
pub fn adrs_chart(
    capacity: &Capacity,
    verdict: &Verdict,
    title: &str,
    direction_note: &str,
) -> Chart {
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
    let mut cap_marks = vec![
        (0.0, capacity.a0_star),
        (1e3 * verdict.ds_star, verdict.as_star),
    ];
    if let Some((_, _, d, a)) = at_d_star(capacity, verdict.du_star) {
        cap_marks.push((1e3 * d, a));
    }
    cap_marks.push((1e3 * capacity.d0_star, 0.0));
    let a_top = capacity.a0_star.max(sp.se(verdict.ts)) * 1.1;
    // The secant of period Ts, from the origin through (ds*, as*).
    let slope = verdict.as_star / verdict.ds_star;
    let secant_end = (a_top / slope).min(d_max);
    let performance = (1e3 * demand_ts, sp.se(verdict.ts));
    Chart {
        title: format!(
            "{title}, {direction_note}: du* {:.1} vs {:.1} mm; a0* {:.3} vs {:.3} m/s²",
            1e3 * verdict.du_star,
            1e3 * verdict.nonlinear.demand,
            capacity.a0_star,
            verdict.linear.demand
        ),
        x_label: "spectral displacement d* (mm)   ● a0*, (ds*, as*), du*, d0*".into(),
        y_label: "spectral acceleration a* (m/s²)".into(),
        legend_title: None,
        series: vec![
            Series::line("capacity a*(d*)", cap, cap_marks),
            Series::line("elastic demand (SDe, Se)", demand, [performance]),
            Series::line(
                format!("du* = 0.4 d0* = {:.1} mm", 1e3 * verdict.du_star),
                vec![(1e3 * verdict.du_star, 0.0), (1e3 * verdict.du_star, a_top)],
                [],
            ),
            Series::line(
                format!("secant of period Ts = {:.3} s", verdict.ts),
                vec![(0.0, 0.0), (1e3 * secant_end, slope * secant_end)],
                [],
            ),
            Series::line(
                format!("nonlinear demand SDe(Ts) = {:.1} mm", 1e3 * demand_ts),
                vec![(1e3 * demand_ts, 0.0), performance],
                [],
            ),
            Series::line(
                format!("linear demand = {:.3} m/s²", verdict.linear.demand),
                vec![
                    (0.0, verdict.linear.demand),
                    (1e3 * capacity.d0_star, verdict.linear.demand),
                ],
                [],
            ),
        ],
    }
}
