//! Descriptive statistics over slices. NaN-free input is the caller's job;
//! empty input gives `None`, never NaN.

use super::select::{self, Values};
use super::sum;
use std::ops::Range;

/// Arithmetic mean (the sum in fixed lanes, [`super::sum`]).
pub fn mean(x: &[f64]) -> Option<f64> {
    (!x.is_empty()).then(|| sum::sum(x) / x.len() as f64)
}

/// [`mean`] of the finite values among `f(0..n)`, computed in place of
/// collected (count and sum in one pass).
pub fn mean_finite_by(n: usize, f: impl Fn(usize) -> f64 + Sync) -> Option<f64> {
    let (count, total) = finite_sum(n, &f);
    (count > 0).then(|| total / count as f64)
}

/// [`sd`] of the finite values among `f(0..n)`, computed in place of
/// collected.
pub fn sd_finite_by(n: usize, f: impl Fn(usize) -> f64 + Sync) -> Option<f64> {
    let (count, total) = finite_sum(n, &f);
    if count < 2 {
        return None;
    }
    let m = total / count as f64;
    let ss = sum::sum_by(n, |i| match f(i) {
        v if v.is_finite() => (v - m).powi(2),
        _ => 0.0,
    });
    Some((ss / (count - 1) as f64).sqrt())
}

/// The count and sum of the finite values among `f(0..n)`, in one pass
/// (the count summed as a float is exact below 2^53).
fn finite_sum(n: usize, f: &(impl Fn(usize) -> f64 + Sync)) -> (usize, f64) {
    let [count, total] = sum::sums_by(n, |i| match f(i) {
        v if v.is_finite() => [1.0, v],
        _ => [0.0, 0.0],
    });
    (count as usize, total)
}

/// [`sd`] of `f(0..n)`, computed in place of collected.
pub fn sd_by(n: usize, f: impl Fn(usize) -> f64 + Sync) -> Option<f64> {
    let m = sum::sum_by(n, &f) / n as f64;
    sd_about_by(n, m, f)
}

/// [`sd_by`] about a mean `m` the caller has already taken (as [`mean`]
/// does, so the same bits), without summing again.
fn sd_about_by(n: usize, m: f64, f: impl Fn(usize) -> f64 + Sync) -> Option<f64> {
    if n < 2 {
        return None;
    }
    let ss = sum::sum_by(n, |i| (f(i) - m).powi(2));
    Some((ss / (n - 1) as f64).sqrt())
}

/// Sample standard deviation (n − 1). `None` for fewer than 2 values.
pub fn sd(x: &[f64]) -> Option<f64> {
    sd_by(x.len(), |i| x[i])
}

/// The mean of `x` and its [`sd`] (`None` for fewer than 2 values), the
/// mean summed once for both.
pub fn mean_sd(x: &[f64]) -> Option<(f64, Option<f64>)> {
    let m = mean(x)?;
    Some((m, sd_about_by(x.len(), m, |i| x[i])))
}

/// A least-squares line y = a + b·x, with the mean of the y it was
/// fitted to (its callers need both; the fit has it already).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Line {
    /// Intercept a.
    pub a: f64,
    /// Slope b.
    pub b: f64,
    /// Mean of y.
    pub mean_y: f64,
}

/// Least-squares line through paired samples. `None` for fewer than 2
/// pairs or when every x is the same.
pub fn line_fit(x: &[f64], y: &[f64]) -> Option<Line> {
    let n = x.len().min(y.len());
    if n == 0 {
        return None;
    }
    let [sx, sy] = sum::sums_by(n, |i| [x[i], y[i]]);
    let (mx, my) = (sx / n as f64, sy / n as f64);
    let [sxx, sxy] = sum::sums_by(n, |i| {
        let dx = x[i] - mx;
        [dx * dx, dx * (y[i] - my)]
    });
    (n >= 2 && sxx > 0.0).then(|| Line {
        a: my - sxy / sxx * mx,
        b: sxy / sxx,
        mean_y: my,
    })
}

/// Median (average of the two middle values for even lengths), without a
/// copy of `x` ([`super::select`]).
pub fn median(x: &[f64]) -> Option<f64> {
    select::median(&select::of_slice(x), x.len())
}

/// Median of a scratch buffer, reordering it: selection (`select_nth_unstable`,
/// O(n)) instead of a full sort; the order statistics and so the result are
/// the same as after sorting by `f64::total_cmp`.
pub fn median_in_place(v: &mut [f64]) -> Option<f64> {
    let n = v.len();
    if n == 0 {
        return None;
    }
    let (left, mid, _) = v.select_nth_unstable_by(n / 2, f64::total_cmp);
    let hi = *mid;
    if n % 2 == 1 {
        return Some(hi);
    }
    // The lower middle value is the largest of the left partition.
    let lo = left.iter().copied().max_by(f64::total_cmp).unwrap_or(hi);
    Some(0.5 * (lo + hi))
}

/// Median absolute deviation scaled to a Gaussian standard deviation
/// (× 1.4826).
pub fn mad_sigma(x: &[f64]) -> Option<f64> {
    mad_sigma_of(&select::of_slice(x), x.len())
}

/// `mad_sigma` of the `n` values of `v`, read again for each median rather
/// than copied.
fn mad_sigma_of<F, I>(v: &Values<F>, n: usize) -> Option<f64>
where
    F: Fn(Range<usize>) -> I + Sync,
    I: Iterator<Item = f64>,
{
    let m = select::median(v, n)?;
    let deviations = Values {
        positions: v.positions,
        read: |r: Range<usize>| (v.read)(r).map(move |d| (d - m).abs()),
    };
    select::median(&deviations, n).map(|d| 1.4826 * d)
}

/// White-noise standard deviation: the MAD of the first differences
/// divided by √2. Steps, slow drift and rare slips barely move it, so it
/// measures the sample-to-sample noise, not the signal. Non-finite
/// differences are skipped; `None` with fewer than 3 finite differences.
pub fn noise_sigma(x: &[f64]) -> Option<f64> {
    let diffs = Values {
        positions: x.len().saturating_sub(1),
        read: |r: Range<usize>| {
            x[r.start..r.end + 1]
                .windows(2)
                .map(|w| w[1] - w[0])
                .filter(|d| d.is_finite())
        },
    };
    let n = diffs.count();
    if n < 3 {
        return None;
    }
    mad_sigma_of(&diffs, n).map(|s| s / std::f64::consts::SQRT_2)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The values computed in place, non-finite ones skipped, give the
    /// mean and sd of the finite values collected; too few give `None`.
    #[test]
    fn in_place_statistics_skip_non_finite_values() {
        let x = [
            1.0,
            f64::NAN,
            2.0,
            f64::INFINITY,
            4.0,
            f64::NEG_INFINITY,
            8.0,
        ];
        let finite = [1.0, 2.0, 4.0, 8.0];
        assert_eq!(mean_finite_by(x.len(), |i| x[i]), mean(&finite));
        assert_eq!(sd_finite_by(x.len(), |i| x[i]), sd(&finite));
        assert_eq!(mean(&finite), Some(3.75));
        let sd4 = sd(&finite).unwrap();
        assert!((sd4 - (28.75f64 / 3.0).sqrt()).abs() < 1e-15, "{sd4}");
        assert_eq!(sd_by(4, |i| finite[i]), Some(sd4));
        assert_eq!(mean_sd(&finite), Some((3.75, Some(sd4))));
        assert_eq!(mean_sd(&[2.0]), Some((2.0, None)));
        assert_eq!(mean_sd(&[]), None);
        assert_eq!(mean_finite_by(2, |_| f64::NAN), None);
        assert_eq!(sd_finite_by(3, |i| [1.0, f64::NAN, f64::NAN][i]), None);
        assert_eq!(sd_by(1, |_| 1.0), None);
    }

    /// The closed form on exact data: y = 2 − 0.5 x; degenerate inputs
    /// give `None`.
    #[test]
    fn line_fit_recovers_a_line() {
        let x = [0.0, 1.0, 3.0, 4.5];
        let y: Vec<f64> = x.iter().map(|v| 2.0 - 0.5 * v).collect();
        let Line { a, b, mean_y } = line_fit(&x, &y).unwrap();
        assert_eq!(mean(&y), Some(mean_y));
        assert!(
            (a - 2.0).abs() < 1e-12 && (b + 0.5).abs() < 1e-12,
            "{a} {b}"
        );
        assert!(line_fit(&[1.0], &[2.0]).is_none());
        assert!(line_fit(&[1.0, 1.0], &[2.0, 3.0]).is_none());
    }

    /// Selection gives exactly the sorted-copy median (the old method, kept
    /// here as the oracle), ties, signed zeros and both parities included.
    #[test]
    fn selection_median_equals_sorted_median() {
        fn sorted_median(x: &[f64]) -> f64 {
            let mut v = x.to_vec();
            v.sort_by(f64::total_cmp);
            let n = v.len();
            if n % 2 == 1 {
                v[n / 2]
            } else {
                0.5 * (v[n / 2 - 1] + v[n / 2])
            }
        }
        let noise = crate::signal::testing::gaussian_noise(4001, 1.0, 11);
        for n in 1..200 {
            let x: Vec<f64> = noise[..n].iter().map(|v| (v * 4.0).round() / 4.0).collect();
            assert_eq!(median(&x).unwrap().to_bits(), sorted_median(&x).to_bits());
        }
        for n in [1000, 1001, 4000, 4001] {
            let x = &noise[..n];
            assert_eq!(median(x).unwrap().to_bits(), sorted_median(x).to_bits());
        }
        assert!(median(&[]).is_none());
    }

    /// The noise estimate read straight from the differences equals the
    /// one from a copied buffer of them (the old method), bit for bit.
    #[test]
    fn noise_sigma_equals_the_copied_buffer_method() {
        fn copied(x: &[f64]) -> Option<f64> {
            let mut d: Vec<f64> = x.windows(2).map(|w| w[1] - w[0]).collect();
            let m = median_in_place(&mut d)?;
            d.iter_mut().for_each(|v| *v = (*v - m).abs());
            median_in_place(&mut d).map(|s| 1.4826 * s / std::f64::consts::SQRT_2)
        }
        let noise = crate::signal::testing::gaussian_noise(200_001, 0.3, 3);
        let x: Vec<f64> = noise
            .iter()
            .enumerate()
            .map(|(i, e)| 0.5 + 0.1 * ((i % 700) as f64 / 700.0) + e)
            .collect();
        for n in [4, 5, 1000, 100_000, 200_001] {
            let got = noise_sigma(&x[..n]).unwrap();
            assert_eq!(got.to_bits(), copied(&x[..n]).unwrap().to_bits(), "n = {n}");
            let mad = mad_sigma(&x[..n]).unwrap();
            let mut v = x[..n].to_vec();
            let m = median_in_place(&mut v).unwrap();
            v.iter_mut().for_each(|d| *d = (*d - m).abs());
            let want = 1.4826 * median_in_place(&mut v).unwrap();
            assert_eq!(mad.to_bits(), want.to_bits());
        }
    }

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
