//! Timing of `POST /api/analyze`, the request the page sends on every slider move, in process
//! (the router called directly: no socket, no browser) for the bundled semicircular arch at
//! n = 32, 200 and 1000 voussoirs, with its parts: the analysis (static bound and certified
//! mechanism), the drawing (SVG) and the JSON. Run with `cargo bench --bench serve`. Target:
//! well under the page's 50 ms budget at n <= 200 (the browser's own figure, from the
//! end-to-end test, is in docs/web.md). Each n is timed rigid and with a finite compressive
//! strength (`material.compressive_strength`, 20 and 1 MPa: the crushing working set of issue
//! 28), and, with crushing, the analysis once more with the chain program on all joints
//! (`StaticSettings::working_set` off: the page before issue 28).

use axum::body::Body;
use axum::http::Request;
use http_body_util::BodyExt;
use std::sync::Arc;
use std::time::Instant;
use tower::ServiceExt;
use voussoir::analysis::{self, Options};
use voussoir::outcome::Direction;
use voussoir::report;
use voussoir::serve::{self, api, Limits, ServerState};

/// Median of `reps` wall times (ms) of `f`.
fn median_ms(reps: usize, mut f: impl FnMut()) -> f64 {
    f();
    let mut times: Vec<f64> = (0..reps)
        .map(|_| {
            let t = Instant::now();
            f();
            t.elapsed().as_secs_f64() * 1e3
        })
        .collect();
    times.sort_by(f64::total_cmp);
    times[reps / 2]
}

fn main() {
    let state = match ServerState::with_default_scene(Limits::default()) {
        Ok(s) => Arc::new(s),
        Err(e) => panic!("bundled scene: {e}"),
    };
    let runtime = match tokio::runtime::Builder::new_current_thread()
        .enable_all()
        .build()
    {
        Ok(r) => r,
        Err(e) => panic!("runtime: {e}"),
    };
    println!("POST /api/analyze in process, semicircle t/R = 0.15 (median ms)");
    println!(
        "{:>6} {:>8} {:>10} {:>10} {:>10} {:>10} {:>10} {:>14}",
        "n", "fc MPa", "request", "analysis", "svg", "json", "svg kB", "all joints"
    );
    for (n, fc) in [32_i64, 200, 1000]
        .into_iter()
        .flat_map(|n| [(n, f64::INFINITY), (n, 20e6), (n, 1e6)])
    {
        let scene = match state
            .scene
            .with_value("arch.voussoirs", toml::Value::Integer(n))
            .and_then(|s| s.with_value("material.compressive_strength", toml::Value::Float(fc)))
        {
            Ok(s) => s,
            Err(e) => panic!("scene: {e}"),
        };
        let body = serde_json::json!({ "scene": api::table_json(scene.table()) }).to_string();
        let request = || {
            let body = body.clone();
            runtime.block_on(async {
                let r = serve::router(state.clone())
                    .oneshot(
                        Request::post("/api/analyze")
                            .header("content-type", "application/json")
                            .body(Body::from(body))
                            .unwrap_or_default(),
                    )
                    .await;
                match r {
                    Ok(r) => {
                        // Time answers, not refusals.
                        assert!(r.status().is_success(), "{}", r.status());
                        r.into_body().collect().await.map(|b| b.to_bytes().len())
                    }
                    Err(e) => match e {},
                }
            })
        };
        let reps = if n > 500 { 30 } else { 100 };
        let t_request = median_ms(reps, || {
            let _ = request();
        });
        let options = Options::default();
        let t_analysis = median_ms(reps, || {
            let _ = analysis::analyse(&scene, &options);
        });
        let a = match analysis::analyse(&scene, &options) {
            Ok(a) => a,
            Err(e) => panic!("analysis: {e}"),
        };
        let mut svg_len = 0;
        let t_svg = median_ms(reps, || {
            svg_len = report::analysis_svg(&scene, &a, Direction::Right)
                .map(|s| s.len())
                .unwrap_or(0);
        });
        let t_json = median_ms(reps, || {
            let _ = serde_json::to_string(&report::AnalysisReport::new(&scene, &a));
        });
        let t_all = if fc.is_finite() {
            let mut all = Options::default();
            all.static_settings = all.static_settings.working_set(false);
            format!(
                "{:.3}",
                median_ms(reps.min(30), || {
                    let _ = analysis::analyse(&scene, &all);
                })
            )
        } else {
            "-".to_string()
        };
        println!(
            "{n:>6} {:>8} {t_request:>10.3} {t_analysis:>10.3} {t_svg:>10.3} {t_json:>10.3} {:>10.1} {t_all:>14}",
            fc / 1e6,
            svg_len as f64 / 1e3
        );
    }
}
