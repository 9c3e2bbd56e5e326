//! The SVG drawings: well-formed XML carrying the elements asked for, drawn to scale (one
//! scale for both axes), with the thrust line, hinges and displaced blocks where the analysis
//! puts them. Set `VOUSSOIR_SVG_DIR` to keep the pictures for looking at them.

use roxmltree::{Document, Node};
use voussoir::assembly::{Assembly, Hinge};
use voussoir::drawing::chart::{self, Chart, Series};
use voussoir::drawing::svg::{
    self, Drawing, Mechanism, Placements, SvgError, DASH, POINT_LOAD_SHARE,
};
use voussoir::drawing::thrust_points;
use voussoir::geometry::Vec2;
use voussoir::model::{LoadSource, Model};
use voussoir::scene::Scene;
use voussoir::statics::{self, Direction, StaticResult, StaticSettings, Status};

fn scene(text: &str) -> Scene {
    Scene::from_toml_str(text, "test").expect("valid scene")
}

fn semicircle(t: f64, n: usize) -> Model {
    voussoir::scene::build(&scene(&format!(
        "[arch]\nshape = \"circular\"\nradius = 1.0\nthickness = {t}\nvoussoirs = {n}\n"
    )))
    .expect("valid model")
}

fn portal() -> Model {
    voussoir::scene::build(&scene(
        "[arch]\nshape = \"circular\"\nradius = 1.0\nthickness = 0.15\nvoussoirs = 16\n\
         [piers]\nheight = 1.2\nwidth = 0.35\ncourses = 2\n",
    ))
    .expect("valid model")
}

fn analyse(m: &Model) -> StaticResult {
    let r = statics::analyse(m, &StaticSettings::default()).expect("analysis runs");
    assert_eq!(r.status, Status::Collapse);
    r
}

/// Write the picture where the developer asked, then parse it.
fn keep(name: &str, text: &str) {
    if let Ok(dir) = std::env::var("VOUSSOIR_SVG_DIR") {
        std::fs::write(std::path::Path::new(&dir).join(name), text).expect("write picture");
    }
}

fn group<'a, 'i>(doc: &'a Document<'i>, id: &str) -> Node<'a, 'i> {
    doc.descendants()
        .find(|n| n.has_tag_name("g") && n.attribute("id") == Some(id))
        .unwrap_or_else(|| panic!("no group {id}"))
}

fn children<'a, 'i>(g: Node<'a, 'i>, tag: &str) -> Vec<Node<'a, 'i>> {
    g.children().filter(|n| n.has_tag_name(tag)).collect()
}

fn points(n: &Node) -> Vec<(f64, f64)> {
    n.attribute("points")
        .expect("points")
        .split_whitespace()
        .map(|p| {
            let (x, y) = p.split_once(',').expect("x,y");
            (x.parse().expect("x"), y.parse().expect("y"))
        })
        .collect()
}

fn texts(doc: &Document) -> Vec<String> {
    doc.descendants()
        .filter(|n| n.has_tag_name("text"))
        .filter_map(|n| n.text().map(|t| t.trim().to_string()))
        .collect()
}

fn attr_f(n: &Node, a: &str) -> f64 {
    n.attribute(a).expect("attribute").parse().expect("number")
}

/// The world-to-pixel map of a structure drawing, `(x0, y0, s)` with `px = x0 + s x`,
/// `py = y0 - s y`, fitted by least squares to every block corner and then checked on each:
/// one scale for both axes, i.e. the blocks are drawn to scale.
fn fit_frame(doc: &Document, a: &Assembly) -> (f64, f64, f64) {
    let polys = children(group(doc, "blocks"), "polygon");
    assert_eq!(polys.len(), a.blocks.len(), "one polygon per block");
    let pairs: Vec<((f64, f64), Vec2)> = polys
        .iter()
        .zip(&a.blocks)
        .flat_map(|(poly, b)| {
            let drawn = points(poly);
            assert_eq!(drawn.len(), b.polygon.len());
            drawn.into_iter().zip(b.polygon.iter().copied())
        })
        .collect();
    let n = pairs.len() as f64;
    // A drawn point and the corner it stands for.
    type Pair = ((f64, f64), Vec2);
    let mean = |f: &dyn Fn(&Pair) -> f64| pairs.iter().map(f).sum::<f64>() / n;
    let (px, py) = (mean(&|q| q.0 .0), mean(&|q| q.0 .1));
    let (wx, wy) = (mean(&|q| q.1.x), mean(&|q| q.1.y));
    let num: f64 = pairs
        .iter()
        .map(|((x, y), w)| (w.x - wx) * (x - px) - (w.y - wy) * (y - py))
        .sum();
    let den: f64 = pairs
        .iter()
        .map(|(_, w)| (w.x - wx).powi(2) + (w.y - wy).powi(2))
        .sum();
    let s = num / den;
    let (x0, y0) = (px - s * wx, py + s * wy);
    for ((x, y), w) in &pairs {
        let e = (x0 + s * w.x, y0 - s * w.y);
        // Whole pixels: half a pixel of rounding, plus the fit's own error.
        assert!(
            near((*x, *y), e, 1.0),
            "corner {w:?} drawn at ({x}, {y}), expected {e:?}"
        );
    }
    (x0, y0, s)
}

fn near(p: (f64, f64), q: (f64, f64), tol: f64) -> bool {
    (p.0 - q.0).abs() <= tol && (p.1 - q.1).abs() <= tol
}

#[test]
fn semicircle_shows_blocks_thrust_line_hinges_and_mechanism() {
    let m = semicircle(0.15, 32);
    let a = &m.assembly;
    let r = analyse(&m);
    let forces = r.forces.as_deref().expect("forces at collapse");
    let d = Drawing {
        title: format!(
            "semicircular arch, t/R = 0.15, 32 voussoirs\nlambda = {:.4}",
            r.lambda.unwrap_or(f64::NAN)
        ),
        forces: Some(forces),
        hinges: &r.hinges,
        sliding: &r.sliding,
        mechanism: Some(Mechanism {
            velocities: &r.mechanism,
            amplification: None,
        }),
        load: Some(Direction::Right),
        ..Default::default()
    };
    let text = svg::structure_svg(a, &d).expect("drawing");
    keep("semicircle.svg", &text);
    let doc = Document::parse(&text).expect("well-formed XML");
    assert!(doc.root_element().has_tag_name("svg"));

    // To scale: the outline spans 2 (R + t/2) by R + t/2.
    let (x0, y0, s) = fit_frame(&doc, a);
    let all: Vec<_> = children(group(&doc, "blocks"), "polygon")
        .iter()
        .flat_map(points)
        .collect();
    let w = all.iter().map(|p| p.0).fold(f64::MIN, f64::max)
        - all.iter().map(|p| p.0).fold(f64::MAX, f64::min);
    let h = all.iter().map(|p| p.1).fold(f64::MIN, f64::max)
        - all.iter().map(|p| p.1).fold(f64::MAX, f64::min);
    assert!((w / h - 2.0).abs() < 0.01, "aspect {w}/{h}");

    // The thrust line passes through the pressure point of every joint, in joint order.
    let lines = children(group(&doc, "thrust-line"), "polyline");
    assert_eq!(
        lines.len(),
        1,
        "every joint is compressed: one unbroken line"
    );
    let drawn = points(&lines[0]);
    let expected: Vec<Vec2> = thrust_points(a, forces).into_iter().flatten().collect();
    assert_eq!(drawn.len(), a.joints.len());
    for (p, q) in drawn.iter().zip(&expected) {
        assert!(
            near(*p, (x0 + s * q.x, y0 - s * q.y), 2.0),
            "{p:?} vs {q:?}"
        );
    }
    // No line of action: it lay under the thrust line, listed in the legend but unseen.
    assert!(doc
        .descendants()
        .all(|n| n.attribute("id") != Some("line-of-action")));

    // Four hinges, circles at the joint ends the analysis names.
    let circles = children(group(&doc, "hinges"), "circle");
    assert_eq!(r.hinges.len(), 4);
    assert_eq!(circles.len(), r.hinges.len());
    for (c, hg) in circles.iter().zip(&r.hinges) {
        let end = Hinge::at(a, hg.joint, hg.end);
        let c = (attr_f(c, "cx"), attr_f(c, "cy"));
        assert!(near(c, (x0 + s * end.x, y0 - s * end.y), 2.0));
    }

    // The mechanism: three rigid pieces between four hinges, each one dashed outline.
    let dashed = children(group(&doc, "mechanism"), "polyline");
    assert!(dashed
        .iter()
        .all(|p| p.attribute("stroke-dasharray") == Some(DASH)));
    assert_eq!(dashed.len(), 3, "one closed outline per moving piece");
    for p in &dashed {
        let pts = points(p);
        assert!(near(pts[0], pts[pts.len() - 1], 0.1), "outline is closed");
    }
    // Largest displacement 10 % of the size: the displaced corners reach at most that far
    // from the blocks' bounding box.
    let reach = 0.1 * a.size() * s + 1.0;
    let (minx, maxx) = all
        .iter()
        .fold((f64::MAX, f64::MIN), |(l, h), p| (l.min(p.0), h.max(p.0)));
    for p in dashed.iter().flat_map(points) {
        assert!(p.0 >= minx - reach && p.0 <= maxx + reach);
    }

    // The hinges are numbered 1..4 in chain order, each number beside its circle.
    let numbers = children(group(&doc, "hinge-numbers"), "text");
    assert_eq!(numbers.len(), 4);
    for (k, (t, c)) in numbers.iter().zip(&circles).enumerate() {
        assert_eq!(t.text(), Some((k + 1).to_string().as_str()));
        let d = (attr_f(t, "x") - attr_f(c, "cx")).hypot(attr_f(t, "y") - attr_f(c, "cy"));
        assert!(
            d > 8.0 && d < 25.0,
            "number {} at {d} px from its hinge",
            k + 1
        );
    }
    assert!(r.hinges.windows(2).all(|w| w[0].joint < w[1].joint));

    let t = texts(&doc);
    for want in [
        "thrust line",
        "hinge (4), numbered along the chain",
        "support",
    ] {
        assert!(t.iter().any(|s| s == want), "legend lacks {want}: {t:?}");
    }
    assert!(!t.iter().any(|s| s.contains("line of action")));
    // The default factor shrinks the virtual displacements here: the legend says so.
    assert!(
        t.iter().any(
            |s| s.starts_with("collapse mechanism, displacements scaled x0.")
                && s.contains("10% of size")
        ),
        "{t:?}"
    );
    assert!(!t.iter().any(|s| s.contains("amplified")));
    assert_inside_canvas(&doc);
    assert!(t.iter().any(|s| s.starts_with("semicircular arch")));
    assert_eq!(
        doc.descendants()
            .find(|n| n.has_tag_name("title"))
            .and_then(|n| n.text()),
        Some(d.title.as_str())
    );
}

#[test]
fn portal_shows_piers_supports_and_its_mechanism() {
    let m = portal();
    let a = &m.assembly;
    let r = analyse(&m);
    let d = Drawing {
        title: "portal".into(),
        forces: r.forces.as_deref(),
        hinges: &r.hinges,
        sliding: &r.sliding,
        mechanism: Some(Mechanism {
            velocities: &r.mechanism,
            amplification: None,
        }),
        ..Default::default()
    };
    let text = svg::structure_svg(a, &d).expect("drawing");
    keep("portal.svg", &text);
    let doc = Document::parse(&text).expect("well-formed XML");
    let (_, y0, s) = fit_frame(&doc, a);
    assert_eq!(a.blocks.len(), 16 + 2 * 2);

    // Two supports (the pier bases at y = -1.2), hatched below the base.
    let base = y0 + s * 1.2;
    let strokes = children(group(&doc, "supports"), "polyline");
    assert!(
        strokes.len() >= 2 * 4,
        "a ground line and hatching per support"
    );
    for p in strokes.iter().flat_map(points) {
        assert!(p.1 >= base - 1.0, "hatching at {p:?} above the base {base}");
    }
    assert!(strokes.iter().flat_map(points).any(|p| p.1 > base + 5.0));

    assert_eq!(
        children(group(&doc, "hinges"), "circle").len(),
        r.hinges.len()
    );
    assert!(r.hinges.len() >= 3);
    let dashed = children(group(&doc, "mechanism"), "polyline");
    assert!(!dashed.is_empty());
    assert!(dashed.len() < a.blocks.len(), "pieces, not blocks");
    assert_eq!(children(group(&doc, "thrust-line"), "polyline").len(), 1);
}

#[test]
fn second_positions_are_the_blocks_moved_rigidly() {
    let m = semicircle(0.2, 8);
    let a = &m.assembly;
    let moves: Vec<(Vec2, f64)> = (0..8)
        .map(|i| (Vec2::new(0.03 * i as f64, -0.02), 0.05 * i as f64))
        .collect();
    let d = Drawing {
        title: "DEM: initial and final positions".into(),
        moved: Some(Placements {
            moves: &moves,
            label: "final positions".into(),
        }),
        ..Default::default()
    };
    let text = svg::structure_svg(a, &d).expect("drawing");
    keep("dem.svg", &text);
    let doc = Document::parse(&text).expect("well-formed XML");
    let (x0, y0, s) = fit_frame(&doc, a);
    let moved = children(group(&doc, "moved-blocks"), "polygon");
    assert_eq!(moved.len(), 8);
    for ((poly, b), (t, th)) in moved.iter().zip(&a.blocks).zip(&moves) {
        for (p, q) in points(poly).iter().zip(&b.polygon) {
            let r = q - b.centroid;
            let m = b.centroid
                + t
                + Vec2::new(
                    th.cos() * r.x - th.sin() * r.y,
                    th.sin() * r.x + th.cos() * r.y,
                );
            let e = (x0 + s * m.x, y0 - s * m.y);
            assert!(near(*p, e, 2.0), "{p:?} vs {e:?}");
        }
    }
    assert!(texts(&doc).iter().any(|t| t == "final positions"));
}

#[test]
fn drawing_rejects_data_that_do_not_fit_the_assembly() {
    let m = semicircle(0.15, 8);
    let a = &m.assembly;
    let r = analyse(&m);
    let forces = r.forces.as_deref().expect("forces");
    let short = Drawing {
        forces: Some(&forces[1..]),
        ..Drawing::new("x")
    };
    assert!(matches!(
        svg::structure_svg(a, &short),
        Err(SvgError::Invalid(_))
    ));
    let v = vec![[0.0, 0.0, 1.0]; 3];
    let wrong = Drawing {
        mechanism: Some(Mechanism {
            velocities: &v,
            amplification: None,
        }),
        ..Drawing::new("x")
    };
    assert!(matches!(
        svg::structure_svg(a, &wrong),
        Err(SvgError::Invalid(_))
    ));
    let bad = Drawing {
        sliding: &[99],
        ..Drawing::new("x")
    };
    assert!(matches!(
        svg::structure_svg(a, &bad),
        Err(SvgError::Invalid(_))
    ));
}

#[test]
fn draw_structure_writes_the_file() {
    let m = semicircle(0.15, 8);
    let a = &m.assembly;
    let dir = tempfile::tempdir().expect("temp dir");
    let path = dir.path().join("a.svg");
    let title = "blocks only: t < R & \"quoted\"";
    svg::draw_structure(&path, a, &Drawing::new(title)).expect("written");
    let text = std::fs::read_to_string(&path).expect("read back");
    let doc = Document::parse(&text).expect("well-formed XML");
    assert!(
        texts(&doc).iter().any(|t| t == title),
        "title escaped and kept"
    );
    assert_eq!(children(group(&doc, "blocks"), "polygon").len(), 8);
    let missing = dir.path().join("no/such/dir/a.svg");
    assert!(matches!(
        svg::draw_structure(&missing, a, &Drawing::new("x")),
        Err(SvgError::Io { .. })
    ));
}

fn study() -> Chart {
    let ts = [0.10, 0.125, 0.15, 0.175, 0.20];
    Chart {
        title: "circular arches".into(),
        x_label: "t/R".into(),
        y_label: "lambda_c".into(),
        legend_title: Some("embrace_deg".into()),
        series: vec![
            Series::new("180", ts.iter().map(|&t| (t, Some(2.0 * (t - 0.08))))),
            // A case that cannot stand breaks the line.
            Series::new(
                "150",
                ts.iter()
                    .enumerate()
                    .map(|(i, &t)| (t, (i != 2).then_some(3.0 * (t - 0.05)))),
            ),
            Series::new("120", ts.iter().map(|&t| (t, Some(4.0 * t)))),
        ],
    }
}

#[test]
fn chart_has_axes_lines_breaks_and_legend() {
    let c = study();
    let text = chart::chart_svg(&c).expect("chart");
    keep("chart.svg", &text);
    let doc = Document::parse(&text).expect("well-formed XML");
    let series: Vec<_> = doc
        .descendants()
        .filter(|n| n.has_tag_name("g") && n.attribute("class") == Some("series"))
        .collect();
    assert_eq!(series.len(), 3);
    let runs: Vec<usize> = series
        .iter()
        .map(|g| children(*g, "polyline").len())
        .collect();
    assert_eq!(
        runs,
        vec![1, 2, 1],
        "the missing point breaks the second line"
    );
    let markers: Vec<usize> = series
        .iter()
        .map(|g| children(*g, "circle").len())
        .collect();
    assert_eq!(markers, vec![5, 4, 5]);
    // Each line has its own colour.
    let colours: std::collections::BTreeSet<_> = series
        .iter()
        .map(|g| {
            children(*g, "polyline")[0]
                .attribute("stroke")
                .map(str::to_string)
        })
        .collect();
    assert_eq!(colours.len(), 3);
    // A larger y is drawn higher: the 120 line (4 t) ends above the 180 line (2 (t - 0.08)).
    let last_y = |g: &Node| {
        let p = points(&children(*g, "polyline")[0]);
        p[p.len() - 1].1
    };
    assert!(last_y(&series[2]) < last_y(&series[0]));

    let t = texts(&doc);
    for want in [
        "circular arches",
        "t/R",
        "lambda_c",
        "embrace_deg",
        "180",
        "150",
        "120",
    ] {
        assert!(t.iter().any(|s| s == want), "missing text {want}: {t:?}");
    }
    // Tick labels on both axes.
    assert!(t.iter().filter(|s| s.parse::<f64>().is_ok()).count() >= 6);
}

#[test]
fn chart_without_values_still_draws_and_says_so() {
    let c = Chart {
        title: "nothing stands".into(),
        x_label: "x".into(),
        y_label: "y".into(),
        series: vec![Series::new("a", [(1.0, None), (2.0, None)])],
        ..Default::default()
    };
    let dir = tempfile::tempdir().expect("temp dir");
    let path = dir.path().join("c.svg");
    chart::draw_lines(&path, &c).expect("written");
    let text = std::fs::read_to_string(&path).expect("read back");
    let doc = Document::parse(&text).expect("well-formed XML");
    assert!(texts(&doc).iter().any(|t| t == "no finite values to plot"));
}

/// Shapes, portals, both load directions, friction, 1000 voussoirs: the drawing carries one
/// element per block, hinge and sliding joint, the thrust line on the joints, and, for a
/// four-hinge mechanism, one closed dashed outline per moving rigid piece (three).
#[test]
fn every_kind_of_structure_draws() {
    let cases = [
        ("circular-1000", "[arch]\nshape = \"circular\"\nradius = 1.0\nthickness = 0.15\nvoussoirs = 1000\n", Direction::Right),
        ("circular-200-thin", "[arch]\nshape = \"circular\"\nradius = 1.0\nthickness = 0.1075\nvoussoirs = 200\n", Direction::Right),
        ("segmental", "[arch]\nshape = \"circular\"\nradius = 1.0\nembrace_deg = 120\nthickness = 0.1\nvoussoirs = 30\n", Direction::Right),
        ("pointed-left", "[arch]\nshape = \"pointed\"\nradius = 1.0\neccentricity = 0.3\nthickness = 0.12\nvoussoirs = 40\n", Direction::Left),
        ("basket", "[arch]\nshape = \"basket\"\nspan = 3.0\nrise = 0.9\nthickness = 0.2\nvoussoirs = 25\n", Direction::Right),
        ("portal-friction", "[arch]\nshape = \"circular\"\nradius = 1.0\nthickness = 0.15\nvoussoirs = 12\n[piers]\nheight = 2.5\nwidth = 0.6\ncourses = 6\n[material]\nfriction = 0.42\n", Direction::Right),
    ];
    let mut slid = 0;
    for (name, text, dir) in cases {
        let m = voussoir::scene::build(&scene(text)).expect("valid model");
        let a = &m.assembly;
        let r = statics::analyse(&m, &StaticSettings::default().direction(dir)).expect("runs");
        assert_eq!(r.status, Status::Collapse, "{name}");
        let forces = r.forces.as_deref().expect("forces");
        let d = Drawing {
            title: format!("{name}\nlambda = {:.4}", r.lambda.unwrap_or(f64::NAN)),
            forces: Some(forces),
            hinges: &r.hinges,
            sliding: &r.sliding,
            mechanism: Some(Mechanism {
                velocities: &r.mechanism,
                amplification: None,
            }),
            load: Some(dir),
            ..Default::default()
        };
        let text = svg::structure_svg(a, &d).expect("drawing");
        keep(&format!("{name}.svg"), &text);
        let doc = Document::parse(&text).expect("well-formed XML");
        assert_inside_canvas(&doc);
        let (x0, y0, s) = fit_frame(&doc, a);

        // Every drawn pressure point lies on its joint (within the pixel rounding).
        let line: Vec<_> = children(group(&doc, "thrust-line"), "polyline")
            .iter()
            .flat_map(points)
            .collect();
        let on_joints: Vec<_> = a
            .joints
            .iter()
            .zip(thrust_points(a, forces))
            .filter_map(|(j, p)| p.map(|_| j))
            .collect();
        assert_eq!(line.len(), on_joints.len(), "{name}");
        for (p, j) in line.iter().zip(on_joints) {
            let w = Vec2::new((p.0 - x0) / s, (y0 - p.1) / s);
            let u = j.tangent();
            let along = (w - j.p1).dot(&u);
            let off = (w - j.p1 - along * u).norm() * s;
            assert!(off <= 1.5, "{name}: pressure point {off} px off its joint");
            assert!(along >= -1.5 / s && along <= j.length() + 1.5 / s, "{name}");
        }
        assert_eq!(
            children(group(&doc, "hinges"), "circle").len(),
            r.hinges.len(),
            "{name}"
        );
        if !r.sliding.is_empty() {
            slid += 1;
            assert_eq!(
                children(group(&doc, "sliding"), "polyline").len(),
                r.sliding.len()
            );
        }
        let dashed = children(group(&doc, "mechanism"), "polyline");
        assert!(!dashed.is_empty(), "{name}");
        if r.sliding.is_empty() && r.hinges.len() == 4 {
            assert_eq!(dashed.len(), 3, "{name}: three moving pieces");
            for p in &dashed {
                let pts = points(p);
                assert!(near(pts[0], pts[pts.len() - 1], 0.1), "{name}: closed");
            }
        }
    }
    assert!(slid > 0, "the friction case slides");
}

/// Every text's estimated extent lies inside the canvas: a generous width (0.6 em per
/// character, 0.66 em bold) placed by its anchor, its height from its baseline shift;
/// labels rotated by 270 degrees (the y axis title) turned accordingly.
fn assert_inside_canvas(doc: &Document) {
    let svg = doc.root_element();
    let (w, h) = (attr_f(&svg, "width"), attr_f(&svg, "height"));
    for n in doc.descendants().filter(|n| n.has_tag_name("text")) {
        let Some(s) = n.text().map(str::trim).filter(|s| !s.is_empty()) else {
            continue;
        };
        let fs = attr_f(&n, "font-size");
        let bold = n.attribute("font-weight") == Some("bold");
        let tw = if bold { 0.66 } else { 0.6 } * fs * s.chars().count() as f64;
        let (x, y) = (attr_f(&n, "x"), attr_f(&n, "y"));
        let (a, b) = match n.attribute("text-anchor") {
            Some("middle") => (-0.5 * tw, 0.5 * tw),
            Some("end") => (-tw, 0.0),
            _ => (0.0, tw),
        };
        let dy = n.attribute("dy").map_or(0.0, |d| {
            if let Some(v) = d.strip_suffix("em") {
                v.parse::<f64>().expect("dy") * fs
            } else if let Some(v) = d.strip_suffix("ex") {
                v.parse::<f64>().expect("dy") * 0.5 * fs
            } else {
                d.parse().expect("dy")
            }
        });
        // Across the text: from 0.8 em above its baseline to 0.25 em below.
        let (above, below) = (dy - 0.8 * fs, dy + 0.25 * fs);
        let (left, right, top, bottom) = match n.attribute("transform") {
            Some(t) if t.starts_with("rotate(270") => (x + above, x + below, y - b, y - a),
            Some(t) => panic!("unexpected transform {t}"),
            None => (x + a, x + b, y + above, y + below),
        };
        assert!(
            left >= 0.0 && right <= w && top >= 0.0 && bottom <= h,
            "text {s:?} spans x {left:.0}..{right:.0}, y {top:.0}..{bottom:.0} on a {w} x {h} canvas"
        );
    }
}

fn model_of(text: &str) -> Model {
    voussoir::scene::build(&scene(text)).expect("valid model")
}

const SEMI: &str = "[arch]\nshape = \"circular\"\nradius = 1.0\nthickness = 0.15\nvoussoirs = 32\n";
const PORTAL: &str =
    "[arch]\nshape = \"circular\"\nradius = 1.0\nthickness = 0.15\nvoussoirs = 16\n\
     [piers]\nheight = 1.2\nwidth = 0.35\ncourses = 2\n";

/// A drawing of everything an analysis gives, with the loads of `m`.
fn full_drawing<'a>(title: &str, m: &'a Model, r: &'a StaticResult, dir: Direction) -> Drawing<'a> {
    Drawing {
        title: title.into(),
        forces: r.forces.as_deref(),
        hinges: &r.hinges,
        sliding: &r.sliding,
        mechanism: (!r.mechanism.is_empty()).then_some(Mechanism {
            velocities: &r.mechanism,
            amplification: None,
        }),
        load: Some(dir),
        loads: Some(&m.loads),
        ..Default::default()
    }
}

fn draw(name: &str, m: &Model, dir: Direction, title: &str) -> (StaticResult, String) {
    let r = statics::analyse(m, &StaticSettings::default().direction(dir)).expect("analysis runs");
    let text = svg::structure_svg(&m.assembly, &full_drawing(title, m, &r, dir)).expect("drawing");
    keep(name, &text);
    (r, text)
}

/// Ids of the top-level groups, in drawing order.
fn layer_order(doc: &Document) -> Vec<String> {
    doc.root_element()
        .children()
        .filter_map(|n| n.attribute("id").map(str::to_string))
        .collect()
}

fn head_tips(g: Node) -> Vec<(f64, f64)> {
    g.descendants()
        .filter(|n| n.has_tag_name("polygon") && n.attribute("class") == Some("arrow-head"))
        .map(|n| points(&n)[0])
        .collect()
}

#[test]
fn fill_is_a_shaded_region_behind_the_blocks() {
    let m = model_of(&format!("{SEMI}[fill]\nlevel = 1.3\n"));
    let (_, text) = draw(
        "fill.svg",
        &m,
        Direction::Right,
        "semicircle with fill to 1.3 m",
    );
    let doc = Document::parse(&text).expect("well-formed XML");
    let (x0, y0, s) = fit_frame(&doc, &m.assembly);
    let regions: Vec<&Vec<Vec2>> = m
        .loads
        .applied()
        .iter()
        .filter(|a| a.source == LoadSource::Fill)
        .filter_map(|a| a.region.as_ref())
        .collect();
    assert_eq!(regions.len(), 32, "every voussoir carries fill");
    let fill = group(&doc, "fill");
    let polys: Vec<_> = children(fill, "polygon")
        .into_iter()
        .filter(|p| p.attribute("class") == Some("fill-region"))
        .collect();
    assert_eq!(polys.len(), regions.len(), "one shaded polygon per region");
    for (p, reg) in polys.iter().zip(&regions) {
        let drawn = points(p);
        assert_eq!(drawn.len(), reg.len());
        for (d, w) in drawn.iter().zip(reg.iter()) {
            assert!(
                near(*d, (x0 + s * w.x, y0 - s * w.y), 1.0),
                "{d:?} vs {w:?}"
            );
        }
    }
    // One colour, the stroke the same as the fill: no lines between the pieces.
    let styles: std::collections::BTreeSet<_> = polys
        .iter()
        .map(|p| (p.attribute("fill"), p.attribute("stroke")))
        .collect();
    assert_eq!(styles.len(), 1);
    let (f, st) = styles.into_iter().next().expect("one style");
    assert_eq!(f, st);
    // Hatched over the whole.
    assert!(children(fill, "path")
        .iter()
        .any(|p| p.attribute("fill") == Some("url(#fill-hatch)")));
    assert!(fill.descendants().any(|n| n.has_tag_name("pattern")));
    // Behind the blocks.
    let order = layer_order(&doc);
    let at = |id: &str| order.iter().position(|g| g == id).expect(id);
    assert!(at("fill") < at("blocks"), "{order:?}");
    // The union's outline reaches the level, y = 1.3.
    let outline: Vec<_> = children(fill, "polyline").iter().flat_map(points).collect();
    assert!(!outline.is_empty());
    let top = outline.iter().map(|p| p.1).fold(f64::MAX, f64::min);
    assert!((top - (y0 - 1.3 * s)).abs() < 1.0, "outline top {top}");
    assert!(texts(&doc).iter().any(|t| t == "fill up to y = 1.3 m"));
    assert_inside_canvas(&doc);
}

#[test]
fn point_loads_are_arrows_ending_at_their_points() {
    let thick = "[arch]\nshape = \"circular\"\nradius = 1.0\nthickness = 0.25\nvoussoirs = 16\n\
                 [piers]\nheight = 1.2\nwidth = 0.5\ncourses = 2\n";
    let m = model_of(&format!(
        "{thick}[[loads]]\ntype = \"point\"\nat = [0.3, 0.95]\nforce = [0.0, -2000.0]\n\
         [[loads]]\ntype = \"point\"\nat = [-0.6, 0.75]\nforce = [500.0, 0.0]\n"
    ));
    let (r, text) = draw(
        "point-loads.svg",
        &m,
        Direction::Right,
        "portal with point loads",
    );
    assert_eq!(r.status, Status::Collapse);
    let doc = Document::parse(&text).expect("well-formed XML");
    let (x0, y0, s) = fit_frame(&doc, &m.assembly);
    let arrows: Vec<_> = group(&doc, "point-loads")
        .children()
        .filter(|n| n.attribute("class") == Some("point-load"))
        .collect();
    assert_eq!(arrows.len(), 2);
    let size = m.assembly.size();
    for (g, (at, force, label)) in arrows.iter().zip([
        (Vec2::new(0.3, 0.95), Vec2::new(0.0, -2000.0), "2 kN"),
        (Vec2::new(-0.6, 0.75), Vec2::new(500.0, 0.0), "0.5 kN"),
    ]) {
        let tip = head_tips(*g)[0];
        assert!(
            near(tip, (x0 + s * at.x, y0 - s * at.y), 1.0),
            "arrow ends at {tip:?}, the load acts at {at:?}"
        );
        // The shaft starts at the tail: against the force, the largest 15 % of the size
        // long, the other in proportion (0.5 / 2 >= 0.2, the shortest drawn in proportion).
        let line = children(*g, "line")[0];
        let tail = (attr_f(&line, "x1"), attr_f(&line, "y1"));
        let len = POINT_LOAD_SHARE * size * force.norm() / 2000.0 * s;
        let d = force / force.norm();
        let expected = (tip.0 - len * d.x, tip.1 + len * d.y);
        assert!(near(tail, expected, 1.0), "{tail:?} vs {expected:?}");
        assert_eq!(children(*g, "text")[0].text(), Some(label));
    }
    let t = texts(&doc);
    assert!(t.iter().any(|s| s == "point load"), "{t:?}");
    assert_inside_canvas(&doc);
}

#[test]
fn line_loads_are_a_row_of_arrows_labelled_with_their_intensity() {
    let m = model_of(&format!(
        "{SEMI}[[loads]]\ntype = \"line\"\nfrom_x = -0.4\nto_x = 0.4\nintensity = 3000.0\n"
    ));
    let (_, text) = draw(
        "line-load.svg",
        &m,
        Direction::Right,
        "semicircle, line load",
    );
    let doc = Document::parse(&text).expect("well-formed XML");
    let (x0, y0, s) = fit_frame(&doc, &m.assembly);
    let g = group(&doc, "line-loads");
    let rows: Vec<_> = g
        .children()
        .filter(|n| n.attribute("class") == Some("line-load"))
        .collect();
    assert_eq!(rows.len(), 1, "one row for the line load");
    let tips: Vec<Vec2> = head_tips(rows[0])
        .iter()
        .map(|p| Vec2::new((p.0 - x0) / s, (y0 - p.1) / s))
        .collect();
    assert!(tips.len() >= 5, "{} arrows", tips.len());
    // The arrows span the loaded length and end on the extrados (between the chords and
    // the circle through the extrados corners).
    let px = 1.5 / s;
    assert!((tips[0].x + 0.4).abs() < px && (tips[tips.len() - 1].x - 0.4).abs() < px);
    let re = 1.075;
    let chord = re * (std::f64::consts::PI / 64.0).cos();
    for t in &tips {
        assert!(t.norm() >= chord - px && t.norm() <= re + px, "tip {t:?}");
    }
    assert_eq!(
        children(rows[0], "text")[0].text(),
        Some("q = 3 kN/m"),
        "the intensity is recovered from the pieces"
    );
    assert!(texts(&doc).iter().any(|s| s == "line load"));
    assert_inside_canvas(&doc);
}

/// A point load spread through the fill by Boussinesq's law is not uniform: its arrows are
/// as long as the local intensity, longest under the load and shortest far from it, and its
/// label gives the total over the peak.
#[test]
fn a_load_spread_by_boussinesq_draws_its_bell_not_a_uniform_row() {
    let x_load = 0.3;
    let m = model_of(&format!(
        "{SEMI}[fill]\nlevel = 1.4\nunit_weight = 18000.0\nspread = \"boussinesq\"\n\
         [[loads]]\ntype = \"point\"\nat = [{x_load:?}, 1.4]\nforce = [0.0, -4000.0]\n"
    ));
    let (_, text) = draw(
        "boussinesq-load.svg",
        &m,
        Direction::Right,
        "semicircle, spread point load",
    );
    let doc = Document::parse(&text).expect("well-formed XML");
    let (x0, _, s) = fit_frame(&doc, &m.assembly);
    let g = group(&doc, "line-loads");
    let rows: Vec<_> = g
        .children()
        .filter(|n| n.attribute("class") == Some("line-load"))
        .collect();
    assert_eq!(rows.len(), 1, "one row for the spread load");
    // Each arrow: the tail (its shaft's first end) and the tip of its head, in metres.
    let tails: Vec<(f64, f64)> = rows[0]
        .descendants()
        .filter(|n| n.has_tag_name("line"))
        .map(|n| (attr_f(&n, "x1"), attr_f(&n, "y1")))
        .collect();
    let tips = head_tips(rows[0]);
    assert_eq!(tails.len(), tips.len());
    let arrows: Vec<(f64, f64)> = tails
        .iter()
        .zip(&tips)
        .map(|(t, p)| ((p.0 - x0) / s, (p.1 - t.1).abs() / s))
        .collect();
    assert!(arrows.len() >= 5, "{} arrows", arrows.len());
    let (peak_x, peak_len) = arrows
        .iter()
        .copied()
        .fold((0.0, 0.0), |a, b| if b.1 > a.1 { b } else { a });
    let shortest = arrows.iter().map(|a| a.1).fold(f64::INFINITY, f64::min);
    assert!(
        shortest < 0.5 * peak_len,
        "lengths vary: {shortest} against {peak_len}"
    );
    // The longest arrow stands near the load (within the arrows' spacing, about 0.1 m here).
    assert!(
        (peak_x - x_load).abs() < 0.15,
        "peak at x = {peak_x}, load at {x_load}"
    );
    // The label: the total the blocks carry (what of the bell falls beyond the springings
    // rests on the ground), over the peak.
    let label = children(rows[0], "text")[0];
    let words = label.text().unwrap_or_default();
    assert!(words.ends_with("kN in all"), "{words}");
    let total: f64 = m
        .loads
        .applied()
        .iter()
        .filter(|a| a.source == LoadSource::Load(0))
        .map(|a| a.force.norm())
        .sum();
    assert!(
        total > 0.9 * 4000.0 && total < 4000.0,
        "{total} N of 4000 N on the blocks"
    );
    let shown: f64 = words
        .trim_end_matches(" kN in all")
        .parse()
        .expect("a number");
    assert!(
        (shown - total / 1000.0).abs() <= 0.01 * total / 1000.0,
        "{shown} kN against {total} N"
    );
    assert!(
        ((attr_f(&label, "x") - x0) / s - peak_x).abs() < 0.15,
        "the label is over the peak"
    );
    assert_inside_canvas(&doc);
}

/// Whether pixel point `p` lies strictly inside the convex polygon `poly`.
fn strictly_inside(poly: &[(f64, f64)], p: (f64, f64)) -> bool {
    let n = poly.len();
    let side = |k: usize| {
        let (a, b) = (poly[k], poly[(k + 1) % n]);
        (b.0 - a.0) * (p.1 - a.1) - (b.1 - a.1) * (p.0 - a.0)
    };
    (0..n).all(|k| side(k) > 0.5) || (0..n).all(|k| side(k) < -0.5)
}

#[test]
fn seismic_load_direction_is_drawn_on_the_structure() {
    for (name, extra, dir, r) in [
        ("seismic-right.svg", "", Direction::Right, 0.0_f64),
        (
            "seismic-r03.svg",
            "[seismic]\nvertical_ratio = 0.3\n",
            Direction::Right,
            0.3,
        ),
        (
            "seismic-left-r-02.svg",
            "[seismic]\nvertical_ratio = -0.2\n",
            Direction::Left,
            -0.2,
        ),
    ] {
        let m = model_of(&format!("{SEMI}{extra}"));
        let (_, text) = draw(name, &m, dir, name);
        let doc = Document::parse(&text).expect("well-formed XML");
        let g = group(&doc, "seismic");
        let lines: Vec<_> = g.descendants().filter(|n| n.has_tag_name("line")).collect();
        let tips = head_tips(g);
        assert_eq!(tips.len(), if r == 0.0 { 1 } else { 2 }, "{name}");
        // The horizontal arrow points the way of the ground motion.
        let tail = (attr_f(&lines[0], "x1"), attr_f(&lines[0], "y1"));
        let along = tips[0].0 - tail.0;
        assert!((tips[0].1 - tail.1).abs() < 0.5, "{name}: horizontal");
        assert!(
            along * dir.sign() > 40.0,
            "{name}: {tail:?} -> {:?}",
            tips[0]
        );
        let t: Vec<String> = g
            .descendants()
            .filter(|n| n.has_tag_name("text"))
            .filter_map(|n| n.text().map(str::to_string))
            .collect();
        assert!(t.iter().any(|s| s == "\u{3bb}g"), "{name}: {t:?}");
        if r != 0.0 {
            // The vertical component from the same tail, up for r > 0.
            let tail2 = (attr_f(&lines[1], "x1"), attr_f(&lines[1], "y1"));
            assert!(near(tail, tail2, 0.5));
            assert!((tips[1].0 - tail.0).abs() < 0.5);
            assert!(
                (tips[1].1 - tail.1) * r.signum() < -10.0,
                "{name}: up when r > 0"
            );
            assert!(
                t.iter().any(|s| s.contains(&format!("r = {r}"))),
                "{name}: {t:?}"
            );
            assert!(texts(&doc)
                .iter()
                .any(|s| s.starts_with("seismic load") && s.contains(&format!("r = {r}"))));
        }
        // On the drawing, clear of the blocks.
        let blocks: Vec<Vec<(f64, f64)>> = children(group(&doc, "blocks"), "polygon")
            .iter()
            .map(points)
            .collect();
        let ends = lines
            .iter()
            .flat_map(|l| {
                [
                    (attr_f(l, "x1"), attr_f(l, "y1")),
                    (attr_f(l, "x2"), attr_f(l, "y2")),
                ]
            })
            .chain(tips.iter().copied());
        for p in ends {
            assert!(
                blocks.iter().all(|b| !strictly_inside(b, p)),
                "{name}: arrow point {p:?} inside a block"
            );
        }
        assert_inside_canvas(&doc);
    }
}

#[test]
fn scale_bar_has_a_round_length_to_scale() {
    for (text, want) in [
        (SEMI.to_string(), 0.5),
        (PORTAL.to_string(), 0.5),
        (
            SEMI.replace("radius = 1.0", "radius = 12.0")
                .replace("0.15", "1.8"),
            5.0,
        ),
    ] {
        let m = model_of(&text);
        let r = analyse(&m);
        let out = svg::structure_svg(&m.assembly, &full_drawing("x", &m, &r, Direction::Right))
            .expect("drawing");
        let doc = Document::parse(&out).expect("well-formed XML");
        let (_, _, s) = fit_frame(&doc, &m.assembly);
        let g = group(&doc, "scale-bar");
        let bar = children(g, "rect")
            .into_iter()
            .find(|r| r.attribute("class") == Some("scale-bar"))
            .expect("the bar");
        let label = children(g, "text")[0].text().expect("label").to_string();
        let metres: f64 = label
            .strip_suffix(" m")
            .expect("in metres")
            .parse()
            .expect("number");
        assert_eq!(metres, want, "{label}");
        assert!(
            (attr_f(&bar, "width") - metres * s).abs() < 0.05,
            "bar {} px for {label} at {s} px/m",
            attr_f(&bar, "width")
        );
        assert_inside_canvas(&doc);
    }
}

#[test]
fn mechanism_legend_says_amplified_only_when_it_is() {
    let m = semicircle(0.15, 8);
    let r = analyse(&m);
    let d = Drawing {
        mechanism: Some(Mechanism {
            velocities: &r.mechanism,
            amplification: Some(3.0),
        }),
        ..Drawing::new("x")
    };
    let doc_text = svg::structure_svg(&m.assembly, &d).expect("drawing");
    let doc = Document::parse(&doc_text).expect("well-formed XML");
    let t = texts(&doc);
    assert!(
        t.iter()
            .any(|s| s.starts_with("collapse mechanism, displacements amplified x3 (")),
        "{t:?}"
    );
}

#[test]
fn long_titles_stay_inside_the_canvas() {
    let mut c = study();
    c.title = "basket-handle arches, rise/span = 0.3, side angle 60 deg: lambda_c against \
               t/span for every number of voussoirs"
        .into();
    let text = chart::chart_svg(&c).expect("chart");
    keep("chart-long-title.svg", &text);
    let doc = Document::parse(&text).expect("well-formed XML");
    assert!(texts(&doc).iter().any(|s| s == &c.title));
    assert_inside_canvas(&doc);
    // A short title is centred on the canvas.
    let doc_text = chart::chart_svg(&study()).expect("chart");
    let doc = Document::parse(&doc_text).expect("well-formed XML");
    let title = children(group(&doc, "title"), "text")[0];
    assert_eq!(title.text().map(str::trim), Some("circular arches"));
    assert_eq!(attr_f(&title, "x"), 480.0);
    assert_inside_canvas(&doc);

    let m = semicircle(0.15, 8);
    let long = "a semicircular arch of radius 1 m and thickness 0.15 m in 8 voussoirs, with its \
                thrust line at collapse and the mechanism";
    let text = svg::structure_svg(&m.assembly, &Drawing::new(long)).expect("drawing");
    let doc = Document::parse(&text).expect("well-formed XML");
    assert_inside_canvas(&doc);
}

/// A tie of no capacity (one a retrofit design found not needed) carries nothing: it is drawn
/// thin and dashed with its label saying so, not as a tie in place; a tie with a capacity is
/// a solid line.
#[test]
fn a_tie_of_no_capacity_is_drawn_as_none() {
    let m = model_of(&format!(
        "{PORTAL}[[ties]]\nfrom = [-1.0, -0.05]\nto = [1.0, -0.05]\ncapacity = 1500.0\n\
         [[ties]]\nfrom = [-0.9, 0.5]\nto = [0.9, 0.5]\ncapacity = 0.0\n"
    ));
    let r = statics::analyse(&m, &StaticSettings::default()).expect("analysis runs");
    let drawing = Drawing {
        ties: &m.ties,
        tie_forces: &r.ties,
        ..full_drawing("portal, a tie and none", &m, &r, Direction::Right)
    };
    let text = svg::structure_svg(&m.assembly, &drawing).expect("drawing");
    keep("ties-none.svg", &text);
    let doc = Document::parse(&text).expect("well-formed XML");
    let g = group(&doc, "ties");
    let lines = children(g, "line");
    assert_eq!(lines.len(), 2);
    assert_eq!(
        lines[0].attribute("stroke-dasharray"),
        None,
        "the tie in place is solid"
    );
    assert_eq!(
        lines[1].attribute("stroke-dasharray"),
        Some(DASH),
        "the tie of none is dashed"
    );
    let words: Vec<String> = children(g, "text")
        .iter()
        .filter_map(|t| t.text().map(str::to_string))
        .collect();
    assert!(
        words.iter().any(|w| w == "tie 1: none (capacity 0 N)"),
        "{words:?}"
    );
    assert!(
        words
            .iter()
            .any(|w| w.starts_with("tie 0: ") && !w.contains("none")),
        "{words:?}"
    );
}

/// On the arcade of `data/arcade.toml` (118 hinges) no hinge number covers another number or
/// another hinge's circle: a number with no free place beside its circle is left out, and
/// the legend counts those. Each number drawn is its hinge's place in the summary's and the JSON's order,
/// 17 px from its own circle.
#[test]
fn crowded_hinges_keep_their_numbers_apart() {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/data/arcade.toml");
    let text = std::fs::read_to_string(path).expect("bundled arcade");
    let m = model_of(&text);
    let (r, svg_text) = draw("arcade.svg", &m, Direction::Right, "arcade");
    let doc = Document::parse(&svg_text).expect("well-formed XML");
    let circles: Vec<(f64, f64)> = children(group(&doc, "hinges"), "circle")
        .iter()
        .map(|c| (attr_f(c, "cx"), attr_f(c, "cy")))
        .collect();
    assert_eq!(circles.len(), r.hinges.len());
    assert!(r.hinges.len() > 50, "a crowded drawing: {}", r.hinges.len());
    let numbers: Vec<(usize, (f64, f64))> = children(group(&doc, "hinge-numbers"), "text")
        .iter()
        .map(|t| {
            let k: usize = t.text().and_then(|s| s.parse().ok()).expect("a number");
            (k, (attr_f(t, "x"), attr_f(t, "y")))
        })
        .collect();
    let left_out = r.hinges.len() - numbers.len();
    assert!(
        left_out > 0 && numbers.len() > 20,
        "{} of {}",
        numbers.len(),
        r.hinges.len()
    );
    // A number's box: the font's height (13 px) square plus a pixel; a circle's: radius 6
    // and half its 3 px stroke.
    let (half, radius) = (7.5, 7.5);
    let apart =
        |p: (f64, f64), q: (f64, f64), by: f64| (p.0 - q.0).abs() >= by || (p.1 - q.1).abs() >= by;
    for (i, &(k, p)) in numbers.iter().enumerate() {
        let own = circles[k - 1];
        let d = (p.0 - own.0).hypot(p.1 - own.1);
        // The circles' centres are whole pixels (plotters rounds them), the numbers' tenths.
        assert!(
            (d - 17.0).abs() < 0.75,
            "number {k} at {d} px from its hinge"
        );
        for (j, &c) in circles.iter().enumerate() {
            if j != k - 1 {
                assert!(
                    apart(p, c, half + radius - 0.5),
                    "number {k} covers hinge {}",
                    j + 1
                );
            }
        }
        for &(l, q) in &numbers[i + 1..] {
            // Positions are printed to a tenth of a pixel.
            assert!(apart(p, q, 2.0 * half - 0.1), "numbers {k} and {l} overlap");
        }
    }
    let t = texts(&doc);
    let want = format!(
        "hinge ({}), numbered as the summary and the JSON list them ({left_out} without room for a number)",
        r.hinges.len()
    );
    assert!(t.contains(&want), "legend lacks {want}: {t:?}");
}
