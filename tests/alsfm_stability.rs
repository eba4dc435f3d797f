//! Numerical stability at the extremes named in the issue: φ → 90°,
//! μ0 → cot φ, β exactly 0° and 90°, L → 0 and L < 0, very fine and very
//! coarse lattices, amplitude → 0. Also the 2-D lattice on y-invariant
//! surfaces and adhesion without tension.
#![deny(clippy::float_cmp)]

use tribo::models::alsfm::closed_form::{mu_across, mu_along, WedgeCase};
use tribo::models::alsfm::instant::SpringParams;
use tribo::models::alsfm::numeric_1d::Contact;
use tribo::models::alsfm::solver::{evaluate, Keep, Path, PointResult, Resolution};
use tribo::models::alsfm::surface::Surface;
use tribo::Result;

#[allow(clippy::too_many_arguments)] // a test helper spelling out the scene
fn eval(
    z1: &Surface,
    z2: &Surface,
    mu0: f64,
    beta: f64,
    load: f64,
    k_t: f64,
    res: Resolution,
    force: Option<Path>,
) -> Result<PointResult> {
    let c = Contact {
        z1,
        z2,
        mu0,
        beta_deg: beta,
        springs: SpringParams {
            k_t,
            ..Default::default()
        },
        load,
    };
    evaluate(
        &c,
        &res,
        &Keep {
            series: true,
            force,
            ..Default::default()
        },
    )
}

fn n(nx: usize) -> Resolution {
    Resolution {
        nx: Some(nx),
        ..Default::default()
    }
}

/// φ → 90°: the surfaces lock for any μ0 > cot φ; the error names the slope
/// on every path. Never an infinite or negative μ.
#[test]
fn steep_slopes_lock_with_the_slope_named() {
    let w = Surface::wedges(89.9_f64.to_radians(), 1.0);
    for force in [None, Some(Path::Numeric1d), Some(Path::Numeric2d)] {
        let e = eval(&w, &Surface::Flat, 0.3, 0.0, 0.1, 0.0, n(16), force).unwrap_err();
        assert!(e.to_string().contains("89.9"), "{force:?}: {e}");
        assert!(e.to_string().contains("lock"), "{e}");
    }
}

/// μ0 → cot φ from below: μ grows large but stays finite and positive;
/// at μ0 = cot φ exactly the status is "locked".
#[test]
fn mu0_approaching_cot_phi() {
    let phi = 0.5_f64;
    let w = Surface::wedges(phi, 1.0);
    let cot = 1.0 / phi.tan();
    let mut last = 0.0;
    for eps in [1e-1, 1e-2, 1e-3, 1e-4] {
        let mu0 = cot * (1.0 - eps);
        let r = eval(&w, &w, mu0, 0.0, 1.0, 0.0, n(64), Some(Path::Numeric1d)).unwrap();
        let mu = r.mu.unwrap();
        assert!(mu.is_finite() && mu > last, "{mu}");
        last = mu;
    }
    let e = eval(&w, &w, cot, 0.0, 1.0, 0.0, n(64), Some(Path::Numeric1d)).unwrap_err();
    assert!(
        e.to_string().contains(&format!("{:.6}", phi.to_degrees())),
        "{e}"
    );
    assert!(eval(&w, &w, cot, 0.0, 1.0, 0.0, n(64), None).is_err());
}

/// β exactly 0° and 90° on the numeric path: μ_⊥ vanishes (to rounding:
/// 1e-15) and the closed forms hold; β = 90° needs a single instant.
#[test]
fn beta_exactly_on_the_axes() {
    let phi = 0.3_f64;
    let w = Surface::wedges(phi, 1.0);
    let r0 = eval(&w, &w, 0.3, 0.0, 1.0, 0.0, n(100), Some(Path::Numeric1d)).unwrap();
    let r90 = eval(&w, &w, 0.3, 90.0, 1.0, 0.0, n(100), Some(Path::Numeric1d)).unwrap();
    assert!(r0.mu_perp.unwrap().abs() < 1e-15 && r90.mu_perp.unwrap().abs() < 1e-15);
    let a = mu_across(WedgeCase::BothRough, 0.3, phi).unwrap();
    let b = mu_along(WedgeCase::BothRough, 0.3, phi).unwrap();
    assert!((r0.mu.unwrap() - a).abs() < 1e-12 && (r90.mu.unwrap() - b).abs() < 1e-12);
    assert_eq!(r90.steps, 1);
    // 2-D lattice at the axes agrees as well.
    let r2 = eval(
        &w,
        &w,
        0.3,
        90.0,
        1.0,
        0.0,
        Resolution {
            nx: Some(100),
            ny: Some(2),
            ..Default::default()
        },
        Some(Path::Numeric2d),
    )
    .unwrap();
    assert!((r2.mu.unwrap() - b).abs() < 1e-12);
}

/// L → 0+: finite μ; L = 0 or L < 0 without adhesion: "no contact"; with
/// adhesion: no μ but a finite R_xy.
#[test]
fn vanishing_and_negative_load() {
    let s = Surface::Sinusoid {
        amplitude: 0.05,
        lambda_x: 1.0,
        lambda_y: None,
    };
    for l in [1e-3, 1e-6, 1e-12] {
        let r = eval(&s, &s, 0.3, 0.0, l, 0.0, n(128), None).unwrap();
        let mu = r.mu.unwrap();
        assert!(mu.is_finite() && mu > 0.3 && mu < 3.0, "L = {l}: {mu}");
    }
    for l in [0.0, -0.1] {
        let e = eval(&s, &s, 0.3, 0.0, l, 0.0, n(128), None).unwrap_err();
        assert!(e.to_string().contains("no contact"), "{e}");
        let r = eval(&s, &s, 0.3, 0.0, l, 0.5, n(128), None).unwrap();
        assert!(r.mu.is_none() && r.r_xy.is_finite() && r.r_xy >= 0.0);
    }
}

/// Very coarse (1 and 2 points) and very fine (20000 points) lattices give
/// finite coefficients; the fine one matches the closed form (Case 1, 1e-9).
#[test]
fn coarse_and_fine_lattices() {
    let phi = 0.3_f64;
    let w = Surface::wedges(phi, 1.0);
    for nx in [1, 2, 3] {
        let r = eval(&w, &w, 0.3, 30.0, 0.1, 0.0, n(nx), Some(Path::Numeric1d)).unwrap();
        let mu = r.mu.unwrap();
        assert!(mu.is_finite() && mu > 0.0, "{nx}: {mu}");
    }
    let r = eval(
        &w,
        &Surface::Flat,
        0.3,
        0.0,
        0.01,
        0.0,
        n(20_000),
        Some(Path::Numeric1d),
    )
    .unwrap();
    let a = mu_across(WedgeCase::OneFlat, 0.3, phi).unwrap();
    assert!((r.mu.unwrap() - a).abs() < 1e-9 * a);
}

/// The tolerance knob: the refined μ is within the tolerance of a much
/// finer lattice (the change between refinements bounds the error for this
/// smooth, monotone convergence; checked against 2048 points).
#[test]
fn tolerance_picks_the_resolution() {
    let s = Surface::Sinusoid {
        amplitude: 0.05,
        lambda_x: 1.0,
        lambda_y: None,
    };
    let reference = eval(&s, &s, 0.3, 30.0, 0.02, 0.0, n(2048), None)
        .unwrap()
        .mu
        .unwrap();
    for tol in [1e-3, 1e-5] {
        let r = eval(
            &s,
            &s,
            0.3,
            30.0,
            0.02,
            0.0,
            Resolution {
                tolerance: Some(tol),
                ..Default::default()
            },
            None,
        )
        .unwrap();
        assert_eq!(r.converged, Some(true));
        assert!(
            (r.mu.unwrap() - reference).abs() < 2.0 * tol,
            "tol {tol}: {} vs {reference}",
            r.mu.unwrap()
        );
    }
    let r = eval(
        &s,
        &s,
        0.3,
        30.0,
        0.02,
        0.0,
        Resolution {
            tolerance: Some(1e-14),
            max_points: 64,
            ..Default::default()
        },
        None,
    )
    .unwrap();
    assert_eq!(r.converged, Some(false));
}

/// Amplitude → 0: μ approaches μ0 smoothly (|μ − μ0| ∝ A² for a
/// sinusoid: the slopes enter at second order), and A = 0 gives μ0.
#[test]
fn amplitude_to_zero_gives_mu0_smoothly() {
    let mut prev: Option<f64> = None;
    for k in 1..=6 {
        let a = 0.1 * 10f64.powi(-k);
        let s = Surface::Sinusoid {
            amplitude: a,
            lambda_x: 1.0,
            lambda_y: None,
        };
        let d = eval(&s, &s, 0.3, 0.0, 1.0, 0.0, n(128), None)
            .unwrap()
            .mu
            .unwrap()
            - 0.3;
        assert!(d > 0.0);
        if let Some(p) = prev {
            // Each decade of A divides the excess by ~100 (second order);
            // 50..200 allows for the rounding of tiny excesses.
            let ratio = p / d;
            assert!(
                ratio > 50.0 && ratio < 200.0 || d < 1e-12,
                "A = {a}: ratio {ratio}"
            );
        }
        prev = Some(d);
    }
    let flat = Surface::Sinusoid {
        amplitude: 0.0,
        lambda_x: 1.0,
        lambda_y: None,
    };
    let r = eval(&flat, &flat, 0.3, 20.0, 1.0, 0.0, n(16), None).unwrap();
    assert_eq!(r.path, Path::Flat);
    assert!((r.mu.unwrap() - 0.3).abs() < 1e-15);
}

/// A 2-D surface invariant in y gives the 1-D result (sampled map with
/// identical rows against its profile; sinusoid profile on the 2-D lattice).
/// 1e-12 covers the rotation by α_P ∈ {0, π} and bilinear weights.
#[test]
fn y_invariant_2d_equals_1d() {
    let row: Vec<f64> = (0..32)
        .map(|j| 0.03 * (std::f64::consts::TAU * j as f64 / 32.0).sin() + 0.01 * (j % 5) as f64)
        .collect();
    let p = Surface::Profile {
        dx: 1.0 / 32.0,
        z: row.clone(),
    };
    let m = Surface::Map {
        dx: 1.0 / 32.0,
        dy: 0.25,
        nx: 32,
        z: [row.clone(), row.clone(), row.clone(), row].concat(),
    };
    assert!(m.is_y_invariant());
    for beta in [0.0, 30.0, 90.0] {
        let r1 = eval(
            &p,
            &p,
            0.3,
            beta,
            0.05,
            0.0,
            Resolution {
                nx: Some(64),
                steps: Some(64),
                ..Default::default()
            },
            None,
        )
        .unwrap();
        let r2 = eval(
            &m,
            &m,
            0.3,
            beta,
            0.05,
            0.0,
            Resolution {
                nx: Some(64),
                ny: Some(4),
                steps: Some(64),
                ..Default::default()
            },
            Some(Path::Numeric2d),
        )
        .unwrap();
        assert_eq!(r1.path, Path::Numeric1d);
        let (a, b) = (r1.mu.unwrap(), r2.mu.unwrap());
        assert!((a - b).abs() < 1e-12 * a, "beta {beta}: {a} vs {b}");
        assert!((r1.mu_perp.unwrap() - r2.mu_perp.unwrap()).abs() < 1e-12);
    }
}

/// Adhesion with no spring in tension changes nothing (identical results);
/// the tension fraction is then 0.
#[test]
fn adhesion_without_tension_changes_nothing() {
    let s = Surface::Sinusoid {
        amplitude: 0.05,
        lambda_x: 1.0,
        lambda_y: None,
    };
    for beta in [0.0, 45.0] {
        let a = eval(&s, &s, 0.3, beta, 1.0, 0.0, n(64), None).unwrap();
        let b = eval(&s, &s, 0.3, beta, 1.0, 0.5, n(64), None).unwrap();
        assert!(b.tension_fraction < 1e-300, "no spring in tension");
        assert!((a.mu.unwrap() - b.mu.unwrap()).abs() <= 1e-15 * a.mu.unwrap());
    }
}
