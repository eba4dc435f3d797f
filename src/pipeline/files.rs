//! The per-file phase of a run: every input is read and hashed once, its
//! kind decided, and it is handed to the per-file stages that take it. Files
//! run in parallel; results come back in input order, so that the tables
//! do not depend on the thread count.

use std::borrow::Cow;

use rayon::prelude::*;

use super::cache::{Cache, Failure, Key, KeyBuilder, Route, RouteEntry};
use super::plan::{Plan, PlannedFile};
use crate::error::Result;
use crate::hash::InputHash;
use crate::ingest::kind::{classify, DataKind};
use crate::ingest::source::Source;
use crate::ingest::{read_data, Dataset, Reading};
use crate::stages::{Consumes, FileInput, Progress, Tables};

/// One stage's rows for one file: computed now, or in the cache.
pub enum Part {
    /// Computed in this run (and stored in the cache; by the runner, after
    /// the publish, when the cache holds parts: [`Cache::hold_parts`]).
    Fresh(Result<Tables>),
    /// In the cache: rows (loaded when needed), or the stage's failure.
    Cached(std::result::Result<(), Failure>),
}

/// A file taken by a stage.
pub struct Taken {
    /// The stage (index into the plan's stages).
    pub stage: usize,
    /// The key of its part.
    pub key: Key,
    /// Its rows or failure.
    pub part: Part,
}

/// What became of one input file.
pub enum Fate {
    /// Read, and taken by these stages.
    Taken(Vec<Taken>),
    /// Taken by no stage, and why.
    Untaken(String),
    /// Could not be read.
    Unreadable(Failure),
    /// Not in the cache: a dry run would read it.
    Pending,
}

/// One input file after the per-file phase.
pub struct FileOutcome {
    /// Its SHA-256, when it could be read from disk.
    pub hash: Option<InputHash>,
    /// BLAKE3 of its bytes and its route key, when read.
    pub content: Option<(String, Key)>,
    /// What became of it.
    pub fate: Fate,
}

impl FileOutcome {
    /// Whether any stage computed this file's rows in this run.
    pub fn redone(&self) -> bool {
        match &self.fate {
            Fate::Taken(t) => t.iter().any(|t| matches!(t.part, Part::Fresh(_))),
            _ => false,
        }
    }
}

/// Runs the per-file stages over every input, in parallel, taking from the
/// cache what it holds.
/// `only`: the files of this shard (indices into the plan's files); the
/// others are left out of the result.
pub fn process_files(
    plan: &Plan,
    cache: &Cache,
    only: Option<&std::collections::BTreeSet<usize>>,
    progress: &dyn Progress,
) -> Vec<(usize, FileOutcome)> {
    let mine: Vec<usize> = match only {
        Some(set) => set.iter().copied().collect(),
        None => (0..plan.files.len()).collect(),
    };
    progress.begin("files", mine.len());
    mine.par_iter()
        .map(|&i| {
            let outcome = process_file(plan, cache, &plan.files[i]);
            progress.tick();
            (i, outcome)
        })
        .collect()
}

fn process_file(plan: &Plan, cache: &Cache, f: &PlannedFile) -> FileOutcome {
    let source = match Source::open(&f.path) {
        Ok(s) => s,
        Err(e) => {
            return FileOutcome {
                hash: None,
                content: None,
                fate: Fate::Unreadable(Failure::from(&e)),
            }
        }
    };
    // The cache key takes BLAKE3 (fast: a rerun that finds every file
    // cached hashes only with it); the SHA-256 of the provenance is computed
    // once, when the route is not cached, beside the read (`read_data`).
    let blake = source.blake3();
    let rkey = KeyBuilder::new("route")
        .part(&f.path.display().to_string())
        .part(&blake)
        .part(&format!("{:?}", f.options))
        .finish();
    let (sha256, fate) = match cache.route(&rkey) {
        Some(entry) => {
            let fate = from_cache(plan, cache, f, &rkey, &entry.route, source, &entry.sha256);
            (entry.sha256, fate)
        }
        None if !cache.write => (source.sha256(), Fate::Pending),
        None => {
            let (sha256, route, fate) = read_and_route(plan, cache, f, &rkey, source, None);
            let _ = cache.put_route(
                &rkey,
                &RouteEntry {
                    sha256: sha256.clone(),
                    route,
                },
            );
            (sha256, fate)
        }
    };
    FileOutcome {
        hash: Some(InputHash {
            path: f.path.display().to_string(),
            sha256,
        }),
        content: Some((blake, rkey)),
        fate,
    }
}

/// A file whose route is cached: its parts from the cache; the file is
/// parsed only when a stage's part is missing.
fn from_cache(
    plan: &Plan,
    cache: &Cache,
    f: &PlannedFile,
    rkey: &Key,
    route: &Route,
    source: Source,
    sha256: &str,
) -> Fate {
    let (kind, unknown) = match route {
        Route::NotData(why) => return Fate::Untaken(why.clone()),
        Route::Unreadable(e) => return Fate::Unreadable(e.clone()),
        Route::Data { kind, unknown } => (*kind, unknown),
    };
    let takers = takers(plan, f, kind);
    if takers.is_empty() {
        return Fate::Untaken(untaken_reason(kind, unknown));
    }
    let keys: Vec<Key> = takers.iter().map(|&i| part_key(plan, f, rkey, i)).collect();
    let cached: Option<Vec<_>> = keys.iter().map(|k| cache.part(k)).collect();
    if let Some(cached) = cached {
        let taken = takers
            .iter()
            .zip(keys)
            .zip(cached)
            .map(|((&i, key), c)| Taken {
                stage: i,
                key,
                part: Part::Cached(c),
            })
            .collect();
        return Fate::Taken(taken);
    }
    if !cache.write {
        return Fate::Pending;
    }
    read_and_route(plan, cache, f, rkey, source, Some(sha256.to_string())).2
}

/// Reads a file, decides its route and runs the stages that take it
/// (those whose part is cached are taken from the cache). `sha256`: the
/// file's, when known; else it is computed beside the read. Returns it with
/// the route.
fn read_and_route(
    plan: &Plan,
    cache: &Cache,
    f: &PlannedFile,
    rkey: &Key,
    source: Source,
    sha256: Option<String>,
) -> (String, Route, Fate) {
    let (sha256, read) = read_data(&f.path, &source, sha256, &f.options.ingest);
    // The bytes are not needed once parsed: the analysis runs without them.
    drop(source);
    let ds = match read {
        Err(e) => {
            let failure = Failure::from(&e);
            let route = Route::Unreadable(failure.clone());
            return (sha256, route, Fate::Unreadable(failure));
        }
        Ok(Reading::NotData(why)) => {
            return (sha256, Route::NotData(why.clone()), Fate::Untaken(why))
        }
        Ok(Reading::Data(ds)) => ds,
    };
    let kind = classify(&ds, &f.options.columns);
    let unknown = if kind.is_none() {
        unknown_columns(&ds)
    } else {
        String::new()
    };
    let takers = takers(plan, f, kind);
    let fate = if takers.is_empty() {
        Fate::Untaken(untaken_reason(kind, &unknown))
    } else {
        Fate::Taken(run_takers(plan, cache, f, rkey, ds, &takers))
    };
    (sha256, Route::Data { kind, unknown }, fate)
}

/// Runs the stages that take the file, each from the cache when it holds
/// its part; the last stage to compute gets the dataset itself, the others
/// a view of it.
fn run_takers(
    plan: &Plan,
    cache: &Cache,
    f: &PlannedFile,
    rkey: &Key,
    ds: Dataset,
    takers: &[usize],
) -> Vec<Taken> {
    let keys: Vec<(usize, Key)> = takers
        .iter()
        .map(|&i| (i, part_key(plan, f, rkey, i)))
        .collect();
    let cached: Vec<Option<_>> = keys.iter().map(|(_, k)| cache.part(k)).collect();
    let last = cached.iter().rposition(Option::is_none);
    let mut ds = Some(ds);
    let mut taken = Vec::with_capacity(keys.len());
    for (j, ((i, key), c)) in keys.into_iter().zip(cached).enumerate() {
        let part = match c {
            Some(c) => Part::Cached(c),
            None => {
                let dataset = match Some(j) == last {
                    true => Cow::Owned(ds.take().expect("the dataset is taken once, last")),
                    false => Cow::Borrowed(ds.as_ref().expect("taken only by the last")),
                };
                let input = FileInput {
                    path: &f.path,
                    dataset,
                    columns: &f.options.columns,
                    manifest: plan.manifest(),
                };
                let r = plan.stages[i].stage.run_file(input).and_then(checked);
                if !cache.hold_parts {
                    let _ = cache.put_part(&key, &r, &[]);
                }
                Part::Fresh(r)
            }
        };
        taken.push(Taken {
            stage: i,
            key,
            part,
        });
    }
    taken
}

/// The key of one stage's rows for one file: the file (route key), the
/// stage with its validated parameters and tables, and the file's row of
/// the manifest.
fn part_key(plan: &Plan, f: &PlannedFile, rkey: &Key, i: usize) -> Key {
    let stage = plan.stages[i].stage.as_ref();
    let row = plan.manifest().and_then(|m| m.find(&f.path));
    KeyBuilder::new("part")
        .part(&rkey.0)
        .part(stage.name())
        .part(&stage.parameters().to_string())
        .part(&table_names(stage))
        .part(&format!("{row:?}"))
        .finish()
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

/// The stages that take a file: those whose own `files` list it, else
/// those that read its kind. A file whose columns say nothing goes to the
/// only per-file stage when there is just one (which then says what it
/// misses), and to none otherwise.
fn takers(plan: &Plan, f: &PlannedFile, kind: Option<DataKind>) -> Vec<usize> {
    if !f.forced.is_empty() {
        return f.forced.clone();
    }
    match kind {
        Some(k) => stages_for(plan, k),
        None => match per_file_stages(plan).as_slice() {
            [only] => vec![*only],
            _ => Vec::new(),
        },
    }
}

/// A file's rows checked against their schemas, so that a value the
/// schema does not allow fails that file only.
fn checked(tables: Tables) -> Result<Tables> {
    for (def, t) in &tables {
        def.check(t)?;
    }
    Ok(tables)
}

/// The names of the tables a stage produces, for keys.
pub(super) fn table_names(stage: &dyn crate::stages::StagePlan) -> String {
    let names: Vec<&str> = stage.produces().iter().map(|d| d.name).collect();
    names.join(",")
}

fn untaken_reason(kind: Option<DataKind>, unknown: &str) -> String {
    match kind {
        Some(k) => format!("a {k}, and no stage of this pipeline reads {k} files"),
        None => unknown.to_string(),
    }
}

/// Why a file has no kind: the columns it has.
fn unknown_columns(ds: &Dataset) -> String {
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
