//! Force terms of the spring-block model (MODELS.md §7), each computed by its
//! own function into its own array; the total is their sum.
//!
//! Positions are displacements u_i = r_i − r_i⁰ from the rest lattice, which
//! keeps full precision in spring lengths (r_j − r_i = r_ij⁰ + u_j − u_i).
//!
//! | term | force on block i |
//! |---|---|
//! | internal | Σ_j k_ij (r_ij − l_ij)(r_j − r_i)/r_ij, attractive when stretched |
//! | shear | K_s (v t − u_i) (the slider has moved by v t) |
//! | damping | −m γ u̇_i |
//! | friction, stuck | −F_mot (balances the driving force, |F_mot| ≤ μ_s F_n + F_ad) |
//! | friction, sliding | −μ_d F_n u̇/|u̇| (along −F_mot when u̇ = 0; led by F_mot when u̇ is too slow for the step, [`friction_direction`]) |

use super::lattice::Lattice;

/// Force on block i from a spring of stiffness `k` and rest length `rest`,
/// with (dx, dy) = r_j − r_i: k (r − l)(r_j − r_i)/r.
#[inline(always)]
pub fn spring_force(k: f64, rest: f64, dx: f64, dy: f64) -> (f64, f64) {
    let r = (dx * dx + dy * dy).sqrt();
    let s = k * (r - rest) / r;
    (s * dx, s * dy)
}

/// Internal force on block `i` from its neighbours, at displacements (ux, uy).
#[inline(always)]
pub fn internal_force_on(lat: &Lattice, ux: &[f64], uy: &[f64], i: usize) -> (f64, f64) {
    let (xi, yi) = (ux[i], uy[i]);
    let nb = &lat.nbr[8 * i..8 * i + 8];
    let kk = &lat.k[8 * i..8 * i + 8];
    let (mut fx, mut fy) = (0.0, 0.0);
    for d in 0..8 {
        let j = nb[d] as usize;
        let dx = lat.dx0[d] + ux[j] - xi;
        let dy = lat.dy0[d] + uy[j] - yi;
        let (gx, gy) = spring_force(kk[d], lat.rest[d], dx, dy);
        fx += gx;
        fy += gy;
    }
    (fx, fy)
}

/// Internal spring forces on all blocks into (fx, fy).
pub fn internal_forces(lat: &Lattice, ux: &[f64], uy: &[f64], fx: &mut [f64], fy: &mut [f64]) {
    for i in 0..lat.len() {
        (fx[i], fy[i]) = internal_force_on(lat, ux, uy, i);
    }
}

/// Shear-spring force K_s (s − u) on one block at displacement (ux, uy),
/// slider displacement s = v t.
#[inline(always)]
pub fn shear_force_on(k_shear: f64, slider: (f64, f64), ux: f64, uy: f64) -> (f64, f64) {
    (k_shear * (slider.0 - ux), k_shear * (slider.1 - uy))
}

/// Damping force −m γ u̇ on one block.
#[inline(always)]
pub fn damping_force_on(mass: f64, gamma: f64, vx: f64, vy: f64) -> (f64, f64) {
    (-mass * gamma * vx, -mass * gamma * vy)
}

/// Damping as an acceleration, −γ u̇ (the damping force over m, without
/// the rounding of a multiply and divide by m).
#[inline(always)]
pub fn damping_acceleration(gamma: f64, vx: f64, vy: f64) -> (f64, f64) {
    (-gamma * vx, -gamma * vy)
}

/// Shear-spring forces K_s (s − u_i) with slider displacement s = v t.
pub fn shear_forces(
    k_shear: f64,
    slider: (f64, f64),
    ux: &[f64],
    uy: &[f64],
    fx: &mut [f64],
    fy: &mut [f64],
) {
    for i in 0..ux.len() {
        (fx[i], fy[i]) = shear_force_on(k_shear, slider, ux[i], uy[i]);
    }
}

/// Damping forces −m γ u̇_i.
pub fn damping_forces(
    mass: f64,
    gamma: f64,
    vx: &[f64],
    vy: &[f64],
    fx: &mut [f64],
    fy: &mut [f64],
) {
    for i in 0..vx.len() {
        (fx[i], fy[i]) = damping_force_on(mass, gamma, vx[i], vy[i]);
    }
}

/// Direction of a sliding block's kinetic friction at velocity `w`, led
/// when the block slides too slowly for the step `dt`.
///
/// −μ_d F_n u̇/|u̇| turns a velocity across the motion back at the rate
/// μ_d F_n/(m |u̇|), which explicit RK4 follows only while dt times that
/// rate stays inside its stability interval (2.785): a block sliding
/// slower than about dt |F_mot|/m would see its friction swing off its
/// velocity. There the direction is that of w + τ s F_mot/m, with
/// τ = dt − m |w|/|F_mot| and s = max(0, F_mot·ŵ)/|F_mot|: the velocity
/// a backward-Euler step would head to (the friction's direction treated
/// implicitly). For a block driven along its motion the rate is then at
/// most μ_d F_n/(m |w| + τ s |F_mot|) ≤ 1/dt. A block fast enough (τ ≤ 0)
/// or driven against its motion (s = 0, it is stopping) keeps w, so RK4
/// is unchanged there; so is steady sliding (F_mot ∥ w), whose direction
/// stays exact. The lead is continuous in w and F_mot.
#[inline(always)]
pub fn friction_direction(w: (f64, f64), fm: (f64, f64), mass: f64, dt: f64) -> (f64, f64) {
    let w2 = w.0 * w.0 + w.1 * w.1;
    let f2 = fm.0 * fm.0 + fm.1 * fm.1;
    let along = fm.0 * w.0 + fm.1 * w.1;
    // τ ≤ 0 is m² |w|² ≥ dt² |F_mot|²: the usual path takes no square root
    // (it runs per block and RK4 stage).
    if !(w2 > 0.0 && along > 0.0 && mass * mass * w2 < dt * dt * f2) {
        return w;
    }
    let (wn, f) = (w2.sqrt(), f2.sqrt());
    let tau = dt - mass * wn / f;
    let c = tau * (along / (wn * f)) / mass;
    (w.0 + c * fm.0, w.1 + c * fm.1)
}

/// Kinetic friction on a sliding block: −f_d u̇/|u̇|, or, at zero velocity,
/// against the driving force (F_mot), never larger than it.
#[inline(always)]
pub fn kinetic_friction(f_dyn: f64, vx: f64, vy: f64, fmx: f64, fmy: f64) -> (f64, f64) {
    let v2 = vx * vx + vy * vy;
    if v2 > 0.0 {
        let s = f_dyn / v2.sqrt();
        (-s * vx, -s * vy)
    } else {
        let f = (fmx * fmx + fmy * fmy).sqrt();
        if f > 0.0 {
            let s = f_dyn.min(f) / f;
            (-s * fmx, -s * fmy)
        } else {
            (0.0, 0.0)
        }
    }
}

/// Friction forces: a stuck block's friction cancels its driving force
/// (fmx, fmy) = internal + shear; a sliding block gets kinetic friction
/// `f_dyn[i]` = μ_d^i F_n against its velocity.
#[allow(clippy::too_many_arguments)]
pub fn friction_forces(
    sliding: &[bool],
    f_dyn: &[f64],
    vx: &[f64],
    vy: &[f64],
    fmx: &[f64],
    fmy: &[f64],
    fx: &mut [f64],
    fy: &mut [f64],
) {
    for i in 0..vx.len() {
        (fx[i], fy[i]) = if sliding[i] {
            kinetic_friction(f_dyn[i], vx[i], vy[i], fmx[i], fmy[i])
        } else {
            (-fmx[i], -fmy[i])
        };
    }
}

/// Elastic energy of the internal springs, ½ Σ k (r − l)² over springs
/// (each counted once), and of the shear springs, ½ K_s Σ |v t − u_i|² \[J\].
pub fn elastic_energy(lat: &Lattice, slider: (f64, f64), ux: &[f64], uy: &[f64]) -> f64 {
    let mut e = 0.0;
    for i in 0..lat.len() {
        for d in 0..8 {
            let j = lat.nbr[8 * i + d] as usize;
            if j > i {
                let dx = lat.dx0[d] + ux[j] - ux[i];
                let dy = lat.dy0[d] + uy[j] - uy[i];
                let r = (dx * dx + dy * dy).sqrt();
                e += 0.5 * lat.k[8 * i + d] * (r - lat.rest[d]).powi(2);
            }
        }
        e += 0.5 * lat.k_shear * ((slider.0 - ux[i]).powi(2) + (slider.1 - uy[i]).powi(2));
    }
    e
}

/// Tangent stiffness of a spring of stiffness `k`, rest length `rest` and
/// current vector (dx, dy): k [(1 − l/r) I + (l/r) n nᵀ], as (xx, xy, yy).
#[inline]
pub fn tangent(k: f64, rest: f64, dx: f64, dy: f64) -> [f64; 3] {
    let r2 = dx * dx + dy * dy;
    let r = r2.sqrt();
    let a = k * (1.0 - rest / r);
    let c = k * rest / (r * r2);
    [a + c * dx * dx, c * dx * dy, a + c * dy * dy]
}

#[cfg(test)]
mod tests {
    use super::friction_direction;

    const M: f64 = 1.265e-13;
    const DT: f64 = 1e-8;

    fn unit(d: (f64, f64)) -> (f64, f64) {
        let n = d.0.hypot(d.1);
        (d.0 / n, d.1 / n)
    }

    #[test]
    fn a_fast_or_stopping_block_keeps_its_velocity_as_direction() {
        let f = (7.5e-7, 2e-7);
        // |w| ≥ dt |F|/m ≈ 0.061 m/s: τ ≤ 0.
        let fast = (0.05, 0.04);
        assert_eq!(friction_direction(fast, f, M, DT), fast);
        // Driven against its motion (F·w < 0) or across it (F·w = 0).
        let slow = (-1e-4, 3e-5);
        assert_eq!(friction_direction(slow, f, M, DT), slow);
        assert_eq!(
            friction_direction((0.0, 1e-4), (1e-6, 0.0), M, DT),
            (0.0, 1e-4)
        );
        // At rest, or without a driving force: nothing to lead by.
        assert_eq!(friction_direction((0.0, 0.0), f, M, DT), (0.0, 0.0));
        assert_eq!(friction_direction(slow, (0.0, 0.0), M, DT), slow);
    }

    #[test]
    fn steady_sliding_keeps_the_exact_direction() {
        // F_mot ∥ u̇, as in steady sliding: the lead adds along u̇ only.
        let w = (2e-4 * 0.6, 2e-4 * 0.8);
        let f = (7.5e-7 * 0.6, 7.5e-7 * 0.8);
        let d = unit(friction_direction(w, f, M, DT));
        assert!(
            (d.0 - 0.6).abs() < 1e-15 && (d.1 - 0.8).abs() < 1e-15,
            "{d:?}"
        );
    }

    #[test]
    fn a_slow_block_is_led_toward_its_drive_continuously() {
        let f = (1e-6, 0.0);
        let edge = DT * 1e-6 / M; // |w| where τ = 0
        let angle = |w: (f64, f64)| {
            let d = friction_direction(w, f, M, DT);
            d.1.atan2(d.0)
        };
        // 10° off the drive: far below the edge the direction is nearly
        // the drive's, as backward Euler gives: tan = |w| sin θ/(|w| cos θ
        // + τ cos θ |F|/m).
        let th = 10f64.to_radians();
        let w = (1e-4 * th.cos(), 1e-4 * th.sin());
        let tau = DT - M * 1e-4 / 1e-6;
        let want = (1e-4 * th.sin()).atan2(1e-4 * th.cos() + tau * th.cos() * 1e-6 / M);
        assert!((angle(w) - want).abs() < 1e-12, "{} vs {want}", angle(w));
        assert!(angle(w) < 0.01 * th);
        // Just below and above the edge the directions meet.
        let below = angle((
            edge * (1.0 - 1e-9) * th.cos(),
            edge * (1.0 - 1e-9) * th.sin(),
        ));
        let above = angle((
            edge * (1.0 + 1e-9) * th.cos(),
            edge * (1.0 + 1e-9) * th.sin(),
        ));
        assert!((below - above).abs() < 1e-8 && (above - th).abs() < 1e-12);
    }
}
