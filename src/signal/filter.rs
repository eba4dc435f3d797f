//! Smoothing that keeps edges: a running median removes isolated spikes
//! without rounding off the fast drops of stick-slip.

/// Running median of odd width `w` (even widths are rounded up); the window
/// shrinks at the ends so the output has the input's length.
pub fn median_filter(x: &[f64], w: usize) -> Vec<f64> {
    let half = w / 2;
    if half == 0 || x.len() < 3 {
        return x.to_vec();
    }
    let mut buf = Vec::with_capacity(2 * half + 1);
    (0..x.len())
        .map(|i| {
            let lo = i.saturating_sub(half);
            let hi = (i + half + 1).min(x.len());
            buf.clear();
            buf.extend_from_slice(&x[lo..hi]);
            // Selection, not a sort: same order statistics (stats.rs).
            crate::signal::stats::median_in_place(&mut buf).unwrap_or(x[i])
        })
        .collect()
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
}
