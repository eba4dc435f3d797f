//! `tribo simulate spring-block FILE.toml --out DIR [--threads N]`
//!
//! FILE is a scene (one pattern: pressures × repetitions) or a comparison
//! study (`scenes = [...]` plus measured Coulomb fits); see
//! `docs/spring_block.md`. The `spring-block` stage.

use std::path::{Path, PathBuf};

use tribo::pipeline::exit::Tally;

use super::exec::{execute, set, table_stage};

/// Arguments of `tribo simulate spring-block`.
#[derive(clap::Args, Debug)]
pub struct SimulateSpringBlockArgs {
    /// Scene or comparison-study TOML file.
    file: PathBuf,
    /// Output folder for spring_block, spring_block_summary,
    /// spring_block_curves (and spring_block_compare) Parquet tables.
    #[arg(long)]
    out: PathBuf,
    /// Worker threads (default: all cores). Results do not depend on it.
    #[arg(long)]
    threads: Option<usize>,
}

/// Runs `tribo simulate spring-block`: exit 0 when every run completed, 1
/// when some diverged or reached max_time (their rows say why).
pub fn run(args: &SimulateSpringBlockArgs) -> tribo::Result<Tally> {
    let mut spec = table_stage("spring-block", &args.out);
    set(
        spec.settings_mut("spring-block"),
        "scene",
        args.file.display().to_string(),
    )?;
    execute(&spec, Path::new(""), args.threads)
}
