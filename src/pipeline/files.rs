//! The per-file phase of a run: every input is read and hashed once, its
//! kind decided, and it is handed to the per-file stages that take it. Files
//! run in parallel; results come back in input order, so that the tables
//! do not depend on the thread count.

use rayon::prelude::*;

use super::plan::{Plan, PlannedFile};
use crate::error::{Error, Result};
use crate::hash::InputHash;
use crate::ingest::kind::{classify, DataKind};
use crate::ingest::{read_data, Dataset, Reading};
use crate::stages::{Consumes, FileInput, Progress, Tables};

/// What became of one input file.
pub enum Fate {
    /// Read, and taken by these stages (indices into the plan's stages),
    /// each with its rows or why it failed.
    Taken(Vec<(usize, Result<Tables>)>),
    /// Taken by no stage, and why.
    Untaken(String),
    /// Could not be read.
    Unreadable(Error),
}

/// One input file after the per-file phase.
pub struct FileOutcome {
    /// Its hash, when it could be read from disk.
    pub hash: Option<InputHash>,
    /// What became of it.
    pub fate: Fate,
}

/// Runs the per-file stages over every input, in parallel.
pub fn process_files(plan: &Plan, progress: &dyn Progress) -> Vec<FileOutcome> {
    progress.begin("files", plan.files.len());
    plan.files
        .par_iter()
        .map(|f| {
            let outcome = process_file(plan, f);
            progress.tick();
            outcome
        })
        .collect()
}

fn process_file(plan: &Plan, f: &PlannedFile) -> FileOutcome {
    let bytes = match std::fs::read(&f.path) {
        Ok(b) => b,
        Err(e) => {
            return FileOutcome {
                hash: None,
                fate: Fate::Unreadable(Error::io(&f.path, e)),
            }
        }
    };
    let hash = InputHash::of_bytes(&f.path, &bytes);
    let fate = match read_data(&f.path, &bytes, &f.options.ingest) {
        Err(e) => Fate::Unreadable(e),
        Ok(Reading::NotData(why)) => Fate::Untaken(why),
        Ok(Reading::Data(ds)) => {
            drop(bytes);
            route(plan, f, &ds)
        }
    };
    FileOutcome {
        hash: Some(hash),
        fate,
    }
}

/// The per-file stages that read `kind`.
fn stages_for(plan: &Plan, kind: DataKind) -> Vec<usize> {
    per_file_stages(plan)
        .into_iter()
        .filter(
            |&i| matches!(plan.stages[i].stage.consumes(), Consumes::Files(k) if k.contains(&kind)),
        )
        .collect()
}

/// Indices of the per-file stages of a plan.
pub fn per_file_stages(plan: &Plan) -> Vec<usize> {
    (0..plan.stages.len())
        .filter(|&i| matches!(plan.stages[i].stage.consumes(), Consumes::Files(_)))
        .collect()
}

/// Hands a read file to the stages that take it: those whose own `files`
/// list it, else those that read its kind. A file whose columns say
/// nothing goes to the only per-file stage when there is just one (which
/// then says what it misses), and to none otherwise.
fn route(plan: &Plan, f: &PlannedFile, ds: &Dataset) -> Fate {
    let kind = classify(ds, &f.options.columns);
    let takers = if !f.forced.is_empty() {
        f.forced.clone()
    } else {
        match kind {
            Some(k) => stages_for(plan, k),
            None => match per_file_stages(plan).as_slice() {
                [only] => vec![*only],
                _ => Vec::new(),
            },
        }
    };
    if takers.is_empty() {
        return Fate::Untaken(untaken_reason(kind, ds));
    }
    let input = FileInput {
        path: &f.path,
        dataset: ds,
        columns: &f.options.columns,
        manifest: plan.manifest(),
    };
    Fate::Taken(
        takers
            .into_iter()
            .map(|i| (i, plan.stages[i].stage.run_file(&input).and_then(checked)))
            .collect(),
    )
}

/// A file's rows checked against their schemas, so that a value the
/// schema does not allow fails that file only.
fn checked(tables: Tables) -> Result<Tables> {
    for (name, t) in &tables {
        crate::schema::schema(name)?.check(t)?;
    }
    Ok(tables)
}

fn untaken_reason(kind: Option<DataKind>, ds: &Dataset) -> String {
    match kind {
        Some(k) => format!("a {k}, and no stage of this pipeline reads {k} files"),
        None => {
            let cols: Vec<&str> = ds
                .sections
                .iter()
                .flat_map(|s| s.channels.iter().map(|c| c.name.as_str()))
                .take(8)
                .collect();
            format!(
                "no stage recognises its columns {cols:?}; name their roles in \
                 [[ingest.override]] columns, or list the file in a stage's files"
            )
        }
    }
}
