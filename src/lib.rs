//! # tribo
//!
//! Turns folders of raw tribology exports into trustworthy numbers and model
//! comparisons. The stages, one module each:
//!
//! | module | job |
//! |---|---|
//! | [`ingest`] | read instrument exports into SI channels, keeping the metadata |
//! | [`signal`] | plain functions over slices: peaks, plateaus, segments, statistics |
//! | [`crosscheck`] | one quantity known two ways (a channel and its twin, ours and the instrument's) must agree |
//! | [`extract`] | features from signals: friction, tensile, roughness |
//! | [`fit`] | robust least squares inside argmin; Coulomb and ice-friction fits |
//! | [`models`] | physics as pure functions: ALSFM, Makkonen, spring-block |
//! | [`simulate`] | scene files and drivers for the models |
//! | [`stages`] | one module per pipeline stage, listed in [`stages::STAGES`] |
//! | [`pipeline`] | pipeline files: spec → validated plan → run → tables with provenance |
//! | [`table`] | the one place that talks to polars |
//! | [`schema`] | the output tables' schemas (`schemas/`) |
//!
//! Equation numbers refer to the thesis (A. Berardo, *Numerical and
//! Experimental Study on the Friction of Complex Surfaces*) or to `MODELS.md`
//! (which corrects and completes it).
//!
//! The library never prints and never exits; the `tribo` binary does.
#![deny(clippy::float_cmp)]
#![warn(missing_docs)]

pub mod crosscheck;
pub mod error;
pub mod extract;
pub mod fit;
pub mod hash;
pub mod ingest;
pub mod models;
pub mod paths;
pub mod pipeline;
pub mod plot;
pub mod report;
pub mod schema;
pub mod signal;
pub mod simulate;
pub mod stages;
pub mod status;
pub mod table;
pub mod units;

pub use error::{Error, Result};

/// This build of tribo: its version and a hash of the sources, schemas and
/// locked dependencies it was built from (`build.rs`). Every cache key
/// begins with it, so a rebuilt tribo that may compute otherwise never
/// reuses what an earlier build computed, whatever its version number.
pub const BUILD: &str = env!("TRIBO_BUILD");
