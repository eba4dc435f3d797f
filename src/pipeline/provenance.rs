//! Provenance stored with every table: the tool version, the command, the
//! raw inputs behind the table, the parameters and the references
//! (equations) used. A table can thus be traced back to exactly what
//! produced it. The same keys go into the Parquet footer and into the
//! Arrow schema metadata (what `pyarrow`, polars and DuckDB show).
//!
//! The inputs are a count and one SHA-256 over their list (path and
//! SHA-256 of each, [`crate::hash::inputs_sha256`]); the list itself is
//! the set's `files` table, one row per input with its SHA-256 and the
//! stages that took it. Listed in each table, it was most of every
//! table's footer over a large archive (130 bytes an input, twice per
//! table), written and read again by every rerun that changed anything.

use std::sync::Arc;

use serde::Serialize;

pub use crate::hash::InputHash;

/// What produced a table.
#[derive(Debug, Clone, Default)]
pub struct Provenance {
    /// The command, for example `friction`, `fit coulomb` or
    /// `run pipelines/demo.toml`.
    pub command: String,
    /// The stage that wrote the table.
    pub stage: String,
    /// Raw input files with their hashes, sorted by path (in the metadata:
    /// their count and one SHA-256 of the list).
    pub inputs: Arc<[InputHash]>,
    /// The parameters used, as JSON.
    pub parameters: serde_json::Value,
    /// Equations and sources used (for example "MODELS.md §1").
    pub references: Vec<String>,
    /// The whole pipeline as run (for a command, the pipeline built from
    /// its flags).
    pub pipeline: serde_json::Value,
}

impl Provenance {
    /// The provenance of a table written by `stage` from `inputs`.
    pub fn of_stage(
        command: &str,
        stage: &dyn crate::stages::StagePlan,
        inputs: Arc<[InputHash]>,
        pipeline: &serde_json::Value,
    ) -> Provenance {
        Provenance {
            command: command.into(),
            stage: stage.name().into(),
            inputs,
            parameters: serde_json::json!({ stage.name(): stage.parameters() }),
            references: stage.references(),
            pipeline: pipeline.clone(),
        }
    }

    /// The key-value pairs written into the metadata. Keys are prefixed
    /// `tribo.`; values are plain strings or JSON.
    pub fn key_values(&self, table: &str) -> Vec<(String, String)> {
        vec![
            ("tribo.version".into(), env!("CARGO_PKG_VERSION").into()),
            ("tribo.build".into(), crate::BUILD.into()),
            ("tribo.table".into(), table.into()),
            ("tribo.command".into(), self.command.clone()),
            ("tribo.stage".into(), self.stage.clone()),
            ("tribo.inputs_count".into(), self.inputs.len().to_string()),
            (
                "tribo.inputs_sha256".into(),
                crate::hash::inputs_sha256(&self.inputs),
            ),
            ("tribo.inputs_table".into(), "files".into()),
            ("tribo.parameters".into(), self.parameters.to_string()),
            ("tribo.references".into(), to_json(&self.references)),
            ("tribo.pipeline".into(), self.pipeline.to_string()),
        ]
    }
}

fn to_json(v: &impl Serialize) -> String {
    serde_json::to_string(v).unwrap_or_default()
}
