//! The Levenberg–Marquardt solver and its report on small problems with
//! known answers: exact recovery, status honesty, covariance definitions.

use nalgebra::DMatrix;
use tribo::fit::nist::{read_nist, NistModel, NistProblem};
use tribo::fit::problem::central_difference;
use tribo::fit::{least_squares, FitStatus, LeastSquaresProblem, LmParams};

/// y = b0 exp(−b1 x) on given data.
struct Decay {
    x: Vec<f64>,
    y: Vec<f64>,
}
impl LeastSquaresProblem for Decay {
    fn n_params(&self) -> usize {
        2
    }
    fn n_residuals(&self) -> usize {
        self.x.len()
    }
    fn residuals(&self, b: &[f64], out: &mut [f64]) {
        for ((o, x), y) in out.iter_mut().zip(&self.x).zip(&self.y) {
            *o = b[0] * (-b[1] * x).exp() - y;
        }
    }
}

fn decay(n: usize, a: f64, k: f64, noise: &[f64]) -> Decay {
    let x: Vec<f64> = (0..n).map(|i| i as f64 * 0.5).collect();
    let y = x
        .iter()
        .enumerate()
        .map(|(i, x)| a * (-k * x).exp() + noise[i % noise.len()])
        .collect();
    Decay { x, y }
}

/// Noiseless data: the fit recovers the parameters to ~1e-12 relative
/// (finite-difference Jacobian, ~10 digits, but the minimum itself is
/// exact: r = 0 there).
#[test]
fn noiseless_exponential_is_recovered() {
    let p = decay(12, 3.0, 0.7, &[0.0]);
    let f = least_squares(&p, &[1.0, 0.1], &LmParams::default()).unwrap();
    assert!(f.status.is_converged(), "{}", f.status);
    assert!(
        (f.params[0] - 3.0).abs() < 1e-10 && (f.params[1] - 0.7).abs() < 1e-10,
        "{:?}",
        f.params
    );
}

/// Scaling the data by 1e3 scales the amplitude by 1e3 and leaves the
/// rate unchanged (to 1e-9 relative: both fits stop at their own
/// tolerances), and the gradient cosine, a unit-free quantity, stays small.
#[test]
fn fit_is_invariant_to_data_scale() {
    let noise = [0.01, -0.02, 0.015, -0.005, 0.0];
    let p1 = decay(15, 3.0, 0.7, &noise);
    let p2 = Decay {
        x: p1.x.clone(),
        y: p1.y.iter().map(|y| y * 1e3).collect(),
    };
    let f1 = least_squares(&p1, &[1.0, 0.1], &LmParams::default()).unwrap();
    let f2 = least_squares(&p2, &[1.0, 0.1], &LmParams::default()).unwrap();
    assert!(f1.status.is_converged() && f2.status.is_converged());
    assert!(((f2.params[0] / 1e3 - f1.params[0]) / f1.params[0]).abs() < 1e-9);
    assert!(((f2.params[1] - f1.params[1]) / f1.params[1]).abs() < 1e-9);
    let (s1, s2) = (f1.std_errors.unwrap(), f2.std_errors.unwrap());
    assert!(((s2[1] - s1[1]) / s1[1]).abs() < 1e-6, "{s1:?} {s2:?}");
}

/// A non-finite residual at the start is reported as such, never as a fit.
#[test]
fn non_finite_start_is_reported() {
    let mut p = decay(5, 1.0, 1.0, &[0.0]);
    p.y[2] = f64::NAN;
    let f = least_squares(&p, &[1.0, 1.0], &LmParams::default()).unwrap();
    assert!(matches!(f.status, FitStatus::NonFinite(_)), "{}", f.status);
}

/// y = (b0 b1) x: only the product is identifiable. The solver reaches a
/// zero residual, but the report says singular, with no covariance.
#[test]
fn unidentifiable_parameters_are_singular() {
    struct Product;
    impl LeastSquaresProblem for Product {
        fn n_params(&self) -> usize {
            2
        }
        fn n_residuals(&self) -> usize {
            4
        }
        fn residuals(&self, b: &[f64], out: &mut [f64]) {
            for (i, o) in out.iter_mut().enumerate() {
                let x = i as f64 + 1.0;
                *o = b[0] * b[1] * x - 2.0 * x + 0.01 * (i % 2) as f64;
            }
        }
        fn jacobian(&self, b: &[f64], jac: &mut DMatrix<f64>) -> bool {
            for i in 0..4 {
                let x = i as f64 + 1.0;
                jac[(i, 0)] = b[1] * x;
                jac[(i, 1)] = b[0] * x;
            }
            true
        }
    }
    let f = least_squares(&Product, &[1.0, 1.0], &LmParams::default()).unwrap();
    assert!(
        matches!(f.status, FitStatus::Singular { rank: 1 }),
        "{}",
        f.status
    );
    assert!(f.covariance.is_none() && f.std_errors.is_none());
}

/// Fewer residuals than parameters is a configuration error; as many gives
/// dof = 0 and no standard errors (s² undefined).
#[test]
fn too_few_points_and_zero_dof() {
    let p = decay(1, 1.0, 1.0, &[0.0]);
    assert!(least_squares(&p, &[1.0, 1.0], &LmParams::default()).is_err());
    let p = decay(2, 2.0, 0.3, &[0.0]);
    let f = least_squares(&p, &[1.0, 1.0], &LmParams::default()).unwrap();
    assert_eq!(f.dof, 0);
    assert!(f.std_errors.is_none() && f.s2.is_none());
}

/// The iteration budget ends the run with MaxIterations, not converged.
#[test]
fn iteration_budget_is_not_convergence() {
    let p = decay(12, 3.0, 0.7, &[0.01, -0.01]);
    let prm = LmParams {
        max_iterations: 1,
        ..LmParams::default()
    };
    let f = least_squares(&p, &[1.0, 5.0], &prm).unwrap();
    assert_eq!(f.status, FitStatus::MaxIterations);
}

/// Covariance and correlation definitions: cov = s² (JᵀJ)⁻¹ computed by
/// normal equations on a well-conditioned problem agrees with the SVD path
/// to 1e-10 relative; the correlation has a unit diagonal.
#[test]
fn covariance_matches_normal_equations_when_well_conditioned() {
    let p = decay(15, 3.0, 0.7, &[0.01, -0.02, 0.015, -0.005, 0.0]);
    let f = least_squares(&p, &[1.0, 0.1], &LmParams::default()).unwrap();
    let j = tribo::fit::problem::jacobian_at(&p, &f.params);
    let cov_ne = (j.transpose() * &j).try_inverse().unwrap() * f.s2.unwrap();
    let cov = f.covariance.unwrap();
    for k in 0..4 {
        assert!(
            ((cov[k] - cov_ne[k]) / cov_ne[k]).abs() < 1e-10,
            "{cov} {cov_ne}"
        );
    }
    let c = f.correlation.unwrap();
    assert!((c[(0, 0)] - 1.0).abs() < 1e-14 && c[(0, 1)].abs() < 1.0);
}

/// Each NIST model's analytic gradient agrees with central differences.
#[test]
fn nist_analytic_gradients_match_finite_differences() {
    use NistModel::*;
    let cases: &[(NistModel, &[f64], &[f64])] = &[
        (Bennett5, &[-2500.0, 46.0, 0.93], &[9.0]),
        (ExpRise, &[210.0, 0.55], &[3.0]),
        (Chwirut, &[0.19, 0.006, 0.01], &[2.0]),
        (DanWood, &[0.77, 3.86], &[1.5]),
        (
            Enso,
            &[10.5, 3.1, 0.53, 44.3, -1.6, 0.53, 26.9, 0.21, 1.5],
            &[7.0],
        ),
        (Eckerle4, &[1.55, 4.09, 451.5], &[449.0]),
        (
            Gauss,
            &[99.0, 0.011, 101.0, 107.0, 23.6, 72.0, 153.0, 19.5],
            &[120.0],
        ),
        (Rational33, &[1.3, 1.5, 0.6, 0.05, 0.97, 0.4, 0.05], &[0.7]),
        (Kirby2, &[1.67, -0.14, 0.0026, -0.0017, 2.2e-5], &[30.0]),
        (Lanczos, &[0.096, 1.0, 0.86, 3.0, 1.55, 5.0], &[0.3]),
        (Mgh09, &[0.19, 0.19, 0.12, 0.14], &[2.0]),
        (Mgh10, &[0.0056, 6181.0, 345.0], &[70.0]),
        (Mgh17, &[0.375, 1.94, -1.46, 0.013, 0.022], &[100.0]),
        (Misra1b, &[338.0, 0.00039], &[300.0]),
        (Misra1c, &[636.0, 0.00021], &[300.0]),
        (Misra1d, &[437.0, 0.0003], &[300.0]),
        (Nelson, &[2.59, 0.0056, 0.077], &[16.0, 225.0]),
        (Rat42, &[72.5, 2.6, 0.067], &[40.0]),
        (Rat43, &[699.0, 5.3, 0.76, 1.28], &[6.0]),
        (Roszman1, &[0.2, -6.2e-6, 1204.0, -181.0], &[-1000.0]),
    ];
    for (model, b, x) in cases {
        struct One<'a>(NistModel, &'a [f64]);
        impl LeastSquaresProblem for One<'_> {
            fn n_params(&self) -> usize {
                match self.0 {
                    NistModel::Enso => 9,
                    NistModel::Gauss => 8,
                    NistModel::Rational33 => 7,
                    NistModel::Lanczos => 6,
                    NistModel::Kirby2 | NistModel::Mgh17 => 5,
                    NistModel::Mgh09 | NistModel::Rat43 | NistModel::Roszman1 => 4,
                    NistModel::ExpRise
                    | NistModel::DanWood
                    | NistModel::Misra1b
                    | NistModel::Misra1c
                    | NistModel::Misra1d => 2,
                    _ => 3,
                }
            }
            fn n_residuals(&self) -> usize {
                1
            }
            fn residuals(&self, b: &[f64], out: &mut [f64]) {
                out[0] = self.0.eval(b, self.1, None);
            }
        }
        let p = One(*model, x);
        assert_eq!(p.n_params(), b.len(), "{model:?}");
        let fd = central_difference(&p, b);
        let mut g = vec![0.0; b.len()];
        model.eval(b, x, Some(&mut g));
        let f = model.eval(b, x, None).abs().max(1.0);
        let cbrt_eps = f64::EPSILON.cbrt();
        for (k, gk) in g.iter().enumerate() {
            // Truncation (relative 1e-6 is generous for h ~ 6e-6 |b|) plus
            // rounding of the difference, ~ε |f| / h.
            let h = cbrt_eps * b[k].abs().max(cbrt_eps);
            let tol = 1e-6 * gk.abs() + 10.0 * f64::EPSILON * f / h;
            assert!(
                (fd[(0, k)] - gk).abs() <= tol,
                "{model:?} b{}: analytic {gk} fd {}",
                k + 1,
                fd[(0, k)]
            );
        }
    }
}

/// Finite-difference Jacobians still give ≥ 6 digits on the embedded
/// Misra1a (analytic: ≥ 10).
#[test]
fn finite_difference_fit_of_misra1a() {
    let path = crate::common::root().join("fixtures/nist/Misra1a.dat");
    let data = read_nist(&path).unwrap();
    for start in [1, 2] {
        let r = tribo::fit::nist::run_problem(&data, start, false, &LmParams::default()).unwrap();
        assert!(
            r.status.is_converged() && r.lre_params >= 6.0 && r.lre_se >= 4.0,
            "{r:?}"
        );
    }
    let _ = NistProblem {
        data: &data,
        model: NistModel::ExpRise,
        analytic: false,
    };
}
