//! Modulus: the largest slope dσ/dε of a straight line fitted by least
//! squares over a sliding strain window in the loading part of the curve.
//!
//! The window spans `modulus_window` · ε_m of strain (default 1 %), where ε_m
//! is the strain at maximum stress; windows with fewer than 5 samples are
//! skipped (widening them instead amplifies the rounding of strain written
//! with 3 decimals, as in T150 exports: +20 % on the real file). It slides from the start of loading (ε = 0) up to the
//! maximum stress. Each window needs at least 5 samples. The steepest
//! window is the linear-elastic region for a silk fibre (whose curve softens
//! after yield) and is insensitive to the toe at the start. For a knotted
//! fibre the strain is relative to l0 and the value is an apparent modulus.

/// Largest least-squares slope over windows of strain width `width` in
/// `from..=to`, skipping windows with fewer than 5 samples. `None` when no
/// window qualifies or the strain does not vary.
pub fn max_slope_modulus(
    strain: &[f64],
    stress: &[f64],
    from: usize,
    to: usize,
    width: f64,
) -> Option<f64> {
    const MIN_POINTS: usize = 5;
    if width.is_nan() || width <= 0.0 || to >= strain.len() || from > to {
        return None;
    }
    let mut best: Option<f64> = None;
    let mut j = from;
    for i in from..=to {
        if j < i {
            j = i;
        }
        while j < to && strain[j + 1] - strain[i] <= width {
            j += 1;
        }
        if j + 1 - i < MIN_POINTS {
            continue;
        }
        if let Some(s) = slope(&strain[i..=j], &stress[i..=j]) {
            if best.is_none_or(|b| s > b) {
                best = Some(s);
            }
        }
    }
    best
}

/// Least-squares slope of y on x; `None` when x is constant.
fn slope(x: &[f64], y: &[f64]) -> Option<f64> {
    let n = x.len() as f64;
    let mx = x.iter().sum::<f64>() / n;
    let my = y.iter().sum::<f64>() / n;
    let (mut sxx, mut sxy) = (0.0, 0.0);
    for (a, b) in x.iter().zip(y) {
        sxx += (a - mx) * (a - mx);
        sxy += (a - mx) * (b - my);
    }
    (sxx > 0.0).then(|| sxy / sxx)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn steepest_straight_part_is_found() {
        // σ = 10 GPa · ε up to ε = 0.02, then 1 GPa · ε (plastic)
        let e: Vec<f64> = (0..=100).map(|i| i as f64 * 0.001).collect();
        let s: Vec<f64> = e
            .iter()
            .map(|&e| {
                if e <= 0.02 {
                    10e9 * e
                } else {
                    2e8 + 1e9 * (e - 0.02)
                }
            })
            .collect();
        let m = max_slope_modulus(&e, &s, 0, 100, 0.01).unwrap();
        // exact on the linear part: rounding of the sums only
        assert!((m / 10e9 - 1.0).abs() < 1e-9, "{m}");
        assert_eq!(max_slope_modulus(&e, &s, 0, 3, 0.01), None);
        assert_eq!(max_slope_modulus(&e, &s, 0, 100, 0.0), None);
    }
}
