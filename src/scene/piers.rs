//! The piers of a portal (`[piers]`): their description, how the scene gives them, and their
//! courses as blocks.
//!
//! A portal stands on two piers under the springings. Each pier has a height, a number of
//! equal courses and a profile:
//! - `rectangular` (default): one width b for every course (the pier of `geometry.md`);
//! - `stepped`: a list of course widths from the base up, each narrower or wider than the one
//!   below (a buttress that steps back, or a plinth);
//! - `battered`: a bottom and a top width; the outer face is straight between them, so every
//!   course is a trapezoid.
//!
//! The inner face of every pier is vertical and flush with the intrados springing point, as
//! for the rectangular pier; the profile changes only the outer face. Keys given in `[piers]`
//! apply to both piers; `[piers.left]` and `[piers.right]` override them for one pier, so
//! the two piers may differ in height, width, courses and profile.
//!
//! **Unequal heights.** The arch keeps its shape and its springing line y = 0: a pier of
//! height h stands on its own base at y = -h. Piers of different heights therefore stand on
//! ground at different levels (a portal on a slope or a stepped site); the springings stay
//! level. voussoir does not build rampant arches (springings at different levels): no key
//! asks for one.

use super::{Section, MAX_VOUSSOIRS};
use crate::error::SceneError;
use crate::geometry::Vec2;
use toml::Value;

/// The profile of a pier: how wide each course is.
#[derive(Debug, Clone, PartialEq)]
pub enum PierProfile {
    /// Every course has width `width` (m).
    Rectangular { width: f64 },
    /// Course c (from the base) has width `widths[c]` (m).
    Stepped { widths: Vec<f64> },
    /// The width varies linearly from `bottom_width` at the base to `top_width` at the top.
    Battered { bottom_width: f64, top_width: f64 },
}

/// One pier.
#[derive(Debug, Clone, PartialEq)]
pub struct Pier {
    /// Height h (m), from the pier base to the springing line.
    pub height: f64,
    /// Number of equal courses k.
    pub courses: usize,
    pub profile: PierProfile,
}

impl Pier {
    /// The scene word of the profile (`piers.shape`).
    pub fn shape_name(&self) -> &'static str {
        match self.profile {
            PierProfile::Rectangular { .. } => "rectangular",
            PierProfile::Stepped { .. } => "stepped",
            PierProfile::Battered { .. } => "battered",
        }
    }

    /// Width at the bottom and at the top of course `c` (from the base).
    pub fn course_widths(&self, c: usize) -> (f64, f64) {
        match &self.profile {
            PierProfile::Rectangular { width } => (*width, *width),
            PierProfile::Stepped { widths } => (widths[c], widths[c]),
            PierProfile::Battered {
                bottom_width,
                top_width,
            } => {
                let k = self.courses as f64;
                let at = |f: f64| bottom_width + (top_width - bottom_width) * f;
                (at(c as f64 / k), at((c + 1) as f64 / k))
            }
        }
    }

    /// Width of the base (on the ground).
    pub fn base_width(&self) -> f64 {
        self.course_widths(0).0
    }

    /// Width of the top (under the springing).
    pub fn top_width(&self) -> f64 {
        self.course_widths(self.courses - 1).1
    }

    /// The widest course (m).
    pub fn max_width(&self) -> f64 {
        (0..self.courses)
            .map(|c| {
                let (a, b) = self.course_widths(c);
                a.max(b)
            })
            .fold(0.0, f64::max)
    }

    /// The pier in words: `h = 1 m, b = 0.4 m, 4 courses`, `h = 1 m, stepped b = 0.6/0.5/0.4 m`.
    pub fn describe(&self) -> String {
        let n = |x: f64| crate::geometry::trim(x);
        let courses = format!(
            "{} course{}",
            self.courses,
            if self.courses == 1 { "" } else { "s" }
        );
        match &self.profile {
            PierProfile::Rectangular { width } => {
                format!("h = {} m, b = {} m, {courses}", n(self.height), n(*width))
            }
            PierProfile::Stepped { widths } => format!(
                "h = {} m, stepped b = {} m (base to top)",
                n(self.height),
                widths.iter().map(|w| n(*w)).collect::<Vec<_>>().join("/")
            ),
            PierProfile::Battered {
                bottom_width,
                top_width,
            } => format!(
                "h = {} m, battered b = {} m at the base to {} m at the top, {courses}",
                n(self.height),
                n(*bottom_width),
                n(*top_width)
            ),
        }
    }
}

/// The two piers of a portal.
#[derive(Debug, Clone, PartialEq)]
pub struct Piers {
    pub left: Pier,
    pub right: Pier,
}

impl Piers {
    /// Whether both piers are the same (the portal is symmetric when its arch is).
    pub fn equal(&self) -> bool {
        self.left == self.right
    }

    /// The piers in words.
    pub fn describe(&self) -> String {
        if self.equal() {
            format!("on piers {}", self.left.describe())
        } else {
            format!(
                "on a left pier {} and a right pier {}",
                self.left.describe(),
                self.right.describe()
            )
        }
    }

    /// Tallest pier (m).
    pub fn max_height(&self) -> f64 {
        self.left.height.max(self.right.height)
    }
}

/// A course of a pier as a block: its outline and the bed joint under it (`p1` on the inner
/// face, `p2` on the outer face).
pub(super) struct Course {
    pub polygon: Vec<Vec2>,
    pub bed: (Vec2, Vec2),
}

/// The courses of `pier`, from the base up, with its inner face on `x = x_inner` and its
/// outer face toward `outward` (-1 for the left pier, +1 for the right one). A bed joint is
/// the overlap of the two courses it separates (the base joint: the whole base).
pub(super) fn courses(pier: &Pier, x_inner: f64, outward: f64) -> Vec<Course> {
    let (h, k) = (pier.height, pier.courses);
    (0..k)
        .map(|c| {
            let y0 = -h + h * c as f64 / k as f64;
            let y1 = -h + h * (c + 1) as f64 / k as f64;
            let (wb, wt) = pier.course_widths(c);
            let polygon = if outward < 0.0 {
                vec![
                    Vec2::new(x_inner - wb, y0),
                    Vec2::new(x_inner, y0),
                    Vec2::new(x_inner, y1),
                    Vec2::new(x_inner - wt, y1),
                ]
            } else {
                vec![
                    Vec2::new(x_inner, y0),
                    Vec2::new(x_inner + wb, y0),
                    Vec2::new(x_inner + wt, y1),
                    Vec2::new(x_inner, y1),
                ]
            };
            let bed = if c == 0 {
                wb
            } else {
                wb.min(pier.course_widths(c - 1).1)
            };
            let p2 = if outward < 0.0 {
                Vec2::new(x_inner - bed, y0)
            } else {
                Vec2::new(x_inner + bed, y0)
            };
            Course {
                polygon,
                bed: (Vec2::new(x_inner, y0), p2),
            }
        })
        .collect()
}

/// The keys of `[piers]` (and of `[piers.left]`, `[piers.right]`, which take the same ones
/// but `left` and `right`).
pub(super) const PIER_KEYS: &[&str] = &[
    "height",
    "width",
    "courses",
    "shape",
    "widths",
    "bottom_width",
    "top_width",
];
const SIDES: &[&str] = &["left", "right"];
const SHAPES: &[&str] = &["rectangular", "stepped", "battered"];

/// The keys of `[piers]` as read from one table (the common one or a side's), each with the
/// name of the table it came from.
#[derive(Debug, Clone, Default)]
struct Partial {
    height: Option<(f64, String)>,
    width: Option<(f64, String)>,
    courses: Option<(usize, String)>,
    shape: Option<(String, String)>,
    widths: Option<(Vec<f64>, String)>,
    bottom_width: Option<(f64, String)>,
    top_width: Option<(f64, String)>,
}

impl Partial {
    fn read(s: &mut Section) -> Result<Partial, SceneError> {
        let name = s.name.clone();
        let tag = |x| Some((x, name.clone()));
        let mut p = Partial::default();
        if s.table.contains_key("height") {
            p.height = tag(s.length("height", "pier height h in metres")?);
        }
        if s.table.contains_key("width") {
            p.width = tag(s.length("width", "pier width b in metres")?);
        }
        if s.table.contains_key("courses") {
            p.courses = Some((s.count("courses", None, 1, "")?, name.clone()));
        }
        if s.table.contains_key("shape") {
            let shape = s.string("shape", None)?;
            if !SHAPES.contains(&shape.as_str()) {
                return Err(s.out_of_range(
                    "shape",
                    format!("\"{shape}\""),
                    &format!(
                        "must be \"rectangular\", \"stepped\" or \"battered\"{}",
                        crate::error::did_you_mean(&shape, SHAPES)
                    ),
                ));
            }
            p.shape = Some((shape, name.clone()));
        }
        if s.table.contains_key("widths") {
            p.widths = Some((widths(s)?, name.clone()));
        }
        if s.table.contains_key("bottom_width") {
            p.bottom_width = tag(s.length("bottom_width", "")?);
        }
        if s.table.contains_key("top_width") {
            p.top_width = tag(s.length("top_width", "")?);
        }
        for key in SIDES {
            s.used.insert(key);
        }
        Ok(p)
    }

    /// This table's keys over `base`'s.
    fn over(&self, base: &Partial) -> Partial {
        Partial {
            height: self.height.clone().or(base.height.clone()),
            width: self.width.clone().or(base.width.clone()),
            courses: self.courses.clone().or(base.courses.clone()),
            shape: self.shape.clone().or(base.shape.clone()),
            widths: self.widths.clone().or(base.widths.clone()),
            bottom_width: self.bottom_width.clone().or(base.bottom_width.clone()),
            top_width: self.top_width.clone().or(base.top_width.clone()),
        }
    }
}

/// `widths`: a non-empty list of course widths (m), base to top.
fn widths(s: &mut Section) -> Result<Vec<f64>, SceneError> {
    s.used.insert("widths");
    let v = s
        .table
        .get("widths")
        .cloned()
        .unwrap_or(Value::Array(vec![]));
    let Value::Array(items) = &v else {
        return Err(s.wrong_type("widths", &v, "a list of course widths in metres"));
    };
    if items.is_empty() || items.len() > MAX_VOUSSOIRS {
        return Err(s.out_of_range(
            "widths",
            &v,
            &format!("must list from 1 to {MAX_VOUSSOIRS} course widths, base to top"),
        ));
    }
    let mut out = Vec::with_capacity(items.len());
    for (i, x) in items.iter().enumerate() {
        let w = match x {
            Value::Float(f) => *f,
            Value::Integer(i) => *i as f64,
            _ => return Err(s.wrong_type("widths", x, "a list of numbers (m)")),
        };
        if !(w.is_finite() && (super::MIN_LENGTH..=super::MAX_LENGTH).contains(&w)) {
            return Err(s.out_of_range(
                "widths",
                &v,
                &format!(
                    "width {i} (from the base) is {w}: every width must be a length from {:e} to {:e} m",
                    super::MIN_LENGTH,
                    super::MAX_LENGTH
                ),
            ));
        }
        out.push(w);
    }
    Ok(out)
}

/// Read `[piers]` (with `[piers.left]` and `[piers.right]` when given).
pub(super) fn parse_piers(mut s: Section) -> Result<Piers, SceneError> {
    let mut allowed: Vec<&str> = PIER_KEYS.to_vec();
    allowed.extend(SIDES);
    s.check_known(&allowed, "")?;
    let common = Partial::read(&mut s)?;
    s.finish("")?;
    let mut sides = Vec::new();
    for side in SIDES {
        let own = match s.table.get(*side) {
            None => None,
            Some(Value::Table(t)) => {
                let mut ss = Section::new(format!("piers.{side}"), t, s.origin);
                ss.check_known(PIER_KEYS, "")?;
                let p = Partial::read(&mut ss)?;
                ss.finish("")?;
                Some((p, t))
            }
            Some(v) => {
                return Err(s.wrong_type(side, v, &format!("a table [piers.{side}]")));
            }
        };
        sides.push(own);
    }
    let has_sides = sides.iter().any(Option::is_some);
    let mut used_common: Vec<&'static str> = Vec::new();
    let mut piers = Vec::new();
    for (side, own) in SIDES.iter().zip(&sides) {
        let merged = match own {
            Some((p, _)) => p.over(&common),
            None => common.clone(),
        };
        let here = if has_sides {
            format!("piers.{side}")
        } else {
            "piers".to_string()
        };
        let (pier, used) = resolve(&s, &merged, &here)?;
        for &key in &used {
            let from_common = match key {
                "height" => merged.height.as_ref().is_some_and(|x| x.1 == "piers"),
                "width" => merged.width.as_ref().is_some_and(|x| x.1 == "piers"),
                "courses" => merged.courses.as_ref().is_some_and(|x| x.1 == "piers"),
                "shape" => merged.shape.as_ref().is_some_and(|x| x.1 == "piers"),
                "widths" => merged.widths.as_ref().is_some_and(|x| x.1 == "piers"),
                "bottom_width" => merged.bottom_width.as_ref().is_some_and(|x| x.1 == "piers"),
                "top_width" => merged.top_width.as_ref().is_some_and(|x| x.1 == "piers"),
                _ => false,
            };
            if from_common {
                used_common.push(key);
            }
        }
        // A key of a side's own table that its profile does not take is a mistake.
        if let Some((_, t)) = own {
            for key in t.keys() {
                if !used.contains(&key.as_str()) {
                    return Err(s.out_of_range_key(
                        &format!("piers.{side}.{key}"),
                        &t[key.as_str()],
                        &format!(
                            "the {} pier is {}: {}",
                            side,
                            pier.shape_name(),
                            keys_of(pier.shape_name())
                        ),
                    ));
                }
            }
        }
        piers.push(pier);
    }
    // A key of `[piers]` that neither pier takes is a mistake too.
    for key in s.table.keys() {
        if SIDES.contains(&key.as_str()) || used_common.contains(&key.as_str()) {
            continue;
        }
        return Err(s.out_of_range(
            key,
            &s.table[key.as_str()],
            &format!(
                "no pier takes this key: the left pier is {} and the right one {} ({})",
                piers[0].shape_name(),
                piers[1].shape_name(),
                keys_of(piers[0].shape_name())
            ),
        ));
    }
    let right = piers.pop();
    let left = piers.pop();
    match (left, right) {
        (Some(left), Some(right)) => Ok(Piers { left, right }),
        _ => Err(s.missing("height", "pier height h in metres")),
    }
}

fn keys_of(shape: &str) -> &'static str {
    match shape {
        "stepped" => "a stepped pier takes height, widths (and courses = the number of widths)",
        "battered" => "a battered pier takes height, bottom_width, top_width, courses",
        _ => "a rectangular pier takes height, width, courses",
    }
}

/// One pier from its merged keys, and the keys it used. `here` names the table a missing
/// key should go in.
fn resolve(s: &Section, m: &Partial, here: &str) -> Result<(Pier, Vec<&'static str>), SceneError> {
    let missing = |key: &str, what: &str| SceneError::MissingKey {
        origin: s.origin.to_string(),
        key: format!("{here}.{key}"),
        what: what.to_string(),
    };
    let shape = m.shape.as_ref().map_or("rectangular", |x| x.0.as_str());
    let height = m
        .height
        .as_ref()
        .ok_or_else(|| missing("height", "pier height h in metres"))?
        .0;
    let mut used = vec!["height", "shape"];
    let pier = match shape {
        "stepped" => {
            let (widths, from) = m.widths.clone().ok_or_else(|| {
                missing(
                    "widths",
                    "course widths of the stepped pier in metres, base to top",
                )
            })?;
            if let Some((k, kf)) = &m.courses {
                if *k != widths.len() {
                    return Err(s.out_of_range_key(
                        &format!("{kf}.courses"),
                        k,
                        &format!(
                            "a stepped pier has one course per width: {from}.widths lists {}",
                            widths.len()
                        ),
                    ));
                }
                used.push("courses");
            }
            used.push("widths");
            Pier {
                height,
                courses: widths.len(),
                profile: PierProfile::Stepped { widths },
            }
        }
        "battered" => {
            let bottom_width = m
                .bottom_width
                .as_ref()
                .ok_or_else(|| missing("bottom_width", "width of the pier's base in metres"))?
                .0;
            let top_width = m
                .top_width
                .as_ref()
                .ok_or_else(|| missing("top_width", "width of the pier's top in metres"))?
                .0;
            used.extend(["bottom_width", "top_width", "courses"]);
            Pier {
                height,
                courses: m.courses.as_ref().map_or(1, |x| x.0),
                profile: PierProfile::Battered {
                    bottom_width,
                    top_width,
                },
            }
        }
        _ => {
            let width = m
                .width
                .as_ref()
                .ok_or_else(|| missing("width", "pier width b in metres"))?
                .0;
            used.extend(["width", "courses"]);
            Pier {
                height,
                courses: m.courses.as_ref().map_or(1, |x| x.0),
                profile: PierProfile::Rectangular { width },
            }
        }
    };
    Ok((pier, used))
}

impl Section<'_> {
    /// An out-of-range error for a key given by its full dotted name.
    fn out_of_range_key(&self, key: &str, value: impl ToString, allowed: &str) -> SceneError {
        SceneError::OutOfRange {
            origin: self.origin.to_string(),
            key: key.to_string(),
            value: value.to_string(),
            allowed: allowed.to_string(),
        }
    }
}
