//! The bearing-ratio (Abbott–Firestone) curve and the contact length it
//! implies (thesis Eq. 3.14, 3.15; MODELS.md §4).
//!
//! # Bearing curve
//! The material ratio Rmr(c) is the fraction of the evaluation length (or
//! area) where the surface is at or above height c; the bearing curve is its
//! inverse, c(Rmr). Point-based: with the n heights sorted from highest to
//! lowest, h₀ ≥ … ≥ h₍ₙ₋₁₎, c(Rmr) is the linear interpolation of that
//! sequence at position Rmr·(n − 1). So c(0) is the highest peak and c(1)
//! the deepest valley; heights are relative to the reference line.
//!
//! # Contact length (Eq. 3.14, 3.15)
//!
//! | symbol | meaning | field / unit |
//! |---|---|---|
//! | σ | nominal pressure | [`ContactParams::nominal_pressure`], Pa |
//! | H | hardness of the softer body | [`ContactParams::hardness`], Pa |
//! | ΔA | A_real / A_nom = σ / H (Eq. 3.14) | [`ContactEstimate::area_ratio`] |
//! | d | indentation depth: c(0) − c(ΔA) | [`ContactEstimate::depth`], m |
//! | Rdq | RMS slope (as a slope, not an angle) | argument |
//! | a | contact length 2 d / tan(Rdq) (Eq. 3.15) | [`ContactEstimate::length`], m |
//!
//! Assumptions (thesis Ch. 3): the surface is modelled as symmetric wedge
//! asperities with the RMS slope of the real surface; the real contact area
//! is N/H (fully plastic), the nominal one N/σ. Valid for 0 < σ < H.

use super::params::ContactParams;

/// Heights sorted from highest to lowest (a copy; NaN-free input).
pub fn sorted_descending(z: &[f64]) -> Vec<f64> {
    let mut s = z.to_vec();
    s.sort_unstable_by(|a, b| b.total_cmp(a));
    s
}

/// c(Rmr) on heights sorted from highest to lowest; `mr` is clamped to
/// [0, 1].
pub fn height_at_ratio(sorted_desc: &[f64], mr: f64) -> f64 {
    let n = sorted_desc.len();
    if n == 1 {
        return sorted_desc[0];
    }
    let pos = mr.clamp(0.0, 1.0) * (n - 1) as f64;
    let i = (pos.floor() as usize).min(n - 2);
    let t = pos - i as f64;
    sorted_desc[i] + t * (sorted_desc[i + 1] - sorted_desc[i])
}

/// The bearing curve at `points` equally spaced material ratios from 0 to 1:
/// pairs (Rmr, c(Rmr)).
pub fn bearing_curve(sorted_desc: &[f64], points: usize) -> Vec<(f64, f64)> {
    (0..points)
        .map(|k| {
            let mr = k as f64 / (points - 1) as f64;
            (mr, height_at_ratio(sorted_desc, mr))
        })
        .collect()
}

/// Result of Eq. 3.14–3.15.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactEstimate {
    /// ΔA = σ / H (1).
    pub area_ratio: f64,
    /// d = c(0) − c(ΔA), the depth below the highest peak at which the
    /// material ratio equals ΔA (m).
    pub depth: f64,
    /// a = 2 d / tan(Rdq) (m).
    pub length: f64,
}

/// Contact length from the bearing curve and the RMS slope (a slope, i.e.
/// tan of the Rdq angle). `None` when the RMS slope is zero (a flat surface
/// has no wedge asperities).
pub fn contact_length(
    sorted_desc: &[f64],
    rms_slope: f64,
    params: &ContactParams,
) -> Option<ContactEstimate> {
    if !(rms_slope.is_finite() && rms_slope > 0.0) {
        return None;
    }
    let area_ratio = params.nominal_pressure / params.hardness;
    let depth = height_at_ratio(sorted_desc, 0.0) - height_at_ratio(sorted_desc, area_ratio);
    Some(ContactEstimate {
        area_ratio,
        depth,
        length: 2.0 * depth / rms_slope,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn triangle_wave_gives_a_linear_bearing_curve() {
        // A symmetric triangle wave sampled uniformly has uniformly
        // distributed heights, so c(Rmr) = A − 2A·Rmr exactly at the sample
        // heights; between them the interpolation error is at most one
        // height step, 4A/period = 0.02 A here.
        let a = 1e-6;
        let period = 200;
        let z: Vec<f64> = (0..10 * period)
            .map(|i| {
                let p = (i % period) as f64 / period as f64;
                a * (4.0 * (p - 0.5).abs() - 1.0)
            })
            .collect();
        let s = sorted_descending(&z);
        for (mr, h) in bearing_curve(&s, 51) {
            let expect = a - 2.0 * a * mr;
            assert!((h - expect).abs() <= 0.02 * a, "mr {mr}: {h} vs {expect}");
        }
    }

    #[test]
    fn contact_length_of_a_triangle_wave_matches_the_wedge_geometry() {
        // Triangle wave of amplitude A, period λ: slope ±4A/λ everywhere, so
        // Rdq = 4A/λ. Heights uniform on [−A, A]: d = 2A·ΔA. Then
        // a = 2d/Rdq = ΔA·λ, the width of the wedge tips at depth d,
        // summed over both flanks of one period: the wedge geometry itself.
        let a = 1e-6;
        let period = 1000;
        let dx = 1e-7;
        let lambda = period as f64 * dx;
        let z: Vec<f64> = (0..20 * period)
            .map(|i| {
                let p = (i % period) as f64 / period as f64;
                a * (4.0 * (p - 0.5).abs() - 1.0)
            })
            .collect();
        let s = sorted_descending(&z);
        let c = ContactParams::new(0.085e6, 17.0e6).unwrap();
        let est = contact_length(&s, 4.0 * a / lambda, &c).unwrap();
        let da = 0.085 / 17.0;
        // Height quantisation: one step of 4A/period = 0.004 A in d.
        assert!((est.depth - 2.0 * a * da).abs() < 0.004 * a);
        assert!((est.length - da * lambda).abs() < 0.004 * a / (4.0 * a / lambda) * 2.0);
        assert!(contact_length(&s, 0.0, &c).is_none());
    }
}
