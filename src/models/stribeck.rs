//! Stribeck parameter, Hertz pressure and EHL film of a lubricated point
//! contact (MODELS.md §11).
//!
//! - **Stribeck parameter** η·v / p, m (η dynamic viscosity, v sliding
//!   speed, p a stated contact pressure); a Stribeck curve is μ against it.
//! - **Hertz** (sphere on flat or two spheres): with the reduced modulus
//!   E′ = 2 / [(1 − ν₁²)/E₁ + (1 − ν₂²)/E₂] (Hamrock–Dowson's E′, twice
//!   Johnson's E*) and the reduced radius R′, the contact radius
//!   a = (3·F·R′ / (2·E′))^(1/3), the mean pressure p̄ = F / (π a²) and the
//!   peak 3/2 p̄.
//! - **Hamrock–Dowson** minimum film of a circular contact (ellipticity
//!   k = 1): h_min = R′ · 3.63 U^0.68 G^0.49 W^−0.073 (1 − e^−0.68),
//!   U = η·u / (E′ R′), G = α E′, W = F / (E′ R′²), u the entrainment
//!   (mean rolling) speed. A ball held still on a moving disc entrains at
//!   half the sliding speed, u = v / 2.
//! - **Film parameter** λ = h_min / σ, σ = √(Rq₁² + Rq₂²).
//! - **Journal bearing**: the load over the projected area P = W / (L·D)
//!   and the dimensionless Hersey number η·N / P with the shaft's speed N
//!   in revolutions per second (N = v / (π D) from the surface speed v).

use std::f64::consts::PI;

/// A Hertz point contact.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Hertz {
    /// Contact radius a, m.
    pub radius_m: f64,
    /// Mean pressure F / (π a²), Pa.
    pub mean_pa: f64,
    /// Peak pressure 3/2 of the mean, Pa.
    pub peak_pa: f64,
}

fn positive(x: f64) -> bool {
    x.is_finite() && x > 0.0
}

/// The Hertz contact of a load `f` (N) on a reduced radius `r` (m) with the
/// reduced modulus `e` (Pa, Hamrock–Dowson's E′); `None` unless all three
/// are positive and finite.
pub fn hertz(f: f64, r: f64, e: f64) -> Option<Hertz> {
    if !(positive(f) && positive(r) && positive(e)) {
        return None;
    }
    let a = (3.0 * f * r / (2.0 * e)).cbrt();
    let mean = f / (PI * a * a);
    Some(Hertz {
        radius_m: a,
        mean_pa: mean,
        peak_pa: 1.5 * mean,
    })
}

/// The Stribeck parameter η·v / p, m; `None` unless η and p are positive
/// and v finite (its magnitude is taken).
pub fn stribeck_parameter(eta: f64, v: f64, p: f64) -> Option<f64> {
    (positive(eta) && positive(p) && v.is_finite()).then(|| eta * v.abs() / p)
}

/// The Hersey number η·N / P of a journal bearing (dimensionless): η in
/// Pa·s, the shaft's surface speed `v` (m/s, its magnitude) on a journal
/// of diameter `d` (m), hence N = v / (π d) rev/s, and the load `w` (N)
/// over the projected area L·d (`l` the bearing length, m); `None` unless
/// η, d, l and w are positive and v finite.
pub fn hersey_number(eta: f64, v: f64, d: f64, l: f64, w: f64) -> Option<f64> {
    if !([eta, d, l, w].into_iter().all(positive) && v.is_finite()) {
        return None;
    }
    let n = v.abs() / (PI * d);
    Some(eta * n / (w / (l * d)))
}

/// The inputs of the Hamrock–Dowson film.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Film {
    /// Dynamic viscosity at the inlet η₀, Pa·s.
    pub viscosity_pa_s: f64,
    /// Pressure-viscosity coefficient α, 1/Pa.
    pub alpha_per_pa: f64,
    /// Reduced modulus E′, Pa.
    pub modulus_pa: f64,
    /// Reduced radius R′, m.
    pub radius_m: f64,
}

/// Hamrock–Dowson's minimum film thickness of a circular contact, m, at
/// the entrainment speed `u` (m/s) under `f` (N); `None` unless every
/// input is positive and finite.
pub fn hamrock_dowson_min_film(film: &Film, u: f64, f: f64) -> Option<f64> {
    let Film {
        viscosity_pa_s: eta,
        alpha_per_pa: alpha,
        modulus_pa: e,
        radius_m: r,
    } = *film;
    if ![eta, alpha, e, r, u, f].into_iter().all(positive) {
        return None;
    }
    let speed = eta * u / (e * r);
    let material = alpha * e;
    let load = f / (e * r * r);
    let k: f64 = 1.0;
    let h = 3.63
        * speed.powf(0.68)
        * material.powf(0.49)
        * load.powf(-0.073)
        * (1.0 - (-0.68 * k).exp());
    Some(h * r)
}

/// The film parameter λ = h / σ of a film `h` (m) over a composite
/// roughness σ = √(Rq₁² + Rq₂²) (m); `None` unless both are positive.
pub fn film_parameter(h: f64, sigma: f64) -> Option<f64> {
    (positive(h) && positive(sigma)).then(|| h / sigma)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A 10 mm steel ball on a steel flat under 10 N (E 210 GPa, ν 0.3):
    /// the textbook contact radius ≈ 68.7 µm and peak pressure ≈ 1.01 GPa
    /// (Johnson, Contact Mechanics, §4.2, a = (3FR/4E*)^(1/3)).
    #[test]
    fn hertz_of_a_steel_ball() {
        let e_star = 210e9 / (2.0 * (1.0 - 0.09));
        let h = hertz(10.0, 5e-3, 2.0 * e_star).unwrap();
        let a = (3.0 * 10.0 * 5e-3 / (4.0 * e_star)).cbrt();
        assert!((h.radius_m - a).abs() < 1e-15);
        assert!((h.radius_m * 1e6 - 68.7).abs() < 0.1, "{h:?}");
        assert!((h.peak_pa / 1e9 - 1.01).abs() < 0.01, "{h:?}");
        assert!((h.peak_pa - 3.0 * 10.0 / (2.0 * PI * a * a)).abs() < 1e-3);
        assert!(hertz(0.0, 5e-3, 1e11).is_none());
        assert!(hertz(10.0, f64::NAN, 1e11).is_none());
    }

    /// η·v/p with η = 0.01 Pa·s, v = 0.1 m/s, p = 1 MPa is 1e-9 m; no
    /// pressure, no parameter.
    #[test]
    fn stribeck_parameter_is_eta_v_over_p() {
        assert!((stribeck_parameter(0.01, -0.1, 1e6).unwrap() - 1e-9).abs() < 1e-24);
        assert!(stribeck_parameter(0.01, 0.1, 0.0).is_none());
        assert!(stribeck_parameter(0.0, 0.1, 1e6).is_none());
    }

    /// A 50 mm journal, 40 mm long, under 2 kN at 10 rev/s in a 0.05 Pa·s
    /// oil: P = 2000 / (0.04 · 0.05) = 1 MPa, ηN/P = 0.05 · 10 / 1e6 =
    /// 5e-7; no load or no length, no number.
    #[test]
    fn hersey_number_of_a_journal() {
        let v = PI * 0.05 * 10.0;
        let h = hersey_number(0.05, v, 0.05, 0.04, 2000.0).unwrap();
        assert!((h / 5e-7 - 1.0).abs() < 1e-14, "{h}");
        assert!(hersey_number(0.05, v, 0.05, 0.04, 0.0).is_none());
        assert!(hersey_number(0.05, v, 0.05, f64::NAN, 2000.0).is_none());
    }

    /// The film scales as u^0.68, α^0.49 and F^−0.073 (the formula's
    /// exponents, from ratios), and its value for a steel ball in a light
    /// oil (η 0.01 Pa·s, α 20 /GPa, E′ 231 GPa, R′ 9.525 mm, 20 N, u 1 m/s)
    /// is 56.78 nm, the formula evaluated by hand.
    #[test]
    fn hamrock_dowson_scales_with_its_exponents() {
        let film = Film {
            viscosity_pa_s: 0.01,
            alpha_per_pa: 20e-9,
            modulus_pa: 231e9,
            radius_m: 9.525e-3,
        };
        let h = hamrock_dowson_min_film(&film, 1.0, 20.0).unwrap();
        assert!((h - 56.784e-9).abs() < 0.01e-9, "{h}");
        let h2 = hamrock_dowson_min_film(&film, 2.0, 20.0).unwrap();
        assert!((h2 / h - 2f64.powf(0.68)).abs() < 1e-12);
        let h3 = hamrock_dowson_min_film(&film, 1.0, 40.0).unwrap();
        assert!((h3 / h - 2f64.powf(-0.073)).abs() < 1e-12);
        let thick = Film {
            alpha_per_pa: 40e-9,
            ..film
        };
        let h4 = hamrock_dowson_min_film(&thick, 1.0, 20.0).unwrap();
        assert!((h4 / h - 2f64.powf(0.49)).abs() < 1e-12);
        assert!(hamrock_dowson_min_film(&film, 0.0, 20.0).is_none());
        assert!((film_parameter(h, h / 3.0).unwrap() - 3.0).abs() < 1e-12);
        assert!(film_parameter(h, 0.0).is_none());
    }
}
