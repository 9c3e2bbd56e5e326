//! The validation page (`voussoir validate`, docs/validation.md): every case within its
//! tolerance, and the committed page lists every case as agreeing.

#[test]
fn every_validation_case_agrees_with_its_reference() {
    let cases = voussoir::validation::cases().expect("the cases compute");
    assert!(cases.len() >= 10, "{} cases", cases.len());
    for c in &cases {
        assert!(
            c.computed.is_finite() && c.expected.is_finite() && c.tolerance > 0.0,
            "{}: {c:?}",
            c.id
        );
        assert!(
            c.agrees(),
            "{}: voussoir {} against {} ({}), difference {:e} beyond {:e}",
            c.id,
            c.computed,
            c.expected,
            c.source,
            c.difference(),
            c.tolerance
        );
    }
    // The committed page is the output of the same cases: each listed, all agreeing.
    let page = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/docs/validation.md"))
        .expect("docs/validation.md");
    let n = cases.len();
    assert!(
        page.contains(&format!("{n} of {n} cases within tolerance")),
        "docs/validation.md is stale: regenerate it with `cargo run --release -- validate --markdown docs/validation.md`"
    );
    for c in &cases {
        assert!(
            page.contains(&format!("| {} |", c.id)),
            "docs/validation.md lacks {}: regenerate it",
            c.id
        );
    }
}

/// The command writes the page only to a `.md` file, and prints the table.
#[test]
fn validate_command_refuses_a_page_without_md() {
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_voussoir"))
        .args(["validate", "--markdown", "/tmp/voussoir-validation.html"])
        .output()
        .expect("runs");
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains(".md"), "{err}");
}
