//! The pieces a stage's inputs are made of: the per-file parts joined in
//! input order, tables given as files, and what a failure is reported
//! against.

use std::collections::BTreeMap;
use std::path::Path;

use super::plan::{Plan, PlannedStage};
use super::provenance::{InputHash, Provenance};
use crate::error::Result;
use crate::stages::{Consumes, StagePlan, Tables};
use crate::table::Table;

/// Joins the rows of every file per table, in input order; a table no
/// file contributed to is empty, with its schema's columns.
pub(super) fn join_parts(stage: &dyn StagePlan, parts: Vec<Tables>) -> Result<Tables> {
    let mut by_name: BTreeMap<&'static str, Vec<Table>> = BTreeMap::new();
    for part in parts {
        for (def, t) in part {
            by_name.entry(def.name).or_default().push(t);
        }
    }
    stage
        .produces()
        .into_iter()
        .map(|def| {
            let joined = Table::concat(by_name.remove(def.name).unwrap_or_default())?;
            let t = match joined {
                Some(t) => t,
                None => def.empty_table()?,
            };
            Ok((def, t))
        })
        .collect()
}

/// A table given as a file, with the raw inputs its metadata names and the
/// file itself.
pub(super) fn load_table(path: &Path) -> Result<(Table, Vec<InputHash>)> {
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
pub(super) fn stage_source(plan: &Plan, ps: &PlannedStage) -> String {
    if let Some(h) = ps.stage.own_inputs().first() {
        return h.path.clone();
    }
    if let Some(p) = ps.table_files.values().next() {
        return p.display().to_string();
    }
    match ps.stage.consumes() {
        Consumes::Tables(needs) if !needs.is_empty() => plan
            .out_dir
            .join(format!("{}.parquet", needs[0].table.name))
            .display()
            .to_string(),
        _ => format!("stage {}", ps.stage.name()),
    }
}
