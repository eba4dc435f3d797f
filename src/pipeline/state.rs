//! What the last completed run of an output folder published
//! (`OUT/.tribo/state.bin`, with [`super::state_log`]): per input, its content hash and the cache
//! parts it used; per stage, its key; per table, its key and the size and
//! time of the file written. A rerun reuses a stage whose key is unchanged
//! and whose tables are still the files it wrote; the rest is redone. The
//! state is written last: after a kill, it still describes the previous
//! run, and whatever changed since is redone.
//!
//! An input whose [`FileStat`] (size, modification and change times,
//! inode) is the one the last run saw is taken as unchanged without being
//! read (as `make`, git and rsync do); `--verify` reads and hashes every
//! input again.

use std::cmp::Ordering;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};

use super::by_name::ByName;
use super::entries::{Failure, Route};
use super::keys::Key;
use super::shared::Shared;
use super::stamp::Stamp;
use crate::schema::TableDef;

/// One input as the last run saw it.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct FileState {
    /// BLAKE3 of its bytes (shared with the run's result for it).
    #[serde(deserialize_with = "super::shared::shared_str")]
    pub bytes: std::sync::Arc<str>,
    /// Its route key.
    pub route: Option<Key>,
    /// Per stage, the key of its part.
    pub parts: ByName<Key>,
    /// SHA-256 of its bytes (the provenance's, shared with it).
    #[serde(default, deserialize_with = "super::shared::shared_str_opt")]
    pub sha256: Option<std::sync::Arc<str>>,
    /// How it looked on disk when its bytes were hashed.
    #[serde(default)]
    pub stat: Option<FileStat>,
    /// What it is (its route's entry, without the SHA-256 above).
    #[serde(default)]
    pub what: Option<Route>,
    /// The stages that failed on it, with their failures (the others'
    /// parts hold rows).
    #[serde(default)]
    pub failed: ByName<Failure>,
    /// How the files beside it that its reading looks at (its possible
    /// companions, [`crate::ingest::companion::beside`]) looked before its
    /// route key was made (`None`: absent). Unchanged, so are its
    /// companions, and the key holds without reading them.
    #[serde(default)]
    pub beside: Vec<Option<FileStat>>,
}

/// An input file as seen on disk: what a write to it changes.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
pub struct FileStat {
    /// Size in bytes.
    pub len: u64,
    /// Modification time, ns since the epoch.
    pub modified_ns: u128,
    /// Inode change time, ns since the epoch (0 where there is none): set
    /// by any write, even one that puts the modification time back.
    pub changed_ns: i128,
    /// Inode number (0 where there is none): a file replaced by another
    /// (a rename over it) has another.
    pub inode: u64,
    /// When the stat was taken (before the bytes were read), ns since the
    /// epoch.
    pub seen_ns: u128,
}

/// A write within this long of the modification time can leave it as it
/// was (file systems keep times to 1 ns .. 2 s).
const TIME_GRAIN_NS: u128 = 2_000_000_000;

impl FileStat {
    /// The stat of the file at `path` (through links), now.
    pub fn of(path: &Path) -> Option<FileStat> {
        let now = std::time::SystemTime::now();
        let meta = std::fs::metadata(path).ok()?;
        let since = |t: std::time::SystemTime| {
            t.duration_since(std::time::UNIX_EPOCH)
                .ok()
                .map(|d| d.as_nanos())
        };
        let (changed_ns, inode) = inode_of(&meta);
        Some(FileStat {
            len: meta.len(),
            modified_ns: since(meta.modified().ok()?)?,
            changed_ns,
            inode,
            seen_ns: since(now)?,
        })
    }

    /// Whether `now` is this same file, unchanged since it was hashed. Not
    /// when it was modified within the time grain of the moment it was
    /// seen: a later write in the same grain could have kept the time.
    pub fn unchanged(&self, now: &FileStat) -> bool {
        let settled = self.modified_ns + TIME_GRAIN_NS <= self.seen_ns;
        settled
            && (self.len, self.modified_ns, self.changed_ns, self.inode)
                == (now.len, now.modified_ns, now.changed_ns, now.inode)
    }
}

/// The stats of the files beside a data file that decide its companions
/// ([`crate::ingest::companion::beside`]), now (`None`: absent).
pub fn beside_now(path: &Path) -> Vec<Option<FileStat>> {
    let beside = crate::ingest::companion::beside(path);
    beside.iter().map(|p| FileStat::of(p)).collect()
}

/// Whether the files that decide a data file's companions are `now` (a
/// [`beside_now`]) as a last run saw them (`seen`): each still absent, or
/// the same file unchanged since it was seen.
pub fn beside_unchanged(seen: &[Option<FileStat>], now: &[Option<FileStat>]) -> bool {
    seen.len() == now.len()
        && seen.iter().zip(now).all(|pair| match pair {
            (None, None) => true,
            (Some(seen), Some(now)) => seen.unchanged(now),
            _ => false,
        })
}

#[cfg(unix)]
fn inode_of(meta: &std::fs::Metadata) -> (i128, u64) {
    use std::os::unix::fs::MetadataExt;
    let changed = i128::from(meta.ctime()) * 1_000_000_000 + i128::from(meta.ctime_nsec());
    (changed, meta.ino())
}

#[cfg(not(unix))]
fn inode_of(_meta: &std::fs::Metadata) -> (i128, u64) {
    (0, 0)
}

/// One stage as the last run saw it.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct StageState {
    /// Its key.
    pub key: Key,
    /// Rows without a result.
    pub without_result: usize,
    /// Its notes.
    pub notes: Vec<String>,
    /// The tables it wrote.
    pub tables: Vec<String>,
    /// A per-file stage: what its published tables were joined from.
    #[serde(default)]
    pub joined: Composition,
}

/// What the published tables of a per-file stage were joined from: its
/// parts in input order and, for each table the stage published as joined,
/// each part's rows in it. A rerun takes those rows out of the published
/// table instead of each part's cache entry ([`super::join`]).
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct Composition {
    /// The parts' keys, in input order.
    pub parts: Vec<Key>,
    /// Per table, each part's number of rows.
    pub rows: BTreeMap<String, Vec<u64>>,
}

/// One written table: its key and how the file looked when written.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
pub struct TableState {
    /// The key of its content.
    pub key: Key,
    /// File size in bytes.
    pub len: u64,
    /// Modification time, ns since the epoch.
    pub modified_ns: u128,
}

impl TableState {
    /// The state of the file at `path` holding content `key`.
    pub fn of_file(path: &Path, key: Key) -> Option<Self> {
        let Stamp { len, modified_ns } = Stamp::of(path)?;
        Some(TableState {
            key,
            len,
            modified_ns,
        })
    }

    /// Whether the file at `path` is the one this state recorded, holding
    /// content `key`: the same key, size and modification time.
    pub fn is_file(&self, path: &Path, key: Key) -> bool {
        self.key == key && Self::of_file(path, key).as_ref() == Some(self)
    }
}

/// The state of an output folder.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct State {
    /// Inputs by path (an unchanged input's entry shared with the state
    /// before).
    pub files: ByName<Shared<FileState>>,
    /// Stages by name.
    pub stages: BTreeMap<String, StageState>,
    /// Tables by name.
    pub tables: BTreeMap<String, TableState>,
    /// The set's warnings, with the key of the tables they come from.
    #[serde(default)]
    pub doubts: Option<Doubts>,
    /// The context its inputs' keys were made in ([`super::keys::context_key`]).
    #[serde(default)]
    pub context: Option<Key>,
}

/// The warnings of a published set (rows whose status is not `ok`) and
/// the key of the tables they were read from: a rerun whose tables have
/// that key takes them from here instead of reading the tables.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
pub struct Doubts {
    /// The key of the tables.
    pub key: Key,
    /// The warnings.
    pub rows: Vec<crate::report::Doubt>,
}

/// An input's path with its entry in an old and a new state (either may
/// lack it).
pub type Paired<'a> = (
    &'a String,
    Option<&'a Shared<FileState>>,
    Option<&'a Shared<FileState>>,
);

/// The state's base file (binary, [`super::binfile`]).
pub fn path(out_dir: &Path) -> PathBuf {
    out_dir.join(".tribo").join("state.bin")
}

/// Where an older build kept the state, as JSON.
pub(super) fn json_path(out_dir: &Path) -> PathBuf {
    out_dir.join(".tribo").join("state.json")
}

impl State {
    /// Whether its inputs' keys were made in `context` (a state with no
    /// context was made in none).
    pub(super) fn made_in(&self, context: Option<Key>) -> bool {
        self.context.is_some() && self.context == context
    }

    /// When none of `names` (this run's inputs) is an input of this state
    /// but the first is one of them under another folder prefix (the
    /// pipeline given by another path, or run from another folder): that
    /// input's name in this state. Then every input is new to the cache,
    /// since its name is in its rows and keys.
    pub fn same_input_named_otherwise(&self, names: &[&str]) -> Option<&str> {
        let first = *names.first()?;
        if self.files.is_empty() || names.iter().any(|n| self.files.contains_key(n)) {
            return None;
        }
        let under = |long: &str, short: &str| {
            long.strip_suffix(short)
                .is_some_and(|p| p.ends_with('/') || p.ends_with(std::path::MAIN_SEPARATOR))
        };
        self.files
            .keys()
            .map(String::as_str)
            .find(|old| under(old, first) || under(first, old))
    }

    /// Each input of `old` or `new`, in path order, with its entry in
    /// each: one walk over both maps, where a lookup per input compared
    /// paths a dozen times.
    pub fn inputs_of_both<'a>(old: &'a State, new: &'a State) -> impl Iterator<Item = Paired<'a>> {
        let (mut a, mut b) = (old.files.iter().peekable(), new.files.iter().peekable());
        std::iter::from_fn(move || {
            let order = match (a.peek(), b.peek()) {
                (None, None) => return None,
                (Some(_), None) => Ordering::Less,
                (None, Some(_)) => Ordering::Greater,
                (Some((x, _)), Some((y, _))) => x.cmp(y),
            };
            let (path, was) = match order {
                Ordering::Greater => (b.peek()?.0, None),
                _ => a.next().map(|(p, s)| (p, Some(s)))?,
            };
            let now = match order {
                Ordering::Less => None,
                _ => b.next().map(|(_, s)| s),
            };
            Some((path, was, now))
        })
    }

    /// Whether table `def` is still the file this state wrote with `key`
    /// (a dataset: its manifest).
    pub fn published(&self, out_dir: &Path, def: &TableDef, key: &Key) -> bool {
        let file = stamped_file(out_dir, def);
        let old = self.tables.get(def.name);
        old.is_some_and(|old| old.is_file(&file, *key))
    }
}

/// The file whose stamp tells whether a published table is the one a run
/// wrote: the table's file, or a dataset's manifest (its files are named by
/// their content and never rewritten by tribo).
pub fn stamped_file(out_dir: &Path, def: &TableDef) -> PathBuf {
    match def.is_dataset() {
        true => super::dataset::manifest_path(out_dir, def.name),
        false => def.path_in(out_dir),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn state(files: &[(&str, &str)]) -> State {
        let files = files.iter().map(|(p, b)| {
            let f = FileState {
                bytes: (*b).into(),
                ..FileState::default()
            };
            (p.to_string(), f.into())
        });
        State {
            files: files.collect(),
            ..State::default()
        }
    }

    fn bytes(s: Option<&Shared<FileState>>) -> Option<&str> {
        s.map(|s| &*s.bytes)
    }

    #[test]
    fn both_states_inputs_are_paired_in_path_order() {
        let old = state(&[("a", "1"), ("c", "1"), ("d", "1"), ("f", "1")]);
        let new = state(&[("b", "2"), ("c", "2"), ("d", "1"), ("e", "2")]);
        let paired: Vec<(&str, Option<&str>, Option<&str>)> = State::inputs_of_both(&old, &new)
            .map(|(p, was, now)| (p.as_str(), bytes(was), bytes(now)))
            .collect();
        assert_eq!(
            paired,
            [
                ("a", Some("1"), None),
                ("b", None, Some("2")),
                ("c", Some("1"), Some("2")),
                ("d", Some("1"), Some("1")),
                ("e", None, Some("2")),
                ("f", Some("1"), None),
            ]
        );
        assert_eq!(State::inputs_of_both(&old, &State::default()).count(), 4);
        assert_eq!(State::inputs_of_both(&State::default(), &new).count(), 4);
    }

    /// The last run's inputs, found under another prefix when none of
    /// this run's names is among them; never when one is, nor for a name
    /// that only ends like another without a folder between.
    #[test]
    fn inputs_under_another_prefix_are_recognised() {
        let old = state(&[("lab/traces/a.csv", "1"), ("lab/traces/b.csv", "1")]);
        let named = |names: &[&str]| old.same_input_named_otherwise(names).map(str::to_string);
        let found = named(&["traces/a.csv", "traces/b.csv"]);
        assert_eq!(found.as_deref(), Some("lab/traces/a.csv"));
        let found = named(&["../x/lab/traces/b.csv"]);
        assert_eq!(found.as_deref(), Some("lab/traces/b.csv"));
        assert_eq!(named(&["traces/c.csv"]), None);
        assert_eq!(named(&["races/a.csv"]), None);
        assert_eq!(named(&["traces/a.csv", "lab/traces/b.csv"]), None);
        assert_eq!(named(&[]), None);
        let empty = State::default();
        assert_eq!(empty.same_input_named_otherwise(&["a.csv"]), None);
    }
}
