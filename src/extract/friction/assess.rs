//! A test as a whole (MODELS.md §11): its cycles numbered through its
//! sections, the partial ones flagged, and its running-in and steady state
//! — per test, and for a stepped-velocity test per step (a change of speed
//! is not running-in: each step settles on its own, and the test's
//! running-in is that of its first step). These are the `friction_tests`
//! rows.

use super::cycles::{flag_partial_strokes, CycleRow};
use super::motion::MIN_LAP_SAMPLES;
use super::running_in::{steady_state, SteadyParams, SteadyState};
use super::trace::TraceFeatures;
use super::wear_rate::{rate, Rate};
use crate::signal::stats;
use crate::status::{Code, InputRow, Status};

/// What a `friction_tests` row describes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Scope {
    /// The whole test.
    Test,
    /// One velocity step of it.
    Step,
    /// A test exported as several files ([`super::series`]).
    Series,
}

impl Scope {
    /// The stable text form.
    pub fn as_str(self) -> &'static str {
        match self {
            Scope::Test => "test",
            Scope::Step => "step",
            Scope::Series => "series",
        }
    }
}

/// One row of `friction_tests`.
#[derive(Debug, Clone, PartialEq)]
pub struct TestRow {
    /// The test, or one of its steps.
    pub scope: Scope,
    /// A step's section and number.
    pub step: Option<(String, usize)>,
    /// A step's sliding speed, m/s.
    pub velocity_m_per_s: Option<f64>,
    /// Where the cycles come from (`reversals`, `lap_counter`, …).
    pub cycle_source: Option<&'static str>,
    /// Where the sliding distance comes from.
    pub distance_source: Option<&'static str>,
    /// Cycles, and the whole ones judged.
    pub n_cycles: usize,
    /// Whole cycles with a μ.
    pub n_judged: usize,
    /// First and last cycle number of the row.
    pub cycles: Option<(usize, usize)>,
    /// The running-in and steady state.
    pub steady: SteadyState,
    /// Cycle number of the steady state's first cycle.
    pub steady_from_cycle: Option<usize>,
    /// Sliding distance of the running-in: from the row's first cycle to
    /// the steady state's first, m.
    pub running_in_distance_m: Option<f64>,
    /// μ of the first whole cycle, and the largest cycle μ.
    pub mu_first: Option<f64>,
    /// The largest whole-cycle μ.
    pub mu_max: Option<f64>,
    /// Sliding distance over the row's cycles, m.
    pub distance_m: Option<f64>,
    /// Friction energy over the row's cycles, J.
    pub energy_j: Option<f64>,
    /// Mean normal force over the whole cycles, N.
    pub normal_force_n: Option<f64>,
    /// Slope of the wear depth (each whole cycle's mean) against the
    /// sliding distance, m per m, with its standard error.
    pub wear_depth_rate: Option<Rate>,
    /// Change of the wear depth from the first whole cycle to the last, m.
    pub wear_depth_change_m: Option<f64>,
    /// `ok`, or why not.
    pub status: Status,
}

/// Numbers every trace's cycles through the test (in section order), with
/// their sliding distances carried on from section to section, and flags
/// the partial strokes (`fraction` of the median stroke).
pub fn number_cycles(features: &mut [TraceFeatures], fraction: f64) {
    let (mut next, mut carried) = (1, 0.0);
    for f in features.iter_mut() {
        let rows = &mut f.cycles.rows;
        let mut end = carried;
        for r in rows.iter_mut() {
            r.cycle = next;
            next += 1;
            if let Some((a, b)) = r.distance_m {
                r.distance_m = Some((a + carried, b + carried));
                end = b + carried;
            }
        }
        carried = end;
    }
    let mut all: Vec<&mut CycleRow> = features
        .iter_mut()
        .flat_map(|f| f.cycles.rows.iter_mut())
        .collect();
    flag_partial_strokes(&mut all, fraction);
}

/// The row of a run of cycles: their steady state and sums.
pub(super) fn row_of(cycles: &[&CycleRow], p: &SteadyParams) -> TestRow {
    let judged: Vec<&CycleRow> = cycles
        .iter()
        .copied()
        .filter(|c| c.complete && c.mu.is_some_and(f64::is_finite))
        .collect();
    let mu: Vec<f64> = judged.iter().filter_map(|c| c.mu).collect();
    let steady = steady_state(&mu, p);
    let onset = steady.onset.and_then(|k| judged.get(k));
    let start = judged.first().and_then(|c| c.distance_m).map(|d| d.0);
    let sum = |g: fn(&CycleRow) -> Option<f64>| -> Option<f64> {
        cycles.iter().map(|c| g(c)).sum::<Option<f64>>()
    };
    let worn: Vec<(f64, f64)> = judged
        .iter()
        .filter_map(|c| Some((0.5 * (c.distance_m?.0 + c.distance_m?.1), c.wear_depth_m?)))
        .collect();
    let (wx, wy): (Vec<f64>, Vec<f64>) = worn.iter().copied().unzip();
    let normal: Vec<f64> = judged.iter().filter_map(|c| c.normal_force_n).collect();
    TestRow {
        scope: Scope::Test,
        step: None,
        velocity_m_per_s: None,
        cycle_source: None,
        distance_source: None,
        n_cycles: cycles.len(),
        n_judged: judged.len(),
        cycles: cycles
            .first()
            .zip(cycles.last())
            .map(|(a, b)| (a.cycle, b.cycle)),
        steady_from_cycle: onset.map(|c| c.cycle),
        running_in_distance_m: onset.and_then(|c| Some(c.distance_m?.0 - start?)),
        mu_first: mu.first().copied(),
        mu_max: mu.iter().copied().reduce(f64::max),
        distance_m: sum(|c| c.distance_m.map(|(a, b)| b - a)),
        energy_j: sum(|c| c.energy_j),
        normal_force_n: stats::mean(&normal),
        wear_depth_rate: rate(&wx, &wy),
        wear_depth_change_m: worn.first().zip(worn.last()).map(|(a, b)| b.1 - a.1),
        status: inherited(steady.status.clone(), &judged),
        steady,
    }
}

/// A run of cycles' status: its steady state's, and `doubtful_points`
/// when judged cycles carry warnings that concern their μ (a doubt of
/// their stroke's static peak does not).
fn inherited(mut status: Status, judged: &[&CycleRow]) -> Status {
    let used: Vec<InputRow> = judged
        .iter()
        .map(|c| InputRow {
            label: format!("cycle {}", c.cycle),
            codes: (c.status.warnings().into_iter())
                .filter(|k| !k.doubts_static_peak_only())
                .collect(),
        })
        .collect();
    status.inherit(&used);
    status
}

/// The speeds of a trace's steps differ (more than `tolerance` of the
/// larger): a stepped-velocity test.
fn stepped(features: &[TraceFeatures], tolerance: f64) -> bool {
    let v: Vec<f64> = features
        .iter()
        .flat_map(|f| f.steps.iter().map(|(_, s)| s.velocity_m_per_s))
        .collect();
    let (lo, hi) = v.iter().fold((f64::INFINITY, 0.0f64), |(lo, hi), &x| {
        (lo.min(x), hi.max(x))
    });
    v.len() >= 2 && hi - lo > tolerance * hi
}

/// The `friction_tests` rows of a test whose cycles are numbered: one for
/// the test, and one per velocity step of a stepped test (the cycles whose
/// middle falls within the step); none for a test without cycles (a
/// single pull) that is not stepped.
pub fn assess(features: &[TraceFeatures], p: &SteadyParams, step_tolerance: f64) -> Vec<TestRow> {
    let all: Vec<&CycleRow> = features.iter().flat_map(|f| &f.cycles.rows).collect();
    let source = features
        .iter()
        .find_map(|f| f.cycles.source)
        .map(|s| s.as_str());
    let distance = features
        .iter()
        .find_map(|f| f.cycles.distance)
        .map(|s| s.as_str());
    let sparse: usize = features.iter().map(|f| f.cycles.sparse_laps).sum();
    let described = |mut r: TestRow| {
        (r.cycle_source, r.distance_source) = (source, distance);
        if sparse > 0 && r.scope == Scope::Test {
            r.status.push(
                Code::PartialCycle,
                format!("{sparse} laps have fewer than {MIN_LAP_SAMPLES} samples (the record samples them too sparsely) and are left out"),
            );
        }
        r
    };
    if !stepped(features, step_tolerance) {
        // A single pull (a sled) has no cycles, hence no row.
        return match all.is_empty() {
            true => Vec::new(),
            false => vec![described(row_of(&all, p))],
        };
    }
    let mut steps: Vec<TestRow> = Vec::new();
    for f in features {
        for (section, s) in &f.steps {
            let inside: Vec<&CycleRow> = f
                .cycles
                .rows
                .iter()
                .filter(|c| {
                    &c.section == section
                        && (s.span_s.0..=s.span_s.1).contains(&(0.5 * (c.start_s + c.end_s)))
                })
                .collect();
            let mut r = row_of(&inside, p);
            (r.scope, r.step, r.velocity_m_per_s) = (
                Scope::Step,
                Some((section.clone(), s.step)),
                Some(s.velocity_m_per_s),
            );
            steps.push(described(r));
        }
    }
    // The test: its running-in is its first step's; no single steady μ.
    let mut test = row_of(&all, p);
    let first = steps.iter().find(|s| s.n_judged > 0);
    test.steady = SteadyState {
        n: test.steady.n,
        method: first.and_then(|s| s.steady.method),
        onset: first.and_then(|s| s.steady.onset),
        ..Default::default()
    };
    test.steady_from_cycle = first.and_then(|s| s.steady_from_cycle);
    test.running_in_distance_m = first.and_then(|s| s.running_in_distance_m);
    test.status = Status::of(
        Code::SteppedTest,
        format!("{} velocity steps: the steady μ is per step (the step rows); the running-in is the first step's", steps.len()),
    );
    let mut out = vec![described(test)];
    out.extend(steps);
    out
}

/// The steady state's window in one section: from the first averaged
/// cycle's steady part to the last one's, when the test has a steady μ
/// and its averaged cycles lie in `section`.
pub fn steady_window(features: &TraceFeatures, test: &TestRow) -> Option<(f64, f64)> {
    let from = test.steady.mean_from?;
    let judged: Vec<&CycleRow> = features
        .cycles
        .rows
        .iter()
        .filter(|c| c.complete && c.mu.is_some_and(f64::is_finite))
        .collect();
    let first = judged.get(from)?;
    let last = judged.last()?;
    Some((first.window_s?.0, last.window_s?.1))
}
