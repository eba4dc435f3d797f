//! A whole trace: cleaning, stroke segmentation, per-segment features, μ,
//! the instrument's own μ, and velocity steps. One stroke's features are
//! in [`super::stroke`], the doubts they can carry in [`super::doubts`].

pub use super::doubts::MU_PLAUSIBLE_MAX;
pub use super::rows::{FrictionRow, StickSlipRow};

use super::cycles::CycleInputs;
use super::motion::{trace_cycles, Motion, MotionChannels, TraceCycles};
use super::params::{FrictionParams, StrokeMode};
use super::rows::TraceView;
use super::sample::SampleInfo;
use super::steps::{self, StepRow};
use super::stroke::analyse_stroke;
use crate::ingest::trace::Trace;
use std::borrow::Cow;

use crate::signal::{scan, segment, select, stats};
use crate::status::{Code, Status};

/// Everything extracted from one trace.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct TraceFeatures {
    /// One row per segment.
    pub segments: Vec<FrictionRow>,
    /// One row per velocity step.
    pub steps: Vec<(String, StepRow)>,
    /// One row per stick-slip event.
    pub events: Vec<StickSlipRow>,
    /// The strokes or laps.
    pub cycles: TraceCycles,
}

fn invalid(section: &str, n: usize, status: Status) -> FrictionRow {
    FrictionRow {
        section: section.to_string(),
        n_samples: n,
        status,
        ..Default::default()
    }
}

/// Analyses one trace. Never fails: a trace that cannot be analysed gives a
/// row whose status says why, with null values.
pub fn analyse_trace(trace: &Trace, sample: &SampleInfo, p: &FrictionParams) -> TraceFeatures {
    analyse_trace_with(trace, sample, p, &Motion::default())
}

/// [`analyse_trace`], knowing what the header and manifest say about the
/// motion (a crank, a track radius): its strokes or laps too.
pub fn analyse_trace_with<'t>(
    trace: &'t Trace,
    sample: &SampleInfo,
    p: &FrictionParams,
    motion: &Motion,
) -> TraceFeatures {
    let mut out = TraceFeatures::default();
    let keep = finite_samples(trace);
    let pick = |v: &'t [f64]| -> Cow<'t, [f64]> {
        match &keep {
            None => Cow::Borrowed(v),
            Some(k) => Cow::Owned(k.iter().map(|&i| v[i]).collect()),
        }
    };
    let t = pick(&trace.time_s);
    let f = pick(&trace.friction_n);
    let normal = trace.normal_n.as_deref().map(pick);
    let cof = trace.instrument_cof.as_deref().map(pick);
    let mut view = TraceView {
        section: &trace.section,
        from_cof: trace.friction_from_cof,
        t: &t,
        f: &f,
        normal: normal.as_deref(),
        cof: cof.as_deref(),
        n_nan: keep.as_ref().map_or(0, |k| trace.len() - k.len()),
        noise: None,
    };
    let strokes = match sliding_strokes(&mut view, keep.as_deref(), p) {
        Ok(strokes) => strokes,
        Err(status) => {
            out.segments.push(FrictionRow {
                n_nan_dropped: view.n_nan,
                ..invalid(&trace.section, t.len(), status)
            });
            return out;
        }
    };
    for (k, (range, sign)) in strokes.iter().cloned().enumerate() {
        let (row, events) = analyse_stroke(&view, sample, p, k + 1, range, sign);
        out.events.extend(events.into_iter().map(|e| StickSlipRow {
            section: trace.section.clone(),
            stroke: k + 1,
            event: e,
        }));
        out.segments.push(row);
    }

    // Velocity steps, when the trace tells the sliding speed.
    let velocity = trace.velocity_m_per_s.as_deref().map(&pick);
    let position = trace.position_m.as_deref().map(&pick);
    if let Some(speed) = steps::speed(&t, velocity.as_deref(), position.as_deref()) {
        let step = trace.step.as_deref().map(&pick);
        for s in steps_of(&view, &speed, step.as_deref(), sample, p) {
            out.steps.push((trace.section.clone(), s));
        }
    }
    let laps = trace.laps.as_deref().map(&pick);
    let angle = trace.angle_rad.as_deref().map(&pick);
    let wear = trace.wear_depth_m.as_deref().map(&pick);
    let channels = MotionChannels {
        position_m: position.as_deref(),
        velocity_m_per_s: velocity.as_deref(),
        laps: laps.as_deref(),
        angle_rad: angle.as_deref(),
    };
    let inputs = CycleInputs {
        section: view.section,
        time_s: view.t,
        friction_n: view.f,
        normal_n: view.normal,
        normal_const_n: sample.normal_force_n,
        cof: view.cof,
        wear_m: wear.as_deref(),
        path: None,
    };
    out.cycles = trace_cycles(inputs, &strokes, &out.segments, &channels, motion);
    out
}

/// The samples whose time and force are both finite, or `None` when all
/// are (the trace is then analysed in place, not copied).
fn finite_samples(trace: &Trace) -> Option<Vec<usize>> {
    let n = trace.len();
    let all = scan::all_finite(&[&trace.time_s[..n], &trace.friction_n[..n]]);
    let finite = |i: usize| trace.time_s[i].is_finite() && trace.friction_n[i].is_finite();
    (!all).then(|| (0..n).filter(|&i| finite(i)).collect())
}

/// The strokes of a trace that can be analysed (setting the view's noise
/// band), or the status that says why it cannot: refused as a whole, or no
/// sliding phase at all.
fn sliding_strokes(
    view: &mut TraceView,
    keep: Option<&[usize]>,
    p: &FrictionParams,
) -> Result<Strokes, Status> {
    if let Some(status) = refusal(view, keep, p) {
        return Err(status);
    }
    let (strokes, noise) = strokes_of(view.f, p);
    view.noise = noise;
    if strokes.is_empty() {
        return Err(Status::of(
            Code::NoSlidingPhase,
            "the friction force never leaves the noise band around zero",
        ));
    }
    Ok(strokes)
}

/// Why a whole trace cannot be analysed: too few samples, or time that does
/// not increase (naming the file's sample).
fn refusal(v: &TraceView, keep: Option<&[usize]>, p: &FrictionParams) -> Option<Status> {
    let t = v.t;
    if t.len() < p.min_samples {
        return Some(Status::of(
            Code::TooFewSamples,
            format!("{} valid samples, need at least {}", t.len(), p.min_samples),
        ));
    }
    if let Some(i) = scan::first_pair(t, |a, b| b <= a) {
        return Some(Status::of(
            Code::NonMonotonicTime,
            format!(
                "time does not increase at sample {} ({} s after {} s)",
                keep.map_or(i + 1, |k| k[i + 1]) + 1,
                t[i + 1],
                t[i]
            ),
        ));
    }
    None
}

/// Sample ranges with their direction sign.
type Strokes = Vec<(std::ops::Range<usize>, f64)>;

/// The strokes (sample range, direction sign): the whole trace when strokes
/// are off, else the runs of one sign out of the dead band, the short ones
/// dropped; and the force's noise σ when the dead band needed it.
fn strokes_of(f: &[f64], p: &FrictionParams) -> (Strokes, Option<f64>) {
    match p.strokes {
        StrokeMode::Off => {
            let sign = if stats::mean(f).unwrap_or(0.0) < 0.0 {
                -1.0
            } else {
                1.0
            };
            (vec![(0..f.len(), sign)], None)
        }
        StrokeMode::Auto => {
            let abs = select::Values {
                positions: f.len(),
                read: |r: std::ops::Range<usize>| f[r].iter().map(|v| v.abs()),
            };
            let (level, noise) = rayon::join(
                || select::median(&abs, f.len()).unwrap_or(0.0),
                || stats::noise_sigma(f).unwrap_or(0.0),
            );
            let deadband = (3.0 * noise).max(0.05 * level);
            let runs = segment::strokes(f, deadband, p.min_samples);
            let longest = runs.iter().map(|(r, _)| r.len()).max().unwrap_or(0);
            let min_len = ((p.min_stroke_fraction * longest as f64) as usize).max(p.min_samples);
            let kept = runs.into_iter().filter(|(r, _)| r.len() >= min_len);
            (kept.collect(), Some(noise))
        }
    }
}

/// The velocity steps of a trace with a speed: the file's own steps when it
/// numbers them, else those detected from the speed; μ and the normal force
/// from the trace or the manifest.
fn steps_of(
    v: &TraceView,
    speed: &[f64],
    step: Option<&[f64]>,
    sample: &SampleInfo,
    p: &FrictionParams,
) -> Vec<StepRow> {
    let normal_n: Option<Cow<[f64]>> = match (v.normal, sample.normal_force_n) {
        (Some(n), _) => Some(Cow::Borrowed(n)),
        (None, Some(n)) if n > 0.0 => Some(Cow::Owned(vec![n; v.f.len()])),
        _ => None,
    };
    let mu: Option<Vec<f64>> = normal_n
        .as_ref()
        .map(|n| v.f.iter().zip(n.iter()).map(|(t, n)| t.abs() / n).collect());
    let inputs = steps::StepInputs {
        time_s: v.t,
        speed,
        mu: mu.as_deref(),
        normal_n: normal_n.as_deref(),
        step,
    };
    steps::steps(&inputs, p)
}

#[cfg(test)]
#[path = "trace_tests.rs"]
mod tests;
