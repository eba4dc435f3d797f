//! Many files with a sample manifest: read, analyse, then resolve controls.
//!
//! Manifest columns: `file`, `sample_id`, `material`, `material_class`
//! (`metal`, `plastic`, `elastomer`, `fibre`, `brittle`: the modulus window
//! and break definition, [`super::class`]), `test_direction` (`tension`,
//! `compression`; else found from the load's sign), `knot`, `diameter_um`
//! or `diameter_mm`, `width_mm` and `thickness_mm` (a rectangular
//! section), `area_mm2`, `gauge_length_mm`, `fibre_length_mm` (l),
//! `end_distance_mm` (l0), `density_g_per_cm3`, `control_id`. Without a
//! `sample_id`, the id the file states (Bluehill `Specimen ID`, T150
//! `SpecimenName`, Instron `Specimen label`) is used, else the file stem.
//! A value stated in the file (the T150 diameter, a testXpert section) is
//! used when the manifest is silent.
//!
//! The fibre protocol (thesis Ch. 5) applies to `material_class = fibre`,
//! and without a class to a knotted fibre, a row that uses the protocol's
//! columns (`fibre_length_mm`, `end_distance_mm`, `control_id`) or a file
//! from a fibre tester (T150): there, without a density, the toughness per
//! mass uses silk's 1.4 g/cm³ with the status `defaulted_density`. Any
//! other specimen has a toughness per mass only when its density is given
//! (or its file states its mass and size); without a class its modulus
//! takes tribo's default window with the status `default_modulus_window`.
//! Problems with one specimen (no manifest row, a bad manifest value, zero
//! diameter, an unknown control) become its status; a file that cannot be
//! read at all is an error for that file only.

use crate::status::{Code, Status};
use std::path::Path;

use rayon::prelude::*;

use crate::error::{Error, Result};
use crate::ingest::manifest::{Manifest, ManifestRow};
use crate::ingest::{read_path, Dataset, IngestOptions};

use super::analyze::{analyze_fibre, FibreFeatures};
use super::checks;
use super::class::{Direction, MaterialClass};
use super::curve::{FibreMeta, Knot, DEFAULT_DENSITY_KG_PER_M3};
use super::from_dataset::{curve_from_dataset, file_facts, FileFacts};
use super::params::TensileParams;
use super::records::{apply_controls, FibreRecord};

/// The specimen's metadata from the manifest, and any problems found with
/// it. The density is the manifest's only (the defaults come with the
/// class, [`resolve`]).
pub fn meta_from_manifest(path: &Path, manifest: Option<&Manifest>) -> (FibreMeta, Status) {
    let stem = path
        .file_stem()
        .map(|s| s.to_string_lossy().to_string())
        .unwrap_or_default();
    let mut meta = FibreMeta::new(stem);
    meta.density_kg_per_m3 = None;
    let mut notes = Status::ok();
    let Some(m) = manifest else {
        return (meta, notes);
    };
    let Some(row) = m.find(path) else {
        notes.push(
            Code::NoManifestRow,
            format!(
                "{} has no row for this file: analysed as unknotted, with what the file states",
                m.path.display()
            ),
        );
        return (meta, notes);
    };
    let text = |k: &str| row.fields.get(k).cloned();
    if let Some(id) = text("sample_id") {
        meta.sample_id = id;
    }
    meta.material = text("material").unwrap_or_default();
    meta.knot = Knot::parse(&text("knot").unwrap_or_default());
    meta.control_id = text("control_id");
    if let Some(c) = text("material_class") {
        meta.material_class = MaterialClass::parse(&c);
        if meta.material_class.is_none() {
            let names: Vec<&str> = MaterialClass::ALL.iter().map(|c| c.name()).collect();
            notes.push(
                Code::BadManifest,
                format!("material_class '{c}': expected one of {}", names.join(", ")),
            );
        }
    }
    if let Some(d) = text("test_direction") {
        meta.direction = Direction::parse(&d);
        if meta.direction.is_none() {
            notes.push(
                Code::BadManifest,
                format!("test_direction '{d}': expected tension or compression"),
            );
        }
    }
    let mut num = |k: &str, scale: f64| match m.f64(row, k) {
        Ok(v) => v.map(|v| v * scale),
        Err(e) => {
            notes.push(Code::BadManifest, e.to_string());
            None
        }
    };
    meta.diameter_m = num("diameter_um", 1e-6).or(num("diameter_mm", 1e-3));
    meta.fibre_length_m = num("fibre_length_mm", 1e-3);
    meta.end_distance_m = num("end_distance_mm", 1e-3);
    meta.width_m = num("width_mm", 1e-3);
    meta.thickness_m = num("thickness_mm", 1e-3);
    meta.area_m2 = num("area_mm2", 1e-6);
    meta.gauge_length_m = num("gauge_length_mm", 1e-3);
    meta.density_kg_per_m3 = num("density_g_per_cm3", 1e3);
    (meta, notes)
}

/// Whether a manifest row uses the fibre protocol's own columns.
fn fibre_row(row: Option<&ManifestRow>) -> bool {
    row.is_some_and(|r| {
        ["fibre_length_mm", "end_distance_mm", "control_id"]
            .iter()
            .any(|k| r.fields.get(*k).is_some_and(|v| !v.is_empty()))
    })
}

/// Completes the metadata with what the file states, and settles the
/// class and the density (module doc); the notes say what was defaulted.
fn resolve(
    meta: &mut FibreMeta,
    facts: &FileFacts,
    row: Option<&ManifestRow>,
    params: &TensileParams,
) -> Status {
    let mut notes = facts.notes.clone();
    if meta.diameter_m.is_none() {
        meta.diameter_m = facts.diameter_m;
    }
    if meta.width_m.is_none() && meta.thickness_m.is_none() {
        (meta.width_m, meta.thickness_m) = (facts.width_m, facts.thickness_m);
    }
    if meta.section().is_none() {
        meta.area_m2 = facts.area_m2;
    }
    if meta.gauge_length_m.is_none() {
        meta.gauge_length_m = facts.gauge_length_m;
    }
    let id_from_manifest = row.is_some_and(|r| r.fields.contains_key("sample_id"));
    if let (false, Some(id)) = (id_from_manifest, &facts.specimen_id) {
        meta.sample_id = id.clone();
    }
    let fibre = meta.knot.is_knotted() || fibre_row(row);
    let class = meta
        .material_class
        .or(facts.implied_class)
        .or(fibre.then_some(MaterialClass::Fibre));
    if meta.density_kg_per_m3.is_none() {
        meta.density_kg_per_m3 = facts.density_kg_per_m3;
    }
    match class {
        Some(MaterialClass::Fibre) if meta.density_kg_per_m3.is_none() => {
            meta.density_kg_per_m3 = Some(DEFAULT_DENSITY_KG_PER_M3);
            notes.push(
                Code::DefaultedDensity,
                "no density_g_per_cm3 for this fibre: the toughness per mass uses 1.4 g/cm³ (silk)",
            );
        }
        None if params.modulus_stress_window_mpa.is_none() => notes.push(
            Code::DefaultModulusWindow,
            "no material_class: the modulus is the steepest slope over windows of \
             modulus_window × the strain at maximum stress (give material_class: metal, \
             plastic, elastomer, fibre or brittle for its standard window)",
        ),
        _ => {}
    }
    meta.material_class = class;
    notes
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
    let (mut meta, mut notes) = meta_from_manifest(path, manifest);
    let row = manifest.and_then(|m| m.find(path));
    notes.extend(resolve(&mut meta, &facts, row, params));
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
        let (curve, corrected) = curve_from_dataset(ds, &meta, &facts)?;
        let mut f = analyze_fibre(&curve, &meta, params);
        let g = &mut f.general;
        g.direction = curve.direction;
        g.max_force_n = curve
            .max_force_n
            .or_else(|| Some(g.max_stress_pa? * meta.section()?.1));
        let section = ds.sections.iter().max_by_key(|s| s.rows());
        let checked = checks::check(section, &meta, &facts, &f);
        let mut s = notes;
        s.extend(corrected);
        s.extend(std::mem::take(&mut f.status));
        s.extend(checked);
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
