//! Validated inputs: an equally spaced stylus [`Profile`] z(x) (and the
//! areal [`AreaMap`](super::map::AreaMap) z(x, y)), in metres. A NaN height is a
//! point the instrument did not measure ([`super::mask`]).

use crate::error::{Error, Location, Result};
use crate::signal::scan;
use rayon::prelude::*;

/// Fewest points a profile (or each side of a map) may have. Below that the
/// 7-point derivative and the structure-function fit have nothing to work on.
pub const MIN_POINTS: usize = 8;

/// An equally spaced profile z(x). Heights and positions in metres.
#[derive(Debug, Clone, PartialEq)]
pub struct Profile {
    /// Where the data came from (file path or a label), for messages.
    pub source: String,
    /// Position of the first sample (m).
    pub x0: f64,
    /// Sample spacing Δx (m), > 0.
    pub dx: f64,
    /// Heights (m) at x0 + i·Δx; NaN marks a point the instrument did not
    /// measure ([`super::mask`]). At least [`MIN_POINTS`] are measured.
    pub z: Vec<f64>,
    /// The positions as written in the file (m), when the profile was built
    /// from them ([`Profile::from_xz`]). They select the evaluation window
    /// and carry the least-squares line, as vendor software does with its
    /// own positions (the Dektak check, MODELS.md §4); slopes and spectra
    /// use the uniform spacing Δx.
    pub positions: Option<Vec<f64>>,
}

pub(super) fn bad(source: &str, message: String) -> Error {
    Error::input(Location::file(source), message)
}

/// Heights may be NaN (not measured) but never infinite, and at least
/// [`MIN_POINTS`] must be measured. `at` names point `i` for the message.
pub(super) fn check_heights(source: &str, z: &[f64], at: impl Fn(usize) -> String) -> Result<()> {
    if let Some(i) = scan::first_position(z, f64::is_infinite) {
        return Err(bad(
            source,
            format!(
                "height at {} is {}; expected a finite number, or NaN for a point \
                 not measured",
                at(i),
                z[i]
            ),
        ));
    }
    let measured = z.len() - scan::count(z, f64::is_nan);
    if measured < MIN_POINTS {
        return Err(bad(
            source,
            format!(
                "{measured} of {} points are measured (the others are NaN); at least \
                 {MIN_POINTS} are needed",
                z.len()
            ),
        ));
    }
    Ok(())
}

/// Largest deviation of a position from its uniform-grid slot, as a fraction
/// of the spacing, that is still accepted as uniform. Exports print x rounded
/// (the Dektak file prints a 0.156 µm step with one decimal), which moves a
/// point by up to 0.32 Δx; a point further than half a step from its slot is
/// on the wrong slot, so the sampling is not uniform.
pub const UNIFORM_TOLERANCE: f64 = 0.5;

impl Profile {
    /// A profile from its spacing and heights.
    ///
    /// Errors ([`Error::Input`], naming `source`): fewer than [`MIN_POINTS`]
    /// points or measured points, a spacing that is not finite and
    /// positive, an infinite height (the first one's index is given). NaN
    /// is a point not measured, not an error.
    pub fn new(source: &str, x0: f64, dx: f64, z: Vec<f64>) -> Result<Self> {
        if z.len() < MIN_POINTS {
            return Err(bad(
                source,
                format!(
                    "profile has {} points; at least {MIN_POINTS} are needed",
                    z.len()
                ),
            ));
        }
        if !dx.is_finite() || dx <= 0.0 || !x0.is_finite() {
            return Err(bad(
                source,
                format!("sample spacing {dx} m, start {x0} m; expected finite, spacing > 0"),
            ));
        }
        check_heights(source, &z, |i| {
            format!("point {} (x = {:.6e} m)", i + 1, x0 + i as f64 * dx)
        })?;
        Ok(Profile {
            source: source.to_string(),
            x0,
            dx,
            z,
            positions: None,
        })
    }

    /// A profile from positions and heights (m). The positions must increase
    /// strictly and be uniform within [`UNIFORM_TOLERANCE`] of a step; the
    /// grid (x0, Δx) is the least-squares line of x against the index.
    pub fn from_xz(source: &str, x: Vec<f64>, z: Vec<f64>) -> Result<Self> {
        if x.len() != z.len() {
            return Err(bad(
                source,
                format!("{} positions but {} heights", x.len(), z.len()),
            ));
        }
        if x.len() < MIN_POINTS {
            return Err(bad(
                source,
                format!(
                    "profile has {} points; at least {MIN_POINTS} are needed",
                    x.len()
                ),
            ));
        }
        // The checks find the first offending point on all threads.
        if let Some(i) = scan::first_position(&x, |v| !v.is_finite()) {
            return Err(bad(
                source,
                format!("position at point {} is {}; expected a number", i + 1, x[i]),
            ));
        }
        if let Some(i) = scan::first_pair(&x, |a, b| b <= a) {
            return Err(bad(
                source,
                format!(
                    "positions do not increase strictly: point {} has x = {:.6e} m after \
                     x = {:.6e} m; expected a monotonic scan (sort it or split it)",
                    i + 2,
                    x[i + 1],
                    x[i]
                ),
            ));
        }
        // Grid by least squares of x against the index: robust to the
        // rounding of printed positions, which biases end-point estimates.
        let n = x.len();
        let c = (n as f64 - 1.0) / 2.0;
        let mean = x.iter().sum::<f64>() / n as f64;
        let (mut sxy, mut sxx) = (0.0, 0.0);
        for (i, &xi) in x.iter().enumerate() {
            let t = i as f64 - c;
            sxy += t * (xi - mean);
            sxx += t * t;
        }
        let dx = sxy / sxx;
        let x0 = mean - dx * c;
        // The first largest deviation: chunks keep their first, and the
        // earlier chunk wins a tie, as one pass would.
        let later_if_larger = |a: (usize, f64), b: (usize, f64)| if b.1 > a.1 { b } else { a };
        let (worst, dev) = x
            .par_chunks(1 << 16)
            .enumerate()
            .map(|(c, s)| {
                let at = |(j, &xi): (usize, &f64)| {
                    let i = c * (1 << 16) + j;
                    (i, (xi - (x0 + i as f64 * dx)).abs() / dx)
                };
                s.iter().enumerate().map(at).fold((0, 0.0), later_if_larger)
            })
            .reduce(|| (0, 0.0), later_if_larger);
        if dev > UNIFORM_TOLERANCE {
            return Err(bad(
                source,
                format!(
                    "positions are not equally spaced: point {} at x = {:.6e} m is {:.2} \
                     steps away from its slot on the uniform grid of step {:.6e} m; \
                     expected uniform sampling (resample first)",
                    worst + 1,
                    x[worst],
                    dev,
                    dx
                ),
            ));
        }
        let mut p = Profile::new(source, x0, dx, z)?;
        p.positions = Some(x);
        Ok(p)
    }

    /// Index range [lo, hi) of the samples with window.0 ≤ x ≤ window.1
    /// (inclusive, with a tolerance of 1e-9 Δx for round-off in the bounds);
    /// the whole profile for `None`. Positions as written select when known.
    ///
    /// Errors ([`Error::Input`]): fewer than [`MIN_POINTS`] samples inside.
    pub fn window_range(&self, window: Option<(f64, f64)>) -> Result<(usize, usize)> {
        let n = self.z.len();
        let Some((a, b)) = window else {
            return Ok((0, n));
        };
        let tol = 1e-9 * self.dx;
        let (lo, hi) = match &self.positions {
            Some(x) => (
                x.partition_point(|&v| v < a - tol),
                x.partition_point(|&v| v <= b + tol),
            ),
            None => grid_range(self.x0, self.dx, n, a, b),
        };
        if hi <= lo || hi - lo < MIN_POINTS {
            return Err(bad(
                &self.source,
                format!(
                    "evaluation window [{a:.6e}, {b:.6e}] m holds {} points of the profile \
                     spanning [{:.6e}, {:.6e}] m; at least {MIN_POINTS} are needed",
                    hi.saturating_sub(lo),
                    self.x(0),
                    self.x(n - 1)
                ),
            ));
        }
        Ok((lo, hi))
    }

    /// The part of the profile inside `window` (see [`Profile::window_range`]).
    pub fn windowed(&self, window: Option<(f64, f64)>) -> Result<Profile> {
        let (lo, hi) = self.window_range(window)?;
        Ok(Profile {
            source: self.source.clone(),
            x0: self.x0 + lo as f64 * self.dx,
            dx: self.dx,
            z: self.z[lo..hi].to_vec(),
            positions: self.positions.as_ref().map(|x| x[lo..hi].to_vec()),
        })
    }

    /// Position of sample `i` (m): as written when known, else on the grid.
    pub fn x(&self, i: usize) -> f64 {
        match &self.positions {
            Some(x) => x[i],
            None => self.x0 + i as f64 * self.dx,
        }
    }

    /// Points not measured (NaN heights).
    pub fn n_invalid(&self) -> usize {
        scan::count(&self.z, f64::is_nan)
    }

    /// Length covered, (n − 1)·Δx (m).
    pub fn length(&self) -> f64 {
        (self.z.len() - 1) as f64 * self.dx
    }
}

/// Index range [lo, hi) of grid points x0 + i·d (i < n) inside [a, b],
/// inclusive with a tolerance of 1e-9 d.
pub(super) fn grid_range(x0: f64, d: f64, n: usize, a: f64, b: f64) -> (usize, usize) {
    let tol = 1e-9 * d;
    let lo = ((a - x0 - tol) / d).ceil().max(0.0) as usize;
    let hi_f = ((b - x0 + tol) / d).floor();
    let hi = if hi_f < 0.0 {
        0
    } else {
        (hi_f as usize + 1).min(n)
    };
    (lo.min(n), hi)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rejects_too_few_points_infinity_and_bad_spacing() {
        assert!(Profile::new("p", 0.0, 1e-6, vec![0.0; 3]).is_err());
        let mut z = vec![0.0; 20];
        z[5] = f64::INFINITY;
        let e = Profile::new("p", 0.0, 1e-6, z.clone())
            .unwrap_err()
            .to_string();
        assert!(e.contains("point 6"), "{e}");
        // NaN is a point not measured: accepted and counted.
        z[5] = f64::NAN;
        z[9] = f64::NAN;
        assert_eq!(Profile::new("p", 0.0, 1e-6, z).unwrap().n_invalid(), 2);
        // ... but at least MIN_POINTS must be measured.
        let mut z = vec![f64::NAN; 20];
        z[..MIN_POINTS - 1].fill(1.0);
        let e = Profile::new("p", 0.0, 1e-6, z).unwrap_err().to_string();
        assert!(e.contains("7 of 20 points are measured"), "{e}");
        assert!(Profile::new("p", 0.0, 0.0, vec![0.0; 20]).is_err());
        assert!(Profile::new("p", 0.0, -1.0, vec![0.0; 20]).is_err());
    }

    #[test]
    fn rejects_non_monotonic_and_non_uniform_positions() {
        let mut x: Vec<f64> = (0..20).map(|i| i as f64).collect();
        x.swap(7, 8);
        let e = Profile::from_xz("p", x.clone(), vec![0.0; 20])
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("increase strictly") && e.contains("point 9"),
            "{e}"
        );
        // A gap: points 10.. shifted by 3 steps.
        let x: Vec<f64> = (0..20)
            .map(|i| if i < 10 { i as f64 } else { i as f64 + 3.0 })
            .collect();
        let e = Profile::from_xz("p", x.clone(), vec![0.0; 20])
            .unwrap_err()
            .to_string();
        assert!(e.contains("not equally spaced"), "{e}");
    }

    #[test]
    fn accepts_positions_rounded_by_the_export() {
        // 0.156-step positions printed with one decimal, as the Dektak does.
        let x: Vec<f64> = (0..100)
            .map(|i| (i as f64 * 0.15625 * 10.0).round() / 10.0)
            .collect();
        let p = Profile::from_xz("p", x.clone(), vec![0.0; 100]).unwrap();
        // Rounding errors (≤ 0.05, roughly uniform) over 100 points move the
        // least-squares slope by about 0.05·sqrt(12/100³) ≈ 2e-4.
        assert!((p.dx - 0.15625).abs() < 1e-3, "{}", p.dx);
    }

    #[test]
    fn profile_window_uses_written_positions() {
        let x: Vec<f64> = (0..20).map(|i| 10.0 + i as f64).collect();
        let p = Profile::from_xz("p", x.clone(), (0..20).map(|i| i as f64).collect()).unwrap();
        let w = p.windowed(Some((12.0, 21.0))).unwrap();
        let ints = |v: &[f64]| v.iter().map(|x| *x as i64).collect::<Vec<_>>();
        assert_eq!(ints(&w.z), (2..=11).collect::<Vec<i64>>());
        assert_eq!(ints(w.positions.as_ref().unwrap())[0], 12);
        assert!(p.windowed(Some((12.0, 14.0))).is_err());
    }
}
