//! Scenes of the user's own blocks: the `[blocks]` table (a file or inline polygons, the
//! ground line, the units, the DXF layer), its checks, and the model it builds — the
//! assembly found by [`crate::blocks::detect`] and the loads of `[[loads]]` and `[seismic]`
//! placed on its blocks.
//!
//! Load placement on user blocks:
//! - a point load acts on the first block (in source order) whose outline contains `at`;
//! - a line load of intensity `q` over `[from_x, to_x]` rests on the top of the structure: the
//!   range is cut at the ends of the upward-facing edges, and each piece's load `q * length`
//!   acts on the highest upward-facing edge above it, at that edge's point over the piece's
//!   mid x (an edge hidden under another block carries nothing, as the top edge above it is
//!   higher);
//! - a fill up to `level` rests on the same top: over each piece between consecutive ends of
//!   the upward-facing edges, the region between the highest edge and `level` (where the edge
//!   lies below it) weighs `unit_weight * depth * area` at its centroid, carried by that
//!   edge's block. Over an arch written as blocks the pieces are its extrados chords, so the
//!   fill is the parametric arch's (`scene::build`); unlike there, a pier top or any other
//!   block top under the level is filled too.

use super::{FillSpec, LoadSpec, Material, Section};
use crate::assembly::{Assembly, BlockKind};
use crate::blocks::{self, BlockError, Detected, Polygons, Units};
use crate::error::SceneError;
use crate::geometry::{cross, Vec2};
use crate::model::{AppliedLoad, LoadCase, LoadSource, Model, SpreadLoad};
use std::path::{Path, PathBuf};
use toml::Value;

/// The keys of `[blocks]`.
pub(super) const BLOCKS_KEYS: &[&str] = &[
    "file",
    "polygons",
    "ground_y",
    "layer",
    "units",
    "tolerance",
];

/// Default tolerance of the joint detection, relative to the structure's size.
pub const DEFAULT_TOLERANCE: f64 = 1e-6;

/// Where the blocks came from.
#[derive(Debug, Clone, PartialEq)]
pub enum BlockSource {
    /// A file: as written in the scene, and as resolved (relative to the scene file).
    File { written: String, path: PathBuf },
    /// `polygons = [...]` in the scene.
    Inline,
}

/// A validated `[blocks]` table and the structure found from it.
#[derive(Debug, Clone)]
pub struct BlocksSpec {
    pub source: BlockSource,
    pub units: Units,
    /// `ground_y` as given (None: the lowest vertex).
    pub ground_y: Option<f64>,
    pub layer: Option<String>,
    /// Joint tolerance relative to the structure's size.
    pub tolerance: f64,
    /// The outlines, in metres.
    pub polygons: Polygons,
    /// Blocks and joints found (weights from `[material]`).
    pub detected: Detected,
}

impl BlocksSpec {
    /// The source in words: the file as written, or `inline polygons`.
    pub fn source_words(&self) -> String {
        match &self.source {
            BlockSource::File { written, .. } => written.clone(),
            BlockSource::Inline => "inline polygons".to_string(),
        }
    }
}

/// Read `[blocks]` (the section `s`) given the scene's material; `base` is the directory of
/// the scene file (relative paths are taken from it).
pub(super) fn parse_blocks(
    mut s: Section,
    material: &Material,
    base: Option<&Path>,
) -> Result<BlocksSpec, SceneError> {
    s.check_known(BLOCKS_KEYS, "")?;
    let units = match s.string("units", Some("m"))?.as_str() {
        "m" => Units::Metres,
        "mm" => Units::Millimetres,
        other => {
            return Err(s.out_of_range(
                "units",
                format!("\"{other}\""),
                "must be \"m\" (metres) or \"mm\" (millimetres)",
            ))
        }
    };
    let ground_y = match s.opt_f64("ground_y")? {
        Some(g) if !(g.is_finite() && g.abs() <= super::MAX_LENGTH) => {
            return Err(s.out_of_range(
                "ground_y",
                g,
                &format!("must be a finite y within +-{:e} m", super::MAX_LENGTH),
            ))
        }
        g => g.map(|g| g * units.scale()),
    };
    let layer = match s.table.get("layer") {
        Some(_) => Some(s.string("layer", None)?),
        None => {
            s.used.insert("layer");
            None
        }
    };
    let tolerance = s.opt_f64("tolerance")?.unwrap_or(DEFAULT_TOLERANCE);
    if !(tolerance.is_finite() && (1e-12..=1e-2).contains(&tolerance)) {
        return Err(s.out_of_range(
            "tolerance",
            tolerance,
            "must be from 1e-12 to 1e-2 (a fraction of the structure's size)",
        ));
    }
    let file = s.table.get("file").is_some();
    let inline = s.table.get("polygons").is_some();
    s.used.insert("polygons");
    let (source, polygons, places) = match (file, inline) {
        (true, true) => {
            return Err(s.out_of_range(
                "polygons",
                "[...]",
                "give either `file` or `polygons`, not both",
            ))
        }
        (false, false) => {
            return Err(s.missing(
                "file",
                "a block file (.json, .csv or .dxf, relative to the scene) or inline `polygons`",
            ))
        }
        (true, false) => {
            let written = s.string("file", None)?;
            let path = match base {
                Some(b) if Path::new(&written).is_relative() => b.join(&written),
                _ => PathBuf::from(&written),
            };
            if layer.is_some() && blocks::Format::of_path(&path) != Some(blocks::Format::Dxf) {
                return Err(s.out_of_range(
                    "layer",
                    format!("\"{}\"", layer.as_deref().unwrap_or_default()),
                    "only a .dxf block file has layers",
                ));
            }
            let (polys, places) = blocks::read_file_with_places(&path, units, layer.as_deref())
                .map_err(|e| blocks_error(&s, "file", Some(&path), &[], &e))?;
            (BlockSource::File { written, path }, polys, places)
        }
        (false, true) => {
            s.used.insert("file");
            let raw = inline_polygons(&s)?;
            let places: Vec<String> = (0..raw.len()).map(|i| format!("polygons[{i}]")).collect();
            let polys = blocks::from_vertices(raw, units)
                .map_err(|e| blocks_error(&s, "polygons", None, &places, &e))?;
            (BlockSource::Inline, polys, places)
        }
    };
    s.finish("")?;
    let (key, path) = match &source {
        BlockSource::File { path, .. } => ("file", Some(path.as_path())),
        BlockSource::Inline => ("polygons", None),
    };
    let detected = blocks::detect(
        &polygons,
        ground_y,
        tolerance,
        material.unit_weight * material.depth,
        material.friction,
    )
    .map_err(|e| blocks_error(&s, key, path, &places, &e))?;
    Ok(BlocksSpec {
        source,
        units,
        ground_y,
        layer,
        tolerance,
        polygons,
        detected,
    })
}

/// A block source's error as the scene's: it names the blocks file (unless the message does
/// already) and where in its source each block it is about lies ([`blocks::Places`]), e.g.
/// `walls.csv: block 3: it is not convex ... (block 3 is lines 14-17, label `b3`)`.
fn blocks_error(
    s: &Section,
    key: &str,
    path: Option<&Path>,
    places: &[String],
    e: &BlockError,
) -> SceneError {
    let file = match path {
        Some(p) if !e.names_its_file() => format!("{}: ", p.display()),
        _ => String::new(),
    };
    let located: Vec<String> = e
        .blocks()
        .into_iter()
        .filter_map(|b| places.get(b).map(|place| format!("block {b} is {place}")))
        .collect();
    let place = if located.is_empty() {
        String::new()
    } else {
        format!(" ({})", located.join("; "))
    };
    SceneError::BadBlocks {
        origin: s.origin.to_string(),
        key: s.key(key),
        message: format!("{file}{e}{place}"),
    }
}

/// `polygons = [[[x, y], ...], ...]`, counted before it is copied.
fn inline_polygons(s: &Section) -> Result<Vec<Vec<[f64; 2]>>, SceneError> {
    let v = s.table.get("polygons");
    let expected = "a list of polygons [[[x, y], ...], ...]";
    let wrong = |v: &Value| s.wrong_type("polygons", v, expected);
    let Some(Value::Array(list)) = v else {
        return Err(wrong(v.unwrap_or(&Value::Boolean(false))));
    };
    let total: usize = list
        .iter()
        .map(|p| match p {
            Value::Array(a) => a.len(),
            _ => 0,
        })
        .sum();
    if list.len() > blocks::MAX_BLOCKS || total > blocks::MAX_VERTICES {
        return Err(s.out_of_range(
            "polygons",
            format!("{} polygons, {total} vertices", list.len()),
            &format!(
                "at most {} blocks and {} vertices",
                blocks::MAX_BLOCKS,
                blocks::MAX_VERTICES
            ),
        ));
    }
    let num = |x: &Value| match x {
        Value::Float(f) => Some(*f),
        Value::Integer(i) => Some(*i as f64),
        _ => None,
    };
    list.iter()
        .enumerate()
        .map(|(i, p)| {
            let Value::Array(pts) = p else {
                return Err(wrong(p));
            };
            pts.iter()
                .map(|q| match q {
                    Value::Array(xy) if xy.len() == 2 => match (num(&xy[0]), num(&xy[1])) {
                        (Some(x), Some(y)) => Ok([x, y]),
                        _ => Err(s.wrong_type(
                            &format!("polygons[{i}]"),
                            q,
                            "a vertex [x, y] of two numbers",
                        )),
                    },
                    _ => Err(s.wrong_type(
                        &format!("polygons[{i}]"),
                        q,
                        "a vertex [x, y] of two numbers",
                    )),
                })
                .collect()
        })
        .collect()
}

/// The model of a block scene: the assembly found, and the loads placed on it.
#[allow(clippy::too_many_arguments)]
pub(super) fn build_model(
    spec: &BlocksSpec,
    loads: &[LoadSpec],
    fill: Option<&FillSpec>,
    depth: f64,
    vertical_ratio: f64,
    strength: crate::model::Strength,
    origin: &str,
) -> Result<Model, SceneError> {
    let assembly = spec.detected.assembly.clone();
    let mut case = LoadCase::self_weight(&assembly).with_vertical_ratio(vertical_ratio);
    let tol = spec.detected.tolerance;
    for (k, load) in loads.iter().enumerate() {
        match *load {
            LoadSpec::Point {
                at,
                force,
                seismic,
                live,
            } => {
                let p = Vec2::new(at[0], at[1]);
                let block =
                    first_containing(&assembly, p, tol).ok_or_else(|| SceneError::OutOfRange {
                        origin: origin.to_string(),
                        key: format!("loads[{k}].at"),
                        value: format!("[{}, {}]", at[0], at[1]),
                        allowed: "the point lies outside every block".into(),
                    })?;
                let force = Vec2::new(force[0], force[1]);
                case.add(AppliedLoad::point(k, block, p, force, seismic).live(live));
            }
            LoadSpec::Line {
                from_x,
                to_x,
                intensity,
                seismic,
                live,
            } => {
                case.add_spread(SpreadLoad::line(k, from_x, to_x, intensity, seismic).live(live));
                let pieces = roof_pieces(&assembly, from_x, to_x, tol);
                if pieces.is_empty() {
                    return Err(SceneError::OutOfRange {
                        origin: origin.to_string(),
                        key: format!("loads[{k}].from_x"),
                        value: format!("{from_x} (to_x = {to_x})"),
                        allowed: "the loaded length must lie over the top of some block".into(),
                    });
                }
                for (block, point, length) in pieces {
                    let w = intensity * length;
                    case.add(AppliedLoad {
                        block,
                        point,
                        force: Vec2::new(0.0, -w),
                        seismic_weight: if seismic { w } else { 0.0 },
                        live,
                        source: LoadSource::Load(k),
                        region: None,
                    });
                }
            }
        }
    }
    if let Some(fill) = fill {
        let gamma = fill.unit_weight * depth;
        case.add_spread(SpreadLoad::fill(fill.level, gamma, fill.seismic));
        let regions = fill_regions(&assembly, fill.level, tol);
        if regions.is_empty() {
            return Err(SceneError::OutOfRange {
                origin: origin.to_string(),
                key: "fill.level".to_string(),
                value: fill.level.to_string(),
                allowed: "the fill's top must lie above the top of some block".into(),
            });
        }
        for (block, area, centroid, region) in regions {
            case.add(AppliedLoad::fill(
                block,
                gamma * area,
                centroid,
                region,
                fill.seismic,
            ));
        }
    }
    Ok(Model {
        assembly,
        loads: case,
        strength,
        ties: Vec::new(),
        strips: Vec::new(),
    })
}

/// Upward-facing edges of counter-clockwise outlines, which run toward -x:
/// `(block, left end, right end)`.
fn roof_edges(assembly: &Assembly, tol: f64) -> Vec<(usize, Vec2, Vec2)> {
    let mut edges = Vec::new();
    for (i, b) in assembly.blocks.iter().enumerate() {
        let m = b.polygon.len();
        for k in 0..m {
            let (a, c) = (b.polygon[k], b.polygon[(k + 1) % m]);
            if a.x - c.x > tol {
                edges.push((i, c, a));
            }
        }
    }
    edges
}

/// The highest roof edge over `x`, and its point there.
fn top_at(edges: &[(usize, Vec2, Vec2)], x: f64) -> Option<(usize, Vec2, Vec2)> {
    edges
        .iter()
        .filter(|(_, l, r)| l.x <= x && x <= r.x)
        .map(|&(i, l, r)| (i, l, r))
        .max_by(|a, b| {
            let y = |(_, l, r): &(usize, Vec2, Vec2)| l.y + (x - l.x) / (r.x - l.x) * (r.y - l.y);
            y(a).total_cmp(&y(b))
        })
}

/// The fill regions over the roof of an assembly up to `level`: `(block, area, centroid,
/// outline)` for each piece between consecutive ends of the upward-facing edges where the
/// highest edge lies below the level (see the module docs).
fn fill_regions(assembly: &Assembly, level: f64, tol: f64) -> Vec<(usize, f64, Vec2, Vec<Vec2>)> {
    let edges = roof_edges(assembly, tol);
    let mut cuts: Vec<f64> = edges.iter().flat_map(|(_, l, r)| [l.x, r.x]).collect();
    cuts.sort_by(f64::total_cmp);
    cuts.dedup();
    let mut regions = Vec::new();
    for w in cuts.windows(2) {
        let (x0, x1) = (w[0], w[1]);
        if x1 - x0 <= 0.0 {
            continue;
        }
        let Some((i, l, r)) = top_at(&edges, 0.5 * (x0 + x1)) else {
            continue;
        };
        let on = |x: f64| l + (x - l.x) / (r.x - l.x) * (r - l);
        let (mut a, mut b) = (on(x0), on(x1));
        // Keep the part of the edge below the level.
        if a.y >= level && b.y >= level {
            continue;
        }
        if a.y > level || b.y > level {
            let x = a.x + (level - a.y) / (b.y - a.y) * (b.x - a.x);
            if a.y > level {
                a = on(x);
            } else {
                b = on(x);
            }
        }
        if let Some((area, centroid, outline)) = super::build::fill_region(a, b, level, None) {
            regions.push((i, area, centroid, outline));
        }
    }
    regions
}

/// The first block in source order whose (convex, counter-clockwise) outline holds `p`.
pub(super) fn first_containing(assembly: &Assembly, p: Vec2, tol: f64) -> Option<usize> {
    let source = |i: usize| match assembly.blocks[i].kind {
        BlockKind::User(s) => s,
        _ => i,
    };
    (0..assembly.blocks.len())
        .filter(|&i| {
            let poly = &assembly.blocks[i].polygon;
            let m = poly.len();
            (0..m).all(|k| {
                let e = poly[(k + 1) % m] - poly[k];
                cross(e, p - poly[k]) / e.norm() >= -tol
            })
        })
        .min_by_key(|&i| source(i))
}

/// The pieces of `[from_x, to_x]` under a line load: `(block, point, length)` for each piece
/// between consecutive ends of upward-facing edges, on the highest such edge above it.
fn roof_pieces(assembly: &Assembly, from_x: f64, to_x: f64, tol: f64) -> Vec<(usize, Vec2, f64)> {
    let edges = roof_edges(assembly, tol);
    let mut cuts: Vec<f64> = vec![from_x, to_x];
    for (_, l, r) in &edges {
        for x in [l.x, r.x] {
            if x > from_x && x < to_x {
                cuts.push(x);
            }
        }
    }
    cuts.sort_by(f64::total_cmp);
    cuts.dedup();
    let mut pieces = Vec::new();
    for w in cuts.windows(2) {
        let (x0, x1) = (w[0], w[1]);
        if x1 - x0 <= 0.0 {
            continue;
        }
        let x = 0.5 * (x0 + x1);
        let top = top_at(&edges, x).map(|(i, l, r)| (i, l + (x - l.x) / (r.x - l.x) * (r - l)));
        if let Some((i, p)) = top {
            pieces.push((i, p, x1 - x0));
        }
    }
    pieces
}
