//! Surface roughness of stylus profiles and areal maps (MODELS.md §4, thesis
//! Ch. 3, Table 3.1, Eq. 3.14–3.15).
//!
//! # Model
//! From equally spaced heights z(x) (or z(x, y)), after an evaluation window,
//! form removal ([`Detrend`], least-squares line by default) and optionally
//! the ISO 16610-21 Gaussian filter with cut-off λc
//! ([`crate::signal::gaussian_filter`]):
//!
//! | output | symbol | formula | field |
//! |---|---|---|---|
//! | arithmetic mean deviation | Ra | mean(abs(z)) | [`RoughnessReport::ra`] (m) |
//! | RMS deviation | Rq | sqrt(mean(z²)) | [`RoughnessReport::rq`] (m) |
//! | RMS slope | Rdq | sqrt(mean(z′²)), as atan in degrees | [`RoughnessReport::rdq_deg`] |
//! | skewness | Rsk | mean(z³)/Rq³ | [`RoughnessReport::rsk`] |
//! | kurtosis | Rku | mean(z⁴)/Rq⁴ | [`RoughnessReport::rku`] |
//! | peak, valley, total and mean peak-to-valley heights | Rp, Rv, Rt, Rz (ISO, DIN) | [`heights`] (MODELS.md §9) | [`RoughnessReport::heights`] (m) |
//! | fractal dimension | D | 2 − H (profile), 3 − H (surface) | [`RoughnessReport::fractal`] |
//! | bearing curve | c(Rmr) | [`bearing`] | [`RoughnessReport::bearing`] |
//! | contact length | a | 2 d / tan(Rdq), Eq. 3.15 | [`RoughnessReport::contact`] (m) |
//!
//! The derivative scheme for z′ is a parameter ([`DerivativeScheme`], 7-point
//! of ISO 5436-2 by default), and so is the fractal method ([`fractal`]).
//!
//! # Assumptions and valid range
//! Uniform sampling (positions within half a step of a regular grid), at
//! least [`surface::MIN_POINTS`] points, finite heights. A flat surface
//! (Rq = 0) has Ra = Rq = Rdq = 0 and no skewness, kurtosis or fractal
//! dimension: those are reported as missing with a status that says why.
//! Maps carry the ISO 25178-2 names (Sa, Sq, Sdq, Ssk, Sku, Sp, Sv, Sz) in
//! the table: the same formulas over the area.
//! Parameters are point-based (sums over samples), which is what vendor
//! software reports (the Dektak check in the tests).

pub mod acf;
pub mod amplitude;
pub mod analyze;
pub mod bearing;
pub mod chain;
pub mod circle;
pub mod file;
pub mod form;
pub mod fractal;
pub mod heights;
pub mod hybrid;
pub mod input;
pub mod instrument;
pub mod map;
pub mod mask;
pub mod material;
pub mod params;
pub mod psd;
pub mod reliability;
pub mod report;
pub mod spacing;
pub mod spec;
pub mod stage;
pub mod surface;
pub mod tables;

pub use analyze::{analyze_map, analyze_profile, RoughnessReport, SurfaceKind};
pub use map::AreaMap;
pub use params::{
    ContactParams, DerivativeScheme, Detrend, FilterKind, FractalMethod, FractalParams,
    RoughnessParams,
};
pub use surface::Profile;
