//! Pipelines: a TOML spec ([`spec`]) is validated into a [`plan::Plan`]
//! (paths, units, formats and parameters checked before any computation),
//! then [`run::run`] processes every file independently and in parallel.
//!
//! Each file's result depends only on its bytes and the plan, which is what
//! incremental reprocessing (skip files whose hash is unchanged) and
//! sharding across machines will build on.

pub mod friction_stage;
pub mod plan;
pub mod run;
pub mod spec;

pub use plan::Plan;
pub use run::{run, RunReport};
