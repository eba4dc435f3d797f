//! Running a plan: files in parallel (rayon), each independently; results
//! gathered in the plan's (sorted) order so that outputs do not depend on
//! the thread count; failures listed, never fatal to the other files.

use std::path::PathBuf;

use rayon::prelude::*;
use serde::Serialize;

use crate::error::{Error, Result};
use crate::report::{self, InputHash, Provenance};
use crate::table::TableBuilder;

use super::friction_stage::{process_file, FrictionFile};
use super::plan::{Plan, Stage};

/// A file that could not be processed.
#[derive(Debug, Clone, Serialize)]
pub struct FileFailure {
    /// The path.
    pub source: String,
    /// The stage that failed.
    pub stage: String,
    /// `bad_input` or `not_applicable`.
    pub kind: &'static str,
    /// The error with its location.
    pub message: String,
}

impl FileFailure {
    /// A failure of `stage` on `source`, classified from the error.
    pub fn new(source: String, stage: &str, e: &Error) -> Self {
        let kind = if e.is_bad_input() {
            "bad_input"
        } else {
            "not_applicable"
        };
        FileFailure {
            source,
            stage: stage.into(),
            kind,
            message: e.to_string(),
        }
    }
}

/// What a run did: partial success is a value.
#[derive(Debug, Clone, Default, Serialize)]
pub struct RunReport {
    /// Input files.
    pub files: usize,
    /// Files processed without error by every stage.
    pub succeeded: usize,
    /// Failures, one per (file, stage), with why.
    pub failures: Vec<FileFailure>,
    /// Tables written.
    pub outputs: Vec<PathBuf>,
}

impl RunReport {
    /// Number of distinct files with at least one failed stage.
    pub fn failed_files(&self) -> usize {
        let failed: std::collections::BTreeSet<&str> =
            self.failures.iter().map(|f| f.source.as_str()).collect();
        failed.len()
    }
}

/// Runs the plan. `tick` is called once per finished file (for a progress
/// bar); the library itself never prints.
pub fn run(plan: &Plan, command: &str, tick: &(dyn Fn() + Sync)) -> Result<RunReport> {
    let mut report = RunReport {
        files: plan.files.len(),
        ..Default::default()
    };
    for stage in &plan.stages {
        match stage {
            Stage::Friction => run_friction(plan, command, tick, &mut report)?,
            Stage::Tensile => {
                crate::extract::tensile::stage::run_stage(plan, command, tick, &mut report)?
            }
            Stage::Roughness => {
                crate::extract::roughness::stage::run_stage(plan, command, tick, &mut report)?
            }
        }
    }
    report.succeeded = report.files - report.failed_files();
    Ok(report)
}

fn run_friction(
    plan: &Plan,
    command: &str,
    tick: &(dyn Fn() + Sync),
    report: &mut RunReport,
) -> Result<()> {
    let results: Vec<Result<FrictionFile>> = plan
        .files
        .par_iter()
        .map(|f| {
            let r = process_file(&f.path, &f.options, plan.manifest.as_ref(), &plan.friction);
            tick();
            r
        })
        .collect();
    let mut ok = Vec::new();
    let mut inputs = Vec::new();
    for (f, r) in plan.files.iter().zip(results) {
        match r {
            Ok(file) => {
                inputs.push(InputHash {
                    path: file.source.clone(),
                    sha256: file.sha256.clone(),
                });
                ok.push(file);
            }
            Err(e) => report.failures.push(FileFailure::new(
                f.path.display().to_string(),
                "friction",
                &e,
            )),
        }
    }
    let mut prov = Provenance::new(
        command,
        serde_json::json!({ "pipeline": plan.spec_json, "friction": plan.friction }),
    );
    prov.inputs = inputs;
    prov.references = vec!["MODELS.md §1 (friction traces)".into()];
    let dir = &plan.out_dir;
    report.outputs.push(report::write_table(
        dir,
        "friction",
        &report::friction::friction_table(&ok)?,
        &prov,
    )?);
    report.outputs.push(report::write_table(
        dir,
        "friction_steps",
        &report::friction::steps_table(&ok)?,
        &prov,
    )?);
    report.outputs.push(report::write_table(
        dir,
        "stickslip",
        &report::friction::stickslip_table(&ok)?,
        &prov,
    )?);
    report.outputs.push(report::write_table(
        dir,
        "traces",
        &report::friction::traces_table(&ok)?,
        &prov,
    )?);
    write_errors(dir, report, &prov)
}

/// Writes `errors.parquet` with every failure of the run so far (all
/// stages), so that it is complete after the last stage.
pub fn write_errors(
    dir: &std::path::Path,
    report: &mut RunReport,
    prov: &Provenance,
) -> Result<()> {
    let fl = &report.failures;
    let errors = TableBuilder::new()
        .str("source", fl.iter().map(|f| Some(&f.source)))
        .str("stage", fl.iter().map(|f| Some(&f.stage)))
        .str("kind", fl.iter().map(|f| Some(f.kind)))
        .str("message", fl.iter().map(|f| Some(&f.message)))
        .build()?;
    let path = report::write_table(dir, "errors", &errors, prov)?;
    if !report.outputs.contains(&path) {
        report.outputs.push(path);
    }
    Ok(())
}
