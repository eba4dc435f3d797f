//! The Gaussian profile filter of ISO 16610-21 (formerly ISO 11562), which
//! separates roughness from waviness.
//!
//! # Model
//! The mean line is the profile convolved with the weighting function
//!
//! ```text
//! s(x) = 1/(α λc) · exp(−π (x / (α λc))²),   α = sqrt(ln 2 / π) ≈ 0.4697
//! ```
//!
//! whose transmission for a sine of wavelength λ is
//! `exp(−π (α λc / λ)²)`: exactly 50 % at λ = λc (the definition of the
//! cut-off). The roughness profile is the profile minus the mean line.
//!
//! | symbol | field | unit |
//! |---|---|---|
//! | λc | [`GaussianFilterParams::cutoff`] | m (same unit as the spacing) |
//! | c  | [`GaussianFilterParams::truncation`] | 1 (kernel spans ±c·λc) |
//! | Δx | spacing argument | m |
//!
//! # Discretisation and end effects
//! The weights are `s(j Δx) Δx` for |j Δx| ≤ c λc, normalised to sum to 1.
//! Near the ends the kernel runs off the data. This module renormalises the
//! weights over the samples that exist (zero-order end correction: the mean
//! line of a constant profile is that constant everywhere). The caller may
//! then discard λc/2 at each end, the run-up and run-out of ISO 4288
//! ([`FilterEnds::Discard`]), where even the renormalised line is biased for
//! a sloped or curved profile.
//!
//! The convolution is done by FFT (overlap–save, O(n log K) for a kernel of
//! K taps), see [`super::fft::convolve_same`].

use serde::Serialize;

use super::fft::convolve_same;
use crate::error::{Error, Result};

/// α = sqrt(ln 2 / π), the constant of the ISO 16610-21 Gaussian weighting
/// function (50 % transmission at the cut-off).
pub fn alpha() -> f64 {
    (std::f64::consts::LN_2 / std::f64::consts::PI).sqrt()
}

/// What to do with the ends of the filtered profile.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum FilterEnds {
    /// Keep every point; near the ends the mean line uses the renormalised
    /// kernel (zero-order end correction).
    Renormalize,
    /// Drop λc/2 at each end (ISO 4288 run-up and run-out). Default.
    Discard,
}

/// Parameters of the Gaussian profile filter.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct GaussianFilterParams {
    /// λc, the cut-off wavelength (m; same unit as the spacing). Valid: > 0
    /// and finite. Common values 0.08, 0.25, 0.8, 2.5, 8 mm. No default: the
    /// user chooses it.
    pub cutoff: f64,
    /// c, the kernel half-width as a multiple of λc. Default 1.0 (the weight
    /// lost by truncation is below 1e-6). Valid: 0.5 ≤ c ≤ 3.
    pub truncation: f64,
    /// End handling. Default [`FilterEnds::Discard`].
    pub ends: FilterEnds,
}

impl GaussianFilterParams {
    /// Validated parameters with the default truncation and ends.
    pub fn new(cutoff: f64) -> Result<Self> {
        let p = GaussianFilterParams {
            cutoff,
            truncation: 1.0,
            ends: FilterEnds::Discard,
        };
        p.validate()?;
        Ok(p)
    }

    /// Checks the ranges documented on the fields.
    pub fn validate(&self) -> Result<()> {
        if !(self.cutoff.is_finite() && self.cutoff > 0.0) {
            return Err(Error::Config(format!(
                "Gaussian filter cut-off λc = {} m; expected a finite value > 0",
                self.cutoff
            )));
        }
        if !(0.5..=3.0).contains(&self.truncation) {
            return Err(Error::Config(format!(
                "Gaussian filter truncation c = {}; expected 0.5 ≤ c ≤ 3",
                self.truncation
            )));
        }
        Ok(())
    }

    /// Number of samples dropped at each end with [`FilterEnds::Discard`]
    /// for spacing `dx`: round(λc / (2 Δx)).
    pub fn discard_count(&self, dx: f64) -> usize {
        match self.ends {
            FilterEnds::Renormalize => 0,
            FilterEnds::Discard => (self.cutoff / (2.0 * dx)).round() as usize,
        }
    }
}

/// The normalised discrete kernel `s(j Δx) Δx`, j = −K..=K, K = ⌈c λc / Δx⌉.
pub fn kernel(params: &GaussianFilterParams, dx: f64) -> Vec<f64> {
    let al = alpha() * params.cutoff;
    let half = (params.truncation * params.cutoff / dx).ceil() as usize;
    let mut w: Vec<f64> = (0..=2 * half)
        .map(|i| {
            let x = (i as f64 - half as f64) * dx / al;
            (-std::f64::consts::PI * x * x).exp()
        })
        .collect();
    let s: f64 = w.iter().sum();
    for v in &mut w {
        *v /= s;
    }
    w
}

/// Smallest share of the kernel's in-range weight (the weight on samples
/// that exist) that must fall on measured (non-NaN) samples for the mean
/// line there to be defined: one half.
pub const MIN_MEASURED_WEIGHT: f64 = 0.5;

/// The weight of kernel `w` (odd length, symmetric) that falls on samples
/// 0..n when centred on each sample: 1 in the interior, about one half at
/// the ends. Prefix sums of the kernel give it in O(1) per point.
pub fn in_range_weight(n: usize, w: &[f64]) -> Vec<f64> {
    let at = in_range(n, w);
    (0..n).map(at).collect()
}

/// The in-range weight at sample `i` (see [`in_range_weight`]).
fn in_range(n: usize, w: &[f64]) -> impl Fn(usize) -> f64 {
    let half = w.len() / 2;
    let mut prefix = Vec::with_capacity(w.len() + 1);
    prefix.push(0.0);
    for &v in w {
        prefix.push(prefix.last().copied().unwrap_or(0.0) + v);
    }
    move |i| {
        // Kernel tap j (0..2h) multiplies z[i + h − j]; valid j satisfy
        // 0 ≤ i + h − j < n.
        let j_lo = (i + half + 1).saturating_sub(n);
        let j_hi = (i + half).min(2 * half);
        prefix[j_hi + 1] - prefix[j_lo]
    }
}

/// The Gaussian mean line (waviness) of equally spaced heights `z` with
/// spacing `dx`, with renormalised weights at the ends. Same length as `z`.
///
/// NaN heights are points not measured: the mean line is then the
/// normalised convolution Σ w·z / Σ w over the measured samples under the
/// kernel (the same end correction, extended to gaps), and NaN where they
/// carry less than [`MIN_MEASURED_WEIGHT`] of the in-range weight.
pub fn mean_line(z: &[f64], dx: f64, params: &GaussianFilterParams) -> Result<Vec<f64>> {
    params.validate()?;
    if !(dx.is_finite() && dx > 0.0) {
        return Err(Error::Config(format!(
            "sample spacing {dx}; expected a finite value > 0"
        )));
    }
    let w = kernel(params, dx);
    if z.iter().any(|v| v.is_nan()) {
        let (num, den) = masked_sums(z, &w);
        let full = in_range_weight(z.len(), &w);
        return Ok(normalised(&num, &den, &full));
    }
    let mut m = convolve_same(z, &w);
    let half = w.len() / 2;
    let n = z.len();
    // Renormalise where the kernel runs off the data: divide by the weight
    // that fell on existing samples.
    let full = in_range(n, &w);
    for i in (0..half.min(n)).chain(n.saturating_sub(half).max(half.min(n))..n) {
        let wsum = full(i);
        if wsum > 0.0 {
            m[i] /= wsum;
        }
    }
    Ok(m)
}

/// Σ w·z over the measured samples (NaN read as 0) and Σ w over them.
fn masked_sums(z: &[f64], w: &[f64]) -> (Vec<f64>, Vec<f64>) {
    let zero: Vec<f64> = z
        .iter()
        .map(|&v| if v.is_nan() { 0.0 } else { v })
        .collect();
    let ones: Vec<f64> = z
        .iter()
        .map(|&v| f64::from(u8::from(!v.is_nan())))
        .collect();
    rayon::join(|| convolve_same(&zero, w), || convolve_same(&ones, w))
}

/// num / den where the measured weight `den` is at least
/// [`MIN_MEASURED_WEIGHT`] of the in-range weight `full`, else NaN.
fn normalised(num: &[f64], den: &[f64], full: &[f64]) -> Vec<f64> {
    num.iter()
        .zip(den)
        .zip(full)
        .map(
            |((&a, &b), &f)| match b >= MIN_MEASURED_WEIGHT * f && b > 0.0 {
                true => a / b,
                false => f64::NAN,
            },
        )
        .collect()
}

/// Roughness = profile − Gaussian mean line, with the ends handled as
/// `params.ends` says. Returns the roughness and the number of samples
/// dropped at the start (the same number is dropped at the end).
///
/// Errors: [`Error::NotApplicable`] when the profile is shorter than λc (too
/// short to separate roughness from waviness at that cut-off).
pub fn roughness(z: &[f64], dx: f64, params: &GaussianFilterParams) -> Result<(Vec<f64>, usize)> {
    let length = dx * (z.len().saturating_sub(1)) as f64;
    if length < params.cutoff {
        return Err(Error::NotApplicable(format!(
            "profile length {length:.6e} m is shorter than the cut-off λc = {:.6e} m; \
             choose a smaller λc or a longer profile",
            params.cutoff
        )));
    }
    let m = mean_line(z, dx, params)?;
    let drop = params.discard_count(dx);
    let keep = z.len().saturating_sub(2 * drop);
    let r: Vec<f64> = (drop..drop + keep).map(|i| z[i] - m[i]).collect();
    Ok((r, drop))
}

/// Separable areal Gaussian filter (ISO 16610-61 uses the same weighting in
/// x and y with one cut-off): the mean surface of a row-major `ny × nx`
/// height map. Same size as `z`. Points not measured (NaN) are handled as
/// in [`mean_line`]: the normalised convolution, separable like the
/// kernel, and NaN where the measured points carry less than
/// [`MIN_MEASURED_WEIGHT`] of the in-range weight.
pub fn mean_surface(
    z: &[f64],
    nx: usize,
    ny: usize,
    dx: f64,
    dy: f64,
    params: &GaussianFilterParams,
) -> Result<Vec<f64>> {
    if z.iter().any(|v| v.is_nan()) {
        return masked_mean_surface(z, nx, ny, dx, dy, params);
    }
    let mut rows = Vec::with_capacity(z.len());
    for r in z.chunks(nx) {
        rows.extend(mean_line(r, dx, params)?);
    }
    columns(&rows, nx, ny, |c| mean_line(c, dy, params))
}

/// Applies `f` to every column of a row-major map.
fn columns(
    z: &[f64],
    nx: usize,
    ny: usize,
    f: impl Fn(&[f64]) -> Result<Vec<f64>>,
) -> Result<Vec<f64>> {
    let mut col = vec![0.0; ny];
    let mut out = z.to_vec();
    for c in 0..nx {
        for (r, v) in col.iter_mut().enumerate() {
            *v = z[r * nx + c];
        }
        for (r, v) in f(&col)?.into_iter().enumerate() {
            out[r * nx + c] = v;
        }
    }
    Ok(out)
}

/// The separable convolution of a row-major map with `wx` along x and
/// `wy` along y (zeros outside).
pub(super) fn separable(x: &[f64], nx: usize, ny: usize, wx: &[f64], wy: &[f64]) -> Vec<f64> {
    let mut rows = Vec::with_capacity(x.len());
    for r in x.chunks(nx) {
        rows.extend(convolve_same(r, wx));
    }
    let mut col = vec![0.0; ny];
    let mut out = rows.clone();
    for c in 0..nx {
        for (r, v) in col.iter_mut().enumerate() {
            *v = rows[r * nx + c];
        }
        for (r, v) in convolve_same(&col, wy).into_iter().enumerate() {
            out[r * nx + c] = v;
        }
    }
    out
}

fn masked_mean_surface(
    z: &[f64],
    nx: usize,
    ny: usize,
    dx: f64,
    dy: f64,
    params: &GaussianFilterParams,
) -> Result<Vec<f64>> {
    params.validate()?;
    let (wx, wy) = (kernel(params, dx), kernel(params, dy));
    let zero: Vec<f64> = z
        .iter()
        .map(|&v| if v.is_nan() { 0.0 } else { v })
        .collect();
    let ones: Vec<f64> = z
        .iter()
        .map(|&v| f64::from(u8::from(!v.is_nan())))
        .collect();
    let (num, den) = rayon::join(
        || separable(&zero, nx, ny, &wx, &wy),
        || separable(&ones, nx, ny, &wx, &wy),
    );
    let (fx, fy) = (in_range_weight(nx, &wx), in_range_weight(ny, &wy));
    let full: Vec<f64> = fy
        .iter()
        .flat_map(|b| fx.iter().map(move |a| a * b))
        .collect();
    Ok(normalised(&num, &den, &full))
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    #[test]
    fn alpha_gives_half_transmission_at_cutoff_in_closed_form() {
        // exp(−π α²) = exp(−ln 2) = 1/2 exactly, up to round-off.
        assert!(((-PI * alpha() * alpha()).exp() - 0.5).abs() < 1e-15);
    }

    fn amplitude_in_interior(m: &[f64], skip: usize) -> f64 {
        m[skip..m.len() - skip]
            .iter()
            .fold(0.0_f64, |a, &v| a.max(v.abs()))
    }

    #[test]
    fn sine_at_cutoff_is_transmitted_at_fifty_percent() {
        // λ = λc = 0.8 mm sampled at 0.5 µm (1600 samples per wavelength),
        // 10 wavelengths long. The discrete kernel differs from the
        // continuous one by truncation (< 1e-6) and sampling (spectrally
        // negligible at 1600 samples per period); the interior peak of the
        // sampled mean line may miss the true crest by half a sample, a
        // relative error ≤ (π/1600)² / 2 ≈ 2e-6. Tolerance 1e-4.
        let lc = 0.8e-3;
        let dx = 0.5e-6;
        let n = 16_000;
        let z: Vec<f64> = (0..n)
            .map(|i| (2.0 * PI * i as f64 * dx / lc).sin())
            .collect();
        let p = GaussianFilterParams::new(lc).unwrap();
        let m = mean_line(&z, dx, &p).unwrap();
        let a = amplitude_in_interior(&m, (lc / dx) as usize * 2);
        assert!((a - 0.5).abs() < 1e-4, "transmission {a}");
        // And the roughness keeps the other half.
        let (r, drop) = roughness(&z, dx, &p).unwrap();
        assert_eq!(drop, 800);
        let ar = amplitude_in_interior(&r, (lc / dx) as usize * 2);
        assert!((ar - 0.5).abs() < 1e-4, "roughness amplitude {ar}");
    }

    #[test]
    fn transmission_follows_gaussian_law_off_cutoff() {
        // λ = 2 λc: transmission exp(−π α² / 4) = 2^(−1/4) ≈ 0.8409.
        let lc = 0.25e-3;
        let dx = 0.5e-6;
        let lam = 2.0 * lc;
        let n = 20 * (lam / dx) as usize;
        let z: Vec<f64> = (0..n)
            .map(|i| (2.0 * PI * i as f64 * dx / lam).sin())
            .collect();
        let p = GaussianFilterParams::new(lc).unwrap();
        let m = mean_line(&z, dx, &p).unwrap();
        let a = amplitude_in_interior(&m, (lam / dx) as usize * 2);
        let expect = 2f64.powf(-0.25);
        // Same error budget as the 50 % test.
        assert!((a - expect).abs() < 1e-4, "transmission {a} vs {expect}");
    }

    #[test]
    fn constant_profile_has_itself_as_mean_line_up_to_the_ends() {
        // Renormalisation at the ends: a constant stays constant everywhere.
        let z = vec![3.5; 4000];
        let p = GaussianFilterParams::new(0.25e-3).unwrap();
        let m = mean_line(&z, 1e-6, &p).unwrap();
        for v in m {
            // Sum of ~500 weights normalised: round-off ~1e-15 relative.
            assert!((v - 3.5).abs() < 1e-12);
        }
    }

    #[test]
    fn areal_filter_of_a_plane_wave_along_y_matches_the_profile_filter() {
        // z(x, y) = sin(2π y / λc): rows are constant, so only the y pass
        // acts and the transmission is 50 %.
        let lc = 0.1e-3;
        let d = 1e-6;
        let (nx, ny) = (8, 800);
        let z: Vec<f64> = (0..ny)
            .flat_map(|r| std::iter::repeat_n((2.0 * PI * r as f64 * d / lc).sin(), nx))
            .collect();
        let p = GaussianFilterParams::new(lc).unwrap();
        let m = mean_surface(&z, nx, ny, d, d, &p).unwrap();
        let col: Vec<f64> = (0..ny).map(|r| m[r * nx + 3]).collect();
        let a = amplitude_in_interior(&col, 200);
        // 100 samples per wavelength: the sampled crest may be off by half a
        // sample, relative error ≤ (π/100)²/2 ≈ 5e-4. Tolerance 1e-3.
        assert!((a - 0.5).abs() < 1e-3, "transmission {a}");
    }

    #[test]
    fn gaps_are_bridged_by_the_normalised_kernel_and_wide_ones_stay_gaps() {
        // A line z = a + b x is its own mean line in the interior (the
        // kernel is symmetric); with a short gap it still is, to round-off,
        // on both sides of the gap and across it.
        let dx = 1e-6;
        let p = GaussianFilterParams::new(50e-6).unwrap();
        let line: Vec<f64> = (0..2000).map(|i| 1e-6 + 1e-9 * i as f64).collect();
        let mut z = line.clone();
        z[1000..1010].fill(f64::NAN);
        let m = mean_line(&z, dx, &p).unwrap();
        for i in 200..1800 {
            // Values ~3e-6; the normalised convolution keeps a line exactly
            // where the measured weights are symmetric about the point, and
            // within the gap's asymmetry (≤ 10 samples × slope) elsewhere.
            assert!(
                (m[i] - line[i]).abs() < 1e-8,
                "{i}: {} vs {}",
                m[i],
                line[i]
            );
        }
        // A gap wider than the kernel: its middle has no measured weight.
        let mut z = line;
        z[500..700].fill(f64::NAN);
        let m = mean_line(&z, dx, &p).unwrap();
        assert!(m[600].is_nan() && !m[450].is_nan() && !m[750].is_nan());
        // Without gaps the ends always qualify (half the weight).
        let m = mean_line(&vec![2.0; 300], dx, &p).unwrap();
        assert!(m.iter().all(|v| (v - 2.0).abs() < 1e-12));
        // Maps: corners qualify, a masked block is bridged where it is small.
        let (nx, ny) = (120, 100);
        let mut z: Vec<f64> = (0..nx * ny).map(|i| 3.0 + 0.0 * i as f64).collect();
        for r in 40..44 {
            z[r * nx + 60..r * nx + 64].fill(f64::NAN);
        }
        let m = mean_surface(&z, nx, ny, dx, dx, &p).unwrap();
        assert!(m.iter().all(|v| (v - 3.0).abs() < 1e-12));
    }

    #[test]
    fn bad_parameters_are_rejected() {
        assert!(GaussianFilterParams::new(0.0).is_err());
        assert!(GaussianFilterParams::new(f64::NAN).is_err());
        let z = vec![0.0; 10];
        let p = GaussianFilterParams::new(1.0).unwrap();
        assert!(matches!(
            roughness(&z, 0.01, &p),
            Err(Error::NotApplicable(_))
        ));
    }
}
