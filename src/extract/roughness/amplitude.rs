//! Amplitude parameters (ISO 4287 / ISO 25178-2) and the RMS slope.
//!
//! With z the heights after detrending/filtering (reference line z = 0):
//!
//! | parameter | formula |
//! |---|---|
//! | Ra | mean(abs(z)) |
//! | Rq | sqrt(mean(z²)) |
//! | Rsk | mean(z³) / Rq³ |
//! | Rku | mean(z⁴) / Rq⁴ |
//! | Rdq | sqrt(mean((dz/dx)²)), reported as atan(Rdq) in degrees |
//!
//! The same formulas applied to a map give Sa, Sq, Ssk, Sku and
//! Sdq = sqrt(mean(|∇z|²)).

use super::params::DerivativeScheme;

/// Ra, Rq, and Rsk, Rku when defined.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Amplitude {
    /// Ra (m).
    pub ra: f64,
    /// Rq (m).
    pub rq: f64,
    /// Rsk; `None` for a flat profile.
    pub rsk: Option<f64>,
    /// Rku; `None` for a flat profile.
    pub rku: Option<f64>,
    /// Whether the profile is flat: Rq = 0, or Rq ≤ 1e-12 of the largest
    /// height magnitude before detrending (round-off of removing an exact
    /// line). Rsk and Rku are 0/0 then.
    pub flat: bool,
}

/// Relative threshold below which Rq counts as zero (see [`Amplitude::flat`]).
pub const FLAT_RELATIVE: f64 = 1e-12;

/// Amplitude parameters of `z` over its measured points (NaN is a point
/// not measured, [`super::mask`]); `scale` is the largest |height| of the
/// data before detrending, for the flatness test. A select rather than a
/// branch skips a NaN, so measured heights are summed in the same order
/// with or without gaps.
pub fn amplitude(z: &[f64], scale: f64) -> Amplitude {
    let (mut s1, mut s2, mut s3, mut s4) = (0.0, 0.0, 0.0, 0.0);
    let mut count = 0usize;
    for &v in z {
        let ok = !v.is_nan();
        let v = if ok { v } else { 0.0 };
        count += usize::from(ok);
        let v2 = v * v;
        s1 += v.abs();
        s2 += v2;
        s3 += v2 * v;
        s4 += v2 * v2;
    }
    let n = count as f64;
    let ra = s1 / n;
    let rq = (s2 / n).sqrt();
    let flat = rq == 0.0 || rq <= FLAT_RELATIVE * scale;
    let (rsk, rku) = if flat {
        (None, None)
    } else {
        (Some(s3 / n / rq.powi(3)), Some(s4 / n / rq.powi(4)))
    };
    Amplitude {
        ra,
        rq,
        rsk,
        rku,
        flat,
    }
}

/// Local slopes of equally spaced heights with the given scheme. Returns
/// fewer values than points: n − 1 (forward), n − 2 (central), n − 6
/// (7-point).
pub fn slopes(z: &[f64], dx: f64, scheme: DerivativeScheme) -> Vec<f64> {
    let n = z.len();
    match scheme {
        DerivativeScheme::Forward => z.windows(2).map(|w| (w[1] - w[0]) / dx).collect(),
        DerivativeScheme::Central => z.windows(3).map(|w| (w[2] - w[0]) / (2.0 * dx)).collect(),
        DerivativeScheme::Iso7Point => {
            if n < 7 {
                return Vec::new();
            }
            z.windows(7)
                .map(|w| {
                    (w[6] - 9.0 * w[5] + 45.0 * w[4] - 45.0 * w[2] + 9.0 * w[1] - w[0])
                        / (60.0 * dx)
                })
                .collect()
        }
    }
}

/// Sum of squared slopes and their count, streamed without allocating.
/// A stencil that touches a point not measured gives NaN and is left out.
fn slope_sq_sum(z: &[f64], dx: f64, scheme: DerivativeScheme) -> (f64, usize) {
    let mut s = 0.0;
    let mut k = 0usize;
    let mut add = |d: f64| {
        if !d.is_nan() {
            s += d * d;
            k += 1;
        }
    };
    match scheme {
        DerivativeScheme::Forward => z.windows(2).for_each(|w| add((w[1] - w[0]) / dx)),
        DerivativeScheme::Central => z.windows(3).for_each(|w| add((w[2] - w[0]) / (2.0 * dx))),
        DerivativeScheme::Iso7Point => z.windows(7).for_each(|w| {
            add((w[6] - 9.0 * w[5] + 45.0 * w[4] - 45.0 * w[2] + 9.0 * w[1] - w[0]) / (60.0 * dx))
        }),
    }
    (s, k)
}

/// RMS slope sqrt(mean((dz/dx)²)) (dimensionless) over the stencils whose
/// points are all measured; `None` when there is none.
pub fn rms_slope(z: &[f64], dx: f64, scheme: DerivativeScheme) -> Option<f64> {
    let (s, k) = slope_sq_sum(z, dx, scheme);
    (k > 0).then(|| (s / k as f64).sqrt())
}

/// Points a scheme drops at the start and at the end of a line.
fn dropped(scheme: DerivativeScheme) -> (usize, usize) {
    match scheme {
        DerivativeScheme::Forward => (0, 1),
        DerivativeScheme::Central => (1, 1),
        DerivativeScheme::Iso7Point => (3, 3),
    }
}

/// The slope at `z[i]` along a line of stride `step` (1 along x, nx along
/// y), spacing `d`, with the scheme; NaN when the stencil touches a point
/// not measured. The caller keeps the stencil inside the grid.
#[inline]
fn slope_at(z: &[f64], i: usize, step: usize, d: f64, scheme: DerivativeScheme) -> f64 {
    let at = |k: isize| z[(i as isize + k * step as isize) as usize];
    match scheme {
        DerivativeScheme::Forward => (at(1) - at(0)) / d,
        DerivativeScheme::Central => (at(1) - at(-1)) / (2.0 * d),
        DerivativeScheme::Iso7Point => {
            (at(3) - 9.0 * at(2) + 45.0 * at(1) - 45.0 * at(-1) + 9.0 * at(-2) - at(-3))
                / (60.0 * d)
        }
    }
}

/// RMS gradient sqrt(mean((∂z/∂x)² + (∂z/∂y)²)) of a row-major map (Sdq,
/// ISO 25178-2), averaged over the grid points where the scheme gives both
/// derivatives (for forward differences the (nx − 1) × (ny − 1) points, as
/// SurfaceTopography's `rms_gradient` does) from measured points only.
/// Rows in parallel; each row's sum in column order and the rows' sums in
/// row order, so the same bits whatever the thread count.
pub fn rms_gradient(
    z: &[f64],
    nx: usize,
    ny: usize,
    dx: f64,
    dy: f64,
    scheme: DerivativeScheme,
) -> Option<f64> {
    use rayon::prelude::*;
    let (lo, hi) = dropped(scheme);
    if nx < lo + hi + 1 || ny < lo + hi + 1 {
        return None;
    }
    let rows: Vec<(f64, usize)> = (lo..ny - hi)
        .into_par_iter()
        .map(|r| {
            let (mut s, mut k) = (0.0, 0usize);
            for c in lo..nx - hi {
                let i = r * nx + c;
                let (gx, gy) = (
                    slope_at(z, i, 1, dx, scheme),
                    slope_at(z, i, nx, dy, scheme),
                );
                let g = gx * gx + gy * gy;
                if !g.is_nan() {
                    s += g;
                    k += 1;
                }
            }
            (s, k)
        })
        .collect();
    let (sum, count) = rows
        .iter()
        .fold((0.0, 0usize), |(s, k), &(a, b)| (s + a, k + b));
    (count > 0).then(|| (sum / count as f64).sqrt())
}

/// atan of a slope, in degrees.
pub fn slope_angle_deg(slope: f64) -> f64 {
    slope.atan().to_degrees()
}
