//! The parts of a validated plan: each input file with how to read it, and
//! each stage with the tables it is given as files.

use std::collections::BTreeMap;
use std::path::PathBuf;

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
    /// How to read it.
    pub options: FileOptions,
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
}
