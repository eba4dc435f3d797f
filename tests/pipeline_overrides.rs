//! Column and unit overrides in a pipeline file make an odd export usable:
//! German column names without units, read through `[[ingest.override]]`.

use std::path::Path;
use std::process::Output;

use crate::common;

use tribo::table::Table;

#[test]
fn overrides_name_columns_and_units() {
    let dir = tempfile::tempdir().unwrap();
    write_legacy(dir.path(), "Zeit;Kraft;Last");
    std::fs::write(
        dir.path().join("p.toml"),
        r#"
[input]
files = ["legacy_*.txt"]
[output]
dir = "out"
[[ingest.override]]
files = "legacy_*.txt"
columns = { time = "Zeit", friction_force = "Kraft", normal_force = "Last" }
units = { Zeit = "s", Kraft = "mN", Last = "mN" }
"#,
    )
    .unwrap();
    let o = common::tribo(dir.path(), &["run", "p.toml"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let (t, _) = Table::read_parquet(&dir.path().join("out/friction.parquet")).unwrap();
    assert_eq!(t.str("status").unwrap()[0].as_deref(), Some("ok"));
    // 600 mN / 1000 mN and 500 mN / 1000 mN, noise-free. The window may
    // start on the last samples of the decay inside the 3 % band (at most
    // +15 mN on a few of ~280 samples: below 2e-4 in μ).
    assert!((t.f64("mu_static").unwrap()[0].unwrap() - 0.6).abs() < 1e-9);
    let mu_d = t.f64("mu_dynamic").unwrap()[0].unwrap();
    assert!((0.5..0.5002).contains(&mu_d), "{mu_d}");
    assert!((t.f64("normal_force_N").unwrap()[0].unwrap() - 1.0).abs() < 1e-12);

    // Without the override, the missing units are a clear error.
    std::fs::write(
        dir.path().join("q.toml"),
        "[input]\nfiles = [\"legacy_*.txt\"]\n[output]\ndir = \"out2\"\n",
    )
    .unwrap();
    let o = common::tribo(dir.path(), &["run", "q.toml"]);
    assert_eq!(o.status.code(), Some(1));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains("legacy_1.txt") && err.contains("no friction_force column"),
        "{err}"
    );
}

/// Writes `legacy_1.txt` in `dir`: a stick then slip at 600 and 500 (in the
/// force unit) under a load of 1000, with decimal commas, under `head`.
fn write_legacy(dir: &Path, head: &str) {
    let mut text = format!("{head}\n");
    for i in 0..400 {
        let t = i as f64 * 0.01;
        let f = if t < 1.0 {
            600.0 * t
        } else if t < 1.1 {
            600.0 - 1000.0 * (t - 1.0)
        } else {
            500.0
        };
        text.push_str(&format!(
            "{};{};{}\n",
            format!("{t:.2}").replace('.', ","),
            format!("{f:.1}").replace('.', ","),
            "1000,0"
        ));
    }
    std::fs::write(dir.join("legacy_1.txt"), &text).unwrap();
}

/// Runs the pipeline `text`, written as `name` in `dir`.
fn run_pipeline(dir: &Path, name: &str, text: &str) -> (Output, String) {
    std::fs::write(dir.join(name), text).unwrap();
    let o = common::tribo(dir, &["run", name]);
    let err = String::from_utf8_lossy(&o.stderr).to_string();
    (o, err)
}

const LEGACY: &str = "[input]\nfiles = [\"legacy_*.txt\"]\n";

#[test]
fn an_override_glob_that_matches_no_file_stops_the_run() {
    let dir = tempfile::tempdir().unwrap();
    write_legacy(dir.path(), "Zeit;Kraft;Last");
    let (o, err) = run_pipeline(
        dir.path(),
        "p.toml",
        &format!(
            "{LEGACY}[output]\ndir = \"out\"\n[[ingest.override]]\n\
             files = \"legacy_2*.txt\"\nunits = {{ Zeit = \"s\", Kraft = \"mN\", Last = \"mN\" }}\n"
        ),
    );
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(err.contains("'legacy_2*.txt' matches none"), "{err}");
    assert!(!dir.path().join("out").exists(), "nothing written");
}

#[test]
fn a_manifest_row_without_its_file_warns_or_with_strict_stops_the_run() {
    let dir = tempfile::tempdir().unwrap();
    write_legacy(dir.path(), "Zeit [s];Reibkraft [mN];Normalkraft [mN]");
    std::fs::write(
        dir.path().join("samples.csv"),
        "file,sample_id\nlegacy_1.txt,A\nlegacy_9.txt,B\n",
    )
    .unwrap();
    let input = format!("{LEGACY}samples = \"samples.csv\"\n");
    let (o, err) = run_pipeline(
        dir.path(),
        "p.toml",
        &format!("{input}[output]\ndir = \"out\"\n"),
    );
    assert_eq!(o.status.code(), Some(0), "{err}");
    assert!(
        err.contains("warning: ")
            && err
                .contains("samples.csv:3: the sample row for 'legacy_9.txt' matches no input file"),
        "{err}"
    );
    assert!(!err.contains("legacy_1.txt'"), "{err}");
    let (o, err) = run_pipeline(
        dir.path(),
        "q.toml",
        &format!("{input}strict = true\n[output]\ndir = \"out2\"\n"),
    );
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(
        err.contains("'legacy_9.txt' matches no input file"),
        "{err}"
    );
    assert!(!dir.path().join("out2").exists(), "nothing written");
}

/// An override of `Reibkraft` to mN where the header says N fails the file,
/// naming both units; `force = true` applies it (the forces read in mN).
#[test]
fn a_unit_override_against_the_files_own_unit_fails_the_file_unless_forced() {
    let dir = tempfile::tempdir().unwrap();
    write_legacy(dir.path(), "Zeit [s];Reibkraft [N];Normalkraft [N]");
    let ingest = "[ingest]\nunits = { Reibkraft = \"mN\", Normalkraft = \"mN\" }\n";
    let (o, err) = run_pipeline(
        dir.path(),
        "p.toml",
        &format!("{LEGACY}[output]\ndir = \"out\"\n{ingest}"),
    );
    assert_eq!(o.status.code(), Some(1), "{err}");
    assert!(
        err.contains("legacy_1.txt")
            && err.contains(
                "the file states the unit 'N' and the pipeline's [ingest] units say 'mN'"
            ),
        "{err}"
    );
    let (errors, _) = Table::read_parquet(&dir.path().join("out/errors.parquet")).unwrap();
    assert_eq!(errors.height(), 1);
    let (o, err) = run_pipeline(
        dir.path(),
        "q.toml",
        &format!("{LEGACY}[output]\ndir = \"out2\"\n{ingest}force = true\n"),
    );
    assert_eq!(o.status.code(), Some(0), "{err}");
    let (t, _) = Table::read_parquet(&dir.path().join("out2/friction.parquet")).unwrap();
    assert!((t.f64("normal_force_N").unwrap()[0].unwrap() - 1.0).abs() < 1e-12);
}

/// A friction force in mm is said to be a length, not a missing column.
#[test]
fn a_unit_of_the_wrong_dimension_is_named() {
    let dir = tempfile::tempdir().unwrap();
    write_legacy(dir.path(), "Zeit [s];Friction force [mm];Normal force [N]");
    let (o, err) = run_pipeline(
        dir.path(),
        "p.toml",
        &format!("{LEGACY}[output]\ndir = \"out\"\n"),
    );
    assert_eq!(o.status.code(), Some(1), "{err}");
    assert!(
        err.contains("'mm' is a length unit; the friction_force column needs a force unit: N"),
        "{err}"
    );
    assert!(!err.contains("no friction_force column"), "{err}");
}

/// A `units` key or a `columns` override that names no column of the files
/// it applies to (a typo, or a header read otherwise than assumed) stops
/// the run before anything is computed, naming the key and the columns
/// there are; nothing is written.
#[test]
fn a_units_key_or_column_override_matching_no_column_stops_the_run() {
    let dir = tempfile::tempdir().unwrap();
    write_legacy(dir.path(), "Zeit;Kraft;Last");
    let cases = [
        (
            "[ingest]\nunits = { Zeit = \"s\", Kraft = \"mN\", Lst = \"mN\" }\n",
            "[ingest] units key 'Lst' matches no column of the 1 input files",
        ),
        (
            "[[ingest.override]]\nfiles = \"legacy_*.txt\"\n\
             columns = { time = \"Zeit\", friction_force = \"Kraf\", normal_force = \"Last\" }\n\
             units = { Zeit = \"s\", Kraft = \"mN\", Last = \"mN\" }\n",
            "[[ingest.override]] files = 'legacy_*.txt' columns override friction_force = 'Kraf' \
             matches no column",
        ),
    ];
    for (i, (ingest, expected)) in cases.iter().enumerate() {
        let out = format!("out{i}");
        let (o, err) = run_pipeline(
            dir.path(),
            "p.toml",
            &format!("{LEGACY}[output]\ndir = \"{out}\"\n{ingest}"),
        );
        assert_eq!(o.status.code(), Some(2), "{err}");
        assert!(err.contains(expected), "{err}");
        assert!(err.contains("are: Zeit, Kraft, Last"), "{err}");
        assert!(!dir.path().join(&out).exists(), "nothing written");
    }
}
