//! Validation of the solver on the NIST StRD nonlinear regression suite
//! (27 problems, certified to 11 digits, two starting points each).
//!
//! Accuracy is the log relative error LRE = −log₁₀(|x − c| / |c|), the
//! number of correct significant digits, capped at 11 (the certified
//! digits). [`run_dir`] fits every `.dat` file of a folder from both starts
//! and returns one [`NistRow`] per problem and start; [`format_table`]
//! renders them.

pub mod models;
pub mod parse;

use std::path::Path;

use nalgebra::DMatrix;

pub use models::NistModel;
pub use parse::{parse_nist, NistData};

use super::{least_squares, FitStatus, LeastSquaresProblem, LmParams};
use crate::error::{Error, Location, Result};

/// A NIST dataset with its model, as a least-squares problem (r = f − y).
pub struct NistProblem<'a> {
    /// The data.
    pub data: &'a NistData,
    /// The model.
    pub model: NistModel,
    /// Use the analytic gradient (else central differences).
    pub analytic: bool,
}

impl NistProblem<'_> {
    fn response(&self, i: usize) -> f64 {
        if self.model.log_response() {
            self.data.y[i].ln()
        } else {
            self.data.y[i]
        }
    }
}

impl LeastSquaresProblem for NistProblem<'_> {
    fn n_params(&self) -> usize {
        self.data.certified.len()
    }
    fn n_residuals(&self) -> usize {
        self.data.y.len()
    }
    fn residuals(&self, b: &[f64], out: &mut [f64]) {
        for (i, o) in out.iter_mut().enumerate() {
            *o = self.model.eval(b, &self.data.x[i], None) - self.response(i);
        }
    }
    fn jacobian(&self, b: &[f64], jac: &mut DMatrix<f64>) -> bool {
        if !self.analytic {
            return false;
        }
        let mut g = vec![0.0; b.len()];
        for i in 0..self.data.y.len() {
            self.model.eval(b, &self.data.x[i], Some(&mut g));
            for (j, v) in g.iter().enumerate() {
                jac[(i, j)] = *v;
            }
        }
        true
    }
    fn response_scale(&self) -> Option<f64> {
        Some(
            (0..self.data.y.len())
                .map(|i| self.response(i).abs())
                .fold(0.0, f64::max),
        )
    }
}

/// Correct significant digits of `est` against `cert`, in [0, 11].
pub fn lre(est: f64, cert: f64) -> f64 {
    if !est.is_finite() {
        return 0.0;
    }
    let rel = if cert == 0.0 {
        est.abs()
    } else {
        ((est - cert) / cert).abs()
    };
    if rel == 0.0 {
        11.0
    } else {
        (-rel.log10()).clamp(0.0, 11.0)
    }
}

/// Accuracy of one problem from one start.
#[derive(Debug, Clone)]
pub struct NistRow {
    /// Dataset name.
    pub name: String,
    /// NIST difficulty (Lower, Average, Higher).
    pub difficulty: String,
    /// Start 1 or 2.
    pub start: u8,
    /// Why the solver stopped.
    pub status: FitStatus,
    /// Outer iterations.
    pub iterations: u64,
    /// Final gradient cosine.
    pub cosine: f64,
    /// Estimated digits of the RSS allowed by rounding in the residuals.
    pub rss_digits: Option<f64>,
    /// Minimum LRE over the parameters.
    pub lre_params: f64,
    /// Minimum LRE over the standard errors (0 when none).
    pub lre_se: f64,
    /// LRE of the residual sum of squares.
    pub lre_rss: f64,
}

/// Fits `data` from start 1 or 2 and compares with the certified values.
pub fn run_problem(
    data: &NistData,
    start: u8,
    analytic: bool,
    params: &LmParams,
) -> Result<NistRow> {
    let model = NistModel::for_dataset(&data.name)
        .ok_or_else(|| Error::Config(format!("no model for NIST dataset '{}'", data.name)))?;
    let problem = NistProblem {
        data,
        model,
        analytic,
    };
    let x0 = &data.starts[usize::from(start.clamp(1, 2) - 1)];
    let fit = least_squares(&problem, x0, params)?;
    let min = |it: &mut dyn Iterator<Item = f64>| it.fold(f64::INFINITY, f64::min);
    let lre_params = min(&mut fit
        .params
        .iter()
        .zip(&data.certified)
        .map(|(e, c)| lre(*e, *c)));
    let lre_se = fit.std_errors.as_ref().map_or(0.0, |se| {
        min(&mut se.iter().zip(&data.certified_sd).map(|(e, c)| lre(*e, *c)))
    });
    Ok(NistRow {
        name: data.name.clone(),
        difficulty: data.difficulty.clone(),
        start,
        status: fit.status,
        iterations: fit.iterations,
        cosine: fit.gradient_cosine,
        rss_digits: fit.rss_digits,
        lre_params,
        lre_se,
        lre_rss: lre(fit.rss, data.certified_rss),
    })
}

/// Reads and parses one `.dat` file.
pub fn read_nist(path: &Path) -> Result<NistData> {
    let text = std::fs::read_to_string(path).map_err(|e| Error::io(path, e))?;
    parse_nist(path, &text)
}

/// Every `.dat` file of `dir` (sorted by name), from both starts.
pub fn run_dir(dir: &Path, params: &LmParams) -> Result<Vec<NistRow>> {
    let mut files: Vec<_> = std::fs::read_dir(dir)
        .map_err(|e| Error::io(dir, e))?
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x == "dat"))
        .collect();
    files.sort();
    if files.is_empty() {
        return Err(Error::input(
            Location::file(dir),
            "no .dat files; expected the NIST StRD nonlinear suite",
        ));
    }
    let mut rows = Vec::with_capacity(2 * files.len());
    for f in &files {
        let data = read_nist(f)?;
        for start in [1, 2] {
            rows.push(run_problem(&data, start, true, params)?);
        }
    }
    Ok(rows)
}

/// Plain-text table of the rows, then a summary line per start.
pub fn format_table(rows: &[NistRow]) -> String {
    let mut s = format!(
        "{:<10} {:<8} {:>5} {:>5} {:>9} {:>7} {:>7} {:>8} {:>6}  {}\n",
        "problem",
        "level",
        "start",
        "iter",
        "LRE(b)",
        "LRE(se)",
        "LRE(S)",
        "cos",
        "S-dig",
        "status"
    );
    for r in rows {
        s += &format!(
            "{:<10} {:<8} {:>5} {:>5} {:>9.1} {:>7.1} {:>7.1} {:>8.1e} {:>6.1}  {}\n",
            r.name,
            r.difficulty,
            r.start,
            r.iterations,
            r.lre_params,
            r.lre_se,
            r.lre_rss,
            r.cosine,
            r.rss_digits.unwrap_or(f64::NAN),
            r.status
        );
    }
    for start in [1, 2] {
        let sel: Vec<&NistRow> = rows.iter().filter(|r| r.start == start).collect();
        let conv: Vec<&&NistRow> = sel.iter().filter(|r| r.status.is_converged()).collect();
        let minp = conv
            .iter()
            .map(|r| r.lre_params)
            .fold(f64::INFINITY, f64::min);
        let limited = |r: &&&NistRow| r.rss_digits.is_some_and(|d| d < 4.0);
        let mins = conv
            .iter()
            .filter(|r| !limited(r))
            .map(|r| r.lre_se)
            .fold(f64::INFINITY, f64::min);
        let names: Vec<&str> = conv
            .iter()
            .filter(|r| limited(r))
            .map(|r| r.name.as_str())
            .collect();
        s += &format!(
            "start {start}: {}/{} converged; min LRE(b) {minp:.1}; min LRE(se) {mins:.1} excluding rounding-limited {names:?}\n",
            conv.len(),
            sel.len()
        );
    }
    s
}
