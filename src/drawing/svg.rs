//! SVG drawings of assemblies, thrust lines and collapse mechanisms (plotters, SVG backend).
//!
//! `draw_structure` draws an [`Assembly`] to scale with equal axes, and on top of it what a
//! [`Drawing`] asks for:
//! - the thrust line (line of pressure): the points `p_mid + (M/N) u` where the resultant
//!   crosses each joint (`drawing::thrust_points`), joined in joint order;
//! - hinges as circles at the joint end where the resultant (or the rotation centre) sits,
//!   numbered 1, 2, ... in the order given (chain order, the order of the text summary);
//!   a number with no free place beside its circle (clear of the loads, the other circles
//!   and the other numbers) is left out, and the legend counts those (an arcade or a wall
//!   with a hundred hinges);
//! - sliding joints as thick orange segments;
//! - supports: ground hatching on the ground side of every joint to the ground;
//! - fixed blocks (`[blocks] fixed`: a base, an abutment) shaded grey and hatched, behind the
//!   blocks, their support joints hatched like the ground's;
//! - the collapse mechanism as dashed outlines of the displaced blocks: a point `p` of block
//!   `i` moves by `A (v_i + omega_i x (p - c_i))` (first-order rigid-body displacement,
//!   `omega x r = (-omega r_y, omega r_x)`; first order keeps the blocks on either side of a
//!   hinge joined at the hinge). The default factor `A` makes the largest displacement of any
//!   block corner 10 % of the structure's size; the legend says `A` ("scaled x0.19" or
//!   "amplified x3") and that size.
//!   Blocks that move together as one rigid body are outlined as one piece (their shared
//!   joints are left out), so a 1000-voussoir arch shows its four pieces, not 1000 dashes;
//! - a second set of block positions (for DEM: final positions) as translucent blue blocks,
//!   each block `i` moved by a translation `t_i` and a rotation `theta_i` about its centroid;
//! - the loads of a [`LoadCase`]: the fill as a shaded, hatched region behind the blocks (the
//!   `region` outlines of its `Fill` loads), point loads as arrows ending at their point of
//!   application (the largest 15 % of the structure's size long, the others in proportion,
//!   labelled in kN), line loads as a row of small arrows on the loaded extrados labelled
//!   `q = ... kN/m` (a load of `[[loads]]` applied as more than one piece is a line load); a
//!   distributed load that is not uniform (an axle spread through the fill by Boussinesq's
//!   law) has arrows as long as its local intensity, its outline over them, and its total in
//!   kN over its peak;
//! - the seismic load direction on the structure: an arrow `lambda g` in the direction of the
//!   ground motion (with its vertical component `r lambda g` when the vertical ratio r is not
//!   0), in free space near the top left of the structure;
//! - a scale bar of a round length under the structure.
//!
//! Plotters writes the elements (the SVG backend needs no fonts: without the `ttf` feature
//! its text layout is a width estimate and text is written as SVG `<text>` elements, which
//! the viewer renders with its own fonts). Each kind of element is drawn in its own pass and
//! wrapped in a `<g id="...">` group (`blocks`, `thrust-line`, `hinges`, ...), so the file is
//! easy to inspect and to test; the backend works in whole pixels, which at 1000 px wide is
//! well below what the eye resolves.

use std::io::Write;
use std::path::Path;

use plotters::coord::Shift;
use plotters::element::{Circle, DashedPathElement, PathElement, Polygon, Rectangle, Text};
use plotters::prelude::{DrawingArea, IntoDrawingArea, SVGBackend};
use plotters::style::{Color, FontStyle, IntoFont, RGBColor, ShapeStyle, TextStyle, WHITE};

use crate::assembly::{Assembly, Hinge, JointEnd, JointForce};
use crate::geometry::Vec2;
use crate::model::{AppliedLoad, LoadCase, LoadSource};
use crate::outcome::Direction;

/// Errors of the drawings.
#[derive(Debug, thiserror::Error)]
pub enum SvgError {
    /// Writing the file failed.
    #[error("cannot write {path}: {source}")]
    Io {
        path: String,
        #[source]
        source: std::io::Error,
    },
    /// The data do not fit the assembly (lengths, indices, non-finite values).
    #[error("cannot draw: {0}")]
    Invalid(String),
    /// Plotters reported an error.
    #[error("drawing failed: {0}")]
    Plot(String),
}

/// Colours of the drawing, public so tests and documents can refer to them.
pub mod colours {
    use plotters::style::RGBColor;
    /// Block fill.
    pub const BLOCK: RGBColor = RGBColor(0xE9, 0xDF, 0xC8);
    /// Block outline.
    pub const BLOCK_EDGE: RGBColor = RGBColor(0x7A, 0x6A, 0x50);
    /// Thrust line (line of pressure).
    pub const THRUST: RGBColor = RGBColor(0xD6, 0x27, 0x28);
    /// Hinge markers.
    pub const HINGE: RGBColor = RGBColor(0x1A, 0x1A, 0x1A);
    /// Sliding joints.
    pub const SLIDING: RGBColor = RGBColor(0xFF, 0x8C, 0x00);
    /// Displaced (mechanism) outlines.
    pub const MECHANISM: RGBColor = RGBColor(0x1F, 0x5F, 0xBF);
    /// Second set of block positions (DEM final positions).
    pub const MOVED: RGBColor = RGBColor(0x3A, 0x7C, 0xC8);
    /// Ground and its hatching.
    pub const GROUND: RGBColor = RGBColor(0x40, 0x40, 0x40);
    /// Fixed blocks (hatched with `GROUND`).
    pub const FIXED: RGBColor = RGBColor(0xD4, 0xD4, 0xD4);
    /// Text.
    pub const TEXT: RGBColor = RGBColor(0x10, 0x10, 0x10);
    /// Fill region.
    pub const FILL: RGBColor = RGBColor(0xE4, 0xE4, 0xE0);
    /// Hatching and outline of the fill region.
    pub const FILL_EDGE: RGBColor = RGBColor(0x9A, 0x9A, 0x92);
    /// Point and line loads.
    pub const LOAD: RGBColor = RGBColor(0x2E, 0x7D, 0x32);
    /// Seismic load direction.
    pub const SEISMIC: RGBColor = RGBColor(0x8E, 0x24, 0xAA);
    /// Tie rods.
    pub const TIE: RGBColor = RGBColor(0x37, 0x47, 0x4F);
    /// Bonded strips.
    pub const STRIP: RGBColor = RGBColor(0x00, 0x89, 0x7B);
    /// The fill's passive resistance: the faces against the fill and their reactions.
    pub const PASSIVE: RGBColor = RGBColor(0x8D, 0x5A, 0x2B);
}

use colours::*;

/// A collapse mechanism: virtual velocities of the blocks.
#[derive(Debug, Clone, Copy)]
pub struct Mechanism<'a> {
    /// `[vx, vy, omega]` per block: centroid velocity and rotation rate (counter-clockwise
    /// positive), as `StaticResult::mechanism`.
    pub velocities: &'a [[f64; 3]],
    /// Displacement = amplification * velocity. `None`: the largest corner displacement is
    /// 10 % of the structure's size.
    pub amplification: Option<f64>,
}

/// A second set of block positions, e.g. the final state of a DEM run.
#[derive(Debug, Clone)]
pub struct Placements<'a> {
    /// Per block: translation of the centroid (m) and rotation about the centroid (rad,
    /// counter-clockwise), relative to the assembly's positions.
    pub moves: &'a [(Vec2, f64)],
    /// Legend text, e.g. "final positions (t = 2.0 s)".
    pub label: String,
}

/// What to draw on top of the blocks. Start from `Drawing::new(title)` and set what you have.
#[derive(Debug, Clone, Default)]
pub struct Drawing<'a> {
    /// Title; `\n` starts a new (smaller) line.
    pub title: String,
    /// Joint forces, one per joint (e.g. `StaticResult::forces`): draws the thrust line.
    pub forces: Option<&'a [JointForce]>,
    /// Hinges, drawn as circles at their `(x, y)`.
    pub hinges: &'a [Hinge],
    /// Indices of sliding joints.
    pub sliding: &'a [usize],
    /// Collapse mechanism, drawn as dashed displaced outlines.
    pub mechanism: Option<Mechanism<'a>>,
    /// A second set of block positions (DEM final positions).
    pub moved: Option<Placements<'a>>,
    /// Direction of the horizontal seismic load: drawn as an arrow `lambda g` on the
    /// structure (with the vertical component of `loads`, when given) and in the legend.
    pub load: Option<Direction>,
    /// The load case (e.g. `Model::loads`): draws the fill, the point and line loads, and
    /// the vertical seismic component. `None`: self-weight only, no load marks.
    pub loads: Option<&'a LoadCase>,
    /// Leave out the ground hatching under supports.
    pub hide_supports: bool,
    /// The outlines of the fixed blocks (any shape), drawn grey and hatched behind the blocks.
    pub fixed: &'a [Vec<Vec2>],
    /// Tie rods (`Model::ties`), drawn between their anchors.
    pub ties: &'a [crate::model::Tie],
    /// Their forces at collapse (`StaticResult::ties`), labelled beside them when given.
    pub tie_forces: &'a [crate::model::TieForce],
    /// Bonded strips (`Model::strips`), drawn along their face.
    pub strips: &'a [crate::model::Strip],
    /// Their forces at collapse (`StaticResult::strips`): debonded joints are marked.
    pub strip_forces: &'a [crate::model::StripForce],
    /// The fill's passive faces (`Model::passive`), drawn along the face.
    pub passive: &'a [crate::model::Passive],
    /// Their reactions at collapse (`StaticResult::passive`): an arrow out of the fill, its
    /// length in proportion to the reaction (solid at the cap, light below it).
    pub passive_forces: &'a [crate::model::PassiveForce],
}

impl<'a> Drawing<'a> {
    pub fn new(title: impl Into<String>) -> Self {
        Drawing {
            title: title.into(),
            ..Default::default()
        }
    }
}

/// Default share of the structure's size taken by the largest mechanism displacement.
pub const MECHANISM_SHARE: f64 = 0.10;

/// Draw `assembly` and `drawing` into the SVG file `path`.
pub fn draw_structure<P: AsRef<Path>>(
    path: P,
    assembly: &Assembly,
    drawing: &Drawing,
) -> Result<(), SvgError> {
    let text = structure_svg(assembly, drawing)?;
    write_file(path.as_ref(), &text)
}

/// Draw `assembly` and `drawing` as SVG into `writer`.
pub fn write_structure<W: Write>(
    mut writer: W,
    assembly: &Assembly,
    drawing: &Drawing,
) -> Result<(), SvgError> {
    let text = structure_svg(assembly, drawing)?;
    writer
        .write_all(text.as_bytes())
        .map_err(|source| SvgError::Io {
            path: "<writer>".into(),
            source,
        })
}

/// The SVG document of `assembly` and `drawing`.
pub fn structure_svg(assembly: &Assembly, drawing: &Drawing) -> Result<String, SvgError> {
    check(assembly, drawing)?;
    let size = assembly.size();
    let mech = drawing
        .mechanism
        .as_ref()
        .and_then(|m| displaced(assembly, m, size));
    let moved: Option<Vec<Vec<Vec2>>> = drawing.moved.as_ref().map(|pl| {
        assembly
            .blocks
            .iter()
            .zip(pl.moves)
            .map(|(b, (t, th))| {
                let (s, c) = th.sin_cos();
                b.polygon
                    .iter()
                    .map(|p| {
                        let r = p - b.centroid;
                        b.centroid + t + Vec2::new(c * r.x - s * r.y, s * r.x + c * r.y)
                    })
                    .collect()
            })
            .collect()
    });
    let marks = drawing.loads.map(|l| LoadMarks::new(l, size));

    // World bounding box of everything drawn in world coordinates.
    let mut lo = Vec2::repeat(f64::INFINITY);
    let mut hi = Vec2::repeat(f64::NEG_INFINITY);
    let mut grow = |p: &Vec2| {
        lo = lo.inf(p);
        hi = hi.sup(p);
    };
    assembly
        .blocks
        .iter()
        .flat_map(|b| b.polygon.iter())
        .for_each(&mut grow);
    drawing.fixed.iter().flatten().for_each(&mut grow);
    if let Some(m) = &mech {
        m.edges.iter().flat_map(|(a, b)| [a, b]).for_each(&mut grow);
    }
    if let Some(mv) = &moved {
        mv.iter().flatten().for_each(&mut grow);
    }
    if let Some(mk) = &marks {
        mk.world_points().iter().for_each(&mut grow);
    }
    for t in drawing.ties {
        grow(&t.from.point);
        grow(&t.to.point);
    }
    let ext = hi - lo;
    if !(ext.x.is_finite() && ext.y.is_finite() && ext.max() > 0.0) {
        return Err(SvgError::Invalid(
            "the blocks have no extent (empty or non-finite outlines)".into(),
        ));
    }

    // Layout (pixels): title, the structure to scale in a box, the scale bar and the legend
    // below.
    let width: u32 = 1000;
    let margin = 24.0;
    let pad = 22.0; // room for hatching, hinge circles and their numbers around the structure
    let room = width as f64 - 2.0 * margin;
    // Each title line: font size (shrunk to fit the width), line height, bold.
    let title_lines: Vec<(&str, f64, f64, bool)> = drawing
        .title
        .lines()
        .enumerate()
        .map(|(i, line)| {
            let (px, h, bold) = if i == 0 {
                (20.0, 28.0, true)
            } else {
                (15.0, 22.0, false)
            };
            (line, fit_px(line, px, bold, room, 8.0), h, bold)
        })
        .collect();
    let title_h = title_lines.iter().map(|l| l.2).sum::<f64>();
    let top = margin + title_h + 6.0;
    let max_w = room - 2.0 * pad;
    let max_h = 620.0;
    // A flat structure still gets some height (and a thin one some width).
    let fit = |lo: Vec2, hi: Vec2| {
        let e = (hi - lo).sup(&Vec2::repeat(0.02 * (hi - lo).max()));
        ((max_w / e.x).min(max_h / e.y), e)
    };
    // Load labels take a fixed room in pixels beyond their anchors: fit twice.
    let (mut scale, mut ext) = fit(lo, hi);
    let (mut llo, mut lhi) = (lo, hi);
    if let Some(mk) = &marks {
        for _ in 0..2 {
            (llo, lhi) = (lo, hi);
            for l in mk.labels(scale) {
                llo = llo.inf(&(l.centre - l.half));
                lhi = lhi.sup(&(l.centre + l.half));
            }
            (scale, ext) = fit(llo, lhi);
        }
    }
    let mid = 0.5 * (llo + lhi);
    let plot_w = ext.x * scale;
    let plot_h = ext.y * scale;
    let frame = Frame {
        scale,
        cx: width as f64 / 2.0,
        cy: top + pad + plot_h / 2.0,
        mid,
    };
    let bar = ScaleBar::new(ext.x.max(0.5 * ext.y), scale);
    let bar_y = top + plot_h + 2.0 * pad + 12.0;
    let bar_right = (frame.cx + 0.5 * plot_w).min(width as f64 - margin);

    // The loads' marks and the hinges' numbers are placed before the legend, which counts
    // the numbers left out.
    let marks_svg = marks.as_ref().map(|mk| marks_svg(mk, scale, &frame));
    let load_boxes: &[Rect] = marks_svg.as_ref().map_or(&[], |m| &m.boxes);
    let (numbers, unnumbered) = hinge_numbers(assembly, drawing.hinges, &frame, load_boxes);

    let mut legend = Vec::new();
    let blocks_label = if drawing.moved.is_some() {
        "initial positions (to scale)"
    } else {
        "blocks (to scale)"
    };
    legend.push((Glyph::Block, blocks_label.to_string()));
    if let Some(level) = marks.as_ref().and_then(|m| m.level()) {
        legend.push((Glyph::Fill, format!("fill up to y = {} m", sig(level))));
    }
    let thrust = drawing.forces.map(|f| super::thrust_points(assembly, f));
    // A thrust line runs along a chain; in any other assembly (a wall of several courses) the
    // resultants of the joints are drawn as points, not joined.
    let joined = assembly.is_chain() || {
        let nb = assembly.blocks.len();
        assembly.joints.len() == nb
            && assembly
                .joints
                .iter()
                .enumerate()
                .all(|(k, j)| j.from == k.checked_sub(1) && j.to == Some(k))
    };
    if thrust.is_some() {
        if joined {
            legend.push((Glyph::Line(THRUST, 3, false), "thrust line".into()));
        } else {
            legend.push((
                Glyph::Line(THRUST, 3, false),
                "resultant on each joint (no chain: no thrust line)".into(),
            ));
        }
    }
    if !drawing.hinges.is_empty() {
        legend.push((
            Glyph::Hinge,
            hinge_words(drawing.hinges.len(), joined, unnumbered),
        ));
        if drawing.hinges.iter().any(|h| h.compressed_zone > 0.0) {
            legend.push((
                Glyph::Line(HINGE, 5, false),
                "compressed zone at a hinge (crushing: the hinge at its centre)".into(),
            ));
        }
    }
    if !drawing.sliding.is_empty() {
        legend.push((Glyph::Line(SLIDING, 6, false), "sliding joint".into()));
    }
    if !drawing.strips.is_empty() {
        let words = if drawing.strip_forces.iter().any(|f| f.yielded) {
            "bonded strip (dot: at its capacity, debonding)"
        } else {
            "bonded strip"
        };
        legend.push((Glyph::Line(STRIP, 4, false), words.into()));
    }
    if !drawing.passive.is_empty() {
        let words = if crate::interaction::passive::governs(drawing.passive_forces) {
            "face against the fill; arrow: its passive reaction at collapse (solid: at its cap, governing)"
        } else if drawing.passive_forces.iter().any(|f| f.force > 0.0) {
            "face against the fill; arrow: its passive reaction at collapse"
        } else {
            "face against the fill (passive resistance)"
        };
        legend.push((Glyph::Line(PASSIVE, 4, false), words.into()));
    }
    if !drawing.ties.is_empty() {
        let words = if drawing.tie_forces.is_empty() {
            "tie rod (its capacity)"
        } else {
            "tie rod, its force at collapse (yielded: at its capacity)"
        };
        legend.push((Glyph::Line(TIE, 3, false), words.into()));
    }
    let has_supports = !drawing.hide_supports && assembly.joints.iter().any(|j| j.is_support());
    if has_supports {
        legend.push((Glyph::Ground, "support".into()));
    }
    if !drawing.fixed.is_empty() {
        legend.push((Glyph::Fixed, "fixed block (does not move)".into()));
    }
    if let Some(m) = &mech {
        legend.push((
            Glyph::Mechanism,
            format!(
                "collapse mechanism, displacements {} (largest {} m = {:.0}% of size {} m)",
                factor_words(m.amplification),
                sig(m.largest),
                100.0 * m.largest / size,
                sig(size)
            ),
        ));
    }
    if let Some(pl) = &drawing.moved {
        legend.push((Glyph::Moved, pl.label.clone()));
    }
    if let Some(mk) = &marks {
        if mk.live {
            legend.push((
                Glyph::Arrow(LOAD, false),
                "live load, \u{3bb} \u{d7} as given (\u{3bb}: the adequacy factor)".into(),
            ));
        }
        if mk.points.iter().any(|p| !p.live) {
            legend.push((Glyph::Arrow(LOAD, false), "point load".into()));
        }
        if !mk.lines.is_empty() {
            legend.push((Glyph::Arrow(LOAD, false), "line load".into()));
        }
    }
    let vertical_ratio = drawing.loads.map_or(0.0, |l| l.vertical_ratio());
    if let Some(d) = drawing.load {
        legend.push((
            Glyph::Arrow(SEISMIC, d == Direction::Left),
            seismic_words(d, drawing.loads),
        ));
    }
    let legend_top = bar_y + 18.0;
    let legend_rows = flow_legend(&legend, room);
    let rows = legend_rows.iter().map(|r| r.row).max().map_or(0, |r| r + 1);
    let height = (legend_top + rows as f64 * LEGEND_ROW + margin).ceil() as u32;

    let mut svg = Layers::new(width, height);
    svg.layer("background", |root| {
        root.fill(&WHITE).map_err(plot_err)?;
        Ok(())
    })?;
    if let Some(mk) = marks.as_ref().filter(|m| !m.fill.is_empty()) {
        svg.raw("fill", &fill_svg(&mk.fill, &frame, size));
    }
    if !drawing.fixed.is_empty() {
        svg.raw("fixed-blocks", &fixed_svg(drawing.fixed, &frame));
    }
    if has_supports {
        svg.layer("supports", |root| {
            for j in assembly.joints.iter().filter(|j| j.is_support()) {
                let g = if j.from.is_none() {
                    -j.normal()
                } else {
                    j.normal()
                };
                let u = j.tangent();
                let l = j.length() * scale;
                let over = 6.0 / scale; // the ground line runs a little past the joint
                let a = j.p1 - over * u;
                let b = j.p2 + over * u;
                root.draw(&PathElement::new(
                    vec![frame.px(a), frame.px(b)],
                    GROUND.stroke_width(2),
                ))
                .map_err(plot_err)?;
                let k = ((l + 12.0) / 8.0).floor().max(2.0) as usize;
                let h = 10.0 / scale;
                for i in 0..=k {
                    let q = a + (b - a) * (i as f64 / k as f64);
                    let e = q + h * std::f64::consts::FRAC_1_SQRT_2 * (g - u);
                    root.draw(&PathElement::new(
                        vec![frame.px(q), frame.px(e)],
                        GROUND.stroke_width(1),
                    ))
                    .map_err(plot_err)?;
                }
            }
            Ok(())
        })?;
    }
    svg.layer("blocks", |root| {
        // The edges of thin voussoirs (a few pixels apart) would merge into a dark band:
        // fade them with the typical shortest edge, in pixels.
        let mut shortest: Vec<f64> = assembly
            .blocks
            .iter()
            .map(|b| {
                let n = b.polygon.len();
                (0..n)
                    .map(|k| (b.polygon[(k + 1) % n] - b.polygon[k]).norm())
                    .fold(f64::INFINITY, f64::min)
                    * scale
            })
            .collect();
        shortest.sort_by(f64::total_cmp);
        let typical = shortest.get(shortest.len() / 2).copied().unwrap_or(0.0);
        let edge = BLOCK_EDGE
            .mix((typical / 12.0).clamp(0.2, 1.0))
            .stroke_width(1);
        for b in &assembly.blocks {
            let pts: Vec<_> = b.polygon.iter().map(|p| frame.px(*p)).collect();
            root.draw(&Polygon::new(pts.clone(), BLOCK.filled()))
                .map_err(plot_err)?;
            root.draw(&PathElement::new(closed(pts), edge))
                .map_err(plot_err)?;
        }
        Ok(())
    })?;
    if let Some(mv) = &moved {
        svg.layer("moved-blocks", |root| {
            for poly in mv {
                let pts: Vec<_> = poly.iter().map(|p| frame.px(*p)).collect();
                root.draw(&Polygon::new(pts.clone(), MOVED.mix(0.35).filled()))
                    .map_err(plot_err)?;
                root.draw(&PathElement::new(closed(pts), MOVED.stroke_width(1)))
                    .map_err(plot_err)?;
            }
            Ok(())
        })?;
    }
    if !drawing.sliding.is_empty() {
        svg.layer("sliding", |root| {
            for &k in drawing.sliding {
                let j = &assembly.joints[k];
                root.draw(&PathElement::new(
                    vec![frame.px(j.p1), frame.px(j.p2)],
                    SLIDING.stroke_width(6),
                ))
                .map_err(plot_err)?;
            }
            Ok(())
        })?;
    }
    if let Some(m) = &mech {
        // Written by hand, not by plotters: plotters 0.3 has no dash style (its
        // DashedPathElement writes every dash as its own whole-pixel polyline and restarts
        // the pattern at every element), so a chain of 3 px voussoir edges came out solid.
        let segs: Vec<_> = m
            .edges
            .iter()
            .map(|(a, b)| (frame.pxf(*a), frame.pxf(*b)))
            .collect();
        // A faint fill of the displaced blocks, one path so shared edges leave no seams.
        let mut d = String::new();
        for poly in &m.blocks {
            for (k, p) in poly.iter().enumerate() {
                let (x, y) = frame.pxf(*p);
                d.push_str(&format!("{}{x:.1},{y:.1} ", if k == 0 { "M" } else { "L" }));
            }
            d.push_str("Z ");
        }
        let mut text = format!(
            "<path fill=\"{}\" fill-opacity=\"0.10\" stroke=\"none\" d=\"{}\"/>\n",
            hex(MECHANISM),
            d.trim_end()
        );
        for line in chain(&segs) {
            text.push_str(&format!(
                "<polyline fill=\"none\" stroke=\"{}\" stroke-width=\"2\" \
                 stroke-dasharray=\"{DASH}\" stroke-linejoin=\"round\" points=\"{}\"/>\n",
                hex(MECHANISM),
                points_attr(line)
            ));
        }
        svg.raw("mechanism", &text);
    }
    if let Some(points) = &thrust {
        svg.layer("thrust-line", |root| {
            for run in runs(
                points
                    .iter()
                    .map(|p| p.filter(|q| q.x.is_finite() && q.y.is_finite())),
            ) {
                let pts: Vec<_> = run.iter().map(|p| frame.px(*p)).collect();
                if !joined {
                    for p in pts {
                        root.draw(&Circle::new(p, 3, THRUST.filled()))
                            .map_err(plot_err)?;
                    }
                } else if pts.len() == 1 {
                    root.draw(&Circle::new(pts[0], 3, THRUST.filled()))
                        .map_err(plot_err)?;
                } else {
                    root.draw(&PathElement::new(pts, THRUST.stroke_width(3)))
                        .map_err(plot_err)?;
                }
            }
            Ok(())
        })?;
    }

    if !drawing.ties.is_empty() {
        svg.raw("ties", &ties_svg(drawing, &frame));
    }
    if !drawing.strips.is_empty() {
        svg.raw("strips", &strips_svg(assembly, drawing, &frame));
    }
    if !drawing.passive.is_empty() {
        svg.raw("passive", &passive_svg(drawing, &frame));
    }

    // Everything drawn so far that the seismic arrow should not cover, in pixels.
    let mut obstacles: Vec<Vec<Px>> = Vec::new();
    let px_poly = |poly: &[Vec2]| poly.iter().map(|p| frame.pxf(*p)).collect::<Vec<_>>();
    obstacles.extend(assembly.blocks.iter().map(|b| px_poly(&b.polygon)));
    if let Some(m) = &mech {
        obstacles.extend(m.blocks.iter().map(|b| px_poly(b)));
    }
    if let Some(mv) = &moved {
        obstacles.extend(mv.iter().map(|b| px_poly(b)));
    }
    if has_supports {
        for j in assembly.joints.iter().filter(|j| j.is_support()) {
            obstacles.push(
                Rect::around(&[frame.pxf(j.p1), frame.pxf(j.p2)])
                    .grown(14.0)
                    .corners(),
            );
        }
    }

    if let Some(marks) = &marks_svg {
        if !marks.lines.is_empty() {
            svg.raw("line-loads", &marks.lines);
        }
        if !marks.points.is_empty() {
            svg.raw("point-loads", &marks.points);
        }
    }
    obstacles.extend(load_boxes.iter().map(Rect::corners));
    if !drawing.hinges.is_empty() {
        svg.layer("hinges", |root| {
            for h in drawing.hinges {
                if h.compressed_zone > 0.0 {
                    // With crushing: the compressed zone, a thick bar from the joint's end over
                    // the width a, the hinge circle at its centre.
                    let jt = &assembly.joints[h.joint];
                    let (end, inward) = match h.end {
                        JointEnd::P1 => (jt.p1, jt.tangent()),
                        JointEnd::P2 => (jt.p2, -jt.tangent()),
                    };
                    let zone = vec![
                        frame.px(end),
                        frame.px(end + h.compressed_zone.min(jt.length()) * inward),
                    ];
                    root.draw(&PathElement::new(zone, HINGE.stroke_width(5)))
                        .map_err(plot_err)?;
                }
                let c = frame.px(Vec2::new(h.x, h.y));
                root.draw(&Circle::new(c, 6, HINGE.stroke_width(3)))
                    .map_err(plot_err)?;
            }
            Ok(())
        })?;
        let mut text = String::new();
        for &(i, (x, y)) in &numbers {
            text.push_str(&format!(
                "<text class=\"hinge-number\" x=\"{x:.1}\" y=\"{y:.1}\" dy=\"0.35em\" \
                 text-anchor=\"middle\" font-family=\"sans-serif\" font-size=\"{HINGE_FONT}\" \
                 font-weight=\"bold\" fill=\"{}\" stroke=\"white\" stroke-width=\"3\" \
                 stroke-linejoin=\"round\" paint-order=\"stroke\">{}</text>\n",
                hex(HINGE),
                i + 1
            ));
        }
        for h in drawing.hinges {
            obstacles.push(
                Rect::around(&[frame.pxf(Vec2::new(h.x, h.y))])
                    .grown(9.0)
                    .corners(),
            );
        }
        for &(_, at) in &numbers {
            obstacles.push(Rect::around(&[at]).grown(0.5 * HINGE_FONT + 2.0).corners());
        }
        svg.raw("hinge-numbers", &text);
    }
    if let Some(d) = drawing.load {
        let glyph = SeismicGlyph::new(d, vertical_ratio);
        // Within the structure's box (the fill is no obstacle: the labels have a halo).
        let region = Rect {
            x0: frame.cx - 0.5 * plot_w,
            y0: top + pad,
            x1: frame.cx + 0.5 * plot_w,
            y1: top + pad + plot_h,
        }
        .grown(-6.0);
        let origin = free_spot(&glyph.bounds, &region, &obstacles);
        svg.raw("seismic", &glyph.svg(origin));
    }
    svg.raw("scale-bar", &bar.svg(bar_right, bar_y));
    svg.layer("title", |root| {
        let mut y = margin;
        for &(line, px, h, bold) in &title_lines {
            let mut font = ("sans-serif", font_size(px)).into_font();
            if bold {
                font = font.style(FontStyle::Bold);
            }
            let style = TextStyle::from(font).color(&TEXT);
            root.draw(&Text::new(
                line.to_string(),
                (margin as i32, y as i32),
                style,
            ))
            .map_err(plot_err)?;
            y += h;
        }
        Ok(())
    })?;
    svg.layer("legend", |root| {
        draw_legend(root, &legend, &legend_rows, margin, legend_top)
    })?;
    Ok(svg.finish(&drawing.title))
}

/// The mechanism's displacement factor in words: "scaled x0.19" below 1, "amplified x3" above.
fn factor_words(a: f64) -> String {
    if (a - 1.0).abs() < 0.005 {
        "to scale (x1)".to_string()
    } else if a > 1.0 {
        format!("amplified x{}", sig(a))
    } else {
        format!("scaled x{}", sig(a))
    }
}

/// The loads' marks as SVG (the line loads' and the point loads' groups) and the boxes, in
/// pixels, that their arrows and labels cover: hinge numbers and the seismic glyph keep
/// clear of them.
struct MarksSvg {
    lines: String,
    points: String,
    boxes: Vec<Rect>,
}

fn marks_svg(mk: &LoadMarks, scale: f64, frame: &Frame) -> MarksSvg {
    let mut load_boxes: Vec<Rect> = Vec::new();
    let labels = mk.labels(scale);
    let mut text = String::new();
    for (line, label) in mk.lines.iter().zip(&labels[mk.points.len()..]) {
        text.push_str(&format!(
            "<g class=\"line-load\">\n<polyline fill=\"none\" stroke=\"{}\" stroke-width=\"1.5\" \
             stroke-linejoin=\"round\" points=\"{}\"/>\n",
            hex(LOAD),
            points_attr(line.tails.iter().map(|p| frame.pxf(*p)))
        ));
        for (tail, tip) in &line.arrows {
            text.push_str(&arrow_svg(
                frame.pxf(*tail),
                frame.pxf(*tip),
                LOAD,
                1.5,
                7.0,
            ));
        }
        let (x, y) = frame.pxf(label.centre);
        text.push_str(&text_svg(x, y, LOAD_FONT, "middle", LOAD, &label.text));
        text.push_str("</g>\n");
        for (tail, tip) in &line.arrows {
            load_boxes.push(Rect::around(&[frame.pxf(*tip), frame.pxf(*tail)]).grown(4.0));
        }
        load_boxes.push(label.rect(frame));
    }
    let lines = text;
    let mut text = String::new();
    for (p, label) in mk.points.iter().zip(&labels) {
        let (tail, tip) = (frame.pxf(p.tail), frame.pxf(p.tip));
        text.push_str("<g class=\"point-load\">\n");
        text.push_str(&arrow_svg(tail, tip, LOAD, 2.5, 12.0));
        let (x, y) = frame.pxf(label.centre);
        text.push_str(&text_svg(x, y, LOAD_FONT, "middle", LOAD, &label.text));
        text.push_str("</g>\n");
        load_boxes.push(Rect::around(&[tail, tip]).grown(7.0));
        load_boxes.push(label.rect(frame));
    }
    MarksSvg {
        lines,
        points: text,
        boxes: load_boxes,
    }
}

/// Where the hinges' numbers go: beside each circle, away from the joint's middle (outside
/// the extrados, inside the intrados) unless a box of `keep_clear`, another hinge's circle or
/// another number is there, in the order given (the text summary's). Returns each placed
/// number's hinge (index into `hinges`) and centre, and how many found no free place: those
/// are left out, since on a wall or an arcade with a hundred hinges numbers on top of each
/// other read as nothing.
fn hinge_numbers(
    assembly: &Assembly,
    hinges: &[Hinge],
    frame: &Frame,
    keep_clear: &[Rect],
) -> (Vec<(usize, Px)>, usize) {
    let half = 0.5 * HINGE_FONT + 1.0;
    let circles: Vec<Rect> = hinges
        .iter()
        .map(|h| Rect::around(&[frame.pxf(Vec2::new(h.x, h.y))]).grown(HINGE_RADIUS))
        .collect();
    let mut taken: Vec<Rect> = keep_clear.to_vec();
    let mut placed = Vec::new();
    let mut left_out = 0;
    for (i, h) in hinges.iter().enumerate() {
        let at = frame.pxf(Vec2::new(h.x, h.y));
        let m = frame.pxf(assembly.joints[h.joint].midpoint());
        let (dx, dy) = (at.0 - m.0, at.1 - m.1);
        let n = dx.hypot(dy);
        let (ux, uy) = if n > 1e-9 {
            (dx / n, dy / n)
        } else {
            (0.0, -1.0)
        };
        let place = |deg: f64| {
            let (s, c) = deg.to_radians().sin_cos();
            (
                at.0 + 17.0 * (c * ux - s * uy),
                at.1 + 17.0 * (s * ux + c * uy),
            )
        };
        let free = [0.0, 45.0, -45.0, 90.0, -90.0, 135.0, -135.0, 180.0]
            .into_iter()
            .map(place)
            .find(|&p| {
                let r = Rect::around(&[p]).grown(half);
                !taken.iter().any(|o| r.meets(o))
                    && !circles
                        .iter()
                        .enumerate()
                        .any(|(k, c)| k != i && r.meets(c))
            });
        match free {
            Some(p) => {
                taken.push(Rect::around(&[p]).grown(half));
                placed.push((i, p));
            }
            None => left_out += 1,
        }
    }
    (placed, left_out)
}

/// The legend's words for `count` hinges: numbered along the chain (`joined`) or in the
/// order the summary and the JSON list them, and how many numbers found no room.
fn hinge_words(count: usize, joined: bool, unnumbered: usize) -> String {
    let order = if joined {
        "numbered along the chain"
    } else {
        "numbered as the summary and the JSON list them"
    };
    match unnumbered {
        0 => format!("hinge ({count}), {order}"),
        1 if count == 1 => "hinge (1; no room for its number)".to_string(),
        k if k == count => format!("hinge ({count}; no room for their numbers)"),
        k => format!("hinge ({count}), {order} ({k} without room for a number)"),
    }
}

/// The legend text of the seismic load.
fn seismic_words(d: Direction, loads: Option<&LoadCase>) -> String {
    let r = loads.map_or(0.0, |l| l.vertical_ratio());
    let masses = loads.is_some_and(|l| {
        l.applied()
            .iter()
            .any(|a| a.source != LoadSource::SelfWeight && a.seismic_weight > 0.0)
    });
    let at = if masses {
        "each seismic mass (blocks and seismic loads)"
    } else {
        "each centroid"
    };
    if r == 0.0 {
        format!("horizontal load \u{3bb}W at {at}")
    } else {
        let s = match d {
            Direction::Right => "1",
            Direction::Left => "-1",
        };
        format!("seismic load \u{3bb}W ({s}, r) at {at}, r = {}", sig(r))
    }
}

/// Font size (px) that fits `text` into `room` pixels, from `px` down to `min`.
pub(crate) fn fit_px(text: &str, px: f64, bold: bool, room: f64, min: f64) -> f64 {
    let w = wide_text_width(text, px, bold);
    if w <= room {
        px
    } else {
        (px * room / w).max(min)
    }
}

/// A generous text width estimate (wider than most sans-serif fonts), for text that must
/// not leave the canvas.
pub(crate) fn wide_text_width(text: &str, px: f64, bold: bool) -> f64 {
    (if bold { 0.66 } else { 0.6 }) * px * text.chars().count() as f64
}

/// Validate the drawing against the assembly, so nothing below indexes out of range.
fn check(assembly: &Assembly, d: &Drawing) -> Result<(), SvgError> {
    if assembly.blocks.is_empty() {
        return Err(SvgError::Invalid("the assembly has no blocks".into()));
    }
    if let Some(f) = d.forces {
        if f.len() != assembly.joints.len() {
            return Err(SvgError::Invalid(format!(
                "{} joint forces for {} joints",
                f.len(),
                assembly.joints.len()
            )));
        }
    }
    if let Some(&k) = d.sliding.iter().find(|&&k| k >= assembly.joints.len()) {
        return Err(SvgError::Invalid(format!(
            "sliding joint {k}, but there are {} joints",
            assembly.joints.len()
        )));
    }
    if let Some(h) = d
        .hinges
        .iter()
        .find(|h| !(h.x.is_finite() && h.y.is_finite()))
    {
        return Err(SvgError::Invalid(format!(
            "hinge at joint {} has a non-finite position",
            h.joint
        )));
    }
    if let Some(m) = &d.mechanism {
        if m.velocities.len() != assembly.blocks.len() {
            return Err(SvgError::Invalid(format!(
                "{} mechanism velocities for {} blocks",
                m.velocities.len(),
                assembly.blocks.len()
            )));
        }
        if m.velocities.iter().flatten().any(|v| !v.is_finite()) {
            return Err(SvgError::Invalid(
                "the mechanism has non-finite velocities".into(),
            ));
        }
        if let Some(a) = m.amplification {
            if !(a.is_finite() && a > 0.0) {
                return Err(SvgError::Invalid(format!(
                    "mechanism amplification {a} must be positive"
                )));
            }
        }
    }
    if let Some(l) = d.loads {
        let nb = assembly.blocks.len();
        if l.len() != nb {
            return Err(SvgError::Invalid(format!(
                "the load case has {} blocks, the assembly {nb}",
                l.len()
            )));
        }
        let finite = |p: &Vec2| p.x.is_finite() && p.y.is_finite();
        for a in l.applied() {
            if a.block >= nb {
                return Err(SvgError::Invalid(format!(
                    "a load on block {}, but there are {nb} blocks",
                    a.block
                )));
            }
            if !(finite(&a.point) && finite(&a.force) && a.region.iter().flatten().all(finite)) {
                return Err(SvgError::Invalid(format!(
                    "a load on block {} has non-finite values",
                    a.block
                )));
            }
        }
    }
    if let Some(p) = &d.moved {
        if p.moves.len() != assembly.blocks.len() {
            return Err(SvgError::Invalid(format!(
                "{} block positions for {} blocks",
                p.moves.len(),
                assembly.blocks.len()
            )));
        }
        if p.moves
            .iter()
            .any(|(t, th)| !(t.x.is_finite() && t.y.is_finite() && th.is_finite()))
        {
            return Err(SvgError::Invalid(
                "the block positions have non-finite values".into(),
            ));
        }
    }
    Ok(())
}

/// Displaced outlines of a mechanism.
struct Displaced {
    /// Displaced block edges that are not shared with a block of the same rigid piece.
    edges: Vec<(Vec2, Vec2)>,
    /// Displaced outlines of the blocks that move.
    blocks: Vec<Vec<Vec2>>,
    amplification: f64,
    /// Largest displacement of a block corner (m).
    largest: f64,
}

/// First-order velocity of point `p` of a block with centroid `c` and velocity `v`.
fn velocity(v: &[f64; 3], c: Vec2, p: Vec2) -> Vec2 {
    let r = p - c;
    Vec2::new(v[0] - v[2] * r.y, v[1] + v[2] * r.x)
}

/// The displaced outlines, None when nothing moves.
fn displaced(assembly: &Assembly, m: &Mechanism, size: f64) -> Option<Displaced> {
    let speed = assembly
        .blocks
        .iter()
        .zip(m.velocities)
        .flat_map(|(b, v)| b.polygon.iter().map(|p| velocity(v, b.centroid, *p).norm()))
        .fold(0.0, f64::max);
    // Velocities are finite (checked), so the fold is a number >= 0.
    if speed <= 0.0 {
        return None;
    }
    let amplification = m.amplification.unwrap_or(MECHANISM_SHARE * size / speed);

    // Blocks joined by a joint across which nothing moves relative to each other belong to
    // one rigid piece; their common edges are not outlined.
    let nb = assembly.blocks.len();
    let tol = 1e-4 * speed;
    let mut neighbours = vec![Vec::new(); nb];
    for j in &assembly.joints {
        if let (Some(a), Some(b)) = (j.from, j.to) {
            let (ba, bb) = (&assembly.blocks[a], &assembly.blocks[b]);
            let rel = [j.p1, j.p2]
                .iter()
                .map(|p| {
                    (velocity(&m.velocities[a], ba.centroid, *p)
                        - velocity(&m.velocities[b], bb.centroid, *p))
                    .norm()
                })
                .fold(0.0, f64::max);
            if rel <= tol {
                neighbours[a].push(b);
                neighbours[b].push(a);
            }
        }
    }
    let eps = 1e-9 * size;
    let same = |p: &Vec2, q: &Vec2| (p - q).norm() <= eps;
    let mut edges = Vec::new();
    let mut blocks = Vec::new();
    for (i, b) in assembly.blocks.iter().enumerate() {
        // A block that stays where it is (e.g. the part of an arch below its first hinge)
        // would only be dashed over its own outline.
        let still = b
            .polygon
            .iter()
            .all(|p| velocity(&m.velocities[i], b.centroid, *p).norm() <= tol);
        if still {
            continue;
        }
        let n = b.polygon.len();
        let moved: Vec<Vec2> = b
            .polygon
            .iter()
            .map(|p| p + amplification * velocity(&m.velocities[i], b.centroid, *p))
            .collect();
        for e in 0..n {
            let (p, q) = (b.polygon[e], b.polygon[(e + 1) % n]);
            let shared = neighbours[i].iter().any(|&k| {
                let o = &assembly.blocks[k].polygon;
                (0..o.len()).any(|f| {
                    let (r, s) = (o[f], o[(f + 1) % o.len()]);
                    (same(&p, &s) && same(&q, &r)) || (same(&p, &r) && same(&q, &s))
                })
            });
            if !shared {
                edges.push((moved[e], moved[(e + 1) % n]));
            }
        }
        blocks.push(moved);
    }
    Some(Displaced {
        edges,
        blocks,
        amplification,
        largest: amplification * speed,
    })
}

/// Join segments (pixel coordinates) that share end points into as few polylines as a
/// greedy walk finds, so a dash pattern runs on along a rigid piece's whole outline instead
/// of restarting at every short voussoir edge.
fn chain(segments: &[(Px, Px)]) -> Vec<Vec<Px>> {
    use std::collections::HashMap;
    // Ends closer than 0.05 px are the same point (the displaced corners of blocks of one
    // rigid piece agree to ~1e-4 of the largest displacement).
    let key = |p: (f64, f64)| ((p.0 * 20.0).round() as i64, (p.1 * 20.0).round() as i64);
    let mut at: HashMap<(i64, i64), Vec<usize>> = HashMap::new();
    for (i, (a, b)) in segments.iter().enumerate() {
        at.entry(key(*a)).or_default().push(i);
        at.entry(key(*b)).or_default().push(i);
    }
    let mut used = vec![false; segments.len()];
    let mut out = Vec::new();
    // Start at ends of odd degree first, so open chains are walked from one end.
    let mut starts: Vec<usize> = (0..segments.len()).collect();
    starts.sort_by_key(|&i| {
        let odd = |p| at.get(&key(p)).map_or(0, |v| v.len()) % 2 == 1;
        !(odd(segments[i].0) || odd(segments[i].1))
    });
    for s in starts {
        if used[s] {
            continue;
        }
        used[s] = true;
        let (a, b) = segments[s];
        let odd_b = at.get(&key(b)).map_or(0, |v| v.len()) % 2 == 1;
        let (first, mut end) = if odd_b { (b, a) } else { (a, b) };
        let mut line = vec![first, end];
        while let Some(&next) = at
            .get(&key(end))
            .and_then(|v| v.iter().find(|&&k| !used[k]))
        {
            used[next] = true;
            let (p, q) = segments[next];
            end = if key(p) == key(end) { q } else { p };
            line.push(end);
        }
        out.push(line);
    }
    out
}

/// Runs of consecutive `Some` points.
fn runs(points: impl Iterator<Item = Option<Vec2>>) -> Vec<Vec<Vec2>> {
    let mut out = Vec::new();
    let mut cur = Vec::new();
    for p in points {
        match p {
            Some(q) if q.x.is_finite() && q.y.is_finite() => cur.push(q),
            _ => {
                if !cur.is_empty() {
                    out.push(std::mem::take(&mut cur));
                }
            }
        }
    }
    if !cur.is_empty() {
        out.push(cur);
    }
    out
}

// ---------------------------------------------------------------------------------------------
// Loads.

/// Share of the structure's size taken by the arrow of the largest point load.
pub const POINT_LOAD_SHARE: f64 = 0.15;
/// Share of the structure's size taken by the arrows of line loads.
const LINE_LOAD_SHARE: f64 = 0.05;
/// Spacing of the arrows of a line load, as a share of the structure's size.
const LINE_LOAD_SPACING: f64 = 0.045;
/// Font size (px) of load labels and hinge numbers.
const LOAD_FONT: f64 = 13.0;
const HINGE_FONT: f64 = 13.0;
/// Half the side of the box a hinge's circle covers (px): its radius 6 and half its
/// stroke of 3.
const HINGE_RADIUS: f64 = 7.5;

/// A point load as drawn: an arrow from `tail` to `tip`, the point of application.
struct PointMark {
    tail: Vec2,
    tip: Vec2,
    label: String,
    /// Whether lambda multiplies it (a live load under a live action).
    live: bool,
}

/// A line load as drawn: a row of arrows ending on the extrados, all of one length for a
/// uniform load, each as long as the local intensity for a load that is not (a load spread
/// through the fill by Boussinesq's law, say).
struct LineMark {
    /// The loaded extrados, in x order.
    path: Vec<Vec2>,
    /// The arrows' tails, one above each point of `path`: the load's outline.
    tails: Vec<Vec2>,
    /// Arrows as (tail, tip), tips on `path`.
    arrows: Vec<(Vec2, Vec2)>,
    label: String,
    /// The abscissa the label is centred on: the middle of a uniform load, the peak of one
    /// that is not (two spread axles keep their labels apart).
    label_x: f64,
}

/// The loads of a load case as drawn, in world coordinates.
struct LoadMarks {
    /// Outlines of the fill regions.
    fill: Vec<Vec<Vec2>>,
    points: Vec<PointMark>,
    lines: Vec<LineMark>,
    /// Whether any load drawn is multiplied by lambda (labelled `λ × ...`).
    live: bool,
}

/// A text label: centre and half extent in world coordinates.
struct Label {
    centre: Vec2,
    half: Vec2,
    text: String,
}

impl Label {
    fn rect(&self, frame: &Frame) -> Rect {
        let (x, y) = frame.pxf(self.centre);
        let (hx, hy) = (self.half.x * frame.scale, self.half.y * frame.scale);
        Rect {
            x0: x - hx,
            y0: y - hy,
            x1: x + hx,
            y1: y + hy,
        }
    }
}

impl LoadMarks {
    /// Fill regions, point loads (a `[[loads]]` entry applied as one piece) and line loads
    /// (applied as several pieces) of `loads`.
    fn new(loads: &LoadCase, size: f64) -> LoadMarks {
        let applied = loads.applied();
        let fill = applied
            .iter()
            .filter(|a| a.source == LoadSource::Fill)
            .filter_map(|a| a.region.clone())
            .filter(|r| r.len() >= 3)
            .collect();
        // One group per load: an entry of [[loads]], or one part of a vehicle (an axle, or
        // its distributed load on one side), keyed in that order.
        let mut groups: std::collections::BTreeMap<(usize, usize, usize), Vec<&AppliedLoad>> =
            Default::default();
        for a in applied {
            let key = match a.source {
                LoadSource::Load(k) => (0, k, 0),
                LoadSource::Vehicle(k, p) => (1, k, p),
                _ => continue,
            };
            groups.entry(key).or_default().push(a);
        }
        // A point load: one piece, or equal shares at one point on a joint (drawn as one).
        let point_of = |g: &[&AppliedLoad]| -> Option<(Vec2, Vec2)> {
            let first = g.first()?;
            g.iter().all(|a| a.point == first.point).then(|| {
                let force = g.iter().fold(Vec2::new(0.0, 0.0), |f, a| f + a.force);
                (first.point, force)
            })
        };
        let fmax = groups
            .values()
            .filter_map(|g| point_of(g))
            .map(|(_, force)| force.norm())
            .fold(0.0, f64::max);
        let mut points = Vec::new();
        let mut lines = Vec::new();
        let mut live = false;
        for g in groups.values() {
            // A live load under a live action is what lambda multiplies: its label says so.
            let times = if g.iter().any(|a| loads.is_variable(a)) {
                live = true;
                "\u{3bb} \u{d7} "
            } else {
                ""
            };
            if let Some((point, force)) = point_of(g) {
                let f = force.norm();
                if f > 0.0 {
                    let len = POINT_LOAD_SHARE * size * (f / fmax).max(0.2);
                    points.push(PointMark {
                        tail: point - force * (len / f),
                        tip: point,
                        label: format!("{times}{} kN", sig(f / 1000.0)),
                        live: !times.is_empty(),
                    });
                }
            } else if let Some(mut l) = LineMark::new(g, size) {
                l.label = format!("{times}{}", l.label);
                lines.push(l);
            }
        }
        LoadMarks {
            fill,
            points,
            lines,
            live,
        }
    }

    /// The fill's top surface: the highest point of its regions.
    fn level(&self) -> Option<f64> {
        self.fill.iter().flatten().map(|p| p.y).reduce(f64::max)
    }

    /// Every point drawn in world coordinates (labels aside).
    fn world_points(&self) -> Vec<Vec2> {
        let mut out: Vec<Vec2> = self.fill.iter().flatten().copied().collect();
        for p in &self.points {
            out.extend([p.tail, p.tip]);
        }
        for l in &self.lines {
            out.extend(l.path.iter().chain(&l.tails).copied());
        }
        out
    }

    /// The labels at drawing scale `scale` (px per m): point loads first, then line loads.
    /// A point load's label sits beyond its arrow's tail, a line load's above its arrows.
    fn labels(&self, scale: f64) -> Vec<Label> {
        let h = LOAD_FONT + 2.0;
        let size = |text: &str| {
            Vec2::new(
                0.5 * (wide_text_width(text, LOAD_FONT, false) + 4.0),
                0.5 * h,
            ) / scale
        };
        let mut out = Vec::new();
        for p in &self.points {
            let d = (p.tip - p.tail).normalize();
            let half = size(&p.label) * scale;
            let gap = 5.0 + (half.x * d.x).abs() + (half.y * d.y).abs();
            out.push(Label {
                centre: p.tail - d * (gap / scale),
                half: half / scale,
                text: p.label.clone(),
            });
        }
        for l in &self.lines {
            let half = size(&l.label);
            let xm = l.label_x;
            // Above the highest tail under the label.
            let top = l
                .tails
                .iter()
                .filter(|p| (p.x - xm).abs() <= half.x)
                .map(|p| p.y)
                .chain([
                    interpolate(&l.tails, xm - half.x),
                    interpolate(&l.tails, xm),
                    interpolate(&l.tails, xm + half.x),
                ])
                .fold(f64::NEG_INFINITY, f64::max);
            out.push(Label {
                centre: Vec2::new(xm, top + half.y + 4.0 / scale),
                half,
                text: l.label.clone(),
            });
        }
        out
    }
}

impl LineMark {
    /// A line load from its pieces (one per loaded block, each `q * overlap` at the middle
    /// of its overlap, on the extrados). None when it carries nothing.
    fn new(pieces: &[&AppliedLoad], size: f64) -> Option<LineMark> {
        let mut pts: Vec<(Vec2, f64)> = pieces.iter().map(|a| (a.point, a.force.norm())).collect();
        pts.sort_by(|a, b| a.0.x.total_cmp(&b.0.x));
        let total: f64 = pts.iter().map(|p| p.1).sum();
        // Forces are finite (checked), so the total is a number >= 0.
        if total <= 0.0 {
            return None;
        }
        let len = LINE_LOAD_SHARE * size;
        // The overlaps tile the loaded length, each centred on its piece: the centres of two
        // neighbours lie (w_i + w_i+1) / 2q apart. This gives q, and the ends of the load.
        let dx = pts[pts.len() - 1].0.x - pts[0].0.x;
        let sum: f64 = pts.windows(2).map(|w| 0.5 * (w[0].1 + w[1].1)).sum();
        let q = sum / dx;
        let tiled = dx > 0.0
            && q.is_finite()
            && pts.windows(2).all(|w| {
                let want = 0.5 * (w[0].1 + w[1].1);
                (want - q * (w[1].0.x - w[0].0.x)).abs() <= 1e-6 * want.max(1e-12 * total)
            });
        let mut path: Vec<Vec2> = pts.iter().map(|p| p.0).collect();
        // The arrows' length over each point of the path, in x order.
        let heights: Vec<f64>;
        let mut label_x = 0.5 * (pts[0].0.x + pts[pts.len() - 1].0.x);
        let label = if tiled {
            let n = pts.len();
            let start = pts[0].0.x - 0.5 * pts[0].1 / q;
            let end = pts[n - 1].0.x + 0.5 * pts[n - 1].1 / q;
            let first = extrapolate(path[0], path[1], start);
            let last = extrapolate(path[n - 1], path[n - 2], end);
            path.insert(0, first);
            path.push(last);
            heights = vec![len; path.len()];
            format!("q = {} kN/m", sig(q / 1000.0))
        } else {
            // Not uniform: each piece's intensity is its force over the width it stands for
            // (half-way to its neighbours, as far again at the ends), and the arrows follow it.
            let intensity = local_intensities(&pts);
            let peak = intensity.iter().copied().fold(0.0, f64::max);
            if let Some(k) = intensity.iter().position(|w| *w == peak) {
                label_x = pts[k].0.x;
            }
            heights = intensity
                .iter()
                .map(|w| if peak > 0.0 { len * w / peak } else { len })
                .collect();
            format!("{} kN in all", sig(total / 1000.0))
        };
        let tails: Vec<Vec2> = path
            .iter()
            .zip(&heights)
            .map(|(p, h)| Vec2::new(p.x, p.y + h))
            .collect();
        let profile: Vec<Vec2> = path
            .iter()
            .zip(&heights)
            .map(|(p, h)| Vec2::new(p.x, *h))
            .collect();
        let (x0, x1) = (path[0].x, path[path.len() - 1].x);
        let count = (((x1 - x0) / (LINE_LOAD_SPACING * size)).round() as usize).max(1) + 1;
        let arrows = (0..count)
            .map(|i| {
                let x = x0 + (x1 - x0) * i as f64 / (count - 1) as f64;
                let tip = Vec2::new(x, interpolate(&path, x));
                (Vec2::new(x, tip.y + interpolate(&profile, x)), tip)
            })
            // An arrow too short to have a head is left out; the outline still shows the load.
            .filter(|(tail, tip)| tail.y - tip.y >= 0.15 * len)
            .collect();
        Some(LineMark {
            path,
            tails,
            arrows,
            label,
            label_x,
        })
    }
}

/// The intensity (force per unit length) each piece of a distributed load stands for: its
/// force over the width from half-way to the neighbour before to half-way to the one after
/// (at an end, as far out as in). `pts` are (point, force) in x order, at least two.
fn local_intensities(pts: &[(Vec2, f64)]) -> Vec<f64> {
    let n = pts.len();
    let x = |i: usize| pts[i].0.x;
    (0..n)
        .map(|i| {
            let before = if i > 0 { x(i) - x(i - 1) } else { x(1) - x(0) };
            let after = if i + 1 < n {
                x(i + 1) - x(i)
            } else {
                x(n - 1) - x(n - 2)
            };
            let width = 0.5 * (before + after);
            if width > 0.0 {
                pts[i].1 / width
            } else {
                0.0
            }
        })
        .collect()
}

/// The point at abscissa `x` on the line through `a` and `b` (`a` when the line is vertical).
fn extrapolate(a: Vec2, b: Vec2, x: f64) -> Vec2 {
    if a.x == b.x {
        return a;
    }
    Vec2::new(x, a.y + (b.y - a.y) * (x - a.x) / (b.x - a.x))
}

/// The y of the polyline `path` (in x order) at `x`, held at its ends beyond them.
fn interpolate(path: &[Vec2], x: f64) -> f64 {
    let n = path.len();
    if x <= path[0].x {
        return path[0].y;
    }
    if x >= path[n - 1].x {
        return path[n - 1].y;
    }
    let k = path.partition_point(|p| p.x <= x).clamp(1, n - 1);
    extrapolate(path[k - 1], path[k], x).y
}

/// The fill: every region shaded, hatched over the whole, and the outline of the union
/// (its level and end walls: the region edges no other region shares that are horizontal
/// or vertical; the rest lies on the extrados, under the blocks).
/// The fixed blocks: each outline shaded grey, hatched and outlined in the ground's colour.
fn fixed_svg(outlines: &[Vec<Vec2>], frame: &Frame) -> String {
    let (fill, edge) = (hex(FIXED), hex(GROUND));
    let mut out = format!(
        "<defs><pattern id=\"fixed-hatch\" patternUnits=\"userSpaceOnUse\" width=\"7\" \
         height=\"7\" patternTransform=\"rotate(-45)\"><line x1=\"0\" y1=\"0\" x2=\"0\" \
         y2=\"7\" stroke=\"{edge}\" stroke-width=\"0.8\"/></pattern></defs>\n"
    );
    for o in outlines {
        let pts = points_attr(o.iter().map(|p| frame.pxf(*p)));
        out.push_str(&format!(
            "<polygon class=\"fixed-block\" fill=\"{fill}\" stroke=\"none\" points=\"{pts}\"/>\n\
             <polygon fill=\"url(#fixed-hatch)\" stroke=\"{edge}\" stroke-width=\"1.5\" \
             stroke-linejoin=\"round\" points=\"{pts}\"/>\n"
        ));
    }
    out
}

fn fill_svg(regions: &[Vec<Vec2>], frame: &Frame, size: f64) -> String {
    let fill = hex(FILL);
    let edge = hex(FILL_EDGE);
    let mut out = format!(
        "<defs><pattern id=\"fill-hatch\" patternUnits=\"userSpaceOnUse\" width=\"8\" \
         height=\"8\" patternTransform=\"rotate(45)\"><line x1=\"0\" y1=\"0\" x2=\"0\" \
         y2=\"8\" stroke=\"{edge}\" stroke-width=\"1\"/></pattern></defs>\n"
    );
    let mut d = String::new();
    for r in regions {
        let pts: Vec<String> = r.iter().map(|p| px_text(frame.pxf(*p))).collect();
        // A stroke of the fill colour closes the hairline seams between regions.
        out.push_str(&format!(
            "<polygon class=\"fill-region\" fill=\"{fill}\" stroke=\"{fill}\" \
             stroke-width=\"1\" stroke-linejoin=\"round\" points=\"{}\"/>\n",
            pts.join(" ")
        ));
        d.push_str(&format!("M{} Z ", pts.join(" L")));
    }
    out.push_str(&format!(
        "<path fill=\"url(#fill-hatch)\" stroke=\"none\" d=\"{}\"/>\n",
        d.trim_end()
    ));
    let tol = 1e-7 * size;
    let key = |p: Vec2| ((p.x / tol).round() as i64, (p.y / tol).round() as i64);
    // Edges by their (rounded) end points, either way round.
    type EdgeKey = ((i64, i64), (i64, i64));
    let mut count: std::collections::HashMap<EdgeKey, usize> = Default::default();
    let edges: Vec<(Vec2, Vec2)> = regions
        .iter()
        .flat_map(|r| (0..r.len()).map(move |k| (r[k], r[(k + 1) % r.len()])))
        .filter(|(a, b)| (a - b).norm() > tol)
        .collect();
    let undirected = |a: Vec2, b: Vec2| {
        let (ka, kb) = (key(a), key(b));
        if ka <= kb {
            (ka, kb)
        } else {
            (kb, ka)
        }
    };
    for (a, b) in &edges {
        *count.entry(undirected(*a, *b)).or_default() += 1;
    }
    let straight = |a: Vec2, b: Vec2| (a.x - b.x).abs() <= tol || (a.y - b.y).abs() <= tol;
    let outline: Vec<(Px, Px)> = edges
        .iter()
        .filter(|(a, b)| count[&undirected(*a, *b)] == 1 && straight(*a, *b))
        .map(|(a, b)| (frame.pxf(*a), frame.pxf(*b)))
        .collect();
    for line in chain(&outline) {
        out.push_str(&format!(
            "<polyline class=\"fill-outline\" fill=\"none\" stroke=\"{edge}\" \
             stroke-width=\"1.2\" points=\"{}\"/>\n",
            points_attr(line)
        ));
    }
    out
}

/// An arrow from `tail` to `tip` (pixels): a shaft and a filled head whose first point is
/// the tip.
fn arrow_svg(tail: Px, tip: Px, colour: RGBColor, width: f64, head: f64) -> String {
    let (dx, dy) = (tip.0 - tail.0, tip.1 - tail.1);
    let len = dx.hypot(dy);
    if len <= 0.0 {
        return String::new();
    }
    let (ux, uy) = (dx / len, dy / len);
    let head = head.min(0.6 * len);
    let back = (tip.0 - head * ux, tip.1 - head * uy);
    let half = 0.42 * head;
    let c = hex(colour);
    format!(
        "<line x1=\"{:.1}\" y1=\"{:.1}\" x2=\"{:.1}\" y2=\"{:.1}\" stroke=\"{c}\" \
         stroke-width=\"{width}\"/>\n<polygon class=\"arrow-head\" fill=\"{c}\" \
         points=\"{:.1},{:.1} {:.1},{:.1} {:.1},{:.1}\"/>\n",
        tail.0,
        tail.1,
        back.0 + 0.3 * head * ux,
        back.1 + 0.3 * head * uy,
        tip.0,
        tip.1,
        back.0 - half * uy,
        back.1 + half * ux,
        back.0 + half * uy,
        back.1 - half * ux,
    )
}

/// The stroke of a tie or a strip: `width` px when it carries something, thin and dashed when
/// it has no capacity (not needed by a retrofit design).
fn element_stroke(none: bool, width: f64) -> String {
    if none {
        format!("stroke-width=\"1.5\" stroke-dasharray=\"{DASH}\"")
    } else {
        format!("stroke-width=\"{width}\"")
    }
}

/// The bonded strips: a line along the face through the reinforced ends of the joints each
/// crosses, and a dot where it has reached its capacity.
fn strips_svg(assembly: &Assembly, drawing: &Drawing, frame: &Frame) -> String {
    let mut text = String::new();
    let sources = drawing
        .strips
        .iter()
        .map(|s| s.source)
        .max()
        .map_or(0, |m| m + 1);
    for k in 0..sources {
        let mut pts: Vec<(usize, Px)> = drawing
            .strips
            .iter()
            .filter(|s| s.source == k)
            .map(|s| (s.joint, frame.pxf(s.point(assembly))))
            .collect();
        pts.sort_by_key(|p| p.0);
        // A strip of no capacity at any joint carries nothing (not needed by a retrofit
        // design): thin and dashed, as a tie of none.
        let none = drawing
            .strips
            .iter()
            .filter(|s| s.source == k)
            .all(|s| s.capacity <= 0.0);
        let stroke = element_stroke(none, 4.0);
        text.push_str(&format!(
            "<polyline fill=\"none\" stroke=\"{}\" {stroke} stroke-linejoin=\"round\" stroke-linecap=\"round\" points=\"{}\"/>\n",
            hex(STRIP),
            points_attr(pts.iter().map(|(_, p)| *p))
        ));
    }
    for (s, f) in drawing.strips.iter().zip(drawing.strip_forces) {
        if f.yielded && s.capacity > 0.0 {
            let (x, y) = frame.pxf(s.point(assembly));
            text.push_str(&format!(
                "<circle cx=\"{x:.1}\" cy=\"{y:.1}\" r=\"5\" fill=\"white\" stroke=\"{}\" stroke-width=\"2.5\"/>\n",
                hex(STRIP)
            ));
        }
    }
    text
}

/// The fill's passive faces: a line along each face under the level, and at collapse an
/// arrow from the reaction point out of the fill, up to 40 px for the largest reaction, solid
/// where the reaction is at its cap.
fn passive_svg(drawing: &Drawing, frame: &Frame) -> String {
    let mut text = String::new();
    for p in drawing.passive {
        let (a, b) = (frame.pxf(p.a), frame.pxf(p.b));
        text.push_str(&format!(
            "<line x1=\"{:.1}\" y1=\"{:.1}\" x2=\"{:.1}\" y2=\"{:.1}\" stroke=\"{}\" stroke-width=\"4\" stroke-linecap=\"round\" stroke-opacity=\"0.8\"/>\n",
            a.0,
            a.1,
            b.0,
            b.1,
            hex(PASSIVE)
        ));
    }
    let largest = drawing
        .passive_forces
        .iter()
        .fold(0.0_f64, |m, f| m.max(f.force));
    if largest <= 0.0 {
        return text;
    }
    for (p, f) in drawing.passive.iter().zip(drawing.passive_forces) {
        if f.force <= 1e-9 * largest {
            continue;
        }
        let tip = frame.pxf(p.point);
        // The reaction pushes toward -into: the arrow comes from the fill's side (+into in
        // the drawing's x, which grows to the right as the model's does).
        let len = 8.0 + 32.0 * f.force / largest;
        let tail = (tip.0 + p.into * len, tip.1);
        let colour = if f.yielded {
            PASSIVE
        } else {
            RGBColor(0xC8, 0xA8, 0x8A)
        };
        text.push_str(&arrow_svg(tail, tip, colour, 2.0, 8.0));
    }
    text
}

/// The tie rods: a line between the anchors, a dot at each, and a label above the middle
/// with the force at collapse (or the capacity when there is no solution).
fn ties_svg(drawing: &Drawing, frame: &Frame) -> String {
    let mut text = String::new();
    for (k, t) in drawing.ties.iter().enumerate() {
        let (a, b) = (frame.pxf(t.from.point), frame.pxf(t.to.point));
        // A tie of no capacity carries nothing (a retrofit design found it not needed): drawn
        // thin and dashed, where it would go, so it is not read as a tie in place.
        let none = t.capacity <= 0.0;
        let stroke = element_stroke(none, 3.0);
        text.push_str(&format!(
            "<line x1=\"{:.1}\" y1=\"{:.1}\" x2=\"{:.1}\" y2=\"{:.1}\" stroke=\"{}\" {stroke}/>\n",
            a.0,
            a.1,
            b.0,
            b.1,
            hex(TIE)
        ));
        for p in [a, b] {
            text.push_str(&format!(
                "<circle cx=\"{:.1}\" cy=\"{:.1}\" r=\"4\" fill=\"{}\"/>\n",
                p.0,
                p.1,
                hex(TIE)
            ));
        }
        let label = match drawing.tie_forces.get(k) {
            _ if none => format!("tie {k}: none (capacity 0 N)"),
            Some(f) if f.yielded => format!("tie {k}: {} N, yielded", sig(f.force)),
            Some(f) => format!("tie {k}: {} N of {} N", sig(f.force), sig(t.capacity)),
            None => format!("tie {k}: capacity {} N", sig(t.capacity)),
        };
        let (mx, my) = (0.5 * (a.0 + b.0), 0.5 * (a.1 + b.1));
        text.push_str(&text_svg(mx, my - 12.0, 13.0, "middle", TIE, &label));
    }
    text
}

/// A label centred vertically at `(x, y)` (pixels), with a white halo so it reads over lines
/// and shading.
fn text_svg(x: f64, y: f64, px: f64, anchor: &str, colour: RGBColor, s: &str) -> String {
    format!(
        "<text x=\"{x:.1}\" y=\"{y:.1}\" dy=\"0.35em\" text-anchor=\"{anchor}\" \
         font-family=\"sans-serif\" font-size=\"{px}\" fill=\"{}\" stroke=\"white\" \
         stroke-width=\"3\" stroke-linejoin=\"round\" paint-order=\"stroke\">{}</text>\n",
        hex(colour),
        escape(s)
    )
}

/// An axis-aligned rectangle in pixels.
#[derive(Debug, Clone, Copy)]
struct Rect {
    x0: f64,
    y0: f64,
    x1: f64,
    y1: f64,
}

impl Rect {
    fn around(pts: &[Px]) -> Rect {
        pts.iter().fold(
            Rect {
                x0: f64::INFINITY,
                y0: f64::INFINITY,
                x1: f64::NEG_INFINITY,
                y1: f64::NEG_INFINITY,
            },
            |r, p| Rect {
                x0: r.x0.min(p.0),
                y0: r.y0.min(p.1),
                x1: r.x1.max(p.0),
                y1: r.y1.max(p.1),
            },
        )
    }
    fn union(&self, o: &Rect) -> Rect {
        Rect {
            x0: self.x0.min(o.x0),
            y0: self.y0.min(o.y0),
            x1: self.x1.max(o.x1),
            y1: self.y1.max(o.y1),
        }
    }
    fn grown(&self, by: f64) -> Rect {
        Rect {
            x0: self.x0 - by,
            y0: self.y0 - by,
            x1: self.x1 + by,
            y1: self.y1 + by,
        }
    }
    fn shifted(&self, (x, y): Px) -> Rect {
        Rect {
            x0: self.x0 + x,
            y0: self.y0 + y,
            x1: self.x1 + x,
            y1: self.y1 + y,
        }
    }
    fn corners(&self) -> Vec<Px> {
        vec![
            (self.x0, self.y0),
            (self.x1, self.y0),
            (self.x1, self.y1),
            (self.x0, self.y1),
        ]
    }
    /// Whether the two rectangles overlap (touching edges count).
    fn meets(&self, o: &Rect) -> bool {
        self.x0 <= o.x1 && o.x0 <= self.x1 && self.y0 <= o.y1 && o.y0 <= self.y1
    }
    /// Whether the rectangle overlaps the convex polygon `poly` (separating axes).
    fn overlaps(&self, poly: &[Px]) -> bool {
        let b = Rect::around(poly);
        if b.x1 < self.x0 || b.x0 > self.x1 || b.y1 < self.y0 || b.y0 > self.y1 {
            return false;
        }
        let corners = self.corners();
        let n = poly.len();
        for k in 0..n {
            let (a, c) = (poly[k], poly[(k + 1) % n]);
            let axis = (a.1 - c.1, c.0 - a.0);
            let proj = |p: &Px| p.0 * axis.0 + p.1 * axis.1;
            let (lo, hi) = poly
                .iter()
                .map(proj)
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), v| {
                    (l.min(v), h.max(v))
                });
            let (rl, rh) = corners
                .iter()
                .map(proj)
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), v| {
                    (l.min(v), h.max(v))
                });
            if rh < lo || rl > hi {
                return false;
            }
        }
        true
    }
}

/// The first place (reading order: rows from the top, each from the left) where `bounds`,
/// shifted by the returned offset, lies inside `region` and clear of every obstacle; the top
/// left of `region` when there is none (or `region` is too small).
fn free_spot(bounds: &Rect, region: &Rect, obstacles: &[Vec<Px>]) -> Px {
    let step = 6.0;
    let fallback = (region.x0 - bounds.x0, region.y0 - bounds.y0);
    let boxes: Vec<Rect> = obstacles.iter().map(|o| Rect::around(o)).collect();
    let mut y = region.y0 - bounds.y0;
    while y + bounds.y1 <= region.y1 {
        let mut x = region.x0 - bounds.x0;
        while x + bounds.x1 <= region.x1 {
            let r = bounds.shifted((x, y));
            let clear = obstacles.iter().zip(&boxes).all(|(o, b)| {
                b.x1 < r.x0 || b.x0 > r.x1 || b.y1 < r.y0 || b.y0 > r.y1 || !r.overlaps(o)
            });
            if clear {
                return (x, y);
            }
            x += step;
        }
        y += step;
    }
    fallback
}

/// The seismic load arrow drawn on the structure: `lambda g` across in the direction of the
/// ground motion, and its vertical component `r lambda g` from the same tail when r != 0.
struct SeismicGlyph {
    /// +1 toward +x, -1 toward -x.
    sign: f64,
    r: f64,
    /// Extent of everything drawn, relative to the common tail.
    bounds: Rect,
}

/// Length (px) of the horizontal seismic arrow.
const SEISMIC_ARROW: f64 = 64.0;
const SEISMIC_FONT: f64 = 15.0;

impl SeismicGlyph {
    fn new(d: Direction, r: f64) -> SeismicGlyph {
        let sign = d.sign();
        let mut g = SeismicGlyph {
            sign,
            r,
            bounds: Rect::around(&[(0.0, 0.0)]),
        };
        let mut b = Rect::around(&[(0.0, -8.0), (sign * SEISMIC_ARROW, 8.0)]);
        let (lx, ly) = g.label_at();
        let half = 0.5 * wide_text_width("\u{3bb}g", SEISMIC_FONT, true);
        b = b.union(&Rect::around(&[
            (lx - half, ly - 9.0),
            (lx + half, ly + 9.0),
        ]));
        if let Some((tip, (vx, vy), text)) = g.vertical() {
            let w = wide_text_width(&text, LOAD_FONT, false);
            let x_far = vx - sign * w;
            b = b.union(&Rect::around(&[
                (-8.0, 0.0),
                (8.0, tip.1),
                (x_far, vy - 9.0),
                (vx, vy + 9.0),
            ]));
        }
        g.bounds = b.grown(4.0);
        g
    }

    /// Centre of the `lambda g` label, relative to the tail.
    fn label_at(&self) -> Px {
        (0.5 * self.sign * SEISMIC_ARROW, -13.0)
    }

    /// The vertical component: its tip, its label's anchor (on the side away from the
    /// horizontal arrow) and text, relative to the tail. None when r = 0.
    fn vertical(&self) -> Option<(Px, Px, String)> {
        if self.r == 0.0 {
            return None;
        }
        // To scale, but long enough to show its head.
        let len = (self.r.abs() * SEISMIC_ARROW).max(18.0);
        let tip = (0.0, -self.r.signum() * len);
        let label = (-self.sign * 7.0, 0.5 * tip.1);
        Some((tip, label, format!("r\u{b7}\u{3bb}g, r = {}", sig(self.r))))
    }

    fn svg(&self, origin: Px) -> String {
        let at = |p: Px| (origin.0 + p.0, origin.1 + p.1);
        let mut out = String::from("<g class=\"seismic-load\">\n");
        out.push_str(&arrow_svg(
            at((0.0, 0.0)),
            at((self.sign * SEISMIC_ARROW, 0.0)),
            SEISMIC,
            2.5,
            12.0,
        ));
        let (lx, ly) = at(self.label_at());
        out.push_str(&format!(
            "<text x=\"{lx:.1}\" y=\"{ly:.1}\" dy=\"0.35em\" text-anchor=\"middle\" \
             font-family=\"sans-serif\" font-size=\"{SEISMIC_FONT}\" font-weight=\"bold\" \
             fill=\"{}\" stroke=\"white\" stroke-width=\"3\" stroke-linejoin=\"round\" \
             paint-order=\"stroke\">\u{3bb}g</text>\n",
            hex(SEISMIC)
        ));
        if let Some((tip, label, text)) = self.vertical() {
            out.push_str(&arrow_svg(at((0.0, 0.0)), at(tip), SEISMIC, 2.0, 10.0));
            let (x, y) = at(label);
            let anchor = if self.sign > 0.0 { "end" } else { "start" };
            out.push_str(&text_svg(x, y, LOAD_FONT, anchor, SEISMIC, &text));
        }
        out.push_str("</g>\n");
        out
    }
}

/// A scale bar of a round length (1, 2 or 5 times a power of ten).
struct ScaleBar {
    /// Length (m).
    length: f64,
    /// Length (px).
    px: f64,
}

impl ScaleBar {
    /// The largest round length up to a quarter of `extent` (m), at `scale` px per m.
    fn new(extent: f64, scale: f64) -> ScaleBar {
        let target = 0.25 * extent;
        let p = 10f64.powf(target.log10().floor());
        let length = [5.0, 2.0, 1.0]
            .iter()
            .map(|m| m * p)
            .find(|&l| l <= target * (1.0 + 1e-9))
            .unwrap_or(p);
        ScaleBar {
            length,
            px: length * scale,
        }
    }

    /// The bar ending at `right`, centred on `y` (pixels): two halves, dark and light, and
    /// its length to the left.
    fn svg(&self, right: f64, y: f64) -> String {
        let x0 = right - self.px;
        let h = 6.0;
        let half = 0.5 * self.px;
        let dark = hex(TEXT);
        let mut out = format!(
            "<rect x=\"{x0:.1}\" y=\"{:.1}\" width=\"{half:.2}\" height=\"{h}\" fill=\"{dark}\"/>\n",
            y - 0.5 * h
        );
        out.push_str(&format!(
            "<rect class=\"scale-bar\" x=\"{x0:.2}\" y=\"{:.1}\" width=\"{:.2}\" height=\"{h}\" \
             fill=\"none\" stroke=\"{dark}\" stroke-width=\"1\"/>\n",
            y - 0.5 * h,
            self.px
        ));
        let label = if self.length >= 0.01 {
            format!("{} m", sig(self.length))
        } else {
            format!("{} mm", sig(1000.0 * self.length))
        };
        out.push_str(&text_svg(x0 - 8.0, y, 13.0, "end", TEXT, &label));
        out
    }
}

fn closed<T: Copy>(mut pts: Vec<T>) -> Vec<T> {
    if let Some(&p) = pts.first() {
        pts.push(p);
    }
    pts
}

/// A point in pixels.
type Px = (f64, f64);

/// A pixel point as SVG writes it (to a tenth of a pixel).
fn px_text((x, y): Px) -> String {
    format!("{x:.1},{y:.1}")
}

/// The `points` attribute of a polyline or polygon through the pixel points `pts`.
fn points_attr(pts: impl IntoIterator<Item = Px>) -> String {
    pts.into_iter().map(px_text).collect::<Vec<_>>().join(" ")
}

/// World (m) to pixels, one scale for both axes.
struct Frame {
    scale: f64,
    cx: f64,
    cy: f64,
    mid: Vec2,
}

impl Frame {
    fn pxf(&self, p: Vec2) -> (f64, f64) {
        (
            self.cx + (p.x - self.mid.x) * self.scale,
            self.cy - (p.y - self.mid.y) * self.scale,
        )
    }
    fn px(&self, p: Vec2) -> (i32, i32) {
        let (x, y) = self.pxf(p);
        (x.round() as i32, y.round() as i32)
    }
}

/// Dash pattern of the mechanism outlines (px on, px off).
pub const DASH: &str = "8 5";

fn hex(c: RGBColor) -> String {
    format!("#{:02X}{:02X}{:02X}", c.0, c.1, c.2)
}

/// A number with 3 significant digits, without trailing zeros.
pub(crate) fn sig(x: f64) -> String {
    if x == 0.0 || !x.is_finite() {
        return format!("{x}");
    }
    let digits = (2 - x.abs().log10().floor() as i32).max(0) as usize;
    let s = format!("{:.*}", digits, x);
    if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        s
    }
}

// ---------------------------------------------------------------------------------------------
// Shared by the structure drawing and the charts.

/// Plotters' SVG backend writes `font-size = size / 1.24`; this gives `px` pixels.
pub(crate) fn font_size(px: f64) -> f64 {
    px * 1.24
}

pub(crate) fn plot_err<E: std::fmt::Display>(e: E) -> SvgError {
    SvgError::Plot(e.to_string())
}

pub(crate) fn write_file(path: &Path, text: &str) -> Result<(), SvgError> {
    std::fs::write(path, text).map_err(|source| SvgError::Io {
        path: path.display().to_string(),
        source,
    })
}

/// An SVG document assembled from plotters passes, each wrapped in its own `<g id>` group.
pub(crate) struct Layers {
    width: u32,
    height: u32,
    body: String,
}

pub(crate) type Root<'b> = DrawingArea<SVGBackend<'b>, Shift>;

impl Layers {
    pub(crate) fn new(width: u32, height: u32) -> Self {
        Layers {
            width,
            height,
            body: String::new(),
        }
    }

    /// Run one plotters pass on a fresh backend of the document's size and keep its elements
    /// (without the backend's own `<svg>` wrapper) in a group with this id.
    pub(crate) fn layer<F>(&mut self, id: &str, draw: F) -> Result<(), SvgError>
    where
        F: for<'b> FnOnce(&Root<'b>) -> Result<(), SvgError>,
    {
        self.layer_class(id, "", draw)
    }

    /// As `layer`, with a `class` attribute on the group (when not empty).
    pub(crate) fn layer_class<F>(&mut self, id: &str, class: &str, draw: F) -> Result<(), SvgError>
    where
        F: for<'b> FnOnce(&Root<'b>) -> Result<(), SvgError>,
    {
        let mut buf = String::new();
        {
            let root =
                SVGBackend::with_string(&mut buf, (self.width, self.height)).into_drawing_area();
            draw(&root)?;
            root.present().map_err(plot_err)?;
        }
        // The backend writes "<svg ...>\n", the elements, then "</svg>\n".
        let start = buf.find('\n').map_or(0, |i| i + 1);
        let end = buf.rfind("</svg>").unwrap_or(buf.len()).max(start);
        if class.is_empty() {
            self.body.push_str(&format!("<g id=\"{id}\">\n"));
        } else {
            self.body
                .push_str(&format!("<g id=\"{id}\" class=\"{class}\">\n"));
        }
        self.body.push_str(&buf[start..end]);
        self.body.push_str("</g>\n");
        Ok(())
    }

    /// A group of elements written by hand.
    pub(crate) fn raw(&mut self, id: &str, elements: &str) {
        self.body.push_str(&format!("<g id=\"{id}\">\n"));
        self.body.push_str(elements);
        self.body.push_str("</g>\n");
    }

    pub(crate) fn finish(self, title: &str) -> String {
        let mut out = format!(
            "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<svg xmlns=\"http://www.w3.org/2000/svg\" \
             width=\"{w}\" height=\"{h}\" viewBox=\"0 0 {w} {h}\">\n<title>{t}</title>\n",
            w = self.width,
            h = self.height,
            t = escape(title)
        );
        out.push_str(&self.body);
        out.push_str("</svg>\n");
        out
    }
}

pub(crate) fn escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

/// Legend sample glyphs.
#[derive(Debug, Clone)]
pub(crate) enum Glyph {
    Block,
    Moved,
    /// Colour, stroke width, dashed.
    Line(RGBColor, u32, bool),
    /// Dashed outline over a faint fill (mechanism).
    Mechanism,
    /// A line with point markers (charts).
    Marked(RGBColor),
    Hinge,
    Ground,
    /// Shaded, hatched fill region.
    Fill,
    /// A fixed block: grey, hatched.
    Fixed,
    /// An arrow of this colour, pointing left when true.
    Arrow(RGBColor, bool),
}

pub(crate) const LEGEND_ROW: f64 = 24.0;
const LEGEND_FONT: f64 = 14.0;
const SAMPLE_W: f64 = 30.0;

/// Where a legend entry goes.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Slot {
    pub row: usize,
    pub x: f64,
}

/// Estimated text width: average glyph of a sans-serif font at `px` pixels.
pub(crate) fn text_width(s: &str, px: f64) -> f64 {
    0.58 * px * s.chars().count() as f64
}

/// Lay the entries out left to right, wrapping at `width`.
pub(crate) fn flow_legend(entries: &[(Glyph, String)], width: f64) -> Vec<Slot> {
    let mut slots = Vec::new();
    let (mut row, mut x) = (0, 0.0);
    for (_, text) in entries {
        let w = SAMPLE_W + 8.0 + text_width(text, LEGEND_FONT) + 26.0;
        if x > 0.0 && x + w > width {
            row += 1;
            x = 0.0;
        }
        slots.push(Slot { row, x });
        x += w;
    }
    slots
}

/// Draw legend entries at their slots; `(left, top)` is the legend's corner in pixels.
pub(crate) fn draw_legend(
    root: &Root<'_>,
    entries: &[(Glyph, String)],
    slots: &[Slot],
    left: f64,
    top: f64,
) -> Result<(), SvgError> {
    let style = TextStyle::from(("sans-serif", font_size(LEGEND_FONT)).into_font()).color(&TEXT);
    for ((glyph, text), slot) in entries.iter().zip(slots) {
        let x0 = (left + slot.x) as i32;
        let yc = (top + slot.row as f64 * LEGEND_ROW + LEGEND_ROW / 2.0) as i32;
        let x1 = x0 + SAMPLE_W as i32;
        match glyph {
            Glyph::Block | Glyph::Moved => {
                let (fill, edge) = match glyph {
                    Glyph::Block => (BLOCK.filled(), BLOCK_EDGE.stroke_width(1)),
                    _ => (MOVED.mix(0.35).filled(), MOVED.stroke_width(1)),
                };
                root.draw(&Rectangle::new([(x0, yc - 7), (x1, yc + 7)], fill))
                    .map_err(plot_err)?;
                root.draw(&Rectangle::new([(x0, yc - 7), (x1, yc + 7)], edge))
                    .map_err(plot_err)?;
            }
            Glyph::Line(c, w, dashed) => {
                let style: ShapeStyle = c.stroke_width(*w);
                if *dashed {
                    root.draw(&DashedPathElement::new(
                        vec![(x0, yc), (x1, yc)],
                        7,
                        5,
                        style,
                    ))
                    .map_err(plot_err)?;
                } else {
                    root.draw(&PathElement::new(vec![(x0, yc), (x1, yc)], style))
                        .map_err(plot_err)?;
                }
            }
            Glyph::Mechanism => {
                root.draw(&Rectangle::new(
                    [(x0, yc - 7), (x1, yc + 7)],
                    MECHANISM.mix(0.10).filled(),
                ))
                .map_err(plot_err)?;
                root.draw(&DashedPathElement::new(
                    vec![
                        (x0, yc - 7),
                        (x1, yc - 7),
                        (x1, yc + 7),
                        (x0, yc + 7),
                        (x0, yc - 7),
                    ],
                    8,
                    5,
                    MECHANISM.stroke_width(2),
                ))
                .map_err(plot_err)?;
            }
            Glyph::Marked(c) => {
                root.draw(&PathElement::new(
                    vec![(x0, yc), (x1, yc)],
                    c.stroke_width(2),
                ))
                .map_err(plot_err)?;
                root.draw(&Circle::new(((x0 + x1) / 2, yc), 3, c.filled()))
                    .map_err(plot_err)?;
            }
            Glyph::Hinge => {
                root.draw(&Circle::new(((x0 + x1) / 2, yc), 6, HINGE.stroke_width(3)))
                    .map_err(plot_err)?;
            }
            Glyph::Ground => {
                root.draw(&PathElement::new(
                    vec![(x0, yc - 4), (x1, yc - 4)],
                    GROUND.stroke_width(2),
                ))
                .map_err(plot_err)?;
                for k in 0..5 {
                    let x = x0 + 2 + 6 * k;
                    root.draw(&PathElement::new(
                        vec![(x, yc - 4), (x - 6, yc + 3)],
                        GROUND.stroke_width(1),
                    ))
                    .map_err(plot_err)?;
                }
            }
            Glyph::Fixed => {
                root.draw(&Rectangle::new(
                    [(x0, yc - 7), (x1, yc + 7)],
                    FIXED.filled(),
                ))
                .map_err(plot_err)?;
                root.draw(&Rectangle::new(
                    [(x0, yc - 7), (x1, yc + 7)],
                    GROUND.stroke_width(1),
                ))
                .map_err(plot_err)?;
                for k in 0..3 {
                    let x = x0 + 1 + 8 * k;
                    root.draw(&PathElement::new(
                        vec![(x, yc - 6), (x + 12, yc + 6)],
                        GROUND.stroke_width(1),
                    ))
                    .map_err(plot_err)?;
                }
            }
            Glyph::Fill => {
                root.draw(&Rectangle::new([(x0, yc - 7), (x1, yc + 7)], FILL.filled()))
                    .map_err(plot_err)?;
                for k in 0..3 {
                    let x = x0 + 1 + 8 * k;
                    root.draw(&PathElement::new(
                        vec![(x, yc + 6), (x + 12, yc - 6)],
                        FILL_EDGE.stroke_width(1),
                    ))
                    .map_err(plot_err)?;
                }
                root.draw(&PathElement::new(
                    vec![(x0, yc - 7), (x1, yc - 7)],
                    FILL_EDGE.stroke_width(1),
                ))
                .map_err(plot_err)?;
            }
            Glyph::Arrow(c, left) => {
                let (from, to) = if *left { (x1, x0) } else { (x0, x1) };
                let back = if *left { to + 9 } else { to - 9 };
                root.draw(&PathElement::new(
                    vec![(from, yc), (back, yc)],
                    c.stroke_width(2),
                ))
                .map_err(plot_err)?;
                root.draw(&Polygon::new(
                    vec![(to, yc), (back, yc - 5), (back, yc + 5)],
                    c.filled(),
                ))
                .map_err(plot_err)?;
            }
        }
        let text_style = style.pos(plotters::style::text_anchor::Pos::new(
            plotters::style::text_anchor::HPos::Left,
            plotters::style::text_anchor::VPos::Center,
        ));
        root.draw(&Text::new(text.clone(), (x1 + 8, yc), text_style))
            .map_err(plot_err)?;
    }
    Ok(())
}
