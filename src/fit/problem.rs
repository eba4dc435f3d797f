//! The least-squares problem a fit solves: residuals r(x) ∈ ℝᵐ of parameters
//! x ∈ ℝⁿ, minimise S(x) = Σ rᵢ². The Jacobian Jᵢⱼ = ∂rᵢ/∂xⱼ is analytic
//! when the problem provides it, else central finite differences.

use nalgebra::DMatrix;

/// A nonlinear least-squares problem.
///
/// `residuals` may write non-finite values where the model cannot be
/// evaluated (for example a negative contact length): the solver treats
/// such a trial point as a failed step and shrinks its trust region, and a
/// non-finite start is reported as [`crate::fit::FitStatus::NonFinite`].
pub trait LeastSquaresProblem {
    /// Number of parameters n.
    fn n_params(&self) -> usize;
    /// Number of residuals m.
    fn n_residuals(&self) -> usize;
    /// Writes r(x) into `out` (length m).
    fn residuals(&self, x: &[f64], out: &mut [f64]);
    /// Writes the analytic Jacobian ∂rᵢ/∂xⱼ (m × n) into `jac` and returns
    /// `true`, or returns `false` (the default) to use finite differences.
    fn jacobian(&self, _x: &[f64], _jac: &mut DMatrix<f64>) -> bool {
        false
    }
    /// Typical magnitude of the data the residuals are taken from (for
    /// example max |yᵢ|), if known. It sets the rounding floor of the
    /// residuals, used to judge stationarity and the digits of s² when the
    /// fit is nearly exact. `None` (the default) means "residuals are not
    /// differences of large numbers".
    fn response_scale(&self) -> Option<f64> {
        None
    }
}

/// Residuals as a vector.
pub fn residual_vec<P: LeastSquaresProblem + ?Sized>(p: &P, x: &[f64]) -> Vec<f64> {
    let mut r = vec![0.0; p.n_residuals()];
    p.residuals(x, &mut r);
    r
}

/// The Jacobian at `x`: analytic if provided, else [`central_difference`].
pub fn jacobian_at<P: LeastSquaresProblem + ?Sized>(p: &P, x: &[f64]) -> DMatrix<f64> {
    let mut jac = DMatrix::zeros(p.n_residuals(), p.n_params());
    if !p.jacobian(x, &mut jac) {
        jac = central_difference(p, x);
    }
    jac
}

/// Central finite-difference Jacobian. The step for parameter j is
/// hⱼ = ε^{1/3} · max(|xⱼ|, 1e-8 · ‖x‖∞, ε^{1/3}): the cube root of machine
/// ε balances truncation O(h²) against rounding O(ε/h), giving about 10
/// correct digits, and scaling by |xⱼ| makes the step invariant to the
/// parameter's units. The step is taken as (x + h) − x so that it is exactly
/// representable.
pub fn central_difference<P: LeastSquaresProblem + ?Sized>(p: &P, x: &[f64]) -> DMatrix<f64> {
    let (m, n) = (p.n_residuals(), p.n_params());
    let cbrt_eps = f64::EPSILON.cbrt();
    let xmax = x.iter().fold(0.0_f64, |a, v| a.max(v.abs()));
    let mut jac = DMatrix::zeros(m, n);
    let mut xp = x.to_vec();
    let (mut rp, mut rm) = (vec![0.0; m], vec![0.0; m]);
    for j in 0..n {
        let scale = x[j].abs().max(1e-8 * xmax).max(cbrt_eps);
        let xj = x[j];
        xp[j] = xj + cbrt_eps * scale;
        let hp = xp[j] - xj;
        p.residuals(&xp, &mut rp);
        xp[j] = xj - cbrt_eps * scale;
        let hm = xj - xp[j];
        p.residuals(&xp, &mut rm);
        xp[j] = xj;
        for i in 0..m {
            jac[(i, j)] = (rp[i] - rm[i]) / (hp + hm);
        }
    }
    jac
}
