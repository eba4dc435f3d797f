//! Periodic surfaces z = f(x, y) of the ALSFM: flat, wedges (Sec. 1.1–1.2,
//! asymmetric slopes as in Eq. 1.10–1.12), sinusoids in 1-D or 2-D (Sec. 1.3,
//! 1.4, Figs. 1.8–1.13) and sampled profiles or maps.
//!
//! | shape | fields | unit |
//! |---|---|---|
//! | wedges | rising slope φ_a, falling slope φ_b, wavelength λ | rad, rad, m |
//! | sinusoid | amplitude A, λ_x, optional λ_y | m |
//! | sampled | heights on a periodic grid with spacing dx (dy) | m |
//!
//! Wedges: z rises with slope tan φ_a from 0 to the peak h, then falls with
//! slope tan φ_b back to 0, over one wavelength: h = λ tan φ_a tan φ_b /
//! (tan φ_a + tan φ_b). Sinusoid: z = A sin(2πx/λ_x) in 1-D and
//! z = A sin(2πx/λ_x) sin(2πy/λ_y) in 2-D (the thesis' sin x sin y).
//! Sampled surfaces are periodic and interpolated linearly (bilinearly).
//! At a kink (a wedge's peak or valley, a sample point) the slope is the
//! one on the right (x increasing); the spring grids avoid kinks.
//!
//! Every surface is periodic; a surface without a period in a direction
//! (flat, or 1-D in y) is invariant along it.

mod form;
mod sampled;

use crate::error::{Error, Result};
use sampled::{check_heights, min_max, scale_about_min, Grid};
use std::f64::consts::TAU;

/// A periodic surface. It deserializes from a scene file's table (`kind`,
/// slopes in degrees; [`form`]) and is validated as it does.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(try_from = "form::SurfaceForm", into = "form::SurfaceForm")]
pub enum Surface {
    /// z = 0.
    Flat,
    /// Wedge (triangular) asperities extruded along y.
    Wedges {
        /// φ_a, rad, slope of the rising facet, in [0, 90°).
        phi_rise: f64,
        /// φ_b, rad, slope of the falling facet, in [0, 90°).
        phi_fall: f64,
        /// λ, m, wavelength > 0.
        wavelength: f64,
    },
    /// Sinusoid, 1-D (`lambda_y = None`, extruded along y) or 2-D.
    Sinusoid {
        /// A, m, amplitude ≥ 0.
        amplitude: f64,
        /// λ_x, m, > 0.
        lambda_x: f64,
        /// λ_y, m, > 0, or `None` for a 1-D profile.
        lambda_y: Option<f64>,
    },
    /// Sampled periodic profile z(x_j), x_j = j dx, extruded along y.
    Profile {
        /// dx, m, sample spacing > 0.
        dx: f64,
        /// Heights, m, at least 2 samples; the period is len · dx.
        z: Vec<f64>,
    },
    /// Sampled periodic map z(x_i, y_j), row-major with `nx` samples per row.
    Map {
        /// dx, m, > 0.
        dx: f64,
        /// dy, m, > 0.
        dy: f64,
        /// Samples per row (along x), ≥ 2.
        nx: usize,
        /// Heights, m, `nx · ny` values, row j holds y = j dy.
        z: Vec<f64>,
    },
}

fn finite_pos(name: &str, v: f64) -> Result<()> {
    if v.is_finite() && v > 0.0 {
        Ok(())
    } else {
        Err(Error::Config(format!(
            "{name} must be finite and > 0, got {v}"
        )))
    }
}

impl Surface {
    /// Symmetric wedges of slope φ and wavelength λ.
    pub fn wedges(phi: f64, wavelength: f64) -> Self {
        Surface::Wedges {
            phi_rise: phi,
            phi_fall: phi,
            wavelength,
        }
    }

    /// Checks the parameters (ranges in the field docs).
    pub fn validate(&self) -> Result<()> {
        match self {
            Surface::Flat => Ok(()),
            Surface::Wedges {
                phi_rise,
                phi_fall,
                wavelength,
            } => {
                finite_pos("wedge wavelength", *wavelength)?;
                for (n, p) in [("phi_rise", phi_rise), ("phi_fall", phi_fall)] {
                    if !(p.is_finite() && *p >= 0.0 && *p < std::f64::consts::FRAC_PI_2) {
                        return Err(Error::Config(format!(
                            "wedge {n} must be in [0, 90) deg, got {} deg",
                            p.to_degrees()
                        )));
                    }
                }
                if (*phi_rise == 0.0) != (*phi_fall == 0.0) {
                    return Err(Error::Config(format!(
                        "wedges need both slopes > 0 (or both 0 for a flat surface), got {} and {} deg",
                        phi_rise.to_degrees(),
                        phi_fall.to_degrees()
                    )));
                }
                Ok(())
            }
            Surface::Sinusoid {
                amplitude,
                lambda_x,
                lambda_y,
            } => {
                if !(amplitude.is_finite() && *amplitude >= 0.0) {
                    return Err(Error::Config(format!(
                        "sinusoid amplitude must be finite and >= 0, got {amplitude}"
                    )));
                }
                finite_pos("sinusoid lambda_x", *lambda_x)?;
                if let Some(ly) = lambda_y {
                    finite_pos("sinusoid lambda_y", *ly)?;
                }
                Ok(())
            }
            Surface::Profile { dx, z } => {
                finite_pos("profile dx", *dx)?;
                check_heights(z, 2)
            }
            Surface::Map { dx, dy, nx, z } => {
                finite_pos("map dx", *dx)?;
                finite_pos("map dy", *dy)?;
                if *nx < 2 || z.len() % nx != 0 || z.len() / nx < 2 {
                    return Err(Error::Config(format!(
                        "map needs nx >= 2 and a whole number (>= 2) of rows: nx = {nx}, {} values",
                        z.len()
                    )));
                }
                check_heights(z, 4)
            }
        }
    }

    /// Period along x, m (`None` when invariant in x).
    pub fn period_x(&self) -> Option<f64> {
        match self {
            Surface::Flat => None,
            Surface::Wedges { wavelength, .. } => Some(*wavelength),
            Surface::Sinusoid { lambda_x, .. } => Some(*lambda_x),
            Surface::Profile { dx, z } => Some(dx * z.len() as f64),
            Surface::Map { dx, nx, .. } => Some(dx * *nx as f64),
        }
    }

    /// Period along y, m (`None` when invariant in y).
    pub fn period_y(&self) -> Option<f64> {
        match self {
            Surface::Sinusoid { lambda_y, .. } => *lambda_y,
            Surface::Map { dy, nx, z, .. } => Some(dy * (z.len() / nx) as f64),
            _ => None,
        }
    }

    /// True when z does not vary along y (the 1-D model applies).
    pub fn is_y_invariant(&self) -> bool {
        match self {
            Surface::Map { nx, z, .. } => z.chunks(*nx).all(|row| row == &z[..*nx]),
            Surface::Sinusoid {
                lambda_y: Some(_),
                amplitude,
                ..
            } => *amplitude == 0.0,
            _ => true,
        }
    }

    /// True when z is constant.
    pub fn is_flat(&self) -> bool {
        match self {
            Surface::Flat => true,
            Surface::Wedges { phi_rise, .. } => *phi_rise == 0.0,
            Surface::Sinusoid { amplitude, .. } => *amplitude == 0.0,
            // Exactly constant heights only: a tiny ripple is still roughness.
            #[allow(clippy::float_cmp)]
            Surface::Profile { z, .. } | Surface::Map { z, .. } => z.iter().all(|v| *v == z[0]),
        }
    }

    /// The same surface with its asperity heights scaled by `b` ≥ 0 about the
    /// deepest valley (wear, Sec. 2.2: amplitude × B(t)). Slopes scale by `b`.
    pub fn scaled(&self, b: f64) -> Surface {
        match self {
            Surface::Flat => Surface::Flat,
            Surface::Wedges {
                phi_rise,
                phi_fall,
                wavelength,
            } => Surface::Wedges {
                phi_rise: (b * phi_rise.tan()).atan(),
                phi_fall: (b * phi_fall.tan()).atan(),
                wavelength: *wavelength,
            },
            Surface::Sinusoid {
                amplitude,
                lambda_x,
                lambda_y,
            } => Surface::Sinusoid {
                amplitude: amplitude * b,
                lambda_x: *lambda_x,
                lambda_y: *lambda_y,
            },
            Surface::Profile { dx, z } => Surface::Profile {
                dx: *dx,
                z: scale_about_min(z, b),
            },
            Surface::Map { dx, dy, nx, z } => Surface::Map {
                dx: *dx,
                dy: *dy,
                nx: *nx,
                z: scale_about_min(z, b),
            },
        }
    }

    /// Height z(x, y), m.
    pub fn height(&self, x: f64, y: f64) -> f64 {
        match self {
            Surface::Flat => 0.0,
            Surface::Wedges {
                phi_rise,
                phi_fall,
                wavelength,
            } => {
                let Some(w) = WedgeFacets::new(*phi_rise, *phi_fall, *wavelength) else {
                    return 0.0;
                };
                let u = x.rem_euclid(*wavelength);
                if u < w.apex {
                    w.rise * u
                } else {
                    w.fall * (wavelength - u)
                }
            }
            Surface::Sinusoid {
                amplitude,
                lambda_x,
                lambda_y,
            } => {
                let zx = amplitude * (TAU * x / lambda_x).sin();
                match lambda_y {
                    None => zx,
                    Some(ly) => zx * (TAU * y / ly).sin(),
                }
            }
            Surface::Profile { dx, z } => sampled::profile_height(*dx, z, x),
            Surface::Map { dx, dy, nx, z } => Grid::of(*dx, *dy, *nx, z).height(x, y),
        }
    }

    /// Per-axis parts of a sinusoid's height and gradient at coordinate `v`
    /// along x (`axis` 0, a lattice column) or y (1, a row), such that with
    /// c the column's parts and r the row's, z = c₀ r₀, ∂z/∂x = c₁ r₁ and
    /// ∂z/∂y = c₂ r₂: column [A sin(2πx/λ_x), A k_x cos(k_x x), A k_y
    /// sin(k_x x)], row [sin(2πy/λ_y), sin(k_y y), cos(k_y y)] (in 1-D the
    /// row is [1, 1, 0] and c₂ = 0). These are the very products, in the same
    /// order, that [`Self::height`] and [`Self::gradient`] take, so the
    /// values are the same to the bit; a shifted sinusoid then costs
    /// O(n_x + n_y) trigonometric calls per instant instead of O(n_x n_y).
    /// `None` for other surfaces.
    pub fn axis_parts(&self, axis: usize, v: f64) -> Option<[f64; 3]> {
        let Surface::Sinusoid {
            amplitude,
            lambda_x,
            lambda_y,
        } = self
        else {
            return None;
        };
        if axis == 0 {
            let kx = TAU / lambda_x;
            let gy = match lambda_y {
                None => 0.0,
                Some(ly) => amplitude * (TAU / ly) * (kx * v).sin(),
            };
            return Some([
                amplitude * (TAU * v / lambda_x).sin(),
                amplitude * kx * (kx * v).cos(),
                gy,
            ]);
        }
        Some(match lambda_y {
            None => [1.0, 1.0, 0.0],
            Some(ly) => {
                let ky = TAU / ly;
                [(TAU * v / ly).sin(), (ky * v).sin(), (ky * v).cos()]
            }
        })
    }

    /// Gradient (∂z/∂x, ∂z/∂y) at (x, y).
    pub fn gradient(&self, x: f64, y: f64) -> (f64, f64) {
        match self {
            Surface::Flat => (0.0, 0.0),
            Surface::Wedges {
                phi_rise,
                phi_fall,
                wavelength,
            } => {
                let Some(w) = WedgeFacets::new(*phi_rise, *phi_fall, *wavelength) else {
                    return (0.0, 0.0);
                };
                if x.rem_euclid(*wavelength) < w.apex {
                    (w.rise, 0.0)
                } else {
                    (-w.fall, 0.0)
                }
            }
            Surface::Sinusoid {
                amplitude,
                lambda_x,
                lambda_y,
            } => {
                let kx = TAU / lambda_x;
                match lambda_y {
                    None => (amplitude * kx * (kx * x).cos(), 0.0),
                    Some(ly) => {
                        let ky = TAU / ly;
                        (
                            amplitude * kx * (kx * x).cos() * (ky * y).sin(),
                            amplitude * ky * (kx * x).sin() * (ky * y).cos(),
                        )
                    }
                }
            }
            Surface::Profile { dx, z } => (sampled::profile_slope(*dx, z, x), 0.0),
            Surface::Map { dx, dy, nx, z } => Grid::of(*dx, *dy, *nx, z).gradient(x, y),
        }
    }

    /// Largest slope magnitude |∇z| (exact for wedges and sinusoids, over the
    /// samples for sampled surfaces), used to check applicability up front.
    pub fn max_slope(&self) -> f64 {
        match self {
            Surface::Flat => 0.0,
            Surface::Wedges {
                phi_rise, phi_fall, ..
            } => phi_rise.tan().max(phi_fall.tan()),
            Surface::Sinusoid {
                amplitude,
                lambda_x,
                lambda_y,
            } => {
                let kx = TAU / lambda_x;
                match lambda_y {
                    None => amplitude * kx,
                    // max of A sqrt(kx² cos²u sin²w + ky² sin²u cos²w) = A max(kx, ky)
                    Some(ly) => amplitude * kx.max(TAU / ly),
                }
            }
            Surface::Profile { dx, z } => sampled::profile_max_slope(*dx, z),
            Surface::Map { dx, dy, nx, z } => Grid::of(*dx, *dy, *nx, z).max_slope(),
        }
    }

    /// Peak-to-valley height, m.
    pub fn peak_to_valley(&self) -> f64 {
        match self {
            Surface::Flat => 0.0,
            Surface::Wedges {
                phi_rise,
                phi_fall,
                wavelength,
            } => {
                WedgeFacets::new(*phi_rise, *phi_fall, *wavelength).map_or(0.0, |w| w.rise * w.apex)
            }
            Surface::Sinusoid { amplitude, .. } => 2.0 * amplitude,
            Surface::Profile { z, .. } | Surface::Map { z, .. } => {
                let (lo, hi) = min_max(z);
                hi - lo
            }
        }
    }

    /// Mean volume above the deepest valley per unit area, ∫(z − z_min) dA / A,
    /// in m (MODELS.md §5 wear reference). Wedges: h/2; 1-D sinusoid: A; 2-D
    /// sinusoid: A (z_min = −A, mean 0); sampled: mean of the samples − min.
    pub fn volume_above_valley(&self) -> f64 {
        match self {
            Surface::Flat => 0.0,
            Surface::Wedges { .. } => 0.5 * self.peak_to_valley(),
            Surface::Sinusoid { amplitude, .. } => *amplitude,
            Surface::Profile { z, .. } | Surface::Map { z, .. } => sampled::mean_above_min(z),
        }
    }
}

/// One wedge period: rising facet from x = 0 to the apex, falling facet to
/// the wavelength (MODELS.md §5).
struct WedgeFacets {
    /// tan φ_rise.
    rise: f64,
    /// tan φ_fall.
    fall: f64,
    /// Apex position λ tan φ_fall / (tan φ_rise + tan φ_fall), m.
    apex: f64,
}

impl WedgeFacets {
    /// `None` for flat wedges (both slopes 0, as validated).
    fn new(phi_rise: f64, phi_fall: f64, wavelength: f64) -> Option<Self> {
        let (rise, fall) = (phi_rise.tan(), phi_fall.tan());
        (rise != 0.0).then(|| WedgeFacets {
            rise,
            fall,
            apex: wavelength * fall / (rise + fall),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A sinusoid's height and gradient from its column and row parts equal
    /// [`Surface::height`] and [`Surface::gradient`] to the bit, in 1-D and
    /// 2-D, at points spread over several periods (both signs).
    #[test]
    fn axis_parts_multiply_to_height_and_gradient_exactly() {
        for lambda_y in [None, Some(0.7)] {
            let s = Surface::Sinusoid {
                amplitude: 0.03,
                lambda_x: 1.3,
                lambda_y,
            };
            for k in 0..200 {
                let (x, y) = (-2.0 + 0.0371 * k as f64, 3.1 - 0.0529 * k as f64);
                let (c, r) = (s.axis_parts(0, x).unwrap(), s.axis_parts(1, y).unwrap());
                let (gx, gy) = s.gradient(x, y);
                assert_eq!((c[0] * r[0]).to_bits(), s.height(x, y).to_bits());
                assert_eq!((c[1] * r[1]).to_bits(), gx.to_bits());
                assert_eq!((c[2] * r[2]).to_bits(), gy.to_bits());
            }
        }
        assert!(Surface::wedges(0.3, 1.0).axis_parts(0, 0.1).is_none());
    }

    /// Wedge heights and slopes from the construction: peak h at x = a.
    #[test]
    fn wedge_geometry() {
        let s = Surface::Wedges {
            phi_rise: 0.4f64.atan(),
            phi_fall: 0.8f64.atan(),
            wavelength: 1.0,
        };
        // a = λ tb/(ta+tb) = 2/3, h = 0.4·2/3.
        let h = 0.4 * 2.0 / 3.0;
        assert!((s.peak_to_valley() - h).abs() < 1e-15);
        assert!((s.height(2.0 / 3.0 - 1e-12, 0.0) - h).abs() < 1e-11);
        assert!((s.height(1.25, 0.0) - 0.1).abs() < 1e-15);
        assert!((s.gradient(0.9, 5.0).0 + 0.8).abs() < 1e-15);
        assert!((s.max_slope() - 0.8).abs() < 1e-15);
    }

    /// A profile sampled from a sinusoid interpolates it to O(dx²).
    #[test]
    fn profile_interpolates() {
        let n = 256;
        let dx = 1.0 / n as f64;
        let z: Vec<f64> = (0..n).map(|j| (TAU * j as f64 * dx).sin()).collect();
        let p = Surface::Profile { dx, z };
        // Linear interpolation error ≤ dx² max|z''| / 8 = (2π/256)² / 8 ≈ 7.5e-5.
        for x in [0.1, 0.37, -0.2, 3.9] {
            assert!((p.height(x, 0.0) - (TAU * x).sin()).abs() < 8e-5);
        }
        assert!(p.is_y_invariant());
    }

    /// Scaling about the valley: B = 0 is flat, volume scales by B.
    #[test]
    fn scaling_for_wear() {
        let s = Surface::Sinusoid {
            amplitude: 0.2,
            lambda_x: 1.0,
            lambda_y: Some(2.0),
        };
        assert!(s.scaled(0.0).is_flat());
        assert!((s.scaled(0.5).volume_above_valley() - 0.1).abs() < 1e-15);
        let p = Surface::Profile {
            dx: 0.1,
            z: vec![1.0, 3.0, 2.0, 2.0],
        };
        assert!((p.volume_above_valley() - 1.0).abs() < 1e-15);
        assert!((p.scaled(0.5).volume_above_valley() - 0.5).abs() < 1e-15);
        assert!(!s.is_y_invariant());
    }

    /// A map that repeats one row is y-invariant and matches the profile.
    #[test]
    fn map_of_identical_rows_is_the_profile() {
        let row = vec![0.0, 0.3, 0.1, -0.2];
        let m = Surface::Map {
            dx: 0.25,
            dy: 0.5,
            nx: 4,
            z: [row.clone(), row.clone(), row.clone()].concat(),
        };
        let p = Surface::Profile { dx: 0.25, z: row };
        assert!(m.is_y_invariant());
        for x in [0.05, 0.3, 0.61, 0.99] {
            assert!((m.height(x, 0.77) - p.height(x, 0.0)).abs() < 1e-15);
            assert!((m.gradient(x, 0.77).0 - p.gradient(x, 0.0).0).abs() < 1e-12);
            assert!(m.gradient(x, 0.77).1.abs() < 1e-15);
        }
    }
}
