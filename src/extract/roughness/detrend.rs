//! Form removal: mean, least-squares line (profiles), least-squares plane
//! (maps). Positions are taken relative to the window's centre so that the
//! normal equations stay well conditioned for long profiles.

use super::params::Detrend;

/// Detrends heights in place. The line is fitted against `positions` when
/// given (the positions as written in the file), else against the sample
/// index (for equal spacing the spacing cancels out of the residuals).
pub fn detrend_profile_at(z: &mut [f64], positions: Option<&[f64]>, how: Detrend) {
    let (Detrend::Line, Some(x)) = (how, positions) else {
        return detrend_profile(z, how);
    };
    let n = z.len() as f64;
    let mx = x.iter().sum::<f64>() / n;
    let mz = z.iter().sum::<f64>() / n;
    let (mut sxz, mut sxx) = (0.0, 0.0);
    for (&xi, &zi) in x.iter().zip(z.iter()) {
        sxz += (xi - mx) * (zi - mz);
        sxx += (xi - mx) * (xi - mx);
    }
    let b = if sxx > 0.0 { sxz / sxx } else { 0.0 };
    for (v, &xi) in z.iter_mut().zip(x) {
        *v -= mz + b * (xi - mx);
    }
}

/// Detrends equally spaced heights in place. The line is fitted against the
/// sample index (the spacing cancels out of the residuals).
pub fn detrend_profile(z: &mut [f64], how: Detrend) {
    let n = z.len();
    if n == 0 {
        return;
    }
    match how {
        Detrend::None => {}
        Detrend::Mean => {
            let m = z.iter().sum::<f64>() / n as f64;
            z.iter_mut().for_each(|v| *v -= m);
        }
        Detrend::Line => {
            let c = (n as f64 - 1.0) / 2.0;
            let (mut sz, mut sxz, mut sxx) = (0.0, 0.0, 0.0);
            for (i, &v) in z.iter().enumerate() {
                let t = i as f64 - c;
                sz += v;
                sxz += t * v;
                sxx += t * t;
            }
            let a = sz / n as f64;
            let b = if sxx > 0.0 { sxz / sxx } else { 0.0 };
            for (i, v) in z.iter_mut().enumerate() {
                *v -= a + b * (i as f64 - c);
            }
        }
    }
}

/// Detrends a row-major `ny × nx` map in place; [`Detrend::Line`] removes the
/// least-squares plane z = a + b·x + c·y. On a full regular grid with centred
/// coordinates the normal equations decouple: b and c are the separate
/// one-dimensional slopes.
pub fn detrend_map(z: &mut [f64], nx: usize, ny: usize, how: Detrend) {
    if z.is_empty() {
        return;
    }
    match how {
        Detrend::None => {}
        Detrend::Mean => detrend_profile(z, Detrend::Mean),
        Detrend::Line => {
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
    }
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
    fn plane_detrend_removes_a_plane() {
        let (nx, ny) = (13, 9);
        let mut z: Vec<f64> = (0..ny)
            .flat_map(|r| (0..nx).map(move |c| 1.0 + 0.3 * c as f64 - 0.7 * r as f64))
            .collect();
        detrend_map(&mut z, nx, ny, Detrend::Line);
        assert!(z.iter().all(|v| v.abs() < 1e-12));
    }

    #[test]
    fn mean_detrend_gives_zero_mean() {
        let mut z = vec![1.0, 2.0, 6.0, 3.0];
        detrend_profile(&mut z, Detrend::Mean);
        assert!(z.iter().sum::<f64>().abs() < 1e-15);
        assert!((z[2] - 3.0).abs() < 1e-15);
    }
}
