//! Simulations: scene files, drivers, sweeps and their output tables.

pub mod alsfm;
pub mod ice;
pub mod spring_block;
