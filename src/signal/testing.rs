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
