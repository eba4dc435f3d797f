//! The content-addressed cache of an output folder (`OUT/.tribo/cache/`),
//! so that a rerun redoes only what changed.
//!
//! - routes: what a file is (its kind, or why no stage takes it, or why
//!   it cannot be read) and its SHA-256, keyed by (tribo version, path,
//!   BLAKE3 of its bytes, reading options); the SHA-256 is computed once,
//!   when the route is not cached, and given to the reader;
//! - parts: one per-file stage's rows for one file (or the stage's
//!   failure), keyed by the route key plus the stage, its validated
//!   parameters and the file's manifest row. Routes and parts' summary
//!   rows are kept in packs of many inputs ([`super::pack`]: one index and
//!   one Parquet file per table for all the entries a run made, so that a
//!   small entry costs neither a file nor a read of its own). A dataset
//!   table (`traces`) is written as the file the output set publishes
//!   (compressed, with its provenance), `parts/<key>.<table>.parquet`,
//!   which the set links into its folder (one file, two names); its pack
//!   entry keeps the file's [`Stamp`]: a published file rewritten in place
//!   no longer matches, and the part is made again;
//! - `units/<key>.json`: one run of a simulation study, keyed by the
//!   stage's parameters and the run's index (a shard's share);
//! - `stages/<key>/`: a table or simulation stage's output, keyed by its
//!   parameters and what it reads (so a shard's simulation is reused by the
//!   run that assembles the shards).
//!
//! Entries are written under temporary names and renamed into place, so a
//! killed run leaves whole entries or none; a killed run's temporary
//! entries are removed by the next published run, never those of a run or
//! shard still alive ([`super::owner`]). Keys use BLAKE3 (fast); the
//! provenance keeps SHA-256.

use std::fs;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::sync::{Mutex, OnceLock};

use serde::{Deserialize, Serialize};

pub use super::entries::{Failure, Route, RouteEntry};
use super::entries::{PartEntry, StoredTable};
pub use super::keys::{Key, KeyBuilder};
use super::owner::temp_name;
pub use super::pack::RowsAt;
use super::pack::{Made, Packed, Packs, Pending};
use super::provenance::Provenance;
use super::stamp::Stamp;
use crate::error::{Error, Result};
use crate::schema::def::find;
use crate::schema::TableDef;
use crate::stages::{Output, Tables};
use crate::table::Table;

/// A part's summary rows, `rows` giving where each table's are.
fn entry_rows(
    key: &Key,
    packed: &Packed,
    defs: &[&'static TableDef],
    rows: impl Fn(&str) -> Result<RowsAt>,
) -> Result<Vec<(&'static TableDef, RowsAt)>> {
    let PartEntry::Tables(stored) = &packed.entry else {
        return Err(vanished(key));
    };
    let mut out = Vec::new();
    for StoredTable { name: s, .. } in stored {
        let def = find(defs, s)
            .ok_or_else(|| Error::Table(format!("cache entry {key}: unknown table {s}")))?;
        if !def.is_dataset() {
            out.push((def, rows(s)?));
        }
    }
    Ok(out)
}

fn vanished(key: &Key) -> Error {
    Error::Table(format!("cache entry {key} vanished; rerun with --force"))
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
/// Routes and parts a run makes are held until [`Cache::flush`] writes
/// them as one pack.
pub struct Cache {
    dir: PathBuf,
    packs: OnceLock<Packs>,
    pending: Mutex<Pending>,
    /// The pack this run made ([`Cache::flush`]).
    made: OnceLock<Made>,
    /// `parts/` holds exactly the files the packs list (it is as the last
    /// run left it, [`super::swept`]): a part's files are not looked at,
    /// and only those of dead parts are removed, by name.
    parts_known: bool,
    /// `packs/` is as the last run left it, pruned to what its state
    /// uses: the state's routes and parts are in the packs.
    packs_known: bool,
}

impl Cache {
    /// The cache of `out_dir`.
    pub fn new(out_dir: &Path) -> Self {
        Cache {
            dir: out_dir.join(".tribo").join("cache"),
            packs: OnceLock::new(),
            pending: Mutex::default(),
            made: OnceLock::new(),
            parts_known: false,
            packs_known: false,
        }
    }

    /// The folder of the parts' dataset files.
    pub fn parts_dir(&self) -> PathBuf {
        self.dir.join("parts")
    }

    /// Says that `parts/` holds exactly the files the packs list (its
    /// stamp is the one the last run recorded, and no `--verify`).
    pub fn know_parts(&mut self, known: bool) {
        self.parts_known = known;
    }

    /// The folder of the packs.
    pub fn packs_dir(&self) -> PathBuf {
        self.dir.join("packs")
    }

    /// Says that `packs/` is as the last run left it (its stamp is the one
    /// it recorded, and no `--verify`).
    pub fn know_packs(&mut self, known: bool) {
        self.packs_known = known;
    }

    /// Whether the last run's state stands for the cache: the routes and
    /// parts it names are in the packs, with their files whole, and the
    /// packs hold no other live entry. A lookup then takes the state's
    /// copy (the packs are not read), and a key the state does not name
    /// is not looked for (an entry of a deleted or changed input that a
    /// pack still holds is dead).
    pub fn state_stands(&self) -> bool {
        self.packs_known && self.parts_known
    }

    /// The packs as they were when first looked up in this run.
    fn packs(&self) -> &Packs {
        self.packs.get_or_init(|| Packs::load(&self.packs_dir()))
    }

    fn pending(&self) -> std::sync::MutexGuard<'_, Pending> {
        self.pending.lock().unwrap_or_else(|e| e.into_inner())
    }

    /// A file's route, when cached.
    pub fn route(&self, key: &Key) -> Option<RouteEntry> {
        self.packs().route(key).cloned()
    }

    /// Stores a file's route (with the next pack).
    pub fn put_route(&self, key: &Key, entry: &RouteEntry) -> Result<()> {
        self.pending().routes.insert(*key, entry.clone());
        Ok(())
    }

    /// Whether the files a part shares with the output set are still the
    /// ones it wrote: taken as so when `parts/` is as the last run left it
    /// (a file rewritten in place keeps the folder's stamp: `--verify`
    /// looks at each file).
    fn intact(&self, key: &Key, packed: &Packed) -> bool {
        match &packed.entry {
            PartEntry::Tables(_) if self.parts_known => true,
            PartEntry::Tables(stored) => stored.iter().all(|t| {
                let file = self.part_file(key, &t.name);
                t.linked.is_none_or(|stamp| Stamp::of(&file) == Some(stamp))
            }),
            PartEntry::Failed(_) => true,
        }
    }

    /// Whether a part is cached: `Some(Ok)` with rows, `Some(Err)` when the
    /// stage failed on the file.
    pub fn part(&self, key: &Key) -> Option<std::result::Result<(), Failure>> {
        match &self.packs().part(key, |p| self.intact(key, p))?.1.entry {
            PartEntry::Tables(_) => Some(Ok(())),
            PartEntry::Failed(f) => Some(Err(f.clone())),
        }
    }

    /// The file of a part's dataset table `name`.
    pub fn part_file(&self, key: &Key, name: &str) -> PathBuf {
        self.parts_dir().join(format!("{key}.{name}.parquet"))
    }

    /// Removes, by name, the dataset files the parts `keys` can have in
    /// `parts/` (one try per dataset table; most parts have one).
    fn remove_part_files<'a>(&self, keys: impl Iterator<Item = &'a Key>) {
        let datasets: Vec<_> = super::registry::all()
            .into_iter()
            .filter(|d| d.is_dataset())
            .collect();
        for key in keys {
            for def in &datasets {
                let _ = fs::remove_file(self.part_file(key, def.name));
            }
        }
    }

    /// Where a part's summary rows are (in the pack this run made, or in
    /// an older one); `defs` (the stage's tables) maps stored names back to
    /// their declarations. Dataset tables are left where they are (the set
    /// links their files).
    pub fn part_rows(
        &self,
        key: &Key,
        defs: &[&'static TableDef],
    ) -> Result<Vec<(&'static TableDef, RowsAt)>> {
        if let Some(m) = self.made.get() {
            if let Some(packed) = m.part(key) {
                return entry_rows(key, packed, defs, |name| m.rows(packed, name));
            }
        }
        let packs = self.packs();
        let (i, packed) = packs
            .part(key, |p| self.intact(key, p))
            .ok_or_else(|| vanished(key))?;
        entry_rows(key, packed, defs, |name| packs.rows(i, packed, name))
    }

    /// Stores one file's rows for one stage (or its failure): its dataset
    /// tables written now as published files with `provenance`, the rest
    /// held for the next pack.
    pub fn put_part(
        &self,
        key: &Key,
        result: &Result<Tables>,
        provenance: &Provenance,
    ) -> Result<()> {
        let (entry, small) = match result {
            Ok(tables) => {
                let mut stored = Vec::with_capacity(tables.len());
                let mut small = Vec::new();
                for (def, t) in tables {
                    let linked = match def.is_dataset() {
                        true => Some(self.write_dataset_file(key, def, t, provenance)?),
                        false => {
                            small.push((def.name.to_string(), t.clone()));
                            None
                        }
                    };
                    stored.push(StoredTable {
                        name: def.name.to_string(),
                        linked,
                    });
                }
                (PartEntry::Tables(stored), small)
            }
            Err(e) => (PartEntry::Failed(e.into()), Vec::new()),
        };
        self.pending().put(*key, entry, small);
        Ok(())
    }

    /// Writes a part's dataset table as the file the output set publishes
    /// (under a temporary name, renamed over any older file: a file
    /// published before keeps its own); returns its stamp.
    fn write_dataset_file(
        &self,
        key: &Key,
        def: &TableDef,
        t: &Table,
        provenance: &Provenance,
    ) -> Result<Stamp> {
        let dest = self.part_file(key, def.name);
        let dir = dest.parent().unwrap_or(Path::new("."));
        fs::create_dir_all(dir).map_err(|e| Error::io(dir, e))?;
        let tmp = dir.join(temp_name(&format!(".{key}.{}", def.name)));
        let written = (|| {
            let f = fs::File::create(&tmp).map_err(|e| Error::io(&tmp, e))?;
            let mut w = std::io::BufWriter::new(f);
            let columns = def.schema()?.field_metadata();
            t.write_parquet_open(&mut w, &provenance.key_values(def.name), &columns)?;
            // Synced once for all by the set that publishes it
            // (`dataset::link_files`), not one by one.
            w.flush().map_err(|e| Error::io(&tmp, e))?;
            drop(w);
            let stamp = Stamp::of(&tmp)
                .ok_or_else(|| Error::Table(format!("{}: no stamp", tmp.display())))?;
            fs::rename(&tmp, &dest).map_err(|e| Error::io(&dest, e))?;
            Ok(stamp)
        })();
        if written.is_err() {
            let _ = fs::remove_file(&tmp);
        }
        written
    }

    /// Writes the routes and parts this run made as one pack (once, at
    /// the end of its per-file phase). The pack is kept in memory: the
    /// parts' rows are taken from it, written or not.
    pub fn flush(&mut self) -> Result<()> {
        let pending = std::mem::take(&mut *self.pending());
        let dir = self.packs_dir();
        // Packs not read in this run stay unread: the new one is found
        // by a listing, if ever they are.
        let (made, done) = match pending.stack() {
            Ok(made) => {
                let done = match self.packs.get_mut() {
                    Some(packs) => packs.write(&dir, &made),
                    None => Packs::default().write(&dir, &made),
                };
                (made, done)
            }
            Err(e) => (Made::default(), Err(e)),
        };
        let _ = self.made.set(made);
        // Files no pack lists: `parts/` is listed at the end of the run.
        self.parts_known &= done.is_ok();
        done
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
        self.dir.join("units").join(format!("{key}.json"))
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
        self.dir.join("stages").join(&*key.hex())
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
            write_tables(tmp, &output.tables)?;
            let p = tmp.join("entry.json");
            fs::write(&p, &json).map_err(|e| Error::io(&p, e))
        })
    }
}

/// Writes each table of a stage's output into `dir`, for tribo alone.
fn write_tables(dir: &Path, tables: &Tables) -> Result<()> {
    for (def, t) in tables {
        let p = dir.join(format!("{}.parquet", def.name));
        let f = fs::File::create(&p).map_err(|e| Error::io(&p, e))?;
        t.write_scratch_parquet(std::io::BufWriter::new(f))?;
    }
    Ok(())
}

#[path = "cache_retain.rs"]
mod retain;
