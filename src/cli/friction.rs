//! `tribo friction FILE... --out DIR [--samples SAMPLES.csv]`

use std::path::PathBuf;
use std::process::ExitCode;

use tribo::pipeline::spec::{IngestSpec, InputSpec, OutputSpec, PipelineSpec};
use tribo::pipeline::{run as run_plan, Plan};

use super::progress;

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
}

/// Runs `tribo friction`.
pub fn run(args: &FrictionArgs) -> tribo::Result<ExitCode> {
    let friction = match &args.params {
        Some(p) => {
            let text = std::fs::read_to_string(p).map_err(|e| tribo::Error::io(p, e))?;
            toml::from_str(&text)
                .map_err(|e| tribo::Error::Config(format!("{}: {e}", p.display())))?
        }
        None => Default::default(),
    };
    let spec = PipelineSpec {
        input: InputSpec {
            files: args.files.clone(),
            samples: args.samples.as_ref().map(|p| p.display().to_string()),
        },
        output: OutputSpec {
            dir: args.out.display().to_string(),
        },
        ingest: IngestSpec {
            format: args.format.clone(),
            ..Default::default()
        },
        stages: vec!["friction".into()],
        friction,
    };
    let plan = Plan::from_spec(&spec, std::path::Path::new(""))?;
    let bar = progress::bar(plan.files.len(), "friction");
    let report = run_plan(&plan, "friction", &|| bar.inc(1))?;
    bar.finish_and_clear();
    Ok(progress::summarise(&report))
}
