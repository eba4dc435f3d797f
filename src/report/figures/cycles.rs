//! Figures of a friction test through its cycles (MODELS.md §11): μ per
//! cycle against the sliding distance with the running-in and the steady
//! band, the friction loops (T against x) of chosen reciprocating cycles,
//! and the wear depth against the sliding distance.

use super::{num, Figure};
use crate::extract::friction::assess::{Scope, TestRow};
use crate::extract::friction::cycles::{CycleKind, CycleRow};
use crate::extract::friction::TraceFeatures;
use crate::ingest::trace::Trace;
use crate::plot::{Axis, Band, Chart, Colour, Style};

/// Points of a friction loop drawn at most.
const LOOP_POINTS: usize = 2000;

/// The cycle figures of one file.
pub fn figures(
    source: &str,
    traces: &[Trace],
    features: &[TraceFeatures],
    tests: &[TestRow],
) -> Vec<Figure> {
    let name = super::file_name(source);
    let mut out = Vec::new();
    if let Some(chart) = stribeck_chart(&name, features) {
        out.push(Figure::draw(source, "", "stribeck", &chart));
    }
    let cycles: Vec<&CycleRow> = features.iter().flat_map(|f| &f.cycles.rows).collect();
    if cycles.is_empty() {
        return out;
    }
    out.push(Figure::draw(
        source,
        "",
        "cycles",
        &mu_chart(&name, &cycles, tests),
    ));
    if let Some(chart) = loops_chart(&name, traces, features, tests) {
        out.push(Figure::draw(source, "", "loops", &chart));
    }
    if let Some(chart) = wear_chart(&name, &cycles) {
        out.push(Figure::draw(source, "", "wear", &chart));
    }
    out
}

/// μ of each velocity step against its Stribeck parameter η·v/p (log
/// axis); `None` unless two steps have both.
fn stribeck_chart(name: &str, features: &[TraceFeatures]) -> Option<Chart> {
    let pts: Vec<(f64, f64)> = features
        .iter()
        .flat_map(|f| &f.steps)
        .filter_map(|(_, s)| Some((s.stribeck.parameter_m?, s.mu_mean?)))
        .filter(|(x, y)| *x > 0.0 && y.is_finite())
        .collect();
    if pts.len() < 2 {
        return None;
    }
    let mut c = Chart::new(
        format!("{name}: Stribeck curve"),
        Axis::log("Stribeck parameter η·v/p [m]"),
        Axis::linear("μ"),
    );
    c.push("μ of each velocity step", pts, Colour::Blue, Style::Dots);
    Some(c)
}

/// Where a cycle sits along x: the sliding distance at its end, else its
/// number.
fn at(c: &CycleRow, by_distance: bool) -> f64 {
    match by_distance {
        true => num(c.distance_m.map(|d| d.1)),
        false => c.cycle as f64,
    }
}

/// μ per cycle against the sliding distance (or the cycle number): whole
/// cycles as dots, partial ones as crosses; each row's running-in shaded
/// and its steady band drawn over the steady cycles.
fn mu_chart(name: &str, cycles: &[&CycleRow], tests: &[TestRow]) -> Chart {
    let by_distance = cycles.iter().all(|c| c.distance_m.is_some());
    let x = match by_distance {
        true => Axis::linear("sliding distance [m]"),
        false => Axis::linear("cycle"),
    };
    let kind = if cycles[0].kind == CycleKind::Lap {
        "lap"
    } else {
        "stroke"
    };
    let mut c = Chart::new(format!("{name}: μ per {kind}"), x, Axis::linear("μ"));
    let point = |r: &&&CycleRow| (at(r, by_distance), num(r.mu));
    let (whole, part): (Vec<&&CycleRow>, Vec<&&CycleRow>) = cycles.iter().partition(|r| r.complete);
    for t in tests
        .iter()
        .filter(|t| t.scope == Scope::Step || tests.len() == 1)
    {
        let Some((first, last)) = t.cycles else {
            continue;
        };
        let within: Vec<&&CycleRow> = whole
            .iter()
            .copied()
            .filter(|r| (first..=last).contains(&r.cycle))
            .collect();
        let Some(onset) = t.steady_from_cycle else {
            continue;
        };
        let start = within.first().map(|r| at(r, by_distance));
        let steady: Vec<f64> = within
            .iter()
            .filter(|r| r.cycle >= onset)
            .map(|r| at(r, by_distance))
            .collect();
        if let (Some(a), Some(&b)) = (start, steady.first()) {
            if b > a {
                c.span("running-in", (a, b), Colour::Orange);
            }
        }
        if let (Some(p), Some(h), Some(&a), Some(&b)) = (
            t.steady.plateau,
            t.steady.band,
            steady.first(),
            steady.last(),
        ) {
            c.bands.push(Band {
                name: "steady band".into(),
                points: vec![(a, p - h, p + h), (b, p - h, p + h)],
                colour: Colour::Green,
            });
        }
        if let (Some(m), Some(&a), Some(&b)) = (t.steady.mu, steady.first(), steady.last()) {
            c.push(
                "steady μ",
                vec![(a, m), (b, m)],
                Colour::Green,
                Style::Dashed,
            );
        }
    }
    c.push(
        "μ of whole cycles",
        whole.iter().map(point).collect(),
        Colour::Blue,
        Style::Dots,
    );
    c.push(
        "partial cycles",
        part.iter().map(point).collect(),
        Colour::Red,
        Style::Crosses,
    );
    c
}

/// Friction loops (T against x) of the first whole reciprocating cycle, the
/// first steady one and the last whole one, from the trace's samples;
/// `None` without a position or without a loop.
fn loops_chart(
    name: &str,
    traces: &[Trace],
    features: &[TraceFeatures],
    tests: &[TestRow],
) -> Option<Chart> {
    let steady_from = tests
        .iter()
        .find(|t| t.scope == Scope::Test)
        .and_then(|t| t.steady_from_cycle);
    let mut c = Chart::new(
        format!("{name}: friction loops"),
        Axis::linear("position [m]"),
        Axis::linear("friction force [N]"),
    );
    for (trace, f) in traces.iter().zip(features) {
        let (Some(x), rows) = (trace.position_m.as_deref(), &f.cycles.rows) else {
            continue;
        };
        // The rows that close a loop, and the stroke before each.
        let closing: Vec<usize> = (1..rows.len())
            .filter(|&k| rows[k].loop_area_j.is_some() && rows[k].complete && rows[k - 1].complete)
            .collect();
        let pick = [
            closing.first().copied(),
            steady_from.and_then(|s| closing.iter().copied().find(|&k| rows[k].cycle >= s)),
            closing.last().copied(),
        ];
        let mut drawn: Vec<usize> = Vec::new();
        for k in pick.into_iter().flatten() {
            if drawn.contains(&k) {
                continue;
            }
            drawn.push(k);
            let (t0, t1) = (rows[k - 1].start_s, rows[k].end_s);
            let t = &trace.time_s;
            let (a, b) = (
                t.partition_point(|v| *v < t0),
                t.partition_point(|v| *v <= t1),
            );
            let stride = ((b - a) / LOOP_POINTS).max(1);
            let pts: Vec<(f64, f64)> = (a..b)
                .step_by(stride)
                .map(|i| (x[i], trace.friction_n[i]))
                .collect();
            let label = format!(
                "strokes {}–{} ({:.3e} J)",
                rows[k - 1].cycle,
                rows[k].cycle,
                num(rows[k].loop_area_j)
            );
            c.push(label, pts, Colour::cycle(drawn.len() - 1), Style::Line);
        }
    }
    (!c.is_empty()).then_some(c)
}

/// The wear depth each cycle averages, against the sliding distance;
/// `None` without a wear channel.
fn wear_chart(name: &str, cycles: &[&CycleRow]) -> Option<Chart> {
    let pts: Vec<(f64, f64)> = cycles
        .iter()
        .filter_map(|c| Some((c.distance_m?.1, c.wear_depth_m?)))
        .collect();
    if pts.is_empty() {
        return None;
    }
    let mut c = Chart::new(
        format!("{name}: wear depth"),
        Axis::linear("sliding distance [m]"),
        Axis::linear("wear depth [m]"),
    );
    c.push("mean over each cycle", pts, Colour::Blue, Style::Dots);
    Some(c)
}
