//! What the report looks up per file, gathered in one pass over each
//! table: the figures and rows of every source, and each table's shown
//! columns formatted once. (Looking up per file instead copied every
//! figure and column once per file: quadratic in the number of files.)

use std::collections::BTreeMap;

use super::figures::texts;
use super::numbers::{format_column, pretty_unit, NONE};
use super::summary::{row_statuses, RowStatus};
use crate::error::Result;
use crate::schema::Schema;
use crate::table::{ColumnType, Table};

/// A table's columns as shown: headings, cells, which are numbers, and
/// each row's status.
pub(super) struct Shown {
    pub heads: Vec<String>,
    /// `cells[c][row]`.
    pub cells: Vec<Vec<String>>,
    pub numeric: Vec<bool>,
    /// Each row's status.
    pub status: Vec<RowStatus>,
}

impl Shown {
    /// The columns `cols` (name, heading) of `t` that it has; numbers in
    /// the unit `schema` gives each column, with a prefix for the column.
    pub fn of(t: &Table, schema: &Schema, cols: &[(&str, &str)]) -> Result<Shown> {
        let names = t.column_names();
        let mut s = Shown {
            heads: Vec::new(),
            cells: Vec::new(),
            numeric: Vec::new(),
            status: row_statuses(t)?,
        };
        for (col, head) in cols.iter().filter(|(c, _)| names.iter().any(|n| n == c)) {
            // The status is shown with its details.
            let unit = schema
                .column
                .iter()
                .find(|c| c.name == *col)
                .map_or("", |c| c.unit.as_str());
            let (cells, numeric, unit) = match *col {
                "status" => (
                    s.status.iter().map(|r| r.text.clone()).collect(),
                    false,
                    String::new(),
                ),
                _ => formatted(t, col, unit)?,
            };
            s.heads.push(heading(head, &unit));
            s.cells.push(cells);
            s.numeric.push(numeric);
        }
        Ok(s)
    }
}

/// A column's heading: its name for people (a `[unit]` written in it left
/// out) and the unit its cells are in.
fn heading(head: &str, unit: &str) -> String {
    let name = match head.rfind(" [") {
        Some(i) if head.ends_with(']') => &head[..i],
        _ => head,
    };
    match unit {
        "" => name.to_string(),
        u => format!("{name} [{u}]"),
    }
}

/// A column as shown (cells, whether numbers, their unit): floats in a
/// unit and with digits chosen for the column ([`format_column`]), null
/// as a dash.
fn formatted(t: &Table, col: &str, unit: &str) -> Result<(Vec<String>, bool, String)> {
    let dash = || NONE.to_string();
    Ok(match t.column_type(col) {
        Some(ColumnType::F64) => {
            let n = format_column(&t.f64(col)?, unit);
            (n.cells, true, n.unit)
        }
        Some(ColumnType::I64) => (
            t.i64(col)?
                .iter()
                .map(|v| v.map_or_else(dash, |v| v.to_string()))
                .collect(),
            true,
            pretty_unit(unit),
        ),
        Some(ColumnType::Bool) => (
            t.bool(col)?
                .iter()
                .map(|v| v.map_or_else(dash, |v| v.to_string()))
                .collect(),
            false,
            String::new(),
        ),
        _ => (
            t.str(col)?
                .into_iter()
                .map(|v| v.unwrap_or_else(dash))
                .collect(),
            false,
            String::new(),
        ),
    })
}

/// A figure table's figures by source, in row order: (title, SVG),
/// the SVG borrowed (the SVG of every figure of a large archive is most of
/// the report's memory if copied).
pub(super) type BySource<'a> = BTreeMap<String, Vec<(String, &'a str)>>;

/// Each of the figure `tables` by source ([`BySource`]).
pub(super) fn by_source<'a, 'n>(
    tables: impl Iterator<Item = (&'n str, &'a Table)>,
) -> Result<BTreeMap<&'n str, BySource<'a>>> {
    let mut out = BTreeMap::new();
    for (name, t) in tables {
        let mut by: BySource = BTreeMap::new();
        let (src, title) = (texts(t, "source"), texts(t, "title"));
        let svg = t.str_refs("svg")?;
        for ((s, ti), sv) in src.into_iter().zip(title).zip(svg) {
            by.entry(s).or_default().push((ti, sv.unwrap_or_default()));
        }
        out.insert(name, by);
    }
    Ok(out)
}

/// A table's rows by source, in row order.
pub(super) fn rows_by_source(t: &Table) -> BTreeMap<String, Vec<usize>> {
    let mut out: BTreeMap<String, Vec<usize>> = BTreeMap::new();
    for (i, s) in texts(t, "source").into_iter().enumerate() {
        out.entry(s).or_default().push(i);
    }
    out
}
