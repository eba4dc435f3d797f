//! The state of one run as it goes: the plan, its mode's store, the last
//! run's state and the new one, the report, and the tables made so far
//! (each a [`Produced`], until the set is published). The work is in
//! [`super::run`] (files and their stages), [`super::table_stage`],
//! [`super::reuse`] and [`super::set`] (publishing).

use std::collections::BTreeSet;
use std::path::PathBuf;
use std::sync::{Arc, OnceLock};

use super::cache::Cache;
use super::dataset::{read_table, DataFile};
use super::keys::Key;
use super::outcome::RunReport;
use super::plan::Plan;
use super::provenance::InputHash;
use super::shard::ShardUnits;
use super::state::State;
use super::state_log::LogAt;
use super::store::Store;
use super::swept::Swept;
use crate::error::{Error, Result};
use crate::schema::TableDef;
use crate::table::Table;

/// A table a stage produced (or the last run published, loaded only when
/// a stage that is redone reads it), with the raw inputs behind it.
pub(super) struct Produced {
    pub(super) def: &'static TableDef,
    pub(super) stage: usize,
    pub(super) inputs: Inputs,
    pub(super) key: Key,
    pub(super) table: OnceLock<Table>,
    /// The published file (or dataset folder) of a reused table.
    pub(super) published: Option<PathBuf>,
    /// A dataset table: its files, one per input, in input order.
    pub(super) files: Option<Vec<DataFile>>,
}

impl Produced {
    /// The table, loaded once (a dataset's from its files in `cache`).
    pub(super) fn table(&self, cache: &Cache) -> Result<&Table> {
        if let Some(t) = self.table.get() {
            return Ok(t);
        }
        if let Some(files) = &self.files {
            let paths: Vec<_> = files
                .iter()
                .map(|f| cache.part_file(&f.key, self.def.name))
                .collect();
            let t = match Table::read_stacked(&paths)? {
                Some(t) => t,
                None => self.def.empty_table()?,
            };
            return Ok(self.table.get_or_init(|| t));
        }
        let path = self
            .published
            .as_ref()
            .ok_or_else(|| Error::Table(format!("table {} was not computed", self.def.name)))?;
        let t = read_table(path)?;
        Ok(self.table.get_or_init(|| t))
    }
}

/// One run in progress.
pub(super) struct Runner<'a> {
    pub(super) plan: &'a Plan,
    pub(super) store: Store,
    pub(super) old: State,
    /// Where the state's log stood when `old` was loaded.
    pub(super) old_log: Option<LogAt>,
    pub(super) new: State,
    pub(super) report: RunReport,
    pub(super) made: Vec<Produced>,
    pub(super) forced: bool,
    /// Read and hash every input (`--verify`).
    pub(super) verify: bool,
    /// In a shard: its files and stages.
    pub(super) mine: Option<ShardUnits>,
    /// Cache keys of the study runs this run used.
    pub(super) units_used: BTreeSet<Key>,
    /// The folders the last run left as it recorded them.
    pub(super) swept: Swept,
}

/// A stage's raw inputs, sorted by path, each once: one list that all
/// its tables share (over a large archive, a copy per table was most of
/// what a rerun spent on its stages).
pub(super) type Inputs = Arc<[InputHash]>;

/// Inputs sorted by path, each once.
pub(super) fn sorted(mut v: Vec<InputHash>) -> Inputs {
    v.sort();
    v.dedup();
    v.into()
}
