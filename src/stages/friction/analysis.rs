//! The friction stage's work on one file: its SI traces and their
//! features, its cycles and its running-in, the typed rows its tables and
//! figures are made of.

use super::super::FileInput;
use crate::error::Result;
use crate::extract::friction::assess::{assess, number_cycles, TestRow};
use crate::extract::friction::motion::{apply_crank, Motion};
use crate::extract::friction::stribeck::stribeck_point;
use crate::extract::friction::whole::restate_whole_rows;
use crate::extract::friction::{analyse_trace_with, FrictionParams, SampleInfo, TraceFeatures};
use crate::ingest::drive::declared_crank;
use crate::ingest::radius::{track_radii, RadiusHints};
use crate::ingest::started::started_at;
use crate::ingest::trace::{friction_traces, ManifestHints, Trace};
use crate::status::{Code, Status};

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
    /// When the test started (ISO 8601): the manifest's, else the header's.
    pub started_at: Option<String>,
    /// The test's `friction_tests` rows.
    pub tests: Vec<TestRow>,
}

/// Reads the SI trace of every section of one file and extracts its
/// features, its cycles and its running-in. Errors are bad input (unknown
/// unit, missing column); a trace that reads but cannot be analysed gives
/// rows with a status instead.
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
    // A header date that cannot be read without a guess is said on the
    // test's row, not a failure of the file.
    let (started, started_note) = match &sample.test_started_at {
        Some(at) => (Some(at.clone()), None),
        None => match started_at(&file.dataset) {
            Ok(at) => (at.map(|a| a.to_string()), None),
            Err(e) => (None, Some(e.to_string())),
        },
    };
    let cranks = (0..file.dataset.sections.len())
        .map(|i| declared_crank(&file.dataset, i))
        .collect::<Result<Vec<_>>>()?;
    let mut traces = friction_traces(file.dataset, file.columns, &hints)?;
    let mut features: Vec<TraceFeatures> = traces
        .iter_mut()
        .zip(&cranks)
        .map(|(t, crank)| {
            if let Some(c) = crank {
                apply_crank(t, c);
            }
            let motion = Motion {
                crank: *crank,
                track_radius_m: t.track_radius.as_ref().map(|r| r.radius_m),
            };
            let mut f = analyse_trace_with(t, &sample, params, &motion);
            doubt_named_radius(t, &mut f);
            f
        })
        .collect();
    for (_, s) in features.iter_mut().flat_map(|f| f.steps.iter_mut()) {
        s.stribeck = stribeck_point(
            &sample.lubrication,
            sample.apparent_area_m2,
            s.normal_force_n,
            s.velocity_m_per_s,
        );
    }
    number_cycles(&mut features, params.partial_stroke_fraction);
    let mut tests = assess(&features, &params.steady(), params.step_tolerance);
    restate_whole_rows(&traces, &mut features, &tests, &sample);
    if let (Some(note), Some(test)) = (started_note, tests.first_mut()) {
        let mut s = Status::of(Code::BadInput, format!("test_started_at: {note}"));
        s.extend(std::mem::take(&mut test.status));
        test.status = s;
    }
    Ok(FrictionFile {
        source: file.path.display().to_string(),
        sample,
        traces,
        features,
        started_at: started,
        tests,
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
