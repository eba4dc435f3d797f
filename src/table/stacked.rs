//! A table stored as many small Parquet files (a dataset's, one per
//! input), read as one.

use std::fs;
use std::io::Cursor;
use std::path::{Path, PathBuf};

use polars::prelude::{ParallelStrategy, ParquetReader, SerReader};
use rayon::prelude::*;

use super::Table;
use crate::error::{Error, Location, Result};

impl Table {
    /// The files at `paths` stacked in order (a dictionary column's values
    /// joined across them); `None` when there are none.
    ///
    /// The files are read in parallel, each decoded on the thread that
    /// reads it: a file of a few hundred rows is mostly its footer, and
    /// polars' own parallel decoding, entered from rayon's threads, lets
    /// each waiting thread take another file's read, one inside the other,
    /// until the stack overflows (4 000 figure files did).
    pub fn read_stacked(paths: &[PathBuf]) -> Result<Option<Table>> {
        let tables = paths
            .par_iter()
            .map(|p| read_one(p))
            .collect::<Result<Vec<_>>>()?;
        Table::concat(tables)
    }
}

/// One file, read whole into memory first: polars maps a `File` into
/// memory, and mapping and unmapping thousands of small files cost more
/// than their reading (16 % of a report's CPU over 2 000 figure files).
fn read_one(path: &Path) -> Result<Table> {
    let bytes = fs::read(path).map_err(|e| Error::io(path, e))?;
    let df = ParquetReader::new(Cursor::new(bytes))
        .read_parallel(ParallelStrategy::None)
        .finish()
        .map_err(|e| Error::input(Location::file(path), e.to_string()))?;
    Ok(Table { df })
}
