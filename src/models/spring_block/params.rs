//! Validated parameters of the spring-block model (MODELS.md §7).

use serde::{Deserialize, Serialize};

use crate::error::{Error, Result};

/// How the axial stiffness K_int is tied to Young's modulus E.
///
/// The thesis (§4.3, after Absi and Prager 1975) sets K_int = 3/8 E l_z on the
/// axes and K_int/2 on the diagonals. Under uniform strain that lattice has
/// Poisson's ratio 1/3 and an effective in-plane Young's modulus of **E/2**
/// (C11 = 9/16 E, C12 = 3/16 E, C66 = 3/16 E; see `docs/spring_block.md` and the
/// test `effective_modulus_is_half_of_e_with_thesis_convention`). The
/// `Isotropic` convention doubles both stiffnesses (3/4 E l_z and 3/8 E l_z) so
/// that the effective modulus is E.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, Default)]
#[serde(rename_all = "snake_case")]
pub enum StiffnessConvention {
    /// K_int = 3/8 E l_z (thesis; effective modulus E/2). Default.
    #[default]
    Thesis,
    /// K_int = 3/4 E l_z (effective modulus E).
    Isotropic,
}

impl StiffnessConvention {
    /// The factor c in K_int = c E l_z.
    pub fn factor(self) -> f64 {
        match self {
            StiffnessConvention::Thesis => 3.0 / 8.0,
            StiffnessConvention::Isotropic => 3.0 / 4.0,
        }
    }
}

/// Gaussian statistics of the local friction coefficients (MODELS.md §7).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct LocalFriction {
    /// (μ_s)_m, mean local static coefficient \[1\]. Default 4.5. Range ≥ 0.
    pub mu_static_mean: f64,
    /// σ_s, standard deviation of the local static coefficient \[1\]. Default 0.2. Range ≥ 0.
    pub mu_static_sd: f64,
    /// (μ_d)_m, mean local dynamic coefficient \[1\]. Default 3.0. Range [0, (μ_s)_m].
    pub mu_dynamic_mean: f64,
    /// σ_d, standard deviation of the local dynamic coefficient \[1\]. Default 0.2. Range ≥ 0.
    pub mu_dynamic_sd: f64,
}

impl Default for LocalFriction {
    fn default() -> Self {
        LocalFriction {
            mu_static_mean: 4.5,
            mu_static_sd: 0.2,
            mu_dynamic_mean: 3.0,
            mu_dynamic_sd: 0.2,
        }
    }
}

/// Material, lattice, interface and slider of one spring-block surface.
///
/// Every field is in SI units. Construct with [`SpringBlockParams::default`]
/// (the PDMS setup of thesis §4.3) and change fields, then call
/// [`SpringBlockParams::validate`] (the simulation does it again).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SpringBlockParams {
    /// E, Young's modulus \[Pa\]. Default 0.8e6 (PDMS). Range > 0.
    pub youngs_modulus: f64,
    /// ρ, density [kg/m³]. Default 1012 (PDMS). Range > 0.
    pub density: f64,
    /// l, lattice spacing (block size) \[m\]. Default 5e-6. Range > 0.
    pub spacing: f64,
    /// l_z, thickness of the layer \[m\]. Default = l (thesis). Range > 0.
    pub thickness: f64,
    /// N_x, blocks along x. Default 85. Range ≥ 1.
    pub nx: usize,
    /// N_y, blocks along y. Default 85. Range ≥ 1.
    pub ny: usize,
    /// Stiffness convention (default: the thesis's, effective modulus E/2).
    pub stiffness: StiffnessConvention,
    /// Local friction statistics.
    pub friction: LocalFriction,
    /// F_ad / l², adhesion added to each contact block's static threshold
    /// \[Pa\]. Default 23.8e3 (flat, Table 4.3). Range ≥ 0.
    pub adhesion: f64,
    /// Whether hole blocks keep the adhesion term. Default false: a hole is
    /// not in contact, so it has neither friction nor adhesion.
    pub adhesion_in_holes: bool,
    /// γ, damping rate in F_d = −m γ ṙ [1/s]. The thesis does not give it.
    /// Default 2e6 (about 0.15 of critical for one block's own mode). Range ≥ 0.
    pub damping: f64,
    /// |v|, slider speed [m/s]. Default 2e-4 (0.2 mm/s). Range > 0.
    pub slider_speed: f64,
}

impl Default for SpringBlockParams {
    fn default() -> Self {
        SpringBlockParams {
            youngs_modulus: 0.8e6,
            density: 1012.0,
            spacing: 5e-6,
            thickness: 5e-6,
            nx: 85,
            ny: 85,
            stiffness: StiffnessConvention::Thesis,
            friction: LocalFriction::default(),
            adhesion: 23.8e3,
            adhesion_in_holes: false,
            damping: 2e6,
            slider_speed: 2e-4,
        }
    }
}

fn check(ok: bool, what: &str, value: f64, expected: &str) -> Result<()> {
    if ok {
        Ok(())
    } else {
        Err(Error::Config(format!(
            "spring-block: {what} is {value}; expected {expected}"
        )))
    }
}

impl LocalFriction {
    /// Checks the statistics: every one ≥ 0, and dynamic friction below
    /// static on average.
    pub fn validate(&self) -> Result<()> {
        let nonneg = |x: f64| x.is_finite() && x >= 0.0;
        let f = self;
        check(
            nonneg(f.mu_static_mean),
            "mean local mu_s",
            f.mu_static_mean,
            ">= 0",
        )?;
        check(
            nonneg(f.mu_static_sd),
            "sd of local mu_s",
            f.mu_static_sd,
            ">= 0",
        )?;
        check(
            nonneg(f.mu_dynamic_mean),
            "mean local mu_d",
            f.mu_dynamic_mean,
            ">= 0",
        )?;
        check(
            nonneg(f.mu_dynamic_sd),
            "sd of local mu_d",
            f.mu_dynamic_sd,
            ">= 0",
        )?;
        check(
            f.mu_dynamic_mean <= f.mu_static_mean,
            "mean local mu_d",
            f.mu_dynamic_mean,
            "<= mean local mu_s (dynamic friction below static)",
        )?;
        Ok(())
    }
}

impl SpringBlockParams {
    /// Checks every field against its valid range.
    pub fn validate(&self) -> Result<()> {
        let pos = |x: f64| x.is_finite() && x > 0.0;
        let nonneg = |x: f64| x.is_finite() && x >= 0.0;
        check(
            pos(self.youngs_modulus),
            "Young's modulus E [Pa]",
            self.youngs_modulus,
            "> 0",
        )?;
        check(pos(self.density), "density [kg/m3]", self.density, "> 0")?;
        check(
            pos(self.spacing),
            "lattice spacing l [m]",
            self.spacing,
            "> 0",
        )?;
        check(
            pos(self.thickness),
            "layer thickness l_z [m]",
            self.thickness,
            "> 0",
        )?;
        check(self.nx >= 1, "N_x", self.nx as f64, ">= 1")?;
        check(self.ny >= 1, "N_y", self.ny as f64, ">= 1")?;
        check(
            self.nx.saturating_mul(self.ny) <= u32::MAX as usize / 2,
            "N_x N_y",
            (self.nx * self.ny) as f64,
            "< 2^31",
        )?;
        self.friction.validate()?;
        check(
            nonneg(self.adhesion),
            "adhesion F_ad/l^2 [Pa]",
            self.adhesion,
            ">= 0",
        )?;
        check(
            nonneg(self.damping),
            "damping gamma [1/s]",
            self.damping,
            ">= 0",
        )?;
        check(
            pos(self.slider_speed),
            "slider speed [m/s]",
            self.slider_speed,
            "> 0",
        )?;
        Ok(())
    }

    /// m = ρ l³ (MODELS.md §7; the block is a cube of side l).
    pub fn block_mass(&self) -> f64 {
        self.density * self.spacing.powi(3)
    }

    /// K_int = c E l_z, axial internal spring stiffness [N/m] (c = 3/8 by default).
    pub fn k_internal(&self) -> f64 {
        self.stiffness.factor() * self.youngs_modulus * self.thickness
    }

    /// K_s = K_int (l / l_z)², shear spring stiffness to the slider [N/m].
    pub fn k_shear(&self) -> f64 {
        self.k_internal() * (self.spacing / self.thickness).powi(2)
    }

    /// Number of blocks N_x N_y.
    pub fn n_blocks(&self) -> usize {
        self.nx * self.ny
    }

    /// F_ad, adhesion force per block \[N\].
    pub fn adhesion_force(&self) -> f64 {
        self.adhesion * self.spacing * self.spacing
    }

    /// Upper bound on the lattice's largest angular frequency [rad/s], from
    /// Gershgorin's theorem on the small-strain stiffness matrix: the absolute
    /// row sum for one coordinate is at most 3 K_int + K_s on the diagonal plus
    /// 4 K_int off it (2 axial neighbours, 4 diagonal ones with two coupled
    /// coordinates each), so ω_max² ≤ (7 K_int + K_s)/m. Used to suggest a
    /// stable time step.
    pub fn omega_max(&self) -> f64 {
        let row = 7.0 * self.k_internal() + self.k_shear();
        (row / self.block_mass()).sqrt()
    }

    /// Time step above which classical RK4 is unstable for the fastest mode
    /// (|ω dt| ≤ 2.785 on the imaginary axis), from [`Self::omega_max`].
    pub fn rk4_stable_dt(&self) -> f64 {
        2.785 / self.omega_max()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn defaults_are_valid_and_match_thesis_numbers() {
        let p = SpringBlockParams::default();
        p.validate().unwrap();
        // m = 1012 * (5e-6)^3 = 1.265e-13 kg; K_int = 3/8 * 0.8e6 * 5e-6 = 1.5 N/m.
        assert!((p.block_mass() - 1.265e-13).abs() < 1e-25);
        assert!((p.k_internal() - 1.5).abs() < 1e-12);
        assert!((p.k_shear() - 1.5).abs() < 1e-12);
        // MODELS §7: single-block period about 0.7 µs; RK4 stable well above 1e-8 s.
        assert!(p.rk4_stable_dt() > 1e-7, "{}", p.rk4_stable_dt());
    }

    #[test]
    fn rejects_out_of_range() {
        let mut p = SpringBlockParams {
            slider_speed: 0.0,
            ..Default::default()
        };
        assert!(p
            .validate()
            .unwrap_err()
            .to_string()
            .contains("slider speed"));
        p.slider_speed = 1e-4;
        p.friction.mu_dynamic_mean = 5.0;
        assert!(p.validate().unwrap_err().to_string().contains("mu_d"));
        p.friction.mu_dynamic_mean = 3.0;
        p.damping = -1.0;
        assert!(p.validate().unwrap_err().to_string().contains("damping"));
    }
}
