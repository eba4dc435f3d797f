//! Trapezoid integration of sampled curves y(x).
//!
//! The curve is the piecewise-linear path through the samples, in sample
//! order. [`trapezoid`] integrates it over all samples; [`trapezoid_within`]
//! integrates only the parts of the path with `lo ≤ x ≤ hi`, interpolating
//! linearly where a segment crosses a bound. A segment along which x
//! decreases contributes negatively, as in a line integral ∫ y dx; this keeps
//! the result exact for piecewise-linear data whatever the sampling.
//!
//! Non-finite inputs are the caller's business: the functions return a
//! non-finite result rather than hiding them.

/// ∫ y dx over the whole sampled path, by the trapezoid rule.
///
/// Slices of different lengths are integrated over their common prefix.
pub fn trapezoid(x: &[f64], y: &[f64]) -> f64 {
    x.windows(2)
        .zip(y.windows(2))
        .map(|(xs, ys)| 0.5 * (ys[0] + ys[1]) * (xs[1] - xs[0]))
        .sum()
}

/// ∫ y dx over the parts of the sampled path with `lo ≤ x ≤ hi`
/// (trapezoid rule with linear interpolation at the bounds).
///
/// Returns 0 when `hi ≤ lo`.
pub fn trapezoid_within(x: &[f64], y: &[f64], lo: f64, hi: f64) -> f64 {
    if hi <= lo {
        return 0.0;
    }
    let mut total = 0.0;
    for (xs, ys) in x.windows(2).zip(y.windows(2)) {
        let (x0, x1, y0, y1) = (xs[0], xs[1], ys[0], ys[1]);
        let (a, b, sign) = if x1 >= x0 {
            (x0, x1, 1.0)
        } else {
            (x1, x0, -1.0)
        };
        let from = a.max(lo);
        let to = b.min(hi);
        if to <= from {
            continue;
        }
        // to > from implies x1 ≠ x0, so the interpolation is defined.
        let at = |t: f64| y0 + (y1 - y0) * (t - x0) / (x1 - x0);
        total += sign * 0.5 * (at(from) + at(to)) * (to - from);
    }
    total
}

/// Mean of y over `lo ≤ x ≤ hi` weighted by x:
/// (1 / (hi − lo)) ∫_lo^hi y dx. `None` when `hi ≤ lo`.
pub fn mean_within(x: &[f64], y: &[f64], lo: f64, hi: f64) -> Option<f64> {
    (hi > lo).then(|| trapezoid_within(x, y, lo, hi) / (hi - lo))
}

#[cfg(test)]
mod tests {
    use super::*;

    // Tolerances: the trapezoid rule is exact for piecewise-linear y, so
    // only rounding (≈1e-15 relative per term) remains.
    const TOL: f64 = 1e-12;

    #[test]
    fn linear_function_is_integrated_exactly() {
        let x: Vec<f64> = (0..=10).map(|i| i as f64 * 0.1).collect();
        let y: Vec<f64> = x.iter().map(|x| 3.0 * x + 1.0).collect();
        // ∫_0^1 (3x + 1) dx = 2.5
        assert!((trapezoid(&x, &y) - 2.5).abs() < TOL);
        // ∫_0.25^0.75 (3x + 1) dx = 1.5·(0.75² − 0.25²) + 0.5 = 1.25
        assert!((trapezoid_within(&x, &y, 0.25, 0.75) - 1.25).abs() < TOL);
    }

    #[test]
    fn bounds_outside_the_data_clip_to_the_data() {
        let x = [-1.0, 0.0, 1.0, 2.0];
        let y = [5.0, 0.0, 1.0, 2.0];
        // only x ∈ [0, 2] counts: ∫_0^2 x dx = 2
        assert!((trapezoid_within(&x, &y, 0.0, 10.0) - 2.0).abs() < TOL);
        assert!(trapezoid_within(&x, &y, 1.0, 1.0).abs() < TOL);
        assert_eq!(mean_within(&x, &y, 2.0, 1.0), None);
    }

    #[test]
    fn a_path_that_goes_back_cancels() {
        // out along y = 1 from 0 to 1, back along y = 1: net zero
        let x = [0.0, 1.0, 0.0];
        let y = [1.0, 1.0, 1.0];
        assert!(trapezoid_within(&x, &y, 0.0, 1.0).abs() < TOL);
        assert!(trapezoid(&x, &y).abs() < TOL);
    }

    #[test]
    fn mean_of_a_constant_is_the_constant() {
        let x = [0.0, 0.3, 0.35, 1.0];
        let y = [2.0; 4];
        let m = mean_within(&x, &y, 0.1, 0.9).unwrap();
        assert!((m - 2.0).abs() < TOL);
    }
}
