//! The JSON reports (`analyze --json`, `min-thickness --json`, `dem --json`): a contract for
//! scripts. Later versions add fields, never rename them.

use crate::analysis::SceneAnalysis;
use crate::assembly::{Hinge, JointKind};
use crate::geometry::Stereotomy;
use crate::kinematic::ContinuousHinge;
use crate::model::Model;
use crate::outcome::{Direction, Status};
use crate::scene::{FillSpec, LoadSpec, Pier, PierProfile, Scene, VoussoirShape};
use crate::statics::{ModelSize, StaticResult};
use crate::thickness::{MinThickness, ThicknessAnalysis, ThicknessOutcome};
use serde::Serialize;
use std::collections::BTreeMap;

/// One joint in `analyze --json`.
#[derive(Debug, Serialize)]
pub struct JointReport {
    pub index: usize,
    /// What the joint is: `arch`, `left_pier` or `right_pier` with its number.
    pub kind: JointKind,
    pub p1: [f64; 2],
    pub p2: [f64; 2],
    /// Normal force (N), null when the structure has no collapse state.
    #[serde(rename = "N")]
    pub n: Option<f64>,
    /// Shear force (N) along p1 -> p2.
    #[serde(rename = "V")]
    pub v: Option<f64>,
    /// Moment about the joint midpoint (N m), positive toward p2.
    #[serde(rename = "M")]
    pub m: Option<f64>,
    /// Eccentricity M/N (m) from the midpoint toward p2.
    pub e: Option<f64>,
    /// Thrust-line point `p_mid + e u`.
    pub thrust: Option<[f64; 2]>,
}

/// Scene summary echoed in the JSON.
#[derive(Debug, Serialize)]
pub struct SceneReport {
    pub origin: String,
    pub shape: &'static str,
    pub thickness: f64,
    pub voussoirs: usize,
    pub voussoir_shape: &'static str,
    pub portal: bool,
    /// Coulomb coefficient; null means infinite (no sliding): JSON has no infinity, so
    /// `friction_infinite` says it in a field of its own.
    pub friction: Option<f64>,
    pub total_weight: f64,
    /// The shape's own `[arch]` keys with their scene values, flattened into this object:
    /// `radius`, `embrace_deg` (circular); `radius`, `eccentricity` (pointed); `span`, `rise`,
    /// `side_angle_deg` (basket). Angles that went through radians are rounded to 15
    /// significant digits (`120`, not `119.99999999999999`).
    #[serde(flatten)]
    pub shape_keys: BTreeMap<&'static str, f64>,
    /// `[piers]` (height and width in m, courses), or null for an arch on fixed springings.
    pub piers: Option<PiersReport>,
    /// `[arch] joints`: the stereotomy (`radial`, `vertical`, `horizontal_bed`); `user` for a
    /// scene of the user's own blocks.
    pub joints: &'static str,
    /// `[arch] horizontal_bed_deg` (degrees), or null unless `joints` is `horizontal_bed`.
    pub horizontal_bed_deg: Option<f64>,
    /// `[blocks]` and the joints found, for a scene of the user's own blocks (absent
    /// otherwise). Such a scene reports `shape` = "blocks", `voussoir_shape` = "user",
    /// `thickness` null and `voussoirs` 0.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub blocks: Option<BlocksReport>,
    /// `[arcade]` (`bays`, `column_width` in m), present only for an arcade.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub arcade: Option<crate::scene::ArcadeSpec>,
    /// `[spandrel]` (`level`, `course_height`, `unit_length` in m) with `pieces`, the number
    /// of the wall's blocks; present only with a spandrel wall.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub spandrel: Option<SpandrelReport>,
    /// `[material] unit_weight` (N/m^3).
    pub unit_weight: f64,
    /// `[material] depth` (m).
    pub depth: f64,
    /// Whether the friction coefficient is infinite (joints cannot slide; `friction` is then
    /// null).
    pub friction_infinite: bool,
    /// `[material] compressive_strength` (Pa); null means infinite (rigid joints, no crushing).
    pub compressive_strength: Option<f64>,
    /// The strength ratio `W/(fc d t)` (0 for rigid joints), see [`crate::sweep::sigma`].
    pub sigma: f64,
}

/// `[spandrel]` echoed in the JSON `scene`, with the number of pieces it was cut into.
#[derive(Debug, Serialize)]
pub struct SpandrelReport {
    #[serde(flatten)]
    pub spec: crate::scene::SpandrelSpec,
    /// Blocks of the wall.
    pub pieces: usize,
}

/// `[blocks]` echoed in the JSON `scene`, with what was found: present only for scenes of the
/// user's own blocks.
#[derive(Debug, Serialize)]
pub struct BlocksReport {
    /// The block file as written in the scene, or null for inline polygons.
    pub file: Option<String>,
    /// `"m"` or `"mm"`.
    pub units: &'static str,
    /// Number of blocks.
    pub blocks: usize,
    /// Joints found between blocks.
    pub joints: usize,
    /// Joints found on the ground (and, added, on the fixed blocks).
    pub supports: usize,
    /// y of the ground line (m); null when there is none (added: only fixed blocks support).
    pub ground_y: Option<f64>,
    /// The joint tolerance (m).
    pub tolerance: f64,
    /// Whether the blocks form a chain (between two supports, or on one): the kinematic
    /// search runs only then.
    pub chain: bool,
    /// Why not, when not.
    pub not_a_chain: Option<String>,
    /// Added: the fixed blocks (`[blocks] fixed`), each with its point as written, the block
    /// it names (its index in the source) and the support joints found on it.
    pub fixed: Vec<FixedReport>,
    /// Added: how many outlines were mended as they were read, and how.
    pub mended: crate::blocks::Mending,
}

/// A fixed block in the JSON `scene.blocks.fixed`.
#[derive(Debug, Serialize)]
pub struct FixedReport {
    /// The point of `[blocks] fixed`, in the blocks' units.
    pub point: [f64; 2],
    /// The block it lies in (index in the source).
    pub block: usize,
    /// Support joints found on it.
    pub supports: usize,
}

impl BlocksReport {
    pub fn new(b: &crate::scene::BlocksSpec) -> Self {
        let d = &b.detected;
        BlocksReport {
            file: match &b.source {
                crate::scene::BlockSource::File { written, .. } => Some(written.clone()),
                crate::scene::BlockSource::Inline => None,
            },
            units: b.units.name(),
            blocks: d.assembly.blocks.len(),
            joints: d.assembly.joints.len() - d.supports,
            supports: d.supports,
            ground_y: d.ground_y,
            tolerance: d.tolerance,
            chain: !matches!(d.topology, crate::blocks::Topology::Other(_)),
            not_a_chain: match &d.topology {
                crate::blocks::Topology::Other(why) => Some(why.clone()),
                _ => None,
            },
            fixed: d
                .fixed
                .iter()
                .zip(&b.fixed)
                .map(|(f, &point)| FixedReport {
                    point,
                    block: f.block,
                    supports: f.supports,
                })
                .collect(),
            mended: b.mending,
        }
    }
}

/// `[piers]` echoed in the JSON `scene`: `height`, `width` and `courses` are the left pier's
/// (its base width), the whole portal's when the piers are equal and rectangular; `left` and
/// `right` give each pier with its scene keys.
#[derive(Debug, Serialize)]
pub struct PiersReport {
    pub height: f64,
    pub width: f64,
    pub courses: usize,
    pub left: PierReport,
    pub right: PierReport,
}

/// One pier with its scene keys (`[piers.left]`, `[piers.right]`); the keys its profile does
/// not take are left out.
#[derive(Debug, Serialize)]
pub struct PierReport {
    /// `rectangular`, `stepped` or `battered`.
    pub shape: &'static str,
    pub height: f64,
    pub courses: usize,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub width: Option<f64>,
    /// Course widths, base to top (stepped).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub widths: Option<Vec<f64>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub bottom_width: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub top_width: Option<f64>,
}

impl PierReport {
    fn new(p: &Pier) -> Self {
        let mut r = PierReport {
            shape: p.shape_name(),
            height: p.height,
            courses: p.courses,
            width: None,
            widths: None,
            bottom_width: None,
            top_width: None,
        };
        match &p.profile {
            PierProfile::Rectangular { width } => r.width = Some(*width),
            PierProfile::Stepped { widths } => r.widths = Some(widths.clone()),
            PierProfile::Battered {
                bottom_width,
                top_width,
            } => {
                r.bottom_width = Some(*bottom_width);
                r.top_width = Some(*top_width);
            }
        }
        r
    }
}

/// The loads of a scene as read, and their totals (fields `loads`, `fill`, `vertical_ratio`,
/// `permanent_weight`, `seismic_weight` of every JSON report).
#[derive(Debug, Serialize)]
pub struct LoadsReport {
    /// The `[[loads]]` entries as read (`type`, and `at`/`force` or `from_x`/`to_x`/
    /// `intensity`, and `seismic`).
    pub loads: Vec<LoadSpec>,
    /// Added: the `[[vehicles]]` entries as read (name, axles, at, live, and `beyond`, the
    /// distributed load past the axles of a built-in model), absent when none.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub vehicles: Vec<crate::scene::vehicles::VehicleSpec>,
    /// `[fill]` as read, or null.
    pub fill: Option<FillSpec>,
    /// `[seismic] vertical_ratio`.
    pub vertical_ratio: f64,
    /// Total downward permanent force (N): self-weight, fill, point and line loads.
    pub permanent_weight: f64,
    /// Total weight of the seismic masses (N): the horizontal seismic force is lambda times
    /// this.
    pub seismic_weight: f64,
    /// What lambda multiplies (`[action] kind`): `seismic` (the collapse acceleration in g)
    /// or `live` (the adequacy factor of the live loads).
    pub action: crate::model::Action,
    /// Sum of the magnitudes of the live loads (N); 0 when none is live.
    pub live_weight: f64,
    /// Under a seismic action whose every load is a seismic mass and with no vertical
    /// component, the tilt of a tilting table that loads the blocks as lambda does,
    /// `atan(lambda)` in degrees, from `lambda_lower`; null otherwise (and with no
    /// `lambda_lower`).
    pub tilt_deg: Option<f64>,
}

impl LoadsReport {
    pub fn new(scene: &Scene, model: &Model) -> Self {
        LoadsReport {
            action: scene.action,
            live_weight: model.loads.live_magnitude(),
            tilt_deg: None,
            loads: scene.loads.clone(),
            vehicles: scene.vehicles.clone(),
            fill: scene.fill.clone(),
            vertical_ratio: scene.seismic.vertical_ratio,
            permanent_weight: model.loads.permanent_weight(),
            seismic_weight: model.loads.seismic_weight(),
        }
    }
}

/// `analyze --json`.
#[derive(Debug, Serialize)]
pub struct AnalysisReport {
    pub status: Status,
    pub lambda_lower: Option<f64>,
    pub hinges: Vec<Hinge>,
    pub sliding: Vec<usize>,
    /// Whether `lambda_lower` (or the status) holds for real joints, which slide without
    /// opening: true with infinite friction, when the structure cannot stand, and at collapse
    /// when no joint in contact slips in the static mechanism; false otherwise, and then
    /// `lambda_lower` is the associative multiplier, an upper bound of the real
    /// (non-associative) collapse multiplier, not a safe lower bound (docs/friction.md).
    pub friction_exact: bool,
    /// Exact with finite friction in an assembly that is not a chain (a wall, a stack): the
    /// static collapse state is one of real joints, but joints with little or no compression
    /// (a wall's head joints) can give real joints lower ones, so `lambda_lower` is not called
    /// a lower bound there (docs/friction.md). False otherwise.
    pub friction_lower_states_possible: bool,
    /// The multiplier of the associative friction joint: `lambda_lower` whenever there is one
    /// (exact or not), null otherwise.
    pub lambda_associative: Option<f64>,
    /// Joints in contact that slip in the static collapse mechanism (`friction_exact` is false
    /// when there is any).
    pub slipping_joints: Vec<usize>,
    /// `friction_exact` in words when it is false, null otherwise.
    pub friction_note: Option<String>,
    /// `friction_lower_states_possible` in words when it is true (what the exact value is and
    /// is not), null otherwise.
    pub friction_lower_states_note: Option<String>,
    /// The non-associative collapse multiplier (joints that slide without opening; docs/
    /// friction.md): the lowest converged value of the starts tried, equal to
    /// `lambda_associative` when `friction_exact` is true (not iterated); null when not
    /// computed (`--friction associative`, infinite friction, no collapse) or when no start
    /// converged.
    pub lambda_non_associative: Option<f64>,
    /// Whether a start of the non-associative iteration converged; null when not computed.
    pub non_associative_converged: Option<bool>,
    /// Programs solved by the non-associative iteration, all starts together (0 when the
    /// associative multiplier is exact or nothing was computed).
    pub non_associative_iterations: u32,
    /// The joints that slip (without opening) in the retained non-associative mechanism.
    pub non_associative_sliding_joints: Vec<usize>,
    /// Every start of the non-associative iteration: `start`, `lambda` (its last iterate),
    /// `iterations`, `converged`.
    pub non_associative_starts: Vec<NonAssociativeStartReport>,
    /// What the non-associative value is, in words; null when not computed.
    pub non_associative_note: Option<String>,
    /// The multiplier that governs (the page's large number, `assess`, `retrofit`):
    /// `lambda_non_associative` when there is one, `lambda_lower` otherwise.
    pub lambda_governing: Option<f64>,
    /// The DEM check of the same scene (only with `analyze --dem`): its Coulomb contacts
    /// slide without opening, so it estimates the non-associative collapse.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub dem: Option<AnalysisDemReport>,
    pub joints: Vec<JointReport>,
    pub mechanism: Vec<[f64; 3]>,
    pub equilibrium_residual: f64,
    pub blocks: usize,
    pub solve_time_s: f64,
    pub direction: Direction,
    pub solver_status: String,
    pub iterations: u32,
    pub model: ModelSize,
    pub scene: SceneReport,
    /// The loads beyond self-weight and the weights they add up to.
    #[serde(flatten)]
    pub loads: LoadsReport,
    /// Discrete kinematic (upper-bound) multiplier, or null (no collapse, cannot stand, or
    /// the search was not run: see `kinematic_note`).
    pub lambda_upper: Option<f64>,
    /// Status of the kinematic search (same words as `status`), or null when not run.
    pub kinematic_status: Option<Status>,
    /// `|lambda_upper - lambda_lower| / max(1, lambda_lower)` when both exist.
    pub gap: Option<f64>,
    /// Hinges of the governing kinematic mechanism (same form as `hinges`).
    pub mechanism_hinges: Vec<Hinge>,
    /// Joints that open completely in that mechanism.
    pub open_joints: Vec<usize>,
    /// Finite friction and a static bound below the rotational upper bound: sliding governs.
    pub sliding_governs: bool,
    /// Block velocities of the kinematic mechanism `[vx, vy, omega]`.
    pub kinematic_mechanism: Vec<[f64; 3]>,
    /// Added: joints that slide in the kinematic mechanism (only the general program's
    /// mechanisms slide; empty otherwise).
    pub mechanism_sliding: Vec<usize>,
    /// Why the kinematic search was not run or failed, or what a local search covered.
    pub kinematic_note: Option<String>,
    /// `exhaustive` (lambda_upper is the discrete kinematic multiplier), `local` (only the
    /// mechanisms near the static hinges were searched: lambda_upper is an upper bound, null
    /// when that search found none), `certified`, `general` (the general kinematic program
    /// over every admissible mechanism of any assembly, docs/kinematic.md), or null when no
    /// kinematic search ran.
    pub kinematic_search: Option<crate::kinematic::Search>,
    pub kinematic_time_s: Option<f64>,
    /// Added: the admissible mechanisms the exhaustive or local search valued (the summary's
    /// "over N admissible mechanisms"); null for the certified and the general search and
    /// when none ran.
    pub kinematic_admissible: Option<u64>,
    /// Continuous model (only with `--continuous`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub lambda_continuous: Option<Option<f64>>,
    /// Hinges of the continuous mechanism (only with `--continuous`); angles in degrees.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub continuous_hinges: Option<Vec<ContinuousHinge>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub continuous_note: Option<String>,
    /// The tie rods (`[[ties]]`), in the scene's order, with their forces at collapse.
    pub ties: Vec<TieReport>,
    /// The bonded strips (`[[reinforcements]]`), in the scene's order, with their force at
    /// each joint they cross.
    pub reinforcements: Vec<ReinforcementReport>,
    /// Added: the moving load (`analyze --roll`), absent otherwise; the rest of the object is
    /// then the analysis at its critical position.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub roll: Option<RollReport>,
    /// Added: the fill's passive faces (`[fill] passive = true`), with their reactions at
    /// collapse; empty without passive fill.
    pub passive: Vec<PassiveReport>,
    /// Added: whether the fill's passive resistance governs the collapse (some face's
    /// reaction is at its cap: the fill yields in the mechanism).
    pub passive_governs: bool,
}

/// A moving load's multipliers at every position (`analyze --roll`, [`crate::roll`]).
#[derive(Debug, Clone, Serialize)]
pub struct RollReport {
    /// What moved: `loads[k]` or `vehicles[k]`.
    pub target: String,
    /// The positions (m): a vehicle's first axle, a point load's x, a line load's from_x.
    pub positions: Vec<f64>,
    /// The static status at each position.
    pub status: Vec<Status>,
    /// The static multiplier (lower bound) at each position.
    pub lambda_lower: Vec<Option<f64>>,
    /// The kinematic multiplier (upper bound) at each position, null where none ran.
    pub lambda_upper: Vec<Option<f64>>,
    /// The critical position (m): the least static multiplier, refined between the grid
    /// neighbours by golden section; null when the structure stands nowhere.
    pub critical_position: Option<f64>,
    /// The grid position with the least static multiplier (m).
    pub critical_grid_position: Option<f64>,
}

impl RollReport {
    pub fn new(r: &crate::roll::Roll) -> Self {
        RollReport {
            target: r.spec.target.to_string(),
            positions: r.points.iter().map(|p| p.position).collect(),
            status: r.points.iter().map(|p| p.status).collect(),
            lambda_lower: r.points.iter().map(|p| p.lambda_lower).collect(),
            lambda_upper: r.points.iter().map(|p| p.lambda_upper).collect(),
            critical_position: r.critical.as_ref().map(|c| c.position),
            critical_grid_position: r.critical.as_ref().map(|c| c.grid_position),
        }
    }
}

/// A face against the fill and its passive reaction at collapse.
#[derive(Debug, Clone, Serialize)]
pub struct PassiveReport {
    /// The block (index in `blocks`) whose face lies against the fill.
    pub block: usize,
    /// The face's ends under the fill level (m).
    pub from: [f64; 2],
    pub to: [f64; 2],
    /// Where the reaction acts (m): the centroid of the pressure diagram.
    pub point: [f64; 2],
    /// The direction the face moves into the fill: +1 (+x) or -1 (-x); the reaction pushes
    /// the other way.
    pub into: f64,
    /// The largest reaction, m_p K_p sigma_v h (N).
    pub cap: f64,
    /// The reaction at collapse (N), null when the structure does not collapse.
    pub force: Option<f64>,
    /// Whether it is at its cap, null without collapse.
    pub yielded: Option<bool>,
}

impl PassiveReport {
    /// The passive faces of `model` with the reactions of `r`.
    pub fn all(model: &Model, r: &StaticResult) -> Vec<PassiveReport> {
        model
            .passive
            .iter()
            .enumerate()
            .map(|(k, p)| {
                let f = r.passive.get(k);
                PassiveReport {
                    block: p.block,
                    from: xy(p.a),
                    to: xy(p.b),
                    point: xy(p.point),
                    into: p.into,
                    cap: p.cap,
                    force: f.map(|f| f.force),
                    yielded: f.map(|f| f.yielded),
                }
            })
            .collect()
    }
}

/// The name of a strip's face in the scene and the JSON.
pub(crate) fn face_name(face: crate::assembly::JointEnd) -> &'static str {
    match face {
        crate::assembly::JointEnd::P1 => "intrados",
        crate::assembly::JointEnd::P2 => "extrados",
    }
}

/// A bonded strip and its forces at collapse.
#[derive(Debug, Clone, Serialize)]
pub struct ReinforcementReport {
    pub index: usize,
    /// `intrados` or `extrados`.
    pub face: &'static str,
    pub from_joint: usize,
    pub to_joint: usize,
    /// Tensile capacity at each crossed joint (N).
    pub tensile_capacity: f64,
    /// The crossed joints, with the strip's tension there at collapse.
    pub joints: Vec<StripJointReport>,
}

/// A strip's tension at one joint.
#[derive(Debug, Clone, Serialize)]
pub struct StripJointReport {
    /// The joint (index in `joints`).
    pub joint: usize,
    /// Tension at collapse (N), null when the structure does not collapse.
    pub force: Option<f64>,
    /// Whether it has reached the capacity (debonded), null without collapse.
    pub yielded: Option<bool>,
}

impl ReinforcementReport {
    /// The strips of `scene` with the forces of `r`.
    pub fn all(scene: &Scene, model: &Model, r: &StaticResult) -> Vec<ReinforcementReport> {
        scene
            .reinforcements
            .iter()
            .enumerate()
            .map(|(index, spec)| ReinforcementReport {
                index,
                face: face_name(spec.face),
                from_joint: spec.from_joint,
                to_joint: spec.to_joint,
                // The model's (the scene's, or a retrofit design's when it sized it).
                tensile_capacity: (model.strips.iter())
                    .find(|s| s.source == index)
                    .map(|s| s.capacity)
                    .or(spec.tensile_capacity)
                    .unwrap_or(0.0),
                joints: model
                    .strips
                    .iter()
                    .enumerate()
                    .filter(|(_, s)| s.source == index)
                    .map(|(k, s)| {
                        let f = r.strips.get(k);
                        StripJointReport {
                            joint: s.joint,
                            force: f.map(|f| f.force),
                            yielded: f.map(|f| f.yielded),
                        }
                    })
                    .collect(),
            })
            .collect()
    }
}

/// A tie rod and its force in the static solution at collapse.
#[derive(Debug, Clone, Serialize)]
pub struct TieReport {
    pub index: usize,
    /// Anchor points (m).
    pub from: [f64; 2],
    pub to: [f64; 2],
    /// The anchored blocks (assembly order), null for the ground.
    pub from_block: Option<usize>,
    pub to_block: Option<usize>,
    /// Yield force and prestress (N).
    pub capacity: f64,
    pub prestress: f64,
    /// Tension at collapse (N), null when the structure does not collapse.
    pub force: Option<f64>,
    /// Whether the tie has yielded at collapse (its force at the capacity), null without
    /// collapse.
    pub yielded: Option<bool>,
}

impl TieReport {
    /// The ties of `model` with the forces of `r`.
    pub fn all(model: &Model, r: &StaticResult) -> Vec<TieReport> {
        model
            .ties
            .iter()
            .enumerate()
            .map(|(index, t)| {
                let f = r.ties.get(index);
                TieReport {
                    index,
                    from: xy(t.from.point),
                    to: xy(t.to.point),
                    from_block: t.from.block,
                    to_block: t.to.block,
                    capacity: t.capacity,
                    prestress: t.prestress,
                    force: f.map(|f| f.force),
                    yielded: f.map(|f| f.yielded),
                }
            })
            .collect()
    }
}

/// The tilting table's angle (degrees) that loads the blocks as `lambda` does: `atan(lambda)`,
/// when the action is seismic, every load is a seismic mass and there is no vertical
/// component (then gravity and lambda g act on every mass alike, as the tilted weight's two
/// components do, up to the factor cos of the tilt that does not change a mechanism's
/// multiplier); None otherwise.
pub fn tilt_deg(scene: &Scene, lambda: Option<f64>) -> Option<f64> {
    let every_load_seismic =
        scene.loads.iter().all(LoadSpec::seismic) && scene.fill.as_ref().is_none_or(|f| f.seismic);
    (scene.action == crate::model::Action::Seismic
        && scene.seismic.vertical_ratio == 0.0
        && every_load_seismic)
        .then_some(lambda)
        .flatten()
        .map(|l| l.atan().to_degrees())
}

fn xy(p: crate::geometry::Vec2) -> [f64; 2] {
    [p.x, p.y]
}

fn finite_or_null(x: f64) -> Option<f64> {
    x.is_finite().then_some(x)
}

/// `x` rounded to 15 significant digits: what a value read in degrees and kept in radians
/// was (`119.99999999999999` -> `120`).
fn round15(x: f64) -> f64 {
    if x.is_finite() {
        format!("{x:.14e}").parse().unwrap_or(x)
    } else {
        x
    }
}

impl SceneReport {
    pub fn new(scene: &Scene, model: &Model) -> Self {
        let arch = scene.arch.as_ref();
        SceneReport {
            origin: scene.origin.clone(),
            shape: arch.map_or("blocks", |a| a.shape.name()),
            thickness: arch.map_or(f64::NAN, |a| a.thickness),
            voussoirs: arch.map_or(0, |a| a.voussoirs),
            voussoir_shape: match arch.map(|a| a.voussoir_shape) {
                Some(VoussoirShape::Polygon) => "polygon",
                Some(VoussoirShape::Curved) => "curved",
                None => "user",
            },
            portal: scene.piers.is_some(),
            friction: finite_or_null(scene.material.friction),
            total_weight: model.assembly.total_weight(),
            shape_keys: arch
                .map(|a| a.shape.keys())
                .unwrap_or_default()
                .into_iter()
                .map(|(k, v)| (k, round15(v)))
                .collect(),
            blocks: scene.blocks.as_ref().map(|b| BlocksReport::new(b)),
            arcade: scene.arcade.clone(),
            spandrel: scene.spandrel.clone().map(|spec| SpandrelReport {
                spec,
                pieces: model
                    .assembly
                    .blocks
                    .iter()
                    .filter(|b| matches!(b.kind, crate::assembly::BlockKind::Spandrel(..)))
                    .count(),
            }),
            piers: scene.piers.as_ref().map(|p| PiersReport {
                height: p.left.height,
                width: p.left.base_width(),
                courses: p.left.courses,
                left: PierReport::new(&p.left),
                right: PierReport::new(&p.right),
            }),
            joints: arch.map_or("user", |a| a.joints.name()),
            horizontal_bed_deg: match arch.map(|a| a.joints) {
                Some(Stereotomy::HorizontalBed { angle }) => Some(round15(angle.to_degrees())),
                _ => None,
            },
            unit_weight: scene.material.unit_weight,
            depth: scene.material.depth,
            friction_infinite: scene.material.friction.is_infinite(),
            compressive_strength: finite_or_null(scene.material.compressive_strength),
            sigma: strength_ratio(scene, model),
        }
    }
}

/// `W/(fc d t)` of the scene's model (0 for rigid joints).
fn strength_ratio(scene: &Scene, model: &Model) -> f64 {
    let fc = scene.material.compressive_strength;
    if fc.is_finite() {
        // No ring thickness in a scene of the user's own blocks: no ratio (null).
        let t = scene.arch.as_ref().map_or(f64::NAN, |a| a.thickness);
        model.assembly.total_weight() / (fc * scene.material.depth * t)
    } else {
        0.0
    }
}

impl AnalysisReport {
    pub fn new(scene: &Scene, a: &SceneAnalysis) -> Self {
        let mut report = AnalysisReport::new_static(scene, &a.model, &a.lower);
        match &a.upper {
            Ok(k) => {
                report.lambda_upper = k.lambda_upper;
                report.kinematic_status = Some(k.status);
                report.kinematic_time_s = Some(k.wall_time_s);
                report.kinematic_note.clone_from(&k.note);
                if let Some(m) = &k.mechanism {
                    report.mechanism_hinges = m.hinges.clone();
                    report.open_joints = m.open.clone();
                    report.kinematic_mechanism = m.velocities.clone();
                    report.mechanism_sliding = m.sliding.clone();
                }
            }
            Err(note) => report.kinematic_note = Some(note.clone()),
        }
        report.kinematic_search = a.kinematic_search;
        if let (
            Ok(k),
            Some(crate::kinematic::Search::Exhaustive | crate::kinematic::Search::Local),
        ) = (&a.upper, a.kinematic_search)
        {
            report.kinematic_admissible = Some(k.admissible);
        }
        report.set_non_associative(a);
        report.gap = a.gap();
        report.sliding_governs = a.sliding_governs();
        if let Some(c) = &a.continuous {
            match c {
                Ok(c) => {
                    report.lambda_continuous = Some(c.lambda_continuous);
                    report.continuous_hinges = Some(c.hinges.clone());
                }
                Err(note) => {
                    report.lambda_continuous = Some(None);
                    report.continuous_note = Some(note.clone());
                }
            }
        }
        report
    }

    /// The static part alone.
    pub fn new_static(scene: &Scene, model: &Model, r: &StaticResult) -> Self {
        let mut loads = LoadsReport::new(scene, model);
        loads.tilt_deg = tilt_deg(scene, r.lambda);
        let assembly = &model.assembly;
        let points = r.thrust_points(assembly);
        let joints = assembly
            .joints
            .iter()
            .enumerate()
            .map(|(i, j)| {
                let f = r.forces.as_ref().and_then(|f| f.get(i));
                JointReport {
                    index: i,
                    kind: j.kind,
                    p1: xy(j.p1),
                    p2: xy(j.p2),
                    n: f.map(|f| f.n),
                    v: f.map(|f| f.v),
                    m: f.map(|f| f.m),
                    e: r.eccentricity(i),
                    thrust: points.get(i).copied().flatten().map(xy),
                }
            })
            .collect();
        let friction = r.friction(assembly);
        AnalysisReport {
            status: r.status,
            lambda_lower: r.lambda,
            hinges: r.hinges.clone(),
            sliding: r.sliding.clone(),
            friction_exact: friction.exact,
            friction_lower_states_possible: friction.lower_states_possible,
            lambda_associative: friction.lambda_associative,
            friction_note: super::words::friction_words(&friction, r.status),
            friction_lower_states_note: super::words::exact_friction_words(&friction),
            slipping_joints: friction.slipping,
            lambda_non_associative: None,
            non_associative_converged: None,
            non_associative_iterations: 0,
            non_associative_sliding_joints: Vec::new(),
            non_associative_starts: Vec::new(),
            non_associative_note: None,
            lambda_governing: r.lambda,
            dem: None,
            joints,
            mechanism: r.mechanism.clone(),
            equilibrium_residual: r.equilibrium_residual,
            blocks: assembly.blocks.len(),
            solve_time_s: r.solve_time_s,
            direction: r.direction,
            solver_status: r.solver_status.clone(),
            iterations: r.iterations,
            model: r.model,
            scene: SceneReport::new(scene, model),
            loads,
            lambda_upper: None,
            kinematic_status: None,
            gap: None,
            mechanism_hinges: Vec::new(),
            open_joints: Vec::new(),
            sliding_governs: false,
            kinematic_mechanism: Vec::new(),
            mechanism_sliding: Vec::new(),
            kinematic_note: None,
            kinematic_search: None,
            kinematic_time_s: None,
            kinematic_admissible: None,
            lambda_continuous: None,
            continuous_hinges: None,
            continuous_note: None,
            ties: TieReport::all(model, r),
            reinforcements: ReinforcementReport::all(scene, model, r),
            roll: None,
            passive: PassiveReport::all(model, r),
            passive_governs: crate::interaction::passive::governs(&r.passive),
        }
    }
}

/// The DEM check in `analyze --dem --json`.
#[derive(Debug, Serialize)]
pub struct AnalysisDemReport {
    /// The DEM's multiplier (the middle of its bracket), null when it found none.
    pub lambda_dem: Option<f64>,
    /// The bracket `[stands, collapses]`.
    pub lambda_stands: Option<f64>,
    pub lambda_collapses: Option<f64>,
    pub wall_time_s: Option<f64>,
    /// Why there is no DEM result, or its warnings; null when none.
    pub note: Option<String>,
}

/// One start of the non-associative iteration, in `analyze --json`.
#[derive(Debug, Serialize)]
pub struct NonAssociativeStartReport {
    /// `associative`, `least_friction` or `at_rest` (docs/friction.md).
    pub start: &'static str,
    /// The multiplier of its last program (a solution only when `converged`).
    pub lambda: Option<f64>,
    pub iterations: u32,
    pub converged: bool,
    /// Added: how it settled, `relaxation` or `mechanism_step` (docs/friction.md, "The
    /// mechanism's fixed point"); null when it did not.
    pub settled_by: Option<&'static str>,
}

impl AnalysisReport {
    /// The non-associative fields of `a` (left at their defaults when not computed).
    fn set_non_associative(&mut self, a: &SceneAnalysis) {
        self.lambda_governing = a.lambda_governing();
        self.dem = a.dem.as_ref().map(|d| match d {
            Ok(d) => AnalysisDemReport {
                lambda_dem: d.lambda_dem,
                lambda_stands: d.lambda_stands,
                lambda_collapses: d.lambda_collapses,
                wall_time_s: Some(d.wall_time_s),
                note: (!d.warnings.is_empty()).then(|| d.warnings.join("; ")),
            },
            Err(e) => AnalysisDemReport {
                lambda_dem: None,
                lambda_stands: None,
                lambda_collapses: None,
                wall_time_s: None,
                note: Some(e.clone()),
            },
        });
        let Some(na) = &a.non_associative else {
            return;
        };
        self.lambda_non_associative = na.lambda;
        self.non_associative_converged = Some(na.converged);
        self.non_associative_iterations = na.iterations;
        self.non_associative_sliding_joints.clone_from(&na.sliding);
        self.non_associative_starts = na
            .starts
            .iter()
            .map(|s| NonAssociativeStartReport {
                start: s.start.as_str(),
                lambda: s.lambda,
                iterations: s.iterations,
                converged: s.converged(),
                settled_by: s.settled_by.map(|b| b.as_str()),
            })
            .collect();
        self.non_associative_note = Some(super::words::non_associative_words(na));
    }
}

/// `min-thickness --json`.
#[derive(Debug, Serialize)]
pub struct MinThicknessReport {
    /// `found`, `never_stands` or `stands_at_every_thickness`.
    pub outcome: ThicknessOutcome,
    pub min_thickness: Option<f64>,
    /// min_thickness divided by the characteristic size (R for circular and pointed arches,
    /// span/2 for basket arches).
    pub min_thickness_ratio: Option<f64>,
    pub hinges: Vec<Hinge>,
    pub safety_factor: Option<f64>,
    pub thickness: f64,
    pub evaluations: usize,
    pub scene: SceneReport,
    #[serde(flatten)]
    pub loads: LoadsReport,
    /// Kinematic minimum thickness (where lambda_upper reaches 0), or null when not run.
    pub min_thickness_kinematic: Option<f64>,
    /// `|t_static - t_kinematic| / t_static`.
    pub min_thickness_gap: Option<f64>,
    /// How the kinematic minimum thickness was found: `certified` (the mechanism of the static
    /// hinges by virtual work) or `exhaustive` (bisection on the exhaustive search); null when
    /// not run.
    pub kinematic_search: Option<&'static str>,
    pub kinematic_note: Option<String>,
    /// Continuous-model minimum thickness (only with `--continuous`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub min_thickness_continuous: Option<Option<f64>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub continuous_hinges: Option<Vec<ContinuousHinge>>,
    /// Why the continuous model failed (only with `--continuous`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub continuous_note: Option<String>,
    /// The minimum thickness with non-associative joints, or null when none was found (only
    /// with `--friction non-associative` and finite friction; docs/friction.md).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub min_thickness_non_associative: Option<Option<f64>>,
    /// How that search ended (`found`, `never_stands`, `stands_at_every_thickness`; only with
    /// it).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub non_associative_outcome: Option<ThicknessOutcome>,
}

impl MinThicknessReport {
    /// The report of every method in `t`.
    pub fn new(scene: &Scene, model: &Model, t: &ThicknessAnalysis) -> Self {
        let mut rep = MinThicknessReport::new_static(scene, model, &t.lower);
        rep.min_thickness_kinematic = t.kinematic.as_ref().and_then(|k| k.min_thickness);
        rep.min_thickness_gap = t.gap();
        rep.kinematic_search = t.kinematic_search.map(|k| k.as_str());
        rep.kinematic_note = t.kinematic_note.clone();
        if let Some(na) = &t.non_associative {
            rep.min_thickness_non_associative = Some(na.min_thickness);
            rep.non_associative_outcome = Some(na.outcome);
        }
        match &t.continuous {
            Some(Ok(c)) => {
                rep.min_thickness_continuous = Some(Some(c.thickness));
                rep.continuous_hinges = Some(c.result.hinges.clone());
            }
            Some(Err(e)) => {
                rep.min_thickness_continuous = Some(None);
                // The model's own errors already say where they come from.
                rep.continuous_note = Some(if e.starts_with("continuous model: ") {
                    e.clone()
                } else {
                    format!("continuous model: {e}")
                });
            }
            None => {}
        }
        rep
    }

    /// The static part alone.
    pub fn new_static(scene: &Scene, model: &Model, m: &MinThickness) -> Self {
        MinThicknessReport {
            outcome: m.search.outcome,
            min_thickness: m.search.min_thickness,
            min_thickness_ratio: m.search.min_thickness.map(|t| t / scene.arch_size()),
            hinges: m.hinges.clone(),
            safety_factor: m.safety_factor,
            thickness: scene.arch.as_ref().map_or(f64::NAN, |a| a.thickness),
            evaluations: m.search.evaluations,
            scene: SceneReport::new(scene, model),
            loads: LoadsReport::new(scene, model),
            min_thickness_kinematic: None,
            min_thickness_gap: None,
            kinematic_search: None,
            kinematic_note: None,
            min_thickness_continuous: None,
            continuous_hinges: None,
            continuous_note: None,
            min_thickness_non_associative: None,
            non_associative_outcome: None,
        }
    }
}

/// One DEM run in `dem --json`.
#[derive(Debug, Serialize)]
pub struct DemRunReport {
    /// null for the settling run under gravity alone.
    pub lambda: Option<f64>,
    pub outcome: crate::dem::Outcome,
    /// Simulated time (s) and time steps.
    pub time: f64,
    pub steps: u64,
    pub max_displacement: f64,
}

/// `dem --json`.
#[derive(Debug, Serialize)]
pub struct DemReport {
    /// `collapse`, `no_collapse` (none up to the DEM's max_lambda) or `cannot_stand`.
    pub status: &'static str,
    pub lambda_stands: Option<f64>,
    pub lambda_collapses: Option<f64>,
    pub lambda_dem: Option<f64>,
    /// The static lower bound of the scene's own assembly.
    pub lambda_lower: Option<f64>,
    /// Added: whether `lambda_lower` is exact for real (non-associative) joints, as
    /// `analyze --json`'s `friction_exact` (docs/friction.md); null when no static result was
    /// compared.
    pub friction_exact: Option<bool>,
    /// `analyze --json`'s `friction_lower_states_possible` (docs/friction.md); null when no
    /// static result was compared.
    pub friction_lower_states_possible: Option<bool>,
    /// `(lambda_dem - lambda_lower_simulated) / lambda_lower_simulated`: the DEM against the
    /// static bound of the shapes it simulated.
    pub relative_difference: Option<f64>,
    /// `(lambda_collapses - lambda_stands) / lambda_dem`.
    pub bracket_width: Option<f64>,
    /// Whether `lambda_lower_simulated` lies inside `[lambda_stands, lambda_collapses]`: then
    /// the DEM confirms it to within the bracket, and `relative_difference` (the bracket's
    /// midpoint against it) is known only to half the width.
    pub static_inside_bracket: Option<bool>,
    /// The bracket: the largest multiplier a run stood at and the smallest one a run did not
    /// (the same values as `lambda_stands` and `lambda_collapses`).
    pub lambda_dem_low: Option<f64>,
    pub lambda_dem_high: Option<f64>,
    /// The static lower bound of the shapes the DEM simulated: `lambda_lower` unless
    /// `simulated_shape` is `chord_polygons` (curved voussoirs simulated as their chord
    /// polygons), then the static bound of that polygon assembly under the same loads.
    pub lambda_lower_simulated: Option<f64>,
    /// `blocks` (the assembly's own polygons) or `chord_polygons`.
    pub simulated_shape: &'static str,
    /// Where the bracket search started, and from what: `given` (the scene's
    /// `dem.initial_guess`), `default` (a fixed value independent of the static bound) or
    /// `static` (`--from-static`: the search verifies the static value, so
    /// `relative_difference` is small by construction).
    pub initial_guess: f64,
    pub guess_source: crate::dem::GuessSource,
    pub steps: u64,
    pub wall_time_s: f64,
    /// Joints seen opening at one end, sliding, and opening fully at the onset of collapse.
    pub hinges: Vec<Hinge>,
    pub sliding: Vec<usize>,
    pub open: Vec<usize>,
    /// The Coulomb coefficient the contacts used; `friction_infinite` says it stands for inf.
    pub friction: f64,
    pub friction_infinite: bool,
    pub time_step: f64,
    pub undecided_runs: usize,
    pub runs: Vec<DemRunReport>,
    pub scene: SceneReport,
    #[serde(flatten)]
    pub loads: LoadsReport,
    /// The most time steps one run could take (its longest length over `time_step`), and the
    /// limit it was checked against before the search started (`--max-steps`).
    pub planned_steps_per_run: u64,
    pub max_steps: u64,
    /// What looked implausible (contacts too soft for rigid blocks, a time scale the
    /// defaults do not fit, the DEM contradicting the static status), one sentence each;
    /// empty when nothing did.
    pub warnings: Vec<String>,
    /// The time stepping (`dem.integrator`): `explicit` or `moreau`.
    pub integrator: crate::dem::Integrator,
}

impl DemReport {
    /// The report of a DEM check, compared with the static bound of the shapes it simulated.
    pub fn of(scene: &Scene, d: &crate::analysis::DemAnalysis) -> Self {
        let mut rep = DemReport::new(scene, &d.model, &d.result, d.lower.lambda);
        rep.compare_with(d.lower_simulated, d.chord_polygons);
        let friction = d.lower.friction(&d.model.assembly);
        rep.friction_exact = Some(friction.exact);
        rep.friction_lower_states_possible = Some(friction.lower_states_possible);
        rep
    }

    /// Compare the bracket with `lambda_lower_simulated`, the static bound of the shapes the
    /// DEM simulated (`chord_polygons`: curved voussoirs as polygons).
    pub fn compare_with(&mut self, lambda_lower_simulated: Option<f64>, chord_polygons: bool) {
        let l = lambda_lower_simulated;
        self.lambda_lower_simulated = l;
        self.simulated_shape = if chord_polygons {
            "chord_polygons"
        } else {
            "blocks"
        };
        self.relative_difference = match (self.lambda_dem, l) {
            (Some(d), Some(l)) if l > 0.0 => Some((d - l) / l),
            _ => None,
        };
        self.static_inside_bracket = match (l, self.lambda_stands, self.lambda_collapses) {
            (Some(l), Some(a), Some(b)) => Some(a <= l && l <= b),
            _ => None,
        };
    }

    /// The report of a DEM result of `model`, compared with `lambda_lower` as the static bound
    /// of the shapes simulated (true when no block is curved; otherwise use
    /// [`DemReport::of`] or [`DemReport::compare_with`]).
    pub fn new(
        scene: &Scene,
        model: &Model,
        r: &crate::dem::DemResult,
        lambda_lower: Option<f64>,
    ) -> Self {
        let status = if r.cannot_stand {
            "cannot_stand"
        } else if r.no_collapse {
            "no_collapse"
        } else {
            "collapse"
        };
        DemReport {
            status,
            lambda_stands: r.lambda_stands,
            lambda_collapses: r.lambda_collapses,
            lambda_dem: r.lambda_dem,
            lambda_lower,
            friction_exact: None,
            friction_lower_states_possible: None,
            relative_difference: match (r.lambda_dem, lambda_lower) {
                (Some(d), Some(l)) if l > 0.0 => Some((d - l) / l),
                _ => None,
            },
            bracket_width: r.bracket_width,
            static_inside_bracket: match (lambda_lower, r.lambda_stands, r.lambda_collapses) {
                (Some(l), Some(a), Some(b)) => Some(a <= l && l <= b),
                _ => None,
            },
            lambda_dem_low: r.lambda_stands,
            lambda_dem_high: r.lambda_collapses,
            lambda_lower_simulated: lambda_lower,
            simulated_shape: "blocks",
            initial_guess: r.initial_guess,
            guess_source: r.guess_source,
            steps: r.steps,
            wall_time_s: r.wall_time_s,
            hinges: r.hinges.clone(),
            sliding: r.sliding.clone(),
            open: r.open.clone(),
            friction: r.friction,
            friction_infinite: r.friction_infinite,
            time_step: r.time_step,
            undecided_runs: r.undecided_runs,
            runs: r
                .runs
                .iter()
                .map(|run| DemRunReport {
                    lambda: run.lambda,
                    outcome: run.outcome,
                    time: run.time,
                    steps: run.steps,
                    max_displacement: run.max_displacement,
                })
                .collect(),
            scene: SceneReport::new(scene, model),
            loads: LoadsReport::new(scene, model),
            planned_steps_per_run: r.planned_steps_per_run,
            max_steps: r.params.max_steps,
            warnings: r.warnings.clone(),
            integrator: r.params.integrator,
        }
    }
}

/// The rest test of a dynamic run or an IDA (`--rest-test`, docs/dem.md), flattened into
/// their reports.
#[derive(Debug, Serialize)]
pub struct RestTestReport {
    /// `applied`, `not_applicable` (why in `rest_test_note`) or `off`.
    pub rest_test: &'static str,
    /// The static multipliers toward +x and -x the ground is compared with (null unless
    /// applied).
    pub rest_lambda_right: Option<f64>,
    pub rest_lambda_left: Option<f64>,
    pub rest_test_note: Option<String>,
}

impl RestTestReport {
    pub fn new(r: &crate::dem::rest::RestTest) -> Self {
        RestTestReport {
            rest_test: r.name(),
            rest_lambda_right: r.threshold().map(|t| t.lambda_right),
            rest_lambda_left: r.threshold().map(|t| t.lambda_left),
            rest_test_note: r.note().map(str::to_string),
        }
    }
}

/// `dem --record FILE --json` / `dem --pulse ... --json`: a dynamic run under ground motion.
#[derive(Debug, Serialize)]
pub struct DynamicReport {
    /// `collapse`, `survives` or `cannot_stand`.
    pub status: &'static str,
    /// What moved the ground, its peak acceleration (m/s^2) and duration (s).
    pub excitation: String,
    pub pga: f64,
    pub duration: f64,
    pub collapse_time: Option<f64>,
    /// The control block, its peak and residual horizontal displacement (m) and rotation
    /// (rad).
    pub control_block: usize,
    pub peak_displacement: f64,
    pub peak_rotation: f64,
    pub residual_displacement: f64,
    pub residual_rotation: f64,
    pub steps: u64,
    pub time_step: f64,
    pub wall_time_s: f64,
    pub scene: SceneReport,
    /// The direction the motion of `excitation` acts in: `x` (horizontal, toward +x for a
    /// positive acceleration) or `y` (vertical, upward).
    pub component: &'static str,
    /// A simultaneous vertical motion (`--record-vertical`) and its peak (m/s^2); null
    /// without one.
    pub vertical_excitation: Option<String>,
    pub pga_vertical: Option<f64>,
    /// How the run ended, decided by the state and not the clock: `at_rest`, `collapsed`,
    /// `moving` (still moving when it gave up: `status` is then `undecided`) or
    /// `cannot_stand`; and how long it ran past the motion and its tail to decide it (s).
    pub end_state: crate::dem::dynamic::EndState,
    pub extended: f64,
    /// The collapse criterion (`displacement` or `overturning`, `--criterion`) and the
    /// displacement of a block point (m) it calls collapse.
    pub criterion: crate::dem::dynamic::Criterion,
    pub collapse_displacement: f64,
    /// The most time steps the run could take, checked against the limit before it started.
    pub planned_steps: u64,
    /// What looked implausible, one sentence each; empty when nothing did.
    pub warnings: Vec<String>,
    /// The rest test (`--rest-test`, docs/dem.md).
    #[serde(flatten)]
    pub rest: RestTestReport,
    /// When the ground first reaches the threshold (s; null: never, or the test not applied),
    /// and when the time integration started (s since the ground started moving: 0 without
    /// the test; null when the ground never reached the threshold and nothing was integrated).
    pub first_exceedance_s: Option<f64>,
    pub integration_start_s: Option<f64>,
    /// The time stepping (`dem.integrator`): `explicit` or `moreau`.
    pub integrator: crate::dem::Integrator,
}

impl DynamicReport {
    pub fn new(scene: &Scene, d: &crate::analysis::DynamicAnalysis) -> Self {
        let r = &d.result;
        DynamicReport {
            status: r.status(),
            excitation: d.ground.main.describe(),
            pga: d.ground.main.pga(),
            duration: d.ground.duration(),
            collapse_time: r.collapse_time,
            control_block: r.control_block,
            peak_displacement: r.peak_displacement,
            peak_rotation: r.peak_rotation,
            residual_displacement: r.residual_displacement,
            residual_rotation: r.residual_rotation,
            steps: r.steps,
            time_step: r.time_step,
            wall_time_s: r.wall_time_s,
            scene: SceneReport::new(scene, &d.model),
            component: d.ground.component.name(),
            vertical_excitation: d.ground.vertical.as_ref().map(|v| v.describe()),
            pga_vertical: d.ground.vertical.as_ref().map(|v| v.pga()),
            end_state: r.end_state,
            extended: r.extended,
            criterion: r.criterion,
            collapse_displacement: r.collapse_displacement,
            planned_steps: r.planned_steps,
            warnings: r.warnings.clone(),
            rest: RestTestReport::new(&r.rest_test),
            first_exceedance_s: r.first_exceedance,
            integration_start_s: r.integration_start,
            integrator: r.integrator,
        }
    }
}

/// `dem --record FILE --ida --json`: the scale of a ground motion that brings the structure
/// down.
#[derive(Debug, Serialize)]
pub struct IdaReport {
    pub excitation: String,
    /// Peak ground acceleration of the unscaled motion (m/s^2).
    pub pga: f64,
    /// Largest scale survived, smallest scale that collapsed (null: none up to 1000), and the
    /// PGA at the latter (m/s^2).
    pub scale_survives: f64,
    pub scale_collapses: Option<f64>,
    pub collapse_pga: Option<f64>,
    /// Every run: scale and whether it collapsed.
    pub runs: Vec<(f64, bool)>,
    pub steps: u64,
    pub wall_time_s: f64,
    /// The relative bracket width asked for (`--tolerance`) and the one reached,
    /// `(scale_collapses - scale_survives) / scale_collapses` (null without a collapse).
    pub tolerance: f64,
    pub bracket_width: Option<f64>,
    /// As in the dynamic run's report: the direction of `excitation`, and a simultaneous
    /// vertical motion with its unscaled peak and its peak at the collapse scale (m/s^2).
    pub component: &'static str,
    pub vertical_excitation: Option<String>,
    pub pga_vertical: Option<f64>,
    pub collapse_pga_vertical: Option<f64>,
    /// The collapse criterion of the runs (`displacement` or `overturning`); a run still
    /// moving when it gave up counts as collapsed.
    pub criterion: crate::dem::dynamic::Criterion,
    /// The rest test of the runs, as in the dynamic run's report, and when each run's time
    /// integration started (s, in the order of `runs`; null: that scale never reached the
    /// threshold and cost no integration).
    #[serde(flatten)]
    pub rest: RestTestReport,
    pub runs_integration_start_s: Vec<Option<f64>>,
    /// The time stepping of the runs (`dem.integrator`): `explicit` or `moreau`.
    pub integrator: crate::dem::Integrator,
}

impl IdaReport {
    pub fn new(
        ground: &crate::dem::record::GroundInput,
        r: &crate::dem::dynamic::IdaResult,
        tolerance: f64,
    ) -> Self {
        let pga = ground.main.pga();
        let pga_vertical = ground.vertical.as_ref().map(|v| v.pga());
        IdaReport {
            excitation: ground.main.describe(),
            pga,
            scale_survives: r.scale_survives,
            scale_collapses: r.scale_collapses,
            collapse_pga: r.scale_collapses.map(|s| s * pga),
            runs: r.runs.clone(),
            steps: r.steps,
            wall_time_s: r.wall_time_s,
            tolerance,
            bracket_width: r.scale_collapses.map(|hi| (hi - r.scale_survives) / hi),
            component: ground.component.name(),
            vertical_excitation: ground.vertical.as_ref().map(|v| v.describe()),
            pga_vertical,
            collapse_pga_vertical: r.scale_collapses.zip(pga_vertical).map(|(s, p)| s * p),
            criterion: r.criterion,
            rest: RestTestReport::new(&r.rest_test),
            runs_integration_start_s: r.integration_starts.clone(),
            integrator: r.integrator,
        }
    }
}

/// `dem --pulse-curve FILE.svg --json`: the minimum collapse amplitude of pulses against their
/// period.
#[derive(Debug, Serialize)]
pub struct PulseCurveReport {
    /// The static collapse multiplier the amplitude searches start from (times g), and that
    /// start (m/s^2).
    pub lambda_lower: Option<f64>,
    pub start_amplitude: f64,
    /// Relative bracket width asked for.
    pub tolerance: f64,
    pub points: Vec<PulseCurvePointReport>,
    pub wall_time_s: f64,
    /// The factor between the amplitudes scanned before bisecting (the resolution: a collapse
    /// window narrower than it can be missed), the collapse criterion of the runs, and in words
    /// what the numbers are: the lowest collapse found on the scan, a first bracket and not a
    /// proven minimum.
    pub scan_ratio: f64,
    pub criterion: crate::dem::dynamic::Criterion,
    pub search: &'static str,
}

/// What a pulse curve's brackets are, for the JSON and the summary.
pub const PULSE_CURVE_SEARCH: &str = "scanned up from the start by the scan ratio until a run collapses, then bisected: the lowest collapse found on the scan, a first bracket and not a proven minimum (overturning need not be monotone in the amplitude: Zhang & Makris 2001)";

/// One point of a pulse curve.
#[derive(Debug, Serialize)]
pub struct PulseCurvePointReport {
    /// `sine` (one full cycle `A sin(2 pi t / T)`) or `rect` (`A` for `T` seconds).
    pub shape: &'static str,
    pub period: f64,
    /// Largest amplitude survived and smallest that collapsed (m/s^2; null: none up to
    /// `analysis::PULSE_CURVE_MAX_G` g), and the runs it took.
    pub amplitude_survives: f64,
    pub amplitude_collapses: Option<f64>,
    pub runs: usize,
}

impl PulseCurveReport {
    pub fn new(c: &crate::analysis::PulseCurve) -> Self {
        use crate::dem::record::PulseShape;
        PulseCurveReport {
            lambda_lower: c.lambda_lower,
            start_amplitude: c.start_amplitude,
            tolerance: c.tolerance,
            points: c
                .points
                .iter()
                .map(|p| PulseCurvePointReport {
                    shape: match p.shape {
                        PulseShape::Sine => "sine",
                        PulseShape::Rect => "rect",
                    },
                    period: p.period,
                    amplitude_survives: p.bracket.survives,
                    amplitude_collapses: p.bracket.collapses,
                    runs: p.bracket.runs.len(),
                })
                .collect(),
            wall_time_s: c.wall_time_s,
            scan_ratio: crate::dem::dynamic::PULSE_SCAN_RATIO,
            criterion: c.criterion,
            search: PULSE_CURVE_SEARCH,
        }
    }
}

/// The JSON printer: the document's data (the JSON contract of its command), pretty-printed.
pub fn print(doc: &super::Document) -> String {
    pretty(&doc.data)
}

/// Pretty JSON of any serializable value.
pub fn pretty<T: Serialize>(value: &T) -> String {
    serde_json::to_string_pretty(value).unwrap_or_else(|e| format!("{{\"error\": \"{e}\"}}"))
}
