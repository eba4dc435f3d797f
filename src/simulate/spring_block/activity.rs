//! The one component that decides which blocks are integrated and when the
//! clock may jump, like a physics engine's island/sleep manager: fixed-step
//! RK4 throughout, global jumps over quiet phases ([`Jumper`]), or parked
//! hole clusters and their tiles with jumps whenever nothing moves
//! ([`Parker`]). The driver ([`super::driver`]) asks it before and after
//! each step and never looks inside.

use super::control::{IntegratorParams, Scheme};
use super::event::{Jump, Jumper};
use super::park::Parker;
use super::state::SpringBlockState;
use super::stepper::Stepper;

/// The scheme's bookkeeping of active and parked blocks.
pub enum Activity {
    /// RK4 at fixed dt, every moving block integrated, no jump.
    Integrate,
    /// Jumps of the whole lattice when every contact block sticks and the
    /// free blocks have settled.
    Jump {
        /// Rate system and settling test of all free blocks.
        jumper: Box<Jumper>,
        /// `quiet_tolerance`.
        tol: f64,
        /// Largest slider travel of one jump \[m\].
        travel: f64,
    },
    /// Parked clusters and tiles; the clock jumps whenever nothing moves.
    Park(Box<Parker>),
}

impl Activity {
    /// The bookkeeping of `integ`'s scheme for the stepper's run; parks the
    /// clusters that are settled at the start.
    pub fn new(
        integ: &IntegratorParams,
        travel: f64,
        st: &mut Stepper,
        state: &mut SpringBlockState,
    ) -> Self {
        match (integ.scheme, integ.park_holes) {
            (Scheme::Rk4, _) => Activity::Integrate,
            (Scheme::Event, false) => Activity::Jump {
                jumper: Box::new(Jumper::new(st)),
                tol: integ.quiet_tolerance,
                travel,
            },
            (Scheme::Event, true) => {
                let mut pk = Parker::new(st, integ.quiet_tolerance, travel);
                pk.park_settled(st, state);
                Activity::Park(Box::new(pk))
            }
        }
    }

    /// Jumps the clock over a quiet phase if the scheme allows it now.
    pub fn try_jump(
        &mut self,
        st: &mut Stepper,
        state: &mut SpringBlockState,
        dt: f64,
        t_limit: f64,
    ) -> Jump {
        match self {
            Activity::Integrate => Jump::NotQuiet,
            Activity::Jump {
                jumper,
                tol,
                travel,
            } => {
                // More moving blocks than free ones: a contact block slides.
                if st.moving.len() > jumper.free_count() {
                    return Jump::NotQuiet;
                }
                jumper.try_jump(st, state, *tol, *travel, dt, t_limit)
            }
            Activity::Park(pk) => pk.try_jump(st, state, dt, t_limit),
        }
    }

    /// Bookkeeping after an RK4 step that started `started` slips.
    pub fn after_step(&mut self, st: &mut Stepper, state: &mut SpringBlockState, started: usize) {
        if let Activity::Park(pk) = self {
            pk.after_step(st, state, started);
        }
    }

    /// Jumps made.
    pub fn jumps(&self) -> u64 {
        match self {
            Activity::Integrate => 0,
            Activity::Jump { jumper, .. } => jumper.jumps,
            Activity::Park(pk) => pk.jumps,
        }
    }
}
