//! How a run runs, decided once from the command line, before anything
//! starts: a whole run that publishes its set; a dry run that reads and
//! writes nothing and lists what would be redone; or one shard of N that
//! fills the cache with its share of the work, for a later run to publish.

use super::shard::Shard;
use crate::error::{Error, Result};

/// How a run runs.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Mode {
    /// Compute what changed and publish the set.
    #[default]
    Run,
    /// Write nothing; list what would be redone, and why.
    DryRun,
    /// Run this shard's share of the work into the cache; publish nothing.
    Shard(Shard),
}

impl Mode {
    /// The mode of `--dry-run` and `--shard`; both at once is an error.
    pub fn new(dry_run: bool, shard: Option<Shard>) -> Result<Mode> {
        match (dry_run, shard) {
            (true, Some(_)) => Err(Error::Config(
                "--dry-run and --shard together: a shard runs its share, a dry run nothing".into(),
            )),
            (true, None) => Ok(Mode::DryRun),
            (false, Some(s)) => Ok(Mode::Shard(s)),
            (false, None) => Ok(Mode::Run),
        }
    }

    /// Whether the run writes into the output folder (its cache, its set).
    pub fn writes(self) -> bool {
        self != Mode::DryRun
    }

    /// Whether the run publishes a set (and so holds the folder's lock).
    pub fn publishes(self) -> bool {
        self == Mode::Run
    }

    /// The shard, in a shard's run.
    pub fn shard(self) -> Option<Shard> {
        match self {
            Mode::Shard(s) => Some(s),
            _ => None,
        }
    }
}
