//! Spring-block simulations (MODELS.md §7): the RK4 stepper with stick/slip
//! handling, the event-driven scheme that jumps over stuck phases, single
//! runs, pressure × repetition sweeps, scene files and the comparison with
//! measured Coulomb fits.
//!
//! The physics (parameters, lattice, force terms, patterns) lives in
//! [`crate::models::spring_block`].

pub mod diagnostics;
pub mod event;
pub mod run;
pub mod stepper;

pub use run::{
    simulate_run, IntegratorParams, RunControl, RunReport, RunSpec, Scheme, StopReason,
};
pub use diagnostics::{force_balance, ForceBalance};
pub use event::{Jump, Jumper};
pub use stepper::{SpringBlockState, Stepper};
