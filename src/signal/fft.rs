//! A small iterative radix-2 FFT over complex numbers stored as `(re, im)`
//! pairs, and the linear convolution built on it (overlap–save).
//!
//! Only what roughness analysis needs: the Gaussian profile filter
//! ([`super::gaussian_filter`]) convolves long profiles with a kernel of a few
//! thousand taps, and the power-spectrum fractal dimension needs a periodogram.
//! Lengths are powers of two; [`next_pow2`] pads. Accuracy: round-off grows as
//! O(ε log n); the tests compare with a naive DFT to 1e-12 relative.

use std::f64::consts::PI;

/// A complex number as `(re, im)`.
pub type Complex = (f64, f64);

/// The smallest power of two ≥ `n` (1 for `n = 0`).
pub fn next_pow2(n: usize) -> usize {
    n.max(1).next_power_of_two()
}

/// In-place forward (`inverse = false`, kernel e^{-2πi jk/n}) or inverse
/// (`inverse = true`, e^{+2πi jk/n}, scaled by 1/n) FFT.
///
/// The length must be a power of two (callers pad with [`next_pow2`]); any
/// other length is a programming error caught by a debug assertion, and in a
/// release build the data are left untouched.
pub fn fft(data: &mut [Complex], inverse: bool) {
    let n = data.len();
    if n <= 1 || !n.is_power_of_two() {
        debug_assert!(n <= 1, "fft length {n} is not a power of two");
        return;
    }
    bit_reverse(data);
    let sign = if inverse { 1.0 } else { -1.0 };
    // Twiddles e^{±2πik/n}, k < n/2, computed once directly (not by
    // repeated multiplication, which would accumulate round-off); level
    // `len` uses every (n/len)-th of them.
    let tw: Vec<Complex> = (0..n / 2)
        .map(|k| {
            let a = sign * 2.0 * PI * k as f64 / n as f64;
            (a.cos(), a.sin())
        })
        .collect();
    let mut len = 2;
    while len <= n {
        let half = len / 2;
        let stride = n / len;
        for start in (0..n).step_by(len) {
            for k in 0..half {
                let (wr, wi) = tw[k * stride];
                let (ur, ui) = data[start + k];
                let (vr0, vi0) = data[start + k + half];
                let vr = vr0 * wr - vi0 * wi;
                let vi = vr0 * wi + vi0 * wr;
                data[start + k] = (ur + vr, ui + vi);
                data[start + k + half] = (ur - vr, ui - vi);
            }
        }
        len <<= 1;
    }
    if inverse {
        let s = 1.0 / n as f64;
        for v in data.iter_mut() {
            v.0 *= s;
            v.1 *= s;
        }
    }
}

/// Naive O(n²) DFT, the reference for tests.
pub fn dft_naive(data: &[Complex], inverse: bool) -> Vec<Complex> {
    let n = data.len();
    let sign = if inverse { 1.0 } else { -1.0 };
    (0..n)
        .map(|k| {
            let mut acc = (0.0, 0.0);
            for (j, &(re, im)) in data.iter().enumerate() {
                let a = sign * 2.0 * PI * ((j * k) % n) as f64 / n as f64;
                let (c, s) = (a.cos(), a.sin());
                acc.0 += re * c - im * s;
                acc.1 += re * s + im * c;
            }
            if inverse {
                (acc.0 / n as f64, acc.1 / n as f64)
            } else {
                acc
            }
        })
        .collect()
}

/// Full linear convolution `y[i] = Σ_j x[i - j + h] · k[j]` evaluated at the
/// positions of `x` ("same" size), where `k` has odd length `2h + 1` and is
/// centred; samples of `x` outside `0..n` count as zero.
///
/// Overlap–save with blocks of `fft_len = next_pow2(4 · len(k))`: O(n log K)
/// time and O(K) extra memory besides the output, so a 10⁷-point profile
/// does not need a 2²⁴-point transform.
pub fn convolve_same(x: &[f64], kernel: &[f64]) -> Vec<f64> {
    let n = x.len();
    let m = kernel.len();
    if n == 0 || m == 0 {
        return vec![0.0; n];
    }
    let h = m / 2;
    // Small problems: direct sum is faster and exact.
    if (m as u64) * (n as u64) <= 1 << 16 || m <= 16 {
        return (0..n)
            .map(|i| {
                let mut s = 0.0;
                for (j, &kj) in kernel.iter().enumerate() {
                    let idx = i as isize + h as isize - j as isize;
                    if idx >= 0 && (idx as usize) < n {
                        s += x[idx as usize] * kj;
                    }
                }
                s
            })
            .collect();
    }
    let fft_len = next_pow2(4 * m);
    let step = fft_len - (m - 1); // valid outputs per block
    let mut kf: Vec<Complex> = vec![(0.0, 0.0); fft_len];
    for (j, &kj) in kernel.iter().enumerate() {
        kf[j] = (kj, 0.0);
    }
    fft(&mut kf, false);
    // Full convolution index f = i + h for output i (0..n): f in h..h+n.
    // Full conv c[f] = Σ_j x[f - j] k[j].
    let mut out = vec![0.0; n];
    let mut buf: Vec<Complex> = vec![(0.0, 0.0); fft_len];
    let total = n + m - 1;
    let mut f0 = 0usize; // first full-conv index produced by this block
    while f0 < total {
        // Block input covers x[f0 - (m-1) .. f0 - (m-1) + fft_len].
        let base = f0 as isize - (m as isize - 1);
        for (t, b) in buf.iter_mut().enumerate() {
            let idx = base + t as isize;
            *b = if idx >= 0 && (idx as usize) < n {
                (x[idx as usize], 0.0)
            } else {
                (0.0, 0.0)
            };
        }
        fft(&mut buf, false);
        for (b, &k) in buf.iter_mut().zip(kf.iter()) {
            *b = (b.0 * k.0 - b.1 * k.1, b.0 * k.1 + b.1 * k.0);
        }
        fft(&mut buf, true);
        for t in 0..step {
            let f = f0 + t;
            if f >= total {
                break;
            }
            if f >= h && f - h < n {
                out[f - h] = buf[t + m - 1].0;
            }
        }
        f0 += step;
    }
    out
}

/// The bit-reversal permutation of a radix-2 transform, in place (the
/// length a power of two).
pub(crate) fn bit_reverse(data: &mut [Complex]) {
    let n = data.len();
    let mut j = 0usize;
    for i in 1..n {
        let mut bit = n >> 1;
        while j & bit != 0 {
            j ^= bit;
            bit >>= 1;
        }
        j |= bit;
        if i < j {
            data.swap(i, j);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn lcg(seed: &mut u64) -> f64 {
        *seed = seed
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        ((*seed >> 11) as f64) / ((1u64 << 53) as f64) - 0.5
    }

    #[test]
    fn fft_matches_naive_dft_forward_and_inverse() {
        let mut s = 7u64;
        for &n in &[1usize, 2, 4, 8, 64, 256] {
            let x: Vec<Complex> = (0..n).map(|_| (lcg(&mut s), lcg(&mut s))).collect();
            for inv in [false, true] {
                let mut a = x.clone();
                fft(&mut a, inv);
                let b = dft_naive(&x, inv);
                let scale: f64 = b.iter().map(|v| v.0.abs() + v.1.abs()).sum::<f64>() + 1.0;
                for (p, q) in a.iter().zip(&b) {
                    // Round-off of both sides is O(n ε · |x|); 1e-12 of the
                    // total magnitude is far above that and far below any
                    // indexing or twiddle-sign error.
                    assert!((p.0 - q.0).abs() < 1e-12 * scale, "n={n} inv={inv}");
                    assert!((p.1 - q.1).abs() < 1e-12 * scale, "n={n} inv={inv}");
                }
            }
        }
    }

    #[test]
    fn fft_round_trip_restores_input() {
        let mut s = 3u64;
        let x: Vec<Complex> = (0..1024).map(|_| (lcg(&mut s), lcg(&mut s))).collect();
        let mut a = x.clone();
        fft(&mut a, false);
        fft(&mut a, true);
        for (p, q) in a.iter().zip(&x) {
            // O(log n · ε) round-off.
            assert!((p.0 - q.0).abs() < 1e-13 && (p.1 - q.1).abs() < 1e-13);
        }
    }

    #[test]
    fn overlap_save_convolution_matches_direct_sum() {
        let mut s = 11u64;
        let x: Vec<f64> = (0..5000).map(|_| lcg(&mut s)).collect();
        let k: Vec<f64> = (0..101).map(|_| lcg(&mut s)).collect();
        let fast = convolve_same(&x, &k);
        let h = k.len() / 2;
        for i in (0..x.len()).step_by(7).chain([0, 1, 4999]) {
            let mut d = 0.0;
            for (j, &kj) in k.iter().enumerate() {
                let idx = i as isize + h as isize - j as isize;
                if idx >= 0 && (idx as usize) < x.len() {
                    d += x[idx as usize] * kj;
                }
            }
            // Sums of ~100 terms of magnitude ≤ 0.25: round-off ≪ 1e-12.
            assert!((fast[i] - d).abs() < 1e-12, "i={i}: {} vs {d}", fast[i]);
        }
    }
}
