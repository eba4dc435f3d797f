//! `tribo plot FILE… --out DIR`: the report's figures of input files as
//! SVG files, for papers and quick looks. The files go through the same
//! per-file stages as in a pipeline (friction, roughness, tensile, each
//! taking the files of its kind) in a scratch output folder; their figure
//! tables are then written out as SVG.

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use tribo::pipeline::report::export_figures;
use tribo::pipeline::spec::PipelineSpec;

use super::exec::execute;

/// Arguments of `tribo plot`.
#[derive(clap::Args)]
pub struct PlotArgs {
    /// Friction traces, tensile curves, profiles or maps (globs are expanded).
    #[arg(required = true)]
    files: Vec<String>,
    /// Folder for the SVG files (`<file stem>[-<section>]-<figure>.svg`).
    #[arg(long)]
    out: PathBuf,
    /// Sample manifest CSV, as for the other commands (normal force,
    /// diameter, ...).
    #[arg(long)]
    samples: Option<PathBuf>,
    /// Force a reader instead of sniffing.
    #[arg(long)]
    format: Option<String>,
}

/// Runs `tribo plot`.
pub fn run(args: &PlotArgs) -> tribo::Result<ExitCode> {
    let scratch = args.out.join(".tribo-plot");
    let mut spec = PipelineSpec::single_stage(
        "friction",
        args.files.clone(),
        args.samples.as_ref().map(|p| p.display().to_string()),
        scratch.display().to_string(),
        args.format.clone(),
    );
    spec.stages = vec!["friction".into(), "roughness".into(), "tensile".into()];
    spec.output.traces = false;
    let code = execute(&spec, Path::new(""), None);
    let written = code.and_then(|c| export_figures(&scratch, &args.out).map(|w| (c, w)));
    let _ = std::fs::remove_dir_all(&scratch);
    let (code, written) = written?;
    for w in &written {
        println!("wrote {}", w.display());
    }
    Ok(code)
}
