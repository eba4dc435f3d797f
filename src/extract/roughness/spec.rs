//! The settings of the roughness stage as a user writes them (command line
//! or a pipeline's `[roughness]` table, lengths with their unit), validated
//! into [`RoughnessParams`]. Each stage of the ISO 25178-2/-3 chain is a
//! setting: `short_cutoff` (S-filter λs), `detrend` (F-operator: none,
//! mean, line, polynomial of `form_degree`, circle or cylinder of
//! `form_radius`), `cutoff` with `filter` (L-filter: gaussian, robust,
//! valley_suppression).
//!
//! ```toml
//! [roughness]
//! window = ["468 um", "733 um"]   # evaluation window along x, inclusive
//! window_y = ["0 mm", "1 mm"]     # along y, for areal maps
//! short_cutoff = "2.5 um"         # S-filter λs; omit for none
//! detrend = "line"                # none | mean | line | polynomial | circle
//! form_degree = 2                 # of polynomial
//! form_radius = "5 mm"            # of circle; fitted when absent
//! cutoff = "0.25 mm"              # L-filter λc; omit for no filter
//! filter = "gaussian"             # gaussian | robust | valley_suppression
//! filter_ends = "discard"         # discard | renormalize
//! derivative = "iso7_point"       # forward | central | iso7_point
//! fractal_method = "structure_function"   # or power_spectrum
//! rk_line = "least_squares"       # or secant
//! material_height = "0 um"        # c of Smr(c)
//! material_ratio = 0.1            # mr of Smc(mr)
//! volume_ratios = [0.1, 0.8]      # p, q of the volume parameters
//! tip_radius = "2 um"             # reliability cut-off; the file's by default
//! x_unit = "mm"                   # when the file gives none
//! z_unit = "um"
//! spacing = ["1 um", "1 um"]      # Δx, Δy of a z matrix that does not state them
//! nominal_pressure = "0.085 MPa"  # with hardness: contact length
//! hardness = "25.35 MPa"
//! ```

use serde::{Deserialize, Serialize};

use super::input::AxisUnits;
use super::material::RkLine;
use super::params::{
    ContactParams, DerivativeScheme, Detrend, FilterKind, FractalMethod, FractalParams,
    RoughnessParams,
};
use crate::error::{Error, Result};
use crate::signal::gaussian_filter::{FilterEnds, GaussianFilterParams};
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
    /// Form removal (F-operator): none | mean | line | polynomial | circle.
    /// Default `line`.
    #[serde(default)]
    pub detrend: Option<Detrend>,
    /// Degree of `detrend = "polynomial"` (default 2).
    #[serde(default)]
    pub form_degree: Option<usize>,
    /// Known radius of `detrend = "circle"` with unit; fitted when absent.
    #[serde(default)]
    pub form_radius: Option<String>,
    /// The S-filter's cut-off λs with unit (Gaussian); none when absent.
    #[serde(default)]
    pub short_cutoff: Option<String>,
    /// The L-filter: gaussian | robust | valley_suppression (default
    /// gaussian), with `cutoff`.
    #[serde(default)]
    pub filter: Option<FilterKind>,
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
    /// Largest fraction of points not measured (NaN) before a row gets a
    /// `too_many_invalid` status (default 0.1).
    #[serde(default)]
    pub max_invalid_fraction: Option<f64>,
    /// Equivalent line of the Rk construction: least_squares (default) or
    /// secant.
    #[serde(default)]
    pub rk_line: Option<RkLine>,
    /// Height c of Smr(c) / Rmr(c) with unit, from the reference line
    /// (default "0 m").
    #[serde(default)]
    pub material_height: Option<String>,
    /// Material ratio of Smc(mr) / Rmc(mr), a fraction (default 0.1).
    #[serde(default)]
    pub material_ratio: Option<f64>,
    /// Material ratios [p, q] of the volume parameters (default [0.1, 0.8]).
    #[serde(default)]
    pub volume_ratios: Option<[f64; 2]>,
    /// Threshold s of Sal and Str (default 0.2).
    #[serde(default)]
    pub acf_threshold: Option<f64>,
    /// The surface is periodic (synthetic): circular ACF, no window.
    #[serde(default)]
    pub periodic: Option<bool>,
    /// Compute the PSD and ACF tables (default true).
    #[serde(default)]
    pub spectra: Option<bool>,
    /// Stylus tip radius with unit, for the reliability cut-off (default:
    /// the file's, when it states one).
    #[serde(default)]
    pub tip_radius: Option<String>,
    /// Smallest r² of a fractal fit without a `poor_fit` status (default
    /// 0.9).
    #[serde(default)]
    pub fractal_min_r_squared: Option<f64>,
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
        let filter = self.gaussian_filter()?;
        let fd = FractalParams::default();
        let contact = self.contact()?;
        let length = |v: &Option<String>, what: &str| {
            v.as_ref()
                .map(|t| parse_quantity(t, Quantity::Length, what))
                .transpose()
        };
        let params = RoughnessParams {
            window,
            window_y,
            detrend: self.detrend.unwrap_or(d.detrend),
            short_cutoff: length(&self.short_cutoff, "short_cutoff")?,
            form_degree: self.form_degree.unwrap_or(d.form_degree),
            form_radius: length(&self.form_radius, "form_radius")?,
            filter,
            filter_kind: self.filter.unwrap_or(d.filter_kind),
            derivative: self.derivative.unwrap_or(d.derivative),
            fractal: FractalParams {
                method: self.fractal_method.unwrap_or(fd.method),
                min_lag: self.fractal_min_lag.unwrap_or(fd.min_lag),
                max_lag_fraction: self.fractal_max_lag_fraction.unwrap_or(fd.max_lag_fraction),
            },
            bearing_points: self.bearing_points.unwrap_or(d.bearing_points),
            contact,
            max_invalid_fraction: self.max_invalid_fraction.unwrap_or(d.max_invalid_fraction),
            rk_line: self.rk_line.unwrap_or(d.rk_line),
            material_height: length(&self.material_height, "material_height")?
                .unwrap_or(d.material_height),
            material_ratio: self.material_ratio.unwrap_or(d.material_ratio),
            volume_ratios: self.volume_ratios.map_or(d.volume_ratios, |[p, q]| (p, q)),
            acf_threshold: self.acf_threshold.unwrap_or(d.acf_threshold),
            periodic: self.periodic.unwrap_or(d.periodic),
            spectra: self.spectra.unwrap_or(d.spectra),
            tip_radius: length(&self.tip_radius, "tip_radius")?,
            fractal_min_r_squared: self
                .fractal_min_r_squared
                .unwrap_or(d.fractal_min_r_squared),
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

    /// The Gaussian filter of `cutoff` with its end and truncation options;
    /// those options without a cutoff are an error.
    fn gaussian_filter(&self) -> Result<Option<GaussianFilterParams>> {
        Ok(match &self.cutoff {
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
                if self.filter_ends.is_some()
                    || self.filter_truncation.is_some()
                    || self.filter.is_some()
                {
                    return Err(Error::Config(
                        "filter / filter_ends / filter_truncation given without a cutoff".into(),
                    ));
                }
                None
            }
        })
    }

    /// The contact-length parameters: both pressures or neither.
    fn contact(&self) -> Result<Option<ContactParams>> {
        Ok(match (&self.nominal_pressure, &self.hardness) {
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
        })
    }
}
