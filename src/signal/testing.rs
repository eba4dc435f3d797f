//! Deterministic synthetic signals for tests and benchmarks.

use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution, Normal};

/// `n` samples of Gaussian noise with standard deviation `sigma`, from a
/// fixed seed.
pub fn gaussian_noise(n: usize, sigma: f64, seed: u64) -> Vec<f64> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let d = Normal::new(0.0, sigma.max(0.0)).expect("sigma >= 0");
    (0..n).map(|_| d.sample(&mut rng)).collect()
}

/// A periodic Gaussian random surface of `ny` rows × `nx` columns (row
/// major; both powers of two) with spacing `(dx, dy)`, zero mean, whose
/// expected 2-D power spectral density at each wavevector q of the grid is
/// `psd(qx, qy)` in m⁴, normalised as MODELS §10 and SurfaceTopography:
/// C(q) = (ΔxΔy)²/(LxLy) |Σ h e^{−iq·r}|². White noise (unit variance, so
/// E|W(q)|² = nx·ny) is filtered by √(psd / ΔxΔy) in Fourier space; the
/// filter is even in q, so the surface is real. The q = 0 term is dropped.
///
/// What follows from the generator's parameters alone, for the tests:
/// E[Sq²] = Σ_q psd(q) / (nx·ny·ΔxΔy), and the expected ACF
/// R(t) = Σ_q psd(q) cos(q·t) / (nx·ny·ΔxΔy).
pub fn random_surface(
    nx: usize,
    ny: usize,
    (dx, dy): (f64, f64),
    psd: impl Fn(f64, f64) -> f64,
    seed: u64,
) -> Vec<f64> {
    use super::fft::{fft, Complex};
    assert!(nx.is_power_of_two() && ny.is_power_of_two());
    let mut a: Vec<Complex> = gaussian_noise(nx * ny, 1.0, seed)
        .into_iter()
        .map(|v| (v, 0.0))
        .collect();
    let fft2 = |a: &mut Vec<Complex>, inverse: bool| {
        a.chunks_mut(nx).for_each(|row| fft(row, inverse));
        let mut col = vec![(0.0, 0.0); ny];
        for c in 0..nx {
            (0..ny).for_each(|r| col[r] = a[r * nx + c]);
            fft(&mut col, inverse);
            (0..ny).for_each(|r| a[r * nx + c] = col[r]);
        }
    };
    fft2(&mut a, false);
    for r in 0..ny {
        for c in 0..nx {
            let (qx, qy) = grid_wavevector(c, r, nx, ny, dx, dy);
            let g = if r == 0 && c == 0 {
                0.0
            } else {
                (psd(qx, qy) / (dx * dy)).sqrt()
            };
            let v = &mut a[r * nx + c];
            *v = (v.0 * g, v.1 * g);
        }
    }
    fft2(&mut a, true);
    a.into_iter().map(|v| v.0).collect()
}

/// The wavevector (rad/m) of column `c`, row `r` of an `ny × nx` DFT:
/// frequencies above half the size are the negative ones.
pub fn grid_wavevector(c: usize, r: usize, nx: usize, ny: usize, dx: f64, dy: f64) -> (f64, f64) {
    let signed = |k: usize, n: usize| {
        if 2 * k > n {
            k as f64 - n as f64
        } else {
            k as f64
        }
    };
    let two_pi = 2.0 * std::f64::consts::PI;
    (
        two_pi * signed(c, nx) / (nx as f64 * dx),
        two_pi * signed(r, ny) / (ny as f64 * dy),
    )
}
