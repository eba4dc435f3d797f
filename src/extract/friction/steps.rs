//! Velocity steps of a stepped-velocity test (MODELS.md §1; thesis Ch. 3:
//! 8 velocities from 0.025 to 1 m/s): μ per step as the mean of |T|/N over
//! the steady part of the step, giving μ(v) for the ice fit.

use super::params::FrictionParams;
use crate::signal::{filter, segment, stats};

/// One velocity step.
#[derive(Debug, Clone, PartialEq)]
pub struct StepRow {
    /// 1-based step number within the section.
    pub step: usize,
    /// Median sliding speed over the steady part, m/s.
    pub velocity_m_per_s: f64,
    /// Start and end of the steady part, s.
    pub start_s: f64,
    /// End of the steady part, s.
    pub end_s: f64,
    /// Mean μ over the steady part (`None` without a normal force).
    pub mu_mean: Option<f64>,
    /// Sample sd of μ.
    pub mu_sd: Option<f64>,
    /// Samples in the steady part.
    pub n: usize,
}

/// Sliding speed from a velocity channel, or from the derivative of the
/// position (central differences), as a magnitude.
pub fn speed(
    time_s: &[f64],
    velocity: Option<&[f64]>,
    position: Option<&[f64]>,
) -> Option<Vec<f64>> {
    if let Some(v) = velocity {
        return Some(v.iter().map(|v| v.abs()).collect());
    }
    let x = position?;
    let n = x.len();
    if n < 3 {
        return None;
    }
    let d: Vec<f64> = (0..n)
        .map(|i| {
            let (a, b) = (i.saturating_sub(1), (i + 1).min(n - 1));
            ((x[b] - x[a]) / (time_s[b] - time_s[a])).abs()
        })
        .collect();
    Some(d)
}

/// Splits a trace into velocity steps and averages μ over each step's
/// steady part. `mu` is the pointwise |T|/N (or `None`). Phases at rest
/// (zero speed, such as the loading of a sled) are not steps.
pub fn velocity_steps(
    time_s: &[f64],
    speed: &[f64],
    mu: Option<&[f64]>,
    p: &FrictionParams,
) -> Vec<StepRow> {
    let smooth = filter::median_filter(speed, (p.step_min_samples / 2) | 1);
    let abs_tol = 1e-3 * stats::median(&smooth).unwrap_or(0.0).abs() + f64::MIN_POSITIVE;
    segment::velocity_steps(&smooth, p.step_tolerance, abs_tol, p.step_min_samples)
        .into_iter()
        .enumerate()
        .filter_map(|(k, r)| {
            let skip = (p.step_settle_fraction * r.len() as f64) as usize;
            let steady = r.start + skip..r.end;
            if steady.len() < 2 {
                return None;
            }
            let m = mu.map(|m| &m[steady.clone()]);
            Some(StepRow {
                step: k + 1,
                velocity_m_per_s: stats::median(&speed[steady.clone()])?,
                start_s: time_s[steady.start],
                end_s: time_s[steady.end - 1],
                mu_mean: m.and_then(stats::mean),
                mu_sd: m.and_then(stats::sd),
                n: steady.len(),
            })
        })
        .collect::<Vec<_>>()
        .into_iter()
        .filter(|s| s.velocity_m_per_s > 0.0)
        .enumerate()
        .map(|(k, s)| StepRow { step: k + 1, ..s })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Position of a stepped test: 4 speeds, 100 samples each at 10 Hz; μ
    /// is 0.1 × step number. Steps, speeds and means are recovered exactly
    /// (the derivative of a piecewise-linear position is exact away from the
    /// corners, which the settle fraction leaves out).
    #[test]
    fn stepped_position_gives_the_steps() {
        let speeds = [0.025, 0.05, 0.1, 0.2];
        let (mut t, mut x, mut mu) = (vec![], vec![], vec![]);
        let mut pos = 0.0;
        for (k, v) in speeds.iter().enumerate() {
            for _ in 0..100 {
                t.push(t.len() as f64 * 0.1);
                x.push(pos);
                mu.push(0.1 * (k + 1) as f64);
                pos += v * 0.1;
            }
        }
        let s = speed(&t, None, Some(&x)).unwrap();
        let rows = velocity_steps(&t, &s, Some(&mu), &FrictionParams::default());
        assert_eq!(rows.len(), 4);
        for (k, r) in rows.iter().enumerate() {
            assert!(
                (r.velocity_m_per_s - speeds[k]).abs() < 1e-9 * speeds[k].max(1.0),
                "{r:?}"
            );
            assert!(
                (r.mu_mean.unwrap() - 0.1 * (k + 1) as f64).abs() < 1e-9,
                "{r:?}"
            );
        }
    }
}
