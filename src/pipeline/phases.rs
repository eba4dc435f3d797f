//! Where a run's time went: the wall time of each of its phases, in the
//! order they ran (`tribo run --json` prints them as `phases_s`). A
//! scheduled run over a growing archive is judged by what each phase
//! costs as the archive grows (`docs/scheduling.md`), so the split is
//! measured by the run itself, not by a build made to time it.

use std::time::Instant;

use serde::Serialize;

/// The phases a run passes, each timed from the end of the one before.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Phase {
    /// The pipeline read and its inputs listed (timed when the command
    /// says when it began: [`super::RunOptions::started`]).
    Plan,
    /// The last run's state read (or, from `tribo run`, its reading
    /// finished: it begins with the plan, [`super::preload`]) and every
    /// input's stat taken.
    State,
    /// The per-file phase: each input found unchanged, or read and
    /// extracted, and recorded.
    Files,
    /// The per-file stages' tables joined from their parts and assembled.
    Join,
    /// The table stages (fits, simulations, comparisons) run or reused.
    TableStages,
    /// The set's tables and the run's own (`files`, `errors`) written.
    Tables,
    /// The report rendered or kept, the warnings counted.
    Report,
    /// The set published, the state saved, the cache pruned.
    Commit,
}

/// A phase and its wall time.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct PhaseTime {
    /// The phase.
    pub phase: Phase,
    /// Its wall time, in seconds.
    pub seconds: f64,
}

/// A stopwatch that records a phase each time one ends.
#[derive(Debug, Clone)]
pub struct Stopwatch {
    since: Instant,
    times: Vec<PhaseTime>,
}

impl Default for Stopwatch {
    fn default() -> Self {
        Stopwatch {
            since: Instant::now(),
            times: Vec::new(),
        }
    }
}

impl Stopwatch {
    /// A stopwatch from now; given when the command began (`started`),
    /// the time since then is already its plan phase.
    pub fn from(started: Option<Instant>) -> Stopwatch {
        let mut w = Stopwatch::default();
        if let Some(at) = started {
            w.since = at;
            w.mark(Phase::Plan);
        }
        w
    }

    /// `phase` has ended now: its time is the time since the last mark.
    /// A phase marked twice (each per-file stage's join) adds up.
    pub fn mark(&mut self, phase: Phase) {
        let now = Instant::now();
        let seconds = now.duration_since(self.since).as_secs_f64();
        self.since = now;
        match self.times.iter_mut().find(|t| t.phase == phase) {
            Some(t) => t.seconds += seconds,
            None => self.times.push(PhaseTime { phase, seconds }),
        }
    }

    /// The phases marked, in the order they first ended.
    pub fn times(&self) -> &[PhaseTime] {
        &self.times
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn phases_add_up_in_order_of_first_end() {
        // `start` comes first: the stopwatch's own start is then no
        // earlier, and the phases cannot add up to more than `whole`.
        let start = Instant::now();
        let mut w = Stopwatch::default();
        w.mark(Phase::State);
        std::thread::sleep(std::time::Duration::from_millis(2));
        w.mark(Phase::Join);
        w.mark(Phase::TableStages);
        std::thread::sleep(std::time::Duration::from_millis(2));
        w.mark(Phase::Join);
        let whole = start.elapsed().as_secs_f64();
        let order: Vec<Phase> = w.times().iter().map(|t| t.phase).collect();
        assert_eq!(order, [Phase::State, Phase::Join, Phase::TableStages]);
        let join = w.times()[1].seconds;
        assert!(join >= 0.004, "both joins counted: {join}");
        let sum: f64 = w.times().iter().map(|t| t.seconds).sum();
        assert!(sum <= whole + 1e-9, "{sum} > {whole}");
    }
}
