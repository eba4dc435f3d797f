//! Signal processing as plain functions over slices: statistics, noise
//! levels, filters, peaks and segmentation. Nothing here knows about files
//! or units.

pub mod dft;
pub mod drops;
pub mod fft;
pub mod fft2;
pub mod filter;
pub mod gaussian_filter;
pub mod integrate;
pub mod peaks;
pub mod robust_filter;
pub mod roots;
pub mod scan;
pub mod segment;
pub mod select;
pub mod stats;
pub mod sum;
pub mod testing;
pub mod valley_filter;
