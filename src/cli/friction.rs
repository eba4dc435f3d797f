//! `tribo friction FILE... --out DIR [--samples SAMPLES.csv]`

use std::path::Path;

use tribo::pipeline::exit::Tally;

use super::exec::execute;
use super::file_args::StageArgs;

/// Arguments of `tribo friction`.
#[derive(clap::Args)]
pub struct FrictionArgs {
    /// Friction traces, output folder (friction, friction_steps,
    /// stickslip, traces tables), samples (normal_force_N or mass_g,
    /// apparent_area_m2, pattern, ...), reader, settings.
    #[command(flatten)]
    stage: StageArgs,
    /// Do not write traces.parquet (every sample in SI; the largest table).
    #[arg(long)]
    no_traces: bool,
}

/// Runs `tribo friction`.
pub fn run(args: &FrictionArgs) -> tribo::Result<Tally> {
    let mut spec = args.stage.spec("friction")?;
    spec.output.traces = !args.no_traces;
    execute(&spec, Path::new(""), None)
}
