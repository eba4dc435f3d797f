//! Parked hole clusters: quasi-static free blocks between slips.
//!
//! Free (hole) blocks are frictionless and never stick (MODELS.md §7). A
//! connected cluster of them (8-neighbour springs) whose bordering contact
//! blocks all stick and whose blocks have settled follows the slider
//! quasi-statically: it is *parked* and moves affinely, u = u0 + w (t − t0),
//! where w solves the cluster's tangent-stiffness rate system
//!
//! K_s w_i + Σ_j K_t^(ij) (w_i − w_j) = K_s v   (w_j = 0 for stuck j),
//!
//! the same system as the global jump of [`super::event`], but per cluster:
//! clusters are separated by stuck blocks and decouple. A parked cluster is
//! not integrated; the stuck blocks around it see a linearly changing
//! internal force, so their threshold-crossing times stay closed forms
//! ([`super::event::crossing_time`] with R_i = K_s v + Σ_j K_t^(ij) w_j).
//!
//! - **Park**: every `CHECK_EVERY` steps, an awake cluster with all borders
//!   stuck and net force / speed within `quiet_tolerance` (as for a jump) is
//!   parked: w solved, a Newton correction to equilibrium, w solved again.
//! - **Re-park**: the affine motion is exact to first order; a cluster parked
//!   for a slider travel of ½ `jump_travel` · l is corrected and re-parked.
//! - **Wake**: when a bordering contact block starts to slide, the cluster
//!   is Newton-corrected and goes back into RK4 with velocity w.
//! - **Tiles**: a cluster wider or taller than [`TILE`](super::tiles::TILE) blocks (the grooves
//!   of pattern S) is cut into tiles of [`TILE`](super::tiles::TILE) × [`TILE`](super::tiles::TILE), the unit of
//!   parking. A slip wakes only the tiles with a block within
//!   [`WAKE_RADIUS`] of it (the elastic screening length is about one
//!   spacing); the others stay parked, and the stepper places those next
//!   to integrated blocks at each stage's time. A parked set of tiles
//!   solves the rate system with the free blocks around it at their own
//!   velocity (right-hand side K_s v + Σ_j K_t^(ij) w_j); a connected
//!   group of awake tiles parks as soon as it has settled with its borders
//!   stuck, jointly with the parked tiles next to it, so no tile waits for
//!   its neighbours. Clusters within one tile behave as before.
//! - **Jump**: when nothing moves (every cluster parked, no contact block
//!   sliding), the clock jumps to the next crossing, or to the earliest
//!   re-park deadline (a full `jump_travel` · l of slider travel).

use super::event::Jump;
use super::rate::{RateSystem, Settling};
use super::stepper::{SpringBlockState, Stepper};
use super::tiles::Tiling;

/// Steps between attempts to park awake clusters.
const CHECK_EVERY: u64 = 16;

/// A slip wakes the tiles of a cut cluster that have a block within this
/// many blocks (Chebyshev distance) of it. The elastic screening length is
/// about one spacing (K_s = K_int), so farther blocks barely feel it.
pub const WAKE_RADIUS: usize = 2;

/// Clusters of free blocks, their tiles and parking state.
pub struct Parker {
    /// Clusters and tiles.
    tiling: Tiling,
    parked: Vec<bool>,
    /// Time each parked tile was last (re-)parked \[s\].
    t0: Vec<f64>,
    /// The set being solved: its blocks, and each block's slot in it.
    set: Vec<u32>,
    slot: Vec<u32>,
    /// Rate system scratch, sized for the largest cluster.
    rate: RateSystem,
    /// Settling scales and `quiet_tolerance`.
    settling: Settling,
    tol: f64,
    /// Slider time of a full `jump_travel` \[s\].
    cap: f64,
    /// Earliest t0 + cap/2 over parked tiles \[s\].
    next_repark: f64,
    /// Jumps made.
    pub jumps: u64,
    /// Tiles parked, re-parks included.
    pub parks: u64,
    /// Tiles woken.
    pub wakes: u64,
}

impl Parker {
    /// Finds the clusters of free blocks and cuts those larger than
    /// [`TILE`](super::tiles::TILE) into tiles. `tol` is `quiet_tolerance`, `max_travel` the
    /// largest slider travel between re-parks (m).
    pub fn new(st: &Stepper, tol: f64, max_travel: f64) -> Self {
        let n = st.ctx.lat.len();
        let tiling = Tiling::new(st.ctx.lat, st.ctx.iface);
        let (nt, largest) = (tiling.tiles(), tiling.largest_cluster());
        let speed = st.ctx.vel.0.hypot(st.ctx.vel.1);
        Parker {
            tiling,
            parked: vec![false; nt],
            t0: vec![0.0; nt],
            set: Vec::with_capacity(largest),
            slot: vec![u32::MAX; n],
            rate: RateSystem::new(largest),
            settling: Settling::new(st),
            tol,
            cap: max_travel / speed,
            next_repark: f64::INFINITY,
            jumps: 0,
            parks: 0,
            wakes: 0,
        }
    }

    /// Number of clusters.
    pub fn clusters(&self) -> usize {
        self.tiling.clusters()
    }

    /// Whether every tile of cluster `c` is parked.
    pub fn is_parked(&self, c: usize) -> bool {
        self.parked[self.tiling.tiles_of_cluster(c)]
            .iter()
            .all(|&p| p)
    }

    /// Cluster of block `i`, if it is free.
    pub fn cluster_of(&self, i: usize) -> Option<usize> {
        self.tile_of(i).map(|t| self.tiling.cluster_of_tile(t))
    }

    /// Number of tiles (a cluster no larger than [`TILE`](super::tiles::TILE) is one tile).
    pub fn tiles(&self) -> usize {
        self.tiling.tiles()
    }

    /// Tile of block `i`, if it is free.
    pub fn tile_of(&self, i: usize) -> Option<usize> {
        self.tiling.tile_of(i)
    }

    /// Whether tile `t` is parked.
    pub fn tile_parked(&self, t: usize) -> bool {
        self.parked[t]
    }

    fn members(&self, t: usize) -> std::ops::Range<usize> {
        self.tiling.block_range(t)
    }

    fn borders_stuck(&self, state: &SpringBlockState, t: usize) -> bool {
        self.tiling
            .border_of(t)
            .iter()
            .all(|&j| !state.sliding[j as usize])
    }

    /// Makes `tiles` the current set.
    fn select(&mut self, tiles: &[usize]) {
        for &i in &self.set {
            self.slot[i as usize] = u32::MAX;
        }
        self.set.clear();
        for &t in tiles {
            self.set.extend_from_slice(self.tiling.blocks_of(t));
        }
        for (k, &i) in self.set.iter().enumerate() {
            self.slot[i as usize] = k as u32;
        }
    }

    /// Brings parked blocks in and around the current set up to `state.t`.
    fn materialize_around(&self, st: &mut Stepper, state: &mut SpringBlockState) {
        let lat = st.ctx.lat;
        for &i in &self.set {
            let i = i as usize;
            st.materialize(state, i);
            for d in 0..8 {
                st.materialize(state, lat.nbr[8 * i + d] as usize);
            }
        }
    }

    /// Sets the velocities of the current set to its quasi-static rate w,
    /// with free neighbours outside the set moving at their own velocity
    /// (parked ones at their w).
    fn set_rate(&mut self, st: &Stepper, state: &mut SpringBlockState) -> bool {
        let slot = &self.slot;
        let in_set = |j: usize| (slot[j] != u32::MAX).then(|| slot[j] as usize);
        let (iface, vx, vy) = (st.ctx.iface, &state.vx, &state.vy);
        let outside = |j: usize| iface.is_free(j).then(|| (vx[j], vy[j]));
        if !self
            .rate
            .solve_rate_bounded(st, state, &self.set, &in_set, &outside)
        {
            return false;
        }
        for (k, &i) in self.set.iter().enumerate() {
            state.vx[i as usize] = self.rate.w[2 * k];
            state.vy[i as usize] = self.rate.w[2 * k + 1];
        }
        true
    }

    /// Puts the current set in equilibrium at its current velocities, its
    /// neighbours held where they are.
    fn correct(&mut self, st: &Stepper, state: &mut SpringBlockState) {
        let slot = &self.slot;
        let in_set = |j: usize| (slot[j] != u32::MAX).then(|| slot[j] as usize);
        self.rate.correct(st, state, &self.set, &in_set);
    }

    /// Parks (or re-parks) `tiles` jointly; their borders must stick. False
    /// if the rate system did not converge (the tiles then stay as they
    /// were).
    fn park(&mut self, st: &mut Stepper, state: &mut SpringBlockState, tiles: &[usize]) -> bool {
        self.select(tiles);
        self.materialize_around(st, state);
        if !self.set_rate(st, state) {
            return false;
        }
        self.correct(st, state);
        // Should this second solve fail, the first rate stays: the
        // positions have moved, so the tiles must be parked from here.
        self.set_rate(st, state);
        for k in 0..self.set.len() {
            let i = self.set[k] as usize;
            st.park(state, i, (state.vx[i], state.vy[i]));
        }
        for &t in tiles {
            self.parked[t] = true;
            self.t0[t] = state.t;
        }
        self.parks += tiles.len() as u64;
        true
    }

    fn wake(&mut self, st: &mut Stepper, state: &mut SpringBlockState, t: usize) {
        self.select(&[t]);
        self.correct(st, state);
        for k in self.members(t) {
            st.unpark(self.tiling.blocks[k] as usize);
        }
        self.parked[t] = false;
        self.wakes += 1;
    }

    /// Refreshes the cached forces of the borders of tiles `ts` and the
    /// parked bookkeeping after positions or parking changed.
    fn finish(&mut self, st: &mut Stepper, state: &mut SpringBlockState, ts: &[usize]) {
        st.parked_changed(state);
        st.materialize_all(state);
        for &t in ts {
            for &j in self.tiling.border_of(t) {
                st.refresh(state, j as usize);
            }
        }
        self.next_repark = (0..self.tiles())
            .filter(|&t| self.parked[t])
            .map(|t| self.t0[t] + 0.5 * self.cap)
            .fold(f64::INFINITY, f64::min);
    }

    /// Parks every awake cluster that is settled with all borders stuck. In
    /// a cut cluster, each connected group of awake tiles is a unit: it
    /// parks when settled with its borders stuck, jointly with the parked
    /// tiles next to it (which are corrected and get new rates), the other
    /// parked tiles of the cluster giving boundary rates.
    pub fn park_settled(&mut self, st: &mut Stepper, state: &mut SpringBlockState) {
        let mut done = Vec::new();
        let mut group = Vec::new();
        for c in 0..self.clusters() {
            let tiles = self.tiling.tiles_of_cluster(c);
            if !self.tiling.cut[c] {
                let t = tiles.start;
                if !self.parked[t] && self.borders_stuck(state, t) {
                    self.select(&[t]);
                    if self.settling.settled(st, state, &self.set, self.tol)
                        && self.park(st, state, &[t])
                    {
                        done.push(t);
                    }
                }
                continue;
            }
            let mut visited: Vec<bool> = tiles.clone().map(|t| self.parked[t]).collect();
            for t in tiles.clone() {
                if visited[t - tiles.start] {
                    continue;
                }
                // The connected group of awake tiles containing t.
                group.clear();
                group.push(t);
                visited[t - tiles.start] = true;
                let mut k = 0;
                while k < group.len() {
                    let u = group[k];
                    k += 1;
                    for &v in self.tiling.adjacent(u) {
                        let v = v as usize;
                        if !visited[v - tiles.start] {
                            visited[v - tiles.start] = true;
                            group.push(v);
                        }
                    }
                }
                if !group.iter().all(|&u| self.borders_stuck(state, u)) {
                    continue;
                }
                self.select(&group);
                self.materialize_around(st, state);
                if !self.settling.settled(st, state, &self.set, self.tol) {
                    continue;
                }
                let awake = group.len();
                for k in 0..awake {
                    let u = group[k];
                    for &v in self.tiling.adjacent(u) {
                        let v = v as usize;
                        if self.parked[v] && !group.contains(&v) {
                            group.push(v);
                        }
                    }
                }
                group.sort_unstable();
                if self.park(st, state, &group) {
                    done.extend_from_slice(&group);
                }
            }
        }
        if !done.is_empty() {
            self.finish(st, state, &done);
        }
    }

    /// Re-parks the tiles parked for half the travel cap or longer (in a
    /// cut cluster, all its parked tiles jointly).
    fn repark_aged(&mut self, st: &mut Stepper, state: &mut SpringBlockState) {
        if state.t < self.next_repark {
            return;
        }
        st.materialize_all(state);
        let mut done = Vec::new();
        let mut group = Vec::new();
        for c in 0..self.clusters() {
            let tiles = self.tiling.tiles_of_cluster(c);
            let aged = |p: &Self, t: usize| p.parked[t] && state.t >= p.t0[t] + 0.5 * p.cap;
            if !tiles.clone().any(|t| aged(self, t)) {
                continue;
            }
            group.clear();
            group.extend(tiles.filter(|&t| self.parked[t]));
            // Rebuild their velocities from scratch: correct and park.
            if self.park(st, state, &group) {
                done.extend_from_slice(&group);
            }
        }
        // A failed re-park leaves the tiles parked with their old rates; the
        // deadline then moves on by half a cap.
        for t in 0..self.tiles() {
            if self.parked[t] && state.t >= self.t0[t] + 0.5 * self.cap {
                self.t0[t] = state.t;
            }
        }
        self.finish(st, state, &done);
    }

    /// Wakes the parked tiles next to the blocks that just started to
    /// slide: a whole cluster when it borders the block, the tiles of a cut
    /// cluster within [`WAKE_RADIUS`] of it.
    fn wake_around(&mut self, st: &mut Stepper, state: &mut SpringBlockState, started: &[u32]) {
        let lat = st.ctx.lat;
        let (nx, ny) = (lat.nx, lat.ny);
        let r = WAKE_RADIUS;
        let mut woken = Vec::new();
        for &i in started {
            let i = i as usize;
            for d in 0..8 {
                let j = lat.nbr[8 * i + d] as usize;
                if let Some(t) = self.tile_of(j) {
                    if self.parked[t] && !self.tiling.cut[self.tiling.cluster_of_tile(t)] {
                        if woken.is_empty() {
                            st.materialize_all(state);
                        }
                        self.wake(st, state, t);
                        woken.push(t);
                    }
                }
            }
            let (x, y) = (i % nx, i / nx);
            for yy in y.saturating_sub(r)..(y + r + 1).min(ny) {
                for xx in x.saturating_sub(r)..(x + r + 1).min(nx) {
                    if let Some(t) = self.tile_of(yy * nx + xx) {
                        if self.parked[t] && self.tiling.cut[self.tiling.cluster_of_tile(t)] {
                            if woken.is_empty() {
                                st.materialize_all(state);
                            }
                            self.wake(st, state, t);
                            woken.push(t);
                        }
                    }
                }
            }
        }
        if !woken.is_empty() {
            self.finish(st, state, &woken);
        }
    }

    /// Bookkeeping after an RK4 step that started `started` slips: wakes
    /// tiles next to new slips, re-parks aged tiles and, every
    /// `CHECK_EVERY` steps, parks settled ones.
    pub fn after_step(&mut self, st: &mut Stepper, state: &mut SpringBlockState, started: usize) {
        if started > 0 {
            let s = st.started().to_vec();
            self.wake_around(st, state, &s);
        }
        self.repark_aged(st, state);
        if st.steps % CHECK_EVERY == 0 {
            self.park_settled(st, state);
        }
    }

    /// Jumps the clock when nothing moves: to the next threshold crossing,
    /// to `t_limit`, or to the earliest re-park deadline. A jump shorter
    /// than `dt` is not made.
    pub fn try_jump(
        &mut self,
        st: &mut Stepper,
        state: &mut SpringBlockState,
        dt: f64,
        t_limit: f64,
    ) -> Jump {
        if !st.moving.is_empty() {
            return Jump::NotQuiet;
        }
        let (tc, first) = st.next_crossing().unwrap_or((f64::INFINITY, usize::MAX));
        let deadline = self.next_repark + 0.5 * self.cap;
        let end = tc.min(t_limit).min(deadline);
        let step = end - state.t;
        if step.is_nan() || step < dt {
            return Jump::NotQuiet;
        }
        let hit = tc <= end;
        state.t = end;
        st.advance_parked(step);
        self.repark_aged(st, state);
        let mut started = Vec::new();
        if hit && first != usize::MAX && !state.sliding[first] {
            // The linear loading is the model: this block is at its
            // threshold now.
            st.start_sliding(state, first);
            started.push(first as u32);
        }
        if st.check_thresholds_by(state, end + super::event::TIE * dt) > 0 {
            started.extend_from_slice(st.started());
        }
        self.wake_around(st, state, &started);
        self.jumps += 1;
        Jump::Jumped(step)
    }
}
