//! The roughness stage: settings as written by a user (command line or a
//! pipeline's `[roughness]` table, lengths with their unit), validated into
//! [`RoughnessParams`]; the analysis of one file; the `roughness` and
//! `bearing_curve` tables.
//!
//! ```toml
//! [roughness]
//! window = ["468 um", "733 um"]   # evaluation window along x, inclusive
//! window_y = ["0 mm", "1 mm"]     # along y, for areal maps
//! detrend = "line"                # none | mean | line
//! cutoff = "0.25 mm"              # Gaussian filter λc; omit for no filter
//! filter_ends = "discard"         # discard | renormalize
//! derivative = "iso7_point"       # forward | central | iso7_point
//! fractal_method = "structure_function"   # or power_spectrum
//! x_unit = "mm"                   # when the file gives none
//! z_unit = "um"
//! spacing = ["1 um", "1 um"]      # Δx, Δy of a z matrix that does not state them
//! nominal_pressure = "0.085 MPa"  # with hardness: contact length
//! hardness = "25.35 MPa"
//! ```

use serde::{Deserialize, Serialize};

use super::analyze::{analyze_map, analyze_profile, RoughnessReport, SurfaceKind};
use super::input::{surfaces_from_dataset, AxisUnits, Surface};
use super::params::{
    ContactParams, DerivativeScheme, Detrend, FractalMethod, FractalParams, RoughnessParams,
};
use crate::error::{Error, Result};
use crate::ingest::formats::dektak::analytical_results;
use crate::ingest::Dataset;
use crate::signal::gaussian_filter::{FilterEnds, GaussianFilterParams};
use crate::table::{Table, TableBuilder};
use crate::units::{parse_quantity, parse_unit, Quantity};

/// The `[roughness]` table of a pipeline file, or the command-line options.
#[derive(Debug, Clone, Default, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct RoughnessSpec {
    /// Evaluation window `[start, end]` along x, lengths with units
    /// (`"468 um"`).
    #[serde(default)]
    pub window: Option<[String; 2]>,
    /// Evaluation window along y for areal maps.
    #[serde(default)]
    pub window_y: Option<[String; 2]>,
    /// Sample spacing `[Δx, Δy]` of a z matrix (one row of heights per y)
    /// whose file does not state it, lengths with units.
    #[serde(default)]
    pub spacing: Option<[String; 2]>,
    /// Form removal. Default `line`.
    #[serde(default)]
    pub detrend: Option<Detrend>,
    /// Gaussian filter cut-off λc with unit; none for no filter.
    #[serde(default)]
    pub cutoff: Option<String>,
    /// Filter ends: `discard` (default) or `renormalize`.
    #[serde(default)]
    pub filter_ends: Option<FilterEnds>,
    /// Kernel half-width in cut-offs (default 1).
    #[serde(default)]
    pub filter_truncation: Option<f64>,
    /// Slope scheme. Default `iso7_point`.
    #[serde(default)]
    pub derivative: Option<DerivativeScheme>,
    /// Fractal method. Default `structure_function`.
    #[serde(default)]
    pub fractal_method: Option<FractalMethod>,
    /// Smallest lag in samples (default 1).
    #[serde(default)]
    pub fractal_min_lag: Option<usize>,
    /// Largest lag as a fraction of the length (default 0.1).
    #[serde(default)]
    pub fractal_max_lag_fraction: Option<f64>,
    /// Points of the bearing curve (default 101).
    #[serde(default)]
    pub bearing_points: Option<usize>,
    /// Unit of x (and y) when the file gives none, or to override it.
    #[serde(default)]
    pub x_unit: Option<String>,
    /// Unit of the heights when the file gives none, or to override it.
    #[serde(default)]
    pub z_unit: Option<String>,
    /// Nominal pressure σ with unit (`"0.085 MPa"`), for Eq. 3.14.
    #[serde(default)]
    pub nominal_pressure: Option<String>,
    /// Hardness H with unit (`"25 MPa"`), for Eq. 3.14.
    #[serde(default)]
    pub hardness: Option<String>,
}

fn check_length_unit(u: &Option<String>, what: &str) -> Result<()> {
    if let Some(u) = u {
        match parse_unit(u) {
            Some(p) if p.quantity == Quantity::Length => {}
            _ => {
                return Err(Error::Config(format!(
                    "{what} = '{u}'; expected a length unit (m, mm, um, nm)"
                )))
            }
        }
    }
    Ok(())
}

impl RoughnessSpec {
    /// Validates the spec into analysis parameters and axis units.
    pub fn plan(&self) -> Result<(RoughnessParams, AxisUnits)> {
        let d = RoughnessParams::default();
        let pair = |v: &Option<[String; 2]>, what: [&str; 2]| -> Result<Option<(f64, f64)>> {
            v.as_ref()
                .map(|[a, b]| {
                    Ok((
                        parse_quantity(a, Quantity::Length, what[0])?,
                        parse_quantity(b, Quantity::Length, what[1])?,
                    ))
                })
                .transpose()
        };
        let window = pair(&self.window, ["window start", "window end"])?;
        let window_y = pair(&self.window_y, ["window_y start", "window_y end"])?;
        let spacing = pair(&self.spacing, ["spacing x", "spacing y"])?;
        if let Some((sx, sy)) = spacing {
            if !(sx > 0.0 && sy > 0.0) {
                return Err(Error::Config(format!(
                    "spacing [{sx:e}, {sy:e}] m; expected both > 0"
                )));
            }
        }
        let filter = match &self.cutoff {
            Some(c) => {
                let mut f =
                    GaussianFilterParams::new(parse_quantity(c, Quantity::Length, "cutoff")?)?;
                if let Some(e) = self.filter_ends {
                    f.ends = e;
                }
                if let Some(t) = self.filter_truncation {
                    f.truncation = t;
                }
                f.validate()?;
                Some(f)
            }
            None => {
                if self.filter_ends.is_some() || self.filter_truncation.is_some() {
                    return Err(Error::Config(
                        "filter_ends / filter_truncation given without a cutoff".into(),
                    ));
                }
                None
            }
        };
        let fd = FractalParams::default();
        let contact = match (&self.nominal_pressure, &self.hardness) {
            (Some(p), Some(h)) => Some(ContactParams::new(
                parse_quantity(p, Quantity::Stress, "nominal_pressure")?,
                parse_quantity(h, Quantity::Stress, "hardness")?,
            )?),
            (None, None) => None,
            _ => {
                return Err(Error::Config(
                    "the contact length needs both nominal_pressure and hardness".into(),
                ))
            }
        };
        let params = RoughnessParams {
            window,
            window_y,
            detrend: self.detrend.unwrap_or(d.detrend),
            filter,
            derivative: self.derivative.unwrap_or(d.derivative),
            fractal: FractalParams {
                method: self.fractal_method.unwrap_or(fd.method),
                min_lag: self.fractal_min_lag.unwrap_or(fd.min_lag),
                max_lag_fraction: self.fractal_max_lag_fraction.unwrap_or(fd.max_lag_fraction),
            },
            bearing_points: self.bearing_points.unwrap_or(d.bearing_points),
            contact,
        };
        params.validate()?;
        check_length_unit(&self.x_unit, "x_unit")?;
        check_length_unit(&self.z_unit, "z_unit")?;
        let units = AxisUnits {
            x: self.x_unit.clone(),
            z: self.z_unit.clone(),
            spacing,
        };
        Ok((params, units))
    }
}

/// Everything the stage produced for one file.
#[derive(Debug, Clone)]
pub struct RoughnessFile {
    /// The path as given.
    pub source: String,
    /// One report per profile or map in the file.
    pub reports: Vec<RoughnessReport>,
    /// `sample_id` and `pin` of the file's row in the sample manifest, so
    /// that the table joins the friction tables (and `tribo fit ice`).
    pub sample_id: Option<String>,
    /// See `sample_id`.
    pub pin: Option<String>,
    /// The instrument's own results printed in the file (the Dektak's
    /// "Analytical Results"), written next to ours.
    pub instrument: InstrumentRoughness,
}

/// Roughness results an instrument printed in its export, in SI, with the
/// cursor window they were computed on.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct InstrumentRoughness {
    /// Ra (m).
    pub ra: Option<f64>,
    /// Rq (m).
    pub rq: Option<f64>,
    /// Skewness.
    pub rsk: Option<f64>,
    /// Rz by DIN 4768 (m).
    pub rz_din: Option<f64>,
    /// Cursor window (m): the R and M cursor positions, ordered.
    pub window: Option<(f64, f64)>,
}

impl InstrumentRoughness {
    /// The printed results of a Dektak export; empty for other formats.
    pub fn from_dataset(ds: &Dataset) -> Self {
        if ds.format != "dektak" {
            return Self::default();
        }
        let results = analytical_results(&ds.preamble);
        let get = |f: &str| results.iter().find(|r| r.function.eq_ignore_ascii_case(f));
        let window = results
            .first()
            .map(|r| (r.r_cursor.min(r.m_cursor), r.r_cursor.max(r.m_cursor)));
        InstrumentRoughness {
            ra: get("Ra").map(|r| r.value),
            rq: get("Rq").map(|r| r.value),
            rsk: get("Skew").map(|r| r.value),
            rz_din: get("RzDin").map(|r| r.value),
            window,
        }
    }
}

/// Analyses every profile and map of a file already read.
pub fn analyze_dataset(
    ds: &Dataset,
    params: &RoughnessParams,
    units: &AxisUnits,
) -> Result<RoughnessFile> {
    analyze_surfaces(ds, &surfaces_from_dataset(ds, units)?, params)
}

/// As [`analyze_dataset`], on the file's surfaces already taken from it
/// (the stage draws them too).
pub fn analyze_surfaces(
    ds: &Dataset,
    surfaces: &[Surface],
    params: &RoughnessParams,
) -> Result<RoughnessFile> {
    let reports = surfaces
        .iter()
        .map(|s| match s {
            Surface::Profile(p) => analyze_profile(p, params),
            Surface::Map(m) => analyze_map(m, params),
        })
        .collect::<Result<Vec<_>>>()?;
    // Heights near 1e154 m and beyond overflow Rq's squares: an error of
    // this file, not a null in a column that must hold a value.
    if reports.iter().any(|r| !r.rq.is_finite()) {
        return Err(Error::Numerical(format!(
            "{}: Rq is not finite: the heights are out of range for a surface \
             (their squares overflow); check the height column and its unit",
            ds.source.display()
        )));
    }
    Ok(RoughnessFile {
        source: ds.source.display().to_string(),
        reports,
        sample_id: None,
        pin: None,
        instrument: InstrumentRoughness::from_dataset(ds),
    })
}

/// The `roughness` table: one row per profile or map, with the manifest's
/// `sample_id` and `pin` and the settings. Profiles fill the R columns
/// (ISO 4287), maps the S columns (ISO 25178-2); the other family is null.
pub fn roughness_table(files: &[RoughnessFile], params: &RoughnessParams) -> Result<Table> {
    let rows: Vec<(&RoughnessFile, &RoughnessReport)> = files
        .iter()
        .flat_map(|f| f.reports.iter().map(move |r| (f, r)))
        .collect();
    let reports: Vec<&RoughnessReport> = rows.iter().map(|r| r.1).collect();
    let n = reports.len();
    let rep = |v: Option<f64>| std::iter::repeat_n(v, n);
    let reps = |v: &str| std::iter::repeat_n(Some(v.to_string()), n);
    let f = params.filter;
    let t = TableBuilder::new()
        .str("source", reports.iter().map(|r| Some(r.source.clone())))
        .str("sample_id", rows.iter().map(|r| r.0.sample_id.clone()))
        .str("pin", rows.iter().map(|r| r.0.pin.clone()))
        .str("kind", reports.iter().map(|r| Some(r.kind.as_str())))
        .i64("n_points", reports.iter().map(|r| Some(r.n_points as i64)))
        .f64("length_m", reports.iter().map(|r| Some(r.length)));
    let t = family_columns(t, &reports, SurfaceKind::Profile);
    let t = family_columns(t, &reports, SurfaceKind::Areal);
    let t = instrument_columns(t, &rows);
    t.f64(
        "fractal_dimension",
        reports
            .iter()
            .map(|r| r.fractal.as_ref().and_then(|e| e.dimension)),
    )
    .f64(
        "hurst_exponent",
        reports.iter().map(|r| r.fractal.as_ref().map(|e| e.hurst)),
    )
    .f64(
        "fractal_r_squared",
        reports
            .iter()
            .map(|r| r.fractal.as_ref().map(|e| e.r_squared)),
    )
    .f64(
        "area_ratio",
        reports.iter().map(|r| r.contact.map(|c| c.area_ratio)),
    )
    .f64(
        "contact_depth_m",
        reports.iter().map(|r| r.contact.map(|c| c.depth)),
    )
    .f64(
        "contact_length_m",
        reports.iter().map(|r| r.contact.map(|c| c.length)),
    )
    .str("status", reports.iter().map(|r| Some(r.status())))
    .f64("window_start_m", rep(params.window.map(|w| w.0)))
    .f64("window_end_m", rep(params.window.map(|w| w.1)))
    .f64("window_y_start_m", rep(params.window_y.map(|w| w.0)))
    .f64("window_y_end_m", rep(params.window_y.map(|w| w.1)))
    .str("detrend", reps(&snake(&params.detrend)))
    .f64("filter_cutoff_m", rep(f.map(|f| f.cutoff)))
    .str(
        "filter_ends",
        std::iter::repeat_n(f.map(|f| snake(&f.ends)), n),
    )
    .str("derivative", reps(&snake(&params.derivative)))
    .str("fractal_method", reps(&snake(&params.fractal.method)))
    .build()
}

/// The amplitude, slope and height columns of one family: R-names for
/// profiles, S-names for maps; null on the rows of the other kind.
fn family_columns(
    t: TableBuilder,
    reports: &[&RoughnessReport],
    kind: SurfaceKind,
) -> TableBuilder {
    let p = if kind == SurfaceKind::Profile {
        "R"
    } else {
        "S"
    };
    let col = |get: fn(&RoughnessReport) -> Option<f64>| {
        reports
            .iter()
            .map(move |r| if r.kind == kind { get(r) } else { None })
    };
    let t = t
        .f64(&format!("{p}a_m"), col(|r| Some(r.ra)))
        .f64(&format!("{p}q_m"), col(|r| Some(r.rq)))
        .f64(&format!("{p}dq_deg"), col(|r| r.rdq_deg))
        .f64(&format!("{p}sk"), col(|r| r.rsk))
        .f64(&format!("{p}ku"), col(|r| r.rku))
        .f64(&format!("{p}p_m"), col(|r| Some(r.heights.peak)))
        .f64(&format!("{p}v_m"), col(|r| Some(r.heights.valley)));
    match kind {
        SurfaceKind::Profile => t
            .f64("Rt_m", col(|r| Some(r.heights.total)))
            .f64("Rz_m", col(|r| r.heights.rz_iso))
            .i64(
                "Rz_sampling_lengths",
                reports.iter().map(|r| {
                    (r.kind == kind && r.heights.rz_iso.is_some())
                        .then_some(r.heights.rz_sampling_lengths as i64)
                }),
            )
            .f64("Rz_DIN_m", col(|r| r.heights.rz_din)),
        SurfaceKind::Areal => t.f64("Sz_m", col(|r| Some(r.heights.total))),
    }
}

/// The instrument's printed results (null when the file prints none).
fn instrument_columns(
    t: TableBuilder,
    rows: &[(&RoughnessFile, &RoughnessReport)],
) -> TableBuilder {
    let col = |get: fn(&InstrumentRoughness) -> Option<f64>| {
        rows.iter().map(move |(f, _)| get(&f.instrument))
    };
    t.f64("instrument_Ra_m", col(|i| i.ra))
        .f64("instrument_Rq_m", col(|i| i.rq))
        .f64("instrument_Rsk", col(|i| i.rsk))
        .f64("instrument_Rz_DIN_m", col(|i| i.rz_din))
        .f64("instrument_window_start_m", col(|i| i.window.map(|w| w.0)))
        .f64("instrument_window_end_m", col(|i| i.window.map(|w| w.1)))
}

/// The `bearing_curve` table: material ratio and height for every report.
pub fn bearing_table(reports: &[&RoughnessReport]) -> Result<Table> {
    let rows: Vec<(&str, f64, f64)> = reports
        .iter()
        .flat_map(|r| r.bearing.iter().map(|&(m, h)| (r.source.as_str(), m, h)))
        .collect();
    TableBuilder::new()
        .str("source", rows.iter().map(|r| Some(r.0)))
        .f64("material_ratio", rows.iter().map(|r| Some(r.1)))
        .f64("height_m", rows.iter().map(|r| Some(r.2)))
        .build()
}

/// The serde (snake-case) name of a settings enum, for the table.
fn snake<T: Serialize>(v: &T) -> String {
    match serde_json::to_value(v) {
        Ok(serde_json::Value::String(s)) => s,
        Ok(v) => v.to_string(),
        Err(_) => String::new(),
    }
}
