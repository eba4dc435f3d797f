//! Peaks: topographic prominence, the first real maximum of a trace, and a
//! zig-zag detector for saw-tooth (stick-slip) events.

/// Prominence of the sample at `i` (scipy's definition): its height above
/// the higher of the two lowest points on either side before a higher sample
/// (or the end) is met.
pub fn prominence(x: &[f64], i: usize) -> f64 {
    let p = x[i];
    let left = lowest_until_above(x[..i].rchunks(RUN), p, |c| c.iter().rev());
    let right = lowest_until_above(x[i + 1..].chunks(RUN), p, |c| c.iter());
    p - left.max(right)
}

/// Values per run of [`lowest_until_above`]'s branch-free pass.
const RUN: usize = 256;

/// The lowest value (at most `p`) met before the first value above `p`,
/// walking `runs` in order and each run as `walk` gives it. A run with no
/// value above `p` is folded without a branch per value (the right side of
/// a trace's detachment peak is the whole rest of the trace); the run
/// holding the first higher value is walked value by value. NaN is never
/// above `p` nor lowest, as in the plain walk.
fn lowest_until_above<'a, R, W>(runs: R, p: f64, walk: impl Fn(&'a [f64]) -> W) -> f64
where
    R: Iterator<Item = &'a [f64]>,
    W: Iterator<Item = &'a f64>,
{
    let mut low = p;
    for run in runs {
        let (lo, hi) = super::scan::extremes(run, |_| true);
        // (`hi` is −∞ for an all-NaN run; a NaN `p` walks every run, and
        // finds nothing above it, as the plain walk does.)
        if hi <= p {
            low = low.min(lo);
            continue;
        }
        for &v in walk(run) {
            if v > p {
                return low;
            }
            low = low.min(v);
        }
    }
    low
}

/// The first local maximum whose prominence reaches `threshold`: the
/// detachment (static) peak of a friction trace (MODELS.md §1). Flat tops
/// count once, at their first sample. Returns (index, prominence).
#[allow(clippy::float_cmp)]
pub fn first_prominent_peak(x: &[f64], threshold: f64) -> Option<(usize, f64)> {
    let n = x.len();
    let mut i = 1;
    while i + 1 < n {
        if x[i] > x[i - 1] {
            // Walk over a flat top: identical samples, so exact equality.
            let mut j = i;
            while j + 1 < n && x[j + 1] == x[i] {
                j += 1;
            }
            if j + 1 < n && x[j + 1] < x[i] {
                let p = prominence(x, i);
                if p >= threshold {
                    return Some((i, p));
                }
            }
            i = j + 1;
        } else {
            i += 1;
        }
    }
    None
}

/// A saw-tooth event found by [`zigzag`]: a maximum and the minima around it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Swing {
    /// Index of the minimum before the peak (start of the stick phase).
    pub before: usize,
    /// Index of the peak.
    pub peak: usize,
    /// Index of the minimum after the peak (end of the slip).
    pub after: usize,
}

/// Where a [`zigzag_from`] walk may find its first maximum.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ZigzagStart {
    /// Only after a rise of the threshold from the lowest point so far: a
    /// fall at the very start is not an event (stick-slip in a trace that
    /// starts at rest).
    AfterRise,
    /// At the first sample already: a fall from the start is an event
    /// (drops in a plateau that starts at its highest point).
    AtFirstSample,
}

/// Zig-zag (hysteresis) detector: alternating maxima and minima such that
/// every drop from a maximum to the next minimum, and every rise from a
/// minimum to the next maximum, is at least `threshold`. O(n). Each returned
/// swing is a maximum with the minima on both sides; a final maximum whose
/// fall has reached `threshold` is an event ending at the lowest sample
/// after it. Flat extrema count at their first sample. Non-finite samples
/// are skipped.
pub fn zigzag_from(x: &[f64], threshold: f64, start: ZigzagStart) -> Vec<Swing> {
    enum State {
        /// Before the first rise of `threshold`: tracking the lowest point.
        Start,
        /// Rising: tracking the candidate maximum.
        Up,
        /// Falling after a confirmed maximum: tracking the minimum.
        Down,
    }
    let mut swings = Vec::new();
    let Some(first) = x.iter().position(|v| v.is_finite()) else {
        return swings;
    };
    if threshold.is_nan() || threshold <= 0.0 {
        return swings;
    }
    let mut state = match start {
        ZigzagStart::AfterRise => State::Start,
        ZigzagStart::AtFirstSample => State::Up,
    };
    let (mut lo, mut hi, mut last_min) = (first, first, first);
    for i in first + 1..x.len() {
        let v = x[i];
        if !v.is_finite() {
            continue;
        }
        match state {
            State::Start => {
                if v < x[lo] {
                    lo = i;
                }
                if v - x[lo] >= threshold {
                    (state, hi, last_min) = (State::Up, i, lo);
                }
            }
            State::Up => {
                if v > x[hi] {
                    hi = i;
                }
                if x[hi] - v >= threshold {
                    (state, lo) = (State::Down, i);
                }
            }
            State::Down => {
                if v < x[lo] {
                    lo = i;
                }
                if v - x[lo] >= threshold {
                    swings.push(Swing {
                        before: last_min,
                        peak: hi,
                        after: lo,
                    });
                    (state, hi, last_min) = (State::Up, i, lo);
                }
            }
        }
    }
    if matches!(state, State::Down) {
        swings.push(Swing {
            before: last_min,
            peak: hi,
            after: lo,
        });
    }
    swings
}

/// [`zigzag_from`] with [`ZigzagStart::AfterRise`]: stick-slip swings of a
/// friction trace.
pub fn zigzag(x: &[f64], threshold: f64) -> Vec<Swing> {
    zigzag_from(x, threshold, ZigzagStart::AfterRise)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn prominence_of_a_simple_profile() {
        let x = [0.0, 3.0, 1.0, 5.0, 2.0, 4.0, 0.0];
        assert!((prominence(&x, 1) - 2.0).abs() < 1e-12);
        assert!((prominence(&x, 3) - 5.0).abs() < 1e-12);
        assert!((prominence(&x, 5) - 2.0).abs() < 1e-12);
    }

    /// The value-by-value walk of the definition, kept as the oracle.
    fn prominence_walked(x: &[f64], i: usize) -> f64 {
        let p = x[i];
        let lowest = |it: &mut dyn Iterator<Item = &f64>| {
            let mut low = p;
            for &v in it {
                if v > p {
                    break;
                }
                low = low.min(v);
            }
            low
        };
        p - lowest(&mut x[..i].iter().rev()).max(lowest(&mut x[i + 1..].iter()))
    }

    /// The run-wise walk gives the walk's prominence at every sample of a
    /// noisy saw-tooth with NaN, a plateau and a tall peak whose right side
    /// spans many runs.
    #[test]
    fn runwise_prominence_is_the_walked_one() {
        let noise = crate::signal::testing::gaussian_noise(5 * RUN + 7, 1.0, 3);
        let mut x: Vec<f64> = noise
            .iter()
            .enumerate()
            .map(|(i, e)| (i % 300) as f64 * 0.01 + e)
            .collect();
        x[RUN + 3] = 50.0;
        x[2 * RUN] = f64::NAN;
        x[3 * RUN..3 * RUN + 40].fill(2.0);
        for i in 0..x.len() {
            let (a, b) = (prominence(&x, i), prominence_walked(&x, i));
            assert!(
                a.to_bits() == b.to_bits() || (a.is_nan() && b.is_nan()),
                "{i}: {a} {b}"
            );
        }
    }

    #[test]
    fn first_peak_skips_small_wiggles() {
        let x = [0.0, 0.2, 0.1, 5.0, 3.0, 3.1, 3.0, 3.05];
        assert_eq!(first_prominent_peak(&x, 1.0).map(|p| p.0), Some(3));
        assert_eq!(first_prominent_peak(&x, 10.0), None);
    }

    /// A saw-tooth of 5 teeth: rise over 10 samples from 1 to 2, drop at once.
    #[test]
    fn zigzag_finds_every_tooth() {
        let mut x = Vec::new();
        for _ in 0..5 {
            for k in 0..=10 {
                x.push(1.0 + k as f64 / 10.0);
            }
        }
        x.push(1.0);
        let s = zigzag(&x, 0.5);
        assert_eq!(s.len(), 5);
        for (k, sw) in s.iter().enumerate() {
            assert_eq!(sw.peak, 11 * k + 10);
            assert!((x[sw.peak] - x[sw.after] - 1.0).abs() < 1e-12);
        }
    }

    #[test]
    fn zigzag_start_decides_whether_an_opening_fall_counts() {
        // Falls by 1 from the first sample, rises by 1, falls by 1 again.
        let x = [2.0, 1.5, 1.0, f64::NAN, 1.5, 2.0, 1.5, 1.0];
        let after_rise = zigzag_from(&x, 0.8, ZigzagStart::AfterRise);
        assert_eq!(
            after_rise,
            vec![Swing {
                before: 2,
                peak: 5,
                after: 7
            }]
        );
        let at_first = zigzag_from(&x, 0.8, ZigzagStart::AtFirstSample);
        assert_eq!(at_first.len(), 2);
        assert_eq!((at_first[0].peak, at_first[0].after), (0, 2));
        assert_eq!(at_first[1], after_rise[0]);
        assert!(zigzag_from(&x, f64::NAN, ZigzagStart::AtFirstSample).is_empty());
        assert!(zigzag_from(&[f64::NAN; 4], 0.1, ZigzagStart::AtFirstSample).is_empty());
    }
}
