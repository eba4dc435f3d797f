//! Features of one segment of a friction trace (a stroke, or a whole
//! unidirectional trace), on |T| (MODELS.md §1):
//! - the static peak T_s: the first maximum whose prominence exceeds both
//!   `peak_noise_factor` × σ_noise and `peak_min_relative` × the median level,
//!   found on a running median so that a one-sample spike cannot be it;
//! - the dynamic plateau: the steady-sliding window after the static peak,
//!   from where a running mean first settles within `plateau_tolerance` of
//!   the plateau level, to the end less `end_trim_fraction`;
//! - stick-slip events: saw-tooth maxima followed by a drop of at least
//!   `stickslip_noise_factor` × σ_noise and `stickslip_min_relative` × level,
//!   faster than the rise before it, between the static peak and the end of
//!   the plateau.

use std::ops::Range;

use super::params::FrictionParams;
use crate::signal::{filter, peaks, segment, stats};

/// The detachment peak.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StaticPeak {
    /// Sample index within the segment.
    pub index: usize,
    /// Time, s.
    pub time_s: f64,
    /// |T| at the peak, N.
    pub force_n: f64,
    /// Prominence, N.
    pub prominence_n: f64,
}

/// The steady-sliding window.
#[derive(Debug, Clone, PartialEq)]
pub struct Plateau {
    /// Sample range within the segment.
    pub range: Range<usize>,
    /// Start time, s.
    pub start_s: f64,
    /// End time, s.
    pub end_s: f64,
    /// Mean |T|, N.
    pub mean_n: f64,
    /// Sample sd of |T|, N.
    pub sd_n: f64,
}

/// One stick-slip event.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StickSlipEvent {
    /// Time of the peak, s.
    pub peak_time_s: f64,
    /// |T| at the peak, N.
    pub peak_force_n: f64,
    /// Drop from the peak to the following minimum, N.
    pub drop_n: f64,
    /// Duration of the stick (rise from the previous minimum), s.
    pub rise_time_s: f64,
    /// Duration of the slip (drop), s.
    pub drop_time_s: f64,
    /// Time since the previous event's peak, s (`None` for the first).
    pub period_s: Option<f64>,
}

/// The first prominent peak of the filtered |T| before the trimmed end,
/// taken at the raw maximum near it unless that is a spike.
fn static_peak(
    t: &[f64],
    x: &[f64],
    xf: &[f64],
    trim: usize,
    (noise, level): (f64, f64),
    p: &FrictionParams,
) -> Option<StaticPeak> {
    let n = x.len();
    let threshold = (p.peak_noise_factor * noise).max(p.peak_min_relative * level.abs());
    let searchable = &xf[..n - trim.min(n)];
    let (i, prom) = peaks::first_prominent_peak(searchable, threshold.max(f64::MIN_POSITIVE))?;
    let h = p.median_window / 2;
    let (lo, hi) = (i.saturating_sub(h), (i + h + 1).min(n));
    let (j, raw) = (lo..hi)
        .map(|j| (j, x[j]))
        .max_by(|a, b| a.1.total_cmp(&b.1))
        .expect("non-empty");
    let spike = raw - xf[i] > (3.0 * noise).max(p.peak_min_relative * level.abs());
    let (index, force_n) = if spike { (i, xf[i]) } else { (j, raw) };
    Some(StaticPeak {
        index,
        time_s: t[index],
        force_n,
        prominence_n: prom,
    })
}

/// Features of one segment.
#[derive(Debug, Clone, PartialEq)]
pub struct SegmentFeatures {
    /// White-noise σ of |T|, N.
    pub noise_n: f64,
    /// Median |T|, N.
    pub level_n: f64,
    /// The static peak, if there is a prominent one.
    pub static_peak: Option<StaticPeak>,
    /// The steady-sliding window, if there is one.
    pub plateau: Option<Plateau>,
    /// Stick-slip events after the static peak.
    pub events: Vec<StickSlipEvent>,
}

/// Extracts the features of a segment: times `t` (s, increasing) and
/// magnitudes `x` = |T| (N), both finite.
pub fn segment_features(t: &[f64], x: &[f64], p: &FrictionParams) -> SegmentFeatures {
    segment_features_with(t, x, p, None)
}

/// [`segment_features`], given the noise σ of `x` when it is already known.
pub(super) fn segment_features_with(
    t: &[f64],
    x: &[f64],
    p: &FrictionParams,
    noise: Option<f64>,
) -> SegmentFeatures {
    let n = x.len();
    let (xf, noise) = rayon::join(
        || filter::median_filter(x, p.median_window),
        || noise.unwrap_or_else(|| stats::noise_sigma(x).unwrap_or(0.0)),
    );
    let level = stats::median(&xf).unwrap_or(0.0);

    // A maximum in the trimmed end cannot be the detachment: its right side
    // is cut off (and it is the approach of the next reversal).
    let trim = (p.end_trim_fraction * n as f64) as usize;
    let static_peak = static_peak(t, x, &xf, trim, (noise, level), p);

    let from = static_peak.map_or(0, |s| s.index + 1);
    let w = ((p.plateau_window_fraction * n as f64) as usize).max(3);
    let tol = (p.plateau_tolerance * level.abs()).max(3.0 * noise / (w as f64).sqrt());
    let plateau =
        segment::steady_window(&xf, from, w, tol, trim, (p.min_samples / 2).max(3)).map(|r| {
            let (mean_n, sd_n) = stats::mean_sd(&x[r.clone()]).unwrap_or((f64::NAN, None));
            Plateau {
                start_s: t[r.start],
                end_s: t[r.end - 1],
                mean_n,
                sd_n: sd_n.unwrap_or(0.0),
                range: r,
            }
        });

    let ss_threshold =
        (p.stickslip_noise_factor * noise).max(p.stickslip_min_relative * level.abs());
    // Events belong to steady sliding: from the static peak to the end of
    // the plateau (a stop at the end of a stroke is not a slip).
    let end = plateau
        .as_ref()
        .map_or(n.saturating_sub(trim), |p| p.range.end);
    let start = static_peak.map_or(0, |s| s.index).min(end);
    let swings = peaks::zigzag(&xf[start..end], ss_threshold);
    // Locate on the filtered signal; measure on the raw one near there, so
    // that the filter's rounding of the sharp corners does not bias drops.
    let h = p.median_window / 2;
    let near = |i: usize, better: fn(f64, f64) -> bool| {
        (i.saturating_sub(h)..(i + h + 1).min(n))
            .fold(i, |b, j| if better(x[j], x[b]) { j } else { b })
    };
    let mut events: Vec<StickSlipEvent> = Vec::with_capacity(swings.len());
    for s in swings {
        let k = near(start + s.peak, |a, b| a > b);
        let a = near(start + s.after, |a, b| a < b);
        let b = near(start + s.before, |a, b| a < b);
        // A slip is fast: a drop slower than its stick is a relaxation.
        if t[a] - t[k] > t[k] - t[b] {
            continue;
        }
        events.push(StickSlipEvent {
            peak_time_s: t[k],
            peak_force_n: x[k],
            drop_n: x[k] - x[a],
            rise_time_s: t[k] - t[b],
            drop_time_s: t[a] - t[k],
            period_s: events.last().map(|e| t[k] - e.peak_time_s),
        });
    }
    SegmentFeatures {
        noise_n: noise,
        level_n: level,
        static_peak,
        plateau,
        events,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::signal::testing::gaussian_noise;

    fn times(n: usize, dt: f64) -> Vec<f64> {
        (0..n).map(|i| i as f64 * dt).collect()
    }

    /// A sled trace: linear loading to a detachment peak of 12 N at t = 1 s,
    /// a drop to a 10 N plateau, plus σ = 0.05 N noise and one 30 N spike
    /// during loading. The spike must not be the static peak, and the
    /// plateau mean must be 10 N within 3σ/√n.
    #[test]
    fn static_peak_and_plateau_of_a_noisy_sled_trace() {
        let n = 3000;
        let t = times(n, 1e-3);
        let noise = gaussian_noise(n, 0.05, 1);
        let mut x: Vec<f64> = t
            .iter()
            .zip(&noise)
            .map(|(&t, e)| {
                let clean = if t <= 1.0 {
                    12.0 * t
                } else if t < 1.1 {
                    12.0 - 20.0 * (t - 1.0)
                } else {
                    10.0
                };
                clean + e
            })
            .collect();
        x[400] = 30.0;
        let f = segment_features(&t, &x, &FrictionParams::default());
        let sp = f.static_peak.expect("a static peak");
        assert!((sp.time_s - 1.0).abs() < 0.01, "{sp:?}");
        assert!((sp.force_n - 12.0).abs() < 0.2, "{sp:?}");
        let pl = f.plateau.expect("a plateau");
        assert!(pl.start_s >= 1.1 - 0.02 && pl.start_s < 1.3, "{pl:?}");
        let se = 0.05 / (pl.range.len() as f64).sqrt();
        assert!((pl.mean_n - 10.0).abs() < 4.0 * se, "{pl:?}");
        assert!(f.events.is_empty(), "{:?}", f.events);
    }

    /// A saw-tooth of 8 teeth (rise 9 → 11 N over 0.1 s, instantaneous drop)
    /// with small noise: 8 events... the last tooth is cut by the end trim,
    /// so at least 6 are found, each with a 2 N drop and a 0.1 s period.
    #[test]
    fn stick_slip_teeth_are_counted_with_their_drops() {
        let dt = 1e-3;
        let mut x = Vec::new();
        for _ in 0..8 {
            for k in 0..100 {
                x.push(9.0 + 2.0 * k as f64 / 100.0);
            }
        }
        let noise = gaussian_noise(x.len(), 0.01, 3);
        let x: Vec<f64> = x.iter().zip(&noise).map(|(a, b)| a + b).collect();
        let t = times(x.len(), dt);
        let p = FrictionParams {
            end_trim_fraction: 0.0,
            ..Default::default()
        };
        let f = segment_features(&t, &x, &p);
        assert!(f.events.len() >= 6, "{}", f.events.len());
        for e in &f.events {
            assert!((e.drop_n - 2.0).abs() < 0.1, "{e:?}");
            if let Some(period) = e.period_s {
                assert!((period - 0.1).abs() < 0.005, "{e:?}");
            }
        }
    }

    /// Shifting time shifts every detected time by the same amount.
    #[test]
    fn time_shift_moves_features_by_the_shift() {
        let n = 1000;
        let t = times(n, 1e-3);
        let x: Vec<f64> = t
            .iter()
            .map(|&t| {
                if t < 0.3 {
                    20.0 * t
                } else {
                    5.0 + (t * 40.0).sin() * 0.01
                }
            })
            .collect();
        let a = segment_features(&t, &x, &FrictionParams::default());
        let shifted: Vec<f64> = t.iter().map(|v| v + 100.0).collect();
        let b = segment_features(&shifted, &x, &FrictionParams::default());
        let (sa, sb) = (a.static_peak.unwrap(), b.static_peak.unwrap());
        assert_eq!(sa.index, sb.index);
        // 100 s added to ~0.3 s: the difference is exact to a few ulps of 100.
        assert!((sb.time_s - sa.time_s - 100.0).abs() < 1e-12);
    }
}
