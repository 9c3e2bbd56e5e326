//! Moving loads (`voussoir analyze --roll TARGET --from X0 --to X1 --step DX`, Python's
//! `voussoir.roll`): one load of the scene (`loads[k]`) or one vehicle (`vehicles[k]`) set
//! at each position along x, the scene analysed there by the analysis layer
//! ([`analysis::analyse`], both bounds), and the critical position (the least static
//! multiplier) refined between its neighbours by a golden-section search and analysed again
//! with every method asked for, so its mechanism is that of the critical position itself
//! (the continuous model and the DEM, when asked, run there only).
//!
//! What a position is: a vehicle's `at` (the x of its first axle); a line load's `from_x`
//! (its length kept); a point load's x, the load standing on the top at that x (the fill's
//! road surface over a filled structure, spread through the fill by the scene's law; the
//! extrados of a bare arch), whatever the height of its `at` in the scene. Each position is
//! a scene of its own (the load's keys set as `--set` would), so a load off the structure is
//! that scene's error, naming the key and the position.
//!
//! The golden-section search (Kiefer 1953) assumes the multiplier unimodal between the grid
//! neighbours of the least grid value; within one voussoir it is a ratio of linear functions
//! of the position for each mechanism, so the least multiplier sits at a joint or where two
//! mechanisms cross, and the search closes on it to [`REFINE_TOL`] of the structure's size.

use crate::analysis::{self, Options, SceneAnalysis};
use crate::error::{AnalysisError, SceneError};
use crate::scene::{LoadSpec, Scene};
use crate::statics::Status;
use rayon::prelude::*;
use toml::Value;

/// Largest number of positions of one roll.
pub const MAX_POSITIONS: usize = 100_000;

/// Width of the golden-section search's final bracket, relative to the structure's size.
pub const REFINE_TOL: f64 = 1e-10;

/// What moves.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Target {
    /// `loads[k]`.
    Load(usize),
    /// `vehicles[k]`.
    Vehicle(usize),
}

impl std::fmt::Display for Target {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Target::Load(k) => write!(f, "loads[{k}]"),
            Target::Vehicle(k) => write!(f, "vehicles[{k}]"),
        }
    }
}

impl std::str::FromStr for Target {
    type Err = AnalysisError;

    /// `loads[K]` or `vehicles[K]`.
    fn from_str(text: &str) -> Result<Target, AnalysisError> {
        let bad = || AnalysisError::Settings {
            setting: "--roll".into(),
            value: text.into(),
            allowed:
                "loads[K] or vehicles[K] (K counts the [[loads]] or [[vehicles]] entries from 0)"
                    .into(),
        };
        let t = text.trim();
        let (list, rest) = if let Some(r) = t.strip_prefix("loads[") {
            (Target::Load as fn(usize) -> Target, r)
        } else if let Some(r) = t.strip_prefix("vehicles[") {
            (Target::Vehicle as fn(usize) -> Target, r)
        } else {
            return Err(bad());
        };
        let index = rest.strip_suffix(']').ok_or_else(bad)?;
        index.trim().parse().map(list).map_err(|_| bad())
    }
}

/// A roll: what moves, and where.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RollSpec {
    pub target: Target,
    /// First position (m).
    pub from: f64,
    /// Last position (m), included when reached within round-off.
    pub to: f64,
    /// Distance between positions (m), > 0.
    pub step: f64,
    /// Whether to refine the critical position between its grid neighbours.
    pub refine: bool,
}

impl RollSpec {
    /// The positions `from + i step` up to `to`, or why the range is wrong (naming the flag).
    pub fn positions(&self) -> Result<Vec<f64>, AnalysisError> {
        let bad = |setting: &str, value: f64, allowed: &str| AnalysisError::Settings {
            setting: setting.into(),
            value: value.to_string(),
            allowed: allowed.into(),
        };
        for (flag, x) in [("--from", self.from), ("--to", self.to)] {
            if !x.is_finite() {
                return Err(bad(flag, x, "a finite position in metres"));
            }
        }
        if !(self.step.is_finite() && self.step > 0.0) {
            return Err(bad("--step", self.step, "a finite distance > 0 in metres"));
        }
        if self.to < self.from {
            return Err(bad(
                "--to",
                self.to,
                &format!("at least --from = {}", self.from),
            ));
        }
        let n = ((self.to - self.from) / self.step + 1e-9).floor();
        if n + 1.0 > MAX_POSITIONS as f64 {
            return Err(bad(
                "--step",
                self.step,
                &format!("large enough that --from..--to holds at most {MAX_POSITIONS} positions"),
            ));
        }
        Ok((0..=n as usize)
            .map(|i| self.from + i as f64 * self.step)
            .collect())
    }
}

/// The analysis at one position.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RollPoint {
    pub position: f64,
    pub status: Status,
    /// The static multiplier (lower bound, by the static theorem).
    pub lambda_lower: Option<f64>,
    /// The kinematic multiplier (upper bound, by the kinematic theorem), when one ran.
    pub lambda_upper: Option<f64>,
}

/// The critical position and its analysis.
#[derive(Debug, Clone)]
pub struct Critical {
    /// The critical position (m): the least static multiplier, refined when asked.
    pub position: f64,
    /// The grid position with the least static multiplier (m).
    pub grid_position: f64,
    /// The scene with the load at the critical position.
    pub scene: Scene,
    /// Every method asked for, at the critical position.
    pub analysis: SceneAnalysis,
}

/// A roll's result.
#[derive(Debug, Clone)]
pub struct Roll {
    pub spec: RollSpec,
    pub points: Vec<RollPoint>,
    /// None when no position has a static multiplier (the structure cannot stand anywhere).
    pub critical: Option<Critical>,
}

/// The scene with `target` at `x` (see the module docs).
pub fn scene_at(scene: &Scene, target: Target, x: f64) -> Result<Scene, SceneError> {
    match target {
        Target::Vehicle(k) => {
            count(scene, "vehicles", scene.vehicles.len(), k)?;
            scene.with_value(&format!("vehicles[{k}].at"), Value::Float(x))
        }
        Target::Load(k) => match scene.loads.get(k) {
            None => Err(count(scene, "loads", scene.loads.len(), k).unwrap_err()),
            Some(LoadSpec::Line { from_x, to_x, .. }) => scene.with_values(&[
                (&format!("loads[{k}].from_x"), Value::Float(x)),
                (
                    &format!("loads[{k}].to_x"),
                    Value::Float(x + (to_x - from_x)),
                ),
            ]),
            Some(LoadSpec::Point { .. }) => {
                let y = crate::scene::standing_heights(scene, &[x])?[0].ok_or_else(|| {
                    SceneError::OutOfRange {
                        origin: scene.origin.clone(),
                        key: format!("loads[{k}].at"),
                        value: format!("x = {x} (a position of the roll)"),
                        allowed: "a moving load must stand on the structure: no block's top lies under this x"
                            .into(),
                    }
                })?;
                let at = Value::Array(vec![Value::Float(x), Value::Float(y)]);
                scene.with_value(&format!("loads[{k}].at"), at)
            }
        },
    }
}

/// `Ok` when the list `list` (of `len` entries) has entry `k`.
fn count(scene: &Scene, list: &str, len: usize, k: usize) -> Result<(), SceneError> {
    if k < len {
        return Ok(());
    }
    Err(SceneError::OutOfRange {
        origin: scene.origin.clone(),
        key: format!("{list}[{k}]"),
        value: format!("--roll {list}[{k}]"),
        allowed: format!("the scene has {len} [[{list}]] entries"),
    })
}

/// Roll `spec.target` over its positions and analyse the scene at each with `options`; the
/// critical position refined (when `spec.refine`) and analysed again.
pub fn roll(scene: &Scene, spec: &RollSpec, options: &Options) -> Result<Roll, AnalysisError> {
    options.validate()?;
    let xs = spec.positions()?;
    // Both bounds at every position; the continuous model and the DEM, when asked, at the
    // critical position only.
    let grid = Options {
        continuous: false,
        dem: false,
        ..options.clone()
    };
    let points = xs
        .par_iter()
        .map(|&x| {
            let a = analysis::analyse(&scene_at(scene, spec.target, x)?, &grid)?;
            Ok(RollPoint {
                position: x,
                status: a.lower.status,
                lambda_lower: a.lower.lambda,
                lambda_upper: a.lambda_upper(),
            })
        })
        .collect::<Vec<Result<RollPoint, AnalysisError>>>()
        // The first position's error (in order along x), whichever thread met it first.
        .into_iter()
        .collect::<Result<Vec<_>, AnalysisError>>()?;
    let key = |p: &RollPoint| p.lambda_lower.unwrap_or(f64::INFINITY);
    let best = (0..points.len())
        .filter(|&i| points[i].lambda_lower.is_some())
        .min_by(|&i, &j| key(&points[i]).total_cmp(&key(&points[j])));
    let Some(i) = best else {
        return Ok(Roll {
            spec: *spec,
            points,
            critical: None,
        });
    };
    let grid_position = points[i].position;
    let mut position = grid_position;
    if spec.refine && points.len() > 1 {
        let lo = points[i.saturating_sub(1)].position;
        let hi = points[(i + 1).min(points.len() - 1)].position;
        // The static bound alone decides where the least multiplier is.
        let statics_only = Options {
            kinematic_max_joints: 0,
            continuous: false,
            dem: false,
            friction: analysis::FrictionMode::Associative,
            ..options.clone()
        };
        let f = |x: f64| -> Result<f64, AnalysisError> {
            let a = analysis::analyse(&scene_at(scene, spec.target, x)?, &statics_only)?;
            Ok(a.lower.lambda.unwrap_or(f64::INFINITY))
        };
        let (x, fx) = golden_section(lo, hi, REFINE_TOL * scene.size().max(1e-3), f)?;
        if fx < key(&points[i]) {
            position = x;
        }
    }
    let critical_scene = scene_at(scene, spec.target, position)?;
    let analysis = analysis::analyse(&critical_scene, options)?;
    Ok(Roll {
        spec: *spec,
        points,
        critical: Some(Critical {
            position,
            grid_position,
            scene: critical_scene,
            analysis,
        }),
    })
}

/// The least of `f` over `[lo, hi]` by golden-section search, to a bracket narrower than
/// `tol`: the point and its value (the best point seen).
pub fn golden_section<F>(
    mut lo: f64,
    mut hi: f64,
    tol: f64,
    f: F,
) -> Result<(f64, f64), AnalysisError>
where
    F: Fn(f64) -> Result<f64, AnalysisError>,
{
    let r = 0.5 * (5f64.sqrt() - 1.0);
    let mut c = hi - r * (hi - lo);
    let mut d = lo + r * (hi - lo);
    let (mut fc, mut fd) = (f(c)?, f(d)?);
    let mut best = if fc <= fd { (c, fc) } else { (d, fd) };
    // At most 200 steps: the bracket shrinks by 0.618 each, far past round-off.
    for _ in 0..200 {
        if hi - lo <= tol {
            break;
        }
        if fc <= fd {
            hi = d;
            (d, fd) = (c, fc);
            c = hi - r * (hi - lo);
            fc = f(c)?;
        } else {
            lo = c;
            (c, fc) = (d, fd);
            d = lo + r * (hi - lo);
            fd = f(d)?;
        }
        for (x, fx) in [(c, fc), (d, fd)] {
            if fx < best.1 {
                best = (x, fx);
            }
        }
    }
    Ok(best)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn golden_section_finds_a_kink() {
        let f = |x: f64| Ok((x - 0.3).abs() + 2.0);
        let (x, fx) = golden_section(0.0, 1.0, 1e-12, f).unwrap();
        assert!((x - 0.3).abs() < 1e-11 && (fx - 2.0).abs() < 1e-11);
    }

    #[test]
    fn targets_parse() {
        assert_eq!("loads[2]".parse::<Target>().unwrap(), Target::Load(2));
        assert_eq!("vehicles[0]".parse::<Target>().unwrap(), Target::Vehicle(0));
        assert!("load[0]".parse::<Target>().is_err());
        assert!("vehicles[x]".parse::<Target>().is_err());
    }
}
