//! The `tribo` binary: parses arguments, calls the library, prints errors
//! with their cause chain and maps the outcome to an exit code by the one
//! rule of [`tribo::pipeline::exit`]: 0 success, 1 finished with failures
//! (some files were bad), 2 usage or configuration error.

mod cli;

use std::process::ExitCode;

use clap::{Parser, Subcommand};

/// Friction traces, fibre tests and surface profiles from raw lab exports to
/// trustworthy numbers and model comparisons, written as Parquet tables.
#[derive(Parser)]
#[command(name = "tribo", version = tribo::BUILD, about, long_about = None, propagate_version = true)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Show how files are understood: format, encoding, delimiter, decimal
    /// mark, preamble, sections, columns with units and roles, sample rate.
    Inspect(cli::inspect::InspectArgs),
    /// Extract static and dynamic friction, stick-slip and velocity steps
    /// from friction traces; write friction, friction_steps, stickslip and
    /// traces Parquet tables.
    Friction(cli::friction::FrictionArgs),
    /// Roughness of stylus profiles and areal maps: Ra, Rq, Rdq, Rsk, Rku,
    /// the Rk family, volume, spatial and hybrid parameters, fractal
    /// dimension, bearing curve and contact length; write roughness,
    /// bearing_curve, psd and acf Parquet tables.
    Roughness(Box<cli::roughness::RoughnessArgs>),
    /// Run a declarative pipeline file (see pipelines/demo.toml).
    Run(cli::run::RunArgs),
    /// Render report.html of an output folder again from its tables: every
    /// file with its status and figures, the fits and simulations.
    Report(cli::report::ReportArgs),
    /// Draw the report's figures of input files as SVG files.
    Plot(cli::plot::PlotArgs),
    /// Write Slurm batch scripts for a pipeline: a job array of shards and a
    /// dependent merge job; --submit submits them.
    Slurm(cli::slurm::SlurmArgs),
    /// Fit models: Coulomb law, ice-friction model; validate the solver on
    /// NIST StRD.
    Fit(cli::fit::FitArgs),
    /// Run model simulations: ice-friction grids, the ALSFM, the spring-block
    /// model.
    Simulate(cli::simulate::SimulateArgs),
    /// Fibre tensile tests: strength, toughness (Eq. 5.1/5.2), friction
    /// stress, knot release and toughness ratios (Eq. 5.3/5.4) per fibre
    /// (tensile.parquet); `tensile summarize` for group summaries.
    Tensile(cli::tensile::TensileArgs),
}

/// Output piped into a reader that stops early (`tribo run --json | head`)
/// ends the process quietly, as it does any Unix tool: Rust ignores
/// SIGPIPE, and a print to the closed pipe would panic instead.
fn quiet_on_closed_pipe() {
    #[cfg(unix)]
    // SAFETY: restoring the default action of one signal, before any
    // thread is started.
    unsafe {
        libc::signal(libc::SIGPIPE, libc::SIG_DFL);
    }
}

/// A rerun over a large archive is mostly small allocations; mimalloc
/// makes them a third cheaper than the system's (Cargo.toml).
#[cfg(feature = "mimalloc")]
#[global_allocator]
static GLOBAL: mimalloc::MiMalloc = mimalloc::MiMalloc;

fn main() -> ExitCode {
    quiet_on_closed_pipe();
    let cli = Cli::parse();
    let result = match &cli.command {
        Command::Inspect(a) => cli::inspect::run(a),
        Command::Friction(a) => cli::friction::run(a),
        Command::Roughness(a) => cli::roughness::run(a),
        Command::Run(a) => cli::run::run(a),
        Command::Report(a) => cli::report::run(a),
        Command::Plot(a) => cli::plot::run(a),
        Command::Slurm(a) => cli::slurm::run(a),
        Command::Fit(a) => cli::fit::run(a),
        Command::Simulate(a) => cli::simulate::run(a),
        Command::Tensile(a) => cli::tensile::run(a),
    };
    if let Err(e) = &result {
        eprintln!("error: {e}");
        let mut source = std::error::Error::source(e);
        while let Some(s) = source {
            eprintln!("  caused by: {s}");
            source = s.source();
        }
    }
    ExitCode::from(tribo::pipeline::exit::code(&result))
}
