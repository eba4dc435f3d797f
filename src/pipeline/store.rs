//! The cache as one run uses it, decided once from its [`Mode`] and
//! `--force`: a dry run writes nothing; `--force` looks nothing up; a
//! one-file run holds its fresh per-file parts until the set is published,
//! so that a table the set publishes as it is becomes a hard link to the
//! published file (one file, two names) instead of a second copy; every
//! other run stores a part as soon as it is made.

use std::path::PathBuf;
use std::sync::Mutex;

use super::cache::{Cache, Failure, Route, RouteEntry};
use super::keys::Key;
use super::mode::Mode;
use crate::error::Result;
use crate::schema::TableDef;
use crate::stages::{Output, Tables};
use crate::table::Table;

/// Where fresh per-file parts go.
enum Parts {
    /// Into the cache at once.
    Store,
    /// Held until the set is published, then stored (linked where the set
    /// publishes a table as it is).
    Hold(Mutex<Vec<(Key, Tables)>>),
    /// Nowhere (a dry run).
    Discard,
}

/// The cache of a run's output folder, with the run's policy.
pub struct Store {
    cache: Cache,
    mode: Mode,
    /// Look entries up (not with `--force`).
    lookup: bool,
    parts: Parts,
}

impl Store {
    /// The store of `cache` for a run in `mode` over `files` inputs.
    pub fn new(cache: Cache, mode: Mode, force: bool, files: usize) -> Store {
        let parts = match mode {
            Mode::DryRun => Parts::Discard,
            Mode::Run if files == 1 => Parts::Hold(Mutex::new(Vec::new())),
            _ => Parts::Store,
        };
        Store {
            cache,
            mode,
            lookup: !force,
            parts,
        }
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

    /// A file's route, when cached.
    pub fn route(&self, key: &Key) -> Option<RouteEntry> {
        self.cache.route(key).filter(|_| self.lookup)
    }

    /// Stores a file's route.
    pub fn put_route(&self, key: &Key, sha256: String, route: Route) -> RouteEntry {
        let entry = RouteEntry { sha256, route };
        if self.writes() {
            let _ = self.cache.put_route(key, &entry);
        }
        entry
    }

    /// Whether a part is cached: `Some(Ok)` with rows, `Some(Err)` when the
    /// stage failed on the file.
    pub fn part(&self, key: &Key) -> Option<std::result::Result<(), Failure>> {
        self.lookup.then(|| self.cache.part(key)).flatten()
    }

    /// A cached part's tables.
    pub fn load_part(&self, key: &Key, defs: &[&'static TableDef]) -> Result<Tables> {
        self.cache.load_part(key, defs)
    }

    /// A fresh part: stored now, held until the publish, or dropped (a dry
    /// run). A failure has no table to link: it is stored at once.
    pub fn put_part(&self, key: &Key, part: &Result<Tables>) {
        match (&self.parts, part) {
            (Parts::Discard, _) => {}
            (Parts::Hold(held), Ok(tables)) => {
                if let Ok(mut h) = held.lock() {
                    h.push((key.clone(), tables.clone()));
                }
            }
            _ => {
                let _ = self.cache.put_part(key, part, &[]);
            }
        }
    }

    /// Stores the held parts once the set is published: a table that
    /// `published` finds in the set as it is (the very table, not an equal
    /// one) becomes a hard link to that file.
    pub fn release(&self, published: impl Fn(&TableDef, &Table) -> Option<PathBuf>) {
        let Parts::Hold(held) = &self.parts else {
            return;
        };
        let held = held.lock().map(|mut h| std::mem::take(&mut *h));
        for (key, tables) in held.unwrap_or_default() {
            let linked: Vec<(&str, PathBuf)> = tables
                .iter()
                .filter_map(|(def, t)| Some((def.name, published(def, t)?)))
                .collect();
            let _ = self.cache.put_part(&key, &Ok(tables.clone()), &linked);
        }
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
