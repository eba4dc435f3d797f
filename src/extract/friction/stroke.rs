//! One stroke of a trace: its segment features, dynamic plateau, static
//! peak, normal force, μ and stick-slip, as one `friction.parquet` row.

use std::borrow::Cow;

use super::doubts::{
    doubt_early_peak, doubt_load_ramp, doubt_normal_force, doubt_static_below_dynamic,
    refuse_absurd_mu,
};
use super::params::FrictionParams;
use super::rows::{FrictionRow, TraceView};
use super::sample::SampleInfo;
use super::segment::{segment_features_with, SegmentFeatures, StickSlipEvent};
use super::steps;
use crate::signal::stats;
use crate::status::{Code, Status};

/// One stroke's row and its stick-slip events.
pub(super) fn analyse_stroke(
    v: &TraceView,
    sample: &SampleInfo,
    p: &FrictionParams,
    stroke: usize,
    range: std::ops::Range<usize>,
    sign: f64,
) -> (FrictionRow, Vec<StickSlipEvent>) {
    let ts = &v.t[range.clone()];
    // |T| of the stroke: the force itself when it is positive.
    let x: Cow<[f64]> = match sign.to_bits() == 1.0f64.to_bits() {
        true => Cow::Borrowed(&v.f[range.clone()]),
        false => Cow::Owned(v.f[range.clone()].iter().map(|f| f * sign).collect()),
    };
    let load = StrokeLoad {
        normal: v.normal.map(|n| &n[range.clone()]),
        manifest: sample.normal_force_n,
    };
    // Whether the load ramps does not depend on the features: both at once.
    let (feats, ramp) = rayon::join(
        || {
            let whole = range == (0..v.f.len()) && sign.to_bits() == 1.0f64.to_bits();
            segment_features_with(ts, &x, p, v.noise.filter(|_| whole))
        },
        || load.normal.and_then(|n| steps::load_ramp(ts, n, p)),
    );
    let mut row = FrictionRow {
        section: v.section.to_string(),
        stroke: Some(stroke),
        direction_sign: Some(sign),
        start_s: Some(ts[0]),
        end_s: ts.last().copied(),
        n_samples: ts.len(),
        n_nan_dropped: v.n_nan,
        noise_n: Some(feats.noise_n),
        friction_force_source: Some(if v.from_cof { "coefficient" } else { "trace" }),
        stickslip_events: feats.events.len(),
        ..Default::default()
    };
    let mut notes = Status::ok();
    // Normal force: the trace's own, else the manifest's.
    row.normal_force_source = match (load.normal, load.manifest) {
        (Some(_), _) => Some("trace"),
        (None, Some(_)) => Some("manifest"),
        (None, None) => None,
    };
    if feats.static_peak.is_none() {
        notes.push(Code::NoStaticPeak, "no maximum stands out of the noise");
    }
    add_dynamic(
        &mut row,
        &feats,
        &x,
        &load,
        v.cof.map(|c| &c[range]),
        ramp,
        &mut notes,
    );
    add_static(&mut row, &feats, &load, ts.len(), p, &mut notes);
    refuse_absurd_mu(&mut row, &mut notes);
    doubt_static_below_dynamic(&row, &mut notes);
    doubt_normal_force(&row, &mut notes);
    add_stickslip(&mut row, &feats, ts);
    row.status = notes;
    (row, feats.events)
}

/// A stroke's normal force: its own samples, else the manifest's value.
struct StrokeLoad<'a> {
    normal: Option<&'a [f64]>,
    manifest: Option<f64>,
}

impl StrokeLoad<'_> {
    /// The mean normal force over a sample range of the stroke.
    fn at(&self, r: std::ops::Range<usize>) -> Option<f64> {
        match self.normal {
            Some(n) => {
                let n = &n[r];
                stats::mean_finite_by(n.len(), |i| n[i])
            }
            None => self.manifest,
        }
    }
}

/// A normal force μ can be divided by.
fn usable(n: Option<f64>) -> Option<f64> {
    n.filter(|n| *n > 0.0)
}

/// The dynamic plateau's force, window, normal force, μ_d (with its sd
/// from the samples when the trace has its own normal force) and the
/// instrument's μ over the same window.
#[allow(clippy::too_many_arguments)]
fn add_dynamic(
    row: &mut FrictionRow,
    feats: &SegmentFeatures,
    x: &[f64],
    load: &StrokeLoad,
    cof: Option<&[f64]>,
    ramp: Option<(f64, f64)>,
    notes: &mut Status,
) {
    let Some(pl) = &feats.plateau else {
        notes.push(
            Code::NoSlidingPhase,
            "no steady-sliding window after the static peak",
        );
        return;
    };
    row.dynamic_force_n = Some(pl.mean_n);
    row.dynamic_force_sd_n = Some(pl.sd_n);
    row.dynamic_window_start_s = Some(pl.start_s);
    row.dynamic_window_end_s = Some(pl.end_s);
    row.dynamic_n = Some(pl.range.len());
    row.normal_force_n = load.at(pl.range.clone());
    doubt_load_ramp(ramp, notes);
    if let Some(n) = usable(row.normal_force_n) {
        row.mu_dynamic = Some(pl.mean_n / n);
        row.mu_dynamic_sd = match load.normal {
            Some(sn) => {
                let (x, sn) = (&x[pl.range.clone()], &sn[pl.range.clone()]);
                stats::sd_finite_by(x.len(), |i| x[i] / sn[i])
            }
            None => Some(pl.sd_n / n),
        };
    }
    if let Some(c) = cof {
        let c = &c[pl.range.clone()];
        row.mu_instrument = stats::mean_finite_by(c.len(), |i| c[i]);
    }
}

/// The static peak and μ_s, with the normal force around the peak (the
/// row's normal force when the plateau gave none); the missing peak is
/// noted by the caller, before the plateau's doubts.
fn add_static(
    row: &mut FrictionRow,
    feats: &SegmentFeatures,
    load: &StrokeLoad,
    len: usize,
    p: &FrictionParams,
    notes: &mut Status,
) {
    let Some(sp) = feats.static_peak else {
        return;
    };
    row.static_force_n = Some(sp.force_n);
    row.static_time_s = Some(sp.time_s);
    row.static_prominence_n = Some(sp.prominence_n);
    let h = p.median_window / 2;
    let n_static = load.at(sp.index.saturating_sub(h)..(sp.index + h + 1).min(len));
    if row.normal_force_n.is_none() {
        row.normal_force_n = n_static;
    }
    row.mu_static = usable(n_static).map(|n| sp.force_n / n);
    doubt_early_peak(sp.index, notes);
}

/// Mean drop and frequency of the stick-slip events (from the static peak,
/// or the stroke's start, to its end).
fn add_stickslip(row: &mut FrictionRow, feats: &SegmentFeatures, ts: &[f64]) {
    if feats.events.is_empty() {
        return;
    }
    row.stickslip_mean_drop_n =
        stats::mean(&feats.events.iter().map(|e| e.drop_n).collect::<Vec<_>>());
    let t0 = feats.static_peak.map_or(ts[0], |s| s.time_s);
    let span = ts[ts.len() - 1] - t0;
    row.stickslip_frequency_hz = (span > 0.0).then(|| feats.events.len() as f64 / span);
}
