use voussoir::{assembly::Assembly, lp, scene::Scene};
fn main() {
    for (t, n) in [
        (0.15, 16),
        (0.15, 64),
        (0.15, 1000),
        (0.2, 1000),
        (0.1, 64),
        (0.3, 64),
    ] {
        let s = Scene::from_toml_str(
            &format!("[arch]\nshape=\"circular\"\nradius=1.0\nthickness={t}\nvoussoirs={n}\n"),
            "x",
        )
        .unwrap();
        let a = Assembly::from_scene(&s);
        let r = lp::analyse(&a, &lp::StaticSettings::default()).unwrap();
        println!("t={t} n={n} {:?} lambda={:?} res={:.2e} W={:.3e} it={} time={:.4} hinges={:?} open={:?}", r.status, r.lambda, r.equilibrium_residual, a.total_weight(), r.iterations, r.solve_time_s, r.hinges.iter().map(|h| (h.joint, h.end)).collect::<Vec<_>>(), r.open);
    }
}
