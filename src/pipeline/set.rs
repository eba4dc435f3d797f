//! Publishing a run's set: every table that changed written with its
//! provenance, the others kept, the run's own tables (`files`, `errors`)
//! and the report (each kept as the last set has it when what it is made
//! of is unchanged: an unchanged rerun writes no table); then the state
//! saved (when it changed) and the cache entries nothing uses any more
//! dropped.

use std::collections::{BTreeMap, BTreeSet};
use std::sync::Arc;

use super::inputs::files_table;
use super::keys::{Key, KeyBuilder};
use super::phases::Phase;
use super::provenance::Provenance;
use super::publish::{KeyValues, OutputSet, ToWrite};
use super::registry::{ERRORS, FILES};
use super::runner::{sorted, Inputs, Runner};
use super::state::{stamped_file, Doubts, State, TableState};
use super::state_log;
use crate::error::Result;
use crate::schema::TableDef;
use crate::table::Table;

impl Runner<'_> {
    /// Publishes the set, then saves the state and prunes the cache.
    pub(super) fn publish(&mut self, command: &str) -> Result<()> {
        let mut set = OutputSet::begin(&self.plan.out_dir)?;
        let mut tables = self.write_made(&mut set, command)?;
        let (own, keys) = self.write_own(&mut set, command, &mut tables)?;
        set.write_tables(&tables)?;
        drop(tables);
        self.report.phases.mark(Phase::Tables);
        let report = self.write_report(&mut set, own, &keys)?;
        self.report.phases.mark(Phase::Report);
        let folders = set.commit()?;
        self.save_state(keys.into_iter().chain(report))?;
        let cache = self.store.cache();
        for dir in folders
            .iter()
            .chain([&cache.parts_dir(), &cache.packs_dir()])
        {
            self.swept.record(dir);
        }
        self.swept.save();
        self.report.phases.mark(Phase::Commit);
        Ok(())
    }

    /// The stages' tables: kept as the last run published them, or
    /// returned to be written.
    fn write_made(&mut self, set: &mut OutputSet, command: &str) -> Result<Vec<ToWrite>> {
        let dir = &self.plan.out_dir;
        let mut tables = Vec::new();
        let mut stage_kv: Option<(usize, KeyValues)> = None;
        for p in &self.made {
            let path = p.def.path_in(dir);
            let held = p.def.is_dataset() && self.swept.holds(&path);
            if p.published.is_some() {
                set.keep(p.def, held)?;
                self.report.kept.push(path);
                continue;
            }
            if let Some(files) = &p.files {
                let cache = self.store.cache();
                set.write_dataset(p.def, files, held, |f| cache.part_file(&f.key, p.def.name))?;
                self.report.outputs.push(path);
                continue;
            }
            // A stage's tables share their provenance (every input of it).
            let kv = match &stage_kv {
                Some((i, kv)) if *i == p.stage => kv,
                _ => {
                    let stage = self.plan.stages[p.stage].stage.as_ref();
                    let prov = Provenance::of_stage(
                        command,
                        stage,
                        p.inputs.clone(),
                        &self.plan.spec_json,
                    );
                    &stage_kv
                        .insert((p.stage, prov.key_values(p.def.name).into()))
                        .1
                }
            };
            tables.push((p.def, p.table(self.store.cache())?.clone(), kv.clone()));
            self.report.outputs.push(path);
        }
        Ok(tables)
    }

    /// The run's own tables, `files` and `errors`, with every input of the
    /// set in their provenance; each kept as the last set has it when its
    /// content and provenance are the same (its key), else added to
    /// `tables` to be written. Returns the tables and their keys.
    fn write_own(
        &mut self,
        set: &mut OutputSet,
        command: &str,
        tables: &mut Vec<ToWrite>,
    ) -> Result<([Own; 2], Vec<Kept>)> {
        // Every table's inputs, each once (a stage's tables share one list).
        let mut lists: Vec<&Inputs> = Vec::new();
        for p in &self.made {
            if !lists.iter().any(|l| Arc::ptr_eq(l, &p.inputs)) {
                lists.push(&p.inputs);
            }
        }
        let all = match lists.as_slice() {
            [one] => Arc::clone(one),
            _ => sorted(lists.iter().flat_map(|l| l.iter().cloned()).collect()),
        };
        let common = KeyBuilder::new("own")
            .part(command)
            .part(&self.plan.spec_json.to_string())
            .part_value(&*all)
            .finish();
        let keys = [
            KeyBuilder::new("files")
                .key(&common)
                .part_value(&self.report.inputs)
                .finish(),
            KeyBuilder::new("errors")
                .key(&common)
                .part_value(&self.report.failures)
                .finish(),
        ];
        let prov = Provenance {
            command: command.into(),
            stage: "pipeline".into(),
            inputs: all,
            pipeline: self.plan.spec_json.clone(),
            ..Default::default()
        };
        let own = [
            (&FILES, files_table(&self.report.inputs)?),
            (&ERRORS, self.report.errors_table()?),
        ];
        let dir = &self.plan.out_dir;
        let mut kept = Vec::with_capacity(2);
        let kv: KeyValues = prov.key_values("").into();
        for ((def, table), key) in own.iter().zip(keys) {
            let path = def.path_in(dir);
            match self.old.published(dir, def, &key) {
                true => {
                    set.keep(def, false)?;
                    self.report.kept.push(path);
                }
                false => {
                    tables.push((def, table.clone(), kv.clone()));
                    self.report.outputs.push(path);
                }
            }
            kept.push((def.path_in(dir), def.name.to_string(), key));
        }
        Ok((own, kept))
    }

    /// The warnings of the set (rows whose status is not `ok`) and, unless
    /// the pipeline says `report = false`, `report.html` from the set's
    /// tables (only those it reads or that have a status: never the
    /// traces); the report is kept as the last set has it when those
    /// tables are (their keys, and the folder's name in its title), and
    /// the tables it alone reads are then not read.
    fn write_report(
        &mut self,
        set: &mut OutputSet,
        own: [Own; 2],
        own_keys: &[Kept],
    ) -> Result<Option<Kept>> {
        let mut tables: BTreeMap<String, Table> = own
            .into_iter()
            .map(|(d, t)| (d.name.to_string(), t))
            .collect();
        let out = &self.plan.out_dir;
        let mut key = KeyBuilder::new("report").part(&super::report::title(out));
        for (_, name, k) in own_keys {
            key = key.part(name).key(k);
        }
        for p in self
            .made
            .iter()
            .filter(|p| p.def.in_report() || p.def.has_status())
        {
            key = key.part(p.def.name).key(&p.key);
        }
        let (key, path) = (key.finish(), out.join(super::report::REPORT));
        let old = self.old.tables.get(super::report::REPORT);
        let pages = super::report::page_states(&self.old.tables);
        let same =
            old.is_some_and(|o| o.is_file(&path, key)) && super::report::pages_intact(out, &pages);
        // The warnings read the tables with a status; a report rendered
        // again reads those it shows too (each file's figures, say).
        let render = self.plan.report && !same;
        // The warnings are the last run's when the tables they come from
        // are (an unchanged rerun then reads no table).
        let dkey = self.doubts_key();
        let last = self.old.doubts.as_ref().filter(|d| d.key == dkey);
        for p in &self.made {
            let shown = render && p.def.in_report() && !kept_in_files(p);
            if (p.def.has_status() && last.is_none()) || shown {
                tables.insert(p.def.name.to_string(), p.table(self.store.cache())?.clone());
            }
        }
        self.report.warnings = match last {
            Some(d) => d.rows.clone(),
            None => crate::report::doubts(&tables)?,
        };
        self.new.doubts = Some(Doubts {
            key: dkey,
            rows: self.report.warnings.clone(),
        });
        if !self.plan.report {
            return Ok(None);
        }
        let pages = match render {
            true => {
                self.report.outputs.push(path.clone());
                let kept = self.figure_files();
                super::report::write(set, out, &tables, kept, &self.old.tables)?
            }
            false => {
                set.keep_file(super::report::REPORT)?;
                set.keep_folder(crate::report::PAGES_DIR)?;
                self.report.kept.push(path.clone());
                pages
            }
        };
        self.new.tables.extend(pages);
        Ok(Some((path, super::report::REPORT.to_string(), key)))
    }

    /// The report's figure tables read from files, a page at a time: the
    /// per-file stages' (datasets of a file per input), each input's file
    /// its part in the cache, as the new state records it.
    fn figure_files(&self) -> crate::report::FigureFiles<'_> {
        let tables: Vec<(&'static str, &str)> = self
            .made
            .iter()
            .filter(|p| kept_in_files(p))
            .map(|p| (p.def.name, self.plan.stages[p.stage].stage.name()))
            .collect();
        let names = tables.iter().map(|t| t.0).collect();
        let (files, cache) = (&self.new.files, self.store.cache());
        crate::report::FigureFiles::new(names, move |table, source| {
            let stage = tables.iter().find(|t| t.0 == table)?.1;
            let f = files.get(source)?;
            match f.failed.get(stage) {
                Some(_) => None,
                None => Some(cache.part_file(f.parts.get(stage)?, table)),
            }
        })
    }

    /// The key of the warnings: the tables with a status, the only ones
    /// that have warnings (not the run's own: `files` changes with what a
    /// run did to each input, its warnings do not).
    fn doubts_key(&self) -> Key {
        let mut key = KeyBuilder::new("doubts");
        for p in self.made.iter().filter(|p| p.def.has_status()) {
            key = key.part(p.def.name).key(&p.key);
        }
        key.finish()
    }

    /// Saves the state of the published set (unless it is the last one's),
    /// and drops the cache entries it does not use. `own`: the run's own
    /// files (tables and report) with their keys.
    fn save_state(&mut self, own: impl Iterator<Item = Kept>) -> Result<()> {
        let dir = &self.plan.out_dir;
        for p in self.made.iter().filter(|p| p.published.is_none()) {
            let path = stamped_file(dir, p.def);
            if let Some(s) = TableState::of_file(&path, p.key) {
                self.new.tables.insert(p.def.name.into(), s);
            }
        }
        for (path, name, key) in own {
            if let Some(s) = TableState::of_file(&path, key) {
                self.new.tables.insert(name, s);
            }
        }
        state_log::save(dir, &self.old, self.old_log.as_ref(), &self.new)?;
        let stages = self.new.stages.values().map(|s| s.key).collect();
        let cache = self.store.cache();
        let dead = cache
            .state_stands()
            .then(|| dead_entries(&self.old, &self.new));
        let live = || entries(&self.new);
        cache.retain(live, &stages, &self.units_used, dead.as_deref());
        Ok(())
    }
}

/// The routes and parts `old` names that `new` does not (a key holds its
/// input's path: a key dies with its input's entry).
fn dead_entries(old: &State, new: &State) -> Vec<Key> {
    let mut dead = Vec::new();
    for (_, was, now) in State::inputs_of_both(old, new) {
        let Some(was) = was else { continue };
        if was.route.is_some() && now.and_then(|n| n.route.as_ref()) != was.route.as_ref() {
            dead.extend(was.route);
        }
        for (stage, key) in was.parts.iter() {
            if now.and_then(|n| n.parts.get(stage)) != Some(key) {
                dead.push(*key);
            }
        }
    }
    dead
}

/// The routes and parts a state names.
fn entries(state: &State) -> (BTreeSet<Key>, BTreeSet<Key>) {
    let files = state.files.values();
    let routes = files.clone().filter_map(|f| f.route).collect();
    let parts = files.flat_map(|f| f.parts.values().cloned()).collect();
    (routes, parts)
}

/// One of the run's own tables.
type Own = (&'static TableDef, Table);

/// A file of the run's own (a table, the report): its path, its name in
/// the state, its key.
type Kept = (std::path::PathBuf, String, Key);

/// Whether the report reads `p` from its files, a page at a time: a
/// figure table published as a dataset (a file per input).
fn kept_in_files(p: &super::runner::Produced) -> bool {
    p.def.show == crate::schema::Show::Figures && p.def.is_dataset()
}
