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

use super::activity::Activity;
pub use super::control::{IntegratorParams, RunControl, Scheme, StopReason};
use super::driver::{drive, DriveLimits};
use super::observe::PeakObserver;
use super::state::SpringBlockState;
use super::stepper::Stepper;
use crate::error::{Error, Result};
use crate::models::spring_block::{contact_fraction, Interface, Lattice, SpringBlockParams};
use crate::status::{Code, Status};

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
