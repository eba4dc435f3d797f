//! `tribo run PIPELINE.toml`

use std::path::PathBuf;

use std::time::{Duration, Instant};

use tribo::pipeline::exit::Tally;
use tribo::pipeline::preload::Preload;
use tribo::pipeline::shard::Shard;
use tribo::pipeline::{Mode, Plan, RunOptions};

use super::exec::{execute_plan, How};

/// Arguments of `tribo run`.
#[derive(clap::Args)]
pub struct RunArgs {
    /// Pipeline file (TOML): inputs by glob, sample manifest, column and unit
    /// overrides, the stages and their settings. Paths in it are relative to
    /// it.
    pipeline: PathBuf,
    /// Output folder, overriding the pipeline's [output] dir.
    #[arg(long)]
    out: Option<PathBuf>,
    /// Worker threads (default: all cores). Results do not depend on it.
    #[arg(long)]
    threads: Option<usize>,
    /// Print a machine-readable summary on stdout (counts of files
    /// processed, reused, failed and unrouted, stages run and reused, the
    /// tables).
    #[arg(long)]
    json: bool,
    /// Write nothing; list each file or stage that would be redone, and why.
    #[arg(long)]
    dry_run: bool,
    /// Ignore the cache: recompute everything.
    #[arg(long)]
    force: bool,
    /// Read and hash every input again, even those whose size, times and
    /// inode are the ones the last run saw (a weekly check).
    #[arg(long)]
    verify: bool,
    /// When another run holds the output folder, wait up to this many
    /// seconds for it instead of exiting.
    #[arg(long, value_name = "SECONDS", default_value_t = 0.0)]
    wait: f64,
    /// Process only shard I of N (0-based) of the work, filling the cache;
    /// `tribo run` without it then assembles the tables. Taken from
    /// SLURM_ARRAY_TASK_ID / SLURM_ARRAY_TASK_COUNT inside a job array.
    #[arg(long, value_name = "I/N")]
    shard: Option<String>,
}

/// Runs `tribo run`.
pub fn run(args: &RunArgs) -> tribo::Result<Tally> {
    let started = Instant::now();
    // The last run's state is read while the inputs are listed.
    let (spec, base) = Plan::spec_of(&args.pipeline)?;
    let out = (args.out.clone()).unwrap_or_else(|| Plan::out_dir_of(&spec, &base));
    let preload = (!args.force).then(|| Preload::start(&out)).flatten();
    let mut plan = Plan::from_spec(&spec, &base)?;
    plan.out_dir = out;
    if !(args.wait >= 0.0 && args.wait.is_finite()) {
        return Err(tribo::Error::Config(format!(
            "--wait {}: expected a number of seconds >= 0",
            args.wait
        )));
    }
    let shard = match &args.shard {
        Some(s) => Some(Shard::parse(s)?),
        None => Shard::from_env(|k| std::env::var(k).ok())?,
    };
    let how = How {
        threads: args.threads,
        json: args.json,
        options: RunOptions {
            force: args.force,
            mode: Mode::new(args.dry_run, shard)?,
            wait: Duration::from_secs_f64(args.wait),
            verify: args.verify,
            started: Some(started),
            preload,
        },
    };
    execute_plan(&plan, &how)
}
