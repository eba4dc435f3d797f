//! The `tensile` and `tensile summarize` runs: files in, Parquet tables out.

use std::path::{Path, PathBuf};

use serde::Serialize;

use crate::error::{Error, Result};
use crate::ingest::manifest::Manifest;
use crate::ingest::IngestOptions;
use crate::report::{write_table, InputHash, Provenance};
use crate::table::TableBuilder;

use super::batch::analyze_files;
use super::params::TensileParams;
use super::records::tensile_table;
use super::summary::{fill_ratios, groups_table, rows_from_table, summarize};
use crate::ingest::csv_table::read_table_file;

const REFERENCES: [&str; 2] = [
    "MODELS.md §3 (silk fibres with slip knots)",
    "thesis Ch. 5, Eq. 5.1-5.4, Tables 5.1-5.8",
];

/// What a `tensile` run did.
#[derive(Debug, Default)]
pub struct TensileRunReport {
    /// Tables written.
    pub outputs: Vec<PathBuf>,
    /// Fibres analysed (rows of `tensile.parquet`).
    pub fibres: usize,
    /// Fibres without a toughness (their status says why).
    pub fibres_without_result: usize,
    /// Files that could not be read: (file, message).
    pub failures: Vec<(String, String)>,
}

#[derive(Serialize)]
struct RunParams<'a> {
    params: &'a TensileParams,
    samples: Option<String>,
    ingest: &'a IngestOptions,
}

fn hashes(paths: &[PathBuf]) -> Vec<InputHash> {
    paths
        .iter()
        .filter_map(|p| std::fs::read(p).ok().map(|b| InputHash::of_bytes(p, &b)))
        .collect()
}

/// Analyses `files` (with an optional manifest) and writes
/// `out/tensile.parquet` and `out/errors.parquet`.
pub fn run_tensile(
    files: &[PathBuf],
    samples: Option<&Path>,
    out: &Path,
    options: &IngestOptions,
    params: &TensileParams,
) -> Result<TensileRunReport> {
    params.validate()?;
    let manifest = samples.map(Manifest::read).transpose()?;
    let (records, failures) = analyze_files(files, manifest.as_ref(), options, params)?;
    let mut prov = Provenance::new(
        "tensile",
        RunParams {
            params,
            samples: samples.map(|p| p.display().to_string()),
            ingest: options,
        },
    );
    let mut inputs = files.to_vec();
    inputs.extend(samples.map(Path::to_path_buf));
    prov.inputs = hashes(&inputs);
    prov.references = REFERENCES.iter().map(|s| s.to_string()).collect();
    let mut report = TensileRunReport {
        fibres: records.len(),
        fibres_without_result: records
            .iter()
            .filter(|r| r.features.toughness_j_per_kg.is_none())
            .count(),
        failures: failures
            .iter()
            .map(|(p, e)| (p.display().to_string(), e.to_string()))
            .collect(),
        ..Default::default()
    };
    report.outputs.push(write_table(
        out,
        "tensile",
        &tensile_table(&records)?,
        &prov,
    )?);
    let kind = |e: &Error| {
        if e.is_bad_input() {
            "bad_input"
        } else {
            "not_applicable"
        }
    };
    let errors = TableBuilder::new()
        .str(
            "source",
            failures.iter().map(|(p, _)| Some(p.display().to_string())),
        )
        .str("stage", failures.iter().map(|_| Some("tensile")))
        .str("kind", failures.iter().map(|(_, e)| Some(kind(e))))
        .str("message", failures.iter().map(|(_, e)| Some(e.to_string())))
        .build()?;
    report
        .outputs
        .push(write_table(out, "errors", &errors, &prov)?);
    Ok(report)
}

/// Group summary of a per-fibre table, written to
/// `out/tensile_groups.parquet`. `threshold` classifies knots when the
/// table has no `knot_effective` column.
pub fn run_summarize(table: &Path, out: &Path, threshold: f64) -> Result<PathBuf> {
    if !(threshold > 0.0 && threshold < 1.0) {
        return Err(Error::Config(format!(
            "effective-knot threshold {threshold}: expected a fraction in (0, 1)"
        )));
    }
    let t = read_table_file(table)?;
    let mut rows = rows_from_table(&t, threshold)?;
    fill_ratios(&mut rows);
    let groups = summarize(&rows);
    let mut prov = Provenance::new(
        "tensile summarize",
        serde_json::json!({ "effective_threshold": threshold }),
    );
    prov.inputs = hashes(&[table.to_path_buf()]);
    prov.references = REFERENCES.iter().map(|s| s.to_string()).collect();
    write_table(out, "tensile_groups", &groups_table(&groups)?, &prov)
}
