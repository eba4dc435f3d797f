//! The block–plane interface of one run: local friction coefficients drawn
//! from Gaussians, and the per-block thresholds (MODELS.md §7).
//!
//! μ_s^i ~ Normal((μ_s)_m, σ_s) and μ_d^i ~ Normal((μ_d)_m, σ_d), drawn in
//! block order from a ChaCha8 stream seeded with the run's seed (static then
//! dynamic for each block, contact blocks only). Draws are clipped to be
//! ≥ 0 and μ_d^i ≤ μ_s^i (a Gaussian tail could otherwise give negative
//! friction or a block whose sliding friction exceeds its static one; with
//! the thesis's 4.5 ± 0.2 and 3.0 ± 0.2 the clip never acts in practice).
//! Holes have μ = 0 and, unless `adhesion_in_holes`, no adhesion.

use rand::Rng;
use rand_distr::{Distribution, Normal};

use super::params::SpringBlockParams;
use crate::error::{Error, Result};

/// Per-block friction properties of one run.
#[derive(Debug, Clone)]
pub struct Interface {
    /// μ_s^i (0 in holes).
    pub mu_static: Vec<f64>,
    /// μ_d^i (0 in holes).
    pub mu_dynamic: Vec<f64>,
    /// Static threshold μ_s^i F_n + F_ad \[N\] (0 for a free hole).
    pub threshold: Vec<f64>,
    /// Kinetic friction force μ_d^i F_n \[N\].
    pub kinetic: Vec<f64>,
    /// F_n = p l², normal force per block \[N\].
    pub normal_force: f64,
}

impl Interface {
    /// Draws the coefficients for the contact blocks of `mask` (true = hole)
    /// at pressure `pressure` \[Pa\] (> 0).
    pub fn draw(
        p: &SpringBlockParams,
        mask: &[bool],
        pressure: f64,
        rng: &mut impl Rng,
    ) -> Result<Self> {
        if !(pressure.is_finite() && pressure > 0.0) {
            return Err(Error::Config(format!(
                "spring-block: pressure is {pressure} Pa; expected > 0"
            )));
        }
        let f = &p.friction;
        let ns = Normal::new(f.mu_static_mean, f.mu_static_sd)
            .map_err(|e| Error::Config(format!("spring-block: static friction Gaussian: {e}")))?;
        let nd = Normal::new(f.mu_dynamic_mean, f.mu_dynamic_sd)
            .map_err(|e| Error::Config(format!("spring-block: dynamic friction Gaussian: {e}")))?;
        let f_n = pressure * p.spacing * p.spacing;
        let fad = p.adhesion_force();
        let n = mask.len();
        let mut out = Interface {
            mu_static: vec![0.0; n],
            mu_dynamic: vec![0.0; n],
            threshold: vec![0.0; n],
            kinetic: vec![0.0; n],
            normal_force: f_n,
        };
        for (i, &hole) in mask.iter().enumerate() {
            if hole {
                if p.adhesion_in_holes {
                    out.threshold[i] = fad;
                }
                continue;
            }
            let ms = ns.sample(rng).max(0.0);
            let md = nd.sample(rng).max(0.0).min(ms);
            out.mu_static[i] = ms;
            out.mu_dynamic[i] = md;
            out.threshold[i] = ms * f_n + fad;
            out.kinetic[i] = md * f_n;
        }
        Ok(out)
    }

    /// A block is free when it has no static threshold: it never sticks.
    pub fn is_free(&self, i: usize) -> bool {
        self.threshold[i] <= 0.0
    }

    /// Mean static threshold over blocks that have one \[N\].
    pub fn mean_threshold(&self) -> f64 {
        let (s, c) = self
            .threshold
            .iter()
            .filter(|&&t| t > 0.0)
            .fold((0.0, 0usize), |(s, c), &t| (s + t, c + 1));
        if c == 0 {
            0.0
        } else {
            s / c as f64
        }
    }
}
