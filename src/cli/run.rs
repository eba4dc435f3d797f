//! `tribo run PIPELINE.toml`

use std::path::PathBuf;
use std::process::ExitCode;

use tribo::pipeline::{run as run_plan, Plan};

use super::progress;

/// Arguments of `tribo run`.
#[derive(clap::Args)]
pub struct RunArgs {
    /// Pipeline file (TOML): inputs by glob, sample manifest, column and unit
    /// overrides, stage parameters. Paths in it are relative to it.
    pipeline: PathBuf,
    /// Output folder, overriding the pipeline's [output] dir.
    #[arg(long)]
    out: Option<PathBuf>,
}

/// Runs `tribo run`.
pub fn run(args: &RunArgs) -> tribo::Result<ExitCode> {
    let mut plan = Plan::from_file(&args.pipeline)?;
    if let Some(out) = &args.out {
        plan.out_dir = out.clone();
    }
    let bar = progress::bar(plan.files.len(), "run");
    let command = format!("run {}", args.pipeline.display());
    let report = run_plan(&plan, &command, &|| bar.inc(1))?;
    bar.finish_and_clear();
    Ok(progress::summarise(&report))
}
