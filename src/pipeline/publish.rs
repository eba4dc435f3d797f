//! Writing tables: checked against their schema (`schemas/`), with
//! provenance, atomically (a temporary file in the same folder, flushed to
//! disk, then renamed over the target), so that a reader never sees a
//! half-written file, after an error or a kill.

use std::fs::{self, File};
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};

use super::provenance::Provenance;
use crate::error::{Error, Result};
use crate::schema;
use crate::table::Table;

/// Checks `table` against `schemas/<name>.toml` and writes
/// `dir/<name>.parquet` atomically, with the provenance in the metadata and
/// each column's unit and meaning as field metadata. Returns the path.
pub fn write_table(
    dir: &Path,
    name: &str,
    table: &Table,
    provenance: &Provenance,
) -> Result<PathBuf> {
    let schema = schema::schema(name)?;
    schema.check(table)?;
    let path = dir.join(format!("{name}.parquet"));
    let kv = provenance.key_values(name);
    let columns = schema.field_metadata();
    write_atomic(&path, |w| table.write_parquet_with(w, &kv, &columns))?;
    Ok(path)
}

/// Writes `path` atomically; `fill` writes the content into the temporary
/// file. On any error the temporary file is removed and `path` is untouched.
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
    let tmp = dir.join(format!(".{name}.{}.tmp", std::process::id()));
    let result = (|| {
        let file = File::create(&tmp).map_err(|e| Error::io(&tmp, e))?;
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
