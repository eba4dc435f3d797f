//! Model fitting: a robust least-squares solver inside argmin, fit reports
//! with honest uncertainties, and the Coulomb and ice-friction fits.
//!
//! ```
//! use tribo::fit::{least_squares, LeastSquaresProblem, LmParams};
//! /// y = b1 (1 − exp(−b2 x)) (NIST Misra1a model).
//! struct Exp { x: Vec<f64>, y: Vec<f64> }
//! impl LeastSquaresProblem for Exp {
//!     fn n_params(&self) -> usize { 2 }
//!     fn n_residuals(&self) -> usize { self.x.len() }
//!     fn residuals(&self, b: &[f64], out: &mut [f64]) {
//!         for i in 0..self.x.len() {
//!             out[i] = b[0] * (1.0 - (-b[1] * self.x[i]).exp()) - self.y[i];
//!         }
//!     }
//! }
//! let x: Vec<f64> = (1..=10).map(f64::from).collect();
//! // Data with a small deterministic "noise" of ±0.005.
//! let y = x.iter().map(|x| 2.0 * (1.0 - (-0.3 * x).exp()) + 0.005 * (7.0 * x).sin()).collect();
//! let fit = least_squares(&Exp { x, y }, &[1.0, 1.0], &LmParams::default()).unwrap();
//! assert!(fit.status.is_converged(), "{:?}", fit.status);
//! assert!((fit.params[0] - 2.0).abs() < 0.02 && (fit.params[1] - 0.3).abs() < 0.01);
//! assert!(fit.std_errors.unwrap().iter().all(|&s| s > 0.0));
//! ```

pub mod coulomb;
pub mod ice;
pub mod lm;
pub mod nist;
pub mod problem;
pub mod report;

pub use lm::{LevenbergMarquardt, LmParams};
pub use problem::LeastSquaresProblem;
pub use report::{ConvergedBy, FitReport, FitStatus};

use argmin::core::{Executor, State, TerminationReason};

use crate::error::{Error, Result};

/// Minimises Σ rᵢ(x)² from `x0` with [`LevenbergMarquardt`] run by argmin's
/// `Executor` (no Ctrl-C handler, no timer). `Err` only for bad
/// configuration (dimension mismatch, fewer residuals than parameters,
/// invalid settings); every numerical outcome is a [`FitReport`] whose
/// [`FitStatus`] says whether it converged.
pub fn least_squares<P: LeastSquaresProblem + ?Sized>(
    problem: &P,
    x0: &[f64],
    params: &LmParams,
) -> Result<FitReport> {
    params.validate()?;
    let (m, n) = (problem.n_residuals(), problem.n_params());
    if x0.len() != n || n == 0 {
        return Err(Error::Config(format!(
            "starting point has {} values, the problem has {n} parameters (need at least 1)",
            x0.len()
        )));
    }
    if m < n {
        return Err(Error::Config(format!(
            "{m} residuals for {n} parameters: at least as many data points as parameters are needed"
        )));
    }
    let (mut iterations, mut evaluations) = (0, 0);
    let mut attempt = 0;
    let mut run_params = *params;
    loop {
        let (xe, r, status, it, ev) = run_lm(problem, x0, &run_params)?;
        iterations += it;
        evaluations += ev;
        let jac = problem::jacobian_at(problem, &xe);
        let mut report = FitReport::at_solution(xe, r, &jac, status, iterations, evaluations);
        // Rounding floor of the residuals: ε · scale per residual.
        let fnorm = report.rss.sqrt();
        let m_sqrt = (m as f64).sqrt();
        let floor = problem
            .response_scale()
            .map_or(0.0, |s| f64::EPSILON * s.abs() * m_sqrt);
        if fnorm > 0.0 && floor > 0.0 {
            report.rss_digits = Some(-(4.0 * floor / fnorm).log10());
        }
        let tol = params.stationarity_tol.max(if fnorm > 0.0 {
            10.0 * floor / fnorm
        } else {
            0.0
        });
        if report.status.is_converged() && report.gradient_cosine > tol {
            report.status = FitStatus::NotStationary {
                cosine: report.gradient_cosine,
            };
            if attempt < params.restarts {
                // A plateau is usually reached by a first step that was too
                // long (NIST BoxBOD from start 1 jumps to b2 = 111 where
                // exp(−b2 x) underflows): start again with a trust region
                // 100 times smaller.
                attempt += 1;
                run_params.initial_step_factor *= 0.01;
                continue;
            }
        }
        return Ok(report);
    }
}

type LmRun = (Vec<f64>, Vec<f64>, FitStatus, u64, u64);

/// One run of the argmin executor from `x0`.
fn run_lm<P: LeastSquaresProblem + ?Sized>(
    problem: &P,
    x0: &[f64],
    params: &LmParams,
) -> Result<LmRun> {
    let op = lm::ArgminLeastSquares { inner: problem };
    let solver = LevenbergMarquardt::new(*params);
    let res = Executor::new(op, solver)
        .configure(|s| s.param(x0.to_vec()).max_iters(params.max_iterations))
        .ctrlc(false)
        .timer(false)
        .run()
        .map_err(|e| Error::Numerical(format!("argmin: {e}")))?;
    let mut state = res.state;
    let iterations = state.get_iter();
    let solver = res.solver;
    let status = match (solver.status(), state.get_termination_reason()) {
        (Some(s), _) => s.clone(),
        (None, Some(TerminationReason::MaxItersReached)) => FitStatus::MaxIterations,
        (None, r) => FitStatus::Numerical(format!("solver stopped: {r:?}")),
    };
    let x = state.take_param().unwrap_or_else(|| x0.to_vec());
    let r = state
        .take_residuals()
        .unwrap_or_else(|| problem::residual_vec(problem, &x));
    Ok((x, r, status, iterations, solver.evaluations()))
}
