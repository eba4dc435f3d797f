//! Simulations: scene files, drivers, sweeps and their output tables.
pub mod spring_block;
