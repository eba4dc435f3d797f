//! Descriptive statistics over slices. NaN-free input is the caller's job;
//! empty input gives `None`, never NaN.

/// Arithmetic mean.
pub fn mean(x: &[f64]) -> Option<f64> {
    (!x.is_empty()).then(|| x.iter().sum::<f64>() / x.len() as f64)
}

/// Sample standard deviation (n − 1). `None` for fewer than 2 values.
pub fn sd(x: &[f64]) -> Option<f64> {
    if x.len() < 2 {
        return None;
    }
    let m = mean(x)?;
    let ss: f64 = x.iter().map(|v| (v - m).powi(2)).sum();
    Some((ss / (x.len() - 1) as f64).sqrt())
}

/// Median (average of the two middle values for even lengths).
pub fn median(x: &[f64]) -> Option<f64> {
    if x.is_empty() {
        return None;
    }
    let mut v = x.to_vec();
    v.sort_by(f64::total_cmp);
    let n = v.len();
    Some(if n % 2 == 1 {
        v[n / 2]
    } else {
        0.5 * (v[n / 2 - 1] + v[n / 2])
    })
}

/// Median absolute deviation scaled to a Gaussian standard deviation
/// (× 1.4826).
pub fn mad_sigma(x: &[f64]) -> Option<f64> {
    let m = median(x)?;
    let dev: Vec<f64> = x.iter().map(|v| (v - m).abs()).collect();
    median(&dev).map(|d| 1.4826 * d)
}

/// White-noise level of a signal, from the MAD of its first differences
/// divided by √2. Steps, slow drift and rare slips barely move it, so it
/// measures the sample-to-sample noise, not the signal. Non-finite
/// differences are skipped; `None` with fewer than 3 finite differences.
pub fn noise_sigma(x: &[f64]) -> Option<f64> {
    let d: Vec<f64> = x
        .windows(2)
        .map(|w| w[1] - w[0])
        .filter(|d| d.is_finite())
        .collect();
    if d.len() < 3 {
        return None;
    }
    mad_sigma(&d).map(|s| s / std::f64::consts::SQRT_2)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn closed_form_values() {
        // Exact in binary floating point for these small integers.
        assert!((mean(&[1.0, 2.0, 3.0, 4.0]).unwrap() - 2.5).abs() < 1e-15);
        assert!(
            (sd(&[2.0, 4.0, 4.0, 4.0, 5.0, 5.0, 7.0, 9.0]).unwrap() - (32.0f64 / 7.0).sqrt()).abs()
                < 1e-12
        );
        assert!((median(&[3.0, 1.0, 2.0]).unwrap() - 2.0).abs() < 1e-15);
        assert!((median(&[4.0, 1.0, 2.0, 3.0]).unwrap() - 2.5).abs() < 1e-15);
        assert!(mean(&[]).is_none() && sd(&[1.0]).is_none());
    }

    /// Deterministic pseudo-Gaussian noise of known sigma; the estimate must
    /// land within 10 % (the MAD estimator's sampling error at n = 20000 is
    /// about 1 %), also on top of a large step.
    #[test]
    fn noise_sigma_ignores_steps() {
        let noise = crate::signal::testing::gaussian_noise(20_000, 0.5, 7);
        let x: Vec<f64> = noise
            .iter()
            .enumerate()
            .map(|(i, e)| if i < 10_000 { *e } else { e + 100.0 })
            .collect();
        let s = noise_sigma(&x).unwrap();
        assert!((s - 0.5).abs() < 0.05, "{s}");
    }
}
