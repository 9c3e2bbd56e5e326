//! Sweeps give the same numbers as single analyses, in a deterministic order.

use voussoir::scene::Scene;
use voussoir::statics::{self, StaticSettings};
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
        let r = statics::analyse(
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

#[test]
fn values_of_the_wrong_type_are_refused_before_solving() {
    let base = Scene::from_toml_str(BASE, "t").expect("valid");
    for (bad, key, value) in [
        ("t/R=0.1,abc", "t/R", "abc"),
        ("e/span=0.1,0.2,x", "e/span", "x"),
        ("arch.thickness=0.1,0.2,abc", "arch.thickness", "abc"),
        ("arch.voussoirs=8,8.5", "arch.voussoirs", "8.5"),
    ] {
        let vars = vec![sweep::parse_variation(bad).expect("parses")];
        let e = sweep::check_variations(&base, &vars).expect_err(bad);
        let msg = e.to_string();
        assert!(msg.starts_with(&format!("--vary {key}=")), "{msg}");
        assert!(msg.contains(value), "{msg}");
    }
}

#[test]
fn the_chart_axis_must_vary() {
    let base = Scene::from_toml_str(BASE, "t").expect("valid");
    let vars = vec![
        sweep::parse_variation("t/R=0.1,0.2").expect("parses"),
        sweep::parse_variation("arch.voussoirs=8,16").expect("parses"),
    ];
    let plan = sweep::Sweep::new(&base, vars).expect("valid");
    // Varied keys, and ratios the varied keys change.
    assert!(sweep::check_chart(&plan, "t/R", Some("arch.voussoirs")).is_ok());
    assert!(sweep::check_chart(&plan, "arch.voussoirs", None).is_ok());
    assert!(sweep::check_chart(&plan, "t/span", None).is_ok());
    // e/R is 0 in every case; h/R has no piers; nonsense is nothing.
    for x in ["e/R", "h/R", "rise/span", "arch.thickness", "nonsense"] {
        let e = sweep::check_chart(&plan, x, None).expect_err(x);
        assert!(e.to_string().starts_with(&format!("--x {x}: ")), "{e}");
    }
    let e = sweep::check_chart(&plan, "t/R", Some("t/R")).expect_err("series = x");
    assert!(e.to_string().starts_with("--series t/R: "), "{e}");
}

#[test]
fn chart_labels_are_words_with_units() {
    assert_eq!(
        voussoir::report::figures::key_label("arch.embrace_deg"),
        "embrace (deg)"
    );
    assert_eq!(
        voussoir::report::figures::key_label("arch.thickness"),
        "thickness t (m)"
    );
    assert_eq!(voussoir::report::figures::key_label("t/R"), "t/R");
    assert_eq!(
        voussoir::report::figures::key_label("dem.something"),
        "dem.something"
    );
    let base = Scene::from_toml_str(BASE, "t").expect("valid");
    let vars = vec![
        sweep::parse_variation("arch.thickness=0.2,0.3").expect("parses"),
        sweep::parse_variation("arch.voussoirs=8,16").expect("parses"),
    ];
    let cases = sweep::cases(&base, &vars);
    let settings = StaticSettings::default();
    let rows = sweep::run(&cases, |v, s| sweep::static_case(v, s, &settings), &|| {});
    let chart =
        voussoir::report::figures::chart(&vars, &rows, "arch.thickness", None, "t").expect("chart");
    assert_eq!(chart.x_label, "thickness t (m)");
    assert_eq!(chart.legend_title.as_deref(), Some("voussoirs n"));
}

#[test]
fn csv_without_timings_leaves_out_the_wall_times_only() {
    let base = Scene::from_toml_str(BASE, "t").expect("valid");
    let vars = vec![sweep::parse_variation("t/R=0.1,0.2").expect("parses")];
    let cases = sweep::cases(&base, &vars);
    let settings = StaticSettings::default();
    let mut rows = sweep::run(&cases, |v, s| sweep::static_case(v, s, &settings), &|| {});
    for r in &mut rows {
        r.extra.push(("lambda_dem", Some(0.1)));
        r.extra.push(("dem_time_s", Some(1.5)));
    }
    let mut with = Vec::new();
    sweep::write_csv(&mut with, &vars, &rows).expect("writes");
    let mut without = Vec::new();
    sweep::write_csv_with(&mut without, &vars, &rows, false).expect("writes");
    let (with, without) = (
        String::from_utf8(with).expect("utf8"),
        String::from_utf8(without).expect("utf8"),
    );
    for (a, b) in with.lines().zip(without.lines()) {
        let a: Vec<&str> = a.split(',').collect();
        let b: Vec<&str> = b.split(',').collect();
        // The same fields, less solve_time_s (column 6) and dem_time_s (column 8).
        let kept: Vec<&str> = a
            .iter()
            .enumerate()
            .filter(|(i, _)| *i != 6 && *i != 8)
            .map(|(_, f)| *f)
            .collect();
        assert_eq!(kept, b);
    }
    assert!(with
        .lines()
        .next()
        .unwrap_or("")
        .contains(",solve_time_s,lambda_dem,dem_time_s,"));
    assert!(!without.contains("_time_s"));
}

#[test]
fn a_sweep_of_too_many_cases_is_refused_before_any_case_is_built() {
    let base = Scene::from_toml_str(BASE, "t").expect("valid");
    // Three lists of 2,000 values: 8e9 cases, refused at once (not allocated).
    let variations = vec![
        sweep::parse_variation("arch.thickness=0.1:0.2999:0.0001").expect("valid"),
        sweep::parse_variation("arch.radius=2:3.999:0.001").expect("valid"),
        sweep::parse_variation("material.unit_weight=1:2000:1").expect("valid"),
    ];
    assert!(variations.iter().all(|v| v.values.len() == 2000));
    let e = sweep::Sweep::new(&base, variations).expect_err("too many cases");
    let msg = e.to_string();
    assert!(
        msg.contains("arch.thickness, arch.radius, material.unit_weight")
            && msg.contains("2000 x 2000 x 2000 values make 8000000000 cases")
            && msg.contains(&format!("at most {}", sweep::MAX_CASES)),
        "{msg}"
    );
    // A product beyond any integer is refused as well.
    let big: Vec<sweep::Variation> = (0..8)
        .map(|i| sweep::Variation {
            key: format!("k{i}"),
            values: vec![toml::Value::Integer(1); 100_000],
        })
        .collect();
    let e = sweep::check_case_count(&big).expect_err("overflow");
    assert!(e.to_string().contains("1.0e40 cases"), "{e}");
    // A range of 2^70 values is refused, not wrapped to none.
    let e = sweep::parse_variation("arch.voussoirs=1:1180591620717411303424:1")
        .expect_err("too many values");
    assert!(e.to_string().contains("gives 1.2e21 values"), "{e}");
}

#[test]
fn swept_values_and_ratios_print_as_written() {
    let v = sweep::parse_variation("arch.radius=1.8:1.9:0.025").expect("valid");
    let texts: Vec<String> = v.values.iter().map(|x| x.to_string()).collect();
    assert_eq!(texts, ["1.8", "1.825", "1.85", "1.875", "1.9"]);
    let v = sweep::parse_variation("t/R=0.05:0.2:0.01").expect("valid");
    assert!(
        v.values.iter().all(|x| x.to_string().len() <= 4),
        "{:?}",
        v.values
    );
    // A ratio sets its scene key without noise: t/R = 0.1825 at R = 10 is t = 1.825.
    let base = Scene::from_toml_str(
        "[arch]\nshape = \"circular\"\nradius = 10.0\nthickness = 1.0\nvoussoirs = 16\n",
        "t",
    )
    .expect("valid");
    let s = sweep::apply(&base, &[("t/R", &toml::Value::Float(0.1825))]).expect("valid");
    assert_eq!(s.arch.as_ref().map(|a| a.thickness), Some(1.825));
    // The CSV: values as written, ratios tidy (a semicircle's rise/span is 0.5), results
    // with every digit.
    let plan = sweep::Sweep::new(
        &base,
        vec![sweep::parse_variation("arch.radius=1.8:1.9:0.025").expect("valid")],
    )
    .expect("valid");
    let rows = plan.run(&voussoir::analysis::Options::default(), false, &|| {});
    let mut buf = Vec::new();
    sweep::write_csv(&mut buf, plan.variations(), &rows).expect("csv");
    let csv = String::from_utf8(buf).expect("utf-8");
    assert!(csv.contains("\n1.825,"), "{csv}");
    let mut reader = csv::Reader::from_reader(csv.as_bytes());
    let header = reader.headers().expect("header").clone();
    let col = |name: &str| header.iter().position(|h| h == name).expect(name);
    for rec in reader.records() {
        let rec = rec.expect("row");
        assert_eq!(&rec[col("rise/span")], "0.5");
        // The keys and ratios derived from the inputs carry no round-off digits.
        for name in ["arch.radius", "t/R", "t/span"] {
            assert!(rec[col(name)].len() <= 14, "{name} = {}", &rec[col(name)]);
        }
        let lower: f64 = rec[col("lambda_lower")].parse().expect("number");
        let r = rows
            .iter()
            .find(|r| r.values[0].to_string() == rec[0])
            .expect("row");
        // Full precision: the CSV reads back as the very number.
        assert_eq!(Some(lower), r.lambda_lower);
    }
}

/// The CSV of `plan`'s rows solved on a pool of `threads` threads, without the wall times.
fn csv_on(threads: usize, plan: &sweep::Sweep, options: &voussoir::analysis::Options) -> String {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .expect("thread pool");
    pool.install(|| {
        let rows = plan.run(options, false, &|| {});
        let mut buf = Vec::new();
        sweep::write_csv_with(&mut buf, plan.variations(), &rows, false).expect("csv");
        String::from_utf8(buf).expect("utf-8")
    })
}

#[test]
fn rows_and_csv_bytes_do_not_depend_on_the_thread_count() {
    let base = Scene::from_toml_str(BASE, "t").expect("valid");
    // Invalid cases first (an eccentricity beyond the radius): the header's extra column
    // comes from the first row that has it. 3 x 61 x 4 = 732 cases: several blocks of rows
    // for the CSV's workers.
    let variations = vec![
        sweep::parse_variation("arch.eccentricity=2.5,0,0.4").expect("valid"),
        sweep::parse_variation("t/R=0.05:0.2:0.0025").expect("valid"),
        sweep::parse_variation("arch.voussoirs=6,8,12,16").expect("valid"),
    ];
    let plan = sweep::Sweep::new(&base, variations).expect("valid");
    assert_eq!(plan.len(), 3 * 61 * 4);
    let options = voussoir::analysis::Options {
        continuous: true,
        ..Default::default()
    };
    let one = csv_on(1, &plan, &options);
    for threads in [2, 7] {
        assert!(
            csv_on(threads, &plan, &options) == one,
            "{threads} threads: the CSV differs from one thread's"
        );
    }
    // Every record, in the order of the cases, with the fields of the header (the error
    // rows' continuous column empty).
    let mut reader = csv::Reader::from_reader(one.as_bytes());
    let header = reader.headers().expect("header").clone();
    let col = |name: &str| header.iter().position(|h| h == name).expect(name);
    let records: Vec<csv::StringRecord> =
        reader.records().collect::<Result<_, _>>().expect("records");
    assert_eq!(records.len(), plan.len());
    let mut errors = 0;
    for (k, rec) in records.iter().enumerate() {
        let (values, scene) = plan.case(k);
        for (i, v) in values.iter().enumerate() {
            assert_eq!(rec[i], v.to_string(), "row {k}");
        }
        assert_eq!(rec.len(), header.len(), "row {k}");
        if scene.is_err() {
            errors += 1;
            assert_eq!(&rec[col("status")], "error", "row {k}");
            assert_eq!(&rec[col("lambda_continuous")], "", "row {k}");
        } else {
            assert_ne!(
                &rec[col("status")],
                "error",
                "row {k}: {:?}",
                &rec[col("error")]
            );
        }
    }
    assert_eq!(errors, 61 * 4);
}
