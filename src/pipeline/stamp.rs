//! A file's (or folder's) size and modification time: what a rewrite of
//! a file, or an entry added to or removed from a folder, changes.

use std::path::Path;

use serde::{Deserialize, Serialize};

/// A file's size and modification time: what a rewrite of the file
/// changes (the published tables a rerun keeps, the cache's links to them).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub struct Stamp {
    /// Size in bytes.
    pub len: u64,
    /// Modification time, ns since the epoch.
    pub modified_ns: u128,
}

impl Stamp {
    /// The stamp of the file at `path` (through links).
    pub fn of(path: &Path) -> Option<Stamp> {
        let meta = std::fs::metadata(path).ok()?;
        let modified_ns = meta
            .modified()
            .ok()?
            .duration_since(std::time::UNIX_EPOCH)
            .ok()?
            .as_nanos();
        Some(Stamp {
            len: meta.len(),
            modified_ns,
        })
    }
}
