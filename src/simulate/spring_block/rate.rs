//! The quasi-static rate system of free (hole) blocks, shared by the global
//! jumps of [`super::event`] and the parked clusters of [`super::park`].
//!
//! Free blocks dragged by the slider at velocity w with every contact block
//! stuck satisfy (MODELS.md §7, linearised about the current positions)
//!
//! K_s w_i + Σ_j K_t^(ij) (w_i − w_j) = K_s v   (w_j = 0 outside the set),
//!
//! a symmetric positive definite system solved by conjugate gradients. The
//! same machinery puts a set back in equilibrium (Newton steps on the net
//! force). A set is a list of blocks and, for any block, its slot in the
//! list (`None` outside the set).

use super::state::SpringBlockState;
use super::stepper::Stepper;
use crate::models::spring_block::forces::{damping_force_on, internal_force_on, tangent};

/// Net force (internal + shear + damping) on free block i \[N\]. A free block
/// dragged quasi-statically at velocity w feels a spring force m γ w that
/// balances its damping: the net force is what must vanish.
pub(crate) fn net_force(st: &Stepper, state: &SpringBlockState, i: usize) -> (f64, f64) {
    let ctx = &st.ctx;
    let (fx, fy) = internal_force_on(ctx.lat, &state.ux, &state.uy, i);
    let (gx, gy) = ctx.shear(state.t, state.ux[i], state.uy[i]);
    let (dx, dy) = damping_force_on(ctx.lat.mass, ctx.gamma, state.vx[i], state.vy[i]);
    (fx + gx + dx, fy + gy + dy)
}

/// Reference scales for deciding that free blocks have settled before they
/// are treated quasi-statically.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Settling {
    /// Reference force: the mean static threshold \[N\].
    pub fref: f64,
    /// Reference speed F_ref/√((K_s + 6 K_int) m) [m/s].
    pub vref: f64,
}

impl Settling {
    /// The scales of the stepper's lattice and interface.
    pub fn new(st: &Stepper) -> Self {
        let lat = st.ctx.lat;
        let fref = st.ctx.iface.mean_threshold().max(st.ctx.iface.normal_force);
        let kint = lat.k.iter().cloned().fold(0.0, f64::max);
        let vref = fref / ((lat.k_shear + 6.0 * kint) * lat.mass).sqrt();
        Settling { fref, vref }
    }

    /// Whether every block of `blocks` is near equilibrium: net force below
    /// `tol · F_ref` and speed below 2|v| + tol · v_ref (`tol` is
    /// `quiet_tolerance`).
    pub fn settled(
        &self,
        st: &Stepper,
        state: &SpringBlockState,
        blocks: &[u32],
        tol: f64,
    ) -> bool {
        let vmax = 2.0 * st.ctx.vel.0.hypot(st.ctx.vel.1) + tol * self.vref;
        blocks.iter().all(|&i| {
            let i = i as usize;
            let (fx, fy) = net_force(st, state, i);
            fx.hypot(fy) <= tol * self.fref && state.vx[i].hypot(state.vy[i]) <= vmax
        })
    }
}

/// Tangent stiffnesses and conjugate-gradient vectors for sets of up to a
/// given number of blocks.
pub(crate) struct RateSystem {
    kt: Vec<[f64; 3]>,
    /// Solution (first 2 n entries for a set of n blocks).
    pub w: Vec<f64>,
    r: Vec<f64>,
    p: Vec<f64>,
    ap: Vec<f64>,
    /// Right-hand side (first 2 n entries).
    pub b: Vec<f64>,
}

impl RateSystem {
    /// Scratch for sets of at most `largest` blocks.
    pub fn new(largest: usize) -> Self {
        RateSystem {
            kt: vec![[0.0; 3]; 8 * largest],
            w: vec![0.0; 2 * largest],
            r: vec![0.0; 2 * largest],
            p: vec![0.0; 2 * largest],
            ap: vec![0.0; 2 * largest],
            b: vec![0.0; 2 * largest],
        }
    }

    /// Tangent stiffnesses of the springs of `blocks` at the current
    /// positions.
    pub fn assemble(&mut self, st: &Stepper, state: &SpringBlockState, blocks: &[u32]) {
        let lat = st.ctx.lat;
        for (m, &i) in blocks.iter().enumerate() {
            let i = i as usize;
            for d in 0..8 {
                let j = lat.nbr[8 * i + d] as usize;
                let dx = lat.dx0[d] + state.ux[j] - state.ux[i];
                let dy = lat.dy0[d] + state.uy[j] - state.uy[i];
                self.kt[8 * m + d] = tangent(lat.k[8 * i + d], lat.rest[d], dx, dy);
            }
        }
    }

    /// y = A x over the set (neighbours outside it held fixed).
    fn apply<L: Fn(usize) -> Option<usize>>(
        kt: &[[f64; 3]],
        st: &Stepper,
        blocks: &[u32],
        slot: &L,
        x: &[f64],
        y: &mut [f64],
    ) {
        let lat = st.ctx.lat;
        for (m, &i) in blocks.iter().enumerate() {
            let i = i as usize;
            let (xi, yi) = (x[2 * m], x[2 * m + 1]);
            let (mut ax, mut ay) = (lat.k_shear * xi, lat.k_shear * yi);
            for d in 0..8 {
                let j = lat.nbr[8 * i + d] as usize;
                let (xj, yj) = match slot(j) {
                    Some(s) if j != i => (x[2 * s], x[2 * s + 1]),
                    _ => (0.0, 0.0),
                };
                let [kxx, kxy, kyy] = kt[8 * m + d];
                let (ex, ey) = (xi - xj, yi - yj);
                ax += kxx * ex + kxy * ey;
                ay += kxy * ex + kyy * ey;
            }
            y[2 * m] = ax;
            y[2 * m + 1] = ay;
        }
    }

    /// Solves A w = b over the set by conjugate gradients (after
    /// [`RateSystem::assemble`]). False if it did not converge.
    pub fn solve<L: Fn(usize) -> Option<usize>>(
        &mut self,
        st: &Stepper,
        blocks: &[u32],
        slot: &L,
    ) -> bool {
        let n = 2 * blocks.len();
        let bnorm = self.b[..n].iter().map(|x| x * x).sum::<f64>().sqrt();
        self.w[..n].iter_mut().for_each(|x| *x = 0.0);
        if bnorm == 0.0 {
            return true;
        }
        self.r[..n].copy_from_slice(&self.b[..n]);
        self.p[..n].copy_from_slice(&self.b[..n]);
        let mut rr: f64 = self.r[..n].iter().map(|x| x * x).sum();
        for _ in 0..(n + 100).min(5000) {
            Self::apply(&self.kt, st, blocks, slot, &self.p, &mut self.ap);
            let pap: f64 = self.p[..n]
                .iter()
                .zip(&self.ap[..n])
                .map(|(a, b)| a * b)
                .sum();
            if pap.is_nan() || pap <= 0.0 {
                return false;
            }
            let alpha = rr / pap;
            for k in 0..n {
                self.w[k] += alpha * self.p[k];
                self.r[k] -= alpha * self.ap[k];
            }
            let rr_new: f64 = self.r[..n].iter().map(|x| x * x).sum();
            if rr_new.sqrt() <= 1e-12 * bnorm {
                return true;
            }
            let beta = rr_new / rr;
            rr = rr_new;
            for k in 0..n {
                self.p[k] = self.r[k] + beta * self.p[k];
            }
        }
        false
    }

    /// The rate w of the set dragged by the slider (right-hand side K_s v).
    pub fn solve_rate<L: Fn(usize) -> Option<usize>>(
        &mut self,
        st: &Stepper,
        state: &SpringBlockState,
        blocks: &[u32],
        slot: &L,
    ) -> bool {
        self.assemble(st, state, blocks);
        for k in 0..blocks.len() {
            (self.b[2 * k], self.b[2 * k + 1]) = st.ctx.shear_rate();
        }
        self.solve(st, blocks, slot)
    }

    /// The rate w of the set dragged by the slider, with some neighbours
    /// outside it moving at prescribed rates: right-hand side K_s v +
    /// Σ_j K_t^(ij) w_j over the neighbours j outside the set for which
    /// `outside(j)` gives w_j (those for which it gives `None` are held
    /// still). With no such neighbour this is [`RateSystem::solve_rate`].
    pub fn solve_rate_bounded<L, B>(
        &mut self,
        st: &Stepper,
        state: &SpringBlockState,
        blocks: &[u32],
        slot: &L,
        outside: &B,
    ) -> bool
    where
        L: Fn(usize) -> Option<usize>,
        B: Fn(usize) -> Option<(f64, f64)>,
    {
        self.assemble(st, state, blocks);
        let lat = st.ctx.lat;
        for (m, &i) in blocks.iter().enumerate() {
            let i = i as usize;
            let (mut bx, mut by) = st.ctx.shear_rate();
            for d in 0..8 {
                let j = lat.nbr[8 * i + d] as usize;
                if j == i || slot(j).is_some() {
                    continue;
                }
                if let Some((wx, wy)) = outside(j) {
                    let [kxx, kxy, kyy] = self.kt[8 * m + d];
                    bx += kxx * wx + kxy * wy;
                    by += kxy * wx + kyy * wy;
                }
            }
            self.b[2 * m] = bx;
            self.b[2 * m + 1] = by;
        }
        self.solve(st, blocks, slot)
    }

    /// Puts the set in equilibrium at its current velocities by one or two
    /// Newton steps.
    pub fn correct<L: Fn(usize) -> Option<usize>>(
        &mut self,
        st: &Stepper,
        state: &mut SpringBlockState,
        blocks: &[u32],
        slot: &L,
    ) {
        for _ in 0..2 {
            self.assemble(st, state, blocks);
            let mut worst: f64 = 0.0;
            for (k, &i) in blocks.iter().enumerate() {
                let (fx, fy) = net_force(st, state, i as usize);
                self.b[2 * k] = fx;
                self.b[2 * k + 1] = fy;
                worst = worst.max(fx.hypot(fy));
            }
            if worst <= 1e-12 * st.ctx.iface.normal_force || !self.solve(st, blocks, slot) {
                return;
            }
            for (k, &i) in blocks.iter().enumerate() {
                state.ux[i as usize] += self.w[2 * k];
                state.uy[i as usize] += self.w[2 * k + 1];
            }
        }
    }
}
