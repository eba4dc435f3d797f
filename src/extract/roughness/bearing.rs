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
use rayon::prelude::*;

/// Heights sorted from highest to lowest (a copy; NaN-free input).
pub fn sorted_descending(z: &[f64]) -> Vec<f64> {
    let mut s = z.to_vec();
    s.sort_unstable_by(|a, b| b.total_cmp(a));
    s
}

/// Heights ranked from highest to lowest: the `i`-th highest of `len`.
/// A sorted slice is one; [`SelectedHeights`] holds only the ranks a
/// bearing curve and a contact estimate read, found by selection.
pub trait Ranked {
    /// Number of heights.
    fn count(&self) -> usize;
    /// The height of rank `i` (0 is the highest).
    fn rank(&self, i: usize) -> f64;
}

impl Ranked for [f64] {
    fn count(&self) -> usize {
        <[f64]>::len(self)
    }
    fn rank(&self, i: usize) -> f64 {
        self[i]
    }
}

impl Ranked for Vec<f64> {
    fn count(&self) -> usize {
        <[f64]>::len(self)
    }
    fn rank(&self, i: usize) -> f64 {
        self[i]
    }
}

/// The heights of the ranks that [`height_at_ratio`] reads at the bearing
/// curve's `points` ratios and at `extra` ratios (the contact estimate's
/// ΔA), found by a multi-way selection (`select_nth_unstable`, splitting
/// the copy at each wanted rank in turn): O(n log k) for k ranks instead of
/// a full O(n log n) sort. The order statistics are those of the sort, bit
/// for bit.
#[derive(Debug, Clone)]
pub struct SelectedHeights {
    len: usize,
    /// (rank, height), ranks ascending.
    picks: Vec<(usize, f64)>,
}

impl Ranked for SelectedHeights {
    fn count(&self) -> usize {
        self.len
    }
    fn rank(&self, i: usize) -> f64 {
        let k = self
            .picks
            .binary_search_by_key(&i, |p| p.0)
            .expect("only selected ranks are read");
        self.picks[k].1
    }
}

/// Selects the ranks of `z` (NaN-free) a bearing curve of `points` points
/// and the material ratios `extra` read.
pub fn select_heights(z: &[f64], points: usize, extra: &[f64]) -> SelectedHeights {
    let n = z.len();
    let mut ranks: Vec<usize> = (0..points)
        .map(|k| ratio_at(k, points))
        .chain(extra.iter().copied())
        .chain([0.0])
        .flat_map(|mr| {
            let (i, _) = position(n, mr);
            [i, (i + 1).min(n.saturating_sub(1))]
        })
        .collect();
    ranks.sort_unstable();
    ranks.dedup();
    let mut picks = match n >= BINNED_FROM {
        true => binned_ranks(z, &ranks),
        false => select_ranks(&mut z.to_vec(), 0, &ranks),
    };
    picks.sort_unstable_by_key(|p| p.0);
    SelectedHeights { len: n, picks }
}

/// From this many heights on, ranks are found by binning ([`binned_ranks`]).
const BINNED_FROM: usize = 1 << 14;

/// Bins of the height range in [`binned_ranks`].
const BINS: usize = 1 << 16;

/// Heights per parallel chunk (fixed: the work split never depends on the
/// thread count, and counts are integers).
const CHUNK: usize = 1 << 18;

/// The heights at `ranks` (descending order) without copying or reordering
/// `z`: one pass bins the heights over their range (the bin is a monotone
/// function of the height), the cumulative counts name the bin of each
/// wanted rank, a second pass collects the heights of those bins only, and
/// each rank is read from its bin sorted by `f64::total_cmp`. Both passes
/// run in fixed chunks on all threads; the heights are the order statistics
/// of the sort, bit for bit.
fn binned_ranks(z: &[f64], ranks: &[usize]) -> Vec<(usize, f64)> {
    let n = z.len();
    // Non-finite heights (none in a validated profile) fall in the end bins.
    let (lo, hi) = crate::signal::scan::finite_range(z).unwrap_or((0.0, 0.0));
    let scale = BINS as f64 / (hi - lo).max(f64::MIN_POSITIVE);
    let bin = |x: f64| (((x - lo) * scale) as usize).min(BINS - 1);
    let counts = z
        .par_chunks(CHUNK)
        .map(|c| {
            let mut h = vec![0u32; BINS];
            c.iter().for_each(|&x| h[bin(x)] += 1);
            h
        })
        .reduce(
            || vec![0u32; BINS],
            |mut a, b| {
                a.iter_mut().zip(&b).for_each(|(x, y)| *x += y);
                a
            },
        );
    // Values below each bin; the ascending rank n - 1 - r of each wanted rank.
    let below: Vec<usize> = counts
        .iter()
        .scan(0usize, |acc, &c| {
            let b = *acc;
            *acc += c as usize;
            Some(b)
        })
        .collect();
    let bin_of = |a: usize| below.partition_point(|&b| b <= a) - 1;
    let mut wanted = vec![false; BINS];
    ranks.iter().for_each(|&r| wanted[bin_of(n - 1 - r)] = true);
    let mut held: Vec<(usize, f64)> = z
        .par_chunks(CHUNK)
        .flat_map_iter(|c| c.iter().map(|&x| (bin(x), x)).filter(|(b, _)| wanted[*b]))
        .collect();
    held.sort_unstable_by(|a, b| a.0.cmp(&b.0).then(a.1.total_cmp(&b.1)));
    let start_of = |b: usize| held.partition_point(|h| h.0 < b);
    ranks
        .iter()
        .map(|&r| {
            let a = n - 1 - r;
            let b = bin_of(a);
            (r, held[start_of(b) + a - below[b]].1)
        })
        .collect()
}

/// Places every rank of `ranks` (ascending, offset by `base`) in `v`
/// (descending order), returning its height: select the middle rank, then
/// each side holds the ranks below and above it. The two sides are disjoint,
/// so a long one is selected in parallel with the other; the heights are
/// order statistics, the same whatever the thread count.
fn select_ranks(v: &mut [f64], base: usize, ranks: &[usize]) -> Vec<(usize, f64)> {
    if ranks.is_empty() || v.is_empty() {
        return Vec::new();
    }
    let mid = ranks.len() / 2;
    let k = ranks[mid] - base;
    let (left, nth, right) = v.select_nth_unstable_by(k, |a, b| b.total_cmp(a));
    let pick = (ranks[mid], *nth);
    let (below, above) = (&ranks[..mid], &ranks[mid + 1..]);
    let (mut picks, more) = match left.len() + right.len() > 1 << 16 {
        true => rayon::join(
            || select_ranks(left, base, below),
            || select_ranks(right, base + k + 1, above),
        ),
        false => (
            select_ranks(left, base, below),
            select_ranks(right, base + k + 1, above),
        ),
    };
    picks.push(pick);
    picks.extend(more);
    picks
}

/// The `k`-th of `points` equally spaced material ratios from 0 to 1.
fn ratio_at(k: usize, points: usize) -> f64 {
    k as f64 / (points - 1) as f64
}

/// Rank and interpolation weight of ratio `mr` among `n` heights.
fn position(n: usize, mr: f64) -> (usize, f64) {
    if n < 2 {
        return (0, 0.0);
    }
    let pos = mr.clamp(0.0, 1.0) * (n - 1) as f64;
    let i = (pos.floor() as usize).min(n - 2);
    (i, pos - i as f64)
}

/// c(Rmr) on heights ranked from highest to lowest; `mr` is clamped to
/// [0, 1].
pub fn height_at_ratio<R: Ranked + ?Sized>(heights: &R, mr: f64) -> f64 {
    let n = heights.count();
    if n == 1 {
        return heights.rank(0);
    }
    let (i, t) = position(n, mr);
    heights.rank(i) + t * (heights.rank(i + 1) - heights.rank(i))
}

/// The bearing curve at `points` equally spaced material ratios from 0 to 1:
/// pairs (Rmr, c(Rmr)).
pub fn bearing_curve<R: Ranked + ?Sized>(heights: &R, points: usize) -> Vec<(f64, f64)> {
    (0..points)
        .map(|k| {
            let mr = ratio_at(k, points);
            (mr, height_at_ratio(heights, mr))
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
pub fn contact_length<R: Ranked + ?Sized>(
    sorted_desc: &R,
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

    /// Selection reads the same heights as the full sort (to 1e-12, in
    /// fact bit for bit) on rough, tied, signed-zero and tiny inputs.
    #[test]
    fn selected_heights_give_the_sorted_curve_and_contact() {
        let c = ContactParams::new(0.085e6, 17.0e6).unwrap();
        let ratio = [c.nominal_pressure / c.hardness];
        let rough = crate::extract::roughness::fractal::synthesize_self_affine(5000, 0.7, 1e-6, 3);
        let ties: Vec<f64> = (0..1001).map(|i| ((i * 7) % 13) as f64 * 1e-7).collect();
        let zeros = vec![0.0, -0.0, 1e-9, -0.0, 0.0, -1e-9];
        // Long enough to be binned: a self-affine profile, and one with
        // heavy ties, signed zeros and a lone outlier (most bins empty).
        let long =
            crate::extract::roughness::fractal::synthesize_self_affine(3 * CHUNK, 0.8, 1e-6, 5);
        let mut tied: Vec<f64> = (0..BINNED_FROM * 3)
            .map(|i| [0.0, -0.0, 1e-7, -2e-7][i % 4] * ((i % 5) as f64))
            .collect();
        tied[17] = 1e-3;
        for z in [
            rough,
            ties,
            zeros,
            vec![2e-6],
            vec![1e-6, -1e-6],
            long,
            tied,
        ] {
            let sorted = sorted_descending(&z);
            for points in [2, 11, 101, 257] {
                let picked = select_heights(&z, points, &ratio);
                let (a, b) = (
                    bearing_curve(&sorted, points),
                    bearing_curve(&picked, points),
                );
                for ((ma, ha), (mb, hb)) in a.iter().zip(&b) {
                    assert_eq!(ma.to_bits(), mb.to_bits());
                    assert!(
                        (ha - hb).abs() <= 1e-12 * ha.abs().max(1e-300),
                        "{ha} vs {hb}"
                    );
                    assert_eq!(ha.to_bits(), hb.to_bits());
                }
                let (ca, cb) = (
                    contact_length(sorted.as_slice(), 0.5, &c),
                    contact_length(&picked, 0.5, &c),
                );
                assert_eq!(ca, cb);
            }
        }
    }

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
