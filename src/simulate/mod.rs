//! Simulations: scene files, drivers, sweeps and their output tables.

pub mod ice;
pub mod spring_block;
