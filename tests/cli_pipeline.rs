//! Every command is a one-stage pipeline: `tribo friction|roughness|
//! tensile|tensile summarize|fit …|simulate …` and the same stage declared
//! in a pipeline file over the same inputs write the same tables, value for
//! value (only run metadata such as the command line differs).

use std::path::Path;

use crate::common;

/// A working folder holding copies of `fixtures/` and `pipelines/`, so that
/// both runs see the same relative paths.
fn workspace() -> tempfile::TempDir {
    let dir = tempfile::tempdir().unwrap();
    for sub in ["fixtures", "pipelines"] {
        common::copy_tree(&common::root().join(sub), &dir.path().join(sub));
    }
    dir
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
    common::same_tables(&dir.join("cli"), &dir.join("pipe"));
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
