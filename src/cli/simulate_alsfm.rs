//! `tribo simulate alsfm SCENE.toml --out DIR`: runs an ALSFM scene file
//! (see `docs/alsfm.md` and `fixtures/alsfm/`) and writes `DIR/alsfm.parquet`
//! plus the tables the scene asks for.

use std::path::PathBuf;

/// Arguments of `tribo simulate alsfm`.
#[derive(Debug, Clone, clap::Args)]
pub struct SimulateAlsfmArgs {
    /// The scene file (TOML).
    pub scene: PathBuf,
    /// Output folder (created if missing).
    #[arg(long)]
    pub out: PathBuf,
}

/// Runs the scene. Returns the exit code: 0 when every scene point is `ok`,
/// 1 when the run finished but some points have another status (their
/// `message` says why). Errors (bad scene file, I/O) map to exit code 2.
pub fn run(args: &SimulateAlsfmArgs) -> tribo::Result<u8> {
    let summary = tribo::simulate::alsfm::run_scene_file(&args.scene, &args.out)?;
    Ok(if summary.failures == 0 { 0 } else { 1 })
}
