//! Coulomb law with cohesion (MODELS.md §2): exact recovery, invariance,
//! the singular and 2-point cases, NaN exclusion, outliers, robust loss,
//! and the table with its Eq. 4.2 prediction.

use std::collections::BTreeMap;

use tribo::fit::coulomb::linear::Loss;
use tribo::fit::coulomb::table::{coulomb_tables, CoulombTableParams, SampleInfo};
use tribo::fit::coulomb::{fit_coulomb, predict_area_fraction, CoulombParams, FrictionPoint};
use tribo::table::TableBuilder;

const AREA: f64 = 4e-4; // 20 mm x 20 mm sled

fn synth(mu: f64, tau0: f64, loads: &[f64], noise: &[f64]) -> Vec<FrictionPoint> {
    loads
        .iter()
        .enumerate()
        .map(|(i, &n)| FrictionPoint {
            normal_force_n: n,
            tangential_force_n: tau0 * AREA + mu * n + noise[i % noise.len()],
            area_m2: AREA,
        })
        .collect()
}

/// Noiseless T = τ0 A + μ N: μ and τ0 recovered to rounding (1e-12
/// relative; the centred closed form has no iteration error) and R² = 1.
#[test]
fn noiseless_data_recovers_mu_and_tau0() {
    let pts = synth(0.31, 850.0, &[1.0, 2.0, 4.0, 8.0, 16.0], &[0.0]);
    let f = fit_coulomb(&pts, &CoulombParams::default()).unwrap();
    assert!(
        (f.mu - 0.31).abs() < 1e-12 * 0.31 && (f.tau0_pa - 850.0).abs() < 1e-9 * 850.0,
        "{f:?}"
    );
    assert!((f.r2 - 1.0).abs() < 1e-12 && f.status.is_ok() && f.n == 5);
    assert!(f.mu_se.unwrap() < 1e-12);
}

/// Noisy data: μ, τ0, their standard errors and R² equal
/// `scipy.stats.linregress` of τ = T/A on p = N/A (SciPy 1.17.1: slope,
/// intercept, stderr, intercept_stderr, rvalue²) to 1e-9 relative.
#[test]
fn standard_errors_and_r2_match_scipy_linregress() {
    let loads = [1.0, 2.0, 4.0, 8.0, 16.0, 3.0, 6.0];
    let noise = [0.02, -0.03, 0.01, 0.04, -0.02, -0.01, 0.015];
    let f = fit_coulomb(
        &synth(0.31, 850.0, &loads, &noise),
        &CoulombParams::default(),
    )
    .unwrap();
    let close = |a: f64, b: f64| (a - b).abs() <= 1e-9 * b.abs();
    assert!(close(f.mu, 0.30947368421052623), "{f:?}");
    assert!(close(f.tau0_pa, 866.4473684210534), "{f:?}");
    assert!(close(f.mu_se.unwrap(), 0.002136228712262473), "{f:?}");
    assert!(close(f.tau0_se_pa.unwrap(), 39.6581443275179), "{f:?}");
    assert!(close(f.r2, 0.9997618148971954), "{f:?}");
    assert_eq!(f.n, 7);
}

/// Forces × 1e3: μ unchanged (to 1e-12 relative), τ0 × 1e3.
#[test]
fn scaling_forces_leaves_mu_unchanged() {
    let pts = synth(
        0.4,
        300.0,
        &[1.0, 2.0, 3.0, 5.0, 9.0, 12.0],
        &[0.01, -0.02, 0.005, 0.0],
    );
    let big: Vec<FrictionPoint> = pts
        .iter()
        .map(|p| FrictionPoint {
            normal_force_n: p.normal_force_n * 1e3,
            tangential_force_n: p.tangential_force_n * 1e3,
            ..*p
        })
        .collect();
    let (a, b) = (
        fit_coulomb(&pts, &Default::default()).unwrap(),
        fit_coulomb(&big, &Default::default()).unwrap(),
    );
    assert!(((a.mu - b.mu) / a.mu).abs() < 1e-12, "{} {}", a.mu, b.mu);
    assert!(((b.tau0_pa / 1e3 - a.tau0_pa) / a.tau0_pa).abs() < 1e-9);
    assert!(((b.mu_se.unwrap() - a.mu_se.unwrap()) / a.mu_se.unwrap()).abs() < 1e-9);
}

/// Two points: an exact line whose standard errors are undefined.
#[test]
fn two_points_have_undefined_standard_errors() {
    let f = fit_coulomb(&synth(0.3, 100.0, &[1.0, 3.0], &[0.0]), &Default::default()).unwrap();
    assert!(
        f.status.has(tribo::status::Code::SeUndefined),
        "{}",
        f.status
    );
    assert!(f.mu_se.is_none() && f.tau0_se_pa.is_none());
    assert!((f.mu - 0.3).abs() < 1e-12);
}

/// A line through two points falling with pressure (μ = −7.7, as once
/// reported `ok`): no standard errors, too few points to judge, and a sign
/// the physics rules out, all in its status. Five points rising are `ok`.
#[test]
fn doubtful_fits_say_so() {
    use tribo::status::Code;
    let f = fit_coulomb(&synth(-7.7, 5e4, &[1.0, 3.0], &[0.0]), &Default::default()).unwrap();
    for c in [Code::SeUndefined, Code::FewPoints, Code::UnphysicalSign] {
        assert!(f.status.has(c), "{c}: {}", f.status);
    }
    assert!((f.mu + 7.7).abs() < 1e-9);
    let g = fit_coulomb(
        &synth(0.3, 100.0, &[1.0, 2.0, 3.0, 4.0, 5.0], &[0.0]),
        &Default::default(),
    )
    .unwrap();
    assert!(g.status.is_ok(), "{}", g.status);
}

/// One load for every point: a clear error naming the singular design.
#[test]
fn constant_pressure_is_a_clear_error() {
    let e = fit_coulomb(
        &synth(0.3, 100.0, &[2.0; 5], &[0.01, -0.01, 0.0]),
        &Default::default(),
    )
    .unwrap_err();
    let m = e.to_string();
    assert!(
        m.contains("singular design") && m.contains("pressure"),
        "{m}"
    );
}

/// NaN rows are excluded and counted; the rest still recover μ exactly.
#[test]
fn nan_rows_are_excluded_and_counted() {
    let mut pts = synth(0.25, 500.0, &[1.0, 2.0, 3.0, 4.0, 5.0, 6.0], &[0.0]);
    pts[1].tangential_force_n = f64::NAN;
    pts[4].normal_force_n = f64::INFINITY;
    let f = fit_coulomb(&pts, &Default::default()).unwrap();
    assert_eq!((f.n, f.n_excluded), (4, 2));
    assert!((f.mu - 0.25).abs() < 1e-12);
}

/// One gross outlier among small noise is reported, and the Huber loss
/// recovers μ far better than least squares.
#[test]
fn outlier_reported_and_huber_resists_it() {
    let loads: Vec<f64> = (1..=12).map(f64::from).collect();
    let noise = [
        0.003, -0.002, 0.001, -0.004, 0.002, 0.0, -0.001, 0.004, -0.003, 0.001, 0.002, -0.002,
    ];
    let mut pts = synth(0.3, 200.0, &loads, &noise);
    pts[9].tangential_force_n += 0.8;
    let ls = fit_coulomb(&pts, &Default::default()).unwrap();
    assert_eq!(ls.outliers, vec![9], "{ls:?}");
    let hub = fit_coulomb(
        &pts,
        &CoulombParams {
            loss: Loss::Huber { k: 1.345 },
            ..Default::default()
        },
    )
    .unwrap();
    assert!(
        (hub.mu - 0.3).abs() < 0.2 * (ls.mu - 0.3).abs(),
        "huber {} ls {}",
        hub.mu,
        ls.mu
    );
    assert!((hub.mu - 0.3).abs() < 2e-3);
}

/// Eq. 4.2: a pattern that follows T = AF (τ0,F A + μ_F N) exactly has
/// ratio 1 and μ_pred = AF μ_F.
#[test]
fn area_fraction_prediction_of_an_exact_pattern() {
    let flat = fit_coulomb(
        &synth(0.3, 400.0, &[1.0, 2.0, 4.0], &[0.0]),
        &Default::default(),
    )
    .unwrap();
    let pat = synth(0.3 * 0.65, 400.0 * 0.65, &[1.5, 3.0, 5.0], &[0.0]);
    let (mu_p, tau_p, ratio) = predict_area_fraction(&flat, 0.65, &pat).unwrap();
    assert!(
        (mu_p - 0.195).abs() < 1e-12 && (tau_p - 260.0).abs() < 1e-9 && (ratio - 1.0).abs() < 1e-12
    );
}

/// The table: per-sample and per-pattern rows for both regimes, the
/// across-sample summary, and the Eq. 4.2 ratio read from a manifest.
#[test]
fn coulomb_table_groups_and_predicts() {
    let mut sid = vec![];
    let (mut nf, mut ts, mut td) = (vec![], vec![], vec![]);
    for (s, mu, af) in [
        ("F1", 0.30, 1.0),
        ("F2", 0.32, 1.0),
        ("B1", 0.30 * 0.65, 0.65),
        ("B2", 0.31 * 0.65, 0.65),
    ] {
        for (k, n) in [1.0, 2.0, 4.0, 6.0].iter().enumerate() {
            sid.push(s.to_string());
            nf.push(*n);
            ts.push(af * 300.0 * AREA + mu * n + 1e-3 * k as f64);
            td.push(0.8 * (af * 300.0 * AREA + mu * n));
        }
    }
    let t = TableBuilder::new()
        .str("sample_id", sid.iter().map(Some))
        .f64_values("normal_force_N", nf)
        .f64_values("static_force_N", ts)
        .f64_values("dynamic_force_N", td)
        .build()
        .unwrap();
    let mut samples = BTreeMap::new();
    for (s, p, af) in [
        ("F1", "F", 1.0),
        ("F2", "F", 1.0),
        ("B1", "B", 0.65),
        ("B2", "B", 0.65),
    ] {
        samples.insert(
            s.to_string(),
            SampleInfo {
                apparent_area_m2: Some(AREA),
                pattern: Some(p.into()),
                area_fraction: Some(af),
            },
        );
    }
    let tables = coulomb_tables(&t, &samples, &CoulombTableParams::default()).unwrap();
    let (c, s) = (tables.coulomb, tables.summary);
    tribo::pipeline::registry::schema("coulomb")
        .unwrap()
        .check(&c)
        .unwrap();
    tribo::pipeline::registry::schema("coulomb_summary")
        .unwrap()
        .check(&s)
        .unwrap();
    assert_eq!(c.height(), (4 + 2) * 2);
    let groups = c.str("group").unwrap();
    let regimes = c.str("regime").unwrap();
    let ratio = c.f64("ratio_measured_to_predicted").unwrap();
    let i = (0..c.height())
        .find(|&i| {
            groups[i].as_deref() == Some("pattern=B") && regimes[i].as_deref() == Some("dynamic")
        })
        .unwrap();
    // Dynamic: B follows 0.65 × flat mean (μ 0.305 vs flat 0.31 fitted on F1+F2): ratio within 3 %.
    assert!((ratio[i].unwrap() - 1.0).abs() < 0.03, "{:?}", ratio[i]);
    let n_samples = s.i64("n_samples").unwrap();
    assert!(n_samples.iter().all(|n| *n == Some(2)));
    let sd = s.f64("mu_sd").unwrap();
    let pat = s.str("pattern").unwrap();
    let reg = s.str("regime").unwrap();
    let k = (0..s.height())
        .find(|&k| pat[k].as_deref() == Some("F") && reg[k].as_deref() == Some("dynamic"))
        .unwrap();
    // Dynamic μ of F1, F2: 0.24, 0.256 exactly: sd = 0.016/√2.
    assert!(
        (sd[k].unwrap() - 0.016 / 2f64.sqrt()).abs() < 1e-10,
        "{:?}",
        sd[k]
    );
}

/// Rows that carry warnings of their own make the fits over them say so
/// (`doubtful_points`, naming the rows): a static-peak doubt concerns the
/// static fit only, a speed doubt both; a row without a result (its forces
/// null) is no point of either fit and is not named; a row with an info
/// code is no doubt.
#[test]
fn fits_over_rows_with_warnings_inherit_them() {
    use tribo::status::{Code, Status};
    let loads = [1.0, 2.0, 4.0, 6.0, 8.0];
    let statuses = [
        Status::of(Code::StaticBelowDynamic, "μ_s < μ_d"),
        Status::of(Code::UnsteadySpeed, "speed leaves the band"),
        Status::of(Code::NoSlidingPhase, "no plateau"),
        Status::of(Code::LoadRamp, "ramp"),
        Status::ok(),
    ];
    let value = |k: usize, v: f64| (k != 2).then_some(v);
    let t = TableBuilder::new()
        .str("source", (0..5).map(|k| Some(format!("lab/sled_{k}.csv"))))
        .i64("stroke", [Some(1); 5])
        .str("sample_id", [Some("S1"); 5])
        .f64_values("normal_force_N", loads)
        .f64(
            "static_force_N",
            (0..5).map(|k| value(k, 0.4 * loads[k] + 0.1)),
        )
        .f64(
            "dynamic_force_N",
            (0..5).map(|k| value(k, 0.3 * loads[k] + 0.1)),
        )
        .f64_values("apparent_area_m2", [AREA; 5])
        .status(statuses.iter())
        .build()
        .unwrap();
    let params = CoulombTableParams {
        groupings: vec![vec!["sample_id".into()]],
        ..CoulombTableParams::default()
    };
    let tables = coulomb_tables(&t, &BTreeMap::new(), &params).unwrap();
    let detail = |regime: &str| {
        let f = tables.fits.iter().find(|f| f.regime == regime).unwrap();
        let fit = f.fit.as_ref().unwrap();
        assert_eq!((fit.n, fit.n_excluded), (4, 1), "{regime}");
        assert_eq!(fit.status.codes(), [Code::DoubtfulPoints], "{regime}");
        fit.status.to_string()
    };
    assert_eq!(
        detail("static"),
        "doubtful_points: 2 of the 4 rows used carry warnings: \
         sled_0.csv stroke 1 (static_below_dynamic), sled_1.csv stroke 1 (unsteady_speed)"
    );
    assert_eq!(
        detail("dynamic"),
        "doubtful_points: 1 of the 4 rows used carry warnings: sled_1.csv stroke 1 (unsteady_speed)"
    );
    let c = &tables.coulomb;
    assert_eq!(
        c.str("status").unwrap(),
        [
            Some("doubtful_points".to_string()),
            Some("doubtful_points".to_string())
        ]
    );
    // The summary over samples inherits the per-sample fits' doubts.
    let want =
        "doubtful_points: 1 of the 1 rows used carry warnings: sample_id=S1 (doubtful_points)";
    assert_eq!(
        tables.summary.str("status_detail").unwrap(),
        [Some(want.to_string()), Some(want.to_string())]
    );
}

proptest::proptest! {
    /// Invariant: multiplying every force by c (any unit change) leaves μ
    /// unchanged and multiplies τ0 by c. The centred closed form does the
    /// same arithmetic on scaled numbers, so agreement is to rounding
    /// (1e-10 relative leaves room for the cancellation in Sxy).
    #[test]
    fn mu_is_invariant_to_force_units(mu in 0.05f64..1.5, tau0 in 0.0f64..1e4, c in 1e-3f64..1e3) {
        let pts = synth(mu, tau0, &[0.5, 1.0, 2.0, 3.5, 5.0, 8.0], &[0.004, -0.003, 0.001, 0.0, -0.002]);
        let scaled: Vec<FrictionPoint> = pts
            .iter()
            .map(|p| FrictionPoint { normal_force_n: p.normal_force_n * c, tangential_force_n: p.tangential_force_n * c, ..*p })
            .collect();
        let a = fit_coulomb(&pts, &Default::default()).unwrap();
        let b = fit_coulomb(&scaled, &Default::default()).unwrap();
        proptest::prop_assert!(((a.mu - b.mu) / a.mu).abs() < 1e-10);
        proptest::prop_assert!((b.tau0_pa / c - a.tau0_pa).abs() <= 1e-9 * (a.tau0_pa.abs() + a.mu * 8.0 / AREA));
    }
}
