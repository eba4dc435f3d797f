//! Signal processing as plain functions over slices: statistics, noise
//! levels, peaks, plateaus and segmentation.

pub mod fft;
pub mod gaussian_filter;
