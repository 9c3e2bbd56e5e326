//! `KEY=VALUE` overrides (`--set`, `--vary`, `with_override`): the one reader of their syntax,
//! shared by scenes and by the DEM's knobs.

use crate::error::SceneError;
use toml::{Table, Value};

/// Split `key=value` and read the value as TOML (falling back to a bare string).
pub fn parse_assignment(text: &str) -> Result<(String, Value), SceneError> {
    let (key, raw) = text
        .split_once('=')
        .ok_or_else(|| SceneError::BadOverride {
            text: text.to_string(),
            message: "expected KEY=VALUE, e.g. arch.thickness=0.2".to_string(),
        })?;
    let key = key.trim();
    let raw = raw.trim();
    if key.is_empty() || raw.is_empty() {
        return Err(SceneError::BadOverride {
            text: text.to_string(),
            message: "expected KEY=VALUE with a non-empty key and value".to_string(),
        });
    }
    let value = format!("v = {raw}")
        .parse::<Table>()
        .ok()
        .and_then(|mut t| t.remove("v"))
        .or_else(|| too_large_integer(raw))
        .unwrap_or_else(|| Value::String(raw.to_string()));
    Ok((key.to_string(), value))
}

/// An integer literal too large for TOML's 64-bit integers (`1180591620717411303424`) as the
/// float it is, so the key's range check reports it as written rather than as a string of
/// the wrong type.
fn too_large_integer(raw: &str) -> Option<Value> {
    let digits = raw.strip_prefix(['+', '-']).unwrap_or(raw).replace('_', "");
    if digits.is_empty() || !digits.bytes().all(|b| b.is_ascii_digit()) {
        return None;
    }
    raw.replace('_', "").parse::<f64>().ok().map(Value::Float)
}
