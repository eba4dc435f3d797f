//! `tribo simulate …`: one subcommand per model, each in its own file.

use tribo::pipeline::exit::Tally;

use super::{simulate_alsfm, simulate_ice, simulate_spring_block};

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
    Ice(simulate_ice::SimulateIceArgs),
    /// ALSFM: anisotropic friction of rough surfaces with adhesion, wear and
    /// hierarchy, from a scene file (MODELS.md §5); writes alsfm*.parquet.
    Alsfm(simulate_alsfm::SimulateAlsfmArgs),
    /// 2-D spring-block model of patterned surfaces (thesis Ch. 4): a scene
    /// (pressures × repetitions) or a comparison study against measured
    /// Coulomb fits (docs/spring_block.md); writes spring_block*.parquet.
    SpringBlock(simulate_spring_block::SimulateSpringBlockArgs),
}

/// Runs `tribo simulate`.
pub fn run(args: &SimulateArgs) -> tribo::Result<Tally> {
    match &args.what {
        SimulateCommand::Ice(a) => simulate_ice::run(a),
        SimulateCommand::Alsfm(a) => simulate_alsfm::run(a),
        SimulateCommand::SpringBlock(a) => simulate_spring_block::run(a),
    }
}
