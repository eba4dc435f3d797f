//! Output rows of an ALSFM run and their tables (schemas in
//! `schemas/alsfm*.toml`).

use crate::error::Result;
use crate::models::alsfm::instant::Instant;
use crate::models::alsfm::series::ContactMap;
use crate::models::alsfm::solver::PointResult;
use crate::table::{Table, TableBuilder};

/// One scene point (`alsfm.parquet`).
#[derive(Debug, Clone, PartialEq)]
pub struct PointRow {
    /// β, degrees.
    pub beta_deg: f64,
    /// L, N per spring.
    pub load: f64,
    /// Time-averaged μ (outermost level with hierarchy).
    pub mu: Option<f64>,
    /// μ_∥.
    pub mu_parallel: Option<f64>,
    /// μ_⊥.
    pub mu_perp: Option<f64>,
    /// Mean |R_xy|, N per spring.
    pub r_xy: Option<f64>,
    /// Path taken.
    pub path: String,
    /// Lattice points (0: analytic path).
    pub springs: i64,
    /// Instants per period.
    pub steps: i64,
    /// Largest fraction of springs in tension.
    pub tension_fraction: Option<f64>,
    /// Tolerance refinement converged.
    pub converged: Option<bool>,
    /// Hierarchical levels evaluated.
    pub levels: i64,
    /// Level at which the surfaces lock.
    pub locked_level: Option<i64>,
    /// `ok`, `locked`, `no_contact`, `not_converged`, `averaged_window`, ...
    pub status: String,
    /// Details.
    pub message: String,
}

/// Status of a point without an exact period of the relative motion: μ is
/// the average over a stated sliding distance, a result but not an exact
/// one.
pub const AVERAGED_WINDOW: &str = "averaged_window";

impl PointRow {
    /// Whether the row carries a result: `ok`, `no_coefficient` (R_xy at
    /// L ≤ 0) or `averaged_window` (μ over the stated window).
    pub fn has_result(&self) -> bool {
        matches!(
            self.status.as_str(),
            "ok" | "no_coefficient" | AVERAGED_WINDOW
        )
    }

    /// A row from an evaluated point.
    pub fn from_result(beta_deg: f64, load: f64, r: &PointResult) -> Self {
        let (status, message) = if r.converged == Some(false) {
            (
                "not_converged",
                format!(
                    "lattice refinement stopped at max_points; last change of mu {:.3e}",
                    r.refinement_change.unwrap_or(f64::NAN)
                ),
            )
        } else if !r.whole_periods {
            (
                AVERAGED_WINDOW,
                format!(
                    "beta = {beta_deg} deg has no period on the lattice window within 16 spans \
                     of either axis (an irrational direction on the periodic surfaces); \
                     mu is the average over a sliding distance of {:.6e} m (16 spans)",
                    r.averaged_distance.unwrap_or(f64::NAN)
                ),
            )
        } else if r.mu.is_none() {
            (
                "no_coefficient",
                "L <= 0: mu is undefined, see r_xy_N (adhesion)".to_string(),
            )
        } else {
            ("ok", String::new())
        };
        PointRow {
            beta_deg,
            load,
            mu: r.mu,
            mu_parallel: r.mu_parallel,
            mu_perp: r.mu_perp,
            r_xy: Some(r.r_xy),
            path: r.path.name().into(),
            springs: r.springs as i64,
            steps: r.steps as i64,
            tension_fraction: Some(r.tension_fraction),
            converged: r.converged,
            levels: 1,
            locked_level: None,
            status: status.into(),
            message,
        }
    }

    /// A row for a point that could not be evaluated.
    pub fn failed(beta_deg: f64, load: f64, status: &str, message: String) -> Self {
        PointRow {
            beta_deg,
            load,
            mu: None,
            mu_parallel: None,
            mu_perp: None,
            r_xy: None,
            path: "none".into(),
            springs: 0,
            steps: 0,
            tension_fraction: None,
            converged: None,
            levels: 1,
            locked_level: if status == "locked" { Some(1) } else { None },
            status: status.into(),
            message,
        }
    }
}

/// One instant of μ(t) (`alsfm_time_series.parquet`).
#[derive(Debug, Clone, PartialEq)]
pub struct SeriesRow {
    /// β, degrees.
    pub beta_deg: f64,
    /// L, N per spring.
    pub load: f64,
    /// Instant index.
    pub step: i64,
    /// Sliding distance, m.
    pub distance_m: f64,
    /// Time, s.
    pub time_s: f64,
    /// μ(t) (null for L ≤ 0).
    pub mu: Option<f64>,
    /// μ_∥(t).
    pub mu_parallel: Option<f64>,
    /// μ_⊥(t).
    pub mu_perp: Option<f64>,
    /// R_x, N per spring.
    pub r_x: f64,
    /// R_y, N per spring.
    pub r_y: f64,
    /// R_z^(c), compressive only, N per spring.
    pub r_zc: f64,
    /// Springs in compression.
    pub n_compressed: i64,
    /// Springs in tension.
    pub n_tension: i64,
}

impl SeriesRow {
    /// A row from an instant.
    pub fn new(
        beta_deg: f64,
        load: f64,
        step: i64,
        distance_m: f64,
        time_s: f64,
        i: &Instant,
        (c, s): (f64, f64),
    ) -> Self {
        let m = i.mu(c, s);
        SeriesRow {
            beta_deg,
            load,
            step,
            distance_m,
            time_s,
            mu: m.map(|m| m.0),
            mu_parallel: m.map(|m| m.1),
            mu_perp: m.map(|m| m.2),
            r_x: i.r_x,
            r_y: i.r_y,
            r_zc: i.r_zc,
            n_compressed: i.n_compressed as i64,
            n_tension: i.n_tension as i64,
        }
    }
}

/// R_xy against L (`alsfm_adhesion.parquet`).
#[derive(Debug, Clone, PartialEq)]
pub struct AdhesionRow {
    /// β, degrees.
    pub beta_deg: f64,
    /// L, N per spring.
    pub load: f64,
    /// Mean |R_xy| of the compressed springs, N per spring.
    pub r_xy: Option<f64>,
    /// μ_a = R_xy / L (Eq. 2.2), null for L ≤ 0.
    pub mu_apparent: Option<f64>,
    /// Largest fraction of springs in tension.
    pub tension_fraction: Option<f64>,
    /// Status of the point.
    pub status: String,
}

impl AdhesionRow {
    /// From a point row and its evaluation.
    pub fn from_point(p: &PointRow, r: Option<&PointResult>) -> Self {
        AdhesionRow {
            beta_deg: p.beta_deg,
            load: p.load,
            r_xy: r.map(|r| r.r_xy),
            mu_apparent: r.and_then(|r| r.mu),
            tension_fraction: r.map(|r| r.tension_fraction),
            status: p.status.clone(),
        }
    }
}

/// μ against wear time (`alsfm_wear.parquet`).
#[derive(Debug, Clone, PartialEq)]
pub struct WearRow {
    /// β, degrees.
    pub beta_deg: f64,
    /// L, N per spring.
    pub load: f64,
    /// Time, s.
    pub time_s: f64,
    /// B of the wearing level.
    pub reduction_b: f64,
    /// Level wearing (0: all levels together, no hierarchical wear).
    pub wearing_level: i64,
    /// μ (outermost level).
    pub mu: Option<f64>,
    /// Status.
    pub status: String,
    /// Details.
    pub message: String,
}

/// μ per hierarchical level (`alsfm_hierarchy.parquet`).
#[derive(Debug, Clone, PartialEq)]
pub struct HierarchyRow {
    /// β, degrees.
    pub beta_deg: f64,
    /// L, N per spring.
    pub load: f64,
    /// Level (0: local μ0).
    pub level: i64,
    /// μ_level; null where the surfaces lock.
    pub mu: Option<f64>,
    /// `ok` or `locked`.
    pub status: String,
    /// Details.
    pub message: String,
}

/// One spring at one instant (`alsfm_contact_map.parquet`).
#[derive(Debug, Clone, PartialEq)]
pub struct MapRow {
    /// β, degrees.
    pub beta_deg: f64,
    /// L, N per spring.
    pub load: f64,
    /// Instant index.
    pub step: i64,
    /// x, m.
    pub x_m: f64,
    /// y, m.
    pub y_m: f64,
    /// Axial force, N (compressive > 0).
    pub force_n: f64,
    /// `compressed`, `tension` or `slack`.
    pub state: &'static str,
}

impl MapRow {
    /// Rows from a contact map.
    pub fn from_map(beta_deg: f64, load: f64, m: &ContactMap) -> Vec<MapRow> {
        (0..m.force.len())
            .map(|k| MapRow {
                beta_deg,
                load,
                step: m.step as i64,
                x_m: m.x[k],
                y_m: m.y[k],
                force_n: m.force[k],
                state: if m.force[k] > 0.0 {
                    "compressed"
                } else if m.force[k] < 0.0 {
                    "tension"
                } else {
                    "slack"
                },
            })
            .collect()
    }
}

/// Everything an ALSFM run produces, rows in plan order.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct AlsfmOutput {
    /// `alsfm`.
    pub points: Vec<PointRow>,
    /// `alsfm_time_series`.
    pub series: Vec<SeriesRow>,
    /// `alsfm_adhesion`.
    pub adhesion: Vec<AdhesionRow>,
    /// `alsfm_wear`.
    pub wear: Vec<WearRow>,
    /// `alsfm_hierarchy`.
    pub hierarchy: Vec<HierarchyRow>,
    /// `alsfm_contact_map`.
    pub maps: Vec<MapRow>,
}

macro_rules! col {
    ($rows:expr, $f:ident) => {
        $rows.iter().map(|r| r.$f)
    };
}

impl AlsfmOutput {
    /// Appends another output's rows.
    pub fn append(&mut self, o: AlsfmOutput) {
        self.points.extend(o.points);
        self.series.extend(o.series);
        self.adhesion.extend(o.adhesion);
        self.wear.extend(o.wear);
        self.hierarchy.extend(o.hierarchy);
        self.maps.extend(o.maps);
    }

    /// Scene points that failed: status other than `ok`, `no_coefficient`
    /// (L ≤ 0 with adhesion, where R_xy is the result) and
    /// `averaged_window` (a result over a stated window).
    pub fn failures(&self) -> usize {
        self.points.iter().filter(|p| !p.has_result()).count()
    }

    /// The `alsfm` table: one row per (β, load).
    pub fn points_table(&self) -> Result<Table> {
        let p = &self.points;
        TableBuilder::new()
            .f64_values("beta_deg", col!(p, beta_deg))
            .f64_values("load", col!(p, load))
            .f64("mu", col!(p, mu))
            .f64("mu_parallel", col!(p, mu_parallel))
            .f64("mu_perp", col!(p, mu_perp))
            .f64("r_xy_N", col!(p, r_xy))
            .str("path", p.iter().map(|r| Some(r.path.as_str())))
            .i64("springs", p.iter().map(|r| Some(r.springs)))
            .i64("steps", p.iter().map(|r| Some(r.steps)))
            .f64("tension_fraction", col!(p, tension_fraction))
            .bool("converged", col!(p, converged))
            .i64("levels", p.iter().map(|r| Some(r.levels)))
            .i64("locked_level", col!(p, locked_level))
            .str("status", p.iter().map(|r| Some(r.status.as_str())))
            .str("message", p.iter().map(|r| Some(r.message.as_str())))
            .build()
    }

    /// The `alsfm_time_series` table: one row per instant.
    pub fn series_table(&self) -> Result<Table> {
        let s = &self.series;
        TableBuilder::new()
            .f64_values("beta_deg", col!(s, beta_deg))
            .f64_values("load", col!(s, load))
            .i64("step", s.iter().map(|r| Some(r.step)))
            .f64_values("distance_m", col!(s, distance_m))
            .f64_values("time_s", col!(s, time_s))
            .f64("mu", col!(s, mu))
            .f64("mu_parallel", col!(s, mu_parallel))
            .f64("mu_perp", col!(s, mu_perp))
            .f64_values("r_x_N", col!(s, r_x))
            .f64_values("r_y_N", col!(s, r_y))
            .f64_values("r_zc_N", col!(s, r_zc))
            .i64("n_compressed", s.iter().map(|r| Some(r.n_compressed)))
            .i64("n_tension", s.iter().map(|r| Some(r.n_tension)))
            .build()
    }

    /// The `alsfm_adhesion` table: R_xy per (β, load).
    pub fn adhesion_table(&self) -> Result<Table> {
        let a = &self.adhesion;
        TableBuilder::new()
            .f64_values("beta_deg", col!(a, beta_deg))
            .f64_values("load", col!(a, load))
            .f64("r_xy_N", col!(a, r_xy))
            .f64("mu_apparent", col!(a, mu_apparent))
            .f64("tension_fraction", col!(a, tension_fraction))
            .str("status", a.iter().map(|r| Some(r.status.as_str())))
            .build()
    }

    /// The `alsfm_wear` table.
    pub fn wear_table(&self) -> Result<Table> {
        let w = &self.wear;
        TableBuilder::new()
            .f64_values("beta_deg", col!(w, beta_deg))
            .f64_values("load", col!(w, load))
            .f64_values("time_s", col!(w, time_s))
            .f64_values("reduction_b", col!(w, reduction_b))
            .i64("wearing_level", w.iter().map(|r| Some(r.wearing_level)))
            .f64("mu", col!(w, mu))
            .str("status", w.iter().map(|r| Some(r.status.as_str())))
            .str("message", w.iter().map(|r| Some(r.message.as_str())))
            .build()
    }

    /// The `alsfm_hierarchy` table.
    pub fn hierarchy_table(&self) -> Result<Table> {
        let h = &self.hierarchy;
        TableBuilder::new()
            .f64_values("beta_deg", col!(h, beta_deg))
            .f64_values("load", col!(h, load))
            .i64("level", h.iter().map(|r| Some(r.level)))
            .f64("mu", col!(h, mu))
            .str("status", h.iter().map(|r| Some(r.status.as_str())))
            .str("message", h.iter().map(|r| Some(r.message.as_str())))
            .build()
    }

    /// The `alsfm_contact_map` table.
    pub fn map_table(&self) -> Result<Table> {
        let m = &self.maps;
        TableBuilder::new()
            .f64_values("beta_deg", col!(m, beta_deg))
            .f64_values("load", col!(m, load))
            .i64("step", m.iter().map(|r| Some(r.step)))
            .f64_values("x_m", col!(m, x_m))
            .f64_values("y_m", col!(m, y_m))
            .f64_values("force_N", col!(m, force_n))
            .str("state", m.iter().map(|r| Some(r.state)))
            .build()
    }
}
