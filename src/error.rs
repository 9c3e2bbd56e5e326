//! Typed errors. Every error says what was wrong and where (file, key, value).

use std::path::PathBuf;
use thiserror::Error;

/// A problem with a scene: its file, a key in it, or a `--set` override.
#[derive(Debug, Error)]
pub enum SceneError {
    #[error("cannot read scene file {path}: {source}")]
    Io {
        path: PathBuf,
        #[source]
        source: std::io::Error,
    },
    #[error("{origin}: malformed TOML: {message}")]
    Syntax { origin: String, message: String },
    #[error("{origin}: unknown key `{key}`{hint}")]
    UnknownKey {
        origin: String,
        key: String,
        hint: String,
    },
    #[error("{origin}: missing required key `{key}` ({what})")]
    MissingKey {
        origin: String,
        key: String,
        what: String,
    },
    #[error("{origin}: `{key}` = {value}: wrong type, expected {expected}")]
    WrongType {
        origin: String,
        key: String,
        value: String,
        expected: String,
    },
    #[error("{origin}: `{key}` = {value}: {allowed}")]
    OutOfRange {
        origin: String,
        key: String,
        value: String,
        allowed: String,
    },
    #[error("--set {text}: {message}")]
    BadOverride { text: String, message: String },
    #[error("--vary {text}: {message}")]
    BadVariation { text: String, message: String },
}

impl SceneError {
    /// The scene key the error is about, when there is one (for tests and scripts).
    pub fn key(&self) -> Option<&str> {
        match self {
            SceneError::UnknownKey { key, .. }
            | SceneError::MissingKey { key, .. }
            | SceneError::WrongType { key, .. }
            | SceneError::OutOfRange { key, .. } => Some(key),
            _ => None,
        }
    }
}

/// A failure of an analysis that is not a physical answer (those are statuses, not errors).
#[derive(Debug, Error)]
pub enum AnalysisError {
    #[error("the conic solver could not be set up: {0}")]
    SolverSetup(String),
    #[error("the conic solver stopped with status {status} (after {iterations} iterations): no multiplier is reported")]
    SolverFailed { status: String, iterations: u32 },
    #[error("invalid assembly: {0}")]
    Assembly(String),
    #[error("{0}")]
    Scene(#[from] SceneError),
    #[error("{0}")]
    Other(String),
}

/// Anything the library can report to the CLI.
#[derive(Debug, Error)]
pub enum Error {
    #[error(transparent)]
    Scene(#[from] SceneError),
    #[error(transparent)]
    Analysis(#[from] AnalysisError),
    #[error("cannot write {path}: {message}")]
    Output { path: PathBuf, message: String },
}
