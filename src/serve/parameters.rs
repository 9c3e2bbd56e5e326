//! What the page offers: the scene keys it has sliders for (label, unit, slider range) and
//! the structures it starts from (presets: the bundled example scenes).
//!
//! Slider ranges are practical ranges for a structure of a few metres, not the validity
//! ranges: the scene parser ([`crate::scene`]) decides what is valid, and its message is shown
//! beside the field when a value typed into a number field is refused. A preset may narrow a
//! range to its own size (a 1 m arch's thickness slider does not run to 1.5 m).

use serde::Serialize;

/// The slider ranges of the portals (bare and tied): a 1 m arch on 1 m piers.
const PORTAL_RANGES: &[(&str, f64, f64)] = &[
    ("arch.thickness", 0.05, 0.5),
    ("piers.height", 0.2, 6.0),
    ("piers.width", 0.1, 2.0),
];

/// The scene the page opens with when `voussoir serve` is given none.
pub const DEFAULT_SCENE: &str = include_str!("../../data/semicircular.toml");

/// One slider: a scene key, how to label it, and its practical range.
#[derive(Debug, Clone, Copy, Serialize)]
pub struct Slider {
    /// The dotted scene key, e.g. `arch.thickness`; an entry of `[[loads]]` is written as
    /// the scene's errors write it, `loads[1].intensity`.
    pub key: &'static str,
    pub label: &'static str,
    /// SI unit, or `deg` for keys ending in `_deg`; empty when dimensionless.
    pub unit: &'static str,
    pub min: f64,
    pub max: f64,
    pub step: f64,
    /// A whole number (voussoirs, courses).
    pub integer: bool,
    /// The scene section the key is in: the page shows the slider when the scene has it.
    pub section: &'static str,
    /// For `arch` keys, the `arch.shape` values the key belongs to.
    pub arch_shapes: &'static [&'static str],
    /// What an absent key means, for keys that may be left out (e.g. friction: infinite).
    pub absent: Option<&'static str>,
    pub help: &'static str,
    /// A step of its own for some `arch.shape` values (a pointed arch has an even number of
    /// voussoirs), as `{"pointed": 2}`.
    #[serde(serialize_with = "as_map")]
    pub shape_steps: &'static [(&'static str, f64)],
    /// Sections in whose presence the key does not apply (a portal's arch embraces 180 deg).
    pub not_with: &'static [&'static str],
    /// For `piers` keys, the pier profiles (`piers.shape`: `rectangular`, the default,
    /// `stepped`, `battered`) that take the key; empty: every profile. A stepped pier has no
    /// `width` and its `courses` are its number of widths, so those sliders could only error.
    pub pier_shapes: &'static [&'static str],
    /// The value is a list of numbers (a stepped pier's `widths`, base to top): the page
    /// shows a text field of comma-separated numbers, with no slider and no chart; `min`,
    /// `max` and `step` are those of one entry.
    pub list: bool,
}

fn as_map<S: serde::Serializer>(
    pairs: &&'static [(&'static str, f64)],
    serializer: S,
) -> Result<S::Ok, S::Error> {
    use serde::ser::SerializeMap;
    let mut map = serializer.serialize_map(Some(pairs.len()))?;
    for (k, v) in pairs.iter() {
        map.serialize_entry(k, v)?;
    }
    map.end()
}

/// A slider and the presets whose scenes have its key (`GET /api/parameters`).
#[derive(Debug, Clone, Serialize)]
pub struct Parameter {
    #[serde(flatten)]
    pub slider: Slider,
    /// The presets whose scenes have the key (or may take it: see `absent`).
    pub shapes: Vec<&'static str>,
}

/// One starting structure.
#[derive(Debug, Clone)]
pub struct Preset {
    pub name: &'static str,
    pub label: &'static str,
    /// The scene, as TOML (a bundled example scene).
    pub toml: &'static str,
    /// Slider ranges narrowed to this structure: `(key, min, max)`.
    pub ranges: &'static [(&'static str, f64, f64)],
}

const ALL_SHAPES: &[&str] = &["circular", "pointed", "basket"];

/// The presets, in the order of the shape picker.
pub const PRESETS: &[Preset] = &[
    Preset {
        name: "circular",
        label: "Circular arch",
        toml: DEFAULT_SCENE,
        ranges: &[("arch.thickness", 0.08, 0.5), ("arch.radius", 0.5, 10.0)],
    },
    Preset {
        name: "pointed",
        label: "Pointed arch",
        toml: include_str!("../../data/pointed.toml"),
        // At e = 0.2 the joint next to the crown crosses the axis above 164 voussoirs.
        ranges: &[
            ("arch.thickness", 0.05, 0.5),
            ("arch.radius", 0.5, 10.0),
            ("arch.voussoirs", 4.0, 164.0),
        ],
    },
    Preset {
        name: "basket",
        label: "Basket-handle arch",
        toml: include_str!("../../data/basket.toml"),
        ranges: &[("arch.thickness", 0.05, 0.5), ("arch.rise", 0.3, 1.0)],
    },
    Preset {
        name: "portal",
        label: "Portal (arch on piers)",
        toml: include_str!("../../data/portal.toml"),
        ranges: PORTAL_RANGES,
    },
    Preset {
        name: "tied_portal",
        label: "Portal with a tie rod",
        toml: include_str!("../../data/tied_portal.toml"),
        ranges: PORTAL_RANGES,
    },
    Preset {
        name: "arcade",
        label: "Arcade with a spandrel wall",
        toml: include_str!("../../data/arcade.toml"),
        // The columns carry two springing joints (0.5 m >= 2 t) and the wall's top stays above
        // the crown (R + t/2 < 3.2 m).
        ranges: &[
            ("arch.thickness", 0.1, 0.25),
            ("arch.radius", 1.0, 3.0),
            ("arch.voussoirs", 4.0, 64.0),
            ("piers.height", 0.2, 6.0),
            ("piers.width", 0.25, 2.0),
        ],
    },
    Preset {
        name: "loaded_portal",
        label: "Portal with point and line loads",
        toml: include_str!("../../data/loaded_portal.toml"),
        ranges: &[("arch.thickness", 0.15, 1.2), ("arch.radius", 1.0, 10.0)],
    },
    Preset {
        name: "filled_arch",
        label: "Arch with fill and vertical acceleration",
        toml: include_str!("../../data/filled_arch.toml"),
        ranges: &[("arch.thickness", 0.15, 1.0), ("fill.level", 2.2, 5.0)],
    },
    Preset {
        name: "bridge",
        label: "Arch bridge under a moving tandem",
        toml: include_str!("../../data/rolling_bridge.toml"),
        // The tandem (1.2 m long) stays on the 6.45 m extrados; the fill stays above the
        // crown of the thickest ring (3 + 0.9 / 2 = 3.45 m).
        ranges: &[
            ("vehicles[0].at", -3.2, 2.0),
            ("arch.thickness", 0.3, 0.9),
            ("fill.level", 3.5, 5.0),
        ],
    },
];

/// The sliders, in the order the page lists them.
pub const SLIDERS: &[Slider] = &[
    Slider {
        key: "arch.thickness",
        label: "Thickness t",
        unit: "m",
        min: 0.01,
        max: 1.5,
        step: 0.005,
        integer: false,
        section: "arch",
        arch_shapes: ALL_SHAPES,
        absent: None,
        help: "Thickness of the arch ring, measured radially.",
        shape_steps: &[],
        not_with: &[],
        pier_shapes: &[],
        list: false,
    },
    Slider {
        key: "arch.radius",
        label: "Radius R",
        unit: "m",
        min: 0.5,
        max: 10.0,
        step: 0.05,
        integer: false,
        section: "arch",
        arch_shapes: &["circular", "pointed"],
        absent: None,
        help: "Centreline radius (of each arc of a pointed arch).",
        shape_steps: &[],
        not_with: &[],
        pier_shapes: &[],
        list: false,
    },
    Slider {
        key: "arch.embrace_deg",
        label: "Embrace",
        unit: "deg",
        min: 60.0,
        max: 240.0,
        step: 1.0,
        integer: false,
        section: "arch",
        arch_shapes: &["circular"],
        absent: None,
        help: "Angle the arch spans at its centre (180 for a semicircle; a portal needs 180).",
        shape_steps: &[],
        not_with: &["piers"],
        pier_shapes: &[],
        list: false,
    },
    Slider {
        key: "arch.eccentricity",
        label: "Eccentricity e",
        unit: "m",
        min: 0.0,
        max: 0.6,
        step: 0.01,
        integer: false,
        section: "arch",
        arch_shapes: &["pointed"],
        absent: None,
        help: "Distance of each arc's centre from the axis: 0 is a semicircle.",
        shape_steps: &[],
        not_with: &[],
        pier_shapes: &[],
        list: false,
    },
    Slider {
        key: "arch.span",
        label: "Span",
        unit: "m",
        min: 0.5,
        max: 20.0,
        step: 0.05,
        integer: false,
        section: "arch",
        arch_shapes: &["basket"],
        absent: None,
        help: "Centreline span of the basket-handle arch.",
        shape_steps: &[],
        not_with: &[],
        pier_shapes: &[],
        list: false,
    },
    Slider {
        key: "arch.rise",
        label: "Rise",
        unit: "m",
        min: 0.1,
        max: 10.0,
        step: 0.01,
        integer: false,
        section: "arch",
        arch_shapes: &["basket"],
        absent: None,
        help: "Centreline rise: at most half the span.",
        shape_steps: &[],
        not_with: &[],
        pier_shapes: &[],
        list: false,
    },
    Slider {
        key: "arch.side_angle_deg",
        label: "Side-arc angle",
        unit: "deg",
        min: 10.0,
        max: 80.0,
        step: 1.0,
        integer: false,
        section: "arch",
        arch_shapes: &["basket"],
        absent: None,
        help: "Angle subtended by each side arc of the three-centred arch.",
        shape_steps: &[],
        not_with: &[],
        pier_shapes: &[],
        list: false,
    },
    Slider {
        key: "arch.voussoirs",
        label: "Voussoirs n",
        unit: "",
        min: 4.0,
        max: 200.0,
        step: 1.0,
        integer: true,
        section: "arch",
        arch_shapes: ALL_SHAPES,
        absent: None,
        help: "Number of voussoirs (even for a pointed arch).",
        shape_steps: &[("pointed", 2.0)],
        not_with: &[],
        pier_shapes: &[],
        list: false,
    },
    Slider {
        key: "piers.height",
        label: "Pier height h",
        unit: "m",
        min: 0.2,
        max: 10.0,
        step: 0.05,
        integer: false,
        section: "piers",
        arch_shapes: &[],
        absent: None,
        help: "Height of the piers below the springings.",
        shape_steps: &[],
        not_with: &[],
        pier_shapes: &[],
        list: false,
    },
    Slider {
        key: "piers.width",
        label: "Pier width b",
        unit: "m",
        min: 0.1,
        max: 5.0,
        step: 0.05,
        integer: false,
        section: "piers",
        arch_shapes: &[],
        absent: None,
        help: "Width of each pier.",
        shape_steps: &[],
        not_with: &[],
        pier_shapes: &["rectangular"],
        list: false,
    },
    Slider {
        key: "piers.courses",
        label: "Pier courses",
        unit: "",
        min: 1.0,
        max: 20.0,
        step: 1.0,
        integer: true,
        section: "piers",
        arch_shapes: &[],
        absent: None,
        help: "Number of blocks stacked in each pier.",
        shape_steps: &[],
        not_with: &[],
        pier_shapes: &["rectangular", "battered"],
        list: false,
    },
    Slider {
        key: "piers.bottom_width",
        label: "Pier base width",
        unit: "m",
        min: 0.1,
        max: 5.0,
        step: 0.05,
        integer: false,
        section: "piers",
        arch_shapes: &[],
        absent: None,
        help: "Width of each battered pier at its base.",
        shape_steps: &[],
        not_with: &[],
        pier_shapes: &["battered"],
        list: false,
    },
    Slider {
        key: "piers.top_width",
        label: "Pier top width",
        unit: "m",
        min: 0.1,
        max: 5.0,
        step: 0.05,
        integer: false,
        section: "piers",
        arch_shapes: &[],
        absent: None,
        help: "Width of each battered pier under the springing.",
        shape_steps: &[],
        not_with: &[],
        pier_shapes: &["battered"],
        list: false,
    },
    Slider {
        key: "piers.widths",
        label: "Course widths",
        unit: "m",
        min: 0.1,
        max: 5.0,
        step: 0.05,
        integer: false,
        section: "piers",
        arch_shapes: &[],
        absent: None,
        help: "Width of each course of a stepped pier, base to top, separated by commas: one course per width.",
        shape_steps: &[],
        not_with: &[],
        pier_shapes: &["stepped"],
        list: true,
    },
    Slider {
        key: "arcade.bays",
        label: "Bays",
        unit: "",
        min: 1.0,
        max: 6.0,
        step: 1.0,
        integer: true,
        section: "arcade",
        arch_shapes: &[],
        absent: None,
        help: "Equal bays side by side, each the arch ring; one bay is the portal.",
        shape_steps: &[],
        not_with: &[],
        pier_shapes: &[],
        list: false,
    },
    Slider {
        key: "arcade.column_width",
        label: "Column width",
        unit: "m",
        min: 0.5,
        max: 2.0,
        step: 0.05,
        integer: false,
        section: "arcade",
        arch_shapes: &[],
        absent: None,
        help: "Width of the interior columns (at least two springing joints); they take the piers' height and courses.",
        shape_steps: &[],
        not_with: &[],
        pier_shapes: &[],
        list: false,
    },
    Slider {
        key: "spandrel.level",
        label: "Wall top",
        unit: "m",
        min: 2.2,
        max: 6.0,
        step: 0.05,
        integer: false,
        section: "spandrel",
        arch_shapes: &[],
        absent: None,
        help: "Height of the spandrel wall's top above the springing line (above the crown's extrados).",
        shape_steps: &[],
        not_with: &[],
        pier_shapes: &[],
        list: false,
    },
    Slider {
        key: "spandrel.course_height",
        label: "Course height",
        unit: "m",
        min: 0.1,
        max: 1.0,
        step: 0.01,
        integer: false,
        section: "spandrel",
        arch_shapes: &[],
        absent: None,
        help: "Height of a course of the spandrel wall.",
        shape_steps: &[],
        not_with: &[],
        pier_shapes: &[],
        list: false,
    },
    Slider {
        key: "spandrel.unit_length",
        label: "Unit length",
        unit: "m",
        min: 0.2,
        max: 2.0,
        step: 0.05,
        integer: false,
        section: "spandrel",
        arch_shapes: &[],
        absent: None,
        help: "Length of a unit of the wall's running bond (head joints half a unit apart in alternate courses).",
        shape_steps: &[],
        not_with: &[],
        pier_shapes: &[],
        list: false,
    },
    Slider {
        key: "fill.level",
        label: "Fill level",
        unit: "m",
        min: 0.0,
        max: 10.0,
        step: 0.05,
        integer: false,
        section: "fill",
        arch_shapes: &[],
        absent: None,
        help: "Height of the fill's top surface (y = 0 at the springings).",
        shape_steps: &[],
        not_with: &[],
        pier_shapes: &[],
        list: false,
    },
    Slider {
        key: "fill.unit_weight",
        label: "Fill unit weight",
        unit: "N/m^3",
        min: 0.0,
        max: 25000.0,
        step: 500.0,
        integer: false,
        section: "fill",
        arch_shapes: &[],
        absent: None,
        help: "Unit weight of the fill, which loads the extrados vertically.",
        shape_steps: &[],
        not_with: &[],
        pier_shapes: &[],
        list: false,
    },
    Slider {
        key: "seismic.vertical_ratio",
        label: "Vertical / horizontal acceleration",
        unit: "",
        min: -1.0,
        max: 1.0,
        step: 0.05,
        integer: false,
        section: "seismic",
        arch_shapes: &[],
        absent: Some("0 (no vertical acceleration)"),
        help: "Vertical ground acceleration as a share of the horizontal one (positive upward).",
        shape_steps: &[],
        not_with: &[],
        pier_shapes: &[],
        list: false,
    },
    Slider {
        key: "loads[0].intensity",
        label: "Line load (loads[0])",
        unit: "N/m",
        min: 0.0,
        max: 30000.0,
        step: 250.0,
        integer: false,
        section: "loads",
        arch_shapes: &[],
        absent: None,
        help: "Intensity of the first [[loads]] entry, when it is a line load (downward).",
        shape_steps: &[],
        not_with: &[],
        pier_shapes: &[],
        list: false,
    },
    Slider {
        key: "loads[1].intensity",
        label: "Line load (loads[1])",
        unit: "N/m",
        min: 0.0,
        max: 30000.0,
        step: 250.0,
        integer: false,
        section: "loads",
        arch_shapes: &[],
        absent: None,
        help: "Intensity of the second [[loads]] entry, when it is a line load (downward).",
        shape_steps: &[],
        not_with: &[],
        pier_shapes: &[],
        list: false,
    },
    Slider {
        key: "vehicles[0].at",
        label: "Vehicle position (vehicles[0])",
        unit: "m",
        min: -10.0,
        max: 10.0,
        step: 0.05,
        integer: false,
        section: "vehicles",
        arch_shapes: &[],
        absent: None,
        help: "x of the first axle of the first [[vehicles]] entry: move it and the adequacy factor (the collapse load as a multiple of the vehicle) follows; its chart is lambda against the position.",
        shape_steps: &[],
        not_with: &[],
        pier_shapes: &[],
        list: false,
    },
    Slider {
        key: "ties[0].capacity",
        label: "Tie rod capacity (ties[0])",
        unit: "N",
        min: 0.0,
        max: 10000.0,
        step: 50.0,
        integer: false,
        section: "ties",
        arch_shapes: &[],
        absent: None,
        help: "The force at which the first tie rod yields; 0 is no tie. Drawn with its force at collapse.",
        shape_steps: &[],
        not_with: &[],
        pier_shapes: &[],
        list: false,
    },
    Slider {
        key: "material.friction",
        label: "Friction coefficient",
        unit: "",
        min: 0.1,
        max: 2.0,
        step: 0.01,
        integer: false,
        section: "material",
        arch_shapes: &[],
        absent: Some("inf (joints cannot slide)"),
        help: "Coulomb friction coefficient of the joints.",
        shape_steps: &[],
        not_with: &[],
        pier_shapes: &[],
        list: false,
    },
    Slider {
        key: "material.unit_weight",
        label: "Unit weight",
        unit: "N/m^3",
        min: 10000.0,
        max: 30000.0,
        step: 500.0,
        integer: false,
        section: "material",
        arch_shapes: &[],
        absent: Some("20000 (the default)"),
        help: "Unit weight of the masonry.",
        shape_steps: &[],
        not_with: &[],
        pier_shapes: &[],
        list: false,
    },
    Slider {
        key: "material.compressive_strength",
        label: "Compressive strength",
        unit: "Pa",
        min: 0.5e6,
        max: 50e6,
        step: 0.5e6,
        integer: false,
        section: "material",
        arch_shapes: &[],
        absent: Some("inf (joints cannot crush)"),
        help: "Masonry compressive strength: hinges move inward by half the compressed zone.",
        shape_steps: &[],
        not_with: &[],
        pier_shapes: &[],
        list: false,
    },
];

/// The value at a dotted scene key (`arch.thickness`, `piers.left.height`,
/// `loads[1].intensity`) in a scene table, when it is there.
pub fn lookup<'a>(table: &'a toml::Table, key: &str) -> Option<&'a toml::Value> {
    let mut parts = key.split('.');
    let first = parts.next()?;
    let mut value = match first.split_once('[') {
        Some((list, index)) => table
            .get(list)?
            .as_array()?
            .get(index.strip_suffix(']')?.parse::<usize>().ok()?)?,
        None => table.get(first)?,
    };
    for part in parts {
        value = value.get(part)?;
    }
    Some(value)
}

/// Whether a preset's scene (`table`) has the slider's key, or may take it (a key whose
/// absence means something, such as infinite friction, or the optional vertical component).
fn preset_has(table: &toml::Table, slider: &Slider) -> bool {
    if slider.not_with.iter().any(|sec| table.contains_key(*sec)) {
        return false;
    }
    if !slider.pier_shapes.is_empty() && !slider.pier_shapes.contains(&pier_shape(table)) {
        return false;
    }
    if lookup(table, slider.key).is_some() {
        return true;
    }
    let has_section = table.contains_key(slider.section);
    slider.absent.is_some() && (has_section || slider.section == "seismic")
}

/// The profile of a scene's common pier table (`piers.shape`, `rectangular` when left out).
pub fn pier_shape(table: &toml::Table) -> &str {
    lookup(table, "piers.shape")
        .and_then(toml::Value::as_str)
        .unwrap_or("rectangular")
}

/// Every slider, with the presets whose scenes have its key.
pub fn parameters() -> Vec<Parameter> {
    // Each preset's scene read once (a bundled scene that did not read would list no key).
    let presets: Vec<(&str, Option<toml::Table>)> = PRESETS
        .iter()
        .map(|p| (p.name, p.toml.parse().ok()))
        .collect();
    SLIDERS
        .iter()
        .map(|&slider| Parameter {
            slider,
            shapes: presets
                .iter()
                .filter(|(_, table)| table.as_ref().is_some_and(|t| preset_has(t, &slider)))
                .map(|(name, _)| *name)
                .collect(),
        })
        .collect()
}
