//! The validated plan: every path resolved and checked, every parameter in
//! range, every unit and format name known, before any computation starts.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use crate::error::{Error, Result};
use crate::extract::friction::FrictionParams;
use crate::extract::roughness::stage::RoughnessSpec;
use crate::ingest::manifest::Manifest;
use crate::ingest::roles::Role;
use crate::ingest::{IngestOptions, READERS};
use crate::units::parse_unit;

use super::spec::{IngestSpec, PipelineSpec};

/// Stages the plan can run.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Stage {
    /// Friction features.
    Friction,
    /// Surface roughness (MODELS.md §4).
    Roughness,
    /// Fibre tensile analysis (MODELS.md §3).
    Tensile,
}

/// How to read one input file.
#[derive(Debug, Clone, Default)]
pub struct FileOptions {
    /// Ingestion options.
    pub ingest: IngestOptions,
    /// Column for each role.
    pub columns: BTreeMap<Role, String>,
}

/// One input with its options.
#[derive(Debug, Clone)]
pub struct PlannedFile {
    /// The path.
    pub path: PathBuf,
    /// How to read it.
    pub options: FileOptions,
}

/// A validated plan.
#[derive(Debug, Clone)]
pub struct Plan {
    /// Inputs, sorted by path (the order of every output).
    pub files: Vec<PlannedFile>,
    /// The manifest, read and parsed.
    pub manifest: Option<Manifest>,
    /// Output folder.
    pub out_dir: PathBuf,
    /// Stages in order.
    pub stages: Vec<Stage>,
    /// Friction parameters (validated).
    pub friction: FrictionParams,
    /// Roughness settings (validated by [`RoughnessSpec::plan`]).
    pub roughness: RoughnessSpec,
    /// Tensile parameters (validated).
    pub tensile: crate::extract::tensile::TensileParams,
    /// The spec, for provenance.
    pub spec_json: serde_json::Value,
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

/// Options for a file: the defaults, then each matching override in order.
pub fn options_for(path: &Path, spec: &IngestSpec) -> Result<FileOptions> {
    let mut o = FileOptions::default();
    apply(&mut o, spec);
    let name = path.file_name().and_then(|n| n.to_str()).unwrap_or("");
    for ov in &spec.overrides {
        let glob = ov.files.as_deref().unwrap_or("");
        let pat = glob::Pattern::new(glob)
            .map_err(|e| Error::Config(format!("ingest.override files = '{glob}': {e}")))?;
        if pat.matches(name) || pat.matches_path(path) {
            apply(&mut o, ov);
        }
    }
    Ok(o)
}

/// Lays the options of one `[ingest]` table over `o`.
fn apply(o: &mut FileOptions, spec: &IngestSpec) {
    if spec.format.is_some() {
        o.ingest.format = spec.format.clone();
    }
    o.ingest.units.extend(spec.units.clone());
    o.columns.extend(spec.columns.clone());
    o.ingest.delimiter = spec.delimiter.or(o.ingest.delimiter);
    o.ingest.decimal = spec.decimal.or(o.ingest.decimal);
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

/// Removes `.` and `name/..` from a path without touching the file system,
/// so that outputs name `fixtures/a.csv`, not `pipelines/../fixtures/a.csv`.
pub fn clean_path(path: &Path) -> PathBuf {
    use std::path::Component;
    let mut out: Vec<Component> = Vec::new();
    for c in path.components() {
        match c {
            Component::CurDir => {}
            Component::ParentDir if matches!(out.last(), Some(Component::Normal(_))) => {
                out.pop();
            }
            c => out.push(c),
        }
    }
    if out.is_empty() {
        return PathBuf::from(".");
    }
    out.iter().collect()
}

/// Expands globs (relative to `base`) into a sorted, de-duplicated list of
/// files. A glob that matches nothing is an error: a typo must not silently
/// drop a folder from a batch.
pub fn expand_inputs(patterns: &[String], base: &Path) -> Result<Vec<PathBuf>> {
    let mut files = Vec::new();
    for p in patterns {
        let full = clean_path(&if Path::new(p).is_absolute() {
            PathBuf::from(p)
        } else {
            base.join(p)
        });
        let text = full.to_string_lossy().to_string();
        let matches: Vec<PathBuf> = glob::glob(&text)
            .map_err(|e| Error::Config(format!("input glob '{p}': {e}")))?
            .filter_map(|r| r.ok())
            .filter(|p| p.is_file())
            .collect();
        if matches.is_empty() {
            return Err(Error::Config(format!(
                "input '{p}' matches no file (looked for {text})"
            )));
        }
        files.extend(matches);
    }
    files.sort();
    files.dedup();
    Ok(files)
}

impl Plan {
    /// Validates a spec; relative paths are taken from `base` (the folder of
    /// the pipeline file).
    pub fn from_spec(spec: &PipelineSpec, base: &Path) -> Result<Plan> {
        spec.friction.validate()?;
        spec.roughness.plan()?;
        spec.tensile.validate()?;
        let stages = spec
            .stages
            .iter()
            .map(|s| match s.as_str() {
                "friction" => Ok(Stage::Friction),
                "roughness" => Ok(Stage::Roughness),
                "tensile" => Ok(Stage::Tensile),
                other => Err(Error::Config(format!(
                    "unknown stage '{other}'; known stages: friction, roughness, tensile"
                ))),
            })
            .collect::<Result<Vec<_>>>()?;
        check_ingest_spec(&spec.ingest)?;
        let paths = expand_inputs(&spec.input.files, base)?;
        let files = paths
            .into_iter()
            .map(|path| {
                let options = options_for(&path, &spec.ingest)?;
                check_options(&options, &format!("options for {}", path.display()))?;
                Ok(PlannedFile { path, options })
            })
            .collect::<Result<Vec<_>>>()?;
        let manifest = match &spec.input.samples {
            Some(s) => Some(Manifest::read(&clean_path(&base.join(s)))?),
            None => None,
        };
        Ok(Plan {
            files,
            manifest,
            out_dir: clean_path(&base.join(&spec.output.dir)),
            stages,
            friction: spec.friction.clone(),
            roughness: spec.roughness.clone(),
            tensile: spec.tensile,
            spec_json: serde_json::to_value(spec).unwrap_or_default(),
        })
    }

    /// Reads and validates a pipeline file.
    pub fn from_file(path: &Path) -> Result<Plan> {
        let text = std::fs::read_to_string(path).map_err(|e| Error::io(path, e))?;
        let spec: PipelineSpec =
            toml::from_str(&text).map_err(|e| Error::Config(format!("{}: {e}", path.display())))?;
        let base = path
            .parent()
            .filter(|p| !p.as_os_str().is_empty())
            .unwrap_or(Path::new("."));
        Plan::from_spec(&spec, base)
    }
}
