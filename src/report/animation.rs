//! The animation of a dynamic DEM run (`voussoir dem --record FILE --animation run.html`): one
//! self-contained HTML page (no network, no external script) with the blocks moving, the
//! ground acceleration plotted under them, and a time cursor that follows the playback.
//!
//! The page holds an SVG with every block drawn once, at the placement the motion started
//! from (the settled structure), and the frames of the run as JSON in
//! `<script type="application/json" id="frames">`: per frame its time, the ground
//! acceleration and every block's centroid `(x, y)` and rotation `a` (rad). A frame moves a
//! block by the rigid motion `translate(x, y) rotate(a - a0) translate(-x0, -y0)` from its
//! start placement `(x0, y0, a0)` (`start` in the JSON), which is what the script sets as the
//! polygon's SVG `transform`. The page plays in real time (slower on request), loops, can be
//! paused and scrubbed, and opens paused at a time given as `#t=SECONDS` (or `#t=end`).

use std::fmt::Write;

use crate::analysis::DynamicAnalysis;
use crate::geometry::Vec2;

/// Width of the page's drawing and heights of its two panels (px).
const WIDTH: f64 = 960.0;
const STRUCTURE_HEIGHT: f64 = 440.0;
const GROUND_HEIGHT: f64 = 190.0;
const MARGIN: f64 = 56.0;
/// Points of the ground-acceleration plot.
const GROUND_POINTS: usize = 3000;

/// The page of a dynamic run whose result kept frames (`DynamicSettings::frames_every`),
/// titled `title`. `None` when the run kept no frame (the structure could not stand, or no
/// frames were asked for).
pub fn html(d: &DynamicAnalysis, title: &str) -> Option<String> {
    let r = &d.result;
    if r.frames.is_empty() || r.start.len() != r.start_polygons.len() {
        return None;
    }
    let end = r.frames.last().map_or(0.0, |f| f.time).max(1e-9);

    // Model-space bounds of every block in every frame, and of the supports.
    let (mut lo, mut hi) = (
        Vec2::new(f64::INFINITY, f64::INFINITY),
        Vec2::new(f64::NEG_INFINITY, f64::NEG_INFINITY),
    );
    let mut grow = |p: Vec2| {
        lo = Vec2::new(lo.x.min(p.x), lo.y.min(p.y));
        hi = Vec2::new(hi.x.max(p.x), hi.y.max(p.y));
    };
    for f in &r.frames {
        for (i, poly) in r.start_polygons.iter().enumerate() {
            let (x0, a0) = r.start[i];
            let (x, a) = f.blocks[i];
            let (sn, cs) = (a - a0).sin_cos();
            for v in poly {
                let q = v - x0;
                grow(x + Vec2::new(cs * q.x - sn * q.y, sn * q.x + cs * q.y));
            }
        }
    }
    // The ground the DEM puts under each support: the joint extended by its length on both
    // sides (`dem::world`, which joins the overlapping ones of supports on one line; drawn
    // apart here, they cover the same span).
    let supports: Vec<(Vec2, Vec2)> = d
        .model
        .assembly
        .joints
        .iter()
        .filter(|j| j.is_support())
        .map(|j| {
            (
                j.p1 - j.length() * j.tangent(),
                j.p2 + j.length() * j.tangent(),
            )
        })
        .collect();
    for &(a, b) in &supports {
        grow(a);
        grow(b);
    }
    let size = d.model.assembly.size().max(1e-9);
    // Room for the ground under the supports.
    lo.y -= 0.08 * size;
    let span = hi - lo;
    let scale = ((WIDTH - 2.0 * MARGIN) / span.x.max(1e-9))
        .min((STRUCTURE_HEIGHT - 2.0 * 24.0) / span.y.max(1e-9));
    // Model (x, y) -> page: centred horizontally, bottom of the bounds near the panel's foot.
    let ox = 0.5 * WIDTH - scale * 0.5 * (lo.x + hi.x);
    let oy = STRUCTURE_HEIGHT - 24.0 + scale * lo.y;

    let mut svg = String::new();
    let total_height = STRUCTURE_HEIGHT + GROUND_HEIGHT;
    let _ = write!(
        svg,
        r##"<svg id="anim" xmlns="http://www.w3.org/2000/svg" viewBox="0 0 {WIDTH} {total_height}" width="{WIDTH}" height="{total_height}" font-family="sans-serif" font-size="13">
<rect width="100%" height="100%" fill="#ffffff"/>
<g transform="translate({ox:.3} {oy:.3}) scale({scale:.6} {neg:.6})">
"##,
        neg = -scale
    );
    // The ground under each support: a band below it.
    for (a, b) in &supports {
        let d = 0.06 * size;
        let _ = writeln!(
            svg,
            r##"<polygon points="{:.5},{:.5} {:.5},{:.5} {:.5},{:.5} {:.5},{:.5}" fill="#c8c2b4" stroke="none"/>"##,
            a.x,
            a.y,
            b.x,
            b.y,
            b.x,
            b.y - d,
            a.x,
            a.y - d
        );
    }
    let stroke = 1.0 / scale;
    for (i, poly) in r.start_polygons.iter().enumerate() {
        let pts: Vec<String> = poly
            .iter()
            .map(|p| format!("{:.5},{:.5}", p.x, p.y))
            .collect();
        let fill = if i == r.control_block {
            "#e8a87c"
        } else {
            "#d9d4c7"
        };
        let _ = writeln!(
            svg,
            r##"<polygon class="block" id="b{i}" points="{}" fill="{fill}" stroke="#333333" stroke-width="{stroke:.6}" stroke-linejoin="round"/>"##,
            pts.join(" ")
        );
    }
    svg.push_str("</g>\n");

    // The ground acceleration, under the structure.
    let (px0, px1) = (MARGIN + 20.0, WIDTH - MARGIN);
    let (py0, py1) = (STRUCTURE_HEIGHT + 28.0, total_height - 34.0);
    let samples: Vec<(f64, Vec2)> = (0..=GROUND_POINTS)
        .map(|k| {
            let t = end * k as f64 / GROUND_POINTS as f64;
            (t, d.ground.at(t))
        })
        .collect();
    let vertical =
        d.ground.vertical.is_some() || d.ground.component == crate::dem::record::Component::Y;
    let horizontal = d.ground.component == crate::dem::record::Component::X;
    // The plot spans +-1.15 times the peak, so a constant acceleration does not sit on the
    // frame.
    let peak = 1.15
        * samples
            .iter()
            .fold(0.0_f64, |m, (_, a)| m.max(a.x.abs()).max(a.y.abs()))
            .max(1e-12);
    let g = crate::dem::record::STANDARD_GRAVITY;
    let tx = |t: f64| px0 + (px1 - px0) * t / end;
    let ay = |a: f64| 0.5 * (py0 + py1) - 0.5 * (py1 - py0) * a / peak;
    let pga = peak / 1.15;
    let _ = writeln!(
        svg,
        r##"<rect x="{px0}" y="{py0}" width="{:.1}" height="{:.1}" fill="none" stroke="#999999"/>
<line x1="{px0}" y1="{zy:.2}" x2="{px1}" y2="{zy:.2}" stroke="#bbbbbb"/>
<line x1="{px0}" y1="{top:.2}" x2="{px1}" y2="{top:.2}" stroke="#dddddd" stroke-dasharray="4 4"/>
<line x1="{px0}" y1="{bottom:.2}" x2="{px1}" y2="{bottom:.2}" stroke="#dddddd" stroke-dasharray="4 4"/>
<text x="{lx:.1}" y="{top:.2}" text-anchor="end" dominant-baseline="middle">{:+.3} g</text>
<text x="{lx:.1}" y="{bottom:.2}" text-anchor="end" dominant-baseline="middle">{:+.3} g</text>
<text x="{lx:.1}" y="{zy:.2}" text-anchor="end" dominant-baseline="middle">0</text>
<text x="{px0}" y="{:.1}">0 s</text>
<text x="{px1}" y="{:.1}" text-anchor="end">{end:.2} s</text>
<text x="{:.1}" y="{:.1}" text-anchor="middle">time (s)</text>"##,
        px1 - px0,
        py1 - py0,
        pga / g,
        -pga / g,
        py1 + 18.0,
        py1 + 18.0,
        0.5 * (px0 + px1),
        py1 + 18.0,
        zy = ay(0.0),
        top = ay(pga),
        bottom = ay(-pga),
        lx = px0 - 6.0,
    );
    let mut line = |pick: fn(&Vec2) -> f64, colour: &str, name: &str, row: f64| {
        let pts: Vec<String> = samples
            .iter()
            .map(|(t, a)| format!("{:.2},{:.2}", tx(*t), ay(pick(a))))
            .collect();
        let _ = writeln!(
            svg,
            r##"<polyline points="{}" fill="none" stroke="{colour}" stroke-width="1.2"/>
<text x="{:.1}" y="{:.1}" fill="{colour}">{name}</text>"##,
            pts.join(" "),
            px0 + 190.0 * row,
            py0 - 8.0
        );
    };
    let mut row = 0.0;
    if horizontal {
        line(
            |a| a.x,
            "#1f77b4",
            "ground acceleration, horizontal (+x)",
            row,
        );
        row += 1.5;
    }
    if vertical {
        line(
            |a| a.y,
            "#2ca02c",
            "ground acceleration, vertical (up)",
            row,
        );
    }
    let _ = writeln!(
        svg,
        r##"<line id="cursor" x1="{px0}" y1="{py0}" x2="{px0}" y2="{py1}" stroke="#d62728" stroke-width="1.5"/>
<text id="clock" x="{:.1}" y="22" font-size="15">t = 0.000 s</text>
</svg>"##,
        MARGIN
    );

    // The frames, as JSON: numbers to a micrometre and a microradian.
    let mut data = String::from("{\"start\":[");
    for (i, (x, a)) in r.start.iter().enumerate() {
        let sep = if i > 0 { "," } else { "" };
        let _ = write!(data, "{sep}[{:.6},{:.6},{:.6}]", x.x, x.y, a);
    }
    let _ = write!(
        data,
        "],\"control_block\":{},\"plot\":{{\"x0\":{px0},\"x1\":{px1},\"end\":{end:.6}}},\"frames\":[",
        r.control_block
    );
    for (k, f) in r.frames.iter().enumerate() {
        let sep = if k > 0 { ",\n" } else { "" };
        let _ = write!(
            data,
            "{sep}{{\"t\":{:.6},\"ground\":[{:.6},{:.6}],\"blocks\":[",
            f.time, f.ground.x, f.ground.y
        );
        for (i, (x, a)) in f.blocks.iter().enumerate() {
            let sep = if i > 0 { "," } else { "" };
            let _ = write!(data, "{sep}[{:.6},{:.6},{:.6}]", x.x, x.y, a);
        }
        data.push_str("]}");
    }
    data.push_str("]}");

    Some(format!(
        r##"<!DOCTYPE html>
<html lang="en">
<head>
<meta charset="utf-8">
<title>{title}</title>
<style>
body {{ font-family: sans-serif; margin: 12px; color: #222; }}
h1 {{ font-size: 16px; font-weight: normal; margin: 0 0 6px 0; }}
#controls {{ margin: 6px 0; display: flex; gap: 10px; align-items: center; }}
#scrub {{ width: 520px; }}
</style>
</head>
<body>
<h1>{title}</h1>
<div id="controls">
<button id="play" type="button">pause</button>
<input id="scrub" type="range" min="0" max="{last}" value="0" step="1">
<label>speed <select id="speed"><option value="0.25">0.25x</option><option value="0.5">0.5x</option><option value="1" selected>1x</option><option value="2">2x</option></select></label>
<span>{count} frames</span>
</div>
{svg}
<script type="application/json" id="frames">{data}</script>
<script>
(function () {{
  "use strict";
  var D = JSON.parse(document.getElementById("frames").textContent);
  var F = D.frames, n = F.length;
  var polys = D.start.map(function (_, i) {{ return document.getElementById("b" + i); }});
  var cursor = document.getElementById("cursor"), clock = document.getElementById("clock");
  var scrub = document.getElementById("scrub"), play = document.getElementById("play");
  var speed = document.getElementById("speed");
  var k = 0, playing = true, t0 = null, simStart = 0;
  function show(j) {{
    k = Math.max(0, Math.min(n - 1, j));
    var f = F[k];
    for (var i = 0; i < polys.length; i++) {{
      var s = D.start[i], b = f.blocks[i];
      var deg = (b[2] - s[2]) * 180 / Math.PI;
      polys[i].setAttribute("transform", "translate(" + b[0] + " " + b[1] + ") rotate(" + deg +
        ") translate(" + (-s[0]) + " " + (-s[1]) + ")");
    }}
    var x = D.plot.x0 + (D.plot.x1 - D.plot.x0) * f.t / D.plot.end;
    cursor.setAttribute("x1", x); cursor.setAttribute("x2", x);
    clock.textContent = "t = " + f.t.toFixed(3) + " s";
    scrub.value = k;
  }}
  function frameAt(t) {{
    var a = 0, b = n - 1;
    while (a < b) {{ var m = (a + b + 1) >> 1; if (F[m].t <= t) a = m; else b = m - 1; }}
    return a;
  }}
  function tick(now) {{
    if (!playing) return;
    if (t0 === null) {{ t0 = now; simStart = F[k].t; }}
    var t = simStart + (now - t0) / 1000 * parseFloat(speed.value);
    if (t > D.plot.end) {{ t0 = now; simStart = 0; t = 0; }}
    show(frameAt(t));
    requestAnimationFrame(tick);
  }}
  function setPlaying(p) {{
    playing = p; t0 = null; play.textContent = p ? "pause" : "play";
    if (p) requestAnimationFrame(tick);
  }}
  play.addEventListener("click", function () {{ setPlaying(!playing); }});
  scrub.addEventListener("input", function () {{ setPlaying(false); show(parseInt(scrub.value, 10)); }});
  speed.addEventListener("change", function () {{ t0 = null; }});
  var m = /t=([0-9.]+|end)/.exec(location.hash);
  if (m) {{ show(m[1] === "end" ? n - 1 : frameAt(parseFloat(m[1]))); setPlaying(false); }}
  else {{ show(0); setPlaying(true); }}
}})();
</script>
</body>
</html>
"##,
        title = escape(title),
        last = r.frames.len() - 1,
        count = r.frames.len(),
    ))
}

/// `text` safe inside HTML.
fn escape(text: &str) -> String {
    text.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

/// The fewest frames over a run's planned duration: a pulse of a fraction of a second at 25
/// frames per second would be a handful of pictures.
pub const MIN_FRAMES: usize = 250;

/// The frame interval for a run of `duration` seconds: 25 frames per second of simulated
/// time, more for a short run (at least [`MIN_FRAMES`] over it), fewer for a long one so a
/// page holds at most `max_frames` frames.
pub fn frame_interval(duration: f64, max_frames: usize) -> f64 {
    let fine = (1.0 / 25.0_f64).min(duration / MIN_FRAMES as f64);
    fine.max(duration / max_frames.max(1) as f64)
}
