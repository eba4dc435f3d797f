//! An exponential approach to a plateau, y_k = c + A·e^(−k/τ), fitted by
//! least squares to a series (the per-cycle μ of a test's running-in: the
//! classic running-in curve of Blau, Wear 2005). For a given τ the model
//! is linear in c and A (two normal equations); τ is found by a scan over
//! a geometric grid from half a cycle to five times the record, refined
//! by golden-section search on ln τ.

/// A fitted decay.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DecayFit {
    /// Plateau c.
    pub plateau: f64,
    /// Amplitude A at k = 0.
    pub amplitude: f64,
    /// Time constant τ, in steps of k.
    pub tau: f64,
    /// Residual sum of squares.
    pub ssr: f64,
    /// Standard error of c (for τ fixed at its fit).
    pub se_plateau: f64,
}

/// (c, A, SSR) of the best fit at one τ; `None` when the basis is
/// degenerate (τ so large that e^(−k/τ) is constant to rounding).
fn at_tau(y: &[f64], tau: f64) -> Option<(f64, f64, f64, f64)> {
    let n = y.len() as f64;
    let r = (-1.0 / tau).exp();
    let (mut sg, mut sgg, mut sy, mut sgy, mut g) = (0.0, 0.0, 0.0, 0.0, 1.0);
    for &v in y {
        sg += g;
        sgg += g * g;
        sy += v;
        sgy += g * v;
        g *= r;
    }
    let det = n * sgg - sg * sg;
    if det.is_nan() || det <= 1e-12 * n * sgg {
        return None;
    }
    let a = (n * sgy - sg * sy) / det;
    let c = (sy - a * sg) / n;
    let mut ssr = 0.0;
    let mut g = 1.0;
    for &v in y {
        ssr += (v - c - a * g).powi(2);
        g *= r;
    }
    Some((c, a, ssr, sgg / det))
}

/// The least-squares decay through `y` (finite values, at least 4).
pub fn fit_decay(y: &[f64]) -> Option<DecayFit> {
    let n = y.len();
    if n < 4 {
        return None;
    }
    let (lo, hi) = (0.5f64.ln(), (5.0 * n as f64).ln());
    let steps = 80;
    let ln_tau = |j: usize| lo + (hi - lo) * j as f64 / steps as f64;
    let ssr = |lt: f64| at_tau(y, lt.exp()).map_or(f64::INFINITY, |f| f.2);
    let best = (0..=steps)
        .map(|j| (j, ssr(ln_tau(j))))
        .min_by(|a, b| a.1.total_cmp(&b.1))?;
    if !best.1.is_finite() {
        return None;
    }
    // Golden section between the neighbours of the best grid point.
    let (mut a, mut b) = (
        ln_tau(best.0.saturating_sub(1)),
        ln_tau((best.0 + 1).min(steps)),
    );
    let phi = (5f64.sqrt() - 1.0) / 2.0;
    let (mut x1, mut x2) = (b - phi * (b - a), a + phi * (b - a));
    let (mut f1, mut f2) = (ssr(x1), ssr(x2));
    for _ in 0..60 {
        if f1 <= f2 {
            (b, x2, f2) = (x2, x1, f1);
            x1 = b - phi * (b - a);
            f1 = ssr(x1);
        } else {
            (a, x1, f1) = (x1, x2, f2);
            x2 = a + phi * (b - a);
            f2 = ssr(x2);
        }
    }
    let tau = (if f1 <= f2 { x1 } else { x2 }).exp();
    let (c, amp, ssr, inv) = at_tau(y, tau)?;
    let var = ssr / (n as f64 - 3.0).max(1.0);
    Some(DecayFit {
        plateau: c,
        amplitude: amp,
        tau,
        ssr,
        se_plateau: (var * inv).sqrt(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A noise-free decay is recovered to rounding; a constant gives A ≈ 0.
    #[test]
    fn an_exact_decay_is_recovered() {
        let y: Vec<f64> = (0..300)
            .map(|k| 0.3 + 0.25 * (-(k as f64) / 17.0).exp())
            .collect();
        let f = fit_decay(&y).unwrap();
        assert!((f.tau - 17.0).abs() < 1e-6, "{f:?}");
        assert!(
            (f.plateau - 0.3).abs() < 1e-10 && (f.amplitude - 0.25).abs() < 1e-9,
            "{f:?}"
        );
        // Rising from below.
        let y: Vec<f64> = (0..300)
            .map(|k| 0.5 - 0.2 * (-(k as f64) / 40.0).exp())
            .collect();
        let f = fit_decay(&y).unwrap();
        assert!(
            (f.tau - 40.0).abs() < 1e-5 && (f.amplitude + 0.2).abs() < 1e-9,
            "{f:?}"
        );
        assert!(fit_decay(&[1.0, 2.0, 3.0]).is_none());
    }
}
