//! What the sample manifest says about one test file.

use std::path::Path;

use crate::error::Result;
use crate::ingest::manifest::Manifest;
use crate::units::STANDARD_GRAVITY;

/// Sample information for one input file (all optional).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct SampleInfo {
    /// `sample_id`.
    pub sample_id: Option<String>,
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
            normal_force_n: normal,
            apparent_area_m2: m.f64(row, "apparent_area_m2")?,
            pattern: text("pattern"),
            area_fraction: m.f64(row, "area_fraction")?,
            direction: text("direction"),
            temperature_c: m.f64(row, "temperature_C")?,
            material: text("material"),
            pin: text("pin"),
            track_radius_m: m.f64(row, "track_radius_mm")?.map(|r| r * 1e-3),
        })
    }
}
