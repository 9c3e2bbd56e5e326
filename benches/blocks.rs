//! Timings of the user's own blocks (`[blocks]`): joint detection on 10,000 blocks (a
//! running-bond wall and a 10,000-voussoir arch), and the analysis of a 200-block user chain
//! against the parametric chain of the same blocks. Prints a table; run with
//! `cargo bench --bench blocks`. Targets: detection of 10,000 blocks under 1 s; the user chain
//! within 2x of the parametric one.

mod common;
use common::time;
use voussoir::analysis::{self, Options};
use voussoir::blocks::{self, Polygons, Units};
use voussoir::scene::Scene;

fn scene(text: &str) -> Scene {
    match Scene::from_toml_str(text, "bench") {
        Ok(s) => s,
        Err(e) => panic!("bench scene: {e}"),
    }
}

fn polygons_of(s: &Scene) -> Vec<Vec<[f64; 2]>> {
    let m = voussoir::scene::build(s).expect("model");
    m.assembly
        .blocks
        .iter()
        .map(|b| b.polygon.iter().map(|p| [p.x, p.y]).collect())
        .collect()
}

fn main() {
    println!(
        "{:<44} {:>7} {:>7} {:>10} {:>10}",
        "joint detection", "blocks", "joints", "clean ms", "detect ms"
    );
    let arch = scene("[arch]\nshape='circular'\nradius=10.0\nthickness=1.0\nvoussoirs=10000\n");
    let cases = [
        (
            "running-bond wall, 100 courses",
            common::running_bond_wall(100, 100),
        ),
        ("semicircle, 10,000 voussoirs", polygons_of(&arch)),
    ];
    for (label, raw) in cases {
        let (tc, polys) = time(2, || blocks::from_vertices(raw.clone(), Units::Metres));
        let polys: Polygons = polys.expect("clean polygons");
        let (td, d) = time(2, || {
            blocks::detect(&polys, Some(0.0), 1e-6, 20000.0, f64::INFINITY)
        });
        let d = d.expect("joints found");
        println!(
            "{label:<44} {:>7} {:>7} {:>10.1} {:>10.1}",
            polys.len(),
            d.assembly.joints.len(),
            1e3 * tc,
            1e3 * td
        );
    }

    println!();
    println!(
        "{:<44} {:>7} {:>12} {:>10} {:>10}",
        "analysis of a 200-block chain", "joints", "lambda", "read ms", "analyse ms"
    );
    let text = "[arch]\nshape='circular'\nradius=1.0\nthickness=0.15\nvoussoirs=200\n";
    let parametric = scene(text);
    let polys: Vec<String> = polygons_of(&parametric)
        .iter()
        .map(|p| {
            let v: Vec<String> = p
                .iter()
                .map(|q| format!("[{:e}, {:e}]", q[0], q[1]))
                .collect();
            format!("[{}]", v.join(", "))
        })
        .collect();
    let user_text = format!(
        "[blocks]\nground_y = 0.0\npolygons = [{}]\n",
        polys.join(", ")
    );
    let options = Options::default();
    let mut rows = Vec::new();
    for (label, text) in [
        ("parametric semicircle n = 200", text.to_string()),
        ("the same as user blocks", user_text),
    ] {
        let (tr, s) = time(3, || scene(&text));
        let (ta, a) = time(5, || analysis::analyse(&s, &options));
        let a = a.expect("analysis");
        println!(
            "{label:<44} {:>7} {:>12.9} {:>10.2} {:>10.2}",
            a.model.assembly.joints.len(),
            a.lower.lambda.unwrap_or(f64::NAN),
            1e3 * tr,
            1e3 * ta
        );
        rows.push(ta);
    }
    println!("user / parametric analysis time: {:.2}", rows[1] / rows[0]);
}
