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
#[derive(Debug, Default, Serialize, Deserialize)]
struct Index {
    routes: BTreeMap<Key, RouteEntry>,
    parts: BTreeMap<Key, Packed>,
}

/// Entries a run made, to be written as one pack: routes, and each part's
/// entry with its summary tables by name.
#[derive(Default)]
pub(super) struct Pending {
    pub(super) routes: BTreeMap<Key, RouteEntry>,
    pub(super) parts: BTreeMap<Key, (PartEntry, Vec<(String, Table)>)>,
}

impl Pending {
    fn is_empty(&self) -> bool {
        self.routes.is_empty() && self.parts.is_empty()
    }
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
}

impl Packs {
    /// Reads the index of every pack in `dir` (those being written are
    /// skipped, and so is an index that cannot be read).
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
    pub(super) fn rows(&self, i: usize, packed: &Packed, name: &str) -> Result<Table> {
        let &(at, n) = packed.rows.get(name).ok_or_else(|| {
            Error::Table(format!(
                "cache pack {}: no rows of {name}",
                self.dirs[i].display()
            ))
        })?;
        Ok(self.table(i, name)?.slice(at as usize, n as usize))
    }
}

impl Packs {
    /// Writes `pending` as a new pack in `dir` (nothing when it is empty):
    /// into a temporary folder, renamed into place whole; it is the newest
    /// of these packs from then on.
    pub(super) fn write(&mut self, dir: &Path, pending: Pending) -> Result<()> {
        if pending.is_empty() {
            return Ok(());
        }
        fs::create_dir_all(dir).map_err(|e| Error::io(dir, e))?;
        let tmp = dir.join(temp_name(".pack"));
        let done = fill(&tmp, pending).and_then(|index| {
            let dest = dir.join(pack_name());
            fs::rename(&tmp, &dest).map_err(|e| Error::io(&dest, e))?;
            Ok((dest, index))
        });
        match done {
            Ok((dest, index)) => {
                self.add(dest, index, true);
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

/// Fills the folder `tmp` with a pack of `pending`; returns its index.
fn fill(tmp: &Path, pending: Pending) -> Result<Index> {
    fs::create_dir(tmp).map_err(|e| Error::io(tmp, e))?;
    let mut index = Index {
        routes: pending.routes,
        parts: BTreeMap::new(),
    };
    let mut stacks: BTreeMap<String, (Vec<Table>, u64)> = BTreeMap::new();
    for (key, (entry, tables)) in pending.parts {
        let mut rows = BTreeMap::new();
        for (name, t) in tables {
            let (stack, height) = stacks.entry(name.clone()).or_default();
            let n = t.height() as u64;
            rows.insert(name, (*height, n));
            *height += n;
            stack.push(t);
        }
        index.parts.insert(key, Packed { entry, rows });
    }
    for (name, (stack, _)) in stacks {
        let Some(t) = Table::concat(stack)? else {
            continue;
        };
        let p = tmp.join(format!("{name}.parquet"));
        let f = fs::File::create(&p).map_err(|e| Error::io(&p, e))?;
        t.write_scratch_parquet(std::io::BufWriter::new(f))?;
    }
    binfile::write(&tmp.join(INDEX), &index)?;
    Ok(index)
}

/// Keeps the entries a run uses (`routes`, `parts`): packs holding none
/// are removed; when more than [`MAX_PACKS`] would remain, the newest
/// ones are joined ([`to_join`]), and when a fifth of all entries are
/// dead, every pack: their live entries are written into one new pack and
/// they are removed. A part made again is in a newer pack than the entry
/// it replaces: a live part's entry is its newest (not looked at again:
/// the run that used it found it whole). `packs`: those this run read and
/// wrote (a pack written since by another process stays).
pub(super) fn retain(
    dir: &Path,
    packs: &Packs,
    routes: &BTreeSet<Key>,
    parts: &BTreeSet<Key>,
) -> Result<()> {
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
                all.parts
                    .insert(*k, (p.entry.clone(), small_tables(packs, i, p)?));
            }
        }
        Packs::default().write(dir, all)?;
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
        .map(|name| Ok((name.clone(), packs.rows(i, p, name)?)))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::to_join;

    #[test]
    fn the_newest_packs_are_joined_until_the_next_older_holds_as_many() {
        // Nine one-entry packs on a large one: the nine go, not the large.
        assert_eq!(to_join(&[1, 1, 1, 1, 1, 1, 1, 1, 1, 20_000]), 9);
        // A pack of eight then holds as many as the eight newer ones.
        assert_eq!(to_join(&[1, 1, 1, 1, 1, 1, 1, 1, 8, 20_000]), 8);
        assert_eq!(to_join(&[1, 1, 1, 1, 1, 1, 1, 1, 1, 8, 20_000]), 10);
        // Sizes that double with age: the two newest.
        assert_eq!(to_join(&[1, 1, 2, 4, 8, 16, 32, 64, 128]), 2);
        // Packs with no live entry are removed, not a reason to join.
        assert_eq!(to_join(&[1, 1, 1, 1, 1, 1, 1, 1, 1, 0, 0, 20_000]), 9);
        // All of them, when the oldest holds fewer than the rest.
        assert_eq!(to_join(&[5, 5, 5, 5, 5, 5, 5, 5, 5, 30]), 10);
    }
}
