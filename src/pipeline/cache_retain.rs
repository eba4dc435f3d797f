//! What the cache keeps at the end of a published run: the entries the
//! run used; dead entries, packs nothing can read and killed runs'
//! leftovers go.

use std::collections::BTreeSet;
use std::fs;
use std::path::Path;

use super::super::owner::is_leftover;
use super::super::pack;
use super::{Cache, Key};

impl Cache {
    /// Removes every entry that the current run does not use (those of
    /// deleted or changed inputs, of old parameters), and leftovers of
    /// killed runs. `dead`: when the last run's state stood for the cache,
    /// the routes and parts it named that this run does not use; the
    /// packs are then read only when there are any, or too many packs.
    /// `live`: the routes and parts the run uses (made only when needed).
    pub fn retain(
        &self,
        live: impl FnOnce() -> (BTreeSet<Key>, BTreeSet<Key>),
        stages: &BTreeSet<Key>,
        units: &BTreeSet<Key>,
        dead: Option<&[Key]>,
    ) {
        prune(&self.dir.join("units"), |name| {
            name.strip_suffix(".json")
                .and_then(Key::from_hex)
                .is_some_and(|k| units.contains(&k))
        });
        prune(&self.dir.join("stages"), |name| {
            Key::from_hex(name).is_some_and(|k| stages.contains(&k))
        });
        // Routes and parts of an older cache, one file each, go.
        prune(&self.dir.join("routes"), |_| false);
        let _ = fs::remove_dir(self.dir.join("routes"));
        let prune_packs = match dead {
            Some(dead) => {
                self.remove_part_files(dead.iter());
                !dead.is_empty() || pack::count(&self.packs_dir()) > pack::MAX_PACKS
            }
            None => true,
        };
        // An unreadable pack (read to prune them, or by a lookup) lists
        // none of its parts' files.
        let lost = (prune_packs || self.packs.get().is_some()) && self.packs().any_unreadable();
        let prune_packs = prune_packs || lost;
        let (routes, parts) = match prune_packs {
            true => live(),
            false => Default::default(),
        };
        // `parts/` is listed when its files may not all be in the packs.
        if lost || (dead.is_none() && !self.parts_known) {
            prune(&self.parts_dir(), |name| {
                part_key(name).is_some_and(|k| parts.contains(&k))
            });
        } else if dead.is_none() {
            self.remove_part_files(self.packs().dead_parts(&parts));
        }
        // A pack that cannot be written again stays as it is (its entries
        // are only ever read through their keys).
        if prune_packs {
            let _ = pack::retain(&self.packs_dir(), self.packs(), &routes, &parts);
        }
        prune(&self.packs_dir(), |name| !name.ends_with(".tmp"));
    }
}

/// The key in a part's file name (`<key>.<table>.parquet`).
fn part_key(name: &str) -> Option<Key> {
    let (key, _) = name.strip_suffix(".parquet")?.split_once('.')?;
    Key::from_hex(key)
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
