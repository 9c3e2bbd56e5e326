//! exploration
use crate::common::*;
use voussoir::model::Model;
use voussoir::statics::{self, NonAssociativeSettings, StaticSettings};

fn pair(b: f64, h: f64, mu: f64) -> Model {
    let assembly = voussoir::assembly::Assembly {
        blocks: vec![rect(-b, 0.0, b, h), rect(0.0, 0.0, b, h)],
        joints: vec![
            hjoint(0.0, -b, 0.0, None, Some(0), mu),
            hjoint(b, 0.0, 0.0, None, Some(1), mu),
            voussoir::assembly::Joint {
                p1: voussoir::geometry::Vec2::new(0.0, 0.0),
                p2: voussoir::geometry::Vec2::new(0.0, h),
                from: Some(0),
                to: Some(1),
                friction: mu,
                kind: voussoir::assembly::JointKind::Other,
            },
        ],
    };
    Model::self_weight(assembly)
}

#[test]
fn explore() {
    let s = StaticSettings::default();
    for (name, m) in [
        ("block", Model::self_weight(single_block(1.0, 1.0, 0.5))),
        ("pair", pair(0.5, 2.0, 0.6)),
    ] {
        let a = statics::analyse(&m, &s).unwrap();
        let na = statics::analyse_non_associative(&m, &s, &a, &NonAssociativeSettings::default()).unwrap();
        println!("{name}: assoc {:?} sliding {:?} slipping {:?}", a.lambda, a.sliding, a.friction(&m.assembly).slipping);
        println!("  na {:?} conv {} it {} sliding {:?} starts {:?}", na.lambda, na.converged, na.iterations, na.sliding, na.starts);
    }
}

fn polys_scene(blocks: &[[f64; 4]], mu: f64) -> voussoir::scene::Scene {
    let polys: Vec<String> = blocks
        .iter()
        .map(|[x0, y0, x1, y1]| format!("[[{x0}, {y0}], [{x1}, {y0}], [{x1}, {y1}], [{x0}, {y1}]]"))
        .collect();
    scene(&format!("[blocks]\npolygons = [{}]\n[material]\nfriction = {mu}\n", polys.join(", ")))
}

fn wall_blocks() -> Vec<[f64; 4]> {
    let h = 0.4;
    let mut blocks = Vec::new();
    for c in 0..3 {
        let y0 = c as f64 * h;
        let xs: &[f64] = if c % 2 == 0 { &[0.0, 0.6, 1.2] } else { &[0.0, 0.3, 0.9, 1.2] };
        for w in xs.windows(2) {
            blocks.push([w[0], y0, w[1], y0 + h]);
        }
    }
    blocks
}

fn lintel_blocks() -> Vec<[f64; 4]> {
    vec![[0.0, 0.0, 0.4, 1.6], [1.6, 0.0, 2.0, 1.6], [0.0, 1.6, 2.0, 2.0]]
}

#[test]
fn explore_dem() {
    use voussoir::analysis;
    for mu in [0.4, 0.55, 0.7] {
        let cases = vec![
            ("wall", polys_scene(&wall_blocks(), mu)),
            ("lintel", polys_scene(&lintel_blocks(), mu)),
            ("buttress", voussoir::scene::Scene::from_file(&data("blocks_stepped_buttresses.toml")).unwrap().with_overrides(&[format!("material.friction={mu}")]).unwrap()),
        ];
        for (name, s) in cases {
            let t = std::time::Instant::now();
            let a = analysis::analyse(&s, &analysis::Options::default()).unwrap();
            let dt = t.elapsed().as_secs_f64();
            let na = a.non_associative.as_ref();
            println!("{name} mu {mu}: assoc {:?} exact {} na {:?} it {:?} starts {:?} t {dt:.3}", a.lower.lambda, a.friction().exact, na.and_then(|n| n.lambda), na.map(|n| n.iterations), na.map(|n| n.starts.iter().map(|s| (s.start.as_str(), s.lambda, s.iterations, s.converged)).collect::<Vec<_>>()));
            if std::env::var("DEM").is_ok() {
                let d = analysis::dem(&s, &analysis::DemOptions::default(), &mut |_| {}).unwrap();
                println!("   dem {:?} [{:?}, {:?}]", d.result.lambda_dem, d.result.lambda_stands, d.result.lambda_collapses);
            }
        }
    }
}
