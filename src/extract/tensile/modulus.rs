//! Modulus: the largest slope dσ/dε of a straight line fitted by least
//! squares over a sliding strain window in the loading part of the curve
//! (the thesis's fibres, and the default), or the window of a material
//! class ([`of_class`]: a strain or stress range, a secant, a chord).
//!
//! The window spans `modulus_window` · ε_m of strain (default 1 %), where ε_m
//! is the strain at maximum stress; windows with fewer than 5 samples are
//! skipped (widening them instead amplifies the rounding of strain written
//! with 3 decimals, as in T150 exports: +20 % on the real file). It slides from the start of loading (ε = 0) up to the
//! maximum stress. Each window needs at least 5 samples. The steepest
//! window is the linear-elastic region for a silk fibre (whose curve softens
//! after yield) and is insensitive to the toe at the start. For a knotted
//! fibre the strain is relative to l0 and the value is an apparent modulus.

use super::class::Window;

/// Largest least-squares slope over windows of strain width `width` in
/// `from..=to`, skipping windows with fewer than 5 samples. `None` when no
/// window qualifies or the strain does not vary.
pub fn max_slope_modulus(
    strain: &[f64],
    stress: &[f64],
    from: usize,
    to: usize,
    width: f64,
) -> Option<f64> {
    const MIN_POINTS: usize = 5;
    if width.is_nan() || width <= 0.0 || to >= strain.len() || from > to {
        return None;
    }
    // Windows [i, j] slide with both ends moving forward; the moments are
    // updated in O(1) per sample (Welford add/remove), which keeps the scan
    // O(n). The winning window's slope is then recomputed with the exact
    // two-pass formula, so the reported value carries no update drift.
    let mut acc = Moments::default();
    let mut best: Option<(f64, usize, usize)> = None;
    let mut j = from; // next sample to add
    for i in from..=to {
        if j < i {
            j = i;
            acc = Moments::default();
        }
        while j <= to && strain[j] - strain[i] <= width {
            acc.add(strain[j], stress[j]);
            j += 1;
        }
        if j - i >= MIN_POINTS {
            if let Some(s) = acc.slope() {
                if best.is_none_or(|b| s > b.0) {
                    best = Some((s, i, j - 1));
                }
            }
        }
        if j > i {
            acc.remove(strain[i], stress[i]);
        }
    }
    let (_, i, j) = best?;
    slope(&strain[i..=j], &stress[i..=j])
}

/// The modulus by a class's window (see [`Window`]) over the first loading
/// `from..=to` (from the start of loading to the maximum stress; the
/// max-slope window is `max_slope_fraction` of the strain there), and the
/// method in words for the table. `None` when the curve does not reach the
/// window or it holds fewer than 3 samples.
pub fn of_class(
    window: Window,
    strain: &[f64],
    stress: &[f64],
    from: usize,
    to: usize,
    max_slope_fraction: f64,
) -> (Option<f64>, String) {
    let smax = stress[to];
    match window {
        Window::MaxSlope => (
            max_slope_modulus(strain, stress, from, to, max_slope_fraction * strain[to]),
            format!(
                "max slope over strain windows of {max_slope_fraction} × the strain at maximum stress"
            ),
        ),
        Window::Strain(lo, hi) => {
            let idx: Vec<usize> = (from..=to)
                .take_while(|&i| strain[i] <= hi)
                .filter(|&i| strain[i] >= lo)
                .collect();
            (
                fit_at(strain, stress, &idx),
                format!(
                    "regression over strain {}–{} % of the first loading (ISO 527-1)",
                    lo * 100.0,
                    hi * 100.0
                ),
            )
        }
        Window::StressFraction(lo, hi) => {
            let idx: Vec<usize> = (from..=to)
                .take_while(|&i| stress[i] <= hi * smax)
                .filter(|&i| stress[i] >= lo * smax)
                .collect();
            (
                fit_at(strain, stress, &idx),
                format!(
                    "regression over {}–{} % of the maximum stress on the first loading",
                    lo * 100.0,
                    hi * 100.0
                ),
            )
        }
        Window::Secant(e) => (
            at_strain(strain, stress, from, to, e).map(|s| s / e),
            format!("secant at strain {} (stress at {} % elongation / strain)", e, e * 100.0),
        ),
        Window::Chord(e1, frac) => {
            let s1 = at_strain(strain, stress, from, to, e1);
            let e2 = at_stress(strain, stress, from, to, frac * smax);
            let e = match (s1, e2) {
                (Some(s1), Some(e2)) if e2 > e1 => Some((frac * smax - s1) / (e2 - e1)),
                _ => None,
            };
            (
                e,
                format!(
                    "chord from strain {e1} to {} % of the maximum stress (ASTM C469)",
                    frac * 100.0
                ),
            )
        }
    }
}

/// Least-squares slope over the samples `idx`; `None` with fewer than 3.
fn fit_at(strain: &[f64], stress: &[f64], idx: &[usize]) -> Option<f64> {
    if idx.len() < 3 {
        return None;
    }
    let x: Vec<f64> = idx.iter().map(|&i| strain[i]).collect();
    let y: Vec<f64> = idx.iter().map(|&i| stress[i]).collect();
    slope(&x, &y)
}

/// The stress where the strain first reaches `e` in `from..=to`, linearly
/// interpolated.
pub fn at_strain(strain: &[f64], stress: &[f64], from: usize, to: usize, e: f64) -> Option<f64> {
    crossing(strain, from, to, e).map(|(k, t)| stress[k] + t * (stress[k + 1] - stress[k]))
}

/// The strain where the stress first reaches `s` in `from..=to`, linearly
/// interpolated.
pub fn at_stress(strain: &[f64], stress: &[f64], from: usize, to: usize, s: f64) -> Option<f64> {
    crossing(stress, from, to, s).map(|(k, t)| strain[k] + t * (strain[k + 1] - strain[k]))
}

/// The first k in `from..to` with v[k] < level ≤ v[k+1], and the fraction
/// t of the way from k to k+1 where v reaches it.
fn crossing(v: &[f64], from: usize, to: usize, level: f64) -> Option<(usize, f64)> {
    if to >= v.len() {
        return None;
    }
    (from..to).find_map(|k| {
        (v[k] < level && v[k + 1] >= level).then(|| (k, (level - v[k]) / (v[k + 1] - v[k])))
    })
}

/// Running mean and co-moments of (x, y) with O(1) add and remove.
#[derive(Default)]
struct Moments {
    n: f64,
    mx: f64,
    my: f64,
    cxx: f64,
    cxy: f64,
}

impl Moments {
    fn add(&mut self, x: f64, y: f64) {
        self.n += 1.0;
        let dx = x - self.mx;
        self.mx += dx / self.n;
        self.my += (y - self.my) / self.n;
        self.cxx += dx * (x - self.mx);
        self.cxy += dx * (y - self.my);
    }
    fn remove(&mut self, x: f64, y: f64) {
        if self.n <= 1.0 {
            *self = Moments::default();
            return;
        }
        let dx = x - self.mx;
        self.n -= 1.0;
        self.mx -= dx / self.n;
        self.my -= (y - self.my) / self.n;
        self.cxx -= dx * (x - self.mx);
        self.cxy -= dx * (y - self.my);
    }
    fn slope(&self) -> Option<f64> {
        (self.cxx > 0.0).then(|| self.cxy / self.cxx)
    }
}

/// Least-squares slope of y on x; `None` when x is constant.
fn slope(x: &[f64], y: &[f64]) -> Option<f64> {
    let n = x.len() as f64;
    let mx = x.iter().sum::<f64>() / n;
    let my = y.iter().sum::<f64>() / n;
    let (mut sxx, mut sxy) = (0.0, 0.0);
    for (a, b) in x.iter().zip(y) {
        sxx += (a - mx) * (a - mx);
        sxy += (a - mx) * (b - my);
    }
    (sxx > 0.0).then(|| sxy / sxx)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn steepest_straight_part_is_found() {
        // σ = 10 GPa · ε up to ε = 0.02, then 1 GPa · ε (plastic)
        let e: Vec<f64> = (0..=100).map(|i| i as f64 * 0.001).collect();
        let s: Vec<f64> = e
            .iter()
            .map(|&e| {
                if e <= 0.02 {
                    10e9 * e
                } else {
                    2e8 + 1e9 * (e - 0.02)
                }
            })
            .collect();
        let m = max_slope_modulus(&e, &s, 0, 100, 0.01).unwrap();
        // exact on the linear part: rounding of the sums only
        assert!((m / 10e9 - 1.0).abs() < 1e-9, "{m}");
        assert_eq!(max_slope_modulus(&e, &s, 0, 3, 0.01), None);
        assert_eq!(max_slope_modulus(&e, &s, 0, 100, 0.0), None);
    }

    /// Every class window on a bilinear curve whose slopes are known: the
    /// elastic line 10 GPa to 200 MPa, then 1 GPa to 400 MPa.
    #[test]
    fn class_windows_give_their_closed_forms() {
        let e: Vec<f64> = (0..=2200).map(|i| i as f64 * 1e-4).collect();
        let s: Vec<f64> = e
            .iter()
            .map(|&e| {
                if e <= 0.02 {
                    10e9 * e
                } else {
                    2e8 + 1e9 * (e - 0.02)
                }
            })
            .collect();
        let to = s.len() - 1; // σ_m = 400 MPa at ε = 0.22
        let m = |w| of_class(w, &e, &s, 0, to, 0.01).0.unwrap();
        assert!((m(Window::Strain(0.0005, 0.0025)) / 10e9 - 1.0).abs() < 1e-9);
        // 10–40 % of 400 MPa: 40–160 MPa, on the elastic line
        assert!((m(Window::StressFraction(0.1, 0.4)) / 10e9 - 1.0).abs() < 1e-9);
        // secant at ε = 0.1: σ = 200 + 80 = 280 MPa
        assert!((m(Window::Secant(0.1)) / 2.8e9 - 1.0).abs() < 1e-9);
        // chord from ε = 5e-5 (0.5 MPa) to 160 MPa (ε = 0.016)
        assert!((m(Window::Chord(50e-6, 0.4)) / 10e9 - 1.0).abs() < 1e-9);
        assert!(m(Window::MaxSlope) > 9.99e9);
        // a curve that never reaches the window has no modulus
        assert_eq!(of_class(Window::Secant(1.0), &e, &s, 0, to, 0.01).0, None);
    }
}
