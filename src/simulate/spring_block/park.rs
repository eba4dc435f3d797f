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
//! - **Jump**: when nothing moves (every cluster parked, no contact block
//!   sliding), the clock jumps to the next crossing, or to the earliest
//!   re-park deadline (a full `jump_travel` · l of slider travel).

use super::event::Jump;
use super::rate::{RateSystem, Settling};
use super::stepper::{SpringBlockState, Stepper};

/// Steps between attempts to park awake clusters.
const CHECK_EVERY: u64 = 16;

/// Clusters of free blocks and their parking state.
pub struct Parker {
    /// Blocks of cluster c: `blocks[start[c]..start[c + 1]]`.
    start: Vec<usize>,
    blocks: Vec<u32>,
    /// Contact blocks bordering cluster c: `border[bstart[c]..bstart[c + 1]]`.
    bstart: Vec<usize>,
    border: Vec<u32>,
    /// Cluster of each block (u32::MAX for contact blocks).
    cluster_of: Vec<u32>,
    /// Index of each free block within its cluster.
    local: Vec<u32>,
    parked: Vec<bool>,
    /// Time each parked cluster was last (re-)parked [s].
    t0: Vec<f64>,
    /// Rate system scratch, sized for the largest cluster.
    rate: RateSystem,
    /// Settling scales and `quiet_tolerance`.
    settling: Settling,
    tol: f64,
    /// Slider time of a full `jump_travel` [s].
    cap: f64,
    /// Earliest t0 + cap/2 over parked clusters [s].
    next_repark: f64,
    /// Jumps made.
    pub jumps: u64,
    /// Clusters parked, re-parks included.
    pub parks: u64,
    /// Clusters woken.
    pub wakes: u64,
}

impl Parker {
    /// Finds the clusters of free blocks. `tol` is `quiet_tolerance`,
    /// `max_travel` the largest slider travel between re-parks [m].
    pub fn new(st: &Stepper, tol: f64, max_travel: f64) -> Self {
        let lat = st.lat;
        let n = lat.len();
        let mut cluster_of = vec![u32::MAX; n];
        let mut local = vec![u32::MAX; n];
        let (mut start, mut blocks) = (vec![0usize], Vec::new());
        let (mut bstart, mut border) = (vec![0usize], Vec::new());
        let mut seen_border = vec![u32::MAX; n];
        for seed in 0..n {
            if !st.iface.is_free(seed) || cluster_of[seed] != u32::MAX {
                continue;
            }
            let c = (start.len() - 1) as u32;
            let first = blocks.len();
            cluster_of[seed] = c;
            blocks.push(seed as u32);
            let mut k = first;
            while k < blocks.len() {
                let i = blocks[k] as usize;
                k += 1;
                for d in 0..8 {
                    let j = lat.nbr[8 * i + d] as usize;
                    if j == i {
                        continue;
                    }
                    if st.iface.is_free(j) {
                        if cluster_of[j] == u32::MAX {
                            cluster_of[j] = c;
                            blocks.push(j as u32);
                        }
                    } else if seen_border[j] != c {
                        seen_border[j] = c;
                        border.push(j as u32);
                    }
                }
            }
            blocks[first..].sort_unstable();
            for (m, &i) in blocks[first..].iter().enumerate() {
                local[i as usize] = m as u32;
            }
            border[bstart[bstart.len() - 1]..].sort_unstable();
            start.push(blocks.len());
            bstart.push(border.len());
        }
        let nc = start.len() - 1;
        let largest = (0..nc).map(|c| start[c + 1] - start[c]).max().unwrap_or(0);
        let speed = st.vel.0.hypot(st.vel.1);
        Parker {
            start,
            blocks,
            bstart,
            border,
            cluster_of,
            local,
            parked: vec![false; nc],
            t0: vec![0.0; nc],
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
        self.parked.len()
    }

    /// Whether cluster `c` is parked.
    pub fn is_parked(&self, c: usize) -> bool {
        self.parked[c]
    }

    /// Cluster of block `i`, if it is free.
    pub fn cluster_of(&self, i: usize) -> Option<usize> {
        let c = self.cluster_of[i];
        (c != u32::MAX).then_some(c as usize)
    }

    fn members(&self, c: usize) -> std::ops::Range<usize> {
        self.start[c]..self.start[c + 1]
    }

    fn settled(&self, st: &Stepper, state: &SpringBlockState, c: usize) -> bool {
        let blocks = &self.blocks[self.members(c)];
        self.settling.settled(st, state, blocks, self.tol)
    }

    fn borders_stuck(&self, state: &SpringBlockState, c: usize) -> bool {
        self.border[self.bstart[c]..self.bstart[c + 1]]
            .iter()
            .all(|&j| !state.sliding[j as usize])
    }

    /// Sets the velocities of cluster c to its quasi-static rate w.
    fn set_rate(&mut self, st: &Stepper, state: &mut SpringBlockState, c: usize) -> bool {
        let blocks = &self.blocks[self.start[c]..self.start[c + 1]];
        let (cluster_of, local) = (&self.cluster_of, &self.local);
        let in_set = |j: usize| (cluster_of[j] == c as u32).then(|| local[j] as usize);
        if !self.rate.solve_rate(st, state, blocks, &in_set) {
            return false;
        }
        for (k, &i) in blocks.iter().enumerate() {
            state.vx[i as usize] = self.rate.w[2 * k];
            state.vy[i as usize] = self.rate.w[2 * k + 1];
        }
        true
    }

    /// Puts cluster c in equilibrium at its current velocities.
    fn correct(&mut self, st: &Stepper, state: &mut SpringBlockState, c: usize) {
        let blocks = &self.blocks[self.start[c]..self.start[c + 1]];
        let (cluster_of, local) = (&self.cluster_of, &self.local);
        let in_set = |j: usize| (cluster_of[j] == c as u32).then(|| local[j] as usize);
        self.rate.correct(st, state, blocks, &in_set);
    }

    /// Parks (or re-parks) cluster c; its borders must stick. False if the
    /// rate system did not converge (the cluster then stays as it was).
    fn park(&mut self, st: &mut Stepper, state: &mut SpringBlockState, c: usize) -> bool {
        if !self.set_rate(st, state, c) {
            return false;
        }
        self.correct(st, state, c);
        // Should this second solve fail, the first rate stays: the
        // positions have moved, so the cluster must be parked from here.
        self.set_rate(st, state, c);
        for k in self.members(c) {
            let i = self.blocks[k] as usize;
            st.park(state, i, (state.vx[i], state.vy[i]));
        }
        self.parked[c] = true;
        self.t0[c] = state.t;
        self.parks += 1;
        true
    }

    fn wake(&mut self, st: &mut Stepper, state: &mut SpringBlockState, c: usize) {
        self.correct(st, state, c);
        for k in self.members(c) {
            st.unpark(self.blocks[k] as usize);
        }
        self.parked[c] = false;
        self.wakes += 1;
    }

    /// Refreshes the cached forces of the borders of clusters `cs` and the
    /// parked bookkeeping after positions or parking changed.
    fn finish(&mut self, st: &mut Stepper, state: &mut SpringBlockState, cs: &[usize]) {
        st.parked_changed(state);
        st.materialize_all(state);
        for &c in cs {
            for k in self.bstart[c]..self.bstart[c + 1] {
                st.refresh(state, self.border[k] as usize);
            }
        }
        self.next_repark = (0..self.clusters())
            .filter(|&c| self.parked[c])
            .map(|c| self.t0[c] + 0.5 * self.cap)
            .fold(f64::INFINITY, f64::min);
    }

    /// Parks every awake cluster that is settled with all borders stuck.
    pub fn park_settled(&mut self, st: &mut Stepper, state: &mut SpringBlockState) {
        let mut done = Vec::new();
        for c in 0..self.clusters() {
            if !self.parked[c]
                && self.borders_stuck(state, c)
                && self.settled(st, state, c)
                && self.park(st, state, c)
            {
                done.push(c);
            }
        }
        if !done.is_empty() {
            self.finish(st, state, &done);
        }
    }

    /// Re-parks the clusters parked for half the travel cap or longer.
    fn repark_aged(&mut self, st: &mut Stepper, state: &mut SpringBlockState) {
        if state.t < self.next_repark {
            return;
        }
        st.materialize_all(state);
        let mut done = Vec::new();
        for c in 0..self.clusters() {
            if self.parked[c] && state.t >= self.t0[c] + 0.5 * self.cap {
                // Rebuild its velocity from scratch: unpark, correct, park.
                if self.park(st, state, c) {
                    done.push(c);
                }
            }
        }
        // A failed re-park leaves the cluster parked with its old rate; the
        // deadline then moves on by half a cap.
        for c in 0..self.clusters() {
            if self.parked[c] && state.t >= self.t0[c] + 0.5 * self.cap {
                self.t0[c] = state.t;
            }
        }
        self.finish(st, state, &done);
    }

    /// Wakes the parked clusters next to the blocks that just started to
    /// slide.
    fn wake_around(&mut self, st: &mut Stepper, state: &mut SpringBlockState, started: &[u32]) {
        let lat = st.lat;
        let mut woken = Vec::new();
        for &i in started {
            let i = i as usize;
            for d in 0..8 {
                let j = lat.nbr[8 * i + d] as usize;
                if let Some(c) = self.cluster_of(j) {
                    if self.parked[c] {
                        if woken.is_empty() {
                            st.materialize_all(state);
                        }
                        self.wake(st, state, c);
                        woken.push(c);
                    }
                }
            }
        }
        if !woken.is_empty() {
            self.finish(st, state, &woken);
        }
    }

    /// Bookkeeping after an RK4 step that started `started` slips: wakes
    /// clusters next to new slips, re-parks aged clusters and, every
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
