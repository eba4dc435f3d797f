//! Local law of the ALSFM: the reaction of one spring sliding on a tilted
//! facet (thesis Eq. 1.5–1.7, 1.26–1.28; MODELS.md §5), and its 2-D version on
//! the local tangent plane (Eq. 1.41, 1.42 and the rotation of Sec. 1.4).
//!
//! ```text
//! S   = sqrt(1 + tan²φ cos²β)
//! D   = cos φ · S − μ0 tan φ cos β            (must be > 0)
//! H_x = (sin φ · S + μ0 cos β) / D             F_x = F_z H_x
//! H_y = μ0 sin β / D                           F_y = F_z H_y
//! ```
//!
//! | symbol | argument | unit |
//! |---|---|---|
//! | μ0 | `mu0` | 1, local Coulomb coefficient on the tangent plane, ≥ 0 |
//! | φ | `phi` | rad, slope along the projected direction, in (−90°, 90°) |
//! | β | `beta` | rad, sliding direction measured from x |
//!
//! Sign convention (MODELS.md §5): φ > 0 when the spring climbs the facet in
//! the direction of motion; F_x, F_y > 0 resist the motion of the upper body.
//!
//! Applicability: D > 0, that is the normal reaction stays positive under a
//! compressive spring (Eq. 1.5, Fig. 1.2; for β = 0 this is μ0 < cot φ).
//! Outside it the surfaces lock; [`local_law`] then returns
//! [`Error::NotApplicable`] naming the slope, never an infinite or negative
//! ratio. The lattice and the closed forms also require μ0 < cot φ on every
//! slope whatever β, as MODELS.md §5 states it (see
//! [`super::instant::slope_ok`]).

use crate::error::{Error, Result};
use crate::status::Code;

/// The reaction ratios of one spring (Eq. 1.27, 1.28).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LocalReaction {
    /// S = sqrt(1 + tan²φ cos²β).
    pub s: f64,
    /// D = cos φ S − μ0 tan φ cos β, > 0.
    pub d: f64,
    /// H_x = F_x / F_z.
    pub hx: f64,
    /// H_y = F_y / F_z.
    pub hy: f64,
}

/// Smallest accepted D. Below it the reaction ratios exceed ~1e9 and the
/// surfaces are locked for every practical purpose.
pub const D_MIN: f64 = 1e-9;

/// Reaction ratios of one spring on a facet of slope `phi` sliding in
/// direction `beta` (Eq. 1.27, 1.28). Errors when D ≤ [`D_MIN`] (locking) or
/// when an argument is not finite or |φ| ≥ 90°.
pub fn local_law(mu0: f64, phi: f64, beta: f64) -> Result<LocalReaction> {
    if !(mu0.is_finite() && mu0 >= 0.0 && phi.is_finite() && beta.is_finite()) {
        return Err(Error::Config(format!(
            "local law needs finite mu0 >= 0, phi and beta; got mu0 = {mu0}, phi = {phi}, beta = {beta}"
        )));
    }
    if phi.abs() >= std::f64::consts::FRAC_PI_2 {
        return Err(Error::coded(
            Code::Locked,
            format!(
                "slope phi = {:.6} deg is vertical (|phi| >= 90 deg): the surfaces lock",
                phi.to_degrees()
            ),
        ));
    }
    Ok(local_law_unchecked(mu0, phi.tan(), beta.cos(), beta.sin()))
        .and_then(|r| check_d(r, mu0, phi, beta))
}

fn check_d(r: LocalReaction, mu0: f64, phi: f64, beta: f64) -> Result<LocalReaction> {
    if r.d > D_MIN {
        Ok(r)
    } else {
        Err(locking_error(mu0, phi, beta))
    }
}

/// The error for D ≤ 0 at slope `phi`.
pub fn locking_error(mu0: f64, phi: f64, beta: f64) -> Error {
    Error::coded(
        Code::Locked,
        format!(
            "surfaces lock at slope phi = {:.6} deg (beta = {:.6} deg, mu0 = {mu0}): \
         D = cos(phi) S - mu0 tan(phi) cos(beta) <= 0, i.e. mu0 >= cot(phi) along the sliding \
         direction (MODELS.md §5, Fig. 1.2)",
            phi.to_degrees(),
            beta.to_degrees()
        ),
    )
}

/// Eq. 1.27, 1.28 from tan φ, cos β and sin β, without checks. Callers that
/// evaluate many springs use this and check `d > D_MIN` themselves.
#[inline]
pub fn local_law_unchecked(mu0: f64, tan_phi: f64, cos_b: f64, sin_b: f64) -> LocalReaction {
    // cos φ and sin φ from tan φ, exact for |φ| < 90°.
    let sec = (1.0 + tan_phi * tan_phi).sqrt();
    let cos_phi = 1.0 / sec;
    let sin_phi = tan_phi / sec;
    let s = (1.0 + tan_phi * tan_phi * cos_b * cos_b).sqrt();
    let d = cos_phi * s - mu0 * tan_phi * cos_b;
    LocalReaction {
        s,
        d,
        hx: (sin_phi * s + mu0 * cos_b) / d,
        hy: mu0 * sin_b / d,
    }
}

/// Reaction ratios (F_x/F_z, F_y/F_z) in the global frame for a spring on a
/// 2-D surface with gradient (g_x, g_y) = (∂z/∂x, ∂z/∂y), sliding in direction
/// β (Sec. 1.4). The tangent plane's steepest direction is α_P = atan2(g_y,
/// g_x) and tan φ = |∇z|; the local law is applied with β' = β − α_P and the
/// result rotated back by α_P. Returns `None` when D ≤ [`D_MIN`] (locking).
///
/// For a surface invariant in y (g_y = 0) this equals [`local_law`] with
/// φ = atan g_x (α_P = 0 or π).
#[inline]
pub fn local_law_2d(mu0: f64, gx: f64, gy: f64, cos_b: f64, sin_b: f64) -> Option<(f64, f64)> {
    let t = gx.hypot(gy);
    if t == 0.0 {
        return Some((mu0 * cos_b, mu0 * sin_b));
    }
    // cos α_P, sin α_P without trigonometric calls.
    let (ca, sa) = (gx / t, gy / t);
    // β' = β − α_P.
    let cbp = cos_b * ca + sin_b * sa;
    let sbp = sin_b * ca - cos_b * sa;
    let r = local_law_unchecked(mu0, t, cbp, sbp);
    if r.d <= D_MIN || !r.d.is_finite() {
        return None;
    }
    // Rotate (H_x', H_y') back by +α_P.
    Some((ca * r.hx - sa * r.hy, sa * r.hx + ca * r.hy))
}

/// [`local_law_2d`] and the slope condition of
/// [`super::instant::slope_ok`] in closed form, for the lattice's hot loop:
/// (H_x, H_y, applicable). Substituting tan φ = |g|, cos β' = p/|g| with
/// p = g·ê_β, cos φ = 1/q with q = √(1 + |g|²), and the rotation back by
/// α_P (cos α_P cos β' − sin α_P sin β' = cos β) into Eq. 1.27, 1.28 gives
///
/// ```text
/// S = √(1 + p²)     D = (S − μ0 p q) / q
/// H_x = (g_x S + μ0 cos β q) / (S − μ0 p q)
/// H_y = (g_y S + μ0 sin β q) / (S − μ0 p q)
/// ```
///
/// two square roots and one division instead of `hypot`, four roots and
/// four divisions; branch-free, so a row of springs vectorises. Equal to
/// [`local_law_2d`] to rounding (tested to 1e-13). `applicable` is D >
/// [`D_MIN`] and μ0 |g| < 1 − [`D_MIN`]; the ratios are meaningless when it
/// is false.
#[inline]
pub fn tangent_plane_ratios(
    mu0: f64,
    gx: f64,
    gy: f64,
    cos_b: f64,
    sin_b: f64,
) -> (f64, f64, bool) {
    let t2 = gx * gx + gy * gy;
    let p = cos_b * gx + sin_b * gy;
    let s = (1.0 + p * p).sqrt();
    let q = (1.0 + t2).sqrt();
    let den = s - mu0 * p * q;
    let r = 1.0 / den;
    let ok = den > D_MIN * q && mu0 * mu0 * t2 < (1.0 - D_MIN) * (1.0 - D_MIN);
    (
        (gx * s + mu0 * cos_b * q) * r,
        (gy * s + mu0 * sin_b * q) * r,
        ok,
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    /// At β = 0 the law reduces to H_x = (μ0 + tan φ)/(1 − μ0 tan φ), H_y = 0
    /// (the facet terms of Eq. 1.16); 1e-14 allows a few roundings.
    #[test]
    fn beta_zero_reduces_to_wedge_facet_term() {
        for (mu0, phi) in [(0.3, 0.2), (0.5, -0.6), (0.1, 1.0)] {
            let r = local_law(mu0, phi, 0.0).unwrap();
            let t: f64 = f64::tan(phi);
            assert!((r.hx - (mu0 + t) / (1.0 - mu0 * t)).abs() < 1e-14);
            assert!(r.hy.abs() < 1e-15);
        }
    }

    /// At β = 90° the law gives H_x = tan φ ... and H_y = μ0 / cos φ, the
    /// facet term of Eq. 1.17 (S = 1, D = cos φ).
    #[test]
    fn beta_ninety_gives_mu0_over_cos_phi() {
        let (mu0, phi) = (0.3, 0.5_f64);
        let r = local_law(mu0, phi, std::f64::consts::FRAC_PI_2).unwrap();
        assert!((r.hy - mu0 / phi.cos()).abs() < 1e-14);
        assert!((r.hx - phi.tan()).abs() < 1e-14);
    }

    /// Flat facet: Coulomb along the sliding direction.
    #[test]
    fn flat_facet_is_coulomb() {
        let b = 0.7_f64;
        let r = local_law(0.4, 0.0, b).unwrap();
        assert!((r.hx - 0.4 * b.cos()).abs() < 1e-15 && (r.hy - 0.4 * b.sin()).abs() < 1e-15);
    }

    /// D ≤ 0 is an error that names the slope in degrees.
    #[test]
    fn locking_names_the_slope() {
        let phi = 1.2_f64;
        let mu0 = 1.0 / phi.tan() + 1e-6;
        let e = local_law(mu0, phi, 0.0).unwrap_err().to_string();
        assert!(e.contains("68.754935"), "{e}");
        assert!(local_law(0.1, std::f64::consts::FRAC_PI_2, 0.0).is_err());
        assert!(local_law(f64::NAN, 0.1, 0.0).is_err());
    }

    /// The 2-D law with g_y = 0 equals the 1-D law, for both signs of the
    /// slope and several β; 1e-14 covers the rotation by α_P = 0 or π.
    #[test]
    fn two_d_law_with_y_invariance_equals_one_d() {
        for phi in [-0.8_f64, -0.1, 0.3, 0.9] {
            for beta in [0.0_f64, 0.4, 1.2, std::f64::consts::FRAC_PI_2] {
                let r = local_law(0.25, phi, beta).unwrap();
                let (fx, fy) = local_law_2d(0.25, phi.tan(), 0.0, beta.cos(), beta.sin()).unwrap();
                assert!((fx - r.hx).abs() < 1e-14 && (fy - r.hy).abs() < 1e-14);
            }
        }
    }

    /// A surface invariant in x (slope along y) seen at β = 90° is the 1-D
    /// case rotated by 90°: F_y/F_z = H_x(φ, 0) and F_x/F_z = −H_y(φ, 0) = 0.
    #[test]
    fn two_d_law_is_rotation_covariant() {
        let phi = 0.4_f64;
        let (fx, fy) = local_law_2d(0.3, 0.0, phi.tan(), 0.0, 1.0).unwrap();
        let r = local_law(0.3, phi, 0.0).unwrap();
        assert!((fy - r.hx).abs() < 1e-14 && fx.abs() < 1e-14);
    }

    /// The closed form equals the thesis' rotation form to 1e-13 (relative
    /// to the size of the ratios) on gradients of every direction and
    /// slopes up to tan φ = 3, at several β and μ0, and flags exactly the
    /// same springs as locked away from the boundary (D and μ0 tan φ more
    /// than 1e-9 from it).
    #[test]
    fn closed_form_equals_rotation_form() {
        let mut n = 0;
        for i in 0..40 {
            for j in 0..40 {
                let (gx, gy) = (
                    -3.0 + 0.15 * i as f64 + 0.013,
                    -3.0 + 0.15 * j as f64 - 0.007,
                );
                for (mu0, beta) in [(0.3, 0.0_f64), (0.3, 0.6), (0.8, 1.9), (0.1, -2.7)] {
                    let (cb, sb) = (beta.cos(), beta.sin());
                    let (hx, hy, ok) = tangent_plane_ratios(mu0, gx, gy, cb, sb);
                    let t = gx.hypot(gy);
                    let reference = local_law_2d(mu0, gx, gy, cb, sb)
                        .filter(|_| super::super::instant::slope_ok(mu0, t, 1.0));
                    let d = (1.0 + (cb * gx + sb * gy).powi(2)).sqrt() / (1.0 + t * t).sqrt()
                        - mu0 * (cb * gx + sb * gy);
                    if (d - D_MIN).abs() < 1e-9 || (mu0 * t - 1.0).abs() < 1e-9 {
                        continue;
                    }
                    assert_eq!(ok, reference.is_some(), "{gx} {gy} {mu0} {beta}");
                    if let Some((rx, ry)) = reference {
                        let scale = 1.0 + rx.abs() + ry.abs();
                        assert!((hx - rx).abs() < 1e-13 * scale, "{hx} {rx}");
                        assert!((hy - ry).abs() < 1e-13 * scale, "{hy} {ry}");
                        n += 1;
                    }
                }
            }
        }
        assert!(n > 3000, "{n}");
    }
}
