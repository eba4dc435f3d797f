//! Where the Case 2 closed form is exact (MODELS.md §5, "Where the closed
//! forms are exact").
//!
//! For two identical symmetric triangle waves (slope t = tan φ, wavelength λ)
//! sliding across (β = 0), the time-averaged R_x equals L (H(φ) + H(−φ)) / 2
//! at every load, by the mirror symmetry (x, s) → (−x, −s). The reported
//! μ = mean |R_x(t)| / L equals the closed form μ0 / (1 − s) exactly as long as
//! R_x(t) never turns negative. It does turn negative at light load when
//! t > μ0 (H(−φ) < 0): when the upper surface is shifted by more than half a
//! period, the most compressed springs sit where both surfaces descend.
//!
//! In the continuum, with σ = 1 − s/λ ∈ (0, ½] and a = t σ λ, the gap
//! g = z2(x − s) − z1(x) is −a on a fraction ½ − σ (both facets descending,
//! ratio H(−φ)), +a on a fraction ½ − σ (both rising, H(φ)), and runs
//! linearly from −a to a on a fraction 2σ (mixed, mean ratio). With
//! F = k max(0, u0 − g) and mean F = L this gives R_x(σ, L) in closed form
//! up to the offset u0, found by bisection. [`case2_threshold`] is the
//! smallest load L* above which min_σ R_x ≥ 0.
//!
//! Check against MODELS.md §5 (t = 0.4, λ = 1, k = 1, μ0 = 0.3): exact at
//! 0.05, 0.6 % high at 0.03; L* ≈ 0.0403 (see `tests/alsfm_closed_form.rs`).

use super::local_law::local_law;
use crate::error::Result;

/// Minimum over one period of R_x(t) / k for identical symmetric triangle
/// waves of slope `t` and wavelength 1 at load per spring `l_over_k`
/// (m, L / k), β = 0, `samples` shifts.
pub fn case2_min_rx(mu0: f64, t: f64, l_over_k: f64, samples: usize) -> Result<f64> {
    let phi = t.atan();
    let hp = local_law(mu0, phi, 0.0)?.hx;
    let hm = local_law(mu0, -phi, 0.0)?.hx;
    let hmix = 0.5 * (hp + hm);
    let mut min = f64::INFINITY;
    for k in 1..=samples {
        let sigma = 0.5 * k as f64 / samples as f64;
        let a = t * sigma;
        let parts = |u0: f64| {
            let g = |x: f64| (u0 - x).max(0.0);
            let p1 = (0.5 - sigma) * g(-a);
            let p2 = (0.5 - sigma) * g(a);
            // ∫_{−a}^{a} max(0, u0 − g) dg / (2a)
            let mean_mix = if u0 >= a {
                u0
            } else if u0 <= -a {
                0.0
            } else {
                (u0 + a) * (u0 + a) / (4.0 * a)
            };
            (p1, p2, 2.0 * sigma * mean_mix)
        };
        let total = |u0: f64| {
            let (p1, p2, p3) = parts(u0);
            p1 + p2 + p3
        };
        let (mut lo, mut hi) = (-a, a + 2.0 * l_over_k + 1.0);
        // 80 halvings take the bracket (width < 2 + 2L/k) below 1e-23.
        for _ in 0..80 {
            let mid = 0.5 * (lo + hi);
            if mid <= lo || mid >= hi {
                break;
            }
            if total(mid) < l_over_k {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        let (p1, p2, p3) = parts(0.5 * (lo + hi));
        min = min.min(p1 * hm + p2 * hp + p3 * hmix);
    }
    Ok(min)
}

/// Margin on the load used by the path choice: the closed form is taken
/// only when L ≥ 1.1 L*, so that the lattice's discreteness near the
/// boundary cannot matter.
pub const CASE2_MARGIN: f64 = 1.1;

/// Whether the Case 2 closed form is exact (with [`CASE2_MARGIN`]) at load
/// `l_over_k_lambda` = L / (k λ): one evaluation of [`case2_min_rx`] at
/// L / 1.1 instead of solving for L* (R_x's minimum grows with L).
pub fn case2_exact_at(mu0: f64, t: f64, l_over_k_lambda: f64) -> Result<bool> {
    if t <= mu0 {
        return Ok(l_over_k_lambda > 0.0);
    }
    Ok(l_over_k_lambda > 0.0 && case2_min_rx(mu0, t, l_over_k_lambda / CASE2_MARGIN, 400)? >= 0.0)
}

/// L* / (k λ): the smallest load (per spring, over k λ) above which the Case 2
/// closed form is exact at β = 0 for identical symmetric wedges of slope
/// `t` = tan φ. 0 when t ≤ μ0 (R_x never turns negative); infinite when no
/// load up to 10³ λ k makes it exact.
pub fn case2_threshold(mu0: f64, t: f64) -> Result<f64> {
    const SAMPLES: usize = 400;
    if t <= mu0 {
        return Ok(0.0);
    }
    let mut hi = t;
    while case2_min_rx(mu0, t, hi, SAMPLES)? < 0.0 {
        hi *= 2.0;
        if hi > 1e3 {
            return Ok(f64::INFINITY);
        }
    }
    let mut lo = 0.0;
    for _ in 0..40 {
        let mid = 0.5 * (lo + hi);
        if case2_min_rx(mu0, t, mid, SAMPLES)? < 0.0 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    Ok(hi)
}
