//! Friction features of a trace (MODELS.md §1): segments (strokes of a
//! reciprocating test, or the whole trace), static peak, dynamic plateau,
//! stick-slip events, μ with the normal force from the trace or the
//! manifest, the instrument's own μ over the same window, and velocity steps.

mod doubts;
pub mod params;
mod rows;
pub mod sample;
pub mod segment;
pub mod steps;
mod stroke;
pub mod trace;

pub use params::{FrictionParams, StrokeMode};
pub use sample::SampleInfo;
pub use segment::{segment_features, SegmentFeatures};
pub use steps::StepRow;
pub use trace::{analyse_trace, FrictionRow, StickSlipRow, TraceFeatures};
