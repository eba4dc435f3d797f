//! The ALSFM scene file (TOML): what to simulate. Parsed with
//! `deny_unknown_fields` into [`SceneSpec`], then validated into
//! [`super::plan::Plan`] before any computation starts.
//!
//! ```toml
//! mu0 = 0.3                       # local coefficient μ0
//! beta_deg = [0.0, 45.0, 90.0]    # or 30.0, or { from = 0.0, to = 90.0, count = 7 }
//! load = 0.1                      # N per spring; or a list, or { from, to, count }
//!
//! [lower]                         # z1; kind = flat | wedges | sinusoid | profile | map | file
//! kind = "wedges"
//! phi_rise_deg = 21.8
//! wavelength = 1.0                # m
//!
//! [upper]                         # z2, the surface that slides
//! kind = "flat"
//!
//! [springs]                       # optional: k_c = 1 N/m, l0 = 1 m
//! [adhesion]                      # optional: k_t_over_k_c = 0.5
//! [wear]                          # optional: rate (m³/m), reference_volume (m³), area (m²), samples
//! [hierarchy]                     # optional: levels, scale = 10, wear = false
//! [motion]                        # optional: velocity = 1 m/s, duration (s)
//! [resolution]                    # optional: springs, springs_y, steps, tolerance, max_points
//! [outputs]                       # optional: time_series, adhesion, wear, hierarchy, contact_maps
//! ```
//!
//! Angles are in degrees in the file (the field names say so); lengths in m,
//! the load in N per spring (the mean axial spring force, = R_z).

use serde::de::Error as _;
use serde::{Deserialize, Deserializer, Serialize};

use crate::models::alsfm::surface::Surface;

/// A scene file.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SceneSpec {
    /// μ0, local Coulomb coefficient, ≥ 0.
    pub mu0: f64,
    /// β in degrees: one value, a list, or a range.
    pub beta_deg: Sweep,
    /// L in N per spring: one value, a list, or a range (≤ 0 only with
    /// adhesion).
    pub load: Sweep,
    /// z1, the lower surface.
    pub lower: SurfaceSpec,
    /// z2, the upper (sliding) surface.
    pub upper: SurfaceSpec,
    /// Spring stiffness and rest length.
    #[serde(default)]
    pub springs: Option<SpringsSpec>,
    /// Adhesion: springs may go into tension.
    #[serde(default)]
    pub adhesion: Option<AdhesionSpec>,
    /// Archard wear.
    #[serde(default)]
    pub wear: Option<WearSpec>,
    /// Self-similar hierarchy.
    #[serde(default)]
    pub hierarchy: Option<HierarchySpec>,
    /// Sliding velocity and duration.
    #[serde(default)]
    pub motion: Option<MotionSpec>,
    /// Lattice resolution or tolerance.
    #[serde(default)]
    pub resolution: Option<ResolutionSpec>,
    /// Extra tables.
    #[serde(default)]
    pub outputs: Option<Outputs>,
}

/// One value, a list, or an inclusive range with a count.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(untagged)]
pub enum Sweep {
    /// A single value.
    One(f64),
    /// Listed values.
    List(Vec<f64>),
    /// `count` values evenly spaced from `from` to `to` inclusive.
    Range(RangeSpec),
}

/// An inclusive range.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RangeSpec {
    /// First value.
    pub from: f64,
    /// Last value.
    pub to: f64,
    /// Number of values, ≥ 1 (1: only `from`).
    pub count: usize,
}

/// A surface: a shape of the model ([`Surface`], which reads its own
/// table and validates it), or a measured profile or map read from a
/// roughness file (any format `tribo roughness` reads), windowed and
/// detrended, then taken as one period ([`super::surface_file`]).
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(untagged)]
pub enum SurfaceSpec {
    /// `kind = "flat" | "wedges" | "sinusoid" | "profile" | "map"`.
    Shape(Surface),
    /// `kind = "file"`.
    File(SurfaceFileSpec),
}

impl<'de> Deserialize<'de> for SurfaceSpec {
    /// `kind = "file"` reads a [`SurfaceFileSpec`]; any other kind is the
    /// model's own.
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        let table = toml::Table::deserialize(d)?;
        let file = table.get("kind").and_then(toml::Value::as_str) == Some("file");
        let value = toml::Value::Table(table);
        let read = if file {
            value.try_into().map(SurfaceSpec::File)
        } else {
            value.try_into().map(SurfaceSpec::Shape)
        };
        read.map_err(|e| {
            let e = e.to_string();
            let hint = if e.contains("unknown variant") {
                ", or `file` (a measured surface)"
            } else {
                ""
            };
            D::Error::custom(format!("{}{hint}", e.trim_end()))
        })
    }
}

/// The marker of a file surface's table, `kind = "file"`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum FileKind {
    /// The only value.
    File,
}

/// `kind = "file"`: a surface from a profilometer export.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SurfaceFileSpec {
    /// Always `file`.
    pub kind: FileKind,
    /// Path, relative to the scene file.
    pub path: String,
    /// Which profile or map when the file holds several (1-based).
    #[serde(default)]
    pub section: Option<usize>,
    /// Unit of x (and y) when the file states none, e.g. `"mm"`.
    #[serde(default)]
    pub x_unit: Option<String>,
    /// Unit of the heights when the file states none, e.g. `"um"`.
    #[serde(default)]
    pub z_unit: Option<String>,
    /// `[Δx, Δy]` of a z matrix that does not state it (`"0.5 um"`).
    #[serde(default)]
    pub spacing: Option<[String; 2]>,
    /// Part of the file to use along x, `["468 um", "733 um"]`.
    #[serde(default)]
    pub window: Option<[String; 2]>,
    /// Part of a map to use along y.
    #[serde(default)]
    pub window_y: Option<[String; 2]>,
    /// Form removal: `none`, `mean` or `line` (default: plane or line).
    #[serde(default)]
    pub detrend: Option<crate::extract::roughness::Detrend>,
}

/// Springs.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SpringsSpec {
    /// k_c, N/m, default 1.
    #[serde(default)]
    pub k_c: Option<f64>,
    /// l0, m, default 1.
    #[serde(default)]
    pub l0: Option<f64>,
}

/// Adhesion (Sec. 2.1).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct AdhesionSpec {
    /// k_t / k_c, default 0.5 (MODELS.md §5), > 0.
    #[serde(default)]
    pub k_t_over_k_c: Option<f64>,
}

/// Wear (Sec. 2.2).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct WearSpec {
    /// W, m³/m, > 0.
    pub rate: f64,
    /// V0, m³; default `area` × (volume above the deepest valley per unit
    /// area of z1 + z2, of the innermost level).
    #[serde(default)]
    pub reference_volume: Option<f64>,
    /// Apparent area, m², for the default V0; default 1.
    #[serde(default)]
    pub area: Option<f64>,
    /// Instants from 0 to T_w (or to the end of hierarchical wear), ≥ 2,
    /// default 11.
    #[serde(default)]
    pub samples: Option<usize>,
}

/// Hierarchy (Sec. 2.3, 2.4).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct HierarchySpec {
    /// Number of levels n ≥ 1 (1 = no hierarchy).
    pub levels: usize,
    /// Scale factor between levels (A = B = C of Eq. 2.10), default 10, > 1.
    #[serde(default)]
    pub scale: Option<f64>,
    /// Hierarchical wear (Sec. 2.4): the innermost level wears first.
    #[serde(default)]
    pub wear: Option<bool>,
}

/// Motion.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MotionSpec {
    /// v, m/s, default 1, > 0.
    #[serde(default)]
    pub velocity: Option<f64>,
    /// Length of the time series, s; default one period.
    #[serde(default)]
    pub duration: Option<f64>,
}

/// Resolution.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ResolutionSpec {
    /// Lattice points along x over the window.
    #[serde(default)]
    pub springs: Option<usize>,
    /// Lattice points along y (2-D); default = `springs`.
    #[serde(default)]
    pub springs_y: Option<usize>,
    /// Instants per period; default one per lattice spacing.
    #[serde(default)]
    pub steps: Option<usize>,
    /// Refine the lattice until successive μ differ by less than this.
    #[serde(default)]
    pub tolerance: Option<f64>,
    /// Largest lattice for the refinement, default 65536 points.
    #[serde(default)]
    pub max_points: Option<usize>,
}

/// Which extra tables to write. `alsfm.parquet` is always written; the
/// wear and hierarchy tables need their sections ([`super::plan::Plan`]
/// checks).
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Outputs {
    /// `alsfm_time_series.parquet`: μ(t).
    #[serde(default)]
    pub time_series: bool,
    /// `alsfm_adhesion.parquet`: R_xy against L.
    #[serde(default)]
    pub adhesion: bool,
    /// `alsfm_wear.parquet`: μ against time (needs `[wear]`).
    #[serde(default)]
    pub wear: bool,
    /// `alsfm_hierarchy.parquet`: μ per level (needs `[hierarchy]`).
    #[serde(default)]
    pub hierarchy: bool,
    /// `alsfm_contact_map.parquet`: spring forces at these instants.
    #[serde(default)]
    pub contact_maps: Vec<usize>,
}
