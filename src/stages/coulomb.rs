//! The `coulomb` stage (MODELS.md §2, Eq. 4.1/4.2): τ = τ0 + μ p per group
//! of the friction table, for static and dynamic friction, with the
//! flat-reference prediction and the across-sample summary, as the tables
//! `coulomb` and `coulomb_summary`.
//!
//! ```toml
//! [coulomb]
//! by = ["sample_id", "pattern"]    # groupings; "a,b" groups by two columns
//! reference = ["F", "flat"]        # pattern names of the flat reference
//! huber = 1.345                    # robust loss; least squares when absent
//! samples = "samples.csv"          # optional, keyed by sample_id
//! ```
//!
//! Rows without an apparent area or a grouping value are left out of the
//! fits and counted in a note, not failures.

use crate::status::{only, Code};
use std::collections::BTreeMap;

use serde::{Deserialize, Serialize};

use super::friction::tables::FRICTION;
use super::{
    add_figures, settings, Consumes, Need, Output, PlanContext, Progress, Stage, StagePlan,
    TableInputs,
};
use crate::error::{Error, Result};
use crate::fit::coulomb::linear::Loss;
use crate::fit::coulomb::table::{
    coulomb_tables, read_samples_csv, CoulombTableParams, LeftOut, SampleInfo,
};
use crate::hash::InputHash;
use crate::report::figures::{self, figures_table};
use crate::schema::{Show, TableDef};

/// The registry entry.
pub struct Coulomb;

/// The stage's name in pipeline files, and the model's in the report.
const NAME: &str = "coulomb";

/// One row per group and regime.
pub static COULOMB: TableDef = TableDef::new(
    "coulomb",
    include_str!("../../schemas/coulomb.toml"),
    Show::Model {
        model: NAME,
        columns: &[
            "grouping", "group", "regime", "n", "mu", "mu_se", "tau0_Pa", "r2", "status",
        ],
    },
);

/// Mean ± sd of the per-sample fits by pattern and regime (Table 4.2).
pub static COULOMB_SUMMARY: TableDef = TableDef::new(
    "coulomb_summary",
    include_str!("../../schemas/coulomb_summary.toml"),
    Show::Hidden,
);

/// τ against p with the fitted lines, per grouping and regime.
pub static COULOMB_FIGURES: TableDef = figures_table("coulomb_figures");

/// The stage's settings as written.
#[derive(Debug, Clone, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CoulombSettings {
    /// Groupings; each is one column or several joined by commas. Default
    /// `["sample_id", "pattern"]`.
    #[serde(default)]
    pub by: Vec<String>,
    /// Pattern names of the flat reference (Eq. 4.2). Default `F`, `flat`.
    #[serde(default)]
    pub reference: Vec<String>,
    /// Huber loss threshold k; least squares when absent.
    #[serde(default)]
    pub huber: Option<f64>,
    /// Samples table keyed by `sample_id` (apparent_area_m2, pattern,
    /// area_fraction), for friction tables that lack them.
    #[serde(default)]
    pub samples: Option<String>,
}

impl CoulombSettings {
    /// The fit parameters these settings ask for.
    pub fn table_params(&self) -> Result<CoulombTableParams> {
        let mut p = CoulombTableParams::default();
        if !self.by.is_empty() {
            p.groupings = self
                .by
                .iter()
                .map(|g| g.split(',').map(|c| c.trim().to_string()).collect())
                .collect();
        }
        if p.groupings.iter().flatten().any(String::is_empty) {
            return Err(Error::Config(format!(
                "[coulomb] by = {:?}: empty column name",
                self.by
            )));
        }
        if !self.reference.is_empty() {
            p.reference_patterns = self.reference.clone();
        }
        if let Some(k) = self.huber {
            if !(k > 0.0 && k.is_finite()) {
                return Err(Error::Config(format!(
                    "[coulomb] huber = {k}: expected a threshold > 0"
                )));
            }
            p.fit.loss = Loss::Huber { k };
        }
        Ok(p)
    }
}

/// Every table of the stage.
static TABLES: &[&TableDef] = &[&COULOMB, &COULOMB_SUMMARY, &COULOMB_FIGURES];

impl Stage for Coulomb {
    fn name(&self) -> &'static str {
        NAME
    }
    fn about(&self) -> &'static str {
        "Coulomb law with cohesion, tau = tau0 + mu p, per group of the friction table (Eq. 4.1, 4.2)"
    }
    fn tables(&self) -> &'static [&'static TableDef] {
        TABLES
    }
    fn plan(&self, table: toml::Table, ctx: &PlanContext) -> Result<Box<dyn StagePlan>> {
        let s: CoulombSettings = settings(NAME, table)?;
        let params = s.table_params()?;
        let (samples, hash) = match &s.samples {
            Some(p) => {
                let path = ctx.path(p);
                (read_samples_csv(&path)?, vec![InputHash::of_file(&path)?])
            }
            None => Default::default(),
        };
        Ok(Box::new(CoulombPlan {
            params,
            samples,
            samples_hash: hash,
            figures: ctx.figures,
        }))
    }
}

struct CoulombPlan {
    params: CoulombTableParams,
    samples: BTreeMap<String, SampleInfo>,
    samples_hash: Vec<InputHash>,
    figures: bool,
}

impl StagePlan for CoulombPlan {
    fn name(&self) -> &'static str {
        NAME
    }
    fn consumes(&self) -> Consumes {
        Consumes::Tables(vec![Need::required(&FRICTION)])
    }
    fn produces(&self) -> Vec<&'static TableDef> {
        match self.figures {
            true => vec![&COULOMB, &COULOMB_SUMMARY, &COULOMB_FIGURES],
            false => vec![&COULOMB, &COULOMB_SUMMARY],
        }
    }
    fn parameters(&self) -> serde_json::Value {
        serde_json::to_value(&self.params).unwrap_or_default()
    }
    fn references(&self) -> Vec<String> {
        vec![
            "MODELS.md §2 (Coulomb law with cohesion)".into(),
            "thesis Eq. 4.1, 4.2, Table 4.2".into(),
        ]
    }
    fn own_inputs(&self) -> Vec<InputHash> {
        self.samples_hash.clone()
    }
    fn run_tables(&self, inputs: &TableInputs, _progress: &dyn Progress) -> Result<Output> {
        let friction = inputs.required(&FRICTION)?;
        let t = coulomb_tables(friction, &self.samples, &self.params)?;
        let status = t.coulomb.str("status")?;
        let without_result = t.coulomb.null_count("mu")?;
        let doubtful = status
            .iter()
            .flatten()
            .filter(|s| *s != "ok" && !only(s, &[Code::TooFewPoints, Code::SingularDesign]))
            .count();
        let mut notes = left_out_notes(&t.left_out);
        if doubtful > 0 {
            notes.push(format!(
                "{doubtful} Coulomb fits have a doubt in their status (few_points, \
                 unphysical_sign, se_undefined): see coulomb.parquet"
            ));
        }
        let drawn = self.figures.then(|| figures::fits::coulomb(NAME, &t.fits));
        let mut out = Output {
            notes,
            without_result,
            tables: vec![(&COULOMB, t.coulomb), (&COULOMB_SUMMARY, t.summary)],
        };
        if let Some(d) = drawn {
            add_figures(&mut out, &COULOMB_FIGURES, &d)?;
        }
        Ok(out)
    }
}

fn left_out_notes(l: &LeftOut) -> Vec<String> {
    let mut notes = Vec::new();
    if l.no_area > 0 {
        notes.push(format!(
            "{} friction rows have no apparent_area_m2 and were left out of the fits",
            l.no_area
        ));
    }
    for (grouping, n) in &l.no_key {
        notes.push(format!(
            "{n} friction rows have no value in '{grouping}' and were left out of that grouping"
        ));
    }
    notes
}
