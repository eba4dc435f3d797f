//! What the report looks up per file, gathered in one pass over each
//! table: the figures and rows of every source, and each table's shown
//! columns formatted once. (Looking up per file instead copied every
//! figure and column once per file: quadratic in the number of files.)

use std::collections::BTreeMap;

use super::figures::texts;
use crate::error::Result;
use crate::table::{ColumnType, Table};

/// A table's columns as shown: headings, cells, which are numbers, and
/// each row's status.
pub(super) struct Shown {
    pub heads: Vec<String>,
    /// `cells[c][row]`.
    pub cells: Vec<Vec<String>>,
    pub numeric: Vec<bool>,
    /// Each row's status (empty where the table has none).
    pub status: Vec<String>,
}

impl Shown {
    /// The columns `cols` (name, heading) of `t` that it has.
    pub fn of(t: &Table, cols: &[(&str, &str)]) -> Result<Shown> {
        let names = t.column_names();
        let mut s = Shown {
            heads: Vec::new(),
            cells: Vec::new(),
            numeric: Vec::new(),
            status: match names.iter().any(|n| n == "status") {
                true => texts(t, "status"),
                false => vec![String::new(); t.height()],
            },
        };
        for (col, head) in cols.iter().filter(|(c, _)| names.iter().any(|n| n == c)) {
            let (cells, numeric) = formatted(t, col)?;
            s.heads.push(head.to_string());
            s.cells.push(cells);
            s.numeric.push(numeric);
        }
        Ok(s)
    }
}

/// A column as shown: numbers to 4 decimals, null as a dash.
fn formatted(t: &Table, col: &str) -> Result<(Vec<String>, bool)> {
    let dash = || "–".to_string();
    Ok(match t.column_type(col) {
        Some(ColumnType::F64) => (
            t.f64(col)?
                .iter()
                .map(|v| v.map_or_else(dash, |v| format!("{v:.4}")))
                .collect(),
            true,
        ),
        Some(ColumnType::I64) => (
            t.i64(col)?
                .iter()
                .map(|v| v.map_or_else(dash, |v| v.to_string()))
                .collect(),
            true,
        ),
        Some(ColumnType::Bool) => (
            t.bool(col)?
                .iter()
                .map(|v| v.map_or_else(dash, |v| v.to_string()))
                .collect(),
            false,
        ),
        _ => (
            t.str(col)?
                .into_iter()
                .map(|v| v.unwrap_or_else(dash))
                .collect(),
            false,
        ),
    })
}

/// Figures by source, in table then row order: (title, SVG). `figures`:
/// the names of the figures tables.
pub(super) fn figures_by_source(
    tables: &BTreeMap<String, Table>,
    figures: impl Iterator<Item = &'static str>,
) -> BTreeMap<String, Vec<(String, String)>> {
    let mut out: BTreeMap<String, Vec<(String, String)>> = BTreeMap::new();
    for name in figures {
        let Some(t) = tables.get(name) else { continue };
        let (src, title, svg) = (texts(t, "source"), texts(t, "title"), texts(t, "svg"));
        for ((s, ti), sv) in src.into_iter().zip(title).zip(svg) {
            out.entry(s).or_default().push((ti, sv));
        }
    }
    out
}

/// A table's rows by source, in row order.
pub(super) fn rows_by_source(t: &Table) -> BTreeMap<String, Vec<usize>> {
    let mut out: BTreeMap<String, Vec<usize>> = BTreeMap::new();
    for (i, s) in texts(t, "source").into_iter().enumerate() {
        out.entry(s).or_default().push(i);
    }
    out
}
