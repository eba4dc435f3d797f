//! Long float sums in fixed lanes and chunks. A sum taken in slice order is
//! one chain of dependent additions (four cycles each, on one thread); a
//! trace of 1e7 samples has a dozen such sums. Here each chunk of
//! [`CHUNK`] positions is summed in [`LANES`] interleaved accumulators,
//! combined pairwise, and the chunks' sums are added in chunk order. Chunks
//! and lanes are fixed by the length alone, so the bits are the same for
//! any thread count, on any machine; and the error bound is smaller than a
//! sequential sum's (the additions form a shallower tree). It is not the
//! sequential sum's bits: results move in the last place (docs/speed.md).

use rayon::prelude::*;

/// Positions per chunk: the unit of parallel work.
const CHUNK: usize = 1 << 14;

/// Interleaved accumulators within a chunk.
const LANES: usize = 8;

/// Σ f(i) for i in 0..n, in fixed lanes and chunks.
pub fn sum_by(n: usize, f: impl Fn(usize) -> f64 + Sync) -> f64 {
    sums_by(n, |i| [f(i)])[0]
}

/// Σ x, in fixed lanes and chunks.
pub fn sum(x: &[f64]) -> f64 {
    sum_by(x.len(), |i| x[i])
}

/// `K` sums Σ f(i)[k] in one pass (a mean of x and of y, say), each as
/// [`sum_by`] takes it.
pub fn sums_by<const K: usize>(n: usize, f: impl Fn(usize) -> [f64; K] + Sync) -> [f64; K] {
    let chunk = |c: usize| lanes(c * CHUNK..((c + 1) * CHUNK).min(n), &f);
    let chunks = n.div_ceil(CHUNK);
    if chunks <= 1 {
        return chunk(0);
    }
    let sums: Vec<[f64; K]> = (0..chunks).into_par_iter().map(chunk).collect();
    let mut total = [0.0; K];
    for s in &sums {
        for (t, v) in total.iter_mut().zip(s) {
            *t += v;
        }
    }
    total
}

/// The sums of the chunk `r`: position `r.start + j` goes to lane
/// `j % LANES`; the lanes are added pairwise.
fn lanes<const K: usize>(r: std::ops::Range<usize>, f: &impl Fn(usize) -> [f64; K]) -> [f64; K] {
    let mut acc = [[0.0f64; K]; LANES];
    let add = |lane: &mut [f64; K], v: [f64; K]| {
        for (a, v) in lane.iter_mut().zip(v) {
            *a += v;
        }
    };
    let mut i = r.start;
    while i + LANES <= r.end {
        for (k, lane) in acc.iter_mut().enumerate() {
            add(lane, f(i + k));
        }
        i += LANES;
    }
    for (k, lane) in acc.iter_mut().enumerate().take(r.end - i) {
        add(lane, f(i + k));
    }
    std::array::from_fn(|j| {
        let l = |k: usize| acc[k][j];
        ((l(0) + l(1)) + (l(2) + l(3))) + ((l(4) + l(5)) + (l(6) + l(7)))
    })
}

/// Number of positions i in 0..n for which `hit(i)` holds, on all threads.
pub fn count_by(n: usize, hit: impl Fn(usize) -> bool + Sync) -> usize {
    let chunk = |c: usize| {
        (c * CHUNK..((c + 1) * CHUNK).min(n))
            .map(|i| usize::from(hit(i)))
            .sum::<usize>()
    };
    match n.div_ceil(CHUNK) {
        0 | 1 => chunk(0),
        chunks => (0..chunks).into_par_iter().map(chunk).sum(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Exact on integers (every partial sum representable), for lengths
    /// around the lane and chunk sizes; empty is 0.
    #[test]
    fn integer_sums_are_exact() {
        for n in [0, 1, 7, 8, 9, CHUNK - 1, CHUNK, CHUNK + 1, 5 * CHUNK + 3] {
            let x: Vec<f64> = (0..n).map(|i| (i % 1000) as f64).collect();
            let want: u64 = (0..n as u64).map(|i| i % 1000).sum();
            assert_eq!(sum(&x).to_bits(), (want as f64).to_bits(), "n = {n}");
            assert_eq!(
                count_by(n, |i| x[i] >= 500.0),
                x.iter().filter(|v| **v >= 500.0).count()
            );
        }
    }

    /// The same bits on one thread and on several, within a few units in
    /// the last place of the exact sum (an i128 sum of the values, each a
    /// multiple of 2^-43 below 2^11).
    #[test]
    fn deterministic_and_accurate() {
        let noise = crate::signal::testing::gaussian_noise(3 * CHUNK + 11, 1.0, 9);
        let x: Vec<f64> = noise.iter().map(|e| 1000.0 + e).collect();
        let one = rayon::ThreadPoolBuilder::new()
            .num_threads(1)
            .build()
            .unwrap();
        let four = rayon::ThreadPoolBuilder::new()
            .num_threads(4)
            .build()
            .unwrap();
        let (a, b) = (one.install(|| sum(&x)), four.install(|| sum(&x)));
        assert_eq!(a.to_bits(), b.to_bits());
        // Exact: each value is a multiple of 2^-43 below 2^11.
        let exact: i128 = x.iter().map(|v| (v * 2f64.powi(43)) as i128).sum();
        let exact = exact as f64 / 2f64.powi(43);
        assert!(
            (a - exact).abs() <= 4.0 * f64::EPSILON * exact,
            "{a} {exact}"
        );
    }
}
