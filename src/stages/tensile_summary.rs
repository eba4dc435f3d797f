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

use super::tensile::REFERENCES;
use super::{
    settings, Consumes, Need, Output, PlanContext, Progress, Stage, StagePlan, TableInputs,
};
use crate::error::{Error, Result};
use crate::extract::tensile::summary::{fill_ratios, groups_table, rows_from_table, summarize};

/// The registry entry.
pub struct TensileSummary;

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

impl Stage for TensileSummary {
    fn name(&self) -> &'static str {
        "tensile-summary"
    }
    fn about(&self) -> &'static str {
        "group summaries of the per-fibre tensile table (Tables 5.1, 5.2)"
    }
    fn plan(&self, table: toml::Table, _ctx: &PlanContext) -> Result<Box<dyn StagePlan>> {
        let s: SummarySettings = settings("tensile-summary", table)?;
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
        "tensile-summary"
    }
    fn consumes(&self) -> Consumes {
        Consumes::Tables(vec![Need::required("tensile")])
    }
    fn produces(&self) -> Vec<&'static str> {
        vec!["tensile_groups"]
    }
    fn parameters(&self) -> serde_json::Value {
        serde_json::to_value(self).unwrap_or_default()
    }
    fn references(&self) -> Vec<String> {
        REFERENCES.iter().map(|s| s.to_string()).collect()
    }
    fn run_tables(&self, inputs: &TableInputs, _progress: &dyn Progress) -> Result<Output> {
        let mut rows = rows_from_table(inputs.required("tensile")?, self.effective_threshold)?;
        fill_ratios(&mut rows);
        let groups = groups_table(&summarize(&rows))?;
        Ok(Output::new(vec![("tensile_groups", groups)]))
    }
}
