//! How a spring-block run is integrated (scheme, time step) and when it
//! stops (the run's limits, and why it stopped): settings that the run and
//! the parts it drives (activity, driver, observer) read.

use serde::{Deserialize, Serialize};

use crate::error::{Error, Result};
use crate::status::Code;

/// Time integration scheme.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, Default)]
#[serde(rename_all = "snake_case")]
pub enum Scheme {
    /// RK4 at fixed dt throughout, stuck phases included (the reference).
    Rk4,
    /// RK4 at fixed dt while something slides; closed-form jumps over stuck
    /// phases ([`super::event`]). Default.
    #[default]
    Event,
}

/// Integrator settings; a scene file's `[integrator]` table, with the time
/// step in `dt_s`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct IntegratorParams {
    /// Scheme. Default [`Scheme::Event`].
    pub scheme: Scheme,
    /// dt, RK4 time step \[s\]. Default 1e-8 (thesis). Range > 0; RK4 is
    /// unstable above about [`SpringBlockParams::rk4_stable_dt`].
    #[serde(rename = "dt_s")]
    pub dt: f64,
    /// Settling tolerance of free blocks before a jump, as a fraction of the
    /// mean static threshold \[1\]. Default 1e-3. Range (0, 1).
    pub quiet_tolerance: f64,
    /// Largest slider travel of one jump when there are holes, as a fraction
    /// of l \[1\]. Default 0.02. Range > 0.
    pub jump_travel: f64,
    /// Event scheme only: park settled hole clusters between slips
    /// ([`super::park`]) instead of integrating every hole block while
    /// anything slides. Default true.
    pub park_holes: bool,
}

impl Default for IntegratorParams {
    fn default() -> Self {
        IntegratorParams {
            scheme: Scheme::Event,
            dt: 1e-8,
            quiet_tolerance: 1e-3,
            jump_travel: 0.02,
            park_holes: true,
        }
    }
}

/// When a run stops and what it records; a scene file's `[run]` table, with
/// the times in `*_s` keys.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct RunControl {
    /// Sliding time recorded after the static peak \[s\]. Default 1e-3. Range ≥ 0.
    #[serde(rename = "sliding_time_s")]
    pub sliding_time: f64,
    /// Relative drop of T below its running maximum that marks the static
    /// peak \[1\]. Default 0.02. Range (0, 1).
    pub drop_fraction: f64,
    /// Give up without a peak after this time \[s\]; `None`: four times the
    /// single-block loading time (μ_s F_n + F_ad)/(K_s v) plus the sliding
    /// time.
    #[serde(rename = "max_time_s")]
    pub max_time: Option<f64>,
    /// Interval of the recorded T(t) curve \[s\]; 0 records no curve.
    /// Default 1e-5.
    #[serde(rename = "curve_interval_s")]
    pub curve_interval: f64,
}

impl Default for RunControl {
    fn default() -> Self {
        RunControl {
            sliding_time: 1e-3,
            drop_fraction: 0.02,
            max_time: None,
            curve_interval: 1e-5,
        }
    }
}

impl IntegratorParams {
    /// Checks ranges.
    pub fn validate(&self) -> Result<()> {
        let bad = |what: &str, v: f64, exp: &str| {
            Err(Error::Config(format!(
                "spring-block integrator: {what} is {v}; expected {exp}"
            )))
        };
        if !(self.dt.is_finite() && self.dt > 0.0) {
            return bad("dt [s]", self.dt, "> 0");
        }
        if !(self.quiet_tolerance > 0.0 && self.quiet_tolerance < 1.0) {
            return bad("quiet_tolerance", self.quiet_tolerance, "in (0, 1)");
        }
        if !(self.jump_travel.is_finite() && self.jump_travel > 0.0) {
            return bad("jump_travel", self.jump_travel, "> 0");
        }
        Ok(())
    }
}

impl RunControl {
    /// Checks ranges.
    pub fn validate(&self) -> Result<()> {
        let bad = |what: &str, v: f64, exp: &str| {
            Err(Error::Config(format!(
                "spring-block run: {what} is {v}; expected {exp}"
            )))
        };
        if !(self.sliding_time.is_finite() && self.sliding_time >= 0.0) {
            return bad("sliding_time [s]", self.sliding_time, ">= 0");
        }
        if !(self.drop_fraction > 0.0 && self.drop_fraction < 1.0) {
            return bad("drop_fraction", self.drop_fraction, "in (0, 1)");
        }
        if let Some(t) = self.max_time {
            if !(t.is_finite() && t > 0.0) {
                return bad("max_time [s]", t, "> 0");
            }
        }
        if !(self.curve_interval.is_finite() && self.curve_interval >= 0.0) {
            return bad("curve_interval [s]", self.curve_interval, ">= 0");
        }
        Ok(())
    }
}

/// Why a run stopped.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub enum StopReason {
    /// The static peak and the sliding window were seen.
    Completed,
    /// `max_time` was reached first (the peak may be missing).
    MaxTime,
    /// The integration blew up.
    Diverged {
        /// Step number (1-based) at which it was seen.
        step: u64,
        /// Time at the end of that step \[s\].
        time: f64,
        /// Block index.
        block: usize,
        /// What was seen.
        what: String,
        /// The step used \[s\].
        dt: f64,
        /// The RK4 stability bound for these parameters \[s\].
        dt_stable: f64,
    },
}

impl StopReason {
    /// The status code of a run that stopped early: `time_limit` or
    /// `numerical_failure` (diverged); `None` when it completed.
    pub fn code(&self) -> Option<Code> {
        match self {
            StopReason::Completed => None,
            StopReason::MaxTime => Some(Code::TimeLimit),
            StopReason::Diverged { .. } => Some(Code::NumericalFailure),
        }
    }

    /// The `status` cell: `ok`, or the code of why the run stopped early.
    pub fn status(&self) -> &'static str {
        self.code().map_or(crate::status::OK, Code::as_str)
    }

    /// A message for the user; for a blow-up it names the step and suggests
    /// a smaller dt.
    pub fn message(&self) -> String {
        match self {
            StopReason::Completed => String::new(),
            StopReason::MaxTime => {
                "max_time reached before the static peak and the sliding window".into()
            }
            StopReason::Diverged {
                step,
                time,
                block,
                what,
                dt,
                dt_stable,
            } => format!(
                "the integration blew up at step {step} (t = {time:.6e} s, block {block}): \
                 {what}; the time step dt = {dt:e} s is too large: use a smaller dt \
                 (RK4 is stable below about {dt_stable:.2e} s for these parameters; \
                 the thesis uses 1e-8 s)"
            ),
        }
    }

    /// The stop reason as an error, `None` when the run completed.
    pub fn error(&self) -> Option<Error> {
        match self {
            StopReason::Completed => None,
            StopReason::MaxTime => Some(Error::coded(Code::TimeLimit, self.message())),
            StopReason::Diverged { .. } => Some(Error::Numerical(self.message())),
        }
    }
}
