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
