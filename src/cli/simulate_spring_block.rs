//! `tribo simulate spring-block FILE.toml --out DIR [--threads N]`
//!
//! FILE is a scene (one pattern: pressures × repetitions) or a comparison
//! study (`scenes = [...]` plus measured Coulomb fits); see
//! `docs/spring_block.md`.

use std::path::PathBuf;
use std::process::ExitCode;

use indicatif::{ProgressBar, ProgressStyle};
use tribo::simulate::spring_block::load_input;

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
pub fn run(args: &SimulateSpringBlockArgs) -> tribo::Result<ExitCode> {
    let (input, hashes) = load_input(&args.file)?;
    let n = input.runs();
    let pb = ProgressBar::new(n as u64);
    pb.set_style(
        ProgressStyle::with_template(
            "{spinner} spring-block [{bar:30}] {pos}/{len} runs, {elapsed} (eta {eta})",
        )
        .expect("valid template")
        .progress_chars("=> "),
    );
    let go = || input.run(&args.out, hashes.clone(), &|| pb.inc(1));
    let outcome = match args.threads {
        Some(t) => rayon::ThreadPoolBuilder::new()
            .num_threads(t)
            .build()
            .map_err(|e| tribo::Error::Config(format!("--threads {t}: {e}")))?
            .install(go)?,
        None => go()?,
    };
    pb.finish_and_clear();
    for p in &outcome.outputs {
        eprintln!("wrote {}", p.display());
    }
    for m in &outcome.failure_messages {
        eprintln!("FAILED {m}");
    }
    eprintln!(
        "{} runs, {} did not complete",
        outcome.runs, outcome.failures
    );
    Ok(if outcome.failures == 0 {
        ExitCode::SUCCESS
    } else {
        ExitCode::from(1)
    })
}
