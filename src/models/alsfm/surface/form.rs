//! A surface as a scene file writes it: `kind` names the shape, slopes are
//! in degrees (the field names say so), lengths in m, and a wedge's falling
//! slope defaults to its rising one. [`Surface`] deserializes through this
//! form and is validated on the way, so a scene holds only valid surfaces.

use serde::{Deserialize, Serialize};

use super::Surface;
use crate::error::Error;

/// The scene file's shape of a [`Surface`] (see its variants for ranges).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case", deny_unknown_fields)]
pub(super) enum SurfaceForm {
    Flat,
    Wedges {
        phi_rise_deg: f64,
        #[serde(default)]
        phi_fall_deg: Option<f64>,
        wavelength: f64,
    },
    Sinusoid {
        amplitude: f64,
        lambda_x: f64,
        #[serde(default)]
        lambda_y: Option<f64>,
    },
    Profile {
        dx: f64,
        z: Vec<f64>,
    },
    Map {
        dx: f64,
        dy: f64,
        nx: usize,
        z: Vec<f64>,
    },
}

impl TryFrom<SurfaceForm> for Surface {
    type Error = Error;

    fn try_from(f: SurfaceForm) -> Result<Surface, Error> {
        let s = match f {
            SurfaceForm::Flat => Surface::Flat,
            SurfaceForm::Wedges {
                phi_rise_deg,
                phi_fall_deg,
                wavelength,
            } => Surface::Wedges {
                phi_rise: phi_rise_deg.to_radians(),
                phi_fall: phi_fall_deg.unwrap_or(phi_rise_deg).to_radians(),
                wavelength,
            },
            SurfaceForm::Sinusoid {
                amplitude,
                lambda_x,
                lambda_y,
            } => Surface::Sinusoid {
                amplitude,
                lambda_x,
                lambda_y,
            },
            SurfaceForm::Profile { dx, z } => Surface::Profile { dx, z },
            SurfaceForm::Map { dx, dy, nx, z } => Surface::Map { dx, dy, nx, z },
        };
        s.validate()?;
        Ok(s)
    }
}

impl From<Surface> for SurfaceForm {
    fn from(s: Surface) -> SurfaceForm {
        match s {
            Surface::Flat => SurfaceForm::Flat,
            Surface::Wedges {
                phi_rise,
                phi_fall,
                wavelength,
            } => SurfaceForm::Wedges {
                phi_rise_deg: phi_rise.to_degrees(),
                phi_fall_deg: Some(phi_fall.to_degrees()),
                wavelength,
            },
            Surface::Sinusoid {
                amplitude,
                lambda_x,
                lambda_y,
            } => SurfaceForm::Sinusoid {
                amplitude,
                lambda_x,
                lambda_y,
            },
            Surface::Profile { dx, z } => SurfaceForm::Profile { dx, z },
            Surface::Map { dx, dy, nx, z } => SurfaceForm::Map { dx, dy, nx, z },
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_scene_table_becomes_a_valid_surface() {
        let s: Surface =
            toml::from_str("kind = \"wedges\"\nphi_rise_deg = 30.0\nwavelength = 2.0").unwrap();
        assert_eq!(s, Surface::wedges(30f64.to_radians(), 2.0));
        let e =
            toml::from_str::<Surface>("kind = \"wedges\"\nphi_rise_deg = 95.0\nwavelength = 1.0")
                .unwrap_err()
                .to_string();
        assert!(e.contains("phi_rise must be in [0, 90)"), "{e}");
        let e = toml::from_str::<Surface>("kind = \"sinusoid\"\namplitude = 1.0\ncolour = 1")
            .unwrap_err()
            .to_string();
        assert!(e.contains("colour"), "{e}");
        // Written back in the file's units.
        let back = serde_json::to_value(&s).unwrap();
        assert_eq!(back["kind"], "wedges");
        assert!((back["phi_rise_deg"].as_f64().unwrap() - 30.0).abs() < 1e-12);
    }
}
