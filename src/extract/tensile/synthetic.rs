//! Synthetic stress–strain curves with known answers, for tests, fixtures
//! and benchmarks.
//!
//! A curve is a list of vertices (ε, σ) joined by straight lines; a drop is
//! two vertices at the same strain. Its exact area is the sum of the
//! trapezoids between vertices, so every integral of the analysis has a
//! closed form. [`sample`] turns the vertices into a measured-looking record:
//! a slack region of negative strain, samples every `step` of strain (plus
//! every vertex), Gaussian noise on the stress, and a post-fracture tail.

use rand::SeedableRng;
use rand_distr::{Distribution, Normal};

use super::curve::StressStrainCurve;

/// Vertices of a bilinear elastic–plastic fibre: σ = E ε up to the yield
/// strain ε_y, then σ_y + H (ε − ε_y) up to the break strain ε_f. The curve
/// starts at strain `offset` (0 for an unknotted fibre, ε* after a knot).
pub fn bilinear(
    offset: f64,
    modulus: f64,
    yield_strain: f64,
    hardening: f64,
    break_strain: f64,
) -> Vec<(f64, f64)> {
    let sy = modulus * yield_strain;
    vec![
        (offset, 0.0),
        (offset + yield_strain, sy),
        (
            offset + break_strain,
            sy + hardening * (break_strain - yield_strain),
        ),
    ]
}

/// A knotted fibre (all stresses in Pa, strains relative to l0).
#[derive(Debug, Clone)]
pub struct KnottedSpec {
    /// Stress of the friction plateau (top of the stick-slip teeth).
    pub plateau: f64,
    /// Strain at which the plateau is reached from 0 (linear rise).
    pub plateau_rise: f64,
    /// Strain width of one stick-slip tooth.
    pub tooth_width: f64,
    /// Stress fall of one tooth (a stick-slip drop).
    pub tooth_drop: f64,
    /// Number of teeth; each ends with a drop.
    pub teeth: usize,
    /// Peak stresses of the final unfastening peaks.
    pub unfastening_peaks: Vec<f64>,
    /// Strain width of the rise to each unfastening peak.
    pub unfastening_width: f64,
    /// Stress after each unfastening drop.
    pub unfastening_trough: f64,
    /// The unknotted response after release: (E, ε_y, H, ε_f − ε*), its
    /// stress starting from `unfastening_trough`.
    pub fibre: (f64, f64, f64, f64),
}

impl KnottedSpec {
    /// Vertices of the curve, and the index of the release vertex (ε*).
    pub fn vertices(&self) -> (Vec<(f64, f64)>, usize) {
        let mut v = vec![(0.0, 0.0), (self.plateau_rise, self.plateau)];
        let mut e = self.plateau_rise;
        for _ in 0..self.teeth {
            e += self.tooth_width;
            v.push((e, self.plateau));
            v.push((e, self.plateau - self.tooth_drop));
            // climb back to the plateau over a tenth of the tooth
            v.push((e + 0.1 * self.tooth_width, self.plateau));
        }
        for &p in &self.unfastening_peaks {
            e = v.last().map_or(e, |x| x.0) + self.unfastening_width;
            v.push((e, p));
            v.push((e, self.unfastening_trough));
        }
        let release = v.len() - 1;
        let eps_star = v[release].0;
        let (m, ey, h, ef) = self.fibre;
        for (de, s) in bilinear(0.0, m, ey, h, ef).into_iter().skip(1) {
            v.push((eps_star + de, self.unfastening_trough + s));
        }
        (v, release)
    }
}

/// Exact ∫ σ dε of a vertex path between strains `lo` and `hi` (trapezoids).
pub fn exact_area(v: &[(f64, f64)], lo: f64, hi: f64) -> f64 {
    let x: Vec<f64> = v.iter().map(|p| p.0).collect();
    let y: Vec<f64> = v.iter().map(|p| p.1).collect();
    crate::signal::integrate::trapezoid_within(&x, &y, lo, hi)
}

/// Samples a vertex path into a record: `slack` of negative strain before
/// 0 (stress 0 + noise), a sample every `step` of strain and at each vertex,
/// noise of standard deviation `noise` (Pa) on the stress, and `tail`
/// samples after the fracture (stress 0 + noise). Deterministic in `seed`.
pub fn sample(
    v: &[(f64, f64)],
    step: f64,
    slack: f64,
    noise: f64,
    tail: usize,
    seed: u64,
) -> StressStrainCurve {
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(seed);
    let normal = Normal::new(0.0, noise.max(0.0)).ok();
    let mut jitter = move || normal.map_or(0.0, |n| n.sample(&mut rng));
    let mut e = Vec::new();
    let mut s = Vec::new();
    let n_slack = (slack / step).round() as usize;
    for k in (1..=n_slack).rev() {
        e.push(-(k as f64) * step);
        s.push(jitter());
    }
    for w in v.windows(2) {
        let ((e0, s0), (e1, s1)) = (w[0], w[1]);
        let n = ((e1 - e0) / step).ceil().max(1.0) as usize;
        for k in 0..n {
            let t = k as f64 / n as f64;
            e.push(e0 + t * (e1 - e0));
            s.push(s0 + t * (s1 - s0) + jitter());
        }
    }
    let (e_end, s_end) = *v.last().unwrap_or(&(0.0, 0.0));
    e.push(e_end);
    s.push(s_end + jitter());
    for k in 1..=tail {
        e.push(e_end + k as f64 * step);
        s.push(jitter());
    }
    StressStrainCurve::new(e, s).expect("strain and stress of equal length")
}
