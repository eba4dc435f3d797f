//! Subcommands. Each file holds a clap `Args` struct and a `run` function
//! that builds library types from the arguments, calls the library, and
//! prints.

pub mod exec;
pub mod file_args;
pub mod fit;
pub mod friction;
pub mod inspect;
pub mod plot;
pub mod progress;
pub mod report;
pub mod roughness;
pub mod run;
pub mod simulate;
pub mod simulate_alsfm;
pub mod simulate_ice;
pub mod simulate_spring_block;
pub mod slurm;
pub mod tensile;
