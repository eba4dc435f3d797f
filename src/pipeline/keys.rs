//! Cache keys: BLAKE3 (fast; the provenance keeps SHA-256) of
//! length-prefixed parts, so that ("ab","c") and ("a","bc") differ, each
//! key starting with tribo's version, so that a new version recomputes
//! everything. The keys of a file's route, of a stage's part of one file,
//! of a stage, of a table and of a study's unit are all made here.

use serde::{Deserialize, Serialize};

use super::planned::{PlannedFile, PlannedStage};
use crate::ingest::companion;
use crate::ingest::manifest::Manifest;

/// A cache key: lower-case hex BLAKE3.
#[derive(Debug, Clone, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize, Deserialize)]
pub struct Key(pub String);

/// Builds a key from parts.
pub struct KeyBuilder(blake3::Hasher);

impl KeyBuilder {
    /// A key of one kind (`route`, `part`, `stage`, `table`).
    pub fn new(kind: &str) -> Self {
        KeyBuilder(blake3::Hasher::new())
            .part(env!("CARGO_PKG_VERSION"))
            .part(kind)
    }
    /// Adds one part.
    pub fn part(mut self, part: &str) -> Self {
        self.0.update(&(part.len() as u64).to_le_bytes());
        self.0.update(part.as_bytes());
        self
    }
    /// Adds a value as its binary encoding (`bincode`'s standard), streamed
    /// into a hash of its own (a value that grows with the inputs is never
    /// held whole; as JSON, escaping every string of it took a tenth of a
    /// rerun's publishing).
    pub fn part_value(self, value: &(impl Serialize + ?Sized)) -> Self {
        let mut h = blake3::Hasher::new();
        // Writing into a hasher cannot fail; a value that does not encode
        // adds what was written before it failed. Buffered: the encoder
        // writes a few bytes at a time.
        let mut w = std::io::BufWriter::with_capacity(1 << 16, &mut h);
        let _ = bincode::serde::encode_into_std_write(value, &mut w, bincode::config::standard());
        drop(w);
        self.part(h.finalize().to_hex().as_str())
    }
    /// The key.
    pub fn finish(self) -> Key {
        Key(self.0.finalize().to_hex().to_string())
    }
}

/// The kind of key of a file's route (its version: a route entry holds the
/// file's reader since `route/2`; its companions are in the key since
/// `route/3`).
const ROUTE: &str = "route/3";

/// The key of a file's route: its path, the BLAKE3 of its bytes and its
/// reading options.
pub(super) fn route_key(f: &PlannedFile, blake3: &str) -> Key {
    KeyBuilder::new(ROUTE)
        .part(&f.path.display().to_string())
        .part(blake3)
        .part(&f.options_key)
        .part(&companion_contents(&f.path))
        .finish()
}

/// The companions read with a data file ([`companion::files_of`]) and the
/// BLAKE3 of their bytes: what a data file's reading is made of besides
/// its own bytes, so that a changed `.tx3` or `.TSX` redoes its data file
/// although that file's bytes and stat are unchanged. Empty for a file
/// without companions (no file is opened for those).
fn companion_contents(path: &std::path::Path) -> String {
    companion::files_of(path)
        .iter()
        .map(|c| {
            let content = std::fs::read(c).map_or_else(
                |e| format!("unreadable: {e}"),
                |b| blake3::hash(&b).to_hex().to_string(),
            );
            format!("{}={content}\n", c.display())
        })
        .collect()
}

/// The key of one stage's rows for one file: the file (route key), the
/// stage with its validated parameters and tables, and the file's row of
/// the manifest.
pub(super) fn part_key(
    stage: &PlannedStage,
    f: &PlannedFile,
    rkey: &Key,
    manifest: Option<&Manifest>,
) -> Key {
    let row = manifest.and_then(|m| m.find(&f.path));
    let sig = &stage.signature;
    KeyBuilder::new("part")
        .part(&rkey.0)
        .part(stage.stage.name())
        .part(&sig.parameters)
        .part(&sig.tables)
        .part(&format!("{row:?}"))
        .finish()
}

/// The start of a stage's key: its name, parameters and tables; the keys
/// of what it reads follow.
pub(super) fn stage_key(stage: &PlannedStage) -> KeyBuilder {
    let sig = &stage.signature;
    KeyBuilder::new("stage")
        .part(stage.stage.name())
        .part(&sig.parameters)
        .part(&sig.tables)
}

/// The key of the table `table` of the stage whose key is `stage_key`.
pub(super) fn table_key(stage_key: &Key, table: &str) -> Key {
    KeyBuilder::new("table")
        .part(&stage_key.0)
        .part(table)
        .finish()
}

/// The key of unit `u` of a table stage: its parameters, the files it
/// reads itself, and the unit's index.
pub(super) fn unit_key(stage: &PlannedStage, u: usize) -> Key {
    let mut kb = stage_key(stage).part("unit");
    for h in stage.stage.own_inputs() {
        kb = kb.part(&h.sha256);
    }
    kb.part(&u.to_string()).finish()
}
