//! Archard wear of the asperities (thesis Sec. 2.2, Eq. 2.3–2.9; MODELS.md
//! §5 "Wear").
//!
//! ```text
//! B(t) = 1 − W v t / V0      (Eq. 2.5, 2.7; clamped at 0)
//! T_w  = V0 / (W v)          (B = 0: the surfaces are flat, μ → μ0)
//! ```
//!
//! The asperity heights of both surfaces scale by B about their deepest
//! valley ([`super::surface::Surface::scaled`]); for wedges this is
//! tan φ(t) = B tan φ0, which is Eq. 2.9 with V0 = s² Y tan φ0 / 2.
//!
//! | symbol | field | unit |
//! |---|---|---|
//! | W | `rate` | m³/m, worn volume per sliding distance (Archard K L / H), > 0 |
//! | V0 | `reference_volume` | m³, asperity volume above the deepest valley, > 0 |
//! | v | `velocity` | m/s, sliding velocity, > 0 |
//!
//! The thesis integrates z itself, which vanishes over a sinusoid's period;
//! MODELS.md §5 uses the volume above the deepest valley, ∫(z − z_min) dA,
//! and makes it a parameter.

use crate::error::{Error, Result};

/// Wear parameters.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct WearParams {
    /// W, m³/m, > 0.
    pub rate: f64,
    /// V0, m³, > 0.
    pub reference_volume: f64,
    /// v, m/s, > 0.
    pub velocity: f64,
}

impl WearParams {
    /// Checks that every field is finite and > 0.
    pub fn validate(&self) -> Result<()> {
        for (n, v) in [
            ("wear rate W", self.rate),
            ("reference volume V0", self.reference_volume),
            ("velocity v", self.velocity),
        ] {
            if !(v.is_finite() && v > 0.0) {
                return Err(Error::Config(format!(
                    "{n} must be finite and > 0, got {v}"
                )));
            }
        }
        Ok(())
    }

    /// T_w = V0 / (W v), s.
    pub fn wear_time(&self) -> f64 {
        self.reference_volume / (self.rate * self.velocity)
    }

    /// B(t) = 1 − W v t / V0, clamped to [0, 1].
    pub fn reduction(&self, t: f64) -> f64 {
        (1.0 - self.rate * self.velocity * t / self.reference_volume).clamp(0.0, 1.0)
    }
}

/// Eq. 2.9: tan φ(t) = tan φ0 − 2 W v t / (s² Y) for a wedge of half-width s
/// and depth Y, clamped at 0 (flat).
pub fn wedge_tan_phi(
    tan_phi0: f64,
    rate: f64,
    velocity: f64,
    half_width: f64,
    depth: f64,
    t: f64,
) -> f64 {
    (tan_phi0 - 2.0 * rate * velocity * t / (half_width * half_width * depth)).max(0.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// B is linear from 1 to 0 at T_w and stays 0 after; T_w by hand.
    #[test]
    fn reduction_and_wear_time() {
        let w = WearParams {
            rate: 2e-3,
            reference_volume: 4e-2,
            velocity: 0.5,
        };
        assert!((w.wear_time() - 40.0).abs() < 1e-12);
        assert!((w.reduction(10.0) - 0.75).abs() < 1e-15);
        assert!(w.reduction(40.0).abs() < 1e-15 && w.reduction(80.0).abs() < 1e-15);
    }

    /// Scaling the heights by B is Eq. 2.9 when V0 is the wedge's volume
    /// s² Y tan φ0 / 2 (1e-15: one rounding each).
    #[test]
    fn scaling_is_eq_2_9_for_wedges() {
        let (t0, s, y) = (0.4, 0.5, 2.0);
        let w = WearParams {
            rate: 1e-3,
            reference_volume: s * s * y * t0 / 2.0,
            velocity: 1.0,
        };
        for t in [0.0, 10.0, 30.0, 49.0, 50.0, 70.0] {
            let a = w.reduction(t) * t0;
            let b = wedge_tan_phi(t0, w.rate, w.velocity, s, y, t);
            assert!((a - b).abs() < 1e-15, "{t}: {a} vs {b}");
        }
    }
}
