//! Peaks: topographic prominence, the first real maximum of a trace, and a
//! zig-zag detector for saw-tooth (stick-slip) events.

/// Prominence of the sample at `i` (scipy's definition): its height above
/// the higher of the two lowest points on either side before a higher sample
/// (or the end) is met.
pub fn prominence(x: &[f64], i: usize) -> f64 {
    let p = x[i];
    let mut left = p;
    for &v in x[..i].iter().rev() {
        if v > p {
            break;
        }
        left = left.min(v);
    }
    let mut right = p;
    for &v in &x[i + 1..] {
        if v > p {
            break;
        }
        right = right.min(v);
    }
    p - left.max(right)
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

/// Zig-zag (hysteresis) detector: alternating maxima and minima such that
/// every drop from a maximum to the next minimum, and every rise from a
/// minimum to the next maximum, is at least `threshold`. O(n). Each returned
/// swing is a maximum with the minima on both sides; a final maximum whose
/// drop never completes is not an event.
pub fn zigzag(x: &[f64], threshold: f64) -> Vec<Swing> {
    enum State {
        /// Before the first rise of `threshold`: tracking the lowest point.
        Start,
        /// Rising: tracking the candidate maximum.
        Up,
        /// Falling after a confirmed maximum: tracking the minimum.
        Down,
    }
    let mut swings = Vec::new();
    if x.len() < 3 || threshold <= 0.0 {
        return swings;
    }
    let (mut state, mut lo, mut hi, mut last_min) = (State::Start, 0, 0, 0);
    for i in 1..x.len() {
        match state {
            State::Start => {
                if x[i] < x[lo] {
                    lo = i;
                }
                if x[i] - x[lo] >= threshold {
                    (state, hi, last_min) = (State::Up, i, lo);
                }
            }
            State::Up => {
                if x[i] > x[hi] {
                    hi = i;
                }
                if x[hi] - x[i] >= threshold {
                    (state, lo) = (State::Down, i);
                }
            }
            State::Down => {
                if x[i] < x[lo] {
                    lo = i;
                }
                if x[i] - x[lo] >= threshold {
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
}
