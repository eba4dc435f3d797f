//! The cache as one run uses it, decided once from its [`Mode`] and
//! `--force`: a dry run writes nothing; `--force` looks nothing up; every
//! other run stores a part as soon as it is made. A part's dataset tables
//! (`traces`) are written as the files the output set publishes, with
//! their provenance: the set links them into its folder, so that the
//! cache and the output share one file.

use std::path::PathBuf;

use super::cache::{Cache, Failure, Route, RouteEntry, RowsAt};
use super::keys::Key;
use super::mode::Mode;
use super::provenance::Provenance;
use super::state::FileState;
use crate::error::Result;
use crate::schema::TableDef;
use crate::stages::{Output, Tables};

/// The cache of a run's output folder, with the run's policy.
pub struct Store {
    cache: Cache,
    mode: Mode,
    /// Look entries up (not with `--force`).
    lookup: bool,
    /// The command, for the provenance of the files a part shares with
    /// the output set.
    command: String,
}

impl Store {
    /// The store of `cache` for a run in `mode` of `command`.
    pub fn new(cache: Cache, mode: Mode, force: bool, command: &str) -> Store {
        Store {
            cache,
            mode,
            lookup: !force,
            command: command.into(),
        }
    }

    /// The command of the run.
    pub fn command(&self) -> &str {
        &self.command
    }

    /// Whether the run writes (else a missing entry is work a dry run
    /// would do).
    pub fn writes(&self) -> bool {
        self.mode.writes()
    }

    /// The cache itself.
    pub fn cache(&self) -> &Cache {
        &self.cache
    }

    /// A file's route, when cached. `last`: the file as the last run's
    /// state has it; when that state stands for the cache
    /// ([`Cache::state_stands`]) its copy is taken and the packs are not
    /// read.
    pub fn route(&self, last: Option<&FileState>, key: &Key) -> Option<RouteEntry> {
        if !self.lookup {
            return None;
        }
        if !self.cache.state_stands() {
            return self.cache.route(key);
        }
        let last = last.filter(|l| l.route.as_ref() == Some(key))?;
        Some(RouteEntry {
            sha256: last.sha256.clone()?,
            route: last.what.clone()?,
        })
    }

    /// Stores a file's route.
    pub fn put_route(&self, key: &Key, sha256: std::sync::Arc<str>, route: Route) -> RouteEntry {
        let entry = RouteEntry { sha256, route };
        if self.writes() {
            let _ = self.cache.put_route(key, &entry);
        }
        entry
    }

    /// Whether a part of `stage` is cached: `Some(Ok)` with rows,
    /// `Some(Err)` when the stage failed on the file. `last` as for
    /// [`Store::route`].
    pub fn part(
        &self,
        last: Option<&FileState>,
        stage: &str,
        key: &Key,
    ) -> Option<std::result::Result<(), Failure>> {
        if !self.lookup {
            return None;
        }
        if !self.cache.state_stands() {
            return self.cache.part(key);
        }
        let last = last.filter(|l| l.parts.get(stage) == Some(key))?;
        Some(match last.failed.get(stage) {
            Some(f) => Err(f.clone()),
            None => Ok(()),
        })
    }

    /// Where a cached part's summary rows are (made in this run or not).
    pub fn part_rows(
        &self,
        key: &Key,
        defs: &[&'static TableDef],
    ) -> Result<Vec<(&'static TableDef, RowsAt)>> {
        self.cache.part_rows(key, defs)
    }

    /// Stores a fresh part (unless in a dry run); `provenance` goes into
    /// its dataset tables' files. Returns whether it is stored: its rows
    /// are then taken from the cache ([`Store::part_rows`]).
    pub fn put_part(&self, key: &Key, part: &Result<Tables>, provenance: &Provenance) -> bool {
        self.writes() && self.cache.put_part(key, part, provenance).is_ok()
    }

    /// Writes the routes and parts this run made as one pack of the cache
    /// (at the end of the per-file phase).
    pub fn flush(&mut self) {
        if self.writes() {
            let _ = self.cache.flush();
        }
    }

    /// The file of a cached part's dataset table `name`.
    pub fn part_file(&self, key: &Key, name: &str) -> PathBuf {
        self.cache.part_file(key, name)
    }

    /// One unit of a table stage (a simulation run), when cached.
    pub fn unit(&self, key: &Key) -> Option<Vec<u8>> {
        self.lookup.then(|| self.cache.unit(key)).flatten()
    }

    /// Stores one unit's result.
    pub fn put_unit(&self, key: &Key, bytes: &[u8]) {
        if self.writes() {
            let _ = self.cache.put_unit(key, bytes);
        }
    }

    /// A table stage's output, when cached.
    pub fn stage(&self, key: &Key, defs: &[&'static TableDef]) -> Option<Result<Output>> {
        self.lookup.then(|| self.cache.stage(key, defs)).flatten()
    }

    /// Stores a table stage's output.
    pub fn put_stage(&self, key: &Key, output: &Output) {
        if self.writes() {
            let _ = self.cache.put_stage(key, output);
        }
    }
}
