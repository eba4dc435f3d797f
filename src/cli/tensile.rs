//! `tribo tensile FILE... --out DIR [--samples SAMPLES.csv]` and
//! `tribo tensile summarize TABLE --out DIR`.

use std::path::PathBuf;
use std::process::ExitCode;

use tribo::extract::tensile::{run_summarize, run_tensile, TensileParams};
use tribo::ingest::IngestOptions;

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
    /// delimited).
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

fn expand(patterns: &[String]) -> tribo::Result<Vec<PathBuf>> {
    let mut files = Vec::new();
    for p in patterns {
        if p.contains(['*', '?', '[']) {
            let paths =
                glob::glob(p).map_err(|e| tribo::Error::Config(format!("bad glob '{p}': {e}")))?;
            let mut found: Vec<PathBuf> = paths.filter_map(|r| r.ok()).collect();
            if found.is_empty() {
                return Err(tribo::Error::Config(format!("no file matches '{p}'")));
            }
            found.sort();
            files.extend(found);
        } else {
            files.push(PathBuf::from(p));
        }
    }
    Ok(files)
}

/// Runs `tribo tensile` or `tribo tensile summarize`.
pub fn run(args: &TensileArgs) -> tribo::Result<ExitCode> {
    if let Some(TensileCommand::Summarize(s)) = &args.command {
        let path = run_summarize(&s.table, &s.out, s.threshold)?;
        eprintln!("wrote {}", path.display());
        return Ok(ExitCode::SUCCESS);
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
    let params: TensileParams = match &args.params {
        Some(p) => {
            let text = std::fs::read_to_string(p).map_err(|e| tribo::Error::io(p, e))?;
            toml::from_str(&text)
                .map_err(|e| tribo::Error::Config(format!("{}: {e}", p.display())))?
        }
        None => TensileParams::default(),
    };
    let files = expand(&args.files)?;
    let options = IngestOptions {
        format: args.format.clone(),
        ..Default::default()
    };
    let report = run_tensile(&files, args.samples.as_deref(), out, &options, &params)?;
    for p in &report.outputs {
        eprintln!("wrote {}", p.display());
    }
    for (f, m) in &report.failures {
        eprintln!("FAILED {f}: {m}");
    }
    eprintln!(
        "{} fibres analysed ({} without a result, see the status column), {} files failed",
        report.fibres,
        report.fibres_without_result,
        report.failures.len()
    );
    if report.failures.is_empty() && report.fibres_without_result == 0 {
        Ok(ExitCode::SUCCESS)
    } else {
        Ok(ExitCode::from(1))
    }
}
