//! The run loop as a driver: it asks the [`Activity`] whether the clock may
//! jump, otherwise takes one RK4 step, and hands the slider force to a
//! [`RunObserver`] after every advance, until the observer is done, the
//! time limit is reached or the integration blows up. Solver (the
//! [`Stepper`]), scheduling (the [`Activity`]) and observation stay
//! separate, as argmin separates solver, executor and observers.

use super::activity::Activity;
use super::control::StopReason;
use super::event::Jump;
use super::state::SpringBlockState;
use super::stepper::Stepper;

/// Watches the slider force T_vec(t) = K_s (N v t − Σ u) as the run
/// advances.
pub trait RunObserver {
    /// The slider force `force` \[N\] at time `t` \[s\], after each jump or step.
    fn observe(&mut self, t: f64, force: (f64, f64));
    /// Whether the run has seen what it needs at time `t`.
    fn done(&self, t: f64) -> bool;
}

/// Time step and limits of a drive.
#[derive(Debug, Clone, Copy)]
pub struct DriveLimits {
    /// dt \[s\].
    pub dt: f64,
    /// Stop at this time \[s\].
    pub max_time: f64,
    /// The RK4 stability bound, quoted when the integration blows up \[s\].
    pub dt_stable: f64,
}

/// Advances `state` until `obs` is done or a limit is hit; says why it
/// stopped.
pub fn drive(
    st: &mut Stepper,
    state: &mut SpringBlockState,
    activity: &mut Activity,
    obs: &mut impl RunObserver,
    lim: &DriveLimits,
) -> StopReason {
    loop {
        if obs.done(state.t) {
            return StopReason::Completed;
        }
        if state.t >= lim.max_time {
            return StopReason::MaxTime;
        }
        if let Jump::Jumped(_) = activity.try_jump(st, state, lim.dt, lim.max_time) {
            obs.observe(state.t, st.slider_force(state.t));
            continue;
        }
        match st.step(state, lim.dt) {
            Ok(started) => activity.after_step(st, state, started),
            Err(b) => {
                return StopReason::Diverged {
                    step: st.steps + 1,
                    time: state.t + lim.dt,
                    block: b.block,
                    what: b.what,
                    dt: lim.dt,
                    dt_stable: lim.dt_stable,
                };
            }
        }
        obs.observe(state.t, st.slider_force(state.t));
    }
}
