//! The `ice-grid` stage (MODELS.md §6): the Makkonen film model and its
//! roughness bounds evaluated on a grid of (v, T, a, φ), for plots and
//! comparisons, as the table `ice_grid`.
//!
//! ```toml
//! [ice-grid]
//! v = [0.025, 1.0, 40]          # lowest, highest (m/s), count; log-spaced
//! t = [-17.0, -10.0, -2.0]      # bulk temperatures, °C
//! a = [1e-5, 1e-4]              # contact lengths, m
//! phi = [7.3, 27.2, 33.6]       # slopes (Rdq), degrees
//! delta_t = 0.05                # optional interface ΔT, K
//! mu_max = 1.0                  # larger μ is out_of_validity
//! ```

use serde::{Deserialize, Serialize};

use super::{settings, Consumes, Output, PlanContext, Progress, Stage, StagePlan, TableInputs};
use crate::error::{Error, Result};
use crate::models::makkonen::{MakkonenParams, Thermal};
use crate::schema::{Show, TableDef};
use crate::simulate::ice::{logspace, simulate_ice, IceGrid as Grid};

/// The registry entry.
pub struct IceGrid;

/// The stage's name in pipeline files.
const NAME: &str = "ice-grid";

/// One row per grid point (v, T, a, φ).
pub static ICE_GRID: TableDef = TableDef::new(
    "ice_grid",
    include_str!("../../schemas/ice_grid.toml"),
    Show::Hidden,
);

/// The stage's settings as written.
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct IceGridSettings {
    /// Velocity range: lowest, highest (m/s) and count, log-spaced.
    pub v: [f64; 3],
    /// Bulk temperatures, °C.
    pub t: Vec<f64>,
    /// Contact lengths, m.
    pub a: Vec<f64>,
    /// Slopes φ (Rdq), degrees.
    pub phi: Vec<f64>,
    /// Interface ΔT (K) instead of T_m − T_bulk.
    pub delta_t: Option<f64>,
    /// Largest credible μ; points above it are `out_of_validity`
    /// (default 1).
    pub mu_max: Option<f64>,
}

impl Default for IceGridSettings {
    fn default() -> Self {
        IceGridSettings {
            v: [0.025, 1.0, 40.0],
            t: vec![-17.0, -10.0, -2.0],
            a: vec![1e-5, 1e-4],
            phi: vec![7.3, 27.2, 33.6],
            delta_t: None,
            mu_max: None,
        }
    }
}

impl IceGridSettings {
    /// The grid these settings describe.
    pub fn grid(&self) -> Result<Grid> {
        let [lo, hi, n] = self.v;
        if n.fract() != 0.0 || n < 2.0 {
            return Err(Error::Config(format!(
                "[ice-grid] v = [{lo}, {hi}, {n}]: the count must be a whole number ≥ 2"
            )));
        }
        Ok(Grid {
            velocities_m_per_s: logspace(lo, hi, n as usize)?,
            temperatures_c: self.t.clone(),
            a_m: self.a.clone(),
            phi_deg: self.phi.clone(),
            model: MakkonenParams::default(),
            thermal: self
                .delta_t
                .map_or(Thermal::Bulk, |d| Thermal::Interface { delta_t: d }),
            mu_max: self.mu_max.unwrap_or(1.0),
        })
    }
}

/// Every table of the stage.
static TABLES: &[&TableDef] = &[&ICE_GRID];

impl Stage for IceGrid {
    fn name(&self) -> &'static str {
        NAME
    }
    fn about(&self) -> &'static str {
        "Makkonen ice-friction model with ALSFM bounds on a (v, T, a, phi) grid"
    }
    fn tables(&self) -> &'static [&'static TableDef] {
        TABLES
    }
    fn plan(&self, table: toml::Table, _ctx: &PlanContext) -> Result<Box<dyn StagePlan>> {
        let s: IceGridSettings = settings(NAME, table)?;
        let grid = s.grid()?;
        grid.model.validate()?;
        Ok(Box::new(GridPlan { grid }))
    }
}

struct GridPlan {
    grid: Grid,
}

impl StagePlan for GridPlan {
    fn name(&self) -> &'static str {
        NAME
    }
    fn consumes(&self) -> Consumes {
        Consumes::Tables(Vec::new())
    }
    fn produces(&self) -> Vec<&'static TableDef> {
        vec![&ICE_GRID]
    }
    fn parameters(&self) -> serde_json::Value {
        serde_json::to_value(&self.grid).unwrap_or_default()
    }
    fn references(&self) -> Vec<String> {
        vec![
            "MODELS.md §6 (Makkonen model with ALSFM roughness)".into(),
            "thesis Eq. 3.8 (corrected), 3.11, 3.12, Table 3.2".into(),
        ]
    }
    fn run_tables(&self, _inputs: &TableInputs, _progress: &dyn Progress) -> Result<Output> {
        let t = simulate_ice(&self.grid)?;
        let without = t.null_count("mu_upper")?;
        let mut out = Output::new(vec![(&ICE_GRID, t)]);
        out.without_result = without;
        Ok(out)
    }
}
