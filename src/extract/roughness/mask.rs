//! Points not measured. A NaN height is a point the instrument did not
//! measure (an optical dropout, a masked region, a binary file's invalid
//! value); the readers deliver them as NaN and every parameter excludes them
//! where its standard allows it. The rules for operations that reach across
//! a gap:
//!
//! | operation | rule |
//! |---|---|
//! | amplitude, heights, material ratio, volume | over the measured points only |
//! | form removal (line, plane, polynomial, circle) | fitted to the measured points; subtracted everywhere measured |
//! | Gaussian, robust and valley-suppression filters | normalised convolution: the mean line at a point is the weighted mean of the measured points under the kernel; it is defined when they carry at least [`MIN_MEASURED_WEIGHT`] (one half) of the kernel weight that falls inside the data (so the ends of an unbroken profile or map always qualify), else the point is not measured in the result either |
//! | slopes (Rdq, Sdq) | only where every point of the stencil is measured |
//! | Sdr | over the grid cells whose four corners are measured |
//! | RSm | profile elements that contain a gap are left out |
//! | structure function (fractal D), ACF | over the pairs of measured points at each lag |
//! | PSD | gaps set to the mean line (zero) and the spectrum scaled by n / n_measured; a status says so |
//!
//! More than [`DEFAULT_MAX_INVALID_FRACTION`] of the points not measured (the
//! setting `max_invalid_fraction`) gives a status on the row: the values are
//! computed but stand for less of the surface than its size suggests.

use crate::signal::scan;

/// Default largest fraction of points not measured before a row gets a
/// status (10 %).
pub const DEFAULT_MAX_INVALID_FRACTION: f64 = 0.1;

pub use crate::signal::gaussian_filter::MIN_MEASURED_WEIGHT;

/// Whether a height was measured.
#[inline]
pub fn measured(v: f64) -> bool {
    !v.is_nan()
}

/// Number of points not measured.
pub fn count_invalid(z: &[f64]) -> usize {
    scan::count(z, f64::is_nan)
}

/// The measured heights, in order (a copy).
pub fn measured_heights(z: &[f64]) -> Vec<f64> {
    z.iter().copied().filter(|v| measured(*v)).collect()
}

/// 1 where measured, 0 where not.
pub fn weights(z: &[f64]) -> Vec<f64> {
    z.iter()
        .map(|&v| f64::from(u8::from(measured(v))))
        .collect()
}

/// The heights with the points not measured set to `fill`.
pub fn filled(z: &[f64], fill: f64) -> Vec<f64> {
    z.iter()
        .map(|&v| if measured(v) { v } else { fill })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn counts_copies_and_fills() {
        let z = [1.0, f64::NAN, -2.0, f64::NAN, 0.0];
        assert_eq!(count_invalid(&z), 2);
        assert_eq!(measured_heights(&z), vec![1.0, -2.0, 0.0]);
        assert_eq!(weights(&z), vec![1.0, 0.0, 1.0, 0.0, 1.0]);
        assert_eq!(filled(&z, 7.0), vec![1.0, 7.0, -2.0, 7.0, 0.0]);
    }
}
