//! Smoothing that keeps edges: a running median removes isolated spikes
//! without rounding off the fast drops of stick-slip.

use rayon::prelude::*;

/// Outputs per parallel chunk (fixed: the split does not depend on the
/// thread count, and each output depends only on its window).
const CHUNK: usize = 1 << 16;

/// Running median of odd width `w` (even widths are rounded up); the window
/// shrinks at the ends so the output has the input's length.
pub fn median_filter(x: &[f64], w: usize) -> Vec<f64> {
    let half = w / 2;
    if half == 0 || x.len() < 3 {
        return x.to_vec();
    }
    let mut out = vec![0.0; x.len()];
    if half == 1 {
        // Three points: the interior in a plain loop over three shifted
        // slices (it vectorizes), the two shrunken ends as the general case.
        let n = x.len();
        out.par_chunks_mut(CHUNK).enumerate().for_each(|(c, o)| {
            let from = (c * CHUNK).max(1);
            let to = (c * CHUNK + o.len()).min(n - 1);
            let inner = &mut o[from - c * CHUNK..to - c * CHUNK];
            let (a, b, d) = (&x[from - 1..to - 1], &x[from..to], &x[from + 1..to + 1]);
            for (((y, a), b), d) in inner.iter_mut().zip(a).zip(b).zip(d) {
                *y = median3(*a, *b, *d);
            }
        });
        out[0] = median_of(&x[..2]);
        out[n - 1] = median_of(&x[n - 2..]);
        return out;
    }
    out.par_chunks_mut(CHUNK).enumerate().for_each(|(c, o)| {
        let mut buf = Vec::with_capacity(2 * half + 1);
        for (j, y) in o.iter_mut().enumerate() {
            let i = c * CHUNK + j;
            let window = &x[i.saturating_sub(half)..(i + half + 1).min(x.len())];
            *y = match window {
                [a, b, c] => median3(*a, *b, *c),
                _ => {
                    buf.clear();
                    buf.extend_from_slice(window);
                    // Selection, not a sort: same order statistics (stats.rs).
                    crate::signal::stats::median_in_place(&mut buf).unwrap_or(x[i])
                }
            };
        }
    });
    out
}

/// The median of a short window, by selection on a copy.
fn median_of(w: &[f64]) -> f64 {
    crate::signal::stats::median_in_place(&mut w.to_vec()).unwrap_or(f64::NAN)
}

/// The middle of three values in `f64::total_cmp`'s order (the value a
/// selection gives), without branches.
fn median3(a: f64, b: f64, c: f64) -> f64 {
    use crate::signal::select::{key, value};
    let (a, b, c) = (key(a), key(b), key(c));
    value(a.min(b).max(a.max(b).min(c)))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn removes_a_spike_and_keeps_a_step() {
        let mut x = vec![0.0; 20];
        x[5] = 100.0;
        for v in x.iter_mut().skip(12) {
            *v = 10.0;
        }
        let y = median_filter(&x, 5);
        assert!(y[5].abs() < 1e-12);
        assert!(y[11].abs() < 1e-12 && (y[12] - 10.0).abs() < 1e-12);
    }

    /// The filter equals a window-by-window selection (the definition), bit
    /// for bit, for the three-point fast path and wider windows, across
    /// chunk boundaries, with ties, signed zeros, infinities and NaN.
    #[test]
    fn equals_the_selection_of_each_window() {
        let noise = crate::signal::testing::gaussian_noise(3 * CHUNK + 17, 1.0, 4);
        let mut x: Vec<f64> = noise.iter().map(|e| (e * 4.0).round() / 4.0).collect();
        for (i, v) in [0.0, -0.0, f64::INFINITY, f64::NEG_INFINITY, f64::NAN, -0.0]
            .into_iter()
            .enumerate()
        {
            x[CHUNK - 3 + i] = v;
            x[7 + 2 * i] = v;
        }
        for w in [3, 5, 9] {
            let got = median_filter(&x, w);
            let h = w / 2;
            for (i, g) in got.iter().enumerate() {
                let mut win = x[i.saturating_sub(h)..(i + h + 1).min(x.len())].to_vec();
                let want = crate::signal::stats::median_in_place(&mut win).unwrap();
                assert_eq!(g.to_bits(), want.to_bits(), "w = {w}, i = {i}");
            }
        }
    }
}
