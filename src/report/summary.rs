//! What the first page and the end of a run list: each row whose status
//! holds a warning or an error (by its codes' severity), and each file
//! that failed.

use std::collections::BTreeMap;

use crate::error::Result;
use crate::status::{Code, Severity, OK};
use crate::table::Table;

/// A row of a result table whose status carries a warning.
#[derive(Debug, Clone, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub struct Doubt {
    /// The table.
    pub table: String,
    /// Its source (input file) or group; empty where the table has none.
    pub source: String,
    /// The status with its details (`code: detail; …`).
    pub status: String,
}

/// A row's status as the report shows it: how it weighs and its text.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct RowStatus {
    /// The severity of its most severe code; `None` when ok (or the table
    /// has no status).
    pub severity: Option<Severity>,
    /// `ok`, or every code with its detail; empty where the table has no
    /// status.
    pub text: String,
}

impl RowStatus {
    /// Whether the row is sound: ok, or only codes said for the record.
    pub fn is_sound(&self) -> bool {
        sound(self.severity)
    }
    /// The CSS class of the row: `ok`, `warn` or `err`.
    pub fn class(&self) -> &'static str {
        match self.severity {
            None | Some(Severity::Info) => "ok",
            Some(Severity::Warning) => "warn",
            Some(Severity::Error) => "err",
        }
    }
}

/// Each row's status, from the table's status columns (every row sound
/// where it has none).
pub(crate) fn row_statuses(t: &Table) -> Result<Vec<RowStatus>> {
    match severities(t)? {
        Some(s) => with_text(t, s),
        None => {
            let none = RowStatus {
                severity: None,
                text: String::new(),
            };
            Ok(vec![none; t.height()])
        }
    }
}

/// The rows' statuses from their severities and `status_detail`.
fn with_text(t: &Table, severities: Vec<Option<Severity>>) -> Result<Vec<RowStatus>> {
    let detail = t.str("status_detail")?;
    Ok(severities
        .into_iter()
        .zip(detail)
        .map(|(severity, d)| RowStatus {
            severity,
            text: d.unwrap_or_else(|| OK.to_string()),
        })
        .collect())
}

/// Whether a severity is sound: none, or said for the record only.
fn sound(severity: Option<Severity>) -> bool {
    severity <= Some(Severity::Info)
}

/// Each row's severity: that of its most severe code (`None` when it has
/// none); `None` for a table without status columns.
fn severities(t: &Table) -> Result<Option<Vec<Option<Severity>>>> {
    if !t.column_names().iter().any(|c| c == "status_codes") {
        return Ok(None);
    }
    let most = |s: &mut Option<Severity>, c: Code| *s = (*s).max(Some(c.severity()));
    t.fold_status_codes(None, most).map(Some)
}

/// The column naming what a row is about, by table.
pub(crate) fn source_column(t: &Table) -> Option<&'static str> {
    let names = t.column_names();
    ["source", "group", "pattern"]
        .into_iter()
        .find(|c| names.iter().any(|n| n == c))
}

/// Every row of every table with status columns whose status holds a
/// warning or an error, in table then row order.
pub fn doubts(tables: &BTreeMap<String, Table>) -> Result<Vec<Doubt>> {
    let mut out = Vec::new();
    for (name, t) in tables {
        // The texts are read only for a table with doubts: most have none.
        let status = match severities(t)? {
            Some(s) if !s.iter().all(|&s| sound(s)) => with_text(t, s)?,
            _ => continue,
        };
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
            if s.is_sound() {
                continue;
            }
            let mut source = src.unwrap_or_default();
            if let Some(w) = w {
                source = format!("{source} ({w})");
            }
            out.push(Doubt {
                table: name.clone(),
                source,
                status: s.text,
            });
        }
    }
    Ok(out)
}
