//! Joining a per-file stage's parts into its tables, in input order (a
//! table no file contributed to is empty, with its schema's columns;
//! dataset tables are not joined: the set publishes their files).
//!
//! A rerun takes the rows of the parts the last published table was joined
//! from out of that table (one read, sliced where consecutive parts stay
//! consecutive) instead of reading each part's cache entry: adding one
//! file to thousands reads each published table once and the new file's
//! part. Only a table the stage's assembly passed on as joined can be
//! sliced so; the state records, for those, each part's rows
//! ([`Composition`]).

use std::collections::HashMap;

use super::file_result::{Part, Rows};
use super::keys::Key;
use super::state::Composition;
use super::store::Store;
use crate::error::Result;
use crate::schema::TableDef;
use crate::stages::{Output, Tables};
use crate::table::Table;

/// The last published table, with where each of the last run's parts'
/// rows are in it (by the part's place in [`Composition::parts`]).
struct Published {
    table: Table,
    /// Per part, its first row and its number of rows.
    at: Vec<(usize, usize)>,
}

/// Joins the parts (those the stage did not fail on) per table of `defs`;
/// `published` gives the last published table of a def when it is still
/// the file the last run wrote, `last` what that run joined it from.
/// Returns the tables and what they were joined from.
pub(super) fn join(
    defs: &[&'static TableDef],
    parts: Vec<Part>,
    store: &Store,
    published: impl Fn(&TableDef) -> Option<Table>,
    last: Option<&Composition>,
) -> Result<(Tables, Composition)> {
    let parts: Vec<Part> = parts
        .into_iter()
        .filter(|p| !matches!(p.rows, Rows::Failed(_)))
        .collect();
    let plain: Vec<&'static TableDef> = defs.iter().copied().filter(|d| !d.is_dataset()).collect();
    let olds: HashMap<&str, Published> = plain
        .iter()
        .filter_map(|d| Some((d.name, previous(d, last?, &published)?)))
        .collect();
    // Each part's place among the last run's parts, looked up once.
    let places: HashMap<&Key, usize> = match (olds.is_empty(), last) {
        (false, Some(l)) => l.parts.iter().enumerate().map(|(i, k)| (k, i)).collect(),
        _ => HashMap::new(),
    };
    let slots: Vec<Option<usize>> = parts.iter().map(|p| places.get(&p.key).copied()).collect();
    drop(places);
    // A part whose rows some table cannot take from the published one is
    // loaded (or taken as made).
    let mut own: Vec<Option<Tables>> = Vec::with_capacity(parts.len());
    let mut keys: Vec<Key> = Vec::with_capacity(parts.len());
    for (p, slot) in parts.into_iter().zip(&slots) {
        let sliced = slot.is_some() && plain.iter().all(|d| olds.contains_key(d.name));
        own.push(match (sliced, p.rows) {
            (true, _) => None,
            (false, Rows::Made(t)) => Some(t),
            (false, _) => Some(store.load_part(&p.key, defs)?),
        });
        keys.push(p.key);
    }
    let mut composition = Composition::default();
    let mut tables = Vec::with_capacity(plain.len());
    for def in plain {
        let (t, rows) = join_one(def, &slots, &mut own, olds.get(def.name))?;
        composition.rows.insert(def.name.into(), rows);
        tables.push((def, t));
    }
    composition.parts = keys;
    Ok((tables, composition))
}

/// The last published table `def` with each part's place in it, when the
/// state says what it was joined from and the file is that table.
fn previous(
    def: &TableDef,
    last: &Composition,
    published: &impl Fn(&TableDef) -> Option<Table>,
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
    (offset == table.height()).then_some(Published { table, at })
}

/// One table: slices of the published one and the parts' own rows, in
/// the parts' order (`slots`: each part's place among the last run's
/// parts, when it was one); with each part's rows.
fn join_one(
    def: &'static TableDef,
    slots: &[Option<usize>],
    own: &mut [Option<Tables>],
    old: Option<&Published>,
) -> Result<(Table, Vec<u64>)> {
    let mut pieces: Vec<Table> = Vec::new();
    let mut rows = Vec::with_capacity(slots.len());
    // The current run of consecutive published rows.
    let mut run: Option<(usize, usize)> = None;
    for (slot, mine) in slots.iter().zip(own.iter_mut()) {
        if let Some((o, (at, n))) = old.and_then(|o| Some((o, o.at[(*slot)?]))) {
            rows.push(n as u64);
            run = match run {
                Some((s, l)) if s + l == at => Some((s, l + n)),
                Some((s, l)) => {
                    pieces.push(o.table.slice(s, l));
                    Some((at, n))
                }
                None => Some((at, n)),
            };
            continue;
        }
        if let (Some((s, l)), Some(o)) = (run.take(), old) {
            pieces.push(o.table.slice(s, l));
        }
        let t = mine.as_mut().and_then(|ts| {
            let i = ts.iter().position(|(d, _)| *d == def)?;
            Some(ts.swap_remove(i).1)
        });
        rows.push(t.as_ref().map_or(0, |t| t.height() as u64));
        pieces.extend(t);
    }
    if let (Some((s, l)), Some(o)) = (run, old) {
        pieces.push(o.table.slice(s, l));
    }
    let t = match Table::concat(pieces)? {
        Some(t) => t,
        None => def.empty_table()?,
    };
    Ok((t, rows))
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
