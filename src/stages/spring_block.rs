//! The `spring-block` stage (MODELS.md §7, thesis Ch. 4): a scene (one
//! pattern, pressures × repetitions) or a comparison study (several scenes
//! against measured Coulomb fits, Fig. 4.10), as the tables
//! `spring_block`, `spring_block_summary`, `spring_block_curves` and, for a
//! study, `spring_block_compare`. In a pipeline with a `coulomb` stage, a
//! study compares with the pipeline's own fits (unless the study file
//! names its own `coulomb.parquet`).
//!
//! ```toml
//! [spring-block]
//! scene = "spring_block_compare.toml"   # a scene or a study file
//! ```

use std::path::PathBuf;

use serde::{Deserialize, Serialize};

use super::coulomb::COULOMB;
use super::{
    add_figures, settings, Consumes, Need, Output, PlanContext, Progress, Stage, StagePlan,
    TableInputs,
};
use crate::error::{Error, Result};
use crate::hash::InputHash;
use crate::report::figures::{self, figures_table};
use crate::schema::{Show, TableDef};
use crate::simulate::spring_block::compare::fits_from_table;
use crate::simulate::spring_block::output::REFERENCES;
use crate::simulate::spring_block::study::SimulationOutcome;
use crate::simulate::spring_block::sweep::SweepRun;
use crate::simulate::spring_block::{load_input, SimulationInput};

/// The registry entry.
pub struct SpringBlock;

/// The stage's name in pipeline files, and the model's in the report.
const NAME: &str = "spring-block";

/// One row per run.
pub static SPRING_BLOCK: TableDef = TableDef::new(
    "spring_block",
    include_str!("../../schemas/spring_block.toml"),
    Show::Hidden,
);

/// One row per pattern and pressure.
pub static SPRING_BLOCK_SUMMARY: TableDef = TableDef::new(
    "spring_block_summary",
    include_str!("../../schemas/spring_block_summary.toml"),
    Show::Model {
        model: NAME,
        columns: &[
            "pattern",
            "pressure_Pa",
            "n",
            "mu_static_mean",
            "mu_static_sd",
            "mu_dynamic_mean",
            "n_failed",
        ],
    },
);

/// The decimated T(t) curves.
pub static SPRING_BLOCK_CURVES: TableDef = TableDef::new(
    "spring_block_curves",
    include_str!("../../schemas/spring_block_curves.toml"),
    Show::Hidden,
);

/// A study's simulated μ beside the measured fits.
pub static SPRING_BLOCK_COMPARE: TableDef = TableDef::new(
    "spring_block_compare",
    include_str!("../../schemas/spring_block_compare.toml"),
    Show::Hidden,
);

/// T(t) curves and μ_s(p) against the measured fits.
pub static SPRING_BLOCK_FIGURES: TableDef = figures_table("spring_block_figures");

/// The stage's settings as written.
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SpringBlockSettings {
    /// A scene or a comparison-study file, relative to the pipeline file.
    pub scene: String,
}

/// Every table of the stage.
static TABLES: &[&TableDef] = &[
    &SPRING_BLOCK,
    &SPRING_BLOCK_SUMMARY,
    &SPRING_BLOCK_CURVES,
    &SPRING_BLOCK_COMPARE,
    &SPRING_BLOCK_FIGURES,
];

impl Stage for SpringBlock {
    fn name(&self) -> &'static str {
        NAME
    }
    fn about(&self) -> &'static str {
        "2-D spring-block model of patterned surfaces, and its comparison with measured fits"
    }
    fn tables(&self) -> &'static [&'static TableDef] {
        TABLES
    }
    fn plan(&self, table: toml::Table, ctx: &PlanContext) -> Result<Box<dyn StagePlan>> {
        let s: SpringBlockSettings = settings(NAME, table)?;
        let path = ctx.path(&s.scene);
        let (input, hashes) = load_input(&path)?;
        Ok(Box::new(SpringBlockPlan {
            figures: ctx.figures,
            path,
            input,
            hashes,
        }))
    }
}

struct SpringBlockPlan {
    path: PathBuf,
    input: SimulationInput,
    hashes: Vec<InputHash>,
    figures: bool,
}

impl SpringBlockPlan {
    /// A study whose file does not name its own measured fits.
    fn takes_pipeline_fits(&self) -> bool {
        matches!(&self.input, SimulationInput::Study(s) if s.spec.measured.coulomb.is_none())
    }
}

impl StagePlan for SpringBlockPlan {
    fn name(&self) -> &'static str {
        NAME
    }
    fn consumes(&self) -> Consumes {
        if self.takes_pipeline_fits() {
            Consumes::Tables(vec![Need::optional(&COULOMB)])
        } else {
            Consumes::Tables(Vec::new())
        }
    }
    fn produces(&self) -> Vec<&'static TableDef> {
        let mut v: Vec<&'static TableDef> =
            vec![&SPRING_BLOCK, &SPRING_BLOCK_SUMMARY, &SPRING_BLOCK_CURVES];
        if matches!(self.input, SimulationInput::Study(_)) {
            v.push(&SPRING_BLOCK_COMPARE);
        }
        if self.figures {
            v.push(&SPRING_BLOCK_FIGURES);
        }
        v
    }
    fn parameters(&self) -> serde_json::Value {
        match &self.input {
            SimulationInput::Scene(p) => serde_json::json!({ "scenes": [p.spec] }),
            SimulationInput::Study(s) => {
                let scenes: Vec<_> = s.scenes.iter().map(|p| &p.spec).collect();
                serde_json::json!({ "study": s.spec, "scenes": scenes })
            }
        }
    }
    fn references(&self) -> Vec<String> {
        let mut r: Vec<String> = REFERENCES.iter().map(|s| s.to_string()).collect();
        if matches!(self.input, SimulationInput::Study(_)) {
            r.push("thesis Eq. 4.1, 4.2, Table 4.2, Fig. 4.10".into());
        }
        r
    }
    fn own_inputs(&self) -> Vec<InputHash> {
        self.hashes.clone()
    }
    fn units(&self) -> usize {
        self.input.runs()
    }
    fn unit_costs(&self) -> Vec<f64> {
        // About 0.1 ms of CPU per block and run (docs/spring_block.md: 0.16
        // to 5.3 s per run at 85 x 85, by pattern).
        let units = self.input.units();
        units
            .iter()
            .map(|&u| 1e-4 * self.input.unit_blocks(u) as f64)
            .collect()
    }
    fn run_unit(&self, i: usize) -> Result<Vec<u8>> {
        let unit = self
            .input
            .units()
            .get(i)
            .copied()
            .ok_or_else(|| Error::Config(format!("{NAME}: no run {i}")))?;
        let run = self.input.run_unit(unit)?;
        serde_json::to_vec(&run).map_err(|e| Error::Table(e.to_string()))
    }
    fn run_tables_from_units(&self, inputs: &TableInputs, units: Vec<Vec<u8>>) -> Result<Output> {
        let runs = units
            .iter()
            .map(|b| {
                serde_json::from_slice(b)
                    .map_err(|e| Error::Table(format!("a cached spring-block run: {e}")))
            })
            .collect::<Result<Vec<SweepRun>>>()?;
        let outcome = match self.study_with_fits(inputs)? {
            Some(study) => study.compute_from_units(runs)?,
            None => self.input.compute_from_units(runs)?,
        };
        self.output(outcome)
    }
    fn run_tables(&self, inputs: &TableInputs, progress: &dyn Progress) -> Result<Output> {
        progress.begin("spring-block runs", self.input.runs());
        let tick = || progress.tick();
        let outcome = match self.study_with_fits(inputs)? {
            Some(study) => study.compute(&tick)?,
            None => self.input.compute(&tick)?,
        };
        self.output(outcome)
    }
}

impl SpringBlockPlan {
    /// A study compared with this run's own Coulomb fits, when it has them.
    fn study_with_fits(&self, inputs: &TableInputs) -> Result<Option<SimulationInput>> {
        match (&self.input, inputs.get(&COULOMB)) {
            (SimulationInput::Study(s), Some(c)) if self.takes_pipeline_fits() => {
                let mut study = s.as_ref().clone();
                study.with_measured(fits_from_table(c, "coulomb stage")?);
                Ok(Some(SimulationInput::Study(Box::new(study))))
            }
            _ => Ok(None),
        }
    }

    fn output(&self, outcome: SimulationOutcome) -> Result<Output> {
        let notes = outcome
            .failure_messages
            .iter()
            .map(|m| format!("{}: {m}", self.path.display()))
            .collect();
        let drawn = self.figures.then(|| {
            let compare = outcome.compare.as_ref().map(|(_, rows)| rows.as_slice());
            figures::simulations::spring_block(NAME, &outcome.tables, compare)
        });
        let t = outcome.tables;
        let mut tables: super::Tables = vec![
            (&SPRING_BLOCK, t.runs),
            (&SPRING_BLOCK_SUMMARY, t.summary),
            (&SPRING_BLOCK_CURVES, t.curves),
        ];
        if let Some((compare, _)) = outcome.compare {
            tables.push((&SPRING_BLOCK_COMPARE, compare));
        }
        let mut out = Output {
            tables,
            without_result: outcome.failures,
            notes,
        };
        if let Some(drawn) = drawn {
            add_figures(&mut out, &SPRING_BLOCK_FIGURES, &drawn)?;
        }
        Ok(out)
    }
}
