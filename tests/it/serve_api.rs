//! The API of `voussoir serve` (src/serve/, docs/web.md): every endpoint answers with what
//! the CLI and the library say for the same scene, and every bad request (malformed, invalid,
//! oversized, over a limit, naming a file) is refused with a 4xx and a message naming the
//! key, never a crash. The router is called in process; one test goes through a real socket
//! to the binary.
#![cfg(feature = "serve")]

use axum::body::Body;
use axum::http::{Request, StatusCode};
use http_body_util::BodyExt;
use serde_json::{json, Value};
use std::sync::Arc;
use tower::ServiceExt;
use voussoir::analysis::{self, Options};
use voussoir::outcome::Direction;
use voussoir::scene::Scene;
use voussoir::serve::{self, parameters, Limits, ServerState};
use voussoir::statics::StaticSettings;

fn runtime() -> tokio::runtime::Runtime {
    tokio::runtime::Builder::new_current_thread()
        .enable_all()
        .build()
        .expect("tokio runtime")
}

fn state() -> Arc<ServerState> {
    Arc::new(ServerState::with_default_scene(Limits::default()).expect("bundled scene"))
}

/// One request to the router: status, content type and body.
fn call(
    state: &Arc<ServerState>,
    method: &str,
    path: &str,
    body: Vec<u8>,
) -> (StatusCode, String, Vec<u8>) {
    call_with(
        state,
        method,
        path,
        &[("content-type", "application/json")],
        body,
    )
}

/// One request with the given headers.
fn call_with(
    state: &Arc<ServerState>,
    method: &str,
    path: &str,
    headers: &[(&str, &str)],
    body: Vec<u8>,
) -> (StatusCode, String, Vec<u8>) {
    runtime().block_on(async {
        let mut request = Request::builder().method(method).uri(path);
        for (name, value) in headers {
            request = request.header(*name, *value);
        }
        let request = request.body(Body::from(body)).expect("request");
        let response = serve::router(state.clone())
            .oneshot(request)
            .await
            .expect("router answers");
        let status = response.status();
        let kind = response
            .headers()
            .get("content-type")
            .and_then(|v| v.to_str().ok())
            .unwrap_or("")
            .to_string();
        let bytes = response
            .into_body()
            .collect()
            .await
            .expect("body")
            .to_bytes()
            .to_vec();
        (status, kind, bytes)
    })
}

fn post(state: &Arc<ServerState>, path: &str, body: &Value) -> (StatusCode, Value) {
    let (status, kind, bytes) = call(state, "POST", path, body.to_string().into_bytes());
    assert!(kind.starts_with("application/json"), "{path}: {kind}");
    (status, serde_json::from_slice(&bytes).expect("JSON answer"))
}

fn get_json(state: &Arc<ServerState>, path: &str) -> Value {
    let (status, kind, bytes) = call(state, "GET", path, Vec::new());
    assert_eq!(status, StatusCode::OK, "{path}");
    assert!(kind.starts_with("application/json"), "{path}: {kind}");
    serde_json::from_slice(&bytes).expect("JSON answer")
}

fn data(name: &str) -> String {
    format!("{}/data/{name}", env!("CARGO_MANIFEST_DIR"))
}

/// A scene file as the JSON the page sends (the TOML keys as JSON; inf as "inf").
fn scene_json(file: &str) -> Value {
    let scene = Scene::from_file(std::path::Path::new(&data(file))).expect("scene");
    serve::api::table_json(scene.table())
}

fn library_lambda(scene: &Scene, direction: Direction) -> analysis::SceneAnalysis {
    let options = Options {
        static_settings: StaticSettings::default().direction(direction),
        ..Options::default()
    };
    analysis::analyse(scene, &options).expect("analysis")
}

fn refused(answer: &(StatusCode, Value), status: StatusCode, kind: &str, key: Option<&str>) {
    let (s, body) = answer;
    assert_eq!(*s, status, "{body}");
    assert_eq!(body["kind"], kind, "{body}");
    assert_eq!(body["key"].as_str(), key, "{body}");
    let message = body["error"].as_str().expect("an error message");
    assert!(message.len() > 10, "{message}");
    if let Some(key) = key {
        assert!(
            message.contains(key),
            "the message names `{key}`: {message}"
        );
    }
}

#[test]
fn the_page_and_its_files_are_served_with_their_types() {
    let s = state();
    let (status, kind, body) = call(&s, "GET", "/", Vec::new());
    assert_eq!(status, StatusCode::OK);
    assert!(kind.starts_with("text/html"), "{kind}");
    let html = String::from_utf8(body).expect("utf-8");
    assert!(
        html.contains("app.js") && html.contains("style.css"),
        "{html}"
    );
    let (status, kind, _) = call(&s, "GET", "/app.js", Vec::new());
    assert_eq!(status, StatusCode::OK);
    assert!(kind.starts_with("text/javascript"), "{kind}");
    let (status, kind, _) = call(&s, "GET", "/style.css", Vec::new());
    assert_eq!(status, StatusCode::OK);
    assert!(kind.starts_with("text/css"), "{kind}");
    let (status, kind, body) = call(&s, "GET", "/no/such/page", Vec::new());
    assert_eq!(status, StatusCode::NOT_FOUND);
    assert!(kind.starts_with("application/json"));
    let body: Value = serde_json::from_slice(&body).expect("JSON");
    assert_eq!(body["kind"], "not_found");
}

/// The analysis of the bundled arch through the API is the CLI's, field for field, and the
/// drawing is the file `analyze --svg` writes, byte for byte.
#[test]
fn analyze_returns_the_cli_json_and_drawing() {
    let s = state();
    let scene = get_json(&s, "/api/scene");
    assert_eq!(scene["scene"], scene_json("semicircular.toml"));
    assert_eq!(scene["scene"]["material"]["friction"], "inf");
    let (status, answer) = post(&s, "/api/analyze", &json!({"scene": scene["scene"]}));
    assert_eq!(status, StatusCode::OK, "{answer}");

    let dir = tempfile::tempdir().expect("tempdir");
    let svg = dir.path().join("a.svg");
    let out = assert_cmd::Command::cargo_bin("voussoir")
        .expect("binary")
        .args(["analyze", &data("semicircular.toml"), "--json", "--svg"])
        .arg(&svg)
        .output()
        .expect("run");
    assert!(out.status.success());
    let cli: Value = serde_json::from_slice(&out.stdout).expect("CLI JSON");
    let cli = cli.as_object().expect("object");
    for (field, value) in cli {
        if field.ends_with("time_s") {
            continue; // wall-clock times differ run to run
        }
        if field == "scene" {
            // Only where the scene came from differs (a file, or the request).
            let mut api = answer[field].clone();
            api["origin"] = value["origin"].clone();
            assert_eq!(&api, value);
            continue;
        }
        assert_eq!(&answer[field], value, "field `{field}`");
    }
    assert_eq!(
        answer["svg"].as_str().expect("svg"),
        std::fs::read_to_string(&svg).expect("svg file")
    );
    roxmltree::Document::parse(answer["svg"].as_str().unwrap_or("")).expect("valid SVG");
    assert!(answer["elapsed_ms"].as_f64().is_some_and(|t| t > 0.0));
    // The TOML to download is the same scene.
    let again = Scene::from_toml_str(answer["toml"].as_str().expect("toml"), "downloaded")
        .expect("the returned TOML is a valid scene");
    let a = library_lambda(&again, Direction::Right);
    assert_eq!(a.lower.lambda, answer["lambda_lower"].as_f64());
}

/// Every preset analyses through the API to the library's value, in both directions; the
/// bare scene and the wrapped one are the same request; the symmetric arch gives the same
/// value both ways and the loaded portal does not.
#[test]
fn every_preset_analyses_to_the_library_value_in_both_directions() {
    let s = state();
    let params = get_json(&s, "/api/parameters");
    let presets = params["shapes"].as_array().expect("shapes");
    assert_eq!(presets.len(), parameters::PRESETS.len());
    for preset in presets {
        let name = preset["name"].as_str().expect("name");
        let scene_value = &preset["scene"];
        let p = parameters::PRESETS
            .iter()
            .find(|p| p.name == name)
            .expect("preset");
        let scene = Scene::from_toml_str(p.toml, name).expect("preset scene");
        let mut by_direction = Vec::new();
        for (dir, text) in [(Direction::Right, "right"), (Direction::Left, "left")] {
            if dir == Direction::Left && scene.action == voussoir::model::Action::Live {
                // A live action (the bridge's moving tandem) has no direction: the left one
                // is refused as the CLI's --direction is.
                let (status, refused) = post(
                    &s,
                    "/api/analyze",
                    &json!({"scene": scene_value, "direction": text}),
                );
                assert_eq!(status, StatusCode::BAD_REQUEST, "{name}: {refused}");
                assert_eq!(refused["kind"], "not_for_action", "{name}");
                continue;
            }
            let expected = library_lambda(&scene, dir);
            let (status, wrapped) = post(
                &s,
                "/api/analyze",
                &json!({"scene": scene_value, "direction": text}),
            );
            assert_eq!(status, StatusCode::OK, "{name}: {wrapped}");
            assert_eq!(
                wrapped["lambda_lower"].as_f64(),
                expected.lower.lambda,
                "{name} {text}"
            );
            assert_eq!(wrapped["status"], expected.lower.status.as_str(), "{name}");
            let (status, bare) = post(&s, &format!("/api/analyze?direction={text}"), scene_value);
            assert_eq!(status, StatusCode::OK);
            assert_eq!(bare["lambda_lower"], wrapped["lambda_lower"], "{name}");
            assert_eq!(bare["svg"], wrapped["svg"], "{name}");
            by_direction.push(expected.lower.lambda.expect("every preset collapses"));
        }
        let symmetric = matches!(
            name,
            "circular" | "pointed" | "basket" | "portal" | "tied_portal" | "arcade"
        );
        if by_direction.len() < 2 {
            continue;
        }
        let differ = (by_direction[0] - by_direction[1]).abs();
        if symmetric {
            assert!(differ < 1e-9, "{name}: {by_direction:?}");
        } else if name == "loaded_portal" {
            assert!(differ > 1e-3, "{name}: {by_direction:?}");
        }
    }
}

/// The tied portal's capacity slider: the page's analysis with `ties[0].capacity` set is the
/// library's with the same override, and its JSON lists the tie's force; the tie shows in the
/// drawing.
#[test]
fn the_tie_capacity_slider_analyses_as_the_library() {
    let s = state();
    let mut scene = scene_json("tied_portal.toml");
    for capacity in [0.0, 800.0, 5000.0] {
        scene["ties"][0]["capacity"] = json!(capacity);
        let (status, answer) = post(&s, "/api/analyze", &json!({"scene": scene}));
        assert_eq!(status, StatusCode::OK, "{answer}");
        let lib = Scene::from_file_with_overrides(
            std::path::Path::new(&data("tied_portal.toml")),
            &[format!("ties[0].capacity={capacity}")],
        )
        .expect("scene with the override");
        let expected = library_lambda(&lib, Direction::Right);
        assert_eq!(
            answer["lambda_lower"].as_f64(),
            expected.lower.lambda,
            "{capacity}"
        );
        let force = answer["ties"][0]["force"].as_f64().expect("tie force");
        assert!((0.0..=capacity * (1.0 + 1e-9)).contains(&force), "{force}");
        assert!(answer["svg"].as_str().expect("svg").contains("tie 0"));
    }
    let params = get_json(&s, "/api/parameters");
    let slider = params["parameters"]
        .as_array()
        .expect("parameters")
        .iter()
        .find(|p| p["key"] == "ties[0].capacity")
        .expect("the tie slider");
    assert_eq!(slider["shapes"], json!(["tied_portal"]));
}

#[test]
fn parameters_name_real_scene_keys_with_sane_ranges() {
    let s = state();
    let params = get_json(&s, "/api/parameters");
    let limits = &params["limits"];
    assert_eq!(limits["max_voussoirs"], Limits::default().max_voussoirs);
    assert_eq!(limits["max_body_bytes"], Limits::default().max_body_bytes);
    let base = Scene::from_toml_str(parameters::DEFAULT_SCENE, "default").expect("scene");
    for p in params["parameters"].as_array().expect("parameters") {
        let key = p["key"].as_str().expect("key");
        let (lo, hi, step) = (
            p["min"].as_f64().expect("min"),
            p["max"].as_f64().expect("max"),
            p["step"].as_f64().expect("step"),
        );
        assert!(lo < hi && step > 0.0 && step <= hi - lo, "{key}");
        // Every preset listed for a slider has its key, or may take it (an optional
        // section or key).
        for name in p["shapes"].as_array().expect("shapes") {
            let preset = params["shapes"]
                .as_array()
                .and_then(|ps| ps.iter().find(|q| q["name"] == *name))
                .expect("listed preset");
            let p_scene = parameters::PRESETS
                .iter()
                .find(|q| q.name == *name)
                .expect("preset")
                .toml
                .parse::<toml::Table>()
                .expect("preset TOML");
            assert_eq!(preset["scene"], serve::api::table_json(&p_scene));
            let section = key.split(['.', '[']).next().expect("section");
            let has = parameters::lookup(&p_scene, key).is_some();
            assert!(
                has || !p["absent"].is_null() || section == "seismic",
                "{key} in {name}"
            );
        }
        // The key is one the scene format knows: setting it to a value inside the slider's
        // range on the scene it applies to is accepted (or refused with its own key).
        if p["shapes"]
            .as_array()
            .is_some_and(|s| s.contains(&json!("circular")))
        {
            let mid = if p["integer"] == true {
                toml::Value::Integer(((lo + hi) / 2.0).round() as i64)
            } else {
                toml::Value::Float((lo + hi) / 2.0)
            };
            match base.with_value(key, mid) {
                Ok(_) => {}
                Err(e) => assert_eq!(e.key(), Some(key), "{key}: {e}"),
            }
        }
    }
}

/// Bad requests are 400s (413 over the size limit) with a message naming the key.
#[test]
fn bad_requests_are_refused_with_the_key_they_are_about() {
    let s = state();
    let good = scene_json("semicircular.toml");
    let with = |section: &str, key: &str, value: Value| {
        let mut scene = good.clone();
        scene[section][key] = value;
        json!({ "scene": scene })
    };
    // Malformed bodies.
    for body in [&b"{not json"[..], b"", b"[1, 2]", b"42", b"\xff\xfe"] {
        let (status, _, bytes) = call(&s, "POST", "/api/analyze", body.to_vec());
        let answer: Value = serde_json::from_slice(&bytes).expect("JSON refusal");
        refused(
            &(status, answer),
            StatusCode::BAD_REQUEST,
            "malformed_json",
            None,
        );
    }
    refused(
        &post(&s, "/api/analyze", &json!({"scene": [1, 2]})),
        StatusCode::BAD_REQUEST,
        "malformed_json",
        Some("scene"),
    );
    // Invalid scenes: the scene parser's own words, with the dotted key.
    refused(
        &post(&s, "/api/analyze", &with("arch", "thickness", json!(0.0))),
        StatusCode::BAD_REQUEST,
        "out_of_range",
        Some("arch.thickness"),
    );
    refused(
        &post(&s, "/api/analyze", &with("arch", "radius", json!(-1.0))),
        StatusCode::BAD_REQUEST,
        "out_of_range",
        Some("arch.radius"),
    );
    refused(
        &post(
            &s,
            "/api/analyze",
            &with("arch", "thickness", json!("thick")),
        ),
        StatusCode::BAD_REQUEST,
        "wrong_type",
        Some("arch.thickness"),
    );
    refused(
        &post(&s, "/api/analyze", &with("arch", "thickness", Value::Null)),
        StatusCode::BAD_REQUEST,
        "wrong_type",
        Some("arch.thickness"),
    );
    let answer = post(&s, "/api/analyze", &with("arch", "thicknes", json!(0.2)));
    refused(
        &answer,
        StatusCode::BAD_REQUEST,
        "unknown_key",
        Some("arch.thicknes"),
    );
    assert!(
        answer.1["error"]
            .as_str()
            .unwrap_or("")
            .contains("`thickness`"),
        "{}",
        answer.1
    );
    // A misspelt option is refused, not ignored (the arch would be analysed to the right).
    let answer = post(
        &s,
        "/api/analyze",
        &json!({"scene": good, "directon": "left"}),
    );
    refused(
        &answer,
        StatusCode::BAD_REQUEST,
        "unknown_field",
        Some("directon"),
    );
    assert!(
        answer.1["error"]
            .as_str()
            .unwrap_or("")
            .contains("`direction`"),
        "{}",
        answer.1
    );
    let (status, _, bytes) = call(
        &s,
        "POST",
        "/api/analyze?directon=left",
        json!({ "scene": good }).to_string().into_bytes(),
    );
    let answer: Value = serde_json::from_slice(&bytes).expect("JSON refusal");
    assert_eq!(status, StatusCode::BAD_REQUEST, "{answer}");
    assert!(
        answer["error"].as_str().unwrap_or("").contains("directon"),
        "{answer}"
    );
    // Limits: the block counts however they are written, and files.
    for count in [json!(5000), json!(20000.0), json!(1e300)] {
        refused(
            &post(&s, "/api/analyze", &with("arch", "voussoirs", count)),
            StatusCode::BAD_REQUEST,
            "limit",
            Some("arch.voussoirs"),
        );
    }
    let portal = scene_json("portal.toml");
    let mut tall = portal.clone();
    tall["piers"]["courses"] = json!(20000.0);
    refused(
        &post(&s, "/api/analyze", &tall),
        StatusCode::BAD_REQUEST,
        "limit",
        Some("piers.courses"),
    );
    let mut one_side = portal.clone();
    one_side["piers"]["left"] = json!({"courses": 5000});
    refused(
        &post(&s, "/api/analyze", &one_side),
        StatusCode::BAD_REQUEST,
        "limit",
        Some("piers.left.courses"),
    );
    let mut stepped = portal.clone();
    stepped["piers"] = json!({"shape": "stepped", "height": 1.0, "widths": vec![0.5; 5000]});
    refused(
        &post(&s, "/api/analyze", &stepped),
        StatusCode::BAD_REQUEST,
        "limit",
        Some("piers.widths"),
    );
    let mut blocks = json!({"blocks": {"file": "/etc/passwd"}, "material": good["material"]});
    refused(
        &post(&s, "/api/analyze", &blocks),
        StatusCode::BAD_REQUEST,
        "file_refused",
        Some("blocks.file"),
    );
    blocks["blocks"] = json!({"polygons": vec![json!([[0, 0], [1, 0], [1, 1]]); 1001]});
    refused(
        &post(&s, "/api/analyze", &blocks),
        StatusCode::BAD_REQUEST,
        "limit",
        Some("blocks.polygons"),
    );
    // Options.
    refused(
        &post(
            &s,
            "/api/analyze",
            &json!({"scene": good, "direction": "up"}),
        ),
        StatusCode::BAD_REQUEST,
        "bad_option",
        Some("direction"),
    );
    // Oversized: 413 with a message, and the server goes on answering.
    let big = format!(
        "{{\"scene\": {good}, \"pad\": \"{}\"}}",
        "x".repeat(Limits::default().max_body_bytes)
    );
    let (status, _, bytes) = call(&s, "POST", "/api/analyze", big.into_bytes());
    let answer: Value = serde_json::from_slice(&bytes).expect("JSON refusal");
    refused(
        &(status, answer),
        StatusCode::PAYLOAD_TOO_LARGE,
        "too_large",
        None,
    );
    let (status, _) = post(&s, "/api/analyze", &json!({ "scene": good }));
    assert_eq!(status, StatusCode::OK);
}

/// A user-block scene given inline analyses like its file: the hand-derived single block
/// b/h (width 0.4, height 1.0: lambda = 0.4).
#[test]
fn inline_blocks_analyse_and_give_b_over_h() {
    let s = state();
    let scene = json!({
        "blocks": {"polygons": [[[0.0, 0.0], [0.4, 0.0], [0.4, 1.0], [0.0, 1.0]]]},
        "material": {"unit_weight": 20000.0, "depth": 1.0}
    });
    let (status, answer) = post(&s, "/api/analyze", &scene);
    assert_eq!(status, StatusCode::OK, "{answer}");
    let lambda = answer["lambda_lower"].as_f64().expect("lambda");
    assert!((lambda - 0.4).abs() < 1e-9, "{lambda}");
}

/// The sweep's rows are the analyses of each value; whole-number keys give whole numbers
/// without repeats; bad sweeps are refused with their option named.
#[test]
fn sweep_rows_are_the_analyses_of_each_value() {
    let s = state();
    let scene = scene_json("semicircular.toml");
    let (status, answer) = post(
        &s,
        "/api/sweep",
        &json!({"scene": scene, "key": "arch.thickness", "from": 0.1, "to": 0.3, "points": 5}),
    );
    assert_eq!(status, StatusCode::OK, "{answer}");
    let rows = answer["rows"].as_array().expect("rows");
    assert_eq!(rows.len(), 5);
    let base = Scene::from_file(std::path::Path::new(&data("semicircular.toml"))).expect("scene");
    for row in rows {
        let t = row["value"].as_f64().expect("value");
        let a = library_lambda(&base.with_thickness(t).expect("scene"), Direction::Right);
        assert_eq!(row["status"], a.lower.status.as_str(), "t = {t}");
        if row["status"] == "collapse" {
            assert_eq!(row["lambda_lower"].as_f64(), a.lower.lambda, "t = {t}");
            let upper = row["lambda_upper"].as_f64().expect("upper bound");
            assert!(
                (upper - a.lower.lambda.unwrap_or(f64::NAN)).abs() < 1e-9,
                "t = {t}"
            );
        }
    }
    // The thin end cannot stand (t/R = 0.1 is below Milankovitch's 0.1075); lambda grows.
    assert_eq!(rows[0]["status"], "cannot_stand");
    let lambdas: Vec<f64> = rows[1..]
        .iter()
        .map(|r| r["lambda_lower"].as_f64().expect("lambda"))
        .collect();
    assert!(lambdas.windows(2).all(|w| w[1] > w[0]), "{lambdas:?}");

    // The values a sweep ran at.
    let swept = |body: Value| -> Vec<Value> {
        let (status, answer) = post(&s, "/api/sweep", &body);
        assert_eq!(status, StatusCode::OK, "{answer}");
        let rows = answer["rows"].as_array().expect("rows");
        rows.iter().map(|r| r["value"].clone()).collect()
    };
    let values =
        swept(json!({"scene": scene, "key": "arch.voussoirs", "from": 8, "to": 10, "points": 9}));
    assert_eq!(values, vec![json!(8), json!(9), json!(10)]);

    // A real-valued key whose value is a whole number (JSON writes 1.0 as 1) stays real.
    let portal = scene_json("portal.toml");
    let mut one = portal.clone();
    one["piers"]["height"] = json!(1);
    let heights: Vec<f64> =
        swept(json!({"scene": one, "key": "piers.height", "from": 1, "to": 2, "points": 5}))
            .iter()
            .map(|v| v.as_f64().expect("height"))
            .collect();
    assert_eq!(heights, vec![1.0, 1.25, 1.5, 1.75, 2.0]);

    let sweep = |extra: Value| {
        let mut body =
            json!({"scene": scene, "key": "arch.thickness", "from": 0.1, "to": 0.3, "points": 5});
        for (k, v) in extra.as_object().expect("object") {
            body[k] = v.clone();
        }
        post(&s, "/api/sweep", &body)
    };
    refused(
        &sweep(json!({"points": 0})),
        StatusCode::BAD_REQUEST,
        "limit",
        Some("points"),
    );
    refused(
        &sweep(json!({"points": 1000})),
        StatusCode::BAD_REQUEST,
        "limit",
        Some("points"),
    );
    refused(
        &sweep(json!({"from": 0.5})),
        StatusCode::BAD_REQUEST,
        "bad_option",
        Some("to"),
    );
    refused(
        &sweep(json!({"to": "big"})),
        StatusCode::BAD_REQUEST,
        "bad_option",
        Some("to"),
    );
    refused(
        &sweep(json!({"key": 3})),
        StatusCode::BAD_REQUEST,
        "bad_option",
        Some("key"),
    );
    let (status, answer) = sweep(json!({"key": "arch.colour"}));
    assert_eq!(status, StatusCode::BAD_REQUEST, "{answer}");
    assert!(
        answer["error"]
            .as_str()
            .unwrap_or("")
            .contains("arch.colour"),
        "{answer}"
    );
    refused(
        &sweep(json!({"key": "arch.voussoirs", "from": 19900, "to": 20000})),
        StatusCode::BAD_REQUEST,
        "limit",
        Some("to"),
    );
    refused(
        &sweep(json!({"point": 5})),
        StatusCode::BAD_REQUEST,
        "unknown_field",
        Some("point"),
    );
    let (status, answer) = sweep(json!({"key": "arch.shape", "from": 0.1, "to": 0.2}));
    assert_eq!(status, StatusCode::BAD_REQUEST, "{answer}");
    assert_eq!(
        answer["key"], "key",
        "a bad variation is about the sweep's key: {answer}"
    );
    // A sweep to the left is the library's leftward analysis (the loaded portal is not
    // symmetric).
    let loaded = scene_json("loaded_portal.toml");
    let base = Scene::from_file(std::path::Path::new(&data("loaded_portal.toml"))).expect("scene");
    let ask = json!({"scene": loaded, "key": "arch.thickness", "from": 0.4, "to": 0.5, "points": 3, "direction": "left"});
    let (status, answer) = post(&s, "/api/sweep", &ask);
    assert_eq!(status, StatusCode::OK, "{answer}");
    for row in answer["rows"].as_array().expect("rows") {
        let t = row["value"].as_f64().expect("value");
        let a = library_lambda(&base.with_thickness(t).expect("scene"), Direction::Left);
        assert_eq!(row["lambda_lower"].as_f64(), a.lower.lambda, "t = {t}");
    }
    let (status, answer) = post(&s, "/api/sweep", &json!({"key": "arch.thickness"}));
    refused(
        &(status, answer),
        StatusCode::BAD_REQUEST,
        "bad_option",
        Some("scene"),
    );
    let (status, _, bytes) = call(&s, "POST", "/api/sweep", b"{oops".to_vec());
    let answer: Value = serde_json::from_slice(&bytes).expect("JSON refusal");
    refused(
        &(status, answer),
        StatusCode::BAD_REQUEST,
        "malformed_json",
        None,
    );
}

/// The binary: `serve --port 0` prints its address on the first line, answers a real HTTP
/// request on loopback, and a bad scene file stops it with the file named.
#[test]
fn the_binary_serves_on_loopback() {
    use std::io::{BufRead, BufReader, Read, Write};
    let bin = assert_cmd::cargo::cargo_bin("voussoir");
    let mut child = std::process::Command::new(&bin)
        .args(["serve", "--port", "0", &data("portal.toml")])
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::null())
        .spawn()
        .expect("start the server");
    let mut first = String::new();
    let stdout = child.stdout.take().expect("stdout");
    BufReader::new(stdout)
        .read_line(&mut first)
        .expect("first line");
    let url = first
        .trim()
        .strip_prefix("voussoir serve: listening on http://")
        .expect("the address line")
        .trim_end_matches('/')
        .to_string();
    assert!(url.starts_with("127.0.0.1:"), "{url}");
    let answer = (|| -> std::io::Result<String> {
        let mut stream = std::net::TcpStream::connect(&url)?;
        write!(
            stream,
            "GET /api/scene HTTP/1.1\r\nHost: {url}\r\nConnection: close\r\n\r\n"
        )?;
        let mut text = String::new();
        stream.read_to_string(&mut text)?;
        Ok(text)
    })();
    let _ = child.kill();
    let _ = child.wait();
    let answer = answer.expect("an HTTP answer");
    assert!(answer.starts_with("HTTP/1.1 200"), "{answer}");
    assert!(answer.contains("\"piers\""), "the portal scene: {answer}");

    let out = std::process::Command::new(&bin)
        .args(["serve", "--port", "0", "no/such/scene.toml"])
        .output()
        .expect("run");
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("no/such/scene.toml"), "{err}");
}

/// Only this machine's own page is answered: another Host (DNS rebinding) or Origin (another
/// web site in the user's browser) is refused with 403, a POST not declared JSON with 415, and
/// a method a path does not take with a JSON 405.
#[test]
fn requests_from_elsewhere_are_refused() {
    let s = state();
    let body = json!({ "scene": scene_json("semicircular.toml") }).to_string();
    let json_type = ("content-type", "application/json");
    let kind_of = |(status, _, bytes): (StatusCode, String, Vec<u8>)| {
        let v: Value = serde_json::from_slice(&bytes).expect("JSON refusal");
        assert!(v["error"].as_str().is_some_and(|m| m.len() > 10), "{v}");
        (status, v["kind"].as_str().unwrap_or("").to_string())
    };
    for host in [
        "evil.example",
        "evil.example:8080",
        "127.0.0.1.evil.example",
        "10.0.0.1:80",
    ] {
        let answer = call_with(&s, "GET", "/api/scene", &[("host", host)], Vec::new());
        assert_eq!(
            kind_of(answer),
            (StatusCode::FORBIDDEN, "forbidden".into()),
            "{host}"
        );
    }
    for host in [
        "127.0.0.1:8080",
        "localhost:41000",
        "[::1]:8080",
        "localhost",
    ] {
        let (status, _, _) = call_with(&s, "GET", "/api/scene", &[("host", host)], Vec::new());
        assert_eq!(status, StatusCode::OK, "{host}");
    }
    for origin in [
        "http://evil.example",
        "null",
        "http://127.0.0.1.evil.example:80",
    ] {
        let answer = call_with(
            &s,
            "POST",
            "/api/analyze",
            &[json_type, ("origin", origin)],
            body.clone().into_bytes(),
        );
        assert_eq!(
            kind_of(answer),
            (StatusCode::FORBIDDEN, "forbidden".into()),
            "{origin}"
        );
    }
    let (status, _, _) = call_with(
        &s,
        "POST",
        "/api/analyze",
        &[json_type, ("origin", "http://127.0.0.1:8080")],
        body.clone().into_bytes(),
    );
    assert_eq!(status, StatusCode::OK);
    for content_type in ["text/plain", "application/x-www-form-urlencoded", ""] {
        let headers: Vec<(&str, &str)> = if content_type.is_empty() {
            Vec::new()
        } else {
            vec![("content-type", content_type)]
        };
        let answer = call_with(
            &s,
            "POST",
            "/api/analyze",
            &headers,
            body.clone().into_bytes(),
        );
        assert_eq!(
            kind_of(answer),
            (
                StatusCode::UNSUPPORTED_MEDIA_TYPE,
                "unsupported_media_type".into()
            ),
            "{content_type}"
        );
    }
    let (status, _, _) = call_with(
        &s,
        "POST",
        "/api/analyze",
        &[("content-type", "application/json; charset=utf-8")],
        body.into_bytes(),
    );
    assert_eq!(status, StatusCode::OK);
    for (method, path) in [
        ("GET", "/api/sweep"),
        ("OPTIONS", "/api/analyze"),
        ("POST", "/api/scene"),
    ] {
        let answer = call(&s, method, path, b"{}".to_vec());
        assert_eq!(
            kind_of(answer),
            (StatusCode::METHOD_NOT_ALLOWED, "method_not_allowed".into()),
            "{method} {path}"
        );
    }
}

/// The Host and Origin checks read strictly: a second Host (or Origin) header, a host with
/// text after `[::1]`, a port that is not a number, or a request line naming another host is
/// refused with 403, whichever header the loopback name is in.
#[test]
fn ambiguous_hosts_and_origins_are_refused() {
    let s = state();
    let forbidden = |answer: (StatusCode, String, Vec<u8>), what: &str| {
        let (status, _, bytes) = answer;
        let v: Value = serde_json::from_slice(&bytes).expect("JSON refusal");
        assert_eq!(status, StatusCode::FORBIDDEN, "{what}: {v}");
        assert_eq!(v["kind"], "forbidden", "{what}: {v}");
    };
    for hosts in [
        ["127.0.0.1:8080", "evil.example"],
        ["evil.example", "127.0.0.1:8080"],
        ["localhost", "localhost"],
    ] {
        let headers = [("host", hosts[0]), ("host", hosts[1])];
        forbidden(
            call_with(&s, "GET", "/api/scene", &headers, Vec::new()),
            &format!("{hosts:?}"),
        );
    }
    for host in [
        "[::1]evil.example",
        "[::1]evil.example:8080",
        "[::1].evil.example",
        "localhost:80evil",
        "localhost:",
        "127.0.0.1:8080 evil.example",
    ] {
        forbidden(
            call_with(&s, "GET", "/api/scene", &[("host", host)], Vec::new()),
            host,
        );
    }
    let body = json!({ "scene": scene_json("semicircular.toml") }).to_string();
    let json_type = ("content-type", "application/json");
    for origins in [
        &["http://[::1]evil.example"][..],
        &["http://127.0.0.1:8080/evil"],
        &["http://127.0.0.1:8080", "http://evil.example"],
    ] {
        let mut headers = vec![json_type, ("host", "127.0.0.1:8080")];
        headers.extend(origins.iter().map(|o| ("origin", *o)));
        forbidden(
            call_with(
                &s,
                "POST",
                "/api/analyze",
                &headers,
                body.clone().into_bytes(),
            ),
            &format!("{origins:?}"),
        );
    }
    // A request line naming another host (absolute form) overrides its loopback Host.
    forbidden(
        call_with(
            &s,
            "GET",
            "http://evil.example/api/scene",
            &[("host", "127.0.0.1:8080")],
            Vec::new(),
        ),
        "absolute URI",
    );
    // What a browser on this machine sends still passes.
    for (host, origin) in [
        ("127.0.0.1:8080", "http://127.0.0.1:8080"),
        ("[::1]:8080", "http://[::1]:8080"),
        ("localhost:8080", "http://localhost:8080"),
    ] {
        let (status, _, _) = call_with(
            &s,
            "POST",
            "/api/analyze",
            &[json_type, ("host", host), ("origin", origin)],
            body.clone().into_bytes(),
        );
        assert_eq!(status, StatusCode::OK, "{host} {origin}");
    }
    let (status, _, _) = call_with(
        &s,
        "GET",
        "http://127.0.0.1:8080/api/scene",
        &[("host", "127.0.0.1:8080")],
        Vec::new(),
    );
    assert_eq!(status, StatusCode::OK, "absolute URI to loopback");
}

/// The TOML to download analyses to the page's multiplier wherever it is saved: a leftward
/// analysis says so in its first line, and a start scene's relative blocks file becomes an
/// absolute path, the only file a request may name.
#[test]
fn the_downloaded_toml_stands_on_its_own() {
    let s = state();
    let loaded = scene_json("loaded_portal.toml");
    let (status, answer) = post(
        &s,
        "/api/analyze",
        &json!({"scene": loaded, "direction": "left"}),
    );
    assert_eq!(status, StatusCode::OK, "{answer}");
    let text = answer["toml"].as_str().expect("toml");
    assert!(
        text.starts_with(
            "# analysed with the earthquake to the left: voussoir analyze FILE --direction left\n"
        ),
        "{text}"
    );
    let again = Scene::from_toml_str(text, "downloaded").expect("valid TOML");
    assert_eq!(
        library_lambda(&again, Direction::Left).lower.lambda,
        answer["lambda_lower"].as_f64()
    );
    let (_, right) = post(&s, "/api/analyze", &json!({ "scene": loaded }));
    assert!(!right["toml"].as_str().unwrap_or("#").starts_with('#'));
    assert_ne!(
        right["lambda_lower"], answer["lambda_lower"],
        "the portal is not symmetric"
    );

    // A block-file start scene: its own file may be named, and is written absolute.
    let path = std::path::PathBuf::from(data("blocks_dxf_arch.toml"));
    let start = Scene::from_file(&path).expect("bundled block scene");
    let s = Arc::new(ServerState::new(start.clone(), Limits::default()));
    let scene = get_json(&s, "/api/scene")["scene"].clone();
    let file = scene["blocks"]["file"]
        .as_str()
        .expect("a blocks file")
        .to_string();
    assert!(std::path::Path::new(&file).is_relative(), "{file}");
    let (status, answer) = post(&s, "/api/analyze", &json!({ "scene": scene }));
    assert_eq!(status, StatusCode::OK, "{answer}");
    assert_eq!(
        answer["lambda_lower"].as_f64(),
        library_lambda(&start, Direction::Right).lower.lambda
    );
    let text = answer["toml"].as_str().expect("toml");
    let dir = tempfile::tempdir().expect("tempdir");
    let saved = dir.path().join("downloaded.toml");
    std::fs::write(&saved, text).expect("write");
    let again = Scene::from_file(&saved).expect("the download reads from anywhere");
    assert_eq!(
        library_lambda(&again, Direction::Right).lower.lambda,
        answer["lambda_lower"].as_f64()
    );
    // Any other file is refused, relative or absolute.
    let mut other = scene.clone();
    other["blocks"]["file"] = json!("blocks/../../Cargo.toml");
    refused(
        &post(&s, "/api/analyze", &other),
        StatusCode::BAD_REQUEST,
        "file_refused",
        Some("blocks.file"),
    );
}

/// Short timeouts, so that the tests below see them run out.
fn short_timeouts() -> serve::Timeouts {
    serve::Timeouts {
        header_read: std::time::Duration::from_millis(300),
        body_read: std::time::Duration::from_millis(300),
        shutdown_grace: std::time::Duration::from_millis(300),
    }
}

/// A server on a free loopback port in its own runtime, stopped when `stop` is sent; its
/// address, and the handle that says how it stopped.
fn server_until_stopped(
    timeouts: serve::Timeouts,
) -> (
    std::net::SocketAddr,
    tokio::sync::oneshot::Sender<()>,
    std::thread::JoinHandle<serve::Stopped>,
) {
    let (addr_tx, addr_rx) = std::sync::mpsc::channel();
    let (stop_tx, stop_rx) = tokio::sync::oneshot::channel::<()>();
    let handle = std::thread::spawn(move || {
        let rt = tokio::runtime::Builder::new_multi_thread()
            .worker_threads(2)
            .enable_all()
            .build()
            .expect("runtime");
        rt.block_on(async move {
            let listener = tokio::net::TcpListener::bind("127.0.0.1:0")
                .await
                .expect("bind");
            addr_tx
                .send(listener.local_addr().expect("addr"))
                .expect("send");
            let state = ServerState::with_default_scene(Limits::default())
                .expect("scene")
                .with_timeouts(timeouts);
            serve::serve_until(listener, Arc::new(state), async {
                let _ = stop_rx.await;
            })
            .await
        })
    });
    let addr = addr_rx.recv().expect("the server's address");
    (addr, stop_tx, handle)
}

/// Everything the server sends on `stream` until it closes the connection; an error if it
/// keeps it open for `patience` without a word (that is, for ever as far as a test goes).
fn read_until_closed(
    stream: &mut std::net::TcpStream,
    patience: std::time::Duration,
) -> std::io::Result<String> {
    use std::io::Read;
    stream.set_read_timeout(Some(patience))?;
    let mut all = Vec::new();
    let mut buf = [0u8; 4096];
    loop {
        match stream.read(&mut buf) {
            Ok(0) => return Ok(String::from_utf8_lossy(&all).into_owned()),
            Ok(n) => all.extend_from_slice(&buf[..n]),
            // A reset after an answer is a close too.
            Err(e) if e.kind() == std::io::ErrorKind::ConnectionReset => {
                return Ok(String::from_utf8_lossy(&all).into_owned())
            }
            Err(e) => return Err(e),
        }
    }
}

/// A client that sends half a request's head, one that opens a connection and says nothing,
/// and one that keeps its connection alive after an answer are all closed by the server
/// when the header-read (idle) timeout runs out; a body sent in part is refused with a 400
/// when the body's timeout runs out. Before the timeouts, each held its connection for ever.
#[test]
fn slow_and_idle_clients_are_closed_by_the_timeouts() {
    use std::io::Write;
    let (addr, stop, server) = server_until_stopped(short_timeouts());
    let patience = std::time::Duration::from_secs(15);

    let mut half_head = std::net::TcpStream::connect(addr).expect("connect");
    half_head
        .write_all(b"GET /api/scene HTTP/1.1\r\nHost: 127.0.0.1\r\n")
        .expect("write");
    let mut silent = std::net::TcpStream::connect(addr).expect("connect");
    let mut kept_alive = std::net::TcpStream::connect(addr).expect("connect");
    kept_alive
        .write_all(b"GET /no/such/page HTTP/1.1\r\nHost: 127.0.0.1\r\n\r\n")
        .expect("write");
    let mut half_body = std::net::TcpStream::connect(addr).expect("connect");
    half_body
        .write_all(
            b"POST /api/analyze HTTP/1.1\r\nHost: 127.0.0.1\r\nContent-Type: application/json\r\nContent-Length: 100\r\n\r\n{\"arch\": ",
        )
        .expect("write");

    let closed = |stream: &mut std::net::TcpStream, what: &str| {
        read_until_closed(stream, patience)
            .unwrap_or_else(|e| panic!("{what}: the server kept the connection open ({e})"))
    };
    assert_eq!(
        closed(&mut half_head, "half a head"),
        "",
        "no answer to half a head"
    );
    assert_eq!(closed(&mut silent, "a silent client"), "");
    let answer = closed(&mut kept_alive, "an idle kept-alive connection");
    assert!(answer.starts_with("HTTP/1.1 404"), "{answer}");
    assert!(
        !answer.contains("connection: close"),
        "kept alive: {answer}"
    );
    let answer = closed(&mut half_body, "half a body");
    assert!(answer.starts_with("HTTP/1.1 400"), "{answer}");
    assert!(
        answer.contains("bad_body") && answer.contains("did not arrive"),
        "{answer}"
    );

    // The server itself is well: a whole request is answered.
    let mut whole = std::net::TcpStream::connect(addr).expect("connect");
    whole
        .write_all(b"GET /api/scene HTTP/1.1\r\nHost: 127.0.0.1\r\nConnection: close\r\n\r\n")
        .expect("write");
    let answer = closed(&mut whole, "a whole request");
    assert!(answer.starts_with("HTTP/1.1 200"), "{answer}");
    stop.send(()).expect("stop");
    assert_eq!(server.join().expect("server"), serve::Stopped::Clean);
}

/// Asked to stop, the server takes no new connection and waits for a request in flight no
/// longer than its grace: a client that sent half a request and stays does not keep it
/// running (before, it did until the client left).
#[test]
fn shutdown_waits_at_most_the_grace_for_a_half_sent_request() {
    use std::io::Write;
    let timeouts = serve::Timeouts {
        // Longer than the test's patience: only the grace can end the server.
        header_read: std::time::Duration::from_secs(600),
        ..short_timeouts()
    };
    let (addr, stop, server) = server_until_stopped(timeouts);
    let mut half = std::net::TcpStream::connect(addr).expect("connect");
    half.write_all(b"POST /api/analyze HTTP/1.1\r\nHost: 127.0")
        .expect("write");
    // The connection is taken before the stop.
    std::thread::sleep(std::time::Duration::from_millis(200));
    stop.send(()).expect("stop");
    let (done_tx, done_rx) = std::sync::mpsc::channel();
    std::thread::spawn(move || {
        let _ = done_tx.send(server.join());
    });
    let stopped = done_rx
        .recv_timeout(std::time::Duration::from_secs(20))
        .expect("the server stops within its grace")
        .expect("server thread");
    assert_eq!(stopped, serve::Stopped::GraceExpired { open: 1 });
    drop(half);
}

/// The binary: with a client that sent half a request and stays, and another whose
/// connection is kept alive, SIGINT (Ctrl-C) stops `voussoir serve` within its grace and it
/// says so.
#[cfg(unix)]
#[test]
fn ctrl_c_stops_the_binary_despite_a_half_sent_request() {
    use std::io::{BufRead, BufReader, Read, Write};
    let bin = assert_cmd::cargo::cargo_bin("voussoir");
    let mut child = std::process::Command::new(&bin)
        .args(["serve", "--port", "0"])
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::null())
        .spawn()
        .expect("start the server");
    let mut stdout = BufReader::new(child.stdout.take().expect("stdout"));
    let mut first = String::new();
    stdout.read_line(&mut first).expect("first line");
    let url = first
        .trim()
        .strip_prefix("voussoir serve: listening on http://")
        .expect("the address line")
        .trim_end_matches('/')
        .to_string();
    let mut half = std::net::TcpStream::connect(&url).expect("connect");
    half.write_all(b"GET /api/scene HTTP/1.1\r\nHost: 127.0.0.1\r\n")
        .expect("write");
    let mut alive = std::net::TcpStream::connect(&url).expect("connect");
    alive
        .write_all(b"GET /no/such/page HTTP/1.1\r\nHost: 127.0.0.1\r\n\r\n")
        .expect("write");
    let mut buf = [0u8; 64];
    let n = alive.read(&mut buf).expect("an answer");
    assert!(buf[..n].starts_with(b"HTTP/1.1 404"));
    let sent = std::process::Command::new("kill")
        .args(["-INT", &child.id().to_string()])
        .status()
        .expect("kill -INT");
    assert!(sent.success());
    // The default grace is 5 s; a minute is "never" for this test.
    let start = std::time::Instant::now();
    let status = loop {
        if let Some(status) = child.try_wait().expect("wait") {
            break Some(status);
        }
        if start.elapsed() > std::time::Duration::from_secs(60) {
            break None;
        }
        std::thread::sleep(std::time::Duration::from_millis(50));
    };
    let Some(status) = status else {
        let _ = child.kill();
        let _ = child.wait();
        panic!("voussoir serve did not stop within a minute of SIGINT");
    };
    assert!(status.success(), "{status}");
    let mut rest = String::new();
    stdout.read_to_string(&mut rest).expect("the last lines");
    assert!(rest.contains("voussoir serve: stopped"), "{rest}");
    drop((half, alive));
}

/// Each pier slider applies to the pier profiles it lists (`pier_shapes`) and to no other:
/// on a portal of each profile (rectangular, stepped, battered), a value inside the slider's
/// range is accepted for a listed profile and refused, naming the key, for the others (a
/// stepped pier has no `width`, and its `courses` are its number of widths); the stepped
/// pier's widths are a list (`list`), which the API analyses to the library's value.
#[test]
fn pier_sliders_apply_to_the_pier_profiles_they_list() {
    let s = state();
    let params = get_json(&s, "/api/parameters");
    let profiles = [
        ("portal.toml", "rectangular"),
        ("stepped_portal.toml", "stepped"),
        ("battered_portal.toml", "battered"),
    ];
    let mut applied = std::collections::BTreeSet::new();
    for p in params["parameters"].as_array().expect("parameters") {
        let key = p["key"].as_str().expect("key");
        if !key.starts_with("piers.") {
            continue;
        }
        let shapes: Vec<&str> = p["pier_shapes"]
            .as_array()
            .expect("pier_shapes")
            .iter()
            .filter_map(Value::as_str)
            .collect();
        let (lo, hi) = (
            p["min"].as_f64().expect("min"),
            p["max"].as_f64().expect("max"),
        );
        let entry = |x: f64| {
            if p["integer"] == true {
                toml::Value::Integer(x.round() as i64)
            } else {
                toml::Value::Float(x)
            }
        };
        for (file, profile) in profiles {
            let scene = Scene::from_file(std::path::Path::new(&data(file))).expect("scene");
            let n = scene.piers.as_ref().expect("piers").left.courses;
            // A value the slider can reach; a list as long as the pier's courses.
            let value = if p["list"] == true {
                toml::Value::Array(
                    (0..n)
                        .map(|i| entry(hi.min(0.6) - 0.05 * i as f64))
                        .collect(),
                )
            } else if key == "piers.courses" {
                // Any count but the stepped pier's own number of widths (the one value a
                // courses slider could give without an error there).
                entry(n as f64 + 1.0)
            } else {
                entry(lo + (hi - lo) / 4.0)
            };
            let listed = shapes.is_empty() || shapes.contains(&profile);
            match scene.with_value(key, value.clone()) {
                Ok(changed) => {
                    assert!(
                        listed,
                        "{key} = {value} on a {profile} pier is accepted but not offered"
                    );
                    applied.insert((key.to_string(), profile));
                    // Through the API too, to the library's multiplier.
                    let body = json!({"scene": serve::api::table_json(changed.table())});
                    let (status, answer) = post(&s, "/api/analyze", &body);
                    assert_eq!(status, StatusCode::OK, "{key} on {profile}: {answer}");
                    let lib = library_lambda(&changed, Direction::Right);
                    assert_eq!(answer["lambda_lower"].as_f64(), lib.lower.lambda, "{key}");
                }
                Err(e) => {
                    assert!(
                        !listed,
                        "{key} = {value} on a {profile} pier is offered but refused: {e}"
                    );
                    assert!(
                        e.to_string().contains(key.trim_start_matches("piers.")),
                        "{e}"
                    );
                }
            }
        }
    }
    for (key, profile) in [
        ("piers.width", "rectangular"),
        ("piers.widths", "stepped"),
        ("piers.bottom_width", "battered"),
        ("piers.top_width", "battered"),
        ("piers.courses", "battered"),
        ("piers.height", "stepped"),
    ] {
        assert!(
            applied.contains(&(key.to_string(), profile)),
            "no slider for {key} on a {profile} pier"
        );
    }
}

/// With crushing and finite friction the upper bound of a sweep comes from a search with
/// rigid hinges (the certified mechanism of the compressed zones does not apply to sliding):
/// its rows say so (`upper_rigid`, `kinematic_search`), as does the analysis, whose note
/// says it too; without crushing, or with the certified search, the upper bound is the
/// structure's own.
#[test]
fn an_upper_bound_that_ignores_crushing_is_marked_rigid() {
    let s = state();
    let mut scene = scene_json("semicircular.toml");
    scene["material"]["compressive_strength"] = json!(5e6);
    scene["material"]["friction"] = json!(0.6);
    let body =
        json!({"scene": scene, "key": "arch.thickness", "from": 0.3, "to": 0.7, "points": 3});
    let (status, answer) = post(&s, "/api/sweep", &body);
    assert_eq!(status, StatusCode::OK, "{answer}");
    let table = match serve::api::to_toml("", &scene).expect("TOML") {
        toml::Value::Table(t) => t,
        other => panic!("not a table: {other}"),
    };
    let base = Scene::from_table_in(table, "scene", None).expect("scene");
    for row in answer["rows"].as_array().expect("rows") {
        let t = row["value"].as_f64().expect("value");
        let case = base
            .with_value("arch.thickness", toml::Value::Float(t))
            .expect("scene");
        let a = library_lambda(&case, Direction::Right);
        assert_eq!(row["lambda_upper"].as_f64(), a.lambda_upper(), "t = {t}");
        assert_ne!(row["kinematic_search"], "certified", "{row}");
        assert_eq!(row["upper_rigid"], true, "{row}");
        let note = a
            .upper
            .as_ref()
            .ok()
            .and_then(|k| k.note.clone())
            .unwrap_or_default();
        assert!(note.contains("rigid hinges"), "{note}");
    }
    // The analysis of one scene says the same.
    let said = |scene: &Value| {
        let (status, one) = post(&s, "/api/analyze", &json!({"scene": scene}));
        assert_eq!(status, StatusCode::OK, "{}", one["error"]);
        (one["upper_rigid"].clone(), one["kinematic_search"].clone())
    };
    scene["arch"]["thickness"] = json!(0.5);
    assert_eq!(said(&scene), (json!(true), json!("exhaustive")));
    // Joints that cannot slide: the certified mechanism about the compressed zones.
    scene["material"]["friction"] = json!("inf");
    assert_eq!(said(&scene), (json!(false), json!("certified")));
    // No crushing: the rigid structure is the structure.
    let mut rigid = scene_json("semicircular.toml");
    rigid["material"]["friction"] = json!(0.6);
    rigid["arch"]["thickness"] = json!(0.5);
    assert_eq!(said(&rigid).0, json!(false));
}

/// A live scene (`[action] kind = "live"`): analysed as the CLI does (the adequacy factor,
/// `action: "live"`, live loads labelled as multiplied), and a direction for it is the
/// client's mistake, a 400 naming the action, not a server failure.
#[test]
fn a_live_scene_is_analysed_and_a_direction_for_it_refused() {
    let s = state();
    let scene = scene_json("live_load_arch.toml");
    let (status, body) = post(&s, "/api/analyze", &json!({ "scene": scene }));
    assert_eq!(status, StatusCode::OK, "{body}");
    assert_eq!(body["action"], "live");
    let lib = library_lambda(
        &Scene::from_file(std::path::Path::new(&data("live_load_arch.toml"))).expect("scene"),
        Direction::Right,
    );
    assert_eq!(body["lambda_lower"].as_f64(), lib.lower.lambda);
    assert!(body["svg"].as_str().expect("svg").contains("λ × 20 kN"));
    let answer = post(
        &s,
        "/api/analyze",
        &json!({ "scene": scene, "direction": "left" }),
    );
    refused(&answer, StatusCode::BAD_REQUEST, "not_for_action", None);
    assert!(answer.1["error"]
        .as_str()
        .expect("message")
        .contains("live"));
}

/// Issue 27: the page's "Report .html" download is `voussoir report` of the scene the TOML
/// download writes: the same chapters and numbers, the same SHA-256 of the same text.
#[test]
fn the_report_is_the_clis_report_of_the_downloaded_toml() {
    let s = state();
    let scene = get_json(&s, "/api/scene");
    let (status, answer) = post(&s, "/api/analyze", &json!({"scene": scene["scene"]}));
    assert_eq!(status, StatusCode::OK, "{answer}");
    let toml_text = answer["toml"].as_str().expect("toml").to_string();
    let (status, report) = post(&s, "/api/report", &json!({"scene": scene["scene"]}));
    assert_eq!(status, StatusCode::OK, "{report}");
    let page = report["html"].as_str().expect("html");
    let dir = tempfile::tempdir().expect("tempdir");
    let path = dir.path().join("scene.toml");
    std::fs::write(&path, &toml_text).expect("write");
    let out = assert_cmd::Command::cargo_bin("voussoir")
        .expect("binary")
        .arg("report")
        .arg(&path)
        .output()
        .expect("run");
    assert!(out.status.success());
    let cli = String::from_utf8(out.stdout).expect("utf-8");
    // Where the scene came from and the wall times in the summaries differ; the rest is the
    // same page.
    let strip = |html: &str| -> Vec<String> {
        html.lines()
            .filter(|l| {
                !l.contains(" ms")
                    && !l.contains("scene.toml")
                    && !l.contains("Scene file")
                    && !l.contains("scene file</th>")
            })
            .map(str::to_string)
            .collect()
    };
    let (a, b) = (strip(page), strip(cli.trim_end()));
    assert_eq!(a.len(), b.len());
    for (x, y) in a.iter().zip(&b) {
        assert_eq!(x, y);
    }
    use sha2::Digest;
    let sha: String = sha2::Sha256::digest(toml_text.as_bytes())
        .iter()
        .map(|b| format!("{b:02x}"))
        .collect();
    assert!(page.contains(&sha));
    // An invalid scene is refused as /api/analyze refuses it.
    let mut bad = scene["scene"].clone();
    bad["arch"]["thickness"] = json!(-1.0);
    let (status, err) = post(&s, "/api/report", &json!({"scene": bad}));
    assert_eq!(status, StatusCode::BAD_REQUEST, "{err}");
    assert_eq!(err["key"], "arch.thickness");
}
