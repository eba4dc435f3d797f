//! Which cycles a trace has (MODELS.md §11): strokes when the friction
//! force reverses (or the header states a reciprocating drive), else laps
//! from the file's lap counter, its angle, or the sliding distance over the
//! track length 2π r; none for a single unidirectional pull.

use std::ops::Range;

use super::cycles::{lap_cycles, stroke_cycles, CycleInputs, CycleRow};
use super::path::{
    laps_from_angle, laps_from_counter, laps_from_path, DistanceSource, LapSource, Path,
};
use super::rows::FrictionRow;
use crate::ingest::drive::Crank;
use crate::ingest::roles::Role;
use crate::ingest::trace::Trace;
use crate::status::Code;

/// What a trace's file and manifest say about its motion.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Motion {
    /// The reciprocating crank the header states (CETR's linear wear
    /// module): its strokes are the cycles, its mean speed the sliding
    /// speed.
    pub crank: Option<Crank>,
    /// Track radius of a rotary test, m (manifest, else the file): laps
    /// from the sliding distance over 2π r.
    pub track_radius_m: Option<f64>,
}

/// Where a trace's cycles come from (the `cycle_source` column).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CycleSource {
    /// Reversals of the friction force: strokes.
    Reversals,
    /// Laps, from the counter, the angle or the distance.
    Laps(LapSource),
}

impl CycleSource {
    /// The stable text form.
    pub fn as_str(self) -> &'static str {
        match self {
            CycleSource::Reversals => "reversals",
            CycleSource::Laps(l) => l.as_str(),
        }
    }
}

/// The cycles of one trace.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct TraceCycles {
    /// Where they come from; `None` when the trace has none.
    pub source: Option<CycleSource>,
    /// Where the sliding distance comes from; `None` without one.
    pub distance: Option<DistanceSource>,
    /// One row per cycle.
    pub rows: Vec<CycleRow>,
    /// Laps left out for having fewer than [`MIN_LAP_SAMPLES`] samples
    /// (the record samples them too sparsely to average).
    pub sparse_laps: usize,
}

/// Fewest samples of a lap that is a cycle: a lap sampled once or twice
/// has no mean to speak of.
pub const MIN_LAP_SAMPLES: usize = 3;

/// The channels beside the forces that cycles may read, aligned with the
/// view's samples.
#[derive(Debug, Clone, Copy, Default)]
pub struct MotionChannels<'a> {
    /// Position or sliding distance, m.
    pub position_m: Option<&'a [f64]>,
    /// Sliding speed, m/s.
    pub velocity_m_per_s: Option<&'a [f64]>,
    /// Lap counter.
    pub laps: Option<&'a [f64]>,
    /// Angle, rad.
    pub angle_rad: Option<&'a [f64]>,
}

/// The cycles of a trace whose strokes (`strokes`, with their rows) are
/// known. A stroke of a crank whose duration is not within a factor 2 of
/// half a turn says `speed_mismatch`: the header's speed does not fit the
/// record.
pub fn trace_cycles(
    inp: CycleInputs,
    strokes: &[(Range<usize>, f64)],
    rows: &[FrictionRow],
    ch: &MotionChannels,
    motion: &Motion,
) -> TraceCycles {
    let t = inp.time_s;
    let declared = motion.crank.map(|c| c.mean_speed_m_per_s());
    let path = Path::of(t, ch.position_m, ch.velocity_m_per_s, declared);
    let inp = CycleInputs { path, ..inp };
    let reverses = strokes.windows(2).any(|w| w[0].1 * w[1].1 < 0.0);
    if !strokes.is_empty() && (reverses || motion.crank.is_some()) {
        let mut cycles = stroke_cycles(&inp, strokes, rows);
        if let Some(c) = motion.crank {
            doubt_crank_speed(&mut cycles, &c);
        }
        return TraceCycles {
            source: Some(CycleSource::Reversals),
            distance: path.map(|p| p.source()),
            rows: cycles,
            sparse_laps: 0,
        };
    }
    let track = motion
        .track_radius_m
        .filter(|r| r.is_finite() && *r > 0.0)
        .map(|r| std::f64::consts::TAU * r);
    let laps = match (ch.laps, ch.angle_rad, path.zip(track)) {
        (Some(c), _, _) => Some((LapSource::Counter, laps_from_counter(c))),
        (None, Some(a), _) => Some((LapSource::Angle, laps_from_angle(a))),
        (None, None, Some((p, l))) => Some((LapSource::Distance, laps_from_path(&p, t.len(), l))),
        _ => None,
    };
    match laps {
        Some((source, spans)) if !spans.is_empty() => {
            let total = spans.len();
            let kept: Vec<_> = spans
                .into_iter()
                .filter(|l| l.range.len() >= MIN_LAP_SAMPLES)
                .collect();
            TraceCycles {
                source: Some(CycleSource::Laps(source)),
                distance: path.map(|p| p.source()),
                sparse_laps: total - kept.len(),
                rows: lap_cycles(&inp, &kept),
            }
        }
        _ => TraceCycles::default(),
    }
}

/// Strokes that last far from the crank's half turn.
fn doubt_crank_speed(cycles: &mut [CycleRow], c: &Crank) {
    let expected = c.stroke_duration_s();
    for r in cycles.iter_mut() {
        let took = r.end_s - r.start_s;
        if !(0.5 * expected..=2.0 * expected).contains(&took) {
            r.status.push(
                Code::SpeedMismatch,
                format!(
                    "the header's {:.4} rpm on a {:.4} mm crank strokes in {expected:.4} s, this stroke lasts {took:.4} s: its distance and energy from the header's speed are doubtful",
                    c.frequency_hz * 60.0,
                    c.radius_m * 1e3
                ),
            );
        }
    }
}

/// A trace driven by a crank the header states takes the crank's mean
/// sliding speed 4·r·f as its velocity (the file's velocity column, the
/// CETR carriage's µm/s drift, is not the sliding speed); the role map
/// says where it came from.
pub fn apply_crank(trace: &mut Trace, c: &Crank) {
    trace.velocity_m_per_s = Some(vec![c.mean_speed_m_per_s(); trace.len()]);
    trace.columns.insert(
        Role::Velocity,
        format!(
            "header: {} rpm on a {} mm crank, mean speed 4·r·f",
            c.frequency_hz * 60.0,
            c.radius_m * 1e3
        ),
    );
}
