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
    // Windows [i, j] slide with both ends moving forward; the moments are
    // updated in O(1) per sample (Welford add/remove), which keeps the scan
    // O(n). The winning window's slope is then recomputed with the exact
    // two-pass formula, so the reported value carries no update drift.
    let mut acc = Moments::default();
    let mut best: Option<(f64, usize, usize)> = None;
    let mut j = from; // next sample to add
    for i in from..=to {
        if j < i {
            j = i;
            acc = Moments::default();
        }
        while j <= to && strain[j] - strain[i] <= width {
            acc.add(strain[j], stress[j]);
            j += 1;
        }
        if j - i >= MIN_POINTS {
            if let Some(s) = acc.slope() {
                if best.is_none_or(|b| s > b.0) {
                    best = Some((s, i, j - 1));
                }
            }
        }
        if j > i {
            acc.remove(strain[i], stress[i]);
        }
    }
    let (_, i, j) = best?;
    slope(&strain[i..=j], &stress[i..=j])
}

/// Running mean and co-moments of (x, y) with O(1) add and remove.
#[derive(Default)]
struct Moments {
    n: f64,
    mx: f64,
    my: f64,
    cxx: f64,
    cxy: f64,
}

impl Moments {
    fn add(&mut self, x: f64, y: f64) {
        self.n += 1.0;
        let dx = x - self.mx;
        self.mx += dx / self.n;
        self.my += (y - self.my) / self.n;
        self.cxx += dx * (x - self.mx);
        self.cxy += dx * (y - self.my);
    }
    fn remove(&mut self, x: f64, y: f64) {
        if self.n <= 1.0 {
            *self = Moments::default();
            return;
        }
        let dx = x - self.mx;
        self.n -= 1.0;
        self.mx -= dx / self.n;
        self.my -= (y - self.my) / self.n;
        self.cxx -= dx * (x - self.mx);
        self.cxy -= dx * (y - self.my);
    }
    fn slope(&self) -> Option<f64> {
        (self.cxx > 0.0).then(|| self.cxy / self.cxx)
    }
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
