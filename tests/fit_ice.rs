//! Ice fit (MODELS.md §6): synthetic μ(v) from a known contact length is
//! recovered for each bound; a joint ΔT fit recovers both and reports
//! their correlation; a flat μ(v) (boundary lubrication, like pin #1) is
//! flagged as a misfit; the table carries both bounds per group.

use std::collections::BTreeMap;

use tribo::fit::ice::table::{ice_tables, PinRoughness};
use tribo::fit::ice::{fit_ice, IceFitParams, IceObservation};
use tribo::models::makkonen::{mu_wet, Bound, MakkonenParams, Thermal};
use tribo::table::TableBuilder;

/// The thesis' 8 velocities, 0.025 to 1 m/s.
const V: [f64; 8] = [0.025, 0.05, 0.1, 0.2, 0.35, 0.5, 0.75, 1.0];

fn synth(
    a: f64,
    t_c: f64,
    phi: f64,
    bound: Bound,
    thermal: Thermal,
    noise: &[f64],
) -> Vec<IceObservation> {
    let p = MakkonenParams::default();
    V.iter()
        .enumerate()
        .map(|(i, &v)| {
            let m = bound
                .apply(mu_wet(&p, v, a, t_c, thermal).unwrap(), phi)
                .unwrap();
            IceObservation {
                velocity_m_per_s: v,
                mu: m * (1.0 + noise[i % noise.len()]),
            }
        })
        .collect()
}

/// Noiseless data: a recovered to 1e-8 relative (finite-difference
/// Jacobian of a smooth model; the minimum is an exact fit) for both
/// bounds and the thesis' slopes.
#[test]
fn noiseless_contact_length_is_recovered() {
    for &phi_deg in &[7.3_f64, 27.2, 33.6] {
        for bound in [Bound::Upper, Bound::Lower] {
            let a = 3e-5;
            let obs = synth(a, -10.0, phi_deg.to_radians(), bound, Thermal::Bulk, &[0.0]);
            let f = fit_ice(
                &obs,
                -10.0,
                phi_deg.to_radians(),
                bound,
                &IceFitParams::default(),
            )
            .unwrap();
            assert!(f.status.is_converged(), "{}", f.status);
            assert!(
                ((f.a_m - a) / a).abs() < 1e-8,
                "phi {phi_deg} {bound:?}: {}",
                f.a_m
            );
            assert!(!f.misfit && f.rmse < 1e-10);
        }
    }
}

/// With 2 % multiplicative noise, a is recovered within 3 standard errors
/// and the standard error is a few percent of a.
#[test]
fn noisy_contact_length_within_its_standard_error() {
    let noise = [0.02, -0.015, 0.01, -0.02, 0.005, 0.015, -0.01, 0.0];
    let a = 1e-4;
    let obs = synth(
        a,
        -5.0,
        27.2_f64.to_radians(),
        Bound::Upper,
        Thermal::Bulk,
        &noise,
    );
    let f = fit_ice(
        &obs,
        -5.0,
        27.2_f64.to_radians(),
        Bound::Upper,
        &IceFitParams::default(),
    )
    .unwrap();
    let se = f.a_se_m.unwrap();
    assert!(
        (f.a_m - a).abs() < 3.0 * se && se < 0.1 * a,
        "a {} se {se}",
        f.a_m
    );
}

/// Joint ΔT: data generated with an interface ΔT of 3 K (not the bulk
/// 10 K) spanning both regimes; the joint fit recovers a and ΔT and
/// reports a correlation in (−1, 1).
#[test]
fn joint_delta_t_fit_recovers_both_and_reports_correlation() {
    let (a, dt) = (2e-5, 3.0);
    let obs = synth(
        a,
        -10.0,
        0.2,
        Bound::Lower,
        Thermal::Interface { delta_t: dt },
        &[0.0],
    );
    let p = IceFitParams {
        fit_delta_t: true,
        ..Default::default()
    };
    let f = fit_ice(&obs, -10.0, 0.2, Bound::Lower, &p).unwrap();
    assert!(f.status.is_converged(), "{}", f.status);
    assert!(
        ((f.a_m - a) / a).abs() < 1e-6 && (f.delta_t_k - dt).abs() < 1e-6 * dt,
        "{f:?}"
    );
    // Noiseless: s² = 0 so the covariance is 0·(JᵀJ)⁻¹; correlation needs noise.
    let noisy = synth(
        a,
        -10.0,
        0.2,
        Bound::Lower,
        Thermal::Interface { delta_t: dt },
        &[0.01, -0.01, 0.005],
    );
    let g = fit_ice(&noisy, -10.0, 0.2, Bound::Lower, &p).unwrap();
    let c = g.corr_a_delta_t.unwrap();
    assert!(c.abs() < 1.0 && c.abs() > 0.1, "corr {c}");
}

/// A flat μ(v) = 0.05 (boundary lubrication, pin #1 of the thesis) cannot
/// follow the model's v^±½ shape: flagged as a misfit.
#[test]
fn flat_friction_curve_is_a_misfit() {
    let obs: Vec<IceObservation> = V
        .iter()
        .enumerate()
        .map(|(i, &v)| IceObservation {
            velocity_m_per_s: v,
            mu: 0.05 + 0.01 * (i % 2) as f64,
        })
        .collect();
    let f = fit_ice(
        &obs,
        -10.0,
        7.3_f64.to_radians(),
        Bound::Upper,
        &IceFitParams::default(),
    )
    .unwrap();
    assert!(f.misfit, "rel rmse {}", f.rel_rmse);
}

/// The table: two groups x two bounds, schema-valid, residual rows for
/// every step, Rdq from the roughness map, a NaN step excluded and counted.
#[test]
fn ice_table_from_steps() {
    let (mut v, mut mu, mut t, mut pin) = (vec![], vec![], vec![], vec![]);
    for (p, temp) in [("2", -5.0), ("3", -10.0)] {
        for o in synth(
            5e-5,
            temp,
            27.2_f64.to_radians(),
            Bound::Upper,
            Thermal::Bulk,
            &[0.0],
        ) {
            v.push(o.velocity_m_per_s);
            mu.push(o.mu);
            t.push(temp);
            pin.push(p.to_string());
        }
    }
    mu[3] = f64::NAN;
    let steps = TableBuilder::new()
        .str("pin", pin.iter().map(Some))
        .f64_values("temperature_C", t)
        .f64_values("velocity_m_per_s", v)
        .f64_values("mu_mean", mu)
        .build()
        .unwrap();
    let rough = PinRoughness {
        rdq_deg: [("2".to_string(), 27.2), ("3".to_string(), 27.2)].into(),
        a_bearing_m: BTreeMap::from([("2".to_string(), 4e-5)]),
    };
    let (fit, res) = ice_tables(&steps, &rough, &IceFitParams::default()).unwrap();
    tribo::pipeline::registry::schema("ice_fit")
        .unwrap()
        .check(&fit)
        .unwrap();
    tribo::pipeline::registry::schema("ice_residuals")
        .unwrap()
        .check(&res)
        .unwrap();
    assert_eq!(fit.height(), 4);
    assert_eq!(res.height(), (7 + 8) * 2);
    let a = fit.f64("a_m").unwrap();
    let bound = fit.str("bound").unwrap();
    let excl = fit.i64("n_excluded").unwrap();
    assert_eq!(excl[0], Some(1));
    let bearing = fit.f64("a_bearing_m").unwrap();
    assert_eq!(
        bearing[0].map(|b| (b / 4e-5 - 1.0).abs() < 1e-15),
        Some(true)
    );
    assert!(bearing[2].is_none());
    for i in 0..4 {
        if bound[i].as_deref() == Some("upper") {
            assert!((a[i].unwrap() / 5e-5 - 1.0).abs() < 1e-8, "{:?}", a[i]);
        }
    }
}

/// A step that carries a warning of its own makes every fit over it say so
/// (`doubtful_points`, naming the step); a step with an info code is no
/// doubt, and a step whose μ is missing is no point and is not named.
#[test]
fn fits_over_steps_with_warnings_inherit_them() {
    use tribo::status::{Code, Status};
    let obs = synth(
        5e-5,
        -5.0,
        27.2_f64.to_radians(),
        Bound::Upper,
        Thermal::Bulk,
        &[0.0],
    );
    let n = obs.len();
    let statuses: Vec<Status> = (0..n)
        .map(|k| match k {
            1 => Status::of(Code::UnsteadySpeed, "speed leaves the band"),
            2 => Status::of(Code::LoadRamp, "ramp"),
            3 => Status::of(Code::UnsteadySpeed, "no speed"),
            _ => Status::ok(),
        })
        .collect();
    let steps = TableBuilder::new()
        .str("source", vec![Some("lab/pod_pin2.csv"); n])
        .i64("step", (1..=n as i64).map(Some))
        .str("pin", vec![Some("2"); n])
        .f64_values("temperature_C", vec![-5.0; n])
        .f64_values("velocity_m_per_s", obs.iter().map(|o| o.velocity_m_per_s))
        .f64(
            "mu_mean",
            obs.iter()
                .enumerate()
                .map(|(k, o)| (k != 3).then_some(o.mu)),
        )
        .status(statuses.iter())
        .build()
        .unwrap();
    let rough = PinRoughness {
        rdq_deg: [("2".to_string(), 27.2)].into(),
        a_bearing_m: BTreeMap::new(),
    };
    let (fit, _) = ice_tables(&steps, &rough, &IceFitParams::default()).unwrap();
    let want = format!(
        "doubtful_points: 1 of the {} rows used carry warnings: pod_pin2.csv step 2 (unsteady_speed)",
        n - 1
    );
    assert_eq!(fit.height(), 2);
    for (status, detail) in fit
        .str("status")
        .unwrap()
        .into_iter()
        .zip(fit.str("status_detail").unwrap())
    {
        assert_eq!(status.as_deref(), Some("doubtful_points"));
        assert_eq!(detail.as_deref(), Some(want.as_str()));
    }
}
