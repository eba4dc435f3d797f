//! The observer of a run (MODELS.md §7): T(t) = T_vec · v̂, its static peak
//! (the running maximum when T first drops by `drop_fraction` below it), the
//! time average over the second half of the sliding window, and the
//! decimated curve.

use super::control::RunControl;
use super::driver::RunObserver;

/// Tracks T(t): the static peak, the dynamic average, the decimated curve.
pub struct PeakObserver {
    /// Unit vector of the sliding direction.
    dir: (f64, f64),
    drop: f64,
    sliding_time: f64,
    interval: f64,
    next_sample: f64,
    prev: (f64, f64),
    tmax: f64,
    tmax_time: f64,
    /// (t_peak, T_max) once the static peak is seen.
    pub peak: Option<(f64, f64)>,
    /// ∫ T dt over the second half of the sliding window \[N s\].
    pub integral: f64,
    /// The time of that window the integral covers \[s\]: less than the
    /// half window when the peak was recognised (T fell below the drop
    /// threshold) after the window had begun.
    pub covered: f64,
    /// Decimated curve (t, T).
    pub curve: Vec<(f64, f64)>,
}

impl PeakObserver {
    /// An observer of T along `dir` with `c`'s peak, window and curve settings.
    pub fn new(c: &RunControl, dir: (f64, f64)) -> Self {
        PeakObserver {
            dir,
            drop: c.drop_fraction,
            sliding_time: c.sliding_time,
            interval: c.curve_interval,
            next_sample: 0.0,
            prev: (0.0, 0.0),
            tmax: 0.0,
            tmax_time: 0.0,
            peak: None,
            integral: 0.0,
            covered: 0.0,
            curve: Vec::new(),
        }
    }

    /// T is taken as linear between observations.
    fn observe_along(&mut self, t: f64, f: f64) {
        let (t0, f0) = self.prev;
        let lerp = |s: f64| {
            if t > t0 {
                f0 + (f - f0) * (s - t0) / (t - t0)
            } else {
                f
            }
        };
        if self.interval > 0.0 {
            while self.next_sample <= t && self.curve.len() < 1_000_000 {
                self.curve.push((self.next_sample, lerp(self.next_sample)));
                self.next_sample = self.curve.len() as f64 * self.interval;
            }
        }
        match self.peak {
            None => {
                if f > self.tmax {
                    self.tmax = f;
                    self.tmax_time = t;
                } else if self.tmax > 0.0 && f < (1.0 - self.drop) * self.tmax {
                    self.peak = Some((self.tmax_time, self.tmax));
                }
            }
            Some((tp, _)) => {
                let (a, b) = (tp + 0.5 * self.sliding_time, tp + self.sliding_time);
                let (lo, hi) = (t0.max(a), t.min(b));
                if hi > lo {
                    self.integral += 0.5 * (lerp(lo) + lerp(hi)) * (hi - lo);
                    self.covered += hi - lo;
                }
            }
        }
        self.prev = (t, f);
    }
}

impl RunObserver for PeakObserver {
    fn observe(&mut self, t: f64, (tx, ty): (f64, f64)) {
        self.observe_along(t, tx * self.dir.0 + ty * self.dir.1);
    }

    fn done(&self, t: f64) -> bool {
        matches!(self.peak, Some((tp, _)) if t >= tp + self.sliding_time)
    }
}
