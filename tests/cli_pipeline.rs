//! Every command is a one-stage pipeline: `tribo friction|roughness|
//! tensile|tensile summarize|fit …|simulate …` and the same stage declared
//! in a pipeline file over the same inputs write the same tables, value for
//! value (only run metadata such as the command line differs).

use std::collections::BTreeSet;
use std::path::Path;

use tribo::table::{ColumnType, Table};

use crate::common;

/// A working folder holding copies of `fixtures/` and `pipelines/`, so that
/// both runs see the same relative paths.
fn workspace() -> tempfile::TempDir {
    let dir = tempfile::tempdir().unwrap();
    for sub in ["fixtures", "pipelines"] {
        copy_tree(&common::root().join(sub), &dir.path().join(sub));
    }
    dir
}

fn copy_tree(from: &Path, to: &Path) {
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

/// Runs tribo in `dir` and asserts its exit code.
fn run(dir: &Path, args: &[&str], code: i32) {
    let o = common::tribo(dir, args);
    assert_eq!(
        o.status.code(),
        Some(code),
        "tribo {}: {}",
        args.join(" "),
        String::from_utf8_lossy(&o.stderr)
    );
}

/// Runs the command with `--out cli`, then `p.toml` (a pipeline of one stage)
/// with `dir = "pipe"`, and compares every table the two wrote.
fn same_as_pipeline(dir: &Path, args: &[&str], pipeline: &str, code: i32) {
    let mut cli: Vec<&str> = args.to_vec();
    cli.extend(["--out", "cli"]);
    run(dir, &cli, code);
    let toml = format!("{pipeline}\n[output]\ndir = \"pipe\"\n");
    std::fs::write(dir.join("p.toml"), toml).unwrap();
    run(dir, &["run", "p.toml"], code);
    same_tables(&dir.join("cli"), &dir.join("pipe"));
}

fn parquet_names(dir: &Path) -> BTreeSet<String> {
    common::files_with_ext(dir, "parquet")
        .iter()
        .map(|p| p.file_name().unwrap().to_string_lossy().to_string())
        .collect()
}

/// The two folders hold the same tables with the same columns and values.
fn same_tables(a: &Path, b: &Path) {
    let names = parquet_names(a);
    assert!(names.len() >= 2, "{names:?}");
    assert_eq!(names, parquet_names(b));
    for name in &names {
        let (ta, _) = Table::read_parquet(&a.join(name)).unwrap();
        let (tb, _) = Table::read_parquet(&b.join(name)).unwrap();
        assert_eq!(ta.column_names(), tb.column_names(), "{name}");
        assert_eq!(ta.height(), tb.height(), "{name}");
        for col in ta.column_names() {
            let same = match ta.column_type(&col).unwrap() {
                ColumnType::F64 => bits(&ta, &col) == bits(&tb, &col),
                ColumnType::I64 => ta.i64(&col).unwrap() == tb.i64(&col).unwrap(),
                ColumnType::Str => ta.str(&col).unwrap() == tb.str(&col).unwrap(),
                ColumnType::Bool => ta.bool(&col).unwrap() == tb.bool(&col).unwrap(),
            };
            assert!(same, "{name}: column {col} differs");
        }
    }
}

/// Float columns compared bit for bit (NaN equal to NaN).
fn bits(t: &Table, col: &str) -> Vec<Option<u64>> {
    let v = t.f64(col).unwrap();
    v.into_iter().map(|x| x.map(f64::to_bits)).collect()
}

#[test]
fn friction_command_equals_the_friction_stage() {
    let w = workspace();
    same_as_pipeline(
        w.path(),
        &[
            "friction",
            "fixtures/friction/cetr_umt/*.csv",
            "fixtures/friction/*.tsv",
            "--samples",
            "fixtures/friction/samples.csv",
        ],
        r#"stages = ["friction"]
[input]
files = ["fixtures/friction/cetr_umt/*.csv", "fixtures/friction/*.tsv"]
samples = "fixtures/friction/samples.csv""#,
        0,
    );
}

#[test]
fn roughness_command_equals_the_roughness_stage() {
    let w = workspace();
    same_as_pipeline(
        w.path(),
        &[
            "roughness",
            "fixtures/roughness/dektak/dektak-1.csv",
            "fixtures/roughness/nanovea/test1.txt",
            "--cutoff",
            "0.25mm",
        ],
        r#"stages = ["roughness"]
[input]
files = ["fixtures/roughness/dektak/dektak-1.csv", "fixtures/roughness/nanovea/test1.txt"]
[roughness]
cutoff = "0.25mm""#,
        0,
    );
}

#[test]
fn tensile_command_equals_the_tensile_stage() {
    let w = workspace();
    same_as_pipeline(
        w.path(),
        &[
            "tensile",
            "fixtures/tensile/t150_*.txt",
            "--samples",
            "fixtures/tensile/samples.csv",
        ],
        r#"stages = ["tensile"]
[input]
files = ["fixtures/tensile/t150_*.txt"]
samples = "fixtures/tensile/samples.csv""#,
        0,
    );
}

/// The table stages read the demo's outputs, written first into `demo/`.
fn with_demo_outputs() -> tempfile::TempDir {
    let w = workspace();
    run(
        w.path(),
        &["run", "pipelines/demo.toml", "--out", "demo"],
        0,
    );
    w
}

#[test]
fn table_commands_equal_their_stages() {
    let w = with_demo_outputs();
    let cases: [(&[&str], &str); 3] = [
        (
            &["tensile", "summarize", "demo/tensile.parquet"],
            r#"stages = ["tensile-summary"]
[tensile-summary]
inputs = { tensile = "demo/tensile.parquet" }"#,
        ),
        (
            &[
                "fit",
                "coulomb",
                "demo/friction.parquet",
                "--samples",
                "fixtures/lab/samples.csv",
                "--by",
                "sample_id",
                "--by",
                "pattern",
            ],
            r#"stages = ["coulomb"]
[coulomb]
inputs = { friction = "demo/friction.parquet" }
samples = "fixtures/lab/samples.csv"
by = ["sample_id", "pattern"]"#,
        ),
        (
            &[
                "fit",
                "ice",
                "demo/friction_steps.parquet",
                "--roughness",
                "demo/roughness.parquet",
            ],
            r#"stages = ["ice"]
[ice]
inputs = { friction_steps = "demo/friction_steps.parquet", roughness = "demo/roughness.parquet" }"#,
        ),
    ];
    for (args, pipeline) in cases {
        for out in ["cli", "pipe"] {
            let _ = std::fs::remove_dir_all(w.path().join(out));
        }
        same_as_pipeline(w.path(), args, pipeline, 0);
    }
}

#[test]
fn simulate_commands_equal_their_stages() {
    let w = workspace();
    let cases: [(&[&str], &str); 3] = [
        (
            &["simulate", "ice", "--t=-10,-2", "--phi", "7.3"],
            r#"stages = ["ice-grid"]
[ice-grid]
t = [-10.0, -2.0]
phi = [7.3]"#,
        ),
        (
            &["simulate", "alsfm", "fixtures/alsfm/case2_light_load.toml"],
            r#"stages = ["alsfm"]
[alsfm]
scene = "fixtures/alsfm/case2_light_load.toml""#,
        ),
        (
            &[
                "simulate",
                "spring-block",
                "pipelines/demo/spring_block_study.toml",
            ],
            r#"stages = ["spring-block"]
[spring-block]
scene = "pipelines/demo/spring_block_study.toml""#,
        ),
    ];
    for (args, pipeline) in cases {
        for out in ["cli", "pipe"] {
            let _ = std::fs::remove_dir_all(w.path().join(out));
        }
        same_as_pipeline(w.path(), args, pipeline, 0);
    }
}
