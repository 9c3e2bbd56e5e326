//! The JSON API of `voussoir serve` (docs/web.md, "The API").
//!
//! - `GET /api/scene`: the scene the server was started with, as JSON and as TOML.
//! - `GET /api/parameters`: the sliders, the presets and the limits.
//! - `POST /api/analyze`: a scene (the TOML keys as JSON) -> the object `voussoir analyze
//!   --json` prints, plus `svg` (the drawing `analyze --svg` writes), `toml` and
//!   `elapsed_ms`.
//! - `POST /api/sweep`: a scene, a key and a range -> one row per value, as `voussoir sweep`.
//!
//! Every refusal is a JSON object `{"error", "key", "kind"}`: 400 for a request that cannot be
//! analysed (malformed JSON, an invalid scene, a limit exceeded), 413 for a body over the
//! limit, 404 for an unknown path, 500 when the analysis itself fails.

use super::{parameters, Limits, ServerState};
use crate::analysis::{self, Options};
use crate::error::{AnalysisError, SceneError};
use crate::lp::StaticSettings;
use crate::outcome::Direction;
use crate::report;
use crate::scene::Scene;
use crate::sweep::{self, Sweep, Variation};
use axum::body::Bytes;
use axum::extract::rejection::{BytesRejection, QueryRejection};
use axum::extract::{Query, State};
use axum::http::{StatusCode, Uri};
use axum::response::{IntoResponse, Response};
use axum::Json;
use serde::Deserialize;
use serde_json::{json, Map, Value as JsonValue};
use std::sync::Arc;
use std::time::Instant;
use toml::Value as Toml;

/// A refused request: its HTTP status, the message, the scene key it is about (dotted, when
/// there is one) and a short machine-readable kind.
#[derive(Debug, Clone, PartialEq)]
pub struct ApiError {
    pub status: StatusCode,
    pub message: String,
    pub key: Option<String>,
    pub kind: &'static str,
}

impl ApiError {
    fn bad(kind: &'static str, key: Option<&str>, message: impl Into<String>) -> Self {
        ApiError {
            status: StatusCode::BAD_REQUEST,
            message: message.into(),
            key: key.map(str::to_string),
            kind,
        }
    }
}

impl IntoResponse for ApiError {
    fn into_response(self) -> Response {
        let body = json!({"error": self.message, "key": self.key, "kind": self.kind});
        (self.status, Json(body)).into_response()
    }
}

impl From<SceneError> for ApiError {
    fn from(e: SceneError) -> Self {
        let kind = match &e {
            SceneError::Io { .. } => "io",
            SceneError::Syntax { .. } => "syntax",
            SceneError::UnknownKey { .. } => "unknown_key",
            SceneError::MissingKey { .. } => "missing_key",
            SceneError::WrongType { .. } => "wrong_type",
            SceneError::OutOfRange { .. } => "out_of_range",
            SceneError::BadOverride { .. } => "bad_override",
            SceneError::BadVariation { .. } => "bad_variation",
            SceneError::BadChart { .. } => "bad_chart",
            SceneError::BadBlocks { .. } => "bad_blocks",
            SceneError::Usage(_) => "usage",
        };
        let key = e.key().map(str::to_string);
        ApiError {
            status: StatusCode::BAD_REQUEST,
            message: e.to_string(),
            key,
            kind,
        }
    }
}

impl From<AnalysisError> for ApiError {
    fn from(e: AnalysisError) -> Self {
        match e {
            AnalysisError::Scene(e) => e.into(),
            other => ApiError {
                status: StatusCode::INTERNAL_SERVER_ERROR,
                message: other.to_string(),
                key: None,
                kind: "analysis",
            },
        }
    }
}

/// A body that could not be read: over the limit (413) or cut short (400).
fn body_error(e: BytesRejection, limits: &Limits) -> ApiError {
    let status = e.status();
    if status == StatusCode::PAYLOAD_TOO_LARGE {
        ApiError {
            status,
            message: format!(
                "request body over the limit of {} bytes",
                limits.max_body_bytes
            ),
            key: None,
            kind: "too_large",
        }
    } else {
        ApiError {
            status: StatusCode::BAD_REQUEST,
            message: format!("cannot read the request body: {}", e.body_text()),
            key: None,
            kind: "bad_body",
        }
    }
}

/// The query string's options (`?direction=left`).
#[derive(Debug, Default, Deserialize)]
pub struct QueryOptions {
    pub direction: Option<String>,
}

/// `"right"` or `"left"`.
fn direction(text: Option<&str>) -> Result<Direction, ApiError> {
    match text {
        None | Some("right") => Ok(Direction::Right),
        Some("left") => Ok(Direction::Left),
        Some(other) => Err(ApiError::bad(
            "bad_option",
            Some("direction"),
            format!("direction = \"{other}\": must be \"right\" or \"left\""),
        )),
    }
}

/// Parse a body as one JSON object.
fn json_object(body: &[u8]) -> Result<Map<String, JsonValue>, ApiError> {
    let value: JsonValue = serde_json::from_slice(body).map_err(|e| {
        ApiError::bad(
            "malformed_json",
            None,
            format!("the request body is not valid JSON: {e}"),
        )
    })?;
    match value {
        JsonValue::Object(map) => Ok(map),
        other => Err(ApiError::bad(
            "malformed_json",
            None,
            format!(
                "the request body must be a JSON object (a scene, or {{\"scene\": ...}}), not {}",
                json_kind(&other)
            ),
        )),
    }
}

fn json_kind(v: &JsonValue) -> &'static str {
    match v {
        JsonValue::Null => "null",
        JsonValue::Bool(_) => "a boolean",
        JsonValue::Number(_) => "a number",
        JsonValue::String(_) => "a string",
        JsonValue::Array(_) => "an array",
        JsonValue::Object(_) => "an object",
    }
}

/// A JSON value as TOML; `path` (the dotted key) names it in errors. JSON has no infinity:
/// the scene format's string "inf" stands for it, and an absent friction or strength means
/// infinite anyway.
pub fn to_toml(path: &str, v: &JsonValue) -> Result<Toml, ApiError> {
    Ok(match v {
        JsonValue::Null => {
            return Err(ApiError::bad(
                "wrong_type",
                Some(path),
                format!("`{path}` = null: leave the key out instead (null is not a TOML value)"),
            ))
        }
        JsonValue::Bool(b) => Toml::Boolean(*b),
        JsonValue::Number(n) => match (n.as_i64(), n.as_f64()) {
            (Some(i), _) => Toml::Integer(i),
            (None, Some(x)) => Toml::Float(x),
            (None, None) => {
                return Err(ApiError::bad(
                    "wrong_type",
                    Some(path),
                    format!("`{path}` = {n}: not a number TOML can hold"),
                ))
            }
        },
        JsonValue::String(s) => Toml::String(s.clone()),
        JsonValue::Array(items) => Toml::Array(
            items
                .iter()
                .enumerate()
                .map(|(i, item)| to_toml(&format!("{path}[{i}]"), item))
                .collect::<Result<_, _>>()?,
        ),
        JsonValue::Object(map) => Toml::Table(to_table(path, map)?),
    })
}

fn to_table(path: &str, map: &Map<String, JsonValue>) -> Result<toml::Table, ApiError> {
    map.iter()
        .map(|(k, v)| {
            let key = if path.is_empty() {
                k.clone()
            } else {
                format!("{path}.{k}")
            };
            Ok((k.clone(), to_toml(&key, v)?))
        })
        .collect()
}

/// A TOML value as JSON, infinities as the string "inf" (JSON has none).
pub fn to_json(v: &Toml) -> JsonValue {
    match v {
        Toml::String(s) => JsonValue::String(s.clone()),
        Toml::Integer(i) => json!(i),
        Toml::Float(x) if x.is_finite() => json!(x),
        Toml::Float(x) if x.is_nan() => JsonValue::String("nan".into()),
        Toml::Float(x) => JsonValue::String(if *x > 0.0 { "inf" } else { "-inf" }.into()),
        Toml::Boolean(b) => json!(b),
        Toml::Datetime(d) => JsonValue::String(d.to_string()),
        Toml::Array(items) => JsonValue::Array(items.iter().map(to_json).collect()),
        Toml::Table(t) => table_json(t),
    }
}

/// A TOML table as a JSON object.
pub fn table_json(t: &toml::Table) -> JsonValue {
    JsonValue::Object(t.iter().map(|(k, v)| (k.clone(), to_json(v))).collect())
}

/// Refuse, before anything is built, a scene larger than the limits or naming a file the
/// server was not started with.
fn check_limits(table: &toml::Table, state: &ServerState) -> Result<(), ApiError> {
    let limits = &state.limits;
    let count =
        |section: Option<&Toml>, key: &str| -> Option<i64> { section?.get(key)?.as_integer() };
    let too_many = |key: &str, n: i64, max: usize, what: &str| {
        ApiError::bad(
            "limit",
            Some(key),
            format!(
                "`{key}` = {n}: the server takes at most {max} {what} (the CLI takes more: `voussoir analyze`)"
            ),
        )
    };
    if let Some(n) = count(table.get("arch"), "voussoirs") {
        if n > limits.max_voussoirs as i64 {
            return Err(too_many(
                "arch.voussoirs",
                n,
                limits.max_voussoirs,
                "voussoirs",
            ));
        }
    }
    let piers = table.get("piers");
    let sides = [
        ("piers.courses", count(piers, "courses")),
        (
            "piers.left.courses",
            count(piers.and_then(|p| p.get("left")), "courses"),
        ),
        (
            "piers.right.courses",
            count(piers.and_then(|p| p.get("right")), "courses"),
        ),
    ];
    for (key, n) in sides {
        if let Some(n) = n.filter(|&n| n > limits.max_voussoirs as i64) {
            return Err(too_many(key, n, limits.max_voussoirs, "courses per pier"));
        }
    }
    if let Some(blocks) = table.get("blocks") {
        if let Some(polygons) = blocks.get("polygons").and_then(|p| p.as_array()) {
            if polygons.len() > limits.max_blocks {
                return Err(too_many(
                    "blocks.polygons",
                    polygons.len() as i64,
                    limits.max_blocks,
                    "blocks",
                ));
            }
        }
        if let Some(file) = blocks.get("file") {
            let allowed = state.blocks_file.as_deref();
            if file.as_str() != allowed {
                return Err(ApiError::bad(
                    "file_refused",
                    Some("blocks.file"),
                    format!(
                        "`blocks.file` = {file}: the server reads no files on request{}; give the blocks inline as `blocks.polygons`",
                        allowed.map_or(String::new(), |a| format!(" (only \"{a}\", the file of the scene it was started with)"))
                    ),
                ));
            }
        }
    }
    Ok(())
}

/// The scene of a request: the whole body, or its `scene` member.
fn request_scene(
    body: &Map<String, JsonValue>,
    state: &ServerState,
) -> Result<(Scene, Option<String>), ApiError> {
    let (scene, direction) = match body.get("scene") {
        Some(JsonValue::Object(scene)) => {
            let direction = match body.get("direction") {
                None => None,
                Some(JsonValue::String(d)) => Some(d.clone()),
                Some(other) => {
                    return Err(ApiError::bad(
                        "bad_option",
                        Some("direction"),
                        format!(
                            "direction must be \"right\" or \"left\", not {}",
                            json_kind(other)
                        ),
                    ))
                }
            };
            (scene, direction)
        }
        Some(other) => {
            return Err(ApiError::bad(
                "malformed_json",
                Some("scene"),
                format!(
                    "`scene` must be an object of scene sections, not {}",
                    json_kind(other)
                ),
            ))
        }
        None => (body, None),
    };
    let table = to_table("", scene)?;
    check_limits(&table, state)?;
    let scene = Scene::from_table_in(table, "scene", state.base_dir.as_deref())?;
    Ok((scene, direction))
}

/// Run `work` off the async threads; a panic in it becomes a 500, not a dead server.
async fn blocking<T, F>(work: F) -> Result<T, ApiError>
where
    T: Send + 'static,
    F: FnOnce() -> Result<T, ApiError> + Send + 'static,
{
    tokio::task::spawn_blocking(work).await.unwrap_or_else(|e| {
        Err(ApiError {
            status: StatusCode::INTERNAL_SERVER_ERROR,
            message: format!("the analysis stopped unexpectedly ({e}); please report the scene"),
            key: None,
            kind: "internal",
        })
    })
}

fn options(direction: Direction) -> Options {
    Options {
        static_settings: StaticSettings::default().direction(direction),
        ..Options::default()
    }
}

/// `GET /api/scene`.
pub async fn scene(State(state): State<Arc<ServerState>>) -> Response {
    let table = state.scene.table();
    Json(json!({
        "scene": table_json(table),
        "toml": toml::to_string(table).unwrap_or_default(),
        "origin": state.scene.origin,
    }))
    .into_response()
}

/// `GET /api/parameters`.
pub async fn parameters(State(state): State<Arc<ServerState>>) -> Response {
    let shapes: Vec<JsonValue> = parameters::PRESETS
        .iter()
        .map(|p| {
            let scene = p
                .toml
                .parse::<toml::Table>()
                .map(|t| table_json(&t))
                .unwrap_or(JsonValue::Null);
            let ranges: Map<String, JsonValue> = p
                .ranges
                .iter()
                .map(|(k, lo, hi)| (k.to_string(), json!([lo, hi])))
                .collect();
            json!({"name": p.name, "label": p.label, "scene": scene, "ranges": ranges})
        })
        .collect();
    let l = state.limits;
    Json(json!({
        "parameters": parameters::parameters(),
        "shapes": shapes,
        "limits": {
            "max_voussoirs": l.max_voussoirs,
            "max_blocks": l.max_blocks,
            "max_body_bytes": l.max_body_bytes,
            "max_sweep_points": l.max_sweep_points,
        },
    }))
    .into_response()
}

/// `POST /api/analyze`.
pub async fn analyze(
    State(state): State<Arc<ServerState>>,
    query: Result<Query<QueryOptions>, QueryRejection>,
    body: Result<Bytes, BytesRejection>,
) -> Result<Response, ApiError> {
    let start = Instant::now();
    let body = body.map_err(|e| body_error(e, &state.limits))?;
    let body = json_object(&body)?;
    let (scene, in_body) = request_scene(&body, &state)?;
    let query = query.map_err(|e| {
        ApiError::bad(
            "bad_option",
            None,
            format!("bad query string: {}", e.body_text()),
        )
    })?;
    let dir_text = query.0.direction.or(in_body);
    let dir = direction(dir_text.as_deref())?;
    let mut out = blocking(move || {
        let a = analysis::analyse(&scene, &options(dir))?;
        let svg = report::analysis_svg(&scene, &a, dir).map_err(|e| ApiError {
            status: StatusCode::INTERNAL_SERVER_ERROR,
            message: format!("cannot draw the structure: {e}"),
            key: None,
            kind: "drawing",
        })?;
        let mut out = match serde_json::to_value(report::AnalysisReport::new(&scene, &a)) {
            Ok(JsonValue::Object(map)) => map,
            _ => Map::new(),
        };
        out.insert("svg".into(), JsonValue::String(svg));
        out.insert(
            "toml".into(),
            JsonValue::String(toml::to_string(scene.table()).unwrap_or_default()),
        );
        Ok(out)
    })
    .await?;
    out.insert(
        "elapsed_ms".into(),
        json!(start.elapsed().as_secs_f64() * 1e3),
    );
    Ok(Json(JsonValue::Object(out)).into_response())
}

/// The values of a sweep from `from` to `to` in `points` steps; whole numbers, without
/// repeats, for a whole-number key (voussoirs, courses).
fn sweep_values(scene: &Scene, key: &str, from: f64, to: f64, points: usize) -> Vec<Toml> {
    let current = parameters::lookup(scene.table(), key);
    let at = |i: usize| {
        if points == 1 {
            from
        } else {
            from + (to - from) * i as f64 / (points - 1) as f64
        }
    };
    // A key a slider describes says itself whether it is whole (JSON writes 1.0 as 1, so the
    // scene's value alone cannot tell a pier height of 1 m from a count); any other key
    // follows the type of its value in the scene.
    let whole = match parameters::SLIDERS.iter().find(|p| p.key == key) {
        Some(p) => p.integer,
        None => matches!(current, Some(Toml::Integer(_))),
    };
    if whole {
        let mut values: Vec<i64> = (0..points).map(|i| at(i).round() as i64).collect();
        values.dedup();
        values.into_iter().map(Toml::Integer).collect()
    } else {
        (0..points).map(|i| Toml::Float(at(i))).collect()
    }
}

fn number(body: &Map<String, JsonValue>, name: &str) -> Result<f64, ApiError> {
    match body.get(name) {
        Some(JsonValue::Number(n)) => n.as_f64().filter(|x| x.is_finite()).ok_or_else(|| {
            ApiError::bad(
                "bad_option",
                Some(name),
                format!("`{name}` = {n}: not a finite number"),
            )
        }),
        Some(other) => Err(ApiError::bad(
            "bad_option",
            Some(name),
            format!("`{name}` must be a number, not {}", json_kind(other)),
        )),
        None => Err(ApiError::bad(
            "bad_option",
            Some(name),
            format!(
                "missing `{name}` (the sweep runs `key` from `from` to `to` in `points` values)"
            ),
        )),
    }
}

/// `POST /api/sweep`.
pub async fn sweep(
    State(state): State<Arc<ServerState>>,
    body: Result<Bytes, BytesRejection>,
) -> Result<Response, ApiError> {
    let start = Instant::now();
    let body = body.map_err(|e| body_error(e, &state.limits))?;
    let body = json_object(&body)?;
    if !body.contains_key("scene") {
        return Err(ApiError::bad(
            "bad_option",
            Some("scene"),
            "missing `scene`: the sweep's body is {\"scene\": {...}, \"key\": ..., \"from\": ..., \"to\": ..., \"points\": ...}",
        ));
    }
    let (scene, in_body) = request_scene(&body, &state)?;
    let dir = direction(in_body.as_deref())?;
    let key = match body.get("key") {
        Some(JsonValue::String(k)) if !k.trim().is_empty() => k.trim().to_string(),
        _ => {
            return Err(ApiError::bad(
                "bad_option",
                Some("key"),
                "`key` must name the scene key to vary, e.g. \"arch.thickness\" (or a ratio such as \"t/R\")",
            ))
        }
    };
    let (from, to) = (number(&body, "from")?, number(&body, "to")?);
    if from > to {
        return Err(ApiError::bad(
            "bad_option",
            Some("to"),
            format!("`to` = {to} is below `from` = {from}"),
        ));
    }
    let max = state.limits.max_sweep_points;
    let points = match body.get("points") {
        Some(JsonValue::Number(n)) => n.as_u64(),
        None => Some(21),
        _ => None,
    }
    .filter(|&p| (1..=max as u64).contains(&p))
    .ok_or_else(|| {
        ApiError::bad(
            "limit",
            Some("points"),
            format!("`points` must be a whole number from 1 to {max}"),
        )
    })? as usize;
    let values = sweep_values(&scene, &key, from, to, points);
    let label = sweep::key_label(&key);
    let rows = blocking(move || {
        let sweep = Sweep::new(&scene, vec![Variation { key, values }])?;
        Ok(sweep.run(&options(dir), false, &|| {}))
    })
    .await?;
    let rows: Vec<JsonValue> = rows
        .iter()
        .map(|r| {
            json!({
                "value": r.values.first().map_or(JsonValue::Null, to_json),
                "status": r.status,
                "lambda_lower": r.lambda_lower,
                "lambda_upper": r.lambda_upper,
                "error": r.error,
            })
        })
        .collect();
    let key = body.get("key").cloned().unwrap_or(JsonValue::Null);
    Ok(Json(json!({
        "key": key,
        "label": label,
        "rows": rows,
        "elapsed_ms": start.elapsed().as_secs_f64() * 1e3,
    }))
    .into_response())
}

/// Any other path.
pub async fn not_found(uri: Uri) -> ApiError {
    ApiError {
        status: StatusCode::NOT_FOUND,
        message: format!("no such page or endpoint: {}", uri.path()),
        key: None,
        kind: "not_found",
    }
}
