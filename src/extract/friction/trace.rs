//! A whole trace: cleaning, stroke segmentation, per-segment features, μ,
//! the instrument's own μ, and velocity steps. One stroke's features are
//! in [`super::stroke`], the doubts they can carry in [`super::doubts`].

pub use super::doubts::MU_PLAUSIBLE_MAX;
pub use super::rows::{FrictionRow, StickSlipRow, TraceFeatures};

use super::params::{FrictionParams, StrokeMode};
use super::rows::TraceView;
use super::sample::SampleInfo;
use super::steps::{self, StepRow};
use super::stroke::analyse_stroke;
use crate::ingest::trace::Trace;
use std::borrow::Cow;

use crate::signal::{scan, segment, select, stats};
use crate::status::{Code, Status};

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
pub fn analyse_trace<'t>(
    trace: &'t Trace,
    sample: &SampleInfo,
    p: &FrictionParams,
) -> TraceFeatures {
    let mut out = TraceFeatures::default();
    // Drop samples whose time or force is NaN; count them. A trace without
    // any is analysed in place, not copied.
    let finite = |i: usize| trace.time_s[i].is_finite() && trace.friction_n[i].is_finite();
    let n = trace.len();
    let all = scan::all_finite(&[&trace.time_s[..n], &trace.friction_n[..n]]);
    let keep: Option<Vec<usize>> = (!all).then(|| (0..n).filter(|&i| finite(i)).collect());
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
    let strokes = match refusal(&view, keep.as_deref(), p) {
        None => {
            let (strokes, noise) = strokes_of(&f, p);
            view.noise = noise;
            strokes
        }
        Some(status) => {
            out.segments.push(FrictionRow {
                n_nan_dropped: view.n_nan,
                ..invalid(&trace.section, t.len(), status)
            });
            return out;
        }
    };
    if strokes.is_empty() {
        let status = Status::of(
            Code::NoSlidingPhase,
            "the friction force never leaves the noise band around zero",
        );
        out.segments.push(FrictionRow {
            n_nan_dropped: view.n_nan,
            ..invalid(&trace.section, t.len(), status)
        });
        return out;
    }
    for (k, (range, sign)) in strokes.into_iter().enumerate() {
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
    out
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
mod tests {
    use super::super::doubts::{doubt_early_peak, doubt_static_below_dynamic};
    use super::*;

    fn trace(t: Vec<f64>, f: Vec<f64>, n: Option<Vec<f64>>) -> Trace {
        Trace {
            section: "1".into(),
            time_s: t,
            friction_n: f,
            friction_from_cof: false,
            normal_n: n,
            velocity_m_per_s: None,
            position_m: None,
            temperature_k: None,
            instrument_cof: None,
            step: None,
            columns: Default::default(),
            normal_flipped: false,
        }
    }

    /// A long reciprocating trace with noise (strokes of 125 000 samples:
    /// several chunks of every parallel pass, the selections' bracket, the
    /// lane sums, the scans) gives the same rows and
    /// events, bit for bit, on one thread and on three.
    #[test]
    fn long_trace_rows_do_not_depend_on_the_thread_count() {
        let n = 600_000;
        let noise = crate::signal::testing::gaussian_noise(n, 0.01, 5);
        let t: Vec<f64> = (0..n).map(|i| i as f64 * 1e-4).collect();
        let f: Vec<f64> = t
            .iter()
            .zip(&noise)
            .map(|(t, e)| (t * 0.25).sin().signum() * (1.0 + 0.05 * (t * 70.0).fract()) + e)
            .collect();
        let load: Vec<f64> = noise.iter().map(|e| 2.0 + 0.1 * e).collect();
        let tr = trace(t, f, Some(load));
        let run = |threads: usize| {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap();
            let out = pool
                .install(|| analyse_trace(&tr, &SampleInfo::default(), &FrictionParams::default()));
            let strokes = out.segments.len();
            (strokes, format!("{:?} {:?}", out.segments, out.events))
        };
        let one = run(1);
        assert!(one.0 >= 4 && one.1.contains("mu_dynamic: Some("), "{one:?}");
        assert_eq!(one, run(3));
    }

    fn ramp_plateau(n: usize) -> (Vec<f64>, Vec<f64>) {
        let t: Vec<f64> = (0..n).map(|i| i as f64 * 0.01).collect();
        let f = t
            .iter()
            .map(|&t| {
                if t < 0.5 {
                    4.0 * t
                } else if t < 0.6 {
                    2.0 - 5.0 * (t - 0.5)
                } else {
                    1.5
                }
            })
            .collect();
        (t, f)
    }

    /// Doubts are statuses: a static peak at the edge of its segment, or
    /// below the plateau, is flagged; a clean ramp and break-away is `ok`.
    #[test]
    fn doubtful_static_peaks_are_flagged() {
        let sample = SampleInfo {
            normal_force_n: Some(2.0),
            ..Default::default()
        };
        let (t, f) = ramp_plateau(300);
        let ok = analyse_trace(&trace(t, f, None), &sample, &FrictionParams::default());
        let row = &ok.segments[0];
        assert!(row.status.is_ok(), "{}", row.status);
        let mut notes = Status::ok();
        doubt_early_peak(1, &mut notes);
        assert!(notes.has(Code::PeakAtStart), "{notes}");
        let mut late = Status::ok();
        doubt_early_peak(50, &mut late);
        doubt_static_below_dynamic(row, &mut late);
        assert!(late.is_ok(), "{late}");
        let mut doubted = row.clone();
        (doubted.mu_static, doubted.mu_dynamic) = (Some(0.5), Some(0.75));
        doubt_static_below_dynamic(&doubted, &mut notes);
        assert!(notes.has(Code::StaticBelowDynamic), "{notes}");
    }

    #[test]
    fn empty_and_tiny_traces_get_a_status() {
        let out = analyse_trace(
            &trace(vec![], vec![], None),
            &SampleInfo::default(),
            &FrictionParams::default(),
        );
        assert_eq!(out.segments.len(), 1);
        assert!(out.segments[0].status.has(Code::TooFewSamples));
        assert!(out.segments[0].mu_dynamic.is_none());
    }

    /// NaN samples are dropped and counted; the features are those of the
    /// clean trace.
    #[test]
    fn nan_samples_are_dropped_and_counted() {
        let (t, mut f) = ramp_plateau(300);
        let clean = analyse_trace(
            &trace(t.clone(), f.clone(), Some(vec![3.0; 300])),
            &SampleInfo::default(),
            &FrictionParams::default(),
        );
        f[150] = f64::NAN;
        f[200] = f64::NAN;
        let out = analyse_trace(
            &trace(t, f, Some(vec![3.0; 300])),
            &SampleInfo::default(),
            &FrictionParams::default(),
        );
        let (a, b) = (&clean.segments[0], &out.segments[0]);
        assert_eq!(b.n_nan_dropped, 2);
        assert!(b.status.is_ok(), "{}", b.status);
        // Dropping two plateau samples of a constant plateau changes nothing.
        assert!((a.mu_dynamic.unwrap() - b.mu_dynamic.unwrap()).abs() < 1e-12);
        assert!((a.mu_static.unwrap() - b.mu_static.unwrap()).abs() < 1e-12);
        assert!(
            (b.mu_static.unwrap() - 2.0 / 3.0).abs() < 0.02,
            "peak of 2 N at 3 N"
        );
    }

    #[test]
    fn non_monotonic_time_is_reported_with_the_sample() {
        let (mut t, f) = ramp_plateau(100);
        t[40] = t[38];
        let out = analyse_trace(
            &trace(t, f, None),
            &SampleInfo::default(),
            &FrictionParams::default(),
        );
        assert!(out.segments[0]
            .status
            .to_string()
            .starts_with("non_monotonic_time: time does not increase at sample 41"));
    }

    #[test]
    fn a_trace_that_never_slides_has_no_sliding_phase() {
        let t: Vec<f64> = (0..200).map(|i| i as f64).collect();
        let out = analyse_trace(
            &trace(t, vec![0.0; 200], None),
            &SampleInfo::default(),
            &FrictionParams::default(),
        );
        assert!(
            out.segments[0].status.has(Code::NoSlidingPhase),
            "{}",
            out.segments[0].status
        );
    }

    /// Zero and negative loads: μ is null with a status, never ±inf.
    #[test]
    fn zero_and_negative_normal_force_give_no_mu() {
        let (t, f) = ramp_plateau(300);
        for n in [0.0, -2.0] {
            let out = analyse_trace(
                &trace(t.clone(), f.clone(), Some(vec![n; 300])),
                &SampleInfo::default(),
                &FrictionParams::default(),
            );
            let s = &out.segments[0];
            assert!(s.mu_static.is_none() && s.mu_dynamic.is_none());
            assert!(s.status.has(Code::NonpositiveNormalForce), "{}", s.status);
        }
        let out = analyse_trace(
            &trace(t, f, None),
            &SampleInfo::default(),
            &FrictionParams::default(),
        );
        assert!(out.segments[0].status.has(Code::NoNormalForce));
        assert!((out.segments[0].dynamic_force_n.unwrap() - 1.5).abs() < 1e-12);
    }

    /// A load of 1e-300 N gives μ ~ 1e300: not a number to report.
    #[test]
    fn absurdly_small_normal_force_gives_a_status_not_a_number() {
        let (t, f) = ramp_plateau(300);
        let out = analyse_trace(
            &trace(t, f, Some(vec![1e-300; 300])),
            &SampleInfo::default(),
            &FrictionParams::default(),
        );
        let s = &out.segments[0];
        assert!(s.mu_static.is_none() && s.mu_dynamic.is_none(), "{s:?}");
        assert!(s.status.has(Code::AbsurdMagnitude), "{}", s.status);
        assert!(!s.status.is_ok());
    }

    /// A segment whose normal force ramps 2 → 6 N is flagged `load_ramp`
    /// (its window is part of a ramp); the same trace at a constant 3 N is
    /// not.
    #[test]
    fn a_ramping_load_flags_the_segment() {
        let (t, f) = ramp_plateau(300);
        let ramp: Vec<f64> = (0..300).map(|i| 2.0 + 4.0 * i as f64 / 299.0).collect();
        let p = FrictionParams::default();
        let out = analyse_trace(
            &trace(t.clone(), f.clone(), Some(ramp)),
            &SampleInfo::default(),
            &p,
        );
        assert!(
            out.segments[0].status.has(Code::LoadRamp),
            "{}",
            out.segments[0].status
        );
        let out = analyse_trace(
            &trace(t, f, Some(vec![3.0; 300])),
            &SampleInfo::default(),
            &p,
        );
        assert!(
            !out.segments[0].status.has(Code::LoadRamp),
            "{}",
            out.segments[0].status
        );
    }

    /// Scaling every force by 1e3 (N to mN read as N) leaves μ unchanged.
    #[test]
    fn mu_is_invariant_to_force_scale() {
        let (t, f) = ramp_plateau(300);
        let a = analyse_trace(
            &trace(t.clone(), f.clone(), Some(vec![3.0; 300])),
            &SampleInfo::default(),
            &FrictionParams::default(),
        );
        let f3: Vec<f64> = f.iter().map(|v| v * 1e3).collect();
        let b = analyse_trace(
            &trace(t, f3, Some(vec![3e3; 300])),
            &SampleInfo::default(),
            &FrictionParams::default(),
        );
        let (a, b) = (&a.segments[0], &b.segments[0]);
        assert!((a.mu_static.unwrap() - b.mu_static.unwrap()).abs() < 1e-12);
        assert!((a.mu_dynamic.unwrap() - b.mu_dynamic.unwrap()).abs() < 1e-12);
    }
}
