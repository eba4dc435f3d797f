//! Tests exported as several files, joined when the stage's rows of every
//! file are gathered ([`crate::extract::friction::series`]): the files of
//! one `test_id` get their `friction_cycles` rows numbered on through the
//! test (`test_cycle`, `test_distance_*`) and one `friction_tests` row of
//! scope `series`. Each file's own rows (and cache entry) stay as they are.

use std::collections::BTreeMap;

use super::cycle_tables::{test_lines_table, TestLine, FRICTION_CYCLES, FRICTION_TESTS};
use crate::error::Result;
use crate::extract::friction::assess::TestRow;
use crate::extract::friction::cycles::{CycleKind, CycleRow};
use crate::extract::friction::running_in::SteadyParams;
use crate::extract::friction::series::{join, order, Member};
use crate::stages::Tables;
use crate::table::{Table, TableBuilder};

/// The columns of `friction_cycles` a series reads.
struct Cycles {
    source: Vec<Option<String>>,
    test_id: Vec<Option<String>>,
    started: Vec<Option<String>>,
    sample: Vec<Option<String>>,
    cycle: Vec<Option<i64>>,
    kind: Vec<Option<String>>,
    start: Vec<Option<f64>>,
    end: Vec<Option<f64>>,
    mu: Vec<Option<f64>>,
    complete: Vec<Option<bool>>,
    energy: Vec<Option<f64>>,
    normal: Vec<Option<f64>>,
    wear: Vec<Option<f64>>,
}

impl Cycles {
    fn read(t: &Table) -> Result<Cycles> {
        Ok(Cycles {
            source: t.str("source")?,
            test_id: t.str("test_id")?,
            started: t.str("test_started_at")?,
            sample: t.str("sample_id")?,
            cycle: t.i64("cycle")?,
            kind: t.str("kind")?,
            start: t.f64("distance_start_m")?,
            end: t.f64("distance_end_m")?,
            mu: t.f64("mu")?,
            complete: t.bool("complete")?,
            energy: t.f64("energy_J")?,
            normal: t.f64("normal_force_N")?,
            wear: t.f64("wear_depth_m")?,
        })
    }

    fn row(&self, i: usize) -> CycleRow {
        let kind = match self.kind[i].as_deref() {
            Some("lap") => CycleKind::Lap,
            _ => CycleKind::Stroke,
        };
        CycleRow::summary(
            self.cycle[i].unwrap_or(0).max(0) as usize,
            kind,
            self.start[i].zip(self.end[i]),
            self.mu[i],
            self.complete[i].unwrap_or(false),
            self.energy[i],
            self.normal[i],
            self.wear[i],
        )
    }
}

/// A series: its ordered members with the table rows of their cycles.
struct Series {
    id: String,
    members: Vec<Member>,
    rows: BTreeMap<String, Vec<usize>>,
}

/// The series in the cycles table, in order of first appearance: the
/// `test_id`s shared by two files or more.
fn series_of(c: &Cycles) -> Vec<Series> {
    let mut by_id: Vec<(String, BTreeMap<String, Vec<usize>>)> = Vec::new();
    for i in 0..c.source.len() {
        let (Some(id), Some(src)) = (&c.test_id[i], &c.source[i]) else {
            continue;
        };
        let at = match by_id.iter().position(|(k, _)| k == id) {
            Some(at) => at,
            None => {
                by_id.push((id.clone(), BTreeMap::new()));
                by_id.len() - 1
            }
        };
        by_id[at].1.entry(src.clone()).or_default().push(i);
    }
    by_id
        .into_iter()
        .filter(|(_, files)| files.len() >= 2)
        .map(|(id, rows)| {
            let members = rows
                .iter()
                .map(|(src, idx)| Member {
                    source: src.clone(),
                    started_at: c.started[idx[0]].clone(),
                    cycles: idx.iter().map(|&i| c.row(i)).collect(),
                })
                .collect();
            Series { id, members, rows }
        })
        .collect()
}

/// Joins the series of `tables` (see the module documentation).
pub fn join_series(tables: &mut Tables, p: &SteadyParams) -> Result<()> {
    let Some(ci) = tables.iter().position(|(d, _)| *d == &FRICTION_CYCLES) else {
        return Ok(());
    };
    let c = Cycles::read(&tables[ci].1)?;
    let mut all = series_of(&c);
    if all.is_empty() {
        return Ok(());
    }
    let (mut cycle, mut start, mut end) = (c.cycle.clone(), c.start.clone(), c.end.clone());
    let mut rows: Vec<(usize, &'static str, TestRow)> = Vec::new();
    for (k, s) in all.iter_mut().enumerate() {
        let rule = order(&mut s.members);
        let row = join(&mut s.members, p);
        for m in &s.members {
            for (&i, r) in s.rows[&m.source].iter().zip(&m.cycles) {
                cycle[i] = Some(r.cycle as i64);
                start[i] = r.distance_m.map(|d| d.0);
                end[i] = r.distance_m.map(|d| d.1);
            }
        }
        rows.push((k, rule, row));
    }
    let update = TableBuilder::new()
        .i64("test_cycle", cycle)
        .f64("test_distance_start_m", start)
        .f64("test_distance_end_m", end);
    let cycles = std::mem::replace(&mut tables[ci].1, TableBuilder::new().build()?);
    tables[ci].1 = cycles.update(update)?;
    let lines: Vec<TestLine> = rows
        .iter()
        .map(|(k, rule, row)| {
            let s = &all[*k];
            let first = &s.members[0];
            let i0 = s.rows[&first.source][0];
            TestLine {
                source: &first.source,
                sample_id: c.sample[i0].as_deref(),
                started_at: first.started_at.as_deref(),
                test_id: Some(s.id.as_str()),
                n_files: s.members.len(),
                order: Some(*rule),
                row,
            }
        })
        .collect();
    let series = test_lines_table(&lines)?;
    match tables.iter().position(|(d, _)| *d == &FRICTION_TESTS) {
        Some(ti) => {
            let own = std::mem::replace(&mut tables[ti].1, TableBuilder::new().build()?);
            tables[ti].1 = Table::concat([own, series])?.expect("two tables");
        }
        None => tables.push((&FRICTION_TESTS, series)),
    }
    Ok(())
}
