//! The layers of the crate point one way only:
//! cli → pipeline → stages → {extract, fit, simulate, report}
//!   → {models, signal, crosscheck, ingest, plot} → {units, table, schema, error, hash, paths}.
//! Within one crate nothing stops a lower module from importing a higher
//! one, so this test reads every source file and fails on such an import,
//! and on a cycle between top-level modules of the same layer.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

/// Each top-level module and its layer (higher imports lower).
const LAYERS: &[(&str, u8)] = &[
    ("error", 0),
    ("units", 0),
    ("table", 0),
    ("schema", 0),
    ("hash", 0),
    ("paths", 0),
    ("status", 0),
    ("models", 1),
    ("signal", 1),
    ("crosscheck", 1),
    ("ingest", 1),
    ("plot", 1),
    ("extract", 2),
    ("fit", 2),
    ("simulate", 2),
    ("report", 2),
    ("stages", 3),
    ("pipeline", 4),
    ("cli", 5),
    ("main", 5),
    ("lib", 6),
];

fn layer(module: &str) -> Option<u8> {
    LAYERS.iter().find(|(m, _)| *m == module).map(|(_, l)| *l)
}

fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
    for e in std::fs::read_dir(dir).unwrap() {
        let p = e.unwrap().path();
        if p.is_dir() {
            rust_files(&p, out);
        } else if p.extension().is_some_and(|x| x == "rs") {
            out.push(p);
        }
    }
}

/// The module path of a source file (`src/ingest/formats/t150.rs` →
/// `["ingest", "formats", "t150"]`).
fn module_path(src: &Path, file: &Path) -> Vec<String> {
    let rel = file.strip_prefix(src).unwrap();
    let mut parts: Vec<String> = rel
        .iter()
        .map(|c| c.to_string_lossy().trim_end_matches(".rs").to_string())
        .collect();
    if parts.last().is_some_and(|p| p == "mod") {
        parts.pop();
    }
    parts
}

/// Top-level modules a line of code refers to: `crate::x`, `tribo::x`, or
/// `super::…` climbing to the crate root.
fn references(line: &str, path: &[String]) -> Vec<String> {
    let mut out = Vec::new();
    let ident = |s: &str| -> String {
        s.chars()
            .take_while(|c| c.is_alphanumeric() || *c == '_')
            .collect()
    };
    for prefix in ["crate::", "tribo::"] {
        for (i, _) in line.match_indices(prefix) {
            let before = line[..i].chars().last();
            if before.is_some_and(|c| c.is_alphanumeric() || c == '_') {
                continue;
            }
            out.push(ident(&line[i + prefix.len()..]));
        }
    }
    for (i, _) in line.match_indices("super::") {
        if line[..i].ends_with("super::") {
            continue;
        }
        let mut rest = &line[i..];
        let mut ups = 0;
        while let Some(r) = rest.strip_prefix("super::") {
            ups += 1;
            rest = r;
        }
        if path.len() <= ups {
            out.push(ident(rest));
        }
    }
    out.retain(|m| layer(m).is_some());
    out
}

#[test]
fn lower_layers_never_import_higher_ones() {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut files = Vec::new();
    rust_files(&src, &mut files);
    let mut bad = Vec::new();
    let mut edges: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
    for f in &files {
        let path = module_path(&src, f);
        let top = path[0].clone();
        let Some(own) = layer(&top) else {
            panic!(
                "{}: module '{top}' has no layer in tests/layering.rs",
                f.display()
            );
        };
        let text = std::fs::read_to_string(f).unwrap();
        for (n, line) in text.lines().enumerate() {
            if line.trim_start().starts_with("//") {
                continue;
            }
            for m in references(line, &path) {
                if m != top && layer(&m).unwrap() > own {
                    bad.push(format!("{}:{}: {top} imports {m}", f.display(), n + 1));
                }
                if m != top {
                    edges.entry(top.clone()).or_default().insert(m);
                }
            }
        }
    }
    assert!(bad.is_empty(), "imports pointing up:\n{}", bad.join("\n"));
    for (a, targets) in &edges {
        for b in targets {
            let back = edges.get(b).is_some_and(|t| t.contains(a));
            assert!(!back, "modules '{a}' and '{b}' import each other");
        }
    }
}

#[test]
fn the_checker_sees_imports() {
    let p = |s: &str| s.split('/').map(String::from).collect::<Vec<_>>();
    assert_eq!(
        references("use crate::pipeline::Plan;", &p("ingest/kind")),
        ["pipeline"]
    );
    assert_eq!(
        references("use super::super::stages::X;", &p("ingest/kind")),
        ["stages"]
    );
    assert!(references("use super::roles::Role;", &p("ingest/kind")).is_empty());
    assert_eq!(references("use super::hash::X;", &p("schema")), ["hash"]);
    assert_eq!(
        references("tribo::table::Table::new()", &p("cli/run")),
        ["table"]
    );
}
