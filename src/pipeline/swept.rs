//! Folders that grow with the inputs (the cache's `parts/`, a dataset's
//! folder) are listed only when something other than tribo's last run
//! changed them. A folder's modification time changes with every entry
//! added, removed or renamed in it; the last published run records each
//! such folder's [`Stamp`] after its last change to it
//! (`OUT/.tribo/swept.bin`). A run that finds the same stamp knows the
//! folder holds exactly what that run left (its entries are then known
//! from the packs and the set's manifests, and only those that die are
//! removed, by name); any other stamp (a killed run's leftovers, a
//! shard's entries, a file removed by hand) or none means one listing and
//! a sweep, as with no record at all. A leftover made within the clock
//! tick of the record (no run writes while another holds the lock) would
//! stay until the next sweep: disk, never a wrong table.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use super::binfile;
use super::stamp::Stamp;

/// The stamps of the folders the last published run left as it recorded.
#[derive(Debug, Default)]
pub struct Swept {
    out: PathBuf,
    /// As read at the start of the run.
    old: BTreeMap<String, Stamp>,
    /// As this run leaves them.
    new: BTreeMap<String, Stamp>,
}

/// Its file.
fn path(out: &Path) -> PathBuf {
    out.join(".tribo").join("swept.bin")
}

impl Swept {
    /// The record of `out` (none after `--force`, or when it cannot be
    /// read: then every folder is listed).
    pub fn load(out: &Path, trust: bool) -> Swept {
        let old = match trust {
            true => binfile::read(&path(out), None).unwrap_or_default(),
            false => BTreeMap::new(),
        };
        Swept {
            out: out.to_path_buf(),
            old,
            new: BTreeMap::new(),
        }
    }

    fn name(&self, dir: &Path) -> String {
        dir.strip_prefix(&self.out)
            .unwrap_or(dir)
            .to_string_lossy()
            .into_owned()
    }

    /// Whether `dir` is as the last run left it: nothing added, removed
    /// or renamed in it since. Asked before this run changes it.
    pub fn holds(&self, dir: &Path) -> bool {
        self.old
            .get(&self.name(dir))
            .is_some_and(|s| Stamp::of(dir).as_ref() == Some(s))
    }

    /// Records `dir` as this run leaves it (after its last change to it).
    pub fn record(&mut self, dir: &Path) {
        if let Some(s) = Stamp::of(dir) {
            self.new.insert(self.name(dir), s);
        }
    }

    /// Saves the record (after the set is published and the cache pruned;
    /// a run killed before leaves the last one, which no longer holds for
    /// what it changed).
    pub fn save(&self) {
        if self.new != self.old {
            let _ = binfile::write(&path(&self.out), &self.new);
        }
    }
}
