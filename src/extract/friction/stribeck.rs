//! Each velocity step as a point of a Stribeck curve (MODELS.md §11), from
//! the lubricant and contact the manifest states: the Stribeck parameter
//! η·v/p with its pressure named (nominal F/A when the manifest gives the
//! apparent area, else the mean Hertz pressure from E′ and R′), and, with
//! the pressure-viscosity coefficient, Hamrock–Dowson's minimum film at
//! the entrainment speed v/2 (a pin or ball held still on a moving
//! counterface) and the film parameter λ over the composite roughness. A
//! journal bearing (the manifest's journal diameter and bearing length)
//! divides by the load over the projected area and gets the Hersey number.

use crate::models::stribeck::{
    film_parameter, hamrock_dowson_min_film, hersey_number, hertz, stribeck_parameter, Film,
};

/// The lubricant and contact of a test, from the manifest (all optional).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Lubrication {
    /// `viscosity_Pa_s`: dynamic viscosity η at the test temperature, Pa·s.
    pub viscosity_pa_s: Option<f64>,
    /// `pressure_viscosity_per_GPa`: α, stored in 1/Pa.
    pub alpha_per_pa: Option<f64>,
    /// `reduced_modulus_GPa`: E′ = 2 / Σ(1 − ν²)/E, stored in Pa.
    pub modulus_pa: Option<f64>,
    /// `reduced_radius_mm`: R′, stored in m.
    pub radius_m: Option<f64>,
    /// `composite_rq_um`: σ = √(Rq₁² + Rq₂²), stored in m.
    pub composite_rq_m: Option<f64>,
    /// `journal_diameter_mm` and `bearing_length_mm` of a journal bearing,
    /// stored in m.
    pub journal_m: Option<(f64, f64)>,
}

/// Which contact pressure a Stribeck parameter divides by.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PressureKind {
    /// F / A with the manifest's apparent area.
    Nominal,
    /// The mean Hertz pressure F / (π a²).
    HertzMean,
    /// A journal's load over its projected area W / (L·D).
    Projected,
}

impl PressureKind {
    /// The stable text form.
    pub fn as_str(self) -> &'static str {
        match self {
            PressureKind::Nominal => "nominal",
            PressureKind::HertzMean => "hertz_mean",
            PressureKind::Projected => "projected",
        }
    }
}

/// A step's place on the Stribeck curve; `None` where an input is missing.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct StribeckPoint {
    /// The contact pressure and which one, Pa.
    pub pressure: Option<(f64, PressureKind)>,
    /// η·v / p, m.
    pub parameter_m: Option<f64>,
    /// Hamrock–Dowson minimum film, m.
    pub film_m: Option<f64>,
    /// λ = h_min / σ.
    pub lambda: Option<f64>,
    /// A journal's Hersey number η·N / P.
    pub hersey: Option<f64>,
}

/// The Stribeck point of a step at speed `v` (m/s) under `normal_n` (N),
/// with the manifest's `area_m2`.
pub fn stribeck_point(
    lub: &Lubrication,
    area_m2: Option<f64>,
    normal_n: Option<f64>,
    v: f64,
) -> StribeckPoint {
    let Some(f) = normal_n.filter(|f| f.is_finite() && *f > 0.0) else {
        return StribeckPoint::default();
    };
    let nominal = area_m2
        .filter(|a| a.is_finite() && *a > 0.0)
        .map(|a| (f / a, PressureKind::Nominal));
    let projected = lub
        .journal_m
        .filter(|(d, l)| d * l > 0.0)
        .map(|(d, l)| (f / (l * d), PressureKind::Projected));
    let hertzian = || {
        let h = hertz(f, lub.radius_m?, lub.modulus_pa?)?;
        Some((h.mean_pa, PressureKind::HertzMean))
    };
    let pressure = nominal.or(projected).or_else(hertzian);
    let film = || {
        let film = Film {
            viscosity_pa_s: lub.viscosity_pa_s?,
            alpha_per_pa: lub.alpha_per_pa?,
            modulus_pa: lub.modulus_pa?,
            radius_m: lub.radius_m?,
        };
        hamrock_dowson_min_film(&film, 0.5 * v.abs(), f)
    };
    let film_m = film();
    StribeckPoint {
        pressure,
        parameter_m: lub
            .viscosity_pa_s
            .zip(pressure)
            .and_then(|(eta, (p, _))| stribeck_parameter(eta, v, p)),
        film_m,
        lambda: film_m
            .zip(lub.composite_rq_m)
            .and_then(|(h, s)| film_parameter(h, s)),
        hersey: lub
            .viscosity_pa_s
            .zip(lub.journal_m)
            .and_then(|(eta, (d, l))| hersey_number(eta, v, d, l, f)),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// With an apparent area the pressure is nominal and η·v/p follows;
    /// without one, the mean Hertz pressure; the film needs α, and λ the
    /// roughness; no viscosity, no parameter; no load, nothing.
    #[test]
    fn a_step_on_the_stribeck_curve() {
        let lub = Lubrication {
            viscosity_pa_s: Some(0.01),
            alpha_per_pa: Some(20e-9),
            modulus_pa: Some(231e9),
            radius_m: Some(9.525e-3),
            composite_rq_m: Some(20e-9),
            journal_m: None,
        };
        let p = stribeck_point(&lub, Some(1e-4), Some(100.0), 0.2);
        assert_eq!(p.pressure, Some((1e6, PressureKind::Nominal)));
        assert!((p.parameter_m.unwrap() - 0.01 * 0.2 / 1e6).abs() < 1e-24);
        let q = stribeck_point(&lub, None, Some(20.0), 2.0);
        let (pm, kind) = q.pressure.unwrap();
        assert_eq!(kind, PressureKind::HertzMean);
        let a = (3.0f64 * 20.0 * 9.525e-3 / (2.0 * 231e9)).cbrt();
        assert!((pm / (20.0 / (std::f64::consts::PI * a * a)) - 1.0).abs() < 1e-12);
        // u = v / 2 = 1 m/s: the film of the model's own test, 56.78 nm.
        assert!((q.film_m.unwrap() - 56.784e-9).abs() < 0.01e-9);
        assert!((q.lambda.unwrap() - q.film_m.unwrap() / 20e-9).abs() < 1e-12);
        let dry = Lubrication::default();
        assert_eq!(
            stribeck_point(&dry, Some(1e-4), Some(100.0), 0.2).parameter_m,
            None
        );
        assert_eq!(
            stribeck_point(&lub, Some(1e-4), None, 0.2),
            StribeckPoint::default()
        );
    }

    /// A journal (50 mm, 40 mm long) under 2 kN at 10 rev/s: the pressure
    /// is the projected 1 MPa, the Hersey number 0.05 · 10 / 1e6.
    #[test]
    fn a_journal_step_has_its_hersey_number() {
        let lub = Lubrication {
            viscosity_pa_s: Some(0.05),
            journal_m: Some((0.05, 0.04)),
            ..Default::default()
        };
        let v = std::f64::consts::PI * 0.05 * 10.0;
        let p = stribeck_point(&lub, None, Some(2000.0), v);
        assert_eq!(p.pressure, Some((1e6, PressureKind::Projected)));
        assert!((p.hersey.unwrap() / 5e-7 - 1.0).abs() < 1e-14);
        assert!((p.parameter_m.unwrap() - 0.05 * v / 1e6).abs() < 1e-20);
        let dry = Lubrication {
            viscosity_pa_s: None,
            ..lub
        };
        assert_eq!(stribeck_point(&dry, None, Some(2000.0), v).hersey, None);
    }
}
