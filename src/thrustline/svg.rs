//! SVG drawings of assemblies, thrust lines and collapse mechanisms (plotters, SVG backend).
//!
//! `draw_structure` draws an [`Assembly`] to scale with equal axes, and on top of it what a
//! [`Drawing`] asks for:
//! - the thrust line (line of pressure): the points `p_mid + (M/N) u` where the resultant
//!   crosses each joint (`thrustline::thrust_points`), joined in joint order;
//! - for chains, the line of action of the resultant (the funicular polygon): inside block k
//!   the resultant runs along the force of joint k, `F_k = N_k n_k + V_k u_k`, through its
//!   pressure point, until the block's load line, where it turns into the force of joint
//!   k + 1. The corner is the intersection of the two force lines (by moment equilibrium of
//!   the block it lies on the line of action of the block's load `W (lambda, -1)`, see Heyman,
//!   *The Stone Skeleton*, 1995, ch. 3, and Ochsendorf's thrust-line analysis);
//! - hinges as circles at the joint end where the resultant (or the rotation centre) sits;
//! - sliding joints as thick orange segments;
//! - supports: ground hatching on the ground side of every joint to the ground;
//! - the collapse mechanism as dashed outlines of the displaced blocks: a point `p` of block
//!   `i` moves by `A (v_i + omega_i x (p - c_i))` (first-order rigid-body displacement,
//!   `omega x r = (-omega r_y, omega r_x)`; first order keeps the blocks on either side of a
//!   hinge joined at the hinge). The default amplification `A` makes the largest displacement
//!   of any block corner 10 % of the structure's size; the legend says `A` and that size.
//!   Blocks that move together as one rigid body are outlined as one piece (their shared
//!   joints are left out), so a 1000-voussoir arch shows its four pieces, not 1000 dashes;
//! - a second set of block positions (for DEM: final positions) as translucent blue blocks,
//!   each block `i` moved by a translation `t_i` and a rotation `theta_i` about its centroid.
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

use crate::assembly::{Assembly, Hinge, JointForce};
use crate::geometry::Vec2;
use crate::lp::Direction;

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
    /// Line of action of the resultant (funicular polygon).
    pub const ACTION: RGBColor = RGBColor(0xEE, 0x82, 0x82);
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
    /// Text.
    pub const TEXT: RGBColor = RGBColor(0x10, 0x10, 0x10);
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
    /// Direction of the horizontal load, shown in the legend as an arrow.
    pub load: Option<Direction>,
    /// Leave out the ground hatching under supports.
    pub hide_supports: bool,
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
    if let Some(m) = &mech {
        m.edges.iter().flat_map(|(a, b)| [a, b]).for_each(&mut grow);
    }
    if let Some(mv) = &moved {
        mv.iter().flatten().for_each(&mut grow);
    }
    let ext = hi - lo;
    if !(ext.x.is_finite() && ext.y.is_finite() && ext.max() > 0.0) {
        return Err(SvgError::Invalid(
            "the blocks have no extent (empty or non-finite outlines)".into(),
        ));
    }
    // A flat structure still gets some height (and a thin one some width).
    let ext = ext.sup(&Vec2::repeat(0.02 * ext.max()));
    let mid = 0.5 * (lo + hi);

    // Layout (pixels): title, the structure to scale in a box, the legend below.
    let width: u32 = 1000;
    let margin = 24.0;
    let pad = 22.0; // room for hatching and hinge circles around the structure
    let title_lines: Vec<&str> = drawing.title.lines().collect();
    let title_h = title_lines
        .iter()
        .enumerate()
        .map(|(i, _)| if i == 0 { 28.0 } else { 22.0 })
        .sum::<f64>();
    let top = margin + title_h + 6.0;
    let max_w = width as f64 - 2.0 * margin - 2.0 * pad;
    let max_h = 620.0;
    let scale = (max_w / ext.x).min(max_h / ext.y);
    let plot_h = ext.y * scale;
    let frame = Frame {
        scale,
        cx: width as f64 / 2.0,
        cy: top + pad + plot_h / 2.0,
        mid,
    };

    let mut legend = Vec::new();
    let blocks_label = if drawing.moved.is_some() {
        "initial positions (to scale)"
    } else {
        "blocks (to scale)"
    };
    legend.push((Glyph::Block, blocks_label.to_string()));
    let thrust = drawing.forces.map(|f| super::thrust_points(assembly, f));
    if thrust.is_some() {
        legend.push((Glyph::Line(THRUST, 3, false), "thrust line".into()));
        if assembly.is_chain() {
            legend.push((Glyph::Line(ACTION, 2, false), "line of action".into()));
        }
    }
    if !drawing.hinges.is_empty() {
        legend.push((Glyph::Hinge, format!("hinge ({})", drawing.hinges.len())));
    }
    if !drawing.sliding.is_empty() {
        legend.push((Glyph::Line(SLIDING, 6, false), "sliding joint".into()));
    }
    let has_supports = !drawing.hide_supports && assembly.joints.iter().any(|j| j.is_support());
    if has_supports {
        legend.push((Glyph::Ground, "support".into()));
    }
    if let Some(m) = &mech {
        legend.push((
            Glyph::Mechanism,
            format!(
                "collapse mechanism, displacements x{} (largest {} m = {:.0}% of size {} m)",
                sig(m.amplification),
                sig(m.largest),
                100.0 * m.largest / size,
                sig(size)
            ),
        ));
    }
    if let Some(pl) = &drawing.moved {
        legend.push((Glyph::Moved, pl.label.clone()));
    }
    if let Some(d) = drawing.load {
        let arrow = match d {
            Direction::Right => "\u{2192}",
            Direction::Left => "\u{2190}",
        };
        legend.push((
            Glyph::Text(arrow.into()),
            "horizontal load \u{3bb}W at each centroid".into(),
        ));
    }
    let legend_top = top + plot_h + 2.0 * pad + 10.0;
    let legend_rows = flow_legend(&legend, width as f64 - 2.0 * margin);
    let rows = legend_rows.iter().map(|r| r.row).max().map_or(0, |r| r + 1);
    let height = (legend_top + rows as f64 * LEGEND_ROW + margin).ceil() as u32;

    let mut svg = Layers::new(width, height);
    svg.layer("background", |root| {
        root.fill(&WHITE).map_err(plot_err)?;
        Ok(())
    })?;
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
            let pts: Vec<String> = line.iter().map(|(x, y)| format!("{x:.1},{y:.1}")).collect();
            text.push_str(&format!(
                "<polyline fill=\"none\" stroke=\"{}\" stroke-width=\"2\" \
                 stroke-dasharray=\"{DASH}\" stroke-linejoin=\"round\" points=\"{}\"/>\n",
                hex(MECHANISM),
                pts.join(" ")
            ));
        }
        svg.raw("mechanism", &text);
    }
    if let (Some(points), Some(forces)) = (&thrust, drawing.forces) {
        if assembly.is_chain() {
            let action = line_of_action(assembly, forces, points);
            svg.layer("line-of-action", |root| {
                for run in action {
                    let pts: Vec<_> = run.iter().map(|p| frame.px(*p)).collect();
                    root.draw(&PathElement::new(pts, ACTION.stroke_width(2)))
                        .map_err(plot_err)?;
                }
                Ok(())
            })?;
        }
        svg.layer("thrust-line", |root| {
            for run in runs(
                points
                    .iter()
                    .map(|p| p.filter(|q| q.x.is_finite() && q.y.is_finite())),
            ) {
                let pts: Vec<_> = run.iter().map(|p| frame.px(*p)).collect();
                if pts.len() == 1 {
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
    if !drawing.hinges.is_empty() {
        svg.layer("hinges", |root| {
            for h in drawing.hinges {
                let c = frame.px(Vec2::new(h.x, h.y));
                root.draw(&Circle::new(c, 6, HINGE.stroke_width(3)))
                    .map_err(plot_err)?;
            }
            Ok(())
        })?;
    }
    svg.layer("title", |root| {
        let mut y = margin;
        for (i, line) in title_lines.iter().enumerate() {
            let (px, h, bold) = if i == 0 {
                (20.0, 28.0, true)
            } else {
                (15.0, 22.0, false)
            };
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

/// The funicular polygon of a chain: pressure points joined through the corners where the
/// force lines of consecutive joints meet, in runs broken where a joint carries no force.
fn line_of_action(
    assembly: &Assembly,
    forces: &[JointForce],
    points: &[Option<Vec2>],
) -> Vec<Vec<Vec2>> {
    let dir = |k: usize| {
        let j = &assembly.joints[k];
        forces[k].n * j.normal() + forces[k].v * j.tangent()
    };
    let mut seq: Vec<Option<Vec2>> = Vec::new();
    for k in 0..assembly.joints.len() {
        seq.push(points[k]);
        if k < assembly.blocks.len() {
            let corner = match (points[k], points[k + 1]) {
                (Some(a), Some(b)) => {
                    let (da, db) = (dir(k), dir(k + 1));
                    let den = crate::geometry::cross(da, db);
                    let bl = &assembly.blocks[k];
                    if den.abs() > 1e-12 * da.norm() * db.norm() {
                        // a + s da = b + r db  =>  s = ((b - a) x db) / (da x db)
                        let s = crate::geometry::cross(b - a, db) / den;
                        let c = a + s * da;
                        // Nearly parallel forces (a pier course under a small lambda, the
                        // block at a support) put the corner outside the block, even below
                        // the ground: true, but it reads as a stray spike. Draw the corner
                        // only where the line turns inside the block; elsewhere the run
                        // joins the pressure points.
                        inside(&bl.polygon, c).then_some(c)
                    } else {
                        None
                    }
                }
                _ => None,
            };
            if let Some(c) = corner {
                seq.push(Some(c));
            }
        }
    }
    runs(seq.into_iter())
}

/// Whether `p` lies in the convex polygon `poly` (either orientation), edges included.
fn inside(poly: &[Vec2], p: Vec2) -> bool {
    let n = poly.len();
    let side = |k: usize| crate::geometry::cross(poly[(k + 1) % n] - poly[k], p - poly[k]);
    (0..n).all(|k| side(k) >= 0.0) || (0..n).all(|k| side(k) <= 0.0)
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

fn closed<T: Copy>(mut pts: Vec<T>) -> Vec<T> {
    if let Some(&p) = pts.first() {
        pts.push(p);
    }
    pts
}

/// A point in pixels.
type Px = (f64, f64);

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
    Text(String),
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
            Glyph::Text(s) => {
                let big = TextStyle::from(("sans-serif", font_size(22.0)).into_font())
                    .color(&TEXT)
                    .pos(plotters::style::text_anchor::Pos::new(
                        plotters::style::text_anchor::HPos::Center,
                        plotters::style::text_anchor::VPos::Center,
                    ));
                root.draw(&Text::new(s.clone(), ((x0 + x1) / 2, yc), big))
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
