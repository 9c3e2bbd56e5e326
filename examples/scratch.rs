use voussoir::{lp, scene::Scene, thickness};
fn main() {
    for (n, vs) in [
        (64, "polygon"),
        (128, "polygon"),
        (128, "curved"),
        (256, "curved"),
    ] {
        let s = Scene::from_toml_str(&format!("[arch]\nshape=\"circular\"\nradius=1.0\nthickness=0.15\nvoussoirs={n}\nvoussoir_shape=\"{vs}\"\n"), "x").unwrap();
        let t0 = std::time::Instant::now();
        let m = thickness::min_thickness(&s, &lp::StaticSettings::default()).unwrap();
        let hs: Vec<_> = m
            .hinges
            .iter()
            .map(|h| (h.joint, h.end, (h.x.atan2(h.y)).to_degrees()))
            .collect();
        println!(
            "n={n} {vs} tmin={:?} evals={} time={:.3}s hinges={:?}",
            m.search.min_thickness,
            m.search.evaluations,
            t0.elapsed().as_secs_f64(),
            hs
        );
    }
}
