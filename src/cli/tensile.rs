//! `tribo tensile FILE... --out DIR [--samples SAMPLES.csv]` and
//! `tribo tensile summarize TABLE --out DIR`.

use std::path::{Path, PathBuf};

use tribo::pipeline::exit::Tally;

use super::exec::{execute, set, table_stage};
use super::file_args::StageArgs;

/// Arguments of `tribo tensile`.
#[derive(clap::Args)]
#[command(args_conflicts_with_subcommands = true, subcommand_negates_reqs = true)]
pub struct TensileArgs {
    #[command(subcommand)]
    command: Option<TensileCommand>,
    /// Nanotensile exports (T150 NanoSuite, Instron Bluehill, or CSV with
    /// stress/strain or force/extension), output folder, samples
    /// (sample_id, material, knot, diameter_um, fibre_length_mm, ...),
    /// reader, settings (e.g. `effective_threshold = 0.08`).
    #[command(flatten)]
    stage: StageArgs,
}

#[derive(clap::Subcommand)]
enum TensileCommand {
    /// Group summary (material × knot × effective class) of a per-fibre
    /// table: our tensile.parquet or a CSV with the same column names.
    Summarize(SummarizeArgs),
}

/// Arguments of `tribo tensile summarize`.
#[derive(clap::Args)]
pub struct SummarizeArgs {
    /// tensile.parquet, or a CSV with at least material, knot, strength_MPa,
    /// toughness_J_per_g (and friction_ratio or knot_effective).
    table: PathBuf,
    /// Output folder for tensile_groups.parquet.
    #[arg(long)]
    out: PathBuf,
    /// Effective-knot threshold on friction stress / strength, used when the
    /// table has no knot_effective column.
    #[arg(long, default_value_t = 0.08)]
    threshold: f64,
}

/// Runs `tribo tensile` or `tribo tensile summarize`.
pub fn run(args: &TensileArgs) -> tribo::Result<Tally> {
    if let Some(TensileCommand::Summarize(s)) = &args.command {
        let mut spec = table_stage("tensile-summary", &s.out);
        let settings = spec.settings_mut("tensile-summary");
        set(settings, "effective_threshold", s.threshold)?;
        let mut inputs = toml::Table::new();
        set(&mut inputs, "tensile", s.table.display().to_string())?;
        settings.insert("inputs".into(), toml::Value::Table(inputs));
        return execute(&spec, Path::new(""), None);
    }
    // Without the subcommand clap requires FILE... and --out.
    execute(&args.stage.spec("tensile")?, Path::new(""), None)
}
