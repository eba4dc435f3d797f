//! The valley-suppression filter of ISO 13565-1, on which the Rk family
//! (ISO 13565-2) is defined for plateau-honed surfaces: deep valleys would
//! pull an ordinary Gaussian mean line down into the plateau.
//!
//! 1. The first mean line m₁: the ISO 16610-21 Gaussian filter of the
//!    primary profile ([`mean_line`], renormalised at the ends).
//! 2. Every point below m₁ is replaced by m₁ there: z′ = max(z, m₁).
//! 3. The mean line m₂: the same Gaussian filter of z′.
//! 4. The roughness is the original profile minus m₂.
//!
//! A map takes the areal Gaussian filter in both passes (the same
//! construction over the area). Points not measured stay so in z′ and are
//! handled by the Gaussian filter's rule.

use super::gaussian_filter::{mean_line, mean_surface, GaussianFilterParams};
use crate::error::Result;

fn suppress(z: &[f64], m1: &[f64]) -> Vec<f64> {
    z.iter()
        .zip(m1)
        .map(|(&v, &m)| if v < m { m } else { v })
        .collect()
}

/// The second mean line m₂ of a profile (see the module documentation).
pub fn valley_mean_line(z: &[f64], dx: f64, params: &GaussianFilterParams) -> Result<Vec<f64>> {
    let m1 = mean_line(z, dx, params)?;
    mean_line(&suppress(z, &m1), dx, params)
}

/// The second mean surface of a row-major `ny × nx` map.
pub fn valley_mean_surface(
    z: &[f64],
    nx: usize,
    ny: usize,
    dx: f64,
    dy: f64,
    params: &GaussianFilterParams,
) -> Result<Vec<f64>> {
    let m1 = mean_surface(z, nx, ny, dx, dy, params)?;
    mean_surface(&suppress(z, &m1), nx, ny, dx, dy, params)
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    #[test]
    fn plateau_with_scratches_keeps_its_mean_line_at_the_plateau() {
        // A fine plateau texture (amplitude 0.05 µm, period 20 µm) with a
        // 10 µm-deep scratch every 200 µm (4 % of the points), λc = 0.8 mm.
        // The first mean line sinks into the scratches' mean (−0.4 µm); the
        // second, over the valleys replaced by m₁, keeps half of the
        // plateau texture's own mean offset only: within 0.05 µm of 0.
        let (dx, lc) = (1e-6, 0.8e-3);
        let z: Vec<f64> = (0..8000)
            .map(|i| {
                let t = 0.05e-6 * (2.0 * PI * i as f64 / 20.0).sin();
                if i % 200 < 8 {
                    t - 10e-6
                } else {
                    t
                }
            })
            .collect();
        let p = GaussianFilterParams::new(lc).unwrap();
        let m1 = mean_line(&z, dx, &p).unwrap();
        let m2 = valley_mean_line(&z, dx, &p).unwrap();
        let mid = 4000;
        assert!((m1[mid] + 0.4e-6).abs() < 0.01e-6, "{}", m1[mid]);
        assert!(m2[mid].abs() < 0.05e-6, "{}", m2[mid]);
        assert!(m2[mid] > m1[mid]);
    }
}
