//! The content-addressed cache of an output folder (`OUT/.tribo/cache/`),
//! so that a rerun redoes only what changed.
//!
//! - `routes/<key>.json`: what a file is (its kind, or why no stage takes
//!   it, or why it cannot be read) and its SHA-256, keyed by (tribo
//!   version, path, BLAKE3 of its bytes, reading options); the SHA-256 is
//!   computed once, when the route is not cached, and given to the reader;
//! - `parts/<key>/`: one per-file stage's rows for one file, a Parquet
//!   file per table, uncompressed and without statistics (quick to write;
//!   only tribo reads it) (or the stage's failure), keyed by the route key
//!   plus the stage, its validated parameters and the file's manifest row.
//!   A dataset table (`traces`) is written as the file the output set
//!   publishes (compressed, with its provenance), which the set links into
//!   its folder (one file, two names), kept with the file's [`Stamp`]: a
//!   published file rewritten in place no longer matches, and the part is
//!   made again;
//! - `units/<key>.json`: one run of a simulation study, keyed by the
//!   stage's parameters and the run's index (a shard's share);
//! - `stages/<key>/`: a table or simulation stage's output, keyed by its
//!   parameters and what it reads (so a shard's simulation is reused by the
//!   run that assembles the shards).
//!
//! Entries are written into a fresh temporary folder and renamed into
//! place, so a killed run leaves whole entries or none; a killed run's
//! temporary entries are removed by the next published run, never those
//! of a run or shard still alive ([`super::owner`]). Keys use BLAKE3
//! (fast); the provenance keeps SHA-256.

use std::collections::BTreeSet;
use std::fs;
use std::io::Write;
use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};

pub use super::keys::{Key, KeyBuilder};
use super::owner::{is_leftover, temp_name};
use super::provenance::Provenance;
use super::state::Stamp;
use crate::error::{Error, ErrorKind, Result};
use crate::ingest::kind::DataKind;
use crate::schema::def::find;
use crate::schema::TableDef;
use crate::stages::{Output, Tables};
use crate::table::Table;

/// A failure as the cache keeps it.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct Failure {
    /// Its family.
    pub kind: ErrorKind,
    /// The message with its location.
    pub message: String,
}

impl From<&Error> for Failure {
    fn from(e: &Error) -> Self {
        Failure {
            kind: e.kind(),
            message: e.to_string(),
        }
    }
}

/// What a file is, once read.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub enum Route {
    /// Data: its reader, and its kind when its columns tell (else why
    /// not).
    Data {
        /// The reader that understood it.
        format: String,
        /// The kind.
        kind: Option<DataKind>,
        /// Why no kind, when none (the columns it has).
        unknown: String,
    },
    /// Not data (a notes file), and why.
    NotData(String),
    /// Cannot be read.
    Unreadable(Failure),
}

/// A file's route with its SHA-256 (for the provenance).
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct RouteEntry {
    /// SHA-256 of the bytes, hex.
    pub sha256: String,
    /// What it is.
    pub route: Route,
}

/// What a part holds: its tables, or the stage's failure.
#[derive(Debug, Clone, Serialize, Deserialize)]
enum PartEntry {
    Tables(Vec<StoredTable>),
    Failed(Failure),
}

/// One table of a part: its name, and the stamp of its file when the
/// output set shares it (a dataset's file).
#[derive(Debug, Clone, Serialize, Deserialize)]
struct StoredTable {
    name: String,
    linked: Option<Stamp>,
}

/// A table or simulation stage's output as the cache keeps it.
#[derive(Debug, Clone, Serialize, Deserialize)]
struct StageEntry {
    tables: Vec<String>,
    without_result: usize,
    notes: Vec<String>,
}

/// The cache of one output folder: entries stored and looked up; when a
/// run stores or looks up is the run's decision ([`super::store::Store`]).
pub struct Cache {
    dir: PathBuf,
}

impl Cache {
    /// The cache of `out_dir`.
    pub fn new(out_dir: &Path) -> Self {
        Cache {
            dir: out_dir.join(".tribo").join("cache"),
        }
    }

    fn route_path(&self, key: &Key) -> PathBuf {
        self.dir.join("routes").join(format!("{}.json", key.0))
    }

    fn part_dir(&self, key: &Key) -> PathBuf {
        self.dir.join("parts").join(&key.0)
    }

    /// A file's route, when cached.
    pub fn route(&self, key: &Key) -> Option<RouteEntry> {
        let text = fs::read_to_string(self.route_path(key)).ok()?;
        serde_json::from_str(&text).ok()
    }

    /// Stores a file's route.
    pub fn put_route(&self, key: &Key, entry: &RouteEntry) -> Result<()> {
        let json = serde_json::to_string(entry).map_err(|e| Error::Table(e.to_string()))?;
        self.put_entry(&self.route_path(key), |tmp| {
            fs::write(tmp, &json).map_err(|e| Error::io(tmp, e))
        })
    }

    /// Whether a part is cached: `Some(Ok)` with rows, `Some(Err)` when the
    /// stage failed on the file.
    pub fn part(&self, key: &Key) -> Option<std::result::Result<(), Failure>> {
        match intact_part(&self.part_dir(key))? {
            PartEntry::Tables(_) => Some(Ok(())),
            PartEntry::Failed(f) => Some(Err(f)),
        }
    }

    /// The file of table `name` of the part `key`.
    pub fn part_file(&self, key: &Key, name: &str) -> PathBuf {
        self.part_dir(key).join(format!("{name}.parquet"))
    }

    /// Loads a cached part's tables; `defs` (the stage's tables) maps
    /// stored names back to their declarations. Dataset tables are left
    /// where they are (the set links their files).
    pub fn load_part(&self, key: &Key, defs: &[&'static TableDef]) -> Result<Tables> {
        let dir = self.part_dir(key);
        let Some(PartEntry::Tables(stored)) = read_part_entry(&dir) else {
            return Err(Error::Table(format!(
                "cache entry {} vanished; rerun with --force",
                dir.display()
            )));
        };
        let mut out = Vec::new();
        for StoredTable { name: s, .. } in stored {
            let def = find(defs, &s).ok_or_else(|| {
                Error::Table(format!("cache entry {}: unknown table {s}", dir.display()))
            })?;
            if def.is_dataset() {
                continue;
            }
            let (t, _) = Table::read_parquet(&dir.join(format!("{s}.parquet")))?;
            out.push((def, t));
        }
        Ok(out)
    }

    /// Stores one file's rows for one stage (or its failure); its dataset
    /// tables are written as published files with `provenance`.
    pub fn put_part(
        &self,
        key: &Key,
        result: &Result<Tables>,
        provenance: &Provenance,
    ) -> Result<()> {
        let dir = self.part_dir(key);
        if dir.exists() && intact_part(&dir).is_none() {
            // A shared file that was rewritten: made again now.
            let _ = fs::remove_dir_all(&dir);
        }
        self.put_entry(&dir, |tmp| {
            fs::create_dir(tmp).map_err(|e| Error::io(tmp, e))?;
            let entry = match result {
                Ok(tables) => PartEntry::Tables(write_tables(tmp, tables, Some(provenance))?),
                Err(e) => PartEntry::Failed(e.into()),
            };
            let json = serde_json::to_string(&entry).map_err(|e| Error::Table(e.to_string()))?;
            let p = tmp.join("entry.json");
            fs::write(&p, &json).map_err(|e| Error::io(&p, e))
        })
    }

    /// Writes an entry at a unique temporary path beside `dest`, then renames
    /// it into place. An entry already there (a concurrent run wrote the same
    /// content) is kept.
    fn put_entry(&self, dest: &Path, fill: impl FnOnce(&Path) -> Result<()>) -> Result<()> {
        let parent = dest.parent().unwrap_or(Path::new("."));
        fs::create_dir_all(parent).map_err(|e| Error::io(parent, e))?;
        let tmp = parent.join(temp_name(".entry"));
        let done = fill(&tmp).and_then(|_| {
            if dest.exists() {
                return Ok(());
            }
            fs::rename(&tmp, dest).map_err(|e| Error::io(dest, e))
        });
        if tmp.is_dir() {
            let _ = fs::remove_dir_all(&tmp);
        } else if tmp.exists() {
            let _ = fs::remove_file(&tmp);
        }
        done
    }

    fn unit_path(&self, key: &Key) -> PathBuf {
        self.dir.join("units").join(format!("{}.json", key.0))
    }

    /// One unit of a table stage (a simulation run), when cached.
    pub fn unit(&self, key: &Key) -> Option<Vec<u8>> {
        fs::read(self.unit_path(key)).ok()
    }

    /// Stores one unit's result.
    pub fn put_unit(&self, key: &Key, bytes: &[u8]) -> Result<()> {
        self.put_entry(&self.unit_path(key), |tmp| {
            fs::write(tmp, bytes).map_err(|e| Error::io(tmp, e))
        })
    }

    fn stage_dir(&self, key: &Key) -> PathBuf {
        self.dir.join("stages").join(&key.0)
    }

    /// A table stage's output, when cached (computed by a shard, or by an
    /// earlier run); `defs` maps stored names back to the stage's tables.
    pub fn stage(&self, key: &Key, defs: &[&'static TableDef]) -> Option<Result<Output>> {
        let dir = self.stage_dir(key);
        let text = fs::read_to_string(dir.join("entry.json")).ok()?;
        let entry: StageEntry = serde_json::from_str(&text).ok()?;
        let load = || -> Result<Output> {
            let mut tables = Vec::new();
            for s in &entry.tables {
                let Some(def) = find(defs, s) else {
                    return Err(Error::Table(format!(
                        "cache entry {}: unknown table {s}",
                        dir.display()
                    )));
                };
                let (t, _) = Table::read_parquet(&dir.join(format!("{s}.parquet")))?;
                tables.push((def, t));
            }
            Ok(Output {
                tables,
                without_result: entry.without_result,
                notes: entry.notes.clone(),
            })
        };
        Some(load())
    }

    /// Stores a table stage's output.
    pub fn put_stage(&self, key: &Key, output: &Output) -> Result<()> {
        let entry = StageEntry {
            tables: output
                .tables
                .iter()
                .map(|(d, _)| d.name.to_string())
                .collect(),
            without_result: output.without_result,
            notes: output.notes.clone(),
        };
        let json = serde_json::to_string(&entry).map_err(|e| Error::Table(e.to_string()))?;
        self.put_entry(&self.stage_dir(key), |tmp| {
            fs::create_dir(tmp).map_err(|e| Error::io(tmp, e))?;
            write_tables(tmp, &output.tables, None)?;
            let p = tmp.join("entry.json");
            fs::write(&p, &json).map_err(|e| Error::io(&p, e))
        })
    }

    /// Removes every entry that the current run does not use (those of
    /// deleted or changed inputs, of old parameters), and leftovers of
    /// killed runs.
    pub fn retain(
        &self,
        routes: &BTreeSet<Key>,
        parts: &BTreeSet<Key>,
        stages: &BTreeSet<Key>,
        units: &BTreeSet<Key>,
    ) {
        prune(&self.dir.join("units"), |name| {
            name.strip_suffix(".json")
                .is_some_and(|k| units.contains(&Key(k.to_string())))
        });
        prune(&self.dir.join("stages"), |name| {
            stages.contains(&Key(name.to_string()))
        });
        prune(&self.dir.join("routes"), |name| {
            name.strip_suffix(".json")
                .is_some_and(|k| routes.contains(&Key(k.to_string())))
        });
        prune(&self.dir.join("parts"), |name| {
            parts.contains(&Key(name.to_string()))
        });
    }
}

/// Writes each table into `dir`: a dataset table as the file the output
/// set publishes (with `provenance`), stamped; the others for tribo alone.
fn write_tables(
    dir: &Path,
    tables: &Tables,
    provenance: Option<&Provenance>,
) -> Result<Vec<StoredTable>> {
    let mut stored = Vec::with_capacity(tables.len());
    for (def, t) in tables {
        let p = dir.join(format!("{}.parquet", def.name));
        let f = fs::File::create(&p).map_err(|e| Error::io(&p, e))?;
        let mut w = std::io::BufWriter::new(f);
        let linked = match (def.is_dataset(), provenance) {
            (true, Some(prov)) => {
                let columns = def.schema()?.field_metadata();
                t.write_parquet_open(&mut w, &prov.key_values(def.name), &columns)?;
                // Synced once for all by the set that publishes it
                // (`dataset::link_files`), not one by one.
                w.flush().map_err(|e| Error::io(&p, e))?;
                Stamp::of(&p)
            }
            _ => {
                t.write_scratch_parquet(w)?;
                None
            }
        };
        stored.push(StoredTable {
            name: def.name.to_string(),
            linked,
        });
    }
    Ok(stored)
}

fn read_part_entry(dir: &Path) -> Option<PartEntry> {
    let text = fs::read_to_string(dir.join("entry.json")).ok()?;
    serde_json::from_str(&text).ok()
}

/// A part's entry, unless a table it links to was rewritten since.
fn intact_part(dir: &Path) -> Option<PartEntry> {
    let entry = read_part_entry(dir)?;
    let intact = match &entry {
        PartEntry::Tables(stored) => stored.iter().all(|t| {
            let file = dir.join(format!("{}.parquet", t.name));
            t.linked.is_none_or(|stamp| Stamp::of(&file) == Some(stamp))
        }),
        PartEntry::Failed(_) => true,
    };
    intact.then_some(entry)
}

fn prune(dir: &Path, keep: impl Fn(&str) -> bool) {
    let Ok(entries) = fs::read_dir(dir) else {
        return;
    };
    for e in entries.flatten() {
        let name = e.file_name().to_string_lossy().to_string();
        // A temporary entry of a run (or shard) that may be alive stays.
        let alive = name.ends_with(".tmp") && !is_leftover(&name, true);
        if keep(&name) || alive {
            continue;
        }
        let p = e.path();
        let _ = if p.is_dir() {
            fs::remove_dir_all(&p)
        } else {
            fs::remove_file(&p)
        };
    }
}
