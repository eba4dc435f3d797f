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
//! The stepper is assembled from parts with one job each: the read-only
//! [`StepContext`], the [`Rk4Scratch`], the [`StuckCache`], the
//! [`CrossingTree`] and the [`ParkedBlocks`].
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

use super::context::StepContext;
use super::crossing::CrossingTree;
use super::parked::ParkedBlocks;
use super::scratch::Rk4Scratch;
pub use super::state::{BlowUp, SpringBlockState};
use super::stuck::StuckCache;
use crate::models::spring_block::forces::{
    damping_acceleration, friction_direction, internal_force_on, kinetic_friction,
};
use crate::models::spring_block::{Interface, Lattice};

/// One run's stepper: the context it reads, the parts it owns, the moving
/// list and the running sums.
pub struct Stepper<'a> {
    /// Lattice, interface, slider velocity, γ.
    pub(crate) ctx: StepContext<'a>,
    sc: Rk4Scratch,
    cache: StuckCache,
    cross: CrossingTree,
    pub(crate) parked: ParkedBlocks,
    /// Blocks whose cache must be refreshed after a step.
    dirty: Vec<bool>,
    dirty_list: Vec<u32>,
    /// Moving blocks (sliding contact blocks and free blocks).
    pub(crate) moving: Vec<u32>,
    /// Running Σ u_x, Σ u_y over all blocks \[m\].
    sum_u: (f64, f64),
    /// Steps taken.
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
        let mut s = Stepper {
            ctx: StepContext::new(lat, iface, vel, gamma),
            sc: Rk4Scratch::new(&state.ux, &state.uy),
            cache: StuckCache::new(n),
            cross: CrossingTree::new(n),
            parked: ParkedBlocks::new(n),
            dirty: vec![false; n],
            dirty_list: Vec::with_capacity(n),
            moving: Vec::with_capacity(n),
            sum_u: (0.0, 0.0),
            steps: 0,
            block_steps: 0,
        };
        s.resync(state);
        s
    }

    /// The read-only context.
    pub fn context(&self) -> &StepContext<'a> {
        &self.ctx
    }

    /// Recomputes every cache from `state` (after a jump or at the start).
    pub fn resync(&mut self, state: &SpringBlockState) {
        let lat = self.ctx.lat;
        self.sc.px.copy_from_slice(&state.ux);
        self.sc.py.copy_from_slice(&state.uy);
        for i in 0..lat.len() {
            let f = internal_force_on(lat, &state.ux, &state.uy, i);
            let r = self.parked_rate(state, i);
            self.cache.store(i, f, r, state.t);
        }
        let parked = &self.parked.flag;
        self.moving.clear();
        self.moving.extend(
            (0..lat.len() as u32).filter(|&i| state.sliding[i as usize] && !parked[i as usize]),
        );
        let mut cross = std::mem::replace(&mut self.cross, CrossingTree::new(0));
        cross.rebuild(|i| self.crossing(state, i));
        self.cross = cross;
        self.sum_u = (state.ux.iter().sum(), state.uy.iter().sum());
    }

    /// Time at which stuck block `i` reaches its threshold if its internal
    /// force stays as cached (∞ if it slides).
    fn crossing(&self, state: &SpringBlockState, i: usize) -> f64 {
        if state.sliding[i] {
            return f64::INFINITY;
        }
        let g = self.cache.driving_force(&self.ctx, state, i);
        let r = self.cache.loading_rate(&self.ctx, i);
        state.t + super::crossing::crossing_time(g, r, self.ctx.iface.threshold[i])
    }

    /// R_int = Σ_j K_t^(ij) w_j over parked neighbours j of block i [N/s].
    fn parked_rate(&self, state: &SpringBlockState, i: usize) -> (f64, f64) {
        let lat = self.ctx.lat;
        let (mut rx, mut ry) = (0.0, 0.0);
        if self.parked.none() {
            return (rx, ry);
        }
        for d in 0..8 {
            let j = lat.nbr[8 * i + d] as usize;
            if j == i || !self.parked.flag[j] {
                continue;
            }
            let dx = lat.dx0[d] + state.ux[j] - state.ux[i];
            let dy = lat.dy0[d] + state.uy[j] - state.uy[i];
            let [kxx, kxy, kyy] =
                crate::models::spring_block::forces::tangent(lat.k[8 * i + d], lat.rest[d], dx, dy);
            let (wx, wy) = (state.vx[j], state.vy[j]);
            rx += kxx * wx + kxy * wy;
            ry += kxy * wx + kyy * wy;
        }
        (rx, ry)
    }

    /// Recomputes the cached internal force (and its rate) of block `j` if
    /// it is stuck, and its crossing time.
    pub(crate) fn refresh(&mut self, state: &mut SpringBlockState, j: usize) {
        let lat = self.ctx.lat;
        if !state.sliding[j] {
            if !self.parked.none() {
                for d in 0..8 {
                    self.parked
                        .materialize(state, &mut self.sc, lat.nbr[8 * j + d] as usize);
                }
            }
            let f = internal_force_on(lat, &state.ux, &state.uy, j);
            let r = self.parked_rate(state, j);
            self.cache.store(j, f, r, state.t);
        }
        let c = self.crossing(state, j);
        self.cross.set(j, c);
    }

    /// Parks free block `i` at its current position with velocity `w`:
    /// u = u0 + w (t − t0) from now on. Call [`Self::parked_changed`] after
    /// a batch of park and unpark calls.
    pub(crate) fn park(&mut self, state: &mut SpringBlockState, i: usize, w: (f64, f64)) {
        self.parked.park(state, i);
        (state.vx[i], state.vy[i]) = w;
    }

    /// Unparks block `i` (its position is current) and puts it back in the
    /// moving list.
    pub(crate) fn unpark(&mut self, i: usize) {
        self.parked.flag[i] = false;
        self.moving.push(i as u32);
    }

    /// Rebuilds the parked list, Σ w and the moving list after parking or
    /// unparking.
    pub(crate) fn parked_changed(&mut self, state: &SpringBlockState) {
        self.parked.rebuild(&self.ctx, state);
        let flag = &self.parked.flag;
        self.moving.retain(|&i| !flag[i as usize]);
    }

    /// Accounts for the motion of parked blocks in Σ u after the clock
    /// advanced by `dt`. Their positions are brought up to date only when
    /// read ([`Self::materialize`]).
    pub(crate) fn advance_parked(&mut self, dt: f64) {
        self.sum_u.0 += self.parked.wsum.0 * dt;
        self.sum_u.1 += self.parked.wsum.1 * dt;
    }

    /// Brings the position of block `i` up to `state.t` if it is parked.
    #[inline]
    pub(crate) fn materialize(&mut self, state: &mut SpringBlockState, i: usize) {
        self.parked.materialize(state, &mut self.sc, i);
    }

    /// Brings every parked position up to date and recomputes Σ u (after
    /// positions were corrected).
    pub(crate) fn materialize_all(&mut self, state: &mut SpringBlockState) {
        self.parked.materialize_all(state, &mut self.sc);
        self.sum_u = (state.ux.iter().sum(), state.uy.iter().sum());
    }

    /// Marks stuck block `i` as sliding and puts it in the moving list.
    pub(crate) fn start_sliding(&mut self, state: &mut SpringBlockState, i: usize) {
        if state.sliding[i] {
            return;
        }
        state.sliding[i] = true;
        self.moving.push(i as u32);
        self.cross.set(i, f64::INFINITY);
    }

    /// Blocks that started to slide in the last [`Self::check_thresholds`]
    /// that returned a nonzero count.
    pub(crate) fn started(&self) -> &[u32] {
        self.cross.due()
    }

    /// Earliest threshold crossing of a stuck block under linear loading,
    /// and that block (`None` if no block is stuck).
    pub fn next_crossing(&self) -> Option<(f64, usize)> {
        self.cross.earliest()
    }

    /// Friction force on the slider, T_vec = K_s (N v t − Σ u) \[N\].
    pub fn slider_force(&self, t: f64) -> (f64, f64) {
        let (lat, vel) = (self.ctx.lat, self.ctx.vel);
        let n = lat.len() as f64;
        (
            lat.k_shear * (n * vel.0 * t - self.sum_u.0),
            lat.k_shear * (n * vel.1 * t - self.sum_u.1),
        )
    }

    /// Number of moving blocks that are not free (sliding contact blocks).
    pub fn sliding_contacts(&self) -> usize {
        let iface = self.ctx.iface;
        self.moving
            .iter()
            .filter(|&&i| !iface.is_free(i as usize))
            .count()
    }

    /// Acceleration of moving block `i` at stage positions, stage velocity
    /// (wx, wy), velocity at the step's start (ox, oy) and stage time `t`:
    /// (F_int + F_shear + F_friction)/m − γ u̇ (MODELS.md §7).
    /// Kinetic friction follows the stage velocity (led by the driving
    /// force when that is too slow for the step `dt`, see
    /// [`friction_direction`]) unless it has reversed with respect to the
    /// step's start: then it keeps opposing the original motion, so that
    /// the block is seen to stop at the step's end instead of chattering
    /// around zero velocity.
    #[inline(always)]
    fn accel(&self, i: usize, w: (f64, f64), (ox, oy): (f64, f64), t: f64, dt: f64) -> (f64, f64) {
        let ctx = &self.ctx;
        let (wx, wy) = w;
        let (fix, fiy) = internal_force_on(ctx.lat, &self.sc.px, &self.sc.py, i);
        let (gx, gy) = ctx.shear(t, self.sc.px[i], self.sc.py[i]);
        let (fmx, fmy) = (fix + gx, fiy + gy);
        let f_dyn = ctx.iface.kinetic[i];
        let (dx, dy) = if wx * ox + wy * oy < 0.0 {
            (ox, oy)
        } else if f_dyn > 0.0 {
            friction_direction(w, (fmx, fmy), ctx.lat.mass, dt)
        } else {
            w // a free (hole) block: no friction to direct
        };
        let (ffx, ffy) = kinetic_friction(f_dyn, dx, dy, fmx, fmy);
        let (dax, day) = damping_acceleration(ctx.gamma, wx, wy);
        let inv_m = 1.0 / ctx.lat.mass;
        ((fmx + ffx) * inv_m + dax, (fmy + ffy) * inv_m + day)
    }

    /// The four RK4 stages of the moving blocks from `state` at time t;
    /// leaves the weighted sums in the scratch.
    fn stages(&mut self, state: &SpringBlockState, dt: f64) {
        let (t, nm) = (state.t, self.moving.len());
        // Stage 1 at the start of the step (px = ux between steps).
        self.parked.place_halo(state, &mut self.sc, t);
        for m in 0..nm {
            let i = self.moving[m] as usize;
            let w = (state.vx[i], state.vy[i]);
            let a = self.accel(i, w, w, t, dt);
            self.sc.first_stage(m, w, a);
        }
        for (c, weight) in [(0.5 * dt, 2.0), (0.5 * dt, 2.0), (dt, 1.0)] {
            let sc = &mut self.sc;
            for m in 0..nm {
                let i = self.moving[m] as usize;
                sc.px[i] = state.ux[i] + c * sc.kxx[m];
                sc.py[i] = state.uy[i] + c * sc.kxy[m];
                sc.svx[m] = state.vx[i] + c * sc.kvx[m];
                sc.svy[m] = state.vy[i] + c * sc.kvy[m];
            }
            self.parked.place_halo(state, &mut self.sc, t + c);
            for m in 0..nm {
                let i = self.moving[m] as usize;
                let w = (self.sc.svx[m], self.sc.svy[m]);
                let a = self.accel(i, w, (self.sc.ovx[m], self.sc.ovy[m]), t + c, dt);
                self.sc.later_stage(m, weight, w, a);
            }
        }
    }

    /// Advances `state` by `dt` with classical RK4 over the moving blocks,
    /// then applies stick/slip transitions. Returns the number of blocks that
    /// started to slide, or where the integration blew up.
    pub fn step(&mut self, state: &mut SpringBlockState, dt: f64) -> Result<usize, BlowUp> {
        let t = state.t;
        let nm = self.moving.len();
        self.stages(state, dt);
        let h6 = dt / 6.0;
        let (mut dsx, mut dsy) = (0.0, 0.0);
        for m in 0..nm {
            let i = self.moving[m] as usize;
            let sc = &mut self.sc;
            let (dx, dy) = (h6 * sc.sxx[m], h6 * sc.sxy[m]);
            state.ux[i] += dx;
            state.uy[i] += dy;
            state.vx[i] += h6 * sc.svsx[m];
            state.vy[i] += h6 * sc.svsy[m];
            sc.px[i] = state.ux[i];
            sc.py[i] = state.uy[i];
            dsx += dx;
            dsy += dy;
            self.check_finite(state, i)?;
        }
        self.sum_u.0 += dsx;
        self.sum_u.1 += dsy;
        state.t = t + dt;
        self.advance_parked(dt);
        self.steps += 1;
        self.block_steps += nm as u64;
        Ok(self.transitions(state))
    }

    /// A blow-up at block `i`: a non-finite value or a speed above the
    /// physical bound.
    #[inline(always)]
    fn check_finite(&self, state: &SpringBlockState, i: usize) -> Result<(), BlowUp> {
        let (vx, vy) = (state.vx[i], state.vy[i]);
        if !(state.ux[i].is_finite() && state.uy[i].is_finite() && vx.is_finite() && vy.is_finite())
        {
            return Err(BlowUp {
                block: i,
                what: "a non-finite position or velocity".into(),
            });
        }
        // Squared speeds: hypot is slow and this runs per block-step.
        let vb = self.ctx.v_blowup;
        if vx * vx + vy * vy > vb * vb {
            return Err(BlowUp {
                block: i,
                what: format!(
                    "a speed of {:.3e} m/s, above the physical bound {vb:.3e} m/s",
                    vx.hypot(vy)
                ),
            });
        }
        Ok(())
    }

    /// Sliding contact blocks whose velocity reversed in the last step come
    /// to rest, and stick if their driving force is below the threshold.
    fn stop_reversed(&mut self, state: &mut SpringBlockState) {
        let ctx = self.ctx;
        let t = state.t;
        for m in 0..self.moving.len() {
            let i = self.moving[m] as usize;
            if ctx.iface.is_free(i) {
                continue;
            }
            let (ox, oy) = (self.sc.ovx[m], self.sc.ovy[m]);
            let (vx, vy) = (state.vx[i], state.vy[i]);
            if ox * ox + oy * oy > 0.0 && vx * ox + vy * oy <= 0.0 {
                state.vx[i] = 0.0;
                state.vy[i] = 0.0;
                let (fix, fiy) = internal_force_on(ctx.lat, &state.ux, &state.uy, i);
                let (gx, gy) = ctx.shear(t, state.ux[i], state.uy[i]);
                let (fmx, fmy) = (fix + gx, fiy + gy);
                let th = ctx.iface.threshold[i];
                if fmx * fmx + fmy * fmy <= th * th {
                    state.sliding[i] = false;
                }
            }
        }
    }

    /// Refreshes the internal-force cache of the stuck blocks next to
    /// moving ones.
    fn refresh_near_moving(&mut self, state: &mut SpringBlockState) {
        let lat = self.ctx.lat;
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
            if !state.sliding[j] || self.cross.time(j).is_finite() {
                self.refresh(state, j);
            }
        }
        self.dirty_list = dirty;
        self.dirty_list.clear();
    }

    /// Stick/slip transitions after a step; refreshes caches and the moving
    /// list. Returns the number of blocks that started to slide.
    fn transitions(&mut self, state: &mut SpringBlockState) -> usize {
        self.stop_reversed(state);
        self.refresh_near_moving(state);
        // Moving list: keep the still-moving blocks, add new slips in index
        // order.
        self.moving.retain(|&i| state.sliding[i as usize]);
        self.check_thresholds(state)
    }

    /// Marks stuck blocks whose driving force has reached the static
    /// threshold (crossing time ≤ t) as sliding and adds them to the moving
    /// list, in index order. Returns how many. Allocates nothing.
    pub(crate) fn check_thresholds(&mut self, state: &mut SpringBlockState) -> usize {
        let t = state.t;
        self.check_thresholds_by(state, t)
    }

    /// [`Self::check_thresholds`] for crossing times up to `t_due`.
    pub(crate) fn check_thresholds_by(
        &mut self,
        state: &mut SpringBlockState,
        t_due: f64,
    ) -> usize {
        let due = self.cross.collect_due(t_due);
        for &i in due {
            state.sliding[i as usize] = true;
            self.moving.push(i);
        }
        due.len()
    }

    /// Driving force F_mot on a stuck block from the cache \[N\].
    pub(crate) fn driving_force_cached(&self, state: &SpringBlockState, i: usize) -> (f64, f64) {
        self.cache.driving_force(&self.ctx, state, i)
    }
}
