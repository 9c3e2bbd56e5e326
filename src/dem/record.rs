//! Ground-motion input for dynamic DEM runs: acceleration records read from files and
//! analytic pulses, as one [`GroundMotion`] (ground acceleration in m/s^2 against time,
//! linearly interpolated between samples, zero before the start and after the end), and the
//! direction they act in ([`GroundInput`]: one motion along x or y, and optionally a
//! vertical one with a horizontal one; positive toward +x and upward).
//!
//! Formats read:
//! - PEER NGA `.AT2` files (PEER Ground Motion Database; Ancheta et al. 2014, "NGA-West2
//!   database", Earthquake Spectra 30:989-1005): four header lines (database, event and
//!   station, `ACCELERATION TIME HISTORY IN UNITS OF G`, then the sampling) and the samples
//!   in g, any number per line. The sampling line comes in the two styles the database has
//!   used: `NPTS=  3000, DT=   .0100 SEC` (NGA-West2) and `4164  0.0100  NPTS, DT` (the older
//!   NGA files);
//! - text or CSV with one column (acceleration; the time step is given separately) or two
//!   (time, acceleration), separated by commas, semicolons, tabs or spaces, `#` comments and
//!   one optional header line of column names; the unit of acceleration is said by the
//!   caller ([`AccelUnit`]), since nothing in such a file says it;
//! - pulses ([`Pulse`]): one full sine cycle `A sin(2 pi t / T)` for `0 <= t <= T`, or a
//!   rectangular pulse `A` for `0 <= t < T` (Housner 1963, "The behavior of inverted
//!   pendulum structures during earthquakes", BSSA 53:403-417, uses both).
//!
//! Every error names the file and the line ([`RecordError`]). A record in g is converted with
//! the standard gravity 9.80665 m/s^2.

use std::path::Path;

/// Standard gravity (m/s^2), the g of records given in g.
pub const STANDARD_GRAVITY: f64 = 9.80665;

/// The largest ground acceleration a record or pulse may hold, in g. The strongest recorded
/// ground motions peak at 3 to 4 g; a sample beyond 100 g is a unit mistake or a corrupt
/// file, refused with the line it is on (and would only make the blocks fly off).
pub const MAX_ACCELERATION_G: f64 = 100.0;

/// The largest time step (s) of a sampled record: accelerographs sample at 0.001 to 0.05 s;
/// a record sampled less than once a second is not a ground motion (and `DT = 1e9` would
/// plan a run of 3e12 s).
pub const MAX_RECORD_DT: f64 = 1.0;

/// Refuse a sample `value` (m/s^2) beyond [`MAX_ACCELERATION_G`], naming the file and line.
fn plausible(value: f64, written: &str, path: &Path, line: usize) -> Result<f64, RecordError> {
    if value.abs() <= MAX_ACCELERATION_G * STANDARD_GRAVITY {
        Ok(value)
    } else {
        Err(RecordError::Data {
            path: path.to_path_buf(),
            line,
            message: format!(
                "sample `{written}`{}: beyond the {MAX_ACCELERATION_G} g any ground motion stays within (wrong unit, or a corrupt file?)",
                if value.is_finite() {
                    format!(" is {:.4e} g", value / STANDARD_GRAVITY)
                } else {
                    String::new()
                }
            ),
        })
    }
}

/// Refuse a record time step above [`MAX_RECORD_DT`], naming the file and line.
fn plausible_dt(dt: f64, path: &Path, line: usize) -> Result<f64, RecordError> {
    if dt <= MAX_RECORD_DT {
        Ok(dt)
    } else {
        Err(RecordError::Data {
            path: path.to_path_buf(),
            line,
            message: format!(
                "time step {dt} s: a ground-motion record is sampled at most every {MAX_RECORD_DT} s (usually 0.005 to 0.02 s)"
            ),
        })
    }
}

pub use crate::error::RecordError;

/// Unit of the accelerations of a text record.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum AccelUnit {
    /// Multiples of the standard gravity.
    G,
    /// m/s^2.
    MetersPerSecondSquared,
    /// cm/s^2 (gal).
    CentimetersPerSecondSquared,
}

impl AccelUnit {
    /// m/s^2 per unit.
    pub fn factor(self) -> f64 {
        match self {
            AccelUnit::G => STANDARD_GRAVITY,
            AccelUnit::MetersPerSecondSquared => 1.0,
            AccelUnit::CentimetersPerSecondSquared => 0.01,
        }
    }
}

/// A ground acceleration history: samples `accel[i]` (m/s^2) at strictly increasing
/// `time[i]` (s), the first at `time[0]` >= 0.
#[derive(Debug, Clone, PartialEq)]
pub struct GroundMotion {
    pub time: Vec<f64>,
    pub accel: Vec<f64>,
    /// Where it came from (file name or pulse description), for reports.
    pub source: String,
}

impl GroundMotion {
    /// The acceleration (m/s^2) at time `t` (s): linear between samples, 0 outside.
    pub fn at(&self, t: f64) -> f64 {
        let (time, a) = (&self.time, &self.accel);
        let (Some(&first), Some(&last)) = (time.first(), time.last()) else {
            return 0.0;
        };
        if !(t >= first && t <= last) {
            return 0.0;
        }
        // First sample after t.
        let k = time.partition_point(|&s| s <= t);
        if k == 0 {
            return a[0];
        }
        if k >= time.len() {
            return a[time.len() - 1];
        }
        let (t0, t1) = (time[k - 1], time[k]);
        a[k - 1] + (a[k] - a[k - 1]) * (t - t0) / (t1 - t0)
    }

    /// Duration (s): the time of the last sample.
    pub fn duration(&self) -> f64 {
        self.time.last().copied().unwrap_or(0.0)
    }

    /// Peak ground acceleration (m/s^2), the largest absolute sample.
    pub fn pga(&self) -> f64 {
        self.accel.iter().fold(0.0_f64, |m, a| m.max(a.abs()))
    }

    /// The same history with every acceleration times `s`.
    pub fn scaled(&self, s: f64) -> GroundMotion {
        GroundMotion {
            time: self.time.clone(),
            accel: self.accel.iter().map(|a| a * s).collect(),
            source: self.source.clone(),
        }
    }
}

/// The shape of an analytic pulse.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PulseShape {
    /// One full cycle `A sin(2 pi t / T)`, `0 <= t <= T`.
    Sine,
    /// `A` for `0 <= t < T`.
    Rect,
}

/// An analytic acceleration pulse of amplitude `amplitude` (m/s^2) and period (sine) or
/// duration (rect) `period` (s).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Pulse {
    pub shape: PulseShape,
    pub amplitude: f64,
    pub period: f64,
}

impl Pulse {
    /// A pulse, checked: finite amplitude, finite period > 0.
    pub fn new(shape: PulseShape, amplitude: f64, period: f64) -> Result<Pulse, RecordError> {
        if !amplitude.is_finite() {
            return Err(RecordError::Pulse(format!(
                "amplitude = {amplitude}: must be a finite number"
            )));
        }
        if amplitude.abs() > MAX_ACCELERATION_G * STANDARD_GRAVITY {
            return Err(RecordError::Pulse(format!(
                "amplitude = {amplitude} m/s^2: beyond the {MAX_ACCELERATION_G} g any ground motion stays within"
            )));
        }
        if !(period.is_finite() && period > 0.0) {
            return Err(RecordError::Pulse(format!(
                "period = {period}: must be a finite number of seconds > 0"
            )));
        }
        Ok(Pulse {
            shape,
            amplitude,
            period,
        })
    }

    /// The acceleration (m/s^2) at time `t` (s), exact (not sampled).
    pub fn at(&self, t: f64) -> f64 {
        match self.shape {
            PulseShape::Sine if (0.0..=self.period).contains(&t) => {
                self.amplitude * (std::f64::consts::TAU * t / self.period).sin()
            }
            PulseShape::Rect if (0.0..self.period).contains(&t) => self.amplitude,
            _ => 0.0,
        }
    }
}

/// Parse one number of a record, Fortran `D` exponents included.
fn number(token: &str, path: &Path, line: usize) -> Result<f64, RecordError> {
    let t = token.trim();
    let parsed = t
        .parse::<f64>()
        .or_else(|_| t.replace(['D', 'd'], "E").parse::<f64>());
    match parsed {
        Ok(v) if v.is_finite() => Ok(v),
        _ => Err(RecordError::NotANumber {
            path: path.to_path_buf(),
            line,
            token: t.to_string(),
        }),
    }
}

/// Read a record file: `.AT2` (any case) as PEER NGA, anything else as text with `unit` and,
/// for one column, the time step `dt`.
pub fn read(path: &Path, unit: AccelUnit, dt: Option<f64>) -> Result<GroundMotion, RecordError> {
    let text = std::fs::read_to_string(path).map_err(|e| RecordError::Io {
        path: path.to_path_buf(),
        message: e.to_string(),
    })?;
    let at2 = path
        .extension()
        .and_then(|e| e.to_str())
        .is_some_and(|e| e.eq_ignore_ascii_case("at2"));
    if at2 {
        parse_at2(&text, path)
    } else {
        parse_text(&text, path, unit, dt)
    }
}

/// The sampling line of an AT2 header: `NPTS= 3000, DT= .0100 SEC` or `4164 0.0100 NPTS, DT`.
fn at2_sampling(text: &str, path: &Path, line: usize) -> Result<(usize, f64), RecordError> {
    let header = |message: String| RecordError::Header {
        path: path.to_path_buf(),
        line,
        message,
    };
    let upper = text.to_ascii_uppercase();
    let (npts, dt) = if let (Some(n), Some(d)) = (upper.find("NPTS="), upper.find("DT=")) {
        // NGA-West2 style: the value follows each `=`.
        let value = |from: usize| {
            upper[from..]
                .split(|c: char| c == ',' || c.is_whitespace())
                .find(|s| !s.is_empty())
                .unwrap_or("")
                .to_string()
        };
        (value(n + 5), value(d + 3))
    } else if upper.contains("NPTS") && upper.contains("DT") {
        // Older style: the two numbers, then the words `NPTS, DT`.
        let tokens: Vec<&str> = upper
            .split(|c: char| c == ',' || c.is_whitespace())
            .filter(|s| !s.is_empty())
            .collect();
        if tokens.len() < 2 {
            return Err(header(format!(
                "expected `NPTS, DT` values before the words, found `{}`",
                text.trim()
            )));
        }
        (tokens[0].to_string(), tokens[1].to_string())
    } else {
        return Err(header(format!(
            "expected the sampling line `NPTS= 3000, DT= .0100 SEC` or `3000 0.0100 NPTS, DT`, found `{}`",
            text.trim()
        )));
    };
    let n = match npts.parse::<f64>() {
        Ok(v) if v.is_finite() && v >= 1.0 && v.fract() == 0.0 => v as usize,
        _ => {
            return Err(header(format!(
                "NPTS = `{npts}` is not a whole number of points >= 1"
            )))
        }
    };
    let dt_value = npts_dt_number(&dt).ok_or_else(|| RecordError::TimeStep {
        path: path.to_path_buf(),
        line,
        value: dt.clone(),
    })?;
    Ok((n, dt_value))
}

fn npts_dt_number(s: &str) -> Option<f64> {
    s.parse::<f64>().ok().filter(|v| v.is_finite() && *v > 0.0)
}

/// Parse the text of a PEER NGA `.AT2` file (`path` names it in errors).
pub fn parse_at2(text: &str, path: &Path) -> Result<GroundMotion, RecordError> {
    let lines: Vec<&str> = text.lines().collect();
    if lines.len() < 4 {
        return Err(RecordError::Header {
            path: path.to_path_buf(),
            line: lines.len() + 1,
            message: format!(
                "an AT2 file has four header lines; this one ends after {}",
                lines.len()
            ),
        });
    }
    let units = lines[2].to_ascii_uppercase();
    if units.contains("UNITS OF") && !units.contains("UNITS OF G") {
        return Err(RecordError::Header {
            path: path.to_path_buf(),
            line: 3,
            message: format!(
                "expected `ACCELERATION TIME HISTORY IN UNITS OF G`, found `{}`",
                lines[2].trim()
            ),
        });
    }
    if units.contains("VELOCITY") || units.contains("DISPLACEMENT") {
        return Err(RecordError::Header {
            path: path.to_path_buf(),
            line: 3,
            message: format!(
                "this is not an acceleration record (`{}`): give the .AT2 file",
                lines[2].trim()
            ),
        });
    }
    let (npts, dt) = at2_sampling(lines[3], path, 4)?;
    let dt = plausible_dt(dt, path, 4)?;
    // NPTS is the file's word, not a measure of it: reserve no more than the text can hold
    // (one sample takes at least two characters), so `NPTS = 2^61` cannot abort.
    let mut accel = Vec::with_capacity(npts.min(text.len() / 2 + 1));
    let mut last_line = 4;
    for (k, l) in lines.iter().enumerate().skip(4) {
        let line = k + 1;
        let mut any = false;
        for token in l.split(|c: char| c == ',' || c.is_whitespace()) {
            if token.is_empty() {
                continue;
            }
            let a = STANDARD_GRAVITY * number(token, path, line)?;
            accel.push(plausible(a, token, path, line)?);
            any = true;
        }
        if any {
            last_line = line;
        }
    }
    if accel.len() != npts {
        return Err(RecordError::Count {
            path: path.to_path_buf(),
            line: 4,
            declared: npts,
            found: accel.len(),
            first_data_line: 5,
            last_data_line: last_line.max(5),
        });
    }
    let time = (0..npts).map(|i| i as f64 * dt).collect();
    Ok(GroundMotion {
        time,
        accel,
        source: path.display().to_string(),
    })
}

/// Parse a one- or two-column text/CSV record (`path` names it in errors): accelerations in
/// `unit`; one column needs the time step `dt`.
pub fn parse_text(
    text: &str,
    path: &Path,
    unit: AccelUnit,
    dt: Option<f64>,
) -> Result<GroundMotion, RecordError> {
    let data_err = |line: usize, message: String| RecordError::Data {
        path: path.to_path_buf(),
        line,
        message,
    };
    let mut rows: Vec<(usize, Vec<f64>)> = Vec::new();
    let mut columns: Option<usize> = None;
    for (k, raw) in text.lines().enumerate() {
        let line = k + 1;
        let l = raw.split('#').next().unwrap_or("").trim();
        if l.is_empty() {
            continue;
        }
        let tokens: Vec<&str> = l
            .split(|c: char| c == ',' || c == ';' || c.is_whitespace())
            .filter(|s| !s.is_empty())
            .collect();
        // One header line of column names may precede the data.
        if rows.is_empty() && columns.is_none() && tokens.iter().all(|t| t.parse::<f64>().is_err())
        {
            columns = Some(tokens.len());
            continue;
        }
        let values = tokens
            .iter()
            .map(|t| number(t, path, line))
            .collect::<Result<Vec<f64>, _>>()?;
        let n = rows.first().map_or(values.len(), |r| r.1.len());
        if values.len() != n || !(1..=2).contains(&n) {
            return Err(data_err(
                line,
                format!(
                    "{} values; a record has one column (acceleration) or two (time, acceleration) on every line",
                    values.len()
                ),
            ));
        }
        rows.push((line, values));
    }
    if rows.is_empty() {
        return Err(RecordError::Empty {
            path: path.to_path_buf(),
            message: "no samples".to_string(),
        });
    }
    let f = unit.factor();
    let two = rows[0].1.len() == 2;
    let (time, accel) = if two {
        let mut time = Vec::with_capacity(rows.len());
        for (line, v) in &rows {
            let t = v[0];
            if let Some(&prev) = time.last() {
                if t <= prev {
                    return Err(data_err(
                        *line,
                        format!("time {t} s does not increase (previous {prev} s)"),
                    ));
                }
            } else if t < 0.0 {
                return Err(data_err(*line, format!("time {t} s is negative")));
            }
            time.push(t);
        }
        let mut accel = Vec::with_capacity(rows.len());
        for (line, v) in &rows {
            accel.push(plausible(f * v[1], &v[1].to_string(), path, *line)?);
        }
        (time, accel)
    } else {
        let dt = match dt {
            Some(d) if d.is_finite() && d > 0.0 => d,
            Some(d) => {
                return Err(RecordError::TimeStep {
                    path: path.to_path_buf(),
                    line: rows[0].0,
                    value: d.to_string(),
                })
            }
            None => {
                return Err(data_err(
                    rows[0].0,
                    "one column of accelerations: give the time step (--dt) or a time column"
                        .to_string(),
                ))
            }
        };
        let dt = plausible_dt(dt, path, rows[0].0)?;
        let mut accel = Vec::with_capacity(rows.len());
        for (line, v) in &rows {
            accel.push(plausible(f * v[0], &v[0].to_string(), path, *line)?);
        }
        ((0..rows.len()).map(|i| i as f64 * dt).collect(), accel)
    };
    Ok(GroundMotion {
        time,
        accel,
        source: path.display().to_string(),
    })
}

/// A ground motion of either kind.
#[derive(Debug, Clone, PartialEq)]
pub enum Excitation {
    Record(GroundMotion),
    Pulse(Pulse),
}

impl Excitation {
    /// The acceleration (m/s^2) at time `t` (s).
    pub fn at(&self, t: f64) -> f64 {
        match self {
            Excitation::Record(r) => r.at(t),
            Excitation::Pulse(p) => p.at(t),
        }
    }
    /// How long the ground moves (s).
    pub fn duration(&self) -> f64 {
        match self {
            Excitation::Record(r) => r.duration(),
            Excitation::Pulse(p) => p.period,
        }
    }
    /// Peak ground acceleration (m/s^2).
    pub fn pga(&self) -> f64 {
        match self {
            Excitation::Record(r) => r.pga(),
            Excitation::Pulse(p) => p.amplitude.abs(),
        }
    }
    /// The same motion with every acceleration times `s`.
    pub fn scaled(&self, s: f64) -> Excitation {
        match self {
            Excitation::Record(r) => Excitation::Record(r.scaled(s)),
            Excitation::Pulse(p) => Excitation::Pulse(Pulse {
                amplitude: p.amplitude * s,
                ..*p
            }),
        }
    }
    /// The times at which the motion may jump or turn: a record's sample times, a pulse's
    /// start and end (and a sine's quarter periods). Between two consecutive ones it is
    /// continuous and monotone (linear for a record, constant for a rectangular pulse), and it
    /// is 0 before the first and after the last; the rest test ([`super::rest`]) reads it
    /// piece by piece.
    pub fn breaks(&self) -> Vec<f64> {
        match self {
            Excitation::Record(r) => r.time.clone(),
            Excitation::Pulse(p) => match p.shape {
                PulseShape::Sine => (0..=4).map(|k| 0.25 * k as f64 * p.period).collect(),
                PulseShape::Rect => vec![0.0, p.period],
            },
        }
    }

    /// Whether the motion is linear between consecutive [`Excitation::breaks`] (a record, a
    /// rectangular pulse), not only monotone (a sine).
    pub fn piecewise_linear(&self) -> bool {
        !matches!(
            self,
            Excitation::Pulse(Pulse {
                shape: PulseShape::Sine,
                ..
            })
        )
    }

    /// The limits of the acceleration (m/s^2) at `t` from the left and from the right: they
    /// differ only where the motion jumps (a record's first and last sample, from and to 0; a
    /// rectangular pulse's start and end).
    pub fn limits(&self, t: f64) -> (f64, f64) {
        let (first, last) = match self {
            Excitation::Record(r) => match (r.time.first(), r.time.last()) {
                (Some(&f), Some(&l)) => (f, l),
                _ => return (0.0, 0.0),
            },
            Excitation::Pulse(p) => (0.0, p.period),
        };
        let inside = self.at(t);
        let left = if t > first && t <= last {
            match self {
                // A rectangular pulse's value at its end is the one just after.
                Excitation::Pulse(p) if p.shape == PulseShape::Rect && t == last => p.amplitude,
                _ => inside,
            }
        } else {
            0.0
        };
        let right = if t >= first && t < last {
            inside
        } else if t == last {
            match self {
                Excitation::Record(_) => 0.0,
                Excitation::Pulse(_) => inside,
            }
        } else {
            0.0
        };
        (left, right)
    }

    /// A short description for reports.
    pub fn describe(&self) -> String {
        match self {
            Excitation::Record(r) => format!("record {}", r.source),
            Excitation::Pulse(p) => format!(
                "{} pulse, amplitude {} m/s^2, {} {} s",
                match p.shape {
                    PulseShape::Sine => "sine",
                    PulseShape::Rect => "rectangular",
                },
                p.amplitude,
                match p.shape {
                    PulseShape::Sine => "period",
                    PulseShape::Rect => "duration",
                },
                p.period
            ),
        }
    }
}

/// The direction a ground motion acts in (`--component`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Component {
    /// Horizontal, toward +x for a positive acceleration.
    #[default]
    X,
    /// Vertical, upward for a positive acceleration.
    Y,
}

impl Component {
    /// `x` or `y`, as the command line and the JSON say it.
    pub fn name(self) -> &'static str {
        match self {
            Component::X => "x",
            Component::Y => "y",
        }
    }
}

/// The ground motion of a dynamic run: one motion along `component`, and optionally a
/// vertical one acting together with a horizontal main motion. Accelerations are toward +x
/// and upward (see [`super::dynamic`] for what they do to the blocks).
#[derive(Debug, Clone, PartialEq)]
pub struct GroundInput {
    pub main: Excitation,
    pub component: Component,
    /// A simultaneous vertical motion (only with a horizontal `main`).
    pub vertical: Option<Excitation>,
}

impl From<Excitation> for GroundInput {
    /// A horizontal motion alone.
    fn from(main: Excitation) -> Self {
        GroundInput {
            main,
            component: Component::X,
            vertical: None,
        }
    }
}

impl GroundInput {
    /// A motion along `component`, with an optional simultaneous vertical one; refused when
    /// the main motion is itself vertical and a second vertical one is given.
    pub fn new(
        main: Excitation,
        component: Component,
        vertical: Option<Excitation>,
    ) -> Result<GroundInput, RecordError> {
        if component == Component::Y && vertical.is_some() {
            return Err(RecordError::Flag {
                flag: "--component".to_string(),
                value: "y".to_string(),
                message:
                    "the motion already acts vertically: a second vertical motion cannot be added"
                        .to_string(),
            });
        }
        Ok(GroundInput {
            main,
            component,
            vertical,
        })
    }

    /// The ground acceleration (m/s^2) at time `t` (s): horizontal (toward +x), vertical
    /// (upward).
    pub fn at(&self, t: f64) -> crate::geometry::Vec2 {
        let a = self.main.at(t);
        match self.component {
            Component::X => {
                crate::geometry::Vec2::new(a, self.vertical.as_ref().map_or(0.0, |v| v.at(t)))
            }
            Component::Y => crate::geometry::Vec2::new(0.0, a),
        }
    }

    /// How long the ground moves (s): the longer of the two motions.
    pub fn duration(&self) -> f64 {
        self.vertical
            .as_ref()
            .map_or(0.0, Excitation::duration)
            .max(self.main.duration())
    }

    /// Both motions times `s`.
    pub fn scaled(&self, s: f64) -> GroundInput {
        GroundInput {
            main: self.main.scaled(s),
            component: self.component,
            vertical: self.vertical.as_ref().map(|v| v.scaled(s)),
        }
    }

    /// Peak acceleration (m/s^2) of the horizontal and of the vertical motion (0 when
    /// there is none).
    pub fn pga_xy(&self) -> (f64, f64) {
        match self.component {
            Component::X => (
                self.main.pga(),
                self.vertical.as_ref().map_or(0.0, Excitation::pga),
            ),
            Component::Y => (0.0, self.main.pga()),
        }
    }
}
