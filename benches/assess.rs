//! Timing of `voussoir assess` on the bundled portal (data/portal.toml, 32 voussoirs on piers
//! of 4 courses) at a site: the whole assessment (static bound, certified mechanism, capacity
//! curve of 200 points, verdict with both bisections for the largest passing ag) and its parts.
//! Run with `cargo bench --bench assess`. Target: the whole assessment well under a second.

mod common;
use common::time;
use voussoir::analysis::{self, AssessOptions, Options};
use voussoir::assess::{self, CapacitySettings};
use voussoir::outcome::Direction;
use voussoir::scene::Scene;

fn main() {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("data/portal.toml");
    let scene = match Scene::from_file(&path).and_then(|s| {
        s.with_overrides(&[
            "site.ag=0.25",
            "site.soil=\"B\"",
            "site.F0=2.4",
            "site.Tc_star=0.3",
        ])
    }) {
        Ok(s) => s,
        Err(e) => panic!("bench scene: {e}"),
    };
    let options = Options::default();
    let (t_all, a) = time(20, || {
        analysis::assess(&scene, &options, &AssessOptions::default())
    });
    let a = match a {
        Ok(a) => a,
        Err(e) => panic!("assess: {e}"),
    };
    let mech = match a
        .analysis
        .upper
        .as_ref()
        .ok()
        .and_then(|k| k.mechanism.clone())
    {
        Some(m) => m,
        None => panic!("no mechanism"),
    };
    let model = &a.analysis.model;
    let settings = CapacitySettings {
        fc: a.site.fc,
        ..CapacitySettings::default()
    };
    let (t_cap, cap) = time(20, || {
        assess::capacity(model, &mech, Direction::Right, &settings)
    });
    let cap = match cap {
        Ok(c) => c,
        Err(e) => panic!("capacity: {e}"),
    };
    let (t_verdict, _) = time(20, || assess::verdict(model, &cap, &a.site));
    println!(
        "{:<52} {:>10}",
        "assess data/portal.toml (200-point curve)", "best ms"
    );
    println!(
        "{:<52} {:>10.3}",
        "whole assessment (analysis + capacity + verdict)",
        1e3 * t_all
    );
    println!(
        "{:<52} {:>10.3}",
        "capacity curve (200 points, d_k0 by bisection)",
        1e3 * t_cap
    );
    println!(
        "{:<52} {:>10.3}",
        "verdict (both largest passing ag)",
        1e3 * t_verdict
    );
}
