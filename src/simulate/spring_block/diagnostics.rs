//! Force-balance diagnostics: every force term summed over the lattice,
//! computed with the per-term functions of
//! [`crate::models::spring_block::forces`].
//!
//! Newton's third law makes Σ F_int vanish; when every block sticks and is at
//! rest, friction balances the driving force block by block, so the total
//! shear-spring force (the measured T_vec) equals minus the total friction.

use super::stepper::SpringBlockState;
use crate::models::spring_block::forces::{
    damping_forces, friction_forces, internal_forces, shear_forces,
};
use crate::models::spring_block::{Interface, Lattice};

/// Sums of the force terms over all blocks \[N\], as (x, y).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ForceBalance {
    /// Σ F_int (zero by Newton's third law).
    pub internal: (f64, f64),
    /// Σ F_s = T_vec, the force the slider feels.
    pub shear: (f64, f64),
    /// Σ F_d.
    pub damping: (f64, f64),
    /// Σ F_fr.
    pub friction: (f64, f64),
    /// Σ of the per-block totals (equals the sum of the four terms).
    pub total: (f64, f64),
    /// Largest |total force| on a stuck block (zero: friction balances it).
    pub max_stuck_residual: f64,
}

/// Computes each force term into its own array and sums them.
pub fn force_balance(
    lat: &Lattice,
    iface: &Interface,
    state: &SpringBlockState,
    slider_velocity: (f64, f64),
    gamma: f64,
) -> ForceBalance {
    let n = lat.len();
    let mut a = vec![vec![0.0; n]; 8];
    let [ix, iy, sx, sy, dx, dy, fx, fy] = &mut a[..] else {
        unreachable!()
    };
    internal_forces(lat, &state.ux, &state.uy, ix, iy);
    let s = (slider_velocity.0 * state.t, slider_velocity.1 * state.t);
    shear_forces(lat.k_shear, s, &state.ux, &state.uy, sx, sy);
    damping_forces(lat.mass, gamma, &state.vx, &state.vy, dx, dy);
    let mx: Vec<f64> = (0..n).map(|i| ix[i] + sx[i]).collect();
    let my: Vec<f64> = (0..n).map(|i| iy[i] + sy[i]).collect();
    friction_forces(
        &state.sliding,
        &iface.kinetic,
        &state.vx,
        &state.vy,
        &mx,
        &my,
        fx,
        fy,
    );
    let sum = |v: &[f64]| v.iter().sum::<f64>();
    let mut total = (0.0, 0.0);
    let mut resid: f64 = 0.0;
    for i in 0..n {
        let tx = ix[i] + sx[i] + dx[i] + fx[i];
        let ty = iy[i] + sy[i] + dy[i] + fy[i];
        total.0 += tx;
        total.1 += ty;
        if !state.sliding[i] {
            resid = resid.max(tx.hypot(ty));
        }
    }
    ForceBalance {
        internal: (sum(ix), sum(iy)),
        shear: (sum(sx), sum(sy)),
        damping: (sum(dx), sum(dy)),
        friction: (sum(fx), sum(fy)),
        total,
        max_stuck_residual: resid,
    }
}
