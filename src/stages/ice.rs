//! The `ice` stage (MODELS.md §6): the Makkonen film model with the ALSFM
//! roughness bounds fitted to μ(v) per pin and temperature, as the tables
//! `ice_fit` and `ice_residuals`. The pin's slope (Rdq) and the
//! bearing-curve contact length come from the roughness table, joined on
//! the manifest's `pin`.
//!
//! ```toml
//! [ice]
//! delta_t = 0.05        # interface ΔT, K, instead of T_m − T_bulk
//! fit_delta_t = false   # fit ΔT jointly with a
//! misfit_tol = 0.15     # relative RMSE above which a fit is a misfit
//! ```

use serde::{Deserialize, Serialize};

use super::friction::tables::FRICTION_STEPS;
use super::roughness::ROUGHNESS;
use super::{
    add_figures, settings, Consumes, Need, Output, PlanContext, Progress, Stage, StagePlan,
    TableInputs,
};
use crate::error::{Error, Result};
use crate::fit::ice::table::{ice_fits, IceFits, PinRoughness};
use crate::fit::ice::IceFitParams;
use crate::models::makkonen::Thermal;
use crate::report::figures::{self, figures_table};
use crate::schema::{Show, TableDef};

/// The registry entry.
pub struct Ice;

/// The stage's name in pipeline files, and the model's in the report.
const NAME: &str = "ice";

/// One row per pin × temperature group and bound.
pub static ICE_FIT: TableDef = TableDef::new(
    "ice_fit",
    include_str!("../../schemas/ice_fit.toml"),
    Show::Model {
        model: NAME,
        columns: &[
            "group", "bound", "a_m", "a_se_m", "rmse", "misfit", "status",
        ],
    },
);

/// One row per observation used by a fit.
pub static ICE_RESIDUALS: TableDef = TableDef::new(
    "ice_residuals",
    include_str!("../../schemas/ice_residuals.toml"),
    Show::Hidden,
);

/// μ(v) with the model at both bounds, per group.
pub static ICE_FIGURES: TableDef = figures_table("ice_figures");

/// The stage's settings as written.
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct IceSettings {
    /// Interface ΔT, K; `None` for T_m − T_bulk.
    pub delta_t: Option<f64>,
    /// Fit ΔT jointly with a and report their correlation.
    pub fit_delta_t: bool,
    /// Relative RMSE above which a fit is flagged as a misfit.
    pub misfit_tol: f64,
}

impl Default for IceSettings {
    fn default() -> Self {
        IceSettings {
            delta_t: None,
            fit_delta_t: false,
            misfit_tol: IceFitParams::default().misfit_tol,
        }
    }
}

impl IceSettings {
    /// The fit parameters.
    pub fn params(&self) -> Result<IceFitParams> {
        if !(self.misfit_tol > 0.0 && self.misfit_tol.is_finite()) {
            return Err(Error::Config(format!(
                "[ice] misfit_tol = {}: expected > 0",
                self.misfit_tol
            )));
        }
        if let Some(d) = self.delta_t {
            if !(d >= 0.0 && d.is_finite()) {
                return Err(Error::Config(format!(
                    "[ice] delta_t = {d}: expected a ΔT ≥ 0 K"
                )));
            }
        }
        Ok(IceFitParams {
            thermal: self
                .delta_t
                .map_or(Thermal::Bulk, |d| Thermal::Interface { delta_t: d }),
            fit_delta_t: self.fit_delta_t,
            misfit_tol: self.misfit_tol,
            ..Default::default()
        })
    }
}

/// Every table of the stage.
static TABLES: &[&TableDef] = &[&ICE_FIT, &ICE_RESIDUALS, &ICE_FIGURES];

impl Stage for Ice {
    fn name(&self) -> &'static str {
        NAME
    }
    fn about(&self) -> &'static str {
        "Makkonen ice-friction model with ALSFM roughness bounds fitted to mu(v) (Eq. 3.8, 3.11, 3.12)"
    }
    fn tables(&self) -> &'static [&'static TableDef] {
        TABLES
    }
    fn plan(&self, table: toml::Table, ctx: &PlanContext) -> Result<Box<dyn StagePlan>> {
        let s: IceSettings = settings(NAME, table)?;
        Ok(Box::new(IcePlan {
            params: s.params()?,
            figures: ctx.figures,
        }))
    }
}

struct IcePlan {
    params: IceFitParams,
    figures: bool,
}

impl StagePlan for IcePlan {
    fn name(&self) -> &'static str {
        NAME
    }
    fn consumes(&self) -> Consumes {
        Consumes::Tables(vec![
            Need::required(&FRICTION_STEPS),
            Need::optional(&ROUGHNESS),
        ])
    }
    fn produces(&self) -> Vec<&'static TableDef> {
        match self.figures {
            true => vec![&ICE_FIT, &ICE_RESIDUALS, &ICE_FIGURES],
            false => vec![&ICE_FIT, &ICE_RESIDUALS],
        }
    }
    fn parameters(&self) -> serde_json::Value {
        serde_json::to_value(self.params).unwrap_or_default()
    }
    fn references(&self) -> Vec<String> {
        vec![
            "MODELS.md §6 (Makkonen model with ALSFM roughness)".into(),
            "thesis Eq. 3.2, 3.8 (corrected), 3.11, 3.12, Table 3.2".into(),
        ]
    }
    fn run_tables(&self, inputs: &TableInputs, _progress: &dyn Progress) -> Result<Output> {
        let rough = match inputs.get(&ROUGHNESS) {
            Some(t) => PinRoughness::from_table(t)?,
            None => PinRoughness::default(),
        };
        let steps = inputs.required(&FRICTION_STEPS)?;
        let IceFits {
            fit,
            residuals: res,
            rows,
        } = ice_fits(steps, &rough, &self.params)?;
        let status = fit.str("status")?;
        let failed = status
            .iter()
            .filter(|s| s.as_deref() != Some("converged"))
            .count();
        let flagged = fit
            .bool("misfit")?
            .iter()
            .filter(|m| **m == Some(true))
            .count();
        let drawn = self.figures.then(|| figures::fits::ice(NAME, &rows));
        let mut out = Output::new(vec![(&ICE_FIT, fit), (&ICE_RESIDUALS, res)]);
        if let Some(d) = drawn {
            add_figures(&mut out, &ICE_FIGURES, &d)?;
        }
        out.without_result = failed;
        if flagged > 0 {
            out.notes.push(format!(
                "{flagged} ice fits are flagged as misfits (see ice_fit.misfit)"
            ));
        }
        Ok(out)
    }
}
