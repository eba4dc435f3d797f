//! What a run did — partial success is a value — and what it counts
//! against its exit code ([`super::exit`]).

use std::path::PathBuf;

use serde::Serialize;

use super::exit::{self, Tally};
use super::Mode;
use crate::error::{Error, ErrorKind, Result};
use crate::table::{Table, TableBuilder};

/// `tribo run --json`'s summary, borrowed from the report; fields in
/// alphabetical order, as its readers have always seen them.
#[derive(Serialize)]
struct Summary<'a> {
    exit_code: u8,
    files: usize,
    files_failed: usize,
    files_hashed: usize,
    files_processed: usize,
    files_reused: usize,
    files_unrouted: usize,
    inputs: &'a [super::inputs::InputFile],
    notes: &'a [String],
    phases_s: &'a [super::phases::PhaseTime],
    runs_computed: usize,
    runs_reused: usize,
    stages_reused: usize,
    stages_run: usize,
    tables: Vec<String>,
    warnings: usize,
}

/// A file (or a table stage) that could not be processed.
#[derive(Debug, Clone, Serialize)]
pub struct FileFailure {
    /// The input file, or the table a table stage read.
    pub source: String,
    /// The stage that failed (`ingest` when the file could not be read).
    pub stage: String,
    /// The family of the error.
    pub kind: ErrorKind,
    /// The error with its location.
    pub message: String,
}

impl FileFailure {
    /// A failure kept in the cache from an earlier run.
    pub fn from_failure(source: String, stage: &str, f: &super::cache::Failure) -> Self {
        FileFailure {
            source,
            stage: stage.into(),
            kind: f.kind,
            message: f.message.clone(),
        }
    }

    /// A failure of `stage` on `source`, classified from the error.
    pub fn new(source: String, stage: &str, e: &Error) -> Self {
        FileFailure {
            source,
            stage: stage.into(),
            kind: e.kind(),
            message: e.to_string(),
        }
    }
}

/// Rows a stage wrote without a result (their status says why).
#[derive(Debug, Clone, Serialize)]
pub struct WithoutResult {
    /// The stage.
    pub stage: String,
    /// How many rows.
    pub rows: usize,
}

/// In a dry run: a file or stage that would be redone, and why.
#[derive(Debug, Clone, Serialize)]
pub struct Redo {
    /// `file` or `stage`.
    pub what: &'static str,
    /// The file's path or the stage's name.
    pub name: String,
    /// Why.
    pub reason: String,
}

impl Redo {
    /// A file that would be read again.
    pub fn file(path: &str, reason: &str) -> Self {
        Redo {
            what: "file",
            name: path.into(),
            reason: reason.into(),
        }
    }
    /// A stage that would run again.
    pub fn stage(name: &str, reason: &str) -> Self {
        Redo {
            what: "stage",
            name: name.into(),
            reason: reason.into(),
        }
    }
}

/// What a run did.
#[derive(Debug, Clone, Default, Serialize)]
pub struct RunReport {
    /// Input files.
    pub files: usize,
    /// Files taken by at least one stage and failed by none.
    pub succeeded: usize,
    /// Of those, files that some stage computed in this run.
    pub files_processed: usize,
    /// Of those, files whose every result came from the cache.
    pub files_reused: usize,
    /// Files read and hashed in this run; the others' size, times and
    /// inode were the ones the last run saw (`--verify` reads them all).
    pub files_hashed: usize,
    /// Files that no stage takes, and why (listed, not errors).
    pub unrouted: Vec<(String, String)>,
    /// Failures, one per (file, stage), with why.
    pub failures: Vec<FileFailure>,
    /// Per stage, rows without a result.
    pub without_result: Vec<WithoutResult>,
    /// Lines for the user from the stages (rows left out, failed runs).
    pub notes: Vec<String>,
    /// Stages that ran, in order.
    pub stages_run: Vec<String>,
    /// Stages whose published tables were still current.
    pub stages_reused: Vec<String>,
    /// Runs of simulation studies computed in this run.
    pub units_run: usize,
    /// Runs of simulation studies taken from the cache (a shard's).
    pub units_reused: usize,
    /// In a dry run: what would be redone, and why.
    pub redo: Vec<Redo>,
    /// Tables written.
    pub outputs: Vec<PathBuf>,
    /// Tables of the output set left as the last run wrote them.
    pub kept: Vec<PathBuf>,
    /// Rows of the published set whose status holds a warning.
    pub warnings: Vec<crate::report::Doubt>,
    /// Every input file and what became of it (the `files` table), in
    /// input order; a dry run's are not listed.
    pub inputs: Vec<super::inputs::InputFile>,
    /// How the run ran.
    #[serde(skip)]
    pub mode: super::Mode,
    /// The wall time of each phase.
    #[serde(skip)]
    pub phases: super::phases::Stopwatch,
}

impl RunReport {
    /// Number of distinct files with at least one failed stage.
    pub fn failed_files(&self) -> usize {
        let failed: std::collections::BTreeSet<&str> =
            self.failures.iter().map(|f| f.source.as_str()).collect();
        failed.len()
    }

    /// Rows without a result, over every stage.
    pub fn rows_without_result(&self) -> usize {
        self.without_result.iter().map(|w| w.rows).sum()
    }

    /// What the run counts against its exit code: a configuration error a
    /// stage met while running, and failed files or rows without a result.
    /// A dry run computes nothing, so counts nothing; a shard that finished
    /// did its part (its failed files are in the cache, and the run that
    /// publishes the set reports them), so only a configuration error
    /// counts (and holds the publishing run back).
    pub fn tally(&self) -> Tally {
        let configuration = self
            .failures
            .iter()
            .filter(|f| f.kind == ErrorKind::Configuration)
            .count();
        match self.mode {
            Mode::DryRun => Tally::ok(),
            Mode::Shard(_) => Tally {
                configuration,
                without_result: 0,
            },
            Mode::Run => Tally {
                configuration,
                without_result: self.failed_files() + self.rows_without_result(),
            },
        }
    }

    /// The exit code of the run ([`exit::code`] of its [`Self::tally`]).
    pub fn exit_code(&self) -> u8 {
        exit::code(&Ok(self.tally()))
    }

    /// The machine-readable summary of `tribo run --json`, as JSON text
    /// (a line). Serialized from the report as it is: built as a JSON
    /// value first, the rows of 20 000 inputs took 40 ms to copy and print.
    pub fn summary_json(&self) -> String {
        let mut tables: Vec<String> = self
            .outputs
            .iter()
            .chain(&self.kept)
            .filter_map(|p| p.file_stem().map(|s| s.to_string_lossy().to_string()))
            .collect();
        tables.sort();
        let summary = Summary {
            exit_code: self.exit_code(),
            files: self.files,
            files_failed: self.failed_files(),
            files_hashed: self.files_hashed,
            files_processed: self.files_processed,
            files_reused: self.files_reused,
            files_unrouted: self.unrouted.len(),
            inputs: &self.inputs,
            notes: &self.notes,
            phases_s: self.phases.times(),
            runs_computed: self.units_run,
            runs_reused: self.units_reused,
            stages_reused: self.stages_reused.len(),
            stages_run: self.stages_run.len(),
            tables,
            warnings: self.warnings.len(),
        };
        // Plain data with string keys: serializing it cannot fail.
        serde_json::to_string(&summary).unwrap_or_default()
    }

    /// The `errors` table: one row per failure.
    pub fn errors_table(&self) -> Result<Table> {
        let fl = &self.failures;
        let t = TableBuilder::new()
            .str("source", fl.iter().map(|f| Some(&f.source)))
            .str("stage", fl.iter().map(|f| Some(&f.stage)))
            .str("kind", fl.iter().map(|f| Some(f.kind.as_str())))
            .str("message", fl.iter().map(|f| Some(&f.message)))
            .build()?;
        super::registry::ERRORS.check(&t)?;
        Ok(t)
    }
}
