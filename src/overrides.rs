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
        .unwrap_or_else(|| Value::String(raw.to_string()));
    Ok((key.to_string(), value))
}
