//! The user's own blocks: polygons read from a file (JSON, CSV, DXF) or given inline, checked,
//! and joined into an [`crate::assembly::Assembly`] by finding their joints automatically ([`joints`]); some of
//! them may be fixed (a base, an abutment, rock: [`detect_with_fixed`], [`blocks_at`]).
//!
//! A scene's `[blocks]` table (read by the scene module) names the source; this module knows the
//! formats and the geometry, nothing of scenes:
//! - JSON: `{"polygons": [[[x, y], [x, y], ...], ...]}`;
//! - CSV: rows `block,x,y` (an optional header row), the vertices of a block on consecutive
//!   rows in order; the block labels are any text, blocks numbered in order of appearance;
//! - DXF: every `LWPOLYLINE` or `POLYLINE` entity (of one layer, when asked) is a block, closed
//!   by its flag or by a last vertex that repeats the first; arc segments (bulges) are refused.
//!
//! Coordinates are scaled by the scene's `units` (`"m"` or `"mm"`) to metres. Outlines are
//! mended as CAD programs and surveys write them, and the mending is counted ([`Mending`]): an
//! open DXF polyline whose last vertex repeats its first (within 1e-12 of the structure's size)
//! is closed there; repeated vertices and vertices on a straight edge are dropped (they do not
//! change the block); a clockwise outline is turned counter-clockwise. Nothing else is
//! repaired: an open polyline whose ends differ, and an outline that crosses itself (named by
//! the two edges, by their vertices as written), are errors.
//!
//! Inputs are bounded before anything is allocated for them: a file larger than
//! [`MAX_FILE_BYTES`], more than [`MAX_BLOCKS`] blocks, [`MAX_VERTICES`] vertices in all or
//! [`MAX_BLOCK_VERTICES`] in one block are refused with an error that says so.

pub mod joints;

pub use joints::{detect, detect_with_fixed, Detected, FixedBlock, Topology};

use crate::error::excerpt;
use crate::geometry::{cross, Vec2};
use std::io::Read;
use std::path::{Path, PathBuf};
use thiserror::Error;

/// Largest block file read (bytes): 64 MiB, some two million vertices of text.
pub const MAX_FILE_BYTES: u64 = 64 * 1024 * 1024;
/// Largest number of blocks.
pub const MAX_BLOCKS: usize = 100_000;
/// Largest number of vertices over all blocks.
pub const MAX_VERTICES: usize = 2_000_000;
/// Largest number of vertices of one block (the self-intersection check is quadratic in it).
pub const MAX_BLOCK_VERTICES: usize = 1_000;

/// Largest coordinate (m) of a vertex: a thousand kilometres, as for every scene length.
pub const MAX_COORDINATE: f64 = 1e6;

/// The length unit of a block source.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Units {
    Metres,
    Millimetres,
}

impl Units {
    /// Metres per unit.
    pub fn scale(self) -> f64 {
        match self {
            Units::Metres => 1.0,
            Units::Millimetres => 1e-3,
        }
    }
    pub fn name(self) -> &'static str {
        match self {
            Units::Metres => "m",
            Units::Millimetres => "mm",
        }
    }
}

/// A file format of blocks.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Format {
    Json,
    Csv,
    Dxf,
}

impl Format {
    /// The format of a file by its extension (case-insensitive).
    pub fn of_path(path: &Path) -> Option<Format> {
        let ext = path.extension()?.to_str()?.to_ascii_lowercase();
        match ext.as_str() {
            "json" => Some(Format::Json),
            "csv" => Some(Format::Csv),
            "dxf" => Some(Format::Dxf),
            _ => None,
        }
    }
}

/// Why a block source cannot be used. The messages name the block (its index in the source,
/// from 0) and coordinates in the source's units where that helps find it.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum BlockError {
    #[error("cannot read {path}: {message}")]
    Io { path: PathBuf, message: String },
    #[error("{path}: {size} bytes is more than the {MAX_FILE_BYTES} a block file may have (blocks::MAX_FILE_BYTES)")]
    TooLarge { path: PathBuf, size: u64 },
    #[error("{0}")]
    Format(String),
    #[error("{count} {what} is more than the {max} allowed")]
    TooMany {
        what: &'static str,
        count: usize,
        max: usize,
    },
    #[error("no blocks: {0}")]
    Empty(String),
    /// A problem of one block's outline.
    #[error("block {block}: {message}")]
    Block { block: usize, message: String },
    /// A problem between two blocks (they overlap).
    #[error("blocks {} and {} {message}", .blocks[0], .blocks[1])]
    Pair { blocks: [usize; 2], message: String },
    /// A problem between blocks, or of the structure as a whole.
    #[error("{0}")]
    Structure(String),
    /// A problem of the fixed block named `index`-th (`[blocks] fixed[index]`): its point lies
    /// in no block, or the block touches nothing. `block`: the block it names, if any.
    #[error("{message}")]
    Fixed {
        index: usize,
        block: Option<usize>,
        message: String,
    },
}

impl BlockError {
    /// The blocks the error is about (their indices in the source, from 0).
    pub fn blocks(&self) -> Vec<usize> {
        match self {
            BlockError::Block { block, .. } => vec![*block],
            BlockError::Pair { blocks, .. } => blocks.to_vec(),
            BlockError::Fixed { block, .. } => block.iter().copied().collect(),
            _ => Vec::new(),
        }
    }

    /// Whether the message already names the file it is about.
    pub fn names_its_file(&self) -> bool {
        matches!(
            self,
            BlockError::Io { .. }
                | BlockError::TooLarge { .. }
                | BlockError::Format(_)
                | BlockError::Empty(_)
        )
    }
}

/// Where each block is in its source, in words a user can search the file with: `lines 7-10,
/// label `b`` in a CSV file, `polygons[3]` in JSON (and inline), `handle 2A, layer `WALLS``
/// in a DXF drawing. One entry per block, in source order.
pub type Places = Vec<String>;

/// The outlines of the blocks, in metres, counter-clockwise, in source order.
#[derive(Debug, Clone, PartialEq)]
pub struct Polygons(pub Vec<Vec<Vec2>>);

impl Polygons {
    pub fn len(&self) -> usize {
        self.0.len()
    }
    pub fn is_empty(&self) -> bool {
        self.0.is_empty()
    }
    /// Bounding box `(lo, hi)` of every vertex.
    pub fn bounds(&self) -> (Vec2, Vec2) {
        let mut lo = Vec2::repeat(f64::INFINITY);
        let mut hi = Vec2::repeat(f64::NEG_INFINITY);
        for p in self.0.iter().flatten() {
            lo = lo.inf(p);
            hi = hi.sup(p);
        }
        (lo, hi)
    }
    /// The largest extent of the bounding box (m).
    pub fn size(&self) -> f64 {
        let (lo, hi) = self.bounds();
        (hi - lo).max()
    }
}

/// Read the blocks of a file, its format told by its extension; `layer` selects the DXF
/// layer (ignored by the other formats). Coordinates are multiplied by `units.scale()`.
pub fn read_file(path: &Path, units: Units, layer: Option<&str>) -> Result<Polygons, BlockError> {
    read_source(path, units, layer).map(|s| s.polygons)
}

/// [`read_file`], with where each block is in the file ([`Places`]), for messages.
pub fn read_file_with_places(
    path: &Path,
    units: Units,
    layer: Option<&str>,
) -> Result<(Polygons, Places), BlockError> {
    read_source(path, units, layer).map(|s| (s.polygons, s.places))
}

/// Blocks as read from their source: the outlines, where each lies in the source, and how
/// they were mended on the way ([`Mending`]).
#[derive(Debug, Clone, PartialEq)]
pub struct Source {
    pub polygons: Polygons,
    pub places: Places,
    pub mending: Mending,
}

/// [`read_file`], with the places of the blocks in the file and how their outlines were
/// mended.
pub fn read_source(path: &Path, units: Units, layer: Option<&str>) -> Result<Source, BlockError> {
    let format = Format::of_path(path).ok_or_else(|| {
        BlockError::Format(format!(
            "{}: unknown block file type (the extension must be .json, .csv or .dxf)",
            path.display()
        ))
    })?;
    let io = |e: std::io::Error| BlockError::Io {
        path: path.to_path_buf(),
        message: e.to_string(),
    };
    let file = std::fs::File::open(path).map_err(io)?;
    let size = file.metadata().map_err(io)?.len();
    if size > MAX_FILE_BYTES {
        return Err(BlockError::TooLarge {
            path: path.to_path_buf(),
            size,
        });
    }
    let mut bytes = Vec::with_capacity(size as usize);
    // `take` guards against a file that grows while it is read.
    file.take(MAX_FILE_BYTES + 1)
        .read_to_end(&mut bytes)
        .map_err(io)?;
    if bytes.len() as u64 > MAX_FILE_BYTES {
        return Err(BlockError::TooLarge {
            path: path.to_path_buf(),
            size: bytes.len() as u64,
        });
    }
    let name = path.display().to_string();
    // A UTF-8 byte-order mark, which some editors and spreadsheets write, is no part of the
    // data, in any format.
    let bytes = bytes.strip_prefix(b"\xef\xbb\xbf").unwrap_or(&bytes);
    let (raw, places) = match format {
        Format::Json => {
            let raw = read_json(bytes, &name)?;
            let places = (0..raw.len()).map(|i| format!("polygons[{i}]")).collect();
            (closed_outlines(raw), places)
        }
        Format::Csv => {
            let (raw, places) = read_csv(bytes, &name)?;
            (closed_outlines(raw), places)
        }
        Format::Dxf => read_dxf(bytes, &name, layer)?,
    };
    // An outline's error says where the outline lies in the file (the scene's messages add
    // that only once the blocks are read).
    let (polygons, mending) = clean(raw, units, &name).map_err(|e| match e {
        BlockError::Block { block, message } => {
            let place = places
                .get(block)
                .map_or(String::new(), |p| format!(" (block {block} is {p})"));
            BlockError::Block {
                block,
                message: format!("{message}{place}"),
            }
        }
        e => e,
    })?;
    Ok(Source {
        polygons,
        places,
        mending,
    })
}

/// Blocks given inline (`polygons = [[[x, y], ...], ...]`), in `units`.
pub fn from_vertices(raw: Vec<Vec<[f64; 2]>>, units: Units) -> Result<Polygons, BlockError> {
    from_vertices_mended(raw, units).map(|(p, _)| p)
}

/// [`from_vertices`], with how the outlines were mended.
pub fn from_vertices_mended(
    raw: Vec<Vec<[f64; 2]>>,
    units: Units,
) -> Result<(Polygons, Mending), BlockError> {
    clean(closed_outlines(raw), units, "polygons")
}

/// Outlines of a format without open polylines (JSON, CSV, inline): each closes on itself.
fn closed_outlines(raw: Vec<Vec<[f64; 2]>>) -> Vec<RawOutline> {
    raw.into_iter()
        .map(|points| RawOutline {
            points,
            open: false,
        })
        .collect()
}

fn count_limits(blocks: usize, vertices: usize) -> Result<(), BlockError> {
    if blocks > MAX_BLOCKS {
        return Err(BlockError::TooMany {
            what: "blocks",
            count: blocks,
            max: MAX_BLOCKS,
        });
    }
    if vertices > MAX_VERTICES {
        return Err(BlockError::TooMany {
            what: "vertices",
            count: vertices,
            max: MAX_VERTICES,
        });
    }
    Ok(())
}

fn read_json(bytes: &[u8], name: &str) -> Result<Vec<Vec<[f64; 2]>>, BlockError> {
    #[derive(serde::Deserialize)]
    #[serde(deny_unknown_fields)]
    struct File {
        polygons: Vec<Vec<[f64; 2]>>,
    }
    // The file's size is bounded, so is what serde allocates for it.
    let file: File = serde_json::from_slice(bytes).map_err(|e| {
        BlockError::Format(format!(
            "{name}: not a block file {{\"polygons\": [[[x, y], ...], ...]}}: {e}"
        ))
    })?;
    Ok(file.polygons)
}

/// Outlines as read (in the source's units) and where each is in its source.
type Outlines = (Vec<Vec<[f64; 2]>>, Places);

fn read_csv(bytes: &[u8], name: &str) -> Result<Outlines, BlockError> {
    let mut reader = csv::ReaderBuilder::new()
        .has_headers(false)
        .trim(csv::Trim::All)
        .flexible(true)
        .comment(Some(b'#'))
        .from_reader(bytes);
    let mut blocks: Vec<Vec<[f64; 2]>> = Vec::new();
    let mut labels: Vec<String> = Vec::new();
    // The first and last line of each block.
    let mut lines: Vec<(u64, u64)> = Vec::new();
    let mut vertices = 0usize;
    for (row, record) in reader.records().enumerate() {
        let record =
            record.map_err(|e| BlockError::Format(format!("{name}: row {}: {e}", row + 1)))?;
        // Rows are counted without comments and blank lines; lines are the file's own.
        let line = record
            .position()
            .map_or(row as u64 + 1, |p| first_data_line(bytes, p));
        let at = |row: usize| format!("row {} (line {line})", row + 1);
        if record.len() != 3 {
            return Err(BlockError::Format(format!(
                "{name}: {}: {} fields; each row is block,x,y",
                at(row),
                record.len()
            )));
        }
        let (x, y) = (record[1].parse::<f64>(), record[2].parse::<f64>());
        let (x, y) = match (x, y) {
            (Ok(x), Ok(y)) => (x, y),
            _ if row == 0 => continue, // a header row
            _ => {
                return Err(BlockError::Format(format!(
                    "{name}: {}: `{},{}` are not two numbers x,y",
                    at(row),
                    excerpt(&record[1]),
                    excerpt(&record[2])
                )))
            }
        };
        let label = &record[0];
        if labels.last().map(String::as_str) != Some(label) {
            if labels.iter().any(|l| l == label) {
                return Err(BlockError::Format(format!(
                    "{name}: {}: block `{}` appears again after other blocks; a block's vertices must be on consecutive rows",
                    at(row),
                    excerpt(label)
                )));
            }
            labels.push(label.to_string());
            blocks.push(Vec::new());
            lines.push((line, line));
        }
        vertices += 1;
        count_limits(blocks.len(), vertices)?;
        if let Some(b) = blocks.last_mut() {
            b.push([x, y]);
        }
        if let Some(l) = lines.last_mut() {
            l.1 = line;
        }
    }
    let places = labels
        .iter()
        .zip(&lines)
        .map(|(label, (first, last))| format!("lines {first}-{last}, label `{}`", excerpt(label)))
        .collect();
    Ok((blocks, places))
}

/// The line a CSV record starts on: the reader's position may be that of the comment or
/// blank lines it skipped before the record, so those are stepped over here.
fn first_data_line(bytes: &[u8], at: &csv::Position) -> u64 {
    let mut line = at.line();
    let mut rest = bytes.get(at.byte() as usize..).unwrap_or_default();
    loop {
        let end = rest.iter().position(|&b| b == b'\n');
        let text = &rest[..end.unwrap_or(rest.len())];
        let trimmed = text.trim_ascii();
        match end {
            Some(e) if trimmed.is_empty() || trimmed.starts_with(b"#") => {
                rest = &rest[e + 1..];
                line += 1;
            }
            _ => return line,
        }
    }
}

fn read_dxf(
    bytes: &[u8],
    name: &str,
    layer: Option<&str>,
) -> Result<(Vec<RawOutline>, Places), BlockError> {
    let drawing = dxf::Drawing::load(&mut std::io::Cursor::new(bytes))
        .map_err(|e| BlockError::Format(format!("{name}: not a readable DXF file: {e}")))?;
    let mut blocks = Vec::new();
    let mut places = Vec::new();
    let mut vertices = 0usize;
    let mut other_layers = std::collections::BTreeSet::new();
    for entity in drawing.entities() {
        let on_layer = layer.is_none_or(|l| entity.common.layer.eq_ignore_ascii_case(l));
        let (points, closed, bulge): (Vec<[f64; 2]>, bool, bool) = match &entity.specific {
            dxf::entities::EntityType::LwPolyline(p) => (
                p.vertices.iter().map(|v| [v.x, v.y]).collect(),
                p.is_closed(),
                p.vertices.iter().any(|v| v.bulge != 0.0),
            ),
            dxf::entities::EntityType::Polyline(p) => (
                p.vertices().map(|v| [v.location.x, v.location.y]).collect(),
                p.is_closed(),
                p.vertices().any(|v| v.bulge != 0.0),
            ),
            _ => continue,
        };
        if !on_layer {
            other_layers.insert(entity.common.layer.clone());
            continue;
        }
        let index = blocks.len();
        let at = points.first().map_or(String::new(), |p| {
            format!(" starting at ({}, {})", p[0], p[1])
        });
        // An open polyline is a block when it ends on its first vertex, as CAD often writes
        // a closed outline; `clean` checks that and counts it as mended.
        if bulge {
            return Err(BlockError::Block {
                block: index,
                message: format!(
                    "the polyline{at} (handle {:X}) has arc segments (bulges); draw blocks with straight edges",
                    entity.common.handle.0
                ),
            });
        }
        vertices += points.len();
        count_limits(index + 1, vertices)?;
        blocks.push(RawOutline {
            points,
            open: !closed,
        });
        places.push(format!(
            "handle {:X}, layer `{}`",
            entity.common.handle.0, entity.common.layer
        ));
    }
    if blocks.is_empty() {
        let hint = match (layer, other_layers.is_empty()) {
            (Some(l), false) => format!(
                " on layer `{l}` (polylines lie on layers: {})",
                other_layers.into_iter().collect::<Vec<_>>().join(", ")
            ),
            (Some(l), true) => format!(" on layer `{l}`"),
            _ => String::new(),
        };
        return Err(BlockError::Empty(format!(
            "{name} has no LWPOLYLINE or POLYLINE entity{hint}"
        )));
    }
    Ok((blocks, places))
}

/// How the outlines were mended as they were read (docs/geometry.md, "Drawings as CAD writes
/// them"): each count is a number of outlines. Nothing else is ever repaired: an outline that
/// crosses itself, or an open polyline whose ends differ, is an error.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, serde::Serialize)]
pub struct Mending {
    /// Outlines changed in any of the ways below.
    pub outlines: usize,
    /// Open DXF polylines (no closed flag) whose last vertex repeats the first: closed there.
    pub closed: usize,
    /// Outlines with a vertex repeating the one before it (or a closing copy of the first)
    /// dropped.
    pub repeated_vertices: usize,
    /// Outlines with a vertex on the straight line between its neighbours dropped.
    pub straight_vertices: usize,
    /// Outlines given clockwise, turned counter-clockwise.
    pub reversed: usize,
}

impl Mending {
    /// Whether any outline was mended.
    pub fn any(&self) -> bool {
        self.outlines > 0
    }
}

/// One outline as read: its vertices in the source's units, and whether it came as an open
/// polyline (a DXF polyline without the closed flag), which must then end where it started.
struct RawOutline {
    points: Vec<[f64; 2]>,
    open: bool,
}

/// Check the counts and numbers, scale to metres, close open outlines that end on their first
/// vertex, drop repeated and straight-angle vertices, refuse outlines that cross themselves,
/// and turn every outline counter-clockwise, counting what was mended. `name` names the
/// source in messages.
fn clean(
    raw: Vec<RawOutline>,
    units: Units,
    name: &str,
) -> Result<(Polygons, Mending), BlockError> {
    if raw.is_empty() {
        return Err(BlockError::Empty(format!("{name} holds no polygon")));
    }
    count_limits(raw.len(), raw.iter().map(|r| r.points.len()).sum())?;
    let scale = units.scale();
    let limit = MAX_COORDINATE;
    let mut scaled = Vec::with_capacity(raw.len());
    for (i, poly) in raw.iter().enumerate() {
        let fail = |message: String| BlockError::Block { block: i, message };
        if poly.points.len() > MAX_BLOCK_VERTICES {
            return Err(fail(format!(
                "{} vertices is more than the {MAX_BLOCK_VERTICES} a block may have",
                poly.points.len()
            )));
        }
        if let Some((k, p)) = poly
            .points
            .iter()
            .enumerate()
            .find(|(_, p)| !(p[0].is_finite() && p[1].is_finite()))
        {
            return Err(fail(format!(
                "vertex {k} is ({}, {}): coordinates must be finite numbers",
                p[0], p[1]
            )));
        }
        let pts: Vec<Vec2> = poly
            .points
            .iter()
            .map(|p| Vec2::new(p[0] * scale, p[1] * scale))
            .collect();
        if let Some((k, p)) = pts
            .iter()
            .enumerate()
            .find(|(_, p)| p.x.abs() > limit || p.y.abs() > limit)
        {
            return Err(fail(format!(
                "vertex {k} is ({}, {}) m: coordinates must lie within +-{limit:e} m",
                p.x, p.y
            )));
        }
        scaled.push(pts);
    }
    // Tolerance for repeated and straight vertices: relative to the whole structure.
    let size = Polygons(scaled.clone()).size();
    let tol = 1e-12 * size.max(f64::MIN_POSITIVE);
    let mut mending = Mending::default();
    let mut out = Vec::with_capacity(raw.len());
    for (i, (pts, poly)) in scaled.into_iter().zip(&raw).enumerate() {
        let fail = |message: String| BlockError::Block { block: i, message };
        // In the source's units, for messages.
        let at = |k: usize| {
            let p = poly.points[k];
            format!("({}, {})", p[0], p[1])
        };
        // Each vertex with its index in the source.
        let mut v: Vec<(Vec2, usize)> = pts.into_iter().enumerate().map(|(k, p)| (p, k)).collect();
        let mut closed = false;
        if poly.open {
            let ends = v.first().zip(v.last()).map(|(a, b)| (b.0 - a.0).norm());
            match ends {
                Some(d) if d <= tol && v.len() > 1 => {
                    v.pop();
                    closed = true;
                }
                _ => {
                    let last = poly.points.len().saturating_sub(1);
                    return Err(fail(format!(
                        "the polyline is open and its last vertex {} does not repeat its first {}; each block must be a closed polyline (the closed flag set, or the first vertex repeated at the end)",
                        at(last),
                        at(0)
                    )));
                }
            }
        }
        let before = v.len();
        v.dedup_by(|b, a| b.0 == a.0);
        while v.len() > 1 && v.first().map(|p| p.0) == v.last().map(|p| p.0) {
            v.pop();
        }
        let mut repeated = v.len() < before;
        let (v, near, straight) = drop_straight(v, tol);
        repeated |= near;
        if v.len() < 3 {
            return Err(fail(format!(
                "its outline has {} distinct vertices, not enough for a block (at least 3 not on one line)",
                v.len()
            )));
        }
        // A self-intersecting outline is refused, never repaired: which block is meant is
        // the user's to say. The edges are named by their vertices in the source.
        let m = v.len();
        for k in 0..m {
            for l in k + 2..m {
                if k == 0 && l == m - 1 {
                    continue;
                }
                let (a, b) = (v[k], v[(k + 1) % m]);
                let (c, d) = (v[l], v[(l + 1) % m]);
                if let Some(x) = joints::segments_cross(a.0, b.0, c.0, d.0) {
                    return Err(fail(format!(
                        "its outline intersects itself: the edge from vertex {} {} to vertex {} {} crosses the edge from vertex {} {} to vertex {} {} at ({:.6}, {:.6}) (vertices numbered from 0 as written)",
                        a.1,
                        at(a.1),
                        b.1,
                        at(b.1),
                        c.1,
                        at(c.1),
                        d.1,
                        at(d.1),
                        x.x / scale,
                        x.y / scale
                    )));
                }
            }
        }
        let mut p: Vec<Vec2> = v.into_iter().map(|(p, _)| p).collect();
        let reversed = signed_area2(&p) < 0.0;
        if reversed {
            p.reverse();
        }
        mending.closed += usize::from(closed);
        mending.repeated_vertices += usize::from(repeated);
        mending.straight_vertices += usize::from(straight);
        mending.reversed += usize::from(reversed);
        mending.outlines += usize::from(closed || repeated || straight || reversed);
        out.push(p);
    }
    Ok((Polygons(out), mending))
}

/// Drop vertices within `tol` of the one before (near-repeats) and vertices within `tol` of
/// the line through their neighbours; says whether each kind was dropped.
fn drop_straight(mut pts: Vec<(Vec2, usize)>, tol: f64) -> (Vec<(Vec2, usize)>, bool, bool) {
    let (mut near, mut straight) = (false, false);
    loop {
        let m = pts.len();
        if m < 3 {
            return (pts, near, straight);
        }
        let drop = (0..m).find_map(|k| {
            let (a, b, c) = (pts[(k + m - 1) % m].0, pts[k].0, pts[(k + 1) % m].0);
            let ac = c - a;
            let len = ac.norm();
            if (b - a).norm() <= tol {
                Some((k, true))
            } else {
                (len > tol
                    && cross(ac, b - a).abs() <= tol * len
                    && (b - a).dot(&ac) > 0.0
                    && (c - b).dot(&ac) > 0.0)
                    .then_some((k, false))
            }
        });
        match drop {
            Some((k, repeat)) => {
                pts.remove(k);
                if repeat {
                    near = true;
                } else {
                    straight = true;
                }
            }
            None => return (pts, near, straight),
        }
    }
}

/// The block each of `points` (m) lies in, by its source index: the points of `[blocks]
/// fixed`. A point lies in a block when it is inside its outline (any simple outline: the
/// crossing-number test) or within `tol` (m) of it. A point in no block, or on the outlines
/// of two, is an error [`BlockError::Fixed`] naming it by its position and saying which block
/// lies nearest (at a distance in `units`).
pub fn blocks_at(
    polygons: &Polygons,
    points: &[Vec2],
    tol: f64,
    units: Units,
) -> Result<Vec<usize>, BlockError> {
    points
        .iter()
        .enumerate()
        .map(|(k, &p)| {
            let distance: Vec<f64> = polygons.0.iter().map(|q| joints::distance_to_polygon(p, q)).collect();
            let holding: Vec<usize> = (0..polygons.len())
                .filter(|&i| distance[i] <= tol || inside_outline(&polygons.0[i], p))
                .collect();
            match holding.as_slice() {
                [one] => Ok(*one),
                [] => {
                    let (near, d) = distance
                        .iter()
                        .copied()
                        .enumerate()
                        .min_by(|a, b| a.1.total_cmp(&b.1))
                        .unwrap_or((0, f64::NAN));
                    Err(BlockError::Fixed {
                        index: k,
                        block: Some(near),
                        message: format!(
                            "the point lies outside every block: the nearest is block {near}, {} {} away; a fixed point lies inside the block that does not move",
                            crate::geometry::trim(d / units.scale()),
                            units.name()
                        ),
                    })
                }
                [a, b, ..] => Err(BlockError::Fixed {
                    index: k,
                    block: None,
                    message: format!(
                        "the point lies on the outlines of blocks {a} and {b}; give a point inside the one block that does not move"
                    ),
                }),
            }
        })
        .collect()
}

/// Distance from `p` to the outline `poly` (m).
pub fn distance_to_outline(p: Vec2, poly: &[Vec2]) -> f64 {
    joints::distance_to_polygon(p, poly)
}

/// Whether `p` lies inside the simple polygon `poly` (crossing number: a ray toward +x crosses
/// the outline an odd number of times).
pub fn inside_outline(poly: &[Vec2], p: Vec2) -> bool {
    let m = poly.len();
    let mut odd = false;
    for k in 0..m {
        let (a, b) = (poly[k], poly[(k + 1) % m]);
        if (a.y > p.y) != (b.y > p.y) {
            let x = a.x + (p.y - a.y) / (b.y - a.y) * (b.x - a.x);
            if x > p.x {
                odd = !odd;
            }
        }
    }
    odd
}

/// Twice the signed area (positive counter-clockwise).
pub fn signed_area2(pts: &[Vec2]) -> f64 {
    let m = pts.len();
    (0..m).map(|k| cross(pts[k], pts[(k + 1) % m])).sum()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn outlines_are_cleaned_and_turned_counter_clockwise() {
        let raw = vec![vec![
            [0.0, 0.0],
            [0.0, 1.0],
            [0.0, 1.0],
            [1.0, 1.0],
            [1.0, 0.5],
            [1.0, 0.0],
            [0.0, 0.0],
        ]];
        let p = from_vertices(raw, Units::Metres).unwrap();
        assert_eq!(p.0[0].len(), 4);
        assert!(signed_area2(&p.0[0]) > 0.0);
        let mm = from_vertices(
            vec![vec![[0.0, 0.0], [1000.0, 0.0], [0.0, 500.0]]],
            Units::Millimetres,
        )
        .unwrap();
        assert_eq!(mm.0[0][1], Vec2::new(1.0, 0.0));
    }

    #[test]
    fn csv_groups_consecutive_rows_and_skips_a_header() {
        let text = b"block,x,y\na,0,0\na,1,0\na,1,1\nb,0,1\nb,1,1\nb,1,2\n";
        let (raw, places) = read_csv(text, "t.csv").unwrap();
        assert_eq!(raw.len(), 2);
        assert_eq!(raw[1][2], [1.0, 2.0]);
        assert_eq!(places, ["lines 2-4, label `a`", "lines 5-7, label `b`"]);
        let again = read_csv(b"a,0,0\nb,1,0\na,1,1\n", "t.csv").unwrap_err();
        assert!(again.to_string().contains("appears again"), "{again}");
    }
}
