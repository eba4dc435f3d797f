//! The `alsfm` stage (MODELS.md §5): an ALSFM scene file — surfaces, μ0,
//! sliding directions, loads, adhesion, wear, hierarchy — evaluated on the
//! cheapest exact path, as the table `alsfm` and, when the scene asks for
//! them, `alsfm_time_series`, `alsfm_adhesion`, `alsfm_wear`,
//! `alsfm_hierarchy` and `alsfm_contact_map` (see `docs/alsfm.md`).
//!
//! ```toml
//! [alsfm]
//! scene = "../fixtures/alsfm/wedges_beta_sweep.toml"
//! ```

use std::path::PathBuf;

use serde::{Deserialize, Serialize};

use super::{
    add_figures, settings, Consumes, Output, PlanContext, Progress, Stage, StagePlan, TableInputs,
};
use crate::error::Result;
use crate::hash::InputHash;
use crate::report::figures;
use crate::simulate::alsfm::plan::Plan;
use crate::simulate::alsfm::scene::SceneSpec;
use crate::simulate::alsfm::{load_scene, resolved, run, REFERENCES};

/// The registry entry.
pub struct Alsfm;

/// The stage's settings as written.
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct AlsfmSettings {
    /// The scene file, relative to the pipeline file.
    pub scene: String,
}

impl Stage for Alsfm {
    fn name(&self) -> &'static str {
        "alsfm"
    }
    fn about(&self) -> &'static str {
        "anisotropic lattice spring friction model of rough surfaces, from a scene file"
    }
    fn plan(&self, table: toml::Table, ctx: &PlanContext) -> Result<Box<dyn StagePlan>> {
        let s: AlsfmSettings = settings("alsfm", table)?;
        let path = ctx.path(&s.scene);
        let (plan, spec, hashes) = load_scene(&path)?;
        Ok(Box::new(AlsfmPlan {
            path,
            plan,
            spec,
            hashes,
            figures: ctx.figures,
        }))
    }
}

struct AlsfmPlan {
    path: PathBuf,
    plan: Plan,
    spec: SceneSpec,
    hashes: Vec<InputHash>,
    figures: bool,
}

impl StagePlan for AlsfmPlan {
    fn name(&self) -> &'static str {
        "alsfm"
    }
    fn consumes(&self) -> Consumes {
        Consumes::Tables(Vec::new())
    }
    fn produces(&self) -> Vec<&'static str> {
        let o = &self.plan.outputs;
        let mut v = vec!["alsfm"];
        for (want, name) in [
            (o.time_series, "alsfm_time_series"),
            (o.adhesion, "alsfm_adhesion"),
            (o.wear, "alsfm_wear"),
            (o.hierarchy, "alsfm_hierarchy"),
            (!o.contact_maps.is_empty(), "alsfm_contact_map"),
        ] {
            if want {
                v.push(name);
            }
        }
        if self.figures {
            v.push("alsfm_figures");
        }
        v
    }
    fn parameters(&self) -> serde_json::Value {
        serde_json::json!({ "scene": self.spec, "resolved": resolved(&self.plan) })
    }
    fn references(&self) -> Vec<String> {
        REFERENCES.iter().map(|s| s.to_string()).collect()
    }
    fn own_inputs(&self) -> Vec<InputHash> {
        self.hashes.clone()
    }
    fn units(&self) -> usize {
        self.plan.beta_deg.len() * self.plan.loads.len()
    }
    fn run_tables(&self, _inputs: &TableInputs, _progress: &dyn Progress) -> Result<Output> {
        let output = run(&self.plan)?;
        let notes = output
            .points
            .iter()
            .filter(|p| p.status != "ok" && p.status != "no_coefficient")
            .map(|p| {
                format!(
                    "{}: beta = {} deg, load = {}: {}: {}",
                    self.path.display(),
                    p.beta_deg,
                    p.load,
                    p.status,
                    p.message
                )
            })
            .collect();
        let mut out = Output {
            without_result: output.failures(),
            tables: output.tables()?,
            notes,
        };
        if self.figures {
            let drawn = figures::simulations::alsfm(
                out.table("alsfm_time_series"),
                out.table("alsfm_adhesion"),
            );
            add_figures(&mut out, "alsfm_figures", &drawn)?;
        }
        Ok(out)
    }
}
