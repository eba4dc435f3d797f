//! The friction stage for one file: read, build the SI trace of every
//! section, extract features. Independent of every other file, so files run
//! in parallel and, later, incrementally or on several machines.

use std::path::Path;

use crate::error::Result;
use crate::extract::friction::{analyse_trace, FrictionParams, SampleInfo, TraceFeatures};
use crate::ingest::manifest::Manifest;
use crate::ingest::read_path;
use crate::ingest::trace::{friction_trace, Trace};

use super::plan::FileOptions;

/// Everything the friction stage produced for one file.
#[derive(Debug, Clone)]
pub struct FrictionFile {
    /// The path as given.
    pub source: String,
    /// SHA-256 of the bytes.
    pub sha256: String,
    /// Manifest information.
    pub sample: SampleInfo,
    /// One trace per section, in SI.
    pub traces: Vec<Trace>,
    /// Features per trace.
    pub features: Vec<TraceFeatures>,
}

/// Processes one file. Errors are bad input (unreadable file, unknown unit,
/// missing column); a trace that reads but cannot be analysed gives rows
/// with a status instead.
pub fn process_file(
    path: &Path,
    options: &FileOptions,
    manifest: Option<&Manifest>,
    params: &FrictionParams,
) -> Result<FrictionFile> {
    let ds = read_path(path, &options.ingest)?;
    let sample = SampleInfo::from_manifest(manifest, path)?;
    let traces = (0..ds.sections.len())
        .map(|i| friction_trace(&ds, i, &options.columns))
        .collect::<Result<Vec<_>>>()?;
    let features = traces
        .iter()
        .map(|t| analyse_trace(t, &sample, params))
        .collect();
    Ok(FrictionFile {
        source: path.display().to_string(),
        sha256: ds.sha256,
        sample,
        traces,
        features,
    })
}
