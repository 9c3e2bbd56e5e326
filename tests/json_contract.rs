//! The JSON printed by the CLI is a contract for scripts: later versions add fields, never
//! rename or remove them. These lists pin every field that exists today.

mod common;
use common::{data, voussoir};

fn json(args: &[&str], scene: &str) -> serde_json::Value {
    let out = voussoir().args(args).arg(data(scene)).assert().success();
    serde_json::from_slice(&out.get_output().stdout).expect("one JSON object")
}

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
        ],
        "analyze",
    );
    has_all(
        &v["joints"][0],
        &["index", "kind", "p1", "p2", "N", "V", "M", "e", "thrust"],
        "joint",
    );
    has_all(&v["hinges"][0], &["joint", "end", "x", "y"], "hinge");
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
            "kinematic_note",
            "min_thickness_continuous",
            "continuous_hinges",
        ],
        "min-thickness",
    );
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
        ],
        "dem",
    );
}
