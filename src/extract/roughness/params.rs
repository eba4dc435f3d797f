//! Settings of a roughness analysis, validated once before any computation.

use serde::Serialize;

use crate::error::{Error, Result};
use crate::signal::gaussian_filter::GaussianFilterParams;

/// Form removal (the F-operator of ISO 25178-2/-3), applied to the
/// evaluation window after the S-filter and before the L-filter.
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
    /// Subtract the least-squares polynomial of degree
    /// [`RoughnessParams::form_degree`] (maps: total degree in x and y).
    Polynomial,
    /// Subtract the least-squares circle (profiles: a roller's crown) or
    /// cylinder (maps), radius [`RoughnessParams::form_radius`] when given.
    Circle,
}

/// The L-filter that separates roughness from waviness.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum FilterKind {
    /// The ISO 16610-21 Gaussian filter (maps: ISO 16610-61). Default.
    Gaussian,
    /// The robust Gaussian regression filter of ISO 16610-31 (second
    /// order for profiles; zero order for maps), for stratified surfaces.
    Robust,
    /// The valley-suppression filter of ISO 13565-1, on which the Rk
    /// family is defined.
    ValleySuppression,
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
    /// The S-filter: the cut-off λs (m) of a Gaussian short-wave filter
    /// applied first (ISO 3274, ISO 25178-3), which keeps the wavelengths
    /// above λs; `None` for none. Default `None`.
    pub short_cutoff: Option<f64>,
    /// Degree of [`Detrend::Polynomial`], ≥ 1. Default 2.
    pub form_degree: usize,
    /// Radius (m) of [`Detrend::Circle`] when known (the roller's); `None`
    /// to fit it. Default `None`.
    pub form_radius: Option<f64>,
    /// The L-filter's cut-off λc and ends (ISO 16610-21 parameters);
    /// `None` for no filter (the form-removed primary surface is
    /// analysed). Default `None`.
    pub filter: Option<GaussianFilterParams>,
    /// Which L-filter. Default [`FilterKind::Gaussian`].
    pub filter_kind: FilterKind,
    /// Slope scheme. Default [`DerivativeScheme::Iso7Point`].
    pub derivative: DerivativeScheme,
    /// Fractal dimension settings.
    pub fractal: FractalParams,
    /// Number of equally spaced material ratios (0 to 1) at which the bearing
    /// curve is reported, ≥ 2. Default 101 (1 % steps).
    pub bearing_points: usize,
    /// Contact length settings; `None` to skip it.
    pub contact: Option<ContactParams>,
    /// Equivalent line of the Rk construction. Default least squares.
    pub rk_line: super::material::RkLine,
    /// Height c (m, from the reference line z = 0) of Smr(c) / Rmr(c).
    /// Default 0.
    pub material_height: f64,
    /// Material ratio (0..1) of Smc(mr) / Rmc(mr). Default 0.1.
    pub material_ratio: f64,
    /// Material ratios p < q of the volume parameters (ISO 25178-2
    /// defaults 0.1 and 0.8).
    pub volume_ratios: (f64, f64),
    /// Threshold s of Sal and Str (ISO 25178-3 default 0.2).
    pub acf_threshold: f64,
    /// Whether the surface is periodic (synthetic): spectra and ACF are
    /// then circular and unwindowed. Default false.
    pub periodic: bool,
    /// Whether the PSD and ACF are computed (their tables). Default true.
    pub spectra: bool,
    /// Stylus tip radius (m) for the reliability cut-off; `None` to take
    /// the file's (the Dektak's `Stylus Radius`) or skip it.
    pub tip_radius: Option<f64>,
    /// Smallest r² of the fractal fit that is not doubtful (default 0.9).
    pub fractal_min_r_squared: f64,
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
            short_cutoff: None,
            form_degree: 2,
            form_radius: None,
            filter: None,
            filter_kind: FilterKind::Gaussian,
            derivative: DerivativeScheme::Iso7Point,
            fractal: FractalParams::default(),
            bearing_points: 101,
            contact: None,
            rk_line: super::material::RkLine::LeastSquares,
            material_height: 0.0,
            material_ratio: 0.1,
            volume_ratios: (0.1, 0.8),
            acf_threshold: super::acf::DEFAULT_THRESHOLD,
            periodic: false,
            spectra: true,
            tip_radius: None,
            fractal_min_r_squared: 0.9,
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
        self.check_lengths()?;
        self.check_fractions()
    }

    /// The optional lengths (> 0), λs below λc, and the form degree.
    fn check_lengths(&self) -> Result<()> {
        let positive = |v: Option<f64>, what: &str| match v {
            Some(v) if !(v.is_finite() && v > 0.0) => Err(Error::Config(format!(
                "{what} = {v} m; expected a finite value > 0"
            ))),
            _ => Ok(()),
        };
        positive(self.short_cutoff, "short_cutoff (λs)")?;
        positive(self.form_radius, "form_radius")?;
        positive(self.tip_radius, "tip_radius")?;
        if let (Some(ls), Some(f)) = (self.short_cutoff, self.filter) {
            if ls >= f.cutoff {
                return Err(Error::Config(format!(
                    "short_cutoff λs = {ls:e} m is not below the cut-off λc = {:e} m",
                    f.cutoff
                )));
            }
        }
        if self.form_degree < 1 || self.form_degree > 20 {
            return Err(Error::Config(format!(
                "form_degree = {}; expected 1 ≤ degree ≤ 20",
                self.form_degree
            )));
        }
        Ok(())
    }

    /// Ratios and fractions, each in its range (fractions, not percent).
    fn check_fractions(&self) -> Result<()> {
        let (p, q) = self.volume_ratios;
        let ratio = |v: f64| (0.0..=1.0).contains(&v);
        if !(ratio(p) && ratio(q) && p < q && ratio(self.material_ratio)) {
            return Err(Error::Config(format!(
                "volume ratios ({p}, {q}) and material_ratio {}: expected 0 ≤ p < q ≤ 1 and \
                 0 ≤ mr ≤ 1 (fractions, not percent)",
                self.material_ratio
            )));
        }
        if !self.material_height.is_finite() {
            return Err(Error::Config("material_height must be finite".into()));
        }
        if !(self.acf_threshold > 0.0 && self.acf_threshold < 1.0) {
            return Err(Error::Config(format!(
                "acf_threshold = {}; expected 0 < s < 1",
                self.acf_threshold
            )));
        }
        if !(0.0..=1.0).contains(&self.fractal_min_r_squared) {
            return Err(Error::Config(format!(
                "fractal_min_r_squared = {}; expected 0 ≤ value ≤ 1",
                self.fractal_min_r_squared
            )));
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
