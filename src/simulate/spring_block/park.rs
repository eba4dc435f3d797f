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
//! - **Tiles**: a cluster wider or taller than [`TILE`] blocks (the grooves
//!   of pattern S) is cut into tiles of [`TILE`] × [`TILE`], the unit of
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

/// Steps between attempts to park awake clusters.
const CHECK_EVERY: u64 = 16;

/// Largest extent of a cluster kept whole (blocks); larger clusters are cut
/// into tiles of this many columns and rows.
pub const TILE: usize = 8;

/// A slip wakes the tiles of a cut cluster that have a block within this
/// many blocks (Chebyshev distance) of it. The elastic screening length is
/// about one spacing (K_s = K_int), so farther blocks barely feel it.
pub const WAKE_RADIUS: usize = 2;

/// Clusters of free blocks, their tiles and parking state.
pub struct Parker {
    /// Tiles of cluster c: `cstart[c]..cstart[c + 1]`.
    cstart: Vec<usize>,
    /// Whether cluster c is cut into several tiles.
    cut: Vec<bool>,
    /// Blocks of tile t: `blocks[start[t]..start[t + 1]]`.
    start: Vec<usize>,
    blocks: Vec<u32>,
    /// Contact blocks bordering tile t: `border[bstart[t]..bstart[t + 1]]`.
    bstart: Vec<usize>,
    border: Vec<u32>,
    /// Tiles of the same cluster next to tile t: `adj[astart[t]..astart[t + 1]]`.
    astart: Vec<usize>,
    adj: Vec<u32>,
    /// Cluster of each tile.
    tile_cluster: Vec<u32>,
    /// Tile of each block (u32::MAX for contact blocks).
    tile_of: Vec<u32>,
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
    /// [`TILE`] into tiles. `tol` is `quiet_tolerance`, `max_travel` the
    /// largest slider travel between re-parks (m).
    pub fn new(st: &Stepper, tol: f64, max_travel: f64) -> Self {
        let lat = st.lat;
        let n = lat.len();
        let nx = lat.nx;
        let mut cluster_of = vec![u32::MAX; n];
        let mut tile_of = vec![u32::MAX; n];
        let mut cstart = vec![0usize];
        let mut cut = Vec::new();
        let (mut start, mut blocks) = (vec![0usize], Vec::<u32>::new());
        let mut tile_cluster = Vec::new();
        let mut members = Vec::<u32>::new();
        for seed in 0..n {
            if !st.iface.is_free(seed) || cluster_of[seed] != u32::MAX {
                continue;
            }
            let c = cut.len() as u32;
            members.clear();
            cluster_of[seed] = c;
            members.push(seed as u32);
            let mut k = 0;
            while k < members.len() {
                let i = members[k] as usize;
                k += 1;
                for d in 0..8 {
                    let j = lat.nbr[8 * i + d] as usize;
                    if j != i && st.iface.is_free(j) && cluster_of[j] == u32::MAX {
                        cluster_of[j] = c;
                        members.push(j as u32);
                    }
                }
            }
            members.sort_unstable();
            let xs = members.iter().map(|&i| i as usize % nx);
            let (x0, x1) = (xs.clone().min().unwrap(), xs.max().unwrap());
            let ys = members.iter().map(|&i| i as usize / nx);
            let (y0, y1) = (ys.clone().min().unwrap(), ys.max().unwrap());
            let whole = x1 - x0 < TILE && y1 - y0 < TILE;
            cut.push(!whole);
            let key = |i: u32| {
                let (x, y) = (i as usize % nx, i as usize / nx);
                ((y - y0) / TILE, (x - x0) / TILE)
            };
            let mut keys: Vec<(usize, usize)> = if whole {
                vec![(0, 0)]
            } else {
                members.iter().map(|&i| key(i)).collect()
            };
            keys.sort_unstable();
            keys.dedup();
            for kk in keys {
                let t = tile_cluster.len() as u32;
                for &i in &members {
                    if whole || key(i) == kk {
                        tile_of[i as usize] = t;
                        blocks.push(i);
                    }
                }
                start.push(blocks.len());
                tile_cluster.push(c);
            }
            cstart.push(tile_cluster.len());
        }
        let nt = tile_cluster.len();
        let (mut bstart, mut border) = (vec![0usize], Vec::new());
        let (mut astart, mut adj) = (vec![0usize], Vec::new());
        let mut seen = vec![u32::MAX; n.max(nt)];
        let mut seen_tile = vec![u32::MAX; nt];
        for t in 0..nt {
            let b0 = border.len();
            let a0 = adj.len();
            for &i in &blocks[start[t]..start[t + 1]] {
                let i = i as usize;
                for d in 0..8 {
                    let j = lat.nbr[8 * i + d] as usize;
                    if j == i {
                        continue;
                    }
                    let tj = tile_of[j];
                    if tj == u32::MAX {
                        if seen[j] != t as u32 {
                            seen[j] = t as u32;
                            border.push(j as u32);
                        }
                    } else if tj != t as u32 && seen_tile[tj as usize] != t as u32 {
                        seen_tile[tj as usize] = t as u32;
                        adj.push(tj);
                    }
                }
            }
            border[b0..].sort_unstable();
            adj[a0..].sort_unstable();
            bstart.push(border.len());
            astart.push(adj.len());
        }
        let nc = cut.len();
        let largest = (0..nc)
            .map(|c| start[cstart[c + 1]] - start[cstart[c]])
            .max()
            .unwrap_or(0);
        let speed = st.vel.0.hypot(st.vel.1);
        Parker {
            cstart,
            cut,
            start,
            blocks,
            bstart,
            border,
            astart,
            adj,
            tile_cluster,
            tile_of,
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
        self.cut.len()
    }

    /// Whether every tile of cluster `c` is parked.
    pub fn is_parked(&self, c: usize) -> bool {
        self.parked[self.cstart[c]..self.cstart[c + 1]]
            .iter()
            .all(|&p| p)
    }

    /// Cluster of block `i`, if it is free.
    pub fn cluster_of(&self, i: usize) -> Option<usize> {
        self.tile_of(i).map(|t| self.tile_cluster[t] as usize)
    }

    /// Number of tiles (a cluster no larger than [`TILE`] is one tile).
    pub fn tiles(&self) -> usize {
        self.parked.len()
    }

    /// Tile of block `i`, if it is free.
    pub fn tile_of(&self, i: usize) -> Option<usize> {
        let t = self.tile_of[i];
        (t != u32::MAX).then_some(t as usize)
    }

    /// Whether tile `t` is parked.
    pub fn tile_parked(&self, t: usize) -> bool {
        self.parked[t]
    }

    fn members(&self, t: usize) -> std::ops::Range<usize> {
        self.start[t]..self.start[t + 1]
    }

    fn borders_stuck(&self, state: &SpringBlockState, t: usize) -> bool {
        self.border[self.bstart[t]..self.bstart[t + 1]]
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
            self.set
                .extend_from_slice(&self.blocks[self.start[t]..self.start[t + 1]]);
        }
        for (k, &i) in self.set.iter().enumerate() {
            self.slot[i as usize] = k as u32;
        }
    }

    /// Brings parked blocks in and around the current set up to `state.t`.
    fn materialize_around(&self, st: &mut Stepper, state: &mut SpringBlockState) {
        let lat = st.lat;
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
        let (iface, vx, vy) = (st.iface, &state.vx, &state.vy);
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
            st.unpark(self.blocks[k] as usize);
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
            for k in self.bstart[t]..self.bstart[t + 1] {
                st.refresh(state, self.border[k] as usize);
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
            let tiles = self.cstart[c]..self.cstart[c + 1];
            if !self.cut[c] {
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
                    for a in self.astart[u]..self.astart[u + 1] {
                        let v = self.adj[a] as usize;
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
                    for a in self.astart[u]..self.astart[u + 1] {
                        let v = self.adj[a] as usize;
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
            let tiles = self.cstart[c]..self.cstart[c + 1];
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
        let lat = st.lat;
        let (nx, ny) = (lat.nx, lat.ny);
        let r = WAKE_RADIUS;
        let mut woken = Vec::new();
        for &i in started {
            let i = i as usize;
            for d in 0..8 {
                let j = lat.nbr[8 * i + d] as usize;
                if let Some(t) = self.tile_of(j) {
                    if self.parked[t] && !self.cut[self.tile_cluster[t] as usize] {
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
                        if self.parked[t] && self.cut[self.tile_cluster[t] as usize] {
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
        if st.check_thresholds(state) > 0 {
            started.extend_from_slice(st.started());
        }
        self.wake_around(st, state, &started);
        self.jumps += 1;
        Jump::Jumped(step)
    }
}
