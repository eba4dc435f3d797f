//! `tribo fit …`: model fits. Subcommands `nist`, `coulomb`, `ice`.

use std::path::PathBuf;
use std::process::ExitCode;

use tribo::fit::coulomb::linear::Loss;
use tribo::fit::coulomb::table::{coulomb_tables, read_samples_csv, CoulombTableParams};
use tribo::fit::ice::table::{ice_tables, read_table, PinRoughness};
use tribo::fit::ice::IceFitParams;
use tribo::fit::nist::{format_table, run_dir};
use tribo::fit::LmParams;
use tribo::models::makkonen::Thermal;
use tribo::report::{write_table, Provenance};
use tribo::table::Table;

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

/// Exit code 1 when some items finished without a result.
fn code(any_failed: bool) -> ExitCode {
    if any_failed {
        ExitCode::from(1)
    } else {
        ExitCode::SUCCESS
    }
}

/// Runs `tribo fit`.
pub fn run(args: &FitArgs) -> tribo::Result<ExitCode> {
    match &args.what {
        FitCommand::Nist { dir } => {
            let rows = run_dir(dir, &LmParams::default())?;
            print!("{}", format_table(&rows));
            Ok(code(rows.iter().any(|r| !r.status.is_converged())))
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

fn run_coulomb(a: &CoulombArgs) -> tribo::Result<ExitCode> {
    let (friction, _) = Table::read_parquet(&a.friction)?;
    let samples = match &a.samples {
        Some(p) => read_samples_csv(p)?,
        None => Default::default(),
    };
    let mut params = CoulombTableParams {
        reference_patterns: a.reference.clone(),
        ..Default::default()
    };
    if !a.by.is_empty() {
        params.groupings =
            a.by.iter()
                .map(|g| g.split(',').map(|c| c.trim().to_string()).collect())
                .collect();
    }
    if let Some(k) = a.huber {
        params.fit.loss = Loss::Huber { k };
    }
    let (c, s) = coulomb_tables(&friction, &samples, &params)?;
    let prov = Provenance::new("fit coulomb", &params);
    write_table(&a.out, "coulomb", &c, &prov)?;
    write_table(&a.out, "coulomb_summary", &s, &prov)?;
    let failed = c
        .str("status")?
        .iter()
        .filter(|s| !matches!(s.as_deref(), Some("ok" | "se_undefined")))
        .count();
    eprintln!("coulomb: {} fits, {failed} without a result", c.height());
    Ok(code(failed > 0))
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

fn run_ice(a: &IceArgs) -> tribo::Result<ExitCode> {
    let steps = read_table(&a.steps)?;
    let rough = match &a.roughness {
        Some(p) => PinRoughness::from_table(&read_table(p)?)?,
        None => PinRoughness::default(),
    };
    let params = IceFitParams {
        thermal: a
            .delta_t
            .map_or(Thermal::Bulk, |d| Thermal::Interface { delta_t: d }),
        fit_delta_t: a.fit_delta_t,
        misfit_tol: a.misfit_tol,
        ..Default::default()
    };
    let (fit, res) = ice_tables(&steps, &rough, &params)?;
    let prov = Provenance::new("fit ice", params);
    write_table(&a.out, "ice_fit", &fit, &prov)?;
    write_table(&a.out, "ice_residuals", &res, &prov)?;
    let status = fit.str("status")?;
    let misfit = fit.bool("misfit")?;
    let failed = status
        .iter()
        .filter(|s| s.as_deref() != Some("converged"))
        .count();
    let flagged = misfit.iter().filter(|m| **m == Some(true)).count();
    eprintln!(
        "ice: {} fits, {failed} not converged, {flagged} flagged as misfit",
        fit.height()
    );
    Ok(code(failed > 0))
}
