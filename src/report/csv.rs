//! The CSV printer: the thrust line (`analyze --thrust-csv`, one row per joint), a dynamic
//! run's time history (`dem --history`), a pulse curve's points (`dem --pulse-curve`), and
//! any table of a document ([`write_table`]).

use super::joint_label;
use crate::assembly::Assembly;
use crate::statics::StaticResult;

/// Write the thrust line as CSV: one row per joint.
pub fn write_thrust_csv<W: std::io::Write>(
    out: W,
    assembly: &Assembly,
    r: &StaticResult,
) -> Result<(), csv::Error> {
    let mut w = csv::Writer::from_writer(out);
    w.write_record([
        "joint", "kind", "x", "y", "N", "V", "M", "e", "p1_x", "p1_y", "p2_x", "p2_y",
    ])?;
    let forces = r.forces.as_deref().unwrap_or(&[]);
    let points = r.thrust_points(assembly);
    for (i, (j, f)) in assembly.joints.iter().zip(forces).enumerate() {
        let (x, y) = points[i].map_or((String::new(), String::new()), |p| {
            (p.x.to_string(), p.y.to_string())
        });
        let e = r.eccentricity(i).map_or(String::new(), |e| e.to_string());
        w.write_record([
            i.to_string(),
            joint_label(j.kind),
            x,
            y,
            f.n.to_string(),
            f.v.to_string(),
            f.m.to_string(),
            e,
            j.p1.x.to_string(),
            j.p1.y.to_string(),
            j.p2.x.to_string(),
            j.p2.y.to_string(),
        ])?;
    }
    w.flush()?;
    Ok(())
}

/// Write a dynamic run's time history of the control block: one row per sample.
pub fn write_history_csv<W: std::io::Write>(
    out: W,
    history: &[crate::dem::dynamic::Sample],
) -> Result<(), csv::Error> {
    let mut w = csv::Writer::from_writer(out);
    w.write_record([
        "time_s",
        "ground_acceleration_m_s2",
        "displacement_m",
        "rotation_rad",
        "ground_acceleration_vertical_m_s2",
    ])?;
    for h in history {
        w.write_record([
            format!("{:.6}", h.time),
            format!("{:.6e}", h.ground_acceleration),
            format!("{:.9e}", h.displacement),
            format!("{:.9e}", h.rotation),
            format!("{:.6e}", h.ground_acceleration_vertical),
        ])?;
    }
    w.flush()?;
    Ok(())
}

/// Write a pulse curve: one row per shape and period.
pub fn write_pulse_curve_csv<W: std::io::Write>(
    out: W,
    rep: &super::PulseCurveReport,
) -> Result<(), csv::Error> {
    let g = crate::dem::record::STANDARD_GRAVITY;
    let mut w = csv::Writer::from_writer(out);
    w.write_record([
        "shape",
        "period_s",
        "amplitude_survives_m_s2",
        "amplitude_collapses_m_s2",
        "amplitude_collapses_g",
        "runs",
    ])?;
    for p in &rep.points {
        w.write_record([
            p.shape.to_string(),
            format!("{}", p.period),
            format!("{:.6}", p.amplitude_survives),
            p.amplitude_collapses
                .map_or(String::new(), |a| format!("{a:.6}")),
            p.amplitude_collapses
                .map_or(String::new(), |a| format!("{:.6}", a / g)),
            p.runs.to_string(),
        ])?;
    }
    w.flush()?;
    Ok(())
}

/// Write a document's table: its headers, then its values as text (without units).
pub fn write_table<W: std::io::Write>(
    out: W,
    table: &super::document::Table,
) -> Result<(), csv::Error> {
    let mut w = csv::Writer::from_writer(out);
    w.write_record(table.columns.iter().map(|c| c.header.as_str()))?;
    for row in &table.rows {
        w.write_record(row.iter().map(super::document::Value::show))?;
    }
    w.flush()?;
    Ok(())
}
