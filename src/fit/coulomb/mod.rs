//! Coulomb law with cohesion (thesis Eq. 4.1, 4.2; MODELS.md §2).
//!
//! τ = τ0 + μ p, with τ = T / A_th and p = N / A_th, fitted as a straight
//! line of τ against p ([`linear`]).
//!
//! | symbol | field | unit |
//! |---|---|---|
//! | T | `tangential_force_n` | N, static or dynamic friction force |
//! | N | `normal_force_n` | N |
//! | A_th | `area_m2` | m², apparent (theoretical) contact area |
//! | μ | [`CoulombFit::mu`] | 1 |
//! | τ0 | [`CoulombFit::tau0_pa`] | Pa, cohesion |
//! | AF | `area_fraction` | 1, 1 − A_holes / A_th |
//!
//! Eq. 4.2 predicts a patterned surface from the flat reference F:
//! T = AF (τ0,F A_th + μ_F N), i.e. μ_pred = AF μ_F and τ0,pred = AF τ0,F;
//! [`predict_area_fraction`] gives the ratio of measured to predicted
//! force.
//!
//! Assumptions: independent errors of equal variance in τ (unweighted;
//! the fit states `weighted = false`), or a Huber loss when outliers are
//! expected. Rows with a non-finite or missing value are excluded and
//! counted. Outliers are points whose internally studentized residual
//! exceeds a threshold (default 3); they are reported, and kept unless the
//! robust loss is chosen. Valid range: at least 2 points with distinct
//! pressures; with exactly 2 the line is exact and the standard errors are
//! undefined (status `se_undefined`).

pub mod linear;
pub mod samples;
pub mod table;

use crate::status::{Code, Status};
use linear::{fit_line, Loss};

use crate::error::{Error, Result};

/// One friction measurement.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FrictionPoint {
    /// Normal force N, newtons.
    pub normal_force_n: f64,
    /// Friction force T, newtons.
    pub tangential_force_n: f64,
    /// Apparent contact area A_th, m².
    pub area_m2: f64,
}

impl FrictionPoint {
    /// Whether the point enters a fit: finite forces and a positive area.
    pub fn usable(&self) -> bool {
        self.normal_force_n.is_finite()
            && self.tangential_force_n.is_finite()
            && self.area_m2.is_finite()
            && self.area_m2 > 0.0
    }
}

/// Settings of [`fit_coulomb`].
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct CoulombParams {
    /// Loss function. Default least squares.
    pub loss: Loss,
    /// |studentized residual| above which a point is reported as an
    /// outlier. Default 3, range (0, ∞).
    pub outlier_threshold: f64,
}

impl Default for CoulombParams {
    fn default() -> Self {
        CoulombParams {
            loss: Loss::LeastSquares,
            outlier_threshold: 3.0,
        }
    }
}

/// A Coulomb fit of one group.
#[derive(Debug, Clone, PartialEq)]
pub struct CoulombFit {
    /// Points used.
    pub n: usize,
    /// Points excluded for a missing or non-finite value (or A_th ≤ 0).
    pub n_excluded: usize,
    /// Friction coefficient μ (slope).
    pub mu: f64,
    /// Standard error of μ (`None` with 2 points).
    pub mu_se: Option<f64>,
    /// Cohesion τ0, Pa (intercept).
    pub tau0_pa: f64,
    /// Standard error of τ0, Pa (`None` with 2 points).
    pub tau0_se_pa: Option<f64>,
    /// R² of τ against p.
    pub r2: f64,
    /// Indices (into the input) of the outliers.
    pub outliers: Vec<usize>,
    /// `ok` or `se_undefined` (2 points).
    pub status: Status,
    /// Loss used.
    pub loss: Loss,
}

/// Fits τ = τ0 + μ p. Errors: fewer than 2 usable points, or a constant
/// pressure (singular design), both [`Error::NotApplicable`].
pub fn fit_coulomb(points: &[FrictionPoint], params: &CoulombParams) -> Result<CoulombFit> {
    if params.outlier_threshold.is_nan() || params.outlier_threshold <= 0.0 {
        return Err(Error::Config(format!(
            "outlier threshold must be > 0, got {}",
            params.outlier_threshold
        )));
    }
    let mut idx = vec![];
    let (mut p, mut tau) = (vec![], vec![]);
    for (i, q) in points.iter().enumerate() {
        if q.usable() {
            idx.push(i);
            p.push(q.normal_force_n / q.area_m2);
            tau.push(q.tangential_force_n / q.area_m2);
        }
    }
    let n_excluded = points.len() - idx.len();
    if idx.len() < 2 {
        return Err(Error::coded(
            Code::TooFewPoints,
            format!(
                "Coulomb fit needs at least 2 usable points, got {} ({n_excluded} excluded for missing or non-finite values)",
                idx.len()
            ),
        ));
    }
    let line = fit_line(&p, &tau, params.loss).map_err(|e| match e {
        Error::Coded { code, message } => Error::coded(
            code,
            format!("Coulomb fit: {message} (pressure p = N / A_th is constant)"),
        ),
        e => e,
    })?;
    let outliers = line.studentized.as_ref().map_or(vec![], |s| {
        s.iter()
            .enumerate()
            .filter(|(_, v)| v.abs() > params.outlier_threshold)
            .map(|(k, _)| idx[k])
            .collect()
    });
    Ok(CoulombFit {
        n: line.n,
        n_excluded,
        mu: line.slope,
        mu_se: line.slope_se,
        tau0_pa: line.intercept,
        tau0_se_pa: line.intercept_se,
        r2: line.r2,
        outliers,
        status: fit_doubts(line.n, line.slope),
        loss: params.loss,
    })
}

/// What a Coulomb fit's status says: no standard errors from 2 points; too
/// few points to judge the line (fewer than its 2 parameters + 2); a
/// negative μ, which the physics rules out (Eq. 4.1).
fn fit_doubts(n: usize, mu: f64) -> Status {
    let mut s = Status::ok();
    if n == 2 {
        s.push(Code::SeUndefined, "");
    }
    if n < 4 {
        s.push(Code::FewPoints, format!("{n} points for 2 parameters"));
    }
    if mu < 0.0 {
        s.push(Code::UnphysicalSign, format!("μ = {mu:.3} < 0"));
    }
    s
}

/// Eq. 4.2 prediction for a pattern of area fraction `af` from the flat
/// reference fit: (μ_pred, τ0,pred, ratio) with μ_pred = AF μ_F,
/// τ0,pred = AF τ0,F and ratio = Σ T_measured / Σ T_predicted over the
/// usable points (a ratio of sums, so that small forces do not dominate).
pub fn predict_area_fraction(
    reference: &CoulombFit,
    af: f64,
    points: &[FrictionPoint],
) -> Result<(f64, f64, f64)> {
    if !(af > 0.0 && af <= 1.0) {
        return Err(Error::Config(format!(
            "area fraction must be in (0, 1], got {af}"
        )));
    }
    let (mu_p, tau_p) = (af * reference.mu, af * reference.tau0_pa);
    let (mut meas, mut pred) = (0.0, 0.0);
    for q in points {
        if q.normal_force_n.is_finite() && q.tangential_force_n.is_finite() && q.area_m2 > 0.0 {
            meas += q.tangential_force_n;
            pred += tau_p * q.area_m2 + mu_p * q.normal_force_n;
        }
    }
    if pred.is_nan() || pred == 0.0 {
        return Err(Error::NotApplicable(
            "predicted force is zero: no usable points".into(),
        ));
    }
    Ok((mu_p, tau_p, meas / pred))
}

/// Mean and sample standard deviation (n − 1); sd is `None` for one value.
pub fn mean_sd(v: &[f64]) -> Option<(f64, Option<f64>)> {
    if v.is_empty() {
        return None;
    }
    let n = v.len() as f64;
    let m = v.iter().sum::<f64>() / n;
    let sd =
        (v.len() > 1).then(|| (v.iter().map(|x| (x - m).powi(2)).sum::<f64>() / (n - 1.0)).sqrt());
    Some((m, sd))
}
