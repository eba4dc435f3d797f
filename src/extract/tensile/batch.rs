//! Many files with a sample manifest: read, analyse, then resolve controls.
//!
//! Manifest columns: `file`, `sample_id`, `material`, `knot`, `diameter_um`,
//! `fibre_length_mm` (l), `end_distance_mm` (l0), `density_g_per_cm3`
//! (default 1.4, with the status `defaulted_density`), `control_id`,
//! `width_mm` and `thickness_mm` (a rectangular section). Without a
//! `sample_id`, the id the file states (Bluehill `Specimen ID`, T150
//! `SpecimenName`, Instron `Specimen label`) is used, else the file stem. A value stated in the file (the T150
//! diameter) is used when the manifest is silent. Problems with one fibre
//! (no manifest row, a bad manifest value, zero diameter, an unknown
//! control) become that fibre's status; a file that cannot be read at all
//! is an error for that file only.

use crate::status::{Code, Status};
use std::path::Path;

use rayon::prelude::*;

use crate::error::{Error, Result};
use crate::ingest::manifest::Manifest;
use crate::ingest::{read_path, Dataset, IngestOptions};

use super::analyze::{analyze_fibre, FibreFeatures};
use super::curve::{FibreMeta, Knot, DEFAULT_DENSITY_KG_PER_M3};
use super::from_dataset::{curve_from_dataset, file_facts};
use super::params::TensileParams;
use super::records::{apply_controls, FibreRecord};

/// The fibre's metadata from the manifest, and any problems found with it.
pub fn meta_from_manifest(path: &Path, manifest: Option<&Manifest>) -> (FibreMeta, Status) {
    let stem = path
        .file_stem()
        .map(|s| s.to_string_lossy().to_string())
        .unwrap_or_default();
    let mut meta = FibreMeta::new(stem);
    let mut notes = Status::ok();
    let defaulted = |notes: &mut Status| {
        notes.push(
            Code::DefaultedDensity,
            "no density_g_per_cm3 for this file: the toughness per mass uses 1.4 g/cm³ (silk)",
        )
    };
    let Some(m) = manifest else {
        defaulted(&mut notes);
        return (meta, notes);
    };
    let Some(row) = m.find(path) else {
        notes.push(
            Code::NoManifestRow,
            format!(
                "{} has no row for this file; analysed as unknotted, density 1.4",
                m.path.display()
            ),
        );
        defaulted(&mut notes);
        return (meta, notes);
    };
    let text = |k: &str| row.fields.get(k).cloned();
    if let Some(id) = text("sample_id") {
        meta.sample_id = id;
    }
    meta.material = text("material").unwrap_or_default();
    meta.knot = Knot::parse(&text("knot").unwrap_or_default());
    meta.control_id = text("control_id");
    let mut num = |k: &str, scale: f64| match m.f64(row, k) {
        Ok(v) => v.map(|v| v * scale),
        Err(e) => {
            notes.push(Code::BadManifest, e.to_string());
            None
        }
    };
    meta.diameter_m = num("diameter_um", 1e-6);
    meta.fibre_length_m = num("fibre_length_mm", 1e-3);
    meta.end_distance_m = num("end_distance_mm", 1e-3);
    meta.width_m = num("width_mm", 1e-3);
    meta.thickness_m = num("thickness_mm", 1e-3);
    let density = num("density_g_per_cm3", 1e3);
    meta.density_kg_per_m3 = density.unwrap_or(DEFAULT_DENSITY_KG_PER_M3);
    if density.is_none() {
        defaulted(&mut notes);
    }
    (meta, notes)
}

/// A file that could not be read, and why.
pub type FileFailure = (std::path::PathBuf, Error);

fn empty_with(status: Status) -> FibreFeatures {
    FibreFeatures::empty(status)
}

/// Reads and analyses one file. `Err` only when the file cannot be read
/// as a table; every other problem is in the record's status.
pub fn analyze_file(
    path: &Path,
    manifest: Option<&Manifest>,
    options: &IngestOptions,
    params: &TensileParams,
) -> Result<FibreRecord> {
    analyze_dataset(&read_path(path, options)?, manifest, params)
}

/// As [`analyze_file`], for a file already read.
pub fn analyze_dataset(
    ds: &Dataset,
    manifest: Option<&Manifest>,
    params: &TensileParams,
) -> Result<FibreRecord> {
    analyze_with_curve(ds, manifest, params).map(|(r, _)| r)
}

/// As [`analyze_dataset`], also returning the stress–strain curve it
/// analysed (for drawing); none when the diameter ruled the curve out.
pub fn analyze_with_curve(
    ds: &Dataset,
    manifest: Option<&Manifest>,
    params: &TensileParams,
) -> Result<(FibreRecord, Option<super::StressStrainCurve>)> {
    let path = ds.source.as_path();
    let facts = file_facts(ds);
    let (mut meta, notes) = meta_from_manifest(path, manifest);
    if meta.diameter_m.is_none() {
        meta.diameter_m = facts.diameter_m;
    }
    if meta.width_m.is_none() && meta.thickness_m.is_none() {
        (meta.width_m, meta.thickness_m) = (facts.width_m, facts.thickness_m);
    }
    if meta.section().is_none() {
        meta.area_m2 = facts.area_m2;
    }
    let id_from_manifest = manifest
        .and_then(|m| m.find(path))
        .is_some_and(|r| r.fields.contains_key("sample_id"));
    if let (false, Some(id)) = (id_from_manifest, &facts.specimen_id) {
        meta.sample_id = id.clone();
    }
    let diameter_ok = meta.diameter_m.is_none_or(|d| d > 0.0 && d.is_finite());
    let (features, curve) = if !diameter_ok {
        let mut s = notes;
        s.push(
            Code::BadDiameter,
            format!(
                "{} um, expected > 0",
                meta.diameter_m.unwrap_or(f64::NAN) * 1e6
            ),
        );
        (empty_with(s), None)
    } else {
        // A file without a usable curve failed: it belongs in the errors
        // table and the failed count, not in a row.
        let curve = curve_from_dataset(ds, &meta, &facts)?;
        let mut f = analyze_fibre(&curve, &meta, params);
        let mut s = notes;
        s.extend(std::mem::take(&mut f.status));
        f.status = s;
        (f, Some(curve))
    };
    let record = FibreRecord {
        source: path.display().to_string(),
        meta,
        features,
        instrument: facts.instrument,
    };
    Ok((record, curve))
}

/// Analyses files in parallel (results in input order, so the output does
/// not depend on the thread count), then applies Eq. 5.4 with the controls.
/// Returns the records and the files that could not be read.
pub fn analyze_files(
    paths: &[std::path::PathBuf],
    manifest: Option<&Manifest>,
    options: &IngestOptions,
    params: &TensileParams,
) -> Result<(Vec<FibreRecord>, Vec<FileFailure>)> {
    let planned: Vec<(std::path::PathBuf, IngestOptions)> =
        paths.iter().map(|p| (p.clone(), options.clone())).collect();
    analyze_planned(&planned, manifest, params)
}

/// As [`analyze_files`], with reading options per file (the entry point for
/// a pipeline stage, whose plan resolves `[[ingest.override]]` per file).
pub fn analyze_planned(
    files: &[(std::path::PathBuf, IngestOptions)],
    manifest: Option<&Manifest>,
    params: &TensileParams,
) -> Result<(Vec<FibreRecord>, Vec<FileFailure>)> {
    params.validate()?;
    let results: Vec<Result<FibreRecord>> = files
        .par_iter()
        .map(|(p, o)| analyze_file(p, manifest, o, params))
        .collect();
    let mut records = Vec::new();
    let mut failures = Vec::new();
    for ((p, _), r) in files.iter().zip(results) {
        match r {
            Ok(rec) => records.push(rec),
            Err(e) => failures.push((p.clone(), e)),
        }
    }
    apply_controls(&mut records);
    Ok((records, failures))
}
