//! Timing of `voussoir fragility` by the capacity route on the bundled portal with uncertain
//! inputs (data/fragility_portal.toml: the ring's thickness, the piers' width, the unit
//! weight): 1,000 Latin hypercube samples, each assessed in both directions at the site (the
//! static bound, the certified mechanism, its capacity curve and the nonlinear check's
//! largest passing ag), and the lognormal fit. Run with `cargo bench --bench fragility`.
//! Target (issue 30): seconds on 2 cores. The samples run in parallel (rayon, one thread per
//! core).

mod common;
use common::median;
use voussoir::fragility::{self, Settings};
use voussoir::scene::Scene;

fn main() {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("data/fragility_portal.toml");
    let scene = match Scene::from_file(&path) {
        Ok(s) => s,
        Err(e) => panic!("bench scene: {e}"),
    };
    for samples in [100, 1000] {
        let settings = Settings {
            samples,
            seed: 1,
            ..Settings::default()
        };
        let (t, f) = median(3, || fragility::capacity_route(&scene, &settings));
        let f = match f {
            Ok(f) => f,
            Err(e) => panic!("fragility: {e}"),
        };
        let fit = match &f.fit {
            Ok(fit) => format!("median {:.4} g, beta {:.4}", fit.median, fit.beta),
            Err(e) => format!("no fit: {e}"),
        };
        println!(
            "capacity-route fragility, {samples} samples on {} threads: {t:.3} s ({:.2} ms per sample); {fit}, {} not assessed",
            rayon::current_num_threads(),
            1e3 * t / samples as f64,
            f.not_assessed()
        );
    }
}
