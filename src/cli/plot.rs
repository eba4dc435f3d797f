//! `tribo plot FILE… --out DIR`: the report's figures of input files as
//! SVG files, for papers and quick looks. The files go through the same
//! per-file stages as in a pipeline (friction, roughness, tensile, each
//! taking the files of its kind) in a scratch output folder; their figure
//! tables are then written out as SVG.

use std::path::Path;

use tribo::pipeline::exit::Tally;
use tribo::pipeline::report::export_figures;

use super::exec::execute;
use super::file_args::FileArgs;

/// Arguments of `tribo plot`.
#[derive(clap::Args)]
pub struct PlotArgs {
    /// Friction traces, tensile curves, profiles or maps; the folder for
    /// the SVG files (`<file stem>[-<section>]-<figure>.svg`); samples
    /// (normal force, diameter, ...); reader.
    #[command(flatten)]
    files: FileArgs,
}

/// Runs `tribo plot`.
pub fn run(args: &PlotArgs) -> tribo::Result<Tally> {
    let out = args.files.out.clone().unwrap_or_default();
    let scratch = out.join(".tribo-plot");
    let mut spec = args.files.spec("friction");
    spec.output.dir = scratch.display().to_string();
    spec.stages = vec!["friction".into(), "roughness".into(), "tensile".into()];
    spec.output.traces = false;
    let code = execute(&spec, Path::new(""), None);
    let written = code.and_then(|c| export_figures(&scratch, &out).map(|w| (c, w)));
    let _ = std::fs::remove_dir_all(&scratch);
    let (code, written) = written?;
    for w in &written {
        println!("wrote {}", w.display());
    }
    Ok(code)
}
