//! Pipelines: a TOML spec ([`spec`]) is validated into a [`plan::Plan`]
//! (paths, units, formats and every stage's settings checked, the run
//! order derived from what each stage needs) before any computation; then
//! [`run::run`] reads each input once, routes it to the per-file stages
//! that take its kind, runs the table stages, and writes every table with
//! its provenance and `errors.parquet`. The exit code follows from the
//! [`outcome::RunReport`] alone.
//!
//! Every command of the binary is a one-stage pipeline built from its
//! flags, so there is one path from inputs to tables.

mod assemble;
pub mod cache;
pub mod files;
pub mod fuzz;
mod held;
pub mod lock;
pub mod order;
pub mod outcome;
pub mod plan;
pub mod provenance;
pub mod publish;
pub mod registry;
pub mod report;
mod reuse;
pub mod run;
pub mod shard;
pub mod slurm;
pub mod spec;
pub mod state;

pub use outcome::{FileFailure, RunReport};
pub use plan::Plan;
pub use run::{run, run_with, RunOptions};
