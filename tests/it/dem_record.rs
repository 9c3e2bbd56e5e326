//! Ground-motion input (issue 15, item 2): PEER NGA `.AT2` in both header styles, one- and
//! two-column text with a unit, pulses, and a table of bad records whose errors name the line.

use std::path::Path;
use voussoir::dem::record::{
    self, AccelUnit, GroundMotion, Pulse, PulseShape, RecordError, STANDARD_GRAVITY,
};

const WEST2: &str = "PEER NGA STRONG MOTION DATABASE RECORD
IMPERIAL VALLEY 10/15/79 2316, EL CENTRO ARRAY #6, 230
ACCELERATION TIME HISTORY IN UNITS OF G
NPTS=    7, DT=   .0100 SEC
  .1000000E-02  -.2000000E-02   .3000000E-02  -.4000000E-02   .5000000E-02
  -.6000000E-02   .7000000E-02
";

const OLD: &str = "PEER STRONG MOTION DATABASE RECORD. PROCESSING BY PACIFIC ENGINEERING.
IMPERIAL VALLEY 10/15/79 2316, EL CENTRO ARRAY #6, 230
ACCELERATION TIME HISTORY IN UNITS OF G
     7    0.01000  NPTS, DT
   0.00100  -0.00200   0.00300  -0.00400   0.00500  -0.00600   0.00700
";

fn at2(text: &str) -> Result<GroundMotion, RecordError> {
    record::parse_at2(text, Path::new("test.AT2"))
}

#[test]
fn both_at2_header_styles_read_the_same_record() {
    let a = at2(WEST2).expect("NGA-West2 header");
    let b = at2(OLD).expect("older header");
    assert_eq!(a.time.len(), 7);
    for (k, (x, y)) in a.accel.iter().zip(&b.accel).enumerate() {
        // Sample k is (k+1) 1e-3 g with alternating sign, converted with standard gravity.
        let sign = if k % 2 == 0 { 1.0 } else { -1.0 };
        let want = sign * (k + 1) as f64 * 1e-3 * STANDARD_GRAVITY;
        assert!((x - want).abs() < 1e-15 && (y - want).abs() < 1e-15, "{k}");
        assert!((a.time[k] - 0.01 * k as f64).abs() < 1e-15);
        assert_eq!(a.time[k], b.time[k]);
    }
    assert!((a.pga() - 7e-3 * STANDARD_GRAVITY).abs() < 1e-15);
    assert!((a.duration() - 0.06).abs() < 1e-15);
    // Linear between samples, zero outside the record.
    let mid = a.at(0.005);
    assert!((mid - 0.5 * (a.accel[0] + a.accel[1])).abs() < 1e-15);
    assert_eq!(a.at(-0.1), 0.0);
    assert_eq!(a.at(0.07), 0.0);
}

#[test]
fn text_records_in_either_unit_and_column_layout_agree() {
    let p = Path::new("rec.csv");
    let g = record::parse_text(
        "time,acc_g\n0.0,0.1\n0.02,-0.2\n0.04,0.05\n",
        p,
        AccelUnit::G,
        None,
    )
    .expect("two columns in g");
    let si = record::parse_text(
        &format!(
            "# accelerations in m/s^2\n{}\n{}\n{}\n",
            0.1 * STANDARD_GRAVITY,
            -0.2 * STANDARD_GRAVITY,
            0.05 * STANDARD_GRAVITY
        ),
        p,
        AccelUnit::MetersPerSecondSquared,
        Some(0.02),
    )
    .expect("one column in m/s^2");
    assert_eq!(g.time, si.time);
    for (a, b) in g.accel.iter().zip(&si.accel) {
        assert!((a - b).abs() < 1e-12, "{a} {b}");
    }
    let gal = record::parse_text(
        "0 98.0665\n0.01 0\n",
        p,
        AccelUnit::CentimetersPerSecondSquared,
        None,
    )
    .expect("gal");
    assert!((gal.accel[0] - 0.1 * STANDARD_GRAVITY).abs() < 1e-12);
    // Scaling multiplies the accelerations only.
    let s = g.scaled(2.5);
    assert_eq!(s.time, g.time);
    assert!((s.pga() - 2.5 * g.pga()).abs() < 1e-12);
}

#[test]
fn pulses_are_exact() {
    let a = 3.0;
    let t = 0.4;
    let sine = Pulse::new(PulseShape::Sine, a, t).expect("sine");
    let rect = Pulse::new(PulseShape::Rect, a, t).expect("rect");
    assert!((sine.at(0.25 * t) - a).abs() < 1e-12);
    assert!((sine.at(0.75 * t) + a).abs() < 1e-12);
    assert_eq!(sine.at(1.01 * t), 0.0);
    // One full cycle: the ground velocity returns to zero (midpoint rule over 1000 steps).
    let n = 1000;
    let v: f64 = (0..n)
        .map(|i| sine.at((i as f64 + 0.5) * t / n as f64) * t / n as f64)
        .sum();
    assert!(v.abs() < 1e-12, "{v}");
    assert_eq!(rect.at(0.0), a);
    assert_eq!(rect.at(0.999 * t), a);
    assert_eq!(rect.at(t), 0.0);
    assert!(Pulse::new(PulseShape::Rect, a, 0.0).is_err());
    assert!(Pulse::new(PulseShape::Sine, f64::NAN, 1.0).is_err());
}

/// A bad record, the line its error must name and a word the message must contain.
struct Bad {
    what: &'static str,
    text: String,
    at2: bool,
    line: usize,
    says: &'static str,
}

#[test]
fn bad_records_are_refused_naming_the_line() {
    let header = "PEER NGA STRONG MOTION DATABASE RECORD\nEVENT, STATION\nACCELERATION TIME HISTORY IN UNITS OF G\n";
    let cases = vec![
        Bad {
            what: "bad sampling line",
            text: format!("{header}SAMPLES: 7 EVERY 0.01 S\n0.1 0.2\n"),
            at2: true,
            line: 4,
            says: "sampling line",
        },
        Bad {
            what: "header cut short",
            text: "PEER NGA\nEVENT\nACCELERATION TIME HISTORY IN UNITS OF G\n".to_string(),
            at2: true,
            line: 4,
            says: "four header lines",
        },
        Bad {
            what: "not in g",
            text: "PEER\nEVENT\nACCELERATION TIME HISTORY IN UNITS OF CM/S/S\nNPTS=    2, DT=   .0100 SEC\n1 2\n".to_string(),
            at2: true,
            line: 3,
            says: "UNITS OF G",
        },
        Bad {
            what: "non-numeric sample",
            text: format!("{header}NPTS=    4, DT=   .0100 SEC\n0.1 0.2\n0.3 abc\n"),
            at2: true,
            line: 6,
            says: "abc",
        },
        Bad {
            what: "negative DT, NGA-West2 header",
            text: format!("{header}NPTS=    2, DT=  -.0100 SEC\n0.1 0.2\n"),
            at2: true,
            line: 4,
            says: "-.0100",
        },
        Bad {
            what: "negative DT, older header",
            text: format!("{header}     2   -0.01000  NPTS, DT\n0.1 0.2\n"),
            at2: true,
            line: 4,
            says: "-0.01000",
        },
        Bad {
            what: "zero DT",
            text: format!("{header}NPTS=    2, DT=   0.0 SEC\n0.1 0.2\n"),
            at2: true,
            line: 4,
            says: "DT",
        },
        Bad {
            what: "NPTS larger than the data",
            text: format!("{header}NPTS=    5, DT=   .0100 SEC\n0.1 0.2\n0.3 0.4\n"),
            at2: true,
            line: 4,
            says: "hold 4 values",
        },
        Bad {
            what: "NPTS smaller than the data",
            text: format!("{header}     3    0.01000  NPTS, DT\n0.1 0.2\n0.3 0.4\n"),
            at2: true,
            line: 4,
            says: "NPTS = 3",
        },
        Bad {
            what: "NPTS not a whole number",
            text: format!("{header}NPTS=  2.5, DT=   .0100 SEC\n0.1 0.2\n"),
            at2: true,
            line: 4,
            says: "NPTS",
        },
        Bad {
            what: "text: non-numeric value",
            text: "time,acc\n0.0,0.1\n0.01,x1\n".to_string(),
            at2: false,
            line: 3,
            says: "x1",
        },
        Bad {
            what: "text: infinite value",
            text: "0.0 0.1\n0.01 inf\n".to_string(),
            at2: false,
            line: 2,
            says: "inf",
        },
        Bad {
            what: "text: time going back",
            text: "0.0 0.1\n0.02 0.2\n0.01 0.3\n".to_string(),
            at2: false,
            line: 3,
            says: "does not increase",
        },
        Bad {
            what: "text: ragged columns",
            text: "0.0 0.1\n0.02 0.2 0.5\n".to_string(),
            at2: false,
            line: 2,
            says: "3 values",
        },
        Bad {
            what: "text: one column without a time step",
            text: "# acc\n0.1\n0.2\n".to_string(),
            at2: false,
            line: 2,
            says: "--dt",
        },
    ];
    for c in cases {
        let p = Path::new("bad.rec");
        let r = if c.at2 {
            record::parse_at2(&c.text, p)
        } else {
            record::parse_text(&c.text, p, AccelUnit::G, None)
        };
        let e = match r {
            Ok(m) => panic!("{}: accepted as {} samples", c.what, m.accel.len()),
            Err(e) => e.to_string(),
        };
        assert!(
            e.contains(&format!("line {}:", c.line)) && e.contains("bad.rec"),
            "{}: {e}",
            c.what
        );
        assert!(e.contains(c.says), "{}: {e}", c.what);
    }
    // A one-column record with a negative time step names its first data line.
    let e = record::parse_text("a\n0.1\n", Path::new("x.txt"), AccelUnit::G, Some(-0.01))
        .expect_err("negative dt")
        .to_string();
    assert!(e.contains("line 2:") && e.contains("-0.01"), "{e}");
}

#[test]
fn files_are_read_by_their_extension() {
    let dir = tempfile::tempdir().expect("tempdir");
    let a = dir.path().join("rec.at2");
    std::fs::write(&a, WEST2).expect("write");
    let m = record::read(&a, AccelUnit::MetersPerSecondSquared, None).expect("AT2");
    // The AT2 is in g whatever unit the caller gives for text files.
    assert!((m.accel[0] - 1e-3 * STANDARD_GRAVITY).abs() < 1e-15);
    let missing = dir.path().join("none.at2");
    let e = record::read(&missing, AccelUnit::G, None).expect_err("missing");
    assert!(matches!(e, RecordError::Io { .. }));
    assert!(e.to_string().contains("none.at2"));
}

/// A bad record reaches the analysis layer's error as itself (`AnalysisError::Record`), not
/// as a string: a caller can match the file, the line and the value, and the message is the
/// record's own, word for word.
#[test]
fn record_errors_stay_typed_in_the_analysis_error() {
    use voussoir::error::AnalysisError;
    let text = WEST2.replace("-.4000000E-02", "-.4ooo000E-02");
    let e = at2(&text).expect_err("bad sample");
    let message = e.to_string();
    let a: AnalysisError = e.into();
    assert_eq!(a.to_string(), message);
    match a {
        AnalysisError::Record(RecordError::NotANumber { path, line, token }) => {
            assert_eq!(path, Path::new("test.AT2"));
            assert_eq!(line, 5);
            assert_eq!(token, "-.4ooo000E-02");
        }
        other => panic!("not a typed record error: {other:?}"),
    }
}

/// The bundled synthetic record (data/records/synthetic_10s.AT2, written by
/// examples/synthetic_record.py) is the recipe its header says: 1001 samples every 0.01 s, a
/// peak of 0.1 g, silent at both ends of its envelope, and sample i is the formula's value.
#[test]
fn the_bundled_synthetic_record_is_its_recipe() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("data/records/synthetic_10s.AT2");
    let m = record::read(&path, AccelUnit::G, None).expect("bundled record reads");
    assert_eq!(m.time.len(), 1001);
    assert!((m.duration() - 10.0).abs() < 1e-9);
    assert!(
        (m.pga() / STANDARD_GRAVITY - 0.1).abs() < 1e-7,
        "{}",
        m.pga()
    );
    let freqs = [1.1, 1.9, 2.7, 3.6, 5.2, 7.9];
    let raw = |t: f64| {
        let envelope = (t / 1.0).min(1.0).min((10.0 - t) / 3.0).max(0.0);
        envelope
            * freqs
                .iter()
                .enumerate()
                .map(|(k, f)| {
                    (2.0 * std::f64::consts::PI * f * t + k as f64).sin() / (1.0 + k as f64)
                })
                .sum::<f64>()
    };
    let peak = (0..=1000)
        .map(|i| raw(i as f64 * 0.01).abs())
        .fold(0.0, f64::max);
    for (i, a) in m.accel.iter().enumerate() {
        let expected = 0.1 * STANDARD_GRAVITY * raw(i as f64 * 0.01) / peak;
        // 8 significant digits in the file.
        assert!(
            (a - expected).abs() <= 1e-7 * STANDARD_GRAVITY,
            "sample {i}: {a} vs {expected}"
        );
    }
    assert_eq!(m.accel[0], 0.0);
    assert!(m.accel[1000].abs() < 1e-12);
}

/// Issue 26: an AT2 header is the file's word, not a measure of it. `NPTS = 2^61` panicked
/// (capacity overflow) and `NPTS = 1e10` aborted (an 80 GB allocation) before a sample was
/// read; both are now the count mismatch of line 4. A sample of 1e308 g (which reached the
/// contact law as an infinite force) and a DT of 1e9 s (a run of 3e12 s) are refused with the
/// file and the line; so is a text sample beyond 100 g in its unit.
#[test]
fn absurd_headers_and_samples_are_refused_not_allocated() {
    let head = "PEER\nEVENT\nACCELERATION TIME HISTORY IN UNITS OF G\n";
    for npts in ["2305843009213693952", "10000000000", "18446744073709551615"] {
        let text = format!("{head}NPTS= {npts}, DT= .0100 SEC\n0.1 0.2 0.3\n");
        match at2(&text) {
            Err(RecordError::Count {
                line: 4, found: 3, ..
            }) => {}
            other => panic!("NPTS = {npts}: {other:?}"),
        }
    }
    let e = at2(&format!("{head}NPTS= 3, DT= .0100 SEC\n0.1\n-1e308 0.3\n")).expect_err("1e308 g");
    assert!(
        matches!(&e, RecordError::Data { line: 6, message, .. } if message.contains("-1e308") && message.contains("100 g")),
        "{e}"
    );
    assert!(e.to_string().starts_with("test.AT2, line 6"), "{e}");
    let e = at2(&format!("{head}NPTS= 3, DT= 1e9 SEC\n0.1 0.2 0.3\n")).expect_err("DT");
    assert!(
        matches!(&e, RecordError::Data { line: 4, message, .. } if message.contains("1000000000 s")),
        "{e}"
    );
    // 150 g in a text record (m/s^2): refused on its line; 50 g is a number a record can hold.
    let path = Path::new("r.csv");
    let e = record::parse_text(
        "0 0\n0.01 1471\n",
        path,
        AccelUnit::MetersPerSecondSquared,
        None,
    )
    .expect_err("150 g");
    assert!(matches!(e, RecordError::Data { line: 2, .. }), "{e}");
    assert!(record::parse_text(
        "0 0\n0.01 490\n",
        path,
        AccelUnit::MetersPerSecondSquared,
        None
    )
    .is_ok());
    let e = record::parse_text("0.1\n0.2\n", path, AccelUnit::G, Some(5.0)).expect_err("dt");
    assert!(matches!(e, RecordError::Data { line: 1, .. }), "{e}");
    assert!(Pulse::new(PulseShape::Sine, 1e300, 0.5).is_err());
}
