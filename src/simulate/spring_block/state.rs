//! The state of a spring-block run (positions, velocities, which blocks
//! slide) and why a step could not be completed: what the stepper and the
//! parts it drives (parked blocks, the stuck cache, events, rates) share.

use crate::models::spring_block::Interface;

/// Positions, velocities and stick state of all blocks.
#[derive(Debug, Clone)]
pub struct SpringBlockState {
    /// t, time \[s\].
    pub t: f64,
    /// u_x, displacement from rest \[m\].
    pub ux: Vec<f64>,
    /// u_y \[m\].
    pub uy: Vec<f64>,
    /// u̇_x [m/s].
    pub vx: Vec<f64>,
    /// u̇_y [m/s].
    pub vy: Vec<f64>,
    /// Whether each block slides (free blocks always do).
    pub sliding: Vec<bool>,
}

impl SpringBlockState {
    /// All blocks at rest at their rest positions at t = 0; free blocks are
    /// marked sliding.
    pub fn at_rest(iface: &Interface) -> Self {
        let n = iface.threshold.len();
        SpringBlockState {
            t: 0.0,
            ux: vec![0.0; n],
            uy: vec![0.0; n],
            vx: vec![0.0; n],
            vy: vec![0.0; n],
            sliding: (0..n).map(|i| iface.is_free(i)).collect(),
        }
    }
}

/// Why a step could not be completed.
#[derive(Debug, Clone, PartialEq)]
pub struct BlowUp {
    /// Block where it was seen.
    pub block: usize,
    /// What was seen.
    pub what: String,
}
