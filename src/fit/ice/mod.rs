//! Fit of the Makkonen film model with ALSFM roughness bounds to μ(v)
//! (MODELS.md §6, thesis Figs. 3.7–3.9), one pin × temperature group at a
//! time, for the upper and the lower bound ([`crate::models::makkonen`]).
//!
//! The free parameter is the contact length a, fitted as ln a (a > 0 by
//! construction, and the step is scale-free); its standard error is
//! a · se(ln a) (delta method). The thermal assumption is explicit
//! ([`Thermal`]); optionally ΔT is fitted jointly, and the correlation of
//! a and ΔT is reported (in the conduction regime only ΔT/√a is
//! identifiable, and the correlation tends to ±1 or the fit is singular).
//! The start of ln a comes from a scan over a = 1e-9 … 1e-1 m (33 points
//! per run, deterministic), so no initial guess is needed.
//!
//! Misfit: the fit is flagged when its RMSE exceeds `misfit_tol` × the mean
//! |μ| of the group (default 0.15), or it did not converge. Pin #1 of the
//! thesis (boundary lubrication) is expected to be flagged.

pub mod table;

use crate::error::{Error, Result};
use crate::fit::{least_squares, FitStatus, LeastSquaresProblem, LmParams};
use crate::models::makkonen::{mu_wet_gamma, Bound, MakkonenParams, Thermal};

/// One velocity step.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct IceObservation {
    /// Sliding velocity v, m/s.
    pub velocity_m_per_s: f64,
    /// Mean friction coefficient of the step.
    pub mu: f64,
}

impl IceObservation {
    /// Whether the observation enters a fit: a positive finite velocity
    /// and a finite μ.
    pub fn usable(&self) -> bool {
        self.velocity_m_per_s.is_finite() && self.velocity_m_per_s > 0.0 && self.mu.is_finite()
    }
}

/// Settings of [`fit_ice`].
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct IceFitParams {
    /// Model constants (Table 3.2).
    pub model: MakkonenParams,
    /// Thermal assumption (and the start of ΔT when fitted). Default bulk.
    pub thermal: Thermal,
    /// Fit ΔT jointly with a. Default false.
    pub fit_delta_t: bool,
    /// Relative RMSE above which the fit is flagged as a misfit. Default
    /// 0.15, range (0, ∞).
    pub misfit_tol: f64,
    /// Solver settings.
    pub lm: LmParams,
}

impl Default for IceFitParams {
    fn default() -> Self {
        IceFitParams {
            model: MakkonenParams::default(),
            thermal: Thermal::Bulk,
            fit_delta_t: false,
            misfit_tol: 0.15,
            lm: LmParams::default(),
        }
    }
}

/// The fit of one bound to one group.
#[derive(Debug, Clone)]
pub struct IceFit {
    /// Which bound.
    pub bound: Bound,
    /// Contact length a, m.
    pub a_m: f64,
    /// Standard error of a, m (`None` without dof or when singular).
    pub a_se_m: Option<f64>,
    /// ΔT used (fitted, given or from the bulk temperature), K.
    pub delta_t_k: f64,
    /// Standard error of ΔT when fitted.
    pub delta_t_se_k: Option<f64>,
    /// Correlation of a and ΔT when fitted.
    pub corr_a_delta_t: Option<f64>,
    /// Root-mean-square residual of μ.
    pub rmse: f64,
    /// RMSE / mean |μ|.
    pub rel_rmse: f64,
    /// Points used.
    pub n: usize,
    /// Residuals μ_model − μ_measured, in input order.
    pub residuals: Vec<f64>,
    /// Model μ at each point.
    pub mu_model: Vec<f64>,
    /// Solver status.
    pub status: FitStatus,
    /// Misfit flag (see the module documentation).
    pub misfit: bool,
    /// Solver iterations.
    pub iterations: u64,
}

struct IceProblem<'a> {
    obs: &'a [IceObservation],
    phi: f64,
    bound: Bound,
    p: &'a IceFitParams,
    hardness: f64,
    gamma_per_k: f64,
    fixed_delta_t: f64,
}

impl IceProblem<'_> {
    /// The ln a of least squares on a 33-point grid over [1e-9, 1e-1] m (at
    /// the given ΔT): the fit's start. An error when no a gives a finite
    /// residual.
    fn start_ln_a(&self, delta_t: f64) -> Result<f64> {
        let mut best = (f64::INFINITY, (1e-4f64).ln());
        let mut r = vec![0.0; self.obs.len()];
        for k in 0..33 {
            let la = (1e-9f64).ln() + k as f64 * ((1e-1f64).ln() - (1e-9f64).ln()) / 32.0;
            let mut x = vec![la];
            if self.p.fit_delta_t {
                x.push(delta_t);
            }
            self.residuals(&x, &mut r);
            let s: f64 = r.iter().map(|v| v * v).sum();
            if s < best.0 {
                best = (s, la);
            }
        }
        if !best.0.is_finite() {
            return Err(Error::NotApplicable(format!(
                "the {} bound cannot be evaluated for any a in [1e-9, 1e-1] m (surfaces lock at slope {:.2} deg?)",
                self.bound.name(),
                self.phi.to_degrees()
            )));
        }
        Ok(best.1)
    }
}

impl IceProblem<'_> {
    fn model(&self, v: f64, a: f64, dt: f64) -> f64 {
        let gamma = dt * self.gamma_per_k;
        mu_wet_gamma(&self.p.model, v, a, gamma, self.hardness)
            .and_then(|m| self.bound.apply(m, self.phi))
            .unwrap_or(f64::NAN)
    }
    fn unpack(&self, x: &[f64]) -> (f64, f64) {
        (
            x[0].exp(),
            if self.p.fit_delta_t {
                x[1]
            } else {
                self.fixed_delta_t
            },
        )
    }
}

impl LeastSquaresProblem for IceProblem<'_> {
    fn n_params(&self) -> usize {
        1 + usize::from(self.p.fit_delta_t)
    }
    fn n_residuals(&self) -> usize {
        self.obs.len()
    }
    fn residuals(&self, x: &[f64], out: &mut [f64]) {
        let (a, dt) = self.unpack(x);
        for (o, ob) in out.iter_mut().zip(self.obs) {
            *o = if dt >= 0.0 {
                self.model(ob.velocity_m_per_s, a, dt) - ob.mu
            } else {
                f64::NAN
            };
        }
    }
    fn response_scale(&self) -> Option<f64> {
        Some(self.obs.iter().fold(0.0, |m, o| m.max(o.mu.abs())))
    }
}

/// Fits a (and optionally ΔT) of one bound to one group's μ(v) at bulk
/// temperature `t_c` (°C) and slope `phi` (rad). Rows with a non-finite
/// or non-positive velocity or a non-finite μ are dropped (the caller
/// counts them). Errors: fewer than 1 + (ΔT fitted) usable points, or
/// invalid constants.
pub fn fit_ice(
    obs: &[IceObservation],
    t_c: f64,
    phi: f64,
    bound: Bound,
    p: &IceFitParams,
) -> Result<IceFit> {
    p.model.validate()?;
    if p.misfit_tol.is_nan() || p.misfit_tol <= 0.0 {
        return Err(Error::Config(format!(
            "misfit_tol must be > 0, got {}",
            p.misfit_tol
        )));
    }
    let obs: Vec<IceObservation> = obs.iter().copied().filter(|o| o.usable()).collect();
    let n_par = 1 + usize::from(p.fit_delta_t);
    if obs.len() < n_par {
        return Err(Error::NotApplicable(format!(
            "ice fit needs at least {n_par} velocity steps, got {}",
            obs.len()
        )));
    }
    let hardness = p.model.hardness(t_c)?;
    let (d1, _) = p.thermal.delta_t(p.model.t_melt_c, t_c)?;
    let problem = IceProblem {
        obs: &obs,
        phi,
        bound,
        p,
        hardness,
        gamma_per_k: p.model.ice.effusivity() + p.model.slider.effusivity(),
        fixed_delta_t: d1,
    };
    let start = problem.start_ln_a(d1)?;
    let mut x0 = vec![start];
    if p.fit_delta_t {
        x0.push(if d1 > 0.0 { d1 } else { 1.0 });
    }
    let fit = least_squares(&problem, &x0, &p.lm)?;
    let (a, dt) = problem.unpack(&fit.params);
    let se = fit.std_errors.as_ref();
    let n = obs.len();
    let rmse = (fit.rss / n as f64).sqrt();
    let mean_mu = obs.iter().map(|o| o.mu.abs()).sum::<f64>() / n as f64;
    let rel_rmse = rmse / mean_mu;
    let mu_model: Vec<f64> = obs
        .iter()
        .zip(&fit.residuals)
        .map(|(o, r)| o.mu + r)
        .collect();
    Ok(IceFit {
        bound,
        a_m: a,
        a_se_m: se.map(|s| a * s[0]),
        delta_t_k: dt,
        delta_t_se_k: if p.fit_delta_t {
            se.map(|s| s[1])
        } else {
            None
        },
        corr_a_delta_t: if p.fit_delta_t {
            fit.correlation.as_ref().map(|c| c[(0, 1)])
        } else {
            None
        },
        rmse,
        rel_rmse,
        n,
        residuals: fit.residuals.clone(),
        mu_model,
        misfit: !fit.status.is_converged() || rel_rmse.is_nan() || rel_rmse > p.misfit_tol,
        status: fit.status,
        iterations: fit.iterations,
    })
}
