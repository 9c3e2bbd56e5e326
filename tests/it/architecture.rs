//! The library's modules depend on each other one way only, and `docs/architecture.md` says
//! exactly how: its table of modules and their dependencies must match the `crate::` paths
//! the code uses (comments and unit-test modules aside), and the graph must have no cycle.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

type Graph = BTreeMap<String, BTreeSet<String>>;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
    for entry in std::fs::read_dir(dir).expect("read src") {
        let path = entry.expect("dir entry").path();
        if path.is_dir() {
            rust_files(&path, out);
        } else if path.extension().is_some_and(|e| e == "rs") {
            out.push(path);
        }
    }
}

/// Top-level module of a library file (None for the crate root and the binary).
fn module_of(src: &Path, file: &Path) -> Option<String> {
    let rel = file.strip_prefix(src).ok()?;
    let first = rel.components().next()?.as_os_str().to_str()?.to_string();
    match first.as_str() {
        "lib.rs" | "main.rs" | "cli" => None,
        _ => Some(first.trim_end_matches(".rs").to_string()),
    }
}

/// The `crate::NAME` paths of a file's code (not its comments, not its `#[cfg(test)]` tail).
fn crate_paths(text: &str) -> BTreeSet<String> {
    let mut out = BTreeSet::new();
    for line in text.lines() {
        let line = line.trim_start();
        if line.starts_with("#[cfg(test)]") {
            break;
        }
        if line.starts_with("//") {
            continue;
        }
        let mut rest = line;
        while let Some(k) = rest.find("crate::") {
            rest = &rest[k + "crate::".len()..];
            let name: String = rest
                .chars()
                .take_while(|c| c.is_ascii_alphanumeric() || *c == '_')
                .collect();
            if !name.is_empty() {
                out.insert(name);
            }
        }
    }
    out
}

fn code_graph() -> Graph {
    let src = root().join("src");
    let mut files = Vec::new();
    rust_files(&src, &mut files);
    let mut g = Graph::new();
    for f in files {
        let Some(m) = module_of(&src, &f) else {
            continue;
        };
        let text = std::fs::read_to_string(&f).expect("read source");
        let deps = g.entry(m.clone()).or_default();
        for d in crate_paths(&text) {
            if d != m {
                deps.insert(d);
            }
        }
    }
    g
}

/// The table of `docs/architecture.md`: rows `| `module` | `dep`, `dep` |`.
fn documented_graph() -> Graph {
    let text =
        std::fs::read_to_string(root().join("docs/architecture.md")).expect("docs/architecture.md");
    let mut g = Graph::new();
    for line in text.lines() {
        let cells: Vec<&str> = line.split('|').map(str::trim).collect();
        if cells.len() < 4 || !cells[1].starts_with('`') {
            continue;
        }
        let names = |cell: &str| -> Vec<String> {
            cell.split('`')
                .skip(1)
                .step_by(2)
                .map(|s| s.to_string())
                .collect()
        };
        let module = names(cells[1]).into_iter().next().expect("module name");
        g.insert(module, names(cells[2]).into_iter().collect());
    }
    g
}

#[test]
fn docs_architecture_matches_the_code() {
    let code = code_graph();
    let docs = documented_graph();
    assert!(!docs.is_empty(), "docs/architecture.md has no module table");
    let mut problems = Vec::new();
    for (m, deps) in &code {
        match docs.get(m) {
            None => problems.push(format!("module `{m}` is missing from the table")),
            Some(d) if d != deps => problems.push(format!(
                "`{m}`: the code depends on {deps:?}, the table says {d:?}"
            )),
            _ => {}
        }
    }
    for m in docs.keys() {
        if !code.contains_key(m) {
            problems.push(format!("the table lists `{m}`, which is no module of src/"));
        }
    }
    assert!(problems.is_empty(), "{}", problems.join("\n"));
}

#[test]
fn no_import_cycle() {
    let g = code_graph();
    // Depth-first search with colours; report the first cycle found.
    fn visit(
        g: &Graph,
        m: &str,
        state: &mut BTreeMap<String, u8>,
        path: &mut Vec<String>,
    ) -> Option<Vec<String>> {
        match state.get(m) {
            Some(2) => return None,
            Some(1) => {
                let start = path.iter().position(|p| p == m).unwrap_or(0);
                let mut cycle = path[start..].to_vec();
                cycle.push(m.to_string());
                return Some(cycle);
            }
            _ => {}
        }
        state.insert(m.to_string(), 1);
        path.push(m.to_string());
        for d in g.get(m).into_iter().flatten() {
            if let Some(c) = visit(g, d, state, path) {
                return Some(c);
            }
        }
        path.pop();
        state.insert(m.to_string(), 2);
        None
    }
    let mut state = BTreeMap::new();
    for m in g.keys() {
        let mut path = Vec::new();
        if let Some(c) = visit(&g, m, &mut state, &mut path) {
            panic!("import cycle: {}", c.join(" -> "));
        }
    }
}

/// The checker itself: comments and unit tests do not count, paths do.
#[test]
fn crate_paths_reads_code_only() {
    let text = "use crate::a::X;\n// crate::b in a comment\nlet y = crate::c::f();\n#[cfg(test)]\nuse crate::d;\n";
    let got: Vec<String> = crate_paths(text).into_iter().collect();
    assert_eq!(got, ["a", "c"]);
}

/// The model is built once per analysis: reading a scene builds nothing, `analyze` (with the
/// continuous model too) builds once, and the static minimum-thickness search once per
/// trial thickness (plus the hinges at the minimum found).
#[test]
fn the_model_is_built_once_per_analysis() {
    use voussoir::scene::{builds_on_this_thread as builds, Scene};
    let text = "[arch]\nshape = \"circular\"\nradius = 1.0\nthickness = 0.15\nvoussoirs = 16\n[[loads]]\ntype = \"line\"\nfrom_x = -0.5\nto_x = 0.2\nintensity = 1000.0\n";
    let before = builds();
    let scene = Scene::from_toml_str(text, "test").expect("scene");
    let overridden = scene.with_thickness(0.2).expect("override");
    assert_eq!(builds(), before, "reading a scene builds no model");
    assert!(overridden.loads.len() == 1);
    for continuous in [false, true] {
        let options = voussoir::analysis::Options {
            continuous,
            ..Default::default()
        };
        let start = builds();
        let a = voussoir::analysis::analyse(&scene, &options).expect("analysis");
        assert!(a.lower.lambda.is_some());
        assert_eq!(builds() - start, 1, "analyze (continuous {continuous})");
    }
    let start = builds();
    let t = voussoir::thickness::min_thickness(&scene, &Default::default()).expect("search");
    assert!(t.search.min_thickness.is_some());
    assert_eq!(
        builds() - start,
        t.search.evaluations as u64 + 1,
        "one build per trial thickness and one at the minimum"
    );
}
