//! Scene files: a TOML spec (`deny_unknown_fields`) turned into a validated
//! [`ScenePlan`] before anything runs. The format is documented with
//! examples in `docs/spring_block.md`; `pipelines/spring_block/*.toml` holds
//! one scene per pattern of Table 4.1.

use std::path::Path;

use serde::{Deserialize, Serialize};

use super::run::{IntegratorParams, RunControl};
use crate::error::{Error, Result};
use crate::models::spring_block::{LocalFriction, Pattern, SpringBlockParams, StiffnessConvention};

/// `[material]`.
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields, default)]
pub struct MaterialSpec {
    /// E \[Pa\].
    #[serde(rename = "youngs_modulus_Pa")]
    pub youngs_modulus: f64,
    /// ρ [kg/m³].
    #[serde(rename = "density_kg_per_m3")]
    pub density: f64,
    /// γ [1/s].
    #[serde(rename = "damping_per_s")]
    pub damping: f64,
}

/// `[lattice]`.
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields, default)]
pub struct LatticeSpec {
    /// l \[m\].
    pub spacing_m: f64,
    /// l_z \[m\]; defaults to l.
    pub thickness_m: Option<f64>,
    /// N_x.
    pub nx: usize,
    /// N_y.
    pub ny: usize,
    /// `thesis` (K_int = 3/8 E l_z) or `isotropic` (3/4 E l_z).
    pub stiffness: StiffnessConvention,
}

/// `[friction]`.
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields, default)]
pub struct FrictionSpec {
    /// (μ_s)_m.
    pub mu_static_mean: f64,
    /// σ_s.
    pub mu_static_sd: f64,
    /// (μ_d)_m.
    pub mu_dynamic_mean: f64,
    /// σ_d.
    pub mu_dynamic_sd: f64,
    /// F_ad/l² \[Pa\].
    #[serde(rename = "adhesion_Pa")]
    pub adhesion: f64,
    /// Whether holes keep the adhesion term.
    pub adhesion_in_holes: bool,
}

/// `[slider]`.
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields, default)]
pub struct SliderSpec {
    /// |v| [m/s].
    pub speed_m_per_s: f64,
    /// α is drawn uniformly in [angle_min_deg, angle_max_deg] per run.
    pub angle_min_deg: f64,
    /// Upper end of the α range [°].
    pub angle_max_deg: f64,
}

/// A scene file.
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct SceneSpec {
    /// Label of the pattern in the output tables (`flat`, `A`, `Sx`, …).
    pub name: String,
    /// Seed of the scene; each run's seed derives from it.
    pub seed: u64,
    /// Monte-Carlo repetitions per pressure (≥ 1).
    pub repetitions: usize,
    /// Pressures to sweep \[Pa\] (each > 0).
    #[serde(rename = "pressures_Pa")]
    pub pressures: Vec<f64>,
    /// Material.
    #[serde(default)]
    pub material: MaterialSpec,
    /// Lattice.
    #[serde(default)]
    pub lattice: LatticeSpec,
    /// Pattern.
    #[serde(default)]
    pub pattern: Pattern,
    /// Local friction and adhesion.
    #[serde(default)]
    pub friction: FrictionSpec,
    /// Slider.
    #[serde(default)]
    pub slider: SliderSpec,
    /// Integrator.
    #[serde(default)]
    pub integrator: IntegratorParams,
    /// Run control.
    #[serde(default)]
    pub run: RunControl,
}

impl Default for MaterialSpec {
    fn default() -> Self {
        let p = SpringBlockParams::default();
        MaterialSpec {
            youngs_modulus: p.youngs_modulus,
            density: p.density,
            damping: p.damping,
        }
    }
}

impl Default for LatticeSpec {
    fn default() -> Self {
        let p = SpringBlockParams::default();
        LatticeSpec {
            spacing_m: p.spacing,
            thickness_m: None,
            nx: p.nx,
            ny: p.ny,
            stiffness: p.stiffness,
        }
    }
}

impl Default for FrictionSpec {
    fn default() -> Self {
        let p = SpringBlockParams::default();
        FrictionSpec {
            mu_static_mean: p.friction.mu_static_mean,
            mu_static_sd: p.friction.mu_static_sd,
            mu_dynamic_mean: p.friction.mu_dynamic_mean,
            mu_dynamic_sd: p.friction.mu_dynamic_sd,
            adhesion: p.adhesion,
            adhesion_in_holes: p.adhesion_in_holes,
        }
    }
}

impl Default for SliderSpec {
    fn default() -> Self {
        SliderSpec {
            speed_m_per_s: SpringBlockParams::default().slider_speed,
            angle_min_deg: 0.0,
            angle_max_deg: 45.0,
        }
    }
}

/// A validated scene: everything a sweep needs, checked before it starts.
#[derive(Debug, Clone)]
pub struct ScenePlan {
    /// Pattern label.
    pub name: String,
    /// Scene seed.
    pub seed: u64,
    /// Repetitions per pressure.
    pub repetitions: usize,
    /// Pressures \[Pa\].
    pub pressures: Vec<f64>,
    /// Model parameters.
    pub params: SpringBlockParams,
    /// Pattern.
    pub pattern: Pattern,
    /// Hole mask (true = hole), row-major.
    pub mask: Vec<bool>,
    /// α range \[rad\].
    pub angle_range: (f64, f64),
    /// Integrator.
    pub integrator: IntegratorParams,
    /// Run control.
    pub control: RunControl,
    /// The spec as read (recorded in the outputs' provenance).
    pub spec: SceneSpec,
}

impl SceneSpec {
    /// Parses a scene from TOML text; `origin` names the file in errors.
    pub fn from_toml(text: &str, origin: &Path) -> Result<Self> {
        toml::from_str(text).map_err(|e| {
            Error::Config(format!(
                "{}: not a valid spring-block scene: {e}",
                origin.display()
            ))
        })
    }

    /// The model parameters the scene sets.
    fn params(&self) -> SpringBlockParams {
        let f = &self.friction;
        SpringBlockParams {
            youngs_modulus: self.material.youngs_modulus,
            density: self.material.density,
            spacing: self.lattice.spacing_m,
            thickness: self.lattice.thickness_m.unwrap_or(self.lattice.spacing_m),
            nx: self.lattice.nx,
            ny: self.lattice.ny,
            stiffness: self.lattice.stiffness,
            friction: LocalFriction {
                mu_static_mean: f.mu_static_mean,
                mu_static_sd: f.mu_static_sd,
                mu_dynamic_mean: f.mu_dynamic_mean,
                mu_dynamic_sd: f.mu_dynamic_sd,
            },
            adhesion: f.adhesion,
            adhesion_in_holes: f.adhesion_in_holes,
            damping: self.material.damping,
            slider_speed: self.slider.speed_m_per_s,
        }
    }

    /// Validates the scene and builds the plan.
    pub fn plan(&self) -> Result<ScenePlan> {
        let cfg = |m: String| {
            Err(Error::Config(format!(
                "spring-block scene '{}': {m}",
                self.name
            )))
        };
        if self.repetitions == 0 {
            return cfg("repetitions is 0; expected at least 1".into());
        }
        if self.pressures.is_empty() {
            return cfg("pressures_Pa is empty; expected at least one pressure".into());
        }
        if let Some(p) = self
            .pressures
            .iter()
            .find(|p| !(p.is_finite() && **p > 0.0))
        {
            return cfg(format!(
                "pressure {p} Pa in pressures_Pa; expected every pressure > 0"
            ));
        }
        let s = &self.slider;
        if !(s.angle_min_deg.is_finite()
            && s.angle_max_deg.is_finite()
            && s.angle_min_deg <= s.angle_max_deg)
        {
            return cfg(format!(
                "slider angle range [{}, {}]°; expected finite angle_min_deg <= angle_max_deg",
                s.angle_min_deg, s.angle_max_deg
            ));
        }
        let params = self.params();
        params.validate()?;
        let pattern = self.pattern.clone();
        let mask = pattern.mask(params.nx, params.ny, params.spacing)?;
        let integrator = self.integrator;
        integrator.validate()?;
        let control = self.run;
        control.validate()?;
        Ok(ScenePlan {
            name: self.name.clone(),
            seed: self.seed,
            repetitions: self.repetitions,
            pressures: self.pressures.clone(),
            params,
            pattern,
            mask,
            angle_range: (s.angle_min_deg.to_radians(), s.angle_max_deg.to_radians()),
            integrator,
            control,
            spec: self.clone(),
        })
    }
}
