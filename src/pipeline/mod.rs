//! Pipelines: a TOML spec ([`spec`]) is validated into a [`plan::Plan`]
//! (paths, units, formats and every stage's settings checked, the run
//! order derived from what each stage needs) before any computation; then
//! [`run::run`] reads each input once, routes it to the per-file stages
//! that take its kind, runs the table stages, and writes every table with
//! its provenance and `errors.parquet`. The exit code follows from the
//! [`outcome::RunReport`] alone, by the rule every command shares
//! ([`exit::code`]).
//!
//! Every command of the binary is a one-stage pipeline built from its
//! flags, so there is one path from inputs to tables.

mod assemble;
pub mod atomic;
mod binfile;
mod by_name;
pub mod cache;
mod column_keys;
pub mod dataset;
mod entries;
pub mod examine;
pub mod exit;
pub mod file_options;
pub mod file_result;
pub mod files;
pub mod fuzz;
pub mod inputs;
mod join;
pub mod keys;
pub mod lock;
pub mod mode;
pub mod order;
pub mod outcome;
pub mod owner;
mod pack;
pub mod phases;
pub mod plan;
pub mod planned;
pub mod preload;
pub mod provenance;
pub mod publish;
pub mod registry;
pub mod report;
mod reuse;
pub mod route;
pub mod run;
mod runner;
mod set;
pub mod shard;
pub mod shared;
pub mod slurm;
pub mod spec;
mod splice;
mod stamp;
pub mod state;
mod state_log;
pub mod store;
mod swept;
mod table_stage;

pub use mode::Mode;
pub use outcome::{FileFailure, RunReport};
pub use plan::Plan;
pub use run::{run, run_with, RunOptions};
