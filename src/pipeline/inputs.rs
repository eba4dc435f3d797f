//! Every input file accounted for: what became of each (processed,
//! failed, read as a companion, or taken by no stage and why), as the
//! run's `files` table, the report's first table and `--json`'s `inputs`.

use std::borrow::Cow;

use serde::Serialize;

use super::registry::FILES;
use crate::error::Result;
use crate::ingest::kind::DataKind;
use crate::table::{Table, TableBuilder};

/// What became of an input file.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Outcome {
    /// Every stage that took it gave rows.
    Processed,
    /// The reader or a stage failed on it (the reason says how).
    Failed,
    /// Read with a data file ([`InputFile::companion_of`]), not on its own.
    Companion,
    /// No stage of the pipeline takes it (the reason says why).
    NotTaken,
}

impl Outcome {
    /// Stable text form.
    pub fn as_str(self) -> &'static str {
        match self {
            Outcome::Processed => "processed",
            Outcome::Failed => "failed",
            Outcome::Companion => "companion",
            Outcome::NotTaken => "not_taken",
        }
    }
}

/// One input file of a run: a row of the `files` table.
#[derive(Debug, Clone, Serialize)]
pub struct InputFile {
    /// The path as given (shared with its provenance when read).
    pub file: std::sync::Arc<str>,
    /// Its size, when it could be opened.
    pub size_bytes: Option<u64>,
    /// SHA-256 of its bytes, when read (shared with its provenance).
    pub sha256: Option<std::sync::Arc<str>>,
    /// The reader that understood it.
    pub format: Option<std::sync::Arc<str>>,
    /// What it holds.
    pub kind: Option<DataKind>,
    /// The stages that took it.
    pub stages: Vec<&'static str>,
    /// What became of it.
    pub outcome: Outcome,
    /// Why it failed or was not taken.
    pub reason: Option<String>,
    /// For a companion: the data file it is read with.
    pub companion_of: Option<String>,
}

/// The `files` table: one row per input, in input order.
pub fn files_table(inputs: &[InputFile]) -> Result<Table> {
    let t = TableBuilder::new()
        .str("source", inputs.iter().map(|f| Some(&*f.file)))
        .i64(
            "size_bytes",
            inputs.iter().map(|f| f.size_bytes.map(|n| n as i64)),
        )
        .str("sha256", inputs.iter().map(|f| f.sha256.as_deref()))
        .str("format", inputs.iter().map(|f| f.format.as_ref()))
        .str("kind", inputs.iter().map(|f| f.kind.map(DataKind::as_str)))
        .str(
            "stages",
            inputs.iter().map(|f| match f.stages.as_slice() {
                [] => None,
                [one] => Some(Cow::Borrowed(*one)),
                all => Some(Cow::Owned(all.join(","))),
            }),
        )
        .str("outcome", inputs.iter().map(|f| Some(f.outcome.as_str())))
        .str("reason", inputs.iter().map(|f| f.reason.as_ref()))
        .str(
            "companion_of",
            inputs.iter().map(|f| f.companion_of.as_ref()),
        )
        .build()?;
    FILES.check(&t)?;
    Ok(t)
}
