//! Every input file accounted for (#28 item 5): the `files` table lists
//! each input of a run with its size, SHA-256, reader, kind, the stages
//! that took it and what became of it; the report's first table and
//! `--json` say the same, and `tribo inspect` says why a file has no kind.

use std::path::Path;

use sha2::{Digest, Sha256};
use tribo::table::Table;

use crate::common;
use crate::common::files_table as files;

fn sha256(path: &Path) -> String {
    format!("{:x}", Sha256::digest(std::fs::read(path).unwrap()))
}

/// The demo: every file the glob matched is a row, in input order, with
/// its own size and SHA-256 (computed here, independently); the data files
/// are processed by the stage of their kind, the notes file is not taken
/// with the reason the run gives.
#[test]
fn every_demo_input_is_a_row_with_its_outcome() {
    let dir = tempfile::tempdir().unwrap();
    let report = common::run_demo(dir.path());
    let rows = files(dir.path());
    assert_eq!(rows.len(), report.files, "{:?}", rows.keys());
    assert_eq!(report.inputs.len(), report.files);
    let order: Vec<&str> = report.inputs.iter().map(|i| &*i.file).collect();
    let mut sorted = order.clone();
    sorted.sort();
    assert_eq!(order, sorted, "input order");
    for (source, row) in &rows {
        let path = Path::new(source);
        assert_eq!(row["sha256"], sha256(path), "{source}");
        let size = std::fs::metadata(path).unwrap().len();
        assert_eq!(row["size_bytes"], size.to_string(), "{source}");
        let name = path.file_name().unwrap().to_string_lossy();
        if name == "notes.txt" {
            assert_eq!(row["outcome"], "not_taken", "{row:?}");
            assert_eq!(row["stages"], "");
            let (_, why) = report.unrouted.iter().find(|(f, _)| f == source).unwrap();
            assert_eq!(&row["reason"], why);
            assert!(!why.is_empty());
            continue;
        }
        assert_eq!(row["outcome"], "processed", "{row:?}");
        assert_eq!(row["reason"], "", "{row:?}");
        let (kind, stage) = match path.parent().unwrap().file_name().unwrap().to_str() {
            Some("friction") => ("friction_trace", "friction"),
            Some("fibres") => ("tensile_curve", "tensile"),
            _ => ("", "roughness"),
        };
        assert_eq!(row["stages"], stage, "{row:?}");
        if !kind.is_empty() {
            assert_eq!(row["kind"], kind, "{row:?}");
        }
        assert!(!row["format"].is_empty(), "{row:?}");
    }
    // The report's first table has every input, the notes file too.
    let html = std::fs::read_to_string(dir.path().join("report.html")).unwrap();
    let first = &html[..html.find("</table>").unwrap()];
    for source in rows.keys() {
        assert!(
            first.contains(&tribo::plot::escape(source)),
            "{source} not in the first table"
        );
    }
    let notes = first.lines().find(|l| l.contains("notes.txt")).unwrap();
    assert!(notes.contains("not taken: "), "{notes}");
}

/// A file that fails is `failed` with its error, the same as in
/// `errors.parquet`; `--json` lists every input with its outcome. A file
/// named as an input that no stage takes is a failure that says why.
#[test]
fn a_failed_file_is_failed_with_its_error_in_the_table_and_json() {
    let dir = tempfile::tempdir().unwrap();
    let lab = dir.path();
    let good = common::root().join("fixtures/lab/friction/sled_A1_50g.csv");
    std::fs::copy(&good, lab.join("good.csv")).unwrap();
    // A friction trace whose force column holds a unit tribo does not know.
    std::fs::write(
        lab.join("bad.csv"),
        "time (s),Fx (furlong)\n0,1\n1,2\n2,3\n",
    )
    .unwrap();
    std::fs::write(lab.join("README.md"), "# Notes\n\nThe sled runs of May.\n").unwrap();
    std::fs::write(
        lab.join("p.toml"),
        "stages = [\"friction\"]\n[input]\nfiles = [\"good.csv\", \"bad.csv\", \"README.md\"]\n\
         [output]\ndir = \"out\"\n",
    )
    .unwrap();
    let o = common::tribo(lab, &["run", "p.toml", "--json"]);
    let err = String::from_utf8_lossy(&o.stderr);
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let inputs = v["inputs"].as_array().unwrap();
    assert_eq!(inputs.len(), 3, "{v}");
    let by = |f: &str| inputs.iter().find(|i| i["file"] == f).unwrap();
    assert_eq!(by("good.csv")["outcome"], "processed");
    assert_eq!(by("good.csv")["stages"][0], "friction");
    assert_eq!(by("bad.csv")["outcome"], "failed", "{err}");
    let rows = files(&lab.join("out"));
    let (errors, _) = Table::read_parquet(&lab.join("out/errors.parquet")).unwrap();
    let sources = errors.str("source").unwrap();
    let k = sources
        .iter()
        .position(|s| s.as_deref() == Some("bad.csv"))
        .unwrap();
    let message = errors.str("message").unwrap()[k].clone().unwrap();
    assert!(
        rows["bad.csv"]["reason"].contains(&message),
        "{:?}",
        rows["bad.csv"]
    );
    assert_eq!(by("bad.csv")["reason"], rows["bad.csv"]["reason"].as_str());
    // The README, named on the command line, is a failure that says why.
    assert_eq!(rows["README.md"]["outcome"], "failed");
    assert!(
        rows["README.md"]["reason"].contains("no stage takes it"),
        "{:?}",
        rows["README.md"]
    );
    assert_eq!(o.status.code(), Some(1), "{err}");
}

/// `tribo inspect` gives a file's kind, and for a file no stage would take
/// the same reason as a run; a notes file is not a data file, and why.
#[test]
fn inspect_says_the_kind_or_why_there_is_none() {
    let dir = tempfile::tempdir().unwrap();
    let lab = dir.path();
    std::fs::write(lab.join("odd.csv"), "alpha,beta\n1,2\n3,4\n5,6\n").unwrap();
    std::fs::write(lab.join("notes.txt"), "sled runs, see the lab book\n").unwrap();
    let trace = common::root().join("fixtures/lab/friction/sled_A1_50g.csv");
    let o = common::tribo(lab, &["inspect", trace.to_str().unwrap(), "odd.csv"]);
    let out = String::from_utf8_lossy(&o.stdout);
    assert!(out.contains("kind        friction_trace"), "{out}");
    assert!(
        out.contains("kind        none: no stage recognises its columns [\"alpha\", \"beta\"]"),
        "{out}"
    );
    assert_eq!(o.status.code(), Some(0));
    let o = common::tribo(lab, &["inspect", "--json", "notes.txt"]);
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let e = v[0]["error"].as_str().unwrap();
    assert!(e.contains("not a data file: no numeric table"), "{e}");
    assert_eq!(o.status.code(), Some(1));
}
