//! Segmentation: strokes of a reciprocating test (by the sign of the
//! friction force), velocity steps of a stepped-velocity test, and the
//! steady-sliding window after a detachment peak.

use std::ops::Range;

use super::stats::median;

/// Samples per block of [`strokes`]' branch-free test.
const BLOCK: usize = 64;

/// Strokes: maximal runs where the force keeps one sign. Samples with
/// |T| ≤ `deadband` keep the current sign (so noise around zero at a
/// reversal does not split a stroke). Runs shorter than `min_len` are
/// reversal transients (the decaying tail of the previous stroke) and are
/// dropped. Returns (range, sign) per stroke, in order.
pub fn strokes(t: &[f64], deadband: f64, min_len: usize) -> Vec<(Range<usize>, f64)> {
    let mut runs: Vec<(Range<usize>, i8)> = Vec::new();
    let mut current = 0i8;
    let mut start = 0;
    let mut i = 0;
    while i < t.len() {
        // Inside a stroke, a block all beyond the dead band keeps the sign:
        // one branch-free test per block instead of a branch per sample.
        if current != 0 && deadband >= 0.0 && i + BLOCK <= t.len() {
            let sign = f64::from(current);
            let kept = t[i..i + BLOCK]
                .iter()
                .fold(true, |all, &v| all & (v * sign > deadband));
            if kept {
                i += BLOCK;
                continue;
            }
        }
        let v = t[i];
        let s = if v > deadband {
            1
        } else if v < -deadband {
            -1
        } else {
            current
        };
        if s != current {
            if current != 0 && i > start {
                runs.push((start..i, current));
            }
            start = i;
            current = s;
        }
        i += 1;
    }
    if current != 0 && t.len() > start {
        runs.push((start..t.len(), current));
    }
    runs.retain(|(r, _)| r.len() >= min_len.max(1));
    // Dropping a transient can leave two neighbours of the same sign: merge.
    let mut merged: Vec<(Range<usize>, i8)> = Vec::new();
    for (r, s) in runs {
        match merged.last_mut() {
            Some((last, ls)) if *ls == s => last.end = r.end,
            _ => merged.push((r, s)),
        }
    }
    merged.into_iter().map(|(r, s)| (r, f64::from(s))).collect()
}

/// Velocity steps: runs where the speed stays within `rel_tol` of the run's
/// running median, at least `min_len` samples long. A new step starts when
/// `min_len` consecutive samples leave the band. Returns the ranges.
pub fn velocity_steps(v: &[f64], rel_tol: f64, abs_tol: f64, min_len: usize) -> Vec<Range<usize>> {
    let n = v.len();
    let min_len = min_len.max(2);
    let mut steps = Vec::new();
    let mut start = 0;
    while start + min_len <= n {
        let level = median(&v[start..start + min_len]).unwrap_or(0.0);
        let tol = |level: f64| rel_tol * level.abs() + abs_tol;
        let mut end = start + min_len;
        let mut out = 0;
        while end < n {
            if (v[end] - level).abs() > tol(level) {
                out += 1;
                if out >= min_len {
                    end -= out - 1;
                    break;
                }
            } else {
                out = 0;
            }
            end += 1;
        }
        if end >= n {
            end = n;
        }
        steps.push(start..end);
        start = end;
    }
    if let (Some(last), true) = (steps.last_mut(), start < n) {
        last.end = n;
    }
    steps
}

/// The steady-sliding window after index `from`: the level is the median
/// of the signal from `from` to `trim` samples before the end; the window
/// runs from the first sample where both the sample and the running mean of
/// width `w` after it come within `tol` of the level, to the last sample
/// where both the sample and the running mean of width `w` before it are
/// within `tol`. So a slow settling at the start and a stop at the end of a
/// stroke (the force relaxing at rest) are both left out. `None` when fewer
/// than `min_len` samples remain.
pub fn steady_window(
    x: &[f64],
    from: usize,
    w: usize,
    tol: f64,
    trim: usize,
    min_len: usize,
) -> Option<Range<usize>> {
    let end = x.len().saturating_sub(trim);
    if end <= from || end - from < min_len.max(2) {
        return None;
    }
    let rest = &x[from..end];
    let level = median(rest)?;
    let w = w.clamp(1, rest.len());
    let inside = |i: usize, window: &[f64]| {
        (window.iter().sum::<f64>() / w as f64 - level).abs() <= tol
            && (rest[i] - level).abs() <= tol
    };
    let start = (0..=rest.len() - w).find(|&i| inside(i, &rest[i..i + w]))?;
    let last = (w - 1..rest.len())
        .rev()
        .find(|&i| inside(i, &rest[i + 1 - w..=i]))?;
    let r = from + start..from + last + 1;
    (r.len() >= min_len.max(2)).then_some(r)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn strokes_drop_the_reversal_tail() {
        let mut t = vec![5.0, 3.0, 1.0];
        t.extend(std::iter::repeat_n(-10.0, 20));
        t.extend(std::iter::repeat_n(10.0, 20));
        let s = strokes(&t, 0.5, 5);
        assert_eq!(s, vec![(3..23, -1.0), (23..43, 1.0)]);
    }

    /// The block test changes nothing: the runs are those of a walk sample
    /// by sample (the former loop, kept as the oracle) on long strokes with
    /// noise across the dead band, NaN and a negative dead band.
    #[test]
    fn strokes_equal_the_sample_walk() {
        fn walk(t: &[f64], deadband: f64) -> Vec<(Range<usize>, i8)> {
            let (mut runs, mut current, mut start) = (Vec::new(), 0i8, 0);
            for (i, &v) in t.iter().enumerate() {
                let s = if v > deadband {
                    1
                } else if v < -deadband {
                    -1
                } else {
                    current
                };
                if s != current {
                    if current != 0 && i > start {
                        runs.push((start..i, current));
                    }
                    (start, current) = (i, s);
                }
            }
            if current != 0 && t.len() > start {
                runs.push((start..t.len(), current));
            }
            runs
        }
        let noise = crate::signal::testing::gaussian_noise(20 * BLOCK + 5, 1.0, 8);
        let mut t: Vec<f64> = noise
            .iter()
            .enumerate()
            .map(|(i, e)| {
                if (i / 300) % 2 == 0 {
                    3.0 + e
                } else {
                    -3.0 + e
                }
            })
            .collect();
        t[5 * BLOCK + 1] = f64::NAN;
        for deadband in [0.5, 2.0, -0.5, 0.0] {
            let want: Vec<(Range<usize>, f64)> = walk(&t, deadband)
                .into_iter()
                .map(|(r, s)| (r, f64::from(s)))
                .collect();
            assert_eq!(strokes(&t, deadband, 1), want, "dead band {deadband}");
        }
    }

    #[test]
    fn steps_of_a_staircase() {
        let mut v = Vec::new();
        for level in [0.025, 0.05, 0.1, 0.2] {
            v.extend(std::iter::repeat_n(level, 50));
        }
        let s = velocity_steps(&v, 0.05, 0.0, 10);
        assert_eq!(s, vec![0..50, 50..100, 100..150, 150..200]);
    }

    #[test]
    fn steady_window_skips_the_settling() {
        let x: Vec<f64> = (0..100)
            .map(|i| if i < 20 { 2.0 - i as f64 * 0.05 } else { 1.0 })
            .collect();
        let r = steady_window(&x, 0, 5, 0.005, 5, 10).unwrap();
        assert_eq!(r, 20..95);
        // A stop at the end (the force relaxing at rest) is left out too.
        let mut y = x.clone();
        y.extend(std::iter::repeat_n(0.8, 30));
        let r = steady_window(&y, 0, 5, 0.005, 0, 10).unwrap();
        assert_eq!(r, 20..100);
    }
}
