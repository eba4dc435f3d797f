//! Provenance stored in every Parquet file's key-value metadata: the tool
//! version, the command, a SHA-256 of each input file, the parameters and the
//! references (equations) used. A table can thus be traced back to exactly
//! what produced it, and reprocessing can tell which inputs changed.

use std::path::Path;

use serde::Serialize;
use sha2::{Digest, Sha256};

/// One input file and the SHA-256 of its bytes.
#[derive(Debug, Clone, Serialize, PartialEq, Eq)]
pub struct InputHash {
    /// The path as given by the user.
    pub path: String,
    /// Lower-case hex SHA-256 of the file content.
    pub sha256: String,
}

impl InputHash {
    /// Hashes bytes already read from `path`.
    pub fn of_bytes(path: &Path, bytes: &[u8]) -> Self {
        InputHash {
            path: path.display().to_string(),
            sha256: sha256_hex(bytes),
        }
    }
}

/// Lower-case hex SHA-256.
pub fn sha256_hex(bytes: &[u8]) -> String {
    let digest = Sha256::digest(bytes);
    digest.iter().map(|b| format!("{b:02x}")).collect()
}

/// What produced a table.
#[derive(Debug, Clone, Serialize, Default)]
pub struct Provenance {
    /// The command or stage, for example `friction` or `fit coulomb`.
    pub command: String,
    /// Input files with their hashes, in a deterministic order.
    pub inputs: Vec<InputHash>,
    /// The parameters used, as JSON.
    pub parameters: serde_json::Value,
    /// Equations and sources used (for example "MODELS.md §1").
    pub references: Vec<String>,
}

impl Provenance {
    /// A provenance for a command with its parameters.
    pub fn new(command: &str, parameters: impl Serialize) -> Self {
        Provenance {
            command: command.to_string(),
            parameters: serde_json::to_value(parameters).unwrap_or(serde_json::Value::Null),
            ..Default::default()
        }
    }

    /// The key-value pairs written into Parquet metadata. Keys are prefixed
    /// `tribo.`; values are plain strings or JSON.
    pub fn key_values(&self, table: &str) -> Vec<(String, String)> {
        vec![
            ("tribo.version".into(), env!("CARGO_PKG_VERSION").into()),
            ("tribo.table".into(), table.into()),
            ("tribo.command".into(), self.command.clone()),
            ("tribo.inputs".into(), to_json(&self.inputs)),
            ("tribo.parameters".into(), self.parameters.to_string()),
            ("tribo.references".into(), to_json(&self.references)),
        ]
    }
}

fn to_json(v: &impl Serialize) -> String {
    serde_json::to_string(v).unwrap_or_default()
}
