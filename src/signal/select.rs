//! Order statistics without a copy of the data: selections over a source
//! that can be read again (a slice, or values computed from one, such as
//! first differences), so a median of a long trace needs a small buffer
//! instead of a scratch copy as long as the trace (peak memory,
//! `docs/speed.md`).
//!
//! A long input is first bracketed (Floyd & Rivest's selection): a fixed
//! pseudo-random sample of about n^(2/3) values is sorted, and the sample
//! values a few standard errors either side of the wanted rank's place bound
//! it. One pass counts the values below the bracket and collects those
//! inside it (a few per cent of them), and the rank is taken among those.
//! When the bracket misses the rank (improbable: five standard errors) or
//! holds too many ties to collect, a radix selection does the work: each pass
//! counts, among the values whose leading key bits match those already
//! fixed, the next 16 bits of the key that orders `f64` as `f64::total_cmp`
//! does, then fixes the bucket holding the wanted rank; once that bucket
//! holds few values they are collected.
//!
//! Passes read the source in fixed chunks of positions on all threads.
//! Counts are integers and order statistics under a total order are unique,
//! so the value is bit for bit the one a sort would give, whatever the thread
//! count or the path taken.

use rayon::prelude::*;
use std::ops::Range;

/// Key bits fixed per radix pass.
const BITS: u32 = 16;

/// A bucket this small is collected and selected in memory.
const COLLECT: usize = 1 << 16;

/// Positions per parallel chunk: fixed, so that the split of the work does
/// not depend on the thread count (the result never does).
const CHUNK: usize = 1 << 18;

/// The key whose unsigned order is `f64::total_cmp`'s order.
pub(crate) fn key(x: f64) -> u64 {
    let b = x.to_bits() as i64;
    let t = b ^ ((((b >> 63) as u64) >> 1) as i64);
    (t as u64) ^ (1 << 63)
}

/// The value of a key (the inverse of [`key`]).
pub(crate) fn value(k: u64) -> f64 {
    let t = (k ^ (1 << 63)) as i64;
    f64::from_bits((t ^ ((((t >> 63) as u64) >> 1) as i64)) as u64)
}

/// The values at positions `0..positions`: `read(r)` yields those of the
/// positions in `r` (none, one or several per position, the same each time).
pub struct Values<F> {
    /// Number of positions.
    pub positions: usize,
    /// Reads the values of a range of positions.
    pub read: F,
}

impl<F, I> Values<F>
where
    F: Fn(Range<usize>) -> I + Sync,
    I: Iterator<Item = f64>,
{
    /// The chunks of positions, on all threads.
    fn chunks(&self) -> impl IndexedParallelIterator<Item = Range<usize>> {
        let n = self.positions;
        (0..n.div_ceil(CHUNK))
            .into_par_iter()
            .map(move |c| c * CHUNK..((c + 1) * CHUNK).min(n))
    }

    /// The sum over all chunks of `per_chunk`'s result.
    fn sum<T: Send>(
        &self,
        per_chunk: impl Fn(I) -> T + Sync,
        zero: impl Fn() -> T + Sync,
        add: impl Fn(T, T) -> T + Sync,
    ) -> T {
        self.chunks()
            .map(|r| per_chunk((self.read)(r)))
            .reduce(&zero, &add)
    }

    /// Number of values.
    pub fn count(&self) -> usize {
        self.sum(Iterator::count, || 0, |a, b| a + b)
    }

    /// The values whose key lies in `keys`, in no particular order.
    fn collect(&self, keys: (u64, u64)) -> Vec<f64> {
        let parts: Vec<Vec<f64>> = self
            .chunks()
            .map(|r| {
                (self.read)(r)
                    .filter(|&x| (keys.0..=keys.1).contains(&key(x)))
                    .collect()
            })
            .collect();
        parts.concat()
    }

    /// The largest value whose key is below `k`.
    fn max_below(&self, k: u64) -> Option<f64> {
        let most = |i: I| i.map(key).filter(|&kx| kx < k).max();
        self.sum(most, || None, |a, b| a.max(b)).map(value)
    }
}

/// The `k`-th smallest (0-based) of the `n` values of `v`, and the
/// `k - 1`-th when `k > 0`: the two middle values of an even count.
pub fn nth_and_below<F, I>(v: &Values<F>, n: usize, k: usize) -> (f64, Option<f64>)
where
    F: Fn(Range<usize>) -> I + Sync,
    I: Iterator<Item = f64>,
{
    assert!(k < n, "rank {k} of {n} values");
    if n > COLLECT {
        if let Some(found) = bracketed(v, n, k) {
            return found;
        }
    }
    radix(v, n, k)
}

/// A fixed pseudo-random sequence (SplitMix64): the sample is the same
/// for the same input, and does not alias with a periodic signal as a
/// stride would.
fn splitmix(j: u64) -> u64 {
    let mut z = j.wrapping_add(0x9E37_79B9_7F4A_7C15);
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

/// The keys bounding rank `k` of `n`, from a sorted sample; `None` when
/// too few sampled positions hold a value.
fn bracket<F, I>(v: &Values<F>, n: usize, k: usize) -> Option<(u64, u64)>
where
    F: Fn(Range<usize>) -> I + Sync,
    I: Iterator<Item = f64>,
{
    let want = ((n as f64).powf(2.0 / 3.0) as usize).clamp(1 << 10, 1 << 16);
    let positions = v.positions as u64;
    let mut sample: Vec<u64> = (0..want as u64)
        .filter_map(|j| {
            let p = (splitmix(j) % positions) as usize;
            (v.read)(p..p + 1).next().map(key)
        })
        .collect();
    if sample.len() < want / 2 {
        return None;
    }
    sample.sort_unstable();
    let m = sample.len() as f64;
    // The rank's place in the sample, ± 5 standard errors of a binomial.
    let at = (k as f64 + 0.5) / n as f64 * m;
    let d = 2.5 * m.sqrt();
    let lo = match at - d {
        x if x < 0.0 => 0,
        x => sample[x as usize],
    };
    let hi = match at + d {
        x if x >= m - 1.0 => u64::MAX,
        x => sample[x.ceil() as usize],
    };
    Some((lo, hi))
}

/// Rank `k` (and the one below) by a bracket, or `None` when the bracket
/// misses it or holds too many values to collect.
fn bracketed<F, I>(v: &Values<F>, n: usize, k: usize) -> Option<(f64, Option<f64>)>
where
    F: Fn(Range<usize>) -> I + Sync,
    I: Iterator<Item = f64>,
{
    let (lo, hi) = bracket(v, n, k)?;
    let Inside {
        below,
        count,
        values,
    } = v.sum(|i| Inside::of(i, (lo, hi)), Inside::empty, Inside::add);
    if k < below || k >= below + count {
        return None;
    }
    let j = k - below;
    let under = |vals: &[f64]| match (j, k) {
        (_, 0) => None,
        (0, _) => v.max_below(lo),
        _ => vals.iter().copied().max_by(f64::total_cmp),
    };
    if lo == hi {
        let x = value(lo);
        return Some((x, under(&[x])));
    }
    let mut vals = values?; // too many ties to collect
    let (left, mid, _) = vals.select_nth_unstable_by(j, f64::total_cmp);
    let mid = *mid;
    Some((mid, under(left)))
}

/// One pass over a bracket: the values below it counted, those inside it
/// counted and collected (`None` once a chunk holds more of them than a
/// bracket should: ties, left to the radix passes).
struct Inside {
    below: usize,
    count: usize,
    values: Option<Vec<f64>>,
}

impl Inside {
    fn empty() -> Inside {
        Inside {
            below: 0,
            count: 0,
            values: Some(Vec::new()),
        }
    }

    fn of(values: impl Iterator<Item = f64>, (lo, hi): (u64, u64)) -> Inside {
        let cap = CHUNK / 8;
        let mut out = Inside::empty();
        // Half the values fall below a median's bracket, in no order a
        // branch predictor could learn: counted without a branch; the few
        // inside it take the branch.
        let width = hi.wrapping_sub(lo);
        for x in values {
            let kx = key(x);
            out.below += usize::from(kx < lo);
            if kx.wrapping_sub(lo) <= width {
                out.count += 1;
                if let Some(v) = out.values.as_mut() {
                    match v.len() < cap {
                        true => v.push(x),
                        false => out.values = None,
                    }
                }
            }
        }
        out
    }

    fn add(mut self, other: Inside) -> Inside {
        self.below += other.below;
        self.count += other.count;
        self.values = match (self.values, other.values) {
            (Some(mut a), Some(b)) => {
                a.extend(b);
                Some(a)
            }
            _ => None,
        };
        self
    }
}

/// Rank `k` (and the one below) by radix passes over the key.
fn radix<F, I>(v: &Values<F>, n: usize, k: usize) -> (f64, Option<f64>)
where
    F: Fn(Range<usize>) -> I + Sync,
    I: Iterator<Item = f64>,
{
    let rank = k;
    let (mut prefix, mut fixed, mut k, mut count) = (0u64, 0u32, k, n);
    // Whether a key lies in the bucket fixed so far.
    let inside = |kx: u64, prefix: u64, fixed: u32| fixed == 0 || kx >> (64 - fixed) == prefix;
    while count > COLLECT && fixed < 64 {
        let shift = 64 - fixed - BITS;
        let histogram = |i: I| {
            let mut h = vec![0usize; 1 << BITS];
            for kx in i.map(key).filter(|&kx| inside(kx, prefix, fixed)) {
                h[((kx >> shift) & 0xFFFF) as usize] += 1;
            }
            h
        };
        let add = |mut a: Vec<usize>, b: Vec<usize>| {
            a.iter_mut().zip(&b).for_each(|(x, y)| *x += y);
            a
        };
        let hist = v.sum(histogram, || vec![0; 1 << BITS], add);
        let mut below = 0;
        for (b, &c) in hist.iter().enumerate() {
            if k < below + c {
                (prefix, k, count) = ((prefix << BITS) | b as u64, k - below, c);
                break;
            }
            below += c;
        }
        fixed += BITS;
    }
    // The rank's bucket: every value in it, or (all bits fixed) one value.
    let low = if fixed == 0 {
        0
    } else {
        prefix << (64 - fixed)
    };
    let (hi, lower) = match fixed {
        64 => (value(prefix), (k > 0).then(|| value(prefix))),
        _ => {
            // The keys of the bucket: the fixed leading bits, any others.
            let high = low | (u64::MAX >> fixed);
            let mut vals = v.collect((low, high));
            let (left, mid, _) = vals.select_nth_unstable_by(k, f64::total_cmp);
            (*mid, left.iter().copied().max_by(f64::total_cmp))
        }
    };
    if lower.is_some() || rank == 0 {
        return (hi, lower);
    }
    // The rank below is the largest value under the bucket.
    (hi, v.max_below(low))
}

/// The median of the `n` values of `v` (the mean of the two middle ones for
/// an even count), as a sort by `f64::total_cmp` gives it.
pub fn median<F, I>(v: &Values<F>, n: usize) -> Option<f64>
where
    F: Fn(Range<usize>) -> I + Sync,
    I: Iterator<Item = f64>,
{
    if n == 0 {
        return None;
    }
    let (hi, lo) = nth_and_below(v, n, n / 2);
    Some(match n % 2 {
        1 => hi,
        _ => 0.5 * (lo.unwrap_or(hi) + hi),
    })
}

/// A slice read as it is.
pub type SliceRead<'a> = std::iter::Copied<std::slice::Iter<'a, f64>>;

/// The values of a slice, one per position.
pub fn of_slice<'a>(x: &'a [f64]) -> Values<impl Fn(Range<usize>) -> SliceRead<'a> + Sync + 'a> {
    Values {
        positions: x.len(),
        read: move |r: Range<usize>| x[r].iter().copied(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sorted(x: &[f64]) -> Vec<f64> {
        let mut v = x.to_vec();
        v.sort_by(f64::total_cmp);
        v
    }

    /// Every rank of small inputs (ties, signed zeros, infinities, NaN)
    /// equals the sorted copy's, bit for bit, with the rank below it.
    #[test]
    fn every_rank_equals_the_sort() {
        let x = [
            3.0,
            -0.0,
            0.0,
            1.5,
            f64::INFINITY,
            -2.0,
            1.5,
            f64::NEG_INFINITY,
            f64::NAN,
            -f64::NAN,
            1e-310,
            -1e-310,
        ];
        let s = sorted(&x);
        for k in 0..x.len() {
            let (v, below) = nth_and_below(&of_slice(&x), x.len(), k);
            assert_eq!(v.to_bits(), s[k].to_bits(), "rank {k}");
            assert_eq!(
                below.map(f64::to_bits),
                k.checked_sub(1).map(|j| s[j].to_bits())
            );
        }
    }

    /// Long inputs go through the histogram passes: noise around a level
    /// (the buckets of a trace), heavy ties (all bits fixed) and a rank at
    /// the lower edge of its bucket (the rank below found by another pass).
    #[test]
    fn long_inputs_equal_the_sort() {
        let noise = crate::signal::testing::gaussian_noise(300_001, 1.0, 5);
        let level: Vec<f64> = noise.iter().map(|e| 0.5 + 0.01 * e).collect();
        let ties: Vec<f64> = noise.iter().map(|e| (e * 2.0).round()).collect();
        let mut edge = vec![1.0; 200_000];
        edge.extend(vec![2.0; 200_000]);
        for x in [&noise, &level, &ties, &edge] {
            let s = sorted(x);
            for k in [0, 1, x.len() / 3, x.len() / 2, x.len() / 2 - 1, x.len() - 1] {
                let (v, below) = nth_and_below(&of_slice(x), x.len(), k);
                assert_eq!(v.to_bits(), s[k].to_bits(), "rank {k}");
                assert_eq!(
                    below.map(f64::to_bits),
                    k.checked_sub(1).map(|j| s[j].to_bits())
                );
            }
            let m = median(&of_slice(x), x.len()).unwrap();
            let n = s.len();
            let want = match n % 2 {
                1 => s[n / 2],
                _ => 0.5 * (s[n / 2 - 1] + s[n / 2]),
            };
            assert_eq!(m.to_bits(), want.to_bits());
        }
        assert!(median(&of_slice(&[]), 0).is_none());
    }

    /// Both paths give the sort's ranks: the bracket (when it holds the
    /// rank) and the radix passes, on noise, a quantised signal (heavy ties
    /// at the bracket's bounds), a constant, and a source with positions
    /// that hold no value (non-finite differences skipped).
    #[test]
    fn bracket_and_radix_agree_with_the_sort() {
        let noise = crate::signal::testing::gaussian_noise(400_000, 1.0, 9);
        let quantised: Vec<f64> = noise.iter().map(|e| (e * 20.0).round() / 20.0).collect();
        let constant = vec![0.25; 200_000];
        let mut holed = noise.clone();
        for i in (0..holed.len()).step_by(7) {
            holed[i] = f64::NAN;
        }
        let diffs = Values {
            positions: holed.len() - 1,
            read: |r: Range<usize>| {
                holed[r.start..r.end + 1]
                    .windows(2)
                    .map(|w| w[1] - w[0])
                    .filter(|d| d.is_finite())
            },
        };
        let d: Vec<f64> = (diffs.read)(0..diffs.positions).collect();
        assert_eq!(diffs.count(), d.len());
        let mut bracketed_some = 0;
        let check = |all: &[f64], k: usize, v: (f64, Option<f64>)| {
            let s = sorted(all);
            assert_eq!(v.0.to_bits(), s[k].to_bits(), "rank {k}");
            assert_eq!(
                v.1.map(f64::to_bits),
                k.checked_sub(1).map(|j| s[j].to_bits())
            );
        };
        for x in [&noise, &quantised, &constant] {
            let n = x.len();
            for k in [0, 1, n / 100, n / 2 - 1, n / 2, n - 2, n - 1] {
                check(x, k, radix(&of_slice(x), n, k));
                if let Some(b) = bracketed(&of_slice(x), n, k) {
                    bracketed_some += 1;
                    check(x, k, b);
                }
            }
        }
        for k in [0, d.len() / 2, d.len() - 1] {
            check(&d, k, radix(&diffs, d.len(), k));
            check(&d, k, nth_and_below(&diffs, d.len(), k));
        }
        // The bracket is the usual path, not a rare one.
        assert!(bracketed_some >= 15, "{bracketed_some} of 21");
    }
}
