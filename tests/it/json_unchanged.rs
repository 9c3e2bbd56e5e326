//! Behaviour unchanged by the model redesign (issue 22): the `analyze --json` object of every
//! bundled scene and of 200 random scenes (loads, fill, piers, user blocks, crushing, finite
//! friction, vertical component, both directions) is, field for field and bit for bit, the
//! one the code gave before the redesign (commit 4dff1e0), fields added since aside (they are
//! listed in `ADDED`) and the wall times.
//!
//! The baseline, `tests/data/json_baseline.txt`, holds one line per case: its name and a
//! 64-bit FNV-1a hash of the canonical JSON (keys sorted, floats in Rust's shortest
//! round-trip form). It was written by this very file run against 4dff1e0 with
//! `VOUSSOIR_WRITE_BASELINE=tests/data/json_baseline.txt cargo test --release --test
//! json_unchanged`; on a mismatch the test prints the case's scene and JSON to compare by
//! hand. Changed since on purpose: the 7 random cases with a point load on the crown joint of
//! an arch with an even number of voussoirs (session 11: a point load on a joint is shared
//! equally by the blocks that meet there, `scene::placement`), their lines rewritten.

use serde_json::Value;
use voussoir::analysis::{self, Options};
use voussoir::scene::Scene;
use voussoir::statics::{Direction, StaticSettings};

/// Fields added to the JSON contract since the baseline, ignored in the comparison, and
/// `file` (a block file's path, which depends on where the checkout is).
const ADDED: &[&str] = &[
    "capacity_curve_method",
    "capacity_curve_end",
    "incremental_programs",
    "action",
    "live_weight",
    "tilt_deg",
    "live",
    "file",
    "ties",
    "reinforcements",
    "friction_exact",
    "friction_lower_states_possible",
    "friction_lower_states_note",
    "lambda_associative",
    "slipping_joints",
    "friction_note",
    "fixed",
    "mended",
    "mechanism_sliding",
    "kinematic_admissible",
    "lambda_non_associative",
    "non_associative_converged",
    "non_associative_iterations",
    "non_associative_sliding_joints",
    "non_associative_starts",
    "non_associative_note",
    "lambda_governing",
    "dem",
    "passive",
    "passive_governs",
];

/// The kinematic fields of an assembly that is not a chain as the baseline wrote them, before
/// the general kinematic program gave such assemblies an upper bound (issue 23): no bound, no
/// mechanism, and the note that said why. Only these fields changed for those assemblies;
/// their new values are checked against the static bound in `general_kinematic.rs`.
fn undo_general(v: &mut Value, a: &analysis::SceneAnalysis) {
    if v["kinematic_search"] != "general" {
        return;
    }
    let why = analysis::not_a_chain(&a.model.assembly)
        .expect("only assemblies that are not chains get the general program by default");
    for key in [
        "lambda_upper",
        "kinematic_status",
        "gap",
        "kinematic_search",
    ] {
        v[key] = Value::Null;
    }
    for key in ["mechanism_hinges", "open_joints", "kinematic_mechanism"] {
        v[key] = Value::Array(Vec::new());
    }
    v["kinematic_note"] = Value::String(format!(
        "none: the blocks are not a chain between two supports ({why}), so only the static bound and the DEM apply; the collapse mechanism (drawn with --svg) is read from the static program's duals"
    ));
}

/// Strip the added fields and the wall times, recursively.
fn strip(v: &mut Value) {
    match v {
        Value::Object(map) => {
            map.retain(|k, _| !ADDED.contains(&k.as_str()) && !k.ends_with("_time_s"));
            for x in map.values_mut() {
                strip(x);
            }
        }
        Value::Array(a) => a.iter_mut().for_each(strip),
        _ => {}
    }
}

/// Canonical text: keys sorted (serde_json's map is ordered), floats as Rust writes them.
fn canonical(v: &Value, out: &mut String) {
    match v {
        Value::Object(map) => {
            let mut keys: Vec<&String> = map.keys().collect();
            keys.sort();
            out.push('{');
            for k in keys {
                out.push_str(k);
                out.push(':');
                canonical(&map[k], out);
                out.push(',');
            }
            out.push('}');
        }
        Value::Array(a) => {
            out.push('[');
            for x in a {
                canonical(x, out);
                out.push(',');
            }
            out.push(']');
        }
        Value::Number(n) => match n.as_f64() {
            Some(x) if n.is_f64() => out.push_str(&format!("{:?}", x.to_bits())),
            _ => out.push_str(&n.to_string()),
        },
        other => out.push_str(&other.to_string()),
    }
}

fn fnv1a(text: &str) -> u64 {
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    for b in text.bytes() {
        h ^= u64::from(b);
        h = h.wrapping_mul(0x0000_0100_0000_01b3);
    }
    h
}

/// A small deterministic generator (SplitMix64).
struct Rng(u64);
impl Rng {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }
    fn uniform(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * (self.next() >> 11) as f64 / (1u64 << 53) as f64
    }
    fn pick(&mut self, n: usize) -> usize {
        (self.next() % n as u64) as usize
    }
    fn chance(&mut self, p: f64) -> bool {
        self.uniform(0.0, 1.0) < p
    }
}

/// Three decimals: the scenes are written as text, so every value is what the file says.
fn r3(x: f64) -> f64 {
    (x * 1000.0).round() / 1000.0
}

/// A random scene as TOML, and the direction to analyse it in.
fn random_scene(rng: &mut Rng) -> (String, Direction) {
    let mut text = String::new();
    let (rise, half_span);
    match rng.pick(3) {
        0 => {
            let embrace = [180.0, 150.0, 120.0, 200.0][rng.pick(4)];
            let t = r3(rng.uniform(0.12, 0.3));
            let n = 6 + rng.pick(20);
            text += &format!(
                "[arch]\nshape = \"circular\"\nradius = 1.0\nembrace_deg = {embrace}\nthickness = {t}\nvoussoirs = {n}\n"
            );
            half_span = 1.0;
            rise = 1.0 + t / 2.0;
        }
        1 => {
            let e = r3(rng.uniform(0.05, 0.3));
            let t = r3(rng.uniform(0.1, 0.3));
            let n = 2 * (4 + rng.pick(10));
            text += &format!(
                "[arch]\nshape = \"pointed\"\nradius = 1.0\neccentricity = {e}\nthickness = {t}\nvoussoirs = {n}\n"
            );
            half_span = 1.0 - e;
            rise = 0.9;
        }
        _ => {
            let f = r3(rng.uniform(0.5, 0.9));
            let t = r3(rng.uniform(0.12, 0.3));
            let n = 7 + rng.pick(18);
            text += &format!(
                "[arch]\nshape = \"basket\"\nspan = 2.0\nrise = {f}\nthickness = {t}\nvoussoirs = {n}\n"
            );
            half_span = 1.0;
            rise = f;
        }
    }
    if rng.chance(0.3) {
        let h = r3(rng.uniform(0.5, 1.5));
        let b = r3(rng.uniform(0.3, 0.6));
        let k = 1 + rng.pick(4);
        text += &format!("[piers]\nheight = {h}\nwidth = {b}\ncourses = {k}\n");
    }
    let friction = if rng.chance(0.3) {
        format!("{}", r3(rng.uniform(0.4, 1.0)))
    } else {
        "inf".to_string()
    };
    text += &format!("[material]\nfriction = {friction}\n");
    if rng.chance(0.15) {
        let fc = [2e6, 5e6, 1e7][rng.pick(3)];
        text += &format!("compressive_strength = {fc:e}\n");
    }
    if rng.chance(0.4) {
        let from = r3(rng.uniform(-half_span, 0.0));
        let to = r3(from + rng.uniform(0.1, half_span));
        let q = r3(rng.uniform(500.0, 5000.0));
        let seismic = rng.chance(0.5);
        text += &format!(
            "[[loads]]\ntype = \"line\"\nfrom_x = {from}\nto_x = {to}\nintensity = {q}\nseismic = {seismic}\n"
        );
    }
    if rng.chance(0.3) {
        // On the crown voussoir: just below the crown's extrados, at x = 0 or beside it.
        let x = if rng.chance(0.5) { 0.0 } else { 0.01 };
        let fy = -r3(rng.uniform(500.0, 4000.0));
        let seismic = rng.chance(0.5);
        text += &format!(
            "[[loads]]\ntype = \"point\"\nat = [{x}, {}]\nforce = [0.0, {fy}]\nseismic = {seismic}\n",
            r3(rise - 0.06)
        );
    }
    if rng.chance(0.2) {
        let level = r3(rise + rng.uniform(0.25, 0.6));
        text += &format!("[fill]\nlevel = {level}\nunit_weight = 18000.0\n");
    }
    if rng.chance(0.2) {
        let r = r3(rng.uniform(-0.3, 0.3));
        text += &format!("[seismic]\nvertical_ratio = {r}\n");
    }
    let direction = if rng.chance(0.5) {
        Direction::Right
    } else {
        Direction::Left
    };
    (text, direction)
}

/// The same structure as inline user blocks (the parametric scene's polygons), with its
/// material, loads and vertical component, when it has no fill (fill over user blocks is
/// newer than the baseline).
fn as_blocks(text: &str) -> Option<String> {
    let scene = Scene::from_toml_str(text, "random").ok()?;
    if scene.fill.is_some() {
        return None;
    }
    let model = voussoir::scene::build(&scene).ok()?;
    let polygons: Vec<String> = model
        .assembly
        .blocks
        .iter()
        .map(|b| {
            let pts: Vec<String> = b
                .polygon
                .iter()
                .map(|p| format!("[{:?}, {:?}]", p.x, p.y))
                .collect();
            format!("[{}]", pts.join(", "))
        })
        .collect();
    let ground = model
        .assembly
        .blocks
        .iter()
        .flat_map(|b| b.polygon.iter().map(|p| p.y))
        .fold(f64::INFINITY, f64::min);
    let mut rest: toml::Table = text.parse().ok()?;
    rest.remove("arch");
    rest.remove("piers");
    Some(format!(
        "[blocks]\npolygons = [{}]\nground_y = {ground:?}\n{rest}",
        polygons.join(", ")
    ))
}

/// Every case: `(name, scene text, direction)`.
fn cases() -> Vec<(String, String, Direction)> {
    let mut out = Vec::new();
    let data = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("data");
    let mut bundled: Vec<_> = std::fs::read_dir(&data)
        .expect("data/")
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|e| e == "toml"))
        .collect();
    bundled.sort();
    for path in bundled {
        let name = path
            .file_name()
            .expect("name")
            .to_string_lossy()
            .to_string();
        let text = std::fs::read_to_string(&path).expect("bundled scene");
        for d in [Direction::Right, Direction::Left] {
            out.push((format!("{name} {d:?}"), text.clone(), d));
        }
    }
    let mut rng = Rng(22);
    let mut k = 0;
    while k < 200 {
        let (text, d) = random_scene(&mut rng);
        // The baseline's reading of a scene built its model too (a load on no block was an
        // error of the scene): the same scenes are kept.
        let valid =
            Scene::from_toml_str(&text, "random").is_ok_and(|s| voussoir::scene::build(&s).is_ok());
        if !valid {
            continue;
        }
        if k % 5 == 4 {
            if let Some(blocks) = as_blocks(&text) {
                out.push((format!("random {k} blocks {d:?}"), blocks, d));
                k += 1;
                continue;
            }
        }
        out.push((format!("random {k} {d:?}"), text, d));
        k += 1;
    }
    out
}

/// The stripped JSON of one case under `settings` (toward `direction`), or the error's text.
fn json_value(text: &str, settings: StaticSettings, direction: Direction) -> Result<Value, String> {
    // Relative block files resolve from data/.
    let data = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("data");
    let table: toml::Table = text.parse().map_err(|e| format!("TOML error: {e}"))?;
    let scene = Scene::from_table_in(table, "case", Some(&data))
        .map_err(|e| format!("scene error: {e}"))?;
    let options = Options {
        static_settings: settings.direction(direction),
        ..Options::default()
    };
    let a = analysis::analyse(&scene, &options).map_err(|e| format!("analysis error: {e}"))?;
    let mut v =
        serde_json::to_value(voussoir::report::AnalysisReport::new(&scene, &a)).expect("JSON");
    strip(&mut v);
    undo_general(&mut v, &a);
    Ok(v)
}

/// The settings the baseline's program is run with: the defaults, but with finite
/// compressive strength the chain program with the cones of every joint (`working_set`
/// off), the program the baseline was written with. The working set, the default since issue
/// 28, reaches the same optimum by another path, so not the same bits: it is compared with
/// this program in `crushing_cases_by_the_working_set_equal_the_baseline_program`.
fn baseline_settings() -> StaticSettings {
    StaticSettings::default().working_set(false)
}

/// The canonical JSON of one case, or the error's text.
fn json_of(text: &str, direction: Direction) -> String {
    match json_value(text, baseline_settings(), direction) {
        Ok(v) => {
            let mut out = String::new();
            canonical(&v, &mut out);
            out
        }
        Err(e) => e,
    }
}

/// Where two stripped JSON values differ beyond round-off: the same keys, strings and
/// integers (the solver's words and counts, and the kinematic note that prints lambda,
/// aside), floats within `tol(path)` of the larger magnitude (at least 1).
fn differences(a: &Value, b: &Value, path: &str, tol: &dyn Fn(&str) -> f64, out: &mut Vec<String>) {
    match (a, b) {
        (Value::Object(x), Value::Object(y)) => {
            let keys: std::collections::BTreeSet<&String> = x.keys().chain(y.keys()).collect();
            for k in keys {
                if ["solver_status", "iterations", "kinematic_note"].contains(&k.as_str()) {
                    continue;
                }
                match (x.get(k), y.get(k)) {
                    (Some(p), Some(q)) => differences(p, q, &format!("{path}.{k}"), tol, out),
                    _ => out.push(format!("{path}.{k}: in one only")),
                }
            }
        }
        (Value::Array(x), Value::Array(y)) if x.len() == y.len() => {
            for (i, (p, q)) in x.iter().zip(y).enumerate() {
                differences(p, q, &format!("{path}[{i}]"), tol, out);
            }
        }
        (Value::Number(p), Value::Number(q)) if p.is_f64() || q.is_f64() => {
            let (p, q) = (
                p.as_f64().unwrap_or(f64::NAN),
                q.as_f64().unwrap_or(f64::NAN),
            );
            let within = (p - q).abs() <= tol(path) * p.abs().max(q.abs()).max(1.0);
            if !within {
                out.push(format!("{path}: {p} vs {q}"));
            }
        }
        _ if a == b => {}
        _ => out.push(format!("{path}: {a} vs {b}")),
    }
}

#[test]
fn crushing_cases_by_the_working_set_equal_the_baseline_program() {
    // Every crushing case of the baseline, analysed with the default settings (the working
    // set of issue 28), against the program the baseline holds bit for bit: the same
    // statuses, hinges, open and sliding joints and the multipliers, thrust points and
    // hinge offsets to 1e-9. The baseline's joint forces and mechanism are the interior
    // point's, which stops at a gap of 1e-10: its forces away from the hinges are accurate to
    // a few 1e-9 of their size (3.4e-9 measured) and its duals, the mechanism, to about 1e-7
    // (8.1e-8 measured), against the working set's optimum, exact to round-off (its KKT
    // conditions checked at every joint).
    let tol = |path: &str| {
        if path.starts_with(".mechanism") {
            1e-6
        } else if path.starts_with(".joints")
            && [".N", ".V", ".M"].iter().any(|f| path.ends_with(f))
        {
            1e-8
        } else {
            1e-9
        }
    };
    let mut compared = 0;
    for (name, text, d) in cases() {
        if !text.contains("compressive_strength") {
            continue;
        }
        let default = json_value(&text, StaticSettings::default(), d);
        let baseline = json_value(&text, baseline_settings(), d);
        let (Ok(a), Ok(b)) = (&default, &baseline) else {
            assert_eq!(default, baseline, "{name}");
            continue;
        };
        let mut out = Vec::new();
        differences(a, b, "", &tol, &mut out);
        assert!(out.is_empty(), "{name}:\n{}\n{text}", out.join("\n"));
        compared += 1;
    }
    assert!(compared >= 20, "{compared} crushing cases");
}

#[test]
fn analyze_json_is_unchanged_for_bundled_and_random_scenes() {
    let cases = cases();
    assert!(cases.len() >= 220, "{} cases", cases.len());
    let jsons: Vec<String> = cases.iter().map(|(_, text, d)| json_of(text, *d)).collect();
    // The comparison is of analyses, not of error messages.
    let errors: Vec<&String> = jsons.iter().filter(|j| !j.starts_with('{')).collect();
    assert!(
        errors.len() * 20 <= cases.len(),
        "{} of {} cases are errors: {errors:?}",
        errors.len(),
        cases.len()
    );
    let lines: Vec<String> = cases
        .iter()
        .zip(&jsons)
        .map(|((name, _, _), json)| format!("{name}\t{:016x}", fnv1a(json)))
        .collect();
    if let Ok(path) = std::env::var("VOUSSOIR_WRITE_BASELINE") {
        std::fs::write(&path, lines.join("\n") + "\n").expect("write the baseline");
        return;
    }
    // Cases by name: a scene bundled since the baseline has nothing to compare with, but
    // every case of the baseline must still be there.
    let baseline = include_str!("../data/json_baseline.txt");
    let expected: std::collections::BTreeMap<&str, &str> = baseline
        .lines()
        .filter_map(|l| l.split_once('\t'))
        .collect();
    let mut differ = Vec::new();
    let mut compared = 0;
    for (line, (name, text, d)) in lines.iter().zip(&cases) {
        let Some(want) = expected.get(name.as_str()) else {
            continue;
        };
        compared += 1;
        if line != &format!("{name}\t{want}") {
            differ.push(format!(
                "{name}: {line} against {want}\n{text}\n{}",
                json_of(text, *d)
            ));
        }
    }
    assert_eq!(
        compared,
        expected.len(),
        "every case of the baseline is compared"
    );
    assert!(
        differ.is_empty(),
        "{} of {} cases differ from the baseline:\n{}",
        differ.len(),
        lines.len(),
        differ.join("\n\n")
    );
}
