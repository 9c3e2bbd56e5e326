//! `voussoir report` (issue 27): the hand-in report is one well-formed, self-contained page
//! (an XML parser reads it; nothing in it points outside it), every number it prints in its
//! results is a number of the JSON of the same run (`--json`) at the precision printed, and
//! the report of a failing structure, of one that cannot stand, of a block scene without a
//! chain mechanism and of one with sliding joints says so in words. The print to PDF in
//! headless Chromium is tests/e2e/report.test.mjs.

use crate::common::{data, rect_polygons, running_bond_wall_rects, scene_file, voussoir};
use sha2::{Digest, Sha256};
use std::path::Path;

/// The report's HTML and the JSON of the same run: `voussoir report SCENE ARGS -o ... --json`.
fn report(scene: &Path, args: &[&str]) -> (String, serde_json::Value) {
    let dir = tempfile::tempdir().expect("temp dir");
    let html = dir.path().join("report.html");
    let out = voussoir()
        .arg("report")
        .arg(scene)
        .args(args)
        .arg("-o")
        .arg(&html)
        .arg("--json")
        .output()
        .expect("runs");
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let json = serde_json::from_slice(&out.stdout).expect("JSON on stdout");
    (
        std::fs::read_to_string(&html).expect("report written"),
        json,
    )
}

/// The page parsed as XML (it is XHTML-compatible), with its doctype.
fn parse(html: &str) -> roxmltree::Document<'_> {
    let options = roxmltree::ParsingOptions {
        allow_dtd: true,
        ..Default::default()
    };
    roxmltree::Document::parse_with_options(html, options)
        .unwrap_or_else(|e| panic!("the report is not well-formed: {e}"))
}

/// Nothing in the page is fetched: no script, no external style, font, image or frame, no
/// link out of the page, no URL at all.
fn assert_self_contained(html: &str, doc: &roxmltree::Document) {
    assert!(
        !html.contains("http://") && !html.contains("https://"),
        "a URL in the report"
    );
    assert!(!html.contains("@import") && !html.contains("@font-face"));
    for node in doc.descendants().filter(|n| n.is_element()) {
        let name = node.tag_name().name();
        assert!(
            !matches!(
                name,
                "script" | "link" | "img" | "iframe" | "object" | "embed" | "image" | "use"
            ),
            "<{name}> in the report"
        );
        for attr in node.attributes() {
            assert!(attr.name() != "src", "src= on <{name}>");
            if attr.name() == "href" {
                assert!(attr.value().starts_with('#'), "href {}", attr.value());
            }
            assert!(
                !attr.value().contains("url(") || attr.value().contains("url(#"),
                "{}",
                attr.value()
            );
        }
    }
    let style: String = doc
        .descendants()
        .filter(|n| n.has_tag_name("style"))
        .filter_map(|n| n.text())
        .collect();
    assert!(!style.contains("url("), "the style sheet fetches something");
    // Every inline SVG is a figure of its own, and ids are unique in the page.
    let mut ids = std::collections::BTreeSet::new();
    for node in doc.descendants() {
        if let Some(id) = node.attribute("id") {
            assert!(ids.insert(id.to_string()), "id {id} twice");
        }
    }
}

/// Every number in the JSON, and every number written inside its strings (a note printed
/// as it is).
fn json_numbers(v: &serde_json::Value, out: &mut Vec<f64>) {
    match v {
        serde_json::Value::Number(n) => out.extend(n.as_f64()),
        serde_json::Value::String(s) => out.extend(tokens(s).into_iter().map(|t| t.value)),
        serde_json::Value::Array(a) => {
            // A count the report prints ("41 joints") is the length of the JSON's list.
            out.push(a.len() as f64);
            a.iter().for_each(|x| json_numbers(x, out))
        }
        serde_json::Value::Object(o) => {
            // A hinge's place on a circular ring centred at the origin (the bundled portal's),
            // as the summary prints it: its polar angle and its angle from the vertical
            // (report::words::joint_angles_deg), from the position the JSON gives.
            if let (Some(x), Some(y)) = (
                o.get("x").and_then(|v| v.as_f64()),
                o.get("y").and_then(|v| v.as_f64()),
            ) {
                let polar = y.atan2(x).to_degrees();
                out.extend([polar, (90.0 - polar).abs()]);
            }
            // The equilibrium residual as a fraction of the weight, as the summary prints it.
            if let Some(r) = o.get("equilibrium_residual").and_then(|v| v.as_f64()) {
                for w in ["permanent_weight", "seismic_weight"] {
                    out.extend(o.get(w).and_then(|v| v.as_f64()).map(|w| r / w));
                }
            }
            o.values().for_each(|x| json_numbers(x, out))
        }
        _ => {}
    }
}

/// A number as printed: its value and its decimals (the precision it was rounded to).
#[derive(Debug)]
struct Token {
    text: String,
    value: f64,
    decimals: i32,
}

/// The numbers in `text`: a run of digits with at most one decimal point and an optional
/// exponent, signed when the sign stands before it. A run glued to a letter before it (`p1`,
/// `T1`, `F0`: names) is a name, not a number.
fn tokens(text: &str) -> Vec<Token> {
    let chars: Vec<char> = text.chars().collect();
    let mut out = Vec::new();
    let mut i = 0;
    while i < chars.len() {
        let dotted = i >= 2 && chars[i - 1] == '.' && chars[i - 2].is_alphanumeric();
        let starts = chars[i].is_ascii_digit()
            && !dotted
            && (i == 0 || !(chars[i - 1].is_alphanumeric() || chars[i - 1] == '_'));
        if !starts {
            i += 1;
            continue;
        }
        let sign = i > 0
            && matches!(chars[i - 1], '-' | '+' | '−')
            && (i < 2 || !chars[i - 2].is_alphanumeric());
        let start = i;
        while i < chars.len() && chars[i].is_ascii_digit() {
            i += 1;
        }
        let mut decimals = 0;
        if i + 1 < chars.len() && chars[i] == '.' && chars[i + 1].is_ascii_digit() {
            i += 1;
            while i < chars.len() && chars[i].is_ascii_digit() {
                i += 1;
                decimals += 1;
            }
        }
        let mut exponent = 0;
        if i + 1 < chars.len() && (chars[i] == 'e' || chars[i] == 'E') {
            let mut j = i + 1;
            if j < chars.len() && (chars[j] == '-' || chars[j] == '+') {
                j += 1;
            }
            if j < chars.len() && chars[j].is_ascii_digit() {
                let e0 = j;
                while j < chars.len() && chars[j].is_ascii_digit() {
                    j += 1;
                }
                let digits: String = chars[e0..j].iter().collect();
                exponent =
                    digits.parse::<i32>().unwrap_or(0) * if chars[i + 1] == '-' { -1 } else { 1 };
                i = j;
            }
        }
        // A dotted section number (C8.7.1) or a version (0.1.0) is no number.
        if i < chars.len()
            && chars[i] == '.'
            && i + 1 < chars.len()
            && chars[i + 1].is_ascii_digit()
        {
            while i < chars.len() && (chars[i].is_ascii_digit() || chars[i] == '.') {
                i += 1;
            }
            continue;
        }
        let body: String = chars[start..i].iter().collect();
        let text = if sign { format!("-{body}") } else { body };
        let value: f64 = text.replace('−', "-").parse().unwrap_or(f64::NAN);
        // `-` before a number is a minus only where the report writes signed values; a
        // range or a dash before a number is read as a sign too, so both signs are tried.
        out.push(Token {
            text,
            value,
            decimals: decimals - exponent,
        });
    }
    out
}

/// Whether the printed `t` is one of `numbers` rounded as printed, in the units the report
/// prints them in (the JSON's SI values, seconds as ms, m as mm, N as kN, fractions as %).
fn matches(t: &Token, numbers: &[f64]) -> bool {
    let half = 0.5 * 10f64.powi(-t.decimals);
    numbers.iter().any(|&x| {
        [1.0, 1e3, 1e-3, 100.0].iter().any(|&scale| {
            let v = x * scale;
            [t.value, -t.value]
                .iter()
                .any(|&p| (v - p).abs() <= half * (1.0 + 1e-9) + 1e-12 * p.abs())
        })
    })
}

/// The chapters of the page: (title, element).
fn chapters<'a>(doc: &'a roxmltree::Document<'a>) -> Vec<(String, roxmltree::Node<'a, 'a>)> {
    doc.descendants()
        .filter(|n| {
            n.has_tag_name("section") && n.attribute("class").is_some_and(|c| c.contains("chapter"))
        })
        .map(|n| {
            let title = n
                .children()
                .find(|c| c.has_tag_name("h2"))
                .map(text_of)
                .unwrap_or_default();
            (title, n)
        })
        .collect()
}

/// The text of a node, the figures' SVG left out (the drawings' own labels and axes are
/// tests/it/svg.rs's), their captions kept.
fn text_of(node: roxmltree::Node) -> String {
    let mut s = String::new();
    for d in node.descendants() {
        if d.ancestors().any(|a| a.has_tag_name("svg")) {
            continue;
        }
        if let Some(t) = d.text().filter(|_| d.is_text()) {
            s.push_str(t);
            s.push(' ');
        }
    }
    s
}

/// The numbers of a scene file and its overrides (what the structure chapter echoes).
fn scene_numbers(text: &str, overrides: &[&str], out: &mut Vec<f64>) {
    fn walk(v: &toml::Value, out: &mut Vec<f64>) {
        match v {
            toml::Value::Integer(i) => out.push(*i as f64),
            toml::Value::Float(x) => out.push(*x),
            toml::Value::Array(a) => a.iter().for_each(|x| walk(x, out)),
            toml::Value::Table(t) => t.values().for_each(|x| walk(x, out)),
            toml::Value::String(s) => out.extend(tokens(s).into_iter().map(|t| t.value)),
            _ => {}
        }
    }
    let table: toml::Table = toml::from_str(text).expect("scene TOML");
    walk(&toml::Value::Table(table), out);
    for o in overrides {
        out.extend(tokens(o).into_iter().map(|t| t.value));
    }
}

/// The whole check of one report: well-formed, self-contained, every number of its results
/// one of the JSON's, the reproducibility chapter's hash the file's.
fn check(scene: &Path, args: &[&str]) -> (String, serde_json::Value) {
    let (html, json) = report(scene, args);
    let doc = parse(&html);
    assert_self_contained(&html, &doc);
    let text = std::fs::read_to_string(scene).expect("scene");
    let sha: String = Sha256::digest(text.as_bytes())
        .iter()
        .map(|b| format!("{b:02x}"))
        .collect();
    assert_eq!(json["scene_sha256"], sha.as_str());
    assert_eq!(json["voussoir_version"], env!("CARGO_PKG_VERSION"));
    let mut numbers = Vec::new();
    json_numbers(&json, &mut numbers);
    let overrides: Vec<&str> = args.iter().copied().filter(|a| a.contains('=')).collect();
    let mut inputs = Vec::new();
    scene_numbers(&text, &overrides, &mut inputs);
    let chapters = chapters(&doc);
    let titles: Vec<&str> = chapters.iter().map(|(t, _)| t.as_str()).collect();
    let order = [
        "Identification",
        "The structure",
        "Method and assumptions",
        "Results",
        "Minimum thickness",
        "Seismic check",
        "Sensitivity",
        "Limits of validity",
        "Reproducibility",
    ];
    assert_eq!(titles.len(), order.len(), "{titles:?}");
    for (t, want) in titles.iter().zip(order) {
        assert!(t.contains(want), "chapter {t}, expected {want}");
    }
    let mut checked = 0;
    for (title, node) in &chapters {
        let body = text_of(*node);
        // Fixed words (methods, references, limits; the version and the hash) print no
        // result: the reproducibility chapter is checked below.
        if ["Method", "Limits", "Reproducibility"]
            .iter()
            .any(|w| title.contains(w))
        {
            continue;
        }
        // The citations of the code in headings and rules are names, not results.
        let body = body
            .replace("NTC 2018", "NTC")
            .replace("Circolare 2019", "Circolare")
            .replace("-10 % and +10 %", "");
        // The structure chapter echoes the scene: its numbers are the scene's or the JSON's.
        let allowed: Vec<f64> = if title.contains("structure") || title.contains("Identification") {
            numbers.iter().chain(&inputs).copied().collect()
        } else {
            numbers.clone()
        };
        for t in tokens(&body) {
            // Ordinals of chapters and figures are the page's own.
            if body.contains(&format!("Figure {}:", t.text))
                || title.starts_with(&format!("{}.", t.text))
            {
                continue;
            }
            assert!(
                matches(&t, &allowed),
                "{}: `{}` ({} decimals) is no number of the JSON; in: …{}…",
                title,
                t.text,
                t.decimals,
                context(&body, &t.text)
            );
            checked += 1;
        }
    }
    assert!(checked > 50, "only {checked} numbers checked");
    // Reproducibility: the version, the hash and the scene file in full.
    let (_, repro) = chapters.last().expect("chapters");
    let repro_text = text_of(*repro);
    assert!(repro_text.contains(&sha), "the hash");
    assert!(repro_text.contains(env!("CARGO_PKG_VERSION")));
    let pre = repro
        .descendants()
        .find(|n| n.has_tag_name("pre"))
        .and_then(|n| n.text())
        .expect("the scene in full");
    assert_eq!(pre, text, "the scene file in full, as read");
    (html, json)
}

fn context<'a>(body: &'a str, needle: &str) -> &'a str {
    let i = body.find(needle).unwrap_or(0);
    let mut a = i.saturating_sub(80);
    while !body.is_char_boundary(a) {
        a -= 1;
    }
    let mut b = (i + 80).min(body.len());
    while !body.is_char_boundary(b) {
        b += 1;
    }
    &body[a..b]
}

/// The text of the chapter whose title contains `what`.
fn chapter_text(html: &str, what: &str) -> String {
    let doc = parse(html);
    let chapters = chapters(&doc);
    let (_, node) = chapters
        .iter()
        .find(|(t, _)| t.contains(what))
        .unwrap_or_else(|| panic!("no chapter {what}"));
    text_of(*node)
        .split_whitespace()
        .collect::<Vec<_>>()
        .join(" ")
}

#[test]
fn the_portals_report_prints_the_jsons_numbers_and_nothing_from_outside() {
    let (html, json) = check(&data("assess_portal.toml"), &[]);
    let a = &json["analysis"];
    let conclusion = chapter_text(&html, "Identification");
    // The [report] table's words, and the governing multiplier as the summary prints it.
    assert!(conclusion.contains("Semicircular stone portal on two piers"));
    let lambda = a["lambda_governing"].as_f64().expect("lambda");
    assert!(
        conclusion.contains(&format!("lambda = {lambda:.6} (static lower bound)")),
        "{conclusion}"
    );
    let sf = json["min_thickness"]["safety_factor"]
        .as_f64()
        .expect("safety factor");
    assert!(conclusion.contains(&format!("t / t_min = {sf:.4}")));
    assert!(json["assessment"]["passes"].as_bool().expect("verdict"));
    assert!(conclusion.contains("the mechanism passes"), "{conclusion}");
    // The sensitivity: thickness -10 % and +10 %, each analysed; friction inf is not varied.
    let rows = json["sensitivity"].as_array().expect("rows");
    assert_eq!(rows.len(), 2);
    let thicker = &rows[1];
    assert_eq!(thicker["key"], "arch.thickness");
    assert!((thicker["value"].as_f64().expect("value") - 0.22).abs() < 1e-12);
    // A thicker ring of the same span carries more: its multiplier is larger.
    assert!(thicker["lambda_governing"].as_f64().expect("l") > lambda);
    let sens = chapter_text(&html, "Sensitivity");
    for r in rows {
        let l = r["lambda_governing"].as_f64().expect("lambda");
        assert!(sens.contains(&format!("{l:.6}")), "{sens}");
    }
    assert_eq!(json["sensitivity_skipped"][0]["key"], "material.friction");
    // The figures: the structure, the thrust line and mechanism, the thrust line at t_min,
    // the capacity curves, the ADRS plot and the moved mechanism.
    assert_eq!(html.matches("<figure").count(), 6);
}

#[test]
fn a_failing_structure_is_said_to_fail() {
    let (html, json) = check(&data("assess_portal.toml"), &["--site", "ag=0.6"]);
    assert!(!json["assessment"]["passes"].as_bool().expect("verdict"));
    let conclusion = chapter_text(&html, "Identification");
    assert!(
        conclusion.contains(
            "the mechanism does not pass: neither the linear nor the nonlinear check is satisfied"
        ),
        "{conclusion}"
    );
    let seismic = chapter_text(&html, "Seismic check");
    assert!(seismic.contains("NOT satisfied"), "{seismic}");
}

#[test]
fn a_structure_that_cannot_stand_is_said_to_and_has_no_assessment() {
    let (html, json) = check(
        &data("assess_portal.toml"),
        &["--set", "arch.thickness=0.09"],
    );
    assert_eq!(json["analysis"]["status"], "cannot_stand");
    assert!(json["assessment"].is_null());
    let conclusion = chapter_text(&html, "Identification");
    assert!(
        conclusion.contains("cannot stand: no thrust line fits under its permanent loads alone"),
        "{conclusion}"
    );
    assert!(conclusion.contains("(below 1: this arch cannot stand)"));
    assert!(
        conclusion.contains("Seismic check: not made"),
        "{conclusion}"
    );
}

#[test]
fn a_block_scene_without_a_chain_mechanism_says_what_is_not_computed() {
    // The running-bond wall of docs/dem.md: no chain, so the general kinematic program.
    let text = format!(
        "[blocks]\npolygons = {}\n[material]\nfriction = 0.6\n[site]\nag = 0.2\nsoil = \"B\"\nF0 = 2.4\nTc_star = 0.3\n",
        rect_polygons(&running_bond_wall_rects())
    );
    let (_dir, path) = scene_file(&text);
    let (html, json) = check(&path, &[]);
    assert_eq!(json["analysis"]["kinematic_search"], "general");
    assert!(json["min_thickness"].is_null() && json["assessment"].is_null());
    let conclusion = chapter_text(&html, "Identification");
    assert!(
        conclusion.contains("Seismic check: not made (")
            && conclusion.contains("slide at collapse: sliding governs"),
        "{conclusion}"
    );
    let t = chapter_text(&html, "Minimum thickness");
    assert!(
        t.contains("No minimum thickness") && t.contains("parametric"),
        "{t}"
    );
    let s = chapter_text(&html, "Sensitivity");
    assert!(s.contains("arch.thickness not varied: the structure is the user's own blocks"));
}

#[test]
fn sliding_joints_are_said_to_slide_and_the_bound_named() {
    let (html, json) = check(
        &data("assess_portal.toml"),
        &["--set", "material.friction=0.4"],
    );
    let a = &json["analysis"];
    assert_eq!(a["friction_exact"], false);
    assert_eq!(a["sliding_governs"], true);
    let conclusion = chapter_text(&html, "Identification");
    let na = a["lambda_non_associative"]
        .as_f64()
        .expect("non-associative");
    assert!(
        conclusion.contains(&format!(
            "lambda = {na:.6} (the non-associative multiplier, joints that slide without opening). Sliding governs"
        )),
        "{conclusion}"
    );
    let results = chapter_text(&html, "Results");
    assert!(
        results.contains("so this multiplier is an upper bound of the real (non-associative) collapse multiplier, not a safe lower bound"),
        "{results}"
    );
    assert!(results.contains("sliding governs"));
}

#[test]
fn the_report_section_is_checked_like_any_scene_table() {
    let text = std::fs::read_to_string(data("portal.toml")).expect("portal");
    let (_dir, path) = scene_file(&format!("{text}\n[report]\nauthr = \"me\"\n"));
    let out = voussoir()
        .arg("report")
        .arg(&path)
        .arg("--json")
        .output()
        .expect("runs");
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("report.authr") && err.contains("author"),
        "{err}"
    );
    // A TOML date is the same words as a string.
    let (_dir2, path) = scene_file(&format!("{text}\n[report]\ndate = 2026-11-26\n"));
    let (_, json) = report(&path, &[]);
    assert_eq!(json["identification"]["date"], "2026-11-26");
}

#[test]
fn with_dem_the_report_gives_the_dems_bracket_as_the_json_has_it() {
    let (html, json) = check(&data("portal.toml"), &["--dem"]);
    let dem = &json["analysis"]["dem"];
    let (stands, collapses) = (
        dem["lambda_stands"].as_f64().expect("stands"),
        dem["lambda_collapses"].as_f64().expect("collapses"),
    );
    // The DEM's bracket holds the collapse multiplier of infinite friction (no sliding: the
    // static and the kinematic bound agree) to within its width.
    let lambda = json["analysis"]["lambda_lower"].as_f64().expect("lambda");
    assert!(
        stands < collapses && (stands - lambda).abs() < 0.05 && (collapses - lambda).abs() < 0.05
    );
    let results = chapter_text(&html, "Results");
    assert!(
        results.contains(&format!(
            "DEM (Coulomb contacts, no dilatancy): stands at {stands:.6}, collapses at {collapses:.6}"
        )),
        "{results}"
    );
    assert!(chapter_text(&html, "Method").contains("The discrete element check"));
}
