//! Cache keys: BLAKE3 (fast; the provenance keeps SHA-256) of
//! length-prefixed parts, so that ("ab","c") and ("a","bc") differ, each
//! key starting with tribo's version, so that a new version recomputes
//! everything. The keys of a file's route, of a stage's part of one file,
//! of a stage, of a table and of a study's unit are all made here.

use serde::{Deserialize, Serialize};

use super::plan::Plan;
use super::planned::{PlannedFile, PlannedStage};
use crate::ingest::companion;
use crate::ingest::manifest::Manifest;

/// A cache key: a BLAKE3 hash, held as its 32 bytes (a run over a large
/// archive holds tens of thousands; as hex strings, each was an allocation
/// of its own) and written as lower-case hex, its form in every file
/// (state, packs, cache names), which therefore did not change. Bytes
/// order as their hex does.
#[derive(Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct Key([u8; 32]);

impl Key {
    /// The key whose hex is `hex` (64 lower- or upper-case hex digits).
    pub fn from_hex(hex: &str) -> Option<Key> {
        // By a table: a state holds a hundred thousand keys, and a
        // decoder that matches each digit took longer than the strings
        // it replaces.
        let hex = hex.as_bytes();
        if hex.len() != 64 {
            return None;
        }
        let mut key = [0u8; 32];
        let mut bad = 0u8;
        for (k, pair) in key.iter_mut().zip(hex.chunks_exact(2)) {
            let (hi, lo) = (HEX[pair[0] as usize], HEX[pair[1] as usize]);
            bad |= (hi | lo) & 0x10;
            *k = (hi << 4) | (lo & 0x0f);
        }
        (bad == 0).then_some(Key(key))
    }

    /// Its hex, on the stack.
    pub fn hex(&self) -> impl std::ops::Deref<Target = str> {
        blake3::Hash::from_bytes(self.0).to_hex()
    }

    /// The key that is the BLAKE3 of `text` (for tests).
    #[cfg(test)]
    pub(crate) fn of_text(text: &str) -> Key {
        Key(*blake3::hash(text.as_bytes()).as_bytes())
    }
}

impl std::fmt::Display for Key {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.hex())
    }
}

impl std::fmt::Debug for Key {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "Key({})", &*self.hex())
    }
}

impl Serialize for Key {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.serialize_str(&self.hex())
    }
}

impl<'de> Deserialize<'de> for Key {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Key, D::Error> {
        struct Hex;
        impl serde::de::Visitor<'_> for Hex {
            type Value = Key;
            fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
                f.write_str("a key: 64 hex digits")
            }
            fn visit_str<E: serde::de::Error>(self, v: &str) -> Result<Key, E> {
                Key::from_hex(v)
                    .ok_or_else(|| E::invalid_value(serde::de::Unexpected::Str(v), &self))
            }
        }
        d.deserialize_str(Hex)
    }
}

/// Each byte's value as a hex digit, or 0x10 for a byte that is not one.
const HEX: [u8; 256] = {
    let mut t = [0x10u8; 256];
    let mut i = 0;
    while i < 10 {
        t[b'0' as usize + i] = i as u8;
        i += 1;
    }
    let mut i = 0;
    while i < 6 {
        t[b'a' as usize + i] = 10 + i as u8;
        t[b'A' as usize + i] = 10 + i as u8;
        i += 1;
    }
    t
};

/// Builds a key from parts.
pub struct KeyBuilder(blake3::Hasher);

impl KeyBuilder {
    /// A key of one kind (`route`, `part`, `stage`, `table`), of this
    /// build ([`crate::BUILD`]): no other build makes the same keys.
    pub fn new(kind: &str) -> Self {
        Self::of_build(crate::BUILD, kind)
    }
    /// [`KeyBuilder::new`] as the build `build` makes it.
    fn of_build(build: &str, kind: &str) -> Self {
        KeyBuilder(blake3::Hasher::new()).part(build).part(kind)
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
    /// Adds a key, as its hex (the form keys took when they were text,
    /// so that every key made of keys is the one it was).
    pub fn key(self, key: &Key) -> Self {
        self.part(&key.hex())
    }
    /// The key.
    pub fn finish(self) -> Key {
        Key(*self.0.finalize().as_bytes())
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
        .part(&f.source)
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

/// The key of what each input's keys are made of besides the input itself
/// (its path, bytes and companions): tribo's version, the pipeline as
/// written (reading options, stage globs), each stage's signature and the
/// manifest. A run whose context is the last run's takes an unchanged
/// input's keys from the state instead of hashing them again
/// ([`super::files`]). `None` when the pipeline could not be written out
/// (then no context is the same as another).
pub(super) fn context_key(plan: &Plan) -> Option<Key> {
    if plan.spec_json.is_null() {
        return None;
    }
    let mut kb = KeyBuilder::new("context/1")
        .part(ROUTE)
        .part_value(&plan.spec_json);
    for s in &plan.stages {
        let sig = &s.signature;
        kb = kb
            .part(s.stage.name())
            .part(&sig.parameters)
            .part(&sig.tables);
    }
    let manifest = plan.manifest.as_ref().map(|(_, h)| &*h.sha256);
    Some(kb.part(manifest.unwrap_or("")).finish())
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
        .key(rkey)
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
    KeyBuilder::new("table").key(stage_key).part(table).finish()
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

#[cfg(test)]
mod tests {
    use super::*;

    /// Keys are this build's: the same parts under another build (the same
    /// version, other sources) make another key.
    #[test]
    fn another_build_makes_other_keys() {
        let key = |kb: KeyBuilder| kb.part("traces/a.csv").finish();
        let version = env!("CARGO_PKG_VERSION");
        assert!(crate::BUILD.starts_with(&format!("{version}+")));
        assert_eq!(
            key(KeyBuilder::new("route")),
            key(KeyBuilder::of_build(crate::BUILD, "route"))
        );
        let other = format!("{version}+0000000000000000");
        assert_ne!(
            key(KeyBuilder::new("route")),
            key(KeyBuilder::of_build(&other, "route"))
        );
    }

    #[test]
    fn a_key_reads_back_from_its_hex_as_blake3_writes_it() {
        for text in ["", "a", "route/3", "twenty thousand inputs"] {
            let key = Key::of_text(text);
            let hex = blake3::hash(text.as_bytes()).to_hex();
            assert_eq!(&*key.hex(), hex.as_str());
            assert_eq!(Key::from_hex(&hex), Some(key));
            assert_eq!(Key::from_hex(&hex.to_ascii_uppercase()), Some(key));
        }
    }

    #[test]
    fn what_is_not_64_hex_digits_is_no_key() {
        let hex = Key::of_text("x").hex().to_string();
        assert_eq!(Key::from_hex(&hex[..62]), None);
        assert_eq!(Key::from_hex(&format!("{hex}0")), None);
        for bad in ['g', 'G', ' ', '/', ':', '@', '`', 'é'] {
            let mut s = hex.clone();
            s.replace_range(10..10 + bad.len_utf8(), &bad.to_string());
            assert_eq!(Key::from_hex(&s), None, "{s}");
        }
    }

    #[test]
    fn keys_order_as_their_hex_and_serialize_as_it() {
        let mut keys: Vec<Key> = (0..200).map(|i| Key::of_text(&i.to_string())).collect();
        let mut hexes: Vec<String> = keys.iter().map(|k| k.hex().to_string()).collect();
        keys.sort();
        hexes.sort();
        let back: Vec<String> = keys.iter().map(ToString::to_string).collect();
        assert_eq!(back, hexes);
        let json = serde_json::to_string(&keys[0]).unwrap();
        assert_eq!(json, format!("\"{}\"", hexes[0]));
        let cfg = bincode::config::standard();
        let bytes = bincode::serde::encode_to_vec(keys[0], cfg).unwrap();
        assert_eq!(
            bytes,
            bincode::serde::encode_to_vec(&hexes[0], cfg).unwrap()
        );
        let (k, _): (Key, usize) = bincode::serde::decode_from_slice(&bytes, cfg).unwrap();
        assert_eq!(k, keys[0]);
        assert!(serde_json::from_str::<Key>("\"not a key\"").is_err());
    }
}
