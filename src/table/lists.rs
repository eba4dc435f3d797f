//! Columns of string lists (a row's status codes): Parquet's LIST of
//! strings, which pandas reads as arrays, polars as `List(String)` and
//! DuckDB as `VARCHAR[]`.

use polars::prelude::{IntoSeries, ListBuilderTrait, ListStringChunkedBuilder};

use super::{table_err, Table, TableBuilder};
use crate::error::Result;

impl TableBuilder {
    /// A column of string lists, one list per row.
    pub fn str_list<S: AsRef<str>, L: IntoIterator<Item = S>>(
        self,
        name: &str,
        rows: impl IntoIterator<Item = L>,
    ) -> Self {
        let rows: Vec<Vec<S>> = rows.into_iter().map(|l| l.into_iter().collect()).collect();
        let values = rows.iter().map(Vec::len).sum();
        let mut b = ListStringChunkedBuilder::new(name.into(), rows.len(), values);
        for l in &rows {
            b.append_values_iter(l.iter().map(|s| s.as_ref()));
        }
        self.push(b.finish().into_series().into())
    }
}

impl Table {
    /// A column of string lists as vectors.
    pub fn str_list(&self, name: &str) -> Result<Vec<Option<Vec<String>>>> {
        let c = self.column(name)?;
        Ok(c.list()
            .map_err(table_err)?
            .amortized_iter()
            .map(|l| {
                l.and_then(|s| {
                    s.as_ref()
                        .str()
                        .ok()
                        .map(|s| s.iter().flatten().map(str::to_string).collect())
                })
            })
            .collect())
    }

    /// A column of string lists, each string read in place by `f` (no
    /// copy: a summary table's status codes are read on every run that
    /// joins it, a list per input). A null list, or one of other values,
    /// is empty, as [`Table::str_list`] gives it.
    pub fn str_list_map<T>(
        &self,
        name: &str,
        mut f: impl FnMut(&str) -> Result<T>,
    ) -> Result<Vec<Vec<T>>> {
        let c = self.column(name)?;
        c.list()
            .map_err(table_err)?
            .amortized_iter()
            .map(|l| match l.as_ref().and_then(|s| s.as_ref().str().ok()) {
                Some(s) => s.iter().flatten().map(&mut f).collect(),
                None => Ok(Vec::new()),
            })
            .collect()
    }
}
