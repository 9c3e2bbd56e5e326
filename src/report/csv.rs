//! The thrust line as CSV (`analyze --thrust-csv`): one row per joint.

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
