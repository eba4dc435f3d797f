//! An areal height map z(x, y) on a regular grid, in metres; NaN heights
//! are points not measured ([`super::mask`]).

use super::surface::{bad, check_heights, grid_range, MIN_POINTS};
use crate::error::Result;
use crate::signal::scan;

/// An areal height map z(x, y) on a regular grid, row-major: row r (y index)
/// holds `nx` heights along x. Heights, spacings and origin in metres.
#[derive(Debug, Clone, PartialEq)]
pub struct AreaMap {
    /// Where the data came from, for messages.
    pub source: String,
    /// Position of the first column (m); 0 unless the file gives positions.
    pub x0: f64,
    /// Position of the first row (m).
    pub y0: f64,
    /// Spacing along x (m), > 0.
    pub dx: f64,
    /// Spacing along y (m), > 0.
    pub dy: f64,
    /// Points per row (along x), ≥ [`MIN_POINTS`].
    pub nx: usize,
    /// Rows (along y), ≥ [`MIN_POINTS`].
    pub ny: usize,
    /// Heights (m), `z[r * nx + c]` at (x0 + c·Δx, y0 + r·Δy); NaN marks a
    /// point not measured ([`super::mask`]).
    pub z: Vec<f64>,
}

impl AreaMap {
    /// A validated map. Errors ([`Error::Input`]): a side shorter than
    /// [`MIN_POINTS`], size mismatch, bad spacing, an infinite height,
    /// fewer than [`MIN_POINTS`] measured (non-NaN) heights.
    pub fn new(source: &str, dx: f64, dy: f64, nx: usize, ny: usize, z: Vec<f64>) -> Result<Self> {
        if nx < MIN_POINTS || ny < MIN_POINTS {
            return Err(bad(
                source,
                format!("map is {nx} × {ny} points; at least {MIN_POINTS} per side are needed"),
            ));
        }
        if z.len() != nx * ny {
            return Err(bad(
                source,
                format!(
                    "map has {} heights; {nx} × {ny} = {} expected",
                    z.len(),
                    nx * ny
                ),
            ));
        }
        for (name, d) in [("x", dx), ("y", dy)] {
            if !(d.is_finite() && d > 0.0) {
                return Err(bad(
                    source,
                    format!("spacing along {name} is {d} m; expected a finite value > 0"),
                ));
            }
        }
        check_heights(source, &z, |i| {
            format!("row {}, column {}", i / nx + 1, i % nx + 1)
        })?;
        Ok(AreaMap {
            source: source.to_string(),
            x0: 0.0,
            y0: 0.0,
            dx,
            dy,
            nx,
            ny,
            z,
        })
    }
}

impl AreaMap {
    /// Points not measured (NaN heights).
    pub fn n_invalid(&self) -> usize {
        scan::count(&self.z, f64::is_nan)
    }

    /// The same map with its first point at (x0, y0).
    pub fn with_origin(mut self, x0: f64, y0: f64) -> Self {
        self.x0 = x0;
        self.y0 = y0;
        self
    }

    /// The part of the map inside the windows along x and y (inclusive,
    /// positions x0 + c·Δx and y0 + r·Δy); `None` keeps that axis whole.
    ///
    /// Errors ([`Error::Input`]): fewer than [`MIN_POINTS`] columns or rows
    /// inside, naming the axis.
    pub fn windowed(&self, wx: Option<(f64, f64)>, wy: Option<(f64, f64)>) -> Result<AreaMap> {
        let axis = |w: Option<(f64, f64)>, o: f64, d: f64, n: usize, name: &str| {
            let Some((a, b)) = w else {
                return Ok((0, n));
            };
            let (lo, hi) = grid_range(o, d, n, a, b);
            if hi <= lo || hi - lo < MIN_POINTS {
                return Err(bad(
                    &self.source,
                    format!(
                        "evaluation window along {name} [{a:.6e}, {b:.6e}] m holds {} points \
                         of the map spanning [{o:.6e}, {:.6e}] m; at least {MIN_POINTS} are needed",
                        hi.saturating_sub(lo),
                        o + (n - 1) as f64 * d
                    ),
                ));
            }
            Ok((lo, hi))
        };
        let (c0, c1) = axis(wx, self.x0, self.dx, self.nx, "x")?;
        let (r0, r1) = axis(wy, self.y0, self.dy, self.ny, "y")?;
        let z = (r0..r1)
            .flat_map(|r| self.z[r * self.nx + c0..r * self.nx + c1].iter().copied())
            .collect();
        Ok(AreaMap {
            source: self.source.clone(),
            x0: self.x0 + c0 as f64 * self.dx,
            y0: self.y0 + r0 as f64 * self.dy,
            dx: self.dx,
            dy: self.dy,
            nx: c1 - c0,
            ny: r1 - r0,
            z,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn map_rejects_size_mismatch_and_infinity_and_counts_nan() {
        assert!(AreaMap::new("m", 1.0, 1.0, 10, 10, vec![0.0; 99]).is_err());
        let mut z = vec![0.0; 100];
        z[23] = f64::INFINITY;
        let e = AreaMap::new("m", 1.0, 1.0, 10, 10, z.clone())
            .unwrap_err()
            .to_string();
        assert!(e.contains("row 3, column 4"), "{e}");
        z[23] = f64::NAN;
        assert_eq!(
            AreaMap::new("m", 1.0, 1.0, 10, 10, z).unwrap().n_invalid(),
            1
        );
    }

    #[test]
    fn map_window_selects_columns_and_rows_by_position() {
        // z = 100 r + c on a 20 × 12 grid, origin (1, 2), spacing (0.5, 0.25).
        let z: Vec<f64> = (0..12)
            .flat_map(|r| (0..20).map(move |c| (100 * r + c) as f64))
            .collect();
        let m = AreaMap::new("m", 0.5, 0.25, 20, 12, z)
            .unwrap()
            .with_origin(1.0, 2.0);
        let w = m.windowed(Some((2.0, 6.0)), Some((2.5, 4.5))).unwrap();
        // x = 1 + 0.5 c in [2, 6]: c = 2..=10; y = 2 + 0.25 r in [2.5, 4.5]: r = 2..=10.
        assert_eq!((w.nx, w.ny), (9, 9));
        // Exact: small integers and binary fractions.
        assert_eq!(
            (w.x0.to_bits(), w.y0.to_bits()),
            (2f64.to_bits(), 2.5f64.to_bits())
        );
        assert_eq!(w.z[0].to_bits(), 202f64.to_bits());
        assert_eq!(w.z[w.z.len() - 1].to_bits(), 1010f64.to_bits());
        assert_eq!(m.windowed(None, None).unwrap(), m);
        let e = m.windowed(None, Some((2.0, 3.0))).unwrap_err().to_string();
        assert!(e.contains("along y") && e.contains("holds 5 points"), "{e}");
    }
}
