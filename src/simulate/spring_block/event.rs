//! Event-driven jumps over stuck phases.
//!
//! While every contact block sticks, nothing moves except the free (hole)
//! blocks, which follow the slider quasi-statically once their oscillations
//! have died out. The driving force on stuck block i then grows linearly:
//!
//! F_mot^i(t + τ) = G_i + R_i τ,  R_i = K_s v + Σ_{j free} K_t^(ij) w_j,
//!
//! where K_t^(ij) is the tangent stiffness of spring ij and w solves the
//! quasi-static rate equation of the free blocks, A w = K_s v with
//! (A w)_i = K_s w_i + Σ_j K_t^(ij) (w_i − w_j) (w_j = 0 for stuck j). Block i
//! slips when |G_i + R_i τ| = μ_s^i F_n + F_ad, a quadratic in τ; the clock
//! jumps to the smallest root over blocks and that block starts to slide.
//!
//! On a flat surface (no free blocks) this is exact: the loading is linear.
//! With holes it is exact to first order in the jump; the jump is therefore
//! capped (slider travel ≤ `jump_travel` · l) and each jump ends with a
//! Newton correction that puts the free blocks back in equilibrium. The
//! error against a fine-step reference is measured in `benches/spring_block.rs`.

use super::crossing::crossing_time;
use super::rate::{RateSystem, Settling};
use super::state::SpringBlockState;
use super::stepper::Stepper;
use crate::models::spring_block::forces::tangent;

/// Crossings this fraction of a step after a jump's end count as now:
/// blocks that reach their thresholds together (equal loads and
/// thresholds) have crossing times a rounding apart, and start in the same
/// instant rather than a step later. TIE × dt is far below a step and far
/// above the rounding of a crossing time (1e-16 of the loading time).
pub(crate) const TIE: f64 = 1e-6;

/// What a jump attempt did.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Jump {
    /// The system is not quiet, or the next slip is within one step: step.
    NotQuiet,
    /// The clock advanced by this many seconds.
    Jumped(f64),
}

/// Scratch space for jumps: the free blocks and their rate system.
pub struct Jumper {
    free: Vec<u32>,
    /// Position in `free` of each block, u32::MAX if not free.
    slot: Vec<u32>,
    rate: RateSystem,
    settling: Settling,
    /// Number of jumps made.
    pub jumps: u64,
}

impl Jumper {
    /// Collects the free blocks of the stepper's interface.
    pub fn new(st: &Stepper) -> Self {
        let n = st.ctx.lat.len();
        let free: Vec<u32> = (0..n as u32)
            .filter(|&i| st.ctx.iface.is_free(i as usize))
            .collect();
        let mut slot = vec![u32::MAX; n];
        for (f, &i) in free.iter().enumerate() {
            slot[i as usize] = f as u32;
        }
        Jumper {
            rate: RateSystem::new(free.len()),
            settling: Settling::new(st),
            free,
            slot,
            jumps: 0,
        }
    }

    /// Number of free blocks.
    pub fn free_count(&self) -> usize {
        self.free.len()
    }

    /// Puts the free blocks in equilibrium.
    fn correct(&mut self, st: &Stepper, state: &mut SpringBlockState) {
        let slot = &self.slot;
        let in_set = |j: usize| (slot[j] != u32::MAX).then(|| slot[j] as usize);
        self.rate.correct(st, state, &self.free, &in_set);
    }

    /// Earliest threshold crossing over stuck blocks while the free blocks
    /// move at their rates w: R_i = K_s v + Σ_j K_t^(ij) w_j (module docs).
    fn next_slip(&self, st: &Stepper, state: &SpringBlockState) -> (f64, usize) {
        let lat = st.ctx.lat;
        let (mut tau, mut first) = (f64::INFINITY, usize::MAX);
        for i in 0..lat.len() {
            if state.sliding[i] {
                continue;
            }
            let g = st.driving_force_cached(state, i);
            let (mut rx, mut ry) = st.ctx.shear_rate();
            for d in 0..8 {
                let j = lat.nbr[8 * i + d] as usize;
                let s = self.slot[j];
                if s == u32::MAX || j == i {
                    continue;
                }
                let dx = lat.dx0[d] + state.ux[j] - state.ux[i];
                let dy = lat.dy0[d] + state.uy[j] - state.uy[i];
                let [kxx, kxy, kyy] = tangent(lat.k[8 * i + d], lat.rest[d], dx, dy);
                let (wx, wy) = (self.rate.w[2 * s as usize], self.rate.w[2 * s as usize + 1]);
                rx += kxx * wx + kxy * wy;
                ry += kxy * wx + kyy * wy;
            }
            let ti = crossing_time(g, (rx, ry), st.ctx.iface.threshold[i]);
            if ti < tau {
                tau = ti;
                first = i;
            }
        }
        (tau, first)
    }

    /// Jumps over a stuck phase if the system is quiet: no contact block
    /// slides and the free blocks are settled (`tol`). The jump ends at the
    /// next slip, at `t_limit`, or after a slider travel of `max_travel`
    /// (only when there are free blocks). A jump shorter than `dt` is not
    /// made.
    pub fn try_jump(
        &mut self,
        st: &mut Stepper,
        state: &mut SpringBlockState,
        tol: f64,
        max_travel: f64,
        dt: f64,
        t_limit: f64,
    ) -> Jump {
        if st.sliding_contacts() > 0 {
            return Jump::NotQuiet;
        }
        let has_free = !self.free.is_empty();
        if has_free {
            if !self.settling.settled(st, state, &self.free, tol) {
                return Jump::NotQuiet;
            }
            self.correct(st, state);
            st.resync(state);
            let slot = &self.slot;
            let in_set = |j: usize| (slot[j] != u32::MAX).then(|| slot[j] as usize);
            if !self.rate.solve_rate(st, state, &self.free, &in_set) {
                return Jump::NotQuiet;
            }
        }
        // Next slip time over stuck blocks: from the stepper's tree when
        // nothing else moves, else with the free blocks' rates.
        let (mut tau, mut first) = (f64::INFINITY, usize::MAX);
        if !has_free {
            if let Some((tc, i)) = st.next_crossing() {
                tau = tc - state.t;
                first = i;
            }
        } else {
            (tau, first) = self.next_slip(st, state);
        }
        let speed = st.ctx.vel.0.hypot(st.ctx.vel.1);
        let mut step = tau.min(t_limit - state.t);
        if has_free {
            step = step.min(max_travel / speed);
        }
        if step < dt {
            return Jump::NotQuiet;
        }
        let hit = step >= tau;
        state.t += step;
        for (f, &i) in self.free.iter().enumerate() {
            let i = i as usize;
            let (wx, wy) = (self.rate.w[2 * f], self.rate.w[2 * f + 1]);
            state.ux[i] += wx * step;
            state.uy[i] += wy * step;
            state.vx[i] = wx;
            state.vy[i] = wy;
        }
        if has_free {
            self.correct(st, state);
        }
        if hit && !has_free && first != usize::MAX {
            // Exact on a flat surface: this block is at its threshold now.
            state.sliding[first] = true;
        }
        st.resync(state);
        st.check_thresholds_by(state, state.t + TIE * dt);
        self.jumps += 1;
        Jump::Jumped(step)
    }
}
