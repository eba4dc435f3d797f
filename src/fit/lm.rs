//! Levenberg–Marquardt as an argmin [`Solver`]: Moré's scaled trust-region
//! variant (Moré 1978, *The Levenberg–Marquardt algorithm: implementation
//! and theory*; MINPACK `lmder`), with the step computed from a singular
//! value decomposition of the scaled Jacobian instead of the normal
//! equations, so that ill-conditioned problems keep their digits.
//!
//! Each outer iteration evaluates the Jacobian J once, rescales it to
//! Ĵ = J D⁻¹ with D = diag(maxₖ ‖J₍ₖ₎ column‖) and factors Ĵ = U S Vᵀ. The
//! trial step solves min ‖r + Ĵ p̂‖ subject to ‖p̂‖ ≤ Δ: the Gauss–Newton
//! step when it fits inside the trust region, else the Levenberg–Marquardt
//! step p̂(λ) = −Σ sᵢ cᵢ/(sᵢ² + λ) vᵢ (c = Uᵀ r) whose length is within 10 %
//! of Δ (λ from the secular equation, safeguarded Newton on 1/‖p̂‖). The
//! ratio of actual to predicted reduction updates Δ exactly as MINPACK does.
//!
//! Stopping (never calls a failure converged):
//! - relative reduction: actual and predicted relative reductions of the
//!   sum of squares both ≤ `ftol`;
//! - step: Δ ≤ `xtol` ‖D x‖;
//! - gradient: the cosine between r and every column of J ≤ `gtol`;
//! - exact fit: r = 0;
//! - otherwise the iteration or evaluation budget, a collapsed trust region
//!   (no step reduces S: stalled) or a non-finite Jacobian end the run with
//!   a failure status.

use argmin::core::{
    CostFunction, Error as ArgminError, IterState, Jacobian, Operator, Problem, Solver, State,
    TerminationReason, TerminationStatus, KV,
};
use nalgebra::{DMatrix, DVector, SVD};

use super::problem::{jacobian_at, LeastSquaresProblem};
use super::report::{ConvergedBy, FitStatus};

/// Settings of [`crate::fit::least_squares`]. Defaults are tight enough for
/// 7+ correct digits on the NIST StRD problems (docs/fitting.md).
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct LmParams {
    /// Relative-reduction tolerance on the sum of squares. Default 1e-15,
    /// range [ε, 1).
    pub ftol: f64,
    /// Relative step tolerance on the scaled parameters. Default 1e-12,
    /// range [ε, 1).
    pub xtol: f64,
    /// Gradient (orthogonality) tolerance. Default 1e-12, range [0, 1).
    pub gtol: f64,
    /// Maximum outer iterations (Jacobian evaluations). Default 1000.
    pub max_iterations: u64,
    /// Maximum residual evaluations in total. Default 20 000.
    pub max_evaluations: u64,
    /// Initial trust radius as a multiple of ‖D x₀‖ (MINPACK `factor`).
    /// Default 100, range (0, ∞).
    pub initial_step_factor: f64,
    /// Largest gradient cosine accepted at convergence (before allowing for
    /// rounding in the residuals, see
    /// [`crate::fit::LeastSquaresProblem::response_scale`]). At the NIST
    /// minima it is ≤ 6e-8; on a plateau it is O(1). Default 1e-5, range
    /// (0, 1).
    pub stationarity_tol: f64,
    /// Restarts from x₀ with a 100 times smaller initial trust region when a
    /// tolerance was met but the gradient cosine is too large. Default 2.
    pub restarts: u32,
}

impl Default for LmParams {
    fn default() -> Self {
        LmParams {
            ftol: 1e-15,
            xtol: 1e-12,
            gtol: 1e-12,
            max_iterations: 1000,
            max_evaluations: 20_000,
            initial_step_factor: 100.0,
            stationarity_tol: 1e-5,
            restarts: 2,
        }
    }
}

impl LmParams {
    /// Checks the ranges documented on each field.
    pub fn validate(&self) -> crate::Result<()> {
        let eps = f64::EPSILON;
        let ok = (eps..1.0).contains(&self.ftol)
            && (eps..1.0).contains(&self.xtol)
            && (0.0..1.0).contains(&self.gtol)
            && self.max_iterations > 0
            && self.max_evaluations > 0
            && self.initial_step_factor.is_finite()
            && self.initial_step_factor > 0.0
            && self.stationarity_tol > 0.0
            && self.stationarity_tol < 1.0;
        if ok {
            Ok(())
        } else {
            Err(crate::Error::Config(format!(
                "invalid LmParams {self:?}: expected ftol, xtol in [eps, 1), gtol in [0, 1), positive budgets and step factor"
            )))
        }
    }
}

/// A [`LeastSquaresProblem`] seen through argmin's traits: `apply` gives the
/// residual vector, `jacobian` the (analytic or finite-difference) Jacobian,
/// `cost` the sum of squares.
pub struct ArgminLeastSquares<'a, P: ?Sized> {
    /// The wrapped problem.
    pub inner: &'a P,
}

impl<P: LeastSquaresProblem + ?Sized> Operator for ArgminLeastSquares<'_, P> {
    type Param = Vec<f64>;
    type Output = Vec<f64>;
    fn apply(&self, x: &Vec<f64>) -> Result<Vec<f64>, ArgminError> {
        Ok(super::problem::residual_vec(self.inner, x))
    }
}

impl<P: LeastSquaresProblem + ?Sized> Jacobian for ArgminLeastSquares<'_, P> {
    type Param = Vec<f64>;
    type Jacobian = DMatrix<f64>;
    fn jacobian(&self, x: &Vec<f64>) -> Result<DMatrix<f64>, ArgminError> {
        Ok(jacobian_at(self.inner, x))
    }
}

impl<P: LeastSquaresProblem + ?Sized> CostFunction for ArgminLeastSquares<'_, P> {
    type Param = Vec<f64>;
    type Output = f64;
    fn cost(&self, x: &Vec<f64>) -> Result<f64, ArgminError> {
        Ok(sum_sq(&super::problem::residual_vec(self.inner, x)))
    }
}

/// The argmin state used by [`LevenbergMarquardt`]: parameters, residuals,
/// Jacobian; cost = sum of squared residuals.
pub type LmState = IterState<Vec<f64>, (), DMatrix<f64>, (), Vec<f64>, f64>;

/// Moré's scaled Levenberg–Marquardt (see the module documentation).
#[derive(Debug, Clone)]
pub struct LevenbergMarquardt {
    params: LmParams,
    /// Trust radius Δ in scaled parameters.
    delta: f64,
    /// Scale D.
    diag: Vec<f64>,
    /// Last Levenberg parameter λ.
    lambda: f64,
    evaluations: u64,
    status: Option<FitStatus>,
}

impl LevenbergMarquardt {
    /// A solver with the given (validated) settings.
    pub fn new(params: LmParams) -> Self {
        LevenbergMarquardt {
            params,
            delta: 0.0,
            diag: Vec::new(),
            lambda: 0.0,
            evaluations: 0,
            status: None,
        }
    }

    /// Why the solver stopped, if it decided to stop by itself.
    pub fn status(&self) -> Option<&FitStatus> {
        self.status.as_ref()
    }

    /// Residual evaluations used, the initial one included.
    pub fn evaluations(&self) -> u64 {
        self.evaluations
    }
}

fn sum_sq(r: &[f64]) -> f64 {
    // Scaled to avoid overflow for large residuals.
    let scale = r.iter().fold(0.0_f64, |a, v| a.max(v.abs()));
    if scale == 0.0 || !scale.is_finite() {
        return if scale == 0.0 { 0.0 } else { f64::INFINITY };
    }
    let s: f64 = r.iter().map(|v| (v / scale).powi(2)).sum();
    s * scale * scale
}

fn norm(r: &[f64]) -> f64 {
    sum_sq(r).sqrt()
}

fn all_finite(r: &[f64]) -> bool {
    r.iter().all(|v| v.is_finite())
}

/// The scaled step p̂ of length ≈ Δ, and λ. `s`, `c` are the singular values
/// of Ĵ and Uᵀ r; `vt` is Vᵀ.
fn trust_step(
    s: &[f64],
    c: &[f64],
    vt: &DMatrix<f64>,
    delta: f64,
    rank_tol: f64,
) -> (DVector<f64>, f64) {
    let n = vt.ncols();
    let combine = |w: &dyn Fn(usize) -> f64| {
        let mut p = DVector::zeros(n);
        for (i, _) in s.iter().enumerate() {
            let wi = w(i);
            if wi != 0.0 {
                p.axpy(-wi, &vt.row(i).transpose(), 1.0);
            }
        }
        p
    };
    // Gauss–Newton (minimum-norm pseudo-inverse) step.
    let gn = |i: usize| if s[i] > rank_tol { c[i] / s[i] } else { 0.0 };
    let gn_norm = (0..s.len()).map(|i| gn(i).powi(2)).sum::<f64>().sqrt();
    if gn_norm <= 1.1 * delta {
        return (combine(&gn), 0.0);
    }
    let q = |lam: f64| -> (f64, f64) {
        let mut q2 = 0.0;
        let mut d = 0.0;
        for i in 0..s.len() {
            let den = s[i] * s[i] + lam;
            if den > 0.0 {
                q2 += (s[i] * c[i] / den).powi(2);
                d += (s[i] * c[i]).powi(2) / den.powi(3);
            }
        }
        (q2.sqrt(), d)
    };
    let g_norm = (0..s.len())
        .map(|i| (s[i] * c[i]).powi(2))
        .sum::<f64>()
        .sqrt();
    let (mut lo, mut hi) = (0.0_f64, g_norm / delta);
    let mut lam = hi * 1e-3;
    for _ in 0..100 {
        let (qn, d) = q(lam);
        if (qn - delta).abs() <= 0.1 * delta || hi - lo <= f64::EPSILON * hi {
            break;
        }
        if qn > delta {
            lo = lam;
        } else {
            hi = lam;
        }
        // Newton on ψ(λ) = 1/q − 1/Δ, ψ' = d / q³.
        let psi = 1.0 / qn - 1.0 / delta;
        let next = lam - psi * qn.powi(3) / d;
        lam = if next > lo && next < hi && next.is_finite() {
            next
        } else if lo > 0.0 {
            (lo * hi).sqrt()
        } else {
            hi * 1e-3
        };
    }
    let p = combine(&|i: usize| s[i] * c[i] / (s[i] * s[i] + lam));
    (p, lam)
}

/// ‖D x‖, the norm of the scaled parameters.
fn scaled_norm(x: &[f64], d: &[f64]) -> f64 {
    norm(&x.iter().zip(d).map(|(a, b)| a * b).collect::<Vec<_>>())
}

/// The largest cosine between r and a nonzero column of J (MINPACK's
/// gradient test).
fn gradient_cosine(jac: &DMatrix<f64>, r: &[f64], col_norms: &[f64], fnorm: f64) -> f64 {
    let jtr = jac.transpose() * DVector::from_column_slice(r);
    (0..col_norms.len())
        .filter(|&j| col_norms[j] != 0.0)
        .map(|j| (jtr[j] / (col_norms[j] * fnorm)).abs())
        .fold(0.0_f64, f64::max)
}

/// The SVD of the scaled Jacobian Ĵ = J D⁻¹ as the trust step needs it:
/// singular values s, c = Uᵀ r, Vᵀ and the rank tolerance.
struct ScaledSvd {
    s: Vec<f64>,
    c: Vec<f64>,
    vt: DMatrix<f64>,
    rank_tol: f64,
}

impl ScaledSvd {
    /// `None` when the SVD does not converge.
    fn new(jac: &DMatrix<f64>, diag: &[f64], r: &[f64]) -> Option<Self> {
        let (m, n) = (jac.nrows(), jac.ncols());
        let mut jhat = jac.clone();
        for (j, d) in diag.iter().enumerate() {
            jhat.column_mut(j).scale_mut(1.0 / d);
        }
        let svd = SVD::try_new(jhat, true, true, f64::EPSILON, 0)?;
        let (u, vt) = (svd.u?, svd.v_t?);
        let s: Vec<f64> = svd.singular_values.iter().copied().collect();
        let c: Vec<f64> = (u.transpose() * DVector::from_column_slice(r))
            .iter()
            .copied()
            .collect();
        let smax = s.iter().fold(0.0_f64, |a, &v| a.max(v));
        let rank_tol = smax * (m.max(n) as f64) * f64::EPSILON;
        Some(ScaledSvd { s, c, vt, rank_tol })
    }
}

/// One trial step: the new point, its residual norm and the reductions
/// that decide whether it is taken and how the trust radius changes.
struct Trial {
    x: Vec<f64>,
    r: Vec<f64>,
    fnorm: f64,
    actred: f64,
    prered: f64,
    dirder: f64,
    ratio: f64,
    pnorm: f64,
    lam: f64,
}

impl LevenbergMarquardt {
    /// D = max over iterations of the Jacobian's column norms (zero columns
    /// scaled by 1 at the start).
    fn update_scale(&mut self, col_norms: &[f64], first: bool) {
        if first {
            self.diag = col_norms
                .iter()
                .map(|&v| if v == 0.0 { 1.0 } else { v })
                .collect();
        } else {
            for (d, &v) in self.diag.iter_mut().zip(col_norms) {
                *d = d.max(v);
            }
        }
    }

    /// Takes the trust step from x and evaluates it (one residual
    /// evaluation). The first trial of the run shrinks Δ to the step.
    fn trial<P: LeastSquaresProblem + ?Sized>(
        &mut self,
        problem: &mut Problem<ArgminLeastSquares<'_, P>>,
        jac: &DMatrix<f64>,
        svd: &ScaledSvd,
        x: &[f64],
        fnorm: f64,
        first_trial: bool,
    ) -> Result<Trial, ArgminError> {
        let (phat, lam) = trust_step(&svd.s, &svd.c, &svd.vt, self.delta, svd.rank_tol);
        self.lambda = lam;
        let pnorm = phat.norm();
        if first_trial {
            self.delta = self.delta.min(pnorm);
        }
        let p: Vec<f64> = (0..x.len()).map(|j| phat[j] / self.diag[j]).collect();
        let xnew: Vec<f64> = x.iter().zip(&p).map(|(a, b)| a + b).collect();
        let rnew = problem.apply(&xnew)?;
        self.evaluations += 1;
        let fnorm1 = if all_finite(&rnew) {
            norm(&rnew)
        } else {
            f64::INFINITY
        };
        let actred = if 0.1 * fnorm1 < fnorm {
            1.0 - (fnorm1 / fnorm).powi(2)
        } else {
            -1.0
        };
        let jp = jac * DVector::from_column_slice(&p);
        let temp1 = jp.norm() / fnorm;
        let temp2 = lam.sqrt() * pnorm / fnorm;
        let prered = temp1 * temp1 + 2.0 * temp2 * temp2;
        let dirder = -(temp1 * temp1 + temp2 * temp2);
        let ratio = if prered != 0.0 { actred / prered } else { 0.0 };
        Ok(Trial {
            x: xnew,
            r: rnew,
            fnorm: fnorm1,
            actred,
            prered,
            dirder,
            ratio,
            pnorm,
            lam,
        })
    }

    /// MINPACK's trust-radius update from the trial's reduction ratio;
    /// `fnorm` is the residual norm before the trial.
    fn update_radius(&mut self, t: &Trial, fnorm: f64) {
        if t.ratio <= 0.25 {
            let mut temp = if t.actred >= 0.0 {
                0.5
            } else {
                0.5 * t.dirder / (t.dirder + 0.5 * t.actred)
            };
            if 0.1 * t.fnorm >= fnorm || temp.is_nan() || temp < 0.1 {
                temp = 0.1;
            }
            self.delta = temp * self.delta.min(t.pnorm / 0.1);
        } else if t.lam == 0.0 || t.ratio >= 0.75 {
            self.delta = t.pnorm / 0.5;
        }
    }

    /// Why to stop after a trial, if at all (see the module documentation).
    fn stop_reason(
        &self,
        fnorm: f64,
        actred: f64,
        prered: f64,
        ratio: f64,
        xnorm: f64,
    ) -> Option<FitStatus> {
        let p = &self.params;
        if fnorm == 0.0 {
            Some(FitStatus::Converged(ConvergedBy::ExactFit))
        } else if actred.abs() <= p.ftol && prered <= p.ftol && 0.5 * ratio <= 1.0 {
            Some(FitStatus::Converged(ConvergedBy::RelativeReduction))
        } else if self.delta <= p.xtol * xnorm {
            Some(FitStatus::Converged(ConvergedBy::StepSize))
        } else if self.evaluations >= p.max_evaluations {
            Some(FitStatus::MaxEvaluations)
        } else if self.delta <= f64::EPSILON * xnorm || self.delta == 0.0 {
            Some(FitStatus::Stalled)
        } else {
            None
        }
    }
}

impl<'a, P: LeastSquaresProblem + ?Sized> Solver<ArgminLeastSquares<'a, P>, LmState>
    for LevenbergMarquardt
{
    fn name(&self) -> &str {
        "Levenberg-Marquardt (More, SVD step)"
    }

    fn init(
        &mut self,
        problem: &mut Problem<ArgminLeastSquares<'a, P>>,
        mut state: LmState,
    ) -> Result<(LmState, Option<KV>), ArgminError> {
        let x = state.take_param().ok_or_else(|| {
            ArgminError::msg("Levenberg-Marquardt needs an initial parameter vector")
        })?;
        let r = problem.apply(&x)?;
        self.evaluations = 1;
        let cost = sum_sq(&r);
        if !all_finite(&r) || !all_finite(&x) {
            self.status = Some(FitStatus::NonFinite(
                "residuals at the starting point".into(),
            ));
        } else if cost == 0.0 {
            self.status = Some(FitStatus::Converged(ConvergedBy::ExactFit));
        }
        Ok((state.param(x).residuals(r).cost(cost), None))
    }

    fn next_iter(
        &mut self,
        problem: &mut Problem<ArgminLeastSquares<'a, P>>,
        mut state: LmState,
    ) -> Result<(LmState, Option<KV>), ArgminError> {
        let mut x = state
            .take_param()
            .ok_or_else(|| ArgminError::msg("no parameters"))?;
        let mut r = state
            .take_residuals()
            .ok_or_else(|| ArgminError::msg("no residuals"))?;
        let first = self.diag.is_empty();
        let jac = problem.jacobian(&x)?;
        if jac.iter().any(|v| !v.is_finite()) {
            self.status = Some(FitStatus::NonFinite(format!(
                "Jacobian at iteration {}",
                state.get_iter() + 1
            )));
            return Ok((state.param(x).residuals(r), None));
        }
        let col_norms: Vec<f64> = (0..jac.ncols()).map(|j| jac.column(j).norm()).collect();
        self.update_scale(&col_norms, first);
        let mut xnorm = scaled_norm(&x, &self.diag);
        if first {
            self.delta = self.params.initial_step_factor * xnorm;
            if self.delta == 0.0 {
                self.delta = self.params.initial_step_factor;
            }
        }
        let mut fnorm = norm(&r);
        if gradient_cosine(&jac, &r, &col_norms, fnorm) <= self.params.gtol {
            self.status = Some(FitStatus::Converged(ConvergedBy::Gradient));
            return Ok((state.param(x).residuals(r), None));
        }
        let Some(svd) = ScaledSvd::new(&jac, &self.diag, &r) else {
            self.status = Some(FitStatus::Numerical(
                "SVD of the Jacobian did not converge".into(),
            ));
            return Ok((state.param(x).residuals(r), None));
        };
        let mut first_trial = first;
        loop {
            let trial = self.trial(problem, &jac, &svd, &x, fnorm, first_trial)?;
            first_trial = false;
            self.update_radius(&trial, fnorm);
            let accepted = trial.ratio >= 1e-4;
            if accepted {
                fnorm = trial.fnorm;
                x = trial.x;
                r = trial.r;
                xnorm = scaled_norm(&x, &self.diag);
            }
            if let Some(status) =
                self.stop_reason(fnorm, trial.actred, trial.prered, trial.ratio, xnorm)
            {
                self.status = Some(status);
            }
            if accepted || self.status.is_some() {
                break;
            }
        }
        let cost = fnorm * fnorm;
        Ok((state.param(x).residuals(r).jacobian(jac).cost(cost), None))
    }

    fn terminate(&mut self, _state: &LmState) -> TerminationStatus {
        match &self.status {
            None => TerminationStatus::NotTerminated,
            Some(s) if s.is_converged() => {
                TerminationStatus::Terminated(TerminationReason::SolverConverged)
            }
            Some(s) => TerminationStatus::Terminated(TerminationReason::SolverExit(s.to_string())),
        }
    }
}
