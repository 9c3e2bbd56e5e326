//! Scenes: what the user describes (shape, thickness, voussoirs, piers, material), read from
//! the TOML format of `shared/spec/geometry.md`, with `--set key=value` overrides and
//! validation that names the key, the value and what is allowed.
//!
//! A `Scene` keeps the TOML table it was read from, so overrides (from the command line, a
//! sweep or the minimum-thickness search) go through exactly the same validation.

pub mod arcade;
mod build;
mod piers;
mod placement;
pub mod reinforcements;
pub mod spandrel;
pub mod spread;
pub mod ties;
pub mod uncertain;
pub mod units;
mod user_blocks;
pub mod vehicles;
pub use arcade::ArcadeSpec;
pub use build::{build, build_for_design, builds_on_this_thread, standing_heights};
pub use piers::{Pier, PierProfile, Piers};
pub use spandrel::SpandrelSpec;
pub use user_blocks::{BlockSource, BlocksSpec};

use crate::error::{did_you_mean, SceneError};
use crate::geometry::{
    basket_radii, side_voussoirs, ArchGeometry, ArchShape, Basket, Circular, Pointed, Stereotomy,
};
use std::collections::BTreeSet;
use std::path::Path;
use std::sync::Arc;
use toml::{Table, Value};

/// Largest number of voussoirs (and of pier courses) a scene may ask for: beyond it the
/// dense outputs and the discrete searches stop being useful, not just slow.
pub const MAX_VOUSSOIRS: usize = 20_000;

/// Largest finite Coulomb coefficient: beyond it the friction limit is infinite to solver
/// precision (mu = 1e8 and inf give the same lambda to 1e-9).
pub const MAX_FRICTION: f64 = 1e8;

/// Largest force component of a point load (N) and intensity of a line load (N/m): far beyond
/// any structure, small enough that sums of loads stay finite.
pub const MAX_FORCE: f64 = 1e15;
/// Largest unit weight of a fill (N/m^3): a hundred times that of lead.
pub const MAX_UNIT_WEIGHT: f64 = 1e7;
/// Smallest `arch.embrace_deg` (degrees): below it a voussoir's area underflows.
pub const MIN_EMBRACE_DEG: f64 = 0.01;

/// Smallest length a scene may give (m): a micrometre.
pub const MIN_LENGTH: f64 = 1e-6;
/// Largest length a scene may give (m): a thousand kilometres.
pub const MAX_LENGTH: f64 = 1e6;
/// Smallest thickness relative to the arch's size (radius, or half the span): thinner rings
/// have no meaning for masonry and lose all digits in the joint geometry.
pub const MIN_RELATIVE_THICKNESS: f64 = 1e-6;

/// How a voussoir's weight and centroid are computed.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum VoussoirShape {
    /// The quadrilateral with straight chords (default; what the DEM simulates).
    Polygon,
    /// The exact annular piece between circular intrados and extrados.
    Curved,
}

/// The arch ring.
#[derive(Debug, Clone)]
pub struct ArchSpec {
    /// The shape and its own dimensions (one type per shape, in `crate::geometry`).
    pub shape: Arc<dyn ArchShape>,
    /// Radial thickness t (m).
    pub thickness: f64,
    /// Number of voussoirs n.
    pub voussoirs: usize,
    pub voussoir_shape: VoussoirShape,
    /// How the ring is cut into voussoirs (`joints`; radial by default).
    pub joints: Stereotomy,
}

impl ArchSpec {
    /// The joints and arcs of the ring, cut with the scene's stereotomy.
    pub fn geometry(&self) -> Result<ArchGeometry, String> {
        let g = self.shape.geometry(self.thickness, self.voussoirs);
        crate::geometry::recut(
            &g,
            self.joints,
            self.voussoir_shape == VoussoirShape::Curved,
        )
    }
}

/// Material and out-of-plane depth.
#[derive(Debug, Clone, PartialEq)]
pub struct Material {
    /// Unit weight (N/m^3).
    pub unit_weight: f64,
    /// Out-of-plane depth (m).
    pub depth: f64,
    /// Coulomb friction coefficient; `f64::INFINITY` means joints cannot slide.
    pub friction: f64,
    /// Compressive strength fc (Pa) of the joints, a rectangular stress block over `depth`;
    /// `f64::INFINITY` (the default) means joints cannot crush.
    pub compressive_strength: f64,
    /// Design yield strength of tie steel (Pa), for choosing bars in a retrofit design.
    /// Default 391e6 (B450C: 450 MPa over the partial factor 1.15).
    pub tie_design_strength: f64,
}

/// Default `material.tie_design_strength` (Pa): B450C, 450 MPa over 1.15.
pub const DEFAULT_TIE_DESIGN_STRENGTH: f64 = 391e6;

/// A load of the scene's `[[loads]]` list, as the user wrote it (placed on blocks by
/// [`fn@crate::scene::build`]).
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
#[serde(tag = "type", rename_all = "snake_case")]
pub enum LoadSpec {
    /// A force at a point, carried by the block whose outline contains the point.
    Point {
        /// Point of application (m).
        at: [f64; 2],
        /// Permanent force (N).
        force: [f64; 2],
        /// Whether the load is a seismic mass `|force_y| / g`.
        seismic: bool,
        /// Whether the load is live: multiplied by lambda under `[action] kind = "live"`.
        live: bool,
    },
    /// A vertical load per metre of horizontal length on the extrados, downward.
    Line {
        from_x: f64,
        to_x: f64,
        /// N/m, downward.
        intensity: f64,
        seismic: bool,
        /// Whether the load is live: multiplied by lambda under `[action] kind = "live"`.
        live: bool,
    },
}

impl LoadSpec {
    pub fn seismic(&self) -> bool {
        match self {
            LoadSpec::Point { seismic, .. } | LoadSpec::Line { seismic, .. } => *seismic,
        }
    }

    /// Whether the load is live (`live = true`).
    pub fn live(&self) -> bool {
        match self {
            LoadSpec::Point { live, .. } | LoadSpec::Line { live, .. } => *live,
        }
    }
}

/// Fill (or masonry) above the arch up to a level, carried by the voussoirs below it.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct FillSpec {
    /// y of the top surface (m).
    pub level: f64,
    /// Unit weight (N/m^3), times the scene depth.
    pub unit_weight: f64,
    pub seismic: bool,
    /// Where loads on the fill stand and how they spread to the extrados (`surface`,
    /// `spread_deg`, `spread`: [`spread`]).
    #[serde(flatten)]
    pub dispersal: spread::Dispersal,
    /// The fill's passive resistance (`passive = true`), when switched on.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub passive: Option<PassiveSpec>,
}

/// `[fill] passive = true`: the fill resists the extrados moving into it
/// (`crate::interaction::passive`).
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct PassiveSpec {
    /// The fill's angle of friction (radians, from `friction_deg`), 0 to < pi/2.
    pub friction: f64,
    /// The mobilised fraction of the passive pressure (`passive_mobilisation`), 0..1.
    pub mobilisation: f64,
}

impl PassiveSpec {
    /// The passive pressure per unit depth below the level and per unit unit weight:
    /// `m_p K_p`.
    pub fn coefficient(&self) -> f64 {
        self.mobilisation * crate::interaction::passive::rankine_kp(self.friction)
    }
}

/// The seismic action beyond its horizontal component.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct SeismicSpec {
    /// Vertical seismic force per unit horizontal one (+y up), -1..1.
    pub vertical_ratio: f64,
}

/// A validated scene.
#[derive(Debug, Clone)]
pub struct Scene {
    /// The parametric arch; None when the structure is the user's blocks (`[blocks]`).
    pub arch: Option<ArchSpec>,
    /// The user's own blocks (`[blocks]`), instead of `[arch]` and `[piers]`.
    pub blocks: Option<Arc<BlocksSpec>>,
    pub piers: Option<Piers>,
    /// `[arcade]`: the bays side by side (None: one arch, or a portal).
    pub arcade: Option<ArcadeSpec>,
    /// `[spandrel]`: the wall in running bond above the ring(s).
    pub spandrel: Option<SpandrelSpec>,
    pub material: Material,
    /// Loads beyond self-weight (`[[loads]]`), in file order.
    pub loads: Vec<LoadSpec>,
    /// Trains of axles (`[[vehicles]]`), in file order.
    pub vehicles: Vec<vehicles::VehicleSpec>,
    /// Tie rods (`[[ties]]`), in file order.
    pub ties: Vec<ties::TieSpec>,
    /// Bonded strips (`[[reinforcements]]`), in file order.
    pub reinforcements: Vec<reinforcements::ReinforcementSpec>,
    /// `[fill]`, when given.
    pub fill: Option<FillSpec>,
    /// `[seismic]` (defaults: horizontal ground motion only).
    pub seismic: SeismicSpec,
    /// `[action] kind`: what lambda multiplies (default seismic).
    pub action: crate::model::Action,
    /// The raw `[dem]` table (time-stepping knobs), validated by `crate::dem_settings`; empty when
    /// the scene has none.
    pub dem: Table,
    /// `[site]`, when given: the seismic site for `voussoir assess` ([`crate::spectrum`]).
    pub site: Option<crate::spectrum::Site>,
    /// `[report]`, when given: who and what the hand-in report (`voussoir report`) is
    /// about. No analysis reads it.
    pub report: Option<ReportInfo>,
    /// `[uncertain]`: the uncertain inputs `voussoir fragility` samples (empty when none);
    /// every other command analyses the scene's own values.
    pub uncertain: Vec<uncertain::UncertainInput>,
    /// `[uncertain] correlation`: rank correlations between those inputs (empty: independent).
    pub uncertain_correlation: Vec<uncertain::RankCorrelation>,
    /// Where the scene came from (file path or `"<string>"`), for messages.
    pub origin: String,
    /// The TOML the scene was built from, with overrides applied.
    table: Table,
    /// The scene file's directory (paths in the scene are relative to it).
    base_dir: Option<std::path::PathBuf>,
}

impl Scene {
    /// Read and validate a scene file.
    pub fn from_file(path: &Path) -> Result<Scene, SceneError> {
        let text = std::fs::read_to_string(path).map_err(|source| SceneError::Io {
            path: path.to_path_buf(),
            source,
        })?;
        let table = parse_toml(&text, &path.display().to_string())?;
        parse(table, &path.display().to_string(), path.parent())
    }

    /// Read a scene file, apply the overrides `KEY=VALUE` to it, then validate the result
    /// once: a file that is invalid on its own but made valid by an override (a pointed
    /// arch's odd voussoir count with `arch.voussoirs=12`) is accepted, as `--set` promises.
    pub fn from_file_with_overrides<S: AsRef<str>>(
        path: &Path,
        assignments: &[S],
    ) -> Result<Scene, SceneError> {
        let text = std::fs::read_to_string(path).map_err(|source| SceneError::Io {
            path: path.to_path_buf(),
            source,
        })?;
        let origin = path.display().to_string();
        let table = parse_toml(&text, &origin)?;
        if assignments.is_empty() {
            return parse(table, &origin, path.parent());
        }
        let (table, sets) = overridden(table, assignments)?;
        parse(table, &format!("{origin} (with{sets})"), path.parent())
    }

    /// Parse and validate a scene from TOML text; `origin` names it in errors.
    pub fn from_toml_str(text: &str, origin: &str) -> Result<Scene, SceneError> {
        Scene::from_table(parse_toml(text, origin)?, origin)
    }

    /// Validate a scene given as a TOML table (paths in it relative to the working directory).
    pub fn from_table(table: Table, origin: &str) -> Result<Scene, SceneError> {
        parse(table, origin, None)
    }

    /// Validate a scene given as a TOML table whose relative paths (`blocks.file`) are
    /// relative to `base_dir` (the directory of the scene file it came from, when it did).
    pub fn from_table_in(
        table: Table,
        origin: &str,
        base_dir: Option<&Path>,
    ) -> Result<Scene, SceneError> {
        parse(table, origin, base_dir)
    }

    /// The directory the scene's relative paths are relative to (None: the working
    /// directory).
    pub fn base_dir(&self) -> Option<&Path> {
        self.base_dir.as_deref()
    }

    /// The parametric arch, or an error saying that `what` needs one when the scene is made
    /// of the user's blocks.
    pub fn parametric(&self, what: &str) -> Result<&ArchSpec, SceneError> {
        self.arch.as_ref().ok_or_else(|| SceneError::OutOfRange {
            origin: self.origin.clone(),
            key: "blocks".into(),
            value: self
                .blocks
                .as_ref()
                .map_or("?".into(), |b| format!("\"{}\"", b.source_words())),
            allowed: format!("{what} needs a parametric structure ([arch], [piers]); a scene of the user's own blocks takes `analyze` and `dem`"),
        })
    }

    /// Whether a search over the arch's thickness may vary this scene: not with tie rods,
    /// which are anchored at fixed points while the voussoirs and the piers (a portal's
    /// piers stand under the intrados) move with the thickness, so at another thickness an
    /// anchor may lie in another block or in none. Refused, naming the key, rather than
    /// searched with ties that no longer sit where the user put them.
    pub fn thickness_may_vary(&self) -> Result<(), SceneError> {
        match self.ties.first() {
            None => Ok(()),
            Some(t) => Err(SceneError::OutOfRange {
                origin: self.origin.clone(),
                key: "ties[0].from".into(),
                value: format!("[{}, {}]", t.from[0], t.from[1]),
                allowed: "a fixed anchor, which a search over the arch's thickness would leave behind (the voussoirs and the piers move with the thickness): the minimum thickness is not searched with [[ties]]; analyse each thickness with `voussoir analyze --set arch.thickness=...`, or remove the ties for the untied structure's minimum".into(),
            }),
        }
    }

    /// The TOML table behind this scene (overrides included).
    pub fn table(&self) -> &Table {
        &self.table
    }

    /// A copy of the scene with `key` (dotted, e.g. `arch.thickness`) set to `value`,
    /// validated like a scene file.
    pub fn with_value(&self, key: &str, value: Value) -> Result<Scene, SceneError> {
        self.with_values(&[(key, value)])
    }

    /// A copy of the scene with the override `key=value` applied (the value is read as a TOML
    /// value, or as a bare string such as `shape=pointed`).
    pub fn with_override(&self, assignment: &str) -> Result<Scene, SceneError> {
        self.with_overrides(&[assignment])
    }

    /// A copy of the scene with all the overrides applied together, then validated once (so
    /// `arch.shape=pointed` and `arch.eccentricity=0.2` can be given in either order).
    pub fn with_overrides<S: AsRef<str>>(&self, assignments: &[S]) -> Result<Scene, SceneError> {
        let (table, sets) = overridden(self.table.clone(), assignments)?;
        let origin = if sets.is_empty() {
            self.origin.clone()
        } else {
            format!("{} (with{sets})", self.origin)
        };
        parse(table, &origin, self.base_dir.as_deref())
    }

    /// A copy of the scene with several `(key, value)` pairs set together, validated once.
    pub fn with_values(&self, values: &[(&str, Value)]) -> Result<Scene, SceneError> {
        let mut table = self.table.clone();
        for (key, value) in values {
            set_dotted(&mut table, key, value.clone()).map_err(|message| {
                SceneError::BadOverride {
                    text: key.to_string(),
                    message,
                }
            })?;
        }
        parse(table, &self.origin, self.base_dir.as_deref())
    }

    /// A copy of the scene with the arch thickness set to `t`.
    pub fn with_thickness(&self, t: f64) -> Result<Scene, SceneError> {
        self.with_value("arch.thickness", Value::Float(t))
    }

    /// The largest arch thickness the scene admits (exclusive): the shape's limit with the
    /// scene's voussoirs, with a fill (or a spandrel wall) the thickness at which the crown's
    /// extrados reaches its level (a thicker ring would stand above it), and with an arcade's
    /// columns or a wall on the pier tops the thickness whose springing joints still fit
    /// there.
    pub fn max_thickness(&self) -> f64 {
        let Some(arch) = &self.arch else {
            return f64::NAN;
        };
        let shape = &arch.shape;
        let mut t_max = shape.max_thickness(arch.voussoirs);
        let level = [
            self.fill.as_ref().map(|f| f.level),
            self.spandrel.as_ref().map(|w| w.level),
        ]
        .into_iter()
        .flatten()
        .reduce(f64::min);
        if let Some(level) = level {
            if shape.crown_extrados(t_max) > level {
                // The crown's extrados rises with t: bisect for the thickness that meets the level.
                let (mut lo, mut hi) = (0.0, t_max);
                for _ in 0..200 {
                    let mid = 0.5 * (lo + hi);
                    if shape.crown_extrados(mid) > level {
                        hi = mid;
                    } else {
                        lo = mid;
                    }
                }
                t_max = lo;
            }
        }
        // An arcade's columns and a spandrel's pier tops must hold the springing joints,
        // which widen with t: bisect for the thickness at which they just fit.
        let fits = |t: f64| self.springings_fit(t);
        if !fits(t_max) {
            let (mut lo, mut hi) = (0.0, t_max);
            for _ in 0..200 {
                let mid = 0.5 * (lo + hi);
                if fits(mid) {
                    lo = mid;
                } else {
                    hi = mid;
                }
            }
            t_max = lo;
        }
        t_max
    }

    /// Whether the springing joints of the ring at thickness `t` fit where they rest: side by
    /// side on an arcade's interior columns (`arcade.column_width`), and beside a spandrel
    /// wall on the pier tops (the checks of `[arcade]` and `[spandrel]`).
    fn springings_fit(&self, t: f64) -> bool {
        let Some(arch) = &self.arch else {
            return true;
        };
        let columns = self.arcade.as_ref().filter(|a| a.bays > 1);
        let walled = self.spandrel.is_some();
        if columns.is_none() && !walled {
            return true;
        }
        let Ok(g) = crate::geometry::recut(
            &arch.shape.geometry(t, arch.voussoirs),
            arch.joints,
            arch.voussoir_shape == VoussoirShape::Curved,
        ) else {
            return false;
        };
        let n = g.voussoirs();
        let (left, right) = (
            g.joints[0].0.x - g.joints[0].1.x,
            g.joints[n].1.x - g.joints[n].0.x,
        );
        if columns.is_some_and(|a| left + right > a.column_width) {
            return false;
        }
        match (&self.piers, walled) {
            (Some(p), true) => p.left.top_width() >= left && p.right.top_width() >= right,
            _ => true,
        }
    }

    /// The assembly and load case of this scene ([`fn@build`]).
    pub fn model(&self) -> Result<crate::model::Model, SceneError> {
        build(self)
    }

    /// The arch's own size: R for circular and pointed arches, span/2 for basket arches; the
    /// largest extent of the user's blocks that move (a fixed base or rock aside).
    pub fn arch_size(&self) -> f64 {
        match (&self.arch, &self.blocks) {
            (Some(a), _) => a.shape.size(),
            (None, Some(b)) => b.detected.assembly.size(),
            (None, None) => f64::NAN,
        }
    }

    /// A characteristic length of the structure (its overall size), used to make tolerances
    /// and the conic program dimensionless.
    pub fn size(&self) -> f64 {
        let bays = self.arcade.as_ref().map_or(1, |a| a.bays) as f64;
        (bays * self.arch_size())
            .max(self.piers.as_ref().map_or(0.0, |p| p.max_height()))
            .max(self.spandrel.as_ref().map_or(0.0, |w| w.level))
    }
}

pub use crate::overrides::parse_assignment;

fn set_dotted(table: &mut Table, key: &str, value: Value) -> Result<(), String> {
    // One entry of `[[loads]]`, as the scene's errors name it: `loads[1].intensity`.
    if let Some(rest) = key.strip_prefix("loads[") {
        return set_entry(table, "loads", key, rest, value);
    }
    // One entry of `[[ties]]`: `ties[0].capacity`.
    if let Some(rest) = key.strip_prefix("ties[") {
        return set_entry(table, "ties", key, rest, value);
    }
    if let Some(rest) = key.strip_prefix("reinforcements[") {
        return set_entry(table, "reinforcements", key, rest, value);
    }
    if let Some(rest) = key.strip_prefix("vehicles[") {
        return set_entry(table, "vehicles", key, rest, value);
    }
    let parts: Vec<&str> = key.split('.').collect();
    // One pier of a portal is set with three parts: `piers.left.height`.
    let pier_side =
        parts.len() == 3 && parts[0] == "piers" && ["left", "right"].contains(&parts[1]);
    if !(parts.len() == 2 || pier_side) || parts.iter().any(|p| p.is_empty()) {
        return Err(format!(
            "key `{key}` must be SECTION.KEY, e.g. arch.thickness or piers.height (or piers.left.KEY, piers.right.KEY)"
        ));
    }
    if !SECTIONS.contains(&parts[0]) {
        return Err(format!(
            "unknown section `{}`{} (allowed: {})",
            parts[0],
            did_you_mean(parts[0], SECTIONS),
            SECTIONS.join(", ")
        ));
    }
    let section = table
        .entry(parts[0].to_string())
        .or_insert_with(|| Value::Table(Table::new()));
    let Value::Table(t) = section else {
        return Err(format!("`{}` is not a table in the scene", parts[0]));
    };
    if pier_side {
        let side = t
            .entry(parts[1].to_string())
            .or_insert_with(|| Value::Table(Table::new()));
        let Value::Table(st) = side else {
            return Err(format!("`piers.{}` is not a table in the scene", parts[1]));
        };
        st.insert(parts[2].to_string(), value);
    } else {
        t.insert(parts[1].to_string(), value);
    }
    Ok(())
}

/// Set `LIST[N].KEY` (`rest` is `N].KEY`) in the entry N (counted from 0) of the array of
/// tables `list` (`[[loads]]`, `[[ties]]`).
fn set_entry(
    table: &mut Table,
    list: &str,
    key: &str,
    rest: &str,
    value: Value,
) -> Result<(), String> {
    let example = match list {
        "ties" => "capacity",
        "reinforcements" => "tensile_capacity",
        "vehicles" => "at",
        _ => "intensity",
    };
    let form = || {
        format!("key `{key}` must be {list}[N].KEY, e.g. {list}[0].{example} (N counts the [[{list}]] from 0)")
    };
    let (index, name) = rest.split_once("].").ok_or_else(form)?;
    let index: usize = index.trim().parse().map_err(|_| form())?;
    if name.is_empty() || name.contains('.') {
        return Err(form());
    }
    let count = match table.get(list) {
        Some(Value::Array(items)) => items.len(),
        _ => 0,
    };
    let Some(Value::Array(items)) = table.get_mut(list) else {
        return Err(format!("`{key}`: the scene has no [[{list}]]"));
    };
    match items.get_mut(index) {
        Some(Value::Table(t)) => {
            t.insert(name.to_string(), value);
            Ok(())
        }
        Some(_) => Err(format!("`{list}[{index}]` is not a table in the scene")),
        None => Err(format!(
            "`{key}`: the scene has {count} [[{list}]] ({list}[0] to {list}[{}])",
            count.saturating_sub(1)
        )),
    }
}

const SECTIONS: &[&str] = &[
    "arch",
    "piers",
    "material",
    "dem",
    "fill",
    "seismic",
    "loads",
    "site",
    "blocks",
    "action",
    "ties",
    "reinforcements",
    "arcade",
    "spandrel",
    "report",
    "vehicles",
    "uncertain",
];

/// The keys of `[arch]` every shape takes.
const ARCH_KEYS: &[&str] = &[
    "shape",
    "thickness",
    "voussoirs",
    "voussoir_shape",
    "joints",
    "horizontal_bed_deg",
];
/// The keys of `[arch]` each shape adds.
const SHAPE_KEYS: &[(&str, &[&str])] = &[
    ("circular", &["radius", "embrace_deg"]),
    ("pointed", &["radius", "eccentricity"]),
    ("basket", &["span", "rise", "side_angle_deg"]),
];
const MATERIAL_KEYS: &[&str] = &[
    "unit_weight",
    "depth",
    "friction",
    "compressive_strength",
    "tie_design_strength",
];
const FILL_KEYS: &[&str] = &[
    "level",
    "unit_weight",
    "seismic",
    "live",
    "passive",
    "friction_deg",
    "passive_mobilisation",
];
const ACTION_KEYS: &[&str] = &["kind"];
const SEISMIC_KEYS: &[&str] = &["vertical_ratio"];
/// The keys of a `[[loads]]` entry every type takes, and those each type adds.
const LOAD_KEYS: &[&str] = &["type", "seismic", "live"];
const LOAD_TYPE_KEYS: &[(&str, &[&str])] = &[
    ("point", &["at", "force"]),
    ("line", &["from_x", "to_x", "intensity"]),
];

/// The keys allowed in a section whose keys depend on a kind (the arch's `shape`, a load's
/// `type`): the common keys and the kind's own, or every kind's when the kind is not (yet)
/// known, with the words naming the kind for messages (`for shape = "circular" `).
fn keys_of_kind(
    table: &Table,
    kind_key: &str,
    common: &[&'static str],
    kinds: &[(&str, &[&'static str])],
) -> (Vec<&'static str>, String) {
    let kind = match table.get(kind_key) {
        Some(Value::String(k)) => kinds.iter().find(|(name, _)| name == k),
        _ => None,
    };
    let mut keys: Vec<&'static str> = common.to_vec();
    let own: Vec<&[&'static str]> = match kind {
        Some((_, own)) => vec![*own],
        None => kinds.iter().map(|(_, own)| *own).collect(),
    };
    for k in own.into_iter().flatten() {
        if !keys.contains(k) {
            keys.push(k);
        }
    }
    let context = kind.map_or(String::new(), |(name, _)| {
        format!("for {kind_key} = \"{name}\" ")
    });
    (keys, context)
}

/// Reads one section, remembering which keys were used so that the rest are reported as
/// unknown.
struct Section<'a> {
    name: String,
    table: &'a Table,
    origin: &'a str,
    used: BTreeSet<&'static str>,
}

impl<'a> Section<'a> {
    fn new(name: impl Into<String>, table: &'a Table, origin: &'a str) -> Self {
        Section {
            name: name.into(),
            table,
            origin,
            used: BTreeSet::new(),
        }
    }

    fn key(&self, key: &str) -> String {
        format!("{}.{}", self.name, key)
    }

    fn wrong_type(&self, key: &str, v: &Value, expected: &str) -> SceneError {
        SceneError::WrongType {
            origin: self.origin.to_string(),
            key: self.key(key),
            value: v.to_string(),
            expected: expected.to_string(),
        }
    }

    fn out_of_range(&self, key: &str, value: impl ToString, allowed: &str) -> SceneError {
        let mut value = value.to_string();
        // A float far from 1 prints every digit (1e300 as 301 of them): say it as 1e300.
        if value.len() > 24 {
            if let Ok(x) = value.parse::<f64>() {
                value = format!("{x:e}");
            }
        }
        SceneError::OutOfRange {
            origin: self.origin.to_string(),
            key: self.key(key),
            value,
            allowed: allowed.to_string(),
        }
    }

    fn missing(&self, key: &str, what: &str) -> SceneError {
        SceneError::MissingKey {
            origin: self.origin.to_string(),
            key: self.key(key),
            what: what.to_string(),
        }
    }

    fn opt_f64(&mut self, key: &'static str) -> Result<Option<f64>, SceneError> {
        self.used.insert(key);
        match self.table.get(key) {
            None => Ok(None),
            Some(Value::Float(x)) => Ok(Some(*x)),
            Some(Value::Integer(i)) => Ok(Some(*i as f64)),
            Some(Value::String(s)) if s.trim().eq_ignore_ascii_case("inf") => {
                Ok(Some(f64::INFINITY))
            }
            Some(v) => Err(self.wrong_type(key, v, &units::expected(key))),
        }
    }

    /// A finite number `> 0`, required (`what` describes it) or defaulted.
    fn positive(
        &mut self,
        key: &'static str,
        default: Option<f64>,
        what: &str,
    ) -> Result<f64, SceneError> {
        let v = match (self.opt_f64(key)?, default) {
            (Some(v), _) => v,
            (None, Some(d)) => d,
            (None, None) => return Err(self.missing(key, what)),
        };
        if !(v.is_finite() && v > 0.0) {
            return Err(self.out_of_range(key, v, "must be a finite number > 0"));
        }
        Ok(v)
    }

    /// A length (m) within [`MIN_LENGTH`, `MAX_LENGTH`].
    fn length(&mut self, key: &'static str, what: &str) -> Result<f64, SceneError> {
        let v = self.positive(key, None, what)?;
        if !(MIN_LENGTH..=MAX_LENGTH).contains(&v) {
            return Err(self.out_of_range(
                key,
                v,
                &format!("must be a length from {MIN_LENGTH:e} to {MAX_LENGTH:e} m"),
            ));
        }
        Ok(v)
    }

    fn count(
        &mut self,
        key: &'static str,
        default: Option<usize>,
        min: usize,
        what: &str,
    ) -> Result<usize, SceneError> {
        self.used.insert(key);
        let allowed = format!("must be a whole number from {min} to {MAX_VOUSSOIRS}");
        let in_range = |v: f64| (min as f64..=MAX_VOUSSOIRS as f64).contains(&v);
        match (self.table.get(key), default) {
            (Some(Value::Integer(i)), _) => match usize::try_from(*i) {
                Ok(n) if in_range(n as f64) => Ok(n),
                _ => Err(self.out_of_range(key, i, &allowed)),
            },
            // A whole number written as a float (`16.0`, `1e21`): checked as the float it is,
            // so a huge one is echoed as written, not as the largest integer.
            (Some(Value::Float(x)), _) if x.fract() == 0.0 && x.is_finite() => {
                if in_range(*x) {
                    Ok(*x as usize)
                } else {
                    Err(self.out_of_range(key, short(*x), &allowed))
                }
            }
            (Some(v), _) => Err(self.wrong_type(key, v, "a whole number")),
            (None, Some(d)) => Ok(d),
            (None, None) => Err(self.missing(key, what)),
        }
    }

    /// A whole number >= 0 (an index), required.
    fn index(&mut self, key: &'static str, what: &str) -> Result<usize, SceneError> {
        self.used.insert(key);
        let allowed = "must be a whole number >= 0";
        match self.table.get(key) {
            Some(Value::Integer(i)) => {
                usize::try_from(*i).map_err(|_| self.out_of_range(key, i, allowed))
            }
            Some(Value::Float(x)) if x.fract() == 0.0 && (0.0..=1e9).contains(x) => Ok(*x as usize),
            Some(Value::Float(x)) => Err(self.out_of_range(key, short(*x), allowed)),
            Some(v) => Err(self.wrong_type(key, v, "a whole number")),
            None => Err(self.missing(key, what)),
        }
    }

    /// A finite number, required.
    fn finite(&mut self, key: &'static str, what: &str) -> Result<f64, SceneError> {
        let v = self.opt_f64(key)?.ok_or_else(|| self.missing(key, what))?;
        if !v.is_finite() {
            return Err(self.out_of_range(key, v, "must be a finite number"));
        }
        Ok(v)
    }

    /// A pair `[x, y]` of finite numbers, required.
    fn pair(&mut self, key: &'static str, what: &str) -> Result<[f64; 2], SceneError> {
        self.used.insert(key);
        let v = self.table.get(key).ok_or_else(|| self.missing(key, what))?;
        let num = |x: &Value| match x {
            Value::Float(f) => Some(*f),
            Value::Integer(i) => Some(*i as f64),
            _ => None,
        };
        match v {
            Value::Array(a) if a.len() == 2 => match (num(&a[0]), num(&a[1])) {
                (Some(x), Some(y)) if x.is_finite() && y.is_finite() => Ok([x, y]),
                (Some(_), Some(_)) => Err(self.out_of_range(key, v, "both numbers must be finite")),
                _ => Err(self.wrong_type(key, v, "a pair of numbers [x, y]")),
            },
            _ => Err(self.wrong_type(key, v, "a pair of numbers [x, y]")),
        }
    }

    fn boolean(&mut self, key: &'static str, default: bool) -> Result<bool, SceneError> {
        self.used.insert(key);
        match self.table.get(key) {
            None => Ok(default),
            Some(Value::Boolean(b)) => Ok(*b),
            Some(v) => Err(self.wrong_type(key, v, "true or false")),
        }
    }

    fn string(&mut self, key: &'static str, default: Option<&str>) -> Result<String, SceneError> {
        self.used.insert(key);
        match (self.table.get(key), default) {
            (Some(Value::String(s)), _) => Ok(s.clone()),
            (Some(v), _) => Err(self.wrong_type(key, v, "a string")),
            (None, Some(d)) => Ok(d.to_string()),
            (None, None) => Err(self.missing(key, "a string")),
        }
    }

    /// Report the first key of the section that is not `allowed`, with the allowed key
    /// closest to it (a likely typo). Called before any key is read, so a misspelt required
    /// key is reported as the unknown key it is rather than as the missing one.
    fn check_known(&self, allowed: &[&str], context: &str) -> Result<(), SceneError> {
        for key in self.table.keys() {
            if !allowed.contains(&key.as_str()) {
                return Err(SceneError::UnknownKey {
                    origin: self.origin.to_string(),
                    key: self.key(key),
                    hint: format!(
                        "{} {context}(allowed: {})",
                        did_you_mean(key, allowed),
                        allowed.join(", ")
                    ),
                });
            }
        }
        Ok(())
    }

    /// Report the first key that was not read (a safety net behind [`Self::check_known`]).
    fn finish(&self, context: &str) -> Result<(), SceneError> {
        for key in self.table.keys() {
            if !self.used.contains(key.as_str()) {
                let allowed: Vec<&str> = self.used.iter().copied().collect();
                return Err(SceneError::UnknownKey {
                    origin: self.origin.to_string(),
                    key: self.key(key),
                    hint: format!(" {context}(allowed: {})", allowed.join(", ")),
                });
            }
        }
        Ok(())
    }
}

fn section<'a>(
    table: &'a Table,
    name: &str,
    origin: &str,
) -> Result<Option<&'a Table>, SceneError> {
    match table.get(name) {
        None => Ok(None),
        Some(Value::Table(t)) => Ok(Some(t)),
        Some(v) => Err(SceneError::WrongType {
            origin: origin.to_string(),
            key: name.to_string(),
            value: v.to_string(),
            expected: format!("a table [{name}]"),
        }),
    }
}

/// `table` with the overrides `KEY=VALUE` set, and the words ` --set A --set B` saying so.
fn overridden<S: AsRef<str>>(
    mut table: Table,
    assignments: &[S],
) -> Result<(Table, String), SceneError> {
    let mut sets = String::new();
    for a in assignments {
        let a = a.as_ref();
        let (key, value) = parse_assignment(a)?;
        set_dotted(&mut table, &key, value).map_err(|message| SceneError::BadOverride {
            text: a.to_string(),
            message,
        })?;
        sets.push_str(&format!(" --set {a}"));
    }
    Ok((table, sets))
}

/// Parse TOML text (a scene or a study file). A UTF-8 byte-order mark, which some editors
/// write, is skipped as TOML allows. A syntax error says the line and column and quotes the
/// line there, cut around the column when it is long ([`crate::error::excerpt_around`]): a
/// malformed 10 MB line gives a message of a few lines, not of 10 MB.
pub fn parse_toml(text: &str, origin: &str) -> Result<Table, SceneError> {
    let text = strip_bom(text);
    text.parse()
        .map_err(|e: toml::de::Error| syntax_error(text, origin, &e))
}

/// `text` without a leading UTF-8 byte-order mark (U+FEFF).
pub fn strip_bom(text: &str) -> &str {
    text.strip_prefix('\u{feff}').unwrap_or(text)
}

/// The message of a TOML syntax error: line, column, what is wrong, and the line quoted.
fn syntax_error(text: &str, origin: &str, e: &toml::de::Error) -> SceneError {
    let what = e.message().trim().replace('\n', " ");
    let message = match e.span() {
        Some(span) => {
            let mut at = span.start.min(text.len());
            while !text.is_char_boundary(at) {
                at -= 1;
            }
            let line_start = text[..at].rfind('\n').map_or(0, |i| i + 1);
            let line_end = text[at..].find('\n').map_or(text.len(), |i| at + i);
            let line = text[line_start..line_end].trim_end_matches('\r');
            let number = text[..line_start].matches('\n').count() + 1;
            let column = text[line_start..at].chars().count() + 1;
            format!(
                "line {number}, column {column}: {what}: `{}`",
                crate::error::excerpt_around(line, at - line_start)
            )
        }
        None => crate::error::excerpt(&what),
    };
    SceneError::Syntax {
        origin: origin.to_string(),
        message,
    }
}

fn parse(mut table: Table, origin: &str, base_dir: Option<&Path>) -> Result<Scene, SceneError> {
    // "150 mm", "5 MPa": to SI numbers before anything reads them.
    units::to_si(&mut table);
    for key in table.keys() {
        if !SECTIONS.contains(&key.as_str()) {
            return Err(SceneError::UnknownKey {
                origin: origin.to_string(),
                key: key.clone(),
                hint: format!(
                    "{} (allowed sections: {})",
                    did_you_mean(key, SECTIONS),
                    SECTIONS.join(", ")
                ),
            });
        }
    }
    let empty = Table::new();
    let material = parse_material(Section::new(
        "material",
        section(&table, "material", origin)?.unwrap_or(&empty),
        origin,
    ))?;
    // The structure: the user's blocks, or the parametric arch (and piers).
    let (arch, piers, blocks, arcade, spandrel) = match section(&table, "blocks", origin)? {
        Some(t) => {
            for (name, instead) in [
                ("arch", "the blocks are the structure"),
                ("piers", "model piers as blocks"),
                ("arcade", "model the bays as blocks"),
                ("spandrel", "model the wall as blocks"),
            ] {
                if table.contains_key(name) {
                    return Err(SceneError::OutOfRange {
                        origin: origin.to_string(),
                        key: name.to_string(),
                        value: format!("[{name}]"),
                        allowed: format!("a scene with [blocks] takes no [{name}] ({instead})"),
                    });
                }
            }
            let spec =
                user_blocks::parse_blocks(Section::new("blocks", t, origin), &material, base_dir)?;
            (None, None, Some(Arc::new(spec)), None, None)
        }
        None => {
            let arch_table =
                section(&table, "arch", origin)?.ok_or_else(|| SceneError::MissingKey {
                    origin: origin.to_string(),
                    key: "arch".to_string(),
                    what: "the [arch] table (or [blocks] for a structure of your own blocks)"
                        .to_string(),
                })?;
            let arch = parse_arch(Section::new("arch", arch_table, origin))?;
            let piers = match section(&table, "piers", origin)? {
                Some(t) => Some(parse_piers(Section::new("piers", t, origin), &arch)?),
                None => None,
            };
            let arcade = match section(&table, "arcade", origin)? {
                Some(t) => Some(arcade::parse(
                    Section::new("arcade", t, origin),
                    &arch,
                    piers.as_ref(),
                )?),
                None => None,
            };
            let spandrel = match section(&table, "spandrel", origin)? {
                Some(t) => Some(spandrel::parse(
                    Section::new("spandrel", t, origin),
                    &arch,
                    piers.as_ref(),
                )?),
                None => None,
            };
            (Some(arch), piers, None, arcade, spandrel)
        }
    };
    let dem = section(&table, "dem", origin)?.cloned().unwrap_or_default();
    let loads = parse_loads(&table, origin)?;
    let vehicles = vehicles::parse(&table, origin)?;
    let ties = ties::parse_ties(&table, origin)?;
    let reinforcements = reinforcements::parse(&table, origin)?;
    let fill = match section(&table, "fill", origin)? {
        Some(t) => Some(parse_fill(
            Section::new("fill", t, origin),
            arch.as_ref(),
            spandrel.as_ref(),
        )?),
        None => None,
    };
    if arcade.as_ref().is_some_and(|a| a.bays > 1) && !reinforcements.is_empty() {
        return Err(SceneError::OutOfRange {
            origin: origin.to_string(),
            key: "reinforcements[0].from_joint".into(),
            value: reinforcements[0].from_joint.to_string(),
            allowed: "a strip names the joints of one arch; an arcade of several bays has several arches, and strips on arcades are not supported yet (analyse one bay as a portal)".into(),
        });
    }
    let seismic = parse_seismic(Section::new(
        "seismic",
        section(&table, "seismic", origin)?.unwrap_or(&empty),
        origin,
    ))?;
    let site = section(&table, "site", origin)?
        .map(|t| crate::spectrum::Site::from_table(t, origin))
        .transpose()?;
    let action = parse_action(
        Section::new(
            "action",
            section(&table, "action", origin)?.unwrap_or(&empty),
            origin,
        ),
        &table,
        &loads,
        &vehicles,
    )?;
    let uncertain_table = section(&table, "uncertain", origin)?;
    let uncertain = uncertain_table
        .map(|t| uncertain::parse(t, origin))
        .transpose()?
        .unwrap_or_default();
    let uncertain_correlation = uncertain_table
        .map(|t| uncertain::parse_correlation(t, &uncertain, origin))
        .transpose()?
        .unwrap_or_default();
    let scene = Scene {
        arch,
        blocks,
        piers,
        arcade,
        spandrel,
        material,
        loads,
        vehicles,
        ties,
        reinforcements,
        fill,
        seismic,
        action,
        dem,
        site,
        report: section(&table, "report", origin)?
            .map(|t| parse_report(Section::new("report", t, origin)))
            .transpose()?,
        uncertain,
        uncertain_correlation,
        origin: origin.to_string(),
        table,
        base_dir: base_dir.map(Path::to_path_buf),
    };
    // A scene holds values, never a model: the one build is the analysis's (`build`), where a
    // load outside every block is reported as this scene's error. The [dem] knobs are checked
    // here, each against its own range, so a typo is caught whatever the command; the checks
    // that need the blocks (a contact tolerance against the shortest joint) run with the DEM.
    if !scene.dem.is_empty() {
        let nothing = crate::assembly::Assembly {
            blocks: Vec::new(),
            joints: Vec::new(),
        };
        let mut p = crate::dem_settings::IntegrationParameters::for_assembly(&nothing);
        p.apply_table(&scene.dem, &scene.origin)?;
    }
    Ok(scene)
}

/// The keys of `[report]`, in the order the report's identification lists them.
pub const REPORT_KEYS: &[&str] = &["title", "structure", "location", "author", "date", "notes"];

/// `[report]`: words for the hand-in report's identification, each optional (docs/geometry.md).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct ReportInfo {
    pub title: Option<String>,
    pub structure: Option<String>,
    pub location: Option<String>,
    pub author: Option<String>,
    /// As written: a string, or a TOML date (`date = 2026-11-26`) in its TOML form.
    pub date: Option<String>,
    pub notes: Option<String>,
}

impl ReportInfo {
    /// The keys given, with their words, in [`REPORT_KEYS`]' order.
    pub fn entries(&self) -> Vec<(&'static str, &str)> {
        [
            ("title", &self.title),
            ("structure", &self.structure),
            ("location", &self.location),
            ("author", &self.author),
            ("date", &self.date),
            ("notes", &self.notes),
        ]
        .into_iter()
        .filter_map(|(k, v)| v.as_deref().map(|v| (k, v)))
        .collect()
    }
}

fn parse_report(mut s: Section) -> Result<ReportInfo, SceneError> {
    s.check_known(REPORT_KEYS, "")?;
    let mut words = |key: &'static str| -> Result<Option<String>, SceneError> {
        match s.table.get(key) {
            None => Ok(None),
            // A date written as a TOML date rather than a string is the same words.
            Some(Value::Datetime(d)) if key == "date" => {
                s.used.insert(key);
                Ok(Some(d.to_string()))
            }
            Some(_) => s.string(key, None).map(Some),
        }
    };
    let info = ReportInfo {
        title: words("title")?,
        structure: words("structure")?,
        location: words("location")?,
        author: words("author")?,
        date: words("date")?,
        notes: words("notes")?,
    };
    s.finish("")?;
    Ok(info)
}

fn parse_arch(mut s: Section) -> Result<ArchSpec, SceneError> {
    let (allowed, context) = keys_of_kind(s.table, "shape", ARCH_KEYS, SHAPE_KEYS);
    s.check_known(&allowed, &context)?;
    let shape_name = s.string("shape", None)?;
    let thickness = s.length("thickness", "arch thickness t in metres")?;
    let vs = s.string("voussoir_shape", Some("polygon"))?;
    let voussoir_shape = match vs.as_str() {
        "polygon" => VoussoirShape::Polygon,
        "curved" => VoussoirShape::Curved,
        other => {
            return Err(s.out_of_range(
                "voussoir_shape",
                format!("\"{other}\""),
                "must be \"polygon\" or \"curved\"",
            ))
        }
    };
    let (shape, voussoirs) = match shape_name.as_str() {
        "circular" => {
            let radius = s.length("radius", "centreline radius R in metres")?;
            let embrace_deg = s.positive("embrace_deg", Some(180.0), "")?;
            // Below MIN_EMBRACE_DEG the voussoirs' areas underflow to zero weight.
            if !(MIN_EMBRACE_DEG..360.0).contains(&embrace_deg) {
                return Err(s.out_of_range(
                    "embrace_deg",
                    embrace_deg,
                    &format!("must be from {MIN_EMBRACE_DEG} to less than 360 (degrees)"),
                ));
            }
            if thickness >= 2.0 * radius {
                return Err(s.out_of_range(
                    "thickness",
                    thickness,
                    &format!("must be < 2 * radius = {}", 2.0 * radius),
                ));
            }
            let n = s.count("voussoirs", None, 1, "number of voussoirs n")?;
            // A polygon voussoir is a quadrilateral of straight chords: it needs less than
            // 180 deg of arc.
            if embrace_deg / n as f64 >= 180.0 {
                return Err(s.out_of_range(
                    "voussoirs",
                    n,
                    &format!(
                        "each voussoir would subtend {} deg; an embrace of {embrace_deg} deg needs at least {} voussoirs",
                        embrace_deg / n as f64,
                        (embrace_deg / 180.0).floor() as usize + 1
                    ),
                ));
            }
            let shape: Arc<dyn ArchShape> = Arc::new(Circular {
                radius,
                embrace: embrace_deg.to_radians(),
            });
            (shape, n)
        }
        "pointed" => {
            let radius = s.length("radius", "centreline radius R in metres")?;
            let e = s.opt_f64("eccentricity")?.ok_or_else(|| {
                s.missing(
                    "eccentricity",
                    "eccentricity e of the two centres in metres",
                )
            })?;
            if !(e.is_finite() && e >= 0.0 && e < radius - 0.5 * thickness) {
                return Err(s.out_of_range(
                    "eccentricity",
                    e,
                    &format!(
                        "must satisfy 0 <= e < R - t/2 = {}",
                        radius - 0.5 * thickness
                    ),
                ));
            }
            let n = s.count("voussoirs", None, 2, "number of voussoirs n (even)")?;
            if n % 2 != 0 {
                return Err(s.out_of_range("voussoirs", n, "must be even for a pointed arch"));
            }
            // The intrados meets the axis x = 0 at a larger polar angle than the centreline;
            // the last radial joint before the crown must stay on its own side of the axis,
            // or that voussoir folds over the crown joint.
            let phi_end = (-e / radius).acos();
            let psi_intrados = (-e / (radius - 0.5 * thickness)).acos();
            let h = (n / 2) as f64;
            let phi_last = std::f64::consts::PI - (std::f64::consts::PI - phi_end) * (h - 1.0) / h;
            if n > 2 && phi_last <= psi_intrados {
                return Err(s.out_of_range(
                    "eccentricity",
                    e,
                    &format!(
                        "too close to R - t/2 for {n} voussoirs: the radial joint next to the crown would cross the axis on the intrados; use fewer voussoirs (at most {}) or a smaller eccentricity",
                        max_pointed_voussoirs(phi_end, psi_intrados)
                    ),
                ));
            }
            let shape: Arc<dyn ArchShape> = Arc::new(Pointed {
                radius,
                eccentricity: e,
            });
            (shape, n)
        }
        "basket" => {
            let span = s.length("span", "centreline span L in metres")?;
            let rise = s.length("rise", "centreline rise f in metres")?;
            let side_deg = s.positive("side_angle_deg", Some(60.0), "")?;
            if side_deg >= 90.0 {
                return Err(s.out_of_range(
                    "side_angle_deg",
                    side_deg,
                    "must be > 0 and < 90 (degrees)",
                ));
            }
            let b = side_deg.to_radians();
            let (r1, r2) = basket_radii(span, rise, b);
            if !(r1 > 0.0 && r1 < r2) {
                return Err(s.out_of_range(
                    "rise",
                    rise,
                    &format!(
                        "with side_angle_deg = {side_deg} the rise must lie strictly between {} and span/2 = {} (so that 0 < r1 < r2; here r1 = {r1:.6}, r2 = {r2:.6}); a flatter basket needs a larger side_angle_deg",
                        0.5 * span * (1.0 - b.sin()) / b.cos(),
                        0.5 * span
                    ),
                ));
            }
            if thickness >= 2.0 * r1 {
                return Err(s.out_of_range(
                    "thickness",
                    thickness,
                    &format!(
                        "must be < 2 * r1 = {} (twice the side-arc radius)",
                        2.0 * r1
                    ),
                ));
            }
            let n = s.count("voussoirs", None, 3, "number of voussoirs n")?;
            let ns = side_voussoirs(n, r1, r2, b);
            if n < 2 * ns + 1 {
                return Err(s.out_of_range(
                    "voussoirs",
                    n,
                    &format!(
                        "too few: each side arc takes {ns} and the crown arc needs at least 1"
                    ),
                ));
            }
            let shape: Arc<dyn ArchShape> = Arc::new(Basket {
                span,
                rise,
                side_angle: b,
            });
            (shape, n)
        }
        other => {
            return Err(s.out_of_range(
                "shape",
                format!("\"{other}\""),
                "must be \"circular\", \"pointed\" or \"basket\"",
            ))
        }
    };
    let size = shape.size();
    if thickness < MIN_RELATIVE_THICKNESS * size {
        return Err(s.out_of_range(
            "thickness",
            thickness,
            &format!("must be at least {MIN_RELATIVE_THICKNESS:e} of the arch's size ({size} m)"),
        ));
    }
    let joints = parse_joints(&mut s)?;
    s.finish(&format!("for shape = \"{shape_name}\" "))?;
    let arch = ArchSpec {
        shape,
        thickness,
        voussoirs,
        voussoir_shape,
        joints,
    };
    if let Err(why) = arch.geometry() {
        return Err(s.out_of_range(
            "joints",
            format!("\"{}\"", joints.name()),
            &format!("cannot cut this {} arch: {why}", arch.shape.title()),
        ));
    }
    Ok(arch)
}

/// `joints` (the stereotomy) and `horizontal_bed_deg` (its angle, for horizontal beds only).
fn parse_joints(s: &mut Section) -> Result<Stereotomy, SceneError> {
    let word = s.string("joints", Some("radial"))?;
    let angle = s.opt_f64("horizontal_bed_deg")?;
    match (word.as_str(), angle) {
        ("radial", None) => Ok(Stereotomy::Radial),
        ("vertical", None) => Ok(Stereotomy::Vertical),
        ("horizontal_bed", Some(deg)) => {
            if !(deg.is_finite() && deg > 0.0 && deg < 90.0) {
                return Err(s.out_of_range(
                    "horizontal_bed_deg",
                    deg,
                    "must be > 0 and < 90 (degrees from the horizontal up to which joints are horizontal beds)",
                ));
            }
            Ok(Stereotomy::HorizontalBed {
                angle: deg.to_radians(),
            })
        }
        ("horizontal_bed", None) => Err(s.missing(
            "horizontal_bed_deg",
            "with joints = \"horizontal_bed\", the angle in degrees from the horizontal up to which the radial joints become horizontal beds",
        )),
        ("radial" | "vertical", Some(deg)) => Err(s.out_of_range(
            "horizontal_bed_deg",
            deg,
            &format!("applies only to joints = \"horizontal_bed\" (here joints = \"{word}\")"),
        )),
        (other, _) => Err(s.out_of_range(
            "joints",
            format!("\"{other}\""),
            &format!(
                "must be \"radial\", \"vertical\" or \"horizontal_bed\"{}",
                did_you_mean(other, &["radial", "vertical", "horizontal_bed"])
            ),
        )),
    }
}

/// The largest even n whose joint next to the crown stays left of the axis on the intrados.
fn max_pointed_voussoirs(phi_end: f64, psi_intrados: f64) -> usize {
    // phi_last = pi - (pi - phi_end)(h - 1)/h > psi  <=>  h < (pi - phi_end) / (psi - phi_end)
    let span = std::f64::consts::PI - phi_end;
    let limit = span / (psi_intrados - phi_end);
    let h = if limit.is_finite() {
        (limit.ceil() as usize).saturating_sub(1).max(1)
    } else {
        1
    };
    2 * h
}

fn parse_piers(s: Section, arch: &ArchSpec) -> Result<Piers, SceneError> {
    let origin = s.origin;
    let piers = piers::parse_piers(s)?;
    if !arch.shape.horizontal_springings() {
        // Only a circular arch with an embrace other than 180 deg has inclined springings.
        let (key, value) = arch
            .shape
            .keys()
            .into_iter()
            .find(|(k, _)| *k == "embrace_deg")
            .map_or(("shape", f64::NAN), |(k, v)| (k, v));
        return Err(SceneError::OutOfRange {
            origin: origin.to_string(),
            key: format!("arch.{key}"),
            value: ((value * 1e9).round() / 1e9).to_string(),
            allowed: format!("piers need horizontal springing joints: a {} arch on piers must have embrace_deg = 180", arch.shape.name()),
        });
    }
    Ok(piers)
}

/// A capacity that a retrofit design may size (`[[ties]] capacity`, `[[reinforcements]]
/// tensile_capacity`): a force from 0 to [`MAX_FORCE`] N, or the string `"design"` (None).
fn capacity_or_design(
    s: &mut Section,
    key: &'static str,
    what: &str,
) -> Result<Option<f64>, SceneError> {
    if matches!(s.table.get(key), Some(Value::String(c)) if c.trim() == "design") {
        s.string(key, None)?;
        return Ok(None);
    }
    let c = s.finite(key, &format!("{what}, in N, or \"design\""))?;
    if !(0.0..=MAX_FORCE).contains(&c) {
        return Err(s.out_of_range(
            key,
            short(c),
            &format!("must be from 0 to {MAX_FORCE:e} N, or \"design\""),
        ));
    }
    Ok(Some(c))
}

/// The optional `cost` of a tie or strip: its cost per newton of capacity in a retrofit
/// design (default 1), a finite number > 0.
fn design_cost(s: &mut Section) -> Result<f64, SceneError> {
    let cost = s.opt_f64("cost")?.unwrap_or(1.0);
    if !(cost.is_finite() && cost > 0.0) {
        return Err(s.out_of_range(
            "cost",
            short(cost),
            "must be a finite number > 0 (the cost of one newton of capacity in a retrofit design, relative to the other ties and strips)",
        ));
    }
    Ok(cost)
}

/// The tables of the array of tables `list` (`[[loads]]`, `[[ties]]`), empty when absent;
/// anything else there is an error naming the key.
fn entries<'a>(table: &'a Table, list: &str, origin: &str) -> Result<Vec<&'a Table>, SceneError> {
    let items = match table.get(list) {
        None => return Ok(Vec::new()),
        Some(Value::Array(a)) => a,
        Some(v) => {
            return Err(SceneError::WrongType {
                origin: origin.to_string(),
                key: list.to_string(),
                value: v.to_string(),
                expected: format!("a list of [[{list}]] tables"),
            })
        }
    };
    items
        .iter()
        .enumerate()
        .map(|(k, item)| match item {
            Value::Table(t) => Ok(t),
            _ => Err(SceneError::WrongType {
                origin: origin.to_string(),
                key: format!("{list}[{k}]"),
                value: item.to_string(),
                expected: format!("a [[{list}]] table"),
            }),
        })
        .collect()
}

fn parse_loads(table: &Table, origin: &str) -> Result<Vec<LoadSpec>, SceneError> {
    let items = entries(table, "loads", origin)?;
    let mut loads = Vec::with_capacity(items.len());
    for (k, t) in items.into_iter().enumerate() {
        let mut s = Section::new(format!("loads[{k}]"), t, origin);
        let (allowed, context) = keys_of_kind(t, "type", LOAD_KEYS, LOAD_TYPE_KEYS);
        s.check_known(&allowed, &context)?;
        let kind = s.string("type", None)?;
        let live = s.boolean("live", false)?;
        // A live load carries no seismic mass: its default is then false, and true is refused.
        let seismic = s.boolean("seismic", !live)?;
        if live && seismic {
            return Err(s.out_of_range(
                "seismic",
                "true",
                "a live load (live = true) carries no seismic mass: leave seismic out or set it to false",
            ));
        }
        let load = match kind.as_str() {
            "point" => {
                let at = s.pair("at", "point of application [x, y] in metres")?;
                if at.iter().any(|c| c.abs() > MAX_LENGTH) {
                    return Err(s.out_of_range(
                        "at",
                        format!("[{}, {}]", short(at[0]), short(at[1])),
                        &format!("coordinates must lie within +-{MAX_LENGTH:e} m"),
                    ));
                }
                let force = s.pair("force", "force [fx, fy] in newtons")?;
                if force.iter().any(|c| c.abs() > MAX_FORCE) {
                    return Err(s.out_of_range(
                        "force",
                        format!("[{}, {}]", short(force[0]), short(force[1])),
                        &format!("components must lie within +-{MAX_FORCE:e} N"),
                    ));
                }
                LoadSpec::Point {
                    at,
                    force,
                    seismic,
                    live,
                }
            }
            "line" => {
                let from_x = s.finite("from_x", "start x of the loaded length in metres")?;
                let to_x = s.finite("to_x", "end x of the loaded length in metres")?;
                for (key, x) in [("from_x", from_x), ("to_x", to_x)] {
                    if x.abs() > MAX_LENGTH {
                        return Err(s.out_of_range(
                            key,
                            x,
                            &format!("must lie within +-{MAX_LENGTH:e} m"),
                        ));
                    }
                }
                if to_x <= from_x {
                    return Err(s.out_of_range(
                        "to_x",
                        to_x,
                        &format!("must be greater than from_x = {from_x}"),
                    ));
                }
                let intensity = s.finite("intensity", "load per metre in N/m, downward")?;
                if intensity > MAX_FORCE {
                    return Err(s.out_of_range(
                        "intensity",
                        intensity,
                        &format!("must be at most {MAX_FORCE:e} N/m"),
                    ));
                }
                if intensity < 0.0 {
                    return Err(s.out_of_range(
                        "intensity",
                        intensity,
                        "must be >= 0 (N/m, acting downward)",
                    ));
                }
                LoadSpec::Line {
                    from_x,
                    to_x,
                    intensity,
                    seismic,
                    live,
                }
            }
            other => {
                return Err(s.out_of_range(
                    "type",
                    format!("\"{other}\""),
                    "must be \"point\" or \"line\"",
                ))
            }
        };
        s.finish(&format!("for type = \"{kind}\" "))?;
        loads.push(load);
    }
    Ok(loads)
}

/// A number as a user reads it in a message: plain when moderate, in exponent form when huge
/// or tiny.
fn short(x: f64) -> String {
    if x != 0.0 && !(1e-4..1e7).contains(&x.abs()) {
        format!("{x:e}")
    } else {
        x.to_string()
    }
}

/// `[fill]`. Over a parametric arch its level must not be below the crown extrados; over the
/// user's blocks, that it lies above some block top is checked where it is placed.
fn parse_fill(
    mut s: Section,
    arch: Option<&ArchSpec>,
    spandrel: Option<&SpandrelSpec>,
) -> Result<FillSpec, SceneError> {
    let keys: Vec<&str> = FILL_KEYS.iter().chain(spread::KEYS).copied().collect();
    s.check_known(&keys, "")?;
    let crown = arch.map(|a| a.shape.crown_extrados(a.thickness));
    let dispersal = spread::parse(&mut s, crown)?;
    let level = s.finite("level", "y of the fill's top surface in metres")?;
    if level.abs() > MAX_LENGTH {
        return Err(s.out_of_range(
            "level",
            level,
            &format!("must lie within +-{MAX_LENGTH:e} m"),
        ));
    }
    let unit_weight = s.opt_f64("unit_weight")?.unwrap_or(18000.0);
    if !(unit_weight.is_finite() && (0.0..=MAX_UNIT_WEIGHT).contains(&unit_weight)) {
        return Err(s.out_of_range(
            "unit_weight",
            unit_weight,
            &format!("must be a number from 0 to {MAX_UNIT_WEIGHT:e} (N/m^3)"),
        ));
    }
    let seismic = s.boolean("seismic", true)?;
    if s.boolean("live", false)? {
        return Err(s.out_of_range(
            "live",
            "true",
            "a fill is a permanent load and cannot be live: give a live load as [[loads]] with live = true",
        ));
    }
    let passive = parse_passive(&mut s)?;
    s.finish("")?;
    if let Some(wall) = spandrel {
        if level <= wall.level {
            return Err(s.out_of_range(
                "level",
                level,
                &format!(
                    "a fill rests on the spandrel wall's top: it must be above spandrel.level = {}",
                    wall.level
                ),
            ));
        }
    }
    if let Some(arch) = arch {
        let crown = arch.shape.crown_extrados(arch.thickness);
        if level < crown {
            return Err(s.out_of_range(
                "level",
                level,
                &format!("must not be below the crown extrados, y = {crown}"),
            ));
        }
    }
    Ok(FillSpec {
        level,
        unit_weight,
        seismic,
        dispersal,
        passive,
    })
}

/// `[fill] passive`, `friction_deg` and `passive_mobilisation`: the fill's passive resistance
/// (off by default; on, it needs the fill's angle of friction).
fn parse_passive(s: &mut Section) -> Result<Option<PassiveSpec>, SceneError> {
    let on = s.boolean("passive", false)?;
    let friction_deg = s.opt_f64("friction_deg")?;
    if let Some(phi) = friction_deg {
        if !(phi.is_finite() && (0.0..90.0).contains(&phi)) {
            return Err(s.out_of_range(
                "friction_deg",
                phi,
                "the fill's angle of friction must be a number from 0 to below 90 (degrees)",
            ));
        }
    }
    let mobilisation = s
        .opt_f64("passive_mobilisation")?
        .unwrap_or(crate::interaction::passive::DEFAULT_MOBILISATION);
    if !(mobilisation.is_finite() && (0.0..=1.0).contains(&mobilisation)) {
        return Err(s.out_of_range(
            "passive_mobilisation",
            mobilisation,
            "the mobilised fraction of the passive pressure must be a number from 0 to 1",
        ));
    }
    if !on {
        return Ok(None);
    }
    let Some(phi) = friction_deg else {
        return Err(s.missing(
            "friction_deg",
            "the fill's angle of friction in degrees, which passive = true needs for K_p = tan^2(45 + phi/2)",
        ));
    };
    Ok(Some(PassiveSpec {
        friction: phi.to_radians(),
        mobilisation,
    }))
}

/// `[action]`: what lambda multiplies. A live action needs live loads, and takes no
/// `[seismic]` table (its vertical ratio would multiply nothing).
fn parse_action(
    mut s: Section,
    table: &Table,
    loads: &[LoadSpec],
    vehicles: &[vehicles::VehicleSpec],
) -> Result<crate::model::Action, SceneError> {
    use crate::model::Action;
    s.check_known(ACTION_KEYS, "")?;
    let word = s.string("kind", Some("seismic"))?;
    let action: Action = word
        .parse()
        .map_err(|why: String| s.out_of_range("kind", format!("\"{word}\""), &why))?;
    s.finish("")?;
    if action == Action::Live {
        if table.contains_key("seismic") {
            return Err(s.out_of_range(
                "kind",
                "\"live\"",
                "a live action takes no [seismic] table: lambda multiplies the live loads, not a ground motion (remove [seismic], or use kind = \"seismic\")",
            ));
        }
        if !loads.iter().any(LoadSpec::live) && !vehicles.iter().any(|v| v.live) {
            return Err(s.out_of_range(
                "kind",
                "\"live\"",
                "a live action needs at least one [[loads]] entry with live = true, or a live [[vehicles]] entry (lambda multiplies those loads and nothing else)",
            ));
        }
    }
    Ok(action)
}

fn parse_seismic(mut s: Section) -> Result<SeismicSpec, SceneError> {
    s.check_known(SEISMIC_KEYS, "")?;
    let r = s.opt_f64("vertical_ratio")?.unwrap_or(0.0);
    if !(r.is_finite() && (-1.0..=1.0).contains(&r)) {
        return Err(s.out_of_range("vertical_ratio", r, "must be from -1 to 1"));
    }
    s.finish("")?;
    Ok(SeismicSpec { vertical_ratio: r })
}

fn parse_material(mut s: Section) -> Result<Material, SceneError> {
    s.check_known(MATERIAL_KEYS, "")?;
    let unit_weight = s.positive("unit_weight", Some(20000.0), "")?;
    // Bounded so that every block's weight is a finite, nonzero number.
    if unit_weight > MAX_UNIT_WEIGHT {
        return Err(s.out_of_range(
            "unit_weight",
            unit_weight,
            &format!("must be a number > 0 and at most {MAX_UNIT_WEIGHT:e} (N/m^3)"),
        ));
    }
    let depth = s.positive("depth", Some(1.0), "")?;
    if !(MIN_LENGTH..=MAX_LENGTH).contains(&depth) {
        return Err(s.out_of_range(
            "depth",
            depth,
            &format!("must be a length from {MIN_LENGTH:e} to {MAX_LENGTH:e} m"),
        ));
    }
    let friction = s.opt_f64("friction")?.unwrap_or(f64::INFINITY);
    if friction.is_nan() || friction < 0.0 || (friction.is_finite() && friction > MAX_FRICTION) {
        return Err(s.out_of_range(
            "friction",
            friction,
            &format!("must be from 0 to {MAX_FRICTION:e}, or inf for no sliding (a larger finite coefficient is inf to solver precision, and its rows would wreck the conic program's scaling)"),
        ));
    }
    let compressive_strength = s.opt_f64("compressive_strength")?.unwrap_or(f64::INFINITY);
    if compressive_strength.is_nan() || compressive_strength <= 0.0 {
        return Err(s.out_of_range(
            "compressive_strength",
            compressive_strength,
            "must be a stress > 0 in Pa (for example 1e6 for 1 MPa), or inf for joints that cannot crush",
        ));
    }
    let tie_design_strength = s.positive(
        "tie_design_strength",
        Some(DEFAULT_TIE_DESIGN_STRENGTH),
        "the design yield strength of tie steel in Pa",
    )?;
    s.finish("")?;
    Ok(Material {
        unit_weight,
        depth,
        friction,
        compressive_strength,
        tie_design_strength,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    const BASE: &str =
        "[arch]\nshape = \"circular\"\nradius = 1.0\nthickness = 0.15\nvoussoirs = 16\n";

    #[test]
    fn defaults_are_the_spec_ones() {
        let s = Scene::from_toml_str(BASE, "t").unwrap();
        assert_eq!(s.material.unit_weight, 20000.0);
        assert_eq!(s.material.depth, 1.0);
        assert!(s.material.friction.is_infinite());
        let arch = s.arch.as_ref().unwrap();
        assert_eq!(arch.voussoir_shape, VoussoirShape::Polygon);
        assert_eq!(arch.shape.name(), "circular");
        let (key, deg) = arch.shape.keys()[1];
        assert!(key == "embrace_deg" && (deg - 180.0).abs() < 1e-12);
    }

    #[test]
    fn override_revalidates() {
        let s = Scene::from_toml_str(BASE, "t").unwrap();
        let s2 = s.with_override("arch.thickness=0.3").unwrap();
        assert_eq!(s2.arch.as_ref().unwrap().thickness, 0.3);
        let e = s.with_override("arch.thickness=-1").unwrap_err();
        assert_eq!(e.key(), Some("arch.thickness"));
        let e = s.with_override("arch.colour=3").unwrap_err();
        assert_eq!(e.key(), Some("arch.colour"));
        let s3 = s.with_override("material.friction=inf").unwrap();
        assert!(s3.material.friction.is_infinite());
    }
}
