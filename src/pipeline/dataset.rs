//! Tables published as datasets ([`TableDef::dataset`]): a table whose size
//! grows with the inputs (`traces`) is the folder `OUT/<table>/` of one
//! Parquet file per input, which DuckDB (`read_parquet('OUT/traces/*.parquet')`),
//! polars (`scan_parquet`), pyarrow (`dataset`) and Spark read as one table.
//!
//! - A file is named by its input and its cache part's key
//!   (`<stem>-<key>.parquet`): a name always holds the same rows. It is
//!   the cache's part itself (a hard link: one file, two names), written
//!   once, in the per-file phase.
//! - The published set lists the table's files in input order in
//!   `<table>.dataset.json` (linked as `OUT/<table>.dataset.json`, like the
//!   tables). A reader that goes through it sees one complete set.
//! - A rerun links the files of new or changed inputs into the folder
//!   before the set is published, and removes the files the new set does
//!   not list after; an unchanged input's file is not touched.

use std::collections::{BTreeSet, HashSet};
use std::fs;
use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};

use super::keys::Key;
use super::owner::{is_leftover, temp_name};
use super::registry;
use crate::error::{Error, Result};
use crate::schema::TableDef;
use crate::table::Table;

/// The suffix of a dataset's manifest: `OUT/<table>.dataset.json`.
pub const MANIFEST: &str = ".dataset.json";

/// What the published set says of a dataset: its files, in input order.
#[derive(Debug, Clone, Default, Serialize, Deserialize)]
pub struct Manifest {
    /// The table's name (its folder).
    pub table: String,
    /// File names in the folder, in input order.
    pub files: Vec<String>,
}

/// One file of a dataset as a run publishes it.
#[derive(Debug, Clone)]
pub struct DataFile {
    /// Its name in the table's folder.
    pub name: String,
    /// The key of its cache part, whose file is the same file under
    /// another name ([`super::cache::Cache::part_file`]): made into a path
    /// only for a file that is linked, not for each of thousands of
    /// unchanged inputs.
    pub key: Key,
    /// Made in this run: linked into the folder even where a file of that
    /// name is there (a part made again replaces it).
    pub fresh: bool,
}

/// The manifest file of the dataset `name` in `dir` (an output folder, or
/// a set).
pub fn manifest_path(dir: &Path, name: &str) -> PathBuf {
    dir.join(format!("{name}{MANIFEST}"))
}

/// The name of an input's file in a dataset: its file stem (letters,
/// digits, `-`, `_`, `.`; at most 64 of them) and 16 hex digits of its
/// part's key.
pub fn file_name(input: &str, part: &Key) -> String {
    let stem = Path::new(input)
        .file_stem()
        .map(|s| s.to_string_lossy())
        .unwrap_or_default();
    // Made in one allocation: a name per input, every run.
    let mut name = String::with_capacity(stem.len().min(64) + 25);
    name.extend(stem.chars().take(64).map(|c| {
        match c.is_ascii_alphanumeric() || "-_.".contains(c) {
            true => c,
            false => '_',
        }
    }));
    name.push('-');
    name.push_str(&part.hex()[..16]);
    name.push_str(".parquet");
    name
}

/// Reads a manifest.
pub fn read_manifest(path: &Path) -> Result<Manifest> {
    let text = fs::read_to_string(path).map_err(|e| Error::io(path, e))?;
    serde_json::from_str(&text)
        .map_err(|e| Error::Table(format!("{}: not a dataset manifest: {e}", path.display())))
}

/// Reads a published table as one table: a Parquet file, or a dataset's
/// folder, its files stacked in the order its manifest lists them (a
/// dictionary column's values joined across the files).
pub fn read_table(path: &Path) -> Result<Table> {
    if !path.is_dir() {
        return Ok(Table::read_parquet(path)?.0);
    }
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().to_string())
        .unwrap_or_default();
    let dir = path.parent().unwrap_or(Path::new("."));
    let manifest = read_manifest(&manifest_path(dir, &name))?;
    let paths: Vec<_> = manifest.files.iter().map(|f| path.join(f)).collect();
    match Table::read_stacked(&paths)? {
        Some(t) => Ok(t),
        None => registry::find(&name)
            .ok_or_else(|| Error::Table(format!("no table named '{name}'")))?
            .empty_table(),
    }
}

/// Links `files` into the folder of `def` in `out` (made when missing):
/// a file not there, or made in this run, is linked (or copied, across file
/// systems) under its name from its cache part's file (`source`); the
/// others are left as they are. What was linked is flushed to disk, with
/// one call for all the files. `known`: the folder's files, when known
/// without listing it.
pub(super) fn link_files(
    out: &Path,
    def: &TableDef,
    files: &[DataFile],
    known: Option<&[String]>,
    source: impl Fn(&DataFile) -> PathBuf,
) -> Result<()> {
    let dir = def.path_in(out);
    if !dir.is_dir() {
        // A file where the folder should be (an older table) goes.
        let _ = fs::remove_file(&dir);
        fs::create_dir_all(&dir).map_err(|e| Error::io(&dir, e))?;
    }
    // At most one listing of the folder, not a stat per file: an
    // unchanged input's file is there already and is left alone.
    // (A name that is not UTF-8 is no dataset file's.)
    let listed: Vec<String>;
    let names = match known {
        Some(names) => names,
        None => {
            listed = fs::read_dir(&dir)
                .map_err(|e| Error::io(&dir, e))?
                .flatten()
                .filter_map(|e| e.file_name().into_string().ok())
                .collect();
            &listed
        }
    };
    let present: HashSet<&str> = names.iter().map(String::as_str).collect();
    let mut linked = Vec::new();
    for f in files {
        if !f.fresh && present.contains(f.name.as_str()) {
            continue;
        }
        let source = source(f);
        let to = dir.join(&f.name);
        linked.push(to.clone());
        // A new name appears whole (a link is one step); a name already
        // there is replaced by a rename.
        let tmp = dir.join(temp_name(&format!(".{}", f.name)));
        if fs::hard_link(&source, &tmp).is_err() {
            fs::copy(&source, &tmp).map_err(|e| Error::io(&tmp, e))?;
        }
        let renamed = fs::rename(&tmp, &to);
        // A rename onto another link of the same file does nothing and
        // leaves the temporary name: it goes either way.
        let _ = fs::remove_file(&tmp);
        renamed.map_err(|e| Error::io(&to, e))?;
    }
    if !linked.is_empty() {
        sync_files(&dir, &linked);
    }
    Ok(())
}

/// Flushes new files to disk: on Linux the whole file system at once (one
/// call: a sync per file costs a journal commit each, seconds for
/// thousands of files), elsewhere file by file.
#[cfg(target_os = "linux")]
fn sync_files(dir: &Path, _files: &[PathBuf]) {
    use std::os::fd::AsRawFd;
    if let Ok(d) = fs::File::open(dir) {
        // SAFETY: `d` is an open descriptor for the call's duration.
        unsafe { libc::syncfs(d.as_raw_fd()) };
    }
}

#[cfg(not(target_os = "linux"))]
fn sync_files(_dir: &Path, files: &[PathBuf]) {
    for f in files {
        if let Ok(f) = fs::File::open(f) {
            let _ = f.sync_all();
        }
    }
}

/// Removes from the folder `dir` the Parquet files `keep` does not name,
/// and temporary files of runs that are gone.
pub(super) fn prune(dir: &Path, keep: &BTreeSet<&str>) {
    let Ok(entries) = fs::read_dir(dir) else {
        return;
    };
    for e in entries.flatten() {
        let name = e.file_name().to_string_lossy().to_string();
        let stale = match name.ends_with(".tmp") {
            true => name.starts_with('.') && is_leftover(&name, true),
            false => name.ends_with(".parquet") && !keep.contains(name.as_str()),
        };
        if stale {
            let _ = fs::remove_file(e.path());
        }
    }
}

/// Removes the folder of a dataset no longer published: its Parquet files,
/// then the folder if nothing else is in it.
pub(super) fn remove(dir: &Path) {
    prune(dir, &BTreeSet::new());
    let _ = fs::remove_dir(dir);
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_file_is_named_by_its_input_stem_and_key() {
        let key = Key::of_text("k");
        let hex = key.hex()[..16].to_string();
        let name = file_name("in/run 3 (µ=0.2).csv", &key);
        assert_eq!(name, format!("run_3____0.2_-{hex}.parquet"));
        let long = format!("in/{}.csv", "ab".repeat(40));
        let name = file_name(&long, &key);
        assert_eq!(name, format!("{}-{hex}.parquet", "ab".repeat(32)));
        assert_eq!(file_name("", &key), format!("-{hex}.parquet"));
    }
}
