//! `tribo fit …`: model fits. Subcommands `nist`, `coulomb`, `ice`.

use std::path::PathBuf;

use tribo::fit::nist::{format_table, run_dir};
use tribo::fit::LmParams;

/// Arguments of `tribo fit`.
#[derive(clap::Args, Debug)]
pub struct FitArgs {
    /// What to fit.
    #[command(subcommand)]
    pub what: FitCommand,
}

/// The fits.
#[derive(clap::Subcommand, Debug)]
pub enum FitCommand {
    /// Validate the solver on the NIST StRD nonlinear suite and print the
    /// table of correct digits (LRE) per problem and start.
    Nist {
        /// Folder with the NIST .dat files.
        #[arg(default_value = "../shared/data/nist_strd")]
        dir: PathBuf,
    },
    /// Coulomb law with cohesion, τ = τ0 + μ p (MODELS.md §2).
    Coulomb(crate::cli::fit_coulomb::CoulombArgs),
    /// Makkonen film model with ALSFM roughness bounds (MODELS.md §6).
    Ice(crate::cli::fit_ice::IceArgs),
}

/// Runs `tribo fit`.
pub fn run(args: &FitArgs) -> tribo::Result<()> {
    match &args.what {
        FitCommand::Nist { dir } => {
            let rows = run_dir(dir, &LmParams::default())?;
            print!("{}", format_table(&rows));
            Ok(())
        }
        FitCommand::Coulomb(a) => crate::cli::fit_coulomb::run(a),
        FitCommand::Ice(a) => crate::cli::fit_ice::run(a),
    }
}
