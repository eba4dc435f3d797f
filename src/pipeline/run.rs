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
use std::path::{Path, PathBuf};
use std::sync::OnceLock;
use std::time::Duration;

use super::cache::{Cache, Key, KeyBuilder};
use super::files::{per_file_stages, process_files, Fate, FileOutcome, Part};
use super::lock::Lock;
use super::outcome::{FileFailure, Redo, RunReport, WithoutResult};
use super::plan::{Plan, PlannedFile, PlannedStage};
use super::provenance::{InputHash, Provenance};
use super::publish::OutputSet;
use super::shard::{assign, file_cost, stage_cost, Shard};
use super::state::{FileState, StageState, State, TableState};
use crate::error::{Error, ErrorKind, Result};
use crate::schema;
use crate::stages::{Consumes, Output, Progress, StagePlan, TableInputs, Tables};
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
struct Produced {
    name: &'static str,
    stage: usize,
    inputs: Vec<InputHash>,
    key: Key,
    table: OnceLock<Table>,
    /// The published file of a reused table.
    published: Option<PathBuf>,
}

impl Produced {
    fn table(&self) -> Result<&Table> {
        if let Some(t) = self.table.get() {
            return Ok(t);
        }
        let path = self
            .published
            .as_ref()
            .ok_or_else(|| Error::Table(format!("table {} was not computed", self.name)))?;
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
    let mut r = Runner {
        plan,
        cache: Cache::new(&plan.out_dir, !opts.force, !opts.dry_run),
        old,
        new: State::default(),
        report: RunReport {
            files: plan.files.len(),
            ..Default::default()
        },
        made: Vec::new(),
        forced: opts.force,
        mine: opts.shard.map(|s| shard_units(plan, s)),
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
    if r.mine.is_some() {
        return Ok(r.report);
    }
    if opts.dry_run {
        r.list_deleted();
    } else {
        r.publish(command)?;
    }
    Ok(r.report)
}

struct Runner<'a> {
    plan: &'a Plan,
    cache: Cache,
    old: State,
    new: State,
    report: RunReport,
    made: Vec<Produced>,
    forced: bool,
    /// In a shard: its files and stages.
    mine: Option<ShardUnits>,
}

/// A shard's work: input files (indices into the plan's files) and the
/// simulation stages that read no table of the run.
struct ShardUnits {
    files: BTreeSet<usize>,
    stages: BTreeSet<usize>,
}

/// Splits the plan's work units between shards by their estimated cost.
fn shard_units(plan: &Plan, shard: Shard) -> ShardUnits {
    let produced: BTreeSet<&str> = plan
        .stages
        .iter()
        .flat_map(|s| s.stage.produces())
        .collect();
    let standalone: Vec<usize> = (0..plan.stages.len())
        .filter(|&i| match plan.stages[i].stage.consumes() {
            Consumes::Tables(needs) => needs.iter().all(|n| !produced.contains(n.table)),
            Consumes::Files(_) => false,
        })
        .collect();
    let mut costs: Vec<f64> = plan
        .files
        .iter()
        .map(|f| file_cost(std::fs::metadata(&f.path).map_or(0, |m| m.len())))
        .collect();
    costs.extend(
        standalone
            .iter()
            .map(|&i| stage_cost(plan.stages[i].stage.units())),
    );
    let n = plan.files.len();
    let mine = assign(&costs, shard);
    ShardUnits {
        files: mine.iter().copied().filter(|&u| u < n).collect(),
        stages: mine
            .iter()
            .filter(|&&u| u >= n)
            .map(|&u| standalone[u - n])
            .collect(),
    }
}

/// Per per-file stage: the parts of the files it took, in input order,
/// and the inputs behind them; `pending` when a dry run would read files.
#[derive(Default)]
struct Gathered {
    parts: Vec<(Key, Part)>,
    inputs: Vec<InputHash>,
    pending: bool,
}

fn table_key(stage_key: &Key, table: &str) -> Key {
    KeyBuilder::new("table")
        .part(&stage_key.0)
        .part(table)
        .finish()
}

fn stage_key(stage: &dyn StagePlan) -> KeyBuilder {
    KeyBuilder::new("stage")
        .part(stage.name())
        .part(&stage.parameters().to_string())
        .part(&stage.produces().join(","))
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

    /// Why a dry run would read a file.
    fn file_reason(&self, path: &str, bytes: &str) -> &'static str {
        match self.old.files.get(path) {
            _ if self.forced => "forced",
            None => "new file",
            Some(old) if old.bytes != bytes => "changed file",
            Some(_) => "stage parameters, manifest row or reading options changed",
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
        let names = stage.produces();
        let parts: Result<Vec<Tables>> = g
            .parts
            .into_iter()
            .filter_map(|(k, part)| match part {
                Part::Fresh(Ok(t)) => Some(Ok(t)),
                Part::Cached(Ok(())) => Some(self.cache.load_part(&k, &names)),
                _ => None,
            })
            .collect();
        let output = parts
            .and_then(|p| join_parts(stage, p))
            .and_then(|t| stage.assemble(t));
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
            let source = match ps.table_files.get(need.table) {
                Some(path) => match InputHash::of_file(path) {
                    Ok(h) => {
                        kb = kb.part(&h.sha256);
                        Source::File(path.clone())
                    }
                    Err(e) => return self.fail_stage(i, e),
                },
                None => match self.made.iter().position(|p| p.name == need.table) {
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
                            need.table
                        )),
                        )
                    }
                    None => {
                        kb = kb.part("absent");
                        continue;
                    }
                },
            };
            sources.push((need.table, source));
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
        let output = self
            .load_sources(&sources, &mut inputs)
            .and_then(|available| {
                progress.begin(ps.stage.name(), ps.stage.units());
                ps.stage.run_tables(&TableInputs::new(&available), progress)
            });
        if let Ok(o) = &output {
            let _ = self.cache.put_stage(&key, o);
        }
        self.report.stages_run.push(ps.stage.name().into());
        self.record(i, key, output, inputs);
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

    /// Reuses stage `i` when the last run published it with this key and
    /// its tables are still the files it wrote.
    fn reuse(&mut self, i: usize, key: &Key, inputs: &[InputHash]) -> bool {
        let stage = self.plan.stages[i].stage.as_ref();
        let Some(old) = self.old.stages.get(stage.name()) else {
            return false;
        };
        let out = &self.plan.out_dir;
        let names = stage.produces();
        let intact = names
            .iter()
            .all(|t| self.old.published(out, t, &table_key(key, t)));
        if old.key != *key || !intact {
            return false;
        }
        let old = old.clone();
        self.report.stages_reused.push(stage.name().into());
        self.report.notes.extend(old.notes.clone());
        if old.without_result > 0 {
            self.report.without_result.push(WithoutResult {
                stage: stage.name().into(),
                rows: old.without_result,
            });
        }
        for t in names {
            self.made.push(Produced {
                name: t,
                stage: i,
                inputs: sorted(inputs.to_vec()),
                key: table_key(key, t),
                table: OnceLock::new(),
                published: Some(out.join(format!("{t}.parquet"))),
            });
            if let Some(s) = self.old.tables.get(t) {
                self.new.tables.insert(t.into(), s.clone());
            }
        }
        self.new.stages.insert(stage.name().into(), old);
        true
    }

    /// Why a dry run would redo stage `i`.
    fn stage_reason(&self, i: usize, key: &Key) -> &'static str {
        match self.old.stages.get(self.plan.stages[i].stage.name()) {
            _ if self.forced => "forced",
            None => "not run before into this folder",
            Some(old) if old.key != *key => "its inputs or parameters changed",
            Some(_) => "its tables were changed or removed",
        }
    }

    /// In a dry run: lists the stage, and stands its tables in for the
    /// stages after it (with the new key, so that they are redone too).
    fn would_redo(&mut self, i: usize, key: Key, why: &str, inputs: Vec<InputHash>) {
        let stage = self.plan.stages[i].stage.as_ref();
        self.report.redo.push(Redo::stage(stage.name(), why));
        for t in stage.produces() {
            self.made.push(Produced {
                name: t,
                stage: i,
                inputs: inputs.clone(),
                key: table_key(&key, t),
                table: OnceLock::new(),
                published: None,
            });
        }
    }

    fn fail_stage(&mut self, i: usize, e: Error) {
        let ps = &self.plan.stages[i];
        let source = stage_source(self.plan, ps);
        self.report
            .failures
            .push(FileFailure::new(source, ps.stage.name(), &e));
    }

    /// Takes a stage's output: its tables (each checked against its schema
    /// now, so that a defect fails this stage only), rows without a result
    /// and notes; or its failure.
    fn record(&mut self, i: usize, key: Key, output: Result<Output>, inputs: Vec<InputHash>) {
        let name = self.plan.stages[i].stage.name();
        let checked = output.and_then(|o| {
            for (t, table) in &o.tables {
                schema::schema(t)?.check(table)?;
            }
            Ok(o)
        });
        let output = match checked {
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
                tables: output.tables.iter().map(|(t, _)| t.to_string()).collect(),
            },
        );
        for (t, table) in output.tables {
            self.made.push(Produced {
                name: t,
                stage: i,
                inputs: inputs.clone(),
                key: table_key(&key, t),
                table: OnceLock::from(table),
                published: None,
            });
        }
    }

    /// In a dry run: inputs the last run had that are gone.
    fn list_deleted(&mut self) {
        let now: BTreeSet<String> = self
            .plan
            .files
            .iter()
            .map(|f| f.path.display().to_string())
            .collect();
        for path in self.old.files.keys().filter(|p| !now.contains(*p)) {
            self.report
                .redo
                .push(Redo::file(path, "deleted: its rows leave the tables"));
        }
    }

    /// Publishes the set: the tables that changed written, the others kept,
    /// `errors.parquet`; then saves the state and drops cache entries that
    /// nothing uses any more.
    fn publish(&mut self, command: &str) -> Result<()> {
        let dir = &self.plan.out_dir;
        let mut set = OutputSet::begin(dir)?;
        for p in &self.made {
            let path = dir.join(format!("{}.parquet", p.name));
            if p.published.is_some() {
                set.keep(p.name)?;
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
            set.write_table(p.name, p.table()?, &prov)?;
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
        set.write_table("errors", &self.report.errors_table()?, &prov)?;
        self.report.outputs.push(dir.join("errors.parquet"));
        set.commit()?;
        for p in self.made.iter().filter(|p| p.published.is_none()) {
            let path = dir.join(format!("{}.parquet", p.name));
            if let Some(s) = TableState::of_file(&path, p.key.clone()) {
                self.new.tables.insert(p.name.into(), s);
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
        self.cache.retain(&routes, &parts, &stages);
        Ok(())
    }
}

/// Where a table stage's input comes from.
enum Source {
    File(PathBuf),
    Made(usize),
}

fn sorted(mut v: Vec<InputHash>) -> Vec<InputHash> {
    v.sort();
    v.dedup();
    v
}

/// Joins the rows of every file per table, in input order; a table no
/// file contributed to is empty, with its schema's columns.
fn join_parts(stage: &dyn StagePlan, parts: Vec<Tables>) -> Result<Tables> {
    let mut by_name: BTreeMap<&'static str, Vec<Table>> = BTreeMap::new();
    for part in parts {
        for (name, t) in part {
            by_name.entry(name).or_default().push(t);
        }
    }
    stage
        .produces()
        .into_iter()
        .map(|name| {
            let joined = Table::concat(by_name.remove(name).unwrap_or_default())?;
            let t = match joined {
                Some(t) => t,
                None => schema::schema(name)?.empty_table()?,
            };
            Ok((name, t))
        })
        .collect()
}

/// A table given as a file, with the raw inputs its metadata names and the
/// file itself.
fn load_table(path: &Path) -> Result<(Table, Vec<InputHash>)> {
    let mut inputs = vec![InputHash::of_file(path)?];
    let table = if path
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("parquet"))
    {
        let (t, kv) = Table::read_parquet(path)?;
        inputs.extend(Provenance::inputs_from(&kv));
        t
    } else {
        crate::ingest::csv_table::read_table_file(path)?
    };
    Ok((table, inputs))
}

/// What a stage's failure is reported against: the file it read itself,
/// else the first table file it was given, else its first input table.
fn stage_source(plan: &Plan, ps: &PlannedStage) -> String {
    if let Some(h) = ps.stage.own_inputs().first() {
        return h.path.clone();
    }
    if let Some(p) = ps.table_files.values().next() {
        return p.display().to_string();
    }
    match ps.stage.consumes() {
        Consumes::Tables(needs) if !needs.is_empty() => plan
            .out_dir
            .join(format!("{}.parquet", needs[0].table))
            .display()
            .to_string(),
        _ => format!("stage {}", ps.stage.name()),
    }
}
