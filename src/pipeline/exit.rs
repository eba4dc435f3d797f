//! The exit code of every command, decided by one rule ([`code`]) from
//! what the command counted ([`Tally`]) or the error that stopped it. A
//! script calling `tribo` branches on three cases, whatever the command:
//!
//! - 2: the command could not do what it was asked: a usage or
//!   configuration error (found before anything ran, or by a stage while
//!   running: its input table lacks a column it needs), or any error that
//!   stopped the command. The same call fails again until it is changed.
//! - 1: it finished, but some items have no result: failed files, rows
//!   without a result, fits that did not converge, files that could not
//!   be inspected, a batch job that failed. The others are written.
//! - 0: every item has a result. Warnings are not failures.

use crate::error::Result;

/// What a finished command counts against its exit code.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Tally {
    /// Configuration errors met while running (a stage's input table
    /// without a column it needs).
    pub configuration: usize,
    /// Items that finished without a result.
    pub without_result: usize,
}

impl Tally {
    /// Every item has a result.
    pub fn ok() -> Tally {
        Tally::default()
    }

    /// `n` items finished without a result.
    pub fn without_result(n: usize) -> Tally {
        Tally {
            without_result: n,
            ..Tally::default()
        }
    }
}

/// The exit code of a command that finished with `tally`, or stopped with
/// an error (see the module's doc for the rule).
pub fn code(ended: &Result<Tally>) -> u8 {
    match ended {
        Err(_) => 2,
        Ok(t) if t.configuration > 0 => 2,
        Ok(t) if t.without_result > 0 => 1,
        Ok(_) => 0,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::error::Error;

    #[test]
    fn one_rule_for_every_ending() {
        let t = |configuration, without_result| {
            Ok(Tally {
                configuration,
                without_result,
            })
        };
        assert_eq!(code(&Ok(Tally::ok())), 0);
        assert_eq!(code(&t(0, 1)), 1);
        assert_eq!(code(&Ok(Tally::without_result(7))), 1);
        // A configuration error outweighs failed items: the call itself
        // must change.
        assert_eq!(code(&t(1, 0)), 2);
        assert_eq!(code(&t(1, 5)), 2);
        for e in [
            Error::Config("bad flag".into()),
            Error::NotApplicable("no data".into()),
            Error::io(
                std::path::Path::new("x"),
                std::io::Error::from(std::io::ErrorKind::NotFound),
            ),
        ] {
            assert_eq!(code(&Err(e)), 2);
        }
    }

    /// A run's tally by mode: a shard counts only configuration errors, a
    /// dry run nothing.
    #[test]
    fn a_run_counts_by_its_mode() {
        use crate::pipeline::outcome::{FileFailure, RunReport, WithoutResult};
        use crate::pipeline::{shard::Shard, Mode};
        let bad = |e: Error| FileFailure::new("a.csv".into(), "friction", &e);
        let failed = RunReport {
            failures: vec![
                bad(Error::NotApplicable("no data".into())),
                bad(Error::NotApplicable("again".into())),
            ],
            without_result: vec![WithoutResult {
                stage: "coulomb".into(),
                rows: 2,
            }],
            ..Default::default()
        };
        let misconfigured = RunReport {
            failures: vec![bad(Error::Config("no column normal_force_N".into()))],
            ..Default::default()
        };
        let shard = Mode::Shard(Shard::parse("1/3").unwrap());
        let with = |r: &RunReport, mode| RunReport { mode, ..r.clone() };
        // One failed file (two failures) and two rows without a result.
        assert_eq!(failed.tally(), Tally::without_result(3));
        assert_eq!(failed.exit_code(), 1);
        assert_eq!(with(&failed, shard).exit_code(), 0);
        assert_eq!(with(&failed, Mode::DryRun).exit_code(), 0);
        for mode in [Mode::Run, shard] {
            assert_eq!(with(&misconfigured, mode).exit_code(), 2);
        }
        assert_eq!(RunReport::default().exit_code(), 0);
    }
}
