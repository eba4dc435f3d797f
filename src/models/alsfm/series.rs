//! The time series μ(t) of a sliding lattice and its average over whole
//! periods (MODELS.md §5: "the time series μ(t) comes from sliding z2 over
//! z1 at velocity v; its mean is the reported coefficient").
//!
//! The average of μ(t) = |R_xy(t)| / R_z is taken instant by instant, so it
//! exceeds |mean R_xy| / R_z when R_xy turns during a period; μ_∥ and μ_⊥ are
//! averaged the same way (they are linear in the forces).

use super::instant::Instant;
use crate::error::{Error, Result};
use crate::status::Code;

/// μ(t) over one period of relative motion.
#[derive(Debug, Clone, PartialEq)]
pub struct Series {
    /// Sliding distance of each instant (shift of z2 along the sliding
    /// direction), m, from 0 over one period.
    pub distance: Vec<f64>,
    /// The lattice reaction at each instant.
    pub instants: Vec<Instant>,
    /// Period of the relative motion along the sliding direction, m (`None`:
    /// the configuration does not change, one instant suffices).
    pub period: Option<f64>,
    /// Lattice points used.
    pub springs: usize,
    /// cos β, sin β.
    pub cos_sin: (f64, f64),
    /// True when the average covers an exact period; false when the motion
    /// is not periodic on the window and a long distance was averaged.
    pub whole_periods: bool,
    /// Spring forces at the instants that were asked for.
    pub maps: Vec<ContactMap>,
}

/// Axial spring forces over the lattice at one instant (compressed > 0,
/// tensile < 0), for the contact maps of Figs. 2.5–2.7.
#[derive(Debug, Clone, PartialEq)]
pub struct ContactMap {
    /// Index of the instant in the series.
    pub step: usize,
    /// Lattice point x, m.
    pub x: Vec<f64>,
    /// Lattice point y, m (0 in 1-D).
    pub y: Vec<f64>,
    /// Axial force, N.
    pub force: Vec<f64>,
}

/// Time-averaged coefficients of one series.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Averages {
    /// mean μ(t) = mean |R_xy| / L.
    pub mu: f64,
    /// mean μ_∥(t).
    pub mu_parallel: f64,
    /// mean μ_⊥(t).
    pub mu_perp: f64,
    /// mean |R_xy|, N per spring.
    pub r_xy: f64,
    /// Smallest and largest μ(t).
    pub mu_min: f64,
    /// Largest μ(t).
    pub mu_max: f64,
    /// Largest fraction of springs in tension at any instant.
    pub tension_fraction: f64,
    /// Whether all separations came from the exact solution.
    pub exact_separation: bool,
}

impl Series {
    /// Averages over the stored instants (one whole period).
    pub fn averages(&self) -> Result<Averages> {
        let (c, s) = self.cos_sin;
        let n = self.instants.len() as f64;
        let mut a = Averages {
            mu: 0.0,
            mu_parallel: 0.0,
            mu_perp: 0.0,
            r_xy: 0.0,
            mu_min: f64::INFINITY,
            mu_max: f64::NEG_INFINITY,
            tension_fraction: 0.0,
            exact_separation: true,
        };
        for (k, i) in self.instants.iter().enumerate() {
            let (m, p, q) = i.mu(c, s).ok_or_else(|| {
                Error::coded(
                    Code::NoCoefficient,
                    format!(
                    "no friction coefficient at instant {k}: the load per spring L = {} is not > 0 \
                     (see R_xy in the adhesion table)",
                    i.r_z
                ),
                )
            })?;
            if !(m.is_finite() && p.is_finite() && q.is_finite()) {
                return Err(Error::Numerical(format!(
                    "non-finite coefficient at instant {k} (distance {} m)",
                    self.distance[k]
                )));
            }
            a.mu += m / n;
            a.mu_parallel += p / n;
            a.mu_perp += q / n;
            a.mu_min = a.mu_min.min(m);
            a.mu_max = a.mu_max.max(m);
            a.r_xy += i.r_xy() / n;
            a.tension_fraction = a
                .tension_fraction
                .max(i.n_tension as f64 / self.springs as f64);
            a.exact_separation &= i.exact;
        }
        Ok(a)
    }

    /// Mean |R_xy| over the period (defined for any load), N per spring.
    pub fn mean_r_xy(&self) -> f64 {
        self.instants.iter().map(Instant::r_xy).sum::<f64>() / self.instants.len() as f64
    }
}

/// cos β and sin β for β in degrees, exact at multiples of 90°.
pub fn cos_sin_deg(beta_deg: f64) -> (f64, f64) {
    let r = beta_deg.rem_euclid(360.0);
    // Exact values at the axes: the 1-D model then sees no shift at 90°.
    #[allow(clippy::float_cmp)]
    {
        if r == 0.0 {
            return (1.0, 0.0);
        }
        if r == 90.0 {
            return (0.0, 1.0);
        }
        if r == 180.0 {
            return (-1.0, 0.0);
        }
        if r == 270.0 {
            return (0.0, -1.0);
        }
    }
    let b = beta_deg.to_radians();
    (b.cos(), b.sin())
}

/// A window holding whole periods of both surfaces along one axis: the
/// smallest common multiple p·P1 = q·P2 with p, q ≤ 64 (relative 1e-9).
/// `None` when both surfaces are invariant along the axis.
pub fn common_period(p1: Option<f64>, p2: Option<f64>, axis: &str) -> Result<Option<f64>> {
    match (p1, p2) {
        (None, None) => Ok(None),
        (Some(p), None) | (None, Some(p)) => Ok(Some(p)),
        (Some(a), Some(b)) => {
            for q in 1..=64u32 {
                let w = b * q as f64;
                let p = (w / a).round();
                if p >= 1.0 && (p * a - w).abs() <= 1e-9 * w {
                    return Ok(Some(w));
                }
            }
            Err(Error::Config(format!(
                "the periods of the two surfaces along {axis} ({a} m and {b} m) have no common \
                 multiple within 64 periods; give commensurate wavelengths"
            )))
        }
    }
}
