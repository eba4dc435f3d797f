//! Discrete Fourier transforms of any length, planned once and applied to
//! many lines (the rows and columns of a map): radix 2 with precomputed
//! twiddles for powers of two, Bluestein's chirp-z convolution (on a radix-2
//! transform of length ≥ 2n − 1) for the others, so a map of 1000 × 3001
//! points is transformed at its own size, as numpy and SurfaceTopography
//! do, without padding that would move its wavevectors.
//!
//! Conventions as [`super::fft::fft`]: forward kernel e^{−2πi jk/n},
//! inverse e^{+2πi jk/n} scaled by 1/n. Accuracy: the tests compare with a
//! naive DFT to 1e-12 of the total magnitude.

use std::f64::consts::PI;

use super::fft::Complex;

/// A transform of one length, reusable across lines and threads.
#[derive(Debug, Clone)]
pub struct Plan {
    n: usize,
    kind: Kind,
}

#[derive(Debug, Clone)]
enum Kind {
    /// Radix 2: twiddles e^{−2πik/n}, k < n/2.
    Pow2(Vec<Complex>),
    /// Bluestein: chirp w_j = e^{−πi j²/n}, the radix-2 plan of length m,
    /// and the transform of the conjugate chirp laid out for a circular
    /// convolution of length m.
    Chirp {
        w: Vec<Complex>,
        inner: Box<Plan>,
        b: Vec<Complex>,
    },
}

fn mul(a: Complex, b: Complex) -> Complex {
    (a.0 * b.0 - a.1 * b.1, a.0 * b.1 + a.1 * b.0)
}

fn conj(a: Complex) -> Complex {
    (a.0, -a.1)
}

impl Plan {
    /// A plan for length `n` (≥ 1).
    pub fn new(n: usize) -> Plan {
        let n = n.max(1);
        if n.is_power_of_two() {
            let tw = (0..n / 2)
                .map(|k| {
                    let a = -2.0 * PI * k as f64 / n as f64;
                    (a.cos(), a.sin())
                })
                .collect();
            return Plan {
                n,
                kind: Kind::Pow2(tw),
            };
        }
        // j² mod 2n keeps the chirp's angle small and exact for large j.
        let w: Vec<Complex> = (0..n)
            .map(|j| {
                let q = ((j as u128 * j as u128) % (2 * n as u128)) as f64;
                let a = -PI * q / n as f64;
                (a.cos(), a.sin())
            })
            .collect();
        let m = (2 * n - 1).next_power_of_two();
        let inner = Plan::new(m);
        let mut b = vec![(0.0, 0.0); m];
        b[0] = conj(w[0]);
        for j in 1..n {
            b[j] = conj(w[j]);
            b[m - j] = conj(w[j]);
        }
        inner.forward(&mut b);
        Plan {
            n,
            kind: Kind::Chirp {
                w,
                inner: Box::new(inner),
                b,
            },
        }
    }

    /// The length.
    pub fn len(&self) -> usize {
        self.n
    }

    /// Whether the length is zero (never: plans have length ≥ 1).
    pub fn is_empty(&self) -> bool {
        self.n == 0
    }

    /// In-place forward transform of `data` (length [`Plan::len`]).
    pub fn forward(&self, data: &mut [Complex]) {
        debug_assert_eq!(data.len(), self.n);
        match &self.kind {
            Kind::Pow2(tw) => radix2(data, tw),
            Kind::Chirp { w, inner, b } => {
                let m = inner.len();
                let mut a = vec![(0.0, 0.0); m];
                for j in 0..self.n {
                    a[j] = mul(data[j], w[j]);
                }
                inner.forward(&mut a);
                for (x, y) in a.iter_mut().zip(b) {
                    *x = mul(*x, *y);
                }
                inner.inverse(&mut a);
                for k in 0..self.n {
                    data[k] = mul(a[k], w[k]);
                }
            }
        }
    }

    /// In-place inverse transform, scaled by 1/n: conj(F(conj(x)))/n.
    pub fn inverse(&self, data: &mut [Complex]) {
        data.iter_mut().for_each(|v| v.1 = -v.1);
        self.forward(data);
        let s = 1.0 / self.n as f64;
        data.iter_mut().for_each(|v| *v = (v.0 * s, -v.1 * s));
    }
}

/// Iterative radix-2 transform with the twiddles of its length.
fn radix2(data: &mut [Complex], tw: &[Complex]) {
    let n = data.len();
    if n <= 1 {
        return;
    }
    super::fft::bit_reverse(data);
    let mut len = 2;
    while len <= n {
        let half = len / 2;
        let stride = n / len;
        for start in (0..n).step_by(len) {
            for k in 0..half {
                let v = mul(data[start + k + half], tw[k * stride]);
                let u = data[start + k];
                data[start + k] = (u.0 + v.0, u.1 + v.1);
                data[start + k + half] = (u.0 - v.0, u.1 - v.1);
            }
        }
        len <<= 1;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::signal::fft::dft_naive;

    #[test]
    fn any_length_matches_the_naive_dft_and_round_trips() {
        let mut s = 5u64;
        let mut r = || {
            s = s
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            ((s >> 11) as f64) / ((1u64 << 53) as f64) - 0.5
        };
        for n in [1usize, 2, 3, 5, 7, 12, 64, 100, 101, 243, 1000, 1024] {
            let x: Vec<Complex> = (0..n).map(|_| (r(), r())).collect();
            let plan = Plan::new(n);
            let mut a = x.clone();
            plan.forward(&mut a);
            let want = dft_naive(&x, false);
            let scale: f64 = want.iter().map(|v| v.0.abs() + v.1.abs()).sum::<f64>() + 1.0;
            for (p, q) in a.iter().zip(&want) {
                // Round-off O(ε log m) of the magnitudes summed; 1e-12 of
                // the total catches any indexing or chirp error.
                assert!((p.0 - q.0).abs() < 1e-12 * scale && (p.1 - q.1).abs() < 1e-12 * scale);
            }
            plan.inverse(&mut a);
            for (p, q) in a.iter().zip(&x) {
                assert!(
                    (p.0 - q.0).abs() < 1e-12 && (p.1 - q.1).abs() < 1e-12,
                    "n = {n}"
                );
            }
        }
    }
}
