//! Running a plan: the per-file phase ([`super::files`]), then each table
//! stage in run order, then every table written once, with its provenance,
//! and `errors.parquet`. Nothing a stage does can stop another stage that
//! does not depend on it: a failure is a row of `errors.parquet`.

use std::collections::BTreeMap;
use std::path::Path;

use super::files::{per_file_stages, process_files, Fate};
use super::outcome::{FileFailure, RunReport, WithoutResult};
use super::plan::{Plan, PlannedStage};
use super::provenance::{InputHash, Provenance};
use super::publish::write_table;
use crate::error::{Error, ErrorKind, Result};
use crate::schema;
use crate::stages::{Consumes, Output, Progress, StagePlan, TableInputs, Tables};
use crate::table::Table;

/// A table a stage produced, with the raw inputs behind it.
struct Produced {
    name: &'static str,
    table: Table,
    stage: usize,
    inputs: Vec<InputHash>,
}

/// Runs the plan. `progress` sees each phase; the library itself never
/// prints.
pub fn run(plan: &Plan, command: &str, progress: &dyn Progress) -> Result<RunReport> {
    let mut report = RunReport {
        files: plan.files.len(),
        ..Default::default()
    };
    let mut made: Vec<Produced> = Vec::new();
    run_file_stages(plan, progress, &mut report, &mut made);
    run_table_stages(plan, progress, &mut report, &mut made);
    write_outputs(plan, command, &mut report, &made)?;
    Ok(report)
}

fn run_file_stages(
    plan: &Plan,
    progress: &dyn Progress,
    report: &mut RunReport,
    made: &mut Vec<Produced>,
) {
    let stages = per_file_stages(plan);
    if stages.is_empty() && plan.files.is_empty() {
        return;
    }
    let n = plan.stages.len();
    let mut parts: Vec<Vec<Tables>> = (0..n).map(|_| Vec::new()).collect();
    let mut inputs: Vec<Vec<InputHash>> = vec![Vec::new(); n];
    for (f, o) in plan.files.iter().zip(process_files(plan, progress)) {
        let source = f.path.display().to_string();
        match o.fate {
            Fate::Unreadable(e) => report.failures.push(FileFailure::new(source, "ingest", &e)),
            Fate::Untaken(why) if f.named => report.failures.push(FileFailure {
                message: format!("{source}: named as an input, but no stage takes it: {why}"),
                source,
                stage: "ingest".into(),
                kind: ErrorKind::BadInput,
            }),
            Fate::Untaken(why) => report.unrouted.push((source, why)),
            Fate::Taken(results) => {
                let mut all_ok = true;
                for (i, r) in results {
                    match r {
                        Ok(t) => {
                            parts[i].push(t);
                            inputs[i].extend(o.hash.clone());
                        }
                        Err(e) => {
                            all_ok = false;
                            let name = plan.stages[i].stage.name();
                            report
                                .failures
                                .push(FileFailure::new(source.clone(), name, &e));
                        }
                    }
                }
                report.succeeded += usize::from(all_ok);
            }
        }
    }
    for i in stages {
        let stage = plan.stages[i].stage.as_ref();
        let mut ins = std::mem::take(&mut inputs[i]);
        ins.extend(plan.manifest.as_ref().map(|(_, h)| h.clone()));
        let output =
            join_parts(stage, std::mem::take(&mut parts[i])).and_then(|t| stage.assemble(t));
        record(plan, i, output, ins, report, made);
    }
}

/// Joins the rows of every file per table, in input order; a table no
/// file contributed to is empty, with its schema's columns.
fn join_parts(stage: &dyn StagePlan, parts: Vec<Tables>) -> Result<Tables> {
    let mut by_name: BTreeMap<&'static str, Vec<Table>> = BTreeMap::new();
    for part in parts {
        for (name, t) in part {
            by_name.entry(name).or_default().push(t);
        }
    }
    stage
        .produces()
        .into_iter()
        .map(|name| {
            let joined = Table::concat(by_name.remove(name).unwrap_or_default())?;
            let t = match joined {
                Some(t) => t,
                None => schema::schema(name)?.empty_table()?,
            };
            Ok((name, t))
        })
        .collect()
}

fn run_table_stages(
    plan: &Plan,
    progress: &dyn Progress,
    report: &mut RunReport,
    made: &mut Vec<Produced>,
) {
    for (i, ps) in plan.stages.iter().enumerate() {
        let Consumes::Tables(needs) = ps.stage.consumes() else {
            continue;
        };
        let mut available = BTreeMap::new();
        let mut inputs = ps.stage.own_inputs();
        let mut gathered = Ok(());
        for need in needs {
            let found = match ps.table_files.get(need.table) {
                Some(path) => load_table(path).map(Some),
                None => Ok(made
                    .iter()
                    .find(|p| p.name == need.table)
                    .map(|p| (p.table.clone(), p.inputs.clone()))),
            };
            match found {
                Ok(Some((t, ins))) => {
                    available.insert(need.table.to_string(), t);
                    inputs.extend(ins);
                }
                Ok(None) if need.required => {
                    gathered = Err(Error::NotApplicable(format!(
                        "not run: its input table '{}' was not produced (see the errors above)",
                        need.table
                    )));
                    break;
                }
                Ok(None) => {}
                Err(e) => {
                    gathered = Err(e);
                    break;
                }
            }
        }
        progress.begin(ps.stage.name(), ps.stage.units());
        let output =
            gathered.and_then(|_| ps.stage.run_tables(&TableInputs::new(&available), progress));
        record(plan, i, output, inputs, report, made);
    }
}

/// A table given as a file, with the raw inputs its metadata names and the
/// file itself.
fn load_table(path: &Path) -> Result<(Table, Vec<InputHash>)> {
    let mut inputs = vec![InputHash::of_file(path)?];
    let table = if path
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("parquet"))
    {
        let (t, kv) = Table::read_parquet(path)?;
        inputs.extend(Provenance::inputs_from(&kv));
        t
    } else {
        crate::ingest::csv_table::read_table_file(path)?
    };
    Ok((table, inputs))
}

/// What a stage's failure is reported against: the file it read itself,
/// else the first table file it was given, else its first input table.
fn stage_source(plan: &Plan, ps: &PlannedStage) -> String {
    if let Some(h) = ps.stage.own_inputs().first() {
        return h.path.clone();
    }
    if let Some(p) = ps.table_files.values().next() {
        return p.display().to_string();
    }
    match ps.stage.consumes() {
        Consumes::Tables(needs) if !needs.is_empty() => plan
            .out_dir
            .join(format!("{}.parquet", needs[0].table))
            .display()
            .to_string(),
        _ => format!("stage {}", ps.stage.name()),
    }
}

/// Takes a stage's output: its tables (each checked against its schema
/// now, so that a defect fails this stage only), rows without a result and
/// notes; or its failure.
fn record(
    plan: &Plan,
    i: usize,
    output: Result<Output>,
    mut inputs: Vec<InputHash>,
    report: &mut RunReport,
    made: &mut Vec<Produced>,
) {
    let ps = &plan.stages[i];
    let name = ps.stage.name();
    let checked = output.and_then(|o| {
        for (t, table) in &o.tables {
            schema::schema(t)?.check(table)?;
        }
        Ok(o)
    });
    let output = match checked {
        Ok(o) => o,
        Err(e) => {
            let source = stage_source(plan, ps);
            report.failures.push(FileFailure::new(source, name, &e));
            return;
        }
    };
    inputs.sort();
    inputs.dedup();
    report.stages_run.push(name.into());
    if output.without_result > 0 {
        report.without_result.push(WithoutResult {
            stage: name.into(),
            rows: output.without_result,
        });
    }
    report.notes.extend(output.notes);
    for (t, table) in output.tables {
        made.push(Produced {
            name: t,
            table,
            stage: i,
            inputs: inputs.clone(),
        });
    }
}

/// Writes every table and `errors.parquet` into the output folder.
fn write_outputs(
    plan: &Plan,
    command: &str,
    report: &mut RunReport,
    made: &[Produced],
) -> Result<()> {
    let dir = &plan.out_dir;
    std::fs::create_dir_all(dir).map_err(|e| Error::io(dir, e))?;
    for p in made {
        let stage = &plan.stages[p.stage].stage;
        let prov = Provenance {
            command: command.into(),
            stage: stage.name().into(),
            inputs: p.inputs.clone(),
            parameters: serde_json::json!({ stage.name(): stage.parameters() }),
            references: stage.references(),
            pipeline: plan.spec_json.clone(),
        };
        report
            .outputs
            .push(write_table(dir, p.name, &p.table, &prov)?);
    }
    let mut all: Vec<InputHash> = made.iter().flat_map(|p| p.inputs.clone()).collect();
    all.sort();
    all.dedup();
    let prov = Provenance {
        command: command.into(),
        stage: "pipeline".into(),
        inputs: all,
        pipeline: plan.spec_json.clone(),
        ..Default::default()
    };
    report
        .outputs
        .push(write_table(dir, "errors", &report.errors_table()?, &prov)?);
    Ok(())
}
