//! Golden hashes of the tables: the demo pipeline and a small
//! benchmark-shaped trace and profile (the files of
//! `benches/ingest_extract.rs`, fewer rows) must give the same tables,
//! value for value, as when the hashes were taken. A hash covers a table's
//! column names, types and every value (floats bit for bit, nulls marked),
//! and its schema file's columns (name, type, unit, nullable, meaning); not
//! the run-specific metadata (provenance, paths of temporary folders).
//!
//! A change that alters a table on purpose regenerates the hashes, in a
//! commit that says why:
//!
//! ```sh
//! TRIBO_BLESS=1 cargo test golden_tables
//! ```
//!
//! which rewrites `tests/golden/tables.txt`. A refactor must leave it as it
//! is.

use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::path::Path;

use sha2::{Digest, Sha256};
use tribo::pipeline::spec::PipelineSpec;
use tribo::pipeline::Plan;
use tribo::table::{ColumnType, Table};

use crate::common;

const GOLDEN: &str = "tests/golden/tables.txt";

/// The schema file of a table (every `<stage>_figures` table shares one).
fn schema_file(table: &str) -> String {
    let own = common::root().join(format!("schemas/{table}.toml"));
    let path = match own.is_file() {
        true => own,
        false if table.ends_with("_figures") => common::root().join("schemas/figures.toml"),
        false => panic!("table {table} has no schema file"),
    };
    std::fs::read_to_string(path).unwrap()
}

/// Run-specific text replaced by stable names: the repository, the input
/// and output folders.
struct Paths<'a>(Vec<(String, &'a str)>);

impl Paths<'_> {
    fn clean(&self, s: &str) -> String {
        let mut s = s.to_string();
        for (from, to) in &self.0 {
            s = s.replace(from.as_str(), to);
        }
        s
    }
}

/// The hash of one table: columns, types, values, and its schema's columns.
fn table_hash(name: &str, t: &Table, paths: &Paths) -> String {
    let mut h = Sha256::new();
    let mut field = |bytes: &[u8]| {
        h.update((bytes.len() as u64).to_le_bytes());
        h.update(bytes);
    };
    let schema: toml::Value = toml::from_str(&schema_file(name)).unwrap();
    field(serde_json::to_string(&schema["column"]).unwrap().as_bytes());
    for c in t.column_names() {
        let ty = t.column_type(&c).expect("a column type tribo writes");
        field(c.as_bytes());
        field(ty.name().as_bytes());
        match ty {
            ColumnType::F64 => {
                for v in t.f64(&c).unwrap() {
                    field(&v.map_or(vec![0], |v| v.to_bits().to_le_bytes().to_vec()));
                }
            }
            ColumnType::I64 => {
                for v in t.i64(&c).unwrap() {
                    field(&v.map_or(vec![0], |v| v.to_le_bytes().to_vec()));
                }
            }
            ColumnType::Bool => {
                for v in t.bool(&c).unwrap() {
                    field(&[v.map_or(0, |v| 1 + u8::from(v))]);
                }
            }
            ColumnType::StrList => {
                for v in t.str_list(&c).unwrap() {
                    match v {
                        Some(l) => field(format!("l{}", l.join("\u{1f}")).as_bytes()),
                        None => field(b"n"),
                    }
                }
            }
            ColumnType::Str | ColumnType::Cat => {
                for v in t.str(&c).unwrap() {
                    match v {
                        Some(s) => field(format!("s{}", paths.clean(&s)).as_bytes()),
                        None => field(b"n"),
                    }
                }
            }
        }
    }
    format!("{:x}", h.finalize())
}

/// `case/table rows hash` for every table in `out`, sorted by table.
fn hashes(case: &str, out: &Path, paths: &Paths) -> BTreeMap<String, String> {
    let mut lines = BTreeMap::new();
    // A dataset (a folder of files) is hashed as one table, its files in
    // its manifest's order.
    for file in common::parquet_names(out) {
        let name = file.trim_end_matches(".parquet").to_string();
        let t = common::read_table(&out.join(&file));
        let hash = table_hash(&name, &t, paths);
        lines.insert(format!("{case}/{name}"), format!("{} {hash}", t.height()));
    }
    lines
}

/// A trace shaped like the benchmark's (`benches/ingest_extract.rs`):
/// a ramp to the static peak in the first second, then a sawtooth plateau.
fn bench_trace(rows: usize) -> String {
    let noise = tribo::signal::testing::gaussian_noise(rows, 0.01, 42);
    let mut s = String::with_capacity(rows * 32);
    s.push_str("t (s),Fx [mN],Fz [mN]\n");
    for (i, e) in noise.iter().enumerate() {
        let t = i as f64 * 1e-4;
        let f = if t < 1.0 {
            1200.0 * t
        } else {
            1000.0 + 50.0 * ((t * 7.0).fract() - 0.5)
        };
        let _ = writeln!(s, "{t:.4},{:.3},{:.3}", f + 100.0 * e, 2000.0 + e);
    }
    s
}

/// A self-affine profile as the benchmark's (`x [um],z [um]`).
fn bench_profile(points: usize) -> String {
    let z = tribo::extract::roughness::fractal::synthesize_self_affine(points, 0.7, 1e-6, 7);
    let mut s = String::with_capacity(points * 24);
    s.push_str("x [um],z [um]\n");
    for (i, v) in z.iter().take(points).enumerate() {
        let _ = writeln!(s, "{:.3},{:.5}", i as f64 * 0.1, v * 1e6);
    }
    s
}

/// Runs a one-stage command's pipeline over `file` into `out`.
fn run_command(stage: &str, file: &Path, out: &Path, settings: toml::Table) {
    let mut spec = PipelineSpec::single_stage(
        stage,
        vec![file.display().to_string()],
        None,
        out.display().to_string(),
        None,
    );
    *spec.settings_mut(stage) = settings;
    let plan = Plan::from_spec(&spec, Path::new("")).unwrap();
    tribo::pipeline::run(&plan, stage, &|| {}).unwrap();
}

/// A wear track (a parabolic groove on a tilted line, as in `tests/wear.rs`)
/// and an ALSFM scene with adhesion, through one pipeline: the wear and
/// ALSFM tables and figures, which the demo has not.
fn run_wear_alsfm(input: &Path, out: &Path) {
    let mut s = String::from("x (mm),z (um)\n");
    for i in 0..4800 {
        let x = 0.5e-6 * (i + 1) as f64;
        let u = (x - 0.8e-3) / 40e-6;
        let g = if u.abs() < 1.0 {
            -0.4e-6 * (1.0 - u * u)
        } else {
            0.0
        };
        let ripple = 0.008e-6 * (0.6 * (x / 3.1e-6).sin() + 0.4 * (x / 1.7e-6 + 1.0).sin());
        let z = 2e-5 * x + 1e-7 + g + ripple;
        let _ = writeln!(s, "{:.7},{:.9}", x * 1e3, z * 1e6);
    }
    std::fs::write(input.join("disc.csv"), s).unwrap();
    std::fs::write(
        input.join("samples.csv"),
        "file,sample_id,track_radius_mm,normal_force_N,laps\ndisc.csv,D1,5,10,1000\n",
    )
    .unwrap();
    let scene = common::root().join("fixtures/alsfm/sinusoid_2d_adhesion.toml");
    let text = format!(
        "stages = [\"wear\", \"alsfm\"]\n[input]\nfiles = [\"disc.csv\"]\nsamples = \"samples.csv\"\n\
         [output]\ndir = {:?}\n[alsfm]\nscene = {:?}\n",
        out.display().to_string(),
        scene.display().to_string()
    );
    let spec = PipelineSpec::from_toml(&text, Path::new("p.toml")).unwrap();
    let plan = Plan::from_spec(&spec, input).unwrap();
    tribo::pipeline::run(&plan, "test", &|| {}).unwrap();
}

fn all_hashes() -> BTreeMap<String, String> {
    let root = common::root().display().to_string();
    let dir = tempfile::tempdir().unwrap();
    let demo = dir.path().join("demo");
    common::run_demo(&demo);
    let input = dir.path().join("in");
    std::fs::create_dir_all(&input).unwrap();
    let trace = input.join("trace.csv");
    std::fs::write(&trace, bench_trace(20_000)).unwrap();
    let profile = input.join("profile.csv");
    std::fs::write(&profile, bench_profile(20_000)).unwrap();
    let bench_friction = dir.path().join("bench_friction");
    run_command("friction", &trace, &bench_friction, toml::Table::new());
    let bench_roughness = dir.path().join("bench_roughness");
    let mut detrend = toml::Table::new();
    detrend.insert("detrend".into(), "mean".into());
    run_command("roughness", &profile, &bench_roughness, detrend);
    let wear_alsfm = dir.path().join("wear_alsfm");
    run_wear_alsfm(&input, &wear_alsfm);
    let tmp = dir.path().display().to_string();
    let paths = Paths(vec![(tmp, "<tmp>"), (root, "<root>")]);
    let mut all = hashes("demo", &demo, &paths);
    all.extend(hashes("bench_friction", &bench_friction, &paths));
    all.extend(hashes("bench_roughness", &bench_roughness, &paths));
    all.extend(hashes("wear_alsfm", &wear_alsfm, &paths));
    all
}

const HEADER: &str = "\
# Golden hashes of the tables (tests/golden_tables.rs): table, rows, SHA-256
# of its columns, types, values and schema. Regenerate only when a table
# changes on purpose: TRIBO_BLESS=1 cargo test golden_tables
";

#[test]
fn golden_tables_keep_their_data() {
    let now = all_hashes();
    let mut text = HEADER.to_string();
    for (k, v) in &now {
        let _ = writeln!(text, "{k} {v}");
    }
    let path = common::root().join(GOLDEN);
    if std::env::var_os("TRIBO_BLESS").is_some() {
        std::fs::write(&path, &text).unwrap();
        eprintln!("wrote {}", path.display());
        return;
    }
    let golden = std::fs::read_to_string(&path).unwrap_or_default();
    let mut diff = Vec::new();
    let old: BTreeMap<&str, &str> = golden
        .lines()
        .filter(|l| !l.starts_with('#') && !l.is_empty())
        .filter_map(|l| l.split_once(' '))
        .collect();
    for (k, v) in &now {
        match old.get(k.as_str()) {
            Some(o) if o == v => {}
            Some(o) => diff.push(format!("changed {k}: {o} -> {v}")),
            None => diff.push(format!("new     {k}: {v}")),
        }
    }
    for k in old.keys().filter(|k| !now.contains_key(**k)) {
        diff.push(format!("gone    {k}"));
    }
    assert!(
        diff.is_empty(),
        "tables differ from {GOLDEN} (regenerate with TRIBO_BLESS=1 only for a change made on purpose):\n{}",
        diff.join("\n")
    );
}
