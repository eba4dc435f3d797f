//! The stuck-phase cache: for each stuck block, its internal force at the
//! time it was last refreshed and that force's rate of change from parked
//! neighbours, so that its driving force (and hence its crossing time) is a
//! closed form until a neighbour moves (MODELS.md §7).

use super::context::StepContext;
use super::state::SpringBlockState;

/// Cached internal force F_int(t_f) \[N\], its rate R_int [N/s] and t_f \[s\].
#[derive(Debug, Clone)]
pub(crate) struct StuckCache {
    pub fx: Vec<f64>,
    pub fy: Vec<f64>,
    pub rx: Vec<f64>,
    pub ry: Vec<f64>,
    pub tf: Vec<f64>,
}

impl StuckCache {
    /// An empty cache for `n` blocks.
    pub fn new(n: usize) -> Self {
        StuckCache {
            fx: vec![0.0; n],
            fy: vec![0.0; n],
            rx: vec![0.0; n],
            ry: vec![0.0; n],
            tf: vec![0.0; n],
        }
    }

    /// Stores block `i`'s internal force `f` and rate `r` at time `t`.
    #[inline]
    pub fn store(&mut self, i: usize, f: (f64, f64), r: (f64, f64), t: f64) {
        (self.fx[i], self.fy[i]) = f;
        (self.rx[i], self.ry[i]) = r;
        self.tf[i] = t;
    }

    /// Driving force F_mot = F_int(t_f) + R_int (t − t_f) + K_s (v t − u_i)
    /// on stuck block `i` at the state's time \[N\].
    #[inline]
    pub fn driving_force(
        &self,
        ctx: &StepContext,
        state: &SpringBlockState,
        i: usize,
    ) -> (f64, f64) {
        let s = state.t - self.tf[i];
        let (gx, gy) = ctx.shear(state.t, state.ux[i], state.uy[i]);
        (
            self.fx[i] + self.rx[i] * s + gx,
            self.fy[i] + self.ry[i] * s + gy,
        )
    }

    /// Rate of change of block `i`'s driving force, K_s v + R_int [N/s].
    #[inline]
    pub fn loading_rate(&self, ctx: &StepContext, i: usize) -> (f64, f64) {
        let (kx, ky) = ctx.shear_rate();
        (kx + self.rx[i], ky + self.ry[i])
    }
}
