//! Typed errors. Every error says what was wrong and where (file, key, value).

use std::path::PathBuf;
use thiserror::Error;

/// A problem with a scene: its file, a key in it, or a `--set` override. The user's own text
/// quoted in a message (a key, a value, an override) is cut to [`MAX_QUOTED_CHARS`] characters
/// ([`excerpt`]); the fields keep it whole.
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
    #[error("{origin}: unknown key `{}`{hint}", excerpt(.key))]
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
    #[error("{origin}: `{}` = {}: wrong type, expected {expected}", excerpt(.key), excerpt(.value))]
    WrongType {
        origin: String,
        key: String,
        value: String,
        expected: String,
    },
    #[error("{origin}: `{}` = {}: {allowed}", excerpt(.key), excerpt(.value))]
    OutOfRange {
        origin: String,
        key: String,
        value: String,
        allowed: String,
    },
    #[error("--set {}: {message}", excerpt(.text))]
    BadOverride { text: String, message: String },
    #[error("--vary {}: {message}", excerpt(.text))]
    BadVariation { text: String, message: String },
    /// A chart axis that cannot be drawn (`--x`, `--series`; a study's `x`, `series`).
    #[error("{option} {}: {message}", excerpt(.key))]
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
    /// The site's hazard from its coordinates (`[site] latitude`, `longitude`) could not be
    /// had: the point lies outside the national grid, its return period outside the grid's,
    /// or this build has no grid. `key` is the key it is about (`site.latitude` for the
    /// point, `site.limit_state` for the return period).
    #[error("{origin}: `{key}`: {source}")]
    Hazard {
        origin: String,
        key: String,
        #[source]
        source: HazardError,
    },
}

/// `" (T_R = -V_R / ln(1 - P_VR), V_R = .. years, SLx)"` when known.
fn period_context(v_r: Option<f64>, limit_state: Option<&str>) -> String {
    match (v_r, limit_state) {
        (Some(v), Some(l)) => format!(" (T_R = -V_R / ln(1 - P_VR), V_R = {v} years, {l})"),
        _ => String::new(),
    }
}

/// Why the seismic hazard of NTC 2018 (ag, F0, Tc* of the national grid, NTC 2008
/// Allegati A and B) cannot be given for a site (`crate::hazard`).
#[derive(Debug, Clone, PartialEq, Error)]
pub enum HazardError {
    /// The point is in no cell of the grid (Allegato B, Tabella 1): at sea, abroad, or on
    /// one of the islands whose constant values Allegato B gives in Tabella 2, which is not
    /// bundled.
    #[error(
        "latitude {latitude}, longitude {longitude} lies outside the national hazard grid of NTC 2008 Allegato B, Tabella 1 (the mainland, Sicily, Ischia, Procida and Capri, by the grid's four-node cells); \
         the other islands have the constant values of Allegato B, Tabella 2, which voussoir does not bundle: for such a site give ag, F0 and Tc_star instead"
    )]
    OutsideGrid { latitude: f64, longitude: f64 },
    /// The return period lies outside the grid's 30 to 2475 years.
    #[error(
        "the return period T_R = {t_r:.1} years{} lies outside the 30 to 2475 years the grid tabulates; \
         voussoir does not extrapolate the hazard (NTC 2008 Allegato A interpolates between tabulated periods only): give ag, F0 and Tc_star instead",
        period_context(*.v_r, *.limit_state)
    )]
    ReturnPeriod {
        t_r: f64,
        /// The reference period `V_R` (years) it came from, when it came from a site.
        v_r: Option<f64>,
        /// The limit state it came from, when it came from a site.
        limit_state: Option<&'static str>,
    },
    /// This build was made without the grid's data file (data/hazard/README.md).
    #[error(
        "this build of voussoir has no NTC 2008 hazard grid (its data file was not found when it was built: data/hazard/README.md says where it goes); give ag, F0 and Tc_star instead of latitude and longitude"
    )]
    NotBundled,
}

impl SceneError {
    /// The scene key the error is about, when there is one (for tests and scripts).
    pub fn key(&self) -> Option<&str> {
        match self {
            SceneError::UnknownKey { key, .. }
            | SceneError::MissingKey { key, .. }
            | SceneError::WrongType { key, .. }
            | SceneError::OutOfRange { key, .. }
            | SceneError::BadBlocks { key, .. }
            | SceneError::Hazard { key, .. } => Some(key),
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

    #[test]
    fn a_key_in_the_wrong_case_or_without_its_suffix_is_found_first() {
        let site = [
            "ag",
            "soil",
            "topography",
            "F0",
            "Tc_star",
            "q",
            "FC",
            "Z",
            "H",
            "T1",
        ];
        // `Tc` is one letter from `FC`, but it is `Tc_star` without its suffix.
        assert_eq!(closest("Tc", &site), Some("Tc_star"));
        assert_eq!(closest("tc_STAR", &site), Some("Tc_star"));
        assert_eq!(closest("fc", &site), Some("FC"));
        assert_eq!(
            did_you_mean("fc", &site),
            " (did you mean `FC`? keys are case-sensitive)"
        );
        assert_eq!(did_you_mean("Tc", &site), " (did you mean `Tc_star`?)");
        assert_eq!(
            closest("embrace", &["radius", "embrace_deg"]),
            Some("embrace_deg")
        );
        // An edit-distance tie goes to the candidate in the user's case.
        assert_eq!(closest("ab", &["AC", "ac"]), Some("ac"));
    }

    #[test]
    fn long_text_is_quoted_in_part() {
        assert_eq!(excerpt("short"), "short");
        let long = "é".repeat(10_000_000);
        let e = excerpt(&long);
        assert!(e.chars().count() < 2 * MAX_QUOTED_CHARS, "{}", e.len());
        assert!(e.contains("(10000000 characters)"), "{e}");
        let line = format!("{}X{}", "a".repeat(5000), "b".repeat(5000));
        let e = excerpt_around(&line, 5000);
        assert!(
            e.contains('X') && e.starts_with("... ") && e.ends_with(" ..."),
            "{e}"
        );
        assert!(e.chars().count() <= MAX_QUOTED_CHARS + 8, "{e}");
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

/// The candidate closest to `word`, if it is close enough to be a likely typo. In order of
/// preference:
/// 1. the same word in another case (`fc` for `FC`: keys are case-sensitive);
/// 2. a candidate that is the word with a suffix after `_` (`Tc` for `Tc_star`, `embrace` for
///    `embrace_deg`: the unit or qualifier left out), compared case-insensitively;
/// 3. the candidate at the smallest edit distance, case-insensitively, if at most a third of
///    the longer word's characters differ (rounded up, so a swapped pair of letters in a
///    five-letter word still counts); a tie goes to the candidate that differs least in case,
///    then to the first.
pub fn closest<'a>(word: &str, candidates: &[&'a str]) -> Option<&'a str> {
    let w = word.to_lowercase();
    if let Some(c) = candidates.iter().find(|c| c.to_lowercase() == w) {
        return Some(c);
    }
    if !w.is_empty() {
        let with_suffix = |c: &&&str| {
            c.to_lowercase()
                .strip_prefix(&w)
                .is_some_and(|rest| rest.starts_with('_'))
        };
        if let Some(c) = candidates.iter().find(with_suffix) {
            return Some(c);
        }
    }
    candidates
        .iter()
        .map(|c| {
            (
                edit_distance(&w, &c.to_lowercase()),
                edit_distance(word, c),
                *c,
            )
        })
        .filter(|(d, _, c)| {
            let longest = w.chars().count().max(c.chars().count());
            *d <= longest.div_ceil(3)
        })
        .min_by_key(|(d, exact, _)| (*d, *exact))
        .map(|(_, _, c)| c)
}

/// ` (did you mean `KEY`?)` for the closest candidate ([`closest`]), adding that keys are
/// case-sensitive when the candidate differs from the word only in case; or nothing.
pub fn did_you_mean(word: &str, candidates: &[&str]) -> String {
    match closest(word, candidates) {
        Some(c) if c != word && c.to_lowercase() == word.to_lowercase() => {
            format!(" (did you mean `{c}`? keys are case-sensitive)")
        }
        Some(c) => format!(" (did you mean `{c}`?)"),
        None => String::new(),
    }
}

/// Longest piece of the user's own text (a value, a line of a file) quoted in a message:
/// enough to recognise it, and a 10 MB line is not printed whole.
pub const MAX_QUOTED_CHARS: usize = 120;

/// `text` as a message quotes it: whole when at most [`MAX_QUOTED_CHARS`] characters, else
/// its start and end around `... (N characters) ...`. Cut at character boundaries.
pub fn excerpt(text: &str) -> String {
    excerpt_around(text, 0)
}

/// [`excerpt`] of `text` keeping the characters around the byte offset `at` (where a parser
/// stopped), with `...` where the text was cut.
pub fn excerpt_around(text: &str, at: usize) -> String {
    let count = text.chars().count();
    if count <= MAX_QUOTED_CHARS {
        return text.to_string();
    }
    // The character index of `at`, and a window of MAX_QUOTED_CHARS characters around it.
    let at_char = text
        .char_indices()
        .take_while(|(i, _)| *i < at.min(text.len()))
        .count();
    let half = MAX_QUOTED_CHARS / 2;
    if at_char <= half {
        // The start and the end, as for a value.
        let head: String = text.chars().take(half).collect();
        let tail: String = text.chars().skip(count - half / 2).collect();
        return format!("{head} ... ({count} characters) ... {tail}");
    }
    let start = (at_char - half).min(count - MAX_QUOTED_CHARS);
    let window: String = text.chars().skip(start).take(MAX_QUOTED_CHARS).collect();
    let end = if start + MAX_QUOTED_CHARS < count {
        " ..."
    } else {
        ""
    };
    format!("... {window}{end}")
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

/// A request or a result `voussoir records` refuses (`records`): the flag and its value,
/// or the period where the mean spectrum misses the code's tolerance.
#[derive(Debug, Error, PartialEq)]
pub enum RecordsError {
    #[error("{flag} {value}: {allowed}")]
    Flag {
        flag: &'static str,
        value: String,
        allowed: String,
    },
    /// The matching did not bring the mean spectrum within the tolerance (then nothing is
    /// written).
    #[error("the mean spectrum of the records is {shortfall_pct:.1} % below the target at T = {period:.3} s, more than the 10 % NTC 2018 §3.2.3.6 allows; try another --seed or more --count")]
    Tolerance { period: f64, shortfall_pct: f64 },
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
    /// A method's setting out of its range (`crate::statics::StaticSettings::validate`).
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
    /// A validation case could not be computed (`voussoir validate`).
    #[error("validation: {0}")]
    Validation(String),
    /// Artificial records refused (`voussoir records`).
    #[error(transparent)]
    Records(#[from] RecordsError),
}
