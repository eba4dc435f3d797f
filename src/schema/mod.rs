//! Output-table schemas. Each table tribo writes has one file in `schemas/`
//! (column, type, unit, meaning), compiled in by the declaration of the
//! table ([`def::TableDef`], in the module of the stage that produces it)
//! and parsed once per process. Every table is checked against its schema
//! where it is assembled, so the files in `schemas/` cannot drift from what
//! the tool produces.
//!
//! Format of a schema file:
//! ```toml
//! name = "friction"
//! description = "One row per trace segment."
//! [[column]]
//! name = "mu_static"
//! type = "f64"        # f64, i64, str or bool
//! unit = "1"          # "" for text, "1" for dimensionless
//! nullable = true
//! meaning = "Static coefficient of friction T_s / N (MODELS.md §1)."
//! ```

pub mod def;

pub use def::{Show, TableDef};

use serde::Deserialize;

use crate::error::{Error, Result};
use crate::table::{ColumnType, Table, TableBuilder};

/// One column of a schema.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ColumnSpec {
    /// Column name, with its unit as a suffix where it has one.
    pub name: String,
    /// `f64`, `i64`, `str` or `bool`.
    #[serde(rename = "type")]
    pub ty: String,
    /// Unit: SI symbol, `1` for dimensionless, empty for text.
    pub unit: String,
    /// Whether nulls are allowed.
    #[serde(default)]
    pub nullable: bool,
    /// What the column means.
    pub meaning: String,
}

/// A table schema.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Schema {
    /// Table name (the Parquet file is `<name>.parquet`).
    pub name: String,
    /// What one row is.
    pub description: String,
    /// Columns in order.
    pub column: Vec<ColumnSpec>,
}

impl Schema {
    /// Parses the schema file of the table `name` (`text`: the file's
    /// TOML), checking that it names that table.
    pub fn parse(name: &str, text: &str) -> Result<Schema> {
        let s = Schema::read(name, text)?;
        if s.name != name {
            return Err(Error::Table(format!(
                "the schema of table {name} names the table '{}'",
                s.name
            )));
        }
        Ok(s)
    }

    /// Parses a schema shared by a family of tables (every stage's
    /// figures), for its member `name`.
    pub fn parse_family(name: &str, text: &str) -> Result<Schema> {
        let mut s = Schema::read(name, text)?;
        s.name = name.to_string();
        Ok(s)
    }

    /// The schema in `text`, every column's type checked.
    fn read(name: &str, text: &str) -> Result<Schema> {
        let s: Schema =
            toml::from_str(text).map_err(|e| Error::Table(format!("schema of {name}: {e}")))?;
        for c in &s.column {
            if ColumnType::parse(&c.ty).is_none() {
                return Err(Error::Table(format!(
                    "schema of {name}: column '{}' has unknown type '{}'",
                    c.name, c.ty
                )));
            }
        }
        Ok(s)
    }

    /// Whether the schema has the column `name`.
    pub fn has(&self, name: &str) -> bool {
        self.column.iter().any(|c| c.name == name)
    }
}

impl Schema {
    /// A table with this schema's columns and no rows: the output of a
    /// stage that had nothing to work on.
    pub fn empty_table(&self) -> Result<Table> {
        let mut b = TableBuilder::new();
        for c in &self.column {
            b = match ColumnType::parse(&c.ty) {
                Some(ColumnType::F64) => b.f64(&c.name, std::iter::empty()),
                Some(ColumnType::I64) => b.i64(&c.name, std::iter::empty()),
                Some(ColumnType::Bool) => b.bool(&c.name, std::iter::empty()),
                Some(ColumnType::Cat) => b.cat_runs::<&str>(&c.name, std::iter::empty()),
                _ => b.str::<&str>(&c.name, std::iter::empty()),
            };
        }
        b.build()
    }

    /// Each column's unit and meaning, as Arrow field metadata (`unit`,
    /// `description`), so that a table explains itself in pyarrow, polars
    /// and DuckDB.
    pub fn field_metadata(&self) -> Vec<(String, Vec<(String, String)>)> {
        self.column
            .iter()
            .map(|c| {
                let kv = vec![
                    ("unit".to_string(), c.unit.clone()),
                    ("description".to_string(), c.meaning.clone()),
                ];
                (c.name.clone(), kv)
            })
            .collect()
    }

    /// Checks names, order, types and nullability of `table`.
    pub fn check(&self, table: &Table) -> Result<()> {
        let names = table.column_names();
        let expected: Vec<&str> = self.column.iter().map(|c| c.name.as_str()).collect();
        if names != expected {
            return Err(Error::Table(format!(
                "table '{}' does not match schemas/{}.toml: columns {:?}, expected {:?}",
                self.name, self.name, names, expected
            )));
        }
        for c in &self.column {
            let want = ColumnType::parse(&c.ty);
            let got = table.column_type(&c.name);
            if want != got {
                return Err(Error::Table(format!(
                    "table '{}': column '{}' has type {:?}, schema says {}",
                    self.name,
                    c.name,
                    got.map(ColumnType::name),
                    c.ty
                )));
            }
            if !c.nullable && table.null_count(&c.name)? > 0 {
                return Err(Error::Table(format!(
                    "table '{}': column '{}' has nulls but is not nullable",
                    self.name, c.name
                )));
            }
        }
        Ok(())
    }
}
