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

use super::local_law::local_law;
use crate::error::{Error, Result};
use crate::status::Code;

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
        return Err(Error::coded(
            Code::Locked,
            format!(
                "surfaces lock: mu0 = {mu0} >= cot(phi) = {:.6} at slope phi = {:.6} deg (MODELS.md §5, D <= 0)",
                1.0 / phi.abs().tan(),
                phi.to_degrees()
            ),
        ));
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

/// Slopes of two wedge surfaces (Eq. 1.10–1.12): φ1 rising and φ2 falling
/// facet of the lower surface, φ3 rising and φ4 falling facet of the upper
/// surface, all in [0, 90°) rad. A flat surface has both slopes 0.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WedgeSlopes {
    /// φ1, rad, rising facet of z1.
    pub phi1: f64,
    /// φ2, rad, falling facet of z1.
    pub phi2: f64,
    /// φ3, rad, rising facet of z2.
    pub phi3: f64,
    /// φ4, rad, falling facet of z2.
    pub phi4: f64,
}

/// Global coefficients (μ, μ_∥, μ_⊥) of two wedge surfaces sliding in
/// direction β (rad), assuming equal average spring forces on all facets
/// (Eq. 1.10–1.13). The facet weights ψ/(1+ψ), 1/(1+ψ) with ψ = tan φ2 /
/// tan φ1 (and δ = tan φ4 / tan φ3) are the fractions of the period covered
/// by each facet; a flat surface has ψ = 1. Reduces to Eq. 1.16, 1.17
/// (Case 1) and 1.21, 1.22 (Case 2). Errors when a facet locks (D ≤ 0),
/// naming its slope.
pub fn mu_wedges(mu0: f64, w: &WedgeSlopes, beta: f64) -> Result<(f64, f64, f64)> {
    let weights = |a: f64, b: f64| {
        let (ta, tb) = (a.tan(), b.tan());
        if ta + tb == 0.0 {
            (0.5, 0.5)
        } else {
            (tb / (ta + tb), ta / (ta + tb))
        }
    };
    let (w1, w2) = weights(w.phi1, w.phi2);
    let (w3, w4) = weights(w.phi3, w.phi4);
    let (mut rx, mut ry) = (0.0, 0.0);
    for (wt, phi) in [(w1, w.phi1), (w2, -w.phi2), (w3, w.phi3), (w4, -w.phi4)] {
        if !(phi.is_finite() && phi.abs() < std::f64::consts::FRAC_PI_2) {
            return Err(Error::NotApplicable(format!(
                "wedge slope {} deg is not in [0, 90) deg",
                phi.to_degrees()
            )));
        }
        // MODELS.md §5: μ0 < cot φ on every facet, whatever β.
        check_applicable(mu0, phi.abs())?;
        let r = local_law(mu0, phi, beta)?;
        rx += 0.5 * wt * r.hx;
        ry += 0.5 * wt * r.hy;
    }
    let (c, s) = (beta.cos(), beta.sin());
    Ok((rx.hypot(ry), rx * c + ry * s, ry * c - rx * s))
}

/// Hierarchical wedges at β = 90° (Eq. 2.17): μ_n = μ0 / cos^n φ (both
/// rough) or μ0 ((1/cos φ + 1)/2)^n (one flat). Each level must be
/// applicable with the previous level's coefficient as its μ0; the error
/// names the level where the surfaces lock.
pub fn mu_hierarchy_along(case: WedgeCase, mu0: f64, phi: f64, levels: u32) -> Result<f64> {
    let mut mu = mu0;
    for level in 1..=levels {
        check_applicable(mu, phi)
            .map_err(|e| Error::coded(e.status_code(), format!("level {level}: {e}")))?;
        mu = mu_along(case, mu, phi)?;
    }
    Ok(mu)
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

    /// Eq. 1.10–1.12 with equal facet forces reduce to the Case 1 and Case 2
    /// forms at β = 0 and 90°, for μ, μ_∥ and μ_⊥ (1e-14: a few roundings).
    #[test]
    fn general_wedges_reduce_to_cases() {
        let half_pi = std::f64::consts::FRAC_PI_2;
        for (mu0, phi) in [(0.3, 0.2), (0.5, 0.6), (0.1, 1.0)] {
            let one = WedgeSlopes {
                phi1: phi,
                phi2: phi,
                phi3: 0.0,
                phi4: 0.0,
            };
            let two = WedgeSlopes {
                phi1: phi,
                phi2: phi,
                phi3: phi,
                phi4: phi,
            };
            for (w, case) in [(one, WedgeCase::OneFlat), (two, WedgeCase::BothRough)] {
                let (m, p, q) = mu_wedges(mu0, &w, 0.0).unwrap();
                let a = mu_across(case, mu0, phi).unwrap();
                assert!((m - a).abs() < 1e-14 && (p - a).abs() < 1e-14 && q.abs() < 1e-14);
                let (m, p, q) = mu_wedges(mu0, &w, half_pi).unwrap();
                let b = mu_along(case, mu0, phi).unwrap();
                assert!((m - b).abs() < 1e-14 && (p - b).abs() < 1e-14 && q.abs() < 1e-14);
            }
        }
    }

    /// Asymmetric wedges (Fig. 1.4): the steeper rising facet gives the larger
    /// coefficient across, and at β = 90° φ1 > φ2 and φ1 < φ2 collapse.
    #[test]
    fn asymmetric_wedges_fig_1_4() {
        let (a, b) = (0.5_f64, 0.2_f64);
        let steep_first = WedgeSlopes {
            phi1: a,
            phi2: b,
            phi3: a,
            phi4: b,
        };
        let steep_second = WedgeSlopes {
            phi1: b,
            phi2: a,
            phi3: b,
            phi4: a,
        };
        let sym = WedgeSlopes {
            phi1: a,
            phi2: a,
            phi3: a,
            phi4: a,
        };
        let one_flat = WedgeSlopes {
            phi1: a,
            phi2: a,
            phi3: 0.0,
            phi4: 0.0,
        };
        let m1 = mu_wedges(0.3, &steep_first, 0.0).unwrap().0;
        let m2 = mu_wedges(0.3, &steep_second, 0.0).unwrap().0;
        assert!(m1 > m2, "{m1} {m2}");
        assert!(mu_wedges(0.3, &sym, 0.0).unwrap().0 > mu_wedges(0.3, &one_flat, 0.0).unwrap().0);
        let h = std::f64::consts::FRAC_PI_2;
        let (n1, n2) = (
            mu_wedges(0.3, &steep_first, h).unwrap().0,
            mu_wedges(0.3, &steep_second, h).unwrap().0,
        );
        // Equal up to rounding (1e-14): the facets swap roles only.
        assert!((n1 - n2).abs() < 1e-14);
    }

    /// Eq. 2.17 against its explicit power laws; locking at an outer level
    /// names that level.
    #[test]
    fn hierarchy_power_laws() {
        let (mu0, phi) = (0.3, 0.4_f64);
        for n in 0..5 {
            let both = mu_hierarchy_along(WedgeCase::BothRough, mu0, phi, n).unwrap();
            let one = mu_hierarchy_along(WedgeCase::OneFlat, mu0, phi, n).unwrap();
            let e = n as i32;
            assert!((both - mu0 / phi.cos().powi(e)).abs() < 1e-14);
            assert!((one - mu0 * ((1.0 / phi.cos() + 1.0) / 2.0).powi(e)).abs() < 1e-14);
        }
        // φ = 60°: cot φ = 0.577; μ0 = 0.3 → 0.6 at level 1, locks at level 2.
        let e = mu_hierarchy_along(WedgeCase::BothRough, 0.3, std::f64::consts::FRAC_PI_3, 3)
            .unwrap_err();
        assert!(e.to_string().contains("level 2"), "{e}");
    }
}
