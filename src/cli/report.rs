//! `tribo report OUTDIR`: the report of an output folder, rendered again
//! from its published tables (for example after an upgrade of tribo, or
//! for a folder written with `report = false` and then a run with it).

use std::path::PathBuf;
use std::time::Duration;

use tribo::pipeline::exit::Tally;

/// Arguments of `tribo report`.
#[derive(clap::Args)]
pub struct ReportArgs {
    /// An output folder a pipeline or command wrote.
    out: PathBuf,
    /// When a run holds the folder, wait up to this many seconds.
    #[arg(long, value_name = "SECONDS", default_value_t = 0.0)]
    wait: f64,
}

/// Runs `tribo report`.
pub fn run(args: &ReportArgs) -> tribo::Result<Tally> {
    if !(args.wait >= 0.0 && args.wait.is_finite()) {
        return Err(tribo::Error::Config(format!(
            "--wait {}: expected a number of seconds >= 0",
            args.wait
        )));
    }
    let path = tribo::pipeline::report::rewrite(&args.out, Duration::from_secs_f64(args.wait))?;
    println!("wrote {}", path.display());
    Ok(Tally::ok())
}
