//! Tests of [`super`]: strokes and laps against closed forms.

use super::super::motion::{CycleSource, Motion};
use super::super::path::DistanceSource;
use super::super::{analyse_trace_with, FrictionParams, SampleInfo};
use super::*;
use crate::ingest::trace::Trace;

fn trace(t: Vec<f64>, f: Vec<f64>) -> Trace {
    let n = vec![2.0; t.len()];
    Trace::of_forces(t, f, Some(n))
}

/// A square friction loop: strokes of length L = 10 mm at F0 = 0.8 N,
/// the force +F0 going forward and −F0 going back, flipping while the
/// contact rests at each end (the end sample repeated). Each stroke's
/// energy is F0·L, each cycle's loop area ∮F dx = 2·F0·L, exactly (the
/// trapezoid rule is exact on a piecewise-constant force over a
/// piecewise-linear path): to 1e-9 relative.
#[test]
fn a_square_loop_has_the_closed_form_energy_and_area() {
    let (f0, l, per, cycles) = (0.8, 0.01, 200usize, 5usize);
    let (mut x, mut f) = (Vec::new(), Vec::new());
    for _ in 0..cycles {
        for dir in [1.0, -1.0] {
            for j in 0..=per {
                let s = j as f64 / per as f64 * l;
                x.push(if dir > 0.0 { s } else { l - s });
                f.push(dir * f0);
            }
        }
    }
    let t: Vec<f64> = (0..x.len()).map(|i| i as f64 * 1e-3).collect();
    let mut tr = trace(t, f);
    tr.position_m = Some(x);
    let out = analyse_trace_with(
        &tr,
        &SampleInfo::default(),
        &FrictionParams::default(),
        &Motion::default(),
    );
    let c = &out.cycles;
    assert_eq!(c.source, Some(CycleSource::Reversals));
    assert_eq!(c.distance, Some(DistanceSource::Position));
    assert_eq!(c.rows.len(), 2 * cycles);
    let close = |a: f64, b: f64| ((a - b) / b).abs() < 1e-9;
    for (k, r) in c.rows.iter().enumerate() {
        assert_eq!(r.stroke, Some(k + 1));
        assert!(close(r.energy_j.unwrap(), f0 * l), "{k}: {:?}", r.energy_j);
        let (a, b) = r.distance_m.unwrap();
        assert!((a - k as f64 * l).abs() < 1e-12 && (b - (k + 1) as f64 * l).abs() < 1e-12);
        match k % 2 {
            1 => assert!(close(r.loop_area_j.unwrap(), 2.0 * f0 * l)),
            _ => assert_eq!(r.loop_area_j, None),
        }
        // μ is the stroke row's: 0.8 N on 2 N.
        assert!((r.mu.unwrap() - 0.4).abs() < 1e-12);
        assert_eq!(r.mu, out.segments[k].mu_dynamic);
        assert_eq!(
            r.window_s,
            out.segments[k]
                .dynamic_window_start_s
                .zip(out.segments[k].dynamic_window_end_s)
        );
    }
    let total: f64 = c.rows.iter().map(|r| r.energy_j.unwrap()).sum();
    assert!(close(total, 2.0 * cycles as f64 * f0 * l));
}

/// A partial-slip (fretting) loop: the force follows the position with a
/// stiffness before the contact slides, a parallelogram with corners
/// (0, −F0), (d, F0), (L, F0), (L − d, −F0). Over a whole period the loop
/// area ∮F dx is the parallelogram's, 2·F0·(L − d) (the dissipated
/// energy), while ∫|F||dx| also counts the elastic storage:
/// 2·F0·(L − d) + F0·d. Strokes (runs of one sign of F) start where F
/// crosses zero, mid-stick, so two strokes away from the record's ends
/// span exactly one period.
#[test]
fn a_partial_slip_loop_has_the_parallelogram_area() {
    let (f0, l, d) = (0.5, 0.02, 0.004);
    let corners = [(0.0, -f0), (d, f0), (l, f0), (l - d, -f0), (0.0, -f0)];
    let (mut x, mut f) = (Vec::new(), Vec::new());
    for _ in 0..4 {
        for w in corners.windows(2) {
            for j in 0..100 {
                let s = j as f64 / 100.0;
                x.push(w[0].0 + s * (w[1].0 - w[0].0));
                f.push(w[0].1 + s * (w[1].1 - w[0].1));
            }
        }
    }
    let t: Vec<f64> = (0..x.len()).map(|i| i as f64 * 1e-3).collect();
    let mut tr = trace(t, f);
    tr.position_m = Some(x);
    let out = analyse_trace_with(
        &tr,
        &SampleInfo::default(),
        &FrictionParams::default(),
        &Motion::default(),
    );
    let rows = &out.cycles.rows;
    let n = rows.len();
    let (area, energy) = (2.0 * f0 * (l - d), 2.0 * f0 * (l - d) + f0 * d);
    let close = |a: f64, b: f64| ((a - b) / b).abs() < 1e-9;
    let mut checked = 0;
    // Row k (odd) closes strokes k − 1 and k; away from both ends.
    for k in (3..n.saturating_sub(1)).step_by(2) {
        assert!(
            close(rows[k].loop_area_j.unwrap(), area),
            "{k}: {:?}",
            rows[k].loop_area_j
        );
        let e = rows[k - 1].energy_j.unwrap() + rows[k].energy_j.unwrap();
        assert!(close(e, energy), "{k}: {e} vs {energy}");
        checked += 1;
    }
    assert!(checked >= 2, "{n} strokes");
}

/// Laps from a counter of 1/8 lap per sample: each lap's μ is its mean
/// |T| over the normal force, its instrument μ the mean over the lap, the
/// last, cut lap is flagged and the lap numbers are the counter's.
#[test]
fn counter_laps_average_each_whole_lap() {
    let n = 8 * 20 + 3;
    let t: Vec<f64> = (0..n).map(|i| i as f64 * 0.1).collect();
    let f: Vec<f64> = (0..n).map(|i| 0.6 + 0.1 * ((i * 7) % 5) as f64).collect();
    let mut tr = trace(t, f.clone());
    tr.laps = Some((0..n).map(|i| i as f64 / 8.0).collect());
    tr.instrument_cof = Some(f.iter().map(|v| v / 2.0).collect());
    tr.position_m = Some((0..n).map(|i| i as f64 * 0.005).collect());
    let out = analyse_trace_with(
        &tr,
        &SampleInfo::default(),
        &FrictionParams::default(),
        &Motion::default(),
    );
    let c = &out.cycles;
    assert_eq!(c.source.map(|s| s.as_str()), Some("lap_counter"));
    assert_eq!(c.rows.len(), 21);
    for (k, r) in c.rows.iter().enumerate() {
        let lap = &f[8 * k..(8 * k + 8).min(n)];
        let mean = lap.iter().sum::<f64>() / lap.len() as f64;
        assert_eq!(r.lap, Some(k as i64));
        assert!((r.mu.unwrap() - mean / 2.0).abs() < 1e-12);
        assert!((r.mu_instrument.unwrap() - mean / 2.0).abs() < 1e-12);
        assert_eq!(r.complete, k < 20, "{k}");
        assert_eq!(r.status.has(Code::PartialCycle), k == 20);
        // 8 samples of 5 mm: the lap's span slides 40 mm.
        if k < 20 {
            let (a, b) = r.distance_m.unwrap();
            assert!((b - a - 0.04).abs() < 1e-12 && (a - 0.04 * k as f64).abs() < 1e-12);
        }
    }
}

/// Strokes at the record's edges shorter than 0.9 of the median are cut;
/// the interior ones never are.
#[test]
fn edge_strokes_short_of_the_median_are_partial() {
    let row = |extent: f64, at_edge: bool| CycleRow {
        section: "1".into(),
        kind: CycleKind::Stroke,
        cycle: 0,
        stroke: None,
        lap: None,
        direction_sign: 1.0,
        start_s: 0.0,
        end_s: 1.0,
        distance_m: None,
        window_s: None,
        n_window: 0,
        mu: None,
        mu_sd: None,
        mu_peak: None,
        normal_force_n: None,
        mu_instrument: None,
        energy_j: None,
        loop_area_j: None,
        wear_depth_m: None,
        complete: true,
        extent,
        at_edge,
        status: Status::ok(),
    };
    let mut rows = [
        row(0.3, true),
        row(1.0, false),
        row(0.5, false),
        row(1.0, false),
        row(0.95, true),
    ];
    flag_partial_strokes(&mut rows.iter_mut().collect::<Vec<_>>(), 0.9);
    let complete: Vec<bool> = rows.iter().map(|r| r.complete).collect();
    assert_eq!(complete, vec![false, true, true, true, true]);
    assert!(rows[0].status.has(Code::PartialCycle));
}
