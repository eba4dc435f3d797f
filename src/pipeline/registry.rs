//! Every output table tribo writes, from one registry: the run's own
//! tables (declared here) and each stage's (declared in its module,
//! listed by [`crate::stages::Stage::tables`]). The schemas, the report's
//! sections and the figures are all looked up here, never in a list of
//! names of their own.

use crate::error::{Error, Result};
use crate::schema::{Schema, Show, TableDef};

/// The failures of a run: one row per (file or table stage, stage).
pub static ERRORS: TableDef = TableDef::new(
    "errors",
    include_str!("../../schemas/errors.toml"),
    Show::Errors,
);

/// The run's own tables.
const ENGINE: &[&TableDef] = &[&ERRORS];

/// Every table: the run's own, then each stage's in
/// [`crate::stages::STAGES`] order.
pub fn all() -> Vec<&'static TableDef> {
    ENGINE
        .iter()
        .copied()
        .chain(crate::stages::tables())
        .collect()
}

/// The table called `name`.
pub fn find(name: &str) -> Option<&'static TableDef> {
    all().into_iter().find(|d| d.name == name)
}

/// The schema of the table called `name`.
pub fn schema(name: &str) -> Result<&'static Schema> {
    find(name)
        .ok_or_else(|| Error::Table(format!("no table named '{name}'")))?
        .schema()
}
