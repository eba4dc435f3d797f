//! The parts of a validated plan: each input file with how to read it, and
//! each stage with the tables it is given as files.

use std::collections::BTreeMap;
use std::path::PathBuf;
use std::sync::Arc;

use crate::ingest::roles::Role;
use crate::ingest::IngestOptions;
use crate::stages::StagePlan;

/// How to read one input file.
#[derive(Debug, Clone, Default)]
pub struct FileOptions {
    /// Ingestion options.
    pub ingest: IngestOptions,
    /// Column for each role.
    pub columns: BTreeMap<Role, String>,
}

/// One input with its options and how it was given.
#[derive(Debug, Clone)]
pub struct PlannedFile {
    /// The path.
    pub path: PathBuf,
    /// The path as text (as the tables, the state and the keys give it),
    /// made once.
    pub source: String,
    /// How to read it (shared by the files the same overrides match).
    pub options: Arc<FileOptions>,
    /// The options as text, for the file's cache keys (made once per
    /// distinct options).
    pub options_key: Arc<str>,
    /// Named by a literal path (not matched by a glob): if no stage takes
    /// it, that is an error, not a note.
    pub named: bool,
    /// The stages (indices into the plan's stages) whose own `files` list it:
    /// they take it whatever its kind, and no other stage does.
    pub forced: Vec<usize>,
    /// The data file among the inputs that this file is read with, when it
    /// is a companion ([`crate::ingest::companion`]).
    pub companion_of: Option<PathBuf>,
}

/// A stage in the plan, with the tables it reads from files.
pub struct PlannedStage {
    /// The stage.
    pub stage: Box<dyn StagePlan>,
    /// Input tables given as files (`inputs = { friction = "…" }`).
    pub table_files: BTreeMap<String, PathBuf>,
    /// Its parameters and tables as its keys take them, made once: a key
    /// of each file's part takes them, and serializing the parameters
    /// for each of thousands of files was a rerun's largest cost per file.
    pub signature: StageSignature,
}

impl PlannedStage {
    /// A stage with the tables it reads from files.
    pub fn new(stage: Box<dyn StagePlan>, table_files: BTreeMap<String, PathBuf>) -> Self {
        let signature = StageSignature::of(stage.as_ref());
        PlannedStage {
            stage,
            table_files,
            signature,
        }
    }
}

/// What a stage's keys take of it besides its name: its validated
/// parameters (JSON) and the names of its tables.
#[derive(Debug, Clone)]
pub struct StageSignature {
    /// The parameters as JSON.
    pub parameters: String,
    /// The names of its tables, comma-separated.
    pub tables: String,
}

impl StageSignature {
    /// The signature of `stage`.
    pub fn of(stage: &dyn StagePlan) -> Self {
        let names: Vec<&str> = stage.produces().iter().map(|d| d.name).collect();
        StageSignature {
            parameters: stage.parameters().to_string(),
            tables: names.join(","),
        }
    }
}
