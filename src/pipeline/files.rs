//! The per-file phase of a run: every input is read and hashed once, its
//! kind decided, and it is handed to the per-file stages that take it. An
//! input whose stat is the one the last run saw, and whose route and parts
//! are cached, is not read at all ([`FileStat::unchanged`]). Files
//! run in parallel; results come back in input order, so that the tables
//! do not depend on the thread count.
//!
//! A file's result is one [`FileResult`] from here to the published set:
//! the stages take their [`Part`]s from it, the `files` table its row, the
//! run's state its [`FileState`], the errors its failures.

use std::borrow::Cow;
use std::collections::BTreeSet;
use std::sync::Arc;

use rayon::prelude::*;

use super::cache::{Failure, Route};
pub use super::file_result::{Fate, FileResult, Part, Rows};
use super::keys::{part_key, route_key, Key};
use super::plan::{Plan, PlannedFile};
use super::provenance::Provenance;
use super::route;
use super::shared::Shared;
use super::state::{beside_now, beside_unchanged, FileStat, FileState, State};
use super::store::Store;
use crate::error::Result;
use crate::hash::InputHash;
use crate::ingest::kind::DataKind;
use crate::ingest::source::Source;
use crate::ingest::{read_data, Dataset, Reading};
use crate::stages::{FileInput, Progress, StagePlan, Tables};

/// The files of a run: those of a shard (indices into the plan's files),
/// or all of them (`None`).
type Only<'a> = Option<&'a BTreeSet<usize>>;

fn indices(plan: &Plan, only: Only) -> Vec<usize> {
    match only {
        Some(set) => set.iter().copied().collect(),
        None => (0..plan.files.len()).collect(),
    }
}

/// Each input's stat, now, in parallel (`None` for a file that is not
/// `only`'s or cannot be looked at), by index into the plan's files.
pub fn stats(plan: &Plan, only: Only) -> Vec<Option<FileStat>> {
    plan.files
        .par_iter()
        .enumerate()
        .map(|(i, f)| {
            let mine = only.is_none_or(|s| s.contains(&i));
            mine.then(|| FileStat::of(&f.path)).flatten()
        })
        .collect()
}

/// The last run's state as the per-file phase reads it; `keys`: its
/// inputs' keys were made in this run's context ([`super::keys::context_key`]),
/// so an unchanged input's are taken as they are, not hashed again.
#[derive(Clone, Copy)]
pub struct Known<'a> {
    /// The state.
    pub state: &'a State,
    /// Whether its keys hold for this run.
    pub keys: bool,
}

/// Runs the per-file stages over every input, in parallel, taking from the
/// cache what it holds.
/// `only`: the files of this shard (indices into the plan's files), the
/// others left out of the result, with each file's stat ([`stats`]).
/// `known`: the last run's state, whose unchanged files are not read
/// (`None`: read and hash every file).
pub fn process_files(
    plan: &Plan,
    store: &Store,
    (only, stats): (Only, &[Option<FileStat>]),
    known: Option<Known>,
    progress: &dyn Progress,
) -> Vec<Processed> {
    let mine = indices(plan, only);
    let keys = known.is_some_and(|k| k.keys);
    progress.begin("files", mine.len());
    mine.par_iter()
        .map(|&i| {
            let f = &plan.files[i];
            let entry = known.and_then(|k| k.state.files.get(&f.source));
            let last = entry.map(|l| (&**l, keys));
            let result = process_file(plan, store, f, last, stats[i].clone());
            progress.tick();
            (i, result, entry.cloned())
        })
        .collect()
}

/// An input (index into the plan's files), what became of it, and its
/// entry in the last run's state (looked up once, here).
pub type Processed = (usize, FileResult, Option<Shared<FileState>>);

/// `last`: the file as the last run's state has it, and whether its keys
/// hold for this run ([`Known`]).
fn process_file(
    plan: &Plan,
    store: &Store,
    f: &PlannedFile,
    last: Option<(&FileState, bool)>,
    stat: Option<FileStat>,
) -> FileResult {
    if let Some(r) = unchanged(plan, store, f, last, stat.as_ref()) {
        return r;
    }
    FileResult {
        stat,
        hashed: true,
        ..read_file(plan, store, f, last.map(|(l, _)| l))
    }
}

/// A file whose stat is the one the last run saw (so its bytes are taken
/// as the ones it hashed), with its route and every part in the cache:
/// its result without reading it. `None` when anything is missing.
fn unchanged(
    plan: &Plan,
    store: &Store,
    f: &PlannedFile,
    last: Option<(&FileState, bool)>,
    stat: Option<&FileStat>,
) -> Option<FileResult> {
    let ((last, keys), stat) = (last?, stat?);
    let seen = last.stat.as_ref()?;
    if !seen.unchanged(stat) {
        return None;
    }
    if let Some(data) = &f.companion_of {
        return unchanged_companion(f, data, last, seen);
    }
    // Its companions are in its key: the key holds when the files that
    // decide them are as they were (their stats, taken once, before the
    // key is made again from their bytes).
    let now = beside_now(&f.path);
    let kept = keys && beside_unchanged(&last.beside, &now);
    let (rkey, beside) = match (kept, last.route) {
        (true, Some(k)) => (k, last.beside.clone()),
        _ => (route_key(f, &last.bytes), now),
    };
    let entry = store.route(Some(last), &rkey)?;
    let cached = Cached {
        at: Lookup {
            rkey: &rkey,
            last: Some(last),
            kept,
        },
        route: &entry.route,
    };
    let fate = cached_fate(plan, store, f, cached)?;
    Some(FileResult {
        hash: Some(InputHash {
            path: f.source.as_str().into(),
            sha256: entry.sha256,
        }),
        size: Some(stat.len),
        route: Some(entry.route),
        content: Some((last.bytes.clone(), Some(rkey))),
        // The stat as it was when the bytes were hashed.
        stat: Some(seen.clone()),
        beside,
        hashed: false,
        fate,
    })
}

/// A companion of `data` whose stat is the one the last run saw (`seen`):
/// its row's size and hashes as that run read them, without reading it.
/// What it adds to its data file is in that file's key ([`route_key`]).
fn unchanged_companion(
    f: &PlannedFile,
    data: &std::path::Path,
    last: &FileState,
    seen: &FileStat,
) -> Option<FileResult> {
    Some(FileResult {
        hash: Some(InputHash {
            path: f.source.as_str().into(),
            sha256: last.sha256.clone()?,
        }),
        size: Some(seen.len),
        content: Some((last.bytes.clone(), None)),
        stat: Some(seen.clone()),
        ..FileResult::new(Fate::Companion(data.display().to_string()))
    })
}

/// Reads and hashes a file, then takes from the cache what it holds
/// (`last`: the file as the last run's state has it).
fn read_file(plan: &Plan, store: &Store, f: &PlannedFile, last: Option<&FileState>) -> FileResult {
    let source = match Source::open(&f.path) {
        Ok(s) => s,
        Err(e) => return FileResult::new(Fate::Unreadable(Failure::from(&e))),
    };
    let size = Some(source.bytes().len() as u64);
    let hash = |sha256: Arc<str>| {
        Some(InputHash {
            path: f.source.as_str().into(),
            sha256,
        })
    };
    if let Some(data) = &f.companion_of {
        // Its BLAKE3 for the state: its stat and hashes there let the next
        // run take its row without reading it.
        return FileResult {
            hash: hash(source.sha256().into()),
            size,
            content: Some((source.blake3().into(), None)),
            ..FileResult::new(Fate::Companion(data.display().to_string()))
        };
    }
    // The cache key takes BLAKE3 (fast: a rerun that finds every file
    // cached hashes only with it); the SHA-256 of the provenance is computed
    // once, when the route is not cached, beside the read (`read_data`).
    let blake = source.blake3();
    let beside = beside_now(&f.path);
    let rkey = route_key(f, &blake);
    let (sha256, route, fate) = match store.route(last, &rkey) {
        Some(entry) => {
            let at = Lookup {
                rkey: &rkey,
                last,
                kept: false,
            };
            let cached = Cached {
                at,
                route: &entry.route,
            };
            let fate = from_cache(plan, store, f, cached, source, &entry.sha256);
            (entry.sha256, Some(entry.route), fate)
        }
        None if !store.writes() => (source.sha256().into(), None, Fate::Pending),
        None => {
            let at = Lookup {
                rkey: &rkey,
                last,
                kept: false,
            };
            let (sha256, route, fate) = read_and_route(plan, store, f, at, source, None);
            let entry = store.put_route(&rkey, sha256, route);
            (entry.sha256, Some(entry.route), fate)
        }
    };
    FileResult {
        hash: hash(sha256),
        size,
        route,
        content: Some((blake.into(), Some(rkey))),
        stat: None,
        beside,
        hashed: true,
        fate,
    }
}

/// A file whose route is cached: its parts from the cache; the file is
/// parsed only when a stage's part is missing.
fn from_cache(
    plan: &Plan,
    store: &Store,
    f: &PlannedFile,
    cached: Cached,
    source: Source,
    sha256: &str,
) -> Fate {
    if let Some(fate) = cached_fate(plan, store, f, cached) {
        return fate;
    }
    if !store.writes() {
        return Fate::Pending;
    }
    read_and_route(plan, store, f, cached.at, source, Some(sha256.to_string())).2
}

/// Where a file's cache entries are looked up: its route's key, and the
/// file as the last run's state has it ([`Store::route`]); `kept`: its
/// keys there hold for this run ([`Known`]).
#[derive(Clone, Copy)]
struct Lookup<'a> {
    rkey: &'a Key,
    last: Option<&'a FileState>,
    kept: bool,
}

/// A file whose route is cached, with the route.
#[derive(Clone, Copy)]
struct Cached<'a> {
    at: Lookup<'a>,
    route: &'a Route,
}

/// What became of a file whose route is cached, from the cache alone;
/// `None` when a stage's part is missing.
fn cached_fate(plan: &Plan, store: &Store, f: &PlannedFile, cached: Cached) -> Option<Fate> {
    let (kind, unknown) = match cached.route {
        Route::NotData(why) => return Some(Fate::NotTaken(why.clone())),
        Route::Unreadable(e) => return Some(Fate::Unreadable(e.clone())),
        Route::Data { kind, unknown, .. } => (*kind, unknown),
    };
    let takers = takers(plan, f, kind);
    if takers.is_empty() {
        return Some(Fate::NotTaken(route::untaken_reason(kind, unknown)));
    }
    let at = cached.at;
    let parts = takers
        .into_iter()
        .map(|stage| {
            let name = plan.stages[stage].stage.name();
            let kept = at.last.filter(|_| at.kept).and_then(|l| l.parts.get(name));
            let key = kept
                .copied()
                .unwrap_or_else(|| part_key(&plan.stages[stage], f, at.rkey, plan.manifest()));
            let rows = cached_rows(store.part(at.last, name, &key)?);
            Some(Part {
                stage,
                key,
                rows,
                input: None,
            })
        })
        .collect::<Option<_>>()?;
    Some(Fate::Taken(parts))
}

fn cached_rows(c: std::result::Result<(), Failure>) -> Rows {
    match c {
        Ok(()) => Rows::Cached,
        Err(e) => Rows::Failed(e),
    }
}

/// Reads a file, decides its route and runs the stages that take it
/// (those whose part is cached are taken from the cache). `sha256`: the
/// file's, when known; else it is computed beside the read. Returns it with
/// the route.
fn read_and_route(
    plan: &Plan,
    store: &Store,
    f: &PlannedFile,
    at: Lookup,
    source: Source,
    sha256: Option<String>,
) -> (Arc<str>, Route, Fate) {
    let (sha256, read) = read_data(&f.path, &source, sha256, &f.options.ingest);
    // One string for the route's entry and the parts' provenance.
    let sha256: Arc<str> = sha256.into();
    // The bytes are not needed once parsed: the analysis runs without them.
    drop(source);
    let ds = match read {
        Err(e) => {
            let failure = Failure::from(&e);
            let route = Route::Unreadable(failure.clone());
            return (sha256, route, Fate::Unreadable(failure));
        }
        Ok(Reading::NotData(why)) => {
            return (sha256, Route::NotData(why.clone()), Fate::NotTaken(why))
        }
        Ok(Reading::Data(ds)) => ds,
    };
    let (kind, unknown) = route::kind_of(&ds, &f.options.columns);
    let format = super::shared::interned(ds.format);
    let takers = takers(plan, f, kind);
    let fate = if takers.is_empty() {
        Fate::NotTaken(route::untaken_reason(kind, &unknown))
    } else {
        let input = InputHash {
            path: f.source.as_str().into(),
            sha256: Arc::clone(&sha256),
        };
        Fate::Taken(run_takers(plan, store, f, at, ds, &takers, input))
    };
    let route = Route::Data {
        format,
        kind,
        unknown,
    };
    (sha256, route, fate)
}

/// Runs the stages that take the file (`input`), each from the cache when
/// it holds its part; the last stage to compute gets the dataset itself,
/// the others a view of it.
fn run_takers(
    plan: &Plan,
    store: &Store,
    f: &PlannedFile,
    at: Lookup,
    ds: Dataset,
    takers: &[usize],
    input: InputHash,
) -> Vec<Part> {
    let keys: Vec<(usize, Key)> = takers
        .iter()
        .map(|&i| (i, part_key(&plan.stages[i], f, at.rkey, plan.manifest())))
        .collect();
    let cached: Vec<Option<_>> = keys
        .iter()
        .map(|(i, k)| store.part(at.last, plan.stages[*i].stage.name(), k))
        .collect();
    let last = cached.iter().rposition(Option::is_none);
    let mut ds = Some(ds);
    let mut parts = Vec::with_capacity(keys.len());
    for (j, ((stage, key), c)) in keys.into_iter().zip(cached).enumerate() {
        let rows = match c {
            Some(c) => cached_rows(c),
            None => {
                let dataset = match Some(j) == last {
                    true => Cow::Owned(ds.take().expect("the dataset is taken once, last")),
                    false => Cow::Borrowed(ds.as_ref().expect("taken only by the last")),
                };
                let file = FileInput {
                    path: &f.path,
                    dataset,
                    columns: &f.options.columns,
                    manifest: plan.manifest(),
                };
                let stage = plan.stages[stage].stage.as_ref();
                let made = stage.run_file(file).and_then(checked);
                let prov = Provenance::of_stage(
                    store.command(),
                    stage,
                    vec![input.clone()].into(),
                    &plan.spec_json,
                );
                let stored = store.put_part(&key, &made, &prov);
                match made {
                    Ok(tables) => Rows::Made((!stored).then(|| without_datasets(tables))),
                    Err(e) => Rows::Failed(Failure::from(&e)),
                }
            }
        };
        parts.push(Part {
            stage,
            key,
            rows,
            input: None,
        });
    }
    parts
}

/// A part's tables but its dataset tables, which the set publishes from
/// the cache's files: held until the join, the traces of a first run over
/// 20 000 files took 7 GB.
fn without_datasets(tables: Tables) -> Tables {
    tables
        .into_iter()
        .filter(|(d, _)| !d.is_dataset())
        .collect()
}

/// Indices of the per-file stages of a plan.
pub fn per_file_stages(plan: &Plan) -> Vec<usize> {
    route::per_file(plan.stage_plans())
}

/// The stages that take a file of `kind` ([`route::takers`]).
fn takers(plan: &Plan, f: &PlannedFile, kind: Option<DataKind>) -> Vec<usize> {
    let stages = plan
        .stages
        .iter()
        .map(|s| s.stage.as_ref() as &dyn StagePlan);
    route::takers(stages, &f.forced, kind)
}

/// A file's rows checked against their schemas, where they are made, so
/// that a value the schema does not allow fails that file only.
fn checked(tables: Tables) -> Result<Tables> {
    for (def, t) in &tables {
        def.check(t)?;
    }
    Ok(tables)
}
