//! Running a plan: the per-file phase ([`super::files`]), then each stage
//! in run order, then every table written once, with its provenance, and
//! the run's own tables ([`super::set`]). Nothing a stage does can stop
//! another stage that does not depend on it: a failure is a row of
//! `errors.parquet`.
//!
//! Reruns redo only what changed ([`super::cache`], [`super::state`]): a
//! stage whose key (its parameters and the keys of everything it reads) is
//! the one the last run published, and whose tables are still the files it
//! wrote, is reused without reading them; the rest is recomputed, from
//! cached per-file parts where those hold.

use std::collections::{BTreeMap, BTreeSet};
use std::sync::OnceLock;
use std::time::{Duration, Instant};

use rayon::prelude::*;

use super::assemble::stage_source;
use super::cache::Cache;
use super::dataset::{self, DataFile};
use super::files::{per_file_stages, process_files, stats, Fate, FileResult, Known, Part, Rows};
use super::inputs::InputFile;
use super::join::{as_joined, join};
use super::keys::{context_key, stage_key, table_key, Key};
use super::lock::Lock;
use super::mode::Mode;
use super::outcome::{FileFailure, Redo, RunReport, WithoutResult};
use super::phases::{Phase, Stopwatch};
use super::plan::{Plan, PlannedFile};
use super::preload::{last_state, Preload};
use super::provenance::InputHash;
use super::runner::{sorted, Inputs, Produced, Runner};
use super::shard::shard_units;
use super::shared::Shared;
use super::state::{Composition, FileStat, FileState, StageState, State};
use super::state_log::LogAt;
use super::store::Store;
use super::swept::Swept;
use crate::error::{Error, Result};
use crate::schema::TableDef;
use crate::stages::{Consumes, Output, Progress, Tables};
use crate::table::Table;

/// How to run: the mode, the cache, waiting for the folder's lock.
#[derive(Debug, Clone, Default)]
pub struct RunOptions {
    /// Ignore the cache and the last run: recompute everything.
    pub force: bool,
    /// A whole run, a dry run, or one shard's share of the work.
    pub mode: Mode,
    /// How long to wait for another run on the same folder.
    pub wait: Duration,
    /// Read and hash every input, even those whose stat is the one the
    /// last run saw (a scheduled check that the files are what their
    /// stat says).
    pub verify: bool,
    /// When the command began, before the plan was made: the time from
    /// then to the run is its plan phase.
    pub started: Option<Instant>,
    /// The last run's state, read while the plan was made.
    pub preload: Option<Preload>,
}

/// Runs the plan with the cache. `progress` sees each phase; the library
/// itself never prints.
pub fn run(plan: &Plan, command: &str, progress: &dyn Progress) -> Result<RunReport> {
    run_with(plan, command, progress, &RunOptions::default())
}

/// Runs the plan as `opts` say.
pub fn run_with(
    plan: &Plan,
    command: &str,
    progress: &dyn Progress,
    opts: &RunOptions,
) -> Result<RunReport> {
    let mut phases = Stopwatch::from(opts.started);
    // Shards share the folder: they only add whole cache entries.
    let _lock = match opts.mode.publishes() {
        true => Some(Lock::take(&plan.out_dir, opts.wait)?),
        false => None,
    };
    let mine = opts.mode.shard().map(|s| shard_units(plan, s));
    let files = mine.as_ref().map_or(plan.files.len(), |m| m.files.len());
    // `--verify` looks at every file, and lists every folder, again.
    let swept = Swept::load(&plan.out_dir, !opts.force && !opts.verify);
    let mut cache = Cache::new(&plan.out_dir);
    let only = mine.as_ref().map(|m| &m.files);
    let context = context_key(plan);
    let ((old, old_log), stats) = last_run(plan, (opts, context), only, &mut cache, &swept);
    phases.mark(Phase::State);
    let mut r = Runner {
        plan,
        store: Store::new(cache, opts.mode, opts.force, command),
        old,
        old_log,
        new: State {
            context,
            ..State::default()
        },
        report: RunReport {
            files,
            mode: opts.mode,
            phases,
            ..Default::default()
        },
        made: Vec::new(),
        forced: opts.force,
        verify: opts.verify,
        mine,
        units_used: BTreeSet::new(),
        swept,
    };
    r.report.notes.extend(renamed_inputs(&r.old, plan));
    r.file_stages(&stats, progress);
    r.report.phases.mark(Phase::Join);
    for i in 0..plan.stages.len() {
        if let Consumes::Tables(needs) = plan.stages[i].stage.consumes() {
            let skip = r.mine.as_ref().is_some_and(|m| !m.stages.contains(&i));
            if !skip {
                r.table_stage(i, &needs, progress);
            }
        }
    }
    r.report.phases.mark(Phase::TableStages);
    match opts.mode {
        Mode::Shard(_) => r.shard_units(progress),
        Mode::DryRun => r.list_deleted(),
        Mode::Run => r.publish(command)?,
    }
    free_later((r.store, r.old, r.new, r.made));
    Ok(r.report)
}

/// The last run's state (none with `force`), where its log stands, and
/// each input's stat now, taken while the state is read: the two are a
/// rerun's first costs that grow with the archive. Tells `cache` what the
/// state stands for.
fn last_run(
    plan: &Plan,
    (opts, context): (&RunOptions, Option<Key>),
    only: Option<&BTreeSet<usize>>,
    cache: &mut Cache,
    swept: &Swept,
) -> ((State, Option<LogAt>), Vec<Option<FileStat>>) {
    let held = (
        swept.holds(&cache.parts_dir()),
        swept.holds(&cache.packs_dir()),
    );
    let (last, stats) = rayon::join(
        || last_state(&plan.out_dir, opts.force, opts.preload.as_ref()),
        || stats(plan, only),
    );
    // Only the last run's own state stands for the cache: one that could
    // not be read (damaged, another build's) would make every cached file
    // look new. Another context's parts may be listed only in packs this
    // build cannot read: `parts/` is listed.
    cache.know_parts(held.0 && last.0.made_in(context));
    cache.know_packs(held.1 && last.1.is_some());
    (last, stats)
}

/// A note when the last run knew this run's inputs by other names (the
/// pipeline's path given otherwise): a cache that is whole looks empty,
/// and the user should know why every input is read again.
fn renamed_inputs(old: &State, plan: &Plan) -> Option<String> {
    let names: Vec<&str> = plan.files.iter().map(|f| f.source.as_str()).collect();
    let was = old.same_input_named_otherwise(&names)?;
    Some(format!(
        "every input is new to this folder's cache: the last run named '{was}' what this run \
         names '{}'. Inputs are named by the pipeline's path as given on the command line; \
         give it as the last run did (or run from the folder it ran in) to reuse its results",
        names[0]
    ))
}

/// What the run records of a file besides its state: its failures and
/// its row of the `files` table (none for a file a dry run would read: it
/// lists what it would read, not what became of it).
fn record_of(
    plan: &Plan,
    f: &PlannedFile,
    r: &FileResult,
) -> (Vec<FileFailure>, Option<InputFile>) {
    let failures = r.failures(plan, f);
    let row = (!matches!(r.fate, Fate::Pending)).then(|| r.row(plan, f, &failures));
    (failures, row)
}

/// Frees `held` on a thread of its own: the maps of a run over a large
/// archive (the cache's packs, two states) take a tenth of an unchanged
/// rerun to free, and a command that exits next need not wait for it.
fn free_later<T: Send + 'static>(held: T) {
    // Without a thread to be had, it is freed here, as the spawn fails.
    let _ = std::thread::Builder::new().spawn(move || drop(held));
}

impl Runner<'_> {
    /// The per-file phase, then each per-file stage from its files' parts.
    /// `stats`: each input's, as [`stats`] took them.
    fn file_stages(&mut self, stats: &[Option<FileStat>], progress: &dyn Progress) {
        let stages = per_file_stages(self.plan);
        if stages.is_empty() && self.plan.files.is_empty() {
            return;
        }
        let only = self.mine.as_ref().map(|m| &m.files);
        let known = (!self.verify).then_some(Known {
            state: &self.old,
            keys: self.old.made_in(self.new.context),
        });
        let results = process_files(self.plan, &self.store, (only, stats), known, progress);
        self.store.flush();
        let mut pending: BTreeSet<usize> = BTreeSet::new();
        let plan = self.plan;
        // Made on the threads straight into their own lists: one record per
        // input gathering them was 16 MB of fresh memory at 20 000 inputs.
        let states: Vec<Option<(String, Shared<FileState>)>> = results
            .par_iter()
            .map(|(k, r, last)| {
                let path = &plan.files[*k].source;
                Some((path.clone(), r.state_after(plan, last.as_ref())?))
            })
            .collect();
        let records: Vec<(Vec<FileFailure>, Option<InputFile>)> = results
            .par_iter()
            .map(|(k, r, _)| record_of(plan, &plan.files[*k], r))
            .collect();
        // Sized once: grown push by push, these lists of large rows were
        // copied at every doubling.
        let n = results.len();
        let mut by_stage: BTreeMap<usize, Vec<Part>> =
            stages.iter().map(|&i| (i, Vec::with_capacity(n))).collect();
        self.report.inputs.reserve(n);
        for ((k, result, _), (failures, row)) in results.into_iter().zip(records) {
            let f = &plan.files[k];
            self.record_file(f, &result, failures, row);
            match result.fate {
                Fate::Taken(parts) => {
                    for mut p in parts {
                        // A part carries the file's hash to its stage's
                        // inputs unless the stage failed on it.
                        if !matches!(p.rows, Rows::Failed(_)) {
                            p.input = result.hash.clone();
                        }
                        by_stage.entry(p.stage).or_default().push(p);
                    }
                }
                Fate::Pending => pending.extend(self.pending_stages(f)),
                _ => {}
            }
        }
        // Built in bulk (sorted once), not by an insert per input.
        self.new.files = states.into_iter().flatten().collect();
        self.report.phases.mark(Phase::Files);
        if self.mine.is_some() {
            return;
        }
        for (i, parts) in by_stage {
            self.file_stage(i, parts, pending.contains(&i));
        }
    }

    /// Records what became of one file: its failures, its row of the
    /// `files` table, the counts.
    fn record_file(
        &mut self,
        f: &PlannedFile,
        result: &FileResult,
        failures: Vec<FileFailure>,
        row: Option<InputFile>,
    ) {
        self.report.files_hashed += usize::from(result.hashed);
        match &result.fate {
            Fate::NotTaken(why) if !f.named => {
                let source = f.source.clone();
                self.report.unrouted.push((source, why.clone()))
            }
            Fate::Pending => {
                let bytes = result.content.as_ref().map_or("", |c| &*c.0);
                let reason = self.file_reason(&f.source, bytes);
                self.report.redo.push(Redo::file(&f.source, reason));
            }
            Fate::Taken(_) if failures.is_empty() => {
                self.report.succeeded += 1;
                match result.redone() {
                    true => self.report.files_processed += 1,
                    false => self.report.files_reused += 1,
                }
            }
            _ => {}
        }
        self.report.inputs.extend(row);
        self.report.failures.extend(failures);
    }

    /// The per-file stages a dry run would run for a file it would read:
    /// those that took it last time; for a new file, any.
    fn pending_stages(&self, f: &PlannedFile) -> Vec<usize> {
        let before = self.old.files.get(&f.source).map(|f| &f.parts);
        per_file_stages(self.plan)
            .into_iter()
            .filter(|&i| {
                let name = self.plan.stages[i].stage.name();
                before.is_none_or(|p| p.is_empty() || p.contains_key(name))
            })
            .collect()
    }

    /// Joins a per-file stage's parts and assembles its output, unless the
    /// last run published the same. `pending`: a dry run would read files
    /// of it.
    fn file_stage(&mut self, i: usize, parts: Vec<Part>, pending: bool) {
        let stage = self.plan.stages[i].stage.as_ref();
        let key = parts
            .iter()
            .fold(stage_key(&self.plan.stages[i]), |kb, p| kb.key(&p.key))
            .finish();
        let mut inputs: Vec<InputHash> = parts.iter().filter_map(|p| p.input.clone()).collect();
        inputs.extend(self.plan.manifest.as_ref().map(|(_, h)| h.clone()));
        let inputs = sorted(inputs);
        if pending {
            self.would_redo(i, key, "new or changed input files", inputs);
            return;
        }
        // A dataset's file made again (its cache entry was gone or
        // rewritten) is linked again, even under the same key.
        let remade = stage.produces().iter().any(|d| d.is_dataset())
            && parts.iter().any(|p| matches!(p.rows, Rows::Made(_)));
        if !remade && self.reuse(i, &key, &inputs) {
            return;
        }
        if !self.store.writes() {
            let why = self.stage_reason(i, &key);
            self.would_redo(i, key, why, inputs);
            return;
        }
        let defs = stage.produces();
        let datasets = self.dataset_files(&defs, &parts);
        let (out, old) = (&self.plan.out_dir, &self.old);
        let last = old.stages.get(stage.name());
        let published = |def: &TableDef| -> Option<Table> {
            let key = table_key(&last?.key, def.name);
            old.published(out, def, &key)
                .then(|| Table::read_parquet(&def.path_in(out)).ok())?
                .map(|(t, _)| t)
        };
        let joined = join(
            &defs,
            parts,
            &self.store,
            published,
            last.map(|s| &s.joined),
        );
        // The parts were checked when made; their join holds to the same
        // schemas. Only a table the stage's assembly changed is checked.
        let mut composition = Composition::default();
        let output = joined.and_then(|(t, mut c)| {
            let joined = t.clone();
            let out = stage.assemble(t)?;
            check_changed(&out, &joined)?;
            as_joined(&mut c, &out, &joined);
            composition = c;
            Ok(out)
        });
        self.report.stages_run.push(stage.name().into());
        let ok = output.is_ok();
        self.record(i, key, output, inputs.clone());
        if ok {
            if let Some(s) = self.new.stages.get_mut(stage.name()) {
                s.joined = composition;
            }
            self.record_datasets(i, &key, datasets, inputs);
        }
    }

    /// The files of a per-file stage's dataset tables: each part's file
    /// (those the stage did not fail on), in input order. Named in
    /// parallel: two paths made per input.
    fn dataset_files(
        &self,
        defs: &[&'static TableDef],
        parts: &[Part],
    ) -> Vec<(&'static TableDef, Vec<DataFile>)> {
        let datasets = defs.iter().filter(|d| d.is_dataset());
        datasets
            .map(|&def| {
                let files = parts
                    .par_iter()
                    .filter_map(|p| {
                        let input = p.input.as_ref()?;
                        let fresh = match p.rows {
                            Rows::Made(_) => true,
                            Rows::Cached => false,
                            Rows::Failed(_) => return None,
                        };
                        Some(DataFile {
                            name: dataset::file_name(&input.path, &p.key),
                            key: p.key,
                            fresh,
                        })
                    })
                    .collect();
                (def, files)
            })
            .collect()
    }

    /// Takes a stage's dataset tables, as their files.
    fn record_datasets(
        &mut self,
        i: usize,
        key: &Key,
        datasets: Vec<(&'static TableDef, Vec<DataFile>)>,
        inputs: Inputs,
    ) {
        for (def, files) in datasets {
            if let Some(s) = self.new.stages.get_mut(self.plan.stages[i].stage.name()) {
                s.tables.push(def.name.into());
            }
            self.made.push(Produced {
                def,
                stage: i,
                inputs: inputs.clone(),
                key: table_key(key, def.name),
                table: OnceLock::new(),
                published: None,
                files: Some(files),
            });
        }
    }

    pub(super) fn fail_stage(&mut self, i: usize, e: Error) {
        let ps = &self.plan.stages[i];
        let source = stage_source(self.plan, ps);
        self.report
            .failures
            .push(FileFailure::new(source, ps.stage.name(), &e));
    }

    /// Takes a stage's output, its tables checked: its tables, rows without
    /// a result and notes; or its failure.
    pub(super) fn record(&mut self, i: usize, key: Key, output: Result<Output>, inputs: Inputs) {
        let name = self.plan.stages[i].stage.name();
        let output = match output {
            Ok(o) => o,
            Err(e) => return self.fail_stage(i, e),
        };
        if output.without_result > 0 {
            self.report.without_result.push(WithoutResult {
                stage: name.into(),
                rows: output.without_result,
            });
        }
        self.report.notes.extend(output.notes.clone());
        self.new.stages.insert(
            name.into(),
            StageState {
                key,
                without_result: output.without_result,
                notes: output.notes,
                tables: output.tables.iter().map(|(d, _)| d.name.into()).collect(),
                joined: Composition::default(),
            },
        );
        for (def, table) in output.tables {
            self.made.push(Produced {
                def,
                stage: i,
                inputs: inputs.clone(),
                key: table_key(&key, def.name),
                table: OnceLock::from(table),
                published: None,
                files: None,
            });
        }
    }
}

/// Checks each table of `out` against its schema, but those passed on as
/// they are from `checked` (tables already checked: the same columns, not
/// equal ones), so that a defect fails its stage only and no table is
/// checked twice.
pub(super) fn check_changed(out: &Output, checked: &Tables) -> Result<()> {
    for (def, table) in &out.tables {
        let kept = checked.iter().any(|(d, t)| d == def && t.is_same(table));
        if !kept {
            def.check(table)?;
        }
    }
    Ok(())
}
