//! One instant of the spring lattice (MODELS.md §5, Eq. 1.29–1.35, with
//! adhesion Eq. 2.1, 2.2): given each spring's compression at zero
//! separation and the reaction ratios of its two halves, solve the
//! separation for the load and sum the forces.
//!
//! At every lattice point x_i sit two springs of equal length, one attached
//! to each body (so half the springs belong to each body): the one attached
//! to the upper body slides on z1 with ratios (H_x, H_y)₁, the other slides on
//! z2 with (H_x, H_y)₂. With F_i the axial force (compressive > 0):
//!
//! ```text
//! R_z = mean_i F_i                                (= L, the load per spring)
//! R_x = mean_i F_i⁺ (H_x,1 + H_x,2) / 2           (Eq. 1.34, compressed only)
//! R_y = mean_i F_i⁺ (H_y,1 + H_y,2) / 2           (Eq. 1.35)
//! ```
//!
//! Tensile springs (adhesion, k_t > 0) carry load but no friction (Eq. 2.2).

use super::local_law::D_MIN;
use super::separation::{solve_separation, Separation};
use crate::error::{Error, Result};
use crate::status::Code;

/// Spring parameters.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct SpringParams {
    /// k_c, N/m, stiffness in compression; default 1, > 0.
    pub k_c: f64,
    /// l0, m, rest length; default 1 (only differences matter), finite.
    pub l0: f64,
    /// k_t, N/m, stiffness in tension; 0 = no adhesion (default), with
    /// adhesion k_c / 2 by default (MODELS.md §5), ≥ 0.
    pub k_t: f64,
}

impl Default for SpringParams {
    fn default() -> Self {
        SpringParams {
            k_c: 1.0,
            l0: 1.0,
            k_t: 0.0,
        }
    }
}

impl SpringParams {
    /// Checks the ranges.
    pub fn validate(&self) -> Result<()> {
        if !(self.k_c.is_finite() && self.k_c > 0.0) {
            return Err(Error::Config(format!(
                "k_c must be finite and > 0, got {}",
                self.k_c
            )));
        }
        if !(self.k_t.is_finite() && self.k_t >= 0.0) {
            return Err(Error::Config(format!(
                "k_t must be finite and >= 0, got {}",
                self.k_t
            )));
        }
        if !self.l0.is_finite() {
            return Err(Error::Config(format!("l0 must be finite, got {}", self.l0)));
        }
        Ok(())
    }
}

/// The reaction of the lattice at one instant.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Instant {
    /// L, the apparent load per spring: mean of all axial forces, N.
    pub r_z: f64,
    /// R_z^(c): mean of the compressive forces only, N (= L without tension).
    pub r_zc: f64,
    /// R_x, N per spring, from compressed springs.
    pub r_x: f64,
    /// R_y, N per spring, from compressed springs.
    pub r_y: f64,
    /// Separation d, m.
    pub d: f64,
    /// Springs (lattice points) in compression.
    pub n_compressed: usize,
    /// Springs in tension (adhesion only).
    pub n_tension: usize,
    /// Whether the separation came from the exact sorted solution.
    pub exact: bool,
}

impl Instant {
    /// (μ, μ_∥, μ_⊥) = (|R_xy|, R·ê_β, R·ê_⊥) / L (Eq. 1.13, 2.2); `None` when
    /// L ≤ 0 (adhesion at zero or tensile load: report R_xy instead).
    pub fn mu(&self, cos_b: f64, sin_b: f64) -> Option<(f64, f64, f64)> {
        if self.r_z <= 0.0 {
            return None;
        }
        Some((
            self.r_x.hypot(self.r_y) / self.r_z,
            (self.r_x * cos_b + self.r_y * sin_b) / self.r_z,
            (self.r_y * cos_b - self.r_x * sin_b) / self.r_z,
        ))
    }

    /// |R_xy|, N per spring.
    pub fn r_xy(&self) -> f64 {
        self.r_x.hypot(self.r_y)
    }
}

/// Reaction ratios of the two halves of every lattice point:
/// (H_x,1, H_y,1, H_x,2, H_y,2). Entries with D ≤ 0 hold NaN and are
/// reported through [`Locked`].
pub type Ratios = [f64; 4];

/// Where the lattice first locks (D ≤ 0): the surface (1 = lower, 2 =
/// upper), the lattice point and the slope.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Locked {
    /// 1 or 2.
    pub surface: u8,
    /// Lattice point x, m.
    pub x: f64,
    /// Lattice point y, m.
    pub y: f64,
    /// tan φ there (magnitude of the gradient).
    pub tan_phi: f64,
}

impl Locked {
    /// The error for this lock.
    pub fn to_error(self, mu0: f64, beta_deg: f64) -> Error {
        Error::coded(Code::Locked, format!(
            "surfaces lock: on surface z{} at x = {:.6e} m, y = {:.6e} m the slope phi = {:.6} deg \
             gives D <= 0 (mu0 = {mu0} >= cot(phi) along beta = {beta_deg} deg; MODELS.md §5, Fig. 1.2)",
            self.surface,
            self.x,
            self.y,
            self.tan_phi.atan().to_degrees()
        ))
    }
}

/// True when a reaction denominator is acceptable.
#[inline]
pub fn d_ok(d: f64) -> bool {
    d > D_MIN && d.is_finite()
}

/// Applicability of one spring (MODELS.md §5: "D > 0 everywhere, that is
/// μ0 < cot φ"): D > 0 along the sliding direction and μ0 tan|φ| < 1, which
/// is D > 0 for sliding straight across the slope, the worst direction. The
/// second condition matters only for oblique sliding (at β = 90° on 1-D
/// wedges D stays positive for any μ0); it is kept so that every path, and
/// every hierarchical level, locks at the same μ0 = cot φ.
#[inline]
pub fn slope_ok(mu0: f64, tan_phi: f64, d: f64) -> bool {
    d_ok(d) && mu0 * tan_phi.abs() < 1.0 - D_MIN
}

/// Resolves one instant: separation for the load, then the sums. `c` holds
/// the compressions at zero separation, `h` the ratios; both of length n.
/// Returns `None` when no separation carries the load (L ≤ 0 without
/// adhesion). `forces`, when given, receives each spring's axial force.
pub fn resolve_instant(
    c: &[f64],
    h: &[Ratios],
    springs: &SpringParams,
    load: f64,
    scratch: &mut Vec<f64>,
    mut forces: Option<&mut Vec<f64>>,
) -> Option<Instant> {
    let Separation { d, exact } = solve_separation(c, springs.k_c, springs.k_t, load, scratch)?;
    let n = c.len() as f64;
    let (mut fz, mut fzc, mut rx, mut ry) = (0.0, 0.0, 0.0, 0.0);
    let (mut nc, mut nt) = (0usize, 0usize);
    if let Some(f) = forces.as_deref_mut() {
        f.clear();
    }
    for (ci, hi) in c.iter().zip(h) {
        let u = ci - d;
        let f = if u > 0.0 {
            nc += 1;
            let f = springs.k_c * u;
            fzc += f;
            rx += f * (hi[0] + hi[2]);
            ry += f * (hi[1] + hi[3]);
            f
        } else if u < 0.0 && springs.k_t > 0.0 {
            nt += 1;
            springs.k_t * u
        } else {
            0.0
        };
        fz += f;
        if let Some(fs) = forces.as_deref_mut() {
            fs.push(f);
        }
    }
    Some(Instant {
        r_z: fz / n,
        r_zc: fzc / n,
        r_x: 0.5 * rx / n,
        r_y: 0.5 * ry / n,
        d,
        n_compressed: nc,
        n_tension: nt,
        exact,
    })
}
