//! The friction stage's work on one file: its SI traces and their
//! features, the typed rows its tables and figures are made of.

use super::super::FileInput;
use crate::error::Result;
use crate::extract::friction::{analyse_trace, FrictionParams, SampleInfo, TraceFeatures};
use crate::ingest::trace::{declared_track_radius_m, friction_traces, ManifestHints, Trace};

/// Everything the stage produced for one file.
#[derive(Debug, Clone)]
pub struct FrictionFile {
    /// The path as given.
    pub source: String,
    /// Manifest information.
    pub sample: SampleInfo,
    /// One trace per section, in SI.
    pub traces: Vec<Trace>,
    /// Features per trace.
    pub features: Vec<TraceFeatures>,
}

/// Reads the SI trace of every section of one file and extracts its
/// features. Errors are bad input (unknown unit, missing column); a trace
/// that reads but cannot be analysed gives rows with a status instead.
pub fn analyse_file(file: FileInput, params: &FrictionParams) -> Result<FrictionFile> {
    let sample = SampleInfo::from_manifest(file.manifest, file.path)?;
    // The manifest's track radius first, else the one the file states.
    let track_radius_m = match sample.track_radius_m {
        Some(r) => Some(r),
        None => declared_track_radius_m(&file.dataset)?,
    };
    let hints = ManifestHints {
        normal_force_n: sample.normal_force_n,
        track_radius_m,
    };
    let traces = friction_traces(file.dataset, file.columns, &hints)?;
    let features = traces
        .iter()
        .map(|t| analyse_trace(t, &sample, params))
        .collect();
    Ok(FrictionFile {
        source: file.path.display().to_string(),
        sample,
        traces,
        features,
    })
}
