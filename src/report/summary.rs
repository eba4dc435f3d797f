//! What the first page and the end of a run list: each row whose status
//! is not `ok`, and each file that failed.

use std::collections::BTreeMap;

use crate::error::Result;
use crate::table::Table;

/// A row of a result table whose status carries a warning.
#[derive(Debug, Clone, PartialEq, Eq, serde::Serialize)]
pub struct Doubt {
    /// The table.
    pub table: String,
    /// Its source (input file) or group; empty where the table has none.
    pub source: String,
    /// The status text (`code: detail; …`).
    pub status: String,
}

/// Whether a status cell says the row is sound: `ok` (every table), or
/// `converged` (the ice fit's solver). Null or empty cells are not
/// warnings: a missing value is reported by its own table.
pub fn is_sound(status: &str) -> bool {
    matches!(status, "ok" | "converged" | "")
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
        if !t.column_names().iter().any(|c| c == "status") {
            continue;
        }
        let status = t.str("status")?;
        let source = match source_column(t) {
            Some(c) => t.str(c)?,
            None => vec![None; t.height()],
        };
        // Which fit of a group: its regime or bound.
        let names = t.column_names();
        let which = match ["regime", "bound"]
            .iter()
            .find(|c| names.iter().any(|n| n == *c))
        {
            Some(c) => t.str(c)?,
            None => vec![None; t.height()],
        };
        for ((s, src), w) in status.into_iter().zip(source).zip(which) {
            let Some(s) = s.filter(|s| !is_sound(s)) else {
                continue;
            };
            let mut source = src.unwrap_or_default();
            if let Some(w) = w {
                source = format!("{source} ({w})");
            }
            out.push(Doubt {
                table: name.clone(),
                source,
                status: s,
            });
        }
    }
    Ok(out)
}
