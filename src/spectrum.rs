//! The seismic site of a structure and its elastic response spectrum: the scene's `[site]`
//! table and the horizontal elastic spectrum of NTC 2018 §3.2.3.2 (the Eurocode 8 shape,
//! EN 1998-1 §3.2.2.2, with the Italian site parameters `ag`, `F0`, `Tc*`).
//!
//! Equations (NTC 2018, D.M. 17/01/2018):
//! - §3.2.3.2.1, eq. 3.2.2: with `S = SS ST`, `eta = 1` (5 % damping), `TC = CC Tc*`,
//!   `TB = TC/3`, `TD = 4.0 ag/g + 1.6` (s):
//!   `Se = ag S eta F0 [T/TB + (1 - T/TB)/(eta F0)]` for `T < TB`,
//!   `Se = ag S eta F0` for `TB <= T < TC`, `Se = ag S eta F0 TC/T` for `TC <= T < TD`,
//!   `Se = ag S eta F0 TC TD/T^2` for `T >= TD`;
//! - Tab. 3.2.IV (stratigraphic amplification `SS` and `CC` of soil categories A-E);
//! - Tab. 3.2.V (topographic amplification `ST`: T1 1.0, T2 1.2, T3 1.2, T4 1.4, the value at
//!   the top of the relief; the linear decrease down the slope is not applied);
//! - §3.2.3.2.3, eq. 3.2.12-3.2.13: the displacement spectrum `SDe = Se (T/2 pi)^2` up to
//!   `TE`, then a linear transition to `dg = 0.025 ag S TC TD` at `TF` (Tab. 3.2.VIII:
//!   `TE` = 4.5 s on A, 5.0 s on B, 6.0 s on C-E; `TF` = 10 s).
//!
//! Units: `ag` is given in g (as the Italian hazard maps give it); spectral accelerations are
//! returned in m/s^2, displacements in m, periods in s.
//!
//! The site's `ag`, `F0` and `Tc*` are either given (`ag`, `F0`, `Tc_star`) or taken from the
//! national hazard grid at the site's coordinates (`latitude`, `longitude`, with
//! `nominal_life`, `use_class` and `limit_state`: [`crate::hazard`]).

use crate::error::{did_you_mean, HazardError, SceneError};
use crate::hazard::{self, Grid, LimitState, SiteHazard, UseClass};
use toml::{Table, Value};

/// Standard gravity (m/s^2), the g that `ag` is a fraction of.
pub const G: f64 = 9.80665;

/// The keys of the scene's `[site]` table.
pub const SITE_KEYS: &[&str] = &[
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
    "latitude",
    "longitude",
    "nominal_life",
    "use_class",
    "limit_state",
];

/// Default nominal life `V_N` (years) of a site given by its coordinates: ordinary
/// constructions (NTC 2018 Tab. 2.4.I, "costruzioni con livelli di prestazioni ordinari").
pub const DEFAULT_NOMINAL_LIFE: f64 = 50.0;
/// Default use class of a site given by its coordinates: II, ordinary use (NTC 2018 §2.4.2).
pub const DEFAULT_USE_CLASS: UseClass = UseClass::II;
/// Default limit state of a site given by its coordinates: SLV (life safety), the state of
/// the checks of Circolare 2019 C8.7.1 that `voussoir assess` makes.
pub const DEFAULT_LIMIT_STATE: LimitState = LimitState::SLV;

/// Default structure (behaviour) factor of the linear kinematic check (Circolare 2019
/// C8.7.1.2.1: q = 2.0).
pub const DEFAULT_Q: f64 = 2.0;
/// Default confidence factor: knowledge level LC1 (Circolare 2019, Tab. C8.5.IV).
pub const DEFAULT_FC: f64 = 1.35;

/// Soil category (NTC 2018 §3.2.2, Tab. 3.2.II).
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
pub enum Soil {
    A,
    B,
    C,
    D,
    E,
}

impl Soil {
    fn parse(s: &str) -> Option<Soil> {
        Some(match s {
            "A" => Soil::A,
            "B" => Soil::B,
            "C" => Soil::C,
            "D" => Soil::D,
            "E" => Soil::E,
            _ => return None,
        })
    }

    pub fn as_str(self) -> &'static str {
        match self {
            Soil::A => "A",
            Soil::B => "B",
            Soil::C => "C",
            Soil::D => "D",
            Soil::E => "E",
        }
    }

    /// Stratigraphic amplification `SS` (Tab. 3.2.IV) for `ag` in g.
    pub fn ss(self, ag: f64, f0: f64) -> f64 {
        let x = f0 * ag;
        match self {
            Soil::A => 1.0,
            Soil::B => (1.40 - 0.40 * x).clamp(1.00, 1.20),
            Soil::C => (1.70 - 0.60 * x).clamp(1.00, 1.50),
            Soil::D => (2.40 - 1.50 * x).clamp(0.90, 1.80),
            Soil::E => (2.00 - 1.10 * x).clamp(1.00, 1.60),
        }
    }

    /// `CC` (Tab. 3.2.IV), `TC = CC Tc*`.
    pub fn cc(self, tc_star: f64) -> f64 {
        match self {
            Soil::A => 1.0,
            Soil::B => 1.10 * tc_star.powf(-0.20),
            Soil::C => 1.05 * tc_star.powf(-0.33),
            Soil::D => 1.25 * tc_star.powf(-0.50),
            Soil::E => 1.15 * tc_star.powf(-0.40),
        }
    }

    /// `TE` of the displacement spectrum (Tab. 3.2.VIII), s.
    pub fn te(self) -> f64 {
        match self {
            Soil::A => 4.5,
            Soil::B => 5.0,
            _ => 6.0,
        }
    }
}

/// Topographic category (NTC 2018 §3.2.2, Tab. 3.2.III).
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
pub enum Topography {
    T1,
    T2,
    T3,
    T4,
}

impl Topography {
    fn parse(s: &str) -> Option<Topography> {
        Some(match s {
            "T1" => Topography::T1,
            "T2" => Topography::T2,
            "T3" => Topography::T3,
            "T4" => Topography::T4,
            _ => return None,
        })
    }

    pub fn as_str(self) -> &'static str {
        match self {
            Topography::T1 => "T1",
            Topography::T2 => "T2",
            Topography::T3 => "T3",
            Topography::T4 => "T4",
        }
    }

    /// Topographic amplification `ST` at the top of the relief (Tab. 3.2.V).
    pub fn st(self) -> f64 {
        match self {
            Topography::T1 => 1.0,
            Topography::T2 | Topography::T3 => 1.2,
            Topography::T4 => 1.4,
        }
    }
}

/// A validated `[site]` table.
#[derive(Debug, Clone, PartialEq)]
pub struct Site {
    /// Peak ground acceleration on rock `ag` (in g) of the limit state checked.
    pub ag: f64,
    pub soil: Soil,
    pub topography: Topography,
    /// Maximum amplification of the spectrum `F0` (>= 2.2 in the Italian hazard data).
    pub f0: f64,
    /// `Tc*` (s), the upper corner period on rock.
    pub tc_star: f64,
    /// Structure factor of the linear check. Default 2.0.
    pub q: f64,
    /// Confidence factor `FC` (>= 1). Default 1.35 (knowledge level LC1).
    pub fc: f64,
    /// Height (m) above the foundation of the base of the mechanism; 0 for a mechanism at
    /// ground level (then `H` and `T1` are not needed).
    pub z: f64,
    /// Height (m) of the building the mechanism belongs to (needed when `Z > 0`).
    pub h: Option<f64>,
    /// First period (s) of the building (needed when `Z > 0`).
    pub t1: Option<f64>,
    /// Where `ag`, `F0` and `Tc*` came from when the site was given by its coordinates
    /// (`latitude`, `longitude`): the national grid's values there; `None` when they were
    /// given.
    pub hazard: Option<SiteHazard>,
}

impl Site {
    /// Read and validate a `[site]` table; errors name `site.KEY` in `origin`.
    pub fn from_table(table: &Table, origin: &str) -> Result<Site, SceneError> {
        let key = |k: &str| format!("site.{k}");
        for k in table.keys() {
            if !SITE_KEYS.contains(&k.as_str()) {
                return Err(SceneError::UnknownKey {
                    origin: origin.to_string(),
                    key: key(k),
                    hint: format!(
                        "{} (allowed: {})",
                        did_you_mean(k, SITE_KEYS),
                        SITE_KEYS.join(", ")
                    ),
                });
            }
        }
        let bad = |k: &str, v: String, allowed: &str| SceneError::OutOfRange {
            origin: origin.to_string(),
            key: key(k),
            value: v,
            allowed: allowed.to_string(),
        };
        let missing = |k: &str, what: &str| SceneError::MissingKey {
            origin: origin.to_string(),
            key: key(k),
            what: what.to_string(),
        };
        let number = |k: &str| -> Result<Option<f64>, SceneError> {
            match table.get(k) {
                None => Ok(None),
                Some(Value::Float(x)) => Ok(Some(*x)),
                Some(Value::Integer(i)) => Ok(Some(*i as f64)),
                Some(v) => Err(SceneError::WrongType {
                    origin: origin.to_string(),
                    key: key(k),
                    value: v.to_string(),
                    expected: "a number".to_string(),
                }),
            }
        };
        let word = |k: &str| -> Result<Option<String>, SceneError> {
            match table.get(k) {
                None => Ok(None),
                Some(Value::String(s)) => Ok(Some(s.clone())),
                Some(v) => Err(SceneError::WrongType {
                    origin: origin.to_string(),
                    key: key(k),
                    value: v.to_string(),
                    expected: "a string".to_string(),
                }),
            }
        };
        let hazard = site_hazard(table, origin, &number, &word)?;
        let given = |k: &str, what: &str| -> Result<f64, SceneError> {
            match &hazard {
                None => number(k)?.ok_or_else(|| missing(k, what)),
                Some(h) => Ok(match k {
                    "ag" => h.params.ag,
                    "F0" => h.params.f0,
                    _ => h.params.tc_star,
                }),
            }
        };
        let ag = given(
            "ag",
            "peak ground acceleration on rock, in g, e.g. ag = 0.25 (or the site's latitude and longitude)",
        )?;
        if !(ag.is_finite() && ag > 0.0 && ag <= 2.0) {
            return Err(bad(
                "ag",
                ag.to_string(),
                "must be a peak ground acceleration in g, above 0 and at most 2",
            ));
        }
        let soil_text =
            word("soil")?.ok_or_else(|| missing("soil", "soil category, one of A, B, C, D, E"))?;
        let soil = Soil::parse(&soil_text).ok_or_else(|| {
            bad(
                "soil",
                format!("\"{soil_text}\""),
                "unknown soil category (allowed: A, B, C, D, E)",
            )
        })?;
        let topography = match word("topography")? {
            None => Topography::T1,
            Some(t) => Topography::parse(&t).ok_or_else(|| {
                bad(
                    "topography",
                    format!("\"{t}\""),
                    "unknown topographic category (allowed: T1, T2, T3, T4)",
                )
            })?,
        };
        let f0 = given(
            "F0",
            "maximum spectral amplification of the site, e.g. F0 = 2.4 (or the site's latitude and longitude)",
        )?;
        if !(f0.is_finite() && (1.0..=5.0).contains(&f0)) {
            return Err(bad("F0", f0.to_string(), "must be from 1 to 5"));
        }
        let tc_star = given(
            "Tc_star",
            "upper corner period on rock Tc* (s), e.g. Tc_star = 0.3 (or the site's latitude and longitude)",
        )?;
        if !(tc_star.is_finite() && tc_star > 0.0 && tc_star <= 2.0) {
            return Err(bad(
                "Tc_star",
                tc_star.to_string(),
                "must be a period in s, above 0 and at most 2",
            ));
        }
        let q = number("q")?.unwrap_or(DEFAULT_Q);
        if !(q.is_finite() && (1.0..=10.0).contains(&q)) {
            return Err(bad("q", q.to_string(), "must be from 1 to 10"));
        }
        let fc = number("FC")?.unwrap_or(DEFAULT_FC);
        if !(fc.is_finite() && (1.0..=10.0).contains(&fc)) {
            return Err(bad(
                "FC",
                fc.to_string(),
                "the confidence factor must be from 1 to 10 (1.35, 1.2, 1.0 for knowledge levels LC1-LC3)",
            ));
        }
        let z = number("Z")?.unwrap_or(0.0);
        if !(z.is_finite() && z >= 0.0) {
            return Err(bad("Z", z.to_string(), "must be a height in m, 0 or more"));
        }
        let h = number("H")?;
        if let Some(h) = h {
            if !(h.is_finite() && h > 0.0) {
                return Err(bad("H", h.to_string(), "must be a height in m, above 0"));
            }
        }
        let t1 = number("T1")?;
        if let Some(t) = t1 {
            if !(t.is_finite() && t > 0.0 && t <= 10.0) {
                return Err(bad(
                    "T1",
                    t.to_string(),
                    "must be a period in s, above 0 and at most 10",
                ));
            }
        }
        if z > 0.0 {
            let h = h.ok_or_else(|| {
                missing(
                    "H",
                    "the building's height (m), needed for a mechanism at Z > 0",
                )
            })?;
            if z > h {
                return Err(bad(
                    "Z",
                    z.to_string(),
                    &format!("must not exceed the building's height H = {h}"),
                ));
            }
            if t1.is_none() {
                return Err(missing(
                    "T1",
                    "the building's first period (s), needed for a mechanism at Z > 0",
                ));
            }
        }
        Ok(Site {
            ag,
            soil,
            topography,
            f0,
            tc_star,
            q,
            fc,
            z,
            h,
            t1,
            hazard,
        })
    }

    /// The same site with another `ag` (in g). The grid's values no longer apply to it, so
    /// it has no `hazard`.
    pub fn with_ag(&self, ag: f64) -> Site {
        Site {
            ag,
            hazard: None,
            ..self.clone()
        }
    }

    /// The elastic spectrum of this site.
    pub fn spectrum(&self) -> Spectrum {
        Spectrum::of(self)
    }

    /// Whether the mechanism sits above ground level (`Z > 0`).
    pub fn elevated(&self) -> bool {
        self.z > 0.0
    }
}

/// The hazard of a `[site]` given by its coordinates: `latitude` and `longitude` (degrees),
/// `nominal_life` (years, default 50), `use_class` (`"I"`..`"IV"`, default `"II"`) and
/// `limit_state` (`"SLO"`, `"SLD"`, `"SLV"`, `"SLC"`, default `"SLV"`) give `ag`, `F0` and
/// `Tc*` on the national grid ([`crate::hazard`]); `None` for a site whose `ag`, `F0` and
/// `Tc_star` are given. Giving both is an error, and so are the three design keys without
/// coordinates (they would be ignored).
fn site_hazard(
    table: &Table,
    origin: &str,
    number: &dyn Fn(&str) -> Result<Option<f64>, SceneError>,
    word: &dyn Fn(&str) -> Result<Option<String>, SceneError>,
) -> Result<Option<SiteHazard>, SceneError> {
    let key = |k: &str| format!("site.{k}");
    let bad = |k: &str, v: String, allowed: &str| SceneError::OutOfRange {
        origin: origin.to_string(),
        key: key(k),
        value: v,
        allowed: allowed.to_string(),
    };
    let latitude = number("latitude")?;
    let longitude = number("longitude")?;
    if latitude.is_none() && longitude.is_none() {
        for k in ["nominal_life", "use_class", "limit_state"] {
            if let Some(v) = table.get(k) {
                return Err(bad(
                    k,
                    v.to_string(),
                    "is read only with the site's latitude and longitude (it chooses the return period of the hazard taken from the national grid); with ag, F0 and Tc_star given, those are the hazard",
                ));
            }
        }
        return Ok(None);
    }
    let missing = |k: &str, what: &str| SceneError::MissingKey {
        origin: origin.to_string(),
        key: key(k),
        what: what.to_string(),
    };
    let latitude = latitude.ok_or_else(|| {
        missing(
            "latitude",
            "the site's latitude in degrees, north positive, given with its longitude",
        )
    })?;
    let longitude = longitude.ok_or_else(|| {
        missing(
            "longitude",
            "the site's longitude in degrees, east positive, given with its latitude",
        )
    })?;
    if !(latitude.is_finite() && (-90.0..=90.0).contains(&latitude)) {
        return Err(bad(
            "latitude",
            latitude.to_string(),
            "must be a latitude in degrees, from -90 to 90",
        ));
    }
    if !(longitude.is_finite() && (-180.0..=180.0).contains(&longitude)) {
        return Err(bad(
            "longitude",
            longitude.to_string(),
            "must be a longitude in degrees, from -180 to 180",
        ));
    }
    for k in ["ag", "F0", "Tc_star"] {
        if let Some(v) = table.get(k) {
            return Err(bad(
                k,
                v.to_string(),
                "give either the site's latitude and longitude (ag, F0 and Tc* then come from the national hazard grid) or ag, F0 and Tc_star, not both",
            ));
        }
    }
    let nominal_life = number("nominal_life")?.unwrap_or(DEFAULT_NOMINAL_LIFE);
    if !(nominal_life.is_finite() && nominal_life > 0.0 && nominal_life <= 1000.0) {
        return Err(bad(
            "nominal_life",
            nominal_life.to_string(),
            "must be the nominal life V_N in years, above 0 and at most 1000 (NTC 2018 Tab. 2.4.I: 10 temporary, 50 ordinary, 100 strategic constructions)",
        ));
    }
    let use_class = one_of(
        word("use_class")?,
        UseClass::parse,
        DEFAULT_USE_CLASS,
        |v| {
            bad(
                "use_class",
                v,
                "unknown use class (allowed: I, II, III, IV; NTC 2018 §2.4.2)",
            )
        },
    )?;
    let limit_state = one_of(
        word("limit_state")?,
        LimitState::parse,
        DEFAULT_LIMIT_STATE,
        |v| {
            bad(
                "limit_state",
                v,
                "unknown limit state (allowed: SLO, SLD, SLV, SLC; NTC 2018 §3.2.1)",
            )
        },
    )?;
    let hazard_error = |source: HazardError| SceneError::Hazard {
        origin: origin.to_string(),
        key: key(match source {
            HazardError::ReturnPeriod { .. } => "limit_state",
            _ => "latitude",
        }),
        source,
    };
    let grid = Grid::bundled().map_err(hazard_error)?;
    hazard::site_hazard(
        grid,
        latitude,
        longitude,
        nominal_life,
        use_class,
        limit_state,
    )
    .map(Some)
    .map_err(hazard_error)
}

/// A word of a closed list read by `parse`, `default` when the key is absent, and `bad` of
/// the quoted word when `parse` does not know it.
fn one_of<T>(
    word: Option<String>,
    parse: fn(&str) -> Option<T>,
    default: T,
    bad: impl FnOnce(String) -> SceneError,
) -> Result<T, SceneError> {
    match word {
        None => Ok(default),
        Some(w) => parse(&w).ok_or_else(|| bad(format!("\"{w}\""))),
    }
}

/// The horizontal elastic spectrum of a site (NTC 2018 §3.2.3.2.1), 5 % damping.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct Spectrum {
    /// `ag` (m/s^2).
    pub ag: f64,
    /// `S = SS ST`.
    pub s: f64,
    pub ss: f64,
    pub st: f64,
    /// Damping correction (1 at 5 % damping).
    pub eta: f64,
    pub f0: f64,
    /// Corner periods (s).
    pub tb: f64,
    pub tc: f64,
    pub td: f64,
    /// Periods of the displacement spectrum's transition to the ground displacement (s).
    pub te: f64,
    pub tf: f64,
}

impl Spectrum {
    pub fn of(site: &Site) -> Spectrum {
        let ss = site.soil.ss(site.ag, site.f0);
        let st = site.topography.st();
        let tc = site.soil.cc(site.tc_star) * site.tc_star;
        Spectrum {
            ag: site.ag * G,
            s: ss * st,
            ss,
            st,
            eta: 1.0,
            f0: site.f0,
            tb: tc / 3.0,
            tc,
            td: 4.0 * site.ag + 1.6,
            te: site.soil.te(),
            tf: 10.0,
        }
    }

    /// Elastic spectral acceleration `Se(T)` (m/s^2), eq. 3.2.2.
    pub fn se(&self, t: f64) -> f64 {
        let top = self.ag * self.s * self.eta * self.f0;
        let t = t.max(0.0);
        if t < self.tb {
            top * (t / self.tb + (1.0 - t / self.tb) / (self.eta * self.f0))
        } else if t < self.tc {
            top
        } else if t < self.td {
            top * self.tc / t
        } else {
            top * self.tc * self.td / (t * t)
        }
    }

    /// Elastic spectral displacement `SDe(T)` (m), eq. 3.2.12-3.2.13.
    pub fn sde(&self, t: f64) -> f64 {
        let two_pi = 2.0 * std::f64::consts::PI;
        let t = t.max(0.0);
        if t <= self.te {
            return self.se(t) * (t / two_pi).powi(2);
        }
        let dg = 0.025 * self.ag * self.s * self.tc * self.td;
        if t <= self.tf {
            dg * (self.f0 * self.eta
                + (1.0 - self.f0 * self.eta) * (t - self.te) / (self.tf - self.te))
        } else {
            dg
        }
    }
}
