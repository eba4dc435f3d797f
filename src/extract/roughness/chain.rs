//! The processing chain in the order of ISO 25178-2/-3 (and ISO 4287/3274
//! for profiles): evaluation window → S-filter (λs) → F-operator (form
//! removal) → L-filter (λc: Gaussian, robust or valley suppression) → the
//! heights the parameters are computed on. Each stage is chosen in
//! [`RoughnessParams`] (the pipeline file's `[roughness]` table or the
//! command line); points not measured stay so through every stage
//! ([`super::mask`]).
//!
//! The form of a profile is fitted against its positions as printed in the
//! file when it has them ([`Profile::positions`]), as vendor software does:
//! a Dektak prints a 0.15625 µm step rounded to 0.1 µm, and its Ra, Rq and
//! Rsk are those of a line fitted against the printed positions (MODELS.md
//! §4; the golden test: against the uniform grid Ra moves by 0.08 %).
//! Filters, slopes and spectra use the uniform spacing Δx.

use super::circle::{remove_circle, remove_cylinder};
use super::form::{detrend_map, detrend_profile_at, remove_polynomial, remove_polynomial_map};
use super::map::AreaMap;
use super::params::{Detrend, FilterKind, RoughnessParams};
use super::surface::{Profile, MIN_POINTS};
use crate::error::{Error, Result};
use crate::signal::gaussian_filter::{mean_line, mean_surface, FilterEnds, GaussianFilterParams};
use crate::signal::robust_filter::{robust_mean_line, robust_mean_surface, RobustRun};
use crate::signal::valley_filter::{valley_mean_line, valley_mean_surface};
use rayon::prelude::*;

/// The heights the parameters are computed on, and what the chain did.
#[derive(Debug, Clone)]
pub struct Chained {
    /// Row-major heights (m), `ny` rows of `nx`; a profile has `ny = 1`.
    pub z: Vec<f64>,
    /// Points per row.
    pub nx: usize,
    /// Rows.
    pub ny: usize,
    /// Spacing along x (m).
    pub dx: f64,
    /// Spacing along y (m); Δx for a profile.
    pub dy: f64,
    /// The largest height magnitude before form removal (the scale of the
    /// round-off in the amplitude sums, for the flatness test).
    pub scale: f64,
    /// Radius of the fitted circle or cylinder (m).
    pub form_radius: Option<f64>,
    /// How the robust filter ended, when it ran.
    pub robust: Option<RobustRun>,
}

/// At least [`MIN_POINTS`] of `z` measured, else an error naming `source`
/// and `where_`.
pub fn enough_measured(source: &str, z: &[f64], where_: &str) -> Result<()> {
    let n = z.len() - super::mask::count_invalid(z);
    if n < MIN_POINTS {
        return Err(Error::NotApplicable(format!(
            "{source}: {n} of {} points {where_} are measured (the others are not: NaN in \
             the file, or a gap wider than the filter can bridge); at least {MIN_POINTS} \
             are needed",
            z.len()
        )));
    }
    Ok(())
}

/// The largest |z| (the scale of round-off in the amplitude sums), on all
/// threads: a maximum does not depend on the order it is taken in.
fn largest_magnitude(z: &[f64]) -> f64 {
    crate::signal::scan::finite_range(z).map_or(0.0, |(lo, hi)| lo.abs().max(hi.abs()))
}

/// The S-filter's Gaussian with cut-off λs, ends renormalised (nothing is
/// discarded at this stage).
fn short_filter(ls: f64) -> Result<GaussianFilterParams> {
    let mut f = GaussianFilterParams::new(ls)?;
    f.ends = FilterEnds::Renormalize;
    Ok(f)
}

/// Points not measured in `before` stay so in `after`.
fn keep_gaps(after: &mut [f64], before: &[f64]) {
    after.par_iter_mut().zip(before).for_each(|(a, b)| {
        if b.is_nan() {
            *a = f64::NAN;
        }
    });
}

/// Form removal of a profile with positions `x` (m); the fitted
/// circle's radius.
pub fn profile_form(z: &mut [f64], x: &[f64], params: &RoughnessParams) -> Result<Option<f64>> {
    match params.detrend {
        Detrend::None | Detrend::Mean | Detrend::Line => {
            detrend_profile_at(z, Some(x), params.detrend)
        }
        Detrend::Polynomial => remove_polynomial(z, x, params.form_degree)?,
        Detrend::Circle => return Ok(Some(remove_circle(z, x, params.form_radius)?.radius)),
    }
    Ok(None)
}

/// The window, S-filter, form removal and L-filter of a profile.
pub fn profile_chain(p: &Profile, params: &RoughnessParams) -> Result<Chained> {
    let (lo, hi) = p.window_range(params.window)?;
    let mut z: Vec<f64> = p.z[lo..hi].par_iter().copied().collect();
    enough_measured(&p.source, &z, "in the evaluation window")?;
    let scale = largest_magnitude(&z);
    if let Some(ls) = params.short_cutoff {
        let mut s = mean_line(&z, p.dx, &short_filter(ls)?)?;
        keep_gaps(&mut s, &z);
        z = s;
    }
    let x: Vec<f64> = match &p.positions {
        Some(printed) => printed[lo..hi].to_vec(),
        None => (lo..hi).map(|i| p.x0 + i as f64 * p.dx).collect(),
    };
    let form_radius = profile_form(&mut z, &x, params)?;
    let mut robust = None;
    if let Some(f) = &params.filter {
        let length = (z.len() - 1) as f64 * p.dx;
        if length < f.cutoff {
            return Err(Error::NotApplicable(format!(
                "{}: profile length {length:.6e} m is shorter than the cut-off λc = {:.6e} m; \
                 choose a smaller λc or a longer profile",
                p.source, f.cutoff
            )));
        }
        let mean = match params.filter_kind {
            FilterKind::Gaussian => mean_line(&z, p.dx, f)?,
            FilterKind::Robust => {
                let (m, run) = robust_mean_line(&z, p.dx, f)?;
                robust = Some(run);
                m
            }
            FilterKind::ValleySuppression => valley_mean_line(&z, p.dx, f)?,
        };
        let drop = f.discard_count(p.dx);
        let keep = z.len().saturating_sub(2 * drop);
        if keep < MIN_POINTS {
            return Err(Error::NotApplicable(format!(
                "{}: {keep} points remain after discarding λc/2 at each end; at least \
                 {MIN_POINTS} are needed (shorter λc or Renormalize ends)",
                p.source
            )));
        }
        z = (drop..drop + keep).map(|i| z[i] - mean[i]).collect();
        enough_measured(&p.source, &z, "after the filter")?;
    }
    let n = z.len();
    Ok(Chained {
        z,
        nx: n,
        ny: 1,
        dx: p.dx,
        dy: p.dx,
        scale,
        form_radius,
        robust,
    })
}

/// Form removal of a row-major map.
pub fn map_form(
    z: &mut [f64],
    (nx, ny): (usize, usize),
    (dx, dy): (f64, f64),
    params: &RoughnessParams,
) -> Result<Option<f64>> {
    match params.detrend {
        Detrend::None | Detrend::Mean | Detrend::Line => detrend_map(z, nx, ny, params.detrend),
        Detrend::Polynomial => remove_polynomial_map(z, nx, ny, params.form_degree)?,
        Detrend::Circle => {
            return Ok(Some(
                remove_cylinder(z, nx, ny, dx, dy, params.form_radius)?.radius,
            ))
        }
    }
    Ok(None)
}

/// The windows, S-filter, form removal and L-filter of a map.
pub fn map_chain(m: &AreaMap, params: &RoughnessParams) -> Result<Chained> {
    let w = m.windowed(params.window, params.window_y)?;
    let (mut nx, mut ny, mut z) = (w.nx, w.ny, w.z);
    enough_measured(&m.source, &z, "in the evaluation window")?;
    let scale = largest_magnitude(&z);
    if let Some(ls) = params.short_cutoff {
        let mut s = mean_surface(&z, nx, ny, m.dx, m.dy, &short_filter(ls)?)?;
        keep_gaps(&mut s, &z);
        z = s;
    }
    let form_radius = map_form(&mut z, (nx, ny), (m.dx, m.dy), params)?;
    let mut robust = None;
    if let Some(f) = &params.filter {
        let lx = (nx - 1) as f64 * m.dx;
        let ly = (ny - 1) as f64 * m.dy;
        if lx.min(ly) < f.cutoff {
            return Err(Error::NotApplicable(format!(
                "{}: map of {lx:.6e} × {ly:.6e} m is smaller than the cut-off λc = {:.6e} m",
                m.source, f.cutoff
            )));
        }
        let mean = match params.filter_kind {
            FilterKind::Gaussian => mean_surface(&z, nx, ny, m.dx, m.dy, f)?,
            FilterKind::Robust => {
                let (s, run) = robust_mean_surface(&z, nx, ny, m.dx, m.dy, f)?;
                robust = Some(run);
                s
            }
            FilterKind::ValleySuppression => valley_mean_surface(&z, nx, ny, m.dx, m.dy, f)?,
        };
        let (drop_x, drop_y) = (f.discard_count(m.dx), f.discard_count(m.dy));
        let (nx2, ny2) = (nx.saturating_sub(2 * drop_x), ny.saturating_sub(2 * drop_y));
        if nx2 < MIN_POINTS || ny2 < MIN_POINTS {
            return Err(Error::NotApplicable(format!(
                "{}: {nx2} × {ny2} points remain after discarding λc/2 at each edge; \
                 at least {MIN_POINTS} per side are needed",
                m.source
            )));
        }
        let mut r = Vec::with_capacity(nx2 * ny2);
        for row in drop_y..drop_y + ny2 {
            for c in drop_x..drop_x + nx2 {
                r.push(z[row * nx + c] - mean[row * nx + c]);
            }
        }
        enough_measured(&m.source, &r, "after the filter")?;
        (z, nx, ny) = (r, nx2, ny2);
    }
    Ok(Chained {
        z,
        nx,
        ny,
        dx: m.dx,
        dy: m.dy,
        scale,
        form_radius,
        robust,
    })
}
