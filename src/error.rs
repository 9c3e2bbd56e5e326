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
    /// A chart axis that cannot be drawn (`--x`, `--series`; a study's `x`, `series`).
    #[error("{option} {key}: {message}")]
    BadChart {
        /// The option, e.g. `--x`.
        option: String,
        /// The key given to it.
        key: String,
        message: String,
    },
    /// A block source (`[blocks]`) that cannot be read or does not make a structure; the
    /// message names the file, the blocks and the coordinates.
    #[error("{origin}: `{key}`: {message}")]
    BadBlocks {
        origin: String,
        key: String,
        message: String,
    },
    /// Options that do not fit together (e.g. `--x` without `--svg`).
    #[error("{0}")]
    Usage(String),
}

impl SceneError {
    /// The scene key the error is about, when there is one (for tests and scripts).
    pub fn key(&self) -> Option<&str> {
        match self {
            SceneError::UnknownKey { key, .. }
            | SceneError::MissingKey { key, .. }
            | SceneError::WrongType { key, .. }
            | SceneError::OutOfRange { key, .. }
            | SceneError::BadBlocks { key, .. } => Some(key),
            _ => None,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn edit_distance_counts_single_character_edits() {
        assert_eq!(edit_distance("", "abc"), 3);
        assert_eq!(edit_distance("thicknes", "thickness"), 1);
        assert_eq!(edit_distance("kitten", "sitting"), 3);
        assert_eq!(edit_distance("radius", "radius"), 0);
    }

    #[test]
    fn closest_suggests_likely_typos_only() {
        let keys = ["shape", "thickness", "voussoirs", "radius", "embrace_deg"];
        assert_eq!(closest("thicknes", &keys), Some("thickness"));
        assert_eq!(closest("Radius", &keys), Some("radius"));
        assert_eq!(closest("vousoirs", &keys), Some("voussoirs"));
        assert_eq!(closest("colour", &keys), None);
        assert_eq!(
            closest("depht", &["unit_weight", "depth", "friction"]),
            Some("depth")
        );
        assert_eq!(did_you_mean("x", &keys), "");
    }
}

/// Edit distance between two words (Levenshtein: insertions, deletions and substitutions
/// of one character each cost 1).
pub fn edit_distance(a: &str, b: &str) -> usize {
    let b: Vec<char> = b.chars().collect();
    let mut row: Vec<usize> = (0..=b.len()).collect();
    for (i, ca) in a.chars().enumerate() {
        let mut diagonal = row[0];
        row[0] = i + 1;
        for (j, cb) in b.iter().enumerate() {
            let substitute = diagonal + usize::from(ca != *cb);
            diagonal = row[j + 1];
            row[j + 1] = substitute.min(row[j] + 1).min(row[j + 1] + 1);
        }
    }
    row[b.len()]
}

/// The candidate closest to `word` (case-insensitively), if it is close enough to be a
/// likely typo: at most a third of the longer word's characters differ (rounded up, so a
/// swapped pair of letters in a five-letter word still counts).
/// Ties go to the first candidate.
pub fn closest<'a>(word: &str, candidates: &[&'a str]) -> Option<&'a str> {
    let w = word.to_lowercase();
    candidates
        .iter()
        .map(|c| (edit_distance(&w, &c.to_lowercase()), *c))
        .filter(|(d, c)| {
            let longest = w.chars().count().max(c.chars().count());
            *d <= longest.div_ceil(3)
        })
        .min_by_key(|(d, _)| *d)
        .map(|(_, c)| c)
}

/// ` (did you mean `KEY`?)` for the closest candidate, or nothing.
pub fn did_you_mean(word: &str, candidates: &[&str]) -> String {
    closest(word, candidates).map_or(String::new(), |c| format!(" (did you mean `{c}`?)"))
}

/// What is wrong with a ground-motion input (`dem::record`), and where: the file, the line
/// and the value read there.
#[derive(Debug, Error, PartialEq)]
pub enum RecordError {
    #[error("{path}: cannot read the record: {message}")]
    Io { path: PathBuf, message: String },
    #[error("{path}, line {line}: {message}")]
    Header {
        path: PathBuf,
        line: usize,
        message: String,
    },
    #[error("{path}, line {line}: `{token}` is not a finite number")]
    NotANumber {
        path: PathBuf,
        line: usize,
        token: String,
    },
    #[error("{path}, line {line}: the time step DT = {value} must be a finite number > 0")]
    TimeStep {
        path: PathBuf,
        line: usize,
        value: String,
    },
    #[error("{path}, line {line}: NPTS = {declared}, but the data (lines {first_data_line}-{last_data_line}) hold {found} values")]
    Count {
        path: PathBuf,
        line: usize,
        declared: usize,
        found: usize,
        first_data_line: usize,
        last_data_line: usize,
    },
    #[error("{path}, line {line}: {message}")]
    Data {
        path: PathBuf,
        line: usize,
        message: String,
    },
    #[error("{path}: {message}")]
    Empty { path: PathBuf, message: String },
    #[error("pulse: {0}")]
    Pulse(String),
    /// A command-line value of a ground motion (`--scale`, `--component`, ...).
    #[error("{flag} {value}: {message}")]
    Flag {
        flag: String,
        value: String,
        message: String,
    },
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
    /// A ground-motion record or pulse that cannot be read or used.
    #[error(transparent)]
    Record(#[from] RecordError),
    /// A method's setting out of its range (`crate::lp::StaticSettings::validate`).
    #[error("{setting} = {value}: must be {allowed}")]
    Settings {
        setting: String,
        value: String,
        allowed: String,
    },
    /// A method or option that has no meaning for the scene's action (`[action] kind`):
    /// e.g. a ground motion's direction, a site assessment or a time history with a live
    /// action.
    #[error("{origin}: {what} does not apply to [action] kind = \"{action}\": {why}")]
    NotForAction {
        origin: String,
        what: String,
        action: String,
        why: String,
    },
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
