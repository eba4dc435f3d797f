//! Friction features of a trace (MODELS.md §1): segments (strokes of a
//! reciprocating test, or the whole trace), static peak, dynamic plateau,
//! stick-slip events, μ with the normal force from the trace or the
//! manifest, the instrument's own μ over the same window, and velocity steps.

pub mod assess;
pub mod cycles;
mod decay;
mod doubts;
pub mod motion;
pub mod params;
pub mod path;
mod rows;
pub mod running_in;
pub mod sample;
pub mod segment;
pub mod series;
pub mod steps;
pub mod stribeck;
mod stroke;
pub mod trace;
pub mod wear_rate;
pub mod whole;

pub use params::{FrictionParams, StrokeMode};
pub use sample::SampleInfo;
pub use segment::{segment_features, SegmentFeatures};
pub use steps::StepRow;
pub use trace::{analyse_trace, analyse_trace_with, FrictionRow, StickSlipRow, TraceFeatures};
