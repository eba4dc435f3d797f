//! ALSFM simulations (thesis Ch. 1–2, MODELS.md §5): a scene file
//! ([`scene`]) is validated into a [`plan::Plan`], which [`run`] evaluates
//! point by point on the cheapest exact path
//! ([`crate::models::alsfm::solver`]), producing the rows of
//! [`rows::AlsfmOutput`] and its tables.
//!
//! ```no_run
//! let plan = tribo::simulate::alsfm::plan::Plan::from_toml(
//!     &std::fs::read_to_string("fixtures/alsfm/wedges_beta_sweep.toml")?,
//! )?;
//! let out = tribo::simulate::alsfm::run(&plan)?;
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

pub mod driver;
pub mod plan;
pub mod rows;
pub mod scene;

pub use driver::run;
pub use rows::AlsfmOutput;
