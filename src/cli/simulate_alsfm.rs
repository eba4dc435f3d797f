//! `tribo simulate alsfm SCENE.toml --out DIR`: runs an ALSFM scene file
//! (see `docs/alsfm.md` and `fixtures/alsfm/`) and writes `DIR/alsfm.parquet`
//! plus the tables the scene asks for (the `alsfm` stage).

use std::path::{Path, PathBuf};

use tribo::pipeline::exit::Tally;

use super::exec::{execute, set, table_stage};

/// Arguments of `tribo simulate alsfm`.
#[derive(Debug, Clone, clap::Args)]
pub struct SimulateAlsfmArgs {
    /// The scene file (TOML).
    pub scene: PathBuf,
    /// Output folder (created if missing).
    #[arg(long)]
    pub out: PathBuf,
}

/// Runs the scene: exit 0 when every scene point is `ok`, 1 when the run
/// finished but some points failed (locked, no contact, not converged), 2
/// for a bad scene file.
pub fn run(args: &SimulateAlsfmArgs) -> tribo::Result<Tally> {
    let mut spec = table_stage("alsfm", &args.out);
    set(
        spec.settings_mut("alsfm"),
        "scene",
        args.scene.display().to_string(),
    )?;
    execute(&spec, Path::new(""), None)
}
