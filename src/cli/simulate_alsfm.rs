//! `tribo simulate alsfm SCENE.toml --out DIR`: runs an ALSFM scene file
//! (see `docs/alsfm.md` and `fixtures/alsfm/`) and writes `DIR/alsfm.parquet`
//! plus the tables the scene asks for.

use std::path::PathBuf;
use std::process::ExitCode;

/// Arguments of `tribo simulate alsfm`.
#[derive(Debug, Clone, clap::Args)]
pub struct SimulateAlsfmArgs {
    /// The scene file (TOML).
    pub scene: PathBuf,
    /// Output folder (created if missing).
    #[arg(long)]
    pub out: PathBuf,
}

/// Runs the scene, prints the tables written and the points that failed,
/// and returns the exit code: 0 when every scene point is `ok`, 1 when the
/// run finished but some points failed (locked, no contact, not converged).
/// Errors (bad scene file, I/O) are returned; `main` maps them to 2.
pub fn exit_code(args: &SimulateAlsfmArgs) -> tribo::Result<u8> {
    let summary = tribo::simulate::alsfm::run_scene_file(&args.scene, &args.out)?;
    for p in &summary.written {
        println!("{}", p.display());
    }
    for p in &summary.output.points {
        if p.status != "ok" && p.status != "no_coefficient" {
            eprintln!(
                "beta = {} deg, load = {}: {}: {}",
                p.beta_deg, p.load, p.status, p.message
            );
        }
    }
    Ok(if summary.failures == 0 { 0 } else { 1 })
}

/// [`exit_code`] as a process exit code.
pub fn run(args: &SimulateAlsfmArgs) -> tribo::Result<ExitCode> {
    exit_code(args).map(ExitCode::from)
}
