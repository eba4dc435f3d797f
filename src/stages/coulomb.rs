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
use crate::report::figures;

/// The registry entry.
pub struct Coulomb;

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

impl Stage for Coulomb {
    fn name(&self) -> &'static str {
        "coulomb"
    }
    fn about(&self) -> &'static str {
        "Coulomb law with cohesion, tau = tau0 + mu p, per group of the friction table (Eq. 4.1, 4.2)"
    }
    fn plan(&self, table: toml::Table, ctx: &PlanContext) -> Result<Box<dyn StagePlan>> {
        let s: CoulombSettings = settings("coulomb", table)?;
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
        "coulomb"
    }
    fn consumes(&self) -> Consumes {
        Consumes::Tables(vec![Need::required("friction")])
    }
    fn produces(&self) -> Vec<&'static str> {
        let mut names = vec!["coulomb", "coulomb_summary"];
        if self.figures {
            names.push("coulomb_figures");
        }
        names
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
        let friction = inputs.required("friction")?;
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
        let drawn = match self.figures {
            true => Some(figures::fits::coulomb(friction, &t.coulomb)),
            false => None,
        };
        let mut out = Output {
            notes,
            without_result,
            tables: vec![("coulomb", t.coulomb), ("coulomb_summary", t.summary)],
        };
        if let Some(d) = drawn {
            add_figures(&mut out, "coulomb_figures", &d)?;
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
