//! `tribo tensile FILE... --out DIR [--samples SAMPLES.csv]` and
//! `tribo tensile summarize TABLE --out DIR`.

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use tribo::pipeline::spec::PipelineSpec;

use super::exec::{execute, params_file, set, table_stage};

/// Arguments of `tribo tensile`.
#[derive(clap::Args)]
#[command(args_conflicts_with_subcommands = true)]
pub struct TensileArgs {
    #[command(subcommand)]
    command: Option<TensileCommand>,
    /// Nanotensile exports (T150 NanoSuite, Instron Bluehill, or CSV with
    /// stress/strain or force/extension); globs are expanded.
    files: Vec<String>,
    /// Output folder for tensile.parquet and errors.parquet.
    #[arg(long)]
    out: Option<PathBuf>,
    /// Sample manifest CSV: file, sample_id, material, knot, diameter_um,
    /// fibre_length_mm, end_distance_mm, density_g_per_cm3, control_id.
    #[arg(long)]
    samples: Option<PathBuf>,
    /// Force a reader instead of sniffing (t150-nanosuite, instron-bluehill,
    /// instron-blocks, zwick-testxpert, delimited).
    #[arg(long)]
    format: Option<String>,
    /// Analysis parameters as a TOML file (keys of TensileParams, for
    /// example `effective_threshold = 0.08`).
    #[arg(long)]
    params: Option<PathBuf>,
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
pub fn run(args: &TensileArgs) -> tribo::Result<ExitCode> {
    if let Some(TensileCommand::Summarize(s)) = &args.command {
        let mut spec = table_stage("tensile-summary", &s.out);
        let settings = spec.settings_mut("tensile-summary");
        set(settings, "effective_threshold", s.threshold)?;
        let mut inputs = toml::Table::new();
        set(&mut inputs, "tensile", s.table.display().to_string())?;
        settings.insert("inputs".into(), toml::Value::Table(inputs));
        return execute(&spec, Path::new(""), None);
    }
    let out = args
        .out
        .as_ref()
        .ok_or_else(|| tribo::Error::Config("tribo tensile: --out DIR is required".into()))?;
    if args.files.is_empty() {
        return Err(tribo::Error::Config(
            "tribo tensile: give at least one FILE".into(),
        ));
    }
    let mut spec = PipelineSpec::single_stage(
        "tensile",
        args.files.clone(),
        args.samples.as_ref().map(|p| p.display().to_string()),
        out.display().to_string(),
        args.format.clone(),
    );
    *spec.settings_mut("tensile") = params_file(args.params.as_deref())?;
    execute(&spec, Path::new(""), None)
}
