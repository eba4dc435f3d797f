//! Output-table schemas. Each table tribo writes has one file in `schemas/`
//! (column, type, unit, meaning), embedded here at compile time. Every table
//! is checked against its schema before it is written, so the files in
//! `schemas/` cannot drift from what the tool produces.
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

/// Every schema shipped with tribo, by table name. Adding a table means adding
/// its file to `schemas/` and one line here.
#[rustfmt::skip]
const SCHEMAS: &[(&str, &str)] = &[
    ("errors", include_str!("../schemas/errors.toml")),
    ("friction", include_str!("../schemas/friction.toml")),
    ("friction_steps", include_str!("../schemas/friction_steps.toml")),
    ("stickslip", include_str!("../schemas/stickslip.toml")),
    ("traces", include_str!("../schemas/traces.toml")),
    ("coulomb", include_str!("../schemas/coulomb.toml")),
    ("coulomb_summary", include_str!("../schemas/coulomb_summary.toml")),
    ("ice_fit", include_str!("../schemas/ice_fit.toml")),
    ("ice_residuals", include_str!("../schemas/ice_residuals.toml")),
    ("ice_grid", include_str!("../schemas/ice_grid.toml")),
    ("tensile", include_str!("../schemas/tensile.toml")),
    ("tensile_groups", include_str!("../schemas/tensile_groups.toml")),
    ("roughness", include_str!("../schemas/roughness.toml")),
    ("bearing_curve", include_str!("../schemas/bearing_curve.toml")),
    ("wear", include_str!("../schemas/wear.toml")),
    ("alsfm", include_str!("../schemas/alsfm.toml")),
    ("alsfm_time_series", include_str!("../schemas/alsfm_time_series.toml")),
    ("alsfm_adhesion", include_str!("../schemas/alsfm_adhesion.toml")),
    ("alsfm_wear", include_str!("../schemas/alsfm_wear.toml")),
    ("alsfm_hierarchy", include_str!("../schemas/alsfm_hierarchy.toml")),
    ("alsfm_contact_map", include_str!("../schemas/alsfm_contact_map.toml")),
    ("spring_block", include_str!("../schemas/spring_block.toml")),
    ("spring_block_summary", include_str!("../schemas/spring_block_summary.toml")),
    ("spring_block_curves", include_str!("../schemas/spring_block_curves.toml")),
    ("spring_block_compare", include_str!("../schemas/spring_block_compare.toml")),
    // Every stage's figures have one shape.
    ("friction_figures", include_str!("../schemas/figures.toml")),
    ("roughness_figures", include_str!("../schemas/figures.toml")),
    ("wear_figures", include_str!("../schemas/figures.toml")),
    ("tensile_figures", include_str!("../schemas/figures.toml")),
    ("coulomb_figures", include_str!("../schemas/figures.toml")),
    ("ice_figures", include_str!("../schemas/figures.toml")),
    ("alsfm_figures", include_str!("../schemas/figures.toml")),
    ("spring_block_figures", include_str!("../schemas/figures.toml")),
];

/// All schema names.
pub fn names() -> impl Iterator<Item = &'static str> {
    SCHEMAS.iter().map(|(n, _)| *n)
}

/// Loads the schema of a table.
pub fn schema(name: &str) -> Result<Schema> {
    let (_, text) = SCHEMAS
        .iter()
        .find(|(n, _)| *n == name)
        .ok_or_else(|| Error::Table(format!("no schema named '{name}'")))?;
    let mut s: Schema =
        toml::from_str(text).map_err(|e| Error::Table(format!("schemas/{name}.toml: {e}")))?;
    // A family of tables with one shape (every stage's figures).
    if name.ends_with("_figures") {
        s.name = name.to_string();
    }
    for c in &s.column {
        if ColumnType::parse(&c.ty).is_none() {
            return Err(Error::Table(format!(
                "schemas/{name}.toml: column '{}' has unknown type '{}'",
                c.name, c.ty
            )));
        }
    }
    Ok(s)
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
