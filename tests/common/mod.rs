//! Helpers shared by the integration tests.
#![allow(dead_code)]

pub mod bad;
pub mod browser;
pub mod png;
pub mod variants;
pub mod writers;
pub mod writers_afm;
pub mod writers_arrays;
pub mod writers_keyence;
pub mod writers_optical;
pub mod writers_spm;

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// The repository root: as `cargo test` gives it when it runs the test
/// binary, so that a binary built from another checkout of the same
/// sources (a shared target folder) looks here, not where it was built.
pub fn root() -> PathBuf {
    std::env::var_os("CARGO_MANIFEST_DIR")
        .map_or_else(|| PathBuf::from(env!("CARGO_MANIFEST_DIR")), PathBuf::from)
}

/// `../shared/<rel>` beside the repository (one level further up for a
/// worktree in a subfolder) when present; tests that need it skip, and
/// say so, when it is absent, as on a fresh clone.
pub fn shared(rel: &str) -> Option<PathBuf> {
    let root = root();
    let found = ["../shared", "../../shared"]
        .iter()
        .map(|s| root.join(s).join(rel))
        .find(|p| p.exists());
    if found.is_none() {
        eprintln!("skipped: ../shared/{rel} not present");
    }
    found
}

/// `../shared/data/real/<sub>` when present (see [`shared`]).
pub fn shared_real(sub: &str) -> Option<PathBuf> {
    shared(&format!("data/real/{sub}"))
}

/// `../shared/data/real2/<sub>` when present (the second batch of real
/// exports; see [`shared`]).
pub fn shared_real2(sub: &str) -> Option<PathBuf> {
    shared(&format!("data/real2/{sub}"))
}

/// Runs the tribo binary with `args` in `dir`.
pub fn tribo(dir: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_tribo"))
        .current_dir(dir)
        .args(args)
        .output()
        .expect("run tribo")
}

/// Files in a folder with an extension, sorted.
pub fn files_with_ext(dir: &Path, ext: &str) -> Vec<PathBuf> {
    let mut v: Vec<PathBuf> = std::fs::read_dir(dir)
        .unwrap()
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|e| e == ext))
        .collect();
    v.sort();
    v
}

/// Runs a pipeline file of the repository with its outputs in `out`.
pub fn run_pipeline(file: &str, out: &Path) -> tribo::pipeline::RunReport {
    let mut plan = tribo::pipeline::Plan::from_file(&root().join(file)).unwrap();
    plan.out_dir = out.to_path_buf();
    tribo::pipeline::run(&plan, "test", &|| {}).unwrap()
}

/// Runs every friction fixture through the friction stage
/// (`tests/pipelines/friction_fixtures.toml`) with its outputs in `out`.
pub fn run_friction_fixtures(out: &Path) -> tribo::pipeline::RunReport {
    run_pipeline("tests/pipelines/friction_fixtures.toml", out)
}

/// Runs the demo pipeline with its outputs in `out`.
pub fn run_demo(out: &Path) -> tribo::pipeline::RunReport {
    run_pipeline("pipelines/demo.toml", out)
}

/// Runs one table or simulation stage with `settings` as a pipeline would,
/// writing into `out`.
pub fn run_stage(
    stage: &str,
    settings: toml::Table,
    out: &Path,
    command: &str,
) -> tribo::Result<tribo::pipeline::RunReport> {
    let mut spec = tribo::pipeline::spec::PipelineSpec::single_stage(
        stage,
        Vec::new(),
        None,
        out.display().to_string(),
        None,
    );
    *spec.settings_mut(stage) = settings;
    let plan = tribo::pipeline::Plan::from_spec(&spec, Path::new(""))?;
    tribo::pipeline::run(&plan, command, &|| {})
}

/// `{ key = "path" }`, the settings of a stage that reads one file.
pub fn file_setting(key: &str, path: &Path) -> toml::Table {
    let mut t = toml::Table::new();
    t.insert(key.into(), path.display().to_string().into());
    t
}

/// Copies a folder tree.
pub fn copy_tree(from: &Path, to: &Path) {
    std::fs::create_dir_all(to).unwrap();
    for e in std::fs::read_dir(from).unwrap() {
        let p = e.unwrap().path();
        let dest = to.join(p.file_name().unwrap());
        if p.is_dir() {
            copy_tree(&p, &dest);
        } else {
            std::fs::copy(&p, &dest).unwrap();
        }
    }
}

/// The tables published in a folder: its Parquet files, and its datasets
/// (the folder `<name>` that `<name>.dataset.json` lists), by name in the
/// folder.
pub fn parquet_names(dir: &Path) -> std::collections::BTreeSet<String> {
    let name = |p: &PathBuf| p.file_name().unwrap().to_string_lossy().to_string();
    let mut names: std::collections::BTreeSet<String> =
        files_with_ext(dir, "parquet").iter().map(name).collect();
    for m in files_with_ext(dir, "json") {
        if let Some(table) = name(&m).strip_suffix(tribo::pipeline::dataset::MANIFEST) {
            names.insert(table.to_string());
        }
    }
    names
}

/// A published table as one table: a Parquet file, or a dataset folder
/// (its files in its manifest's order).
/// A float column with no nulls (a null fails the test, naming the column).
pub fn f64s(t: &tribo::table::Table, name: &str) -> Vec<f64> {
    t.f64(name)
        .unwrap()
        .into_iter()
        .map(|v| v.unwrap_or_else(|| panic!("null in {name}")))
        .collect()
}

pub fn read_table(path: &Path) -> tribo::table::Table {
    tribo::pipeline::dataset::read_table(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

/// The published table `name` of the output folder `out` (a file, or a
/// dataset's folder), as one table.
pub fn table_in(out: &Path, name: &str) -> tribo::table::Table {
    let def = tribo::pipeline::registry::find(name).unwrap_or_else(|| panic!("no table {name}"));
    read_table(&def.path_in(out))
}

/// The two folders hold the same tables with the same columns and values.
pub fn same_tables(a: &Path, b: &Path) {
    let names = parquet_names(a);
    assert!(names.len() >= 2, "{names:?}");
    assert_eq!(names, parquet_names(b));
    for name in &names {
        let ta = read_table(&a.join(name));
        let tb = read_table(&b.join(name));
        assert_eq!(ta.column_names(), tb.column_names(), "{name}");
        assert_eq!(ta.height(), tb.height(), "{name}");
        for col in ta.column_names() {
            let same = match ta.column_type(&col).unwrap() {
                tribo::table::ColumnType::F64 => bits(&ta, &col) == bits(&tb, &col),
                tribo::table::ColumnType::I64 => ta.i64(&col).unwrap() == tb.i64(&col).unwrap(),
                tribo::table::ColumnType::Str => ta.str(&col).unwrap() == tb.str(&col).unwrap(),
                // The dictionary too: readers see it as the column's type.
                tribo::table::ColumnType::Cat => {
                    ta.str(&col).unwrap() == tb.str(&col).unwrap()
                        && ta.categories(&col) == tb.categories(&col)
                }
                tribo::table::ColumnType::Bool => ta.bool(&col).unwrap() == tb.bool(&col).unwrap(),
                tribo::table::ColumnType::StrList => {
                    ta.str_list(&col).unwrap() == tb.str_list(&col).unwrap()
                }
            };
            assert!(same, "{name}: column {col} differs");
        }
    }
}

/// Each row's status as people read it: `ok`, or every code with its
/// detail (`status_detail`).
pub fn status_texts(t: &tribo::table::Table) -> Vec<Option<String>> {
    t.str("status_detail")
        .unwrap()
        .into_iter()
        .map(|d| Some(d.unwrap_or_else(|| "ok".into())))
        .collect()
}

/// Float columns compared bit for bit (NaN equal to NaN).
pub fn bits(t: &tribo::table::Table, col: &str) -> Vec<Option<u64>> {
    let v = t.f64(col).unwrap();
    v.into_iter().map(|x| x.map(f64::to_bits)).collect()
}

/// The distinct file names in a table's `source` column.
pub fn sources(dir: &Path, table: &str) -> std::collections::BTreeSet<String> {
    tribo::table::Table::read_parquet(&dir.join(format!("{table}.parquet")))
        .unwrap()
        .0
        .str("source")
        .unwrap()
        .into_iter()
        .map(|s| {
            let s = s.unwrap();
            let s = s.split('#').next().unwrap();
            Path::new(s)
                .file_name()
                .unwrap()
                .to_string_lossy()
                .to_string()
        })
        .collect()
}

/// The per-file stages and the fits the lab-folder tests run.
pub const LAB_STAGES: &[&str] = &[
    "friction",
    "roughness",
    "tensile",
    "tensile-summary",
    "coulomb",
    "ice",
];

/// The pipeline of the lab-folder tests: every extraction stage and the
/// fits over `lab/*/*`, with `extra` appended (more stages' settings).
pub fn lab_pipeline(stages: &[&str], extra: &str) -> String {
    let list: Vec<String> = stages.iter().map(|s| format!("\"{s}\"")).collect();
    format!(
        "stages = [{}]\n[input]\nfiles = [\"lab/*/*\"]\nsamples = \"lab/samples.csv\"\n\
         [output]\ndir = \"out\"\n[coulomb]\nby = [\"sample_id\", \"pattern\"]\n{extra}",
        list.join(", ")
    )
}

/// A temporary folder holding a copy of `fixtures/lab` as `lab/` and
/// `pipeline` as `p.toml`.
pub fn lab_folder(pipeline: &str) -> tempfile::TempDir {
    let dir = tempfile::tempdir().unwrap();
    copy_tree(&root().join("fixtures/lab"), &dir.path().join("lab"));
    std::fs::write(dir.path().join("p.toml"), pipeline).unwrap();
    dir
}

/// The `files` table of `out` (checked against its schema), by source:
/// every column as text ("" for null).
pub fn files_table(
    out: &Path,
) -> std::collections::BTreeMap<String, std::collections::BTreeMap<String, String>> {
    let (t, _) = tribo::table::Table::read_parquet(&out.join("files.parquet")).unwrap();
    tribo::pipeline::registry::schema("files")
        .unwrap()
        .check(&t)
        .unwrap();
    let source = t.str("source").unwrap();
    let mut rows = std::collections::BTreeMap::new();
    for (i, s) in source.iter().enumerate() {
        let mut row = std::collections::BTreeMap::new();
        for c in t.column_names() {
            let v = match c.as_str() {
                "size_bytes" => t.i64(&c).unwrap()[i].map(|n| n.to_string()),
                _ => t.str(&c).unwrap()[i].clone(),
            };
            row.insert(c, v.unwrap_or_default());
        }
        rows.insert(s.clone().unwrap(), row);
    }
    rows
}

/// Runs the friction, roughness and tensile stages over the real exports
/// in `../shared/data/<folders>` (two levels deep) into `dir/out`, and
/// returns that folder; `None`, saying so, when `../shared` is absent.
pub fn run_real_exports(folders: &[&str], dir: &Path) -> Option<PathBuf> {
    let shared = root().join("../shared/data");
    if !shared.is_dir() {
        eprintln!("skipped: {} not present", shared.display());
        return None;
    }
    let globs: Vec<String> = folders
        .iter()
        .flat_map(|f| ["*/*", "*/*/*"].map(|g| format!("\"{}/{f}/{g}\"", shared.display())))
        .collect();
    let out = dir.join("out");
    let pipeline = dir.join("real.toml");
    let text = format!(
        "stages = [\"friction\", \"roughness\", \"tensile\"]\n\
         [input]\nfiles = [{}]\n[output]\ndir = \"{}\"\n",
        globs.join(", "),
        out.display()
    );
    std::fs::write(&pipeline, text).unwrap();
    let plan = tribo::pipeline::Plan::from_file(&pipeline).unwrap();
    tribo::pipeline::run(&plan, "test", &|| {}).unwrap();
    Some(out)
}
