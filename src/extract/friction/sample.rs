//! What the sample manifest says about one test file.

use std::path::Path;

use super::stribeck::Lubrication;
use crate::error::{Error, Location, Result};
use crate::ingest::manifest::{Manifest, ManifestRow};
use crate::ingest::started::{parse, DayOrder};
use crate::units::STANDARD_GRAVITY;

/// Sample information for one input file (all optional).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct SampleInfo {
    /// `sample_id`.
    pub sample_id: Option<String>,
    /// `test_id`: files with the same one are one test exported as several
    /// files ([`super::series`]).
    pub test_id: Option<String>,
    /// Normal force, N: `normal_force_N`, else `mass_g` × g.
    pub normal_force_n: Option<f64>,
    /// `apparent_area_m2`: apparent contact area A_th, m².
    pub apparent_area_m2: Option<f64>,
    /// `pattern` (flat, A, B, C, S, …).
    pub pattern: Option<String>,
    /// `area_fraction` AF of the pattern.
    pub area_fraction: Option<f64>,
    /// `direction` of sliding (for example x or y).
    pub direction: Option<String>,
    /// `temperature_C`.
    pub temperature_c: Option<f64>,
    /// `material`.
    pub material: Option<String>,
    /// `pin`.
    pub pin: Option<String>,
    /// `track_radius_mm`: wear-track radius of a pin-on-disc test, m.
    pub track_radius_m: Option<f64>,
    /// `test_started_at`: when the test started (ISO 8601 as normalised),
    /// overriding the file's header.
    pub test_started_at: Option<String>,
    /// The lubricant and contact, for the Stribeck curve.
    pub lubrication: Lubrication,
}

impl SampleInfo {
    /// The manifest row for `input`, if any. Bad numbers are errors naming
    /// the manifest line and column.
    pub fn from_manifest(manifest: Option<&Manifest>, input: &Path) -> Result<SampleInfo> {
        let Some(m) = manifest else {
            return Ok(SampleInfo::default());
        };
        let Some(row) = m.find(input) else {
            return Ok(SampleInfo::default());
        };
        let text = |k: &str| row.fields.get(k).cloned();
        let normal = match m.f64(row, "normal_force_N")? {
            Some(n) => Some(n),
            None => m.f64(row, "mass_g")?.map(|g| g * 1e-3 * STANDARD_GRAVITY),
        };
        Ok(SampleInfo {
            sample_id: text("sample_id"),
            test_id: text("test_id").filter(|t| !t.trim().is_empty()),
            normal_force_n: normal,
            apparent_area_m2: m.f64(row, "apparent_area_m2")?,
            pattern: text("pattern"),
            area_fraction: m.f64(row, "area_fraction")?,
            direction: text("direction"),
            temperature_c: m.f64(row, "temperature_C")?,
            material: text("material"),
            pin: text("pin"),
            track_radius_m: m.f64(row, "track_radius_mm")?.map(|r| r * 1e-3),
            test_started_at: started(m, row)?,
            lubrication: Lubrication {
                viscosity_pa_s: m.f64(row, "viscosity_Pa_s")?,
                alpha_per_pa: m.f64(row, "pressure_viscosity_per_GPa")?.map(|a| a * 1e-9),
                modulus_pa: m.f64(row, "reduced_modulus_GPa")?.map(|e| e * 1e9),
                radius_m: m.f64(row, "reduced_radius_mm")?.map(|r| r * 1e-3),
                composite_rq_m: m.f64(row, "composite_rq_um")?.map(|s| s * 1e-6),
                journal_m: m
                    .f64(row, "journal_diameter_mm")?
                    .zip(m.f64(row, "bearing_length_mm")?)
                    .map(|(d, l)| (d * 1e-3, l * 1e-3)),
            },
        })
    }
}

/// The manifest's `test_started_at`, read as a date and time (numeric
/// dates must not be ambiguous; ISO 8601 is best) and written back as ISO
/// 8601; a value that is no date is an error naming the line.
fn started(m: &Manifest, row: &ManifestRow) -> Result<Option<String>> {
    let Some(text) = row.fields.get("test_started_at") else {
        return Ok(None);
    };
    let bad = |why: String| {
        Error::input(
            Location::line(&m.path, row.line).with_column("test_started_at"),
            why,
        )
    };
    match parse(text, DayOrder::Unknown).map_err(bad)? {
        Some(at) => Ok(Some(at.to_string())),
        None => Err(bad(format!(
            "'{text}' is not a date and time (for example 2022-05-12T12:21:50, with +02:00 when the offset is known)"
        ))),
    }
}
