//! `tribo simulate ice`: the Makkonen model and its roughness bounds on a
//! grid of (v, T, a, φ), written as `ice_grid.parquet`.

use std::path::PathBuf;
use std::process::ExitCode;

use tribo::models::makkonen::{MakkonenParams, Thermal};
use tribo::report::{write_table, Provenance};
use tribo::simulate::ice::{logspace, simulate_ice, IceGrid};

/// Arguments of `tribo simulate`.
#[derive(clap::Args, Debug)]
pub struct SimulateArgs {
    /// What to simulate.
    #[command(subcommand)]
    pub what: SimulateCommand,
}

/// The simulations.
#[derive(clap::Subcommand, Debug)]
pub enum SimulateCommand {
    /// Makkonen film model with ALSFM roughness bounds on a (v, T, a, φ)
    /// grid (MODELS.md §6); writes ice_grid.parquet.
    Ice(SimulateIceArgs),
    /// 2-D spring-block model of patterned surfaces (thesis Ch. 4): a scene
    /// (pressures × repetitions) or a comparison study against measured
    /// Coulomb fits (docs/spring_block.md); writes spring_block*.parquet.
    SpringBlock(super::simulate_spring_block::SimulateSpringBlockArgs),
}

/// Runs `tribo simulate`.
pub fn run_simulate(args: &SimulateArgs) -> tribo::Result<ExitCode> {
    match &args.what {
        SimulateCommand::Ice(a) => run(a),
        SimulateCommand::SpringBlock(a) => super::simulate_spring_block::run(a),
    }
}

/// Arguments of `tribo simulate ice`.
#[derive(clap::Args, Debug)]
pub struct SimulateIceArgs {
    /// Output folder.
    #[arg(long)]
    pub out: PathBuf,
    /// Velocity range: lowest, highest (m/s) and count, log-spaced.
    #[arg(long, num_args = 3, value_names = ["LO", "HI", "N"], default_values = ["0.025", "1", "40"])]
    pub v: Vec<String>,
    /// Bulk temperatures, °C.
    #[arg(long, value_delimiter = ',', default_value = "-17,-10,-2")]
    pub t: Vec<f64>,
    /// Contact lengths, m.
    #[arg(long, value_delimiter = ',', default_value = "1e-5,1e-4")]
    pub a: Vec<f64>,
    /// Slopes φ (Rdq), degrees.
    #[arg(long, value_delimiter = ',', default_value = "7.3,27.2,33.6")]
    pub phi: Vec<f64>,
    /// Interface ΔT (K) instead of T_m − T_bulk.
    #[arg(long)]
    pub delta_t: Option<f64>,
}

/// Runs `tribo simulate ice`.
pub fn run(args: &SimulateIceArgs) -> tribo::Result<ExitCode> {
    let num = |s: &str| {
        s.parse::<f64>()
            .map_err(|_| tribo::Error::Config(format!("--v expects numbers LO HI N, got '{s}'")))
    };
    let (lo, hi, n) = (num(&args.v[0])?, num(&args.v[1])?, num(&args.v[2])?);
    let grid = IceGrid {
        velocities_m_per_s: logspace(lo, hi, n as usize)?,
        temperatures_c: args.t.clone(),
        a_m: args.a.clone(),
        phi_deg: args.phi.clone(),
        model: MakkonenParams::default(),
        thermal: args
            .delta_t
            .map_or(Thermal::Bulk, |d| Thermal::Interface { delta_t: d }),
    };
    let table = simulate_ice(&grid)?;
    write_table(
        &args.out,
        "ice_grid",
        &table,
        &Provenance::new("simulate ice", &grid),
    )?;
    Ok(ExitCode::SUCCESS)
}
