//! Power spectral density of profiles and maps (MODELS.md §10; Jacobs,
//! Junge and Pastewka, Surf. Topogr. Metrol. Prop. 5, 013001, 2017, the
//! conventions of SurfaceTopography).
//!
//! | quantity | definition |
//! |---|---|
//! | profile | C1D(q_k) = (Δx²/L) · abs(Σ w_i h_i e^{−i q_k x_i})², q_k = 2πk/L, L = nΔx, k = 1 … n/2 − 1 |
//! | map | C2D(q) = (ΔxΔy)²/(L_x L_y) · abs(Σ w h e^{−i q·r})², radially averaged over abs(q) |
//! | normalisation | Rq² = (1/π) ∫₀^∞ C1D dq, Sq² = (1/2π) ∫₀^∞ q C2D dq (exact with no window, by Parseval) |
//! | window | periodic Hann along x for profiles, the radial Hann w(r) = (1 + cos(π r/r_max))/2, r_max = min(L_x, L_y)/2 about the grid point (n_x/2, n_y/2), for maps; normalised to mean(w²) = 1; none for a surface stated periodic |
//!
//! The spectrum is averaged in log-spaced bins, as SurfaceTopography's
//! `power_spectrum_from_profile` / `_from_area` do by default: bin edges
//! 10^linspace(log10 q_min − 0.01, log10 q_max + 0.01, m), m = ⌈(log10
//! q_max − log10 q_min + 1) · 10⌉, q_min = 2π/L (the smaller of the two
//! for maps), q_max = π/Δx (π/max(Δx, Δy)); a value at q belongs to the
//! bin whose upper edge is the first ≥ q; each bin reports the mean q and
//! the mean C of its values; empty bins are left out.
//!
//! Points not measured are set to zero (the mean line) before the window
//! and the spectrum scaled by n/n_measured, so that a random gap pattern
//! keeps the normalisation; the caller says so with a status.

use rayon::prelude::*;
use std::f64::consts::PI;

use crate::signal::dft::Plan;
use crate::signal::fft2::rfft2;

/// Log-spaced bins per decade.
pub const BINS_PER_DECADE: usize = 10;

/// A binned spectrum: wavevector q (rad/m) and C (m³ for profiles, m⁴ for
/// maps) at each non-empty bin, q increasing.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Spectrum {
    /// Mean wavevector of the bin (rad/m).
    pub q: Vec<f64>,
    /// Mean PSD of the bin.
    pub c: Vec<f64>,
    /// Whether a window was applied (Hann) or not (periodic surface).
    pub windowed: bool,
}

/// Heights with the points not measured set to 0, and the factor
/// n / n_measured that restores the spectrum's scale.
fn zero_filled(z: &[f64]) -> (Vec<f64>, f64) {
    let measured = z.iter().filter(|v| !v.is_nan()).count().max(1);
    let filled = z
        .iter()
        .map(|&v| if v.is_nan() { 0.0 } else { v })
        .collect();
    (filled, z.len() as f64 / measured as f64)
}

/// Periodic Hann window of n points normalised to mean(w²) = 1 (scipy's
/// `get_window("hann", n)`, SurfaceTopography's normalisation).
fn hann(n: usize) -> Vec<f64> {
    let w: Vec<f64> = (0..n)
        .map(|i| 0.5 - 0.5 * (2.0 * PI * i as f64 / n as f64).cos())
        .collect();
    let norm = (n as f64 / w.iter().map(|v| v * v).sum::<f64>()).sqrt();
    w.into_iter().map(|v| v * norm).collect()
}

/// The radial Hann window of a map (see the module table), row-major.
fn radial_hann(nx: usize, ny: usize, dx: f64, dy: f64) -> Vec<f64> {
    let rmax = (nx as f64 * dx).min(ny as f64 * dy) / 2.0;
    let (cx, cy) = ((nx / 2) as f64, (ny / 2) as f64);
    let mut w: Vec<f64> = (0..ny)
        .flat_map(|r| {
            (0..nx).map(move |c| {
                let rr = ((dx * (c as f64 - cx)).powi(2) + (dy * (r as f64 - cy)).powi(2)).sqrt();
                if rr > rmax {
                    0.0
                } else {
                    0.5 + 0.5 * (PI * rr / rmax).cos()
                }
            })
        })
        .collect();
    let norm = ((nx * ny) as f64 / w.iter().map(|v| v * v).sum::<f64>()).sqrt();
    w.iter_mut().for_each(|v| *v *= norm);
    w
}

/// Values (q, C, weight) averaged into the log bins between `qmin` and
/// `qmax` (see the module documentation).
fn log_binned(values: &[(f64, f64, f64)], qmin: f64, qmax: f64) -> (Vec<f64>, Vec<f64>) {
    let (lo, hi) = (qmin.log10() - 0.01, qmax.log10() + 0.01);
    let m = (((qmax.log10() - qmin.log10() + 1.0) * BINS_PER_DECADE as f64).ceil() as usize).max(2);
    let edges: Vec<f64> = (0..m)
        .map(|i| 10f64.powf(lo + (hi - lo) * i as f64 / (m - 1) as f64))
        .collect();
    let mut sums = vec![(0.0, 0.0, 0.0); m + 1];
    for &(q, c, w) in values {
        let b = edges.partition_point(|&e| e < q);
        let s = &mut sums[b];
        *s = (s.0 + w * q, s.1 + w * c, s.2 + w);
    }
    sums[1..m]
        .iter()
        .filter(|s| s.2 > 0.0)
        .map(|s| (s.0 / s.2, s.1 / s.2))
        .unzip()
}

/// The 1-D PSD of an equally spaced profile, binned; a Hann window unless
/// `periodic`.
pub fn profile_psd(z: &[f64], dx: f64, periodic: bool) -> Spectrum {
    let values = profile_values(z, dx, periodic);
    let (q, c) = log_binned(&values, 2.0 * PI / (z.len() as f64 * dx), PI / dx);
    Spectrum {
        q,
        c,
        windowed: !periodic,
    }
}

/// (q_k, C1D(q_k), 1) for k = 1 … n/2 − 1.
fn profile_values(z: &[f64], dx: f64, periodic: bool) -> Vec<(f64, f64, f64)> {
    let n = z.len();
    let (h, scale) = zero_filled(z);
    let w = (!periodic).then(|| hann(n));
    let mut buf: Vec<(f64, f64)> = h
        .iter()
        .enumerate()
        .map(|(i, &v)| (v * w.as_ref().map_or(1.0, |w| w[i]), 0.0))
        .collect();
    Plan::new(n).forward(&mut buf);
    let l = n as f64 * dx;
    let dq = 2.0 * PI / l;
    (1..n / 2)
        .map(|k| {
            let f = buf[k];
            (
                k as f64 * dq,
                dx * dx * (f.0 * f.0 + f.1 * f.1) / l * scale,
                1.0,
            )
        })
        .collect()
}

/// The radially averaged 2-D PSD of a row-major `ny × nx` map, binned; the
/// radial Hann window unless `periodic`.
pub fn map_psd(z: &[f64], nx: usize, ny: usize, dx: f64, dy: f64, periodic: bool) -> Spectrum {
    let values = map_values(z, nx, ny, dx, dy, periodic);
    let (sx, sy) = (nx as f64 * dx, ny as f64 * dy);
    let qmin = (2.0 * PI / sx).min(2.0 * PI / sy);
    let qmax = PI / dx.max(dy);
    let (q, c) = log_binned(&values, qmin, qmax);
    Spectrum {
        q,
        c,
        windowed: !periodic,
    }
}

/// (|q|, C2D, weight) of every kept entry of the half spectrum.
fn map_values(
    z: &[f64],
    nx: usize,
    ny: usize,
    dx: f64,
    dy: f64,
    periodic: bool,
) -> Vec<(f64, f64, f64)> {
    let (mut h, scale) = zero_filled(z);
    if !periodic {
        let w = radial_hann(nx, ny, dx, dy);
        h.par_iter_mut().zip(&w).for_each(|(v, w)| *v *= w);
    }
    let spec = rfft2(&h, nx, ny, ny, nx);
    let (sx, sy) = (nx as f64 * dx, ny as f64 * dy);
    let norm = (dx * dy).powi(2) / (sx * sy) * scale;
    let half = spec.half();
    // Each kept column 0 < kx < nx/2 stands for itself and its mirror
    // (−ky, −kx), whose value and radius are the same: weight 2.
    (0..half)
        .into_par_iter()
        .flat_map_iter(|kx| {
            let spec = &spec;
            let weight = if kx == 0 || 2 * kx == nx { 1.0 } else { 2.0 };
            let qx = 2.0 * PI * kx as f64 / sx;
            (0..ny).map(move |ky| {
                let fy = if ky <= ny / 2 { ky } else { ny - ky } as f64;
                let qy = 2.0 * PI * fy / sy;
                let f = spec.at(ky, kx);
                (
                    (qx * qx + qy * qy).sqrt(),
                    norm * (f.0 * f.0 + f.1 * f.1),
                    weight,
                )
            })
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn periodic_sine_puts_its_variance_in_one_wavevector() {
        // A sine of 16 whole periods over 1000 points (not a power of two),
        // no window: all of its power at k = 16, and by Parseval
        // (1/π) C Δq = Rq² = a²/2 with Δq = 2π/L.
        let (n, dx, a) = (1000usize, 1e-6, 2e-7);
        let z: Vec<f64> = (0..n)
            .map(|i| a * (2.0 * PI * 16.0 * i as f64 / n as f64).sin())
            .collect();
        let v = profile_values(&z, dx, true);
        let l = n as f64 * dx;
        let (k, peak) = v
            .iter()
            .enumerate()
            .max_by(|a, b| a.1 .1.total_cmp(&b.1 .1))
            .unwrap();
        assert_eq!(k + 1, 16);
        assert!((peak.0 - 2.0 * PI * 16.0 / l).abs() < 1e-9 * peak.0);
        let total: f64 = v.iter().map(|e| e.1).sum::<f64>() * (2.0 * PI / l) / PI;
        assert!((total - a * a / 2.0).abs() < 1e-12 * a * a, "{total}");
        assert!((peak.1 * 2.0 * PI / l / PI - a * a / 2.0).abs() < 1e-12 * a * a);
        // With the periodic Hann window the sine's line spreads to k = 15,
        // 16, 17 in the power ratio 1/16 : 1/4 : 1/16, and mean(w²) = 1
        // (that is, 3/8 before the normalisation) keeps the total: a²/2.
        let w = profile_values(&z, dx, false);
        let total: f64 = w.iter().map(|e| e.1).sum::<f64>() * (2.0 * PI / l) / PI;
        assert!((total - a * a / 2.0).abs() < 1e-12 * a * a, "{total}");
    }

    #[test]
    fn map_spectrum_holds_the_variance_with_mirror_weights() {
        // Parseval over the whole grid, no window: Σ C Δqx Δqy / (2π)² =
        // mean z² (z of zero mean: the DC entry is zero). The half spectrum
        // with mirror weights must give the same sum, for even and odd
        // sizes.
        for (nx, ny) in [(64usize, 32usize), (63, 17), (10, 11)] {
            let (dx, dy) = (1e-6, 2e-6);
            let mut z: Vec<f64> = (0..nx * ny)
                .map(|i| ((i * 7919 % 97) as f64 - 48.0) * 1e-9)
                .collect();
            let m = z.iter().sum::<f64>() / z.len() as f64;
            z.iter_mut().for_each(|v| *v -= m);
            let ms = z.iter().map(|v| v * v).sum::<f64>() / z.len() as f64;
            let (sx, sy) = (nx as f64 * dx, ny as f64 * dy);
            let sum: f64 = map_values(&z, nx, ny, dx, dy, true)
                .iter()
                .map(|(_, c, w)| c * w)
                .sum::<f64>()
                * (2.0 * PI / sx)
                * (2.0 * PI / sy)
                / (4.0 * PI * PI);
            assert!((sum - ms).abs() < 1e-12 * ms, "{nx}x{ny}: {sum} vs {ms}");
        }
    }
}
