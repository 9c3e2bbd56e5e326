//! The seismic hazard of a site from its coordinates, by the rules of the Italian code: the
//! return period of a limit state, and `ag`, `F0`, `Tc*` interpolated on the national hazard
//! grid.
//!
//! Equations and data:
//! - NTC 2018 (D.M. 17/01/2018) §2.4.3: the reference period `V_R = V_N C_U`, with the
//!   nominal life `V_N` (years, §2.4.1) and the coefficient of the use class, `C_U` = 0.7,
//!   1.0, 1.5, 2.0 for classes I-IV (Tab. 2.4.II); at least 35 years, the floor of NTC 2008
//!   §2.4.3 ("se V_R <= 35 anni si pone comunque V_R = 35 anni"), kept here: it matters only
//!   where `V_N C_U` < 35 years (temporary constructions), whose return periods would
//!   otherwise fall below the grid's 30 years at SLO and SLD.
//! - NTC 2018 §3.2.1, Tab. 3.2.I: the probability of exceedance in `V_R` of each limit state,
//!   `P_VR` = 81 % (SLO), 63 % (SLD), 10 % (SLV), 5 % (SLC); and the return period (NTC 2008
//!   Allegato A) `T_R = -V_R / ln(1 - P_VR)` (so V_N = 50 years, class II, SLV gives
//!   `T_R = -50 / ln 0.9` = 474.6 years, the 475 years of the grid).
//! - NTC 2008 (D.M. 14/01/2008) Allegato B, Tabella 1, which NTC 2018 §3.2 keeps: the
//!   reference grid of 10,751 nodes (`ID`, longitude, latitude; about 5.5 km apart) with
//!   `ag` (in g/10 in the table; in g here), `F0` and `Tc*` (s) at the nine return periods
//!   30, 50, 72, 101, 140, 201, 475, 975, 2475 years.
//! - NTC 2008 Allegato A: a parameter `p` at a point is the mean of its values `p_i` at the
//!   four nodes of the grid's cell that contains the point, weighted by the inverse of the
//!   distances `d_i` from the point, `p = sum(p_i / d_i) / sum(1 / d_i)` ("eq. 1" below); between the
//!   tabulated return periods `T_R1 < T_R < T_R2`,
//!   `log p = log p1 + log(p2 / p1) log(T_R / T_R1) / log(T_R2 / T_R1)` (eq. 2), with `p1`,
//!   `p2` the site's values (eq. 1) at `T_R1`, `T_R2`.
//!
//! Choices the annex leaves open, made here: the distances are great-circle distances on a
//! sphere (their ratios, all eq. 1 uses, are those of any Earth radius); a point on a node
//! takes the node's values (the limit of eq. 1); the cell of a point is the quadrilateral of
//! nodes `n`, `n + 1`, `n + R + 1`, `n + R` (the grid is numbered row by row, `R` = 222 to a
//! row, `n + 1` to the east and `n + R` to the south: `build.rs` checks it) that contains it,
//! its sides taken straight in longitude and latitude, and a point on a side shared by two
//! cells takes the cell of the lower `n` (eq. 1 over four nodes is not continuous across a
//! side). A point in no complete cell is outside the grid, and a return period outside 30 to
//! 2475 years is refused, not extrapolated. Latitude and longitude are taken on the grid's
//! datum (ED50 in the annex's use); GPS and web maps give WGS84, whose coordinates of a
//! point in Italy differ by some 100 m, small against the grid's 5.5 km spacing.
//!
//! The bundled grid (`Grid::bundled`) is embedded at build time by `build.rs` from the data
//! file described in `data/hazard/README.md`; a build without that file has no grid and
//! refuses coordinates (`HazardError::NotBundled`).

use crate::error::HazardError;
use std::collections::HashMap;
use std::sync::OnceLock;

/// The return periods of the grid's columns (years), NTC 2008 Allegato B.
pub const RETURN_PERIODS: [f64; 9] = [30.0, 50.0, 72.0, 101.0, 140.0, 201.0, 475.0, 975.0, 2475.0];

/// The least reference period (years), NTC 2008 §2.4.3.
pub const MIN_REFERENCE_PERIOD: f64 = 35.0;

/// Nodes to a row of the national grid's numbering.
pub const NATIONAL_ROW: u32 = 222;

/// Radius (m) of the sphere the distances are measured on (the mean Earth radius; eq. 1
/// uses only ratios of distances).
const EARTH_RADIUS: f64 = 6_371_008.8;

/// A limit state of NTC 2018 §3.2.1.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
pub enum LimitState {
    /// Operativity (SLO).
    SLO,
    /// Damage limitation (SLD).
    SLD,
    /// Life safety (SLV), the state the assessment of `voussoir assess` checks.
    SLV,
    /// Collapse prevention (SLC).
    SLC,
}

impl LimitState {
    pub const ALL: [LimitState; 4] = [
        LimitState::SLO,
        LimitState::SLD,
        LimitState::SLV,
        LimitState::SLC,
    ];

    pub fn parse(s: &str) -> Option<LimitState> {
        LimitState::ALL.into_iter().find(|l| l.as_str() == s)
    }

    pub fn as_str(self) -> &'static str {
        match self {
            LimitState::SLO => "SLO",
            LimitState::SLD => "SLD",
            LimitState::SLV => "SLV",
            LimitState::SLC => "SLC",
        }
    }

    /// Probability of exceedance in the reference period, `P_VR` (NTC 2018 Tab. 3.2.I).
    pub fn p_vr(self) -> f64 {
        match self {
            LimitState::SLO => 0.81,
            LimitState::SLD => 0.63,
            LimitState::SLV => 0.10,
            LimitState::SLC => 0.05,
        }
    }
}

/// A use class of NTC 2018 §2.4.2.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
pub enum UseClass {
    I,
    II,
    III,
    IV,
}

impl UseClass {
    pub const ALL: [UseClass; 4] = [UseClass::I, UseClass::II, UseClass::III, UseClass::IV];

    pub fn parse(s: &str) -> Option<UseClass> {
        UseClass::ALL.into_iter().find(|c| c.as_str() == s)
    }

    pub fn as_str(self) -> &'static str {
        match self {
            UseClass::I => "I",
            UseClass::II => "II",
            UseClass::III => "III",
            UseClass::IV => "IV",
        }
    }

    /// `C_U` (NTC 2018 Tab. 2.4.II).
    pub fn cu(self) -> f64 {
        match self {
            UseClass::I => 0.7,
            UseClass::II => 1.0,
            UseClass::III => 1.5,
            UseClass::IV => 2.0,
        }
    }
}

/// `V_R = max(V_N C_U, 35)` (years): NTC 2018 §2.4.3 with the floor of NTC 2008 §2.4.3.
pub fn reference_period(nominal_life: f64, class: UseClass) -> f64 {
    (nominal_life * class.cu()).max(MIN_REFERENCE_PERIOD)
}

/// `T_R = -V_R / ln(1 - P_VR)` (years): the return period whose probability of exceedance in
/// `V_R` is `P_VR` for Poisson occurrences (NTC 2008 Allegato A).
pub fn return_period(reference_period: f64, state: LimitState) -> f64 {
    -reference_period / (1.0 - state.p_vr()).ln()
}

/// `ag` (g), `F0`, `Tc*` (s).
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct Params {
    pub ag: f64,
    #[serde(rename = "F0")]
    pub f0: f64,
    #[serde(rename = "Tc_star")]
    pub tc_star: f64,
}

impl Params {
    fn map(self, other: Params, f: impl Fn(f64, f64) -> f64) -> Params {
        Params {
            ag: f(self.ag, other.ag),
            f0: f(self.f0, other.f0),
            tc_star: f(self.tc_star, other.tc_star),
        }
    }
}

/// A node of the grid: its id, longitude and latitude (degrees) and its values at the nine
/// return periods of [`RETURN_PERIODS`] (`ag` in g).
#[derive(Debug, Clone, PartialEq)]
pub struct Node {
    pub id: u32,
    pub longitude: f64,
    pub latitude: f64,
    pub values: [Params; 9],
}

/// A node of the cell a site was interpolated in, and its distance from the site.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct CellNode {
    pub id: u32,
    pub longitude: f64,
    pub latitude: f64,
    /// Great-circle distance from the site (m).
    pub distance: f64,
}

/// A hazard grid: nodes numbered row by row, `row` to a row (`id + 1` east, `id + row`
/// south).
#[derive(Debug, Clone)]
pub struct Grid {
    nodes: Vec<Node>,
    by_id: HashMap<u32, usize>,
    row: u32,
}

/// The little-endian f64 rows `[id, lon, lat, 27 values]` that `build.rs` embeds.
static BUNDLED: &[u8] = include_bytes!(concat!(env!("OUT_DIR"), "/ntc2008_grid.bin"));

impl Grid {
    /// A grid of `nodes` numbered row by row, `row` to a row. Ids must be unique.
    pub fn new(nodes: Vec<Node>, row: u32) -> Grid {
        let by_id = nodes.iter().enumerate().map(|(i, n)| (n.id, i)).collect();
        Grid { nodes, by_id, row }
    }

    /// The national grid of NTC 2008 Allegato B, Tabella 1, embedded at build time, or
    /// `HazardError::NotBundled` when this build was made without its data file.
    pub fn bundled() -> Result<&'static Grid, HazardError> {
        static GRID: OnceLock<Option<Grid>> = OnceLock::new();
        GRID.get_or_init(|| {
            const ROW_BYTES: usize = 30 * 8;
            if BUNDLED.is_empty() || !BUNDLED.len().is_multiple_of(ROW_BYTES) {
                return None;
            }
            let f = |b: &[u8]| {
                let mut a = [0u8; 8];
                a.copy_from_slice(b);
                f64::from_le_bytes(a)
            };
            let nodes = BUNDLED
                .chunks_exact(ROW_BYTES)
                .map(|r| {
                    let x: Vec<f64> = r.chunks_exact(8).map(f).collect();
                    let values = std::array::from_fn(|k| Params {
                        // The table gives ag in g/10.
                        ag: x[3 + 3 * k] / 10.0,
                        f0: x[4 + 3 * k],
                        tc_star: x[5 + 3 * k],
                    });
                    Node {
                        id: x[0] as u32,
                        longitude: x[1],
                        latitude: x[2],
                        values,
                    }
                })
                .collect();
            Some(Grid::new(nodes, NATIONAL_ROW))
        })
        .as_ref()
        .ok_or(HazardError::NotBundled)
    }

    /// Whether this build embeds the national grid.
    pub fn is_bundled() -> bool {
        Grid::bundled().is_ok()
    }

    pub fn nodes(&self) -> &[Node] {
        &self.nodes
    }

    pub fn node(&self, id: u32) -> Option<&Node> {
        self.by_id.get(&id).map(|&i| &self.nodes[i])
    }

    /// The four nodes of the cell that contains the point (north-west, north-east,
    /// south-east, south-west), or `OutsideGrid`.
    pub fn cell(&self, latitude: f64, longitude: f64) -> Result<[&Node; 4], HazardError> {
        let outside = HazardError::OutsideGrid {
            latitude,
            longitude,
        };
        if !(latitude.is_finite() && longitude.is_finite()) {
            return Err(outside);
        }
        // Projected locally (x scaled by cos latitude) so that "inside" is judged on the
        // ground's proportions; cells are a few km wide, so their sides are straight enough.
        let c = latitude.to_radians().cos();
        let xy = |n: &Node| ((n.longitude - longitude) * c, n.latitude - latitude);
        let mut best: Option<[&Node; 4]> = None;
        for nw in &self.nodes {
            // Only cells near the point (a cell spans well under 0.2 degree).
            if (nw.latitude - latitude).abs() > 0.2 || (nw.longitude - longitude).abs() > 0.3 {
                continue;
            }
            let corner = |id: u32| self.node(id);
            let (Some(ne), Some(se), Some(sw)) = (
                corner(nw.id + 1),
                corner(nw.id + self.row + 1),
                corner(nw.id + self.row),
            ) else {
                continue;
            };
            let quad = [nw, ne, se, sw];
            let p: Vec<(f64, f64)> = quad.iter().map(|n| xy(n)).collect();
            // The origin is inside (or on) the convex quadrilateral when it is on the same
            // side of all four sides.
            let side = |a: (f64, f64), b: (f64, f64)| a.0 * b.1 - a.1 * b.0;
            let s: Vec<f64> = (0..4).map(|i| side(p[i], p[(i + 1) % 4])).collect();
            let inside = s.iter().all(|&v| v >= 0.0) || s.iter().all(|&v| v <= 0.0);
            if inside && best.is_none_or(|b| nw.id < b[0].id) {
                best = Some(quad);
            }
        }
        best.ok_or(outside)
    }

    /// The site's values at the grid's `k`-th return period by eq. 1, and the cell's nodes
    /// with their distances.
    fn at_column(
        cell: &[&Node; 4],
        latitude: f64,
        longitude: f64,
        k: usize,
    ) -> (Params, [CellNode; 4]) {
        let nodes = cell.map(|n| CellNode {
            id: n.id,
            longitude: n.longitude,
            latitude: n.latitude,
            distance: distance(latitude, longitude, n.latitude, n.longitude),
        });
        if let Some(i) = nodes.iter().position(|n| n.distance == 0.0) {
            return (cell[i].values[k], nodes);
        }
        // Eq. 1, each parameter on its own.
        let weights = nodes.map(|n| 1.0 / n.distance);
        let total: f64 = weights.iter().sum();
        let mean = |p: fn(&Params) -> f64| -> f64 {
            cell.iter()
                .zip(weights)
                .map(|(n, w)| w * p(&n.values[k]))
                .sum::<f64>()
                / total
        };
        let params = Params {
            ag: mean(|p| p.ag),
            f0: mean(|p| p.f0),
            tc_star: mean(|p| p.tc_star),
        };
        (params, nodes)
    }

    /// `ag`, `F0`, `Tc*` at a point and return period `t_r` (years, 30 to 2475): eq. 1 at
    /// the tabulated periods around `t_r`, then eq. 2 between them.
    pub fn at(&self, latitude: f64, longitude: f64, t_r: f64) -> Result<Interpolated, HazardError> {
        let cell = self.cell(latitude, longitude)?;
        let (lo, hi) = bracket(t_r).ok_or(HazardError::ReturnPeriod {
            t_r,
            v_r: None,
            limit_state: None,
        })?;
        let (p1, nodes) = Grid::at_column(&cell, latitude, longitude, lo);
        let params = if lo == hi {
            p1
        } else {
            let (p2, _) = Grid::at_column(&cell, latitude, longitude, hi);
            let (t1, t2) = (RETURN_PERIODS[lo], RETURN_PERIODS[hi]);
            let w = (t_r / t1).ln() / (t2 / t1).ln();
            p1.map(p2, |a, b| (a.ln() + (b / a).ln() * w).exp())
        };
        Ok(Interpolated {
            params,
            nodes,
            periods: [RETURN_PERIODS[lo], RETURN_PERIODS[hi]],
        })
    }
}

/// The result of [`Grid::at`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Interpolated {
    pub params: Params,
    /// The cell's nodes (north-west, north-east, south-east, south-west).
    pub nodes: [CellNode; 4],
    /// The tabulated return periods interpolated between (equal when `t_r` is one).
    pub periods: [f64; 2],
}

/// The columns `(lo, hi)` of [`RETURN_PERIODS`] around `t_r` (equal when `t_r` is one of
/// them), or `None` outside 30 to 2475 years.
pub fn bracket(t_r: f64) -> Option<(usize, usize)> {
    if let Some(k) = RETURN_PERIODS.iter().position(|&t| t == t_r) {
        return Some((k, k));
    }
    let hi = RETURN_PERIODS.iter().position(|&t| t > t_r)?;
    (hi > 0).then_some((hi - 1, hi))
}

/// Great-circle distance (m) between two points given in degrees (haversine formula).
pub fn distance(lat1: f64, lon1: f64, lat2: f64, lon2: f64) -> f64 {
    let (p1, p2) = (lat1.to_radians(), lat2.to_radians());
    let dp = p2 - p1;
    let dl = (lon2 - lon1).to_radians();
    let h = (dp / 2.0).sin().powi(2) + p1.cos() * p2.cos() * (dl / 2.0).sin().powi(2);
    2.0 * EARTH_RADIUS * h.sqrt().min(1.0).asin()
}

/// The hazard of a site: where it is, what it is designed for, and what the grid gives.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct SiteHazard {
    pub latitude: f64,
    pub longitude: f64,
    /// `V_N` (years).
    pub nominal_life: f64,
    pub use_class: UseClass,
    #[serde(rename = "C_U")]
    pub cu: f64,
    /// `V_R = max(V_N C_U, 35)` (years).
    #[serde(rename = "V_R")]
    pub v_r: f64,
    pub limit_state: LimitState,
    #[serde(rename = "P_VR")]
    pub p_vr: f64,
    /// `T_R` (years).
    #[serde(rename = "T_R")]
    pub t_r: f64,
    /// `ag` (g), `F0`, `Tc*` (s) at the site and `T_R`.
    #[serde(flatten)]
    pub params: Params,
    /// The tabulated return periods interpolated between.
    pub return_periods: [f64; 2],
    /// The four nodes of the grid's cell (north-west, north-east, south-east, south-west).
    pub nodes: [CellNode; 4],
    /// Where the values come from.
    pub source: &'static str,
}

/// Where the bundled grid's values come from, in the JSON.
pub const SOURCE: &str = "NTC 2008 Allegato B, Tabella 1 (national hazard grid), interpolated by Allegato A (the cell's 4 nodes weighted by inverse distance; eq. 2, logarithmic between return periods)";

/// The hazard of a site on `grid` (NTC 2018 §2.4.3, §3.2.1; NTC 2008 Allegati A, B).
pub fn site_hazard(
    grid: &Grid,
    latitude: f64,
    longitude: f64,
    nominal_life: f64,
    use_class: UseClass,
    limit_state: LimitState,
) -> Result<SiteHazard, HazardError> {
    let v_r = reference_period(nominal_life, use_class);
    let t_r = return_period(v_r, limit_state);
    // The point first: a site outside the grid is refused as such, whatever its period.
    grid.cell(latitude, longitude)?;
    let at = grid.at(latitude, longitude, t_r).map_err(|e| match e {
        HazardError::ReturnPeriod { t_r, .. } => HazardError::ReturnPeriod {
            t_r,
            v_r: Some(v_r),
            limit_state: Some(limit_state.as_str()),
        },
        e => e,
    })?;
    Ok(SiteHazard {
        latitude,
        longitude,
        nominal_life,
        use_class,
        cu: use_class.cu(),
        v_r,
        limit_state,
        p_vr: limit_state.p_vr(),
        t_r,
        params: at.params,
        return_periods: at.periods,
        nodes: at.nodes,
        source: SOURCE,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bracket_finds_the_columns_around_a_period() {
        assert_eq!(bracket(30.0), Some((0, 0)));
        assert_eq!(bracket(2475.0), Some((8, 8)));
        assert_eq!(bracket(474.6), Some((5, 6)));
        assert_eq!(bracket(29.9), None);
        assert_eq!(bracket(2475.1), None);
        assert_eq!(bracket(f64::NAN), None);
    }

    #[test]
    fn distance_of_a_degree_of_latitude() {
        // A degree of a great circle is R pi / 180.
        let d = distance(42.0, 12.0, 43.0, 12.0);
        assert!((d - EARTH_RADIUS * std::f64::consts::PI / 180.0).abs() < 1e-6);
        assert_eq!(distance(42.0, 12.0, 42.0, 12.0), 0.0);
    }
}
