//! What became of one input file in the per-file phase ([`super::files`]):
//! one [`FileResult`] from there to the published set. The stages take
//! their [`Part`]s from it, the `files` table its row, the run's state its
//! [`FileState`], the errors its failures.

use super::by_name::ByName;
use super::cache::{Failure, Route};
use super::inputs::{InputFile, Outcome};
use super::keys::Key;
use super::outcome::FileFailure;
use super::plan::{Plan, PlannedFile};
use super::state::{FileStat, FileState};
use crate::error::ErrorKind;
use crate::hash::InputHash;
use crate::ingest::kind::DataKind;
use crate::stages::Tables;

/// One stage's rows for one file.
pub struct Part {
    /// The stage (index into the plan's stages).
    pub stage: usize,
    /// The key of the part in the cache.
    pub key: Key,
    /// The rows.
    pub rows: Rows,
    /// The file behind the rows, for the stage's provenance (unless the
    /// stage failed on it).
    pub input: Option<InputHash>,
}

/// A part's rows.
pub enum Rows {
    /// Made in this run: its summary tables when the cache could not
    /// store them (else they are taken from the cache's new pack).
    Made(Option<Tables>),
    /// In the cache (loaded when a stage needs them).
    Cached,
    /// The stage failed on the file (in this run, or in the cache).
    Failed(Failure),
}

/// What became of one input file.
pub enum Fate {
    /// Read with this data file (a companion), not on its own.
    Companion(String),
    /// Read, and taken by these stages.
    Taken(Vec<Part>),
    /// Taken by no stage, and why.
    NotTaken(String),
    /// Could not be read.
    Unreadable(Failure),
    /// Not in the cache: a dry run would read it.
    Pending,
}

/// One input file after the per-file phase.
pub struct FileResult {
    /// Its SHA-256, when it could be read from disk.
    pub hash: Option<InputHash>,
    /// Its size, when it could be opened.
    pub size: Option<u64>,
    /// What it is (its reader and kind, or why no stage takes it), when
    /// read or known from the cache.
    pub route: Option<Route>,
    /// BLAKE3 of its bytes and its route key, when read.
    pub content: Option<(String, Key)>,
    /// How it looked on disk when its bytes were hashed.
    pub stat: Option<FileStat>,
    /// Whether it was read and hashed in this run (not taken as unchanged
    /// from its stat).
    pub hashed: bool,
    /// What became of it.
    pub fate: Fate,
}

impl FileResult {
    pub(super) fn new(fate: Fate) -> Self {
        FileResult {
            hash: None,
            size: None,
            route: None,
            content: None,
            stat: None,
            hashed: false,
            fate,
        }
    }

    /// Its reader and kind, when it is data.
    pub fn read(&self) -> Option<(&str, Option<DataKind>)> {
        match &self.route {
            Some(Route::Data { format, kind, .. }) => Some((format, *kind)),
            _ => None,
        }
    }

    /// Whether any stage made this file's rows in this run.
    pub fn redone(&self) -> bool {
        match &self.fate {
            Fate::Taken(t) => t.iter().any(|p| matches!(p.rows, Rows::Made(_))),
            _ => false,
        }
    }

    /// Its failures: the reader's, each taking stage's, or none taking a
    /// file named as an input (`f.named`).
    pub fn failures(&self, plan: &Plan, f: &PlannedFile) -> Vec<FileFailure> {
        let source = f.source.clone();
        match &self.fate {
            Fate::Unreadable(e) => vec![FileFailure::from_failure(source, "ingest", e)],
            Fate::NotTaken(why) if f.named => vec![FileFailure {
                message: format!("{source}: named as an input, but no stage takes it: {why}"),
                source,
                stage: "ingest".into(),
                kind: ErrorKind::BadInput,
            }],
            Fate::Taken(parts) => parts
                .iter()
                .filter_map(|p| match &p.rows {
                    Rows::Failed(e) => {
                        let stage = plan.stages[p.stage].stage.name();
                        Some(FileFailure::from_failure(source.clone(), stage, e))
                    }
                    _ => None,
                })
                .collect(),
            _ => Vec::new(),
        }
    }

    /// Its row of the `files` table, given its `failures`.
    pub fn row(&self, plan: &Plan, f: &PlannedFile, failures: &[FileFailure]) -> InputFile {
        let mut row = InputFile {
            file: f.source.clone(),
            size_bytes: self.size,
            sha256: self.hash.as_ref().map(|h| h.sha256.clone()),
            format: self.read().map(|r| r.0.to_string()),
            kind: self.read().and_then(|r| r.1),
            stages: Vec::new(),
            outcome: Outcome::Processed,
            reason: None,
            companion_of: None,
        };
        match &self.fate {
            Fate::Companion(data) => {
                row.outcome = Outcome::Companion;
                row.companion_of = Some(data.clone());
            }
            Fate::NotTaken(why) if !f.named => {
                row.outcome = Outcome::NotTaken;
                row.reason = Some(why.clone());
            }
            Fate::Taken(parts) => {
                let name = |p: &Part| plan.stages[p.stage].stage.name().to_string();
                row.stages = parts.iter().map(name).collect();
            }
            _ => {}
        }
        if !failures.is_empty() {
            row.outcome = Outcome::Failed;
            let why: Vec<String> = failures
                .iter()
                .map(|f| format!("{}: {}", f.stage, f.message))
                .collect();
            row.reason = Some(why.join("; "));
        }
        row
    }

    /// What the run's state keeps of it: its bytes' hash, its route and
    /// its parts' keys by stage; `None` when it was not read.
    pub fn state(&self, plan: &Plan) -> Option<FileState> {
        let (bytes, route) = self.content.clone()?;
        let taken: &[Part] = match &self.fate {
            Fate::Taken(taken) => taken,
            _ => &[],
        };
        let stage = |p: &Part| plan.stages[p.stage].stage.name().to_string();
        // Collected, each list is as long as it needs: most inputs have one
        // stage, and an insert each left room for four.
        let parts: ByName<Key> = taken.iter().map(|p| (stage(p), p.key)).collect();
        let failed = taken
            .iter()
            .filter_map(|p| match &p.rows {
                Rows::Failed(e) => Some((stage(p), e.clone())),
                _ => None,
            })
            .collect();
        Some(FileState {
            bytes,
            route: Some(route),
            parts,
            sha256: self.hash.as_ref().map(|h| h.sha256.clone()),
            stat: self.stat.clone(),
            what: self.route.clone(),
            failed,
        })
    }
}
