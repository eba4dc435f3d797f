//! The robust Gaussian regression filter of ISO 16610-31 (profiles) and
//! its zero-order areal form (maps), for stratified surfaces where deep
//! valleys would pull an ordinary Gaussian mean line down.
//!
//! # Profiles: second-order regression
//! At each x the mean line is the constant term of the local quadratic
//! fitted by weighted least squares, with weights s(u) δ_k, u = x_k − x:
//!
//! ```text
//! s(u) = exp(−π (u / (γ λc))²),  γ = √((−1 − W₋₁(−1/(2e))) / π) ≈ 0.7309
//! ```
//!
//! γ makes the transmission (1 + t) e^{−t}, t = π (γ λc / λ)², exactly 50 %
//! at λ = λc (the quadratic regression's own response; γ solves
//! (1 + t) e^{−t} = 1/2 for t = π γ²). The regression needs no end
//! correction: at the ends the local quadratic extrapolates the trend.
//!
//! The robust weights (Tukey's biweight) start at 1 and are, from the
//! residuals r_k = z_k − w_k of the previous mean line,
//! δ_k = (1 − (r_k / c_B)²)² for |r_k| < c_B, else 0, with
//! c_B = 4.4478 · median |r| (ISO 16610-31). The iteration stops when c_B
//! changes by less than 1e-4 of itself, or after [`MAX_ITERATIONS`].
//!
//! The sums Σ s δ u^p and Σ s δ z u^p (p ≤ 4 and ≤ 2) are convolutions of
//! δ and δ z with the kernels s(u) u^p, done by FFT: eight per iteration,
//! O(n log K).
//!
//! # Maps: zero-order
//! The mean surface is the normalised convolution Σ s δ z / Σ s δ with the
//! ISO 16610-21 weights (α = √(ln 2/π), separable), iterated with the same
//! robust weights: the robust areal Gaussian filter of ISO 16610-71 in its
//! zero-order form (a second-order areal regression needs 21 moment
//! convolutions per iteration).
//!
//! Points not measured (NaN) have δ = 0 and the rule of the Gaussian
//! filter: the mean line is defined where they carry at least half of the
//! in-range kernel weight.

use super::fft::convolve_same;
use super::gaussian_filter::{
    in_range_weight, kernel, separable, GaussianFilterParams, MIN_MEASURED_WEIGHT,
};
use crate::error::Result;

/// Most robust iterations.
pub const MAX_ITERATIONS: usize = 50;

/// c_B = this × median |residual| (ISO 16610-31).
pub const TUKEY_FACTOR: f64 = 4.4478;

/// γ of the second-order Gaussian regression filter: √(t/π) with t the
/// root of (1 + t) e^{−t} = 1/2, by Newton's method from t = 1.7.
pub fn gamma() -> f64 {
    let mut t: f64 = 1.7;
    for _ in 0..50 {
        let f = (1.0 + t) * (-t).exp() - 0.5;
        let df = -t * (-t).exp();
        t -= f / df;
    }
    (t / std::f64::consts::PI).sqrt()
}

/// How a robust filter ended.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RobustRun {
    /// Iterations made (the first, non-robust pass counts as one).
    pub iterations: usize,
    /// Whether c_B settled before [`MAX_ITERATIONS`].
    pub converged: bool,
}

/// The moment kernels w_p[j] = s(u) (u/λc)^p, u = (h − j) Δx (laid out for
/// [`convolve_same`], which multiplies tap j with sample i + h − j).
fn moment_kernels(dx: f64, cutoff: f64) -> Vec<Vec<f64>> {
    let gl = gamma() * cutoff;
    // ±2 λc: the weight beyond is below 1e-10 even times u⁴.
    let half = (2.0 * cutoff / dx).ceil() as isize;
    (0..5)
        .map(|p| {
            (0..=2 * half)
                .map(|j| {
                    let u = (half - j) as f64 * dx;
                    (-std::f64::consts::PI * (u / gl).powi(2)).exp() * (u / cutoff).powi(p)
                })
                .collect()
        })
        .collect()
}

/// The quadratic regression's constant term at every point for weights δ.
fn regression(z: &[f64], delta: &[f64], kernels: &[Vec<f64>]) -> Vec<f64> {
    let dz: Vec<f64> = z
        .iter()
        .zip(delta)
        .map(|(v, d)| if *d > 0.0 { v * d } else { 0.0 })
        .collect();
    let s: Vec<Vec<f64>> = kernels.iter().map(|k| convolve_same(delta, k)).collect();
    let t: Vec<Vec<f64>> = kernels[..3].iter().map(|k| convolve_same(&dz, k)).collect();
    (0..z.len())
        .map(|i| {
            let (s0, s1, s2, s3, s4) = (s[0][i], s[1][i], s[2][i], s[3][i], s[4][i]);
            let (t0, t1, t2) = (t[0][i], t[1][i], t[2][i]);
            // Cramer's rule for the constant term of [S0 S1 S2; S1 S2 S3;
            // S2 S3 S4] c = [T0 T1 T2].
            let det =
                s0 * (s2 * s4 - s3 * s3) - s1 * (s1 * s4 - s3 * s2) + s2 * (s1 * s3 - s2 * s2);
            let num =
                t0 * (s2 * s4 - s3 * s3) - s1 * (t1 * s4 - s3 * t2) + s2 * (t1 * s3 - s2 * t2);
            if det.abs() > 1e-12 * s0.powi(3) {
                num / det
            } else {
                f64::NAN
            }
        })
        .collect()
}

/// Tukey biweights of the residuals z − m, and c_B; NaN residuals weigh 0.
fn biweights(z: &[f64], m: &[f64]) -> (Vec<f64>, f64) {
    let mut abs: Vec<f64> = z
        .iter()
        .zip(m)
        .map(|(a, b)| (a - b).abs())
        .filter(|r| !r.is_nan())
        .collect();
    if abs.is_empty() {
        return (vec![0.0; z.len()], 0.0);
    }
    let mid = abs.len() / 2;
    let (_, med, _) = abs.select_nth_unstable_by(mid, f64::total_cmp);
    let cb = TUKEY_FACTOR * *med;
    let w = z
        .iter()
        .zip(m)
        .map(|(a, b)| {
            let r = (a - b) / cb;
            if r.abs() < 1.0 {
                (1.0 - r * r).powi(2)
            } else {
                0.0
            }
        })
        .collect();
    (w, cb)
}

/// Iterates `mean_of(δ)` with robust weights from the mask of `z`.
fn iterate(z: &[f64], mean_of: impl Fn(&[f64]) -> Vec<f64>) -> (Vec<f64>, RobustRun) {
    let mask: Vec<f64> = z.iter().map(|v| f64::from(u8::from(!v.is_nan()))).collect();
    let mut m = mean_of(&mask);
    let mut last_cb = f64::NAN;
    for it in 1..MAX_ITERATIONS {
        let (w, cb) = biweights(z, &m);
        if cb == 0.0 || (cb - last_cb).abs() <= 1e-4 * cb {
            return (
                m,
                RobustRun {
                    iterations: it,
                    converged: true,
                },
            );
        }
        last_cb = cb;
        let delta: Vec<f64> = w.iter().zip(&mask).map(|(a, b)| a * b).collect();
        m = mean_of(&delta);
    }
    (
        m,
        RobustRun {
            iterations: MAX_ITERATIONS,
            converged: false,
        },
    )
}

/// The robust second-order Gaussian regression mean line of a profile
/// (ISO 16610-31), spacing `dx`, cut-off `params.cutoff`.
pub fn robust_mean_line(
    z: &[f64],
    dx: f64,
    params: &GaussianFilterParams,
) -> Result<(Vec<f64>, RobustRun)> {
    params.validate()?;
    let kernels = moment_kernels(dx, params.cutoff);
    let full = in_range_weight(z.len(), &kernels[0]);
    let mask: Vec<f64> = z.iter().map(|v| f64::from(u8::from(!v.is_nan()))).collect();
    let measured = convolve_same(&mask, &kernels[0]);
    let (mut m, run) = iterate(z, |delta| regression(z, delta, &kernels));
    // Where the measured weight is below half the in-range weight the mean
    // line is not defined (the rule of points not measured).
    for ((v, a), f) in m.iter_mut().zip(&measured).zip(&full) {
        if *a < MIN_MEASURED_WEIGHT * f {
            *v = f64::NAN;
        }
    }
    Ok((m, run))
}

/// The robust zero-order Gaussian mean surface of a row-major `ny × nx`
/// map (see the module documentation).
pub fn robust_mean_surface(
    z: &[f64],
    nx: usize,
    ny: usize,
    dx: f64,
    dy: f64,
    params: &GaussianFilterParams,
) -> Result<(Vec<f64>, RobustRun)> {
    params.validate()?;
    let (wx, wy) = (kernel(params, dx), kernel(params, dy));
    let (fx, fy) = (in_range_weight(nx, &wx), in_range_weight(ny, &wy));
    let full: Vec<f64> = fy
        .iter()
        .flat_map(|b| fx.iter().map(move |a| a * b))
        .collect();
    let mean_of = |delta: &[f64]| -> Vec<f64> {
        let dz: Vec<f64> = z
            .iter()
            .zip(delta)
            .map(|(v, d)| if *d > 0.0 { v * d } else { 0.0 })
            .collect();
        let (num, den) = rayon::join(
            || separable(&dz, nx, ny, &wx, &wy),
            || separable(delta, nx, ny, &wx, &wy),
        );
        num.iter()
            .zip(&den)
            .map(|(a, b)| if *b > 0.0 { a / b } else { f64::NAN })
            .collect()
    };
    let (mut m, run) = iterate(z, mean_of);
    // The measured-weight rule, on the mask alone.
    let mask: Vec<f64> = z.iter().map(|v| f64::from(u8::from(!v.is_nan()))).collect();
    let measured = separable(&mask, nx, ny, &wx, &wy);
    for ((v, a), f) in m.iter_mut().zip(&measured).zip(&full) {
        if *a < MIN_MEASURED_WEIGHT * f {
            *v = f64::NAN;
        }
    }
    Ok((m, run))
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    #[test]
    fn gamma_gives_half_transmission_at_the_cutoff() {
        let t = PI * gamma() * gamma();
        assert!(((1.0 + t) * (-t).exp() - 0.5).abs() < 1e-15);
        assert!((gamma() - 0.7309).abs() < 1e-4);
    }

    #[test]
    fn transmission_of_the_regression_is_half_at_the_cutoff_and_ends_keep_a_parabola() {
        // A sine of wavelength λc: the second-order regression passes half
        // of it into the mean line (without robust weighting, which a pure
        // sine leaves almost uniform: c_B = 4.4 median|r| ≫ amplitude).
        let (lc, dx) = (0.25e-3, 0.5e-6);
        let n = 10 * (lc / dx) as usize;
        let z: Vec<f64> = (0..n)
            .map(|i| (2.0 * PI * i as f64 * dx / lc).sin())
            .collect();
        let kernels = moment_kernels(dx, lc);
        let ones = vec![1.0; n];
        let m = regression(&z, &ones, &kernels);
        let skip = 3 * (lc / dx) as usize;
        let amp = m[skip..n - skip].iter().fold(0.0f64, |a, v| a.max(v.abs()));
        // 500 samples per wavelength: the sampled crest is within (π/500)²
        // of the peak; kernel truncation at 2λc: < 1e-9. Tolerance 1e-4.
        assert!((amp - 0.5).abs() < 1e-4, "{amp}");
        // A parabola is its own mean line everywhere, ends included: the
        // point of a regression filter.
        let p: Vec<f64> = (0..n)
            .map(|i| {
                let x = i as f64 * dx / lc;
                1.0 - 0.3 * x + 0.05 * x * x
            })
            .collect();
        let m = regression(&p, &ones, &kernels);
        for (a, b) in m.iter().zip(&p) {
            assert!((a - b).abs() < 1e-9, "{a} vs {b}");
        }
    }

    #[test]
    fn deep_valleys_do_not_pull_the_robust_mean_line_down() {
        // A plateau at 0 with rare deep scratches (−5 µm, 2 % of the
        // points): the Gaussian mean line sinks by about 0.1 µm, the robust
        // one stays within 1 % of that of the plateau.
        let (lc, dx) = (0.25e-3, 1e-6);
        let n = 4000;
        let z: Vec<f64> = (0..n)
            .map(|i| {
                let base = 0.05e-6 * ((i as f64 * 0.37).sin());
                if i % 50 < 1 {
                    -5e-6
                } else {
                    base
                }
            })
            .collect();
        let p = GaussianFilterParams::new(lc).unwrap();
        let plain = super::super::gaussian_filter::mean_line(&z, dx, &p).unwrap();
        let (robust, run) = robust_mean_line(&z, dx, &p).unwrap();
        assert!(run.converged, "{run:?}");
        let mid = n / 2;
        assert!(plain[mid] < -0.08e-6, "{}", plain[mid]);
        assert!(robust[mid].abs() < 0.01e-6, "{}", robust[mid]);
        let (surf, run) = robust_mean_surface(&z[..40 * 100], 100, 40, dx, dx, &p).unwrap();
        assert!(run.converged);
        assert!(
            surf[20 * 100 + 50].abs() < 0.01e-6,
            "{}",
            surf[20 * 100 + 50]
        );
    }
}
