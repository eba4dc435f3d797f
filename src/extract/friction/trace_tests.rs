//! Tests of [`super`]: whole traces, their doubts and statuses.
use super::super::doubts::{doubt_early_peak, doubt_static_below_dynamic};
use super::*;

fn trace(t: Vec<f64>, f: Vec<f64>, n: Option<Vec<f64>>) -> Trace {
    Trace::of_forces(t, f, n)
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
        let out =
            pool.install(|| analyse_trace(&tr, &SampleInfo::default(), &FrictionParams::default()));
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
