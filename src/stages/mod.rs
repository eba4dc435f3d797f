//! Stages: each owns one step of a pipeline whole — its settings as the
//! user writes them (a table of the pipeline file, or a command's flags),
//! their validation, the work, and the tables it produces (whose schemas
//! are in `schemas/`). Every stage is listed once, in [`STAGES`]; the
//! pipeline asks the list, never matches on names.
//!
//! Two shapes of work:
//! - **per-file** stages ([`Consumes::Files`]) take the input files of the
//!   kinds they read, one at a time, and return that file's rows; the
//!   pipeline joins the rows of all files in input order and hands them to
//!   [`StagePlan::assemble`] (which resolves what spans files, such as the
//!   tensile controls of Eq. 5.4);
//! - **table** stages ([`Consumes::Tables`]) take tables of earlier stages
//!   (or files) and produce their own: fits, summaries, simulations.
//!
//! Stages never write files, print or decide exit codes: they return
//! [`Output`]s, and the pipeline does the rest once for all of them.
//!
//! Each stage declares the tables it produces ([`TableDef`]: name, schema
//! file, how the report shows them) in its own module, next to the code
//! that turns its typed rows into columns; [`Stage::tables`] lists them,
//! and every list of tables is derived from those lists ([`tables`]).

pub mod alsfm;
pub mod coulomb;
pub mod film;
pub mod friction;
pub mod ice;
pub mod ice_grid;
pub mod roughness;
pub mod spring_block;
pub mod tensile;
pub mod tensile_summary;
pub mod wear;

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use serde::de::DeserializeOwned;

use crate::error::{Error, Result};
use crate::hash::InputHash;
use crate::ingest::kind::DataKind;
use crate::ingest::manifest::Manifest;
use crate::ingest::roles::Role;
use crate::ingest::Dataset;
use crate::schema::TableDef;
use crate::table::Table;

/// Tables with their declarations: a stage's rows for one file, or its
/// whole output.
pub type Tables = Vec<(&'static TableDef, Table)>;

/// A stage as [`STAGES`] lists it: a name, what it does, and how to turn
/// its table of a pipeline file into a validated [`StagePlan`].
pub trait Stage: Sync {
    /// The name in pipeline files (`friction`, `tensile-summary`, …).
    fn name(&self) -> &'static str;
    /// One line for `--help` and error messages.
    fn about(&self) -> &'static str;
    /// Every table the stage can produce (a plan produces those its
    /// settings ask for: [`StagePlan::produces`]).
    fn tables(&self) -> &'static [&'static TableDef];
    /// Validates the stage's settings. Paths in them are relative to
    /// `ctx.base`. Every check happens here, before any work starts.
    fn plan(&self, settings: toml::Table, ctx: &PlanContext) -> Result<Box<dyn StagePlan>>;
}

/// Every stage, in the order they usually run (and the report shows their
/// tables).
pub static STAGES: &[&dyn Stage] = &[
    &friction::Friction,
    &tensile::Tensile,
    &tensile_summary::TensileSummary,
    &roughness::Roughness,
    &wear::Wear,
    &coulomb::Coulomb,
    &ice::Ice,
    &film::Film,
    &ice_grid::IceGrid,
    &spring_block::SpringBlock,
    &alsfm::Alsfm,
];

/// Every table of every stage, in [`STAGES`] order.
pub fn tables() -> impl Iterator<Item = &'static TableDef> {
    STAGES.iter().flat_map(|s| s.tables().iter().copied())
}

/// The stage called `name`.
pub fn find(name: &str) -> Option<&'static dyn Stage> {
    STAGES.iter().copied().find(|s| s.name() == name)
}

/// The names of every stage, for error messages.
pub fn names() -> String {
    STAGES
        .iter()
        .map(|s| s.name())
        .collect::<Vec<_>>()
        .join(", ")
}

/// What planning a stage may look at besides its own settings.
#[derive(Debug, Clone)]
pub struct PlanContext {
    /// The folder that relative paths in the settings start from (the
    /// pipeline file's folder).
    pub base: PathBuf,
    /// Whether the run writes the per-sample `traces` table.
    pub traces: bool,
    /// Whether stages draw their figures (`<stage>_figures` tables).
    pub figures: bool,
}

impl PlanContext {
    /// A relative path from the settings, resolved against [`Self::base`].
    pub fn path(&self, p: &str) -> PathBuf {
        crate::paths::clean_path(&self.base.join(p))
    }
}

/// What a planned stage consumes.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Consumes {
    /// Input files of these kinds.
    Files(&'static [DataKind]),
    /// Tables of earlier stages.
    Tables(Vec<Need>),
}

/// A table a table stage reads.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Need {
    /// The table (`friction`, `coulomb`, …).
    pub table: &'static TableDef,
    /// Whether the stage can run without it.
    pub required: bool,
}

impl Need {
    /// A table the stage cannot run without.
    pub fn required(table: &'static TableDef) -> Self {
        Need {
            table,
            required: true,
        }
    }
    /// A table the stage uses when the pipeline has it.
    pub fn optional(table: &'static TableDef) -> Self {
        Need {
            table,
            required: false,
        }
    }
}

/// One input file, read once by the pipeline and shared by every stage that
/// takes it.
pub struct FileInput<'a> {
    /// The path.
    pub path: &'a Path,
    /// What was read: owned by the last stage that reads the file, which
    /// may then take its columns (converting them to SI in place) rather
    /// than copy them.
    pub dataset: std::borrow::Cow<'a, Dataset>,
    /// The user's column for each role (`[ingest] columns`).
    pub columns: &'a BTreeMap<Role, String>,
    /// The sample manifest, when the pipeline has one.
    pub manifest: Option<&'a Manifest>,
}

/// The tables a table stage reads, by name.
pub struct TableInputs<'a> {
    tables: &'a BTreeMap<String, Table>,
}

impl<'a> TableInputs<'a> {
    /// Wraps the tables available to a stage.
    pub fn new(tables: &'a BTreeMap<String, Table>) -> Self {
        TableInputs { tables }
    }
    /// A table, if the pipeline has it.
    pub fn get(&self, table: &TableDef) -> Option<&'a Table> {
        self.tables.get(table.name)
    }
    /// A table the stage declared as required.
    pub fn required(&self, table: &TableDef) -> Result<&'a Table> {
        self.get(table)
            .ok_or_else(|| Error::Config(format!("input table '{}' is missing", table.name)))
    }
}

/// What a stage produced.
#[derive(Debug, Default)]
pub struct Output {
    /// Its tables.
    pub tables: Tables,
    /// Rows that carry no result (their status says why); a run with any
    /// exits 1.
    pub without_result: usize,
    /// Lines for the user: rows left out, runs that failed.
    pub notes: Vec<String>,
}

impl Output {
    /// Tables with every row holding a result.
    pub fn new(tables: Tables) -> Self {
        Output {
            tables,
            ..Default::default()
        }
    }
    /// One of its tables.
    pub fn table(&self, table: &TableDef) -> Option<&Table> {
        self.tables
            .iter()
            .find(|(d, _)| *d == table)
            .map(|(_, t)| t)
    }
}

/// Progress of long work; the pipeline's caller draws it (the library
/// never prints).
pub trait Progress: Sync {
    /// A phase of `total` steps begins.
    fn begin(&self, _what: &str, _total: usize) {}
    /// One step is done.
    fn tick(&self) {}
}

impl<F: Fn() + Sync> Progress for F {
    fn tick(&self) {
        self()
    }
}

/// A stage with validated settings, ready to run.
pub trait StagePlan: Send + Sync {
    /// The stage's name.
    fn name(&self) -> &'static str;
    /// What it consumes.
    fn consumes(&self) -> Consumes;
    /// The tables it writes (of [`Stage::tables`]), as its settings ask.
    fn produces(&self) -> Vec<&'static TableDef>;
    /// Its validated settings, for the provenance.
    fn parameters(&self) -> serde_json::Value;
    /// Equations and sources it uses, for the provenance.
    fn references(&self) -> Vec<String>;
    /// Files it reads itself (scene files, sample tables), for the
    /// provenance.
    fn own_inputs(&self) -> Vec<InputHash> {
        Vec::new()
    }
    /// Work units, for progress: files are counted by the pipeline; a
    /// simulation counts its runs.
    fn units(&self) -> usize {
        1
    }
    /// Per-file stages: the rows of one file. `Err` when the file cannot
    /// be analysed at all (a row with a status is not an error).
    fn run_file(&self, _file: FileInput) -> Result<Tables> {
        Err(Error::Config(format!(
            "stage '{}' does not take input files",
            self.name()
        )))
    }
    /// Per-file stages: the rows of every file, joined in input order, made
    /// into the stage's output.
    fn assemble(&self, tables: Tables) -> Result<Output> {
        Ok(Output::new(tables))
    }
    /// Table stages whose work is independent runs (a simulation study):
    /// the estimated seconds of each run, so that shards can share them;
    /// empty when the stage is one piece of work.
    fn unit_costs(&self) -> Vec<f64> {
        Vec::new()
    }
    /// Runs unit `i`; its serialised result is what the cache keeps.
    fn run_unit(&self, _i: usize) -> Result<Vec<u8>> {
        Err(Error::Config(format!(
            "stage '{}' has no units",
            self.name()
        )))
    }
    /// The output from every unit's result, in unit order.
    fn run_tables_from_units(&self, _inputs: &TableInputs, _units: Vec<Vec<u8>>) -> Result<Output> {
        Err(Error::Config(format!(
            "stage '{}' has no units",
            self.name()
        )))
    }
    /// Table stages: the work.
    fn run_tables(&self, _inputs: &TableInputs, _progress: &dyn Progress) -> Result<Output> {
        Err(Error::Config(format!(
            "stage '{}' does not take tables",
            self.name()
        )))
    }
}

/// Adds a stage's figures to its output as the table `table` (a
/// `<stage>_figures` table, schema `figures`).
pub fn add_figures(
    out: &mut Output,
    table: &'static TableDef,
    figures: &[crate::report::figures::Figure],
) -> Result<()> {
    out.tables
        .push((table, crate::report::figures::to_table(figures)?));
    Ok(())
}

/// Deserialises a stage's settings, naming the stage in the error.
pub fn settings<T: DeserializeOwned>(stage: &str, table: toml::Table) -> Result<T> {
    T::deserialize(toml::Value::Table(table))
        .map_err(|e| Error::Config(format!("[{stage}]: {}", e.message())))
}

/// A count of rows whose `column` is null: the rows without a result.
pub fn nulls(tables: &Tables, table: &TableDef, column: &str) -> Result<usize> {
    match tables.iter().find(|(d, _)| *d == table) {
        Some((_, t)) => t.null_count(column),
        None => Ok(0),
    }
}
