//! Line charts for parametric studies (`voussoir sweep --svg`): e.g. the collapse multiplier
//! against t/R, one line per embrace angle. Plotters draws the axes, ticks and lines (SVG
//! backend, no fonts needed: text goes out as SVG `<text>` elements); the legend sits to the
//! right of the plot, so it never hides a line.
//!
//! A point with a non-finite x or y (NaN for a case that cannot stand or failed) breaks its
//! line; by default every finite point also gets a marker, so an isolated point still shows,
//! while a finely sampled curve (a capacity curve, a spectrum) is drawn as a plain line with
//! only its significant points marked ([`Markers::At`]). Each series is its own group
//! `<g id="series-K" class="series">` in the file.

use std::path::Path;

use plotters::chart::{ChartBuilder, ChartContext};
use plotters::coord::cartesian::Cartesian2d;
use plotters::coord::types::RangedCoordf64;
use plotters::element::{Circle, PathElement, Text};
use plotters::prelude::SVGBackend;
use plotters::series::LineSeries;
use plotters::style::text_anchor::{HPos, Pos, VPos};
use plotters::style::{Color, FontStyle, IntoFont, RGBAColor, RGBColor, TextStyle, WHITE};

use super::svg::colours::TEXT;
use super::svg::{
    draw_legend, fit_px, font_size, plot_err, text_width, write_file, Glyph, Layers, Root, Slot,
    SvgError,
};

/// One named line of a chart.
#[derive(Debug, Clone, PartialEq)]
pub struct Series {
    /// Legend text, e.g. "embrace_deg = 150".
    pub name: String,
    /// `(x, y)` points; a non-finite x or y breaks the line there. Drawn in x order.
    pub points: Vec<(f64, f64)>,
    /// Which points get a marker.
    pub markers: Markers,
}

/// The markers of a series.
#[derive(Debug, Clone, Default, PartialEq)]
pub enum Markers {
    /// A marker on every finite point (study points: each is a case that was solved).
    #[default]
    Every,
    /// Markers at these points only (none when empty): a curve sampled finely enough to read
    /// as a line, with its significant points marked.
    At(Vec<(f64, f64)>),
}

impl Series {
    /// A series from optional values (`None` breaks the line).
    pub fn new(
        name: impl Into<String>,
        points: impl IntoIterator<Item = (f64, Option<f64>)>,
    ) -> Self {
        Series {
            name: name.into(),
            points: points
                .into_iter()
                .map(|(x, y)| (x, y.unwrap_or(f64::NAN)))
                .collect(),
            markers: Markers::Every,
        }
    }

    /// A line through `points` with markers only at `marks` (none when empty).
    pub fn line(
        name: impl Into<String>,
        points: Vec<(f64, f64)>,
        marks: impl IntoIterator<Item = (f64, f64)>,
    ) -> Self {
        Series {
            name: name.into(),
            points,
            markers: Markers::At(marks.into_iter().collect()),
        }
    }
}

/// A line chart.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Chart {
    pub title: String,
    pub x_label: String,
    pub y_label: String,
    /// Heading of the legend, e.g. the `--series` key.
    pub legend_title: Option<String>,
    pub series: Vec<Series>,
}

/// Colours of successive series (Tableau 10, distinguishable and printable).
pub const PALETTE: [RGBColor; 10] = [
    RGBColor(0x1F, 0x77, 0xB4),
    RGBColor(0xFF, 0x7F, 0x0E),
    RGBColor(0x2C, 0xA0, 0x2C),
    RGBColor(0xD6, 0x27, 0x28),
    RGBColor(0x94, 0x67, 0xBD),
    RGBColor(0x8C, 0x56, 0x4B),
    RGBColor(0xE3, 0x77, 0xC2),
    RGBColor(0x7F, 0x7F, 0x7F),
    RGBColor(0xBC, 0xBD, 0x22),
    RGBColor(0x17, 0xBE, 0xCF),
];

/// Unbroken runs of finite points of one series.
type Runs = Vec<Vec<(f64, f64)>>;

const WIDTH: u32 = 960;
const HEIGHT: u32 = 600;

/// Draw `chart` into the SVG file `path`.
pub fn draw_lines<P: AsRef<Path>>(path: P, chart: &Chart) -> Result<(), SvgError> {
    let text = chart_svg(chart)?;
    write_file(path.as_ref(), &text)
}

/// Draw `chart` as SVG into `writer`.
pub fn write_lines<W: std::io::Write>(mut writer: W, chart: &Chart) -> Result<(), SvgError> {
    let text = chart_svg(chart)?;
    writer
        .write_all(text.as_bytes())
        .map_err(|source| SvgError::Io {
            path: "<writer>".into(),
            source,
        })
}

/// The SVG document of `chart`.
pub fn chart_svg(chart: &Chart) -> Result<String, SvgError> {
    // Sorted finite points of each series, with the breaks kept.
    let series: Vec<(String, Runs, &Markers)> = chart
        .series
        .iter()
        .map(|s| {
            let mut pts = s.points.clone();
            pts.sort_by(|a, b| a.0.total_cmp(&b.0));
            let mut runs: Vec<Vec<(f64, f64)>> = Vec::new();
            let mut cur = Vec::new();
            for (x, y) in pts {
                if x.is_finite() && y.is_finite() {
                    cur.push((x, y));
                } else if !cur.is_empty() {
                    runs.push(std::mem::take(&mut cur));
                }
            }
            if !cur.is_empty() {
                runs.push(cur);
            }
            (s.name.clone(), runs, &s.markers)
        })
        .collect();
    let finite = || series.iter().flat_map(|(_, r, _)| r.iter().flatten());
    let has_data = finite().next().is_some();
    let (mut x0, mut x1, mut y0, mut y1) = finite().fold(
        (
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::INFINITY,
            f64::NEG_INFINITY,
        ),
        |(a, b, c, d), &(x, y)| (a.min(x), b.max(x), c.min(y), d.max(y)),
    );
    if !has_data {
        (x0, x1, y0, y1) = (0.0, 1.0, 0.0, 1.0);
    }
    // Multipliers and ratios are positive: start the axis at 0 so lines compare honestly.
    if y0 > 0.0 {
        y0 = 0.0;
    }
    // Room around the data so end markers stay clear of the axes: 2 % each side in x, 6 %
    // above (and below, when negative) in y; a single value gets a range around it.
    let widen = |lo: f64, hi: f64| {
        if hi > lo {
            (lo, hi)
        } else {
            let h = 0.5 * lo.abs().max(1.0);
            (lo - h, hi + h)
        }
    };
    (x0, x1) = widen(x0, x1);
    (x0, x1) = (x0 - 0.02 * (x1 - x0), x1 + 0.02 * (x1 - x0));
    (y0, y1) = widen(y0, y1);
    let dy = y1 - y0;
    (y0, y1) = (if y0 < 0.0 { y0 - 0.06 * dy } else { y0 }, y1 + 0.06 * dy);

    if ![x0, x1, y0, y1].iter().all(|v| v.is_finite()) {
        return Err(SvgError::Invalid(
            "the values span more than a finite range".into(),
        ));
    }

    // The legend column to the right of the plot.
    let mut entries: Vec<(Glyph, String)> = Vec::new();
    for (k, (name, _, markers)) in series.iter().enumerate() {
        let colour = PALETTE[k % PALETTE.len()];
        let glyph = match markers {
            Markers::At(at) if at.is_empty() => Glyph::Line(colour, 2, false),
            _ => Glyph::Marked(colour),
        };
        entries.push((glyph, name.clone()));
    }
    let legend_w = entries
        .iter()
        .map(|(_, t)| text_width(t, 14.0) + 76.0)
        .chain(
            chart
                .legend_title
                .iter()
                .map(|t| text_width(t, 15.0) + 30.0),
        )
        .fold(0.0, f64::max)
        .clamp(120.0, 340.0);
    let plot_w = WIDTH - legend_w.ceil() as u32;
    // One entry per row: give each entry the whole column width.
    let slots: Vec<_> = entries
        .iter()
        .enumerate()
        .map(|(k, _)| Slot { row: k, x: 0.0 })
        .collect();

    let mut svg = Layers::new(WIDTH, HEIGHT);
    svg.layer("background", |root| root.fill(&WHITE).map_err(plot_err))?;

    svg.layer("axes", |root| {
        let (left, _) = root.split_horizontally(plot_w);
        let mut c = builder(&left, chart, (x0..x1, y0..y1))?;
        let label = TextStyle::from(("sans-serif", font_size(13.0)).into_font());
        let desc = TextStyle::from(("sans-serif", font_size(16.0)).into_font());
        c.configure_mesh()
            .x_desc(chart.x_label.clone())
            .y_desc(chart.y_label.clone())
            .label_style(label)
            .axis_desc_style(desc)
            .light_line_style(INVISIBLE)
            .bold_line_style(RGBColor(0xDD, 0xDD, 0xDD))
            .draw()
            .map_err(plot_err)?;
        if !has_data {
            let style = TextStyle::from(("sans-serif", font_size(16.0)).into_font());
            c.plotting_area()
                .draw(&Text::new(
                    "no finite values to plot".to_string(),
                    (x0 + 0.05 * (x1 - x0), y0 + 0.5 * (y1 - y0)),
                    style,
                ))
                .map_err(plot_err)?;
        }
        Ok(())
    })?;
    for (k, (_, runs, markers)) in series.iter().enumerate() {
        let colour = PALETTE[k % PALETTE.len()];
        svg.layer_class(&format!("series-{k}"), "series", |root| {
            let (left, _) = root.split_horizontally(plot_w);
            let mut c = builder(&left, chart, (x0..x1, y0..y1))?;
            for run in runs {
                if run.len() > 1 {
                    c.draw_series(LineSeries::new(run.iter().copied(), colour.stroke_width(2)))
                        .map_err(plot_err)?;
                }
                if let Markers::Every = markers {
                    c.draw_series(run.iter().map(|&p| Circle::new(p, 3, colour.filled())))
                        .map_err(plot_err)?;
                }
            }
            if let Markers::At(at) = markers {
                let inside =
                    |&(x, y): &(f64, f64)| (x0..=x1).contains(&x) && (y0..=y1).contains(&y);
                c.draw_series(
                    at.iter()
                        .copied()
                        .filter(inside)
                        .map(|p| Circle::new(p, 4, colour.filled())),
                )
                .map_err(plot_err)?;
            }
            Ok(())
        })?;
    }
    if !chart.title.is_empty() {
        // Centred on the canvas (not on the plot, whose centre sits left of the canvas's:
        // a long title would start left of it), in a smaller font when it is too wide.
        let px = fit_px(&chart.title, TITLE_PX, true, WIDTH as f64 - 32.0, 8.0);
        svg.layer("title", |root| {
            let style = TextStyle::from(
                ("sans-serif", font_size(px))
                    .into_font()
                    .style(FontStyle::Bold),
            )
            .color(&TEXT)
            .pos(Pos::new(HPos::Center, VPos::Top));
            root.draw(&Text::new(
                chart.title.clone(),
                ((WIDTH / 2) as i32, TITLE_TOP),
                style,
            ))
            .map_err(plot_err)
        })?;
    }
    svg.layer("legend", |root| {
        let left = plot_w as f64 + 4.0;
        let mut top = 60.0;
        if let Some(t) = &chart.legend_title {
            let style = TextStyle::from(
                ("sans-serif", font_size(15.0))
                    .into_font()
                    .style(FontStyle::Bold),
            )
            .color(&TEXT);
            root.draw(&Text::new(t.clone(), (left as i32, top as i32), style))
                .map_err(plot_err)?;
            top += 24.0;
        }
        // A thin frame around the entries.
        let h = entries.len() as f64 * super::svg::LEGEND_ROW;
        if !entries.is_empty() {
            root.draw(&PathElement::new(
                vec![
                    ((left - 6.0) as i32, (top - 4.0) as i32),
                    ((WIDTH - 10) as i32, (top - 4.0) as i32),
                    ((WIDTH - 10) as i32, (top + h + 4.0) as i32),
                    ((left - 6.0) as i32, (top + h + 4.0) as i32),
                    ((left - 6.0) as i32, (top - 4.0) as i32),
                ],
                RGBColor(0xB0, 0xB0, 0xB0).stroke_width(1),
            ))
            .map_err(plot_err)?;
        }
        draw_legend(root, &entries, &slots, left, top)
    })?;
    Ok(svg.finish(&chart.title))
}

/// Transparent: the backend writes no element for it.
const INVISIBLE: RGBAColor = RGBAColor(255, 255, 255, 0.0);

/// Font size (px) of the title, and its top (px).
const TITLE_PX: f64 = 20.0;
const TITLE_TOP: i32 = 18;

/// The chart's coordinate system on `area`. Every pass builds it the same way, so all passes
/// share one mapping; the caption is invisible: it only takes the title's room, the title is
/// drawn on its own (centred on the canvas).
fn builder<'a, 'b>(
    area: &'a Root<'b>,
    chart: &Chart,
    (xr, yr): (std::ops::Range<f64>, std::ops::Range<f64>),
) -> Result<ChartContext<'a, SVGBackend<'b>, Cartesian2d<RangedCoordf64, RangedCoordf64>>, SvgError>
{
    let mut b = ChartBuilder::on(area);
    b.margin(16).x_label_area_size(56).y_label_area_size(72);
    if !chart.title.is_empty() {
        let font = ("sans-serif", font_size(TITLE_PX))
            .into_font()
            .style(FontStyle::Bold);
        b.caption(" ", TextStyle::from(font).color(&INVISIBLE));
    }
    b.build_cartesian_2d(xr, yr).map_err(plot_err)
}
