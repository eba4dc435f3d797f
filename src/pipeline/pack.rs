//! Packs: the small entries of the cache, many inputs' at once. A file's
//! route and a per-file stage's summary rows (or its failure) are a few
//! kilobytes each, most of it a Parquet footer and a file system block;
//! kept one file each they cost more disk than the tables they come from.
//! A run holds the entries it makes and writes them at the end of its
//! per-file phase as one pack, `packs/<name>/`: `index.bin` (each route,
//! each part's entry and its rows in the pack's tables) and one Parquet
//! file per summary table, every part's rows stacked. A lookup reads the
//! indexes once per run (no file per input); a part's rows are a slice of
//! its pack's table, read once.
//!
//! Packs are named by the time they were written, so the newest holds an
//! entry made again. Packs nothing uses are removed; when more than
//! [`MAX_PACKS`] remain, the newest are joined into one, and when a fifth
//! of their entries are dead, all of them ([`retain`]).

use std::collections::{BTreeMap, BTreeSet, HashMap};
use std::fs;
use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex};

use serde::{Deserialize, Serialize};

use super::binfile;
use super::entries::{PartEntry, RouteEntry};
use super::keys::Key;
use super::owner::temp_name;
use crate::error::{Error, Result};
use crate::table::Table;

/// A pack's index file ([`super::binfile`]).
const INDEX: &str = "index.bin";

/// The index as an older build wrote it.
const INDEX_JSON: &str = "index.json";

/// Packs left before the live entries are joined into one.
pub const MAX_PACKS: usize = 8;

/// One part in a pack: its entry, and its rows in each of the pack's
/// tables (offset, count).
#[derive(Debug, Clone, Serialize, Deserialize)]
pub(super) struct Packed {
    pub(super) entry: PartEntry,
    #[serde(default)]
    pub(super) rows: BTreeMap<String, (u64, u64)>,
}

/// What a pack holds.
#[derive(Debug, Default, Clone, Serialize, Deserialize)]
struct Index {
    routes: BTreeMap<Key, RouteEntry>,
    parts: BTreeMap<Key, Packed>,
}

/// Entries a run made, to be written as one pack: routes, and each part's
/// entry with its rows in the summary tables, which are stacked as the
/// parts come. Held as each part made them (one row, tens of columns), a
/// first run's summary tables took about 150 kB per input until the join.
#[derive(Default)]
pub(super) struct Pending {
    pub(super) routes: BTreeMap<Key, RouteEntry>,
    parts: BTreeMap<Key, Packed>,
    stacks: BTreeMap<String, Stack>,
}

/// Parts' rows of one summary table, in the order they came: stacked
/// into one table every [`STACK_EVERY`] parts.
#[derive(Default)]
struct Stack {
    stacked: Vec<Table>,
    loose: Vec<Table>,
    height: u64,
}

/// Parts whose rows are stacked at once.
const STACK_EVERY: usize = 256;

impl Stack {
    /// Adds a part's rows; returns where they are (offset, count).
    fn push(&mut self, t: Table) -> (u64, u64) {
        let at = (self.height, t.height() as u64);
        self.height += at.1;
        self.loose.push(t);
        if self.loose.len() >= STACK_EVERY {
            let loose = std::mem::take(&mut self.loose);
            match Table::concat(loose.iter().cloned()) {
                Ok(Some(t)) => self.stacked.push(t),
                // Stacked with the rest when written, or its error told then.
                _ => self.stacked.extend(loose),
            }
        }
        at
    }

    fn table(self) -> Result<Option<Table>> {
        Table::concat(self.stacked.into_iter().chain(self.loose))
    }
}

impl Pending {
    /// Adds a part: its entry and its summary tables by name.
    pub(super) fn put(&mut self, key: Key, entry: PartEntry, tables: Vec<(String, Table)>) {
        let rows = tables
            .into_iter()
            .map(|(name, t)| {
                let at = self.stacks.entry(name.clone()).or_default().push(t);
                (name, at)
            })
            .collect();
        self.parts.insert(key, Packed { entry, rows });
    }

    /// The pack these entries make, its tables stacked.
    pub(super) fn stack(self) -> Result<Made> {
        let mut tables = BTreeMap::new();
        for (name, stack) in self.stacks {
            if let Some(t) = stack.table()? {
                tables.insert(name, Arc::new(t));
            }
        }
        let index = Index {
            routes: self.routes,
            parts: self.parts,
        };
        Ok(Made { index, tables })
    }
}

/// A pack made in memory: what a run made, kept after it is written so
/// that its parts' rows are read from here.
#[derive(Default)]
pub(super) struct Made {
    index: Index,
    tables: BTreeMap<String, Arc<Table>>,
}

impl Made {
    /// A part's entry and where its rows are.
    pub(super) fn part(&self, key: &Key) -> Option<&Packed> {
        self.index.parts.get(key)
    }

    /// The rows of a part's table `name`.
    pub(super) fn rows(&self, packed: &Packed, name: &str) -> Result<RowsAt> {
        let table = self.tables.get(name).cloned();
        at_rows(packed, name, table, || "made by this run".to_string())
    }
}

/// Some rows of a stacked table: a part's rows.
#[derive(Clone)]
pub struct RowsAt {
    /// The table.
    pub table: Arc<Table>,
    /// The first row.
    pub at: usize,
    /// The number of rows.
    pub n: usize,
}

impl RowsAt {
    /// The rows as a table of their own.
    pub fn slice(&self) -> Table {
        self.table.slice(self.at, self.n)
    }
}

/// A part's rows of table `name` in `table` (`pack`: which pack, for the
/// error).
fn at_rows(
    packed: &Packed,
    name: &str,
    table: Option<Arc<Table>>,
    pack: impl Fn() -> String,
) -> Result<RowsAt> {
    let missing = || Error::Table(format!("cache pack {}: no rows of {name}", pack()));
    let &(at, n) = packed.rows.get(name).ok_or_else(missing)?;
    let table = table.ok_or_else(missing)?;
    let (at, n) = (at as usize, n as usize);
    if at + n > table.height() {
        return Err(missing());
    }
    Ok(RowsAt { table, at, n })
}

/// The packs of a cache, as read.
#[derive(Default)]
pub(super) struct Packs {
    /// Newest first.
    dirs: Vec<PathBuf>,
    /// Each route with the newest pack that holds it.
    routes: HashMap<Key, (usize, RouteEntry)>,
    /// Entries (routes and parts) in all the packs, duplicates included.
    entries: usize,
    /// Each part's entries, newest pack first.
    parts: HashMap<Key, Vec<(usize, Packed)>>,
    /// Per pack, the tables read so far.
    tables: Vec<Mutex<HashMap<String, Arc<Table>>>>,
    /// Packs whose index could not be read (damaged, or written by a build
    /// whose format differs): nothing in them can be found, and the parts
    /// they list are not known ([`retain`] removes them).
    unreadable: Vec<PathBuf>,
}

impl Packs {
    /// Reads the index of every pack in `dir` (those being written are
    /// skipped; so is an index that cannot be read, noted as such).
    pub(super) fn load(dir: &Path) -> Packs {
        let mut names: Vec<String> = fs::read_dir(dir)
            .into_iter()
            .flatten()
            .flatten()
            .map(|e| e.file_name().to_string_lossy().to_string())
            .filter(|n| n.starts_with("pack-") && !n.ends_with(".tmp"))
            .collect();
        names.sort_unstable_by(|a, b| b.cmp(a));
        let mut packs = Packs::default();
        for name in names {
            let path = dir.join(&name);
            let Some(index) =
                binfile::read::<Index>(&path.join(INDEX), Some(&path.join(INDEX_JSON)))
            else {
                packs.unreadable.push(path);
                continue;
            };
            packs.add(path, index, false);
        }
        packs
    }

    /// Adds the pack at `path`: older than those already here, or the
    /// newest (`newest`: one this run wrote).
    fn add(&mut self, path: PathBuf, index: Index, newest: bool) {
        let i = self.dirs.len();
        self.entries += index.routes.len() + index.parts.len();
        for (k, r) in index.routes {
            if newest || !self.routes.contains_key(&k) {
                self.routes.insert(k, (i, r));
            }
        }
        for (k, p) in index.parts {
            let entries = self.parts.entry(k).or_default();
            match newest {
                true => entries.insert(0, (i, p)),
                false => entries.push((i, p)),
            }
        }
        self.dirs.push(path);
        self.tables.push(Mutex::default());
    }

    /// Whether a pack's index could not be read: the parts' files are then
    /// not all listed in the packs.
    pub(super) fn any_unreadable(&self) -> bool {
        !self.unreadable.is_empty()
    }

    /// A route.
    pub(super) fn route(&self, key: &Key) -> Option<&RouteEntry> {
        self.routes.get(key).map(|(_, r)| r)
    }

    /// A part's newest entry that is `intact`, with its pack.
    pub(super) fn part(
        &self,
        key: &Key,
        intact: impl Fn(&Packed) -> bool,
    ) -> Option<(usize, &Packed)> {
        let found = self.parts.get(key)?.iter().find(|(_, p)| intact(p))?;
        Some((found.0, &found.1))
    }

    /// The parts the packs hold that are not in `live`.
    pub(super) fn dead_parts<'a>(
        &'a self,
        live: &'a BTreeSet<Key>,
    ) -> impl Iterator<Item = &'a Key> + 'a {
        self.parts.keys().filter(|k| !live.contains(*k))
    }

    /// The pack `i`'s table `name` (read once).
    pub(super) fn table(&self, i: usize, name: &str) -> Result<Arc<Table>> {
        let mut read = self.tables[i].lock().unwrap_or_else(|e| e.into_inner());
        if let Some(t) = read.get(name) {
            return Ok(t.clone());
        }
        let path = self.dirs[i].join(format!("{name}.parquet"));
        let t = Arc::new(Table::read_parquet(&path)?.0);
        read.insert(name.to_string(), t.clone());
        Ok(t)
    }

    /// The rows of a part's table `name`, from pack `i`.
    pub(super) fn rows(&self, i: usize, packed: &Packed, name: &str) -> Result<RowsAt> {
        let table = match packed.rows.contains_key(name) {
            true => Some(self.table(i, name)?),
            false => None,
        };
        at_rows(packed, name, table, || self.dirs[i].display().to_string())
    }
}

impl Packs {
    /// Writes `made` as a new pack in `dir` (nothing when it is empty):
    /// into a temporary folder, renamed into place whole; it is the newest
    /// of these packs from then on.
    pub(super) fn write(&mut self, dir: &Path, made: &Made) -> Result<()> {
        if made.index.routes.is_empty() && made.index.parts.is_empty() {
            return Ok(());
        }
        fs::create_dir_all(dir).map_err(|e| Error::io(dir, e))?;
        let tmp = dir.join(temp_name(".pack"));
        let done = fill(&tmp, made).and_then(|_| {
            let dest = dir.join(pack_name());
            fs::rename(&tmp, &dest).map_err(|e| Error::io(&dest, e))?;
            Ok(dest)
        });
        match done {
            Ok(dest) => {
                self.add(dest, made.index.clone(), true);
                Ok(())
            }
            Err(e) => {
                let _ = fs::remove_dir_all(&tmp);
                Err(e)
            }
        }
    }
}

/// The number of packs in `dir` (those being written aside).
pub(super) fn count(dir: &Path) -> usize {
    fs::read_dir(dir)
        .into_iter()
        .flatten()
        .flatten()
        .filter(|e| {
            let name = e.file_name();
            let name = name.to_string_lossy();
            name.starts_with("pack-") && !name.ends_with(".tmp")
        })
        .count()
}

/// A new pack's name: the time (so that names sort as the packs were
/// written) and a random tail.
fn pack_name() -> String {
    let now = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map_or(0, |d| d.as_nanos());
    format!("pack-{now:024}-{:08x}", rand::random::<u32>())
}

/// Fills the folder `tmp` with the pack `made`.
fn fill(tmp: &Path, made: &Made) -> Result<()> {
    fs::create_dir(tmp).map_err(|e| Error::io(tmp, e))?;
    for (name, t) in &made.tables {
        let p = tmp.join(format!("{name}.parquet"));
        let f = fs::File::create(&p).map_err(|e| Error::io(&p, e))?;
        t.write_scratch_parquet(std::io::BufWriter::new(f))?;
    }
    binfile::write(&tmp.join(INDEX), &made.index)
}

/// Keeps the entries a run uses (`routes`, `parts`): packs holding none
/// are removed; when more than [`MAX_PACKS`] would remain, the newest
/// ones are joined ([`to_join`]), and when a fifth of all entries are
/// dead, every pack: their live entries are written into one new pack and
/// they are removed. A part made again is in a newer pack than the entry
/// it replaces: a live part's entry is its newest (not looked at again:
/// the run that used it found it whole). A pack whose index could not be
/// read is removed: its entries can never be found (a build reads only
/// the entries it made itself), and kept it would hold its parts' files
/// on disk for good. `packs`: those this run read and wrote (a pack
/// written since by another process stays).
pub(super) fn retain(
    dir: &Path,
    packs: &Packs,
    routes: &BTreeSet<Key>,
    parts: &BTreeSet<Key>,
) -> Result<()> {
    for d in &packs.unreadable {
        let _ = fs::remove_dir_all(d);
    }
    let mut live: Vec<(Vec<Key>, Vec<Key>)> = vec![Default::default(); packs.dirs.len()];
    for (key, entries) in &packs.parts {
        if let Some((i, _)) = entries.first().filter(|_| parts.contains(key)) {
            live[*i].1.push(*key);
        }
    }
    for (key, (i, _)) in &packs.routes {
        if routes.contains(key) {
            live[*i].0.push(*key);
        }
    }
    let sizes: Vec<usize> = live.iter().map(|(r, p)| r.len() + p.len()).collect();
    let entries: usize = sizes.iter().sum();
    let dead = packs.entries - entries;
    let held = sizes.iter().filter(|&&n| n > 0).count();
    let join = match () {
        _ if dead > 0 && dead * 5 > entries => sizes.len(),
        _ if held > MAX_PACKS => to_join(&sizes),
        _ => 0,
    };
    if join > 0 {
        let mut all = Pending::default();
        for (rs, ps) in &live[..join] {
            for k in rs {
                all.routes.insert(*k, packs.routes[k].1.clone());
            }
            for k in ps {
                let Some((i, p)) = packs.part(k, |_| true) else {
                    continue;
                };
                all.put(*k, p.entry.clone(), small_tables(packs, i, p)?);
            }
        }
        Packs::default().write(dir, &all.stack()?)?;
    }
    for (i, (d, n)) in packs.dirs.iter().zip(&sizes).enumerate() {
        if i < join || *n == 0 {
            let _ = fs::remove_dir_all(d);
        }
    }
    Ok(())
}

/// How many of the newest packs to join into one, given each pack's live
/// entries (newest first): those from the oldest that holds fewer than all
/// newer packs together, and at least the two newest. A pack kept then
/// holds as many entries as the newer ones together, so that the packs
/// double in size with age: an entry is written again about log2(entries)
/// times over the life of a cache, where joining every pack wrote the whole
/// archive again every [`MAX_PACKS`] runs (seconds at 20 000 inputs).
fn to_join(sizes: &[usize]) -> usize {
    let mut newer: usize = sizes.iter().sum();
    for (i, &n) in sizes.iter().enumerate().rev() {
        newer -= n;
        if n > 0 && n < newer {
            return i + 1;
        }
    }
    sizes.len().min(2)
}

/// A part's summary tables, from pack `i` (a slice each).
fn small_tables(packs: &Packs, i: usize, p: &Packed) -> Result<Vec<(String, Table)>> {
    p.rows
        .keys()
        .map(|name| Ok((name.clone(), packs.rows(i, p, name)?.slice())))
        .collect()
}

#[cfg(test)]
#[path = "pack_tests.rs"]
mod tests;
