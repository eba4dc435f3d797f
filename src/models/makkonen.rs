//! Ice friction: Makkonen's melt-water film model with ALSFM roughness
//! bounds (thesis Ch. 3, Eq. 3.2, 3.8 corrected, 3.11, 3.12; MODELS.md §6).
//!
//! The friction is the shear of a water film of thickness h over the real
//! contact area A = N / H: μ_wet = η v / (H h) (Eq. 3.2). The heat balance
//! per unit real contact area, with contact time a / v,
//!
//! ```text
//! η v² / h = γ √(v / (2a)) + ρ_w L h v / a
//! ```
//!
//! has the positive root that gives (Eq. 3.8 with γ² under the root, as
//! MODELS.md corrects the thesis)
//!
//! ```text
//! μ_wet = 1/(H √a) · 1/(2 √(2v)) · [γ + √(γ² + 8 η L ρ_w v²)]
//! γ     = ΔT₁ √(c₁ k₁ ρ₁) + ΔT₂ √(c₂ k₂ ρ₂)        (1 = ice, 2 = slider)
//! H     = C₁ T + C₂                                  (T bulk, °C)
//! ```
//!
//! Limits: conduction-dominated (γ² ≫ 8ηLρ_w v²) μ → γ / (H √(2 a v));
//! melt-dominated μ → √(ρ_w L η v / a) / H.
//!
//! Roughness (Eq. 3.11, 3.12): μ_wet replaces μ0 in the ALSFM wedge closed
//! forms with one flat surface (the ice), φ = Rdq of the pin: the upper
//! bound f^u slides across (β = 0), the lower bound f^l along (β = 90°).
//!
//! | symbol | field / argument | unit | default (Table 3.2) |
//! |---|---|---|---|
//! | η | `eta` | Pa s | 1.76e-3 |
//! | ρ_w | `rho_water` | kg/m³ | 1000 |
//! | L | `latent_heat` | J/kg | 330e3 |
//! | ρ₁, k₁, c₁ | `ice` | kg/m³, W/(m K), J/(kg K) | 916, 2.2, 2090 |
//! | ρ₂, k₂, c₂ | `slider` | same | 7750, 20, 460 (steel) |
//! | C₁, C₂ | `c1`, `c2` | Pa/K, Pa | −5.08e6, 15.19e6 |
//! | T_m | `t_melt_c` | °C | 0 |
//! | v | `v` | m/s | > 0 |
//! | a | `a` | m, contact length | > 0 |
//! | T | `t_c` | °C, bulk temperature | H > 0 (T < 2.99 °C); tests −17 to −2 |
//! | φ | `phi` | rad | μ_wet < cot φ |
//!
//! Assumptions: the film is thin and laminar; the heat conducted into both
//! bodies is that of a semi-infinite solid during the contact time; all the
//! real contact carries hardness pressure H. The thermal driving ΔT is an
//! explicit choice ([`Thermal`]): from the bulk temperature, or a given
//! interface ΔT (in the conduction regime only ΔT/√a is identifiable).

use crate::error::{Error, Result};
use crate::models::alsfm::closed_form::{mu_across, mu_along, WedgeCase};

/// Thermal properties of one body.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Material {
    /// Density ρ, kg/m³, > 0.
    pub rho: f64,
    /// Conductivity k, W/(m K), > 0.
    pub k: f64,
    /// Specific heat c, J/(kg K), > 0.
    pub c: f64,
}

impl Material {
    /// Thermal effusivity √(c k ρ), J/(m² K s^½).
    pub fn effusivity(&self) -> f64 {
        (self.c * self.k * self.rho).sqrt()
    }
}

/// Constants of the model (Table 3.2); see the module table.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct MakkonenParams {
    /// Water viscosity η, Pa s. Default 1.76e-3, > 0.
    pub eta: f64,
    /// Water density ρ_w, kg/m³. Default 1000, > 0.
    pub rho_water: f64,
    /// Latent heat of fusion L, J/kg. Default 330e3, > 0.
    pub latent_heat: f64,
    /// Ice (body 1). Default ρ 916, k 2.2, c 2090.
    pub ice: Material,
    /// Slider (body 2). Default steel ρ 7750, k 20, c 460.
    pub slider: Material,
    /// Hardness slope C₁, Pa/K. Default −5.08e6.
    pub c1: f64,
    /// Hardness at 0 °C C₂, Pa. Default 15.19e6.
    pub c2: f64,
    /// Melting point T_m, °C. Default 0.
    pub t_melt_c: f64,
}

impl Default for MakkonenParams {
    fn default() -> Self {
        MakkonenParams {
            eta: 1.76e-3,
            rho_water: 1000.0,
            latent_heat: 330e3,
            ice: Material {
                rho: 916.0,
                k: 2.2,
                c: 2090.0,
            },
            slider: Material {
                rho: 7750.0,
                k: 20.0,
                c: 460.0,
            },
            c1: -5.08e6,
            c2: 15.19e6,
            t_melt_c: 0.0,
        }
    }
}

impl MakkonenParams {
    /// Checks that every constant is finite and the positive ones positive.
    pub fn validate(&self) -> Result<()> {
        let pos = [
            self.eta,
            self.rho_water,
            self.latent_heat,
            self.ice.rho,
            self.ice.k,
            self.ice.c,
            self.slider.rho,
            self.slider.k,
            self.slider.c,
        ];
        if pos.iter().all(|v| v.is_finite() && *v > 0.0)
            && self.c1.is_finite()
            && self.c2.is_finite()
            && self.t_melt_c.is_finite()
        {
            Ok(())
        } else {
            Err(Error::Config(format!(
                "invalid Makkonen constants {self:?}: all must be finite, material constants > 0"
            )))
        }
    }

    /// Ice hardness H = C₁ T + C₂, Pa (T in °C). Error when H ≤ 0.
    pub fn hardness(&self, t_c: f64) -> Result<f64> {
        let h = self.c1 * t_c + self.c2;
        if h.is_finite() && h > 0.0 {
            Ok(h)
        } else {
            Err(Error::NotApplicable(format!(
                "ice hardness H = C1 T + C2 = {h:.4e} Pa at T = {t_c} C is not positive"
            )))
        }
    }

    /// γ = ΔT₁ √(c₁k₁ρ₁) + ΔT₂ √(c₂k₂ρ₂), W s^½ / m².
    pub fn gamma(&self, thermal: Thermal, t_c: f64) -> Result<f64> {
        let (d1, d2) = thermal.delta_t(self.t_melt_c, t_c)?;
        Ok(d1 * self.ice.effusivity() + d2 * self.slider.effusivity())
    }
}

/// Where the thermal driving ΔT comes from.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Thermal {
    /// ΔT₁ = ΔT₂ = T_m − T_bulk (both bodies at the bulk temperature).
    Bulk,
    /// A given ΔT (K, ≥ 0) for both bodies.
    Interface {
        /// ΔT, K.
        delta_t: f64,
    },
}

impl Thermal {
    /// (ΔT₁, ΔT₂), K; error when negative or non-finite.
    pub fn delta_t(self, t_melt_c: f64, t_c: f64) -> Result<(f64, f64)> {
        let d = match self {
            Thermal::Bulk => t_melt_c - t_c,
            Thermal::Interface { delta_t } => delta_t,
        };
        if d.is_finite() && d >= 0.0 {
            Ok((d, d))
        } else {
            Err(Error::NotApplicable(format!(
                "thermal driving Delta T = {d} K must be finite and >= 0 (T <= T_m)"
            )))
        }
    }
}

fn check_va(v: f64, a: f64) -> Result<()> {
    if v.is_finite() && v > 0.0 && a.is_finite() && a > 0.0 {
        Ok(())
    } else {
        Err(Error::NotApplicable(format!(
            "velocity v = {v} m/s and contact length a = {a} m must be finite and > 0"
        )))
    }
}

/// Film thickness h, m: the positive root of the heat balance
/// (ρ_w L v / a) h² + γ √(v/(2a)) h − η v² = 0, in the cancellation-free
/// form h = 2C / (B + √(B² + 4AC)).
pub fn film_thickness(p: &MakkonenParams, v: f64, a: f64, gamma: f64) -> Result<f64> {
    check_va(v, a)?;
    let qa = p.rho_water * p.latent_heat * v / a;
    let qb = gamma * (v / (2.0 * a)).sqrt();
    let qc = p.eta * v * v;
    Ok(2.0 * qc / (qb + (qb * qb + 4.0 * qa * qc).sqrt()))
}

/// μ_wet from the corrected Eq. 3.8 with a given γ and H.
pub fn mu_wet_gamma(p: &MakkonenParams, v: f64, a: f64, gamma: f64, hardness: f64) -> Result<f64> {
    check_va(v, a)?;
    if !(gamma.is_finite() && gamma >= 0.0 && hardness.is_finite() && hardness > 0.0) {
        return Err(Error::NotApplicable(format!(
            "gamma = {gamma} must be >= 0 and H = {hardness} Pa > 0"
        )));
    }
    let root = (gamma * gamma + 8.0 * p.eta * p.latent_heat * p.rho_water * v * v).sqrt();
    Ok((gamma + root) / (hardness * a.sqrt() * 2.0 * (2.0 * v).sqrt()))
}

/// μ_wet (corrected Eq. 3.8) at velocity `v` (m/s), contact length `a`
/// (m) and bulk temperature `t_c` (°C).
pub fn mu_wet(p: &MakkonenParams, v: f64, a: f64, t_c: f64, thermal: Thermal) -> Result<f64> {
    mu_wet_gamma(p, v, a, p.gamma(thermal, t_c)?, p.hardness(t_c)?)
}

/// Upper (across, β = 0, Eq. 3.11) and lower (along, β = 90°, Eq. 3.12)
/// bounds: the ALSFM one-flat wedge forms with μ0 = μ_wet and slope `phi`
/// (rad). Error when the surfaces lock (μ_wet ≥ cot φ).
pub fn mu_bounds(
    p: &MakkonenParams,
    v: f64,
    a: f64,
    t_c: f64,
    thermal: Thermal,
    phi: f64,
) -> Result<(f64, f64)> {
    let m = mu_wet(p, v, a, t_c, thermal)?;
    Ok((
        mu_across(WedgeCase::OneFlat, m, phi)?,
        mu_along(WedgeCase::OneFlat, m, phi)?,
    ))
}

/// Which bound of the roughness model.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Bound {
    /// f^u, sliding across the asperities (Eq. 3.11).
    Upper,
    /// f^l, sliding along the asperities (Eq. 3.12).
    Lower,
}

impl Bound {
    /// `upper` or `lower`.
    pub fn name(self) -> &'static str {
        match self {
            Bound::Upper => "upper",
            Bound::Lower => "lower",
        }
    }
    /// The bound's μ given μ_wet and φ.
    pub fn apply(self, mu_wet: f64, phi: f64) -> Result<f64> {
        match self {
            Bound::Upper => mu_across(WedgeCase::OneFlat, mu_wet, phi),
            Bound::Lower => mu_along(WedgeCase::OneFlat, mu_wet, phi),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const P: fn() -> MakkonenParams = MakkonenParams::default;

    /// The closed form equals η v / (H h) with h from the quadratic, to
    /// 1e-13 relative (two roundings of the same algebra), over 6 decades
    /// of v and 3 of a.
    #[test]
    fn closed_form_equals_film_shear() {
        let p = P();
        for &v in &[1e-3, 0.025, 0.1, 1.0, 10.0, 1e3] {
            for &a in &[1e-6, 1e-4, 1e-3] {
                for &t in &[-17.0, -2.0] {
                    let g = p.gamma(Thermal::Bulk, t).unwrap();
                    let h = film_thickness(&p, v, a, g).unwrap();
                    let hard = p.hardness(t).unwrap();
                    let direct = p.eta * v / (hard * h);
                    let cf = mu_wet(&p, v, a, t, Thermal::Bulk).unwrap();
                    assert!(
                        ((cf - direct) / direct).abs() < 1e-13,
                        "v {v} a {a}: {cf} vs {direct}"
                    );
                    // h solves the heat balance (residual relative to its terms).
                    let lhs = p.eta * v * v / h;
                    let rhs = g * (v / (2.0 * a)).sqrt() + p.rho_water * p.latent_heat * h * v / a;
                    assert!(((lhs - rhs) / lhs).abs() < 1e-13);
                }
            }
        }
    }

    /// Conduction-dominated (slow, cold): μ → γ / (H √(2 a v)); the
    /// relative gap is (√(1+ε) − 1)/2 ≈ ε/4 with ε = 8ηLρ_w v²/γ², checked
    /// against that bound. Melt-dominated (γ = 0 exactly): μ equals
    /// √(ρ_w L η v / a) / H to rounding.
    #[test]
    fn conduction_and_melt_limits() {
        let p = P();
        let (a, t) = (1e-4, -10.0);
        let g = p.gamma(Thermal::Bulk, t).unwrap();
        let hard = p.hardness(t).unwrap();
        for &v in &[1e-4, 1e-3, 1e-2] {
            let eps = 8.0 * p.eta * p.latent_heat * p.rho_water * v * v / (g * g);
            let lim = g / (hard * (2.0 * a * v).sqrt());
            let m = mu_wet(&p, v, a, t, Thermal::Bulk).unwrap();
            assert!(
                (m / lim - 1.0).abs() <= eps / 4.0 + 1e-15 && eps < 1e-3,
                "v {v}"
            );
        }
        for &v in &[0.01, 1.0, 30.0] {
            let m = mu_wet(&p, v, a, 0.0, Thermal::Interface { delta_t: 0.0 }).unwrap();
            let lim = (p.rho_water * p.latent_heat * p.eta * v / a).sqrt() / p.c2;
            assert!((m / lim - 1.0).abs() < 1e-14, "v {v}: {m} {lim}");
        }
        // Scalings: conduction μ ∝ v^−½, melt μ ∝ v^½.
        let slow = |v: f64| mu_wet(&p, v, a, t, Thermal::Bulk).unwrap();
        assert!(((slow(1e-5) / slow(4e-5)) - 2.0).abs() < 1e-3);
    }

    /// Upper ≥ lower ≥ μ_wet, equal at φ = 0; a locking slope is an error.
    #[test]
    fn bounds_ordering() {
        let p = P();
        for &phi_deg in &[0.0_f64, 7.3, 27.2, 33.6] {
            for &v in &[0.025, 0.1, 1.0] {
                let m = mu_wet(&p, v, 1e-4, -10.0, Thermal::Bulk).unwrap();
                let (u, l) =
                    mu_bounds(&p, v, 1e-4, -10.0, Thermal::Bulk, phi_deg.to_radians()).unwrap();
                assert!(u >= l && l >= m, "phi {phi_deg} v {v}: {u} {l} {m}");
                if phi_deg == 0.0 {
                    assert!((u - m).abs() < 1e-15 * m && (l - m).abs() < 1e-15 * m);
                }
            }
        }
        assert!(mu_bounds(&p, 1e-6, 1e-9, -17.0, Thermal::Bulk, 1.5).is_err());
    }

    /// Invalid inputs are errors, not numbers.
    #[test]
    fn invalid_inputs_are_errors() {
        let p = P();
        assert!(mu_wet(&p, 0.0, 1e-4, -5.0, Thermal::Bulk).is_err());
        assert!(mu_wet(&p, 0.1, -1e-4, -5.0, Thermal::Bulk).is_err());
        assert!(mu_wet(&p, 0.1, 1e-4, 5.0, Thermal::Bulk).is_err()); // above T_m
        assert!(p.hardness(3.0).is_err());
        assert!(mu_wet(&p, 0.1, 1e-4, -5.0, Thermal::Interface { delta_t: -1.0 }).is_err());
    }
}
