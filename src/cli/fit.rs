//! `tribo fit …`: model fits. Subcommands `nist`, `coulomb`, `ice`.

use std::path::{Path, PathBuf};

use tribo::fit::nist::{format_table, run_dir};
use tribo::fit::LmParams;
use tribo::pipeline::exit::Tally;
use tribo::stages::coulomb::CoulombSettings;
use tribo::stages::ice::IceSettings;

use super::exec::{execute, set, table_stage};

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
    Coulomb(CoulombArgs),
    /// Makkonen film model with ALSFM roughness bounds (MODELS.md §6).
    Ice(IceArgs),
}

/// Runs `tribo fit`.
pub fn run(args: &FitArgs) -> tribo::Result<Tally> {
    match &args.what {
        FitCommand::Nist { dir } => {
            let rows = run_dir(dir, &LmParams::default())?;
            print!("{}", format_table(&rows));
            // A start that did not converge has no result.
            let failed = rows.iter().filter(|r| !r.status.is_converged()).count();
            Ok(Tally::without_result(failed))
        }
        FitCommand::Coulomb(a) => run_coulomb(a),
        FitCommand::Ice(a) => run_ice(a),
    }
}

/// Arguments of `tribo fit coulomb`.
#[derive(clap::Args, Debug)]
pub struct CoulombArgs {
    /// friction.parquet written by `tribo friction`.
    pub friction: PathBuf,
    /// Output folder (coulomb.parquet, coulomb_summary.parquet).
    #[arg(long)]
    pub out: PathBuf,
    /// Grouping columns, comma-separated; repeat for several groupings.
    /// Default: `sample_id` and `pattern`.
    #[arg(long)]
    pub by: Vec<String>,
    /// Samples manifest CSV (sample_id, apparent_area_m2, pattern, area_fraction).
    #[arg(long)]
    pub samples: Option<PathBuf>,
    /// Pattern name(s) of the flat reference for Eq. 4.2 (case-insensitive).
    #[arg(long, default_values = ["F", "flat"])]
    pub reference: Vec<String>,
    /// Huber loss threshold k (robust fit); least squares when absent.
    #[arg(long)]
    pub huber: Option<f64>,
}

/// The input tables of a table stage, given as files.
fn inputs(pairs: &[(&str, Option<&PathBuf>)]) -> tribo::Result<toml::Value> {
    let mut t = toml::Table::new();
    for (name, path) in pairs {
        if let Some(p) = path {
            set(&mut t, name, p.display().to_string())?;
        }
    }
    Ok(toml::Value::Table(t))
}

fn run_coulomb(a: &CoulombArgs) -> tribo::Result<Tally> {
    let settings = CoulombSettings {
        by: a.by.clone(),
        reference: a.reference.clone(),
        huber: a.huber,
        samples: a.samples.as_ref().map(|p| p.display().to_string()),
    };
    let mut spec = table_stage("coulomb", &a.out);
    let table = spec.settings_mut("coulomb");
    *table = toml::Table::try_from(&settings)
        .map_err(|e| tribo::Error::Config(format!("coulomb settings: {e}")))?;
    table.insert("inputs".into(), inputs(&[("friction", Some(&a.friction))])?);
    execute(&spec, Path::new(""), None)
}

/// Arguments of `tribo fit ice`.
#[derive(clap::Args, Debug)]
pub struct IceArgs {
    /// friction_steps table (Parquet, or CSV with the same column names).
    pub steps: PathBuf,
    /// Output folder (ice_fit.parquet, ice_residuals.parquet).
    #[arg(long)]
    pub out: PathBuf,
    /// Roughness table with `pin` and `Rdq_deg` (when the steps table has
    /// no `Rdq_deg`).
    #[arg(long)]
    pub roughness: Option<PathBuf>,
    /// Use this interface ΔT (K) instead of T_m − T_bulk.
    #[arg(long)]
    pub delta_t: Option<f64>,
    /// Fit ΔT jointly with a and report their correlation.
    #[arg(long)]
    pub fit_delta_t: bool,
    /// Relative RMSE above which a fit is flagged as a misfit.
    #[arg(long, default_value_t = 0.15)]
    pub misfit_tol: f64,
}

fn run_ice(a: &IceArgs) -> tribo::Result<Tally> {
    let settings = IceSettings {
        delta_t: a.delta_t,
        fit_delta_t: a.fit_delta_t,
        misfit_tol: a.misfit_tol,
    };
    let mut spec = table_stage("ice", &a.out);
    let table = spec.settings_mut("ice");
    *table = toml::Table::try_from(&settings)
        .map_err(|e| tribo::Error::Config(format!("ice settings: {e}")))?;
    table.insert(
        "inputs".into(),
        inputs(&[
            ("friction_steps", Some(&a.steps)),
            ("roughness", a.roughness.as_ref()),
        ])?,
    );
    execute(&spec, Path::new(""), None)
}
