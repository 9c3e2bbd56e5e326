//! Values with units. A scene is in SI units (N, Pa, m, N/m^3, N/m), and a dimensioned key
//! also takes a string of a number and a unit, as engineers write them: `thickness = "150 mm"`,
//! `compressive_strength = "5 MPa"` (or `"5 N/mm2"`), `unit_weight = "20 kN/m3"`,
//! `force = ["0 kN", "-10 kN"]`, `intensity = "12 kN/m"`. Such strings are turned into SI
//! numbers before the scene is validated ([`to_si`]), so every reader of the scene (the
//! analyses, `--set`, sweeps, the page of `serve`, Python) sees plain numbers. A string that is
//! not a number with a unit of the key's kind is left as it is, and the key's check refuses it
//! saying how to write the value ([`expected`]).

use toml::{Table, Value};

/// What a key measures.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Dimension {
    /// m.
    Length,
    /// Pa.
    Stress,
    /// N/m^3.
    UnitWeight,
    /// N.
    Force,
    /// N/m.
    ForcePerLength,
}

impl Dimension {
    /// The units accepted, with their factor to SI; matched case-insensitively (no two differ
    /// only in case within one kind). The first is the SI unit.
    fn units(self) -> &'static [(&'static str, f64)] {
        match self {
            Dimension::Length => &[("m", 1.0), ("mm", 1e-3), ("cm", 1e-2), ("km", 1e3)],
            Dimension::Stress => &[
                ("Pa", 1.0),
                ("kPa", 1e3),
                ("MPa", 1e6),
                ("GPa", 1e9),
                ("N/mm2", 1e6),
                ("N/mm^2", 1e6),
                ("N/m2", 1.0),
                ("N/m^2", 1.0),
                ("kN/m2", 1e3),
                ("kN/m^2", 1e3),
            ],
            Dimension::UnitWeight => &[
                ("N/m3", 1.0),
                ("N/m^3", 1.0),
                ("kN/m3", 1e3),
                ("kN/m^3", 1e3),
            ],
            Dimension::Force => &[("N", 1.0), ("kN", 1e3), ("MN", 1e6)],
            Dimension::ForcePerLength => &[("N/m", 1.0), ("kN/m", 1e3)],
        }
    }

    /// The SI unit's name.
    pub fn si(self) -> &'static str {
        self.units()[0].0
    }

    /// An example in words for messages.
    fn example(self) -> &'static str {
        match self {
            Dimension::Length => "0.15 or \"150 mm\"",
            Dimension::Stress => "5e6 or \"5 MPa\" (= \"5 N/mm2\")",
            Dimension::UnitWeight => "20000 or \"20 kN/m3\"",
            Dimension::Force => "-10000 or \"-10 kN\"",
            Dimension::ForcePerLength => "12000 or \"12 kN/m\"",
        }
    }
}

/// The dimension of a scene key (its last part: `thickness`, `piers.left.height`), if it has
/// one. Angles (`*_deg`, in degrees) and ratios (friction, vertical_ratio, tolerance) have
/// none.
pub fn dimension_of(key: &str) -> Option<Dimension> {
    let name = key.rsplit('.').next().unwrap_or(key);
    Some(match name {
        "thickness" | "radius" | "span" | "rise" | "eccentricity" | "depth" | "level"
        | "height" | "width" | "bottom_width" | "top_width" | "from_x" | "to_x" | "ground_y"
        | "at" | "from" | "to" => Dimension::Length,
        "compressive_strength" | "tie_design_strength" => Dimension::Stress,
        "unit_weight" => Dimension::UnitWeight,
        "force" | "capacity" | "prestress" | "tensile_capacity" => Dimension::Force,
        "intensity" => Dimension::ForcePerLength,
        _ => return None,
    })
}

/// `text` as a number of `dim` in SI: `"150 mm"` is 0.15 (m), `"5MPa"` is 5e6 (Pa); None when
/// it is not a finite number followed by one of the kind's units (a bare number is not taken
/// here: the scene's numbers are numbers).
pub fn quantity(text: &str, dim: Dimension) -> Option<f64> {
    let t = text.trim();
    // The longest prefix that reads as a number, then a unit.
    let (number, unit) = (1..t.len())
        .rev()
        .filter(|&i| t.is_char_boundary(i))
        .find_map(|i| {
            let x = t[..i].trim().parse::<f64>().ok()?;
            Some((x, t[i..].trim()))
        })?;
    if !number.is_finite() || unit.is_empty() {
        return None;
    }
    let factor = dim
        .units()
        .iter()
        .find(|(name, _)| name.eq_ignore_ascii_case(unit))?
        .1;
    Some(number * factor)
}

/// What a key takes, for a message refusing a value: "a number in m (SI), e.g. 0.15 or
/// \"150 mm\" (units: m, mm, cm, km)" for a dimensioned key, "a number" for the others.
pub fn expected(key: &str) -> String {
    match dimension_of(key) {
        Some(d) => format!(
            "a number in {} (SI), e.g. {}; a string takes the units {}",
            d.si(),
            d.example(),
            d.units()
                .iter()
                .map(|(n, _)| *n)
                .collect::<Vec<_>>()
                .join(", ")
        ),
        None if key.ends_with("_deg") => "a number (degrees)".to_string(),
        None => "a number".to_string(),
    }
}

/// Replace, in the sections of a scene, every string of a dimensioned key that is a number
/// with a unit by its SI value (in arrays too: `force = ["0 kN", "-10 kN"]`). Other values are
/// left for the scene's checks.
pub fn to_si(table: &mut Table) {
    for (name, section) in table.iter_mut() {
        match section {
            Value::Table(t) => convert_table(t, name == "piers"),
            // [[loads]], [[ties]]
            Value::Array(items) => {
                for item in items {
                    if let Value::Table(t) = item {
                        convert_table(t, false);
                    }
                }
            }
            _ => {}
        }
    }
}

fn convert_table(t: &mut Table, nested: bool) {
    for (key, value) in t.iter_mut() {
        match value {
            // `[piers.left]` and `[piers.right]`.
            Value::Table(inner) if nested => convert_table(inner, false),
            _ => {
                if let Some(d) = dimension_of(key) {
                    convert_value(value, d);
                }
            }
        }
    }
}

fn convert_value(value: &mut Value, d: Dimension) {
    match value {
        Value::String(s) => {
            if let Some(x) = quantity(s, d) {
                *value = Value::Float(x);
            }
        }
        Value::Array(items) => items.iter_mut().for_each(|v| convert_value(v, d)),
        _ => {}
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn quantities_are_read_in_si() {
        let close = |a: Option<f64>, b: f64| a.is_some_and(|a| (a - b).abs() <= 1e-12 * b.abs());
        assert!(close(quantity("150 mm", Dimension::Length), 0.15));
        assert!(close(quantity("150mm", Dimension::Length), 0.15));
        assert!(close(quantity(" 2 m ", Dimension::Length), 2.0));
        assert!(close(quantity("5 MPa", Dimension::Stress), 5e6));
        assert!(close(quantity("5 mpa", Dimension::Stress), 5e6));
        assert!(close(quantity("5 N/mm2", Dimension::Stress), 5e6));
        assert!(close(quantity("1.5e3 kPa", Dimension::Stress), 1.5e6));
        assert!(close(quantity("20 kN/m3", Dimension::UnitWeight), 20e3));
        assert!(close(quantity("-10 kN", Dimension::Force), -1e4));
        assert!(close(quantity("12 kN/m", Dimension::ForcePerLength), 12e3));
        // Not a quantity of the kind: left for the key's check.
        assert_eq!(quantity("5 MPa", Dimension::Length), None);
        assert_eq!(quantity("10", Dimension::Force), None);
        assert_eq!(quantity("kN", Dimension::Force), None);
        assert_eq!(quantity("1e400 N", Dimension::Force), None);
        assert_eq!(quantity("ten kN", Dimension::Force), None);
    }

    #[test]
    fn a_scene_table_is_converted_in_place() {
        let mut t: Table =
            "[arch]\nthickness = \"15 cm\"\nshape = \"circular\"\nembrace_deg = \"90 deg\"\n\
             [piers.left]\nheight = \"2 m\"\n[[loads]]\nforce = [\"0 kN\", \"-1 kN\"]\n"
                .parse()
                .expect("toml");
        to_si(&mut t);
        assert_eq!(t["arch"]["thickness"].as_float(), Some(0.15));
        assert_eq!(t["arch"]["shape"].as_str(), Some("circular"));
        // Angles take no units: left for the check to refuse.
        assert_eq!(t["arch"]["embrace_deg"].as_str(), Some("90 deg"));
        assert_eq!(t["piers"]["left"]["height"].as_float(), Some(2.0));
        assert_eq!(t["loads"][0]["force"][1].as_float(), Some(-1000.0));
    }
}
