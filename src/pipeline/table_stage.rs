//! A table stage in a run: its input tables gathered (made by earlier
//! stages, or given as files), its key from theirs, then reused, taken from
//! the cache, or run (a study's runs each from the cache or run, in
//! parallel).

use std::collections::BTreeMap;
use std::path::PathBuf;

use rayon::prelude::*;

use super::assemble::load_table;
use super::keys::{stage_key, unit_key, Key};
use super::provenance::InputHash;
use super::run::check_changed;
use super::runner::{sorted, Runner};
use crate::error::{Error, Result};
use crate::stages::{Need, Progress, TableInputs};
use crate::table::Table;

/// Where a table stage's input comes from.
enum Source {
    /// A file given in the pipeline: its bytes, read once (for its hash in
    /// the stage's key, and parsed only if the stage runs), and its hash.
    File(PathBuf, Vec<u8>, InputHash),
    /// A table made (or kept) by an earlier stage of this run.
    Made(usize),
}

impl Runner<'_> {
    /// A table stage: its inputs gathered, then reused, or run.
    pub(super) fn table_stage(&mut self, i: usize, needs: &[Need], progress: &dyn Progress) {
        let plan = self.plan;
        let ps = &plan.stages[i];
        let mut kb = stage_key(ps);
        let mut inputs = ps.stage.own_inputs();
        for h in &inputs {
            kb = kb.part(&h.sha256);
        }
        let mut sources: Vec<(&'static str, Source)> = Vec::new();
        for need in needs {
            let source = match ps.table_files.get(need.table.name) {
                Some(path) => match std::fs::read(path) {
                    Ok(bytes) => {
                        let h = InputHash::of_bytes(path, &bytes);
                        kb = kb.part(&h.sha256);
                        Source::File(path.clone(), bytes, h)
                    }
                    Err(e) => return self.fail_stage(i, Error::io(path, e)),
                },
                None => match self.made.iter().position(|p| p.def == need.table) {
                    Some(j) => {
                        kb = kb.key(&self.made[j].key);
                        inputs.extend(self.made[j].inputs.iter().cloned());
                        Source::Made(j)
                    }
                    None if need.required => {
                        let e = Error::NotApplicable(format!(
                            "not run: its input table '{}' was not produced (see the errors above)",
                            need.table.name
                        ));
                        return self.fail_stage(i, e);
                    }
                    None => {
                        kb = kb.part("absent");
                        continue;
                    }
                },
            };
            sources.push((need.table.name, source));
        }
        let key = kb.finish();
        self.run_table_stage(i, key, sources, inputs, progress);
    }

    /// A table stage with its key: reused, from the cache, or run.
    fn run_table_stage(
        &mut self,
        i: usize,
        key: Key,
        sources: Vec<(&'static str, Source)>,
        mut inputs: Vec<InputHash>,
        progress: &dyn Progress,
    ) {
        let stage = self.plan.stages[i].stage.as_ref();
        let known = sorted(inputs.clone());
        if self.reuse(i, &key, &known) {
            return;
        }
        if !self.store.writes() {
            let why = self.stage_reason(i, &key);
            self.would_redo(i, key, why, known);
            return;
        }
        if let Some(cached) = self.store.stage(&key, &stage.produces()) {
            self.report.stages_reused.push(stage.name().into());
            return self.record(i, key, cached, known);
        }
        // A table stage's tables are checked here, where they are made (a
        // stage output from the cache was checked when it was made).
        let output = self
            .load_sources(sources, &mut inputs)
            .and_then(|available| {
                let tables = TableInputs::new(&available);
                let n_units = stage.unit_costs().len();
                if n_units == 0 {
                    progress.begin(stage.name(), stage.units());
                    return stage.run_tables(&tables, progress);
                }
                let all: Vec<usize> = (0..n_units).collect();
                let results = self.run_units(i, &all, progress)?;
                stage.run_tables_from_units(&tables, results)
            })
            .and_then(|o| check_changed(&o, &Vec::new()).map(|_| o));
        if let Ok(o) = &output {
            self.store.put_stage(&key, o);
        }
        self.report.stages_run.push(stage.name().into());
        self.record(i, key, output, sorted(inputs));
    }

    /// In a shard: its runs of the studies, into the cache.
    pub(super) fn shard_units(&mut self, progress: &dyn Progress) {
        let Some(mine) = &self.mine else {
            return;
        };
        let mut by_stage: BTreeMap<usize, Vec<usize>> = BTreeMap::new();
        for &(s, u) in &mine.units {
            by_stage.entry(s).or_default().push(u);
        }
        for (s, units) in by_stage {
            if let Err(e) = self.run_units(s, &units, progress) {
                self.fail_stage(s, e);
            }
        }
    }

    /// Units of a table stage (runs of a study): from the cache, or run in
    /// parallel and cached; their results in the order of `units`.
    fn run_units(
        &mut self,
        i: usize,
        units: &[usize],
        progress: &dyn Progress,
    ) -> Result<Vec<Vec<u8>>> {
        let planned = &self.plan.stages[i];
        let stage = planned.stage.as_ref();
        let keys: Vec<Key> = units.iter().map(|&u| unit_key(planned, u)).collect();
        progress.begin(stage.name(), units.len());
        let store = &self.store;
        let results: Vec<Result<(Vec<u8>, bool)>> = units
            .par_iter()
            .zip(&keys)
            .map(|(&u, key)| {
                let r = match store.unit(key) {
                    Some(b) => Ok((b, false)),
                    None => stage.run_unit(u).map(|b| {
                        store.put_unit(key, &b);
                        (b, true)
                    }),
                };
                progress.tick();
                r
            })
            .collect();
        self.units_used.extend(keys);
        let mut out = Vec::with_capacity(results.len());
        for r in results {
            let (bytes, fresh) = r?;
            self.report.units_run += usize::from(fresh);
            self.report.units_reused += usize::from(!fresh);
            out.push(bytes);
        }
        Ok(out)
    }

    fn load_sources(
        &self,
        sources: Vec<(&'static str, Source)>,
        inputs: &mut Vec<InputHash>,
    ) -> Result<BTreeMap<String, Table>> {
        let mut available = BTreeMap::new();
        for (name, source) in sources {
            let t = match source {
                Source::File(path, bytes, hash) => {
                    let (t, ins) = load_table(&path, bytes, hash)?;
                    inputs.extend(ins);
                    t
                }
                Source::Made(j) => self.made[j].table(self.store.cache())?.clone(),
            };
            available.insert(name.to_string(), t);
        }
        Ok(available)
    }
}
