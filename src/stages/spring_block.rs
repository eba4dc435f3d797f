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

use super::{
    add_figures, settings, Consumes, Need, Output, PlanContext, Progress, Stage, StagePlan,
    TableInputs,
};
use crate::error::{Error, Result};
use crate::hash::InputHash;
use crate::report::figures;
use crate::simulate::spring_block::compare::fits_from_table;
use crate::simulate::spring_block::output::REFERENCES;
use crate::simulate::spring_block::study::SimulationOutcome;
use crate::simulate::spring_block::sweep::SweepRun;
use crate::simulate::spring_block::{load_input, SimulationInput};

/// The registry entry.
pub struct SpringBlock;

/// The stage's settings as written.
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SpringBlockSettings {
    /// A scene or a comparison-study file, relative to the pipeline file.
    pub scene: String,
}

impl Stage for SpringBlock {
    fn name(&self) -> &'static str {
        "spring-block"
    }
    fn about(&self) -> &'static str {
        "2-D spring-block model of patterned surfaces, and its comparison with measured fits"
    }
    fn plan(&self, table: toml::Table, ctx: &PlanContext) -> Result<Box<dyn StagePlan>> {
        let s: SpringBlockSettings = settings("spring-block", table)?;
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
        "spring-block"
    }
    fn consumes(&self) -> Consumes {
        if self.takes_pipeline_fits() {
            Consumes::Tables(vec![Need::optional("coulomb")])
        } else {
            Consumes::Tables(Vec::new())
        }
    }
    fn produces(&self) -> Vec<&'static str> {
        let mut v = vec![
            "spring_block",
            "spring_block_summary",
            "spring_block_curves",
        ];
        if matches!(self.input, SimulationInput::Study(_)) {
            v.push("spring_block_compare");
        }
        if self.figures {
            v.push("spring_block_figures");
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
            .ok_or_else(|| Error::Config(format!("spring-block: no run {i}")))?;
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
        match (&self.input, inputs.get("coulomb")) {
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
        let mut out = Output {
            tables: outcome.tables,
            without_result: outcome.failures,
            notes,
        };
        if self.figures {
            let drawn = figures::simulations::spring_block(
                out.table("spring_block_curves"),
                out.table("spring_block_summary"),
                out.table("spring_block_compare"),
            );
            add_figures(&mut out, "spring_block_figures", &drawn)?;
        }
        Ok(out)
    }
}
