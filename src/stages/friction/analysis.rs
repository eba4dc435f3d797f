//! The friction stage's work on one file: its SI traces and their
//! features, the typed rows its tables and figures are made of.

use super::super::FileInput;
use crate::error::Result;
use crate::extract::friction::{analyse_trace, FrictionParams, SampleInfo, TraceFeatures};
use crate::ingest::radius::{track_radii, RadiusHints};
use crate::ingest::trace::{friction_traces, ManifestHints, Trace};
use crate::status::Code;

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
    // Each section's track radius: the manifest's, the file's, the stage
    // positions', the name's (ingest::radius).
    let radius_hints = RadiusHints::from_manifest(file.manifest, file.path)?;
    let hints = ManifestHints {
        normal_force_n: sample.normal_force_n,
        track_radius_m: None,
        radii: track_radii(&file.dataset, &radius_hints)?,
    };
    let traces = friction_traces(file.dataset, file.columns, &hints)?;
    let features = traces
        .iter()
        .map(|t| {
            let mut f = analyse_trace(t, &sample, params);
            doubt_named_radius(t, &mut f);
            f
        })
        .collect();
    Ok(FrictionFile {
        source: file.path.display().to_string(),
        sample,
        traces,
        features,
    })
}

/// A sliding speed from a track radius that only the file's name gives is
/// a guess about a name: every step of the trace says so.
fn doubt_named_radius(t: &Trace, f: &mut TraceFeatures) {
    let Some(r) = t.track_radius.filter(|r| r.source.from_file_name()) else {
        return;
    };
    let detail = format!(
        "the track radius {:.4} mm that turns rpm into the sliding speed comes from the file's name \
         (give track_radius_mm, track_centre_mm or step_track_radius_mm in the manifest)",
        r.radius_m * 1e3
    );
    for (_, s) in &mut f.steps {
        s.status.push(Code::RadiusFromFileName, detail.clone());
    }
}
