use voussoir::{assembly::Assembly, lp, scene::Scene};
fn run(label: &str, text: &str) {
    match Scene::from_toml_str(text, label) {
        Err(e) => println!("{label}: SCENE ERR {e}"),
        Ok(s) => match lp::analyse(&Assembly::from_scene(&s), &lp::StaticSettings::default()) {
            Ok(r) => println!(
                "{label}: {:?} {:?} res={:.1e} it={} {}",
                r.status,
                r.lambda,
                r.equilibrium_residual / Assembly::from_scene(&s).total_weight(),
                r.iterations,
                r.solver_status
            ),
            Err(e) => println!("{label}: ERR {e}"),
        },
    }
}
fn circ(t: f64, n: usize, emb: f64, extra: &str) -> String {
    format!("[arch]\nshape=\"circular\"\nradius=1.0\nembrace_deg={emb}\nthickness={t}\nvoussoirs={n}\n{extra}")
}
fn main() {
    let tmin = 0.10746543762308022; // n=128
    for f in [1.0 + 1e-3, 1.0 + 1e-5, 1.0 + 1e-7, 1.0 - 1e-7, 1.0 - 1e-5] {
        run(&format!("tmin*{f}"), &circ(tmin * f, 128, 180.0, ""));
    }
    run("thick 0.9", &circ(0.9, 64, 180.0, ""));
    run("thick 1.9", &circ(1.9, 64, 180.0, ""));
    run("flat 20", &circ(0.05, 32, 20.0, ""));
    run("flat 20 thin", &circ(0.005, 32, 20.0, ""));
    run("horseshoe 300", &circ(0.3, 64, 300.0, ""));
    run("horseshoe 300 thick", &circ(0.6, 64, 300.0, ""));
    run("n=2", &circ(0.3, 2, 180.0, ""));
    run("n=1", &circ(0.3, 1, 180.0, ""));
    run("n=2000", &circ(0.15, 2000, 180.0, ""));
    for mu in ["0.01", "0.1", "0.5", "1e3", "1e6", "inf"] {
        run(
            &format!("mu={mu}"),
            &circ(0.2, 32, 180.0, &format!("[material]\nfriction={mu}\n")),
        );
    }
    for e in [0.9, 0.92, 0.924, 0.9249] {
        run(&format!("pointed e={e}"), &format!("[arch]\nshape=\"pointed\"\nradius=1.0\neccentricity={e}\nthickness=0.15\nvoussoirs=32\n"));
    }
    for rs in [0.1, 0.2, 0.3, 0.45, 0.49] {
        run(
            &format!("basket r/s={rs}"),
            &format!(
                "[arch]\nshape=\"basket\"\nspan=2.0\nrise={}\nthickness=0.05\nvoussoirs=32\n",
                2.0 * rs
            ),
        );
    }
    for (h, b) in [(4.0, 0.2), (0.1, 0.5), (2.0, 0.1), (0.06, 0.3)] {
        run(
            &format!("piers h={h} b={b}"),
            &circ(
                0.2,
                32,
                180.0,
                &format!("[piers]\nheight={h}\nwidth={b}\ncourses=4\n"),
            ),
        );
    }
}
