//! The `tensile-summary` stage: group summaries of the per-fibre table
//! (material × knot × effective class, thesis Tables 5.1 and 5.2), as the
//! table `tensile_groups`.
//!
//! ```toml
//! [tensile-summary]
//! effective_threshold = 0.08        # when the table has no knot_effective
//! inputs = { tensile = "fibres.csv" }  # optional: a table from a file
//! ```

use serde::{Deserialize, Serialize};

use super::tensile::{REFERENCES, TENSILE};
use super::{
    settings, Consumes, Need, Output, PlanContext, Progress, Stage, StagePlan, TableInputs,
};
use crate::error::{Error, Result};
use crate::extract::tensile::summary::{fill_ratios, groups_table, rows_from_table, summarize};
use crate::schema::{Show, TableDef};

/// The registry entry.
pub struct TensileSummary;

/// The stage's name in pipeline files.
const NAME: &str = "tensile-summary";

/// One row per material × knot × effective class.
pub static TENSILE_GROUPS: TableDef = TableDef::new(
    "tensile_groups",
    include_str!("../../schemas/tensile_groups.toml"),
    Show::Hidden,
);

/// Settings of the stage.
#[derive(Debug, Clone, Copy, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct SummarySettings {
    /// Effective-knot threshold on friction stress / strength, used when
    /// the table has no `knot_effective` column. Default 0.08; in (0, 1).
    pub effective_threshold: f64,
}

impl Default for SummarySettings {
    fn default() -> Self {
        SummarySettings {
            effective_threshold: 0.08,
        }
    }
}

/// Every table of the stage.
static TABLES: &[&TableDef] = &[&TENSILE_GROUPS];

impl Stage for TensileSummary {
    fn name(&self) -> &'static str {
        NAME
    }
    fn about(&self) -> &'static str {
        "group summaries of the per-fibre tensile table (Tables 5.1, 5.2)"
    }
    fn tables(&self) -> &'static [&'static TableDef] {
        TABLES
    }
    fn plan(&self, table: toml::Table, _ctx: &PlanContext) -> Result<Box<dyn StagePlan>> {
        let s: SummarySettings = settings(NAME, table)?;
        let t = s.effective_threshold;
        if !(t > 0.0 && t < 1.0) {
            return Err(Error::Config(format!(
                "effective-knot threshold {t}: expected a fraction in (0, 1)"
            )));
        }
        Ok(Box::new(s))
    }
}

impl StagePlan for SummarySettings {
    fn name(&self) -> &'static str {
        NAME
    }
    fn consumes(&self) -> Consumes {
        Consumes::Tables(vec![Need::required(&TENSILE)])
    }
    fn produces(&self) -> Vec<&'static TableDef> {
        vec![&TENSILE_GROUPS]
    }
    fn parameters(&self) -> serde_json::Value {
        serde_json::to_value(self).unwrap_or_default()
    }
    fn references(&self) -> Vec<String> {
        REFERENCES.iter().map(|s| s.to_string()).collect()
    }
    fn run_tables(&self, inputs: &TableInputs, _progress: &dyn Progress) -> Result<Output> {
        let mut rows = rows_from_table(inputs.required(&TENSILE)?, self.effective_threshold)?;
        fill_ratios(&mut rows);
        let groups = groups_table(&summarize(&rows))?;
        Ok(Output::new(vec![(&TENSILE_GROUPS, groups)]))
    }
}
