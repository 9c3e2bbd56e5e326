//! Sweeps give the same numbers as single analyses, in a deterministic order.

use voussoir::lp::{self, StaticSettings};
use voussoir::scene::Scene;
use voussoir::sweep;

const BASE: &str = "[arch]\nshape = \"pointed\"\nradius = 2.0\neccentricity = 0.0\nthickness = 0.3\nvoussoirs = 16\n";

#[test]
fn sweep_rows_equal_single_analyses() {
    let base = Scene::from_toml_str(BASE, "t").expect("valid");
    let variations = vec![
        sweep::parse_variation("e/R=0,0.1,0.3").expect("valid"),
        sweep::parse_variation("arch.voussoirs=8,16").expect("valid"),
        sweep::parse_variation("t/R=0.1:0.2:0.05").expect("valid"),
    ];
    let cases = sweep::cases(&base, &variations);
    assert_eq!(cases.len(), 3 * 2 * 3);
    let settings = StaticSettings::default();
    let rows = sweep::run(&cases, |v, s| sweep::static_case(v, s, &settings), &|| {});
    for (k, row) in rows.iter().enumerate() {
        // The first key changes slowest.
        let (i, j, l) = (k / 6, (k / 3) % 2, k % 3);
        assert_eq!(row.values[0], variations[0].values[i]);
        assert_eq!(row.values[1], variations[1].values[j]);
        assert_eq!(row.values[2], variations[2].values[l]);
        // The same scene through --set-like overrides and a single analysis.
        let e = [0.0, 0.1, 0.3][i] * 2.0;
        let n = [8, 16][j];
        let t = [0.1, 0.15, 0.2][l] * 2.0;
        let scene = base
            .with_override(&format!("arch.eccentricity={e}"))
            .and_then(|s| s.with_override(&format!("arch.voussoirs={n}")))
            .and_then(|s| s.with_override(&format!("arch.thickness={t}")))
            .expect("valid");
        let r = lp::analyse(
            &voussoir::scene::build(&scene).expect("valid model"),
            &settings,
        )
        .expect("solves");
        assert_eq!(row.status, r.status.as_str());
        match (row.lambda_lower, r.lambda) {
            (Some(a), Some(b)) => assert!((a - b).abs() <= 1e-12 * b.max(1.0), "{a} vs {b}"),
            (None, None) => {}
            other => panic!("row {k}: {other:?}"),
        }
        let ratios: std::collections::HashMap<_, _> = row.ratios.iter().copied().collect();
        assert!((ratios["t/R"] - t / 2.0).abs() < 1e-12);
        assert!((ratios["e/R"] - e / 2.0).abs() < 1e-12);
    }
}

#[test]
fn invalid_cases_stay_in_the_sweep_with_status_error() {
    let base = Scene::from_toml_str(BASE, "t").expect("valid");
    let variations = vec![sweep::parse_variation("arch.eccentricity=0.5,2.5").expect("valid")];
    let cases = sweep::cases(&base, &variations);
    let settings = StaticSettings::default();
    let rows = sweep::run(&cases, |v, s| sweep::static_case(v, s, &settings), &|| {});
    assert_eq!(rows[0].status, "collapse");
    assert_eq!(rows[1].status, "error");
    assert!(rows[1]
        .error
        .as_deref()
        .unwrap_or("")
        .contains("arch.eccentricity"));
    let mut csv = Vec::new();
    sweep::write_csv(&mut csv, &variations, &rows).expect("writes");
    let text = String::from_utf8(csv).expect("utf8");
    assert_eq!(text.lines().count(), 3);
    assert!(text.lines().next().unwrap_or("").starts_with(
        "arch.eccentricity,status,lambda_lower,lambda_upper,gap,hinges,solve_time_s,"
    ));
}

#[test]
fn ranges_include_their_end_and_reject_nonsense() {
    let v = sweep::parse_variation("t/R=0.1:0.3:0.05").expect("valid");
    let xs: Vec<f64> = v.values.iter().filter_map(|x| x.as_float()).collect();
    assert_eq!(xs, vec![0.1, 0.15, 0.2, 0.25, 0.3]);
    for bad in [
        "t/R=0.3:0.1:0.05",
        "t/R=0:1:0",
        "t/R=a:b:c",
        "t/R",
        "t/R=0:1",
    ] {
        assert!(sweep::parse_variation(bad).is_err(), "{bad}");
    }
}

#[test]
fn clashing_or_unknown_varied_keys_are_refused_before_solving() {
    let base = Scene::from_toml_str(BASE, "t").expect("valid");
    for bad in [
        vec!["arch.thickness=0.1", "t/R=0.2"],
        vec!["t/R=0.1", "t/R=0.2"],
        vec!["t/span=0.1", "t/R=0.2"],
        vec!["e/span=0.1", "arch.radius=2"],
        vec!["arch.colour=1,2"],
        vec!["T/R=1,2"],
        vec!["nosuch.key=1"],
    ] {
        let vars: Vec<_> = bad
            .iter()
            .map(|v| sweep::parse_variation(v).expect("parses"))
            .collect();
        let e = sweep::check_variations(&base, &vars).expect_err(&bad.join(" "));
        assert!(e.to_string().starts_with("--vary "), "{e}");
    }
    // Out-of-range values are the cases' own business.
    let vars = vec![sweep::parse_variation("arch.thickness=0.1,5").expect("parses")];
    assert!(sweep::check_variations(&base, &vars).is_ok());
}
