//! The pieces a stage's inputs are made of: tables given as files, and
//! what a failure is reported against (the per-file parts are joined in
//! [`super::join`]).

use std::path::Path;

use super::plan::{Plan, PlannedStage};
use super::provenance::InputHash;
use crate::error::Result;
use crate::stages::Consumes;
use crate::table::Table;

/// A table given as a file, from its bytes (read once, when the stage's
/// key was made), with the file itself as its input (`hash`; a table
/// tribo wrote names its own inputs in its metadata).
pub(super) fn load_table(
    path: &Path,
    bytes: Vec<u8>,
    hash: InputHash,
) -> Result<(Table, Vec<InputHash>)> {
    let inputs = vec![hash];
    let table = if path
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("parquet"))
    {
        Table::read_parquet_bytes(bytes, path)?.0
    } else {
        crate::ingest::csv_table::csv_table_of(path, bytes)?
    };
    Ok((table, inputs))
}

/// What a stage's failure is reported against: the file it read itself,
/// else the first table file it was given, else its first input table.
pub(super) fn stage_source(plan: &Plan, ps: &PlannedStage) -> String {
    if let Some(h) = ps.stage.own_inputs().first() {
        return h.path.to_string();
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
