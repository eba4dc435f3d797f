//! The analysis of one file for the roughness stage: its profiles and maps
//! through [`super::analyze`], with the instrument's own statements as
//! defaults and references ([`super::instrument`]): the evaluation window
//! a Dektak's cursors give (when the settings give none) and its stylus tip
//! radius (for the reliability cut-off, when the settings give none); its
//! printed results beside ours, and statuses when the windows or the
//! values differ. The settings are in [`super::spec`], the tables in
//! [`super::tables`].

use super::analyze::{analyze_map, analyze_profile};
use super::input::{assumed_units, surfaces_from_dataset, AxisUnits, Surface};
use super::params::RoughnessParams;
use crate::error::{Error, Result};
use crate::ingest::Dataset;

pub use super::file::RoughnessFile;
pub use super::instrument::InstrumentRoughness;
pub use super::spec::RoughnessSpec;
pub use super::tables::{acf_table, bearing_table, psd_table, roughness_table};
pub use crate::units::parse_quantity;

/// Analyses every profile and map of a file already read.
pub fn analyze_dataset(
    ds: &Dataset,
    params: &RoughnessParams,
    units: &AxisUnits,
) -> Result<RoughnessFile> {
    analyze_surfaces(ds, &surfaces_from_dataset(ds, units)?, params, units)
}

/// As [`analyze_dataset`], on the file's surfaces already taken from it
/// (the stage draws them too).
pub fn analyze_surfaces(
    ds: &Dataset,
    surfaces: &[Surface],
    params: &RoughnessParams,
    units: &AxisUnits,
) -> Result<RoughnessFile> {
    let instrument = InstrumentRoughness::from_dataset(ds);
    let mut p = params.clone();
    p.tip_radius = p.tip_radius.or(instrument.tip_radius);
    let mut reports = surfaces
        .iter()
        .map(|s| match s {
            Surface::Profile(prof) => {
                let mut pp = p.clone();
                // The instrument's window, when the data cover it (a file
                // cut short is analysed whole, and says window_differs).
                let stated = instrument
                    .window
                    .filter(|&w| prof.window_range(Some(w)).is_ok());
                pp.window = pp.window.or(stated);
                let mut r = analyze_profile(prof, &pp)?;
                let notes = instrument.compare(&r);
                r.notes.extend(notes);
                Ok(r)
            }
            Surface::Map(m) => analyze_map(m, &p),
        })
        .collect::<Result<Vec<_>>>()?;
    let assumed = assumed_units(ds, units);
    reports
        .iter_mut()
        .for_each(|r| r.notes.extend(assumed.clone()));
    // Heights near 1e154 m and beyond overflow Rq's squares: an error of
    // this file, not a null in a column that must hold a value.
    if reports.iter().any(|r| !r.rq.is_finite()) {
        return Err(Error::Numerical(format!(
            "{}: Rq is not finite: the heights are out of range for a surface \
             (their squares overflow); check the height column and its unit",
            ds.source.display()
        )));
    }
    Ok(RoughnessFile {
        source: ds.source.display().to_string(),
        reports,
        sample_id: None,
        pin: None,
        instrument,
    })
}
