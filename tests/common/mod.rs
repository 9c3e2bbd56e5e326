//! Scene builders shared by the integration tests.
#![allow(dead_code)]

use voussoir::assembly::{Assembly, Block, BlockKind, Joint, JointKind};
use voussoir::geometry::{polygon_area_centroid, Vec2};
use voussoir::model::Model;
use voussoir::scene::Scene;

pub fn circular(t: f64, n: usize, embrace_deg: f64, vs: &str) -> Scene {
    Scene::from_toml_str(
        &format!(
            "[arch]\nshape = \"circular\"\nradius = 1.0\nembrace_deg = {embrace_deg}\nthickness = {t}\nvoussoirs = {n}\nvoussoir_shape = \"{vs}\"\n"
        ),
        "test",
    )
    .expect("valid test scene")
}

pub fn semicircle(t: f64, n: usize) -> Scene {
    circular(t, n, 180.0, "polygon")
}

pub fn scene(text: &str) -> Scene {
    Scene::from_toml_str(text, "test").expect("valid test scene")
}

/// The model (assembly and loads) of a scene.
pub fn model_of(scene: &Scene) -> Model {
    voussoir::scene::build(scene).expect("valid test model")
}

/// A rectangle `[x0, x0 + b] x [y0, y0 + h]` as a block of unit weight density.
pub fn rect(x0: f64, y0: f64, b: f64, h: f64) -> Block {
    let polygon = vec![
        Vec2::new(x0, y0),
        Vec2::new(x0 + b, y0),
        Vec2::new(x0 + b, y0 + h),
        Vec2::new(x0, y0 + h),
    ];
    let (area, centroid) = polygon_area_centroid(&polygon);
    Block {
        polygon,
        area,
        centroid,
        weight: area,
        kind: BlockKind::Other,
    }
}

/// A horizontal joint at height y from x = a to x = c (p1 at a), carrying `to` on `from`
/// when a > c (normal up).
pub fn hjoint(a: f64, c: f64, y: f64, from: Option<usize>, to: Option<usize>, mu: f64) -> Joint {
    Joint {
        p1: Vec2::new(a, y),
        p2: Vec2::new(c, y),
        from,
        to,
        friction: mu,
        kind: JointKind::Other,
    }
}

/// A single block b x h standing on the ground.
pub fn single_block(b: f64, h: f64, mu: f64) -> Assembly {
    Assembly {
        blocks: vec![rect(-0.5 * b, 0.0, b, h)],
        joints: vec![hjoint(0.5 * b, -0.5 * b, 0.0, None, Some(0), mu)],
    }
}

/// A bundled scene file under `data/`.
pub fn data(name: &str) -> std::path::PathBuf {
    std::path::PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("data")
        .join(name)
}

/// The `voussoir` binary, for end-to-end runs.
pub fn voussoir() -> assert_cmd::Command {
    assert_cmd::Command::cargo_bin("voussoir").expect("binary built")
}
