//! Height parameters of a profile (ISO 4287 / ISO 4288, DIN 4768) and of a
//! map (ISO 25178-2), MODELS.md §9.
//!
//! With z the heights after detrending/filtering (reference line z = 0) over
//! the evaluation length:
//!
//! | parameter | formula |
//! |---|---|
//! | Rp (Sp) | max z: highest peak above the reference line |
//! | Rv (Sv) | −min z: deepest valley below it, as a positive depth |
//! | Rt (Sz for maps) | Rp + Rv over the whole evaluation length (area) |
//! | Rz (ISO 4287/4288) | mean over the sampling lengths lr of (max z − min z) in each |
//! | Rz DIN (DIN 4768) | the evaluation length cut into five equal parts; mean of (max z − min z) in each |
//!
//! The two Rz differ only in how the length is cut: ISO uses the sampling
//! length lr, which ISO 4288 ties to the filter cut-off (lr = λc), and counts
//! the whole sampling lengths that fit the evaluated length (five for the
//! standard 5 λc, four after the filter discarded λc/2 at each end of a
//! 5 λc trace); DIN always uses five equal parts. Without a filter, lr is
//! the evaluated length / 5 and the two coincide.

/// Number of parts of the DIN 4768 Rz, and of ISO 4288's default
/// evaluation length in sampling lengths.
pub const SEGMENTS: usize = 5;

/// Height parameters of one profile or map (m).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Heights {
    /// Rp (Sp): max z.
    pub peak: f64,
    /// Rv (Sv): −min z (≥ 0 whenever the reference line is inside the data).
    pub valley: f64,
    /// Rt (Sz): peak + valley.
    pub total: f64,
    /// Rz by ISO 4287/4288 (profiles only); `None` when the evaluated length
    /// holds no whole sampling length.
    pub rz_iso: Option<f64>,
    /// Whole sampling lengths behind [`Heights::rz_iso`].
    pub rz_sampling_lengths: usize,
    /// Rz by DIN 4768 (profiles only); `None` with fewer than five points.
    pub rz_din: Option<f64>,
}

/// Largest and smallest measured value (NaN is a point not measured, and
/// `f64::max`/`min` pass it over); (−∞, +∞) when none is measured.
fn extremes(z: &[f64]) -> (f64, f64) {
    z.iter()
        .fold((f64::NEG_INFINITY, f64::INFINITY), |(hi, lo), &v| {
            (hi.max(v), lo.min(v))
        })
}

/// Peak-to-valley height max z − min z over the measured points of a
/// slice; `None` when none is measured.
pub fn peak_to_valley(z: &[f64]) -> Option<f64> {
    let (hi, lo) = extremes(z);
    (hi >= lo).then_some(hi - lo)
}

/// Mean of the peak-to-valley heights of the parts that hold a measured
/// point (a part entirely in a gap has no peak or valley), and how many
/// they are.
fn mean_over_parts<'a>(parts: impl Iterator<Item = &'a [f64]>) -> Option<(f64, usize)> {
    let (sum, count) = parts
        .filter_map(peak_to_valley)
        .fold((0.0, 0usize), |(s, k), v| (s + v, k + 1));
    (count > 0).then(|| (sum / count as f64, count))
}

/// DIN 4768 Rz: `z` cut into five parts of equal point count (the first
/// n mod 5 parts one point longer, so every point belongs to a part), the
/// mean of their peak-to-valley heights. `None` with fewer than five
/// points, or when a part holds no measured point (DIN's mean is over five
/// parts).
pub fn rz_din(z: &[f64]) -> Option<f64> {
    let n = z.len();
    if n < SEGMENTS {
        return None;
    }
    let (base, extra) = (n / SEGMENTS, n % SEGMENTS);
    let mut start = 0;
    let parts = (0..SEGMENTS).map(|k| {
        let len = base + usize::from(k < extra);
        start += len;
        &z[start - len..start]
    });
    mean_over_parts(parts).and_then(|(v, k)| (k == SEGMENTS).then_some(v))
}

/// ISO 4287/4288 Rz with sampling length `lr` (m) on heights spaced `dx`:
/// the mean of max − min over the whole sampling lengths that fit, counted
/// from the start; a sampling length is round(lr / dx) points. Returns the
/// value and the number of sampling lengths used (one entirely in a gap of
/// points not measured is left out), `None` when none fits (or a sampling
/// length would be a single point).
pub fn rz_iso(z: &[f64], dx: f64, lr: f64) -> Option<(f64, usize)> {
    let len = (lr / dx).round();
    if len.is_nan() || len < 2.0 || len > z.len() as f64 {
        return None;
    }
    mean_over_parts(z.chunks_exact(len as usize))
}

/// Heights of a profile. `sampling_length` is ISO's lr (m), `None` for the
/// evaluated length / 5 (no filter).
pub fn profile_heights(z: &[f64], dx: f64, sampling_length: Option<f64>) -> Heights {
    let (hi, lo) = extremes(z);
    let iso = match sampling_length {
        Some(lr) => rz_iso(z, dx, lr),
        // Five equal parts: the DIN cut, so the two coincide by definition.
        None => rz_din(z).map(|v| (v, SEGMENTS)),
    };
    Heights {
        peak: hi,
        valley: -lo,
        total: hi - lo,
        rz_iso: iso.map(|v| v.0),
        rz_sampling_lengths: iso.map_or(0, |v| v.1),
        rz_din: rz_din(z),
    }
}

/// Heights of a map: Sp, Sv and Sz = Sp + Sv (ISO 25178-2); no Rz.
pub fn map_heights(z: &[f64]) -> Heights {
    let (hi, lo) = extremes(z);
    Heights {
        peak: hi,
        valley: -lo,
        total: hi - lo,
        rz_iso: None,
        rz_sampling_lengths: 0,
        rz_din: None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    /// A sin(2π x / λ) with `per` points per period (a multiple of 4, so
    /// that samples fall on the crests and troughs) over `periods` periods.
    fn sine(a: f64, per: usize, periods: usize) -> Vec<f64> {
        (0..per * periods)
            .map(|i| a * (2.0 * PI * i as f64 / per as f64).sin())
            .collect()
    }

    // Tolerances: the crest sample is sin(π/2) = 1 to within one ulp, so the
    // heights are A to ~1e-16 relative; 1e-12 leaves room for the sums.
    const TOL: f64 = 1e-12;

    #[test]
    fn sinusoid_closed_forms() {
        let a = 2.5e-6;
        let z = sine(a, 400, 10);
        let h = profile_heights(&z, 1e-6, None);
        assert!((h.peak - a).abs() < TOL * a, "Rp {}", h.peak);
        assert!((h.valley - a).abs() < TOL * a, "Rv {}", h.valley);
        assert!((h.total - 2.0 * a).abs() < TOL * a, "Rt {}", h.total);
        // Each fifth holds two whole periods: a crest and a trough.
        assert!((h.rz_din.unwrap() - 2.0 * a).abs() < TOL * a);
        assert!((h.rz_iso.unwrap() - 2.0 * a).abs() < TOL * a);
        assert_eq!(h.rz_sampling_lengths, 5);
    }

    #[test]
    fn din_is_the_mean_of_five_parts_and_rt_the_largest() {
        // Five parts of 2 periods each with amplitudes 1..5 µm.
        let z: Vec<f64> = (1..=5).flat_map(|k| sine(k as f64 * 1e-6, 40, 2)).collect();
        let h = profile_heights(&z, 1e-6, None);
        // Mean of 2·(1+2+3+4+5)/5 µm = 6 µm; Rt = 2·5 µm; Rp = Rv = 5 µm.
        assert!((h.rz_din.unwrap() - 6e-6).abs() < 1e-18);
        assert!((h.total - 10e-6).abs() < 1e-18);
        assert!((h.peak - 5e-6).abs() < 1e-18 && (h.valley - 5e-6).abs() < 1e-18);
    }

    #[test]
    fn iso_counts_whole_sampling_lengths_and_differs_from_din() {
        // 400 points, dx = 1: lr = 100 points gives four sampling lengths,
        // DIN cuts five parts of 80. Heights: a ramp 0..399, so every run of
        // m points spans m − 1.
        let z: Vec<f64> = (0..400).map(|i| i as f64).collect();
        let (rz, count) = rz_iso(&z, 1.0, 100.0).unwrap();
        assert_eq!(count, 4);
        assert!((rz - 99.0).abs() < 1e-12);
        assert!((rz_din(&z).unwrap() - 79.0).abs() < 1e-12);
        // 90-point sampling lengths: four fit, the 40 left over are unused.
        let (rz, count) = rz_iso(&z, 1.0, 90.0).unwrap();
        assert_eq!(count, 4);
        assert!((rz - 89.0).abs() < 1e-12);
        assert!(rz_iso(&z, 1.0, 500.0).is_none());
    }

    #[test]
    fn din_spreads_a_remainder_over_the_first_parts() {
        // 7 points: parts of 2, 2, 1, 1, 1 points; ramp heights give
        // peak-to-valley 1, 1, 0, 0, 0.
        let z: Vec<f64> = (0..7).map(|i| i as f64).collect();
        assert!((rz_din(&z).unwrap() - 0.4).abs() < 1e-15);
        assert!(rz_din(&z[..4]).is_none());
    }

    #[test]
    fn map_sz_is_peak_plus_pit() {
        let z = [0.5, -1.5, 2.0, 0.0];
        let h = map_heights(&z);
        // Exact: sums and signs of binary fractions.
        assert_eq!(
            [h.peak, h.valley, h.total].map(f64::to_bits),
            [2.0, 1.5, 3.5].map(f64::to_bits)
        );
        assert!(h.rz_iso.is_none() && h.rz_din.is_none());
    }
}
