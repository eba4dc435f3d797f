//! The result of a fit: parameters with covariance s² (JᵀJ)⁻¹, standard
//! errors, correlation, residuals, RSS, degrees of freedom, iterations and a
//! status that never calls a failure converged.

use std::fmt;

use nalgebra::{DMatrix, SVD};

use crate::status::{Code, Status};

/// Which criterion ended a successful fit.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum ConvergedBy {
    /// Actual and predicted relative reductions of the RSS ≤ `ftol`.
    RelativeReduction,
    /// Trust radius ≤ `xtol` ‖D x‖.
    StepSize,
    /// Residuals orthogonal to the Jacobian's columns within `gtol`.
    Gradient,
    /// All residuals are exactly zero.
    ExactFit,
    /// A linear problem solved in closed form (one factorisation).
    Direct,
}

/// Why a fit stopped.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum FitStatus {
    /// A convergence criterion was met and the Jacobian at the solution has
    /// full rank.
    Converged(ConvergedBy),
    /// The iteration budget ran out first.
    MaxIterations,
    /// The residual-evaluation budget ran out first.
    MaxEvaluations,
    /// No step reduces the RSS although no criterion is met (trust region
    /// collapsed to machine precision).
    Stalled,
    /// The Jacobian at the end point is rank-deficient: the parameters are
    /// not identifiable (rank given) and no covariance exists.
    Singular {
        /// Numerical rank of J.
        rank: usize,
    },
    /// A step or reduction tolerance was met, but the residuals are not
    /// orthogonal to the Jacobian (largest cosine given): a plateau, or a
    /// parameter running off to infinity, not a minimum.
    NotStationary {
        /// Largest cosine between r and a column of J.
        cosine: f64,
    },
    /// A non-finite value where a finite one is required (named).
    NonFinite(String),
    /// A numerical routine failed (named).
    Numerical(String),
}

impl FitStatus {
    /// Whether the fit converged (the only status whose parameters can be
    /// trusted as a least-squares solution).
    pub fn is_converged(&self) -> bool {
        matches!(self, FitStatus::Converged(_))
    }
    /// As a row's status: `ok` when converged, else the code of why not
    /// with this status's text as the detail.
    pub fn status(&self) -> Status {
        let code = match self {
            FitStatus::Converged(_) => return Status::ok(),
            FitStatus::MaxIterations
            | FitStatus::MaxEvaluations
            | FitStatus::Stalled
            | FitStatus::NotStationary { .. } => Code::NotConverged,
            FitStatus::Singular { .. } => Code::SingularDesign,
            FitStatus::NonFinite(_) => Code::NonFinite,
            FitStatus::Numerical(_) => Code::NumericalFailure,
        };
        Status::of(code, self.to_string())
    }
    /// A short snake_case label for tables.
    pub fn label(&self) -> &'static str {
        match self {
            FitStatus::Converged(_) => "converged",
            FitStatus::MaxIterations => "max_iterations",
            FitStatus::MaxEvaluations => "max_evaluations",
            FitStatus::Stalled => "stalled",
            FitStatus::Singular { .. } => "singular",
            FitStatus::NotStationary { .. } => "not_stationary",
            FitStatus::NonFinite(_) => "non_finite",
            FitStatus::Numerical(_) => "numerical_failure",
        }
    }
}

impl fmt::Display for FitStatus {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            FitStatus::Converged(by) => write!(f, "converged ({by:?})"),
            FitStatus::MaxIterations => f.write_str("not converged: maximum iterations reached"),
            FitStatus::MaxEvaluations => f.write_str("not converged: maximum evaluations reached"),
            FitStatus::Stalled => {
                f.write_str("not converged: no step reduces the residual sum of squares")
            }
            FitStatus::Singular { rank } => write!(
                f,
                "singular: Jacobian has rank {rank}, parameters not identifiable"
            ),
            FitStatus::NotStationary { cosine } => write!(
                f,
                "not converged: tolerance met on a plateau, gradient cosine {cosine:.2e}"
            ),
            FitStatus::NonFinite(w) => write!(f, "non-finite value: {w}"),
            FitStatus::Numerical(w) => write!(f, "numerical failure: {w}"),
        }
    }
}

/// The outcome of a least-squares fit.
#[derive(Debug, Clone)]
pub struct FitReport {
    /// Best parameters found (the last accepted point when not converged).
    pub params: Vec<f64>,
    /// Covariance s² (JᵀJ)⁻¹ (n × n); `None` when J is rank-deficient or
    /// dof = 0 (s² undefined).
    pub covariance: Option<DMatrix<f64>>,
    /// Standard errors √diag(covariance).
    pub std_errors: Option<Vec<f64>>,
    /// Correlation matrix cov_ij / (se_i se_j).
    pub correlation: Option<DMatrix<f64>>,
    /// Residuals r(x) at `params` (model − data or data − model, as the
    /// problem defines them).
    pub residuals: Vec<f64>,
    /// Residual sum of squares.
    pub rss: f64,
    /// Degrees of freedom m − n.
    pub dof: usize,
    /// Residual variance s² = RSS / dof (`None` when dof = 0).
    pub s2: Option<f64>,
    /// Numerical rank of the Jacobian at `params`.
    pub rank: usize,
    /// Condition number s_max / s_min of the Jacobian at `params`.
    pub condition: f64,
    /// Largest cosine between the residual vector and a column of J at
    /// `params` (0 at an exact stationary point; invariant to the units of
    /// the parameters and the data).
    pub gradient_cosine: f64,
    /// Estimated correct digits of the RSS given rounding in the residuals:
    /// −log₁₀(4 ε S √m / ‖r‖) with S the data scale
    /// ([`crate::fit::LeastSquaresProblem::response_scale`]), a bound on
    /// 2 Σ|rᵢ| ε (|yᵢ| + |fᵢ|) / RSS by Cauchy–Schwarz. When the residuals
    /// sit within a few hundred ulps of the data, s² and hence the standard
    /// errors carry no more digits than this (NIST Lanczos1: ≈ 1.5).
    /// `None` without a data scale.
    pub rss_digits: Option<f64>,
    /// Outer iterations (Jacobian evaluations).
    pub iterations: u64,
    /// Residual evaluations.
    pub evaluations: u64,
    /// Why the fit stopped.
    pub status: FitStatus,
}

impl FitReport {
    /// Assembles the report at `params` from the Jacobian there. A converged
    /// status becomes [`FitStatus::Singular`] when J is rank-deficient.
    pub fn at_solution(
        params: Vec<f64>,
        residuals: Vec<f64>,
        jac: &DMatrix<f64>,
        mut status: FitStatus,
        iterations: u64,
        evaluations: u64,
    ) -> FitReport {
        let (m, n) = jac.shape();
        let rss: f64 = residuals.iter().map(|r| r * r).sum();
        let dof = m.saturating_sub(n);
        let s2 = (dof > 0 && rss.is_finite()).then(|| rss / dof as f64);
        let (rank, condition, covariance) = rank_and_covariance(jac, s2);
        let gradient_cosine = gradient_cosine(jac, &residuals, rss.sqrt());
        if status.is_converged() && rank < n {
            status = FitStatus::Singular { rank };
        }
        let std_errors = covariance.as_ref().map(|c: &DMatrix<f64>| {
            (0..n)
                .map(|i| c[(i, i)].max(0.0).sqrt())
                .collect::<Vec<_>>()
        });
        let correlation = covariance
            .as_ref()
            .zip(std_errors.as_ref())
            .map(|(c, se)| DMatrix::from_fn(n, n, |i, j| c[(i, j)] / (se[i] * se[j])));
        FitReport {
            params,
            covariance,
            std_errors,
            correlation,
            residuals,
            rss,
            dof,
            s2,
            rank,
            condition,
            gradient_cosine,
            rss_digits: None,
            iterations,
            evaluations,
            status,
        }
    }
}

/// Rank, condition number and covariance (s² (JᵀJ)⁻¹, only at full rank
/// and with a residual variance) from the SVD of the column-scaled Jacobian:
/// the rank test and the inverse are then invariant to the parameters' units.
fn rank_and_covariance(jac: &DMatrix<f64>, s2: Option<f64>) -> (usize, f64, Option<DMatrix<f64>>) {
    let (m, n) = jac.shape();
    if n == 0 || !jac.iter().all(|v| v.is_finite()) {
        return (0, f64::INFINITY, None);
    }
    let scale: Vec<f64> = (0..n)
        .map(|j| {
            let c = jac.column(j).norm();
            if c > 0.0 {
                c
            } else {
                1.0
            }
        })
        .collect();
    let mut js = jac.clone();
    for (j, sc) in scale.iter().enumerate() {
        js.column_mut(j).scale_mut(1.0 / sc);
    }
    let Some(svd) = SVD::try_new(js, false, true, f64::EPSILON, 0) else {
        return (0, f64::INFINITY, None);
    };
    let s = &svd.singular_values;
    let smax = s.max();
    let tol = smax * (m.max(n) as f64) * f64::EPSILON;
    let rank = s.iter().filter(|&&v| v > tol).count();
    let condition = smax / s.min();
    let covariance = match (rank == n, s2, svd.v_t.as_ref()) {
        (true, Some(s2), Some(vt)) => {
            let mut cov = DMatrix::zeros(n, n);
            for k in 0..s.len() {
                let v = vt.row(k).transpose();
                cov += (&v * v.transpose()) / (s[k] * s[k]);
            }
            for i in 0..n {
                for j in 0..n {
                    cov[(i, j)] *= s2 / (scale[i] * scale[j]);
                }
            }
            Some(cov)
        }
        _ => None,
    };
    (rank, condition, covariance)
}

/// The largest cosine between the residuals and a column of J (0 at an
/// exact fit): near 0 at a stationary point.
fn gradient_cosine(jac: &DMatrix<f64>, residuals: &[f64], fnorm: f64) -> f64 {
    if fnorm.is_nan() || fnorm <= 0.0 {
        return 0.0;
    }
    (0..jac.ncols())
        .map(|j| {
            let c = jac.column(j);
            let cn = c.norm();
            if cn > 0.0 {
                (c.iter().zip(residuals).map(|(a, b)| a * b).sum::<f64>() / (cn * fnorm)).abs()
            } else {
                0.0
            }
        })
        .fold(0.0, f64::max)
}
