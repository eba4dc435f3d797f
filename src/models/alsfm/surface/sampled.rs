//! Sampled periodic surfaces: heights on a grid that wraps around,
//! interpolated linearly along a profile and bilinearly over a map. At a
//! sample point the slope is the one on the right (x increasing).

use crate::error::{Error, Result};

/// A row-major map of `nx` samples per row, spacing dx along x, dy along y.
pub(super) struct Grid<'a> {
    dx: f64,
    dy: f64,
    nx: usize,
    z: &'a [f64],
}

impl<'a> Grid<'a> {
    /// The grid of a validated map (`nx` ≥ 2, whole rows).
    pub fn of(dx: f64, dy: f64, nx: usize, z: &'a [f64]) -> Self {
        Grid { dx, dy, nx, z }
    }

    fn ny(&self) -> usize {
        self.z.len() / self.nx
    }

    /// The corners z(i, j), z(i+1, j), z(i, j+1), z(i+1, j+1) of the cell
    /// holding (x, y), and the fractions of the way across it.
    fn cell_at(&self, x: f64, y: f64) -> ([f64; 4], f64, f64) {
        let (nx, ny) = (self.nx, self.ny());
        let (i, fx) = cell(x, self.dx, nx);
        let (j, fy) = cell(y, self.dy, ny);
        let at = |i: usize, j: usize| self.z[j * nx + i];
        let (i1, j1) = ((i + 1) % nx, (j + 1) % ny);
        ([at(i, j), at(i1, j), at(i, j1), at(i1, j1)], fx, fy)
    }

    /// Height, bilinear in the cell.
    pub fn height(&self, x: f64, y: f64) -> f64 {
        let ([z00, z10, z01, z11], fx, fy) = self.cell_at(x, y);
        let z0 = z00 + fx * (z10 - z00);
        let z1 = z01 + fx * (z11 - z01);
        z0 + fy * (z1 - z0)
    }

    /// Gradient of the bilinear height.
    pub fn gradient(&self, x: f64, y: f64) -> (f64, f64) {
        let ([z00, z10, z01, z11], fx, fy) = self.cell_at(x, y);
        let gx0 = (z10 - z00) / self.dx;
        let gx1 = (z11 - z01) / self.dx;
        let gy0 = (z01 - z00) / self.dy;
        let gy1 = (z11 - z10) / self.dy;
        (gx0 + fy * (gx1 - gx0), gy0 + fx * (gy1 - gy0))
    }

    /// Largest |∇z| at the cells' centres.
    pub fn max_slope(&self) -> f64 {
        let (nx, ny) = (self.nx, self.ny());
        let (px, py) = (self.dx * nx as f64, self.dy * ny as f64);
        let mut m = 0.0_f64;
        for j in 0..ny {
            for i in 0..nx {
                let (gx, gy) = self.gradient(
                    (i as f64 + 0.5) * px / nx as f64,
                    (j as f64 + 0.5) * py / ny as f64,
                );
                m = m.max(gx.hypot(gy));
            }
        }
        m
    }
}

/// Height of a profile at x, linear between samples.
pub(super) fn profile_height(dx: f64, z: &[f64], x: f64) -> f64 {
    let (j, f) = cell(x, dx, z.len());
    z[j] + f * (z[(j + 1) % z.len()] - z[j])
}

/// Slope of a profile at x (the sample interval's).
pub(super) fn profile_slope(dx: f64, z: &[f64], x: f64) -> f64 {
    let (j, _) = cell(x, dx, z.len());
    (z[(j + 1) % z.len()] - z[j]) / dx
}

/// Largest |slope| over a profile's intervals.
pub(super) fn profile_max_slope(dx: f64, z: &[f64]) -> f64 {
    (0..z.len())
        .map(|j| ((z[(j + 1) % z.len()] - z[j]) / dx).abs())
        .fold(0.0, f64::max)
}

/// At least `min_len` heights, all finite.
pub(super) fn check_heights(z: &[f64], min_len: usize) -> Result<()> {
    if z.len() < min_len {
        return Err(Error::Config(format!(
            "sampled surface needs at least {min_len} heights, got {}",
            z.len()
        )));
    }
    if let Some(j) = z.iter().position(|v| !v.is_finite()) {
        return Err(Error::Config(format!(
            "sampled surface height {j} is not finite ({})",
            z[j]
        )));
    }
    Ok(())
}

/// Lowest and highest height.
pub(super) fn min_max(z: &[f64]) -> (f64, f64) {
    z.iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| {
            (a.min(*v), b.max(*v))
        })
}

/// Heights scaled by `b` about the lowest.
pub(super) fn scale_about_min(z: &[f64], b: f64) -> Vec<f64> {
    let (lo, _) = min_max(z);
    z.iter().map(|v| lo + b * (v - lo)).collect()
}

/// Mean height above the lowest.
pub(super) fn mean_above_min(z: &[f64]) -> f64 {
    let (lo, _) = min_max(z);
    z.iter().map(|v| v - lo).sum::<f64>() / z.len() as f64
}

/// Cell index and fraction of `x` on a periodic grid of `n` samples.
fn cell(x: f64, dx: f64, n: usize) -> (usize, f64) {
    let u = (x / dx).rem_euclid(n as f64);
    let j = (u.floor() as usize).min(n - 1);
    (j, u - j as f64)
}
