//! Spring-block simulations (MODELS.md §7): the RK4 stepper with stick/slip
//! handling (assembled from a read-only context, scratch, stuck-phase cache,
//! crossing tree and parked blocks), the activity manager that decides what
//! is integrated and when the clock jumps, the driver and its observers, single
//! runs, pressure × repetition sweeps, scene files and the comparison with
//! measured Coulomb fits.
//!
//! The physics (parameters, lattice, force terms, patterns) lives in
//! [`crate::models::spring_block`].

pub mod activity;
pub mod compare;
pub mod context;
pub mod control;
mod crossing;
pub mod diagnostics;
pub mod driver;
pub mod event;
pub mod observe;
pub mod output;
pub mod park;
mod parked;
mod rate;
pub mod run;
pub mod scene;
mod scratch;
pub mod state;
pub mod stepper;
mod stuck;
pub mod study;
pub mod sweep;
pub mod tiles;

pub use activity::Activity;
pub use diagnostics::{force_balance, ForceBalance};
pub use driver::{drive, DriveLimits, RunObserver};
pub use event::{Jump, Jumper};
pub use observe::PeakObserver;
pub use park::Parker;
pub use run::{simulate_run, IntegratorParams, RunControl, RunReport, RunSpec, Scheme, StopReason};
pub use scene::{ScenePlan, SceneSpec};
pub use stepper::{SpringBlockState, Stepper};
pub use study::{load_input, SimulationInput, SimulationOutcome};
pub use sweep::{derive_seed, run_sweep, SweepRun};
