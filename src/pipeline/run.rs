//! Running a plan: the per-file phase ([`super::files`]), then each stage
//! in run order, then every table written once, with its provenance, and
//! `errors.parquet`. Nothing a stage does can stop another stage that does
//! not depend on it: a failure is a row of `errors.parquet`.
//!
//! Reruns redo only what changed ([`super::cache`], [`super::state`]): a
//! stage whose key (its parameters and the keys of everything it reads) is
//! the one the last run published, and whose tables are still the files it
//! wrote, is reused without reading them; the rest is recomputed, from
//! cached per-file parts where those hold.

use std::collections::{BTreeMap, BTreeSet};

use rayon::prelude::*;
use std::path::PathBuf;
use std::sync::OnceLock;
use std::time::Duration;

use super::assemble::{join_parts, load_table, stage_source};
use super::cache::{Cache, Key};
use super::files::{per_file_stages, process_files, Fate, FileOutcome, Part};
use super::lock::Lock;
use super::outcome::{FileFailure, Redo, RunReport, WithoutResult};
use super::plan::{Plan, PlannedFile};
use super::provenance::{InputHash, Provenance};
use super::publish::OutputSet;
use super::registry::ERRORS;
use super::reuse::{stage_key, table_key, unit_key};
use super::shard::{shard_units, Shard, ShardUnits};
use super::state::{FileState, StageState, State, TableState};
use crate::error::{Error, ErrorKind, Result};
use crate::schema::TableDef;
use crate::stages::{Consumes, Output, Progress, TableInputs, Tables};
use crate::table::Table;

/// How to run: the cache, dry runs, waiting for the folder's lock.
#[derive(Debug, Clone, Default)]
pub struct RunOptions {
    /// Ignore the cache and the last run: recompute everything.
    pub force: bool,
    /// Write nothing; list what would be redone, and why.
    pub dry_run: bool,
    /// How long to wait for another run on the same folder.
    pub wait: Duration,
    /// Run only this shard's share of the work, filling the cache; a later
    /// run without a shard assembles the tables.
    pub shard: Option<Shard>,
}

/// A table a stage produced (or the last run published, loaded only when
/// a stage that is redone reads it), with the raw inputs behind it.
pub(super) struct Produced {
    pub(super) def: &'static TableDef,
    pub(super) stage: usize,
    pub(super) inputs: Vec<InputHash>,
    pub(super) key: Key,
    pub(super) table: OnceLock<Table>,
    /// The published file of a reused table.
    pub(super) published: Option<PathBuf>,
}

impl Produced {
    fn table(&self) -> Result<&Table> {
        if let Some(t) = self.table.get() {
            return Ok(t);
        }
        let path = self
            .published
            .as_ref()
            .ok_or_else(|| Error::Table(format!("table {} was not computed", self.def.name)))?;
        let (t, _) = Table::read_parquet(path)?;
        Ok(self.table.get_or_init(|| t))
    }
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
    // Shards share the folder: they only add whole cache entries.
    let _lock = match opts.dry_run || opts.shard.is_some() {
        true => None,
        false => Some(Lock::take(&plan.out_dir, opts.wait)?),
    };
    let old = match opts.force {
        true => State::default(),
        false => State::load(&plan.out_dir),
    };
    let mut cache = Cache::new(&plan.out_dir, !opts.force, !opts.dry_run);
    cache.hold_parts = opts.shard.is_none() && plan.files.len() == 1;
    let mut r = Runner {
        plan,
        cache,
        old,
        new: State::default(),
        report: RunReport {
            files: plan.files.len(),
            ..Default::default()
        },
        made: Vec::new(),
        forced: opts.force,
        mine: opts.shard.map(|s| shard_units(plan, s)),
        units_used: BTreeSet::new(),
        held: Vec::new(),
    };
    if let Some(m) = &r.mine {
        r.report.files = m.files.len();
    }
    r.file_stages(progress);
    for i in 0..plan.stages.len() {
        if let Consumes::Tables(needs) = plan.stages[i].stage.consumes() {
            let skip = r.mine.as_ref().is_some_and(|m| !m.stages.contains(&i));
            if !skip {
                r.table_stage(i, &needs, progress);
            }
        }
    }
    if let Some(mine) = &r.mine {
        let mut by_stage: BTreeMap<usize, Vec<usize>> = BTreeMap::new();
        for &(s, u) in &mine.units {
            by_stage.entry(s).or_default().push(u);
        }
        for (s, units) in by_stage {
            if let Err(e) = r.run_units(s, &units, progress) {
                r.fail_stage(s, e);
            }
        }
        return Ok(r.report);
    }
    if opts.dry_run {
        r.list_deleted();
    } else {
        r.publish(command)?;
    }
    Ok(r.report)
}

pub(super) struct Runner<'a> {
    pub(super) plan: &'a Plan,
    pub(super) cache: Cache,
    pub(super) old: State,
    pub(super) new: State,
    pub(super) report: RunReport,
    pub(super) made: Vec<Produced>,
    pub(super) forced: bool,
    /// In a shard: its files and stages.
    mine: Option<ShardUnits>,
    /// Cache keys of the study runs this run used.
    units_used: BTreeSet<Key>,
    /// Fresh per-file parts the cache holds for the publish
    /// ([`Cache::hold_parts`]), with their keys.
    pub(super) held: Vec<(Key, Tables)>,
}

/// Per per-file stage: the parts of the files it took, in input order,
/// and the inputs behind them; `pending` when a dry run would read files.
#[derive(Default)]
struct Gathered {
    parts: Vec<(Key, Part)>,
    inputs: Vec<InputHash>,
    pending: bool,
}

impl Runner<'_> {
    fn file_stages(&mut self, progress: &dyn Progress) {
        let stages = per_file_stages(self.plan);
        if stages.is_empty() && self.plan.files.is_empty() {
            return;
        }
        let mut gathered: Vec<Gathered> = (0..self.plan.stages.len())
            .map(|_| Gathered::default())
            .collect();
        let only = self.mine.as_ref().map(|m| &m.files);
        let outcomes = process_files(self.plan, &self.cache, only, progress);
        let plan = self.plan;
        for (k, o) in outcomes {
            self.take_file(&plan.files[k], o, &mut gathered);
        }
        if self.mine.is_some() {
            return;
        }
        for i in stages {
            let mut g = std::mem::take(&mut gathered[i]);
            g.inputs
                .extend(self.plan.manifest.as_ref().map(|(_, h)| h.clone()));
            self.file_stage(i, g);
        }
    }

    /// Records what became of one file and hands its parts to its stages.
    fn take_file(&mut self, f: &PlannedFile, o: FileOutcome, gathered: &mut [Gathered]) {
        let source = f.path.display().to_string();
        let redone = o.redone();
        let mut state = FileState::default();
        if let Some((bytes, rkey)) = &o.content {
            state.bytes = bytes.clone();
            state.route = Some(rkey.clone());
        }
        let report = &mut self.report;
        match o.fate {
            Fate::Unreadable(e) => {
                report
                    .failures
                    .push(FileFailure::from_failure(source.clone(), "ingest", &e))
            }
            Fate::Untaken(why) if f.named => report.failures.push(FileFailure {
                message: format!("{source}: named as an input, but no stage takes it: {why}"),
                source: source.clone(),
                stage: "ingest".into(),
                kind: ErrorKind::BadInput,
            }),
            Fate::Untaken(why) => report.unrouted.push((source.clone(), why)),
            Fate::Pending => {
                let reason = self.file_reason(&source, &state.bytes);
                self.report.redo.push(Redo::file(&source, reason));
                // The stages that took it last time; a new file, any.
                let before = self.old.files.get(&source).map(|f| &f.parts);
                for i in per_file_stages(self.plan) {
                    let name = self.plan.stages[i].stage.name();
                    if before.is_none_or(|p| p.is_empty() || p.contains_key(name)) {
                        gathered[i].pending = true;
                    }
                }
            }
            Fate::Taken(taken) => {
                let mut all_ok = true;
                for t in taken {
                    let name = self.plan.stages[t.stage].stage.name();
                    state.parts.insert(name.into(), t.key.clone());
                    let failure = match &t.part {
                        Part::Fresh(Err(e)) => Some(FileFailure::new(source.clone(), name, e)),
                        Part::Cached(Err(e)) => {
                            Some(FileFailure::from_failure(source.clone(), name, e))
                        }
                        _ => None,
                    };
                    if let Part::Fresh(r) = &t.part {
                        self.hold(&t.key, r);
                    }
                    let g = &mut gathered[t.stage];
                    match failure {
                        Some(ff) => {
                            all_ok = false;
                            self.report.failures.push(ff);
                        }
                        None => g.inputs.extend(o.hash.clone()),
                    }
                    g.parts.push((t.key, t.part));
                }
                if all_ok {
                    self.report.succeeded += 1;
                    match redone {
                        true => self.report.files_processed += 1,
                        false => self.report.files_reused += 1,
                    }
                }
            }
        }
        if o.content.is_some() {
            self.new.files.insert(source, state);
        }
    }

    /// Joins a per-file stage's parts and assembles its output, unless the
    /// last run published the same.
    fn file_stage(&mut self, i: usize, g: Gathered) {
        let stage = self.plan.stages[i].stage.as_ref();
        let mut kb = stage_key(stage);
        for (k, _) in &g.parts {
            kb = kb.part(&k.0);
        }
        let key = kb.finish();
        if g.pending {
            self.would_redo(i, key, "new or changed input files", g.inputs);
            return;
        }
        if self.reuse(i, &key, &g.inputs) {
            return;
        }
        if !self.cache.write {
            let why = self.stage_reason(i, &key);
            self.would_redo(i, key, why, g.inputs);
            return;
        }
        let defs = stage.produces();
        let parts: Result<Vec<Tables>> = g
            .parts
            .into_iter()
            .filter_map(|(k, part)| match part {
                Part::Fresh(Ok(t)) => Some(Ok(t)),
                Part::Cached(Ok(())) => Some(self.cache.load_part(&k, &defs)),
                _ => None,
            })
            .collect();
        // The parts were checked when made; their join holds to the same
        // schemas. Only a table the stage's assembly changed is checked.
        let output = parts.and_then(|p| join_parts(stage, p)).and_then(|t| {
            let joined = t.clone();
            let out = stage.assemble(t)?;
            check_changed(&out, &joined)?;
            Ok(out)
        });
        self.report.stages_run.push(stage.name().into());
        self.record(i, key, output, g.inputs);
    }

    /// A table stage: its inputs gathered, then reused, or run.
    fn table_stage(&mut self, i: usize, needs: &[crate::stages::Need], progress: &dyn Progress) {
        let plan = self.plan;
        let ps = &plan.stages[i];
        let mut kb = stage_key(ps.stage.as_ref());
        let mut inputs = ps.stage.own_inputs();
        for h in &inputs {
            kb = kb.part(&h.sha256);
        }
        let mut sources: Vec<(&'static str, Source)> = Vec::new();
        for need in needs {
            let source = match ps.table_files.get(need.table.name) {
                Some(path) => match InputHash::of_file(path) {
                    Ok(h) => {
                        kb = kb.part(&h.sha256);
                        Source::File(path.clone())
                    }
                    Err(e) => return self.fail_stage(i, e),
                },
                None => match self.made.iter().position(|p| p.def == need.table) {
                    Some(j) => {
                        kb = kb.part(&self.made[j].key.0);
                        inputs.extend(self.made[j].inputs.clone());
                        Source::Made(j)
                    }
                    None if need.required => {
                        return self.fail_stage(
                            i,
                            Error::NotApplicable(format!(
                            "not run: its input table '{}' was not produced (see the errors above)",
                            need.table.name
                        )),
                        )
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
        if self.reuse(i, &key, &inputs) {
            return;
        }
        if !self.cache.write {
            let why = self.stage_reason(i, &key);
            self.would_redo(i, key, why, inputs);
            return;
        }
        if let Some(cached) = self.cache.stage(&key, &ps.stage.produces()) {
            self.report.stages_reused.push(ps.stage.name().into());
            return self.record(i, key, cached, inputs);
        }
        // A table stage's tables are checked here, where they are made (a
        // stage output from the cache was checked when it was made).
        let output = self
            .load_sources(&sources, &mut inputs)
            .and_then(|available| {
                let tables = TableInputs::new(&available);
                let n_units = ps.stage.unit_costs().len();
                if n_units == 0 {
                    progress.begin(ps.stage.name(), ps.stage.units());
                    return ps.stage.run_tables(&tables, progress);
                }
                let all: Vec<usize> = (0..n_units).collect();
                let results = self.run_units(i, &all, progress)?;
                ps.stage.run_tables_from_units(&tables, results)
            })
            .and_then(|o| check_changed(&o, &Vec::new()).map(|_| o));
        if let Ok(o) = &output {
            let _ = self.cache.put_stage(&key, o);
        }
        self.report.stages_run.push(ps.stage.name().into());
        self.record(i, key, output, inputs);
    }

    /// Units of a table stage (runs of a study): from the cache, or run in
    /// parallel and cached; their results in the order of `units`.
    fn run_units(
        &mut self,
        i: usize,
        units: &[usize],
        progress: &dyn Progress,
    ) -> Result<Vec<Vec<u8>>> {
        let stage = self.plan.stages[i].stage.as_ref();
        let keys: Vec<Key> = units.iter().map(|&u| unit_key(stage, u)).collect();
        progress.begin(stage.name(), units.len());
        let cache = &self.cache;
        let results: Vec<Result<(Vec<u8>, bool)>> = units
            .par_iter()
            .zip(&keys)
            .map(|(&u, key)| {
                let r = match cache.unit(key) {
                    Some(b) => Ok((b, false)),
                    None => stage.run_unit(u).map(|b| {
                        let _ = cache.put_unit(key, &b);
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
        sources: &[(&'static str, Source)],
        inputs: &mut Vec<InputHash>,
    ) -> Result<BTreeMap<String, Table>> {
        let mut available = BTreeMap::new();
        for (name, source) in sources {
            let t = match source {
                Source::File(path) => {
                    let (t, ins) = load_table(path)?;
                    inputs.extend(ins);
                    t
                }
                Source::Made(j) => self.made[*j].table()?.clone(),
            };
            available.insert(name.to_string(), t);
        }
        Ok(available)
    }

    fn fail_stage(&mut self, i: usize, e: Error) {
        let ps = &self.plan.stages[i];
        let source = stage_source(self.plan, ps);
        self.report
            .failures
            .push(FileFailure::new(source, ps.stage.name(), &e));
    }

    /// Takes a stage's output, its tables checked: its tables, rows without
    /// a result and notes; or its failure.
    fn record(&mut self, i: usize, key: Key, output: Result<Output>, inputs: Vec<InputHash>) {
        let name = self.plan.stages[i].stage.name();
        let output = match output {
            Ok(o) => o,
            Err(e) => return self.fail_stage(i, e),
        };
        let inputs = sorted(inputs);
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
                key: key.clone(),
                without_result: output.without_result,
                notes: output.notes,
                tables: output.tables.iter().map(|(d, _)| d.name.into()).collect(),
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
            });
        }
    }

    /// Publishes the set: the tables that changed written, the others kept,
    /// `errors.parquet`; then saves the state and drops cache entries that
    /// nothing uses any more.
    fn publish(&mut self, command: &str) -> Result<()> {
        let dir = &self.plan.out_dir;
        let mut set = OutputSet::begin(dir)?;
        for p in &self.made {
            let path = dir.join(format!("{}.parquet", p.def.name));
            if p.published.is_some() {
                set.keep(p.def.name)?;
                self.report.kept.push(path);
                continue;
            }
            let stage = &self.plan.stages[p.stage].stage;
            let prov = Provenance {
                command: command.into(),
                stage: stage.name().into(),
                inputs: p.inputs.clone(),
                parameters: serde_json::json!({ stage.name(): stage.parameters() }),
                references: stage.references(),
                pipeline: self.plan.spec_json.clone(),
            };
            set.write_table(p.def, p.table()?, &prov)?;
            self.report.outputs.push(path);
        }
        let all = sorted(self.made.iter().flat_map(|p| p.inputs.clone()).collect());
        let prov = Provenance {
            command: command.into(),
            stage: "pipeline".into(),
            inputs: all,
            pipeline: self.plan.spec_json.clone(),
            ..Default::default()
        };
        let errors = self.report.errors_table()?;
        set.write_table(&ERRORS, &errors, &prov)?;
        self.report
            .outputs
            .push(dir.join(format!("{}.parquet", ERRORS.name)));
        self.write_report(&mut set, errors)?;
        set.commit()?;
        self.store_held();
        for p in self.made.iter().filter(|p| p.published.is_none()) {
            let path = dir.join(format!("{}.parquet", p.def.name));
            if let Some(s) = TableState::of_file(&path, p.key.clone()) {
                self.new.tables.insert(p.def.name.into(), s);
            }
        }
        self.new.save(dir)?;
        let stages = self.new.stages.values().map(|s| s.key.clone()).collect();
        let routes = self
            .new
            .files
            .values()
            .filter_map(|f| f.route.clone())
            .collect();
        let parts = self
            .new
            .files
            .values()
            .flat_map(|f| f.parts.values().cloned())
            .collect();
        self.cache
            .retain(&routes, &parts, &stages, &self.units_used);
        Ok(())
    }
}

impl Runner<'_> {
    /// The warnings of the set (rows whose status is not `ok`) and, unless
    /// the pipeline says `report = false`, `report.html` from the set's
    /// tables (only those it reads or that have a status: never the traces).
    fn write_report(&mut self, set: &mut OutputSet, errors: Table) -> Result<()> {
        let mut tables = BTreeMap::from([(ERRORS.name.to_string(), errors)]);
        for p in &self.made {
            if p.def.in_report() || p.def.has_status() {
                tables.insert(p.def.name.to_string(), p.table()?.clone());
            }
        }
        self.report.warnings = crate::report::doubts(&tables)?;
        if self.plan.report {
            super::report::write(set, &self.plan.out_dir, &tables)?;
            let path = self.plan.out_dir.join(super::report::REPORT);
            self.report.outputs.push(path);
        }
        Ok(())
    }
}

/// Where a table stage's input comes from.
enum Source {
    File(PathBuf),
    Made(usize),
}

/// Checks each table of `out` against its schema, but those passed on as
/// they are from `checked` (tables already checked: the same columns, not
/// equal ones), so that a defect fails its stage only and no table is
/// checked twice.
fn check_changed(out: &Output, checked: &Tables) -> Result<()> {
    for (def, table) in &out.tables {
        let kept = checked.iter().any(|(d, t)| d == def && t.is_same(table));
        if !kept {
            def.check(table)?;
        }
    }
    Ok(())
}

pub(super) fn sorted(mut v: Vec<InputHash>) -> Vec<InputHash> {
    v.sort();
    v.dedup();
    v
}
