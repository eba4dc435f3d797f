//! Content hashes: SHA-256 for provenance (what users and other tools
//! check a file against).

use std::sync::Arc;

use sha2::{Digest, Sha256};

/// Lower-case hex SHA-256 of `bytes`.
pub fn sha256_hex(bytes: &[u8]) -> String {
    hex(&Sha256::digest(bytes))
}

/// Lower-case hex of a digest.
pub fn hex(digest: &[u8]) -> String {
    use std::fmt::Write;
    let mut s = String::with_capacity(digest.len() * 2);
    for b in digest {
        let _ = write!(s, "{b:02x}");
    }
    s
}

/// One input file and the SHA-256 of its bytes, as recorded in every
/// table's provenance. Shared strings: a run over a large archive copies
/// each input's into its results, its stages' input lists and its rows
/// (four allocations an input, as owned strings).
#[derive(Debug, Clone, PartialEq, Eq, PartialOrd, Ord, serde::Serialize, serde::Deserialize)]
pub struct InputHash {
    /// The path as given by the user.
    pub path: Arc<str>,
    /// Lower-case hex SHA-256 of the file content.
    pub sha256: Arc<str>,
}

impl InputHash {
    /// Hashes bytes already read from `path`.
    pub fn of_bytes(path: &std::path::Path, bytes: &[u8]) -> Self {
        InputHash {
            path: path.display().to_string().into(),
            sha256: sha256_hex(bytes).into(),
        }
    }

    /// Reads and hashes a file.
    pub fn of_file(path: &std::path::Path) -> crate::Result<Self> {
        let bytes = std::fs::read(path).map_err(|e| crate::Error::io(path, e))?;
        Ok(Self::of_bytes(path, &bytes))
    }
}

/// The SHA-256 of a list of inputs as `sha256sum` prints them, one
/// `<sha256>  <path>` line each, in the list's order (by path): one value
/// that stands for the whole list, which `files.parquet` holds row by row
/// (`sha256sum FILES | sort -k2 | sha256sum` gives it for files named
/// without spaces or newlines).
pub fn inputs_sha256(inputs: &[InputHash]) -> String {
    let mut h = Sha256::new();
    for i in inputs {
        h.update(i.sha256.as_bytes());
        h.update(b"  ");
        h.update(i.path.as_bytes());
        h.update(b"\n");
    }
    hex(&h.finalize())
}
