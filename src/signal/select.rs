//! Order statistics without a copy of the data: a radix selection over a
//! source that can be read again (a slice, or values computed from one,
//! such as first differences), so a median of a long trace needs a small
//! histogram instead of a scratch buffer as long as the trace
//! (peak memory, `docs/speed.md`).
//!
//! Each pass counts, among the values whose leading key bits match those
//! already fixed, the next 16 bits of the key that orders `f64` as
//! `f64::total_cmp` does, then fixes the bucket holding the wanted rank.
//! Once that bucket holds few values they are collected and the rank taken
//! by `select_nth_unstable_by(f64::total_cmp)`. Order statistics under a
//! total order are unique, so the value is bit for bit the one a sort
//! would give.

/// Key bits fixed per pass.
const BITS: u32 = 16;

/// A bucket this small is collected and selected in memory.
const COLLECT: usize = 1 << 16;

/// The key whose unsigned order is `f64::total_cmp`'s order.
fn key(x: f64) -> u64 {
    let b = x.to_bits() as i64;
    let t = b ^ ((((b >> 63) as u64) >> 1) as i64);
    (t as u64) ^ (1 << 63)
}

/// The value of a key (the inverse of [`key`]).
fn value(k: u64) -> f64 {
    let t = (k ^ (1 << 63)) as i64;
    f64::from_bits((t ^ ((((t >> 63) as u64) >> 1) as i64)) as u64)
}

/// The `k`-th smallest (0-based) of the `n` values `source()` yields, and
/// the `k - 1`-th when `k > 0`: the two middle values of an even count.
/// `source` must yield the same `n` values each time it is called.
pub fn nth_and_below<I, F>(source: F, n: usize, k: usize) -> (f64, Option<f64>)
where
    F: Fn() -> I,
    I: Iterator<Item = f64>,
{
    assert!(k < n, "rank {k} of {n} values");
    let mut hist = vec![0usize; 1 << BITS];
    let rank = k;
    let (mut prefix, mut fixed, mut k, mut count) = (0u64, 0u32, k, n);
    // Whether a key lies in the bucket fixed so far.
    let inside = |kx: u64, prefix: u64, fixed: u32| fixed == 0 || kx >> (64 - fixed) == prefix;
    while count > COLLECT && fixed < 64 {
        hist.fill(0);
        let shift = 64 - fixed - BITS;
        for kx in source().map(key) {
            if inside(kx, prefix, fixed) {
                hist[((kx >> shift) & 0xFFFF) as usize] += 1;
            }
        }
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
    let (hi, lower) = match fixed {
        64 => (value(prefix), (k > 0).then(|| value(prefix))),
        _ => {
            let mut v: Vec<f64> = source()
                .filter(|&x| inside(key(x), prefix, fixed))
                .collect();
            let (left, mid, _) = v.select_nth_unstable_by(k, f64::total_cmp);
            (*mid, left.iter().copied().max_by(f64::total_cmp))
        }
    };
    if lower.is_some() || rank == 0 {
        return (hi, lower);
    }
    // The rank below is the largest value under the bucket.
    let low = if fixed == 0 {
        0
    } else {
        prefix << (64 - fixed)
    };
    let below = source().map(key).filter(|&kx| kx < low).max().map(value);
    (hi, below)
}

/// The median of the `n` values `source()` yields (the mean of the two
/// middle ones for an even count), as a sort by `f64::total_cmp` gives it.
pub fn median<I, F>(source: F, n: usize) -> Option<f64>
where
    F: Fn() -> I,
    I: Iterator<Item = f64>,
{
    if n == 0 {
        return None;
    }
    let (hi, lo) = nth_and_below(source, n, n / 2);
    Some(match n % 2 {
        1 => hi,
        _ => 0.5 * (lo.unwrap_or(hi) + hi),
    })
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
            let (v, below) = nth_and_below(|| x.iter().copied(), x.len(), k);
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
                let (v, below) = nth_and_below(|| x.iter().copied(), x.len(), k);
                assert_eq!(v.to_bits(), s[k].to_bits(), "rank {k}");
                assert_eq!(
                    below.map(f64::to_bits),
                    k.checked_sub(1).map(|j| s[j].to_bits())
                );
            }
            let m = median(|| x.iter().copied(), x.len()).unwrap();
            let n = s.len();
            let want = match n % 2 {
                1 => s[n / 2],
                _ => 0.5 * (s[n / 2 - 1] + s[n / 2]),
            };
            assert_eq!(m.to_bits(), want.to_bits());
        }
        assert!(median(std::iter::empty, 0).is_none());
    }
}
