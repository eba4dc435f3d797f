//! The per-file phase of a run: every input is read and hashed once, its
//! kind decided, and it is handed to the per-file stages that take it. Files
//! run in parallel; results come back in input order, so that the tables
//! do not depend on the thread count.

use std::borrow::Cow;

use rayon::prelude::*;

use super::cache::{Cache, Failure, Key, KeyBuilder, Route, RouteEntry};
use super::plan::{Plan, PlannedFile};
use super::route;
use crate::error::Result;
use crate::hash::InputHash;
use crate::ingest::kind::DataKind;
use crate::ingest::source::Source;
use crate::ingest::{read_data, Dataset, Reading};
use crate::stages::{FileInput, Progress, Tables};

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
    /// Read with this data file (a companion), not on its own.
    Companion(String),
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
    /// Its size, when it could be opened.
    pub size: Option<u64>,
    /// Its reader and kind, when read.
    pub read: Option<(String, Option<DataKind>)>,
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

/// The kind of key of a file's route (its version: a route entry holds the
/// file's reader since `route/2`).
const ROUTE: &str = "route/2";

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
                size: None,
                read: None,
                content: None,
                fate: Fate::Unreadable(Failure::from(&e)),
            }
        }
    };
    let size = Some(source.bytes().len() as u64);
    let hash = |sha256| {
        Some(InputHash {
            path: f.path.display().to_string(),
            sha256,
        })
    };
    if let Some(data) = &f.companion_of {
        return FileOutcome {
            hash: hash(source.sha256()),
            size,
            read: None,
            content: None,
            fate: Fate::Companion(data.display().to_string()),
        };
    }
    // The cache key takes BLAKE3 (fast: a rerun that finds every file
    // cached hashes only with it); the SHA-256 of the provenance is computed
    // once, when the route is not cached, beside the read (`read_data`).
    let blake = source.blake3();
    let rkey = KeyBuilder::new(ROUTE)
        .part(&f.path.display().to_string())
        .part(&blake)
        .part(&format!("{:?}", f.options))
        .finish();
    let (sha256, route, fate) = match cache.route(&rkey) {
        Some(entry) => {
            let fate = from_cache(plan, cache, f, &rkey, &entry.route, source, &entry.sha256);
            (entry.sha256, Some(entry.route), fate)
        }
        None if !cache.write => (source.sha256(), None, Fate::Pending),
        None => {
            let (sha256, route, fate) = read_and_route(plan, cache, f, &rkey, source, None);
            let entry = RouteEntry {
                sha256: sha256.clone(),
                route,
            };
            let _ = cache.put_route(&rkey, &entry);
            (sha256, Some(entry.route), fate)
        }
    };
    let read = match route {
        Some(Route::Data { format, kind, .. }) => Some((format, kind)),
        _ => None,
    };
    FileOutcome {
        hash: hash(sha256),
        size,
        read,
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
        Route::Data { kind, unknown, .. } => (*kind, unknown),
    };
    let takers = takers(plan, f, kind);
    if takers.is_empty() {
        return Fate::Untaken(route::untaken_reason(kind, unknown));
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
    let (kind, unknown) = route::kind_of(&ds, &f.options.columns);
    let ds_format = ds.format;
    let takers = takers(plan, f, kind);
    let fate = if takers.is_empty() {
        Fate::Untaken(route::untaken_reason(kind, &unknown))
    } else {
        Fate::Taken(run_takers(plan, cache, f, rkey, ds, &takers))
    };
    let format = ds_format.to_string();
    (
        sha256,
        Route::Data {
            format,
            kind,
            unknown,
        },
        fate,
    )
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

/// Indices of the per-file stages of a plan.
pub fn per_file_stages(plan: &Plan) -> Vec<usize> {
    route::per_file(&plan.stage_plans())
}

/// The stages that take a file of `kind` ([`route::takers`]).
fn takers(plan: &Plan, f: &PlannedFile, kind: Option<DataKind>) -> Vec<usize> {
    route::takers(&plan.stage_plans(), &f.forced, kind)
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
