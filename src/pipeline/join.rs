//! Joining a per-file stage's parts into its tables, in input order (a
//! table no file contributed to is empty, with its schema's columns;
//! dataset tables are not joined: the set publishes their files).
//!
//! A rerun takes the rows of the parts the last published table was joined
//! from out of that table (one read, sliced where consecutive parts stay
//! consecutive) instead of reading each part's cache entry: adding one
//! file to thousands reads each published table once and takes the new
//! file's rows from the pack the run made. A first run gathers each table
//! from that pack's, whose rows are in the order the parts were made.
//! Only a table the stage's assembly passed on as joined can be sliced
//! so; the state records, for those, each part's rows ([`Composition`]).

use std::collections::HashMap;
use std::sync::Arc;

use rayon::prelude::*;

use super::cache::RowsAt;
use super::file_result::{Part, Rows};
use super::keys::Key;
use super::state::Composition;
use super::store::Store;
use crate::error::Result;
use crate::schema::TableDef;
use crate::stages::{Output, Tables};
use crate::table::{push_range, Table};

/// The last published table, with where each of the last run's parts'
/// rows are in it (by the part's place in [`Composition::parts`]).
struct Published {
    table: Arc<Table>,
    /// Per part, its first row and its number of rows.
    at: Vec<(usize, usize)>,
}

impl Published {
    fn rows(&self, slot: usize) -> RowsAt {
        let (at, n) = self.at[slot];
        RowsAt {
            table: self.table.clone(),
            at,
            n,
        }
    }
}

/// Joins the parts (those the stage did not fail on) per table of `defs`;
/// `published` gives the last published table of a def when it is still
/// the file the last run wrote, `last` what that run joined it from.
/// Returns the tables and what they were joined from.
///
/// Each part's rows are rows of a larger table: the published one, the
/// cache pack's (this run's, for the parts it made) or, where the cache
/// could not keep them, the part's own. Only where they are is held per
/// part; each table is then gathered once per run of parts from one table.
pub(super) fn join(
    defs: &[&'static TableDef],
    parts: Vec<Part>,
    store: &Store,
    published: impl Fn(&TableDef) -> Option<Table> + Sync,
    last: Option<&Composition>,
) -> Result<(Tables, Composition)> {
    let parts: Vec<Part> = parts
        .into_iter()
        .filter(|p| !matches!(p.rows, Rows::Failed(_)))
        .collect();
    let plain: Vec<&'static TableDef> = defs.iter().copied().filter(|d| !d.is_dataset()).collect();
    // Read in parallel: a stage has several summary tables.
    let olds: Vec<Option<Published>> = plain
        .par_iter()
        .map(|d| previous(d, last?, &published))
        .collect();
    // Each part's place among the last run's parts, looked up once; a
    // part is taken from the published tables when every one has it.
    let places: HashMap<&Key, usize> = match (olds.iter().all(Option::is_some), last) {
        (true, Some(l)) if !plain.is_empty() => {
            l.parts.iter().enumerate().map(|(i, k)| (k, i)).collect()
        }
        _ => HashMap::new(),
    };
    let mut sources: Vec<Vec<Option<RowsAt>>> = vec![Vec::with_capacity(parts.len()); plain.len()];
    let mut keys: Vec<Key> = Vec::with_capacity(parts.len());
    for p in parts {
        let found: Vec<Option<RowsAt>> = match (places.get(&p.key), p.rows) {
            (Some(&slot), _) => olds.iter().flatten().map(|o| Some(o.rows(slot))).collect(),
            (None, Rows::Made(Some(own))) => of_part(&plain, own),
            (None, _) if plain.is_empty() => Vec::new(),
            (None, _) => {
                let at = store.part_rows(&p.key, defs)?;
                plain
                    .iter()
                    .map(|d| at.iter().find(|(a, _)| a == d).map(|(_, r)| r.clone()))
                    .collect()
            }
        };
        for (column, rows) in sources.iter_mut().zip(found) {
            column.push(rows);
        }
        keys.push(p.key);
    }
    drop(places);
    let mut composition = Composition::default();
    let mut tables = Vec::with_capacity(plain.len());
    for (def, rows) in plain.into_iter().zip(&sources) {
        let (t, counts) = join_one(def, rows)?;
        composition.rows.insert(def.name.into(), counts);
        tables.push((def, t));
    }
    composition.parts = keys;
    Ok((tables, composition))
}

/// A part's own tables as rows of each of `plain` (none where it has no
/// table).
fn of_part(plain: &[&'static TableDef], own: Tables) -> Vec<Option<RowsAt>> {
    let mut own: Vec<_> = own.into_iter().map(Some).collect();
    plain
        .iter()
        .map(|d| {
            let (_, t) = own
                .iter_mut()
                .find(|o| o.as_ref().is_some_and(|(o, _)| o == d))?
                .take()?;
            let n = t.height();
            Some(RowsAt {
                table: Arc::new(t),
                at: 0,
                n,
            })
        })
        .collect()
}

/// The last published table `def` with each part's place in it, when the
/// state says what it was joined from and the file is that table.
fn previous(
    def: &TableDef,
    last: &Composition,
    published: &(impl Fn(&TableDef) -> Option<Table> + Sync),
) -> Option<Published> {
    let rows = last.rows.get(def.name)?;
    if rows.len() != last.parts.len() {
        return None;
    }
    let table = published(def)?;
    let mut at = Vec::with_capacity(rows.len());
    let mut offset = 0;
    for &n in rows {
        at.push((offset, n as usize));
        offset += n as usize;
    }
    let table = Arc::new(table);
    (offset == table.height()).then_some(Published { table, at })
}

/// Consecutive parts' rows in one table: the table and their ranges.
type Run<'a> = (&'a Arc<Table>, Vec<(usize, usize)>);

/// One table from each part's rows, in the parts' order: one piece per run
/// of consecutive parts whose rows are in the same table; with each part's
/// number of rows.
fn join_one(def: &'static TableDef, rows: &[Option<RowsAt>]) -> Result<(Table, Vec<u64>)> {
    let counts = rows
        .iter()
        .map(|r| r.as_ref().map_or(0, |r| r.n as u64))
        .collect();
    let mut pieces: Vec<Table> = Vec::new();
    let mut run: Option<Run> = None;
    for r in rows.iter().flatten().filter(|r| r.n > 0) {
        match &mut run {
            Some((t, ranges)) if Arc::ptr_eq(t, &r.table) => push_range(ranges, (r.at, r.n)),
            _ => {
                if let Some((t, ranges)) = run.take() {
                    pieces.push(t.rows_of(&ranges)?);
                }
                run = Some((&r.table, vec![(r.at, r.n)]));
            }
        }
    }
    if let Some((t, ranges)) = run {
        pieces.push(t.rows_of(&ranges)?);
    }
    let t = match Table::concat(pieces)? {
        Some(t) => t,
        None => def.empty_table()?,
    };
    Ok((t, counts))
}

/// Keeps in `composition` only the tables `out` passes on as they were
/// joined (`joined`): the others' published rows are the assembly's, not
/// the parts'.
pub(super) fn as_joined(composition: &mut Composition, out: &Output, joined: &Tables) {
    composition.rows.retain(|name, _| {
        out.tables
            .iter()
            .any(|(d, t)| d.name == name && joined.iter().any(|(j, k)| j == d && k.is_same(t)))
    });
}
