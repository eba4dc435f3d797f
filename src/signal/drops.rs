//! Drops in a sampled signal, found with hysteresis.
//!
//! A **drop** is a fall of at least `h` from a local peak to the following
//! local trough (zig-zag segmentation with hysteresis `h`): after a peak, the
//! signal must fall by `h` before the drop is accepted, and the trough ends
//! where the signal rises again by `h`. Fluctuations smaller than `h` (noise)
//! neither start nor end a drop. This is what counts stick-slip events in a
//! stress plateau (MODELS.md §3).

use super::peaks::{zigzag_from, ZigzagStart};

/// One drop: indices of its peak and its trough, and the fall `y[peak] − y[trough]`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Drop {
    /// Index of the local peak that starts the drop.
    pub peak: usize,
    /// Index of the lowest point before the signal rises again by `h`
    /// (or the last sample).
    pub trough: usize,
    /// `y[peak] − y[trough]` (≥ h).
    pub size: f64,
}

/// Drops of at least `h` in `y`, in order (zig-zag with hysteresis `h > 0`,
/// [`zigzag_from`] starting at the first sample).
///
/// The last drop may end at the last sample if the signal does not rise
/// again. Non-finite samples are skipped (they neither start nor end a drop).
pub fn detect_drops(y: &[f64], h: f64) -> Vec<Drop> {
    zigzag_from(y, h, ZigzagStart::AtFirstSample)
        .into_iter()
        .map(|s| Drop {
            peak: s.peak,
            trough: s.after,
            size: y[s.peak] - y[s.after],
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::SeedableRng;
    use rand_distr::{Distribution, Normal};

    /// A sawtooth: rises by 1 over 10 samples, falls by `fall` in one.
    fn sawtooth(teeth: usize, fall: f64) -> Vec<f64> {
        let mut y = Vec::new();
        let mut base = 0.0;
        for _ in 0..teeth {
            for k in 0..=10 {
                y.push(base + k as f64 * 0.1);
            }
            base += 1.0 - fall;
        }
        y
    }

    #[test]
    fn counts_each_tooth_of_a_sawtooth() {
        let y = sawtooth(5, 0.6);
        let d = detect_drops(&y, 0.3);
        // the last tooth has no fall after it
        assert_eq!(d.len(), 4);
        for drop in &d {
            // each fall is exactly 0.6 (values are sums of exact tenths: 1e-12 covers rounding)
            assert!((drop.size - 0.6).abs() < 1e-12, "{drop:?}");
            assert_eq!(drop.trough, drop.peak + 1);
        }
    }

    #[test]
    fn falls_below_the_hysteresis_are_not_drops() {
        let y = sawtooth(5, 0.2);
        assert!(detect_drops(&y, 0.3).is_empty());
        assert!(detect_drops(&y, 0.0).is_empty());
    }

    #[test]
    fn noise_below_the_hysteresis_does_not_split_drops() {
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(7);
        let n = Normal::new(0.0, 0.02).unwrap();
        let y: Vec<f64> = sawtooth(6, 0.6)
            .into_iter()
            .map(|v| v + n.sample(&mut rng))
            .collect();
        // 0.3 is 15 noise sds: a false drop has negligible probability
        assert_eq!(detect_drops(&y, 0.3).len(), 5);
    }

    #[test]
    fn noise_level_is_recovered_on_a_trend() {
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(11);
        let n = Normal::new(0.0, 0.5).unwrap();
        let y: Vec<f64> = (0..4000)
            .map(|i| 0.01 * i as f64 + n.sample(&mut rng))
            .collect();
        let s = crate::signal::stats::noise_sigma(&y).unwrap();
        // MAD-based estimate from 4000 differences: relative sd ≈ 1.7 %, allow 10 %
        assert!((s - 0.5).abs() < 0.05, "{s}");
        assert_eq!(crate::signal::stats::noise_sigma(&[1.0, 2.0]), None);
    }
}
