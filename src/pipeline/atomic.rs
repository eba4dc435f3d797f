//! Files written whole or not at all: one file through a temporary name
//! beside it ([`write_atomic`]), or a folder of documents, the report's
//! pages ([`write_docs`]), each of which that comes out as the last set
//! has it is linked from there rather than written again.

use std::fs::{self, File, OpenOptions};
use std::io::{BufWriter, Write};
use std::path::Path;

use rayon::prelude::*;

use super::owner::temp_name;
use crate::error::{Error, Result};

/// Writes `path` atomically; `fill` writes the content into a temporary
/// file created exclusively beside it (never through an existing file or
/// link). On any error the temporary file is removed and `path` is
/// untouched.
pub fn write_atomic(
    path: &Path,
    fill: impl FnOnce(&mut BufWriter<&File>) -> Result<()>,
) -> Result<()> {
    let dir = path
        .parent()
        .filter(|p| !p.as_os_str().is_empty())
        .unwrap_or(Path::new("."));
    fs::create_dir_all(dir).map_err(|e| Error::io(dir, e))?;
    let name = path
        .file_name()
        .and_then(|n| n.to_str())
        .unwrap_or("output");
    let tmp = dir.join(temp_name(&format!(".{name}")));
    let result = (|| {
        let file = OpenOptions::new()
            .write(true)
            .create_new(true)
            .open(&tmp)
            .map_err(|e| Error::io(&tmp, e))?;
        {
            let mut w = BufWriter::new(&file);
            fill(&mut w)?;
            w.flush().map_err(|e| Error::io(&tmp, e))?;
        }
        file.sync_all().map_err(|e| Error::io(&tmp, e))?;
        fs::rename(&tmp, path).map_err(|e| Error::io(path, e))
    })();
    if result.is_err() {
        let _ = fs::remove_file(&tmp);
    }
    result
}

/// Writes a text file atomically.
pub fn write_text_atomic(path: &Path, text: &str) -> Result<()> {
    write_atomic(path, |w| {
        w.write_all(text.as_bytes()).map_err(|e| Error::io(path, e))
    })
}

/// A document of a folder that [`write_docs`] writes.
pub enum Doc {
    /// Made: its name and content.
    Made(String, String),
    /// The published folder's file of this name, known to be unchanged.
    Kept(String),
}

/// Writes `n` documents made by `doc` into the folder `dir`, in parallel,
/// each made as it is written (never all held at once). A document kept,
/// or made with the bytes that `published` (the folder's last published
/// copy) holds, is linked from there: a report's pages are made again
/// whenever one file's section changes, and most of them come out the
/// same (616 MB of pages at 20 000 friction traces).
pub(super) fn write_docs(
    dir: &Path,
    n: usize,
    doc: impl Fn(usize) -> Result<Doc> + Sync,
    published: Option<&Path>,
) -> Result<()> {
    fs::create_dir_all(dir).map_err(|e| Error::io(dir, e))?;
    (0..n).into_par_iter().try_for_each(|i| {
        let (name, content) = match doc(i)? {
            Doc::Made(name, content) => (name, Some(content)),
            Doc::Kept(name) => (name, None),
        };
        let path = dir.join(&name);
        let old = published.map(|p| p.join(&name));
        let Some(content) = content else {
            let gone = || Error::io(&path, std::io::ErrorKind::NotFound.into());
            let old = old.ok_or_else(gone)?;
            if fs::hard_link(&old, &path).is_err() {
                fs::copy(&old, &path).map_err(|e| Error::io(&path, e))?;
            }
            return Ok(());
        };
        if old
            .is_some_and(|o| same_bytes(&o, content.as_bytes()) && fs::hard_link(&o, &path).is_ok())
        {
            return Ok(());
        }
        write_atomic(&path, |w| {
            w.write_all(content.as_bytes())
                .map_err(|e| Error::io(&path, e))
        })
    })
}

/// Whether the file at `path` holds exactly `bytes` (its length compared
/// first: most changed pages differ in length).
fn same_bytes(path: &Path, bytes: &[u8]) -> bool {
    let same_len = fs::metadata(path).is_ok_and(|m| m.len() == bytes.len() as u64);
    same_len && fs::read(path).is_ok_and(|b| b == bytes)
}
