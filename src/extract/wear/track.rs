//! The cross-section of a wear track on a profile measured across it
//! (MODELS.md §9, "Wear from a track profile").
//!
//! # Model
//! With the profile z(x) across the track:
//! 1. the reference line r(x) = a + b x is the least-squares line of the
//!    unworn surface: the outer `reference_fraction` of the profile at each
//!    end (both sides of the track);
//! 2. the residual is e(x) = z(x) − r(x); the reference band is
//!    ±`band_factor` × RMS(e) over the reference points (or a band given);
//! 3. the edges, when not given, are where the profile leaves the band: from
//!    the deepest point of e, the nearest points on each side with
//!    e ≥ −band;
//! 4. the track cross-section is the area between the reference line and
//!    the profile below it, between the edges:
//!    A = ∫ max(0, −e(x)) dx, integrated exactly on the piecewise-linear
//!    profile (trapezoids, split where e crosses zero), so material piled
//!    above the line inside the track does not cancel worn area.
//!
//! | symbol | field | unit |
//! |---|---|---|
//! | A | [`TrackSection::area`] | m² |
//! | max(−e) | [`TrackSection::depth`] | m |
//! | x_l, x_r | [`TrackSection::edges`] | m |
//!
//! Wear volume and specific wear rate are in [`super::volume`].

use crate::error::{Error, Result};

/// How the track and its reference are found.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct TrackParams {
    /// Fraction of the profile at each end that is unworn surface, on which
    /// the reference line is fitted; in (0, 0.45]. Default 0.2.
    pub reference_fraction: f64,
    /// Half-width of the reference band in RMS deviations of the reference
    /// points from their line, > 0. Default 3.
    pub band_factor: f64,
    /// Half-width of the band (m), instead of `band_factor` × RMS.
    pub band: Option<f64>,
    /// Track edges (m) given by the user, instead of found.
    pub edges: Option<(f64, f64)>,
}

impl Default for TrackParams {
    fn default() -> Self {
        TrackParams {
            reference_fraction: 0.2,
            band_factor: 3.0,
            band: None,
            edges: None,
        }
    }
}

impl TrackParams {
    /// The same parameters with a band half-width given (m).
    pub fn with_band(self, band: f64) -> Self {
        TrackParams {
            band: Some(band),
            ..self
        }
    }

    /// Checks every field's range.
    pub fn validate(&self) -> Result<()> {
        let f = self.reference_fraction;
        if !(f > 0.0 && f <= 0.45) {
            return Err(Error::Config(format!(
                "reference_fraction = {f}; expected 0 < value ≤ 0.45 (the unworn part at each end)"
            )));
        }
        if !(self.band_factor.is_finite() && self.band_factor > 0.0) {
            return Err(Error::Config(format!(
                "band_factor = {}; expected a finite value > 0",
                self.band_factor
            )));
        }
        if let Some(b) = self.band {
            if !(b.is_finite() && b > 0.0) {
                return Err(Error::Config(format!("band = {b} m; expected > 0")));
            }
        }
        if let Some((a, b)) = self.edges {
            if !(a.is_finite() && b.is_finite() && b > a) {
                return Err(Error::Config(format!(
                    "track edges [{a}, {b}] m; expected finite left < right"
                )));
            }
        }
        Ok(())
    }
}

/// The measured cross-section of one track.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TrackSection {
    /// A, area between the reference line and the profile below it (m²).
    pub area: f64,
    /// Largest depth below the reference line between the edges (m).
    pub depth: f64,
    /// Left and right edge (m).
    pub edges: (f64, f64),
    /// Whether the edges were found (true) or given (false).
    pub edges_found: bool,
    /// Half-width of the reference band (m).
    pub band: f64,
    /// Reference line z = intercept + slope · x (m, dimensionless).
    pub line: (f64, f64),
}

/// Least-squares line (intercept, slope) through the points of `idx`.
fn fit_line(x: &[f64], z: &[f64], idx: impl Iterator<Item = usize> + Clone) -> (f64, f64) {
    let n = idx.clone().count() as f64;
    let mx = idx.clone().map(|i| x[i]).sum::<f64>() / n;
    let mz = idx.clone().map(|i| z[i]).sum::<f64>() / n;
    let (mut sxz, mut sxx) = (0.0, 0.0);
    for i in idx {
        sxz += (x[i] - mx) * (z[i] - mz);
        sxx += (x[i] - mx) * (x[i] - mx);
    }
    let slope = if sxx > 0.0 { sxz / sxx } else { 0.0 };
    (mz - slope * mx, slope)
}

/// Area of max(0, −e) between consecutive points, exact for e linear
/// between them (the part below zero of a trapezoid).
fn below_area(x0: f64, e0: f64, x1: f64, e1: f64) -> f64 {
    let (d0, d1) = (-e0, -e1);
    let h = x1 - x0;
    match (d0 > 0.0, d1 > 0.0) {
        (true, true) => 0.5 * (d0 + d1) * h,
        (false, false) => 0.0,
        // One end below: a triangle up to the crossing.
        (true, false) => 0.5 * d0 * h * d0 / (d0 - d1),
        (false, true) => 0.5 * d1 * h * d1 / (d1 - d0),
    }
}

/// ∫ max(0, −e) dx over [xl, xr] on the piecewise-linear profile.
pub fn area_below(x: &[f64], e: &[f64], xl: f64, xr: f64) -> f64 {
    let at = |k: usize, t: f64| {
        let w = (t - x[k]) / (x[k + 1] - x[k]);
        e[k] + w * (e[k + 1] - e[k])
    };
    let mut sum = 0.0;
    for k in 0..x.len() - 1 {
        let (a, b) = (x[k].max(xl), x[k + 1].min(xr));
        if b > a {
            sum += below_area(a, at(k, a), b, at(k, b));
        }
    }
    sum
}

/// From the deepest point, the nearest points on each side back inside
/// the band (e ≥ −band); the profile's ends when it never comes back.
fn find_edges(e: &[f64], band: f64) -> (usize, usize) {
    let deepest = e
        .iter()
        .enumerate()
        .fold(0, |m, (i, &v)| if v < e[m] { i } else { m });
    let left = e[..deepest].iter().rposition(|&v| v >= -band).unwrap_or(0);
    let right = e[deepest..]
        .iter()
        .position(|&v| v >= -band)
        .map_or(e.len() - 1, |k| deepest + k);
    (left, right)
}

/// The cross-section of the track on profile `x` (m, increasing), `z` (m).
///
/// Errors: [`Error::Config`] for invalid parameters or edges outside the
/// profile, [`Error::NotApplicable`] when no point lies below the reference
/// band (no track), or when the track reaches into the reference parts.
pub fn track_section(source: &str, x: &[f64], z: &[f64], p: &TrackParams) -> Result<TrackSection> {
    p.validate()?;
    let n = x.len();
    let m = ((n as f64 * p.reference_fraction).floor() as usize).max(2);
    if n < 2 * m + 3 {
        return Err(Error::NotApplicable(format!(
            "{source}: {n} points; too few for two reference parts of {m} and a track"
        )));
    }
    let refs = (0..m).chain(n - m..n);
    let line = fit_line(x, z, refs.clone());
    let e: Vec<f64> = x
        .iter()
        .zip(z)
        .map(|(&xi, &zi)| zi - (line.0 + line.1 * xi))
        .collect();
    let rms = (refs.clone().map(|i| e[i] * e[i]).sum::<f64>() / (2 * m) as f64).sqrt();
    let band = p.band.unwrap_or(p.band_factor * rms);
    let (edges, found) = match p.edges {
        Some((a, b)) => {
            if a < x[0] || b > x[n - 1] {
                return Err(Error::Config(format!(
                    "{source}: track edges [{a:.6e}, {b:.6e}] m outside the profile \
                     [{:.6e}, {:.6e}] m",
                    x[0],
                    x[n - 1]
                )));
            }
            ((a, b), false)
        }
        None => {
            let (l, r) = find_edges(&e, band);
            if e.iter().all(|&v| v >= -band) {
                return Err(Error::NotApplicable(format!(
                    "{source}: no point lies deeper than the reference band ±{band:.3e} m \
                     below the reference line: no wear track found (give its edges, or a \
                     narrower band)"
                )));
            }
            if l < m || r >= n - m {
                return Err(Error::NotApplicable(format!(
                    "{source}: the track found ({:.6e} to {:.6e} m) reaches into the outer \
                     {:.0} % used as unworn reference; give the edges or a smaller \
                     reference_fraction",
                    x[l],
                    x[r],
                    100.0 * p.reference_fraction
                )));
            }
            ((x[l], x[r]), true)
        }
    };
    let depth = x
        .iter()
        .zip(&e)
        .filter(|(&xi, _)| xi >= edges.0 && xi <= edges.1)
        .fold(0.0_f64, |d, (_, &v)| d.max(-v));
    Ok(TrackSection {
        area: area_below(x, &e, edges.0, edges.1),
        depth,
        edges,
        edges_found: found,
        band,
        line,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn area_below_is_exact_on_piecewise_linear_data() {
        // A V of depth 2 and width 4 between x = 1 and 5: area 4.
        let x = [0.0, 1.0, 3.0, 5.0, 6.0];
        let e = [0.0, 0.0, -2.0, 0.0, 0.0];
        assert!((area_below(&x, &e, 0.0, 6.0) - 4.0).abs() < 1e-15);
        // Half of it.
        assert!((area_below(&x, &e, 0.0, 3.0) - 2.0).abs() < 1e-15);
        // Crossing zero between points: e from −1 to +1 over [0, 2]
        // leaves a triangle of area 0.5 below.
        assert!((area_below(&[0.0, 2.0], &[-1.0, 1.0], 0.0, 2.0) - 0.5).abs() < 1e-15);
        assert!((area_below(&[0.0, 2.0], &[1.0, -1.0], 0.0, 2.0) - 0.5).abs() < 1e-15);
    }

    #[test]
    fn flat_profile_has_no_track() {
        let x: Vec<f64> = (0..100).map(|i| i as f64).collect();
        let z: Vec<f64> = x.iter().map(|v| 1e-3 * (v * 0.7).sin()).collect();
        let e = track_section("p", &x, &z, &TrackParams::default()).unwrap_err();
        assert!(e.to_string().contains("no wear track"), "{e}");
    }
}
