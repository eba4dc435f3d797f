//! Velocity steps of a stepped-velocity test (MODELS.md §1; thesis Ch. 3:
//! 8 velocities from 0.025 to 1 m/s): μ per step as the mean of |T|/N over
//! the steady part of the step, giving μ(v) for the ice fit.
//!
//! Where the file numbers its steps (a step or segment column, or one
//! section per step), the steps are the file's: two steps at close speeds
//! stay two steps. Otherwise they are detected from the speed. Either way a
//! step whose normal force changes steadily across it is a load ramp,
//! reported with its start and end load, not as a plateau.

use std::borrow::Cow;
use std::ops::Range;

use super::params::FrictionParams;
use super::stribeck::StribeckPoint;
use crate::signal::{filter, scan, segment, stats};
use crate::status::{Code, Status};

/// Where a step's bounds come from.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum StepSource {
    /// The file's step column: the steps are the file's.
    File,
    /// Detected from the sliding speed (`step_tolerance`).
    Speed,
}

impl StepSource {
    /// The stable text form, as in `friction_steps`.
    pub fn as_str(self) -> &'static str {
        match self {
            StepSource::File => "file",
            StepSource::Speed => "speed",
        }
    }
}

/// One velocity step.
#[derive(Debug, Clone, PartialEq)]
pub struct StepRow {
    /// The file's step number when it declares its steps, else the 1-based
    /// step within the section.
    pub step: usize,
    /// Where the step's bounds come from.
    pub source: StepSource,
    /// Median sliding speed over the steady part, m/s.
    pub velocity_m_per_s: f64,
    /// Start and end of the steady part, s.
    pub start_s: f64,
    /// End of the steady part, s.
    pub end_s: f64,
    /// The whole step, settling included: first and last sample, s.
    pub span_s: (f64, f64),
    /// Mean μ over the steady part (`None` without a normal force, or for
    /// a load ramp).
    pub mu_mean: Option<f64>,
    /// Sample sd of μ.
    pub mu_sd: Option<f64>,
    /// Samples in the steady part.
    pub n: usize,
    /// Mean normal force over the steady part, N (`None` for a load ramp).
    pub normal_force_n: Option<f64>,
    /// A load ramp's normal force at the step's first and last sample, N,
    /// from a straight line fitted over the step.
    pub ramp_n: Option<(f64, f64)>,
    /// The step on the Stribeck curve (filled from the manifest's
    /// lubricant by [`super::stribeck::stribeck_point`]).
    pub stribeck: StribeckPoint,
    /// `ok`, or `load_ramp` / `unsteady_speed` and why.
    pub status: Status,
}

/// The channels a step analysis reads, aligned sample by sample.
#[derive(Debug, Clone, Copy)]
pub struct StepInputs<'a> {
    /// Time, s.
    pub time_s: &'a [f64],
    /// Sliding speed, m/s (a magnitude).
    pub speed: &'a [f64],
    /// Pointwise |T|/N, when there is a normal force.
    pub mu: Option<&'a [f64]>,
    /// Normal force, N, when the trace has it (column or manifest).
    pub normal_n: Option<&'a [f64]>,
    /// The file's step number of each sample, when it declares its steps.
    pub step: Option<&'a [f64]>,
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

/// The steps of a trace: the file's when it numbers them, else detected
/// from the speed. Phases at rest (zero speed, such as the loading of a
/// sled) are not steps.
pub fn steps(inputs: &StepInputs, p: &FrictionParams) -> Vec<StepRow> {
    match inputs.step {
        Some(labels) => declared_steps(inputs, labels, p),
        None => velocity_steps(inputs, p),
    }
}

/// Steps detected from the speed: runs within `step_tolerance` of their
/// level, at least `step_min_samples` long, numbered 1, 2, …
fn velocity_steps(inputs: &StepInputs, p: &FrictionParams) -> Vec<StepRow> {
    let smooth = filter::median_filter(inputs.speed, (p.step_min_samples / 2) | 1);
    let abs_tol = 1e-3 * stats::median(&smooth).unwrap_or(0.0).abs() + f64::MIN_POSITIVE;
    segment::velocity_steps(&smooth, p.step_tolerance, abs_tol, p.step_min_samples)
        .into_iter()
        .filter_map(|r| step_row(inputs, r, StepSource::Speed, 0, p))
        .filter(|s| s.velocity_m_per_s > 0.0)
        .enumerate()
        .map(|(k, s)| StepRow { step: k + 1, ..s })
        .collect()
}

/// The file's steps: each run of one step number is a step, numbered as
/// the file numbers it (its ordinal when the number is not a whole number).
/// Samples without a step number belong to no step.
fn declared_steps(inputs: &StepInputs, labels: &[f64], p: &FrictionParams) -> Vec<StepRow> {
    let mut runs: Vec<(Range<usize>, f64)> = Vec::new();
    for (i, &l) in labels.iter().enumerate() {
        match runs.last_mut() {
            // Step numbers are labels: compared exactly.
            Some((r, last)) if last.to_bits() == l.to_bits() && r.end == i => r.end = i + 1,
            _ if l.is_finite() => runs.push((i..i + 1, l)),
            _ => {}
        }
    }
    runs.into_iter()
        .enumerate()
        .filter_map(|(k, (r, l))| {
            let number = if l >= 0.0 && l.fract() == 0.0 && l < 1e9 {
                l as usize
            } else {
                k + 1
            };
            step_row(inputs, r, StepSource::File, number, p)
        })
        .filter(|s| s.velocity_m_per_s > 0.0)
        .collect()
}

/// The row of one step over `range`: the steady part after the settle
/// fraction, its median speed and mean μ, and the load-ramp and
/// steady-speed checks. `None` when fewer than 2 samples remain.
fn step_row(
    inputs: &StepInputs,
    range: Range<usize>,
    source: StepSource,
    number: usize,
    p: &FrictionParams,
) -> Option<StepRow> {
    let skip = (p.step_settle_fraction * range.len() as f64) as usize;
    let steady = range.start + skip..range.end;
    if steady.len() < 2 {
        return None;
    }
    let t = inputs.time_s;
    let speed = &inputs.speed[steady.clone()];
    let velocity = stats::median(speed)?;
    let mut status = Status::ok();
    if source == StepSource::File {
        check_steady_speed(speed, velocity, p, &mut status);
    }
    let ramp = inputs
        .normal_n
        .and_then(|n| load_ramp(&t[range.clone()], &n[range.clone()], p));
    let m = inputs.mu.map(|m| &m[steady.clone()]);
    let mut row = StepRow {
        step: number,
        source,
        velocity_m_per_s: velocity,
        start_s: t[steady.start],
        end_s: t[steady.end - 1],
        span_s: (t[range.start], t[range.end - 1]),
        mu_mean: m.and_then(stats::mean),
        mu_sd: m.and_then(stats::sd),
        n: steady.len(),
        normal_force_n: inputs.normal_n.and_then(|n| finite_mean(&n[steady])),
        ramp_n: ramp,
        stribeck: StribeckPoint::default(),
        status: Status::ok(),
    };
    if let Some((a, b)) = ramp {
        status.push(
            Code::LoadRamp,
            format!(
                "the normal force ramps from {a:.4} N to {b:.4} N across the step: no plateau mean"
            ),
        );
        (row.mu_mean, row.mu_sd, row.normal_force_n) = (None, None, None);
    }
    row.status = status;
    Some(row)
}

fn finite_mean(x: &[f64]) -> Option<f64> {
    stats::mean(
        &x.iter()
            .copied()
            .filter(|v| v.is_finite())
            .collect::<Vec<_>>(),
    )
}

/// A declared step whose speed leaves the `step_tolerance` band around its
/// median over the steady part (a sweep, not a step).
fn check_steady_speed(speed: &[f64], level: f64, p: &FrictionParams, status: &mut Status) {
    let (lo, hi) = speed
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &v| {
            (lo.min(v), hi.max(v))
        });
    let band = p.step_tolerance * level.abs();
    if hi - level > band || level - lo > band {
        status.push(
            Code::UnsteadySpeed,
            format!(
                "the speed runs from {lo:.4e} to {hi:.4e} m/s within the step, beyond {} % of its median {level:.4e} m/s",
                100.0 * p.step_tolerance
            ),
        );
    }
}

/// A load ramp: the straight line fitted to the normal force over the whole
/// step changes by more than `load_ramp_fraction` of its mean from the
/// step's first to its last sample, and by more than 6 σ of the scatter
/// about the line (so noise on a plateau is no ramp). Returns the line's
/// values at the first and last sample.
pub(crate) fn load_ramp(t: &[f64], n: &[f64], p: &FrictionParams) -> Option<(f64, f64)> {
    // The finite pairs: the columns themselves when every pair is finite.
    let finite = |(a, b): (&f64, &f64)| a.is_finite() && b.is_finite();
    let len = t.len().min(n.len());
    let (tt, nn): (Cow<[f64]>, Cow<[f64]>) = match scan::all_finite(&[&t[..len], &n[..len]]) {
        true => (Cow::Borrowed(&t[..len]), Cow::Borrowed(&n[..len])),
        false => {
            let (tt, nn): (Vec<f64>, Vec<f64>) = t
                .iter()
                .zip(n)
                .filter(|p| finite(*p))
                .map(|(a, b)| (*a, *b))
                .unzip();
            (Cow::Owned(tt), Cow::Owned(nn))
        }
    };
    let stats::Line { a, b, mean_y } = stats::line_fit(&tt, &nn)?;
    let (first, last) = (a + b * tt[0], a + b * tt[tt.len() - 1]);
    let scatter = stats::sd_by(tt.len(), |i| nn[i] - (a + b * tt[i])).unwrap_or(0.0);
    let change = (last - first).abs();
    let level = mean_y.abs();
    (change > p.load_ramp_fraction * level && change > 6.0 * scatter).then_some((first, last))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn inputs<'a>(
        t: &'a [f64],
        speed: &'a [f64],
        mu: Option<&'a [f64]>,
        normal_n: Option<&'a [f64]>,
        step: Option<&'a [f64]>,
    ) -> StepInputs<'a> {
        StepInputs {
            time_s: t,
            speed,
            mu,
            normal_n,
            step,
        }
    }

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
        let rows = steps(
            &inputs(&t, &s, Some(&mu), None, None),
            &FrictionParams::default(),
        );
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
            assert_eq!(r.source, StepSource::Speed);
        }
    }

    /// Two steps at 100 and 105 mm/s (5 %, inside the 10 % tolerance):
    /// detected from the speed they merge into one; with the file's step
    /// column they are two rows, numbered as the file numbers them.
    #[test]
    fn declared_steps_at_close_speeds_stay_two() {
        let t: Vec<f64> = (0..200).map(|i| i as f64 * 0.1).collect();
        let v: Vec<f64> = (0..200)
            .map(|i| if i < 100 { 0.1 } else { 0.105 })
            .collect();
        let label: Vec<f64> = (0..200).map(|i| if i < 100 { 3.0 } else { 4.0 }).collect();
        let p = FrictionParams::default();
        assert_eq!(steps(&inputs(&t, &v, None, None, None), &p).len(), 1);
        let rows = steps(&inputs(&t, &v, None, None, Some(&label)), &p);
        assert_eq!(rows.len(), 2, "{rows:?}");
        assert_eq!((rows[0].step, rows[1].step), (3, 4));
        assert!((rows[0].velocity_m_per_s - 0.1).abs() < 1e-15);
        assert!((rows[1].velocity_m_per_s - 0.105).abs() < 1e-15);
        assert!(rows
            .iter()
            .all(|r| r.status.is_ok() && r.source == StepSource::File));
        // Steady part: the last 80 of 100 samples of each step.
        assert_eq!(rows[1].n, 80);
        assert!((rows[1].start_s - 12.0).abs() < 1e-12 && (rows[1].end_s - 19.9).abs() < 1e-12);
    }

    /// A step whose load rises 5 → 15 N is a ramp with those ends; a
    /// plateau with noise of ±1 % is not; a declared step that sweeps its
    /// speed is flagged.
    #[test]
    fn load_ramps_and_speed_sweeps_get_their_status() {
        let t: Vec<f64> = (0..101).map(|i| i as f64 * 0.1).collect();
        let v = vec![0.1; 101];
        let ramp: Vec<f64> = t.iter().map(|t| 5.0 + t).collect();
        let plateau: Vec<f64> = (0..101)
            .map(|i| 10.0 + if i % 2 == 0 { 0.1 } else { -0.1 })
            .collect();
        let mu = vec![0.2; 101];
        let label = vec![1.0; 101];
        let p = FrictionParams::default();
        let r = &steps(&inputs(&t, &v, Some(&mu), Some(&ramp), Some(&label)), &p)[0];
        assert!(r.status.has(Code::LoadRamp), "{}", r.status);
        let (a, b) = r.ramp_n.unwrap();
        assert!((a - 5.0).abs() < 1e-9 && (b - 15.0).abs() < 1e-9, "{a} {b}");
        assert!(r.mu_mean.is_none() && r.normal_force_n.is_none());
        let r = &steps(&inputs(&t, &v, Some(&mu), Some(&plateau), Some(&label)), &p)[0];
        assert!(r.status.is_ok(), "{}", r.status);
        assert!((r.normal_force_n.unwrap() - 10.0).abs() < 0.01);
        assert!((r.mu_mean.unwrap() - 0.2).abs() < 1e-12);
        let sweep: Vec<f64> = t.iter().map(|t| 0.05 + 0.01 * t).collect();
        let r = &steps(&inputs(&t, &sweep, None, None, Some(&label)), &p)[0];
        assert!(r.status.has(Code::UnsteadySpeed), "{}", r.status);
    }
}
