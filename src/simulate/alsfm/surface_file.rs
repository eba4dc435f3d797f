//! Scene surfaces from profilometer files (`kind = "file"`): the file is read
//! as `tribo roughness` reads it (same readers, units and errors), the
//! window and form removal of MODELS.md §4 are applied, and the heights
//! become one period of a sampled ALSFM surface (MODELS.md §5).
//!
//! A measured profile is not periodic: the ALSFM wraps it, so the last
//! sample is followed by the first. Line (plane) detrending, the default,
//! removes the tilt that would otherwise put a step at that seam; any
//! remaining seam is one facet among the profile's n.

use std::path::Path;

use super::scene::SurfaceFileSpec;
use crate::error::{Error, Result};
use crate::extract::roughness::chain::{map_form, profile_form};
use crate::extract::roughness::input::{surfaces_from_dataset, Surface as Measured};
use crate::extract::roughness::stage::RoughnessSpec;
use crate::extract::roughness::Detrend;
use crate::hash::InputHash;
use crate::ingest::{read_path, IngestOptions};
use crate::models::alsfm::surface::Surface;

/// Reads the surface a `kind = "file"` table names, with `base` the folder
/// of the scene file. Returns the sampled surface and the file's hash for
/// the provenance.
///
/// Errors: the reader's own (file, line, column), a `section` out of range
/// or missing when the file holds several surfaces, a window with too few
/// points.
pub fn load(spec: &SurfaceFileSpec, base: &Path) -> Result<(Surface, InputHash)> {
    // The roughness stage's own settings parser: same units, ranges, errors.
    let (params, units) = RoughnessSpec {
        window: spec.window.clone(),
        window_y: spec.window_y.clone(),
        spacing: spec.spacing.clone(),
        x_unit: spec.x_unit.clone(),
        z_unit: spec.z_unit.clone(),
        detrend: Some(spec.detrend.unwrap_or(Detrend::Line)),
        ..Default::default()
    }
    .plan()?;
    let path = base.join(&spec.path);
    let ds = read_path(&path, &IngestOptions::default())?;
    let mut found = surfaces_from_dataset(&ds, &units)?;
    let index = match (spec.section, found.len()) {
        (None, 1) => 0,
        (None, n) => {
            return Err(Error::Config(format!(
                "{}: the file holds {n} profiles or maps; choose one with `section` (1..={n})",
                path.display()
            )))
        }
        (Some(k), n) if (1..=n).contains(&k) => k - 1,
        (Some(k), n) => {
            return Err(Error::Config(format!(
                "{}: section = {k}, but the file holds {n} profiles or maps",
                path.display()
            )))
        }
    };
    let (window, window_y) = (params.window, params.window_y);
    // The ALSFM samples a complete surface: a point not measured (NaN) has
    // no height to put there.
    let complete = |z: &[f64]| match crate::extract::roughness::mask::count_invalid(z) {
        0 => Ok(()),
        k => Err(Error::input(
            crate::error::Location::file(&path),
            format!(
                "{k} of {} points are not measured (NaN); a scene surface needs every \
                 height: crop the window to a measured region",
                z.len()
            ),
        )),
    };
    let surface = match found.swap_remove(index) {
        Measured::Profile(p) => {
            let mut w = p.windowed(window)?;
            complete(&w.z)?;
            // The form is fitted against the printed positions, as the
            // roughness stage does (the Dektak's Rq, MODELS §4).
            let x: Vec<f64> = match &w.positions {
                Some(printed) => printed.clone(),
                None => (0..w.z.len()).map(|i| w.x0 + i as f64 * w.dx).collect(),
            };
            profile_form(&mut w.z, &x, &params)?;
            Surface::Profile { dx: w.dx, z: w.z }
        }
        Measured::Map(m) => {
            let mut w = m.windowed(window, window_y)?;
            complete(&w.z)?;
            map_form(&mut w.z, (w.nx, w.ny), (w.dx, w.dy), &params)?;
            Surface::Map {
                dx: w.dx,
                dy: w.dy,
                nx: w.nx,
                z: w.z,
            }
        }
    };
    let hash = InputHash {
        path: path.display().to_string().into(),
        sha256: ds.sha256.into(),
    };
    Ok((surface, hash))
}
