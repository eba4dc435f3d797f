//! `tribo run PIPELINE.toml`

use std::path::PathBuf;
use std::process::ExitCode;

use tribo::pipeline::Plan;

use super::exec::execute_plan;

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
}

/// Runs `tribo run`.
pub fn run(args: &RunArgs) -> tribo::Result<ExitCode> {
    let mut plan = Plan::from_file(&args.pipeline)?;
    if let Some(out) = &args.out {
        plan.out_dir = out.clone();
    }
    let command = format!("run {}", args.pipeline.display());
    execute_plan(&plan, &command, args.threads)
}
