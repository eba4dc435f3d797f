//! "Model only what a scene requires" (MODELS.md §5): evaluate one scene
//! point on the cheapest path that is exact, and report the path.
//!
//! | path | when | cost |
//! |---|---|---|
//! | `flat` | both surfaces flat, L > 0: μ = μ0 | O(1) |
//! | `closed_form` | wedges (Eq. 1.10–1.22) where exact, see below | O(1) |
//! | `numeric_1d` | both surfaces invariant along y | n springs × m steps |
//! | `numeric_2d` | otherwise | nx ny springs × m steps |
//!
//! The closed form (equal average forces on all facets) is exact for:
//! - one flat surface against wedges (symmetric or not), any β, any L > 0
//!   (the gap does not change in time and both facets see the same
//!   heights);
//! - identical wedges at β = 90° (no relative shift: uniform gap), any L > 0;
//! - identical symmetric wedges at β = 0° when L ≥ 1.1 L*
//!   ([`super::exactness::case2_exact_at`]; 10 % margin for the lattice's
//!   discreteness).
//!
//! With adhesion on, the closed form is only used when no spring can be in
//! tension (L ≥ k_c (h1 + h2), or the uniform gap at β = 90°).
//!
//! The numeric paths resolve each instant with the tension bookkeeping only
//! when k_t > 0; the separation solver then covers tension only if a spring
//! really goes slack.
//!
//! Resolution: an explicit lattice, or a tolerance: the lattice is doubled
//! from 16 (1-D) or 8 × 8 (2-D) points until two successive μ differ by less
//! than the tolerance, up to `max_points`; the driver reports whether it
//! converged.

use super::closed_form::{mu_wedges, WedgeSlopes};
use super::exactness::case2_exact_at;
use super::numeric_1d::{simulate_1d, Contact, Lattice};
use super::numeric_2d::simulate_2d;
use super::series::{cos_sin_deg, Series};
use super::surface::Surface;
use crate::error::{Error, Result};

/// The computation used for a scene point.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Path {
    /// Both surfaces flat: μ = μ0.
    Flat,
    /// Wedge closed form (Eq. 1.10–1.22).
    ClosedForm,
    /// Numeric 1-D lattice (Sec. 1.3).
    Numeric1d,
    /// Numeric 2-D lattice (Sec. 1.4).
    Numeric2d,
}

impl Path {
    /// The name written to the tables.
    pub fn name(self) -> &'static str {
        match self {
            Path::Flat => "flat",
            Path::ClosedForm => "closed_form",
            Path::Numeric1d => "numeric_1d",
            Path::Numeric2d => "numeric_2d",
        }
    }
}

/// How finely to resolve the numeric paths.
#[derive(Debug, Clone, PartialEq)]
pub struct Resolution {
    /// Lattice points along x over the window; default 256 (1-D), 32 (2-D).
    pub nx: Option<usize>,
    /// Lattice points along y (2-D); default = nx.
    pub ny: Option<usize>,
    /// Instants per period; default one per lattice spacing.
    pub steps: Option<usize>,
    /// Refine until successive μ differ by less than this (absolute).
    pub tolerance: Option<f64>,
    /// Largest lattice (points in total) the refinement may use.
    pub max_points: usize,
}

impl Default for Resolution {
    fn default() -> Self {
        Resolution {
            nx: None,
            ny: None,
            steps: None,
            tolerance: None,
            max_points: 1 << 16,
        }
    }
}

/// What to keep besides the averages.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Keep {
    /// Keep the series μ(t).
    pub series: bool,
    /// Instants whose spring forces to keep (contact maps).
    pub record: Vec<usize>,
    /// Force a path (tests and benchmarks); `None`: the cheapest exact one.
    pub force: Option<Path>,
}

/// One evaluated scene point.
#[derive(Debug, Clone, PartialEq)]
pub struct PointResult {
    /// Time-averaged μ; `None` when L ≤ 0 (adhesion; see `r_xy`).
    pub mu: Option<f64>,
    /// Time-averaged μ_∥.
    pub mu_parallel: Option<f64>,
    /// Time-averaged μ_⊥.
    pub mu_perp: Option<f64>,
    /// Time-averaged |R_xy|, N per spring (compressed springs only).
    pub r_xy: f64,
    /// The path taken.
    pub path: Path,
    /// Lattice points used (0 for the analytic paths).
    pub springs: usize,
    /// Instants per period used.
    pub steps: usize,
    /// Largest fraction of springs in tension.
    pub tension_fraction: f64,
    /// For a tolerance: whether successive μ agreed within it.
    pub converged: Option<bool>,
    /// Last change of μ in the refinement.
    pub refinement_change: Option<f64>,
    /// Whether the average covered whole periods.
    pub whole_periods: bool,
    /// Sliding distance the time average covered (one period, or the
    /// averaging window when there is none) \[m\]; `None` for the analytic
    /// paths and for motion that changes nothing.
    pub averaged_distance: Option<f64>,
    /// The series, when asked for (numeric paths only).
    pub series: Option<Series>,
}

/// (φ_rise, φ_fall, λ) of a wedge or flat surface; `None` otherwise.
fn wedge_of(s: &Surface) -> Option<(f64, f64, Option<f64>)> {
    match s {
        Surface::Wedges {
            phi_rise,
            phi_fall,
            wavelength,
        } => Some((*phi_rise, *phi_fall, Some(*wavelength))),
        s if s.is_flat() => Some((0.0, 0.0, None)),
        _ => None,
    }
}

/// Whether the closed form is exact for this contact (see the module doc).
pub fn closed_form_exact(c: &Contact) -> Result<bool> {
    let (Some(w1), Some(w2)) = (wedge_of(c.z1), wedge_of(c.z2)) else {
        return Ok(false);
    };
    if c.load <= 0.0 || !c.load.is_finite() {
        return Ok(false);
    }
    let flat1 = w1.0 == 0.0;
    let flat2 = w2.0 == 0.0;
    let beta = c.beta_deg.rem_euclid(360.0);
    let identical = w1 == w2;
    let no_tension_possible = c.springs.k_t == 0.0
        || c.load >= c.springs.k_c * (c.z1.peak_to_valley() + c.z2.peak_to_valley());
    #[allow(clippy::float_cmp)] // exact axis angles are meant
    let ok = if flat1 || flat2 {
        no_tension_possible
    } else if identical && (beta == 90.0 || beta == 270.0) {
        true
    } else if identical && w1.0 == w1.1 && (beta == 0.0 || beta == 180.0) {
        let lambda = w1.2.unwrap_or(1.0);
        no_tension_possible && case2_exact_at(c.mu0, w1.0.tan(), c.load / (c.springs.k_c * lambda))?
    } else {
        false
    };
    Ok(ok)
}

/// Evaluates one scene point on the cheapest exact path.
pub fn evaluate(c: &Contact, res: &Resolution, keep: &Keep) -> Result<PointResult> {
    if !(c.mu0.is_finite() && c.mu0 >= 0.0) {
        return Err(Error::Config(format!(
            "mu0 must be finite and >= 0, got {}",
            c.mu0
        )));
    }
    if !c.beta_deg.is_finite() || !c.load.is_finite() {
        return Err(Error::Config(format!(
            "beta and load must be finite, got beta = {} deg, load = {}",
            c.beta_deg, c.load
        )));
    }
    c.springs.validate()?;
    c.z1.validate()?;
    c.z2.validate()?;
    let path = match keep.force {
        Some(p) => p,
        None if c.z1.is_flat() && c.z2.is_flat() && c.load > 0.0 => Path::Flat,
        None if closed_form_exact(c)? => Path::ClosedForm,
        None if c.z1.is_y_invariant() && c.z2.is_y_invariant() => Path::Numeric1d,
        None => Path::Numeric2d,
    };
    match path {
        Path::Flat | Path::ClosedForm => analytic(c, path),
        Path::Numeric1d | Path::Numeric2d => numeric(c, path, res, keep),
    }
}

fn analytic(c: &Contact, path: Path) -> Result<PointResult> {
    let (m, p, q) = if path == Path::Flat {
        (c.mu0, c.mu0, 0.0)
    } else {
        let (w1, w2) = (
            wedge_of(c.z1).ok_or_else(|| Error::Config("closed form needs wedges".into()))?,
            wedge_of(c.z2).ok_or_else(|| Error::Config("closed form needs wedges".into()))?,
        );
        let slopes = WedgeSlopes {
            phi1: w1.0,
            phi2: w1.1,
            phi3: w2.0,
            phi4: w2.1,
        };
        let (cb, sb) = cos_sin_deg(c.beta_deg);
        mu_wedges(c.mu0, &slopes, sb.atan2(cb))?
    };
    Ok(PointResult {
        mu: Some(m),
        mu_parallel: Some(p),
        mu_perp: Some(q),
        r_xy: m * c.load,
        path,
        springs: 0,
        steps: 0,
        tension_fraction: 0.0,
        converged: None,
        refinement_change: None,
        whole_periods: true,
        averaged_distance: None,
        series: None,
    })
}

fn run_lattice(c: &Contact, path: Path, lattice: &Lattice) -> Result<Series> {
    if path == Path::Numeric1d {
        simulate_1d(c, lattice)
    } else {
        simulate_2d(c, lattice)
    }
}

/// Doubles the lattice from a coarse one until successive levels (μ, or
/// |R_xy| without load) differ by less than `tol`, or the next lattice
/// would pass `res.max_points`: the last series, whether it converged and
/// the last change.
fn refine(
    c: &Contact,
    path: Path,
    res: &Resolution,
    mut lattice: Lattice,
    tol: f64,
) -> Result<(Series, Option<bool>, Option<f64>)> {
    let two_d = path == Path::Numeric2d;
    let mut change = None;
    if !(tol.is_finite() && tol > 0.0) {
        return Err(Error::Config(format!(
            "tolerance must be finite and > 0, got {tol}"
        )));
    }
    lattice.nx = if two_d { 8 } else { 16 };
    lattice.ny = if two_d { 8 } else { 1 };
    let mut prev = run_lattice(c, path, &lattice)?;
    let mut prev_mu = level_of(&prev)?;
    let (series, converged) = loop {
        let next = Lattice {
            nx: lattice.nx * 2,
            ny: if two_d { lattice.ny * 2 } else { 1 },
            ..lattice.clone()
        };
        if next.nx * next.ny > res.max_points {
            break (prev, Some(false));
        }
        let s = run_lattice(c, path, &next)?;
        let mu = level_of(&s)?;
        let d = (mu - prev_mu).abs();
        change = Some(d);
        lattice = next;
        prev = s;
        prev_mu = mu;
        if d < tol {
            break (prev, Some(true));
        }
    };
    Ok((series, converged, change))
}

fn numeric(c: &Contact, path: Path, res: &Resolution, keep: &Keep) -> Result<PointResult> {
    let two_d = path == Path::Numeric2d;
    let default_n = if two_d { 32 } else { 256 };
    let lattice = Lattice {
        nx: res.nx.unwrap_or(default_n),
        ny: if two_d {
            res.ny.or(res.nx).unwrap_or(default_n)
        } else {
            1
        },
        steps: res.steps,
        record: keep.record.clone(),
    };
    let (series, converged, change) = match res.tolerance {
        None => (run_lattice(c, path, &lattice)?, None, None),
        Some(tol) => refine(c, path, res, lattice, tol)?,
    };
    let (mu, par, perp, tension) = if c.load > 0.0 {
        let a = series.averages()?;
        (
            Some(a.mu),
            Some(a.mu_parallel),
            Some(a.mu_perp),
            a.tension_fraction,
        )
    } else {
        let t = series
            .instants
            .iter()
            .map(|i| i.n_tension as f64 / series.springs as f64)
            .fold(0.0, f64::max);
        (None, None, None, t)
    };
    let r_xy = series.mean_r_xy();
    if !r_xy.is_finite() {
        return Err(Error::Numerical("non-finite tangential force".into()));
    }
    Ok(PointResult {
        mu,
        mu_parallel: par,
        mu_perp: perp,
        r_xy,
        path,
        springs: series.springs,
        steps: series.instants.len(),
        tension_fraction: tension,
        converged,
        refinement_change: change,
        whole_periods: series.whole_periods,
        averaged_distance: series.period,
        series: keep.series.then_some(series),
    })
}

/// The quantity refined on: μ when L > 0, else |R_xy|.
fn level_of(s: &Series) -> Result<f64> {
    if s.instants.first().is_some_and(|i| i.r_z > 0.0) {
        Ok(s.averages()?.mu)
    } else {
        Ok(s.mean_r_xy())
    }
}
