//! The material ratio curve and what is read from it (MODELS.md §10): the
//! Rk family of ISO 13565-2 (areal Sk family of ISO 25178-2), Smr(c) and
//! Smc(mr), Sxp, and the volume parameters Vm, Vv, Vmp, Vmc, Vvc, Vvv.
//!
//! # The curve
//! With the n measured heights sorted from highest to lowest, h₀ ≥ … ≥
//! h₍ₙ₋₁₎, the curve c(mr) is the polyline through (i/(n − 1), hᵢ): c(0)
//! is the highest peak, c(1) the deepest valley (the bearing curve of
//! [`super::bearing`], and the empirical quantile numpy's `quantile` and
//! surfalize use). Material ratios are fractions (0..1), not percent.
//!
//! | quantity | definition on the polyline |
//! |---|---|
//! | Smc(mr) | c(mr) |
//! | Smr(c) | the largest mr with c(mr) ≥ c (0 above the highest peak, 1 at or below the deepest valley) |
//! | Sxp | Smc(2.5 %) − Smc(50 %) (ISO 25178-2 defaults) |
//! | Vm(p) | ∫₀ᵖ (c(q) − c(p)) dq: material volume per unit area above Smc(p) (m³/m² = m) |
//! | Vv(p) | ∫ₚ¹ (c(p) − c(q)) dq: void volume per unit area below it |
//! | Vmp, Vmc, Vvc, Vvv | Vm(p), Vm(q) − Vm(p), Vv(p) − Vv(q), Vv(q); p = 10 %, q = 80 % |
//!
//! The integrals are exact on the polyline (trapezoids between knots, a
//! partial trapezoid at the ends).
//!
//! # Rk family (ISO 13565-2)
//! The central region is the 40 % window [m, m + 0.4] whose secant has the
//! smallest gradient (c(m + 0.4) − c(m) largest, being ≤ 0); on the
//! polyline that maximum lies at a knot of c(m) or of c(m + 0.4), so every
//! knot is tried and the first maximum kept. The equivalent straight line
//! is ([`RkLine`]) the least-squares line of the curve's points in that
//! window (default: ISO 25178-2:2021 B.1, surfalize, MountainsMap) or the
//! secant itself. It meets mr = 0 and 1 at c1 and c2:
//! Rk = c1 − c2, Mr1 = Smr(c1), Mr2 = Smr(c2),
//! A1 = ∫₀^Mr1 (c − c1), A2 = ∫_Mr2¹ (c2 − c), Rpk = 2 A1 / Mr1,
//! Rvk = 2 A2 / (1 − Mr2) (0 when there is no peak or valley zone).

use rayon::prelude::*;
use serde::{Deserialize, Serialize};

/// How the equivalent straight line of the Rk construction is drawn
/// through the central 40 % region.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum RkLine {
    /// Least-squares line of the curve's points in the window (ISO
    /// 25178-2:2021 B.1, surfalize, MountainsMap). Default.
    LeastSquares,
    /// The secant over the window itself.
    Secant,
}

/// Width of the central region of the Rk construction (40 %).
pub const CENTRAL_WIDTH: f64 = 0.4;

/// The material ratio curve of the measured heights.
#[derive(Debug, Clone)]
pub struct MaterialCurve {
    /// Measured heights, highest first.
    h: Vec<f64>,
    /// ∫₀^{i/(n−1)} c(q) dq at each knot.
    cum: Vec<f64>,
}

impl MaterialCurve {
    /// The curve of the measured (non-NaN) heights of `z`, sorted on all
    /// threads; `None` with fewer than two.
    pub fn new(z: &[f64]) -> Option<Self> {
        let mut h: Vec<f64> = z.par_iter().copied().filter(|v| !v.is_nan()).collect();
        if h.len() < 2 {
            return None;
        }
        h.par_sort_unstable_by(|a, b| b.total_cmp(a));
        let step = 1.0 / (h.len() - 1) as f64;
        let mut cum = Vec::with_capacity(h.len());
        let mut acc = 0.0;
        cum.push(0.0);
        for w in h.windows(2) {
            acc += 0.5 * (w[0] + w[1]) * step;
            cum.push(acc);
        }
        Some(MaterialCurve { h, cum })
    }

    /// The heights, highest first.
    pub fn sorted(&self) -> &[f64] {
        &self.h
    }

    fn knot(&self, mr: f64) -> (usize, f64) {
        let n = self.h.len();
        let pos = mr.clamp(0.0, 1.0) * (n - 1) as f64;
        let i = (pos.floor() as usize).min(n - 2);
        (i, pos - i as f64)
    }

    /// Smc(mr) = c(mr), `mr` clamped to [0, 1].
    pub fn height(&self, mr: f64) -> f64 {
        let (i, t) = self.knot(mr);
        self.h[i] + t * (self.h[i + 1] - self.h[i])
    }

    /// Smr(c): the largest material ratio at which the curve is at or
    /// above `c`.
    pub fn ratio(&self, c: f64) -> f64 {
        let n = self.h.len();
        let k = self.h.partition_point(|&v| v >= c);
        match k {
            0 => 0.0,
            k if k == n => 1.0,
            k => {
                let (a, b) = (self.h[k - 1], self.h[k]);
                ((k - 1) as f64 + (a - c) / (a - b)) / (n - 1) as f64
            }
        }
    }

    /// ∫₀^mr c(q) dq, exact on the polyline.
    pub fn integral_to(&self, mr: f64) -> f64 {
        let (i, t) = self.knot(mr);
        let step = 1.0 / (self.h.len() - 1) as f64;
        let at = self.h[i] + t * (self.h[i + 1] - self.h[i]);
        self.cum[i] + 0.5 * (self.h[i] + at) * t * step
    }

    /// Vm(p): material volume per unit area above Smc(p) (m).
    pub fn vm(&self, p: f64) -> f64 {
        self.integral_to(p) - p * self.height(p)
    }

    /// Vv(p): void volume per unit area below Smc(p) (m).
    pub fn vv(&self, p: f64) -> f64 {
        let total = self.integral_to(1.0);
        (1.0 - p) * self.height(p) - (total - self.integral_to(p))
    }
}

/// The Rk family of one curve (heights in m, ratios as fractions).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RkFamily {
    /// Rk (Sk): core height c1 − c2.
    pub rk: f64,
    /// Rpk (Spk): reduced peak height.
    pub rpk: f64,
    /// Rvk (Svk): reduced valley depth.
    pub rvk: f64,
    /// Mr1 (Smr1): material ratio at c1.
    pub mr1: f64,
    /// Mr2 (Smr2): material ratio at c2.
    pub mr2: f64,
    /// A1: area of the peak zone above c1 (m · ratio).
    pub a1: f64,
    /// A2: area of the valley zone below c2.
    pub a2: f64,
    /// Height of the equivalent line at mr = 0 (c1) and 1 (c2).
    pub c1: f64,
    /// See `c1`.
    pub c2: f64,
    /// Start of the central 40 % region.
    pub central_start: f64,
}

/// Start m of the central region: the first (smallest) m in [0, 0.6]
/// where c(m + 0.4) − c(m) is largest, tried at every knot of either end
/// and at 0.6. The reduction keeps the larger gain and, on a tie, the
/// smaller m: associative, so the same answer whatever the split.
fn central_start(curve: &MaterialCurve) -> f64 {
    let n = curve.h.len();
    let n1 = (n - 1) as f64;
    let last = 1.0 - CENTRAL_WIDTH;
    let gain = |m: f64| curve.height(m + CENTRAL_WIDTH) - curve.height(m);
    let better = |a: (f64, f64), b: (f64, f64)| {
        if b.1.total_cmp(&a.1).then(a.0.total_cmp(&b.0)).is_gt() {
            b
        } else {
            a
        }
    };
    (0..n)
        .into_par_iter()
        .flat_map_iter(|i| {
            let k = i as f64 / n1;
            [k, k - CENTRAL_WIDTH]
        })
        .chain(rayon::iter::once(last))
        .filter(|m| (0.0..=last).contains(m))
        .map(|m| (m, gain(m)))
        .reduce(|| (0.0, gain(0.0)), better)
        .0
}

/// The equivalent line (c at mr = 0, slope per unit ratio) over [m, m + 0.4].
fn equivalent_line(curve: &MaterialCurve, m: f64, how: RkLine) -> (f64, f64) {
    let (a, b) = (m, m + CENTRAL_WIDTH);
    if how == RkLine::Secant {
        let s = (curve.height(b) - curve.height(a)) / CENTRAL_WIDTH;
        return (curve.height(a) - s * a, s);
    }
    let n1 = (curve.h.len() - 1) as f64;
    let (lo, hi) = (
        (a * n1 - 1e-9).ceil() as usize,
        ((b * n1 + 1e-9).floor() as usize),
    );
    let pts = || (lo..=hi).map(|i| (i as f64 / n1, curve.h[i]));
    let k = (hi + 1 - lo) as f64;
    let (mx, my) = (
        pts().map(|p| p.0).sum::<f64>() / k,
        pts().map(|p| p.1).sum::<f64>() / k,
    );
    let (sxy, sxx) = pts().fold((0.0, 0.0), |(sxy, sxx), (x, y)| {
        (sxy + (x - mx) * (y - my), sxx + (x - mx) * (x - mx))
    });
    let s = if sxx > 0.0 { sxy / sxx } else { 0.0 };
    (my - s * mx, s)
}

/// The Rk family of `curve`.
pub fn rk_family(curve: &MaterialCurve, how: RkLine) -> RkFamily {
    let m = central_start(curve);
    let (c1, s) = equivalent_line(curve, m, how);
    let c2 = c1 + s;
    let (mr1, mr2) = (curve.ratio(c1), curve.ratio(c2));
    let a1 = (curve.integral_to(mr1) - c1 * mr1).max(0.0);
    let total = curve.integral_to(1.0);
    let a2 = (c2 * (1.0 - mr2) - (total - curve.integral_to(mr2))).max(0.0);
    RkFamily {
        rk: c1 - c2,
        rpk: if mr1 > 0.0 { 2.0 * a1 / mr1 } else { 0.0 },
        rvk: if mr2 < 1.0 {
            2.0 * a2 / (1.0 - mr2)
        } else {
            0.0
        },
        mr1,
        mr2,
        a1,
        a2,
        c1,
        c2,
        central_start: m,
    }
}

/// Volume parameters at the material ratios p and q (ISO 25178-2
/// defaults 0.1 and 0.8), m³/m² = m.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Volume {
    /// Vmp = Vm(p): peak material volume.
    pub vmp: f64,
    /// Vmc = Vm(q) − Vm(p): core material volume.
    pub vmc: f64,
    /// Vvc = Vv(p) − Vv(q): core void volume.
    pub vvc: f64,
    /// Vvv = Vv(q): valley void volume.
    pub vvv: f64,
}

/// Volume parameters of `curve` at `p` < `q`.
pub fn volume(curve: &MaterialCurve, p: f64, q: f64) -> Volume {
    Volume {
        vmp: curve.vm(p),
        vmc: curve.vm(q) - curve.vm(p),
        vvc: curve.vv(p) - curve.vv(q),
        vvv: curve.vv(q),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Heights on a piecewise-linear curve through `knots` (mr, c),
    /// sampled at i/(n − 1): the polyline is the curve itself where the
    /// knots fall on samples. Shuffled so that the sort is exercised.
    fn sampled(knots: &[(f64, f64)], n: usize) -> Vec<f64> {
        let c = |m: f64| {
            let k = knots.windows(2).find(|w| m <= w[1].0).unwrap();
            let t = (m - k[0].0) / (k[1].0 - k[0].0);
            k[0].1 + t * (k[1].1 - k[0].1)
        };
        let mut z: Vec<f64> = (0..n).map(|i| c(i as f64 / (n - 1) as f64)).collect();
        let len = z.len();
        for i in 0..len {
            z.swap(i, (i * 7919 + 13) % len);
        }
        z
    }

    #[test]
    fn piecewise_linear_curve_gives_the_rk_closed_forms() {
        // Peaks from 3 to 1 over 0..0.1, core 1 to −0.4 over 0.1..0.8
        // (slope −2), valleys −0.4 to −4 over 0.8..1 (µm). The core is 70 %
        // wide and the least steep, so the equivalent line is the core line
        // c = 1 − 2(mr − 0.1): c1 = 1.2, c2 = −0.8, Rk = 2. Peaks: c = 3 −
        // 20 mr meets 1.2 at Mr1 = 0.09; A1 is the triangle (3 − 1.2)·0.09/2,
        // so Rpk = 3 − 1.2 = 1.8. Valleys: c = −0.4 − 18(mr − 0.8) meets
        // −0.8 at Mr2 = 0.8 + 0.4/18; Rvk = −0.8 − (−4) = 3.2.
        let knots = [(0.0, 3.0), (0.1, 1.0), (0.8, -0.4), (1.0, -4.0)];
        // n − 1 = 1800 puts every knot (and Mr1) on a sample: exact.
        let z = sampled(&knots, 1801);
        let c = MaterialCurve::new(&z).unwrap();
        for how in [RkLine::LeastSquares, RkLine::Secant] {
            let r = rk_family(&c, how);
            let close = |a: f64, b: f64| (a - b).abs() < 1e-12 * b.abs().max(1.0);
            assert!(close(r.c1, 1.2) && close(r.c2, -0.8), "{r:?}");
            assert!(close(r.rk, 2.0), "Rk {}", r.rk);
            assert!(close(r.mr1, 0.09), "Mr1 {}", r.mr1);
            assert!(close(r.mr2, 0.8 + 0.4 / 18.0), "Mr2 {}", r.mr2);
            assert!(close(r.rpk, 1.8), "Rpk {}", r.rpk);
            assert!(close(r.rvk, 3.2), "Rvk {}", r.rvk);
            assert!(close(r.a1, 1.8 * 0.09 / 2.0));
            assert!(close(r.a2, 3.2 * (1.0 - r.mr2) / 2.0));
        }
    }

    #[test]
    fn ratio_and_height_are_inverse_and_volumes_add_up() {
        let knots = [(0.0, 2.0), (0.3, 0.5), (1.0, -1.0)];
        let c = MaterialCurve::new(&sampled(&knots, 1001)).unwrap();
        for mr in [0.0, 0.025, 0.1, 0.5, 0.8, 0.999] {
            assert!((c.ratio(c.height(mr)) - mr).abs() < 1e-12, "{mr}");
        }
        assert!((c.ratio(5.0)).abs() < 1e-15 && (c.ratio(-5.0) - 1.0).abs() < 1e-15);
        // Vm(p) + Vv(p) = ∫ |c − c(p)| split at p; Vm(0) = 0, Vv(1) = 0;
        // Vm(1) − Vv(0) = mean − c(1) − (c(0) − mean) … the identity
        // Vv(p) − Vm(p) = c(p) − mean holds for every p.
        let mean = c.integral_to(1.0);
        for p in [0.0, 0.1, 0.3, 0.8, 1.0] {
            assert!((c.vv(p) - c.vm(p) - (c.height(p) - mean)).abs() < 1e-12);
        }
        // Closed form on the first segment: c = 2 − 5 mr, Vm(p) = 2.5 p².
        assert!((c.vm(0.1) - 2.5 * 0.01).abs() < 1e-12);
    }

    #[test]
    fn nan_heights_are_left_out_and_too_few_give_none() {
        assert!(MaterialCurve::new(&[1.0, f64::NAN]).is_none());
        let c = MaterialCurve::new(&[1.0, f64::NAN, 0.0]).unwrap();
        assert_eq!(c.sorted(), &[1.0, 0.0]);
    }
}
