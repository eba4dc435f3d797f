//! The `wear` stage (MODELS.md §9): for each profile measured across a wear
//! track, the cross-section area below the reference line between the
//! track edges, the wear volume (area × track length) and the specific wear
//! rate (volume / (normal load × sliding distance)), as the table `wear`.
//! Track length, load and distance come from the sample manifest
//! (`track_radius_mm` or `stroke_length_mm`, `normal_force_N`,
//! `sliding_distance_m` or `laps`) or the stage's settings ([`WearSpec`]).
//!
//! Profiles that are not track cross-sections (a roughness scan) fail
//! here with "no wear track found": give the stage its own `files`.

use super::{settings, Consumes, FileInput, Output, PlanContext, Stage, StagePlan, Tables};
use crate::error::Result;
use crate::extract::roughness::input::surfaces_from_dataset;
use crate::extract::wear::{analyze_surfaces, wear_table, WearPlan, WearSpec};
use crate::ingest::kind::DataKind;
use crate::report::figures;

/// The registry entry.
pub struct Wear;

impl Stage for Wear {
    fn name(&self) -> &'static str {
        "wear"
    }
    fn about(&self) -> &'static str {
        "wear track cross-section, wear volume and specific wear rate of profiles across a track"
    }
    fn plan(&self, table: toml::Table, ctx: &PlanContext) -> Result<Box<dyn StagePlan>> {
        let spec: WearSpec = settings("wear", table)?;
        Ok(Box::new(WearStagePlan {
            plan: spec.plan()?,
            figures: ctx.figures,
        }))
    }
}

struct WearStagePlan {
    plan: WearPlan,
    figures: bool,
}

impl StagePlan for WearStagePlan {
    fn name(&self) -> &'static str {
        "wear"
    }
    fn consumes(&self) -> Consumes {
        Consumes::Files(&[DataKind::Profile])
    }
    fn produces(&self) -> Vec<&'static str> {
        match self.figures {
            true => vec!["wear", "wear_figures"],
            false => vec!["wear"],
        }
    }
    fn parameters(&self) -> serde_json::Value {
        serde_json::json!(self.plan)
    }
    fn references(&self) -> Vec<String> {
        vec!["MODELS.md §9 (wear from a track profile)".into()]
    }
    fn run_file(&self, file: FileInput) -> Result<Tables> {
        let surfaces = surfaces_from_dataset(&file.dataset, &self.plan.units)?;
        let rows = analyze_surfaces(&file.dataset, &surfaces, &self.plan, file.manifest)?;
        let table = wear_table(&rows, &self.plan)?;
        if !self.figures {
            return Ok(vec![("wear", table)]);
        }
        let source = file.path.display().to_string();
        let drawn = figures::wear::figures(&source, &surfaces, &table);
        Ok(vec![
            ("wear", table),
            ("wear_figures", figures::to_table(&drawn)?),
        ])
    }
    fn assemble(&self, tables: Tables) -> Result<Output> {
        let mut out = Output::new(tables);
        out.without_result = super::nulls(&out.tables, "wear", "area_m2")?;
        Ok(out)
    }
}
