//! Evaluation of the Makkonen film model and its ALSFM roughness bounds on
//! a grid of (v, T, a, φ) for plots (MODELS.md §6): the `ice_grid` table.
//! Every grid point is independent; a point where the model does not apply
//! (locking slope, H ≤ 0, T above melting) is a row with its reason in
//! `status` and null values, never a number.

use crate::error::{Error, Result};
use crate::models::makkonen::{film_thickness, mu_bounds, mu_wet, MakkonenParams, Thermal};
use crate::status::{Code, Status};
use crate::table::{Table, TableBuilder};

/// The grid; the table has one row per combination, in the nested order
/// v (outermost), T, a, φ.
#[derive(Debug, Clone, serde::Serialize, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct IceGrid {
    /// Velocities, m/s, > 0.
    pub velocities_m_per_s: Vec<f64>,
    /// Bulk temperatures, °C.
    pub temperatures_c: Vec<f64>,
    /// Contact lengths, m, > 0.
    pub a_m: Vec<f64>,
    /// Slopes, degrees, in [0, 90).
    pub phi_deg: Vec<f64>,
    /// Model constants.
    #[serde(default)]
    pub model: MakkonenParams,
    /// Thermal assumption.
    #[serde(default = "bulk")]
    pub thermal: Thermal,
    /// The largest μ the scene accepts as a friction coefficient on ice;
    /// a point above it keeps its values with a `beyond_validity` status.
    /// Default 1.
    #[serde(default = "one")]
    pub mu_max: f64,
}

fn one() -> f64 {
    1.0
}

/// The thinnest film the continuum model describes: about one water
/// molecule (0.28 nm). A thinner computed film is not a film.
pub const MIN_FILM_M: f64 = 3e-10;

/// `ok`, or why a computed point is outside the model's validity: a film
/// thinner than a molecule, or μ above the scene's bound.
fn validity(h: f64, mus: [f64; 3], mu_max: f64) -> Status {
    let mut s = Status::ok();
    if h < MIN_FILM_M {
        s.push(
            Code::BeyondValidity,
            format!("film {h:.3e} m is thinner than a water molecule ({MIN_FILM_M:e} m)"),
        );
    }
    if let Some(m) = mus.iter().copied().find(|m| *m > mu_max) {
        s.push(
            Code::BeyondValidity,
            format!("μ = {m:.3} above the scene's bound mu_max = {mu_max}"),
        );
    }
    s
}

fn bulk() -> Thermal {
    Thermal::Bulk
}

/// Logarithmically spaced values from `lo` to `hi` (inclusive), n ≥ 2.
pub fn logspace(lo: f64, hi: f64, n: usize) -> Result<Vec<f64>> {
    if !(lo > 0.0 && hi > lo && n >= 2 && hi.is_finite()) {
        return Err(Error::Config(format!(
            "logspace needs 0 < lo < hi and n >= 2, got {lo}, {hi}, {n}"
        )));
    }
    let (a, b) = (lo.ln(), hi.ln());
    Ok((0..n)
        .map(|i| (a + (b - a) * i as f64 / (n - 1) as f64).exp())
        .collect())
}

/// Evaluates the grid into the `ice_grid` table.
pub fn simulate_ice(g: &IceGrid) -> Result<Table> {
    g.model.validate()?;
    if g.mu_max.is_nan() || g.mu_max <= 0.0 {
        return Err(Error::Config(format!(
            "mu_max = {}: expected a bound > 0",
            g.mu_max
        )));
    }
    for (name, v) in [
        ("velocities_m_per_s", &g.velocities_m_per_s),
        ("temperatures_c", &g.temperatures_c),
        ("a_m", &g.a_m),
        ("phi_deg", &g.phi_deg),
    ] {
        if v.is_empty() || v.iter().any(|x| !x.is_finite()) {
            return Err(Error::Config(format!(
                "grid '{name}' must be a non-empty list of finite numbers"
            )));
        }
    }
    let mut c: [Vec<Option<f64>>; 11] = Default::default();
    let mut status = vec![];
    let p = &g.model;
    for &v in &g.velocities_m_per_s {
        for &t in &g.temperatures_c {
            for &a in &g.a_m {
                for &phi in &g.phi_deg {
                    let row = (|| -> Result<[f64; 6]> {
                        let hard = p.hardness(t)?;
                        let gamma = p.gamma(g.thermal, t)?;
                        let h = film_thickness(p, v, a, gamma)?;
                        let m = mu_wet(p, v, a, t, g.thermal)?;
                        let (u, l) = mu_bounds(p, v, a, t, g.thermal, phi.to_radians())?;
                        let melt = p.rho_water * p.latent_heat * h * v / a / (p.eta * v * v / h);
                        Ok([hard, h, m, u, l, melt])
                    })();
                    for (k, x) in [v, t, a, phi].iter().enumerate() {
                        c[k].push(Some(*x));
                    }
                    match row {
                        Ok(r) => {
                            for (k, x) in r.iter().enumerate() {
                                c[4 + k].push(Some(*x));
                            }
                            let s = validity(r[1], [r[2], r[3], r[4]], g.mu_max);
                            status.push(s);
                        }
                        Err(e) => {
                            for col in c.iter_mut().skip(4).take(6) {
                                col.push(None);
                            }
                            status.push(e.status());
                        }
                    }
                }
            }
        }
    }
    let names = [
        "velocity_m_per_s",
        "temperature_C",
        "a_m",
        "phi_deg",
        "hardness_Pa",
        "film_thickness_m",
        "mu_wet",
        "mu_upper",
        "mu_lower",
        "melt_fraction",
    ];
    let mut b = TableBuilder::new();
    for (k, name) in names.iter().enumerate() {
        b = b.f64(name, std::mem::take(&mut c[k]));
    }
    b.status(&status).build()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The grid has one row per combination, is schema-valid, reports a
    /// locking slope as a status, and its μ equals the model function.
    #[test]
    fn thin_films_and_large_mu_are_out_of_validity() {
        let ok = validity(1e-7, [0.02, 0.03, 0.01], 1.0);
        assert!(ok.is_ok());
        let thin = validity(1e-13, [0.02, 0.03, 0.01], 1.0);
        assert!(thin.has(Code::BeyondValidity), "{thin}");
        assert!(thin.to_string().contains("thinner than a water molecule"));
        let big = validity(1e-7, [4.1, 0.03, 0.01], 1.0);
        assert!(big.to_string().contains("μ = 4.100 above"), "{big}");
    }

    /// Hardness is Table 3.2's C1 T + C2 (−5.08 MPa/K, 15.19 MPa); the melt
    /// fraction is the melting share of the heat balance η v²/h =
    /// γ √(v/2a) + ρ_w L h v/a (MODELS.md §6): 1 with no ΔT (γ = 0), and
    /// with the conduction share, γ from Table 3.2's ice and steel by
    /// hand, it sums to 1.
    #[test]
    fn hardness_and_heat_shares_follow_table_3_2() {
        let g = IceGrid {
            velocities_m_per_s: vec![0.05, 2.0],
            temperatures_c: vec![-10.0, 0.0],
            a_m: vec![1e-4],
            phi_deg: vec![7.3],
            model: MakkonenParams::default(),
            thermal: Thermal::Bulk,
            mu_max: 1.0,
        };
        let t = simulate_ice(&g).unwrap();
        let col = |c: &str| t.f64(c).unwrap();
        let (hard, h, melt) = (
            col("hardness_Pa"),
            col("film_thickness_m"),
            col("melt_fraction"),
        );
        let effusivity = |c: f64, k: f64, rho: f64| (c * k * rho).sqrt();
        let gamma = 10.0 * (effusivity(2090.0, 2.2, 916.0) + effusivity(460.0, 20.0, 7750.0));
        // rows: (v 0.05, −10 °C), (0.05, 0 °C), (2, −10 °C), (2, 0 °C)
        let rows: [(usize, f64, f64); 4] = [
            (0, 0.05, -10.0),
            (1, 0.05, 0.0),
            (2, 2.0, -10.0),
            (3, 2.0, 0.0),
        ];
        for (row, v, t_c) in rows {
            let want = -5.08e6 * t_c + 15.19e6;
            assert!((hard[row].unwrap() - want).abs() < 1e-9 * want, "row {row}");
            let (h, melt) = (h[row].unwrap(), melt[row].unwrap());
            let conduction = match t_c == 0.0 {
                true => 0.0,
                false => gamma * (v / 2e-4).sqrt() * h / (1.76e-3 * v * v),
            };
            assert!(
                (melt + conduction - 1.0).abs() < 1e-12,
                "row {row}: {melt} + {conduction}"
            );
            assert!(melt > 0.0 && melt <= 1.0 + 1e-12, "row {row}: {melt}");
        }
        // slow and cold is conduction-dominated, fast and cold mostly melting
        assert!(melt[0].unwrap() < 0.5 && melt[2].unwrap() > melt[0].unwrap());
    }

    #[test]
    fn grid_rows_status_and_values() {
        let g = IceGrid {
            velocities_m_per_s: logspace(0.025, 1.0, 3).unwrap(),
            temperatures_c: vec![-17.0, -2.0],
            a_m: vec![1e-5, 1e-4],
            phi_deg: vec![7.3, 89.9],
            model: MakkonenParams::default(),
            thermal: Thermal::Bulk,
            mu_max: 1.0,
        };
        let t = simulate_ice(&g).unwrap();
        let schema = include_str!("../../schemas/ice_grid.toml");
        crate::schema::Schema::parse("ice_grid", schema)
            .unwrap()
            .check(&t)
            .unwrap();
        assert_eq!(t.height(), 3 * 2 * 2 * 2);
        let st = t.str("status").unwrap();
        let detail = t.str("status_detail").unwrap();
        let mu = t.f64("mu_wet").unwrap();
        // Row 0: v 0.025, T −17, a 1e-5, φ 7.3: the value is mu_wet's, but
        // its film (1.7e-13 m) is no film and μ = 2.5: beyond validity.
        assert_eq!(st[0].as_deref(), Some("beyond_validity"));
        let s0 = detail[0].as_deref().unwrap();
        assert!(s0.starts_with("beyond_validity: film 1.744e-13 m"), "{s0}");
        assert!(s0.contains("μ = 2.485 above"), "{s0}");
        let m = mu_wet(&g.model, 0.025, 1e-5, -17.0, Thermal::Bulk).unwrap();
        assert!((mu[0].unwrap() - m).abs() <= 1e-15 * m);
        // Row 1: φ = 89.9° locks when μ_wet > cot 89.9° = 1.7e-3 (it is).
        assert!(
            m * 89.9_f64.to_radians().tan() > 1.0,
            "precondition: mu_wet {m}"
        );
        assert_eq!(st[1].as_deref(), Some("locked"), "{:?}", detail[1]);
        assert!(t.f64("mu_upper").unwrap()[1].is_none());
    }
}
