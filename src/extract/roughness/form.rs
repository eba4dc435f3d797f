//! Form removal (the F-operator of ISO 25178-2/-3): mean, least-squares
//! line or plane, a least-squares polynomial of any degree, fitted to the
//! measured points only (NaN heights are points not measured and stay so).
//! The circle and cylinder of a roller are in [`super::circle`].
//!
//! Polynomials are fitted in the Legendre basis on coordinates scaled to
//! [−1, 1] (profiles: P_a(t); maps: P_a(t_x)·P_b(t_y) with a + b ≤ degree,
//! the total degree, as surfalize's `detrend_polynomial` and Gwyddion's
//! polynomial levelling), which keeps the normal equations well conditioned
//! up to high degrees; they are solved by Cholesky. On a map the sums over
//! a row are taken first (the x basis times each row's mask), so the cost is
//! O(n · (degree + 1)²) and the work is split by rows.

use nalgebra::{DMatrix, DVector};
use rayon::prelude::*;

use super::params::Detrend;
use crate::error::{Error, Result};

/// Detrends heights in place ([`Detrend::None`], [`Detrend::Mean`] or
/// [`Detrend::Line`]; the other forms need [`remove_polynomial`] or
/// [`super::circle`]). The line is fitted against `positions` when given
/// (the positions as written in the file), else against the sample index
/// (for equal spacing the spacing cancels out of the residuals).
pub fn detrend_profile_at(z: &mut [f64], positions: Option<&[f64]>, how: Detrend) {
    let t: Vec<f64>;
    let x = match positions {
        Some(x) => x,
        None => {
            t = (0..z.len()).map(|i| i as f64).collect();
            &t
        }
    };
    match how {
        Detrend::Mean => subtract_mean(z),
        Detrend::Line => subtract_line(z, x),
        _ => {}
    }
}

/// As [`detrend_profile_at`] against the sample index.
pub fn detrend_profile(z: &mut [f64], how: Detrend) {
    detrend_profile_at(z, None, how)
}

fn subtract_mean(z: &mut [f64]) {
    let (s, n) = z
        .iter()
        .filter(|v| !v.is_nan())
        .fold((0.0, 0usize), |(s, n), v| (s + v, n + 1));
    if n > 0 {
        let m = s / n as f64;
        z.iter_mut().for_each(|v| *v -= m);
    }
}

/// The least-squares line through the measured points, in centred
/// coordinates (well conditioned for long profiles).
fn subtract_line(z: &mut [f64], x: &[f64]) {
    let pts = || x.iter().zip(z.iter()).filter(|(_, v)| !v.is_nan());
    let n = pts().count() as f64;
    if n == 0.0 {
        return;
    }
    let mx = pts().map(|p| p.0).sum::<f64>() / n;
    let mz = pts().map(|p| p.1).sum::<f64>() / n;
    let (mut sxz, mut sxx) = (0.0, 0.0);
    for (&xi, &zi) in pts() {
        sxz += (xi - mx) * (zi - mz);
        sxx += (xi - mx) * (xi - mx);
    }
    let b = if sxx > 0.0 { sxz / sxx } else { 0.0 };
    for (v, &xi) in z.iter_mut().zip(x) {
        *v -= mz + b * (xi - mx);
    }
}

/// Detrends a row-major `ny × nx` map in place; [`Detrend::Line`] removes the
/// least-squares plane z = a + b·x + c·y. On a full grid with centred
/// coordinates the normal equations decouple (b and c are the separate
/// one-dimensional slopes); with points not measured the plane is the
/// degree-1 polynomial of [`remove_polynomial_map`].
pub fn detrend_map(z: &mut [f64], nx: usize, ny: usize, how: Detrend) {
    if z.is_empty() {
        return;
    }
    match how {
        Detrend::Mean => subtract_mean(z),
        // At least MIN_POINTS measured points (validated maps): a plane
        // through them is defined unless they are collinear; then the mean
        // is the best that can be done.
        Detrend::Line if z.iter().any(|v| v.is_nan()) => {
            remove_polynomial_map(z, nx, ny, 1).unwrap_or_else(|_| subtract_mean(z))
        }
        Detrend::Line => full_plane(z, nx, ny),
        _ => {}
    }
}

fn full_plane(z: &mut [f64], nx: usize, ny: usize) {
    let cx = (nx as f64 - 1.0) / 2.0;
    let cy = (ny as f64 - 1.0) / 2.0;
    let (mut s, mut sx, mut sy, mut xx, mut yy) = (0.0, 0.0, 0.0, 0.0, 0.0);
    for r in 0..ny {
        let ty = r as f64 - cy;
        for c in 0..nx {
            let tx = c as f64 - cx;
            let v = z[r * nx + c];
            s += v;
            sx += tx * v;
            sy += ty * v;
            xx += tx * tx;
            yy += ty * ty;
        }
    }
    let a = s / (nx * ny) as f64;
    let b = if xx > 0.0 { sx / xx } else { 0.0 };
    let c = if yy > 0.0 { sy / yy } else { 0.0 };
    for r in 0..ny {
        for col in 0..nx {
            z[r * nx + col] -= a + b * (col as f64 - cx) + c * (r as f64 - cy);
        }
    }
}

/// Legendre polynomials P_0..=P_degree at t (three-term recurrence).
fn legendre(t: f64, degree: usize, out: &mut [f64]) {
    out[0] = 1.0;
    if degree >= 1 {
        out[1] = t;
    }
    for k in 2..=degree {
        let kf = k as f64;
        out[k] = ((2.0 * kf - 1.0) * t * out[k - 1] - (kf - 1.0) * out[k - 2]) / kf;
    }
}

/// `x` scaled to [−1, 1] over its range.
fn scaled(x: &[f64]) -> Vec<f64> {
    let (lo, hi) = (x[0], x[x.len() - 1]);
    let (mid, half) = ((lo + hi) / 2.0, ((hi - lo) / 2.0).max(f64::MIN_POSITIVE));
    x.iter().map(|v| (v - mid) / half).collect()
}

/// The basis values of every coordinate: row i holds P_0..=P_degree at t_i.
fn basis(t: &[f64], degree: usize) -> Vec<f64> {
    let p = degree + 1;
    let mut b = vec![0.0; t.len() * p];
    for (i, &ti) in t.iter().enumerate() {
        legendre(ti, degree, &mut b[i * p..(i + 1) * p]);
    }
    b
}

/// Solves the normal equations by Cholesky. A pivot below 1e-10 of its
/// diagonal entry means the measured points do not determine the basis
/// (rank deficient up to round-off): an error, not a wild surface.
fn solve(gram: DMatrix<f64>, rhs: DVector<f64>, what: &str) -> Result<DVector<f64>> {
    let diag: Vec<f64> = (0..gram.nrows()).map(|i| gram[(i, i)]).collect();
    let fail = || {
        Error::NotApplicable(format!(
            "the {what} cannot be fitted: the measured points do not determine it \
             (too few, or all on a line); choose a lower degree"
        ))
    };
    let c = gram.cholesky().ok_or_else(fail)?;
    let l = c.l_dirty();
    if diag
        .iter()
        .enumerate()
        .any(|(i, &d)| l[(i, i)] * l[(i, i)] <= 1e-10 * d || l[(i, i)].is_nan())
    {
        return Err(fail());
    }
    Ok(c.solve(&rhs))
}

/// Subtracts the least-squares polynomial of `degree` in the positions `x`
/// (increasing) from the measured heights. Errors
/// ([`Error::NotApplicable`]): the measured points do not determine it.
pub fn remove_polynomial(z: &mut [f64], x: &[f64], degree: usize) -> Result<()> {
    let p = degree + 1;
    let b = basis(&scaled(x), degree);
    let mut gram = DMatrix::zeros(p, p);
    let mut rhs = DVector::zeros(p);
    for (i, &v) in z.iter().enumerate() {
        if v.is_nan() {
            continue;
        }
        let bi = &b[i * p..(i + 1) * p];
        for a in 0..p {
            rhs[a] += bi[a] * v;
            for c in 0..=a {
                gram[(a, c)] += bi[a] * bi[c];
            }
        }
    }
    fill_upper(&mut gram);
    let coef = solve(gram, rhs, &format!("polynomial of degree {degree}"))?;
    for (i, v) in z.iter_mut().enumerate() {
        let bi = &b[i * p..(i + 1) * p];
        *v -= (0..p).map(|a| coef[a] * bi[a]).sum::<f64>();
    }
    Ok(())
}

fn fill_upper(g: &mut DMatrix<f64>) {
    for a in 0..g.nrows() {
        for c in a + 1..g.ncols() {
            g[(a, c)] = g[(c, a)];
        }
    }
}

/// The terms (a, b) of total degree ≤ `degree`: P_a(t_x)·P_b(t_y).
fn terms(degree: usize) -> Vec<(usize, usize)> {
    (0..=degree)
        .flat_map(|s| (0..=s).map(move |b| (s - b, b)))
        .collect()
}

/// Subtracts the least-squares polynomial surface of total `degree` from the
/// measured heights of a row-major `ny × nx` map (coordinates the column and
/// row indices, scaled to [−1, 1]). Errors ([`Error::NotApplicable`]): the
/// measured points do not determine it.
pub fn remove_polynomial_map(z: &mut [f64], nx: usize, ny: usize, degree: usize) -> Result<()> {
    let p = degree + 1;
    let idx = |n: usize| (0..n).map(|i| i as f64).collect::<Vec<_>>();
    let (bx, by) = (
        basis(&scaled(&idx(nx)), degree),
        basis(&scaled(&idx(ny)), degree),
    );
    let terms = terms(degree);
    // Per row: M[a][a'] = Σ_c m P_a P_a', V[a] = Σ_c m z P_a.
    let per_row: Vec<(Vec<f64>, Vec<f64>)> = z
        .par_chunks(nx)
        .map(|row| {
            let (mut m, mut v) = (vec![0.0; p * p], vec![0.0; p]);
            for (c, &h) in row.iter().enumerate() {
                if h.is_nan() {
                    continue;
                }
                let b = &bx[c * p..(c + 1) * p];
                for a in 0..p {
                    v[a] += b[a] * h;
                    for a2 in 0..=a {
                        m[a * p + a2] += b[a] * b[a2];
                    }
                }
            }
            (m, v)
        })
        .collect();
    let k = terms.len();
    let mut gram = DMatrix::zeros(k, k);
    let mut rhs = DVector::zeros(k);
    for (r, (m, v)) in per_row.iter().enumerate() {
        let q = &by[r * p..(r + 1) * p];
        for (i, &(a, b)) in terms.iter().enumerate() {
            rhs[i] += q[b] * v[a];
            for (j, &(a2, b2)) in terms.iter().enumerate().take(i + 1) {
                let (hi, lo) = (a.max(a2), a.min(a2));
                gram[(i, j)] += q[b] * q[b2] * m[hi * p + lo];
            }
        }
    }
    fill_upper(&mut gram);
    let coef = solve(gram, rhs, &format!("polynomial surface of degree {degree}"))?;
    z.par_chunks_mut(nx).enumerate().for_each(|(r, row)| {
        let q = &by[r * p..(r + 1) * p];
        // The row's polynomial in x: c_a = Σ_b coef[a, b] Q_b(y_r).
        let mut cx = vec![0.0; p];
        for (i, &(a, b)) in terms.iter().enumerate() {
            cx[a] += coef[i] * q[b];
        }
        for (c, v) in row.iter_mut().enumerate() {
            let b = &bx[c * p..(c + 1) * p];
            *v -= (0..p).map(|a| cx[a] * b[a]).sum::<f64>();
        }
    });
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn line_detrend_removes_a_line_exactly_and_keeps_a_symmetric_residual() {
        let mut z: Vec<f64> = (0..101).map(|i| 2.0 + 0.5 * i as f64).collect();
        detrend_profile(&mut z, Detrend::Line);
        // Values up to ~50: round-off ~1e-13.
        assert!(z.iter().all(|v| v.abs() < 1e-12));
    }

    #[test]
    fn line_detrend_at_positions_matches_index_fit_on_a_uniform_grid() {
        let z0: Vec<f64> = (0..50)
            .map(|i| ((i * 7919) % 13) as f64 + 0.1 * i as f64)
            .collect();
        let x: Vec<f64> = (0..50).map(|i| 3.0 + 0.25 * i as f64).collect();
        let (mut a, mut b) = (z0.clone(), z0);
        detrend_profile(&mut a, Detrend::Line);
        detrend_profile_at(&mut b, Some(&x), Detrend::Line);
        for (p, q) in a.iter().zip(&b) {
            // Same line, two parameterisations: round-off only.
            assert!((p - q).abs() < 1e-12);
        }
    }

    #[test]
    fn plane_detrend_removes_a_plane_with_and_without_gaps() {
        let (nx, ny) = (13, 9);
        let plane: Vec<f64> = (0..ny)
            .flat_map(|r| (0..nx).map(move |c| 1.0 + 0.3 * c as f64 - 0.7 * r as f64))
            .collect();
        let mut z = plane.clone();
        detrend_map(&mut z, nx, ny, Detrend::Line);
        assert!(z.iter().all(|v| v.abs() < 1e-12));
        // Points not measured stay so; the plane through the others is
        // still the plane.
        let mut z = plane;
        for i in [0, 5, 17, 60, 116] {
            z[i] = f64::NAN;
        }
        detrend_map(&mut z, nx, ny, Detrend::Line);
        assert_eq!(z.iter().filter(|v| v.is_nan()).count(), 5);
        assert!(z.iter().filter(|v| !v.is_nan()).all(|v| v.abs() < 1e-12));
    }

    #[test]
    fn mean_detrend_gives_zero_mean_over_measured_points() {
        let mut z = vec![1.0, 2.0, 6.0, 3.0];
        detrend_profile(&mut z, Detrend::Mean);
        assert!(z.iter().sum::<f64>().abs() < 1e-15);
        assert!((z[2] - 3.0).abs() < 1e-15);
        let mut z = vec![1.0, f64::NAN, 3.0];
        detrend_profile(&mut z, Detrend::Mean);
        assert!((z[0] + 1.0).abs() < 1e-15 && z[1].is_nan() && (z[2] - 1.0).abs() < 1e-15);
    }

    #[test]
    fn polynomials_of_their_degree_are_removed_exactly() {
        // A cubic in x on 200 points, a gap of 20 points: removed to
        // round-off (values up to ~8, so 1e-12 absolute).
        let x: Vec<f64> = (0..200).map(|i| 1e-3 + 2e-6 * i as f64).collect();
        let t = |x: f64| (x - 1.2e-3) / 2e-4;
        let mut z: Vec<f64> = x
            .iter()
            .map(|&x| 0.5 - t(x) + 0.25 * t(x).powi(2) + 0.1 * t(x).powi(3))
            .collect();
        z[50..70].fill(f64::NAN);
        remove_polynomial(&mut z, &x, 3).unwrap();
        assert!(z.iter().filter(|v| !v.is_nan()).all(|v| v.abs() < 1e-12));
        assert_eq!(z.iter().filter(|v| v.is_nan()).count(), 20);
        // A quadratic is not a line: a line leaves its curvature.
        let mut q: Vec<f64> = x.iter().map(|&x| t(x).powi(2)).collect();
        remove_polynomial(&mut q, &x, 1).unwrap();
        assert!(q.iter().any(|v| v.abs() > 0.1));
        // Degree 1 is the line fit.
        let mut a: Vec<f64> = (0..50).map(|i| ((i * 37) % 11) as f64).collect();
        let mut b = a.clone();
        remove_polynomial(&mut a, &x[..50], 1).unwrap();
        detrend_profile_at(&mut b, Some(&x[..50]), Detrend::Line);
        assert!(a.iter().zip(&b).all(|(p, q)| (p - q).abs() < 1e-12));
    }

    #[test]
    fn map_polynomial_of_total_degree_is_removed_and_cross_terms_count() {
        // z = 1 + x − 2y + 3xy − x² y + 0.5 y³ (total degree 3) on 40 × 30,
        // coordinates in index units; with gaps. Removed to round-off
        // (values up to ~1e5: 1e-8 absolute).
        let (nx, ny) = (40, 30);
        let f = |c: f64, r: f64| 1.0 + c - 2.0 * r + 3.0 * c * r - c * c * r + 0.5 * r * r * r;
        let mut z: Vec<f64> = (0..ny)
            .flat_map(|r| (0..nx).map(move |c| f(c as f64, r as f64)))
            .collect();
        for i in (0..z.len()).step_by(7) {
            z[i] = f64::NAN;
        }
        remove_polynomial_map(&mut z, nx, ny, 3).unwrap();
        let worst = z
            .iter()
            .filter(|v| !v.is_nan())
            .fold(0.0f64, |a, v| a.max(v.abs()));
        assert!(worst < 1e-8, "{worst}");
        // Degree 2 cannot hold x² y: a residual remains.
        let mut z: Vec<f64> = (0..ny)
            .flat_map(|r| (0..nx).map(move |c| f(c as f64, r as f64)))
            .collect();
        remove_polynomial_map(&mut z, nx, ny, 2).unwrap();
        assert!(z.iter().any(|v| v.abs() > 1.0));
        // Too few points for the degree: an error, not a wrong surface.
        let mut z = vec![f64::NAN; nx * ny];
        z[3] = 1.0;
        z[4] = 2.0;
        assert!(remove_polynomial_map(&mut z, nx, ny, 2).is_err());
    }
}
