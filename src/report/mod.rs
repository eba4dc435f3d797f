//! Reports: Parquet tables checked against their schema, with provenance,
//! written atomically.

pub mod atomic;
pub mod friction;
pub mod provenance;
pub mod schema;

use std::path::{Path, PathBuf};

use crate::error::Result;
use crate::table::Table;
pub use provenance::{InputHash, Provenance};

/// Checks `table` against `schemas/<name>.toml` and writes `dir/<name>.parquet`
/// atomically, with the provenance as key-value metadata. Returns the path.
pub fn write_table(
    dir: &Path,
    name: &str,
    table: &Table,
    provenance: &Provenance,
) -> Result<PathBuf> {
    schema::schema(name)?.check(table)?;
    let path = dir.join(format!("{name}.parquet"));
    let kv = provenance.key_values(name);
    atomic::write_atomic(&path, |w| table.write_parquet_to(w, &kv))?;
    Ok(path)
}
