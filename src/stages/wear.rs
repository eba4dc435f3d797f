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
use crate::report::figures::{self, file_figures_table};
use crate::schema::{Show, TableDef};

/// The registry entry.
pub struct Wear;

/// The stage's name in pipeline files.
const NAME: &str = "wear";

/// One row per track profile.
pub static WEAR: TableDef = TableDef::new(
    "wear",
    include_str!("../../schemas/wear.toml"),
    Show::PerFile(&[
        ("area_m2", "area"),
        ("depth_m", "depth"),
        ("width_m", "width"),
        ("volume_m3", "volume"),
        ("specific_wear_rate_mm3_per_N_m", "k"),
        ("status", "status"),
    ]),
);

/// Each profile across the track with the track's edges.
pub static WEAR_FIGURES: TableDef = file_figures_table("wear_figures");

/// Every table of the stage.
static TABLES: &[&TableDef] = &[&WEAR, &WEAR_FIGURES];

impl Stage for Wear {
    fn name(&self) -> &'static str {
        NAME
    }
    fn about(&self) -> &'static str {
        "wear track cross-section, wear volume and specific wear rate of profiles across a track"
    }
    fn tables(&self) -> &'static [&'static TableDef] {
        TABLES
    }
    fn plan(&self, table: toml::Table, ctx: &PlanContext) -> Result<Box<dyn StagePlan>> {
        let spec: WearSpec = settings(NAME, table)?;
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
        NAME
    }
    fn consumes(&self) -> Consumes {
        Consumes::Files(&[DataKind::Profile])
    }
    fn produces(&self) -> Vec<&'static TableDef> {
        match self.figures {
            true => vec![&WEAR, &WEAR_FIGURES],
            false => vec![&WEAR],
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
            return Ok(vec![(&WEAR, table)]);
        }
        let source = file.path.display().to_string();
        let drawn = figures::wear::figures(&source, &surfaces, &rows);
        Ok(vec![
            (&WEAR, table),
            (&WEAR_FIGURES, figures::to_table(&drawn)?),
        ])
    }
    fn assemble(&self, tables: Tables) -> Result<Output> {
        let mut out = Output::new(tables);
        out.without_result = super::nulls(&out.tables, &WEAR, "area_m2")?;
        Ok(out)
    }
}
