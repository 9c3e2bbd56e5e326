//! The site's hazard from its coordinates (`[site] latitude`, `longitude`, `nominal_life`,
//! `use_class`, `limit_state`; src/hazard.rs): the return period of NTC 2018 derived here,
//! the interpolation of NTC 2008 Allegato A checked against its equations worked out in the
//! test on grids made here, and the national grid of Allegato B against a published copy of
//! its values.
//!
//! The national grid is embedded only when its data file was found at build time
//! (data/hazard/README.md); the tests that read it are ignored in a build without it, and
//! `a_build_without_the_grid_refuses_coordinates` checks what such a build answers.

use crate::common::{data, voussoir};
use voussoir::error::{HazardError, SceneError};
use voussoir::hazard::{
    self, Grid, LimitState, Node, Params, UseClass, NATIONAL_ROW, RETURN_PERIODS,
};

const NO_GRID: &str = "the NTC 2008 grid is not bundled in this build (data/hazard/README.md)";

/// Great-circle distance (m) on the sphere of the mean Earth radius, written out here in
/// Vincenty's form for the sphere (well conditioned at short range; the library uses the
/// haversine form).
fn arc(lat1: f64, lon1: f64, lat2: f64, lon2: f64) -> f64 {
    let (p1, p2) = (lat1.to_radians(), lat2.to_radians());
    let dl = (lon2 - lon1).to_radians();
    let y = ((p2.cos() * dl.sin()).powi(2)
        + (p1.cos() * p2.sin() - p1.sin() * p2.cos() * dl.cos()).powi(2))
    .sqrt();
    let x = p1.sin() * p2.sin() + p1.cos() * p2.cos() * dl.cos();
    6_371_008.8 * y.atan2(x)
}

/// NTC 2008 Allegato A's inverse-distance mean ("eq. 1") at column `k`, written out: sum(p_i / d_i) / sum(1 / d_i).
fn eq1(nodes: &[&Node], lat: f64, lon: f64, k: usize) -> Params {
    let w: Vec<f64> = nodes
        .iter()
        .map(|n| 1.0 / arc(lat, lon, n.latitude, n.longitude))
        .collect();
    let total: f64 = w.iter().sum();
    let mean = |f: &dyn Fn(&Params) -> f64| -> f64 {
        nodes
            .iter()
            .zip(&w)
            .map(|(n, w)| w * f(&n.values[k]))
            .sum::<f64>()
            / total
    };
    Params {
        ag: mean(&|p| p.ag),
        f0: mean(&|p| p.f0),
        tc_star: mean(&|p| p.tc_star),
    }
}

/// Allegato A eq. 2, written out: log p = log p1 + log(p2/p1) log(T/T1) / log(T2/T1).
fn eq2(p1: f64, p2: f64, t1: f64, t2: f64, t: f64) -> f64 {
    10f64.powf(p1.log10() + (p2 / p1).log10() * (t / t1).log10() / (t2 / t1).log10())
}

fn close(a: f64, b: f64, tol: f64, what: &str) {
    assert!(
        (a - b).abs() <= tol * b.abs().max(1.0),
        "{what}: {a} against {b}"
    );
}

/// A 3 x 4 grid of nodes near (42 N, 13 E), numbered as the national grid is (`id + 1` east,
/// `id + ROW` south), 0.05 degrees of latitude and 0.07 of longitude apart, with values
/// `value(node, k)` and a row width of 10 (ids 100.., rows 100, 110, 120).
const ROW: u32 = 10;
fn test_grid(value: impl Fn(u32, usize) -> Params) -> Grid {
    let mut nodes = Vec::new();
    for r in 0..3u32 {
        for c in 0..4u32 {
            let id = 100 + r * ROW + c;
            nodes.push(Node {
                id,
                // Rows go south; a slight skew as in the national grid.
                latitude: 42.10 - 0.05 * r as f64 + 0.004 * c as f64,
                longitude: 13.00 + 0.07 * c as f64 + 0.0058 * r as f64,
                values: std::array::from_fn(|k| value(id, k)),
            });
        }
    }
    Grid::new(nodes, ROW)
}

/// Values that differ from node to node and column to column.
fn varied(id: u32, k: usize) -> Params {
    let i = (id - 100) as f64;
    Params {
        ag: 0.02 + 0.01 * k as f64 + 0.003 * i,
        f0: 2.3 + 0.02 * ((i + k as f64) % 5.0),
        tc_star: 0.2 + 0.015 * k as f64 + 0.002 * (i % 7.0),
    }
}

#[test]
fn return_period_of_each_limit_state_by_ntc_2018() {
    // NTC 2018 §2.4.3: V_R = V_N C_U, at least 35 years (NTC 2008 §2.4.3); Tab. 2.4.II: C_U = 0.7, 1, 1.5, 2.
    for (class, cu) in [
        (UseClass::I, 0.7),
        (UseClass::II, 1.0),
        (UseClass::III, 1.5),
        (UseClass::IV, 2.0),
    ] {
        assert_eq!(class.cu(), cu);
        assert_eq!(hazard::reference_period(100.0, class), 100.0 * cu);
    }
    assert_eq!(hazard::reference_period(50.0, UseClass::I), 35.0);
    assert_eq!(hazard::reference_period(10.0, UseClass::II), 35.0);
    assert_eq!(hazard::reference_period(10.0, UseClass::IV), 35.0);
    // Tab. 3.2.I: P_VR; T_R = -V_R / ln(1 - P_VR) (NTC 2008 Allegato A).
    for (state, p) in [
        (LimitState::SLO, 0.81),
        (LimitState::SLD, 0.63),
        (LimitState::SLV, 0.10),
        (LimitState::SLC, 0.05),
    ] {
        assert_eq!(state.p_vr(), p);
    }
    // V_N = 50, class II, SLV: T_R = 50 / -ln(0.9) = 50 / 0.1053605... = 474.56 years, the
    // 475 years of the grid's column; SLO, SLD, SLC give its 30, 50 and 975 years columns.
    let vr = hazard::reference_period(50.0, UseClass::II);
    let tr = |s| hazard::return_period(vr, s);
    close(
        tr(LimitState::SLV),
        50.0 / 0.9f64.recip().ln(),
        1e-15,
        "SLV",
    );
    for (state, years) in [
        (LimitState::SLV, 474.56),
        (LimitState::SLO, 30.1),
        (LimitState::SLD, 50.3),
        (LimitState::SLC, 974.8),
    ] {
        assert!((tr(state) - years).abs() < 0.05, "{state:?}: {}", tr(state));
    }
    // The probability of exceedance in V_R of an event of return period T_R is
    // 1 - exp(-V_R / T_R) (Poisson): it gives back P_VR.
    for s in LimitState::ALL {
        close(1.0 - (-vr / tr(s)).exp(), s.p_vr(), 1e-12, s.as_str());
    }
}

#[test]
fn at_a_node_the_grid_gives_the_nodes_values() {
    let grid = test_grid(varied);
    for id in [100, 101, 111, 112] {
        let n = grid.node(id).expect("node").clone();
        for (k, &t) in RETURN_PERIODS.iter().enumerate() {
            let at = grid.at(n.latitude, n.longitude, t).expect("inside");
            assert_eq!(at.params, n.values[k], "node {id}, T_R = {t}");
        }
    }
}

#[test]
fn at_a_tabulated_period_the_grid_gives_the_inverse_distance_mean_of_that_column() {
    let grid = test_grid(varied);
    // A point inside the cell of north-west node 111 (nodes 111, 112, 122, 121).
    let (lat, lon) = (42.03, 13.115);
    let cell = grid.cell(lat, lon).expect("inside");
    assert_eq!(cell.map(|n| n.id), [111, 112, 122, 121]);
    for (k, &t) in RETURN_PERIODS.iter().enumerate() {
        let at = grid.at(lat, lon, t).expect("inside");
        assert_eq!(at.periods, [t, t]);
        let expected = eq1(&cell, lat, lon, k);
        close(at.params.ag, expected.ag, 1e-13, "ag");
        close(at.params.f0, expected.f0, 1e-13, "F0");
        close(at.params.tc_star, expected.tc_star, 1e-13, "Tc*");
        // A weighted mean lies between the least and the greatest value.
        let ags: Vec<f64> = cell.iter().map(|n| n.values[k].ag).collect();
        let (lo, hi) = ags
            .iter()
            .fold((f64::MAX, f64::MIN), |(a, b), &x| (a.min(x), b.max(x)));
        assert!(lo <= at.params.ag && at.params.ag <= hi);
    }
    // The reported distances are those of the cell's nodes.
    let at = grid.at(lat, lon, 475.0).expect("inside");
    for (n, cn) in cell.iter().zip(at.nodes) {
        assert_eq!(cn.id, n.id);
        close(
            cn.distance,
            arc(lat, lon, n.latitude, n.longitude),
            1e-9,
            "distance",
        );
    }
}

#[test]
fn between_tabulated_periods_the_grid_interpolates_in_logarithms() {
    let grid = test_grid(varied);
    let (lat, lon) = (42.03, 13.115);
    let cell = grid.cell(lat, lon).expect("inside");
    for t in [35.0, 60.0, 100.0, 332.0, 474.56, 712.0, 1898.0] {
        let k = RETURN_PERIODS.iter().position(|&x| x > t).expect("bracket");
        let (t1, t2) = (RETURN_PERIODS[k - 1], RETURN_PERIODS[k]);
        let (p1, p2) = (eq1(&cell, lat, lon, k - 1), eq1(&cell, lat, lon, k));
        let at = grid.at(lat, lon, t).expect("inside");
        assert_eq!(at.periods, [t1, t2]);
        close(at.params.ag, eq2(p1.ag, p2.ag, t1, t2, t), 1e-12, "ag");
        close(at.params.f0, eq2(p1.f0, p2.f0, t1, t2, t), 1e-12, "F0");
        close(
            at.params.tc_star,
            eq2(p1.tc_star, p2.tc_star, t1, t2, t),
            1e-12,
            "Tc*",
        );
    }
    // At the geometric mean of two tabulated periods, eq. 2 is the geometric mean of the
    // two values.
    let t = (201.0f64 * 475.0).sqrt();
    let (p1, p2) = (eq1(&cell, lat, lon, 5), eq1(&cell, lat, lon, 6));
    close(
        grid.at(lat, lon, t).expect("inside").params.ag,
        (p1.ag * p2.ag).sqrt(),
        1e-12,
        "geometric mean",
    );
}

#[test]
fn a_uniform_power_law_hazard_is_reproduced_exactly() {
    // Every node with ag = a T^b, F0 and Tc* constant: eq. 1 of equal values is that value,
    // and eq. 2 (linear in log p against log T) is exact for a power law, at any period.
    let (a, b) = (0.004, 0.42);
    let grid = test_grid(|_, k| Params {
        ag: a * RETURN_PERIODS[k].powf(b),
        f0: 2.47,
        tc_star: 0.31,
    });
    for (lat, lon) in [(42.03, 13.115), (42.07, 13.05), (42.02, 13.2)] {
        for t in [30.0, 44.0, 474.56, 1000.0, 2475.0] {
            let p = grid.at(lat, lon, t).expect("inside").params;
            close(p.ag, a * t.powf(b), 1e-12, "ag = a T^b");
            close(p.f0, 2.47, 1e-14, "F0");
            close(p.tc_star, 0.31, 1e-14, "Tc*");
        }
    }
}

#[test]
fn a_point_outside_the_grid_or_its_periods_is_refused() {
    let grid = test_grid(varied);
    for (lat, lon) in [
        (42.2, 13.1),
        (42.05, 12.9),
        (41.9, 13.1),
        (42.05, 13.4),
        (f64::NAN, 13.1),
    ] {
        match grid.at(lat, lon, 475.0) {
            Err(HazardError::OutsideGrid {
                latitude,
                longitude,
            }) => {
                assert!(latitude.is_nan() || latitude == lat);
                assert_eq!(longitude, lon);
                let text = HazardError::OutsideGrid {
                    latitude,
                    longitude,
                }
                .to_string();
                assert!(
                    text.contains(&format!("latitude {lat}"))
                        && text.contains(&format!("longitude {lon}")),
                    "{text}"
                );
            }
            other => panic!("({lat}, {lon}): {other:?}"),
        }
    }
    // Return periods beyond the table are not extrapolated.
    for t in [29.0, 21.1, 2500.0, 3899.0] {
        assert!(
            matches!(
                grid.at(42.03, 13.115, t),
                Err(HazardError::ReturnPeriod { .. })
            ),
            "T_R = {t}"
        );
    }
    // A site whose design gives such a period says where it came from: V_N = 100, class IV,
    // SLC: V_R = 200, T_R = 200 / -ln(0.95) = 3899 years.
    let e = hazard::site_hazard(&grid, 42.03, 13.115, 100.0, UseClass::IV, LimitState::SLC)
        .expect_err("beyond 2475 years");
    let text = e.to_string();
    assert!(
        text.contains("3899.1 years") && text.contains("V_R = 200 years, SLC"),
        "{text}"
    );
}

/// A `[site]` table on soil B, read.
fn site(text: &str) -> Result<voussoir::spectrum::Site, SceneError> {
    crate::assess::site(&format!("soil = \"B\"\n{text}"))
}

#[test]
fn site_keys_of_the_coordinates_are_checked_before_any_grid_is_read() {
    for (text, key, words) in [
        (
            "latitude = 42.35\nlongitude = 13.4\nag = 0.2",
            "site.ag",
            "not both",
        ),
        (
            "latitude = 42.35\nlongitude = 13.4\nTc_star = 0.3",
            "site.Tc_star",
            "not both",
        ),
        ("latitude = 42.35", "site.longitude", "longitude"),
        ("longitude = 13.4", "site.latitude", "latitude"),
        (
            "latitude = 95\nlongitude = 13.4",
            "site.latitude",
            "from -90 to 90",
        ),
        (
            "latitude = 42.35\nlongitude = 13.4\nuse_class = \"V\"",
            "site.use_class",
            "I, II, III, IV",
        ),
        (
            "latitude = 42.35\nlongitude = 13.4\nlimit_state = \"SLU\"",
            "site.limit_state",
            "SLO, SLD, SLV, SLC",
        ),
        (
            "latitude = 42.35\nlongitude = 13.4\nnominal_life = 0",
            "site.nominal_life",
            "nominal life",
        ),
        (
            "ag = 0.2\nF0 = 2.4\nTc_star = 0.3\nlimit_state = \"SLV\"",
            "site.limit_state",
            "only with the site's latitude and longitude",
        ),
        (
            "ag = 0.2\nF0 = 2.4\nTc_star = 0.3\nnominal_life = 50",
            "site.nominal_life",
            "only with the site's latitude and longitude",
        ),
    ] {
        let e = site(text).expect_err(text);
        assert_eq!(e.key(), Some(key), "{text}: {e}");
        assert!(e.to_string().contains(words), "{text}: {e}");
    }
    // Without coordinates the site reads as before: no hazard, the values given.
    let s = site("ag = 0.2\nF0 = 2.4\nTc_star = 0.3").expect("site");
    assert_eq!(
        (s.ag, s.f0, s.tc_star, s.hazard.is_none()),
        (0.2, 2.4, 0.3, true)
    );
}

#[test]
fn a_build_without_the_grid_refuses_coordinates() {
    let r = site("latitude = 42.35\nlongitude = 13.4");
    if Grid::is_bundled() {
        assert!(r.expect("inside the grid").hazard.is_some());
    } else {
        let e = r.expect_err("no grid");
        assert_eq!(e.key(), Some("site.latitude"));
        assert!(
            matches!(
                e,
                SceneError::Hazard {
                    source: HazardError::NotBundled,
                    ..
                }
            ),
            "{e}"
        );
    }
}

/// The national grid (ignored where this build has none).
fn national() -> &'static Grid {
    Grid::bundled().expect(NO_GRID)
}

#[test]
#[cfg_attr(
    not(hazard_grid),
    ignore = "the NTC 2008 grid is not bundled in this build"
)]
fn the_national_grid_is_the_annex_table() {
    let g = national();
    // Allegato B, Tabella 1: 10,751 nodes, the first of the table ID 13111.
    assert_eq!(g.nodes().len(), 10_751);
    assert!(g.node(13111).is_some());
    // Every node is where the numbering puts it: its east neighbour about 5.5 km east, its
    // south neighbour about 5.5 km south.
    for n in g.nodes() {
        for (id, what) in [(n.id + 1, "east"), (n.id + NATIONAL_ROW, "south")] {
            if let Some(m) = g.node(id) {
                let d = arc(n.latitude, n.longitude, m.latitude, m.longitude);
                assert!(
                    (5400.0..5700.0).contains(&d),
                    "{} to {id} ({what}): {d} m",
                    n.id
                );
            }
        }
    }
    // ag grows with the return period at every node (a hazard curve); F0 is at least 2.2, as
    // the code's spectra take it.
    for n in g.nodes() {
        for k in 1..9 {
            assert!(n.values[k].ag > n.values[k - 1].ag, "node {}", n.id);
        }
        for p in n.values {
            assert!(
                (2.2..3.5).contains(&p.f0) && (0.05..0.65).contains(&p.tc_star),
                "node {}",
                n.id
            );
        }
    }
}

/// Regione Toscana, Direzione Generale Politiche Territoriali ed Ambientali, Settore Servizio
/// Sismico Regionale: "Norme Tecniche per le Costruzioni (D.M. 14 Gennaio 2008) All. B -
/// Distribuzione dei punti della griglia per la provincia di Massa Carrara" (a map of the
/// grid's nodes, each with its ag at T_R = 475 years in g/10 to three decimals; text copy at
/// docslib.org/doc/7676363). Its text lists each row of the map as the row's node ids and
/// the values printed beside them; each row's values are checked here as a set against the
/// grid's values of those nodes, rounded as the map rounds them.
const TOSCANA_ROWS: &[(std::ops::RangeInclusive<u32>, &[f64])] = &[
    (16708..=16712, &[1.909, 2.009, 1.976, 2.023, 2.026]),
    (16929..=16934, &[1.997, 2.024, 2.03, 2.036, 1.948, 2.004]),
    (
        17150..=17158,
        &[1.976, 2.013, 2.04, 2.035, 2.03, 1.936, 1.998, 1.688, 1.83],
    ),
    (
        17372..=17381,
        &[
            2.028, 1.998, 2.042, 2.025, 2.041, 1.986, 1.798, 1.914, 1.657, 1.51,
        ],
    ),
    (
        17595..=17603,
        &[
            2.038, 2.046, 2.017, 2.041, 1.969, 1.763, 1.886, 1.481, 1.624,
        ],
    ),
    (
        17818..=17825,
        &[2.038, 2.048, 2.007, 1.853, 1.95, 1.579, 1.723, 1.443],
    ),
    (
        18040..=18047,
        &[2.032, 1.927, 1.995, 1.818, 1.541, 1.682, 1.313, 1.405],
    ),
];

#[test]
#[cfg_attr(
    not(hazard_grid),
    ignore = "the NTC 2008 grid is not bundled in this build"
)]
fn the_national_grid_matches_a_published_copy_of_its_values() {
    let g = national();
    let mut checked = 0;
    for (ids, published) in TOSCANA_ROWS {
        // ag (g) at 475 years, in g/10 as the annex and the map print it.
        let mut ours: Vec<f64> = ids
            .clone()
            .map(|id| 10.0 * g.node(id).expect("node of the map").values[6].ag)
            .collect();
        let mut theirs = published.to_vec();
        assert_eq!(ours.len(), theirs.len(), "{ids:?}");
        ours.sort_by(f64::total_cmp);
        theirs.sort_by(f64::total_cmp);
        for (o, t) in ours.iter().zip(&theirs) {
            // Three decimals, rounded half up by the map (1.9975 printed 1.998).
            assert!((o - t).abs() <= 0.0005 + 1e-9, "{ids:?}: {o} against {t}");
            checked += 1;
        }
    }
    assert_eq!(checked, 55);
}

#[test]
#[cfg_attr(
    not(hazard_grid),
    ignore = "the NTC 2008 grid is not bundled in this build"
)]
fn the_national_grid_interpolates_a_site_by_the_annex() {
    let g = national();
    // L'Aquila (Piazza del Duomo), Rome (the Pantheon), Palermo (decimal degrees).
    for (lat, lon) in [(42.3498, 13.3995), (41.8986, 12.4768), (38.1157, 13.3615)] {
        let h = hazard::site_hazard(g, lat, lon, 50.0, UseClass::II, LimitState::SLV)
            .expect("inside the grid");
        // The cell's nodes surround the site, each within a cell's diagonal.
        for n in &h.nodes {
            assert!(n.distance < 8000.0, "{n:?}");
        }
        let lats: Vec<f64> = h.nodes.iter().map(|n| n.latitude).collect();
        assert!(lats.iter().any(|&l| l >= lat) && lats.iter().any(|&l| l <= lat));
        // Eq. 1 and eq. 2 worked out here from the nodes' tabulated values.
        let nodes: Vec<&Node> = h
            .nodes
            .iter()
            .map(|n| g.node(n.id).expect("node"))
            .collect();
        let (p1, p2) = (eq1(&nodes, lat, lon, 5), eq1(&nodes, lat, lon, 6));
        let t = 50.0 / 0.9f64.recip().ln();
        assert_eq!(h.return_periods, [201.0, 475.0]);
        close(h.t_r, t, 1e-15, "T_R");
        close(h.params.ag, eq2(p1.ag, p2.ag, 201.0, 475.0, t), 1e-12, "ag");
        close(h.params.f0, eq2(p1.f0, p2.f0, 201.0, 475.0, t), 1e-12, "F0");
        close(
            h.params.tc_star,
            eq2(p1.tc_star, p2.tc_star, 201.0, 475.0, t),
            1e-12,
            "Tc*",
        );
    }
}

#[test]
#[cfg_attr(
    not(hazard_grid),
    ignore = "the NTC 2008 grid is not bundled in this build"
)]
fn islands_of_tabella_2_and_points_abroad_are_refused() {
    // Cagliari (Sardinia), Portoferraio (Elba), Lampedusa, the sea off Genoa, Vienna.
    for (lat, lon) in [
        (39.2238, 9.1217),
        (42.8129, 10.3143),
        (35.5078, 12.6081),
        (43.9, 8.9),
        (48.2082, 16.3738),
    ] {
        let e = site(&format!("latitude = {lat}\nlongitude = {lon}")).expect_err("outside");
        assert_eq!(e.key(), Some("site.latitude"));
        let text = e.to_string();
        assert!(
            text.contains(&format!("latitude {lat}, longitude {lon}"))
                && text.contains("Tabella 2"),
            "{text}"
        );
    }
}

/// `assess --json` of the bundled portal with these `--site` settings.
fn assess_json(site: &[&str]) -> serde_json::Value {
    let mut cmd = voussoir();
    cmd.arg("assess").arg(data("portal.toml")).arg("--json");
    for s in site {
        cmd.args(["--site", s]);
    }
    let out = cmd.output().expect("runs");
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_slice(&out.stdout).expect("JSON")
}

#[test]
#[cfg_attr(
    not(hazard_grid),
    ignore = "the NTC 2008 grid is not bundled in this build"
)]
fn assess_at_coordinates_is_assess_at_the_grids_values() {
    let by_place = assess_json(&["latitude=42.3498", "longitude=13.3995", "soil=B"]);
    let site = &by_place["site"];
    let h = &site["hazard"];
    // The fields added: the coordinates and design as read, and how the grid gave the values.
    assert_eq!(site["latitude"], 42.3498);
    assert_eq!(site["longitude"], 13.3995);
    assert_eq!(site["nominal_life"], 50.0);
    assert_eq!(site["use_class"], "II");
    assert_eq!(site["limit_state"], "SLV");
    assert_eq!(h["C_U"], 1.0);
    assert_eq!(h["V_R"], 50.0);
    assert_eq!(h["P_VR"], 0.1);
    close(
        h["T_R"].as_f64().expect("T_R"),
        50.0 / 0.9f64.recip().ln(),
        1e-15,
        "T_R",
    );
    assert_eq!(h["nodes"].as_array().expect("nodes").len(), 4);
    for k in ["ag", "F0", "Tc_star"] {
        assert_eq!(site[k], h[k], "{k}");
    }
    // The same assessment as with those values given.
    let ag = site["ag"].as_f64().expect("ag");
    let f0 = site["F0"].as_f64().expect("F0");
    let tc = site["Tc_star"].as_f64().expect("Tc*");
    let given = assess_json(&[
        &format!("ag={ag}"),
        &format!("F0={f0}"),
        &format!("Tc_star={tc}"),
        "soil=B",
    ]);
    for k in [
        "spectrum",
        "linear_check",
        "nonlinear_check",
        "passes",
        "ag_max",
        "verdict",
    ] {
        assert_eq!(by_place[k], given[k], "{k}");
    }
    // A site given by its values has none of the added fields.
    for k in [
        "latitude",
        "longitude",
        "nominal_life",
        "use_class",
        "limit_state",
        "hazard",
    ] {
        assert!(given["site"].get(k).is_none(), "{k}");
    }
    // SLC at the same place: a longer return period, a larger ag.
    let slc = assess_json(&[
        "latitude=42.3498",
        "longitude=13.3995",
        "soil=B",
        "limit_state=SLC",
    ]);
    assert_eq!(
        slc["site"]["hazard"]["return_periods"],
        serde_json::json!([475.0, 975.0])
    );
    assert!(slc["site"]["ag"].as_f64().expect("ag") > ag);
}
