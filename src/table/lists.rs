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

    /// A column of string lists, each row's strings folded by `f` from
    /// `init`, read in place (no copy: a summary table's status codes are
    /// read on every run that joins it, a list per input). A null list, or
    /// one of other values, is `init`, as [`Table::str_list`] gives it
    /// empty.
    pub fn str_list_fold<T: Clone>(
        &self,
        name: &str,
        init: T,
        mut f: impl FnMut(&mut T, &str) -> Result<()>,
    ) -> Result<Vec<T>> {
        let c = self.column(name)?;
        c.list()
            .map_err(table_err)?
            .amortized_iter()
            .map(|l| {
                let mut acc = init.clone();
                if let Some(s) = l.as_ref().and_then(|s| s.as_ref().str().ok()) {
                    for v in s.iter().flatten() {
                        f(&mut acc, v)?;
                    }
                }
                Ok(acc)
            })
            .collect()
    }
}
