//! Cycles of a friction test (MODELS.md §11): the strokes of a
//! reciprocating test and the laps of a rotary one, each with its μ over
//! its steady part, its sliding distance, its friction energy and, for
//! strokes, the friction loop.
//!
//! A stroke is the `friction` row of the same number: its steady part is
//! that row's dynamic window (after the break-away peak, once the force
//! has settled, before the approach of the next reversal: the reversal
//! transients are left out by the rule of docs/friction.md), its μ that
//! row's μ_d and its peak μ the break-away μ_s. Nothing is computed twice:
//! the cycle adds only what the row has not, the distance, the energy and
//! the loop. A lap has no reversal: its steady part is the whole lap.
//!
//! A cycle's span runs from its first sample to the next cycle's first
//! (the last to the end of the record), so the spans' energies and
//! distances add up to the test's.

use std::ops::Range;

use rayon::prelude::*;

use super::path::{LapSpan, Path};
use super::rows::FrictionRow;
use crate::signal::{stats, sum};
use crate::status::{Code, Status};

/// What a cycle is.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CycleKind {
    /// A stroke of a reciprocating test, between two reversals.
    Stroke,
    /// A lap of a rotary test.
    Lap,
}

impl CycleKind {
    /// The stable text form.
    pub fn as_str(self) -> &'static str {
        match self {
            CycleKind::Stroke => "stroke",
            CycleKind::Lap => "lap",
        }
    }
}

/// One row of `friction_cycles`.
#[derive(Debug, Clone, PartialEq)]
pub struct CycleRow {
    /// Section of the file.
    pub section: String,
    /// Stroke or lap.
    pub kind: CycleKind,
    /// 1-based through the test (numbered when the test's cycles are
    /// gathered; within the trace until then).
    pub cycle: usize,
    /// The `friction` row's stroke number (strokes).
    pub stroke: Option<usize>,
    /// The file's lap number (laps): the whole part of its lap coordinate.
    pub lap: Option<i64>,
    /// Sign of the friction force: +1 or −1 (a lap: of its mean).
    pub direction_sign: f64,
    /// First sample, s.
    pub start_s: f64,
    /// Last sample of the span (before the next cycle's first), s.
    pub end_s: f64,
    /// Sliding distance at the span's start and end, m, from the start of
    /// the test.
    pub distance_m: Option<(f64, f64)>,
    /// The steady part averaged: first and last sample, s.
    pub window_s: Option<(f64, f64)>,
    /// Samples in the steady part.
    pub n_window: usize,
    /// μ over the steady part: mean |T| / mean N (as `friction.mu_dynamic`).
    pub mu: Option<f64>,
    /// Sample sd of the pointwise μ over the steady part.
    pub mu_sd: Option<f64>,
    /// Break-away μ after the reversal (strokes: the row's μ_s).
    pub mu_peak: Option<f64>,
    /// Mean normal force over the steady part, N.
    pub normal_force_n: Option<f64>,
    /// Mean of the instrument's own μ over the steady part.
    pub mu_instrument: Option<f64>,
    /// Friction energy E = ∫|T| |dx| over the span, J.
    pub energy_j: Option<f64>,
    /// |∮ T dx| of the reciprocating cycle this stroke closes (the second
    /// stroke of each pair: 2, 4, …), J.
    pub loop_area_j: Option<f64>,
    /// Mean of the linear-wear (depth) channel over the span, m.
    pub wear_depth_m: Option<f64>,
    /// Whether the record holds the whole cycle.
    pub complete: bool,
    /// How far the cycle reaches, to judge a stroke at the record's edge:
    /// its travel (m) with a position, else its duration (s).
    pub(super) extent: f64,
    /// Whether it is the first or last stroke of its section.
    pub(super) at_edge: bool,
    /// `ok`, or why the cycle is doubtful.
    pub status: Status,
}

/// The channels of one trace that cycles read (NaN samples of time and
/// force dropped, as for the strokes).
#[derive(Debug, Clone, Copy)]
pub struct CycleInputs<'a> {
    /// Section name.
    pub section: &'a str,
    /// Time, s.
    pub time_s: &'a [f64],
    /// Friction force T, N, signed.
    pub friction_n: &'a [f64],
    /// Normal force column, N.
    pub normal_n: Option<&'a [f64]>,
    /// Normal force from the manifest, N, when the trace has no column.
    pub normal_const_n: Option<f64>,
    /// The instrument's own μ.
    pub cof: Option<&'a [f64]>,
    /// The linear-wear (depth) channel, m.
    pub wear_m: Option<&'a [f64]>,
    /// The sliding path.
    pub path: Option<Path<'a>>,
}

/// Mean of the finite values of `x` over `span`.
fn span_mean(x: Option<&[f64]>, span: Range<usize>) -> Option<f64> {
    let x = &x?[span];
    stats::mean_finite_by(x.len(), |i| x[i])
}

/// Distance slid, energy ∫|T||dx| and signed work ∫T dx over the sample
/// pairs (i, i + 1) of `span` (the pair leaving its last sample included).
fn span_sums(inp: &CycleInputs, span: Range<usize>) -> Option<[f64; 3]> {
    let path = inp.path?;
    let n = inp.time_s.len();
    let end = span.end.min(n.saturating_sub(1));
    let from = span.start.min(end);
    let f = inp.friction_n;
    Some(sum::sums_by(end - from, |j| {
        let i = from + j;
        let ds = path.step(i);
        let dx = path.signed_step(i).unwrap_or(0.0);
        [
            ds,
            0.5 * (f[i].abs() + f[i + 1].abs()) * ds,
            0.5 * (f[i] + f[i + 1]) * dx,
        ]
    }))
}

/// The distance at each span's start and end, from the first sample of the
/// record, given each span's own distance.
fn distances(inp: &CycleInputs, first: usize, own: &[Option<f64>]) -> Vec<Option<(f64, f64)>> {
    let before = span_sums(inp, 0..first).map_or(0.0, |s| s[0]);
    let mut at = before;
    own.iter()
        .map(|d| {
            d.map(|d| {
                let span = (at, at + d);
                at += d;
                span
            })
        })
        .collect()
}

/// Each stroke's span: from its first sample to the next stroke's.
fn stroke_spans(strokes: &[(Range<usize>, f64)], n: usize) -> Vec<Range<usize>> {
    strokes
        .iter()
        .enumerate()
        .map(|(k, (r, _))| r.start..strokes.get(k + 1).map_or(n, |(next, _)| next.start))
        .collect()
}

/// Each span's sums ([`span_sums`]: distance, energy, loop) and its
/// sliding distance at start and end, counted from the record's start.
#[allow(clippy::type_complexity)]
fn spans_sums_and_distances(
    inp: &CycleInputs,
    spans: &[Range<usize>],
) -> (Vec<Option<[f64; 3]>>, Vec<Option<(f64, f64)>>) {
    let sums: Vec<Option<[f64; 3]>> = spans
        .par_iter()
        .map(|s| span_sums(inp, s.clone()))
        .collect();
    let first = spans.first().map_or(0, |s| s.start);
    let own: Vec<Option<f64>> = sums.iter().map(|s| s.map(|s| s[0])).collect();
    let dist = distances(inp, first, &own);
    (sums, dist)
}

/// The cycles of a reciprocating trace: one per stroke, from the stroke's
/// `friction` row (`rows[k]` is stroke k + 1 over `strokes[k]`).
pub fn stroke_cycles(
    inp: &CycleInputs,
    strokes: &[(Range<usize>, f64)],
    rows: &[FrictionRow],
) -> Vec<CycleRow> {
    let (t, n) = (inp.time_s, inp.time_s.len());
    let spans = stroke_spans(strokes, n);
    let (sums, dist) = spans_sums_and_distances(inp, &spans);
    let position = match inp.path {
        Some(Path::Position(x)) => Some(x),
        _ => None,
    };
    let last = strokes.len().saturating_sub(1);
    strokes
        .iter()
        .zip(rows)
        .enumerate()
        .map(|(k, ((range, sign), row))| {
            let extent = match position {
                Some(x) => stats_range(&x[range.clone()]),
                None => t[range.end - 1] - t[range.start],
            };
            // The loop of strokes k − 1 and k (k odd here: the second of
            // its pair), when they run in opposite directions.
            let loop_area_j = (k % 2 == 1 && strokes[k - 1].1 * *sign < 0.0)
                .then(|| Some(sums[k - 1]?[2] + sums[k]?[2]))
                .flatten()
                .filter(|_| position.is_some())
                .map(f64::abs);
            CycleRow {
                section: inp.section.to_string(),
                kind: CycleKind::Stroke,
                cycle: k + 1,
                stroke: row.stroke,
                lap: None,
                direction_sign: *sign,
                start_s: t[range.start],
                end_s: t[spans[k].end - 1],
                distance_m: dist[k],
                window_s: row.dynamic_window_start_s.zip(row.dynamic_window_end_s),
                n_window: row.dynamic_n.unwrap_or(0),
                mu: row.mu_dynamic,
                mu_sd: row.mu_dynamic_sd,
                mu_peak: row.mu_static,
                normal_force_n: row.normal_force_n,
                mu_instrument: row.mu_instrument,
                energy_j: sums[k].map(|s| s[1]),
                loop_area_j,
                wear_depth_m: span_mean(inp.wear_m, spans[k].clone()),
                complete: true,
                extent,
                at_edge: k == 0 || k == last,
                status: row.status.clone(),
            }
        })
        .collect()
}

/// max − min of the finite values.
fn stats_range(x: &[f64]) -> f64 {
    crate::signal::scan::finite_range(x).map_or(0.0, |(lo, hi)| hi - lo)
}

/// The cycles of a rotary trace: one per lap, its steady part the whole
/// lap.
pub fn lap_cycles(inp: &CycleInputs, laps: &[LapSpan]) -> Vec<CycleRow> {
    let n = inp.time_s.len();
    let spans: Vec<Range<usize>> = laps
        .iter()
        .enumerate()
        .map(|(k, l)| l.range.start..laps.get(k + 1).map_or(n, |next| next.range.start))
        .collect();
    let (sums, dist) = spans_sums_and_distances(inp, &spans);
    laps.par_iter()
        .enumerate()
        .map(|(k, lap)| {
            let mut row = lap_row(inp, lap);
            row.cycle = k + 1;
            row.end_s = inp.time_s[spans[k].end - 1];
            row.distance_m = dist[k];
            row.energy_j = sums[k].map(|s| s[1]);
            row.wear_depth_m = span_mean(inp.wear_m, spans[k].clone());
            row
        })
        .collect()
}

/// A lap's μ, sd, normal force and instrument μ over all its samples.
fn lap_row(inp: &CycleInputs, lap: &LapSpan) -> CycleRow {
    let r = lap.range.clone();
    let (t, f) = (&inp.time_s[r.clone()], &inp.friction_n[r.clone()]);
    let [abs_sum, signed_sum] = sum::sums_by(f.len(), |i| [f[i].abs(), f[i]]);
    let mean_abs = abs_sum / f.len() as f64;
    let mut status = Status::ok();
    let normal = match (inp.normal_n, inp.normal_const_n) {
        (Some(nn), _) => {
            let nn = &nn[r.clone()];
            stats::mean_finite_by(nn.len(), |i| nn[i])
        }
        (None, c) => c,
    };
    let usable = normal.filter(|n| *n > 0.0);
    match normal {
        None => status.push(Code::NoNormalForce, "no normal force: μ undefined"),
        Some(n) if n <= 0.0 => status.push(
            Code::NonpositiveNormalForce,
            format!("N = {n} N, μ undefined"),
        ),
        _ => {}
    }
    let mut mu = usable.map(|n| mean_abs / n);
    if let Some(m) = mu.filter(|m| !m.is_finite() || m.abs() > super::doubts::MU_PLAUSIBLE_MAX) {
        status.push(
            Code::AbsurdMagnitude,
            format!("μ = {m:.4e}: not a coefficient of friction (check the normal force)"),
        );
        mu = None;
    }
    let mu_sd = mu.and_then(|_| match (inp.normal_n, usable) {
        (Some(nn), _) => {
            let nn = &nn[r.clone()];
            stats::sd_finite_by(f.len(), |i| f[i].abs() / nn[i])
        }
        (None, Some(n)) => stats::sd_finite_by(f.len(), |i| f[i].abs() / n),
        _ => None,
    });
    if !lap.complete {
        status.push(Code::PartialCycle, "the record holds only part of this lap");
    }
    CycleRow {
        section: inp.section.to_string(),
        kind: CycleKind::Lap,
        cycle: 0,
        stroke: None,
        lap: Some(lap.lap),
        direction_sign: if signed_sum < 0.0 { -1.0 } else { 1.0 },
        start_s: t[0],
        end_s: t[t.len() - 1],
        distance_m: None,
        window_s: Some((t[0], t[t.len() - 1])),
        n_window: t.len(),
        mu,
        mu_sd,
        mu_peak: None,
        normal_force_n: normal,
        mu_instrument: inp.cof.and_then(|c| {
            let c = &c[r];
            stats::mean_finite_by(c.len(), |i| c[i])
        }),
        energy_j: None,
        loop_area_j: None,
        wear_depth_m: None,
        complete: lap.complete,
        extent: t[t.len() - 1] - t[0],
        at_edge: false,
        status,
    }
}

/// Strokes at the edge of their section that reach less than `fraction` of
/// the test's median stroke (travel with a position, else duration) were
/// cut off by the record: flagged `partial_cycle`, not averaged in.
/// Strokes between two reversals are whole by construction.
pub fn flag_partial_strokes(rows: &mut [&mut CycleRow], fraction: f64) {
    let extents: Vec<f64> = rows
        .iter()
        .filter(|r| r.kind == CycleKind::Stroke)
        .map(|r| r.extent)
        .collect();
    let Some(median) = stats::median(&extents) else {
        return;
    };
    for r in rows
        .iter_mut()
        .filter(|r| r.kind == CycleKind::Stroke && r.at_edge)
    {
        if r.extent < fraction * median {
            r.complete = false;
            r.status.push(
                Code::PartialCycle,
                format!(
                    "at the edge of the record, this stroke reaches {:.4e} against the test's median {median:.4e}",
                    r.extent
                ),
            );
        }
    }
}

#[cfg(test)]
#[path = "cycles_tests.rs"]
mod tests;
