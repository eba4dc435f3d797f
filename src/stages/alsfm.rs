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
use crate::report::figures::{self, figures_table};
use crate::schema::{Show, TableDef};
use crate::simulate::alsfm::plan::Plan;
use crate::simulate::alsfm::rows::AlsfmOutput;
use crate::simulate::alsfm::scene::SceneSpec;
use crate::simulate::alsfm::{load_scene, resolved, run, REFERENCES};
use crate::table::Table;

/// The registry entry.
pub struct Alsfm;

/// Builds one of the tables of an ALSFM run from its rows.
type BuildTable = fn(&AlsfmOutput) -> Result<Table>;

/// The stage's name in pipeline files, and the model's in the report.
const NAME: &str = "alsfm";

/// Declares an ALSFM table shown in no section of its own.
const fn hidden(name: &'static str, schema: &'static str) -> TableDef {
    TableDef::new(name, schema, Show::Hidden)
}

/// One row per (β, load).
pub static ALSFM: TableDef = TableDef::new(
    "alsfm",
    include_str!("../../schemas/alsfm.toml"),
    Show::Model {
        model: NAME,
        columns: &["beta_deg", "load", "mu", "r_xy_N", "status"],
    },
);

/// One row per instant of a point's sliding.
pub static ALSFM_TIME_SERIES: TableDef = hidden(
    "alsfm_time_series",
    include_str!("../../schemas/alsfm_time_series.toml"),
);

/// R_xy and the apparent μ per (β, load).
pub static ALSFM_ADHESION: TableDef = hidden(
    "alsfm_adhesion",
    include_str!("../../schemas/alsfm_adhesion.toml"),
);

/// The wear of the asperities over time.
pub static ALSFM_WEAR: TableDef =
    hidden("alsfm_wear", include_str!("../../schemas/alsfm_wear.toml"));

/// μ per level of a hierarchical surface.
pub static ALSFM_HIERARCHY: TableDef = hidden(
    "alsfm_hierarchy",
    include_str!("../../schemas/alsfm_hierarchy.toml"),
);

/// Contact forces on the surface at chosen steps.
pub static ALSFM_CONTACT_MAP: TableDef = hidden(
    "alsfm_contact_map",
    include_str!("../../schemas/alsfm_contact_map.toml"),
);

/// μ along the path and R_xy against load.
pub static ALSFM_FIGURES: TableDef = figures_table("alsfm_figures");

/// The stage's settings as written.
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct AlsfmSettings {
    /// The scene file, relative to the pipeline file.
    pub scene: String,
}

/// Every table of the stage.
static TABLES: &[&TableDef] = &[
    &ALSFM,
    &ALSFM_TIME_SERIES,
    &ALSFM_ADHESION,
    &ALSFM_WEAR,
    &ALSFM_HIERARCHY,
    &ALSFM_CONTACT_MAP,
    &ALSFM_FIGURES,
];

impl Stage for Alsfm {
    fn name(&self) -> &'static str {
        NAME
    }
    fn about(&self) -> &'static str {
        "anisotropic lattice spring friction model of rough surfaces, from a scene file"
    }
    fn tables(&self) -> &'static [&'static TableDef] {
        TABLES
    }
    fn plan(&self, table: toml::Table, ctx: &PlanContext) -> Result<Box<dyn StagePlan>> {
        let s: AlsfmSettings = settings(NAME, table)?;
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
        NAME
    }
    fn consumes(&self) -> Consumes {
        Consumes::Tables(Vec::new())
    }
    fn produces(&self) -> Vec<&'static TableDef> {
        let o = &self.plan.outputs;
        let mut v: Vec<&'static TableDef> = vec![&ALSFM];
        for (want, def) in [
            (o.time_series, &ALSFM_TIME_SERIES),
            (o.adhesion, &ALSFM_ADHESION),
            (o.wear, &ALSFM_WEAR),
            (o.hierarchy, &ALSFM_HIERARCHY),
            (!o.contact_maps.is_empty(), &ALSFM_CONTACT_MAP),
        ] {
            if want {
                v.push(def);
            }
        }
        if self.figures {
            v.push(&ALSFM_FIGURES);
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
        let drawn = self
            .figures
            .then(|| figures::simulations::alsfm(NAME, &output.series, &output.adhesion));
        let mut tables: super::Tables = vec![(&ALSFM, output.points_table()?)];
        // The other tables when they have rows.
        let others: [(&'static TableDef, bool, BuildTable); 5] = [
            (
                &ALSFM_TIME_SERIES,
                output.series.is_empty(),
                AlsfmOutput::series_table,
            ),
            (
                &ALSFM_ADHESION,
                output.adhesion.is_empty(),
                AlsfmOutput::adhesion_table,
            ),
            (&ALSFM_WEAR, output.wear.is_empty(), AlsfmOutput::wear_table),
            (
                &ALSFM_HIERARCHY,
                output.hierarchy.is_empty(),
                AlsfmOutput::hierarchy_table,
            ),
            (
                &ALSFM_CONTACT_MAP,
                output.maps.is_empty(),
                AlsfmOutput::map_table,
            ),
        ];
        for (def, empty, table) in others {
            if !empty {
                tables.push((def, table(&output)?));
            }
        }
        let mut out = Output {
            without_result: output.failures(),
            tables,
            notes,
        };
        if let Some(drawn) = drawn {
            add_figures(&mut out, &ALSFM_FIGURES, &drawn)?;
        }
        Ok(out)
    }
}
