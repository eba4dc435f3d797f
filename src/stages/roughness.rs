//! The `roughness` stage (MODELS.md §4, §9, §10): Ra, Rq, Rdq, Rsk, Rku,
//! Rp, Rv, Rt, Rz (Sa … Sz for maps), the Rk family, material ratio and
//! volume parameters, Sdr, Sal, Str, Std, RSm, fractal dimension, bearing
//! curve, PSD, ACF and contact length of every profile and map, as the
//! tables `roughness`, `bearing_curve`, `psd` and `acf`. Each row carries the
//! manifest's `sample_id` and `pin`, so that the ice fit joins roughness to
//! friction steps.
//!
//! The settings are [`RoughnessSpec`]: lengths with their unit
//! (`window = ["468 um", "733 um"]`, `cutoff = "0.25 mm"`, …).

use super::{settings, Consumes, FileInput, Output, PlanContext, Stage, StagePlan, Tables};
use crate::error::Result;
use crate::extract::roughness::input::{take_surfaces, AxisUnits};
use crate::extract::roughness::stage::{
    acf_table, analyze_surfaces, bearing_table, psd_table, roughness_table, RoughnessSpec,
};
use crate::extract::roughness::RoughnessParams;
use crate::ingest::kind::DataKind;
use crate::report::figures::{self, file_figures_table};
use crate::schema::{Show, TableDef};

/// The registry entry.
pub struct Roughness;

/// The stage's name in pipeline files.
const NAME: &str = "roughness";

/// One row per profile or map.
pub static ROUGHNESS: TableDef = TableDef::new(
    "roughness",
    include_str!("../../schemas/roughness.toml"),
    Show::PerFile(&[
        ("kind", "kind"),
        ("Ra_m", "Ra"),
        ("Rq_m", "Rq"),
        ("Rz_m", "Rz"),
        ("Rdq_deg", "Rdq"),
        ("Sa_m", "Sa"),
        ("Sq_m", "Sq"),
        ("Sdq_deg", "Sdq"),
        ("fractal_dimension", "D"),
        ("status", "status"),
    ]),
);

/// The bearing (Abbott–Firestone) curve of every profile and map.
pub static BEARING_CURVE: TableDef = TableDef::dataset(
    "bearing_curve",
    include_str!("../../schemas/bearing_curve.toml"),
    Show::Hidden,
);

/// The binned PSD of every profile and map (MODELS.md §10).
pub static PSD: TableDef =
    TableDef::dataset("psd", include_str!("../../schemas/psd.toml"), Show::Hidden);

/// The ACF of every profile and map along x, y and radially.
pub static ACF: TableDef =
    TableDef::dataset("acf", include_str!("../../schemas/acf.toml"), Show::Hidden);

/// Each surface as measured, with its window and bearing curve.
pub static ROUGHNESS_FIGURES: TableDef = file_figures_table("roughness_figures");

/// Every table of the stage.
static TABLES: &[&TableDef] = &[&ROUGHNESS, &BEARING_CURVE, &PSD, &ACF, &ROUGHNESS_FIGURES];

impl Stage for Roughness {
    fn name(&self) -> &'static str {
        NAME
    }
    fn about(&self) -> &'static str {
        "roughness parameters, bearing curve and contact length of profiles and areal maps"
    }
    fn tables(&self) -> &'static [&'static TableDef] {
        TABLES
    }
    fn plan(&self, table: toml::Table, ctx: &PlanContext) -> Result<Box<dyn StagePlan>> {
        let spec: RoughnessSpec = settings(NAME, table)?;
        let (params, units) = spec.plan()?;
        Ok(Box::new(RoughnessPlan {
            params,
            units,
            figures: ctx.figures,
        }))
    }
}

struct RoughnessPlan {
    params: RoughnessParams,
    units: AxisUnits,
    figures: bool,
}

impl StagePlan for RoughnessPlan {
    fn name(&self) -> &'static str {
        NAME
    }
    fn consumes(&self) -> Consumes {
        Consumes::Files(&[DataKind::Profile, DataKind::ArealMap])
    }
    fn produces(&self) -> Vec<&'static TableDef> {
        let mut out = vec![&ROUGHNESS, &BEARING_CURVE];
        if self.params.spectra {
            out.extend([&PSD, &ACF]);
        }
        if self.figures {
            out.push(&ROUGHNESS_FIGURES);
        }
        out
    }
    fn parameters(&self) -> serde_json::Value {
        serde_json::json!({ "analysis": self.params, "units": self.units })
    }
    fn references(&self) -> Vec<String> {
        vec![
            "MODELS.md §4 (surface roughness)".into(),
            "thesis Table 3.1, Eq. 3.14, 3.15".into(),
            "MODELS.md §10 (functional, spatial, hybrid and volume parameters)".into(),
            "ISO 16610-21 Gaussian profile filter".into(),
            "ISO 16610-31 robust Gaussian regression filter".into(),
            "ISO 13565-1 valley suppression, ISO 13565-2 Rk family".into(),
            "ISO 25178-2 areal parameters".into(),
            "Jacobs, Junge, Pastewka 2017 (PSD); Sanner et al. 2022 (tip reliability)".into(),
        ]
    }
    fn run_file(&self, file: FileInput) -> Result<Tables> {
        let mut dataset = file.dataset;
        let surfaces = take_surfaces(&mut dataset, &self.units)?;
        // The figures' thinned lines need no result: drawn beside the analysis.
        let (f, thinned) = rayon::join(
            || analyze_surfaces(&dataset, &surfaces, &self.params, &self.units),
            || self.figures.then(|| figures::roughness::thin(&surfaces)),
        );
        let mut f = f?;
        let row = file.manifest.and_then(|m| m.find(file.path));
        let field = |k: &str| row.and_then(|r| r.fields.get(k).cloned());
        (f.sample_id, f.pin) = (field("sample_id"), field("pin"));
        let reports: Vec<_> = f.reports.iter().collect();
        let table = roughness_table(std::slice::from_ref(&f), &self.params)?;
        let bearing = bearing_table(&reports)?;
        let mut out: Tables = vec![(&ROUGHNESS, table), (&BEARING_CURVE, bearing)];
        if self.params.spectra {
            out.push((&PSD, psd_table(&reports)?));
            out.push((&ACF, acf_table(&reports)?));
        }
        if let Some(thinned) = thinned {
            let drawn =
                figures::roughness::figures(&f.source, &surfaces, thinned, &f, &self.params);
            out.push((&ROUGHNESS_FIGURES, figures::to_table(&drawn)?));
        }
        Ok(out)
    }
    fn assemble(&self, tables: Tables) -> Result<Output> {
        let mut out = Output::new(tables);
        // Each row holds Rq (a profile) or Sq (a map), never both: a row
        // with neither has no result.
        let rows = out.table(&ROUGHNESS).map_or(0, |t| t.height());
        let missing = super::nulls(&out.tables, &ROUGHNESS, "Rq_m")?
            + super::nulls(&out.tables, &ROUGHNESS, "Sq_m")?;
        out.without_result = missing.saturating_sub(rows);
        Ok(out)
    }
}
