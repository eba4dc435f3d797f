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

use super::stepper::{SpringBlockState, Stepper};

/// What a jump attempt did.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Jump {
    /// The system is not quiet, or the next slip is within one step: step.
    NotQuiet,
    /// The clock advanced by this many seconds.
    Jumped(f64),
}

/// Scratch space for jumps: the free blocks and the conjugate-gradient
/// vectors.
pub struct Jumper {
    free: Vec<u32>,
    /// Position in `free` of each block, u32::MAX if not free.
    slot: Vec<u32>,
    /// Tangent stiffness per free block and direction: (kxx, kxy, kyy).
    kt: Vec<[f64; 3]>,
    w: Vec<f64>,
    r: Vec<f64>,
    p: Vec<f64>,
    ap: Vec<f64>,
    b: Vec<f64>,
    /// Reference force (mean static threshold) [N].
    fref: f64,
    /// Settling speed scale F_ref/√(K m) [m/s].
    vref: f64,
    /// Number of jumps made.
    pub jumps: u64,
}

/// Tangent stiffness of a spring of stiffness `k`, rest length `rest` and
/// current vector (dx, dy): k [(1 − l/r) I + (l/r) n nᵀ], as (xx, xy, yy).
#[inline]
pub(crate) fn tangent(k: f64, rest: f64, dx: f64, dy: f64) -> [f64; 3] {
    let r2 = dx * dx + dy * dy;
    let r = r2.sqrt();
    let a = k * (1.0 - rest / r);
    let c = k * rest / (r * r2);
    [a + c * dx * dx, c * dx * dy, a + c * dy * dy]
}

/// Smallest τ ≥ 0 with |g + r τ| = th, for |g| ≤ th; ∞ if never.
#[inline]
pub fn crossing_time(g: (f64, f64), r: (f64, f64), th: f64) -> f64 {
    let a = r.0 * r.0 + r.1 * r.1;
    let b = 2.0 * (g.0 * r.0 + g.1 * r.1);
    let c = g.0 * g.0 + g.1 * g.1 - th * th;
    if c >= 0.0 {
        return 0.0;
    }
    if a <= 0.0 {
        return f64::INFINITY;
    }
    let disc = (b * b - 4.0 * a * c).sqrt();
    if b >= 0.0 {
        -2.0 * c / (b + disc)
    } else {
        (-b + disc) / (2.0 * a)
    }
}

impl Jumper {
    /// Collects the free blocks of the stepper's interface.
    pub fn new(st: &Stepper) -> Self {
        let n = st.lat.len();
        let free: Vec<u32> = (0..n as u32)
            .filter(|&i| st.iface.is_free(i as usize))
            .collect();
        let mut slot = vec![u32::MAX; n];
        for (f, &i) in free.iter().enumerate() {
            slot[i as usize] = f as u32;
        }
        let nf = free.len();
        let lat = st.lat;
        let fref = st.iface.mean_threshold().max(st.iface.normal_force);
        let kint = lat.k.iter().cloned().fold(0.0, f64::max);
        let vref = fref / ((lat.k_shear + 6.0 * kint) * lat.mass).sqrt();
        Jumper {
            kt: vec![[0.0; 3]; 8 * nf],
            w: vec![0.0; 2 * nf],
            r: vec![0.0; 2 * nf],
            p: vec![0.0; 2 * nf],
            ap: vec![0.0; 2 * nf],
            b: vec![0.0; 2 * nf],
            free,
            slot,
            fref,
            vref,
            jumps: 0,
        }
    }

    /// Number of free blocks.
    pub fn free_count(&self) -> usize {
        self.free.len()
    }

    /// Net force (internal + shear + damping) on free block i [N]. A free
    /// block dragged quasi-statically at velocity w feels a spring force
    /// m γ w that balances its damping: the net force is what must vanish.
    fn net_force(st: &Stepper, state: &SpringBlockState, i: usize) -> (f64, f64) {
        let (fx, fy) =
            crate::models::spring_block::forces::internal_force_on(st.lat, &state.ux, &state.uy, i);
        let mg = st.lat.mass * st.gamma;
        (
            fx + st.lat.k_shear * (st.vel.0 * state.t - state.ux[i]) - mg * state.vx[i],
            fy + st.lat.k_shear * (st.vel.1 * state.t - state.uy[i]) - mg * state.vy[i],
        )
    }

    /// Whether every free block is near equilibrium: net force below
    /// `tol · F_ref` and speed below 2|v| + tol F_ref/√(K m).
    fn settled(&self, st: &Stepper, state: &SpringBlockState, tol: f64) -> bool {
        let fref = self.fref;
        let vmax = 2.0 * st.vel.0.hypot(st.vel.1) + tol * self.vref;
        self.free.iter().all(|&i| {
            let i = i as usize;
            let (fx, fy) = Self::net_force(st, state, i);
            fx.hypot(fy) <= tol * fref && state.vx[i].hypot(state.vy[i]) <= vmax
        })
    }

    fn assemble(&mut self, st: &Stepper, state: &SpringBlockState) {
        let lat = st.lat;
        for (f, &i) in self.free.iter().enumerate() {
            let i = i as usize;
            for d in 0..8 {
                let j = lat.nbr[8 * i + d] as usize;
                let dx = lat.dx0[d] + state.ux[j] - state.ux[i];
                let dy = lat.dy0[d] + state.uy[j] - state.uy[i];
                self.kt[8 * f + d] = tangent(lat.k[8 * i + d], lat.rest[d], dx, dy);
            }
        }
    }

    /// y = A x over the free blocks.
    fn apply(&self, st: &Stepper, x: &[f64], y: &mut [f64]) {
        let lat = st.lat;
        for (f, &i) in self.free.iter().enumerate() {
            let i = i as usize;
            let (xi, yi) = (x[2 * f], x[2 * f + 1]);
            let (mut ax, mut ay) = (lat.k_shear * xi, lat.k_shear * yi);
            for d in 0..8 {
                let j = lat.nbr[8 * i + d] as usize;
                let s = self.slot[j];
                let (xj, yj) = if s == u32::MAX || j == i {
                    (0.0, 0.0)
                } else {
                    (x[2 * s as usize], x[2 * s as usize + 1])
                };
                let [kxx, kxy, kyy] = self.kt[8 * f + d];
                let (ex, ey) = (xi - xj, yi - yj);
                ax += kxx * ex + kxy * ey;
                ay += kxy * ex + kyy * ey;
            }
            y[2 * f] = ax;
            y[2 * f + 1] = ay;
        }
    }

    /// Solves A w = b by conjugate gradients (b in `self.b`, result in
    /// `self.w`). Returns false if it did not converge.
    fn solve(&mut self, st: &Stepper) -> bool {
        let n = self.b.len();
        let bnorm = self.b.iter().map(|x| x * x).sum::<f64>().sqrt();
        self.w.iter_mut().for_each(|x| *x = 0.0);
        if bnorm == 0.0 {
            return true;
        }
        self.r.copy_from_slice(&self.b);
        self.p.copy_from_slice(&self.b);
        let mut rr: f64 = self.r.iter().map(|x| x * x).sum();
        for _ in 0..(n + 100).min(5000) {
            let (p, mut ap) = (std::mem::take(&mut self.p), std::mem::take(&mut self.ap));
            self.apply(st, &p, &mut ap);
            let pap: f64 = p.iter().zip(&ap).map(|(a, b)| a * b).sum();
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
            let rr_new: f64 = self.r.iter().map(|x| x * x).sum();
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

    /// Puts the free blocks in equilibrium by one or two Newton steps.
    fn correct(&mut self, st: &Stepper, state: &mut SpringBlockState) {
        for _ in 0..2 {
            self.assemble(st, state);
            let mut worst: f64 = 0.0;
            for (f, &i) in self.free.iter().enumerate() {
                let (fx, fy) = Self::net_force(st, state, i as usize);
                self.b[2 * f] = fx;
                self.b[2 * f + 1] = fy;
                worst = worst.max(fx.hypot(fy));
            }
            if worst <= 1e-12 * st.iface.normal_force || !self.solve(st) {
                return;
            }
            for (f, &i) in self.free.iter().enumerate() {
                state.ux[i as usize] += self.w[2 * f];
                state.uy[i as usize] += self.w[2 * f + 1];
            }
        }
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
            if !self.settled(st, state, tol) {
                return Jump::NotQuiet;
            }
            self.correct(st, state);
            st.resync(state);
            self.assemble(st, state);
            for f in 0..self.free.len() {
                self.b[2 * f] = st.lat.k_shear * st.vel.0;
                self.b[2 * f + 1] = st.lat.k_shear * st.vel.1;
            }
            if !self.solve(st) {
                return Jump::NotQuiet;
            }
        }
        // Next slip time over stuck blocks: from the stepper's tree when
        // nothing else moves, else with the free blocks' rates.
        let lat = st.lat;
        let (mut tau, mut first) = (f64::INFINITY, usize::MAX);
        if !has_free {
            if let Some((tc, i)) = st.next_crossing() {
                tau = tc - state.t;
                first = i;
            }
        } else {
            for i in 0..lat.len() {
                if state.sliding[i] {
                    continue;
                }
                let g = st.driving_force_cached(state, i);
                let (mut rx, mut ry) = (lat.k_shear * st.vel.0, lat.k_shear * st.vel.1);
                for d in 0..8 {
                    let j = lat.nbr[8 * i + d] as usize;
                    let s = self.slot[j];
                    if s == u32::MAX || j == i {
                        continue;
                    }
                    let dx = lat.dx0[d] + state.ux[j] - state.ux[i];
                    let dy = lat.dy0[d] + state.uy[j] - state.uy[i];
                    let [kxx, kxy, kyy] = tangent(lat.k[8 * i + d], lat.rest[d], dx, dy);
                    let (wx, wy) = (self.w[2 * s as usize], self.w[2 * s as usize + 1]);
                    rx += kxx * wx + kxy * wy;
                    ry += kxy * wx + kyy * wy;
                }
                let ti = crossing_time(g, (rx, ry), st.iface.threshold[i]);
                if ti < tau {
                    tau = ti;
                    first = i;
                }
            }
        }
        let speed = st.vel.0.hypot(st.vel.1);
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
            let (wx, wy) = (self.w[2 * f], self.w[2 * f + 1]);
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
        st.check_thresholds(state);
        self.jumps += 1;
        Jump::Jumped(step)
    }
}
