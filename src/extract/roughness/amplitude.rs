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

/// Amplitude parameters of `z`; `scale` is the largest |height| of the data
/// before detrending, for the flatness test.
pub fn amplitude(z: &[f64], scale: f64) -> Amplitude {
    let n = z.len() as f64;
    let (mut s1, mut s2, mut s3, mut s4) = (0.0, 0.0, 0.0, 0.0);
    for &v in z {
        let v2 = v * v;
        s1 += v.abs();
        s2 += v2;
        s3 += v2 * v;
        s4 += v2 * v2;
    }
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
fn slope_sq_sum(z: &[f64], dx: f64, scheme: DerivativeScheme) -> (f64, usize) {
    let mut s = 0.0;
    let mut k = 0usize;
    let mut add = |d: f64| {
        s += d * d;
        k += 1;
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

/// RMS slope sqrt(mean((dz/dx)²)) (dimensionless), `None` when the scheme
/// has no point to evaluate.
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

/// RMS gradient sqrt(mean((∂z/∂x)² + (∂z/∂y)²)) of a row-major map (Sdq,
/// ISO 25178-2), averaged over the grid points where the scheme gives both
/// derivatives (for forward differences the (nx − 1) × (ny − 1) points, as
/// SurfaceTopography's `rms_gradient` does). The sum separates: x-slopes
/// of the interior rows plus y-slopes of the interior columns.
pub fn rms_gradient(
    z: &[f64],
    nx: usize,
    ny: usize,
    dx: f64,
    dy: f64,
    scheme: DerivativeScheme,
) -> Option<f64> {
    let (lo, hi) = dropped(scheme);
    if nx < lo + hi + 1 || ny < lo + hi + 1 {
        return None;
    }
    let mut sum = 0.0;
    for row in z.chunks(nx).take(ny - hi).skip(lo) {
        sum += slope_sq_sum(row, dx, scheme).0;
    }
    let mut col = vec![0.0; ny];
    for c in lo..nx - hi {
        for (r, v) in col.iter_mut().enumerate() {
            *v = z[r * nx + c];
        }
        sum += slope_sq_sum(&col, dy, scheme).0;
    }
    let count = (nx - lo - hi) * (ny - lo - hi);
    Some((sum / count as f64).sqrt())
}

/// atan of a slope, in degrees.
pub fn slope_angle_deg(slope: f64) -> f64 {
    slope.atan().to_degrees()
}
