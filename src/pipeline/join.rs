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
    fn rows(&self, slot: usize) -> Slice<'_> {
        let (at, n) = self.at[slot];
        (&self.table, at, n)
    }
}

/// Rows of a table: the table, the first row, the number of rows.
type Slice<'a> = (&'a Arc<Table>, usize, usize);

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
    let mut found: Vec<Found> = Vec::with_capacity(parts.len());
    let mut keys: Vec<Key> = Vec::with_capacity(parts.len());
    for p in parts {
        found.push(match (places.get(&p.key), p.rows) {
            (Some(&slot), _) => Found::Published(slot),
            (None, Rows::Made(Some(own))) => Found::Each(of_part(&plain, own)),
            (None, _) if plain.is_empty() => Found::Each(Vec::new()),
            (None, _) => {
                let at = store.part_rows(&p.key, defs)?;
                let each = plain
                    .iter()
                    .map(|d| at.iter().find(|(a, _)| a == d).map(|(_, r)| r.clone()))
                    .collect();
                Found::Each(each)
            }
        });
        keys.push(p.key);
    }
    drop(places);
    let mut composition = Composition::default();
    let mut tables = Vec::with_capacity(plain.len());
    for (t, def) in plain.into_iter().enumerate() {
        let old = olds[t].as_ref();
        let rows = found.iter().map(|f| match f {
            Found::Published(slot) => old.map(|o| o.rows(*slot)),
            Found::Each(each) => each[t].as_ref().map(|r| (&r.table, r.at, r.n)),
        });
        let (t, counts) = join_one(def, rows)?;
        composition.rows.insert(def.name.into(), counts);
        tables.push((def, t));
    }
    composition.parts = keys;
    Ok((tables, composition))
}

/// Where a part's rows are: in the last published tables, at its place
/// among the last run's parts (most parts of a rerun: held as that place
/// alone, not as rows per table, which cost a list per part); or, per
/// table, in its own table, the run's pack or a cache entry.
enum Found {
    Published(usize),
    Each(Vec<Option<RowsAt>>),
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
fn join_one<'a>(
    def: &'static TableDef,
    rows: impl Iterator<Item = Option<Slice<'a>>>,
) -> Result<(Table, Vec<u64>)> {
    let mut counts = Vec::with_capacity(rows.size_hint().0);
    let mut pieces: Vec<Table> = Vec::new();
    let mut run: Option<Run> = None;
    for r in rows {
        counts.push(r.map_or(0, |(_, _, n)| n as u64));
        let Some((table, at, n)) = r.filter(|&(_, _, n)| n > 0) else {
            continue;
        };
        match &mut run {
            Some((t, ranges)) if Arc::ptr_eq(t, table) => push_range(ranges, (at, n)),
            _ => {
                if let Some((t, ranges)) = run.take() {
                    pieces.push(t.rows_of(&ranges)?);
                }
                run = Some((table, vec![(at, n)]));
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
