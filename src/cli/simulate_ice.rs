//! `tribo simulate ice`: the Makkonen model and its roughness bounds on a
//! grid of (v, T, a, φ), written as `ice_grid.parquet` (the `ice-grid`
//! stage).

use std::path::{Path, PathBuf};

use tribo::pipeline::exit::Tally;
use tribo::stages::ice_grid::IceGridSettings;

use super::exec::{execute, table_stage};

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
pub fn run(args: &SimulateIceArgs) -> tribo::Result<Tally> {
    let num = |s: &str| {
        s.parse::<f64>()
            .map_err(|_| tribo::Error::Config(format!("--v expects numbers LO HI N, got '{s}'")))
    };
    let settings = IceGridSettings {
        v: [num(&args.v[0])?, num(&args.v[1])?, num(&args.v[2])?],
        t: args.t.clone(),
        a: args.a.clone(),
        phi: args.phi.clone(),
        delta_t: args.delta_t,
        mu_max: None,
    };
    let mut spec = table_stage("ice-grid", &args.out);
    *spec.settings_mut("ice-grid") = toml::Table::try_from(&settings)
        .map_err(|e| tribo::Error::Config(format!("ice grid: {e}")))?;
    execute(&spec, Path::new(""), None)
}
