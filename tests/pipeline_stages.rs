//! Stages other than friction in pipeline files: the tensile stage reads the
//! same fibres as `tribo tensile` and gives the same table.

use crate::common;

use tribo::table::Table;

#[test]
fn tensile_stage_in_a_pipeline_matches_the_command() {
    let dir = tempfile::tempdir().unwrap();
    let fx = common::root().join("fixtures/tensile");
    let pipeline = dir.path().join("p.toml");
    std::fs::write(
        &pipeline,
        format!(
            "stages = [\"tensile\"]\n[input]\nfiles = [\"{0}/t150_*.txt\"]\nsamples = \"{0}/samples.csv\"\n[output]\ndir = \"pipe\"\n",
            fx.display()
        ),
    )
    .unwrap();
    let o = common::tribo(dir.path(), &["run", "p.toml"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let files: Vec<String> = common::files_with_ext(&fx, "txt")
        .iter()
        .filter(|p| {
            p.file_name()
                .unwrap()
                .to_string_lossy()
                .starts_with("t150_")
        })
        .map(|p| p.display().to_string())
        .collect();
    let mut args = vec!["tensile".to_string()];
    args.extend(files);
    args.extend([
        "--samples".into(),
        fx.join("samples.csv").display().to_string(),
        "--out".into(),
        "cmd".into(),
    ]);
    let o = common::tribo(
        dir.path(),
        &args.iter().map(String::as_str).collect::<Vec<_>>(),
    );
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let (a, _) = Table::read_parquet(&dir.path().join("pipe/tensile.parquet")).unwrap();
    let (b, _) = Table::read_parquet(&dir.path().join("cmd/tensile.parquet")).unwrap();
    assert_eq!(a.height(), 2);
    for col in ["strength_MPa", "toughness_J_per_g", "strain_at_break"] {
        assert_eq!(a.f64(col).unwrap(), b.f64(col).unwrap(), "{col}");
    }
    assert!(a
        .f64("strength_MPa")
        .unwrap()
        .iter()
        .all(|v| v.is_some_and(|v| v > 0.0)));
}

/// A file that fails in two stages is one failed file: the summary counts
/// files, `errors.parquet` lists each (file, stage), and the good file's
/// results are kept. Files go only to the stages that read their kind, so
/// both files are given to both stages by the stages' own `files` lists.
#[test]
fn a_file_failing_in_two_stages_counts_once() {
    let dir = tempfile::tempdir().unwrap();
    // Readable, but neither a friction trace (no friction force) nor a
    // profile with units.
    std::fs::write(dir.path().join("bad.csv"), "a,b\n1,2\n2,3\n3,4\n").unwrap();
    let good = common::root().join("fixtures/roughness/dektak/dektak-1.csv");
    let both = format!("files = [\"bad.csv\", \"{}\"]\n", good.display());
    std::fs::write(
        dir.path().join("p.toml"),
        format!(
            "stages = [\"friction\", \"roughness\"]\n[output]\ndir = \"out\"\n\
             [friction]\n{both}[roughness]\n{both}"
        ),
    )
    .unwrap();
    let o = common::tribo(dir.path(), &["run", "p.toml"]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(1), "{err}");
    // bad.csv fails both stages, the Dektak profile fails friction only.
    assert!(err.contains("0 of 2 files processed, 2 failed"), "{err}");
    let (e, _) = Table::read_parquet(&dir.path().join("out/errors.parquet")).unwrap();
    assert_eq!(e.height(), 3, "{:?}", e.str("message").unwrap());
    let (r, _) = Table::read_parquet(&dir.path().join("out/roughness.parquet")).unwrap();
    assert_eq!(r.height(), 1);
}
