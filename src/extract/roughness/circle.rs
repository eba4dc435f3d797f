//! Circle and cylinder form removal, for a roller's crown or a profile
//! measured across a cylinder (the F-operator of ISO 25178-2/-3 for curved
//! parts).
//!
//! # Profiles: the least-squares circle
//! (a, b, R) minimise Σ (√((x − a)² + (z − b)²) − R)² over the measured
//! points (radial, geometric residuals; R may be given, then only the
//! centre is fitted). Start: the circle of curvature of the least-squares
//! parabola at its vertex, in centred coordinates scaled by the length;
//! then Levenberg–Marquardt on the radial residuals. The arc is subtracted vertically: z − (b ± √(R² −
//! (x − a)²)), the sign of the side the profile lies on, so that a peak
//! stays a peak (as surfalize's `remove_cylinder` does).
//!
//! # Maps: the least-squares cylinder
//! Axis along y (or x, whichever direction is the less curved: the axis
//! runs along the straighter direction), through (x₀, y_c, z₀) with
//! direction (u, 1, w) (tilts in the plane and out of it), radius R:
//! residuals distance-to-axis − R, fitted by Levenberg–Marquardt from the
//! parabola of the mean cross-profile. Subtracted vertically as for the
//! circle.
//!
//! An arc flatter than its fit can resolve (a parabola coefficient below
//! 1e-9 / length: R above 5e8 × the length, a sagitta below 1e-9 of it)
//! is an error that says to remove a line instead; so is a point outside
//! the circle's reach.

use nalgebra::{DMatrix, DVector};

use crate::error::{Error, Result};

/// The fitted form.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FormFit {
    /// Radius of the circle or cylinder (m).
    pub radius: f64,
}

/// Levenberg–Marquardt on residuals `res(p, out)` of `m` points with a
/// forward-difference Jacobian; returns the parameters.
fn levenberg_marquardt(
    mut p: Vec<f64>,
    m: usize,
    res: impl Fn(&[f64], &mut [f64]),
    scale: &[f64],
) -> Vec<f64> {
    let k = p.len();
    let mut r = vec![0.0; m];
    res(&p, &mut r);
    let mut cost: f64 = r.iter().map(|v| v * v).sum();
    let mut lambda = 1e-3;
    let mut rp = vec![0.0; m];
    for _ in 0..200 {
        let mut jac = DMatrix::zeros(m, k);
        for j in 0..k {
            let h = 1e-7 * scale[j].max(p[j].abs() * 1e-3);
            let mut q = p.clone();
            q[j] += h;
            res(&q, &mut rp);
            for i in 0..m {
                jac[(i, j)] = (rp[i] - r[i]) / h;
            }
        }
        let jtj = jac.transpose() * &jac;
        let jtr = jac.transpose() * DVector::from_column_slice(&r);
        let mut improved = false;
        for _ in 0..20 {
            let mut a = jtj.clone();
            for d in 0..k {
                a[(d, d)] *= 1.0 + lambda;
            }
            let Some(step) = a.lu().solve(&(-&jtr)) else {
                lambda *= 10.0;
                continue;
            };
            let q: Vec<f64> = p.iter().zip(step.iter()).map(|(a, b)| a + b).collect();
            res(&q, &mut rp);
            let c: f64 = rp.iter().map(|v| v * v).sum();
            if c < cost {
                let small = step.iter().zip(scale).all(|(s, sc)| s.abs() <= 1e-12 * sc);
                p = q;
                std::mem::swap(&mut r, &mut rp);
                let done = small || cost - c <= 1e-15 * cost;
                cost = c;
                lambda = (lambda / 10.0).max(1e-12);
                improved = true;
                if done {
                    return p;
                }
                break;
            }
            lambda *= 10.0;
        }
        if !improved {
            break;
        }
    }
    p
}

/// The circle osculating the least-squares parabola z = c₀ + c₁ u + c₂ u²
/// of the points at its vertex: centre (u_v, z_v ∓ R), R = 1/(2 abs c₂); `None`
/// when the points are (numerically) collinear. A start for the
/// geometric fit, as surfalize starts its cylinder.
fn parabola_circle(u: &[f64], v: &[f64]) -> Option<(f64, f64, f64)> {
    let mut a = DMatrix::<f64>::zeros(3, 3);
    let mut b = DVector::<f64>::zeros(3);
    for (&ui, &vi) in u.iter().zip(v) {
        let row = [1.0, ui, ui * ui];
        for i in 0..3 {
            b[i] += row[i] * vi;
            for j in 0..3 {
                a[(i, j)] += row[i] * row[j];
            }
        }
    }
    let c = a.lu().solve(&b)?;
    if c[2].is_nan() || c[2].abs() <= 1e-9 {
        return None;
    }
    let uv = -c[1] / (2.0 * c[2]);
    let zv = c[0] + c[1] * uv + c[2] * uv * uv;
    let r = 1.0 / (2.0 * c[2].abs());
    Some((uv, if c[2] < 0.0 { zv - r } else { zv + r }, r))
}

fn too_flat(radius: f64, length: f64) -> Error {
    Error::NotApplicable(format!(
        "the profile is not curved enough for a circle (fitted radius {radius:.3e} m over \
         {length:.3e} m); remove a line or a polynomial instead"
    ))
}

/// Subtracts the least-squares circle from a profile (positions `x`,
/// heights `z`, NaN where not measured); `radius` fixes R when given.
pub fn remove_circle(z: &mut [f64], x: &[f64], radius: Option<f64>) -> Result<FormFit> {
    let pts: Vec<(f64, f64)> = x
        .iter()
        .zip(z.iter())
        .filter(|p| !p.1.is_nan())
        .map(|(a, b)| (*a, *b))
        .collect();
    let length = x[x.len() - 1] - x[0];
    // Centred and scaled by the length: O(1) numbers for the fit.
    let (mx, mz) = (
        pts.iter().map(|p| p.0).sum::<f64>() / pts.len() as f64,
        pts.iter().map(|p| p.1).sum::<f64>() / pts.len() as f64,
    );
    let s = length.max(f64::MIN_POSITIVE);
    let u: Vec<f64> = pts.iter().map(|p| (p.0 - mx) / s).collect();
    let v: Vec<f64> = pts.iter().map(|p| (p.1 - mz) / s).collect();
    let (a0, b0, r0) = parabola_circle(&u, &v).ok_or_else(|| too_flat(f64::INFINITY, length))?;
    let fixed = radius.map(|r| r / s);
    let res = |p: &[f64], out: &mut [f64]| {
        let rr = fixed.unwrap_or_else(|| p[2]);
        for (i, o) in out.iter_mut().enumerate() {
            *o = ((u[i] - p[0]).powi(2) + (v[i] - p[1]).powi(2)).sqrt() - rr;
        }
    };
    let start = match fixed {
        Some(_) => vec![a0, b0],
        None => vec![a0, b0, r0],
    };
    let scale = vec![r0.max(1.0); start.len()];
    let p = levenberg_marquardt(start, u.len(), res, &scale);
    let r = fixed.unwrap_or_else(|| p[2]);
    // The side of the centre the profile lies on.
    let side = if v.iter().sum::<f64>() / v.len() as f64 >= p[1] {
        1.0
    } else {
        -1.0
    };
    for (zi, &xi) in z.iter_mut().zip(x) {
        if zi.is_nan() {
            continue;
        }
        let d = r * r - ((xi - mx) / s - p[0]).powi(2);
        if d < 0.0 {
            return Err(Error::NotApplicable(format!(
                "a point at x = {xi:.6e} m lies beyond the fitted circle (radius {:.3e} m); \
                 the profile is not an arc",
                r * s
            )));
        }
        *zi -= mz + s * (p[1] + side * d.sqrt());
    }
    Ok(FormFit { radius: r * s })
}

/// Curvature (second-order coefficient) of the least-squares parabola of
/// the mean profile along x (`along_x`) or y of a map.
fn mean_profile_curvature(z: &[f64], nx: usize, ny: usize, along_x: bool) -> f64 {
    let (n, m) = if along_x { (nx, ny) } else { (ny, nx) };
    let mean: Vec<(f64, f64)> = (0..n)
        .filter_map(|i| {
            let vals = (0..m).map(|j| {
                if along_x {
                    z[j * nx + i]
                } else {
                    z[i * nx + j]
                }
            });
            let (s, k) = vals
                .filter(|v| !v.is_nan())
                .fold((0.0, 0), |(s, k), v| (s + v, k + 1));
            (k > 0).then(|| (i as f64 - (n - 1) as f64 / 2.0, s / k as f64))
        })
        .collect();
    // Legendre-like: fit c0 + c2 (t² − mean t²) with t centred: the
    // quadratic coefficient decouples from the linear one.
    let t2m = mean.iter().map(|p| p.0 * p.0).sum::<f64>() / mean.len() as f64;
    let (mut num, mut den) = (0.0, 0.0);
    for &(t, v) in &mean {
        num += (t * t - t2m) * v;
        den += (t * t - t2m).powi(2);
    }
    if den > 0.0 {
        (num / den).abs()
    } else {
        0.0
    }
}

/// Distance of the point `q` from the cylinder axis through (p0, 0, p1)
/// with direction (p2, 1, p3): |w × d| / |d|.
fn axis_distance(p: &[f64], q: &(f64, f64, f64)) -> f64 {
    let d = [p[2], 1.0, p[3]];
    let dn = (d[0] * d[0] + 1.0 + d[2] * d[2]).sqrt();
    let w = [q.0 - p[0], q.1, q.2 - p[1]];
    let c = [
        w[1] * d[2] - w[2] * d[1],
        w[2] * d[0] - w[0] * d[2],
        w[0] * d[1] - w[1] * d[0],
    ];
    (c[0] * c[0] + c[1] * c[1] + c[2] * c[2]).sqrt() / dn
}

/// Where the vertical line through (a, t) meets the cylinder of axis `p`
/// and radius `r` (|w × d|² = R² |d|², quadratic in w_z), on the side of
/// the surface (`side` = ±1); `None` when the line misses it.
fn cylinder_height(p: &[f64], r: f64, (a, t): (f64, f64), side: f64) -> Option<f64> {
    let d = [p[2], 1.0, p[3]];
    let dd = d[0] * d[0] + 1.0 + d[2] * d[2];
    let (wx, wy) = (a - p[0], t);
    let pxy = wx * d[0] + wy * d[1];
    let qa = dd - d[2] * d[2];
    let qb = -2.0 * d[2] * pxy;
    let qc = (wx * wx + wy * wy) * dd - pxy * pxy - r * r * dd;
    let disc = qb * qb - 4.0 * qa * qc;
    if disc < 0.0 {
        return None;
    }
    Some((-qb + side * disc.sqrt()) / (2.0 * qa))
}

/// Subtracts the least-squares cylinder from a row-major `ny × nx` map
/// (spacings `dx`, `dy`, NaN where not measured); the axis runs along the
/// less curved direction; `radius` fixes R when given.
pub fn remove_cylinder(
    z: &mut [f64],
    nx: usize,
    ny: usize,
    dx: f64,
    dy: f64,
    radius: Option<f64>,
) -> Result<FormFit> {
    // Axis along y when the rows (x) are the curved direction.
    let axis_y = mean_profile_curvature(z, nx, ny, true) / (dx * dx)
        >= mean_profile_curvature(z, nx, ny, false) / (dy * dy);
    // Coordinates: a across the axis, t along it.
    let coord = |i: usize| {
        let (r, c) = (i / nx, i % nx);
        let (x, y) = (c as f64 * dx, r as f64 * dy);
        if axis_y {
            (x, y)
        } else {
            (y, x)
        }
    };
    let idx: Vec<usize> = (0..z.len()).filter(|&i| !z[i].is_nan()).collect();
    let length = if axis_y {
        (nx - 1) as f64 * dx
    } else {
        (ny - 1) as f64 * dy
    };
    let s = length.max(f64::MIN_POSITIVE);
    let (ma, mt, mz) = {
        let k = idx.len() as f64;
        let (sa, st, sz) = idx.iter().fold((0.0, 0.0, 0.0), |acc, &i| {
            let (a, t) = coord(i);
            (acc.0 + a, acc.1 + t, acc.2 + z[i])
        });
        (sa / k, st / k, sz / k)
    };
    let pts: Vec<(f64, f64, f64)> = idx
        .iter()
        .map(|&i| {
            let (a, t) = coord(i);
            ((a - ma) / s, (t - mt) / s, (z[i] - mz) / s)
        })
        .collect();
    // Start: the circle of all points projected on the plane across the axis.
    let (ua, uz): (Vec<f64>, Vec<f64>) = pts.iter().map(|p| (p.0, p.2)).unzip();
    let (a0, b0, r0) = parabola_circle(&ua, &uz).ok_or_else(|| too_flat(f64::INFINITY, length))?;
    let fixed = radius.map(|r| r / s);
    let res = |p: &[f64], out: &mut [f64]| {
        let rr = fixed.unwrap_or_else(|| p[4]);
        for (o, q) in out.iter_mut().zip(&pts) {
            *o = axis_distance(p, q) - rr;
        }
    };
    let mut start = vec![a0, b0, 0.0, 0.0];
    if fixed.is_none() {
        start.push(r0);
    }
    let scale = vec![r0.max(1.0); start.len()];
    let p = levenberg_marquardt(start, pts.len(), res, &scale);
    let r = fixed.unwrap_or_else(|| p[4]);
    // The surface lies on the side of the axis where its points are.
    let above = uz.iter().sum::<f64>() / uz.len() as f64 >= p[1];
    let side = if above { 1.0 } else { -1.0 };
    for (i, zi) in z.iter_mut().enumerate() {
        if zi.is_nan() {
            continue;
        }
        let (a, t) = coord(i);
        let Some(wz) = cylinder_height(&p, r, ((a - ma) / s, (t - mt) / s), side) else {
            return Err(Error::NotApplicable(format!(
                "a point lies beyond the fitted cylinder (radius {:.3e} m); the map is \
                 not a cylinder",
                r * s
            )));
        };
        *zi -= mz + s * (p[1] + wz);
    }
    Ok(FormFit { radius: r * s })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn crown_of_a_roller_is_removed_leaving_the_roughness() {
        // An arc of radius 5 mm over 1 mm (sagitta 25 µm), off-centre, with
        // a gap: the fit recovers R and removes the arc to round-off.
        let (r, n) = (5e-3, 2001);
        let x: Vec<f64> = (0..n)
            .map(|i| -0.5e-3 + 1e-3 * i as f64 / (n - 1) as f64)
            .collect();
        let arc = |x: f64| 3e-6 + (r * r - (x - 0.1e-3).powi(2)).sqrt() - r;
        let mut z: Vec<f64> = x.iter().map(|&x| arc(x)).collect();
        z[700..720].fill(f64::NAN);
        let f = remove_circle(&mut z, &x, None).unwrap();
        assert!((f.radius - r).abs() < 1e-9 * r, "{}", f.radius);
        assert!(z.iter().filter(|v| !v.is_nan()).all(|v| v.abs() < 1e-12));
        assert_eq!(z.iter().filter(|v| v.is_nan()).count(), 20);
        // With a 0.1 µm sine of roughness on it: the sine remains (the fit
        // absorbs a little of it: R within 1e-4, the residual's RMS within
        // 1 % of the sine's).
        let rough = |x: f64| 0.1e-6 * (2.0 * std::f64::consts::PI * x / 20e-6).sin();
        let mut z: Vec<f64> = x.iter().map(|&x| arc(x) + rough(x)).collect();
        let f = remove_circle(&mut z, &x, None).unwrap();
        assert!((f.radius - r).abs() < 1e-4 * r, "{}", f.radius);
        let rms = (z.iter().map(|v| v * v).sum::<f64>() / n as f64).sqrt();
        assert!((rms - 0.1e-6 / 2f64.sqrt()).abs() < 1e-2 * 0.1e-6, "{rms}");
        // A straight line is not a circle.
        let mut flat: Vec<f64> = x.iter().map(|&x| 1e-3 * x).collect();
        assert!(remove_circle(&mut flat, &x, None).is_err());
        // With the radius given, a concave arc (a groove) too.
        let mut g: Vec<f64> = x.iter().map(|&x| r - (r * r - x * x).sqrt()).collect();
        let f = remove_circle(&mut g, &x, Some(r)).unwrap();
        assert!((f.radius - r).abs() < 1e-15 && g.iter().all(|v| v.abs() < 1e-12));
    }

    #[test]
    fn cylinder_with_a_tilted_axis_is_removed() {
        // Cylinder of radius 2 mm, axis along y rising with slope t = 0.01
        // and shifted in x, on a 120 × 80 grid of 5 µm. Its vertical
        // section at y is z = t y + √(1 + t²) √(R² − (x − x₀)²) (the
        // section across the axis is the circle). Removed to round-off of
        // the fit (heights ~2 mm: 1e-11 m).
        let (nx, ny, d, r, t) = (120usize, 80usize, 5e-6, 2e-3, 0.01);
        let z: Vec<f64> = (0..ny)
            .flat_map(|row| {
                (0..nx).map(move |c| {
                    let (x, y) = (c as f64 * d, row as f64 * d);
                    t * y + (1.0f64 + t * t).sqrt() * (r * r - (x - 0.2e-3).powi(2)).sqrt()
                })
            })
            .collect();
        let mut m = z.clone();
        let f = remove_cylinder(&mut m, nx, ny, d, d, None).unwrap();
        assert!((f.radius - r).abs() < 1e-9 * r, "{}", f.radius);
        let worst = m.iter().fold(0.0f64, |a, v| a.max(v.abs()));
        assert!(worst < 1e-11, "{worst}");
    }
}
