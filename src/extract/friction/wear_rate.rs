//! Wear through a test (MODELS.md §11): the rate of a linear-wear (depth)
//! channel per sliding distance, the least-squares slope of the wear depth
//! (each cycle's mean) against the sliding distance (the cycle's middle),
//! in m per m, with its standard error. The channel's own sign is kept: a
//! pin that descends reads negative on an instrument that counts height.
//! (The specific wear rate of a wear volume is the wear stage's,
//! `extract::wear::volume`.)

use crate::signal::stats;

/// A fitted rate with its standard error.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Rate {
    /// Slope, y per x.
    pub slope: f64,
    /// Its standard error (`None` with fewer than 3 points).
    pub se: Option<f64>,
    /// Points fitted.
    pub n: usize,
}

/// The slope of `y` against `x` by least squares (finite pairs), with its
/// standard error √(s² / Σ(x − x̄)²), s² the residual variance over n − 2.
pub fn rate(x: &[f64], y: &[f64]) -> Option<Rate> {
    let (xs, ys): (Vec<f64>, Vec<f64>) = x
        .iter()
        .zip(y)
        .filter(|(a, b)| a.is_finite() && b.is_finite())
        .map(|(a, b)| (*a, *b))
        .unzip();
    let line = stats::line_fit(&xs, &ys)?;
    let n = xs.len();
    let mx = xs.iter().sum::<f64>() / n as f64;
    let sxx: f64 = xs.iter().map(|v| (v - mx).powi(2)).sum();
    let ssr: f64 = xs
        .iter()
        .zip(&ys)
        .map(|(a, b)| (b - line.a - line.b * a).powi(2))
        .sum();
    let se = (n > 2).then(|| (ssr / (n - 2) as f64 / sxx).sqrt());
    Some(Rate {
        slope: line.b,
        se,
        n,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A depth falling 2 µm per metre with noise: the slope within 3 se of
    /// −2e-6 and the se that of the textbook formula; exact data, se 0.
    #[test]
    fn a_depth_rate_is_the_fitted_slope() {
        let x: Vec<f64> = (0..200).map(|i| i as f64 * 0.05).collect();
        let e = crate::signal::testing::gaussian_noise(200, 1e-7, 8);
        let y: Vec<f64> = x.iter().zip(&e).map(|(x, e)| 1e-5 - 2e-6 * x + e).collect();
        let r = rate(&x, &y).unwrap();
        let se = r.se.unwrap();
        assert!((r.slope + 2e-6).abs() < 3.0 * se, "{r:?}");
        // se ≈ σ / √Σ(x − x̄)² = 1e-7 / √(200 · var(x)).
        let sxx: f64 = x.iter().map(|v| (v - 4.975).powi(2)).sum();
        assert!((se / (1e-7 / sxx.sqrt()) - 1.0).abs() < 0.15, "{se}");
        let exact: Vec<f64> = x.iter().map(|x| 3e-6 * x).collect();
        let r = rate(&x, &exact).unwrap();
        assert!((r.slope - 3e-6).abs() < 1e-18 && r.se.unwrap() < 1e-15);
        assert!(rate(&[1.0, 1.0], &[0.0, 1.0]).is_none());
    }
}
