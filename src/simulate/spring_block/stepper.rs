//! The hot loop: one RK4 step of the blocks that move, with stick/slip
//! transitions at the step's end.
//!
//! Only *moving* blocks (sliding contact blocks and free hole blocks) are
//! integrated; stuck blocks have u̇ = 0 and keep their position. For each
//! stuck block the internal force is cached and refreshed only when it or a
//! neighbour moved. With a constant internal force the driving force of a
//! stuck block grows linearly, F_int + K_s (v t − u_i), so the time at which
//! it reaches μ_s^i F_n + F_ad is a closed form; these times sit in a
//! tournament (min) tree, and the per-step threshold check costs
//! O(moving · log N) instead of O(N).
//!
//! Arrays are struct-of-arrays, allocated once; a step allocates nothing.
//!
//! Parked blocks ([`super::park`]) are free blocks that move affinely,
//! u = u0 + w (t − t0); they are not integrated. A stuck block next to them
//! sees an internal force that changes linearly, F_int(t) = F_int(t_f) +
//! R_int (t − t_f), R_int = Σ_j K_t^(ij) w_j, which the crossing time uses.
//!
//! Stick/slip handling (MODELS.md §7): within a step the friction of a
//! sliding block follows the stage velocity (RK4 sees a smooth right-hand
//! side while the velocity does not reverse). After the step, a sliding
//! block whose velocity reversed (u̇_new · u̇_old ≤ 0 with u̇_old ≠ 0) is
//! stopped (u̇ = 0); it sticks if its driving force is below the static
//! threshold, otherwise it slides on from rest. A stuck block whose driving
//! force exceeds its threshold starts sliding.

use crate::models::spring_block::forces::{internal_force_on, kinetic_friction};
use crate::models::spring_block::{Interface, Lattice};

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

/// Constants and scratch space of the stepper for one run.
pub struct Stepper<'a> {
    pub(crate) lat: &'a Lattice,
    pub(crate) iface: &'a Interface,
    /// Slider velocity (v_x, v_y) [m/s].
    pub(crate) vel: (f64, f64),
    /// γ [1/s].
    pub(crate) gamma: f64,
    /// Speed above which a block is taken to have blown up [m/s].
    pub(crate) v_blowup: f64,
    /// Stage positions (equal to the state's positions between steps).
    px: Vec<f64>,
    py: Vec<f64>,
    /// Cached internal force on stuck blocks at time `tf`.
    pub(crate) fint_x: Vec<f64>,
    pub(crate) fint_y: Vec<f64>,
    /// Its rate of change from parked neighbours [N/s], and `tf` \[s\].
    rint_x: Vec<f64>,
    rint_y: Vec<f64>,
    tf: Vec<f64>,
    /// Parked blocks: flag, list, u0, t0 and w (also their velocity).
    pub(crate) parked: Vec<bool>,
    parked_list: Vec<u32>,
    /// Parked blocks next to free blocks that are integrated: the stepper
    /// places them at each stage's time.
    halo: Vec<u32>,
    pu0x: Vec<f64>,
    pu0y: Vec<f64>,
    pt0: Vec<f64>,
    /// Σ w over parked blocks [m/s].
    park_wsum: (f64, f64),
    dirty: Vec<bool>,
    dirty_list: Vec<u32>,
    /// Moving blocks (sliding contact blocks and free blocks).
    pub(crate) moving: Vec<u32>,
    // Per moving block: old velocity, stage velocity, last derivatives, sums.
    ovx: Vec<f64>,
    ovy: Vec<f64>,
    svx: Vec<f64>,
    svy: Vec<f64>,
    kxx: Vec<f64>,
    kxy: Vec<f64>,
    kvx: Vec<f64>,
    kvy: Vec<f64>,
    sxx: Vec<f64>,
    sxy: Vec<f64>,
    svsx: Vec<f64>,
    svsy: Vec<f64>,
    /// Time at which each stuck block reaches its threshold (∞ if sliding).
    tcross: Vec<f64>,
    /// Min tree over `tcross`: leaves at `leaves + i`, root at 1.
    tree: Vec<f64>,
    leaves: usize,
    due: Vec<u32>,
    /// Running Σ u_x, Σ u_y over all blocks \[m\].
    pub(crate) sum_ux: f64,
    pub(crate) sum_uy: f64,
    /// Steps taken and block-steps integrated.
    pub steps: u64,
    /// Σ over steps of the number of moving blocks.
    pub block_steps: u64,
}

impl<'a> Stepper<'a> {
    /// Prepares the stepper for `state` (usually at rest).
    pub fn new(
        lat: &'a Lattice,
        iface: &'a Interface,
        vel: (f64, f64),
        gamma: f64,
        state: &SpringBlockState,
    ) -> Self {
        let n = lat.len();
        // A block released from its static threshold reaches about
        // F/√(K m); 1e3 times that (plus the slider speed) is no physics.
        let fref = iface
            .threshold
            .iter()
            .cloned()
            .fold(iface.normal_force, f64::max);
        let v_blowup = 1e3 * (fref / (lat.k_shear * lat.mass).sqrt() + vel.0.hypot(vel.1));
        let mut s = Stepper {
            lat,
            iface,
            vel,
            gamma,
            v_blowup,
            px: state.ux.clone(),
            py: state.uy.clone(),
            fint_x: vec![0.0; n],
            fint_y: vec![0.0; n],
            rint_x: vec![0.0; n],
            rint_y: vec![0.0; n],
            tf: vec![0.0; n],
            parked: vec![false; n],
            parked_list: Vec::new(),
            halo: Vec::new(),
            pu0x: vec![0.0; n],
            pu0y: vec![0.0; n],
            pt0: vec![0.0; n],
            park_wsum: (0.0, 0.0),
            dirty: vec![false; n],
            dirty_list: Vec::with_capacity(n),
            moving: Vec::with_capacity(n),
            ovx: vec![0.0; n],
            ovy: vec![0.0; n],
            svx: vec![0.0; n],
            svy: vec![0.0; n],
            kxx: vec![0.0; n],
            kxy: vec![0.0; n],
            kvx: vec![0.0; n],
            kvy: vec![0.0; n],
            sxx: vec![0.0; n],
            sxy: vec![0.0; n],
            svsx: vec![0.0; n],
            svsy: vec![0.0; n],
            tcross: vec![f64::INFINITY; n],
            tree: vec![f64::INFINITY; 2 * n.next_power_of_two()],
            leaves: n.next_power_of_two(),
            due: Vec::new(),
            sum_ux: 0.0,
            sum_uy: 0.0,
            steps: 0,
            block_steps: 0,
        };
        s.resync(state);
        s
    }

    /// Recomputes every cache from `state` (after a jump or at the start).
    pub fn resync(&mut self, state: &SpringBlockState) {
        self.px.copy_from_slice(&state.ux);
        self.py.copy_from_slice(&state.uy);
        for i in 0..self.lat.len() {
            (self.fint_x[i], self.fint_y[i]) = internal_force_on(self.lat, &state.ux, &state.uy, i);
            (self.rint_x[i], self.rint_y[i]) = self.parked_rate(state, i);
            self.tf[i] = state.t;
        }
        self.moving.clear();
        self.moving.extend(
            (0..self.lat.len() as u32)
                .filter(|&i| state.sliding[i as usize] && !self.parked[i as usize]),
        );
        for i in 0..self.lat.len() {
            self.tcross[i] = self.crossing(state, i);
            self.tree[self.leaves + i] = self.tcross[i];
        }
        for k in (1..self.leaves).rev() {
            self.tree[k] = self.tree[2 * k].min(self.tree[2 * k + 1]);
        }
        self.sum_ux = state.ux.iter().sum();
        self.sum_uy = state.uy.iter().sum();
    }

    /// Time at which stuck block `i` reaches its threshold if its internal
    /// force stays as cached (∞ if it slides).
    fn crossing(&self, state: &SpringBlockState, i: usize) -> f64 {
        if state.sliding[i] {
            return f64::INFINITY;
        }
        let g = self.driving_force_cached(state, i);
        let ks = self.lat.k_shear;
        let tau = super::event::crossing_time(
            g,
            (
                ks * self.vel.0 + self.rint_x[i],
                ks * self.vel.1 + self.rint_y[i],
            ),
            self.iface.threshold[i],
        );
        state.t + tau
    }

    /// R_int = Σ_j K_t^(ij) w_j over parked neighbours j of block i [N/s].
    fn parked_rate(&self, state: &SpringBlockState, i: usize) -> (f64, f64) {
        let lat = self.lat;
        let (mut rx, mut ry) = (0.0, 0.0);
        if self.parked_list.is_empty() {
            return (rx, ry);
        }
        for d in 0..8 {
            let j = lat.nbr[8 * i + d] as usize;
            if j == i || !self.parked[j] {
                continue;
            }
            let dx = lat.dx0[d] + state.ux[j] - state.ux[i];
            let dy = lat.dy0[d] + state.uy[j] - state.uy[i];
            let [kxx, kxy, kyy] = super::rate::tangent(lat.k[8 * i + d], lat.rest[d], dx, dy);
            let (wx, wy) = (state.vx[j], state.vy[j]);
            rx += kxx * wx + kxy * wy;
            ry += kxy * wx + kyy * wy;
        }
        (rx, ry)
    }

    /// Recomputes the cached internal force (and its rate) of block `j` if
    /// it is stuck, and its crossing time.
    pub(crate) fn refresh(&mut self, state: &mut SpringBlockState, j: usize) {
        if !state.sliding[j] {
            if !self.parked_list.is_empty() {
                for d in 0..8 {
                    self.materialize(state, self.lat.nbr[8 * j + d] as usize);
                }
            }
            (self.fint_x[j], self.fint_y[j]) = internal_force_on(self.lat, &state.ux, &state.uy, j);
            (self.rint_x[j], self.rint_y[j]) = self.parked_rate(state, j);
            self.tf[j] = state.t;
        }
        let c = self.crossing(state, j);
        self.set_cross(j, c);
    }

    /// Parks free block `i` at its current position with velocity `w`:
    /// u = u0 + w (t − t0) from now on. Call [`Self::parked_changed`] after
    /// a batch of park and unpark calls.
    pub(crate) fn park(&mut self, state: &mut SpringBlockState, i: usize, w: (f64, f64)) {
        self.parked[i] = true;
        self.pu0x[i] = state.ux[i];
        self.pu0y[i] = state.uy[i];
        self.pt0[i] = state.t;
        (state.vx[i], state.vy[i]) = w;
    }

    /// Unparks block `i` (its position is current) and puts it back in the
    /// moving list.
    pub(crate) fn unpark(&mut self, i: usize) {
        self.parked[i] = false;
        self.moving.push(i as u32);
    }

    /// Rebuilds the parked list, Σ w and the moving list after parking or
    /// unparking.
    pub(crate) fn parked_changed(&mut self, state: &SpringBlockState) {
        let parked = &self.parked;
        self.parked_list.clear();
        self.parked_list
            .extend((0..parked.len() as u32).filter(|&i| parked[i as usize]));
        self.moving.retain(|&i| !parked[i as usize]);
        let (mut sx, mut sy) = (0.0, 0.0);
        for &i in &self.parked_list {
            sx += state.vx[i as usize];
            sy += state.vy[i as usize];
        }
        self.park_wsum = (sx, sy);
        let lat = self.lat;
        self.halo.clear();
        for &i in &self.parked_list {
            let i = i as usize;
            if (0..8).any(|d| {
                let j = lat.nbr[8 * i + d] as usize;
                j != i && !self.parked[j] && self.iface.is_free(j)
            }) {
                self.halo.push(i as u32);
            }
        }
    }

    /// Stage positions of the parked blocks next to integrated ones at time
    /// `t` (their affine motion).
    #[inline]
    fn place_halo(&mut self, state: &SpringBlockState, t: f64) {
        for &i in &self.halo {
            let i = i as usize;
            let s = t - self.pt0[i];
            self.px[i] = self.pu0x[i] + state.vx[i] * s;
            self.py[i] = self.pu0y[i] + state.vy[i] * s;
        }
    }

    /// Accounts for the motion of parked blocks in Σ u after the clock
    /// advanced by `dt`. Their positions are brought up to date only when
    /// read ([`Self::materialize`]).
    pub(crate) fn advance_parked(&mut self, dt: f64) {
        self.sum_ux += self.park_wsum.0 * dt;
        self.sum_uy += self.park_wsum.1 * dt;
    }

    /// Brings the position of block `i` up to `state.t` if it is parked.
    #[inline]
    pub(crate) fn materialize(&mut self, state: &mut SpringBlockState, i: usize) {
        if self.parked[i] {
            let s = state.t - self.pt0[i];
            state.ux[i] = self.pu0x[i] + state.vx[i] * s;
            state.uy[i] = self.pu0y[i] + state.vy[i] * s;
            self.px[i] = state.ux[i];
            self.py[i] = state.uy[i];
        }
    }

    /// Brings every parked position up to date and recomputes Σ u (after
    /// positions were corrected).
    pub(crate) fn materialize_all(&mut self, state: &mut SpringBlockState) {
        let list = std::mem::take(&mut self.parked_list);
        for &i in &list {
            self.materialize(state, i as usize);
        }
        self.parked_list = list;
        self.sum_ux = state.ux.iter().sum();
        self.sum_uy = state.uy.iter().sum();
    }

    /// Marks stuck block `i` as sliding and puts it in the moving list.
    pub(crate) fn start_sliding(&mut self, state: &mut SpringBlockState, i: usize) {
        if state.sliding[i] {
            return;
        }
        state.sliding[i] = true;
        self.moving.push(i as u32);
        self.set_cross(i, f64::INFINITY);
    }

    /// Blocks that started to slide in the last [`Self::check_thresholds`]
    /// that returned a nonzero count.
    pub(crate) fn started(&self) -> &[u32] {
        &self.due
    }

    fn set_cross(&mut self, i: usize, value: f64) {
        self.tcross[i] = value;
        let mut k = self.leaves + i;
        self.tree[k] = value;
        while k > 1 {
            k /= 2;
            let m = self.tree[2 * k].min(self.tree[2 * k + 1]);
            if m.to_bits() == self.tree[k].to_bits() {
                break;
            }
            self.tree[k] = m;
        }
    }

    /// Earliest threshold crossing of a stuck block under linear loading,
    /// and that block (`None` if no block is stuck).
    pub fn next_crossing(&self) -> Option<(f64, usize)> {
        let m = self.tree[1];
        if !m.is_finite() {
            return None;
        }
        let mut k = 1;
        while k < self.leaves {
            k = if self.tree[2 * k].to_bits() == m.to_bits() {
                2 * k
            } else {
                2 * k + 1
            };
        }
        Some((m, k - self.leaves))
    }

    /// Friction force on the slider, T_vec = K_s (N v t − Σ u) \[N\].
    pub fn slider_force(&self, t: f64) -> (f64, f64) {
        let n = self.lat.len() as f64;
        (
            self.lat.k_shear * (n * self.vel.0 * t - self.sum_ux),
            self.lat.k_shear * (n * self.vel.1 * t - self.sum_uy),
        )
    }

    /// Number of moving blocks that are not free (sliding contact blocks).
    pub fn sliding_contacts(&self) -> usize {
        self.moving
            .iter()
            .filter(|&&i| !self.iface.is_free(i as usize))
            .count()
    }

    /// Acceleration of moving block `i` at stage positions, stage velocity
    /// (wx, wy), velocity at the step's start (ox, oy) and stage time `t`.
    /// Kinetic friction follows the stage velocity unless that has reversed
    /// with respect to the step's start: then it keeps opposing the original
    /// motion, so that the block is seen to stop at the step's end instead
    /// of chattering around zero velocity.
    #[inline(always)]
    fn accel(&self, i: usize, (wx, wy): (f64, f64), (ox, oy): (f64, f64), t: f64) -> (f64, f64) {
        let lat = self.lat;
        let (fix, fiy) = internal_force_on(lat, &self.px, &self.py, i);
        let fmx = fix + lat.k_shear * (self.vel.0 * t - self.px[i]);
        let fmy = fiy + lat.k_shear * (self.vel.1 * t - self.py[i]);
        let (dx, dy) = if wx * ox + wy * oy < 0.0 {
            (ox, oy)
        } else {
            (wx, wy)
        };
        let (ffx, ffy) = kinetic_friction(self.iface.kinetic[i], dx, dy, fmx, fmy);
        let inv_m = 1.0 / lat.mass;
        (
            (fmx + ffx) * inv_m - self.gamma * wx,
            (fmy + ffy) * inv_m - self.gamma * wy,
        )
    }

    /// Advances `state` by `dt` with classical RK4 over the moving blocks,
    /// then applies stick/slip transitions. Returns the number of blocks that
    /// started to slide, or where the integration blew up.
    pub fn step(&mut self, state: &mut SpringBlockState, dt: f64) -> Result<usize, BlowUp> {
        let t = state.t;
        let nm = self.moving.len();
        // Stage 1 at the start of the step (px = ux between steps).
        self.place_halo(state, t);
        for m in 0..nm {
            let i = self.moving[m] as usize;
            let (wx, wy) = (state.vx[i], state.vy[i]);
            let (ax, ay) = self.accel(i, (wx, wy), (wx, wy), t);
            self.ovx[m] = wx;
            self.ovy[m] = wy;
            self.kxx[m] = wx;
            self.kxy[m] = wy;
            self.kvx[m] = ax;
            self.kvy[m] = ay;
            self.sxx[m] = wx;
            self.sxy[m] = wy;
            self.svsx[m] = ax;
            self.svsy[m] = ay;
        }
        for (c, w) in [(0.5 * dt, 2.0), (0.5 * dt, 2.0), (dt, 1.0)] {
            for m in 0..nm {
                let i = self.moving[m] as usize;
                self.px[i] = state.ux[i] + c * self.kxx[m];
                self.py[i] = state.uy[i] + c * self.kxy[m];
                self.svx[m] = state.vx[i] + c * self.kvx[m];
                self.svy[m] = state.vy[i] + c * self.kvy[m];
            }
            self.place_halo(state, t + c);
            for m in 0..nm {
                let i = self.moving[m] as usize;
                let (wx, wy) = (self.svx[m], self.svy[m]);
                let (ax, ay) = self.accel(i, (wx, wy), (self.ovx[m], self.ovy[m]), t + c);
                self.kxx[m] = wx;
                self.kxy[m] = wy;
                self.kvx[m] = ax;
                self.kvy[m] = ay;
                self.sxx[m] += w * wx;
                self.sxy[m] += w * wy;
                self.svsx[m] += w * ax;
                self.svsy[m] += w * ay;
            }
        }
        let h6 = dt / 6.0;
        let (mut dsx, mut dsy) = (0.0, 0.0);
        for m in 0..nm {
            let i = self.moving[m] as usize;
            let (dx, dy) = (h6 * self.sxx[m], h6 * self.sxy[m]);
            state.ux[i] += dx;
            state.uy[i] += dy;
            state.vx[i] += h6 * self.svsx[m];
            state.vy[i] += h6 * self.svsy[m];
            self.px[i] = state.ux[i];
            self.py[i] = state.uy[i];
            dsx += dx;
            dsy += dy;
            let (vx, vy) = (state.vx[i], state.vy[i]);
            if !(state.ux[i].is_finite()
                && state.uy[i].is_finite()
                && vx.is_finite()
                && vy.is_finite())
            {
                return Err(BlowUp {
                    block: i,
                    what: "a non-finite position or velocity".into(),
                });
            }
            // Squared speeds: hypot is slow and this runs per block-step.
            if vx * vx + vy * vy > self.v_blowup * self.v_blowup {
                return Err(BlowUp {
                    block: i,
                    what: format!(
                        "a speed of {:.3e} m/s, above the physical bound {:.3e} m/s",
                        vx.hypot(vy),
                        self.v_blowup
                    ),
                });
            }
        }
        self.sum_ux += dsx;
        self.sum_uy += dsy;
        state.t = t + dt;
        self.advance_parked(dt);
        self.steps += 1;
        self.block_steps += nm as u64;
        Ok(self.transitions(state))
    }

    /// Stick/slip transitions after a step; refreshes caches and the moving
    /// list. Returns the number of blocks that started to slide.
    fn transitions(&mut self, state: &mut SpringBlockState) -> usize {
        let lat = self.lat;
        let t = state.t;
        // Sliding contact blocks whose velocity reversed come to rest.
        for m in 0..self.moving.len() {
            let i = self.moving[m] as usize;
            if self.iface.is_free(i) {
                continue;
            }
            let (ox, oy) = (self.ovx[m], self.ovy[m]);
            let (vx, vy) = (state.vx[i], state.vy[i]);
            if ox * ox + oy * oy > 0.0 && vx * ox + vy * oy <= 0.0 {
                state.vx[i] = 0.0;
                state.vy[i] = 0.0;
                let (fix, fiy) = internal_force_on(lat, &state.ux, &state.uy, i);
                let fmx = fix + lat.k_shear * (self.vel.0 * t - state.ux[i]);
                let fmy = fiy + lat.k_shear * (self.vel.1 * t - state.uy[i]);
                let th = self.iface.threshold[i];
                if fmx * fmx + fmy * fmy <= th * th {
                    state.sliding[i] = false;
                }
            }
        }
        // Refresh the internal-force cache of stuck blocks next to movers.
        for &i in &self.moving {
            let i = i as usize;
            for d in 0..8 {
                let j = lat.nbr[8 * i + d] as usize;
                if !self.dirty[j] {
                    self.dirty[j] = true;
                    self.dirty_list.push(j as u32);
                }
            }
            if !self.dirty[i] {
                self.dirty[i] = true;
                self.dirty_list.push(i as u32);
            }
        }
        let dirty = std::mem::take(&mut self.dirty_list);
        for &j in &dirty {
            let j = j as usize;
            self.dirty[j] = false;
            // A sliding block's crossing time is already ∞.
            if !state.sliding[j] || self.tcross[j].is_finite() {
                self.refresh(state, j);
            }
        }
        self.dirty_list = dirty;
        self.dirty_list.clear();
        // Moving list: keep the still-moving blocks, add new slips in index
        // order.
        self.moving.retain(|&i| state.sliding[i as usize]);
        self.check_thresholds(state)
    }

    /// Marks stuck blocks whose driving force has reached the static
    /// threshold (crossing time ≤ t) as sliding and adds them to the moving
    /// list, in index order. Returns how many.
    pub(crate) fn check_thresholds(&mut self, state: &mut SpringBlockState) -> usize {
        let t = state.t;
        if self.tree[1] > t {
            return 0;
        }
        self.due.clear();
        let mut stack = vec![1usize];
        while let Some(k) = stack.pop() {
            if self.tree[k] > t {
                continue;
            }
            if k >= self.leaves {
                self.due.push((k - self.leaves) as u32);
            } else {
                stack.push(2 * k + 1);
                stack.push(2 * k);
            }
        }
        self.due.sort_unstable();
        let due = std::mem::take(&mut self.due);
        for &i in &due {
            let i = i as usize;
            state.sliding[i] = true;
            self.moving.push(i as u32);
            self.set_cross(i, f64::INFINITY);
        }
        let started = due.len();
        self.due = due;
        started
    }

    /// Driving force F_mot on a stuck block from the cache \[N\].
    pub(crate) fn driving_force_cached(&self, state: &SpringBlockState, i: usize) -> (f64, f64) {
        let ks = self.lat.k_shear;
        let s = state.t - self.tf[i];
        (
            self.fint_x[i] + self.rint_x[i] * s + ks * (self.vel.0 * state.t - state.ux[i]),
            self.fint_y[i] + self.rint_y[i] * s + ks * (self.vel.1 * state.t - state.uy[i]),
        )
    }
}
