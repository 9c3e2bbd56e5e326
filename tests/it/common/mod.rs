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

/// The inline `polygons` value of a `[blocks]` table for axis-aligned rectangles
/// `[x0, y0, x1, y1]`.
pub fn rect_polygons(rects: &[[f64; 4]]) -> String {
    let polys: Vec<String> = rects
        .iter()
        .map(|r| {
            format!(
                "[[{}, {}], [{}, {}], [{}, {}], [{}, {}]]",
                r[0], r[1], r[2], r[1], r[2], r[3], r[0], r[3]
            )
        })
        .collect();
    format!("[{}]", polys.join(", "))
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

/// Write `files` and the scene `scene.toml` into `dir`, and read the scene.
pub fn scene_in(
    dir: &std::path::Path,
    toml: &str,
    files: &[(&str, &[u8])],
) -> Result<Scene, String> {
    for (name, bytes) in files {
        std::fs::write(dir.join(name), bytes).map_err(|e| e.to_string())?;
    }
    let path = dir.join("scene.toml");
    std::fs::write(&path, toml).map_err(|e| e.to_string())?;
    Scene::from_file(&path).map_err(|e| e.to_string())
}

/// A DXF `LWPOLYLINE` through `points`, closed by its flag or not.
pub fn lwpolyline(points: &[[f64; 2]], closed: bool) -> dxf::entities::EntityType {
    let mut p = dxf::entities::LwPolyline {
        vertices: points
            .iter()
            .map(|q| dxf::LwPolylineVertex {
                x: q[0],
                y: q[1],
                ..Default::default()
            })
            .collect(),
        ..Default::default()
    };
    p.set_is_closed(closed);
    dxf::entities::EntityType::LwPolyline(p)
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

/// The scene `text` written to a file in a fresh temporary directory (kept alive by the
/// returned guard).
pub fn scene_file(text: &str) -> (tempfile::TempDir, std::path::PathBuf) {
    let dir = tempfile::tempdir().expect("temp dir");
    let path = dir.path().join("scene.toml");
    std::fs::write(&path, text).expect("write scene");
    (dir, path)
}

/// The JSON that `voussoir ARGS SCENE` prints for the scene `text`; the command must succeed.
pub fn json_of(args: &[&str], text: &str) -> serde_json::Value {
    let (_dir, path) = scene_file(text);
    let out = voussoir().args(args).arg(&path).output().expect("runs");
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_slice(&out.stdout).expect("JSON")
}

/// Housner's rigid rocking block (1963), integrated directly: a block b x h on rigid ground
/// under the horizontal ground acceleration `ground(t)` (m/s^2) with gravity `g`, rotating
/// about one base corner at a time (Makris & Roussos 2000; Zhang & Makris 2001, "Rocking
/// response of free-standing blocks under cycloidal pulses", J. Eng. Mech. 127:473-483):
/// `theta'' = -p^2 [sin(alpha sgn(theta) - theta) + (a_g / g) cos(alpha sgn(theta) - theta)]`,
/// `p^2 = 3 g / (4 R)` (R the half-diagonal), rocking starting when `|a_g| > g tan(alpha)`,
/// and at each impact (theta through 0) Housner's sticking impact keeps `1 - 1.5 sin^2(alpha)`
/// of the angular speed. Whether it overturns: it has, once `|theta|` passes pi/2; it has
/// not, once the ground is still (`t >= duration`) and its energy above rest is below the
/// energy to reach the unstable equilibrium, `m g R (1 - cos(alpha))`. Fourth-order
/// Runge-Kutta with a step of 1e-5 s.
pub fn housner_overturns(
    b: f64,
    h: f64,
    g: f64,
    ground: &dyn Fn(f64) -> f64,
    duration: f64,
) -> bool {
    let alpha = (b / h).atan();
    let r = 0.5 * (b * b + h * h).sqrt();
    let p2 = 3.0 * g / (4.0 * r);
    let e = 1.0 - 1.5 * alpha.sin().powi(2);
    let accel = |t: f64, th: f64, side: f64| {
        let ag = ground(t) / g;
        -p2 * ((alpha * side - th).sin() + ag * (alpha * side - th).cos())
    };
    let h_step = 1e-5;
    let (mut t, mut th, mut om) = (0.0_f64, 0.0_f64, 0.0_f64);
    // The corner it rocks on: +1, -1, or 0 while it stands.
    let mut side = 0.0_f64;
    while t < duration + 60.0 {
        if side == 0.0 {
            let ag = ground(t) / g;
            if ag < -alpha.tan() {
                side = 1.0;
            } else if ag > alpha.tan() {
                side = -1.0;
            } else {
                if t >= duration {
                    return false;
                }
                t += h_step;
                continue;
            }
        }
        let f = |t: f64, th: f64, om: f64| (om, accel(t, th, side));
        let (k1a, k1b) = f(t, th, om);
        let (k2a, k2b) = f(
            t + 0.5 * h_step,
            th + 0.5 * h_step * k1a,
            om + 0.5 * h_step * k1b,
        );
        let (k3a, k3b) = f(
            t + 0.5 * h_step,
            th + 0.5 * h_step * k2a,
            om + 0.5 * h_step * k2b,
        );
        let (k4a, k4b) = f(t + h_step, th + h_step * k3a, om + h_step * k3b);
        let th_new = th + h_step / 6.0 * (k1a + 2.0 * k2a + 2.0 * k3a + k4a);
        om += h_step / 6.0 * (k1b + 2.0 * k2b + 2.0 * k3b + k4b);
        t += h_step;
        if th_new * side < 0.0 {
            // Impact: on the other corner, with the angular speed Housner's impact keeps.
            th = 0.0;
            om *= e;
            side = if om > 0.0 { 1.0 } else { -1.0 };
            if om.abs() < 1e-9 {
                side = 0.0;
                om = 0.0;
            }
            continue;
        }
        th = th_new;
        if th.abs() > 0.5 * std::f64::consts::PI {
            return true;
        }
        if t >= duration {
            let energy = om * om / (2.0 * p2) + (alpha - th.abs()).cos() - alpha.cos();
            if energy < 1.0 - alpha.cos() && th.abs() < alpha {
                return false;
            }
        }
    }
    false
}

/// The smallest amplitude (m/s^2) of the pulse `pulse(a, t)` lasting `duration` that
/// overturns Housner's block b x h ([`housner_overturns`]): scanned up from `g tan(alpha)`
/// by 1% (the lowest overturning window is not missed unless narrower than that), then
/// bisected to 1e-4.
pub fn housner_minimum_amplitude(
    b: f64,
    h: f64,
    g: f64,
    pulse: &dyn Fn(f64, f64) -> f64,
    duration: f64,
) -> f64 {
    let mut lo = g * b / h;
    let mut hi = lo;
    while !housner_overturns(b, h, g, &|t| pulse(hi, t), duration) {
        lo = hi;
        hi *= 1.01;
        assert!(hi < 100.0 * g, "no overturning below 100 g");
    }
    while hi - lo > 1e-4 * hi {
        let mid = 0.5 * (lo + hi);
        if housner_overturns(b, h, g, &|t| pulse(mid, t), duration) {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    hi
}

/// The static multiplier of `model` and the DEM's bracket `[stands, collapses]` to 1 %, from
/// the DEM's own start.
pub fn static_and_dem_bracket(model: &Model) -> (f64, f64, f64) {
    let lower = voussoir::statics::analyse(model, &voussoir::statics::StaticSettings::default())
        .expect("the static program solves")
        .lambda
        .expect("collapse");
    let dem = voussoir::dem::collapse_multiplier(
        model,
        &voussoir::dem_settings::IntegrationParameters::for_model(model),
        0.01,
        &mut |_| {},
    )
    .expect("DEM runs");
    (
        lower,
        dem.lambda_stands.expect("a standing run"),
        dem.lambda_collapses.expect("a collapsing run"),
    )
}

/// The running-bond wall of docs/dem.md as rectangles `[x0, y0, x1, y1]`: three courses 0.4 m
/// high, 1.2 m long, the middle one offset by half a block (2 + 3 + 2 blocks).
pub fn running_bond_wall_rects() -> Vec<[f64; 4]> {
    let h = 0.4;
    let mut blocks = Vec::new();
    for c in 0..3 {
        let y0 = c as f64 * h;
        let xs: &[f64] = if c % 2 == 0 {
            &[0.0, 0.6, 1.2]
        } else {
            &[0.0, 0.3, 0.9, 1.2]
        };
        for w in xs.windows(2) {
            blocks.push([w[0], y0, w[1], y0 + h]);
        }
    }
    blocks
}

/// The number `key` of a JSON object (a panic naming it when it is not one).
pub fn f64_of(v: &serde_json::Value, key: &str) -> f64 {
    v[key]
        .as_f64()
        .unwrap_or_else(|| panic!("{key} is not a number: {v}"))
}

/// A rectangular block b x h standing on the ground (one support joint along its base, from
/// the block into the ground), of weight 20 kN/m^2 times its area, with friction `mu`.
pub fn rect_block(b: f64, h: f64, mu: f64) -> Assembly {
    Assembly {
        blocks: vec![Block {
            polygon: vec![
                Vec2::new(-0.5 * b, 0.0),
                Vec2::new(0.5 * b, 0.0),
                Vec2::new(0.5 * b, h),
                Vec2::new(-0.5 * b, h),
            ],
            area: b * h,
            centroid: Vec2::new(0.0, 0.5 * h),
            weight: 20000.0 * b * h,
            kind: BlockKind::Other,
        }],
        joints: vec![Joint {
            p1: Vec2::new(-0.5 * b, 0.0),
            p2: Vec2::new(0.5 * b, 0.0),
            from: Some(0),
            to: None,
            friction: mu,
            kind: JointKind::Other,
        }],
    }
}

/// The static result of `model` toward `d` by the default dispatch (the chain program on a
/// chain) and by the full program, for comparing the two.
pub fn chain_and_full(
    model: &Model,
    d: voussoir::statics::Direction,
) -> (
    voussoir::statics::StaticResult,
    voussoir::statics::StaticResult,
) {
    use voussoir::statics::{self, Program, StaticSettings};
    let settings = StaticSettings::default().direction(d);
    let chain = statics::analyse(model, &settings).expect("chain program");
    let full = statics::analyse(model, &settings.program(Program::Full)).expect("full program");
    (chain, full)
}
