//! Straight-line fit y = a + b x by (weighted) least squares on centred
//! data, with standard errors, R², studentized residuals and an optional
//! Huber loss by iteratively reweighted least squares (IRLS).
//!
//! Centring (x − x̄, y − ȳ) makes the fit exact for the closed form
//! b = Sxy / Sxx, a = ȳ − b x̄, stable when x has a large offset, and
//! invariant to the scale of x and y: scaling both by c leaves b unchanged
//! and multiplies a by c. A design whose x values do not vary (relative
//! spread below 1e-9) is singular: an error, never a number.

use crate::error::{Error, Result};
use crate::status::Code;

/// The loss of the straight-line fit.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Loss {
    /// Ordinary least squares.
    LeastSquares,
    /// Huber loss with threshold k in units of the robust residual scale
    /// σ̂ = 1.4826 MAD (k = 1.345 gives 95 % efficiency on normal errors).
    Huber {
        /// Threshold k, > 0.
        k: f64,
    },
}

impl Loss {
    /// `least_squares` or `huber`.
    pub fn name(&self) -> &'static str {
        match self {
            Loss::LeastSquares => "least_squares",
            Loss::Huber { .. } => "huber",
        }
    }
}

/// The fitted line.
#[derive(Debug, Clone, PartialEq)]
pub struct LineFit {
    /// Points used.
    pub n: usize,
    /// Intercept a.
    pub intercept: f64,
    /// Slope b.
    pub slope: f64,
    /// Standard error of a (`None` when n = 2: no degrees of freedom).
    pub intercept_se: Option<f64>,
    /// Standard error of b (`None` when n = 2).
    pub slope_se: Option<f64>,
    /// Coefficient of determination 1 − RSS / TSS (weighted when weighted;
    /// 1 when TSS = 0 and the fit is exact).
    pub r2: f64,
    /// Residuals yᵢ − a − b xᵢ, in input order.
    pub residuals: Vec<f64>,
    /// Internally studentized residuals rᵢ / (s √(1 − hᵢᵢ)) (`None` when
    /// n = 2 or s = 0).
    pub studentized: Option<Vec<f64>>,
    /// Final weights (all 1 for unweighted least squares).
    pub weights: Vec<f64>,
}

/// Weighted least squares with fixed weights `w` (> 0).
pub fn fit_line_weighted(x: &[f64], y: &[f64], w: &[f64]) -> Result<LineFit> {
    let n = x.len();
    if n != y.len() || n != w.len() {
        return Err(Error::Config(format!(
            "fit_line: {} x, {} y, {} weights",
            x.len(),
            y.len(),
            w.len()
        )));
    }
    if n < 2 {
        return Err(Error::coded(
            Code::TooFewPoints,
            format!("a straight line needs at least 2 points, got {n}"),
        ));
    }
    if let Some(i) =
        (0..n).find(|&i| !(x[i].is_finite() && y[i].is_finite() && w[i].is_finite() && w[i] > 0.0))
    {
        return Err(Error::Config(format!(
            "fit_line: point {i} is not finite or has weight <= 0"
        )));
    }
    let sw: f64 = w.iter().sum();
    let xm = (0..n).map(|i| w[i] * x[i]).sum::<f64>() / sw;
    let ym = (0..n).map(|i| w[i] * y[i]).sum::<f64>() / sw;
    let sxx: f64 = (0..n).map(|i| w[i] * (x[i] - xm).powi(2)).sum();
    let sxy: f64 = (0..n).map(|i| w[i] * (x[i] - xm) * (y[i] - ym)).sum();
    let syy: f64 = (0..n).map(|i| w[i] * (y[i] - ym).powi(2)).sum();
    let xscale = x.iter().fold(0.0_f64, |a, v| a.max(v.abs()));
    // Relative spread of x below 1e-9: at double precision the slope would
    // carry fewer than ~7 digits; treat it as the singular design it is.
    let spread_ok = sxx.sqrt() > 1e-9 * xscale * sw.sqrt();
    if !spread_ok {
        return Err(Error::coded(
            Code::SingularDesign,
            format!(
                "singular design: all {n} points have the same x = {xm:.6e} (relative spread < 1e-9), slope and intercept cannot be separated"
            ),
        ));
    }
    let slope = sxy / sxx;
    let intercept = ym - slope * xm;
    let residuals: Vec<f64> = (0..n).map(|i| y[i] - intercept - slope * x[i]).collect();
    let rss: f64 = (0..n).map(|i| w[i] * residuals[i].powi(2)).sum();
    let r2 = if syy > 0.0 { 1.0 - rss / syy } else { 1.0 };
    let (mut intercept_se, mut slope_se, mut studentized) = (None, None, None);
    if n > 2 {
        let s2 = rss / (n - 2) as f64;
        slope_se = Some((s2 / sxx).sqrt());
        intercept_se = Some((s2 * (1.0 / sw + xm * xm / sxx)).sqrt());
        if s2 > 0.0 {
            studentized = Some(
                (0..n)
                    .map(|i| {
                        let h = w[i] * (1.0 / sw + (x[i] - xm).powi(2) / sxx);
                        residuals[i] * w[i].sqrt() / (s2 * (1.0 - h).max(f64::EPSILON)).sqrt()
                    })
                    .collect(),
            );
        }
    }
    Ok(LineFit {
        n,
        intercept,
        slope,
        intercept_se,
        slope_se,
        r2,
        residuals,
        studentized,
        weights: w.to_vec(),
    })
}

/// Fits y = a + b x with the given loss. Huber: IRLS from the least-squares
/// fit, weights min(1, k σ̂ / |rᵢ|), until the coefficients change by less
/// than 1e-12 relative (at most 100 iterations; the result of the last
/// iteration is returned either way, it is a valid weighted fit).
pub fn fit_line(x: &[f64], y: &[f64], loss: Loss) -> Result<LineFit> {
    let mut fit = fit_line_weighted(x, y, &vec![1.0; x.len()])?;
    let Loss::Huber { k } = loss else {
        return Ok(fit);
    };
    if !(k.is_finite() && k > 0.0) {
        return Err(Error::Config(format!(
            "Huber threshold k must be > 0, got {k}"
        )));
    }
    for _ in 0..100 {
        let abs: Vec<f64> = fit.residuals.iter().map(|r| r.abs()).collect();
        let sigma = 1.4826 * crate::signal::stats::median(&abs).unwrap_or(0.0);
        if sigma == 0.0 {
            break;
        }
        let w: Vec<f64> = fit
            .residuals
            .iter()
            .map(|r| (k * sigma / r.abs()).min(1.0))
            .collect();
        let next = fit_line_weighted(x, y, &w)?;
        let change = ((next.slope - fit.slope).abs() / fit.slope.abs().max(f64::MIN_POSITIVE)).max(
            (next.intercept - fit.intercept).abs()
                / (fit.intercept.abs()
                    + fit.slope.abs() * x.iter().fold(0.0_f64, |a, v| a.max(v.abs()))),
        );
        fit = next;
        if change < 1e-12 {
            break;
        }
    }
    Ok(fit)
}
