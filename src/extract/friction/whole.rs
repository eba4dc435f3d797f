//! The `friction` row of a whole unidirectional trace (a pin-on-disc run
//! is one segment) restated from the test's steady state: its μ_d is the
//! steady state's, over the steady state's window, never the plateau of
//! an arbitrary velocity step or of the running-in (a test that never
//! settles says so on the row too); its μ_s is a break-away only when it
//! comes in the first lap.

use super::assess::{steady_window, Scope, TestRow};
use super::cycles::CycleKind;
use super::sample::SampleInfo;
use super::trace::{FrictionRow, TraceFeatures};
use crate::ingest::trace::Trace;
use crate::signal::stats;
use crate::status::{Code, Status};

/// Restates the whole-trace rows of a rotary test from its `tests` rows:
/// a single-section test with a steady state takes its μ_d over the
/// steady window; a stepped test's whole-trace row has none
/// (`stepped_test`); a static peak after the first lap is a running-in
/// spike, not a break-away (`no_static_peak`).
pub fn restate_whole_rows(
    traces: &[Trace],
    features: &mut [TraceFeatures],
    tests: &[TestRow],
    sample: &SampleInfo,
) {
    let Some(test) = tests.iter().find(|t| t.scope == Scope::Test) else {
        return;
    };
    let single = features.len() == 1;
    for (trace, f) in traces.iter().zip(features.iter_mut()) {
        let laps = f.cycles.rows.iter().any(|c| c.kind == CycleKind::Lap);
        if f.segments.len() != 1 {
            continue;
        }
        let first_lap_end = f.cycles.rows.first().filter(|_| laps).map(|c| c.end_s);
        let window = (single && laps).then(|| steady_window(f, test)).flatten();
        let row = &mut f.segments[0];
        if let (Some(ts), Some(end)) = (row.static_time_s, first_lap_end) {
            if ts > end {
                let what = format!(
                    "the first prominent maximum (μ {:.4} at {ts:.4} s) comes after the first lap (to {end:.4} s): a running-in peak, not a break-away",
                    row.mu_static.unwrap_or(f64::NAN)
                );
                (
                    row.static_force_n,
                    row.static_time_s,
                    row.static_prominence_n,
                    row.mu_static,
                ) = (None, None, None, None);
                row.status = without(&row.status, Code::StaticBelowDynamic);
                row.status.push(Code::NoStaticPeak, what);
            }
        }
        if test.status.has(Code::SteppedTest) {
            (
                row.dynamic_force_n,
                row.dynamic_force_sd_n,
                row.mu_dynamic,
                row.mu_dynamic_sd,
            ) = (None, None, None, None);
            (
                row.dynamic_window_start_s,
                row.dynamic_window_end_s,
                row.dynamic_n,
                row.mu_instrument,
            ) = (None, None, None, None);
            row.status.push(
                Code::SteppedTest,
                "a stepped-velocity test: μ per step in friction_steps and friction_tests, no whole-trace μ_d",
            );
        } else if let Some(w) = window {
            restate_dynamic(trace, row, w, sample.normal_force_n);
        } else if laps && test.status.has(Code::NoSteadyState) {
            row.status.push(
                Code::NoSteadyState,
                "μ does not settle through the test (friction_tests): μ_d is the mean over the segment's plateau window, not a steady state",
            );
        }
    }
}

/// A status without the notes of `code` (a doubt about a value that is no
/// longer reported).
fn without(s: &Status, code: Code) -> Status {
    let mut out = Status::ok();
    for n in s.notes().iter().filter(|n| n.code != code) {
        out.push(n.code, n.detail.clone());
    }
    out
}

/// The row's dynamic values over the window `(t0, t1)`: mean |T| and its
/// sd, the normal force (column, else manifest), μ_d = T_d / N̄, the
/// pointwise μ's sd, and the instrument's μ; samples whose time or force
/// is not finite left out.
fn restate_dynamic(
    trace: &Trace,
    row: &mut FrictionRow,
    (t0, t1): (f64, f64),
    manifest_n: Option<f64>,
) {
    let (t, f) = (&trace.time_s, &trace.friction_n);
    let idx: Vec<usize> = (0..t.len())
        .filter(|&i| t[i].is_finite() && f[i].is_finite() && t[i] >= t0 && t[i] <= t1)
        .collect();
    let Some((mean, sd)) = stats::mean_sd(&idx.iter().map(|&i| f[i].abs()).collect::<Vec<_>>())
    else {
        return;
    };
    let normal = match (&trace.normal_n, manifest_n) {
        (Some(n), _) => stats::mean_finite_by(idx.len(), |j| n[idx[j]]),
        (None, m) => m,
    };
    row.dynamic_force_n = Some(mean);
    row.dynamic_force_sd_n = sd;
    (row.dynamic_window_start_s, row.dynamic_window_end_s) =
        (Some(t[idx[0]]), Some(t[idx[idx.len() - 1]]));
    row.dynamic_n = Some(idx.len());
    row.normal_force_n = normal;
    row.mu_dynamic = normal.filter(|n| *n > 0.0).map(|n| mean / n);
    row.mu_dynamic_sd = match (&trace.normal_n, normal) {
        (Some(n), _) => stats::sd_finite_by(idx.len(), |j| f[idx[j]].abs() / n[idx[j]]),
        (None, Some(n)) if n > 0.0 => sd.map(|s| s / n),
        _ => None,
    };
    row.mu_instrument = trace
        .instrument_cof
        .as_ref()
        .and_then(|c| stats::mean_finite_by(idx.len(), |j| c[idx[j]]));
}
