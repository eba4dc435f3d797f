//! One spring-block run: draw the interface, integrate until the static peak
//! and a sliding window have been seen, and say why the run stopped.
//!
//! Observables (MODELS.md §7): T(t) = T_vec · v̂ with T_vec = Σ_i K_s (v t − u_i).
//! - **static peak**: the first maximum of T, taken as the running maximum at
//!   the moment T first falls below (1 − `drop_fraction`) of it (small
//!   precursor drops of single blocks do not count); μ_s = T_max / N;
//! - **dynamic friction**: the time average of T over the second half of the
//!   sliding window [t_peak, t_peak + `sliding_time`]; μ_d = T̄ / N.
//!
//! N = N_x N_y p l² is the nominal normal load (thesis §4.3).

use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use serde::{Deserialize, Serialize};

use super::activity::Activity;
use super::driver::{drive, DriveLimits};
use super::observe::PeakObserver;
use super::stepper::{SpringBlockState, Stepper};
use crate::error::{Error, Result};
use crate::models::spring_block::{contact_fraction, Interface, Lattice, SpringBlockParams};
use crate::status::{Code, Status};

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

/// Integrator settings.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct IntegratorParams {
    /// Scheme. Default [`Scheme::Event`].
    pub scheme: Scheme,
    /// dt, RK4 time step \[s\]. Default 1e-8 (thesis). Range > 0; RK4 is
    /// unstable above about [`SpringBlockParams::rk4_stable_dt`].
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
    #[serde(default = "yes")]
    pub park_holes: bool,
}

fn yes() -> bool {
    true
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

/// When a run stops and what it records.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct RunControl {
    /// Sliding time recorded after the static peak \[s\]. Default 1e-3. Range ≥ 0.
    pub sliding_time: f64,
    /// Relative drop of T below its running maximum that marks the static
    /// peak \[1\]. Default 0.02. Range (0, 1).
    pub drop_fraction: f64,
    /// Give up without a peak after this time \[s\]; `None`: four times the
    /// single-block loading time (μ_s F_n + F_ad)/(K_s v) plus the sliding
    /// time.
    pub max_time: Option<f64>,
    /// Interval of the recorded T(t) curve \[s\]; 0 records no curve.
    /// Default 1e-5.
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

/// Everything a run needs besides the shared parameters.
#[derive(Debug, Clone, Copy)]
pub struct RunSpec {
    /// p, applied pressure \[Pa\] (> 0).
    pub pressure: f64,
    /// α, slider direction from the x axis \[rad\].
    pub angle: f64,
    /// Seed of the run's friction coefficients.
    pub seed: u64,
}

/// Result of one run (serialisable: a shard's runs are kept in the cache).
#[derive(Debug, Clone, serde::Serialize, serde::Deserialize)]
pub struct RunReport {
    /// Why it stopped.
    pub stop: StopReason,
    /// μ_s = T_max/N, if the peak was seen.
    pub mu_static: Option<f64>,
    /// Static peak force T_max \[N\].
    pub static_force: Option<f64>,
    /// Time of the static peak \[s\].
    pub peak_time: Option<f64>,
    /// μ_d = T̄/N over the second half of the sliding window.
    pub mu_dynamic: Option<f64>,
    /// T̄ \[N\].
    pub dynamic_force: Option<f64>,
    /// N, nominal normal load \[N\].
    pub normal_load: f64,
    /// Fraction of blocks in contact.
    pub contact_fraction: f64,
    /// Final time \[s\].
    pub end_time: f64,
    /// RK4 steps taken.
    pub steps: u64,
    /// Jumps over stuck phases.
    pub jumps: u64,
    /// Block-steps integrated (Σ over steps of moving blocks).
    pub block_steps: u64,
    /// Decimated curve (t \[s\], T \[N\]).
    pub curve: Vec<(f64, f64)>,
    /// Set when the μ_d window was only partly seen (status `short_window`).
    #[serde(default)]
    pub short_window: Option<String>,
}

impl RunReport {
    /// The run's status: the stop reason's, or `short_window`.
    pub fn status(&self) -> Status {
        match (self.stop.code(), &self.short_window) {
            (Some(code), _) => Status::of(code, self.stop.message()),
            (None, Some(m)) => Status::of(Code::ShortWindow, m.clone()),
            (None, None) => Status::ok(),
        }
    }
}

/// Runs one simulation of a validated setup. `mask` marks holes (true).
/// Configuration errors are returned as `Err`; a blow-up or a missing peak
/// is reported in [`RunReport::stop`].
pub fn simulate_run(
    params: &SpringBlockParams,
    lattice: &Lattice,
    mask: &[bool],
    integ: &IntegratorParams,
    control: &RunControl,
    spec: &RunSpec,
) -> Result<RunReport> {
    params.validate()?;
    integ.validate()?;
    control.validate()?;
    if mask.len() != lattice.len() {
        return Err(Error::Config(format!(
            "spring-block: mask has {} blocks; expected {}",
            mask.len(),
            lattice.len()
        )));
    }
    let mut rng = ChaCha8Rng::seed_from_u64(spec.seed);
    let iface = Interface::draw(params, mask, spec.pressure, &mut rng)?;
    let v = params.slider_speed;
    let vel = (v * spec.angle.cos(), v * spec.angle.sin());
    let dir = (spec.angle.cos(), spec.angle.sin());
    let normal_load = iface.normal_force * lattice.len() as f64;
    let max_time = control.max_time.unwrap_or_else(|| {
        4.0 * iface.mean_threshold() / (lattice.k_shear * v) + control.sliding_time
    });

    let mut state = SpringBlockState::at_rest(&iface);
    let mut st = Stepper::new(lattice, &iface, vel, params.damping, &state);
    let travel = integ.jump_travel * params.spacing;
    let mut activity = Activity::new(integ, travel, &mut st, &mut state);
    let mut obs = PeakObserver::new(control, dir);
    let lim = DriveLimits {
        dt: integ.dt,
        max_time,
        dt_stable: params.rk4_stable_dt(),
    };
    let stop = drive(&mut st, &mut state, &mut activity, &mut obs, &lim);
    let (mu_static, static_force, peak_time) = match obs.peak {
        Some((tp, f)) => (Some(f / normal_load), Some(f), Some(tp)),
        None => (None, None, None),
    };
    let (dynamic_force, short_window) = dynamic_average(&obs, &stop, control.sliding_time);
    Ok(RunReport {
        stop,
        mu_static,
        static_force,
        peak_time,
        mu_dynamic: dynamic_force.map(|f| f / normal_load),
        dynamic_force,
        normal_load,
        contact_fraction: contact_fraction(mask),
        end_time: state.t,
        steps: st.steps,
        jumps: activity.jumps(),
        block_steps: st.block_steps,
        curve: obs.curve,
        short_window,
    })
}

/// T̄ over the second half of the sliding window, and a note when the
/// peak was recognised so late that part of that window had passed: T̄ is
/// then the mean over the part seen (never the part's integral divided by
/// the whole window), or none when nothing was seen.
fn dynamic_average(
    obs: &PeakObserver,
    stop: &StopReason,
    sliding_time: f64,
) -> (Option<f64>, Option<String>) {
    let half = 0.5 * sliding_time;
    let (Some((tp, _)), StopReason::Completed) = (obs.peak, stop) else {
        return (None, None);
    };
    if half <= 0.0 {
        return (None, None);
    }
    if obs.covered >= half * (1.0 - 1e-9) {
        return (Some(obs.integral / half), None);
    }
    let note = format!(
        "the static peak (t = {tp:.3e} s) was recognised only after {:.3e} s of the \
         averaging window [{:.3e}, {:.3e}] s had passed; mu_dynamic averages the {:.3e} s seen: \
         lengthen sliding_time_s",
        half - obs.covered,
        tp + half,
        tp + sliding_time,
        obs.covered
    );
    let mean = (obs.covered > 0.0).then(|| obs.integral / obs.covered);
    (mean, Some(note))
}
