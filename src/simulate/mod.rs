//! Simulations: scene files, drivers, sweeps and their output tables.

pub mod ice;
