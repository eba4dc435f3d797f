//! The tip-radius reliability cut-off (MODELS.md §10; Sanner et al., Appl.
//! Surf. Sci. Adv. 7, 100190, 2022; SurfaceTopography's
//! `scanning_probe_reliability_cutoff`, the basis of its
//! `short_reliability_cutoff`).
//!
//! A stylus of tip radius R cannot follow a valley sharper than its tip:
//! curvature h″ < −1/R. At the scale λ the curvature is the second
//! difference over the stencil of total length λ, h″_λ(x) = (h(x − λ/2) −
//! 2h(x) + h(x + λ/2)) / (λ/2)², with heights between samples linearly
//! interpolated and only the stencils inside the data (and, for a map,
//! along x, trimmed by ⌈λ/2Δ⌉ on every side as SurfaceTopography trims its
//! 2-D stencil). The cut-off λ_c is where the most negative curvature over
//! the surface equals −f/R, f = 1/2 (the safety factor estimated in the
//! paper), found by Brent's method between 2Δx and L/2 (Δx and L the means
//! of the two directions for a map). Below λ_c the data may be the tip's
//! shape rather than the surface's.
//!
//! No cut-off when the curvature criterion holds at the smallest scale
//! (the tip follows everything measured); the whole bandwidth L/2 when it
//! fails at the largest. Points not measured are left out of the minimum.

use rayon::prelude::*;

use crate::signal::roots::brent;

/// The safety factor f of the criterion h″ ≥ −f/R.
pub const SAFETY_FACTOR: f64 = 0.5;

/// Where the data stop being reliable.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Cutoff {
    /// The tip follows every scale measured.
    None,
    /// Scales below this length (m) may be tip artefacts.
    At(f64),
    /// Even the largest scale fails the criterion: nothing is reliable
    /// (holds L/2, m).
    Everything(f64),
}

impl Cutoff {
    /// The cut-off length, when there is one.
    pub fn length(self) -> Option<f64> {
        match self {
            Cutoff::None => None,
            Cutoff::At(l) | Cutoff::Everything(l) => Some(l),
        }
    }
}

/// The most negative second difference along x at stencil length
/// `distance` (m) over a row-major `ny × nx` map (a profile: `ny = 1`).
fn min_curvature(z: &[f64], nx: usize, ny: usize, dx: f64, dy: f64, distance: f64) -> Option<f64> {
    let (sx, sy) = (distance / (2.0 * dx), distance / (2.0 * dy));
    let (tx, ty) = (
        sx.ceil() as usize,
        if ny > 1 { sy.ceil() as usize } else { 0 },
    );
    if nx <= 2 * tx || ny <= 2 * ty {
        return None;
    }
    let h = sx * dx;
    // h(x ± s Δx) by linear interpolation between samples of the row.
    let (k, frac) = (sx.floor() as usize, sx - sx.floor());
    let at = |row: &[f64], c: usize, ahead: bool| {
        let (i, j) = match ahead {
            true => (c + k, (c + k + 1).min(nx - 1)),
            false => (c - k, c.saturating_sub(k + 1)),
        };
        row[i] + frac * (row[j] - row[i])
    };
    let m = (ty..ny - ty)
        .into_par_iter()
        .map(|r| {
            let row = &z[r * nx..(r + 1) * nx];
            (tx..nx - tx)
                .map(|c| (at(row, c, false) - 2.0 * row[c] + at(row, c, true)) / (h * h))
                .filter(|v| !v.is_nan())
                .fold(f64::INFINITY, f64::min)
        })
        .reduce(|| f64::INFINITY, f64::min);
    m.is_finite().then_some(m)
}

/// The reliability cut-off of a map (or a profile, `ny = 1`) measured with
/// a tip of radius `tip_radius` (m).
pub fn reliability_cutoff(
    z: &[f64],
    nx: usize,
    ny: usize,
    dx: f64,
    dy: f64,
    tip_radius: f64,
) -> Cutoff {
    let (lower, upper) = match ny > 1 {
        true => ((dx + dy) / 2.0, (nx as f64 * dx + ny as f64 * dy) / 2.0),
        false => (dx, nx as f64 * dx),
    };
    // Distances normalised by the geometric mean of the bandwidth, as
    // SurfaceTopography does, so Brent's tolerances mean the same.
    let fac = (lower * upper).sqrt();
    let target = fac * SAFETY_FACTOR / tip_radius;
    let objective = |d: f64| match min_curvature(z, nx, ny, dx, dy, fac * d) {
        Some(c) => target + fac * c,
        None => target,
    };
    let (a, b) = (2.0 * lower / fac, upper / (2.0 * fac));
    if objective(a) > 0.0 {
        return Cutoff::None;
    }
    if objective(b) < 0.0 {
        return Cutoff::Everything(upper / 2.0);
    }
    match brent(objective, a, b, 2e-12, 1e-8) {
        Some(d) => Cutoff::At(fac * d),
        None => Cutoff::Everything(upper / 2.0),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    #[test]
    fn a_sine_is_reliable_where_its_scale_curvature_stays_above_the_tip() {
        // h = A sin(kx): the second difference over a stencil of length λ
        // has minimum −A (2 sin(kλ/4) / (λ/2))² (at the crests, sampled
        // finely). It equals −f/R where 4A sin²(kλ/4)/(λ/2)² = f/R: solved
        // here by bisection on the closed form, independently of the
        // implementation.
        let (a, wl) = (1e-6, 20e-6);
        let k = 2.0 * PI / wl;
        let dx = wl / 2000.0;
        let z: Vec<f64> = (0..40_000).map(|i| a * (k * i as f64 * dx).sin()).collect();
        let curv = |l: f64| 4.0 * a * (k * l / 4.0).sin().powi(2) / (l / 2.0).powi(2);
        // Peak curvature A k² = 0.099 /µm: a tip of 2 µm (f/R = 0.25 /µm)
        // follows it everywhere; one of 20 µm (0.025 /µm) does not at the
        // finest scales.
        assert_eq!(
            reliability_cutoff(&z, z.len(), 1, dx, dx, 2e-6),
            Cutoff::None
        );
        let r = 20e-6;
        let (mut lo, mut hi) = (2.0 * dx, 1.5 * wl);
        for _ in 0..100 {
            let m = 0.5 * (lo + hi);
            if curv(m) > SAFETY_FACTOR / r {
                lo = m;
            } else {
                hi = m;
            }
        }
        let Cutoff::At(got) = reliability_cutoff(&z, z.len(), 1, dx, dx, r) else {
            panic!("expected a cut-off");
        };
        // The crest is sampled to within half a step (2000 samples per
        // wavelength: curvature off by ≤ (πΔx/λ)² ≈ 2.5e-6) and linear
        // interpolation of the sine between samples moves h(x ± λ/2) by
        // ≤ (kΔx)²/8 A: 1e-4 relative in λ_c.
        assert!((got - lo).abs() < 1e-4 * lo, "{got} vs {lo}");
    }
}
