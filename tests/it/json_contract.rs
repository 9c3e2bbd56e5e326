//! The JSON printed by the CLI is a contract for scripts: later versions add fields, never
//! rename or remove them. These lists pin every field that exists today.

use crate::common;
use common::{data, voussoir};

fn json(args: &[&str], scene: &str) -> serde_json::Value {
    let out = voussoir().args(args).arg(data(scene)).assert().success();
    serde_json::from_slice(&out.get_output().stdout).expect("one JSON object")
}

/// Issue 11: the `scene` fields that, with the load fields, rebuild the scene.
const SCENE_REBUILD_FIELDS: &[&str] = &[
    "radius",
    "embrace_deg",
    "piers",
    "unit_weight",
    "depth",
    "friction_infinite",
    "joints",
    "horizontal_bed_deg",
    // Issue 13: null means infinite (no crushing).
    "compressive_strength",
];

/// Issue 9: the loads as read and their totals, in every report.
const LOAD_FIELDS: &[&str] = &[
    "loads",
    "fill",
    "vertical_ratio",
    "permanent_weight",
    "seismic_weight",
];

fn has_all(v: &serde_json::Value, keys: &[&str], what: &str) {
    for k in keys {
        assert!(
            v.get(k).is_some(),
            "{what}: the contract field `{k}` is missing"
        );
    }
}

#[test]
fn analyze_fields() {
    let v = json(&["analyze", "--json", "--continuous"], "portal.toml");
    has_all(
        &v,
        &[
            // Issue 2 (static bound).
            "status",
            "lambda_lower",
            "hinges",
            "sliding",
            "joints",
            "mechanism",
            "equilibrium_residual",
            "blocks",
            "solve_time_s",
            // Context.
            "direction",
            "solver_status",
            "iterations",
            "model",
            "scene",
            // Issue 3 (kinematic bound, continuous model).
            "lambda_upper",
            "kinematic_status",
            "gap",
            "mechanism_hinges",
            "open_joints",
            "sliding_governs",
            "kinematic_mechanism",
            "kinematic_note",
            "kinematic_time_s",
            "kinematic_search",
            "lambda_continuous",
            "continuous_hinges",
            // Issue 25 (associative friction: whether lambda_lower is exact).
            "friction_exact",
            "lambda_associative",
            "slipping_joints",
            "friction_note",
        ],
        "analyze",
    );
    has_all(
        &v["joints"][0],
        &["index", "kind", "p1", "p2", "N", "V", "M", "e", "thrust"],
        "joint",
    );
    has_all(&v["hinges"][0], &["joint", "end", "x", "y"], "hinge");
    // Issue 13: where a crushing hinge sits inside its joint (0 for rigid joints).
    has_all(
        &v["hinges"][0],
        &["offset", "compressed_zone"],
        "hinge (crushing)",
    );
    has_all(&v["scene"], &["sigma"], "scene (crushing)");
    has_all(
        &v["mechanism_hinges"][0],
        &["joint", "end", "x", "y"],
        "mechanism hinge",
    );
    has_all(
        &v["model"],
        &[
            "variables",
            "constraints",
            "equality_rows",
            "inequality_rows",
            "friction_rows",
        ],
        "model",
    );
    has_all(
        &v["scene"],
        &[
            "origin",
            "shape",
            "thickness",
            "voussoirs",
            "voussoir_shape",
            "portal",
            "friction",
            "total_weight",
        ],
        "scene",
    );
    has_all(&v["scene"], SCENE_REBUILD_FIELDS, "scene");
    has_all(&v, LOAD_FIELDS, "analyze");
    has_all(
        &v["scene"]["piers"],
        &["height", "width", "courses", "left", "right"],
        "scene.piers",
    );
    has_all(
        &v["scene"]["piers"]["left"],
        &["shape", "height", "courses", "width"],
        "scene.piers.left",
    );
    has_all(
        &v["continuous_hinges"][0],
        &["location", "end", "x", "y"],
        "continuous hinge",
    );
}

#[test]
fn min_thickness_fields() {
    let v = json(
        &["min-thickness", "--json", "--continuous"],
        "semicircular.toml",
    );
    has_all(
        &v,
        &[
            "outcome",
            "min_thickness",
            "min_thickness_ratio",
            "hinges",
            "safety_factor",
            "thickness",
            "evaluations",
            "scene",
            "min_thickness_kinematic",
            "min_thickness_gap",
            "kinematic_search",
            "kinematic_note",
            "min_thickness_continuous",
            "continuous_hinges",
        ],
        "min-thickness",
    );
    has_all(&v["scene"], SCENE_REBUILD_FIELDS, "min-thickness scene");
    has_all(&v, LOAD_FIELDS, "min-thickness");
}

#[test]
fn dem_fields() {
    let v = json(
        &[
            "dem",
            "--json",
            "--set",
            "arch.voussoirs=12",
            "--tolerance",
            "0.05",
        ],
        "semicircular.toml",
    );
    has_all(
        &v,
        &[
            "status",
            "lambda_stands",
            "lambda_collapses",
            "lambda_dem",
            "lambda_lower",
            "relative_difference",
            "bracket_width",
            "static_inside_bracket",
            "steps",
            "wall_time_s",
            "hinges",
            "sliding",
            "open",
            "friction",
            "friction_infinite",
            "time_step",
            "undecided_runs",
            "runs",
            "scene",
            "lambda_dem_low",
            "lambda_dem_high",
            "lambda_lower_simulated",
            "simulated_shape",
            "initial_guess",
            "guess_source",
        ],
        "dem",
    );
    // The bracket is the DEM's own: searched from the default start, not the static bound.
    assert_eq!(v["guess_source"], "default");
    assert_eq!(v["lambda_dem_low"], v["lambda_stands"]);
    assert_eq!(v["lambda_dem_high"], v["lambda_collapses"]);
    has_all(&v["scene"], SCENE_REBUILD_FIELDS, "dem scene");
    has_all(&v, LOAD_FIELDS, "dem");
}

/// A TOML number: always with a decimal point or an exponent (a float), `inf` for infinity.
fn toml_float(v: &serde_json::Value) -> String {
    let x = v.as_f64().expect("a number");
    if x.is_infinite() {
        "inf".to_string()
    } else {
        format!("{x:?}")
    }
}

/// The scene file the JSON of `analyze --json` describes: its `scene` object and the load
/// fields beside it.
fn scene_toml(v: &serde_json::Value) -> String {
    let sc = &v["scene"];
    let mut t = String::from("[arch]\n");
    t += &format!("shape = {}\n", sc["shape"]);
    let keys: &[&str] = match sc["shape"].as_str().expect("shape") {
        "circular" => &["radius", "embrace_deg"],
        "pointed" => &["radius", "eccentricity"],
        "basket" => &["span", "rise", "side_angle_deg"],
        other => panic!("unknown shape {other}"),
    };
    for k in keys {
        t += &format!("{k} = {}\n", toml_float(&sc[k]));
    }
    t += &format!("thickness = {}\n", toml_float(&sc["thickness"]));
    t += &format!("voussoirs = {}\n", sc["voussoirs"]);
    t += &format!("voussoir_shape = {}\n", sc["voussoir_shape"]);
    assert_eq!(sc["portal"].as_bool(), Some(!sc["piers"].is_null()));
    // Issue 12: the stereotomy, echoed with its angle.
    t += &format!("joints = {}\n", sc["joints"]);
    if !sc["horizontal_bed_deg"].is_null() {
        t += &format!(
            "horizontal_bed_deg = {}\n",
            toml_float(&sc["horizontal_bed_deg"])
        );
    }
    if !sc["piers"].is_null() {
        let p = &sc["piers"];
        // height/width/courses are the left pier's; `left` and `right` give each pier.
        assert_eq!(p["height"], p["left"]["height"]);
        assert_eq!(p["courses"], p["left"]["courses"]);
        for side in ["left", "right"] {
            t += &format!("\n[piers.{side}]\n");
            for (k, x) in p[side].as_object().expect("a pier") {
                let value = match x {
                    serde_json::Value::Number(_) if k == "courses" => x.to_string(),
                    serde_json::Value::Number(_) => toml_float(x),
                    serde_json::Value::Array(a) => format!(
                        "[{}]",
                        a.iter().map(toml_float).collect::<Vec<_>>().join(", ")
                    ),
                    other => other.to_string(),
                };
                t += &format!("{k} = {value}\n");
            }
        }
    }
    // The convention: `friction` is null exactly when `friction_infinite` is true.
    let infinite = sc["friction_infinite"].as_bool().expect("bool");
    assert_eq!(sc["friction"].is_null(), infinite);
    let friction = if infinite {
        "inf".to_string()
    } else {
        toml_float(&sc["friction"])
    };
    t += &format!(
        "\n[material]\nunit_weight = {}\ndepth = {}\nfriction = {friction}\n",
        toml_float(&sc["unit_weight"]),
        toml_float(&sc["depth"])
    );
    if !sc["compressive_strength"].is_null() {
        t += &format!(
            "compressive_strength = {}\n",
            toml_float(&sc["compressive_strength"])
        );
    }
    for load in v["loads"].as_array().expect("loads") {
        t += "\n[[loads]]\n";
        for (k, x) in load.as_object().expect("a load") {
            let value = match x {
                serde_json::Value::Number(_) => toml_float(x),
                serde_json::Value::Array(a) => format!(
                    "[{}]",
                    a.iter().map(toml_float).collect::<Vec<_>>().join(", ")
                ),
                other => other.to_string(),
            };
            t += &format!("{k} = {value}\n");
        }
    }
    if !v["fill"].is_null() {
        let f = &v["fill"];
        t += &format!(
            "\n[fill]\nlevel = {}\nunit_weight = {}\nseismic = {}\n",
            toml_float(&f["level"]),
            toml_float(&f["unit_weight"]),
            f["seismic"]
        );
    }
    t += &format!(
        "\n[seismic]\nvertical_ratio = {}\n",
        toml_float(&v["vertical_ratio"])
    );
    t
}

/// The JSON's scene fields rebuild the scene: the same analysis from the rebuilt file.
#[test]
fn the_json_scene_rebuilds_the_scene() {
    let cases: &[(&str, &[&str])] = &[
        ("semicircular.toml", &[]),
        ("semicircular.toml", &["material.friction=0.4"]),
        ("segmental.toml", &["arch.voussoir_shape=curved"]),
        ("pointed.toml", &[]),
        ("basket.toml", &["material.friction=0.6"]),
        (
            "portal.toml",
            &["material.depth=0.7", "material.unit_weight=18000"],
        ),
        ("loaded_portal.toml", &[]),
        ("filled_arch.toml", &[]),
        ("stepped_portal.toml", &[]),
        ("battered_portal.toml", &["piers.right.height=1.1"]),
        (
            "portal.toml",
            &["piers.left.width=0.5", "piers.right.courses=2"],
        ),
        (
            "portal.toml",
            &["arch.joints=horizontal_bed", "arch.horizontal_bed_deg=30"],
        ),
        ("semicircular.toml", &["arch.joints=vertical"]),
        ("semicircular.toml", &["material.compressive_strength=2e5"]),
    ];
    for (file, sets) in cases {
        let mut args = vec!["analyze", "--json"];
        for s in *sets {
            args.extend(["--set", s]);
        }
        let v = json(&args, file);
        let text = scene_toml(&v);
        let rebuilt = voussoir::scene::Scene::from_toml_str(&text, "rebuilt")
            .unwrap_or_else(|e| panic!("{file} {sets:?}: {e}\n{text}"));
        let a = voussoir::analysis::analyse(&rebuilt, &voussoir::analysis::Options::default())
            .expect("analysis of the rebuilt scene");
        assert_eq!(
            a.lower.status.as_str(),
            v["status"].as_str().expect("status"),
            "{file} {sets:?}"
        );
        let (l, lj) = (a.lower.lambda, v["lambda_lower"].as_f64());
        match (l, lj) {
            (Some(l), Some(lj)) => {
                assert!(
                    (l - lj).abs() <= 1e-9 * lj.abs().max(1.0),
                    "{file} {sets:?}: {l} against {lj}\n{text}"
                )
            }
            (None, None) => {}
            other => panic!("{file} {sets:?}: {other:?}"),
        }
        let w = v["scene"]["total_weight"].as_f64().expect("weight");
        assert!(
            (a.model.assembly.total_weight() - w).abs() <= 1e-12 * w,
            "{file} {sets:?}"
        );
        // Angles read in degrees come back as written, not as 119.99999999999999.
        if let Some(e) = v["scene"]["embrace_deg"].as_f64() {
            assert_eq!(e, e.round(), "{file}: embrace_deg {e}");
        }
    }
}

/// Issue 9: the load fields say what was read and what it weighs. Without loads the permanent
/// and seismic weights are the self-weight; with the bundled loaded portal they add the point
/// load (10 kN, seismic) and the line load (6 kN/m over x = -1..1, not seismic) to it.
#[test]
fn load_fields_carry_the_loads_as_read() {
    let plain = json(&["analyze", "--json"], "semicircular.toml");
    let w = plain["scene"]["total_weight"]
        .as_f64()
        .expect("total weight");
    assert_eq!(plain["loads"], serde_json::json!([]));
    assert!(plain["fill"].is_null());
    assert_eq!(plain["vertical_ratio"].as_f64(), Some(0.0));
    for key in ["permanent_weight", "seismic_weight"] {
        let x = plain[key].as_f64().expect(key);
        assert!((x - w).abs() <= 1e-9 * w, "{key} {x} vs self-weight {w}");
    }
    let loaded = json(&["analyze", "--json"], "loaded_portal.toml");
    let w = loaded["scene"]["total_weight"]
        .as_f64()
        .expect("total weight");
    let loads = loaded["loads"].as_array().expect("loads");
    assert_eq!(loads.len(), 2);
    assert_eq!(loads[0]["type"], "point");
    assert_eq!(loads[1]["type"], "line");
    let line = 6000.0 * 2.0;
    let p = loaded["permanent_weight"].as_f64().expect("permanent");
    let s = loaded["seismic_weight"].as_f64().expect("seismic");
    assert!(
        (p - (w + 10000.0 + line)).abs() <= 1e-6 * p,
        "permanent {p}"
    );
    assert!((s - (w + 10000.0)).abs() <= 1e-6 * s, "seismic {s}");
}

/// Issue 15: the dynamic run, its incremental dynamic analysis and the pulse curve (a single
/// block 0.2 x 1 under short pulses, so the runs take milliseconds).
#[test]
fn dynamic_fields() {
    let dir = tempfile::tempdir().expect("tempdir");
    let scene = dir.path().join("block.toml");
    std::fs::write(
        &scene,
        "[blocks]\npolygons = [[[-0.1, 0.0], [0.1, 0.0], [0.1, 1.0], [-0.1, 1.0]]]\n[material]\nfriction = \"inf\"\n",
    )
    .expect("scene");
    let run = |args: &[&str]| -> serde_json::Value {
        let out = voussoir()
            .args(["dem", "--json"])
            .args(args)
            .arg(&scene)
            .assert()
            .success();
        serde_json::from_slice(&out.get_output().stdout).expect("one JSON object")
    };
    let pulse = ["--pulse", "rect", "--amplitude", "0.1", "--period", "0.2"];
    let v = run(&pulse);
    has_all(
        &v,
        &[
            "status",
            "excitation",
            "pga",
            "duration",
            "collapse_time",
            "control_block",
            "peak_displacement",
            "peak_rotation",
            "residual_displacement",
            "residual_rotation",
            "steps",
            "time_step",
            "wall_time_s",
            "scene",
            // Added with the vertical component.
            "component",
            "vertical_excitation",
            "pga_vertical",
        ],
        "dem --pulse",
    );
    let mut ida = pulse.to_vec();
    ida.extend(["--ida", "--tolerance", "0.1"]);
    let v = run(&ida);
    has_all(
        &v,
        &[
            "excitation",
            "pga",
            "scale_survives",
            "scale_collapses",
            "collapse_pga",
            "runs",
            "steps",
            "wall_time_s",
            "tolerance",
            "bracket_width",
            "component",
            "vertical_excitation",
            "pga_vertical",
            "collapse_pga_vertical",
        ],
        "dem --ida",
    );
    let svg = dir.path().join("curve.svg");
    let v = run(&[
        "--pulse-curve",
        svg.to_str().expect("path"),
        "--periods",
        "0.2",
        "--tolerance",
        "0.1",
    ]);
    has_all(
        &v,
        &[
            "lambda_lower",
            "start_amplitude",
            "tolerance",
            "points",
            "wall_time_s",
        ],
        "dem --pulse-curve",
    );
    for p in v["points"].as_array().expect("points") {
        has_all(
            p,
            &[
                "shape",
                "period",
                "amplitude_survives",
                "amplitude_collapses",
                "runs",
            ],
            "dem --pulse-curve points",
        );
    }
}
