//! The JSON API of `voussoir serve` (docs/web.md, "The API").
//!
//! - `GET /api/scene`: the scene the server was started with, as JSON and as TOML.
//! - `GET /api/parameters`: the sliders, the presets and the limits.
//! - `POST /api/analyze`: a scene (the TOML keys as JSON) -> the object `voussoir analyze
//!   --json` prints, plus `svg` (the drawing `analyze --svg` writes), `toml` and
//!   `elapsed_ms`.
//! - `POST /api/sweep`: a scene, a key and a range -> one row per value, as `voussoir sweep`.
//! - `POST /api/report`: a scene -> `html`, the hand-in report `voussoir report` writes for
//!   the scene as the page's TOML download has it (its text is the report's input, hashed and
//!   quoted in full), with `elapsed_ms`.
//!
//! Every refusal is a JSON object `{"error", "key", "kind"}`: 400 for a request that cannot be
//! analysed (malformed JSON, an invalid scene, a limit exceeded), 413 for a body over the
//! limit, 404 for an unknown path, 500 when the analysis itself fails.

use super::{parameters, Limits, ServerState};
use crate::analysis::{self, Options};
use crate::error::{AnalysisError, SceneError};
use crate::outcome::Direction;
use crate::report;
use crate::scene::Scene;
use crate::statics::StaticSettings;
use crate::sweep::{self, Sweep, Variation};
use axum::body::Bytes;
use axum::extract::rejection::{BytesRejection, QueryRejection};
use axum::extract::{Query, State};
use axum::http::{StatusCode, Uri};
use axum::response::{IntoResponse, Response};
use axum::Json;
use serde::Deserialize;
use serde_json::{json, Map, Value as JsonValue};
use std::path::Path;
use std::sync::atomic::{AtomicBool, Ordering};
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

impl ApiError {
    /// The same refusal, about `key` when it names none (a sweep's bad variation is about
    /// its `key`).
    fn about(mut self, key: &str) -> Self {
        if self.key.is_none() {
            self.key = Some(key.to_string());
        }
        self
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
            SceneError::Hazard { .. } => "hazard",
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
            // The request's scene made blocks the analysis cannot take (e.g. of no weight).
            AnalysisError::Assembly(message) => ApiError {
                status: StatusCode::BAD_REQUEST,
                message: format!("invalid assembly: {message}"),
                key: None,
                kind: "invalid_assembly",
            },
            // What the request asked for does not apply (a direction for a live action) or is
            // out of range: the client's to change, not a failure of the server.
            e @ AnalysisError::NotForAction { .. } => ApiError {
                status: StatusCode::BAD_REQUEST,
                message: e.to_string(),
                key: None,
                kind: "not_for_action",
            },
            e @ AnalysisError::Settings { .. } => ApiError {
                status: StatusCode::BAD_REQUEST,
                message: e.to_string(),
                key: None,
                kind: "settings",
            },
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
#[serde(deny_unknown_fields)]
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
    // Every count, wherever it is written (`arch.voussoirs`, `piers.courses`,
    // `piers.left.courses`, ...) and however (8 or 8.0), and every list of pier steps.
    let mut counts = Vec::new();
    counted_values("", table, &mut counts);
    for (key, n) in counts {
        let (max, what) = match key.rsplit('.').next() {
            Some("polygons") => (limits.max_blocks, "blocks"),
            Some("voussoirs") => (limits.max_voussoirs, "voussoirs"),
            _ => (limits.max_voussoirs, "courses per pier"),
        };
        if n.is_nan() || n > max as f64 {
            return Err(ApiError::bad(
                "limit",
                Some(&key),
                format!(
                    "`{key}` = {n}: the server takes at most {max} {what} (the CLI takes more: `voussoir analyze`)"
                ),
            ));
        }
    }
    if let Some(blocks) = table.get("blocks") {
        if let Some(file) = blocks.get("file") {
            let allowed = state.blocks_file();
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

/// The keys that count blocks: `voussoirs` and `courses` (their value), and `widths` (a
/// stepped pier's courses) and `polygons` (the user's blocks) by their length.
const COUNTED: &[&str] = &["voussoirs", "courses", "widths", "polygons"];

/// Every counted key below `table` (dotted from `path`) with its count.
fn counted_values(path: &str, table: &toml::Table, out: &mut Vec<(String, f64)>) {
    for (k, v) in table {
        let key = if path.is_empty() {
            k.clone()
        } else {
            format!("{path}.{k}")
        };
        match v {
            Toml::Table(t) => counted_values(&key, t, out),
            Toml::Integer(n) if COUNTED.contains(&k.as_str()) => out.push((key, *n as f64)),
            Toml::Float(x) if COUNTED.contains(&k.as_str()) => out.push((key, *x)),
            Toml::Array(items) if COUNTED.contains(&k.as_str()) => {
                out.push((key, items.len() as f64))
            }
            _ => {}
        }
    }
}

/// The scene of a request: the whole body, or its `scene` member.
fn request_scene(
    body: &Map<String, JsonValue>,
    state: &ServerState,
    fields: &[&str],
) -> Result<(Scene, Option<String>), ApiError> {
    let (scene, direction) = match body.get("scene") {
        Some(JsonValue::Object(scene)) => {
            // A misspelt option (`directon`) must not be ignored silently.
            if let Some(unknown) = body.keys().find(|k| !fields.contains(&k.as_str())) {
                return Err(ApiError::bad(
                    "unknown_field",
                    Some(unknown),
                    format!(
                        "unknown field `{unknown}`{} (this request takes: {})",
                        crate::error::did_you_mean(unknown, fields),
                        fields.join(", ")
                    ),
                ));
            }
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
    let scene = Scene::from_table_in(table, "scene", state.scene.base_dir())?;
    Ok((scene, direction))
}

/// The direction given in the query string (`?direction=left`), if any.
fn query_direction(
    query: Result<Query<QueryOptions>, QueryRejection>,
) -> Result<Option<String>, ApiError> {
    let query = query.map_err(|e| {
        ApiError::bad(
            "bad_option",
            None,
            format!("bad query string: {}", e.body_text()),
        )
    })?;
    Ok(query.0.direction)
}

/// The scene as a TOML file to download: it analyses to the same multiplier wherever it is
/// saved. The direction, which the scene format does not hold, is said in a first comment
/// line, and a relative `blocks.file` becomes absolute (it was relative to the start scene).
fn scene_toml(scene: &Scene, dir: Direction, base_dir: Option<&Path>) -> Result<String, ApiError> {
    let mut table = scene.table().clone();
    if let (Some(base), Some(Toml::Table(blocks))) = (base_dir, table.get_mut("blocks")) {
        if let Some(Toml::String(file)) = blocks.get_mut("file") {
            if Path::new(file.as_str()).is_relative() {
                *file = base.join(&*file).display().to_string();
            }
        }
    }
    let text = toml::to_string(&table).map_err(|e| ApiError {
        status: StatusCode::INTERNAL_SERVER_ERROR,
        message: format!("cannot write the scene as TOML: {e}"),
        key: None,
        kind: "internal",
    })?;
    Ok(match dir {
        Direction::Right => text,
        Direction::Left => format!(
            "# analysed with the earthquake to the left: voussoir analyze FILE --direction left\n{text}"
        ),
    })
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
pub async fn scene(State(state): State<Arc<ServerState>>) -> Result<Response, ApiError> {
    let table = state.scene.table();
    let toml = scene_toml(&state.scene, Direction::Right, None)?;
    Ok(Json(json!({
        "scene": table_json(table),
        "toml": toml,
        "origin": state.scene.origin,
    }))
    .into_response())
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
    let (scene, in_body) = request_scene(&body, &state, &["scene", "direction"])?;
    let dir = direction(query_direction(query)?.or(in_body).as_deref())?;
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
        out.insert("upper_rigid".into(), JsonValue::Bool(upper_rigid(&a)));
        out.insert("svg".into(), JsonValue::String(svg));
        let text = scene_toml(&scene, dir, scene.base_dir())?;
        out.insert("toml".into(), JsonValue::String(text));
        Ok(out)
    })
    .await?;
    out.insert(
        "elapsed_ms".into(),
        json!(start.elapsed().as_secs_f64() * 1e3),
    );
    Ok(Json(JsonValue::Object(out)).into_response())
}

/// `POST /api/report`: the hand-in report of the request's scene ([`crate::dossier`], the
/// page's "Report .html" download). The report's input is the scene as the page's TOML
/// download writes it, so saving that file and running `voussoir report` on it gives the same
/// report, hash included.
pub async fn report(
    State(state): State<Arc<ServerState>>,
    body: Result<Bytes, BytesRejection>,
) -> Result<Response, ApiError> {
    let start = Instant::now();
    let body = body.map_err(|e| body_error(e, &state.limits))?;
    let body = json_object(&body)?;
    let (scene, _) = request_scene(&body, &state, &["scene", "direction"])?;
    let html = blocking(move || {
        let text = scene_toml(&scene, Direction::Right, scene.base_dir())?;
        let d = crate::dossier::run(&scene, &crate::dossier::DossierOptions::default())?;
        let source = report::dossier::Source {
            text,
            overrides: Vec::new(),
        };
        Ok(report::dossier::hand_in(&scene, &source, &d).html())
    })
    .await?;
    Ok(Json(json!({
        "html": html,
        "elapsed_ms": start.elapsed().as_secs_f64() * 1e3,
    }))
    .into_response())
}

/// Whether a scene key is a count (`arch.voussoirs`, `piers.courses`, `piers.left.courses`).
fn is_count(key: &str) -> bool {
    matches!(key.rsplit('.').next(), Some("voussoirs" | "courses"))
}

/// Sets its flag when dropped: the handler of a request whose client has gone is dropped.
#[derive(Default)]
struct CancelOnDrop(Arc<AtomicBool>);

impl Drop for CancelOnDrop {
    fn drop(&mut self) {
        self.0.store(true, Ordering::Relaxed);
    }
}

/// The values of a sweep from `from` to `to` in `points` steps; whole numbers, without
/// repeats, for a count (voussoirs, courses).
fn sweep_values(key: &str, from: f64, to: f64, points: usize) -> Vec<Toml> {
    let at = |i: usize| {
        if points == 1 {
            from
        } else {
            from + (to - from) * i as f64 / (points - 1) as f64
        }
    };
    // Whole numbers for counts only: JSON writes 1.0 as 1, so the scene's value cannot tell
    // a pier height of 1 m from a count.
    if is_count(key) {
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

/// Whether the upper bound is the rigid structure's: a finite compressive strength, and a
/// search other than the certified one (which rotates about the compressed zones' centres),
/// whose hinges sit at the joints' ends, so that it ignores crushing (the analysis says so
/// in `kinematic_note`).
fn upper_rigid(a: &analysis::SceneAnalysis) -> bool {
    a.model.strength.is_finite()
        && a.lambda_upper().is_some()
        && a.kinematic_search != Some(crate::kinematic::Search::Certified)
}

/// One row of `/api/sweep`: the value, the status and both bounds as `voussoir sweep`
/// writes them ([`sweep::case`]), and which kinematic search gave the upper bound
/// (`kinematic_search`) and whether that bound is the rigid structure's (`upper_rigid`: with
/// a finite compressive strength, a search other than the certified one places its hinges
/// at the joints' ends, so its multiplier ignores crushing; an upper bound still, but of
/// another structure's collapse, and the page must not draw it as this one's).
fn sweep_row(values: &[Toml], case: &Result<Scene, SceneError>, options: &Options) -> JsonValue {
    let value = values.first().map_or(JsonValue::Null, to_json);
    let Ok(scene) = case else {
        let r = sweep::case(values, case, options, false);
        return json!({
            "value": value, "status": r.status, "lambda_lower": r.lambda_lower,
            "lambda_upper": r.lambda_upper, "error": r.error,
            "kinematic_search": null, "upper_rigid": false,
        });
    };
    match analysis::analyse(scene, options) {
        Ok(a) => {
            let search = a.kinematic_search;
            let rigid = upper_rigid(&a);
            json!({
                "value": value,
                "status": a.lower.status.as_str(),
                "lambda_lower": a.lower.lambda,
                "lambda_upper": a.lambda_upper(),
                "error": null,
                "kinematic_search": search.map(|k| k.as_str()),
                "upper_rigid": rigid,
                "friction_exact": a.friction().exact,
            })
        }
        Err(e) => json!({
            "value": value, "status": "error", "lambda_lower": null, "lambda_upper": null,
            "error": e.to_string(), "kinematic_search": null, "upper_rigid": false,
        }),
    }
}

/// `POST /api/sweep`.
pub async fn sweep(
    State(state): State<Arc<ServerState>>,
    query: Result<Query<QueryOptions>, QueryRejection>,
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
    let (scene, in_body) = request_scene(
        &body,
        &state,
        &["scene", "direction", "key", "from", "to", "points"],
    )?;
    let dir = direction(query_direction(query)?.or(in_body).as_deref())?;
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
    let values = sweep_values(&key, from, to, points);
    // A count swept past the limit is refused like a scene that asks for it.
    if is_count(&key) && to > state.limits.max_voussoirs as f64 {
        let max = state.limits.max_voussoirs;
        return Err(ApiError::bad(
            "limit",
            Some("to"),
            format!("`to` = {to}: `{key}` goes up to {max} in the server (the CLI takes more: `voussoir sweep`)"),
        ));
    }
    let label = crate::report::figures::key_label(&key);
    // At most a few sweeps at once, and a sweep whose client has gone (the page aborts one
    // when the user moves to another parameter) stops before its next case.
    let _permit = state.sweeps.acquire().await.map_err(|e| ApiError {
        status: StatusCode::INTERNAL_SERVER_ERROR,
        message: format!("the server is shutting down: {e}"),
        key: None,
        kind: "internal",
    })?;
    let cancel = CancelOnDrop::default();
    let cancelled = cancel.0.clone();
    let rows = blocking(move || {
        let sweep = Sweep::new(&scene, vec![Variation { key, values }])
            .map_err(|e| ApiError::from(e).about("key"))?;
        let options = options(dir);
        Ok(sweep.run_with(
            |values, case| {
                (!cancelled.load(Ordering::Relaxed)).then(|| sweep_row(values, case, &options))
            },
            &|| {},
        ))
    })
    .await?;
    drop(cancel);
    let rows: Vec<JsonValue> = rows.into_iter().flatten().collect();
    let key = body.get("key").cloned().unwrap_or(JsonValue::Null);
    Ok(Json(json!({
        "key": key,
        "label": label,
        "rows": rows,
        "elapsed_ms": start.elapsed().as_secs_f64() * 1e3,
    }))
    .into_response())
}

/// Whether an authority (a `Host` header, an origin's host, a request's absolute URI) names
/// this machine's loopback, read strictly: `localhost`, `127.x.y.z` (four decimal numbers)
/// or `[::1]`, then nothing or `:` and a port number. Anything else is refused, also what a
/// lenient reading would cut short: `[::1]evil.example`, `localhost.evil:80`, `127.0.0.1:80x`.
fn loopback_host(authority: &str) -> bool {
    let (loopback, port) = if let Some(rest) = authority.strip_prefix('[') {
        let Some((inside, after)) = rest.split_once(']') else {
            return false;
        };
        let port = match after {
            "" => None,
            _ => match after.strip_prefix(':') {
                Some(port) => Some(port),
                None => return false,
            },
        };
        (
            inside.parse::<std::net::Ipv6Addr>() == Ok(std::net::Ipv6Addr::LOCALHOST),
            port,
        )
    } else {
        let (name, port) = match authority.split_once(':') {
            Some((name, port)) => (name, Some(port)),
            None => (authority, None),
        };
        let loopback = name.eq_ignore_ascii_case("localhost")
            || (name.bytes().all(|b| b.is_ascii_digit() || b == b'.')
                && name
                    .parse::<std::net::Ipv4Addr>()
                    .is_ok_and(|a| a.is_loopback()));
        (loopback, port)
    };
    let port_ok = port.is_none_or(|p| {
        !p.is_empty()
            && p.len() <= 5
            && p.bytes().all(|b| b.is_ascii_digit())
            && p.parse::<u16>().is_ok()
    });
    loopback && port_ok
}

/// The authority of an `Origin` header (`http://127.0.0.1:8080`: a scheme, `://`, the
/// authority and nothing else), or None when it has another form (`null`, a path).
fn origin_authority(origin: &str) -> Option<&str> {
    let rest = origin
        .strip_prefix("http://")
        .or_else(|| origin.strip_prefix("https://"))?;
    (!rest.contains(['/', '?', '#', '@'])).then_some(rest)
}

/// Refuse what does not come from this machine's own page: a `Host` other than loopback (a
/// web site that re-points its name at 127.0.0.1, "DNS rebinding", would send its own name),
/// an `Origin` other than loopback (another site's page in the user's browser), and a POST
/// whose body is not declared JSON (a browser sends `text/plain` from any site without
/// asking; `application/json` from another origin needs a preflight, which is refused).
pub async fn same_machine_only(
    request: axum::extract::Request,
    next: axum::middleware::Next,
) -> Response {
    use axum::http::{header, Method};
    let headers = request.headers();
    let text = |name| headers.get(name).map(|v| v.to_str().unwrap_or("\u{fffd}"));
    let forbidden = |message: String| {
        ApiError {
            status: StatusCode::FORBIDDEN,
            message,
            key: None,
            kind: "forbidden",
        }
        .into_response()
    };
    // One Host and at most one Origin: with two, which one a check reads and which one
    // the rest of the server (or a proxy before it) reads could differ.
    for name in [header::HOST, header::ORIGIN] {
        if headers.get_all(&name).iter().count() > 1 {
            return forbidden(format!(
                "more than one `{name}` header: this server answers only requests with one"
            ));
        }
    }
    if let Some(host) = text(header::HOST) {
        if !loopback_host(host) {
            return forbidden(format!(
                "Host `{host}`: this server answers only requests to 127.0.0.1, localhost or [::1] (with an optional port)"
            ));
        }
    }
    // A request line with an absolute URI (`GET http://evil.example/ HTTP/1.1`) names its
    // host there, and HTTP says it overrides the Host header.
    if let Some(authority) = request.uri().authority() {
        if !loopback_host(authority.as_str()) {
            return forbidden(format!(
                "request for `{authority}`: this server answers only requests to 127.0.0.1, localhost or [::1]"
            ));
        }
    }
    if let Some(origin) = text(header::ORIGIN) {
        if !origin_authority(origin).is_some_and(loopback_host) {
            return forbidden(format!(
                "Origin `{origin}`: this server answers only its own page"
            ));
        }
    }
    if request.method() == Method::POST {
        let json = text(header::CONTENT_TYPE).is_some_and(|t| {
            t.split(';')
                .next()
                .is_some_and(|m| m.trim().eq_ignore_ascii_case("application/json"))
        });
        if !json {
            return ApiError {
                status: StatusCode::UNSUPPORTED_MEDIA_TYPE,
                message: "the body must be JSON, sent with `Content-Type: application/json`".into(),
                key: None,
                kind: "unsupported_media_type",
            }
            .into_response();
        }
    }
    next.run(request).await
}

/// A request body that must arrive before a deadline: past it, reading it fails (the
/// handler answers 400 and hyper closes the connection, which was left mid-body).
struct Deadline {
    body: axum::body::Body,
    sleep: std::pin::Pin<Box<tokio::time::Sleep>>,
    seconds: f64,
}

impl hyper::body::Body for Deadline {
    type Data = Bytes;
    type Error = axum::Error;

    fn poll_frame(
        mut self: std::pin::Pin<&mut Self>,
        cx: &mut std::task::Context<'_>,
    ) -> std::task::Poll<Option<Result<hyper::body::Frame<Bytes>, axum::Error>>> {
        use std::future::Future;
        use std::task::Poll;
        if let Poll::Ready(frame) = std::pin::Pin::new(&mut self.body).poll_frame(cx) {
            return Poll::Ready(frame);
        }
        if self.sleep.as_mut().poll(cx).is_ready() {
            let message = format!(
                "the request body did not arrive within {} s of its headers",
                self.seconds
            );
            return Poll::Ready(Some(Err(axum::Error::new(message))));
        }
        Poll::Pending
    }

    fn is_end_stream(&self) -> bool {
        self.body.is_end_stream()
    }

    fn size_hint(&self) -> hyper::body::SizeHint {
        self.body.size_hint()
    }
}

/// Give the request's body `timeout` to arrive, counted from now (its head has been read):
/// a client that declares a body and sends half of it does not hold a handler for ever.
pub async fn body_deadline(
    axum::extract::State(timeout): axum::extract::State<std::time::Duration>,
    request: axum::extract::Request,
    next: axum::middleware::Next,
) -> Response {
    let request = request.map(|body| {
        axum::body::Body::new(Deadline {
            body,
            sleep: Box::pin(tokio::time::sleep(timeout)),
            seconds: timeout.as_secs_f64(),
        })
    });
    next.run(request).await
}

/// A known path asked with a method it does not take.
pub async fn method_not_allowed(method: axum::http::Method, uri: Uri) -> ApiError {
    let allowed = if uri.path().starts_with("/api/analyze") || uri.path().starts_with("/api/sweep")
    {
        "POST"
    } else {
        "GET"
    };
    ApiError {
        status: StatusCode::METHOD_NOT_ALLOWED,
        message: format!("{method} {}: this path takes {allowed}", uri.path()),
        key: None,
        kind: "method_not_allowed",
    }
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

#[cfg(test)]
mod tests {
    use super::*;

    /// A panic inside an analysis is answered with a 500 and a message; the server goes on.
    #[test]
    fn a_panicking_analysis_is_a_500_not_a_dead_server() {
        let runtime = tokio::runtime::Builder::new_current_thread()
            .build()
            .expect("runtime");
        let answer: Result<(), ApiError> =
            runtime.block_on(blocking(|| panic!("a bug in an analysis")));
        let e = answer.expect_err("the panic is an error");
        assert_eq!(e.status, StatusCode::INTERNAL_SERVER_ERROR);
        assert_eq!(e.kind, "internal");
        assert!(e.message.contains("report the scene"), "{}", e.message);
        let after: Result<u8, ApiError> = runtime.block_on(blocking(|| Ok(7)));
        assert_eq!(after.ok(), Some(7));
    }

    #[test]
    fn loopback_hosts_are_recognised() {
        for ok in [
            "127.0.0.1",
            "127.0.0.1:80",
            "127.1.2.3:8080",
            "localhost:8080",
            "LOCALHOST",
            "[::1]",
            "[::1]:9",
            "[0:0:0:0:0:0:0:1]:9",
            "localhost:65535",
        ] {
            assert!(loopback_host(ok), "{ok}");
        }
        for bad in [
            "",
            "evil.example",
            "10.0.0.1",
            "128.0.0.1",
            "localhost.evil",
            "localhost.",
            "127.0.0.1.evil.example",
            "127.0.0.01",
            "127.1",
            "0x7f.0.0.1",
            "[::2]:80",
            "::1",
            "[::1]evil.example",
            "[::1]evil.example:80",
            "[::1].evil.example",
            "[::1]:80evil",
            "[::1",
            "[::ffff:127.0.0.1]",
            "localhost:",
            "localhost:http",
            "localhost:80:80",
            "localhost:65536",
            "localhost:+80",
            "127.0.0.1:8080x",
            "127.0.0.1 :80",
            "user@localhost",
        ] {
            assert!(!loopback_host(bad), "{bad}");
        }
    }

    #[test]
    fn origins_are_read_strictly() {
        assert_eq!(
            origin_authority("http://127.0.0.1:8080"),
            Some("127.0.0.1:8080")
        );
        assert_eq!(origin_authority("https://[::1]"), Some("[::1]"));
        for bad in [
            "null",
            "127.0.0.1",
            "ftp://127.0.0.1",
            "http://127.0.0.1/",
            "http://user@127.0.0.1",
            "http://127.0.0.1?x",
        ] {
            assert_eq!(origin_authority(bad), None, "{bad}");
        }
        assert!(!origin_authority("http://[::1]evil.example").is_some_and(loopback_host));
    }
}
