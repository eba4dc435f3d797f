//! The declaration of an output table: its name, its schema file (compiled
//! in, parsed once per process) and how the report shows it. Each table is
//! declared once, as a `static` in the module of the stage that produces
//! it (the run's own tables, `errors` and `files`, in the pipeline); every
//! list of tables (what a stage produces, the schemas, the report's file
//! and model tables, the figures) is derived from these declarations.
//!
//! ```ignore
//! pub static WEAR: TableDef = TableDef::new(
//!     "wear",
//!     include_str!("../../schemas/wear.toml"),
//!     Show::PerFile(&[("area_m2", "area"), ("status", "status")]),
//! );
//! ```

use std::fmt;
use std::sync::OnceLock;

use super::Schema;
use crate::error::{Error, Result};
use crate::table::Table;

/// How the report shows a table.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Show {
    /// Not shown (the traces, long-form tables); read for the report only
    /// for its rows' statuses, when it has a `status` column.
    Hidden,
    /// Rows about input files (a `source` column): shown in each file's
    /// section with these columns, as (column, heading). A heading names
    /// the quantity; the report adds the unit, from the schema, with the
    /// prefix that suits the column's values (a `[unit]` written in the
    /// heading is replaced).
    PerFile(&'static [(&'static str, &'static str)]),
    /// A model's results: a section named `model` with these columns, as
    /// (column, heading), and the figures whose source is `model`.
    Model {
        /// The model's name: the section's title and its figures' source.
        model: &'static str,
        /// The columns shown, as (column, heading).
        columns: &'static [(&'static str, &'static str)],
    },
    /// A stage's figures (schema `schemas/figures.toml`): each drawn in
    /// the section of its source (an input file, or a model).
    Figures,
    /// The failures of a run: each in its file's section.
    Errors,
    /// Every input file of the run with its outcome: the report's first
    /// table.
    Files,
}

/// One output table, declared once.
pub struct TableDef {
    /// The table's name: the Parquet file is `<name>.parquet`.
    pub name: &'static str,
    /// The schema file's text (`include_str!("…/schemas/<name>.toml")`).
    toml: &'static str,
    /// How the report shows it.
    pub show: Show,
    /// Published as a dataset (a folder of one file per input) rather
    /// than one file: a table whose size grows with the inputs.
    dataset: bool,
    parsed: OnceLock<std::result::Result<Schema, String>>,
}

impl TableDef {
    /// Declares the table `name` with the schema file `toml`.
    pub const fn new(name: &'static str, toml: &'static str, show: Show) -> TableDef {
        TableDef {
            name,
            toml,
            show,
            dataset: false,
            parsed: OnceLock::new(),
        }
    }

    /// Declares the table `name`, published as a dataset: the folder
    /// `<name>/` of one Parquet file per input, so that a rerun adds or
    /// removes only the files of the inputs that changed.
    pub const fn dataset(name: &'static str, toml: &'static str, show: Show) -> TableDef {
        TableDef {
            name,
            toml,
            show,
            dataset: true,
            parsed: OnceLock::new(),
        }
    }

    /// Whether the table is published as a dataset (a folder of files).
    pub fn is_dataset(&self) -> bool {
        self.dataset
    }

    /// Where the table is published in the output folder `out`: the file
    /// `<name>.parquet`, or the dataset's folder `<name>/`.
    pub fn path_in(&self, out: &std::path::Path) -> std::path::PathBuf {
        match self.dataset {
            true => out.join(self.name),
            false => out.join(format!("{}.parquet", self.name)),
        }
    }

    /// The schema, parsed on first use.
    pub fn schema(&self) -> Result<&Schema> {
        self.parsed
            .get_or_init(|| {
                let parsed = match self.show {
                    Show::Figures => Schema::parse_family(self.name, self.toml),
                    _ => Schema::parse(self.name, self.toml),
                };
                parsed.map_err(|e| e.to_string())
            })
            .as_ref()
            .map_err(|e| Error::Table(e.clone()))
    }

    /// Checks `table` against the schema: names, order, types, nulls.
    pub fn check(&self, table: &Table) -> Result<()> {
        self.schema()?.check(table)
    }

    /// A table with the schema's columns and no rows.
    pub fn empty_table(&self) -> Result<Table> {
        self.schema()?.empty_table()
    }

    /// Whether the rows carry a `status` column (their doubts are listed).
    pub fn has_status(&self) -> bool {
        self.schema().is_ok_and(|s| s.has("status"))
    }

    /// Whether the report reads the table (for its rows or figures).
    pub fn in_report(&self) -> bool {
        self.show != Show::Hidden
    }
}

impl PartialEq for TableDef {
    fn eq(&self, other: &Self) -> bool {
        self.name == other.name
    }
}

impl Eq for TableDef {}

impl fmt::Debug for TableDef {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "TableDef({})", self.name)
    }
}

/// The table among `defs` called `name`.
pub fn find<'a>(defs: &[&'a TableDef], name: &str) -> Option<&'a TableDef> {
    defs.iter().copied().find(|d| d.name == name)
}
