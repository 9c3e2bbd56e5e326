//! The SVG drawings: well-formed XML carrying the elements asked for, drawn to scale (one
//! scale for both axes), with the thrust line, hinges and displaced blocks where the analysis
//! puts them. Set `VOUSSOIR_SVG_DIR` to keep the pictures for looking at them.

use roxmltree::{Document, Node};
use voussoir::assembly::{Assembly, Hinge};
use voussoir::geometry::Vec2;
use voussoir::lp::{self, Direction, StaticResult, StaticSettings, Status};
use voussoir::scene::Scene;
use voussoir::thrustline::chart::{self, Chart, Series};
use voussoir::thrustline::svg::{self, Drawing, Mechanism, Placements, SvgError, DASH};
use voussoir::thrustline::thrust_points;

fn scene(text: &str) -> Scene {
    Scene::from_toml_str(text, "test").expect("valid scene")
}

fn semicircle(t: f64, n: usize) -> Assembly {
    Assembly::from_scene(&scene(&format!(
        "[arch]\nshape = \"circular\"\nradius = 1.0\nthickness = {t}\nvoussoirs = {n}\n"
    )))
}

fn portal() -> Assembly {
    Assembly::from_scene(&scene(
        "[arch]\nshape = \"circular\"\nradius = 1.0\nthickness = 0.15\nvoussoirs = 16\n\
         [piers]\nheight = 1.2\nwidth = 0.35\ncourses = 2\n",
    ))
}

fn analyse(a: &Assembly) -> StaticResult {
    let r = lp::analyse(a, &StaticSettings::default()).expect("analysis runs");
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
    let a = semicircle(0.15, 32);
    let r = analyse(&a);
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
    let text = svg::structure_svg(&a, &d).expect("drawing");
    keep("semicircle.svg", &text);
    let doc = Document::parse(&text).expect("well-formed XML");
    assert!(doc.root_element().has_tag_name("svg"));

    // To scale: the outline spans 2 (R + t/2) by R + t/2.
    let (x0, y0, s) = fit_frame(&doc, &a);
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
    let expected: Vec<Vec2> = thrust_points(&a, forces).into_iter().flatten().collect();
    assert_eq!(drawn.len(), a.joints.len());
    for (p, q) in drawn.iter().zip(&expected) {
        assert!(
            near(*p, (x0 + s * q.x, y0 - s * q.y), 2.0),
            "{p:?} vs {q:?}"
        );
    }
    assert_eq!(children(group(&doc, "line-of-action"), "polyline").len(), 1);

    // Four hinges, circles at the joint ends the analysis names.
    let circles = children(group(&doc, "hinges"), "circle");
    assert_eq!(r.hinges.len(), 4);
    assert_eq!(circles.len(), r.hinges.len());
    for (c, hg) in circles.iter().zip(&r.hinges) {
        let end = Hinge::at(&a, hg.joint, hg.end);
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

    let t = texts(&doc);
    for want in ["thrust line", "line of action", "hinge (4)", "support"] {
        assert!(t.iter().any(|s| s == want), "legend lacks {want}: {t:?}");
    }
    assert!(t
        .iter()
        .any(|s| s.starts_with("collapse mechanism") && s.contains("10% of size")));
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
    let a = portal();
    let r = analyse(&a);
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
    let text = svg::structure_svg(&a, &d).expect("drawing");
    keep("portal.svg", &text);
    let doc = Document::parse(&text).expect("well-formed XML");
    let (_, y0, s) = fit_frame(&doc, &a);
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
    let a = semicircle(0.2, 8);
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
    let text = svg::structure_svg(&a, &d).expect("drawing");
    keep("dem.svg", &text);
    let doc = Document::parse(&text).expect("well-formed XML");
    let (x0, y0, s) = fit_frame(&doc, &a);
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
    let a = semicircle(0.15, 8);
    let r = analyse(&a);
    let forces = r.forces.as_deref().expect("forces");
    let short = Drawing {
        forces: Some(&forces[1..]),
        ..Drawing::new("x")
    };
    assert!(matches!(
        svg::structure_svg(&a, &short),
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
        svg::structure_svg(&a, &wrong),
        Err(SvgError::Invalid(_))
    ));
    let bad = Drawing {
        sliding: &[99],
        ..Drawing::new("x")
    };
    assert!(matches!(
        svg::structure_svg(&a, &bad),
        Err(SvgError::Invalid(_))
    ));
}

#[test]
fn draw_structure_writes_the_file() {
    let a = semicircle(0.15, 8);
    let dir = tempfile::tempdir().expect("temp dir");
    let path = dir.path().join("a.svg");
    let title = "blocks only: t < R & \"quoted\"";
    svg::draw_structure(&path, &a, &Drawing::new(title)).expect("written");
    let text = std::fs::read_to_string(&path).expect("read back");
    let doc = Document::parse(&text).expect("well-formed XML");
    assert!(
        texts(&doc).iter().any(|t| t == title),
        "title escaped and kept"
    );
    assert_eq!(children(group(&doc, "blocks"), "polygon").len(), 8);
    let missing = dir.path().join("no/such/dir/a.svg");
    assert!(matches!(
        svg::draw_structure(&missing, &a, &Drawing::new("x")),
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
        let a = Assembly::from_scene(&scene(text));
        let r = lp::analyse(&a, &StaticSettings::default().direction(dir)).expect("runs");
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
        let text = svg::structure_svg(&a, &d).expect("drawing");
        keep(&format!("{name}.svg"), &text);
        let doc = Document::parse(&text).expect("well-formed XML");
        let (x0, y0, s) = fit_frame(&doc, &a);

        // Every drawn pressure point lies on its joint (within the pixel rounding).
        let line: Vec<_> = children(group(&doc, "thrust-line"), "polyline")
            .iter()
            .flat_map(points)
            .collect();
        let on_joints: Vec<_> = a
            .joints
            .iter()
            .zip(thrust_points(&a, forces))
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
