//! Tables: the one module that talks to polars.
//!
//! polars is pinned to an exact version in `Cargo.toml` and its API is used
//! only here, so that an upgrade touches this file alone. The rest of tribo
//! builds tables column by column with [`TableBuilder`], reads columns back as
//! plain vectors, and writes or reads Parquet with key-value metadata.
//!
//! Non-finite floats never reach a table: [`TableBuilder::f64`] stores NaN and
//! ±inf as null, so a reader never sees a NaN dressed as a value. The row's
//! `status` column says why a value is missing.

use std::fs::File;
use std::path::Path;

use polars::prelude::{
    ArrowDataType, Column, DataFrame, DataType, Float64Chunked, IdxCa, IdxSize, Int64Chunked,
    IntoSeries, NamedFrom, ParquetReader, SerReader, Series, StringChunked,
};

use polars_arrow::array::{MutableBinaryViewArray, PrimitiveArray};
use polars_arrow::bitmap::{Bitmap, MutableBitmap};

use crate::error::{Error, Result};

mod dict;
mod input_rows;
mod lists;
mod parquet;
mod stacked;
mod status_columns;

pub use status_columns::STATUS_COLUMNS;

/// The logical type of a column, as recorded in `schemas/*.toml`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ColumnType {
    /// 64-bit float (Parquet DOUBLE).
    F64,
    /// 64-bit signed integer (Parquet INT64).
    I64,
    /// UTF-8 string.
    Str,
    /// Dictionary-encoded UTF-8 string (an Arrow dictionary, a polars
    /// `Enum`): each distinct value stored once, a small code per row.
    Cat,
    /// Boolean.
    Bool,
    /// A list of UTF-8 strings per row (a row's status codes): Parquet's
    /// LIST of strings, which pandas reads as arrays, polars as
    /// `List(String)`, DuckDB as `VARCHAR[]`.
    StrList,
}

impl ColumnType {
    /// Name used in schema files: `f64`, `i64`, `str`, `cat`, `bool`.
    pub fn name(self) -> &'static str {
        match self {
            ColumnType::F64 => "f64",
            ColumnType::I64 => "i64",
            ColumnType::Str => "str",
            ColumnType::Cat => "cat",
            ColumnType::Bool => "bool",
            ColumnType::StrList => "list<str>",
        }
    }
    /// Parses a schema-file type name.
    pub fn parse(name: &str) -> Option<Self> {
        match name {
            "f64" => Some(ColumnType::F64),
            "i64" => Some(ColumnType::I64),
            "str" => Some(ColumnType::Str),
            "cat" => Some(ColumnType::Cat),
            "bool" => Some(ColumnType::Bool),
            "list<str>" => Some(ColumnType::StrList),
            _ => None,
        }
    }
}

/// Builds a [`Table`] one named column at a time. All columns must have the
/// same length; [`TableBuilder::build`] checks it.
#[derive(Default)]
pub struct TableBuilder {
    columns: Vec<Column>,
    error: Option<String>,
}

impl TableBuilder {
    /// An empty builder.
    pub fn new() -> Self {
        Self::default()
    }

    fn push(mut self, column: Column) -> Self {
        if self.columns.iter().any(|c| c.name() == column.name()) && self.error.is_none() {
            self.error = Some(format!("duplicate column '{}'", column.name()));
        }
        self.columns.push(column);
        self
    }

    /// A nullable float column. NaN and ±inf are stored as null.
    pub fn f64(self, name: &str, values: impl IntoIterator<Item = Option<f64>>) -> Self {
        let v: Vec<Option<f64>> = values
            .into_iter()
            .map(|x| x.filter(|x| x.is_finite()))
            .collect();
        self.push(Series::new(name.into(), v).into())
    }

    /// A float column without nulls in intent; non-finite values still become null.
    pub fn f64_values(self, name: &str, values: impl IntoIterator<Item = f64>) -> Self {
        self.f64(name, values.into_iter().map(Some))
    }

    /// A nullable integer column.
    pub fn i64(self, name: &str, values: impl IntoIterator<Item = Option<i64>>) -> Self {
        let v: Vec<Option<i64>> = values.into_iter().collect();
        self.push(Series::new(name.into(), v).into())
    }

    /// A nullable string column.
    pub fn str<S: AsRef<str>>(
        self,
        name: &str,
        values: impl IntoIterator<Item = Option<S>>,
    ) -> Self {
        // Straight into the column's buffers: an owned copy of each value
        // first was a string per row of fresh memory (the `files` table
        // of a run over 20 000 inputs has five such columns).
        let values = values.into_iter();
        let mut column = MutableBinaryViewArray::<str>::with_capacity(values.size_hint().0);
        for v in values {
            column.push(v.as_ref().map(|s| s.as_ref()));
        }
        let column = StringChunked::with_chunk(name.into(), column.into());
        self.push(column.into_series().into())
    }

    /// A string column given as runs of one value (a file's path, a
    /// section's name repeated over its samples). Each run's value is
    /// stored once and every row is a view into it: no string per row,
    /// whatever the row count.
    pub fn str_runs<S: AsRef<str>>(
        self,
        name: &str,
        runs: impl IntoIterator<Item = (Option<S>, usize)>,
    ) -> Self {
        let mut values = MutableBinaryViewArray::<str>::new();
        for (value, n) in runs {
            match value {
                Some(v) => values.extend_constant(n, Some(v.as_ref())),
                // polars 0.55's `extend_constant` adds no rows for a null.
                None => values.extend_null(n),
            }
        }
        let column = StringChunked::with_chunk(name.into(), values.into());
        self.push(column.into_series().into())
    }

    /// A dictionary-encoded string column given as runs of one value: the
    /// distinct values become the categories in first-seen order (the same
    /// bytes at any thread count) and every row a code, with no string work
    /// per row. Parquet writes it as a dictionary column as it stands,
    /// where a string column has every row hashed to find its dictionary.
    pub fn cat_runs<S: AsRef<str>>(
        self,
        name: &str,
        runs: impl IntoIterator<Item = (Option<S>, usize)>,
    ) -> Self {
        let mut codes = dict::CodeRuns::default();
        for (value, n) in runs {
            codes.push(value.as_ref().map(|s| s.as_ref()), n);
        }
        match codes.into_column(name) {
            Ok(column) => self.push(column),
            Err(e) => self.fail(e),
        }
    }

    fn fail(mut self, e: Error) -> Self {
        self.error.get_or_insert(e.to_string());
        self
    }

    /// An integer column given as runs of one value (null or not).
    pub fn i64_runs(
        self,
        name: &str,
        runs: impl IntoIterator<Item = (Option<i64>, usize)>,
    ) -> Self {
        let runs: Vec<(Option<i64>, usize)> = runs.into_iter().collect();
        let total = runs.iter().map(|(_, n)| n).sum();
        let (mut values, mut valid) = (
            Vec::with_capacity(total),
            MutableBitmap::with_capacity(total),
        );
        for (value, n) in runs {
            values.extend(std::iter::repeat_n(value.unwrap_or(0), n));
            valid.extend_constant(n, value.is_some());
        }
        let valid: Bitmap = valid.into();
        let valid = (valid.unset_bits() > 0).then_some(valid);
        let array = PrimitiveArray::new(ArrowDataType::Int64, values.into(), valid);
        let column = Int64Chunked::with_chunk(name.into(), array);
        self.push(column.into_series().into())
    }

    /// A float column from values already in memory, taken whole; NaN and
    /// ±inf become null through a validity mask, not a copy per value.
    pub fn f64_vec(self, name: &str, values: Vec<f64>) -> Self {
        // Most columns are all finite: a branch-free test first, and the
        // bitmap only when some value is missing.
        let all = values
            .chunks(1 << 12)
            .all(|c| c.iter().fold(true, |all, x| all & x.is_finite()));
        let valid = (!all).then(|| values.iter().map(|x| x.is_finite()).collect::<Bitmap>());
        let array = PrimitiveArray::new(ArrowDataType::Float64, values.into(), valid);
        let column = Float64Chunked::with_chunk(name.into(), array);
        self.push(column.into_series().into())
    }

    /// A float column of `n` nulls.
    pub fn f64_null(self, name: &str, n: usize) -> Self {
        let array = PrimitiveArray::<f64>::new_null(ArrowDataType::Float64, n);
        let column = Float64Chunked::with_chunk(name.into(), array);
        self.push(column.into_series().into())
    }

    /// A nullable boolean column.
    pub fn bool(self, name: &str, values: impl IntoIterator<Item = Option<bool>>) -> Self {
        let v: Vec<Option<bool>> = values.into_iter().collect();
        self.push(Series::new(name.into(), v).into())
    }

    /// Checks the columns and makes the table.
    pub fn build(self) -> Result<Table> {
        if let Some(e) = self.error {
            return Err(Error::Table(e));
        }
        let height = self.columns.first().map_or(0, |c| c.len());
        if let Some(c) = self.columns.iter().find(|c| c.len() != height) {
            return Err(Error::Table(format!(
                "column '{}' has {} rows, expected {height}",
                c.name(),
                c.len()
            )));
        }
        let df = DataFrame::new(height, self.columns).map_err(table_err)?;
        Ok(Table { df })
    }
}

/// A Parquet compression codec.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Codec {
    /// No compression.
    Uncompressed,
    /// Snappy.
    Snappy,
    /// LZ4 (raw block format).
    Lz4,
    /// Zstandard at its default level.
    Zstd,
}

/// The codec every table is written with, chosen by measurement
/// (docs/speed.md, "Parquet codec"): on a 1e7-row traces table Snappy wrote
/// in 0.56 s against 0.55 s for LZ4, 0.76 s for zstd (default level) and
/// 1.14 s uncompressed, at 157 MB against 157, 71 and 240 MB. The traces
/// table is the largest write, and its float columns barely compress, so
/// write time wins over size; Snappy over LZ4 for its wider reader support.
pub const CODEC: Codec = Codec::Snappy;

/// Rows per Parquet row group: every row group's columns are encoded and
/// compressed in parallel, and a 1e7-row trace gives about 40 groups, enough
/// to keep every core busy without the footer growing large.
pub const ROW_GROUP_ROWS: usize = 1 << 18;

/// A table of named, typed columns (Arrow memory, via polars).
#[derive(Clone, Debug)]
pub struct Table {
    df: DataFrame,
}

fn table_err(e: impl std::fmt::Display) -> Error {
    Error::Table(e.to_string())
}

impl Table {
    /// Number of rows.
    pub fn height(&self) -> usize {
        self.df.height()
    }

    /// Rows `offset..offset + len` (no copy).
    pub fn slice(&self, offset: usize, len: usize) -> Table {
        Table {
            df: self.df.slice(offset as i64, len),
        }
    }

    /// The rows of `ranges` (offset, len, as [`push_range`] adds them), in
    /// order: one slice when they
    /// follow each other, else one gather.
    pub fn rows_of(&self, ranges: &[(usize, usize)]) -> Result<Table> {
        let mut merged: Vec<(usize, usize)> = Vec::with_capacity(ranges.len());
        for &range in ranges {
            push_range(&mut merged, range);
        }
        if let [(at, n)] = merged[..] {
            return Ok(self.slice(at, n));
        }
        let mut rows: Vec<IdxSize> = Vec::with_capacity(merged.iter().map(|r| r.1).sum());
        for (at, n) in merged {
            let end = at.checked_add(n).filter(|&e| e <= self.height());
            let (Some(_), Some(first), Some(last)) = (
                end,
                IdxSize::try_from(at).ok(),
                end.and_then(|e| IdxSize::try_from(e).ok()),
            ) else {
                return Err(Error::Table(format!(
                    "rows {at}..{} of a table of {}",
                    at.saturating_add(n),
                    self.height()
                )));
            };
            rows.extend(first..last);
        }
        let idx = IdxCa::from_vec("rows".into(), rows);
        Ok(Table {
            df: self.df.take(&idx).map_err(table_err)?,
        })
    }

    /// Column names in order.
    pub fn column_names(&self) -> Vec<String> {
        self.df
            .get_column_names()
            .iter()
            .map(|s| s.to_string())
            .collect()
    }

    /// The logical type of a column, if it exists and is one tribo writes.
    pub fn column_type(&self, name: &str) -> Option<ColumnType> {
        let c = self.df.column(name).ok()?;
        match c.dtype() {
            DataType::Float64 => Some(ColumnType::F64),
            DataType::Int64 => Some(ColumnType::I64),
            DataType::String => Some(ColumnType::Str),
            d if dict::is_dictionary(d) => Some(ColumnType::Cat),
            DataType::Boolean => Some(ColumnType::Bool),
            DataType::List(inner) if **inner == DataType::String => Some(ColumnType::StrList),
            _ => None,
        }
    }

    fn column(&self, name: &str) -> Result<&Column> {
        self.df
            .column(name)
            .map_err(|_| Error::Table(format!("no column '{name}'")))
    }

    /// A float column as a vector (integers are widened).
    pub fn f64(&self, name: &str) -> Result<Vec<Option<f64>>> {
        let c = self
            .column(name)?
            .cast(&DataType::Float64)
            .map_err(table_err)?;
        Ok(c.f64().map_err(table_err)?.iter().collect())
    }

    /// An integer column as a vector.
    pub fn i64(&self, name: &str) -> Result<Vec<Option<i64>>> {
        let c = self.column(name)?;
        Ok(c.i64().map_err(table_err)?.iter().collect())
    }

    /// A string column as a vector (a dictionary column's values too).
    pub fn str(&self, name: &str) -> Result<Vec<Option<String>>> {
        let mut c = self.column(name)?.clone();
        if dict::is_dictionary(c.dtype()) {
            c = c.cast(&DataType::String).map_err(table_err)?;
        }
        Ok(c.str()
            .map_err(table_err)?
            .iter()
            .map(|s| s.map(str::to_string))
            .collect())
    }

    /// A plain string column's values, borrowed from the table (a large
    /// text column, such as the figures' SVG, is not copied); an error for
    /// a dictionary column, whose values are not held as strings.
    pub fn str_refs(&self, name: &str) -> Result<Vec<Option<&str>>> {
        Ok(self
            .column(name)?
            .str()
            .map_err(table_err)?
            .iter()
            .collect())
    }

    /// A dictionary column's categories in their order (the Parquet and
    /// Arrow dictionary every reader sees); `None` for another column.
    pub fn categories(&self, name: &str) -> Option<Vec<String>> {
        match self.df.column(name).ok()?.dtype() {
            DataType::Enum(frozen, _) => Some(
                frozen
                    .categories()
                    .values_iter()
                    .map(str::to_string)
                    .collect(),
            ),
            _ => None,
        }
    }

    /// A boolean column as a vector.
    pub fn bool(&self, name: &str) -> Result<Vec<Option<bool>>> {
        let c = self.column(name)?;
        Ok(c.bool().map_err(table_err)?.iter().collect())
    }

    /// Stacks tables with identical columns, in order. An empty list gives
    /// `None`. Each part's dictionary columns have categories of their own:
    /// they are joined by remapping each part's codes into the categories
    /// in first-seen order, not by going through the strings row by row.
    /// So the result's categories depend on its rows only, even for one
    /// table sliced from a larger one whose rows were made in thread order.
    pub fn concat(tables: impl IntoIterator<Item = Table>) -> Result<Option<Table>> {
        let tables: Vec<Table> = tables.into_iter().collect();
        let Some(first) = tables.first() else {
            return Ok(None);
        };
        let dictionaries: Vec<(usize, String)> = first
            .df
            .columns()
            .iter()
            .enumerate()
            .filter(|(_, c)| dict::is_dictionary(c.dtype()))
            .map(|(i, c)| (i, c.name().to_string()))
            .collect();
        let mut joined = Vec::with_capacity(dictionaries.len());
        for (i, name) in &dictionaries {
            let mut codes = dict::CodeRuns::default();
            for t in &tables {
                codes.extend(t.column(name)?)?;
            }
            joined.push((*i, codes.into_column(name)?));
        }
        let names: Vec<&String> = dictionaries.iter().map(|(_, n)| n).collect();
        let mut parts = tables
            .iter()
            .map(|t| t.df.drop_many(names.iter().map(|n| n.as_str())));
        let mut df = parts.next().expect("one table at least");
        for part in parts {
            df.vstack_mut(&part).map_err(table_err)?;
        }
        df.rechunk_mut();
        for (i, column) in joined {
            df.insert_column(i, column).map_err(table_err)?;
        }
        Ok(Some(Table { df }))
    }

    /// Reads a Parquet file and its key-value metadata.
    pub fn read_parquet(path: &Path) -> Result<(Table, Vec<(String, String)>)> {
        let file = File::open(path).map_err(|e| Error::io(path, e))?;
        Table::parquet_from(file, path)
    }

    /// Reads a Parquet file already in memory (`path` names it in errors).
    pub fn read_parquet_bytes(
        bytes: Vec<u8>,
        path: &Path,
    ) -> Result<(Table, Vec<(String, String)>)> {
        Table::parquet_from(std::io::Cursor::new(bytes), path)
    }

    fn parquet_from(
        source: impl polars::io::mmap::MmapBytesReader,
        path: &Path,
    ) -> Result<(Table, Vec<(String, String)>)> {
        let mut reader = ParquetReader::new(source);
        let kv = reader
            .get_metadata()
            .map_err(|e| Error::input(crate::error::Location::file(path), e.to_string()))?
            .key_value_metadata()
            .clone()
            .unwrap_or_default()
            .into_iter()
            .map(|kv| (kv.key, kv.value.unwrap_or_default()))
            .collect();
        let df = reader
            .finish()
            .map_err(|e| Error::input(crate::error::Location::file(path), e.to_string()))?;
        Ok((Table { df }, kv))
    }
}

impl Table {
    /// Replaces the columns built in `update` (by name, in place; new names
    /// are appended). `update` must have this table's height.
    pub fn update(mut self, update: TableBuilder) -> Result<Table> {
        let u = update.build()?;
        if u.height() != self.height() && !u.df.columns().is_empty() {
            return Err(Error::Table(format!(
                "update has {} rows, the table {}",
                u.height(),
                self.height()
            )));
        }
        for c in u.df.columns() {
            self.df.with_column(c.clone()).map_err(table_err)?;
        }
        Ok(self)
    }

    /// Whether `other` is this very table, not an equal one: the same
    /// columns holding the same memory, as a table passed on unchanged does
    /// (so that the cache can link to its published file).
    pub fn is_same(&self, other: &Table) -> bool {
        let (a, b) = (self.df.columns(), other.df.columns());
        a.len() == b.len()
            && self.height() == other.height()
            && a.iter()
                .zip(b)
                .all(|(a, b)| a.name() == b.name() && same_column(a, b))
    }

    /// Number of nulls in a column.
    pub fn null_count(&self, name: &str) -> Result<usize> {
        Ok(self.column(name)?.null_count())
    }
}

/// Whether two columns are one: the same memory, or (a constant column,
/// which polars makes of all-null and empty columns and which holds no
/// memory to compare) the same value, type and length.
fn same_column(a: &Column, b: &Column) -> bool {
    match (a, b) {
        (Column::Scalar(x), Column::Scalar(y)) => {
            x.len() == y.len() && x.dtype() == y.dtype() && x.scalar() == y.scalar()
        }
        _ => match (a.as_series(), b.as_series()) {
            (Some(a), Some(b)) => std::sync::Arc::ptr_eq(&a.0, &b.0),
            _ => false,
        },
    }
}

/// Adds the rows `(at, n)` to `ranges`, as one range with the last when
/// they follow it: a rerun's unchanged parts are one slice of the
/// published table, not a range per input.
pub fn push_range(ranges: &mut Vec<(usize, usize)>, (at, n): (usize, usize)) {
    match ranges.last_mut() {
        Some((s, l)) if *s + *l == at => *l += n,
        _ => ranges.push((at, n)),
    }
}

#[cfg(test)]
mod tests;
