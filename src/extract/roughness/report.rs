//! What the analysis of one profile or map reports: the typed row behind
//! the `roughness`, `bearing_curve`, `psd` and `acf` tables and the
//! figures.

use super::bearing::ContactEstimate;
use super::fractal::FractalEstimate;
use super::heights::Heights;
use super::material::{RkFamily, Volume};
use super::psd::Spectrum;
use super::reliability::Cutoff;
use crate::signal::robust_filter::RobustRun;
use crate::status::Status;

/// Whether a report is about a profile (R-parameters) or a map
/// (S-parameters, same formulas over the area).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SurfaceKind {
    /// A stylus profile z(x).
    Profile,
    /// An areal map z(x, y).
    Areal,
}

impl SurfaceKind {
    /// `profile` or `areal`.
    pub fn as_str(self) -> &'static str {
        match self {
            SurfaceKind::Profile => "profile",
            SurfaceKind::Areal => "areal",
        }
    }
}

/// What the material ratio curve gives (MODELS.md §10, [`super::material`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Functional {
    /// The Rk (Sk) family.
    pub rk: RkFamily,
    /// Smr(c) (Rmr(c)) at the configured height c.
    pub smr: f64,
    /// Smc(mr) (Rmc(mr)) at the configured ratio (m).
    pub smc: f64,
    /// Sxp = Smc(2.5 %) − Smc(50 %) (m).
    pub sxp: f64,
    /// Vmp, Vmc, Vvc, Vvv (m³/m²).
    pub volume: Volume,
}

/// Spatial, hybrid and spacing parameters ([`super::acf`],
/// [`super::hybrid`], [`super::spacing`]); each `None` where the data
/// cannot support it (the notes say why) or the kind has no such
/// parameter.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Spatial {
    /// Sal (m), maps.
    pub sal: Option<f64>,
    /// Str, maps.
    pub str_ratio: Option<f64>,
    /// Std (degrees in [0, 180)), maps.
    pub std_deg: Option<f64>,
    /// Sdr (a fraction), maps.
    pub sdr: Option<f64>,
    /// RSm (m), profiles.
    pub rsm: Option<f64>,
}

/// One point of an autocorrelation curve.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AcfPoint {
    /// `x`, `y` or `radial`.
    pub direction: &'static str,
    /// Lag (m).
    pub lag: f64,
    /// f_ACF (1 at lag 0).
    pub value: f64,
}

/// The tip-radius reliability analysis ([`super::reliability`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Reliability {
    /// Tip radius used (m).
    pub tip_radius: f64,
    /// Where the scales stop being reliable.
    pub cutoff: Cutoff,
}

/// Roughness of one profile or map.
#[derive(Debug, Clone, PartialEq)]
pub struct RoughnessReport {
    /// Input label.
    pub source: String,
    /// Profile or areal.
    pub kind: SurfaceKind,
    /// Points evaluated (after window and end discarding), measured or not.
    pub n_points: usize,
    /// Of those, points not measured (NaN in the file, or left undefined by
    /// a filter across a wide gap, [`super::mask`]).
    pub n_invalid: usize,
    /// Evaluated length along x (m).
    pub length: f64,
    /// The evaluation window along x (m) the analysis used (the settings',
    /// or the instrument's when the file states one); `None` for all.
    pub window: Option<(f64, f64)>,
    /// Ra (Sa) (m).
    pub ra: f64,
    /// Rq (Sq) (m).
    pub rq: f64,
    /// RMS slope Rdq (Sdq) as a slope (dimensionless).
    pub rms_slope: Option<f64>,
    /// Rdq as an angle, atan(rms_slope) (degrees).
    pub rdq_deg: Option<f64>,
    /// Rsk (Ssk); `None` when flat.
    pub rsk: Option<f64>,
    /// Rku (Sku); `None` when flat.
    pub rku: Option<f64>,
    /// Rp, Rv, Rt, Rz (Sp, Sv, Sz for maps), MODELS.md §9.
    pub heights: Heights,
    /// Fractal estimate, when one could be made.
    pub fractal: Option<FractalEstimate>,
    /// Bearing curve (material ratio, height in m).
    pub bearing: Vec<(f64, f64)>,
    /// Rk family, Smr, Smc, Sxp and volumes; `None` for a flat surface.
    pub functional: Option<Functional>,
    /// Spatial, hybrid and spacing parameters.
    pub spatial: Spatial,
    /// The binned PSD (empty when spectra are off).
    pub psd: Spectrum,
    /// ACF along x, y and radially (empty when spectra are off).
    pub acf: Vec<AcfPoint>,
    /// The reliability cut-off, with a tip radius.
    pub reliability: Option<Reliability>,
    /// Radius of the fitted circle or cylinder (m).
    pub form_radius: Option<f64>,
    /// How the robust filter ended, when it ran.
    pub robust: Option<RobustRun>,
    /// Contact length (Eq. 3.14–3.15) when requested and defined.
    pub contact: Option<ContactEstimate>,
    /// Notes on values left out or doubtful; empty when everything was
    /// computed.
    pub notes: Status,
}

impl RoughnessReport {
    /// `ok`, or the notes joined by `; `.
    pub fn status(&self) -> String {
        self.notes.to_string()
    }
}
