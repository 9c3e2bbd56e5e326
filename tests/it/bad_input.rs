//! Invalid scenes: each error names the key (and the value) that is wrong.

use voussoir::error::SceneError;
use voussoir::scene::Scene;

const GOOD: &str = "[arch]\nshape = \"circular\"\nradius = 1.0\nthickness = 0.15\nvoussoirs = 16\n";

fn err(text: &str) -> SceneError {
    match Scene::from_toml_str(text, "bad.toml") {
        Ok(_) => panic!("scene should be rejected:\n{text}"),
        Err(e) => e,
    }
}

#[test]
fn each_invalid_scene_names_its_key() {
    let cases: &[(&str, &str, &str)] = &[
        // (scene text, key named, value named)
        ("[arch]\nshape = \"circular\"\nthickness = 0.1\nvoussoirs = 8\n", "arch.radius", ""),
        ("[arch]\nshape = \"circular\"\nradius = 1.0\nvoussoirs = 8\n", "arch.thickness", ""),
        ("[arch]\nshape = \"circular\"\nradius = 1.0\nthickness = 0.1\n", "arch.voussoirs", ""),
        ("[arch]\nradius = 1.0\nthickness = 0.1\nvoussoirs = 8\n", "arch.shape", ""),
        ("[arch]\nshape = \"oval\"\nradius = 1.0\nthickness = 0.1\nvoussoirs = 8\n", "arch.shape", "oval"),
        ("[arch]\nshape = \"circular\"\nradius = -1.0\nthickness = 0.1\nvoussoirs = 8\n", "arch.radius", "-1"),
        ("[arch]\nshape = \"circular\"\nradius = 0.0\nthickness = 0.1\nvoussoirs = 8\n", "arch.radius", "0"),
        ("[arch]\nshape = \"circular\"\nradius = nan\nthickness = 0.1\nvoussoirs = 8\n", "arch.radius", "NaN"),
        ("[arch]\nshape = \"circular\"\nradius = inf\nthickness = 0.1\nvoussoirs = 8\n", "arch.radius", "inf"),
        ("[arch]\nshape = \"circular\"\nradius = \"big\"\nthickness = 0.1\nvoussoirs = 8\n", "arch.radius", "big"),
        ("[arch]\nshape = \"circular\"\nradius = 1.0\nthickness = 2.5\nvoussoirs = 8\n", "arch.thickness", "2.5"),
        ("[arch]\nshape = \"circular\"\nradius = 1.0\nthickness = 0.1\nvoussoirs = 0\n", "arch.voussoirs", "0"),
        ("[arch]\nshape = \"circular\"\nradius = 1.0\nthickness = 0.1\nvoussoirs = 8.5\n", "arch.voussoirs", "8.5"),
        ("[arch]\nshape = \"circular\"\nradius = 1.0\nthickness = 0.1\nvoussoirs = 1000000\n", "arch.voussoirs", "1000000"),
        ("[arch]\nshape = \"circular\"\nradius = 1.0\nthickness = 0.1\nvoussoirs = 8\nembrace_deg = 360\n", "arch.embrace_deg", "360"),
        ("[arch]\nshape = \"circular\"\nradius = 1.0\nthickness = 0.1\nvoussoirs = 8\nvoussoir_shape = \"round\"\n", "arch.voussoir_shape", "round"),
        ("[arch]\nshape = \"circular\"\nradius = 1.0\nthickness = 0.1\nvoussoirs = 8\ncolour = \"red\"\n", "arch.colour", ""),
        ("[arch]\nshape = \"circular\"\nradius = 1.0\nthickness = 0.1\nvoussoirs = 8\neccentricity = 0.1\n", "arch.eccentricity", ""),
        ("[arch]\nshape = \"pointed\"\nradius = 1.0\neccentricity = 0.2\nthickness = 0.1\nvoussoirs = 9\n", "arch.voussoirs", "9"),
        ("[arch]\nshape = \"pointed\"\nradius = 1.0\neccentricity = 0.95\nthickness = 0.1\nvoussoirs = 8\n", "arch.eccentricity", "0.95"),
        ("[arch]\nshape = \"pointed\"\nradius = 1.0\neccentricity = -0.1\nthickness = 0.1\nvoussoirs = 8\n", "arch.eccentricity", "-0.1"),
        ("[arch]\nshape = \"pointed\"\nradius = 1.0\nthickness = 0.1\nvoussoirs = 8\n", "arch.eccentricity", ""),
        ("[arch]\nshape = \"basket\"\nspan = 2.0\nrise = 1.0\nthickness = 0.1\nvoussoirs = 9\n", "arch.rise", "1"),
        ("[arch]\nshape = \"basket\"\nspan = 2.0\nrise = 1.3\nthickness = 0.1\nvoussoirs = 9\n", "arch.rise", "1.3"),
        ("[arch]\nshape = \"basket\"\nspan = 2.0\nrise = 0.6\nthickness = 0.1\nvoussoirs = 9\nside_angle_deg = 95\n", "arch.side_angle_deg", "95"),
        ("[arch]\nshape = \"basket\"\nspan = 2.0\nrise = 0.6\nthickness = 0.1\nvoussoirs = 2\n", "arch.voussoirs", "2"),
        ("[arch]\nshape = \"basket\"\nspan = 2.0\nrise = 0.3\nthickness = 0.9\nvoussoirs = 9\n", "arch.thickness", "0.9"),
        (&format!("{GOOD}[piers]\nheight = 1.0\n"), "piers.width", ""),
        (&format!("{GOOD}[piers]\nheight = 1.0\nwidth = -0.3\n"), "piers.width", "-0.3"),
        (&format!("{GOOD}[piers]\nheight = 1.0\nwidth = 0.3\ncourses = 0\n"), "piers.courses", "0"),
        (&format!("{GOOD}[piers]\nheight = 1.0\nwidth = 0.3\nfoo = 1\n"), "piers.foo", ""),
        ("[arch]\nshape = \"circular\"\nradius = 1.0\nembrace_deg = 120\nthickness = 0.1\nvoussoirs = 8\n[piers]\nheight = 1.0\nwidth = 0.3\n", "arch.embrace_deg", "120"),
        (&format!("{GOOD}[material]\nfriction = -0.5\n"), "material.friction", "-0.5"),
        (&format!("{GOOD}[material]\nfriction = nan\n"), "material.friction", "NaN"),
        (&format!("{GOOD}[material]\nfriction = 1e12\n"), "material.friction", "1000000000000"),
        (&format!("{GOOD}[material]\nunit_weight = 0\n"), "material.unit_weight", "0"),
        (&format!("{GOOD}[material]\ndepth = true\n"), "material.depth", "true"),
        // Values whose blocks would weigh 0 or inf (the value is written as 1e300, not in
        // 301 digits).
        (&format!("{GOOD}[material]\ndepth = 1e300\n"), "material.depth", "1e300"),
        (&format!("{GOOD}[material]\ndepth = 1e-300\n"), "material.depth", "1e-300"),
        (&format!("{GOOD}[material]\nunit_weight = 1e300\n"), "material.unit_weight", "1e300"),
        ("[arch]\nshape = \"circular\"\nradius = 1.0\nthickness = 0.1\nvoussoirs = 8\nembrace_deg = 1e-300\n", "arch.embrace_deg", "1e-300"),
        (&format!("{GOOD}[materials]\ndepth = 1.0\n"), "materials", ""),
        ("arch = 3\n", "arch", "3"),
        ("[piers]\nheight = 1.0\nwidth = 0.3\n", "arch", ""),
    ];
    for (text, key, value) in cases {
        let e = err(text);
        let msg = e.to_string();
        assert_eq!(e.key(), Some(*key), "scene:\n{text}\nerror: {msg}");
        assert!(msg.contains(key), "message should name {key}: {msg}");
        assert!(
            msg.contains("bad.toml"),
            "message should name the file: {msg}"
        );
        if !value.is_empty() {
            assert!(
                msg.contains(value),
                "message should show the value {value}: {msg}"
            );
        }
    }
}

#[test]
fn malformed_toml_is_a_syntax_error_with_the_file() {
    let e = err("[arch\nshape = ");
    assert!(matches!(e, SceneError::Syntax { .. }));
    assert!(e.to_string().contains("bad.toml"));
}

#[test]
fn overrides_are_validated_like_files() {
    let s = Scene::from_toml_str(GOOD, "good.toml").expect("valid");
    for (text, key) in [
        ("arch.thickness=-0.1", Some("arch.thickness")),
        ("arch.thickness=abc", Some("arch.thickness")),
        ("arch.nonsense=1", Some("arch.nonsense")),
        ("piers.height=1.0", Some("piers.width")),
        ("material.friction=-1", Some("material.friction")),
    ] {
        let e = s.with_override(text).expect_err(text);
        assert_eq!(e.key(), key, "{text}: {e}");
    }
    for text in ["thickness=0.2", "nosuch.key=1", "arch.thickness", "=3"] {
        let e = s.with_override(text).expect_err(text);
        assert!(matches!(e, SceneError::BadOverride { .. }), "{text}: {e}");
    }
    // Overrides are applied together and validated once, so their order does not matter.
    let pointed = s
        .with_overrides(&["arch.shape=pointed", "arch.eccentricity=0.2"])
        .expect("a valid pointed arch");
    assert_eq!(pointed.arch.as_ref().expect("arch").shape.name(), "pointed");
}

/// A misspelt key is reported as the unknown key it is (not as the required key it was meant
/// to be), with the closest allowed key, in every section of the scene.
#[test]
fn a_typo_names_the_unknown_key_and_suggests_the_closest() {
    let cases: &[(&str, &str, &str)] = &[
        // (scene text, unknown key, suggested key)
        (
            "[arch]\nshape = \"circular\"\nradius = 1.0\nthicknes = 0.2\nvoussoirs = 8\n",
            "arch.thicknes",
            "thickness",
        ),
        (
            "[arch]\nshape = \"circular\"\nradus = 1.0\nthickness = 0.2\nvoussoirs = 8\n",
            "arch.radus",
            "radius",
        ),
        (
            "[arch]\nshpe = \"circular\"\nradius = 1.0\nthickness = 0.2\nvoussoirs = 8\n",
            "arch.shpe",
            "shape",
        ),
        (
            "[arch]\nshape = \"pointed\"\nradius = 1.0\neccentricty = 0.1\nthickness = 0.1\nvoussoirs = 8\n",
            "arch.eccentricty",
            "eccentricity",
        ),
        (
            "[arch]\nshape = \"basket\"\nspan = 2.0\nrise = 0.6\nthickness = 0.1\nvousoirs = 9\n",
            "arch.vousoirs",
            "voussoirs",
        ),
        (&format!("{GOOD}[piers]\nheigth = 1.0\nwidth = 0.3\n"), "piers.heigth", "height"),
        (&format!("{GOOD}[material]\nfriction = 0.5\ndepht = 1\n"), "material.depht", "depth"),
        (&format!("{GOOD}[fill]\nlevle = 1.5\n"), "fill.levle", "level"),
        (&format!("{GOOD}[seismic]\nvertical_ration = 0.1\n"), "seismic.vertical_ration", "vertical_ratio"),
        (
            &format!("{GOOD}[[loads]]\ntype = \"point\"\nat = [0.0, 1.0]\nforse = [0.0, -100.0]\n"),
            "loads[0].forse",
            "force",
        ),
        (
            &format!("{GOOD}[[loads]]\ntype = \"line\"\nfrom_x = -0.5\nto_x = 0.5\nintensty = 10.0\n"),
            "loads[0].intensty",
            "intensity",
        ),
        (&format!("{GOOD}[materal]\ndepth = 1.0\n"), "materal", "material"),
    ];
    for (text, key, suggestion) in cases {
        let e = err(text);
        let msg = e.to_string();
        assert!(matches!(e, SceneError::UnknownKey { .. }), "{text}\n{msg}");
        assert_eq!(e.key(), Some(*key), "scene:\n{text}\nerror: {msg}");
        assert!(
            msg.contains(&format!("unknown key `{key}`")),
            "message should name the unknown key {key}: {msg}"
        );
        assert!(
            msg.contains(&format!("(did you mean `{suggestion}`?)")),
            "message should suggest {suggestion}: {msg}"
        );
        assert!(msg.contains("bad.toml"), "{msg}");
    }
    // A key far from every allowed one gets no suggestion, only the list.
    let msg = err(&format!(
        "{GOOD}[piers]\nheight = 1.0\nwidth = 0.3\nfoo = 1\n"
    ))
    .to_string();
    assert!(!msg.contains("did you mean"), "{msg}");
    assert!(msg.contains("allowed: height, width, courses"), "{msg}");
    // Overrides go through the same check.
    let s = Scene::from_toml_str(GOOD, "good.toml").expect("valid");
    let e = s.with_override("arch.thicknes=0.2").expect_err("typo");
    assert_eq!(e.key(), Some("arch.thicknes"));
    assert!(e.to_string().contains("did you mean `thickness`"), "{e}");
    let e = s.with_override("arhc.thickness=0.2").expect_err("typo");
    assert!(e.to_string().contains("did you mean `arch`"), "{e}");
}

#[test]
fn a_huge_malformed_line_gives_a_short_message_with_its_place() {
    // A 10 MB line, malformed near its start and near its end.
    let long = "x".repeat(10_000_000);
    let e = err(&format!("[arch]\nshape = \"circular\" radius = {long}\n"));
    let text = e.to_string();
    assert!(matches!(e, SceneError::Syntax { .. }));
    assert!(text.len() < 1000, "{} bytes", text.len());
    assert!(text.contains("line 2, column 20"), "{text}");
    let e = err(&format!("a = [{}]]\n", "1,".repeat(5_000_000)));
    let text = e.to_string();
    assert!(text.len() < 1000, "{} bytes", text.len());
    assert!(text.contains("line 1, column 10000007"), "{text}");
    // Where it stopped is quoted: the end of the list.
    assert!(text.contains("1,1,]]"), "{text}");
    // A value of the wrong type, 10 MB long, is quoted in part.
    let e = err(&format!("{GOOD}[material]\ndepth = \"{long}\"\n"));
    let text = e.to_string();
    assert!(
        text.len() < 1000 && text.contains("(10000002 characters)"),
        "{text}"
    );
}

#[test]
fn a_byte_order_mark_is_accepted_in_toml() {
    let plain = Scene::from_toml_str(GOOD, "t").expect("valid");
    let bom = Scene::from_toml_str(&format!("\u{feff}{GOOD}"), "t").expect("a BOM is no error");
    assert_eq!(
        plain.arch.as_ref().map(|a| a.thickness),
        bom.arch.as_ref().map(|a| a.thickness)
    );
}

#[test]
fn a_number_too_large_is_echoed_as_written_not_as_the_largest_integer() {
    // 2^70 as a float, in a file and as an override.
    for text in [
        GOOD.replace("voussoirs = 16", "voussoirs = 1.180591620717411303424e21"),
        GOOD.replace("voussoirs = 16", "voussoirs = 1e21"),
    ] {
        let e = err(&text);
        let msg = e.to_string();
        assert!(!msg.contains("9223372036854775807"), "{msg}");
        assert!(
            msg.contains("e21: must be a whole number from 1 to"),
            "{msg}"
        );
    }
    let base = Scene::from_toml_str(GOOD, "t").expect("valid");
    let e = base
        .with_override("arch.voussoirs=1180591620717411303424")
        .expect_err("out of range");
    let msg = e.to_string();
    assert!(!msg.contains("9223372036854775807"), "{msg}");
    assert!(
        msg.contains("1.1805916207174113e21: must be a whole number"),
        "{msg}"
    );
    // In a file, the integer literal itself is a syntax error that quotes it.
    let e = err(&GOOD.replace("voussoirs = 16", "voussoirs = 1180591620717411303424"));
    assert!(
        e.to_string().contains("voussoirs = 1180591620717411303424"),
        "{e}"
    );
}

#[test]
fn a_key_in_the_wrong_case_is_suggested_in_its_case() {
    let site = |key: &str| err(&format!("{GOOD}[site]\nag = 0.2\n{key} = 0.4\n")).to_string();
    // `Tc` is `Tc_star` without its suffix, not `FC`.
    let e = site("Tc");
    assert!(e.contains("did you mean `Tc_star`?"), "{e}");
    let e = site("fc");
    assert!(
        e.contains("did you mean `FC`? keys are case-sensitive"),
        "{e}"
    );
    let e = err(&GOOD.replace("thickness", "Thickness"));
    assert!(
        e.to_string()
            .contains("did you mean `thickness`? keys are case-sensitive"),
        "{e}"
    );
}

#[test]
fn values_with_units_are_read_in_si_and_others_say_how_to_write_them() {
    let si = Scene::from_toml_str(
        &format!("{GOOD}[material]\nunit_weight = 18000\ncompressive_strength = 5e6\n[[loads]]\ntype = \"point\"\nat = [0.0, 1.075]\nforce = [0.0, -1000.0]\n"),
        "t",
    )
    .expect("valid");
    let units = Scene::from_toml_str(
        &format!("{GOOD}[material]\nunit_weight = \"18 kN/m3\"\ncompressive_strength = \"5 MPa\"\n[[loads]]\ntype = \"point\"\nat = [\"0 mm\", \"1075 mm\"]\nforce = [\"0 kN\", \"-1 kN\"]\n")
            .replace("thickness = 0.15", "thickness = \"150 mm\""),
        "t",
    )
    .expect("valid with units");
    assert_eq!(units.material, si.material);
    assert_eq!(units.loads, si.loads);
    assert_eq!(
        units.arch.as_ref().map(|a| a.thickness),
        si.arch.as_ref().map(|a| a.thickness)
    );
    // The same multiplier.
    let lambda = |s: &Scene| {
        voussoir::analysis::analyse(s, &voussoir::analysis::Options::default())
            .expect("analysis")
            .lower
            .lambda
    };
    assert_eq!(lambda(&units), lambda(&si));
    // A string that is not a quantity of the key's kind: how to write it.
    let e = err(&format!(
        "{GOOD}[material]\ncompressive_strength = \"5 MPa x\"\n"
    ));
    let msg = e.to_string();
    assert_eq!(e.key(), Some("material.compressive_strength"));
    assert!(
        msg.contains("a number in Pa (SI), e.g. 5e6") && msg.contains("MPa, GPa, N/mm2"),
        "{msg}"
    );
    let e = err(&GOOD.replace("thickness = 0.15", "thickness = \"15 kN\""));
    assert!(e.to_string().contains("a number in m (SI)"), "{e}");
}
