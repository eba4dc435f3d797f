//! The read-only context of a step: lattice, interface, slider velocity,
//! damping and the blow-up bound. Nothing in it changes during a run.

use crate::models::spring_block::forces::shear_force_on;
use crate::models::spring_block::{Interface, Lattice};

/// What every part of the engine reads and none writes.
#[derive(Debug, Clone, Copy)]
pub struct StepContext<'a> {
    /// The lattice (neighbours, stiffnesses, mass).
    pub lat: &'a Lattice,
    /// Thresholds, kinetic friction and free blocks of this run.
    pub iface: &'a Interface,
    /// Slider velocity (v_x, v_y) [m/s].
    pub vel: (f64, f64),
    /// γ [1/s].
    pub gamma: f64,
    /// Speed above which a block is taken to have blown up [m/s].
    pub v_blowup: f64,
}

impl<'a> StepContext<'a> {
    /// The context of a run; the blow-up bound follows from the largest
    /// threshold: a block released from it reaches about F/√(K m), and 1e3
    /// times that (plus the slider speed) is no physics.
    pub fn new(lat: &'a Lattice, iface: &'a Interface, vel: (f64, f64), gamma: f64) -> Self {
        let fref = iface
            .threshold
            .iter()
            .cloned()
            .fold(iface.normal_force, f64::max);
        let v_blowup = 1e3 * (fref / (lat.k_shear * lat.mass).sqrt() + vel.0.hypot(vel.1));
        StepContext {
            lat,
            iface,
            vel,
            gamma,
            v_blowup,
        }
    }

    /// Slider displacement v t at time `t` \[m\].
    #[inline(always)]
    pub fn slider(&self, t: f64) -> (f64, f64) {
        (self.vel.0 * t, self.vel.1 * t)
    }

    /// Shear force on a block at displacement (ux, uy) at time `t` \[N\].
    #[inline(always)]
    pub fn shear(&self, t: f64, ux: f64, uy: f64) -> (f64, f64) {
        shear_force_on(self.lat.k_shear, self.slider(t), ux, uy)
    }

    /// K_s v, the rate at which the shear spring loads a stuck block [N/s].
    #[inline(always)]
    pub fn shear_rate(&self) -> (f64, f64) {
        (self.lat.k_shear * self.vel.0, self.lat.k_shear * self.vel.1)
    }
}
