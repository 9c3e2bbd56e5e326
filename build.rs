//! Build script: embeds the national seismic hazard grid of NTC 2008 Allegato B (Tabella 1:
//! 10,751 nodes, ag / F0 / Tc* at nine return periods) when its data file is found, so that
//! `[site] latitude` / `longitude` work from any directory with no network (src/hazard.rs).
//!
//! The file is the digital table `spettri2008.csv` (columns `OBJECTID, ID, LON, LAT,
//! T30ag, T30F0, T30Tc, ..., T2475Tc`; `data/hazard/README.md` says where it comes from). It is
//! looked for, in order, at `$VOUSSOIR_HAZARD_GRID`, `data/hazard/ntc2008_grid.csv`,
//! `shared/hazard/ntc2008_grid.csv` and `../shared/hazard/ntc2008_grid.csv` (paths relative to
//! this package). Found, it is checked (10,751 rows of 31 finite numbers, unique node ids, the
//! grid's row-major numbering) and written to `$OUT_DIR/ntc2008_grid.bin` as little-endian
//! f64 rows `[id, lon, lat, 27 values]`, and `cfg(hazard_grid)` is set; a file that fails the
//! check fails the build. Not found, the embedded table is empty and `[site] latitude` is
//! refused with `HazardError::NotBundled`.

use std::env;
use std::fs;
use std::path::{Path, PathBuf};

/// Nodes of Allegato B, Tabella 1.
const NODES: usize = 10_751;
/// Columns of a row: OBJECTID, ID, LON, LAT, then (ag, F0, Tc*) at nine return periods.
const COLUMNS: usize = 31;
/// The header the table must have (after any line above it, such as a "TR = 30" band).
const HEADER: [&str; 4] = ["OBJECTID", "ID", "LON", "LAT"];
/// Node ids run row by row, west to east, this many to a row (id + 1 is the node to the
/// east, id + ROW the node to the south); checked below and relied on by src/hazard.rs.
const ROW: i64 = 222;

fn main() {
    println!("cargo::rustc-check-cfg=cfg(hazard_grid)");
    println!("cargo::rerun-if-changed=build.rs");
    println!("cargo::rerun-if-env-changed=VOUSSOIR_HAZARD_GRID");
    let root =
        PathBuf::from(env::var("CARGO_MANIFEST_DIR").expect("cargo sets CARGO_MANIFEST_DIR"));
    let out =
        PathBuf::from(env::var("OUT_DIR").expect("cargo sets OUT_DIR")).join("ntc2008_grid.bin");
    let mut candidates: Vec<PathBuf> = Vec::new();
    if let Some(p) = env::var_os("VOUSSOIR_HAZARD_GRID") {
        candidates.push(PathBuf::from(p));
    }
    for rel in [
        "data/hazard/ntc2008_grid.csv",
        "shared/hazard/ntc2008_grid.csv",
        "../shared/hazard/ntc2008_grid.csv",
    ] {
        candidates.push(root.join(rel));
    }
    // Watch each candidate, or the nearest folder of it that exists (at most two levels up,
    // so a grid put there later is seen): a missing path would make cargo rerun this script,
    // and rebuild the crate, on every build.
    for c in &candidates {
        if let Some(w) = c.ancestors().take(3).find(|a| a.exists()) {
            println!("cargo::rerun-if-changed={}", w.display());
        }
    }
    match candidates.iter().find(|c| c.is_file()) {
        Some(path) => {
            let bytes = match convert(path) {
                Ok(b) => b,
                Err(e) => panic!("{}: not the NTC 2008 hazard grid: {e}", path.display()),
            };
            fs::write(&out, bytes).expect("write the embedded grid to OUT_DIR");
            println!("cargo::rustc-cfg=hazard_grid");
        }
        None => {
            fs::write(&out, []).expect("write the (empty) embedded grid to OUT_DIR");
            println!(
                "cargo::warning=NTC 2008 hazard grid not found (data/hazard/README.md): [site] latitude/longitude will be refused by this build"
            );
        }
    }
}

/// Read and check the table; its rows as little-endian f64 `[id, lon, lat, 27 values]`.
fn convert(path: &Path) -> Result<Vec<u8>, String> {
    let text = fs::read_to_string(path).map_err(|e| format!("cannot read it: {e}"))?;
    let mut lines = text.lines().enumerate();
    // Skip to the header row (the digital table comes with or without a "TR = 30" band).
    loop {
        let Some((n, line)) = lines.next() else {
            return Err("no header row OBJECTID, ID, LON, LAT, ...".into());
        };
        let cells: Vec<String> = line
            .split(',')
            .map(|c| c.trim().trim_matches('"').to_string())
            .collect();
        if cells.len() >= 4 && cells[..4] == HEADER {
            if cells.len() != COLUMNS {
                return Err(format!(
                    "line {}: the header has {} columns, not {COLUMNS}",
                    n + 1,
                    cells.len()
                ));
            }
            break;
        }
    }
    let mut rows: Vec<[f64; 30]> = Vec::with_capacity(NODES);
    for (n, line) in lines {
        if line.trim().is_empty() {
            continue;
        }
        let cells: Vec<&str> = line.split(',').map(str::trim).collect();
        if cells.len() != COLUMNS {
            return Err(format!(
                "line {}: {} columns, not {COLUMNS}",
                n + 1,
                cells.len()
            ));
        }
        let mut row = [0.0; 30];
        for (k, cell) in cells[1..].iter().enumerate() {
            let x: f64 = cell
                .parse()
                .map_err(|_| format!("line {}: `{cell}` is not a number", n + 1))?;
            if !x.is_finite() || (k >= 3 && x <= 0.0) {
                return Err(format!(
                    "line {}: `{cell}` is not a finite positive value",
                    n + 1
                ));
            }
            row[k] = x;
        }
        if row[0].fract() != 0.0 {
            return Err(format!(
                "line {}: node id {} is not an integer",
                n + 1,
                row[0]
            ));
        }
        rows.push(row);
    }
    if rows.len() != NODES {
        return Err(format!("{} nodes, not the annex's {NODES}", rows.len()));
    }
    let mut ids: Vec<i64> = rows.iter().map(|r| r[0] as i64).collect();
    ids.sort_unstable();
    if ids.windows(2).any(|w| w[0] == w[1]) {
        return Err("a node id appears twice".into());
    }
    // The numbering: the node `id + 1` lies about 5.5 km east, `id + ROW` about 5.5 km south.
    let by_id: std::collections::HashMap<i64, &[f64; 30]> =
        rows.iter().map(|r| (r[0] as i64, r)).collect();
    for r in &rows {
        let id = r[0] as i64;
        if let Some(e) = by_id.get(&(id + 1)) {
            let (dx, dy) = (e[1] - r[1], e[2] - r[2]);
            if !(0.05..0.09).contains(&dx) || dy.abs() > 0.01 {
                return Err(format!(
                    "node {} is not {ROW}-wide row-major: node {} is not its east neighbour",
                    id,
                    id + 1
                ));
            }
        }
        if let Some(s) = by_id.get(&(id + ROW)) {
            let (dx, dy) = (s[1] - r[1], s[2] - r[2]);
            if !(-0.06..-0.04).contains(&dy) || dx.abs() > 0.01 {
                return Err(format!(
                    "node {} is not {ROW}-wide row-major: node {} is not its south neighbour",
                    id,
                    id + ROW
                ));
            }
        }
    }
    let mut bytes = Vec::with_capacity(rows.len() * 30 * 8);
    for r in &rows {
        for x in r {
            bytes.extend_from_slice(&x.to_le_bytes());
        }
    }
    Ok(bytes)
}
