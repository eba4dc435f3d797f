//! Settings of a roughness analysis, validated once before any computation.

use serde::Serialize;

use crate::error::{Error, Result};
use crate::signal::gaussian_filter::GaussianFilterParams;

/// Form removal applied to the evaluation window before filtering.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Detrend {
    /// Heights used as given: the reference line is z = 0.
    None,
    /// Subtract the mean height.
    Mean,
    /// Subtract the least-squares line (profiles) or plane (maps). Default
    /// (MODELS.md §4).
    Line,
}

/// Finite-difference scheme for the local slope dz/dx (Rdq). Rdq differs by
/// about 0.1 % between schemes on real profiles (MODELS.md §4).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum DerivativeScheme {
    /// (z\[i+1\] − z\[i\]) / Δx over the n − 1 intervals. What SurfaceTopography's
    /// `rms_slope_from_profile` uses.
    Forward,
    /// (z[i+1] − z[i−1]) / (2Δx) at the n − 2 interior points. Second order.
    Central,
    /// The 7-point formula of ISO 4287 / ISO 5436-2:
    /// (z[i+3] − 9z[i+2] + 45z[i+1] − 45z[i−1] + 9z[i−2] − z[i−3]) / (60Δx)
    /// at the n − 6 interior points. Sixth order. Default.
    Iso7Point,
}

/// Method for the fractal dimension D.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum FractalMethod {
    /// Structure function (variogram) V(τ) = ⟨(z(x+τ) − z(x))²⟩ ∝ τ^{2H},
    /// fitted on a log-log scale over lags from `min_lag` to `max_lag`
    /// samples; D = 2 − H for a profile, 3 − H for a surface. Default.
    StructureFunction,
    /// Power spectrum P(k) ∝ k^{−(1+2H)} of the profile (rows and columns
    /// averaged for a map), fitted over the same wavelength range;
    /// D = 2 − H (profile), 3 − H (surface).
    PowerSpectrum,
}

/// Fractal-dimension settings.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct FractalParams {
    /// Method. Default [`FractalMethod::StructureFunction`].
    pub method: FractalMethod,
    /// Smallest lag (samples), ≥ 1. Default 1.
    pub min_lag: usize,
    /// Largest lag as a fraction of the evaluation length, in (0, 0.5].
    /// Default 0.1 (beyond it few independent pairs remain and the
    /// structure function saturates at 2 Rq²).
    pub max_lag_fraction: f64,
}

impl Default for FractalParams {
    fn default() -> Self {
        FractalParams {
            method: FractalMethod::StructureFunction,
            min_lag: 1,
            max_lag_fraction: 0.1,
        }
    }
}

/// Nominal pressure and hardness for the contact length (Eq. 3.14, 3.15).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct ContactParams {
    /// σ, nominal contact pressure (Pa). Valid: 0 < σ < H. Thesis Ch. 3:
    /// 0.085 MPa.
    pub nominal_pressure: f64,
    /// H, hardness of the softer body (Pa); for ice H = C1 T + C2 (MODELS.md
    /// §6), e.g. 25.35 MPa at −2 °C.
    pub hardness: f64,
}

impl ContactParams {
    /// Validated contact parameters.
    pub fn new(nominal_pressure: f64, hardness: f64) -> Result<Self> {
        if !(nominal_pressure.is_finite() && nominal_pressure > 0.0) {
            return Err(Error::Config(format!(
                "nominal pressure σ = {nominal_pressure} Pa; expected a finite value > 0"
            )));
        }
        if !(hardness.is_finite() && hardness > nominal_pressure) {
            return Err(Error::Config(format!(
                "hardness H = {hardness} Pa with nominal pressure σ = {nominal_pressure} Pa; \
                 expected H > σ (the real contact area cannot exceed the nominal one)"
            )));
        }
        Ok(ContactParams {
            nominal_pressure,
            hardness,
        })
    }
}

/// Everything a roughness analysis needs besides the data.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RoughnessParams {
    /// Evaluation window along x (m), start ≤ x ≤ end, inclusive; `None` for
    /// the whole profile. Default `None`.
    pub window: Option<(f64, f64)>,
    /// Evaluation window along y for areal maps (m), inclusive; `None` for
    /// every row. Ignored for profiles. Default `None`.
    pub window_y: Option<(f64, f64)>,
    /// Form removal. Default [`Detrend::Line`].
    pub detrend: Detrend,
    /// Gaussian roughness filter (ISO 16610-21); `None` for no filter (the
    /// detrended primary profile is analysed). Default `None`.
    pub filter: Option<GaussianFilterParams>,
    /// Slope scheme. Default [`DerivativeScheme::Iso7Point`].
    pub derivative: DerivativeScheme,
    /// Fractal dimension settings.
    pub fractal: FractalParams,
    /// Number of equally spaced material ratios (0 to 1) at which the bearing
    /// curve is reported, ≥ 2. Default 101 (1 % steps).
    pub bearing_points: usize,
    /// Contact length settings; `None` to skip it.
    pub contact: Option<ContactParams>,
    /// Largest fraction of the evaluated points that may be not measured
    /// (NaN) before the row gets a `too_many_invalid` status, in [0, 1].
    /// Default [`super::mask::DEFAULT_MAX_INVALID_FRACTION`] (10 %).
    pub max_invalid_fraction: f64,
}

impl Default for RoughnessParams {
    fn default() -> Self {
        RoughnessParams {
            window: None,
            window_y: None,
            detrend: Detrend::Line,
            filter: None,
            derivative: DerivativeScheme::Iso7Point,
            fractal: FractalParams::default(),
            bearing_points: 101,
            contact: None,
            max_invalid_fraction: super::mask::DEFAULT_MAX_INVALID_FRACTION,
        }
    }
}

impl RoughnessParams {
    /// Checks every field's range.
    pub fn validate(&self) -> Result<()> {
        for (name, w) in [("", self.window), (" along y", self.window_y)] {
            if let Some((a, b)) = w {
                if !(a.is_finite() && b.is_finite() && b > a) {
                    return Err(Error::Config(format!(
                        "evaluation window{name} [{a}, {b}] m; expected finite start < end"
                    )));
                }
            }
        }
        if let Some(f) = &self.filter {
            f.validate()?;
        }
        if self.fractal.min_lag < 1 {
            return Err(Error::Config("fractal min_lag must be ≥ 1 sample".into()));
        }
        let m = self.fractal.max_lag_fraction;
        if !(m > 0.0 && m <= 0.5) {
            return Err(Error::Config(format!(
                "fractal max_lag_fraction = {m}; expected 0 < value ≤ 0.5"
            )));
        }
        if self.bearing_points < 2 {
            return Err(Error::Config(format!(
                "bearing_points = {}; expected ≥ 2",
                self.bearing_points
            )));
        }
        if let Some(c) = self.contact {
            ContactParams::new(c.nominal_pressure, c.hardness)?;
        }
        if !(0.0..=1.0).contains(&self.max_invalid_fraction) {
            return Err(Error::Config(format!(
                "max_invalid_fraction = {}; expected 0 ≤ value ≤ 1",
                self.max_invalid_fraction
            )));
        }
        Ok(())
    }
}
