//! Provenance stored with every table: the tool version, the command, a
//! SHA-256 of each raw input behind the table, the parameters and the
//! references (equations) used. A table can thus be traced back to exactly
//! what produced it. The same keys go into the Parquet footer and into the
//! Arrow schema metadata (what `pyarrow`, polars and DuckDB show).

use serde::Serialize;

pub use crate::hash::InputHash;

/// What produced a table.
#[derive(Debug, Clone, Serialize, Default)]
pub struct Provenance {
    /// The command, for example `friction`, `fit coulomb` or
    /// `run pipelines/demo.toml`.
    pub command: String,
    /// The stage that wrote the table.
    pub stage: String,
    /// Raw input files with their hashes, sorted by path.
    pub inputs: Vec<InputHash>,
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
        inputs: Vec<InputHash>,
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
            ("tribo.table".into(), table.into()),
            ("tribo.command".into(), self.command.clone()),
            ("tribo.stage".into(), self.stage.clone()),
            ("tribo.inputs".into(), to_json(&self.inputs)),
            ("tribo.parameters".into(), self.parameters.to_string()),
            ("tribo.references".into(), to_json(&self.references)),
            ("tribo.pipeline".into(), self.pipeline.to_string()),
        ]
    }

    /// The raw inputs recorded in a table's metadata (`tribo.inputs`), so
    /// that a stage reading a table written earlier lists what is behind it.
    pub fn inputs_from(metadata: &[(String, String)]) -> Vec<InputHash> {
        metadata
            .iter()
            .find(|(k, _)| k == "tribo.inputs")
            .and_then(|(_, v)| serde_json::from_str(v).ok())
            .unwrap_or_default()
    }
}

fn to_json(v: &impl Serialize) -> String {
    serde_json::to_string(v).unwrap_or_default()
}
