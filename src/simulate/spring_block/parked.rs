//! The blocks that move affinely, u = u0 + w (t − t0), instead of being
//! integrated (parked hole blocks, [`super::park`]). Their velocity w is the
//! state's velocity; their positions are brought up to date only when read.

use super::context::StepContext;
use super::scratch::Rk4Scratch;
use super::state::SpringBlockState;

/// Flag, list, u0, t0 and Σ w of the parked blocks, and the halo: the
/// parked blocks next to integrated free blocks, placed at each RK4 stage.
#[derive(Debug, Clone)]
pub(crate) struct ParkedBlocks {
    pub flag: Vec<bool>,
    pub list: Vec<u32>,
    halo: Vec<u32>,
    u0x: Vec<f64>,
    u0y: Vec<f64>,
    t0: Vec<f64>,
    /// Σ w over parked blocks [m/s].
    pub wsum: (f64, f64),
}

impl ParkedBlocks {
    /// No block parked, room for `n`.
    pub fn new(n: usize) -> Self {
        ParkedBlocks {
            flag: vec![false; n],
            list: Vec::new(),
            halo: Vec::new(),
            u0x: vec![0.0; n],
            u0y: vec![0.0; n],
            t0: vec![0.0; n],
            wsum: (0.0, 0.0),
        }
    }

    /// Whether no block is parked.
    #[inline]
    pub fn none(&self) -> bool {
        self.list.is_empty()
    }

    /// Parks block `i` from its current position and time.
    pub fn park(&mut self, state: &SpringBlockState, i: usize) {
        self.flag[i] = true;
        self.u0x[i] = state.ux[i];
        self.u0y[i] = state.uy[i];
        self.t0[i] = state.t;
    }

    /// Rebuilds the list, Σ w and the halo after parking or unparking.
    pub fn rebuild(&mut self, ctx: &StepContext, state: &SpringBlockState) {
        let flag = &self.flag;
        self.list.clear();
        self.list
            .extend((0..flag.len() as u32).filter(|&i| flag[i as usize]));
        let (mut sx, mut sy) = (0.0, 0.0);
        for &i in &self.list {
            sx += state.vx[i as usize];
            sy += state.vy[i as usize];
        }
        self.wsum = (sx, sy);
        let lat = ctx.lat;
        self.halo.clear();
        for &i in &self.list {
            let i = i as usize;
            if (0..8).any(|d| {
                let j = lat.nbr[8 * i + d] as usize;
                j != i && !self.flag[j] && ctx.iface.is_free(j)
            }) {
                self.halo.push(i as u32);
            }
        }
    }

    /// Stage positions of the halo at time `t` (their affine motion).
    #[inline]
    pub fn place_halo(&self, state: &SpringBlockState, sc: &mut Rk4Scratch, t: f64) {
        for &i in &self.halo {
            let i = i as usize;
            let s = t - self.t0[i];
            sc.px[i] = self.u0x[i] + state.vx[i] * s;
            sc.py[i] = self.u0y[i] + state.vy[i] * s;
        }
    }

    /// Brings the position of block `i` up to `state.t` if it is parked.
    #[inline]
    pub fn materialize(&self, state: &mut SpringBlockState, sc: &mut Rk4Scratch, i: usize) {
        if self.flag[i] {
            let s = state.t - self.t0[i];
            state.ux[i] = self.u0x[i] + state.vx[i] * s;
            state.uy[i] = self.u0y[i] + state.vy[i] * s;
            sc.px[i] = state.ux[i];
            sc.py[i] = state.uy[i];
        }
    }

    /// Brings every parked position up to date.
    pub fn materialize_all(&self, state: &mut SpringBlockState, sc: &mut Rk4Scratch) {
        for &i in &self.list {
            self.materialize(state, sc, i as usize);
        }
    }
}
