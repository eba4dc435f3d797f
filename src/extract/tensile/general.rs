//! General tensile analysis beside the knot analysis (MODELS.md §9): the
//! values a materials lab reports for any specimen, fibre or coupon.
//!
//! # Definitions
//! - **Maximum stress** σ_m = max σ over the whole record (ISO 6892-1 Rm,
//!   "tensile strength" when the specimen broke after it), and the maximum
//!   force F_m = σ_m · A when the section area A is known. Reported also when
//!   the record ends at or before its peak (a test stopped at the maximum);
//!   the status then says that no fracture was recorded.
//! - **Modulus** E: either the least-squares slope over a *stated stress
//!   window* [σ_lo, σ_hi] of the first loading (the samples from ε ≥ 0 up to
//!   where σ first exceeds σ_hi, keeping those with σ ≥ σ_lo): the
//!   regression method of ISO 6892-1 Annex G and ASTM E111, with the window
//!   chosen in the linear part of the material's curve; or, without a
//!   stated window, the window of the material class ([`super::class`]);
//!   without a class, the steepest least-squares slope over sliding strain
//!   windows ([`super::modulus`]). The method and window are written with
//!   the value.
//! - **Offset yield** R_p0.2 (ISO 6892-1; ASTM E8 "offset method"): the
//!   stress where the curve first meets the line σ = E (ε − 0.002) at a
//!   positive stress, searched from the start of the final loading
//!   ([`loading_start`]) to the maximum stress, linearly interpolated
//!   between the two samples that bracket the crossing. The strain origin is
//!   the file's (ε = 0 at the start of the test).
//! - **Upper and lower yield** R_eH, R_eL (ISO 6892-1 §3.10.2), where the
//!   final loading has a yield drop: R_eH is the maximum before the first drop of at
//!   least `max(drop_min_fraction · σ_m, noise_factor · σ_noise)` that occurs
//!   before σ_m; R_eL the lowest stress after it until the curve climbs back
//!   above R_eH (initial transient effects are not excluded).
//!
//! # Assumptions
//! - Strain increases through the test. A record whose strain decreases
//!   (end below start, the record reversed or the strain sign flipped) is
//!   refused by [`is_reversed`] rather than given a negative modulus.

use super::class::{Direction, MaterialClass, Window};
use super::modulus::of_class;
use super::params::TensileParams;
use crate::signal::stats;

/// What the general analysis found; `None` where not available.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct GeneralFeatures {
    /// Maximum stress σ_m over the whole record, Pa.
    pub max_stress_pa: Option<f64>,
    /// Maximum force F_m, N: the file's force channel's largest magnitude
    /// in the test's direction, else σ_m times the section (set with the
    /// specimen, [`super::batch`]).
    pub max_force_n: Option<f64>,
    /// Tension or compression (values are magnitudes either way).
    pub direction: Direction,
    /// Strain at σ_m.
    pub strain_at_max_stress: Option<f64>,
    /// 0.2 % offset yield stress R_p0.2, Pa.
    pub yield_stress_pa: Option<f64>,
    /// Strain at R_p0.2.
    pub yield_strain: Option<f64>,
    /// Upper yield stress R_eH, Pa (a yield drop only).
    pub upper_yield_pa: Option<f64>,
    /// Lower yield stress R_eL, Pa (a yield drop only).
    pub lower_yield_pa: Option<f64>,
    /// Modulus E, Pa, by `modulus_method`.
    pub modulus_pa: Option<f64>,
    /// How E was obtained (`stress window 20–50 MPa`, `max slope …`).
    pub modulus_method: Option<String>,
}

/// The general features of a curve (module definitions). The modulus is
/// taken on the stated stress window of `p` when there is one, else on the
/// window of `class` ([`super::class`]), else by the steepest slope. Yield
/// values are for unknotted specimens of a class that yields
/// ([`MaterialClass::yields`]): a knotted fibre's curve is the knot's
/// sliding, an elastomer's or a concrete's has no yield point (the load
/// cycles of a concrete modulus test are not yield drops).
pub fn analyze_general(
    strain: &[f64],
    stress: &[f64],
    knotted: bool,
    class: Option<MaterialClass>,
    p: &TensileParams,
) -> GeneralFeatures {
    let mut g = GeneralFeatures::default();
    let Some(m) = max_index(stress) else {
        return g;
    };
    g.max_stress_pa = Some(stress[m]);
    g.strain_at_max_stress = Some(strain[m]);
    let Some(start) = strain.iter().position(|e| *e >= 0.0) else {
        return g;
    };
    let (e, method) = match p.modulus_stress_window_mpa {
        Some([lo, hi]) => (
            window_modulus(strain, stress, lo * 1e6, hi * 1e6),
            format!("regression over {lo}–{hi} MPa of the first loading"),
        ),
        None => {
            let window = class.map_or(Window::MaxSlope, MaterialClass::window);
            of_class(
                window,
                strain,
                stress,
                start,
                m.max(start),
                p.modulus_window,
            )
        }
    };
    (g.modulus_pa, g.modulus_method) = (e, Some(method));
    if knotted || m < start || !class.is_none_or(MaterialClass::yields) {
        return g;
    }
    // The yield lies on the final loading: a preload, a heating phase or a
    // compressive grip before it holds no yield point (a hot tensile test
    // met the offset line at −8.2 MPa there, in its pre-load).
    let from = loading_start(stress, start, m);
    if let Some((e, s)) = g
        .modulus_pa
        .and_then(|e| offset_yield(strain, stress, from, m, e, p.yield_offset))
    {
        (g.yield_strain, g.yield_stress_pa) = (Some(e), Some(s));
    }
    let drop = min_drop(stress, stress[m], p.drop_min_fraction, p.noise_factor);
    if let Some((upper, lower)) = yield_drop(stress, from, m, drop) {
        (g.upper_yield_pa, g.lower_yield_pa) = (Some(upper), Some(lower));
    }
    g
}

/// The start of the final loading in `start..=m`: the last sample before
/// the maximum `m` at which the stress is at or below its level at
/// `start` (and at most zero when it starts negative). A curve that rises
/// from its first sample starts there; one with a pre-load phase (a hot
/// test holding its grips, slack taken up and released) starts at its
/// foot.
pub fn loading_start(stress: &[f64], start: usize, m: usize) -> usize {
    let level = stress[start].max(0.0);
    (start..=m)
        .rev()
        .find(|&i| stress[i] <= level)
        .unwrap_or(start)
}

/// Index of the maximum stress, the first one when it repeats.
pub fn max_index(stress: &[f64]) -> Option<usize> {
    let mut best: Option<usize> = None;
    for (i, s) in stress.iter().enumerate() {
        if s.is_finite() && best.is_none_or(|b| *s > stress[b]) {
            best = Some(i);
        }
    }
    best
}

/// Whether the strain runs backwards: the mean of the last tenth of the
/// record is below the mean of the first tenth (a tensile record goes from
/// slack or zero to its largest strain).
pub fn is_reversed(strain: &[f64]) -> bool {
    let n = strain.len();
    if n < 4 {
        return false;
    }
    let k = (n / 10).max(2);
    let head = stats::mean(&strain[..k]).unwrap_or(0.0);
    let tail = stats::mean(&strain[n - k..]).unwrap_or(0.0);
    tail < head
}

/// Least-squares slope of σ on ε over the stated stress window of the first
/// loading (see the module's definition). `None` with fewer than 3 samples
/// in the window or a constant strain.
pub fn window_modulus(strain: &[f64], stress: &[f64], lo_pa: f64, hi_pa: f64) -> Option<f64> {
    let start = strain.iter().position(|e| *e >= 0.0)?;
    let end = stress[start..]
        .iter()
        .position(|s| *s > hi_pa)
        .map_or(stress.len(), |k| start + k);
    let pts: Vec<(f64, f64)> = (start..end)
        .filter(|&i| stress[i] >= lo_pa)
        .map(|i| (strain[i], stress[i]))
        .collect();
    if pts.len() < 3 {
        return None;
    }
    let n = pts.len() as f64;
    let me = pts.iter().map(|p| p.0).sum::<f64>() / n;
    let ms = pts.iter().map(|p| p.1).sum::<f64>() / n;
    let see: f64 = pts.iter().map(|p| (p.0 - me).powi(2)).sum();
    let ses: f64 = pts.iter().map(|p| (p.0 - me) * (p.1 - ms)).sum();
    (see > 0.0).then(|| ses / see)
}

/// The offset yield point (strain, stress): the first crossing of the curve
/// with σ = E (ε − offset) in `from..=to` at a positive stress,
/// interpolated linearly. `None` when E ≤ 0 or the curve never crosses the
/// line.
pub fn offset_yield(
    strain: &[f64],
    stress: &[f64],
    from: usize,
    to: usize,
    modulus_pa: f64,
    offset: f64,
) -> Option<(f64, f64)> {
    if modulus_pa.is_nan() || modulus_pa <= 0.0 || to >= strain.len() {
        return None;
    }
    let g = |i: usize| stress[i] - modulus_pa * (strain[i] - offset);
    (from..to).find_map(|k| {
        let (a, b) = (g(k), g(k + 1));
        let t = a / (a - b);
        let point = (
            strain[k] + t * (strain[k + 1] - strain[k]),
            stress[k] + t * (stress[k + 1] - stress[k]),
        );
        // a yield point is a positive stress: the line can also meet a
        // curve that dips below zero (unloaded grips)
        (a > 0.0 && b <= 0.0 && point.1 > 0.0).then_some(point)
    })
}

/// Upper and lower yield (R_eH, R_eL) of a curve with a yield drop before
/// its maximum at `to`; `None` without such a drop. A fall below half the
/// upper yield is an unloading (the load cycles of a modulus test), not a
/// yield drop.
pub fn yield_drop(stress: &[f64], from: usize, to: usize, min_drop: f64) -> Option<(f64, f64)> {
    if to >= stress.len() || from > to || min_drop.is_nan() || min_drop <= 0.0 {
        return None;
    }
    let mut peak = from;
    for k in from..=to {
        if stress[k] > stress[peak] {
            peak = k;
        } else if stress[peak] - stress[k] >= min_drop {
            let upper = stress[peak];
            let lower = stress[k..=to]
                .iter()
                .take_while(|s| **s <= upper)
                .copied()
                .fold(f64::INFINITY, f64::min);
            return (lower >= 0.5 * upper).then_some((upper, lower));
        }
    }
    None
}

/// The smallest drop counted as a yield drop: the larger of a fraction of
/// the maximum stress and a multiple of the noise standard deviation.
pub fn min_drop(stress: &[f64], max_pa: f64, fraction: f64, noise_factor: f64) -> f64 {
    let noise = stats::noise_sigma(stress).unwrap_or(0.0);
    (fraction * max_pa).max(noise_factor * noise)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Elastic E = 200 GPa to 200 MPa, then hardening 2 GPa: the 0.2 %
    /// line meets it where 200e9 (ε − 0.002) = 200e6 + 2e9 (ε − 0.001),
    /// ε = 0.002 · 199/198 + …, solved exactly below.
    #[test]
    fn offset_yield_of_a_bilinear_curve_is_its_closed_form() {
        let e: Vec<f64> = (0..=4000).map(|i| i as f64 * 1e-5).collect();
        let s: Vec<f64> = e
            .iter()
            .map(|&e| {
                if e <= 0.001 {
                    200e9 * e
                } else {
                    200e6 + 2e9 * (e - 0.001)
                }
            })
            .collect();
        let (ey, sy) = offset_yield(&e, &s, 0, e.len() - 1, 200e9, 0.002).unwrap();
        // 200e9 ε − 400e6 = 198e6 + 2e9 ε  →  ε = 598e6 / 198e9
        let exact = 598e6 / 198e9;
        assert!((ey - exact).abs() < 1e-12, "{ey} {exact}");
        assert!((sy - (198e6 + 2e9 * exact)).abs() < 1e-3, "{sy}");
        assert!((window_modulus(&e, &s, 20e6, 150e6).unwrap() / 200e9 - 1.0).abs() < 1e-9);
        assert_eq!(yield_drop(&s, 0, e.len() - 1, 1e6), None);
    }

    /// A yield drop: up to 250 MPa, down to 230 MPa, a plateau, then
    /// hardening to 300 MPa.
    #[test]
    fn upper_and_lower_yield_of_a_drop() {
        let mut s: Vec<f64> = (0..=25).map(|i| i as f64 * 10e6).collect();
        s.extend([240e6, 230e6, 232e6, 231e6, 235e6, 260e6, 280e6, 300e6]);
        let to = max_index(&s).unwrap();
        assert_eq!(yield_drop(&s, 0, to, 5e6), Some((250e6, 230e6)));
        // an unloading to 10 MPa and back is no yield drop
        let mut c: Vec<f64> = (0..=25).map(|i| i as f64 * 10e6).collect();
        c.extend([100e6, 10e6, 150e6, 300e6]);
        assert_eq!(yield_drop(&c, 0, c.len() - 1, 5e6), None);
    }

    #[test]
    fn reversed_strain_is_recognised() {
        let up: Vec<f64> = (0..100).map(|i| i as f64 * 1e-3).collect();
        let down: Vec<f64> = up.iter().rev().copied().collect();
        assert!(!is_reversed(&up));
        assert!(is_reversed(&down));
    }
}
