//! Scenes of the user's own blocks: the `[blocks]` table (a file or inline polygons, the
//! ground line, the units, the DXF layer, the points of the fixed blocks), its checks, and the
//! structure it reads — the assembly found by [`crate::blocks::detect_with_fixed`], on which
//! `scene::build` places the loads ([`super::placement`]). An error about a fixed block is
//! the key `blocks.fixed[k]` with its point as written.

use super::{Material, Section};
use crate::blocks::{self, BlockError, Detected, Polygons, Units};
use crate::error::SceneError;
use crate::geometry::Vec2;
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
    "fixed",
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
    /// `ground_y` as given (None: the lowest vertex, or no ground with fixed blocks).
    pub ground_y: Option<f64>,
    /// `fixed` as given: points in the source's units inside the blocks that do not move.
    pub fixed: Vec<[f64; 2]>,
    /// How the outlines were mended as they were read.
    pub mending: blocks::Mending,
    pub layer: Option<String>,
    /// Joint tolerance relative to the structure's size.
    pub tolerance: f64,
    /// The outlines, in metres, fixed blocks included.
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
    s.used.insert("fixed");
    let fixed_points = fixed_points(&s)?;
    let (source, polygons, places, mending) = match (file, inline) {
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
            let read = blocks::read_source(&path, units, layer.as_deref())
                .map_err(|e| blocks_error(&s, "file", Some(&path), &[], &e))?;
            (
                BlockSource::File { written, path },
                read.polygons,
                read.places,
                read.mending,
            )
        }
        (false, true) => {
            s.used.insert("file");
            let raw = inline_polygons(&s)?;
            let places: Vec<String> = (0..raw.len()).map(|i| format!("polygons[{i}]")).collect();
            let (polys, mending) = blocks::from_vertices_mended(raw, units)
                .map_err(|e| blocks_error(&s, "polygons", None, &places, &e))?;
            (BlockSource::Inline, polys, places, mending)
        }
    };
    s.finish("")?;
    let (key, path) = match &source {
        BlockSource::File { path, .. } => ("file", Some(path.as_path())),
        BlockSource::Inline => ("polygons", None),
    };
    // A fixed block's error names its point (`blocks.fixed[k]`, as written) and the block.
    let fixed_error = |e: &BlockError| match e {
        BlockError::Fixed { index, .. } => {
            let p = fixed_points.get(*index).copied().unwrap_or_default();
            let located = blocks_error(&s, key, path, &places, e);
            let message = match located {
                SceneError::BadBlocks { message, .. } => message,
                other => other.to_string(),
            };
            SceneError::OutOfRange {
                origin: s.origin.to_string(),
                key: s.key(&format!("fixed[{index}]")),
                value: format!("[{}, {}]", super::short(p[0]), super::short(p[1])),
                allowed: message,
            }
        }
        _ => blocks_error(&s, key, path, &places, e),
    };
    let scale = units.scale();
    let at: Vec<Vec2> = fixed_points
        .iter()
        .map(|p| Vec2::new(p[0] * scale, p[1] * scale))
        .collect();
    let fixed = blocks::blocks_at(&polygons, &at, tolerance * polygons.size(), units)
        .map_err(|e| fixed_error(&e))?;
    let detected = blocks::detect_with_fixed(
        &polygons,
        &fixed,
        ground_y,
        tolerance,
        material.unit_weight * material.depth,
        material.friction,
    )
    .map_err(|e| fixed_error(&e))?;
    Ok(BlocksSpec {
        source,
        units,
        ground_y,
        fixed: fixed_points,
        mending,
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

/// `fixed = [[x, y], ...]`: points in the source's units (empty when absent).
fn fixed_points(s: &Section) -> Result<Vec<[f64; 2]>, SceneError> {
    let expected = "a list of points [[x, y], ...] in the blocks' units, each inside a block that does not move";
    let list = match s.table.get("fixed") {
        None => return Ok(Vec::new()),
        Some(Value::Array(list)) => list,
        Some(v) => return Err(s.wrong_type("fixed", v, expected)),
    };
    if list.len() > blocks::MAX_BLOCKS {
        return Err(s.out_of_range(
            "fixed",
            format!("{} points", list.len()),
            &format!("at most {} (blocks::MAX_BLOCKS)", blocks::MAX_BLOCKS),
        ));
    }
    list.iter()
        .enumerate()
        .map(|(k, q)| match point(q) {
            Some([x, y]) if x.is_finite() && y.is_finite() => Ok([x, y]),
            _ => Err(s.wrong_type(
                &format!("fixed[{k}]"),
                q,
                "a point [x, y] of two finite numbers",
            )),
        })
        .collect()
}

/// `[x, y]`: a TOML array of two numbers.
fn point(v: &Value) -> Option<[f64; 2]> {
    let num = |x: &Value| match x {
        Value::Float(f) => Some(*f),
        Value::Integer(i) => Some(*i as f64),
        _ => None,
    };
    match v {
        Value::Array(xy) if xy.len() == 2 => Some([num(&xy[0])?, num(&xy[1])?]),
        _ => None,
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
    list.iter()
        .enumerate()
        .map(|(i, p)| {
            let Value::Array(pts) = p else {
                return Err(wrong(p));
            };
            pts.iter()
                .map(|q| {
                    point(q).ok_or_else(|| {
                        s.wrong_type(
                            &format!("polygons[{i}]"),
                            q,
                            "a vertex [x, y] of two numbers",
                        )
                    })
                })
                .collect()
        })
        .collect()
}
