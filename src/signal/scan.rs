//! Scans of long slices on all threads: each fixed chunk is read by a plain
//! loop (rayon's per-item adaptors cost more per value than the test they
//! run), and the first hit in slice order is kept, so the answer is the one
//! sequential pass gives, whatever the thread count.

use rayon::prelude::*;

/// Values per chunk.
const CHUNK: usize = 1 << 16;

/// Index of the first value for which `hit` holds.
pub fn first_position(x: &[f64], hit: impl Fn(f64) -> bool + Sync) -> Option<usize> {
    x.par_chunks(CHUNK)
        .enumerate()
        .find_map_first(|(c, s)| s.iter().position(|&v| hit(v)).map(|i| c * CHUNK + i))
}

/// Index `i` of the first neighbours `(x[i], x[i + 1])` for which `hit`
/// holds. Each block of [`BLOCK`] pairs is tested without a branch per
/// pair; only a block with a hit is searched.
pub fn first_pair(x: &[f64], hit: impl Fn(f64, f64) -> bool + Sync) -> Option<usize> {
    let pairs = x.len().saturating_sub(1);
    (0..pairs.div_ceil(CHUNK))
        .into_par_iter()
        .find_map_first(|c| {
            let s = &x[c * CHUNK..((c + 1) * CHUNK + 1).min(x.len())];
            let (a, b) = (&s[..s.len() - 1], &s[1..]);
            a.chunks(BLOCK)
                .zip(b.chunks(BLOCK))
                .enumerate()
                .filter(|(_, (a, b))| {
                    a.iter()
                        .zip(*b)
                        .fold(false, |any, (&u, &v)| any | hit(u, v))
                })
                .find_map(|(k, (a, b))| {
                    let i = a.iter().zip(b).position(|(&u, &v)| hit(u, v))?;
                    Some(c * CHUNK + k * BLOCK + i)
                })
        })
}

/// How many values `hit` holds for, on all threads (an integer sum: the
/// same whatever the split).
pub fn count(x: &[f64], hit: impl Fn(f64) -> bool + Sync) -> usize {
    x.par_chunks(CHUNK)
        .map(|c| c.iter().fold(0usize, |n, &v| n + usize::from(hit(v))))
        .sum()
}

/// Pairs per block of [`first_pair`].
const BLOCK: usize = 256;

/// Whether every value of every slice is finite: a branch-free test per
/// chunk, on all threads.
pub fn all_finite(columns: &[&[f64]]) -> bool {
    columns.iter().all(|x| {
        x.par_chunks(CHUNK)
            .all(|c| c.iter().fold(true, |all, v| all & v.is_finite()))
    })
}

/// The smallest and largest finite value (`None` when there is none): a
/// minimum and a maximum do not depend on the order they are taken in.
pub fn finite_range(x: &[f64]) -> Option<(f64, f64)> {
    let (lo, hi) = x
        .par_chunks(CHUNK)
        .map(|c| extremes(c, f64::is_finite))
        .reduce(
            || (f64::INFINITY, f64::NEG_INFINITY),
            |a, b| (a.0.min(b.0), a.1.max(b.1)),
        );
    (lo <= hi).then_some((lo, hi))
}

/// The smallest and largest of the values of `x` that `keep` admits (NaN
/// never counts), on this thread; (+∞, −∞) when there is none. Four lanes
/// of compare-and-select, which compile to vector min and max: a branch
/// per value costs several times more on noisy data.
pub fn extremes(x: &[f64], keep: impl Fn(f64) -> bool) -> (f64, f64) {
    let mut lo = [f64::INFINITY; 4];
    let mut hi = [f64::NEG_INFINITY; 4];
    let mut take = |k: usize, v: f64| {
        let ok = keep(v);
        lo[k] = if ok && v < lo[k] { v } else { lo[k] };
        hi[k] = if ok && v > hi[k] { v } else { hi[k] };
    };
    let mut quads = x.chunks_exact(4);
    for q in &mut quads {
        for (k, &v) in q.iter().enumerate() {
            take(k, v);
        }
    }
    for &v in quads.remainder() {
        take(0, v);
    }
    let lo = lo[0].min(lo[1]).min(lo[2].min(lo[3]));
    let hi = hi[0].max(hi[1]).max(hi[2].max(hi[3]));
    (lo, hi)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The first hit of a sequential pass, across chunk boundaries, with
    /// several hits, none, and inputs of 0, 1 and 2 values.
    #[test]
    fn first_hits_are_those_of_one_pass() {
        let mut x: Vec<f64> = (0..5 * CHUNK + 3).map(|i| i as f64).collect();
        assert_eq!(first_position(&x, f64::is_nan), None);
        assert_eq!(count(&x, |v| v >= CHUNK as f64), 4 * CHUNK + 3);
        assert!(all_finite(&[&x, &x[1..]]) && all_finite(&[]));
        assert_eq!(first_pair(&x, |a, b| b <= a), None);
        for at in [0, CHUNK - 1, CHUNK, 3 * CHUNK + 1, x.len() - 1] {
            let mut y = x.clone();
            y[at] = f64::NAN;
            y[x.len() - 1] = f64::NAN;
            assert_eq!(first_position(&y, f64::is_nan), Some(at));
        }
        x[2 * CHUNK] = -1.0; // the pair ending at a chunk's first value
        x[4 * CHUNK + 7] = -1.0;
        let want = x.windows(2).position(|w| w[1] <= w[0]);
        assert_eq!(first_pair(&x, |a, b| b <= a), want);
        assert_eq!(want, Some(2 * CHUNK - 1));
        let mut y = x.clone();
        y[3 * CHUNK] = f64::NAN;
        y[7] = f64::INFINITY;
        y[CHUNK + 1] = -5.0;
        assert_eq!(finite_range(&y), Some((-5.0, x[x.len() - 1])));
        assert_eq!(finite_range(&[f64::NAN, f64::INFINITY]), None);
        assert_eq!(finite_range(&[]), None);
        // Hits at a block's last pair, its first, and late in a chunk.
        for at in [BLOCK - 1, BLOCK, CHUNK + 3 * BLOCK + 5, CHUNK - 1] {
            let mut y: Vec<f64> = (0..2 * CHUNK).map(|i| i as f64).collect();
            y[at + 1] = -1.0;
            y[at + 9] = -1.0;
            let want = y.windows(2).position(|w| w[1] <= w[0]);
            assert_eq!(want, Some(at));
            assert_eq!(first_pair(&y, |a, b| b <= a), want);
        }
        for short in [&[][..], &[1.0], &[2.0, 1.0]] {
            let want = short.windows(2).position(|w| w[1] <= w[0]);
            assert_eq!(first_pair(short, |a, b| b <= a), want);
        }
    }
}
