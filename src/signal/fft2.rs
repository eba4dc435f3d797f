//! Two-dimensional transforms of real maps, as half spectra: a real map's
//! spectrum is Hermitian, F(−k) = conj F(k), so only the columns kx = 0..=q/2
//! are kept (half the memory and work). Rows are transformed two at a time
//! (one complex transform of `a + i b` gives both), then the kept columns.
//! Rows and columns run in parallel, each line its own sequential transform,
//! so the result is the same whatever the thread count.

use rayon::prelude::*;

use super::dft::Plan;
use super::fft::Complex;

/// The half spectrum of a real `ny × nx` map zero-padded to `p` rows and
/// `q` columns: `q/2 + 1` columns of `p` values each, stored column by
/// column (`data[kx * p + ky]`).
#[derive(Debug, Clone)]
pub struct HalfSpectrum {
    /// Rows of the (padded) transform, the length along y.
    pub p: usize,
    /// Columns of the (padded) transform, the length along x.
    pub q: usize,
    /// Column-major values, `(q/2 + 1) · p`.
    pub data: Vec<Complex>,
}

impl HalfSpectrum {
    /// Columns kept, q/2 + 1.
    pub fn half(&self) -> usize {
        self.q / 2 + 1
    }

    /// F(ky, kx) for kx ≤ q/2.
    pub fn at(&self, ky: usize, kx: usize) -> Complex {
        self.data[kx * self.p + ky]
    }
}

/// The half spectrum of the row-major `ny × nx` map `z`, padded with zeros
/// to `p ≥ ny` rows and `q ≥ nx` columns.
pub fn rfft2(z: &[f64], nx: usize, ny: usize, p: usize, q: usize) -> HalfSpectrum {
    let half = q / 2 + 1;
    let row_plan = Plan::new(q);
    // Rows two at a time: row a in the real part, row b in the imaginary.
    let pairs: Vec<Vec<Complex>> = (0..ny.div_ceil(2))
        .into_par_iter()
        .map(|k| {
            let (ra, rb) = (2 * k, 2 * k + 1);
            let mut buf = vec![(0.0, 0.0); q];
            for (c, b) in buf.iter_mut().take(nx).enumerate() {
                let im = if rb < ny { z[rb * nx + c] } else { 0.0 };
                *b = (z[ra * nx + c], im);
            }
            row_plan.forward(&mut buf);
            // X = (B[k] + conj B[q−k]) / 2, Y = (B[k] − conj B[q−k]) / 2i.
            let mut out = Vec::with_capacity(2 * half);
            for k in 0..half {
                let (u, v) = (buf[k], buf[(q - k) % q]);
                out.push((0.5 * (u.0 + v.0), 0.5 * (u.1 - v.1)));
            }
            for k in 0..half {
                let (u, v) = (buf[k], buf[(q - k) % q]);
                out.push((0.5 * (u.1 + v.1), -0.5 * (u.0 - v.0)));
            }
            out
        })
        .collect();
    let col_plan = Plan::new(p);
    let mut data = vec![(0.0, 0.0); half * p];
    data.par_chunks_mut(p).enumerate().for_each(|(kx, col)| {
        for (r, v) in col.iter_mut().take(ny).enumerate() {
            *v = pairs[r / 2][(r % 2) * half + kx];
        }
        col_plan.forward(col);
    });
    HalfSpectrum { p, q, data }
}

/// The real map whose half spectrum is `spec` (the inverse of [`rfft2`],
/// scaled by 1/(p q)), at the rows `rows` (indices into 0..p) only, each of
/// length q: `out[i * q + x]` is row `rows[i]`.
pub fn irfft2_rows(mut spec: HalfSpectrum, rows: &[usize]) -> Vec<f64> {
    let (p, q, half) = (spec.p, spec.q, spec.half());
    let col_plan = Plan::new(p);
    spec.data
        .par_chunks_mut(p)
        .for_each(|col| col_plan.inverse(col));
    let row_plan = Plan::new(q);
    let mut out = vec![0.0; rows.len() * q];
    // Rows two at a time: the full Hermitian rows of a and b combined as
    // a + i b, one inverse transform, a and b in its real and imaginary
    // parts.
    out.par_chunks_mut(2 * q).enumerate().for_each(|(k, dst)| {
        let ra = rows[2 * k];
        let rb = rows.get(2 * k + 1).copied();
        let mut buf = vec![(0.0, 0.0); q];
        for kx in 0..half {
            let a = spec.data[kx * p + ra];
            let b = rb.map_or((0.0, 0.0), |r| spec.data[kx * p + r]);
            // H_a[kx] + i H_b[kx], and at q − kx the conjugates.
            buf[kx] = (a.0 - b.1, a.1 + b.0);
            if kx > 0 && kx < q - kx {
                buf[q - kx] = (a.0 + b.1, -a.1 + b.0);
            }
        }
        row_plan.inverse(&mut buf);
        let (first, second) = dst.split_at_mut(q.min(dst.len()));
        for (x, v) in first.iter_mut().enumerate() {
            *v = buf[x].0;
        }
        for (x, v) in second.iter_mut().enumerate() {
            *v = buf[x].1;
        }
    });
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::signal::fft::dft_naive;

    fn naive2(z: &[f64], nx: usize, ny: usize, p: usize, q: usize) -> Vec<Complex> {
        // Rows then columns with the naive DFT, padded.
        let mut rows = vec![(0.0, 0.0); p * q];
        for r in 0..ny {
            let line: Vec<Complex> = (0..q)
                .map(|c| (if c < nx { z[r * nx + c] } else { 0.0 }, 0.0))
                .collect();
            rows[r * q..(r + 1) * q].copy_from_slice(&dft_naive(&line, false));
        }
        let mut out = rows.clone();
        for c in 0..q {
            let col: Vec<Complex> = (0..p).map(|r| rows[r * q + c]).collect();
            for (r, v) in dft_naive(&col, false).into_iter().enumerate() {
                out[r * q + c] = v;
            }
        }
        out
    }

    #[test]
    fn half_spectrum_matches_the_naive_transform_and_inverts() {
        for (nx, ny, p, q) in [(5, 3, 5, 6), (7, 4, 8, 16), (6, 5, 9, 12), (4, 4, 4, 4)] {
            let z: Vec<f64> = (0..nx * ny).map(|i| ((i * 37 % 11) as f64) - 4.5).collect();
            let spec = rfft2(&z, nx, ny, p, q);
            let full = naive2(&z, nx, ny, p, q);
            for ky in 0..p {
                for kx in 0..spec.half() {
                    let (a, b) = (spec.at(ky, kx), full[ky * q + kx]);
                    // Values up to ~300: 1e-10 absolute is round-off.
                    assert!((a.0 - b.0).abs() < 1e-10 && (a.1 - b.1).abs() < 1e-10);
                }
            }
            let rows: Vec<usize> = (0..p).collect();
            let back = irfft2_rows(spec, &rows);
            for r in 0..p {
                for c in 0..q {
                    let want = if r < ny && c < nx { z[r * nx + c] } else { 0.0 };
                    assert!(
                        (back[r * q + c] - want).abs() < 1e-12,
                        "{nx}x{ny} -> {p}x{q}"
                    );
                }
            }
        }
    }
}
