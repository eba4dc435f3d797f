//! The cross-section of a wear track on a profile measured across it
//! (MODELS.md §9, "Wear from a track profile").
//!
//! # Model
//! With the profile z(x) across the track:
//! 1. the reference line r(x) = a + b x is the least-squares line of the
//!    unworn surface on both sides of the track: every point outside the
//!    track widened by `margin` × its width on each side (so that material
//!    piled up at the edges is not taken as the surface). The track and the
//!    line depend on each other; starting from the line through all points,
//!    the two are refined until the track's edges no longer move (at most
//!    [`MAX_ROUNDS`] rounds);
//! 2. the residual is e(x) = z(x) − r(x), and its moving average ē over
//!    `smoothing_fraction` of the profile (so that roughness inside the
//!    track does not end it early); the reference band is ±`band_factor` ×
//!    RMS(ē) over the reference points (or a band given);
//! 3. the edges, when not given, are where the profile leaves the band:
//!    from the deepest point of ē, the nearest points on each side with
//!    ē ≥ −band;
//! 4. the track cross-section is the area between the reference line and
//!    the profile below it, between the edges:
//!    A = ∫ max(0, −e(x)) dx on the measured (unsmoothed) profile,
//!    integrated exactly on the piecewise-linear profile (trapezoids, split
//!    where e crosses zero), so material piled above the line inside the
//!    track does not cancel worn area.
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
    /// Width beyond each edge, as a fraction of the track width, left out
    /// of the reference line's fit (pile-up); in [0, 5]. Default 0.5.
    pub margin: f64,
    /// Moving-average window for finding the edges, as a fraction of the
    /// profile's points; in [0, 0.1] (0: no smoothing). Default 0.005.
    pub smoothing_fraction: f64,
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
            margin: 0.5,
            smoothing_fraction: 0.005,
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
        let m = self.margin;
        if !(0.0..=5.0).contains(&m) {
            return Err(Error::Config(format!(
                "margin = {m}; expected 0 ≤ value ≤ 5 (track widths left out beyond each edge)"
            )));
        }
        let f = self.smoothing_fraction;
        if !(0.0..=0.1).contains(&f) {
            return Err(Error::Config(format!(
                "smoothing_fraction = {f}; expected 0 ≤ value ≤ 0.1"
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
    /// Points the reference line was fitted on.
    pub reference_points: usize,
}

/// Most rounds of refining the reference line and the edges together.
pub const MAX_ROUNDS: usize = 8;

/// Least-squares line (intercept, slope) through the points of `idx`.
pub fn fit_line(x: &[f64], z: &[f64], idx: impl Iterator<Item = usize> + Clone) -> (f64, f64) {
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

/// Centred moving average over `w` points (odd; shorter at the ends).
pub fn moving_average(e: &[f64], w: usize) -> Vec<f64> {
    let h = w / 2;
    let mut prefix = Vec::with_capacity(e.len() + 1);
    prefix.push(0.0);
    for v in e {
        prefix.push(prefix[prefix.len() - 1] + v);
    }
    (0..e.len())
        .map(|i| {
            let (lo, hi) = (i.saturating_sub(h), (i + h + 1).min(e.len()));
            (prefix[hi] - prefix[lo]) / (hi - lo) as f64
        })
        .collect()
}

/// From the deepest point, the nearest points on each side back inside
/// the band (s ≥ −band); the profile's ends when it never comes back.
fn find_edges(s: &[f64], band: f64) -> (usize, usize) {
    let deepest = s
        .iter()
        .enumerate()
        .fold(0, |m, (i, &v)| if v < s[m] { i } else { m });
    let left = s[..deepest].iter().rposition(|&v| v >= -band).unwrap_or(0);
    let right = s[deepest..]
        .iter()
        .position(|&v| v >= -band)
        .map_or(s.len() - 1, |k| deepest + k);
    (left, right)
}

/// One round: the line through the points outside `excluded`, its
/// residual, the band and the edges (indices).
struct Round {
    line: (f64, f64),
    e: Vec<f64>,
    band: f64,
    edges: (usize, usize),
    deepest: f64,
}

fn round(x: &[f64], z: &[f64], excluded: (usize, usize), p: &TrackParams, w: usize) -> Round {
    let outside = |i: &usize| *i < excluded.0 || *i > excluded.1;
    let refs = (0..x.len()).filter(outside);
    let line = fit_line(x, z, refs.clone());
    let e: Vec<f64> = x
        .iter()
        .zip(z)
        .map(|(&xi, &zi)| zi - (line.0 + line.1 * xi))
        .collect();
    let s = moving_average(&e, w);
    let count = refs.clone().count() as f64;
    let rms = (refs.map(|i| s[i] * s[i]).sum::<f64>() / count).sqrt();
    let band = p.band.unwrap_or(p.band_factor * rms);
    let edges = match p.edges {
        Some((a, b)) => (
            x.partition_point(|&v| v < a),
            x.partition_point(|&v| v <= b).saturating_sub(1),
        ),
        None => find_edges(&s, band),
    };
    let deepest = s.iter().fold(0.0_f64, |m, &v| m.min(v));
    Round {
        line,
        e,
        band,
        edges,
        deepest,
    }
}

/// The cross-section of the track on profile `x` (m, increasing), `z` (m).
///
/// Errors: [`Error::Config`] for invalid parameters, [`Error::NotApplicable`]
/// for given edges outside the profile, when no point lies below the reference
/// band (no track), or when the track and its margins leave less than a
/// tenth of the profile as unworn reference.
pub fn track_section(source: &str, x: &[f64], z: &[f64], p: &TrackParams) -> Result<TrackSection> {
    p.validate()?;
    let n = x.len();
    if let Some((a, b)) = p.edges {
        let inside = x.iter().filter(|&&v| v >= a && v <= b).count();
        if a < x[0] || b > x[n - 1] || inside < 2 {
            return Err(Error::NotApplicable(format!(
                "{source}: track edges [{a:.6e}, {b:.6e}] m hold {inside} points of the \
                 profile [{:.6e}, {:.6e}] m; expected edges inside it, around the track",
                x[0],
                x[n - 1]
            )));
        }
    }
    let w = 2 * ((n as f64 * p.smoothing_fraction / 2.0) as usize) + 1;
    let min_refs = (n / 10).max(3);
    // No point is excluded at first: the line through the whole profile.
    let mut excluded = (n, n);
    let mut r = round(x, z, excluded, p, w);
    for _ in 0..MAX_ROUNDS {
        if p.edges.is_none() && r.deepest >= -r.band {
            return Err(Error::NotApplicable(format!(
                "{source}: no point lies deeper than the reference band ±{:.3e} m below \
                 the reference line: no wear track found (give its edges, or a band)",
                r.band
            )));
        }
        let (l, rt) = r.edges;
        let pad = (p.margin * (rt - l) as f64).ceil() as usize;
        let next = (l.saturating_sub(pad), (rt + pad).min(n - 1));
        if n - (next.1 - next.0 + 1) < min_refs {
            return Err(Error::NotApplicable(format!(
                "{source}: the track ({:.6e} to {:.6e} m) and its margins leave fewer than \
                 {min_refs} points of unworn surface for the reference line; give the \
                 edges or a smaller margin",
                x[l], x[rt]
            )));
        }
        if next == excluded {
            break;
        }
        excluded = next;
        r = round(x, z, excluded, p, w);
    }
    let (l, rt) = r.edges;
    let edges = p.edges.unwrap_or((x[l], x[rt]));
    let depth = x
        .iter()
        .zip(&r.e)
        .filter(|(&xi, _)| xi >= edges.0 && xi <= edges.1)
        .fold(0.0_f64, |d, (_, &v)| d.max(-v));
    Ok(TrackSection {
        area: area_below(x, &r.e, edges.0, edges.1),
        depth,
        edges,
        edges_found: p.edges.is_none(),
        band: r.band,
        line: r.line,
        reference_points: n - (excluded.1 - excluded.0 + 1),
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
    fn moving_average_by_hand() {
        let s = moving_average(&[0.0, 3.0, 6.0, 0.0, 3.0], 3);
        let want = [1.5, 3.0, 3.0, 3.0, 1.5];
        assert!(
            s.iter().zip(want).all(|(a, b)| (a - b).abs() < 1e-15),
            "{s:?}"
        );
    }

    #[test]
    fn flat_profile_has_no_track() {
        let x: Vec<f64> = (0..100).map(|i| i as f64).collect();
        let z: Vec<f64> = x.iter().map(|v| 1e-3 * (v * 0.7).sin()).collect();
        let e = track_section("p", &x, &z, &TrackParams::default()).unwrap_err();
        assert!(e.to_string().contains("no wear track"), "{e}");
    }
}
