//! Fuzz of the DEM's untrusted inputs (issue 26): the PEER `.AT2` reader (and the text
//! reader) and the `[dem]` table. Deterministic (a fixed-seed xorshift generator, so a failure
//! repeats) and bounded (a fixed number of cases; every DEM run under a small step limit).
//! Each case must end in a typed error that names where the input was wrong, or in finite
//! results: never a panic, an abort or a NaN. A panicking case is printed before it fails.

use std::path::Path;
use voussoir::analysis::{self, DemOptions};
use voussoir::dem::dynamic::{Criterion, DynamicSettings};
use voussoir::dem::record::{self, AccelUnit, Excitation, GroundInput, Pulse, PulseShape};
use voussoir::dem::DEM_KEYS;
use voussoir::scene::Scene;

/// xorshift64* (Vigna 2016): small, deterministic, good enough to pick cases.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_F491_4F6C_DD1D)
    }
    fn below(&mut self, n: usize) -> usize {
        (self.next() % n as u64) as usize
    }
    fn pick<'a>(&mut self, items: &[&'a str]) -> &'a str {
        items[self.below(items.len())]
    }
    /// A float over many orders of magnitude, either sign.
    fn float(&mut self) -> f64 {
        let mantissa = (self.next() >> 11) as f64 / (1u64 << 53) as f64;
        let exponent = self.below(620) as i32 - 310;
        let sign = if self.next() & 1 == 0 { 1.0 } else { -1.0 };
        sign * mantissa * 10f64.powi(exponent)
    }
}

/// Run `case` and, if it panics, say which input made it panic.
fn no_panic<T>(what: &str, input: &str, case: impl FnOnce() -> T) -> T {
    // Nothing is shared with the case after a panic: asserting unwind safety is sound here.
    match std::panic::catch_unwind(std::panic::AssertUnwindSafe(case)) {
        Ok(v) => v,
        Err(_) => panic!("{what} panicked on:\n{input}"),
    }
}

const NUMBERS: &[&str] = &[
    "0.01",
    "0.1",
    "-0.25",
    "1e308",
    "-1e308",
    "1e309",
    "nan",
    "NaN",
    "inf",
    "-inf",
    "1D-3",
    "1.5d2",
    "abc",
    "1e-320",
    "0",
    "-0",
    "2305843009213693952",
    "18446744073709551616",
    "1e10",
    "3.5",
    ".0100",
    "1,2",
    "--1",
    "1e",
    "0x10",
    "99999999999999999999999",
];

/// An AT2 text: a valid header and samples, mangled at random.
fn at2_case(rng: &mut Rng) -> String {
    let mut lines = vec![
        "PEER NGA STRONG MOTION DATABASE RECORD".to_string(),
        "EVENT, STATION".to_string(),
        rng.pick(&[
            "ACCELERATION TIME HISTORY IN UNITS OF G",
            "ACCELERATION TIME HISTORY IN UNITS OF G",
            "ACCELERATION TIME HISTORY IN UNITS OF G",
            "VELOCITY TIME HISTORY IN UNITS OF CM/S",
            "ACCELERATION TIME HISTORY IN UNITS OF CM/S2",
            "",
        ])
        .to_string(),
    ];
    let n = rng.below(12);
    let samples: Vec<String> = (0..n)
        .map(|_| {
            match rng.below(8) {
                0 => rng.pick(NUMBERS).to_string(),
                1 => format!("{:e}", rng.float()),
                // Most samples are what records hold: within a few g.
                _ => format!(
                    "{:.6}",
                    4.0 * ((rng.next() >> 11) as f64 / (1u64 << 53) as f64 - 0.5)
                ),
            }
        })
        .collect();
    let npts = match rng.below(4) {
        0 | 3 => n.to_string(),
        1 => rng.pick(NUMBERS).to_string(),
        _ => rng.next().to_string(),
    };
    let dt = if rng.below(3) != 0 {
        rng.pick(&["0.01", ".0050", "0.02"]).to_string()
    } else {
        rng.pick(NUMBERS).to_string()
    };
    lines.push(match rng.below(5) {
        0 | 3 => format!("NPTS= {npts}, DT= {dt} SEC"),
        1 | 4 => format!("{npts} {dt} NPTS, DT"),
        _ => format!("NPTS {npts} DT"),
    });
    for chunk in samples.chunks(5) {
        lines.push(chunk.join("  "));
    }
    let mut text = lines.join("\n");
    // A few random bytes changed, as a corrupt download would.
    for _ in 0..rng.below(4).saturating_sub(1) {
        if text.is_empty() {
            break;
        }
        let at = rng.below(text.len());
        if text.is_char_boundary(at) && text.is_char_boundary(at + 1) {
            let c = b" 0123456789.-+eE,DNPTS=\n"[rng.below(24)] as char;
            text.replace_range(at..at + 1, &c.to_string());
        }
    }
    text
}

/// What a record the readers accept must be: finite, increasing times, samples within 100 g.
fn check_motion(m: &record::GroundMotion, input: &str) {
    assert_eq!(m.time.len(), m.accel.len(), "{input}");
    assert!(!m.time.is_empty(), "{input}");
    let limit = record::MAX_ACCELERATION_G * record::STANDARD_GRAVITY;
    assert!(
        m.accel.iter().all(|a| a.is_finite() && a.abs() <= limit),
        "{input}"
    );
    assert!(m.time.iter().all(|t| t.is_finite() && *t >= 0.0), "{input}");
    assert!(m.time.windows(2).all(|w| w[1] > w[0]), "{input}");
}

#[test]
fn at2_and_text_readers_never_panic() {
    let mut rng = Rng(0x2026_0026_dead_beef);
    let (mut accepted, mut refused) = (0, 0);
    for _ in 0..3000 {
        let text = at2_case(&mut rng);
        let input = text.clone();
        let r = no_panic("parse_at2", &text, move || {
            record::parse_at2(&input, Path::new("fuzz.AT2"))
        });
        match r {
            Ok(m) => {
                check_motion(&m, &text);
                accepted += 1;
            }
            Err(e) => {
                // Typed, and it names the file.
                assert!(e.to_string().starts_with("fuzz.AT2"), "{e}\n{text}");
                refused += 1;
            }
        }
        // The same text as a one- or two-column text record.
        let body: String = text.lines().skip(4).collect::<Vec<_>>().join("\n");
        let input = body.clone();
        let dt = [None, Some(0.01), Some(f64::NAN), Some(1e9), Some(-1.0)][rng.below(5)];
        let r = no_panic("parse_text", &body, move || {
            record::parse_text(&input, Path::new("fuzz.txt"), AccelUnit::G, dt)
        });
        match r {
            Ok(m) => check_motion(&m, &body),
            Err(e) => assert!(e.to_string().starts_with("fuzz.txt"), "{e}\n{body}"),
        }
    }
    eprintln!("AT2: {accepted} accepted, {refused} refused");
    // The generator must exercise both sides.
    assert!(accepted > 100 && refused > 1000, "{accepted} / {refused}");
}

const VALUES: &[&str] = &[
    "1e308",
    "-1e308",
    "0",
    "-1",
    "1e-300",
    "1e-9",
    "0.5",
    "1",
    "10",
    "1e6",
    "1e16",
    "1e17",
    "\"inf\"",
    "\"nan\"",
    "9223372036854775807",
    "true",
    "\"abc\"",
    "0.999",
    "2",
    "1e-3",
    "-0.0",
    "0.05",
];

/// A block 0.2 x 1 with one to three `[dem]` keys set to values drawn from `VALUES` (and,
/// now and then, a key that does not exist).
fn dem_case(rng: &mut Rng) -> String {
    let mut text = String::from(
        "[blocks]\npolygons = [[[-0.1, 0.0], [0.1, 0.0], [0.1, 1.0], [-0.1, 1.0]]]\n[material]\nfriction = \"inf\"\n[dem]\n",
    );
    let mut used = Vec::new();
    for _ in 0..1 + rng.below(3) {
        let key = if rng.below(20) == 0 {
            "normal_stiffnes"
        } else {
            DEM_KEYS[rng.below(DEM_KEYS.len())]
        };
        if used.contains(&key) {
            continue;
        }
        used.push(key);
        text.push_str(&format!("{key} = {}\n", rng.pick(VALUES)));
    }
    text
}

#[test]
fn dem_keys_never_panic() {
    let mut rng = Rng(0x0026_5eed_0f0d_e300);
    let pulse = GroundInput::from(Excitation::Pulse(
        Pulse::new(PulseShape::Sine, 0.3 * record::STANDARD_GRAVITY, 0.3).expect("pulse"),
    ));
    let (mut ran, mut refused) = (0, 0);
    for k in 0..400 {
        let text = dem_case(&mut rng);
        let scene = match Scene::from_toml_str(&text, "fuzz.toml") {
            Ok(s) => s,
            Err(e) => {
                // Refused while reading: the error names the key.
                assert!(e.to_string().contains("dem."), "{e}\n{text}");
                refused += 1;
                continue;
            }
        };
        let settings = DynamicSettings {
            tail: 0.2,
            history_every: None,
            criterion: if k % 2 == 0 {
                Criterion::Displacement
            } else {
                Criterion::Overturning
            },
            max_steps: Some(400_000),
            ..Default::default()
        };
        let (s, p) = (scene.clone(), pulse.clone());
        match no_panic("dem_dynamic", &text, move || {
            analysis::dem_dynamic(&s, &p, &settings)
        }) {
            Ok(d) => {
                let r = &d.result;
                for x in [
                    r.peak_displacement,
                    r.peak_rotation,
                    r.residual_displacement,
                    r.residual_rotation,
                    r.time_step,
                ] {
                    assert!(x.is_finite(), "{x}\n{text}");
                }
                ran += 1;
            }
            Err(e) => {
                assert!(!e.to_string().is_empty());
                refused += 1;
            }
        }
        // Every tenth case also brackets lambda (the path of Python's `dem()`), coarsely.
        if k % 10 == 0 {
            let options = DemOptions {
                tolerance: 0.3,
                max_steps: Some(400_000),
                ..Default::default()
            };
            let s = scene.clone();
            if let Ok(d) = no_panic("dem", &text, move || {
                analysis::dem(&s, &options, &mut |_| {})
            }) {
                let r = &d.result;
                assert!(r.lambda_dem.is_none_or(f64::is_finite), "{text}");
                assert!(r.lambda_stands.is_none_or(f64::is_finite), "{text}");
            }
        }
    }
    eprintln!("[dem]: {ran} ran, {refused} refused");
    assert!(ran > 60 && refused > 60, "{ran} / {refused}");
}
