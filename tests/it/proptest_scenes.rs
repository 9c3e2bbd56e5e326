//! Property tests over random scenes: no input panics; every rejected scene names a key;
//! every accepted scene builds a valid assembly whose analysis ends in a status or a typed
//! error, never NaN.

use proptest::prelude::*;
use proptest::strategy::ValueTree;
use voussoir::scene::Scene;
use voussoir::statics::{self, StaticSettings};

fn number() -> impl Strategy<Value = String> {
    prop_oneof![
        (-3.0f64..3.0).prop_map(|x| format!("{x:?}")),
        (0.0f64..2.5).prop_map(|x| format!("{x:?}")),
        (-5i64..70).prop_map(|i| i.to_string()),
        Just("nan".to_string()),
        Just("inf".to_string()),
        Just("-inf".to_string()),
        Just("\"abc\"".to_string()),
        Just("true".to_string()),
        Just("1e308".to_string()),
        Just("0".to_string()),
    ]
}

/// A plausible scene of each shape, with numbers drawn over (and a little beyond) their
/// valid ranges, then possibly one key replaced by a bad value or an unknown key added.
fn scene_text() -> impl Strategy<Value = String> {
    let shape = prop_oneof![
        (0.2f64..5.0, 10.0f64..350.0).prop_map(|(r, emb)| format!(
            "shape = \"circular\"\nradius = {r:?}\nembrace_deg = {emb:?}\n"
        )),
        (0.2f64..5.0, 0.0f64..0.9).prop_map(|(r, e)| format!(
            "shape = \"pointed\"\nradius = {r:?}\neccentricity = {:?}\n",
            e * r
        )),
        (0.5f64..6.0, 0.05f64..0.55, 10.0f64..89.0).prop_map(|(l, rs, b)| format!(
            "shape = \"basket\"\nspan = {l:?}\nrise = {:?}\nside_angle_deg = {b:?}\n",
            rs * l
        )),
    ];
    let piers = proptest::option::of((0.05f64..6.0, 0.05f64..2.0, 1usize..6));
    (
        shape,
        0.001f64..1.5,
        1usize..60,
        any::<bool>(),
        piers,
        prop_oneof![
            Just("inf".to_string()),
            (0.0f64..2.0).prop_map(|m| format!("{m:?}"))
        ],
        proptest::option::of((0usize..6, number())),
    )
        .prop_map(|(shape, t, n, curved, piers, mu, mutation)| {
            let mut lines = vec![
                "[arch]".to_string(),
                shape.trim_end().to_string(),
                format!("thickness = {t:?}"),
                format!("voussoirs = {n}"),
                format!(
                    "voussoir_shape = \"{}\"",
                    if curved { "curved" } else { "polygon" }
                ),
            ];
            if let Some((h, b, k)) = piers {
                lines.push(format!(
                    "[piers]\nheight = {h:?}\nwidth = {b:?}\ncourses = {k}"
                ));
            }
            lines.push(format!("[material]\nfriction = {mu}"));
            let mut text = lines.join("\n") + "\n";
            if let Some((which, bad)) = mutation {
                let key = [
                    "thickness",
                    "voussoirs",
                    "radius",
                    "span",
                    "friction",
                    "colour",
                ][which];
                let re = format!("{key} = ");
                if let Some(pos) = text.find(&re) {
                    let end = text[pos..].find('\n').map_or(text.len(), |e| pos + e);
                    text.replace_range(pos..end, &format!("{key} = {bad}"));
                } else {
                    text = text.replacen("[arch]\n", &format!("[arch]\n{key} = {bad}\n"), 1);
                }
            }
            text
        })
}

static ACCEPTED: std::sync::atomic::AtomicUsize = std::sync::atomic::AtomicUsize::new(0);

proptest! {
    #![proptest_config(ProptestConfig { cases: 10_000, failure_persistence: None, ..ProptestConfig::default() })]

    #[test]
    fn random_scenes_never_panic(text in scene_text()) {
        match Scene::from_toml_str(&text, "random.toml") {
            Err(e) => {
                let msg = e.to_string();
                prop_assert!(msg.contains("random.toml"), "{}", msg);
                // Apart from TOML syntax errors, every error names a key.
                if e.key().is_none() {
                    prop_assert!(matches!(e, voussoir::error::SceneError::Syntax { .. }), "{}", msg);
                }
            }
            Ok(scene) => {
                ACCEPTED.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
                let built = voussoir::scene::build(&scene);
                prop_assert!(built.is_ok(), "no model from a valid scene: {:?}\n{}", built.as_ref().err(), text);
                let m = built.expect("checked");
                let a = &m.assembly;
                prop_assert!(a.validate().is_ok(), "invalid assembly from a valid scene:\n{}", text);
                // Solve only small models, so 10,000 cases run in seconds.
                if a.blocks.len() <= 40 {
                    match statics::analyse(&m, &StaticSettings::default()) {
                        Ok(r) => {
                            if let Some(l) = r.lambda {
                                prop_assert!(l.is_finite() && l >= 0.0);
                            }
                        }
                        // A valid scene must solve: a solver failure is a bug, never an answer.
                        Err(e) => prop_assert!(false, "valid scene failed to solve: {}\n{}", e, text),
                    }
                }
            }
        }
    }
}

#[test]
fn random_scenes_accept_some() {
    // Run after the property test in the same process when possible; alone it checks that
    // the generator can produce valid scenes at all.
    let mut runner = proptest::test_runner::TestRunner::new(ProptestConfig {
        cases: 2000,
        failure_persistence: None,
        ..ProptestConfig::default()
    });
    let mut ok = 0usize;
    for _ in 0..2000 {
        let text = scene_text().new_tree(&mut runner).expect("tree").current();
        if Scene::from_toml_str(&text, "r").is_ok() {
            ok += 1;
        }
    }
    eprintln!("accepted {ok} of 2000 random scenes");
    assert!(ok > 20, "the generator must reach valid scenes: {ok}");
}
