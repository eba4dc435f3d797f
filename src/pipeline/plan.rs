//! The validated plan: every path resolved and checked, every stage's
//! settings validated by the stage itself, every unit and format name
//! known, and the run order derived from what each stage needs — all
//! before any computation starts.

use rayon::prelude::*;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use crate::error::{Error, Result};
use crate::hash::InputHash;
use crate::ingest::companion;
use crate::ingest::manifest::Manifest;
use crate::ingest::READERS;
use crate::paths::clean_path;
use crate::stages::{self, Consumes, PlanContext, StagePlan};
use crate::units::parse_unit;

use super::file_options::{glob_files, hits, override_pattern, OptionsFor};
pub use super::planned::{FileOptions, PlannedFile, PlannedStage};
use super::spec::{IngestSpec, PipelineSpec};

/// A validated plan.
pub struct Plan {
    /// Inputs, sorted by path (the order of every output).
    pub files: Vec<PlannedFile>,
    /// The manifest, read and parsed, with its hash.
    pub manifest: Option<(Manifest, InputHash)>,
    /// Output folder.
    pub out_dir: PathBuf,
    /// Stages in run order: per-file stages first, then every table stage
    /// after the stages whose tables it reads.
    pub stages: Vec<PlannedStage>,
    /// The spec, for provenance.
    pub spec_json: serde_json::Value,
    /// Write `report.html` with the set.
    pub report: bool,
    /// What the configuration leaves in doubt without being wrong (a
    /// manifest row no input file matches), for the user to see.
    pub warnings: Vec<String>,
}

fn check_options(o: &FileOptions, context: &str) -> Result<()> {
    if let Some(f) = &o.ingest.format {
        if !READERS.iter().any(|r| r.name() == f) {
            let names: Vec<_> = READERS.iter().map(|r| r.name()).collect();
            return Err(Error::Config(format!(
                "{context}: unknown format '{f}'; known: {}",
                names.join(", ")
            )));
        }
    }
    for (col, unit) in &o.ingest.units {
        if parse_unit(unit).is_none() {
            return Err(Error::Config(format!(
                "{context}: unknown unit '{unit}' for column '{col}'"
            )));
        }
    }
    if let Some(d) = o.ingest.decimal {
        if d != '.' && d != ',' {
            return Err(Error::Config(format!(
                "{context}: decimal mark must be '.' or ',', got '{d}'"
            )));
        }
    }
    Ok(())
}

/// Every override's glob matches an input file: one that matches none is
/// a typo that would leave the files it meant read without it.
fn check_overrides_match(spec: &IngestSpec, files: &[PlannedFile]) -> Result<()> {
    for ov in &spec.overrides {
        let glob = ov.files.as_deref().unwrap_or("");
        let pat = override_pattern(glob)?;
        if !files.iter().any(|f| hits(&pat, &f.path)) {
            return Err(Error::Config(format!(
                "[[ingest.override]] files = '{glob}' matches none of the {} input files \
                 (matched against each file's name and path)",
                files.len()
            )));
        }
    }
    Ok(())
}

/// The manifest rows that match no input file, as warnings naming the row
/// (an error with `[input] strict = true`).
fn unmatched_rows(m: &Manifest, files: &[PlannedFile], strict: bool) -> Result<Vec<String>> {
    let paths: Vec<&Path> = files.iter().map(|f| f.path.as_path()).collect();
    let notes: Vec<String> = m
        .unmatched(&paths)
        .map(|r| {
            format!(
                "{}:{}: the sample row for '{}' matches no input file",
                m.path.display(),
                r.line,
                r.key
            )
        })
        .collect();
    match notes.first() {
        Some(first) if strict => Err(Error::Config(format!(
            "{first} ([input] strict = true; {} such rows)",
            notes.len()
        ))),
        _ => Ok(notes),
    }
}

/// Checks the shape of `[ingest]`: no glob on the defaults, a glob on every
/// override, no nested overrides.
fn check_ingest_spec(spec: &IngestSpec) -> Result<()> {
    if spec.files.is_some() {
        return Err(Error::Config(
            "[ingest] takes no 'files'; use [[ingest.override]] for a subset".into(),
        ));
    }
    for ov in &spec.overrides {
        if ov.files.is_none() {
            return Err(Error::Config(
                "every [[ingest.override]] needs 'files', a glob".into(),
            ));
        }
        if !ov.overrides.is_empty() {
            return Err(Error::Config(
                "[[ingest.override]] tables cannot nest".into(),
            ));
        }
    }
    Ok(())
}

/// Whether a pattern has glob characters (else it names one file).
pub fn is_glob(pattern: &str) -> bool {
    pattern.contains(['*', '?', '['])
}

/// Expands globs (relative to `base`) into a sorted, de-duplicated list of
/// files, each with whether it was named by a literal path. A pattern that
/// matches nothing is an error: a typo must not silently drop a folder from
/// a batch.
pub fn expand_inputs(patterns: &[String], base: &Path) -> Result<Vec<(PathBuf, bool)>> {
    let mut files: Vec<(PathBuf, bool)> = Vec::new();
    for p in patterns {
        let full = clean_path(&if Path::new(p).is_absolute() {
            PathBuf::from(p)
        } else {
            base.join(p)
        });
        let text = full.to_string_lossy().to_string();
        let matches =
            glob_files(&text).map_err(|e| Error::Config(format!("input glob '{p}': {e}")))?;
        if matches.is_empty() {
            return Err(Error::Config(format!(
                "input '{p}' matches no file (looked for {text})"
            )));
        }
        files.extend(matches.into_iter().map(|m| (m, !is_glob(p))));
    }
    // One pattern's files are sorted and distinct already.
    if patterns.len() > 1 {
        files.sort();
        // A file both named and matched by a glob counts as named.
        files.dedup_by(|b, a| {
            let same = a.0 == b.0;
            a.1 |= same && b.1;
            same
        });
    }
    Ok(files)
}

/// The pipeline's own keys in a stage's table, taken out before the stage
/// sees it: `files` (per-file stages) and `inputs` (table stages).
struct StageKeys {
    files: Vec<String>,
    inputs: BTreeMap<String, String>,
}

fn take_stage_keys(name: &str, table: &mut toml::Table) -> Result<StageKeys> {
    let bad = |key: &str, e: toml::de::Error| Error::Config(format!("[{name}] {key}: {e}"));
    let files = match table.remove("files") {
        Some(v) => v.try_into().map_err(|e| bad("files", e))?,
        None => Vec::new(),
    };
    let inputs = match table.remove("inputs") {
        Some(v) => v.try_into().map_err(|e| bad("inputs", e))?,
        None => BTreeMap::new(),
    };
    Ok(StageKeys { files, inputs })
}

impl Plan {
    /// Validates a spec; relative paths are taken from `base` (the folder of
    /// the pipeline file).
    pub fn from_spec(spec: &PipelineSpec, base: &Path) -> Result<Plan> {
        check_ingest_spec(&spec.ingest)?;
        let ctx = PlanContext {
            base: base.to_path_buf(),
            traces: spec.output.traces,
            figures: spec.output.report,
        };
        let mut planned = Vec::new();
        let mut stage_globs = Vec::new();
        for name in &spec.stages {
            let stage = stages::find(name)
                .ok_or_else(|| Error::Config(format!("unknown stage '{name}'")))?;
            let mut table = spec.settings.get(name).cloned().unwrap_or_default();
            let keys = take_stage_keys(name, &mut table)?;
            let plan = stage.plan(table, &ctx)?;
            let table_files = check_stage_keys(plan.as_ref(), &keys, &ctx)?;
            stage_globs.push(keys.files);
            planned.push(PlannedStage::new(plan, table_files));
        }
        let order = super::order::run_order(&planned)?;
        let (planned, stage_globs) = reorder(planned, stage_globs, &order);
        let out_dir = Plan::out_dir_of(spec, base);
        let manifest_path = spec
            .input
            .samples
            .as_ref()
            .map(|s| clean_path(&base.join(s)));
        let mut files = plan_files(spec, base, &stage_globs)?;
        // A glob over the lab folder also matches the manifest and earlier
        // outputs: those are not inputs unless named.
        let out_text = out_dir.as_os_str().as_encoded_bytes();
        files.retain(|f| {
            // Both paths are clean: one under the other starts with its
            // bytes (checked first: comparing paths costs far more).
            let under = |p: &Path| {
                p.as_os_str().as_encoded_bytes().starts_with(out_text) && p.starts_with(&out_dir)
            };
            f.named || !(Some(&f.path) == manifest_path.as_ref() || under(&f.path))
        });
        if files.is_empty() && planned.iter().any(|s| takes_files(s.stage.as_ref())) {
            return Err(Error::Config(
                "the pipeline has a per-file stage but no input files: give [input] files".into(),
            ));
        }
        // Read once: parsed and hashed from the same bytes.
        let manifest = match &manifest_path {
            Some(p) => {
                let bytes = std::fs::read(p).map_err(|e| Error::io(p, e))?;
                Some((
                    Manifest::from_bytes(p, &bytes)?,
                    InputHash::of_bytes(p, &bytes),
                ))
            }
            None => None,
        };
        check_overrides_match(&spec.ingest, &files)?;
        super::column_keys::check(&spec.ingest, &files, |glob, p| {
            override_pattern(glob).is_ok_and(|pat| hits(&pat, p))
        })?;
        let mut warnings = Vec::new();
        if let Some((m, _)) = &manifest {
            let paths: Vec<&Path> = files.iter().map(|f| f.path.as_path()).collect();
            m.check_unambiguous(&paths)?;
            warnings = unmatched_rows(m, &files, spec.input.strict)?;
        }
        Ok(Plan {
            warnings,
            files,
            manifest,
            out_dir,
            stages: planned,
            spec_json: serde_json::to_value(spec).unwrap_or_default(),
            report: spec.output.report,
        })
    }

    /// Reads and validates a pipeline file.
    pub fn from_file(path: &Path) -> Result<Plan> {
        let (spec, base) = Plan::spec_of(path)?;
        Plan::from_spec(&spec, &base)
    }

    /// A pipeline file's spec and the folder its paths are relative to.
    pub fn spec_of(path: &Path) -> Result<(PipelineSpec, PathBuf)> {
        let text = std::fs::read_to_string(path).map_err(|e| Error::io(path, e))?;
        let spec = PipelineSpec::from_toml(&text, path)?;
        let base = path
            .parent()
            .filter(|p| !p.as_os_str().is_empty())
            .unwrap_or(Path::new("."));
        Ok((spec, base.to_path_buf()))
    }

    /// The output folder `spec` names, from `base`.
    pub fn out_dir_of(spec: &PipelineSpec, base: &Path) -> PathBuf {
        clean_path(&base.join(&spec.output.dir))
    }

    /// The stages' plans, in run order.
    pub fn stage_plans(&self) -> Vec<&dyn StagePlan> {
        self.stages.iter().map(|s| s.stage.as_ref()).collect()
    }

    /// The sample manifest, if the pipeline has one.
    pub fn manifest(&self) -> Option<&Manifest> {
        self.manifest.as_ref().map(|(m, _)| m)
    }
}

fn takes_files(s: &dyn StagePlan) -> bool {
    matches!(s.consumes(), Consumes::Files(_))
}

/// Checks `files` and `inputs` against what the stage consumes; returns the
/// input tables given as files, resolved.
fn check_stage_keys(
    stage: &dyn StagePlan,
    keys: &StageKeys,
    ctx: &PlanContext,
) -> Result<BTreeMap<String, PathBuf>> {
    let name = stage.name();
    let needs = match stage.consumes() {
        Consumes::Files(_) if !keys.inputs.is_empty() => {
            return Err(Error::Config(format!(
                "[{name}] inputs: stage '{name}' reads files, not tables; use 'files'"
            )))
        }
        Consumes::Files(_) => return Ok(BTreeMap::new()),
        Consumes::Tables(_) if !keys.files.is_empty() => {
            return Err(Error::Config(format!(
                "[{name}] files: stage '{name}' reads tables, not input files; use inputs = {{ table = \"file\" }}"
            )))
        }
        Consumes::Tables(needs) => needs,
    };
    let mut out = BTreeMap::new();
    for (table, file) in &keys.inputs {
        if !needs.iter().any(|n| n.table.name == table) {
            let known: Vec<_> = needs.iter().map(|n| n.table.name).collect();
            return Err(Error::Config(format!(
                "[{name}] inputs: stage '{name}' reads no table '{table}'; it reads {known:?}"
            )));
        }
        let path = ctx.path(file);
        if !path.is_file() {
            return Err(Error::Config(format!(
                "[{name}] inputs: {table} = '{file}': no such file ({})",
                path.display()
            )));
        }
        out.insert(table.clone(), path);
    }
    Ok(out)
}

fn reorder(
    planned: Vec<PlannedStage>,
    globs: Vec<Vec<String>>,
    order: &[usize],
) -> (Vec<PlannedStage>, Vec<Vec<String>>) {
    let mut slots: Vec<Option<(PlannedStage, Vec<String>)>> =
        planned.into_iter().zip(globs).map(Some).collect();
    order
        .iter()
        .map(|&i| slots[i].take().expect("run_order is a permutation"))
        .unzip()
}

/// Every input file with its options: the `[input]` globs, then each
/// per-file stage's own `files` (which route those files to that stage).
fn plan_files(
    spec: &PipelineSpec,
    base: &Path,
    stage_globs: &[Vec<String>],
) -> Result<Vec<PlannedFile>> {
    // Sorted by path, each once (a map of paths would compare paths
    // n log n times: most of the plan over a large folder).
    let mut found: Vec<(PathBuf, (bool, Vec<usize>))> = expand_inputs(&spec.input.files, base)?
        .into_iter()
        .map(|(path, named)| (path, (named, Vec::new())))
        .collect();
    let mut by_stage = false;
    for (i, globs) in stage_globs.iter().enumerate() {
        if globs.is_empty() {
            continue;
        }
        by_stage = true;
        for (path, _) in expand_inputs(globs, base)? {
            found.push((path, (true, vec![i])));
        }
    }
    if by_stage {
        found.sort_by(|a, b| a.0.cmp(&b.0));
        found.dedup_by(|b, a| {
            let same = a.0 == b.0;
            if same {
                a.1 .0 |= b.1 .0;
                a.1 .1.append(&mut b.1 .1);
            }
            same
        });
    }
    let paths: Vec<&Path> = found.iter().map(|(p, _)| p.as_path()).collect();
    let inputs = companion::Inputs::new(&paths);
    // In parallel: each `.tx3` or `.TSX` input is opened to read its head.
    let companions: Vec<Option<PathBuf>> = paths
        .par_iter()
        .map(|p| companion::data_file_of(p, &inputs).map(Path::to_path_buf))
        .collect();
    let mut options = OptionsFor::new(&spec.ingest)?;
    found
        .into_iter()
        .zip(companions)
        .map(|((path, (named, forced)), companion_of)| {
            let (options, options_key) = options.of(&path, |o| {
                check_options(o, &format!("options for {}", path.display()))
            })?;
            Ok(PlannedFile {
                // Formatting a path is slow; most are UTF-8 already.
                source: path
                    .to_str()
                    .map_or_else(|| path.display().to_string(), str::to_owned),
                path,
                options,
                options_key,
                named,
                forced,
                companion_of,
            })
        })
        .collect()
}
