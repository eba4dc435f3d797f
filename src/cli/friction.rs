//! `tribo friction FILE... --out DIR [--samples SAMPLES.csv]`

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use tribo::pipeline::spec::PipelineSpec;

use super::exec::{execute, params_file};

/// Arguments of `tribo friction`.
#[derive(clap::Args)]
pub struct FrictionArgs {
    /// Friction traces (globs are expanded).
    #[arg(required = true)]
    files: Vec<String>,
    /// Output folder for friction, friction_steps, stickslip, traces and
    /// errors Parquet tables.
    #[arg(long)]
    out: PathBuf,
    /// Sample manifest CSV (file, sample_id, normal_force_N or mass_g,
    /// apparent_area_m2, pattern, ...), joined on the file name.
    #[arg(long)]
    samples: Option<PathBuf>,
    /// Force a reader instead of sniffing.
    #[arg(long)]
    format: Option<String>,
    /// Stage parameters as a TOML file with the keys of a pipeline's
    /// [friction] table.
    #[arg(long)]
    params: Option<PathBuf>,
    /// Do not write traces.parquet (every sample in SI; the largest table).
    #[arg(long)]
    no_traces: bool,
}

/// Runs `tribo friction`.
pub fn run(args: &FrictionArgs) -> tribo::Result<ExitCode> {
    let mut spec = PipelineSpec::single_stage(
        "friction",
        args.files.clone(),
        args.samples.as_ref().map(|p| p.display().to_string()),
        args.out.display().to_string(),
        args.format.clone(),
    );
    spec.output.traces = !args.no_traces;
    *spec.settings_mut("friction") = params_file(args.params.as_deref())?;
    execute(&spec, Path::new(""), None)
}
