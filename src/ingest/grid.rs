//! Channels sampled on a regular grid: the areal maps and profiles that
//! binary and structured formats hold (X3P, SUR, DATX, ...), read straight
//! into one `f64` buffer each.
//!
//! A [`Grid`] is one channel (heights, intensity, phase, ...) with its
//! name, unit and spacing. Lateral positions and spacings are in metres;
//! a height channel's values are in metres too (the reader applies the
//! file's scale factors and units once, while decoding), so that the
//! roughness stage takes the buffer as it is. Other channels keep the unit
//! the file gives them. A point the instrument did not measure (the
//! format's own marker, a no-data value, a mask, a non-finite float) is NaN
//! and counted in [`GridData::n_invalid`].
//!
//! A file with several channels lists them all; the reader decodes the one
//! selected ([`super::IngestOptions::channel`], else the height channel)
//! and describes the others without their values (`data: None`), so that a
//! large multi-channel file is never held whole in memory.

use serde::Serialize;

/// One channel on a regular grid, row-major: row `r` holds the `nx`
/// values at y = y0 + r·dy, x = x0 + c·dx. A profile has `ny == 1`.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Grid {
    /// The channel's name in the file (`Height`, `Intensity`, `Z`, ...).
    pub name: String,
    /// Unit of the values: `m` for heights; as the file gives it for other
    /// channels (empty when it gives none).
    pub unit: String,
    /// Whether this channel holds heights (topography): what the roughness
    /// stage takes by default.
    pub height: bool,
    /// Points per row (along x).
    pub nx: usize,
    /// Rows (along y); 1 for a profile.
    pub ny: usize,
    /// Spacing along x (m).
    #[serde(rename = "dx_m")]
    pub dx: f64,
    /// Spacing along y (m); the x spacing for a profile.
    #[serde(rename = "dy_m")]
    pub dy: f64,
    /// Position of the first column (m).
    #[serde(rename = "x0_m")]
    pub x0: f64,
    /// Position of the first row (m).
    #[serde(rename = "y0_m")]
    pub y0: f64,
    /// The values, when this channel was decoded.
    #[serde(flatten)]
    pub data: Option<GridData>,
}

/// A decoded channel's values.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct GridData {
    /// `nx · ny` values, row-major; NaN where nothing was measured.
    #[serde(skip)]
    pub values: Vec<f64>,
    /// Points not measured (NaN in `values`).
    pub n_invalid: usize,
}

impl GridData {
    /// Values with their NaN count.
    pub fn new(values: Vec<f64>) -> GridData {
        let n_invalid = count_nan(&values);
        GridData { values, n_invalid }
    }
}

/// Number of NaN values, counted on all threads.
pub fn count_nan(values: &[f64]) -> usize {
    use rayon::prelude::*;
    values
        .par_chunks(1 << 16)
        .map(|c| c.iter().filter(|v| v.is_nan()).count())
        .sum()
}

impl Grid {
    /// A height channel described by its size and spacing (m), values to
    /// come.
    pub fn heights(name: &str, nx: usize, ny: usize, dx: f64, dy: f64) -> Grid {
        Grid {
            name: name.to_string(),
            unit: "m".into(),
            height: true,
            nx,
            ny,
            dx,
            dy,
            x0: 0.0,
            y0: 0.0,
            data: None,
        }
    }

    /// Whether this is a profile (one row).
    pub fn is_profile(&self) -> bool {
        self.ny == 1
    }

    /// The decoded values, if any.
    pub fn values(&self) -> Option<&[f64]> {
        self.data.as_ref().map(|d| d.values.as_slice())
    }

    /// Scan size along x, nx · dx (m): the convention of Gwyddion and
    /// SurfaceTopography for a map's physical size.
    pub fn width(&self) -> f64 {
        self.nx as f64 * self.dx
    }

    /// Scan size along y, ny · dy (m).
    pub fn height_extent(&self) -> f64 {
        self.ny as f64 * self.dy
    }
}
