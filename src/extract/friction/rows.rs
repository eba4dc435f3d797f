//! What the analysis of a trace yields (its rows) and what it reads (one
//! trace's columns), shared by the whole-trace analysis ([`super::trace`]),
//! one stroke's ([`super::stroke`]) and the doubts ([`super::doubts`]).

use super::segment::StickSlipEvent;
use crate::status::Status;

/// One row of `friction.parquet`: a segment of a trace.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct FrictionRow {
    /// Section name.
    pub section: String,
    /// 1-based stroke within the section (`None` when the trace is invalid).
    pub stroke: Option<usize>,
    /// Sign of T in this stroke (+1 or −1).
    pub direction_sign: Option<f64>,
    /// Segment start and end, s.
    pub start_s: Option<f64>,
    /// Segment end, s.
    pub end_s: Option<f64>,
    /// Samples in the segment.
    pub n_samples: usize,
    /// Samples dropped because time or force was NaN.
    pub n_nan_dropped: usize,
    /// Noise σ of |T|, N.
    pub noise_n: Option<f64>,
    /// Normal force used for μ, N (mean over the dynamic window when from
    /// the trace).
    pub normal_force_n: Option<f64>,
    /// `trace` or `manifest`.
    pub normal_force_source: Option<&'static str>,
    /// `trace` (a friction-force column) or `coefficient` (T = μ N from the
    /// instrument's coefficient); null for a row without a segment.
    pub friction_force_source: Option<&'static str>,
    /// Static peak |T_s|, N.
    pub static_force_n: Option<f64>,
    /// Its time, s.
    pub static_time_s: Option<f64>,
    /// Its prominence, N.
    pub static_prominence_n: Option<f64>,
    /// μ_s = T_s / N.
    pub mu_static: Option<f64>,
    /// Dynamic friction T_d (mean |T| over the window), N.
    pub dynamic_force_n: Option<f64>,
    /// Sample sd of |T| over the window, N.
    pub dynamic_force_sd_n: Option<f64>,
    /// μ_d = T_d / N.
    pub mu_dynamic: Option<f64>,
    /// Sample sd of the pointwise μ over the window.
    pub mu_dynamic_sd: Option<f64>,
    /// Window start, s.
    pub dynamic_window_start_s: Option<f64>,
    /// Window end, s.
    pub dynamic_window_end_s: Option<f64>,
    /// Samples in the window.
    pub dynamic_n: Option<usize>,
    /// Mean of the instrument's own μ over the same window.
    pub mu_instrument: Option<f64>,
    /// Number of stick-slip events.
    pub stickslip_events: usize,
    /// Mean drop of the events, N.
    pub stickslip_mean_drop_n: Option<f64>,
    /// Event frequency, Hz (events over the segment's duration after the
    /// static peak).
    pub stickslip_frequency_hz: Option<f64>,
    /// `ok`, or a code and reason.
    pub status: Status,
}

/// One row of `stickslip.parquet`.
#[derive(Debug, Clone, PartialEq)]
pub struct StickSlipRow {
    /// Section name.
    pub section: String,
    /// Stroke within the section.
    pub stroke: usize,
    /// The event.
    pub event: StickSlipEvent,
}

/// One trace's columns as the analysis reads them (NaN samples dropped).
pub(super) struct TraceView<'a> {
    pub(super) section: &'a str,
    pub(super) from_cof: bool,
    pub(super) t: &'a [f64],
    pub(super) f: &'a [f64],
    pub(super) normal: Option<&'a [f64]>,
    pub(super) cof: Option<&'a [f64]>,
    pub(super) n_nan: usize,
    /// Noise σ of the whole force, when stroke detection measured it: a
    /// stroke that is the whole positive trace has the same.
    pub(super) noise: Option<f64>,
}
