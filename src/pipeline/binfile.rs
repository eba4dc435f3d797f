//! The run's own bookkeeping files that grow with the inputs (the state,
//! the cache packs' indexes) in a compact binary form: read by every
//! rerun, they cost what their size does, and JSON was several times the
//! size and parse time of the same values in `bincode` (a rerun over
//! 20 000 files read 30 MB of it). A file written by an older build as
//! JSON is still read, once.

use std::path::Path;

use serde::de::DeserializeOwned;
use serde::Serialize;

use super::atomic::write_atomic;
use crate::error::{Error, Result};

/// The encoding: `bincode`'s standard (variable-length integers, little
/// endian), with a limit on what a damaged length can claim.
fn config() -> impl bincode::config::Config {
    bincode::config::standard().with_limit::<{ 1 << 32 }>()
}

/// The value in the binary file at `path`, or in the JSON file `json`
/// beside it when there is no binary one (a folder written by an older
/// build); `None` when neither can be read (then what it held is made
/// again).
pub fn read<T: DeserializeOwned>(path: &Path, json: Option<&Path>) -> Option<T> {
    match std::fs::read(path) {
        Ok(bytes) => decode(&bytes),
        Err(_) => serde_json::from_slice(&std::fs::read(json?).ok()?).ok(),
    }
}

/// The value `bytes` encode, all of them; `None` when they do not.
pub fn decode<T: DeserializeOwned>(bytes: &[u8]) -> Option<T> {
    bincode::serde::decode_from_slice(bytes, config())
        .ok()
        .filter(|(_, n)| *n == bytes.len())
        .map(|(v, _)| v)
}

/// The bytes of `value`.
pub fn encode<T: Serialize>(value: &T) -> Result<Vec<u8>> {
    bincode::serde::encode_to_vec(value, config()).map_err(|e| Error::Table(e.to_string()))
}

/// Writes `value` to `path` atomically.
pub fn write<T: Serialize>(path: &Path, value: &T) -> Result<()> {
    write_tagged(path, b"", value)
}

/// Writes `tag` then `value` to `path` atomically: a tag says which
/// layout of the value follows, so that a file of another layout is
/// refused rather than decoded into something else.
pub fn write_tagged<T: Serialize>(path: &Path, tag: &[u8], value: &T) -> Result<()> {
    let bytes = encode(value).map_err(|e| Error::Table(format!("{}: {e}", path.display())))?;
    write_atomic(path, |w| {
        use std::io::Write;
        let all = w.write_all(tag).and_then(|()| w.write_all(&bytes));
        all.map_err(|e| Error::io(path, e))
    })
}
