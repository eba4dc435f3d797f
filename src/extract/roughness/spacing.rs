//! RSm, the mean width of the profile elements (ISO 4287, MODELS.md §10).
//!
//! A profile element is a profile peak (the part above the mean line
//! between two crossings of it) and the adjacent valley (below). A peak
//! counts when its height reaches the height discrimination (10 % of Rz)
//! and its width the width discrimination (1 % of the sampling length); a
//! valley likewise with its depth. Parts that do not count belong to the
//! element they sit in (hysteresis): an element starts at the up-crossing
//! of the mean line before a counting peak, once a counting valley has
//! followed the previous element's peak, and RSm is the mean distance
//! between consecutive element starts. Crossings are interpolated linearly
//! between samples (exact for a sine's inflection points to O(Δx³)).
//!
//! Points not measured break the profile: an element that would span a
//! gap is left out, the next one starts after it.

/// One part of the profile between crossings of the mean line.
#[derive(Debug, Clone, Copy)]
struct Part {
    /// Interpolated start (samples).
    start: f64,
    /// Width (samples).
    width: f64,
    /// Largest |z| in the part, signed by the side.
    extreme: f64,
    /// Whether a gap (or the profile's start) precedes it.
    after_gap: bool,
}

/// The parts of `z` between crossings of zero, over its measured runs.
fn parts(z: &[f64]) -> Vec<Part> {
    let mut out = Vec::new();
    let mut cur: Option<Part> = None;
    let mut after_gap = true;
    for i in 0..z.len() {
        let v = z[i];
        if v.is_nan() {
            // A part cut by a gap is not a whole part.
            cur = None;
            after_gap = true;
            continue;
        }
        match cur.as_mut() {
            None => {
                // A run starts mid-part: its first part is incomplete and
                // only marks where the next one begins.
                cur = Some(Part {
                    start: f64::NAN,
                    width: 0.0,
                    extreme: v,
                    after_gap,
                });
            }
            Some(p) if (v > 0.0) == (p.extreme > 0.0) || v == 0.0 => {
                if v.abs() > p.extreme.abs() {
                    p.extreme = v;
                }
            }
            Some(p) => {
                let prev = z[i - 1];
                let cross = (i - 1) as f64 + prev / (prev - v);
                if !p.start.is_nan() {
                    p.width = cross - p.start;
                    out.push(*p);
                }
                after_gap = after_gap && p.start.is_nan();
                cur = Some(Part {
                    start: cross,
                    width: 0.0,
                    extreme: v,
                    after_gap,
                });
                after_gap = false;
            }
        }
    }
    out
}

/// RSm (m) of heights `z` about their mean line (z = 0), spacing `dx`,
/// with height discrimination `min_height` (m) and width discrimination
/// `min_width` (m); `None` with fewer than one whole element.
pub fn rsm(z: &[f64], dx: f64, min_height: f64, min_width: f64) -> Option<f64> {
    let counts = |p: &Part| p.extreme.abs() >= min_height && p.width * dx >= min_width;
    let mut starts: Vec<(f64, bool)> = Vec::new();
    let mut valley_seen = true;
    let mut gap_since = false;
    for p in parts(z) {
        gap_since |= p.after_gap;
        if p.after_gap {
            valley_seen = true;
        }
        if !counts(&p) {
            continue;
        }
        if p.extreme > 0.0 && valley_seen {
            starts.push((p.start, gap_since));
            valley_seen = false;
            gap_since = false;
        } else if p.extreme < 0.0 {
            valley_seen = true;
        }
    }
    let widths: Vec<f64> = starts
        .windows(2)
        .filter(|w| !w[1].1)
        .map(|w| (w[1].0 - w[0].0) * dx)
        .collect();
    (!widths.is_empty()).then(|| widths.iter().sum::<f64>() / widths.len() as f64)
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    #[test]
    fn sine_elements_are_its_wavelength() {
        // Phase offset so that no sample falls on a crossing.
        let per = 97.3;
        let z: Vec<f64> = (0..2000)
            .map(|i| (2.0 * PI * (i as f64 + 0.37) / per).sin())
            .collect();
        let r = rsm(&z, 1.0, 0.2, 1.0).unwrap();
        // Linear interpolation of a crossing at an inflection point: error
        // O((2π/97)³) ≈ 3e-4 samples per crossing, averaging out.
        assert!((r - per).abs() < 1e-3 * per, "{r}");
    }

    #[test]
    fn small_wiggles_belong_to_their_element_and_gaps_cut_elements() {
        // A sine of period 100 with a ripple of period 5 and amplitude
        // 0.08, steeper than the sine at its crossings (0.1 against 0.063
        // per sample), so it crosses the mean line several times there:
        // below the height discrimination 0.1, it must not add elements.
        let z: Vec<f64> = (0..3000)
            .map(|i| {
                let x = i as f64 + 0.5;
                (2.0 * PI * x / 100.0).sin() + 0.08 * (2.0 * PI * x / 5.0).sin()
            })
            .collect();
        let r = rsm(&z, 1.0, 0.1, 1.0).unwrap();
        assert!((r - 100.0).abs() < 0.5, "{r}");
        // Without discrimination every ripple crossing makes an element.
        assert!(rsm(&z, 1.0, 0.0, 0.0).unwrap() < 60.0);
        // A gap of 250 samples: the element across it is left out, the
        // others are still 100 wide.
        let mut g = z.clone();
        g[1000..1250].fill(f64::NAN);
        let r = rsm(&g, 1.0, 0.1, 1.0).unwrap();
        assert!((r - 100.0).abs() < 0.5, "{r}");
        assert!(rsm(&z[..120], 1.0, 0.1, 1.0).is_none());
    }
}
