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

use super::event::{tangent, Jump};
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
    /// Scratch (largest cluster): tangent stiffnesses and CG vectors.
    kt: Vec<[f64; 3]>,
    w: Vec<f64>,
    r: Vec<f64>,
    p: Vec<f64>,
    ap: Vec<f64>,
    b: Vec<f64>,
    /// Settling tolerance, reference force [N] and speed [m/s].
    tol: f64,
    fref: f64,
    vref: f64,
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
        let fref = st.iface.mean_threshold().max(st.iface.normal_force);
        let kint = lat.k.iter().cloned().fold(0.0, f64::max);
        let vref = fref / ((lat.k_shear + 6.0 * kint) * lat.mass).sqrt();
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
            kt: vec![[0.0; 3]; 8 * largest],
            w: vec![0.0; 2 * largest],
            r: vec![0.0; 2 * largest],
            p: vec![0.0; 2 * largest],
            ap: vec![0.0; 2 * largest],
            b: vec![0.0; 2 * largest],
            tol,
            fref,
            vref,
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

    /// Net force (internal + shear + damping) on free block i [N]; zero for a
    /// block dragged quasi-statically at its velocity.
    fn net_force(st: &Stepper, state: &SpringBlockState, i: usize) -> (f64, f64) {
        let (fx, fy) =
            crate::models::spring_block::forces::internal_force_on(st.lat, &state.ux, &state.uy, i);
        let mg = st.lat.mass * st.gamma;
        (
            fx + st.lat.k_shear * (st.vel.0 * state.t - state.ux[i]) - mg * state.vx[i],
            fy + st.lat.k_shear * (st.vel.1 * state.t - state.uy[i]) - mg * state.vy[i],
        )
    }

    fn settled(&self, st: &Stepper, state: &SpringBlockState, c: usize) -> bool {
        let vmax = 2.0 * st.vel.0.hypot(st.vel.1) + self.tol * self.vref;
        self.blocks[self.members(c)].iter().all(|&i| {
            let i = i as usize;
            let (fx, fy) = Self::net_force(st, state, i);
            fx.hypot(fy) <= self.tol * self.fref && state.vx[i].hypot(state.vy[i]) <= vmax
        })
    }

    fn borders_stuck(&self, state: &SpringBlockState, c: usize) -> bool {
        self.border[self.bstart[c]..self.bstart[c + 1]]
            .iter()
            .all(|&j| !state.sliding[j as usize])
    }

    fn assemble(&mut self, st: &Stepper, state: &SpringBlockState, c: usize) {
        let lat = st.lat;
        for (m, &i) in self.blocks[self.members(c)].iter().enumerate() {
            let i = i as usize;
            for d in 0..8 {
                let j = lat.nbr[8 * i + d] as usize;
                let dx = lat.dx0[d] + state.ux[j] - state.ux[i];
                let dy = lat.dy0[d] + state.uy[j] - state.uy[i];
                self.kt[8 * m + d] = tangent(lat.k[8 * i + d], lat.rest[d], dx, dy);
            }
        }
    }

    /// y = A x over cluster c (neighbours outside it held fixed).
    fn apply(&self, st: &Stepper, c: usize, x: &[f64], y: &mut [f64]) {
        let lat = st.lat;
        for (m, &i) in self.blocks[self.members(c)].iter().enumerate() {
            let i = i as usize;
            let (xi, yi) = (x[2 * m], x[2 * m + 1]);
            let (mut ax, mut ay) = (lat.k_shear * xi, lat.k_shear * yi);
            for d in 0..8 {
                let j = lat.nbr[8 * i + d] as usize;
                let (xj, yj) = if j == i || self.cluster_of[j] != c as u32 {
                    (0.0, 0.0)
                } else {
                    let s = self.local[j] as usize;
                    (x[2 * s], x[2 * s + 1])
                };
                let [kxx, kxy, kyy] = self.kt[8 * m + d];
                let (ex, ey) = (xi - xj, yi - yj);
                ax += kxx * ex + kxy * ey;
                ay += kxy * ex + kyy * ey;
            }
            y[2 * m] = ax;
            y[2 * m + 1] = ay;
        }
    }

    /// Solves A w = b over cluster c by conjugate gradients (b and w in the
    /// first 2 n_c entries of `self.b`, `self.w`). False if not converged.
    fn solve(&mut self, st: &Stepper, c: usize) -> bool {
        let n = 2 * self.members(c).len();
        let bnorm = self.b[..n].iter().map(|x| x * x).sum::<f64>().sqrt();
        self.w[..n].iter_mut().for_each(|x| *x = 0.0);
        if bnorm == 0.0 {
            return true;
        }
        self.r[..n].copy_from_slice(&self.b[..n]);
        self.p[..n].copy_from_slice(&self.b[..n]);
        let mut rr: f64 = self.r[..n].iter().map(|x| x * x).sum();
        for _ in 0..(n + 100).min(5000) {
            let (p, mut ap) = (std::mem::take(&mut self.p), std::mem::take(&mut self.ap));
            self.apply(st, c, &p, &mut ap);
            let pap: f64 = p[..n].iter().zip(&ap[..n]).map(|(a, b)| a * b).sum();
            self.p = p;
            self.ap = ap;
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

    /// Sets the velocities of cluster c to its quasi-static rate w.
    fn set_rate(&mut self, st: &Stepper, state: &mut SpringBlockState, c: usize) -> bool {
        self.assemble(st, state, c);
        let m = self.members(c).len();
        for k in 0..m {
            self.b[2 * k] = st.lat.k_shear * st.vel.0;
            self.b[2 * k + 1] = st.lat.k_shear * st.vel.1;
        }
        if !self.solve(st, c) {
            return false;
        }
        for (k, &i) in self.blocks[self.members(c)].iter().enumerate() {
            state.vx[i as usize] = self.w[2 * k];
            state.vy[i as usize] = self.w[2 * k + 1];
        }
        true
    }

    /// Puts cluster c in equilibrium at its current velocities (two Newton
    /// steps at most).
    fn correct(&mut self, st: &Stepper, state: &mut SpringBlockState, c: usize) {
        for _ in 0..2 {
            self.assemble(st, state, c);
            let mut worst: f64 = 0.0;
            for (k, &i) in self.blocks[self.members(c)].iter().enumerate() {
                let (fx, fy) = Self::net_force(st, state, i as usize);
                self.b[2 * k] = fx;
                self.b[2 * k + 1] = fy;
                worst = worst.max(fx.hypot(fy));
            }
            if worst <= 1e-12 * st.iface.normal_force || !self.solve(st, c) {
                return;
            }
            for (k, &i) in self.blocks[self.members(c)].iter().enumerate() {
                state.ux[i as usize] += self.w[2 * k];
                state.uy[i as usize] += self.w[2 * k + 1];
            }
        }
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
