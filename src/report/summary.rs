//! What the first page and the end of a run list: each row whose status
//! is not `ok`, and each file that failed.

use std::collections::BTreeMap;

use crate::error::Result;
use crate::table::Table;

/// A row of a result table whose status carries a warning.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Doubt {
    /// The table.
    pub table: String,
    /// Its source (input file) or group; empty where the table has none.
    pub source: String,
    /// The status text (`code: detail; …`).
    pub status: String,
}

/// The column naming what a row is about, by table.
pub(crate) fn source_column(t: &Table) -> Option<&'static str> {
    let names = t.column_names();
    ["source", "group", "pattern"]
        .into_iter()
        .find(|c| names.iter().any(|n| n == c))
}

/// Every row of every table with a `status` column that is not `ok`, in
/// table then row order. Rows without a status (null) are not doubts: a
/// missing value is reported by its own table.
pub fn doubts(tables: &BTreeMap<String, Table>) -> Result<Vec<Doubt>> {
    let mut out = Vec::new();
    for (name, t) in tables {
        if name == "errors" || !t.column_names().iter().any(|c| c == "status") {
            continue;
        }
        let status = t.str("status")?;
        let source = match source_column(t) {
            Some(c) => t.str(c)?,
            None => vec![None; t.height()],
        };
        for (s, src) in status.into_iter().zip(source) {
            match s {
                Some(s) if s != "ok" && !s.is_empty() => out.push(Doubt {
                    table: name.clone(),
                    source: src.unwrap_or_default(),
                    status: s,
                }),
                _ => {}
            }
        }
    }
    Ok(out)
}
