//! Closed forms of the ALSFM for wedge asperities (thesis Eq. 1.16–1.22,
//! MODELS.md §5) and the hierarchical power laws at β = 90° (Eq. 2.17).
//!
//! | symbol | field / argument | unit |
//! |---|---|---|
//! | μ0 | `mu0` | 1, local Coulomb coefficient on the tangent plane |
//! | φ | `phi` | rad, wedge slope |
//! | s | — | sin²φ (1 + μ0²) |
//!
//! Applicability: the local reaction must stay positive, D > 0, which for the
//! wedges is μ0 < cot φ (Fig. 1.2); equivalently s < 1. Outside it the
//! surfaces lock and the model does not apply: [`check_applicable`] returns
//! an error naming the slope, never an infinite or negative coefficient.
//!
//! Where these forms are exact (MODELS.md §5): Case 1 (one flat surface) at any
//! load; Case 2 (identical wedges) only at loads high enough that contact
//! does not concentrate. The numeric model decides when to use them.

use crate::error::{Error, Result};

/// Which surfaces are rough.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum WedgeCase {
    /// Case 1: wedges against a flat surface.
    OneFlat,
    /// Case 2: both surfaces with the same symmetric wedges.
    BothRough,
}

/// Checks μ0 ≥ 0, 0 ≤ φ < 90° and μ0 < cot φ (D > 0 on every facet).
pub fn check_applicable(mu0: f64, phi: f64) -> Result<()> {
    if !(mu0.is_finite() && mu0 >= 0.0) {
        return Err(Error::Config(format!(
            "mu0 must be finite and >= 0, got {mu0}"
        )));
    }
    if !(phi.is_finite() && (0.0..std::f64::consts::FRAC_PI_2).contains(&phi.abs())) {
        return Err(Error::NotApplicable(format!(
            "slope phi = {:.6} deg is not in [0, 90) deg",
            phi.to_degrees()
        )));
    }
    // μ0 < cot φ  ⇔  μ0 tan φ < 1 (also for φ = 0).
    if mu0 * phi.abs().tan() >= 1.0 {
        return Err(Error::NotApplicable(format!(
            "surfaces lock: mu0 = {mu0} >= cot(phi) = {:.6} at slope phi = {:.6} deg (MODELS.md §5, D <= 0)",
            1.0 / phi.abs().tan(),
            phi.to_degrees()
        )));
    }
    Ok(())
}

fn s_of(mu0: f64, phi: f64) -> f64 {
    phi.sin().powi(2) * (1.0 + mu0 * mu0)
}

/// Global coefficient sliding across the wedges (β = 0), Eq. 1.16 (Case 1)
/// and Eq. 1.21 (Case 2).
pub fn mu_across(case: WedgeCase, mu0: f64, phi: f64) -> Result<f64> {
    check_applicable(mu0, phi)?;
    let s = s_of(mu0, phi);
    Ok(match case {
        WedgeCase::OneFlat => mu0 * (2.0 - s) / (2.0 * (1.0 - s)),
        WedgeCase::BothRough => mu0 / (1.0 - s),
    })
}

/// Global coefficient sliding along the wedges (β = 90°), Eq. 1.17 (Case 1)
/// and Eq. 1.22 (Case 2).
pub fn mu_along(case: WedgeCase, mu0: f64, phi: f64) -> Result<f64> {
    check_applicable(mu0, phi)?;
    Ok(match case {
        WedgeCase::OneFlat => 0.5 * mu0 * (1.0 / phi.cos() + 1.0),
        WedgeCase::BothRough => mu0 / phi.cos(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Check values of MODELS.md §5 (μ0, φ, across, along) for Case 2, given
    /// to 7 digits there.
    #[test]
    fn both_rough_matches_models_check_values() {
        for (mu0, phi, across, along) in [
            (0.3, 0.2, 0.3134868, 0.3061017),
            (0.5, 0.6, 0.8312917, 0.6058142),
            (0.1, 1.0, 0.3510671, 0.1850816),
        ] {
            let a = mu_across(WedgeCase::BothRough, mu0, phi).unwrap();
            let b = mu_along(WedgeCase::BothRough, mu0, phi).unwrap();
            assert!((a - across).abs() < 1e-7, "{a} vs {across}");
            assert!((b - along).abs() < 1e-7, "{b} vs {along}");
        }
    }

    /// Flat wedges (φ = 0) give μ0 in every case.
    #[test]
    fn zero_slope_gives_mu0() {
        for case in [WedgeCase::OneFlat, WedgeCase::BothRough] {
            let a = mu_across(case, 0.4, 0.0).unwrap();
            let b = mu_along(case, 0.4, 0.0).unwrap();
            assert!((a - 0.4).abs() < 1e-15 && (b - 0.4).abs() < 1e-15);
        }
    }

    /// At μ0 = cot φ the surfaces lock: an error naming the slope.
    #[test]
    fn locking_is_an_error_naming_the_slope() {
        let phi = 0.9_f64;
        let mu0 = 1.0 / phi.tan();
        let e = mu_across(WedgeCase::OneFlat, mu0 * (1.0 + 1e-12), phi).unwrap_err();
        assert!(e.to_string().contains("51.566"), "{e}");
        assert!(mu_along(WedgeCase::BothRough, 0.1, std::f64::consts::FRAC_PI_2).is_err());
    }
}
