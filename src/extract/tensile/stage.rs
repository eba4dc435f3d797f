//! The tensile stage of a pipeline: the plan's files (with their per-file
//! reading options) analysed in parallel, `tensile.parquet` written, and
//! failures added to the run's `errors.parquet`.

use crate::error::Result;
use crate::pipeline::plan::Plan;
use crate::pipeline::run::{write_errors, FileFailure, RunReport};
use crate::report::{self, InputHash, Provenance};

use super::batch::analyze_planned;
use super::records::tensile_table;

/// Runs the stage; see the module doc.
pub fn run_stage(
    plan: &Plan,
    command: &str,
    tick: &(dyn Fn() + Sync),
    report: &mut RunReport,
) -> Result<()> {
    let files: Vec<_> = plan
        .files
        .iter()
        .map(|f| (f.path.clone(), f.options.ingest.clone()))
        .collect();
    let (records, failures) = analyze_planned(&files, plan.manifest.as_ref(), &plan.tensile)?;
    files.iter().for_each(|_| tick());
    for (path, e) in &failures {
        report
            .failures
            .push(FileFailure::new(path.display().to_string(), "tensile", e));
    }
    let mut prov = Provenance::new(
        command,
        serde_json::json!({ "pipeline": plan.spec_json, "tensile": plan.tensile }),
    );
    prov.inputs = plan
        .files
        .iter()
        .filter(|f| !failures.iter().any(|(p, _)| p == &f.path))
        .filter_map(|f| {
            std::fs::read(&f.path)
                .ok()
                .map(|b| InputHash::of_bytes(&f.path, &b))
        })
        .collect();
    prov.references = vec![
        "MODELS.md §3 (silk fibres with slip knots)".into(),
        "thesis Ch. 5, Eq. 5.1-5.4".into(),
    ];
    report.outputs.push(report::write_table(
        &plan.out_dir,
        "tensile",
        &tensile_table(&records)?,
        &prov,
    )?);
    write_errors(&plan.out_dir, report, &prov)
}
