//! Hybrid and direction parameters of a map: Sdr (ISO 25178-2) and Std
//! (the texture direction), MODELS.md §10.
//!
//! # Sdr
//! Developed interfacial area ratio, (true area / projected area) − 1 (a
//! fraction; ISO prints it in %). The true area of each grid cell is the
//! mean of its two triangulations (ISO 25178-2:2021 D.3, Eq. D.15; the same
//! as surfalize): a quarter of the sum of the four corner triangles, each
//! spanned by one x edge and one y edge, of area
//! ½ √((Δy Δz_x)² + (Δx Δz_y)² + (Δx Δy)²). The excess over the projected
//! cell is summed directly (√(1 + u) − 1 = u / (1 + √(1 + u))), so a smooth
//! surface's small Sdr keeps its digits. Cells with a corner not measured
//! are left out, of both areas.
//!
//! # Std
//! The angle of the largest value of the angular power spectrum (ISO
//! 25178-2: the direction of the dominant wavevector, perpendicular to the
//! lay of the texture; the lay is Std ± 90°), in degrees counter-clockwise
//! from +x with y increasing with the row index, in [0°, 180°). The power
//! abs(F)² of the map's 2-D transform (no window) is summed in bins of
//! 0.5°; Std is the power-weighted circular mean (of doubled angles) of the
//! wavevectors in the largest bin and its two neighbours, so a single
//! sinusoidal texture gives its exact angle rather than a bin edge. Points
//! not measured are set to zero (the mean plane).

use rayon::prelude::*;

use crate::signal::fft2::rfft2;

/// Sdr of a row-major `ny × nx` map (a fraction); `None` when no cell has
/// its four corners measured.
pub fn sdr(z: &[f64], nx: usize, ny: usize, dx: f64, dy: f64) -> Option<f64> {
    if nx < 2 || ny < 2 {
        return None;
    }
    let rows: Vec<(f64, usize)> = (0..ny - 1)
        .into_par_iter()
        .map(|r| {
            let (mut excess, mut cells) = (0.0, 0usize);
            let (a, b) = (&z[r * nx..(r + 1) * nx], &z[(r + 1) * nx..(r + 2) * nx]);
            for c in 0..nx - 1 {
                let (z00, z01, z10, z11) = (a[c], a[c + 1], b[c], b[c + 1]);
                let (bottom, top) = ((z01 - z00) / dx, (z11 - z10) / dx);
                let (left, right) = ((z10 - z00) / dy, (z11 - z01) / dy);
                let e = |gx: f64, gy: f64| {
                    let u = gx * gx + gy * gy;
                    u / (1.0 + (1.0 + u).sqrt())
                };
                let cell =
                    0.25 * (e(bottom, left) + e(bottom, right) + e(top, right) + e(top, left));
                if !cell.is_nan() {
                    excess += cell;
                    cells += 1;
                }
            }
            (excess, cells)
        })
        .collect();
    let (excess, cells) = rows.iter().fold((0.0, 0), |(e, n), r| (e + r.0, n + r.1));
    (cells > 0).then(|| excess / cells as f64)
}

/// Bin width of the angular spectrum (degrees).
const BIN_DEG: f64 = 0.5;

/// Std (degrees in [0, 180)); `None` for a map without variance.
pub fn texture_direction(z: &[f64], nx: usize, ny: usize, dx: f64, dy: f64) -> Option<f64> {
    let h: Vec<f64> = z
        .iter()
        .map(|&v| if v.is_nan() { 0.0 } else { v })
        .collect();
    let spec = rfft2(&h, nx, ny, ny, nx);
    let (sx, sy) = (nx as f64 * dx, ny as f64 * dy);
    // (angle in [0, 180), power × mirror weight) of every entry but DC.
    let entries: Vec<(f64, f64)> = (0..spec.half())
        .into_par_iter()
        .flat_map_iter(|kx| {
            let spec = &spec;
            let weight = if kx == 0 || 2 * kx == nx { 1.0 } else { 2.0 };
            (0..ny).filter_map(move |ky| {
                let fy = if ky <= ny / 2 {
                    ky as f64
                } else {
                    ky as f64 - ny as f64
                };
                let (qx, qy) = (kx as f64 / sx, fy / sy);
                let f = spec.at(ky, kx);
                let pw = weight * (f.0 * f.0 + f.1 * f.1);
                ((kx, ky) != (0, 0)).then(|| (qy.atan2(qx).to_degrees().rem_euclid(180.0), pw))
            })
        })
        .collect();
    let nbins = (180.0 / BIN_DEG).round() as usize;
    let bin = |a: f64| ((a / BIN_DEG) as usize).min(nbins - 1);
    let mut sums = vec![0.0; nbins];
    for &(a, p) in &entries {
        sums[bin(a)] += p;
    }
    let (best, &top) = sums.iter().enumerate().max_by(|a, b| a.1.total_cmp(b.1))?;
    if top.is_nan() || top <= 0.0 {
        return None;
    }
    let near = |b: usize| {
        let d = (b as isize - best as isize).rem_euclid(nbins as isize);
        d <= 1 || d == nbins as isize - 1
    };
    let (s, c) =
        entries
            .iter()
            .filter(|(a, _)| near(bin(*a)))
            .fold((0.0, 0.0), |(s, c), &(a, p)| {
                let t = 2.0 * a.to_radians();
                (s + p * t.sin(), c + p * t.cos())
            });
    Some((s.atan2(c) / 2.0).to_degrees().rem_euclid(180.0))
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    #[test]
    fn sdr_of_a_tilted_plane_is_exact() {
        // z = a x + b y: every corner triangle has the same slope, so
        // Sdr = √(1 + a² + b²) − 1 to round-off.
        let (nx, ny, dx, dy) = (30usize, 20usize, 1e-6, 2e-6);
        let (a, b) = (0.3, -0.4);
        let z: Vec<f64> = (0..ny)
            .flat_map(|r| (0..nx).map(move |c| a * c as f64 * dx + b * r as f64 * dy))
            .collect();
        let want = (1.0f64 + a * a + b * b).sqrt() - 1.0;
        assert!((sdr(&z, nx, ny, dx, dy).unwrap() - want).abs() < 1e-14);
    }

    #[test]
    fn std_of_a_plane_wave_is_its_wavevector_angle() {
        // z = sin(2π(3x/Lx + 5y/Ly)) on a periodic grid: wavevector
        // (3/Lx, 5/Ly), angle atan2(5/Ly, 3/Lx), exact on the FFT grid.
        let (nx, ny, dx, dy) = (64usize, 48usize, 1.0, 1.5);
        let (lx, ly) = (nx as f64 * dx, ny as f64 * dy);
        let z: Vec<f64> = (0..ny)
            .flat_map(|r| {
                (0..nx).map(move |c| {
                    (2.0 * PI * (3.0 * c as f64 * dx / lx + 5.0 * r as f64 * dy / ly)).sin()
                })
            })
            .collect();
        let want = (5.0 / ly).atan2(3.0 / lx).to_degrees();
        let got = texture_direction(&z, nx, ny, dx, dy).unwrap();
        assert!((got - want).abs() < 1e-9, "{got} vs {want}");
        // The same wave mirrored (−5 along y): 180° − the angle.
        let z: Vec<f64> = (0..ny)
            .flat_map(|r| {
                (0..nx).map(move |c| {
                    (2.0 * PI * (3.0 * c as f64 * dx / lx - 5.0 * r as f64 * dy / ly)).sin()
                })
            })
            .collect();
        let got = texture_direction(&z, nx, ny, dx, dy).unwrap();
        assert!((got - (180.0 - want)).abs() < 1e-9, "{got}");
    }
}
