//! The validated ALSFM plan: every range and combination of the scene file
//! is checked here, before any computation starts.

use std::path::Path;

pub use super::scene::Outputs;
use super::scene::{SceneSpec, SurfaceSpec, Sweep};
use crate::error::{Error, Result};
use crate::hash::InputHash;
use crate::models::alsfm::instant::SpringParams;
use crate::models::alsfm::solver::Resolution;
use crate::models::alsfm::surface::Surface;
use crate::models::alsfm::wear::WearParams;

/// Hierarchy settings.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct HierarchyPlan {
    /// Levels n ≥ 1.
    pub levels: usize,
    /// Scale factor between levels, > 1.
    pub scale: f64,
    /// Hierarchical wear.
    pub wear: bool,
}

/// A validated scene.
#[derive(Debug, Clone, PartialEq)]
pub struct Plan {
    /// μ0.
    pub mu0: f64,
    /// β values, degrees, in file order.
    pub beta_deg: Vec<f64>,
    /// Loads, N per spring, in file order.
    pub loads: Vec<f64>,
    /// z1.
    pub lower: Surface,
    /// z2.
    pub upper: Surface,
    /// Springs (k_t > 0 with adhesion).
    pub springs: SpringParams,
    /// Wear, if any.
    pub wear: Option<WearParams>,
    /// Wear instants, ≥ 2.
    pub wear_samples: usize,
    /// Hierarchy, if any.
    pub hierarchy: Option<HierarchyPlan>,
    /// v, m/s.
    pub velocity: f64,
    /// Time-series length, s (`None`: one period).
    pub duration: Option<f64>,
    /// Resolution.
    pub resolution: Resolution,
    /// Extra tables.
    pub outputs: Outputs,
    /// Files the surfaces were read from (`kind = "file"`), for the
    /// provenance.
    pub surface_files: Vec<InputHash>,
}

fn expand(name: &str, s: &Sweep) -> Result<Vec<f64>> {
    let v = match s {
        Sweep::One(x) => vec![*x],
        Sweep::List(v) => v.clone(),
        Sweep::Range(r) => {
            if r.count == 0 {
                return Err(Error::Config(format!("{name}: range count must be >= 1")));
            }
            if r.count == 1 {
                vec![r.from]
            } else {
                (0..r.count)
                    .map(|k| grid_point(r.from, r.to, k, r.count))
                    .collect()
            }
        }
    };
    if v.is_empty() {
        return Err(Error::Config(format!(
            "{name}: at least one value is needed"
        )));
    }
    if let Some(x) = v.iter().find(|x| !x.is_finite()) {
        return Err(Error::Config(format!("{name}: value {x} is not finite")));
    }
    Ok(v)
}

/// Point k of `count` evenly spaced from `from` to `to`: the last is `to`
/// itself, and a point within rounding of zero is zero (a load grid from
/// 0.1 to −0.02 in 7 points has 0 − 1.4e-17 there otherwise, a load that
/// reads as tensile).
fn grid_point(from: f64, to: f64, k: usize, count: usize) -> f64 {
    if k + 1 == count {
        return to;
    }
    let v = from + (to - from) * k as f64 / (count - 1) as f64;
    match v.abs() <= 8.0 * f64::EPSILON * from.abs().max(to.abs()) {
        true => 0.0,
        false => v,
    }
}

fn surface(
    name: &str,
    s: &SurfaceSpec,
    base: &Path,
    files: &mut Vec<InputHash>,
) -> Result<Surface> {
    let out = match s {
        SurfaceSpec::File(f) => {
            let (surface, hash) = super::surface_file::load(f, base)
                .map_err(|e| Error::Config(format!("[{name}]: {e}")))?;
            files.push(hash);
            surface
        }
        // Validated as it was read.
        SurfaceSpec::Shape(s) => return Ok(s.clone()),
    };
    out.validate()
        .map_err(|e| Error::Config(format!("[{name}]: {e}")))?;
    Ok(out)
}

fn positive(name: &str, v: Option<f64>, default: f64) -> Result<f64> {
    let x = v.unwrap_or(default);
    if x.is_finite() && x > 0.0 {
        Ok(x)
    } else {
        Err(Error::Config(format!(
            "{name} must be finite and > 0, got {x}"
        )))
    }
}

impl Plan {
    /// Parses and validates a scene file's text; surface files are found
    /// relative to the current directory.
    pub fn from_toml(text: &str) -> Result<Plan> {
        let spec: SceneSpec =
            toml::from_str(text).map_err(|e| Error::Config(format!("scene file: {e}")))?;
        Plan::from_spec(&spec)
    }

    /// Validates a parsed scene; surface files are found relative to the
    /// current directory.
    pub fn from_spec(s: &SceneSpec) -> Result<Plan> {
        Plan::from_spec_at(s, Path::new(""))
    }

    /// Validates a parsed scene, reading surface files relative to `base`
    /// (the scene file's folder).
    pub fn from_spec_at(s: &SceneSpec, base: &Path) -> Result<Plan> {
        if !(s.mu0.is_finite() && s.mu0 >= 0.0) {
            return Err(Error::Config(format!(
                "mu0 must be finite and >= 0, got {}",
                s.mu0
            )));
        }
        let beta_deg = expand("beta_deg", &s.beta_deg)?;
        let loads = expand("load", &s.load)?;
        let mut surface_files = Vec::new();
        let lower = surface("lower", &s.lower, base, &mut surface_files)?;
        let upper = surface("upper", &s.upper, base, &mut surface_files)?;
        let springs = springs_of(s)?;
        loads_need_contact(&loads, &springs)?;
        let (velocity, duration) = motion_of(s)?;
        let hierarchy = hierarchy_of(s)?;
        let (wear, wear_samples) = match &s.wear {
            None => (None, 0),
            Some(w) => wear_of(w, &lower, &upper, velocity)?,
        };
        if hierarchy.as_ref().is_some_and(|h| h.wear) && wear.is_none() {
            return Err(Error::Config(
                "hierarchy.wear = true needs a [wear] table".into(),
            ));
        }
        let resolution = resolution_of(s)?;
        let outputs = outputs_of(s, wear.is_some(), hierarchy.is_some())?;
        Ok(Plan {
            mu0: s.mu0,
            beta_deg,
            loads,
            lower,
            upper,
            springs,
            wear,
            wear_samples,
            hierarchy,
            velocity,
            duration,
            resolution,
            outputs,
            surface_files,
        })
    }
}

/// Spring stiffnesses and rest length; k_t > 0 only with `[adhesion]`.
fn springs_of(s: &SceneSpec) -> Result<SpringParams> {
    let sp = s.springs.clone().unwrap_or(super::scene::SpringsSpec {
        k_c: None,
        l0: None,
    });
    let k_c = positive("springs.k_c", sp.k_c, 1.0)?;
    let l0 = sp.l0.unwrap_or(1.0);
    let k_t = match &s.adhesion {
        None => 0.0,
        Some(a) => k_c * positive("adhesion.k_t_over_k_c", a.k_t_over_k_c, 0.5)?,
    };
    let springs = SpringParams { k_c, l0, k_t };
    springs.validate()?;
    Ok(springs)
}

/// Without adhesion no spring carries tension, so a load ≤ 0 has no
/// contact.
fn loads_need_contact(loads: &[f64], springs: &SpringParams) -> Result<()> {
    if springs.k_t == 0.0 {
        if let Some(l) = loads.iter().find(|l| **l <= 0.0) {
            return Err(Error::Config(format!(
                "load {l} <= 0 needs [adhesion]: without it no spring carries tension and \
                 there is no contact"
            )));
        }
    }
    Ok(())
}

/// Sliding velocity and optional time-series length.
fn motion_of(s: &SceneSpec) -> Result<(f64, Option<f64>)> {
    let motion = s.motion.clone().unwrap_or(super::scene::MotionSpec {
        velocity: None,
        duration: None,
    });
    let velocity = positive("motion.velocity", motion.velocity, 1.0)?;
    let duration = match motion.duration {
        None => None,
        Some(d) => Some(positive("motion.duration", Some(d), 1.0)?),
    };
    Ok((velocity, duration))
}

/// Hierarchy levels (1..=64) and the scale between them (> 1).
fn hierarchy_of(s: &SceneSpec) -> Result<Option<HierarchyPlan>> {
    let Some(h) = &s.hierarchy else {
        return Ok(None);
    };
    if !(1..=64).contains(&h.levels) {
        return Err(Error::Config(format!(
            "hierarchy.levels must be in 1..=64, got {}",
            h.levels
        )));
    }
    let scale = positive("hierarchy.scale", h.scale, 10.0)?;
    if scale <= 1.0 {
        return Err(Error::Config(format!(
            "hierarchy.scale must be > 1 (outer levels are larger), got {scale}"
        )));
    }
    Ok(Some(HierarchyPlan {
        levels: h.levels,
        scale,
        wear: h.wear.unwrap_or(false),
    }))
}

/// Wear parameters and the number of wear instants (≥ 2); the reference
/// volume defaults to the asperity volume of both surfaces over the area.
fn wear_of(
    w: &super::scene::WearSpec,
    lower: &Surface,
    upper: &Surface,
    velocity: f64,
) -> Result<(Option<WearParams>, usize)> {
    let area = positive("wear.area", w.area, 1.0)?;
    let default_v0 = area * (lower.volume_above_valley() + upper.volume_above_valley());
    let v0 = match w.reference_volume {
        Some(v) => positive("wear.reference_volume", Some(v), 1.0)?,
        None if default_v0 > 0.0 => default_v0,
        None => {
            return Err(Error::Config(
                "wear: both surfaces are flat, there is no asperity volume to wear".into(),
            ))
        }
    };
    let p = WearParams {
        rate: w.rate,
        reference_volume: v0,
        velocity,
    };
    p.validate()?;
    let n = w.samples.unwrap_or(11);
    if n < 2 {
        return Err(Error::Config(format!("wear.samples must be >= 2, got {n}")));
    }
    Ok((Some(p), n))
}

/// Lattice counts (≥ 1), and either a spring count or a tolerance.
fn resolution_of(s: &SceneSpec) -> Result<Resolution> {
    let r = s
        .resolution
        .clone()
        .unwrap_or(super::scene::ResolutionSpec {
            springs: None,
            springs_y: None,
            steps: None,
            tolerance: None,
            max_points: None,
        });
    for (n, v) in [
        ("springs", r.springs),
        ("springs_y", r.springs_y),
        ("steps", r.steps),
    ] {
        if v == Some(0) {
            return Err(Error::Config(format!("resolution.{n} must be >= 1")));
        }
    }
    if let Some(t) = r.tolerance {
        positive("resolution.tolerance", Some(t), 1.0)?;
        if r.springs.is_some() {
            return Err(Error::Config(
                "resolution: give either springs or tolerance, not both".into(),
            ));
        }
    }
    Ok(Resolution {
        nx: r.springs,
        ny: r.springs_y,
        steps: r.steps,
        tolerance: r.tolerance,
        max_points: r.max_points.unwrap_or(1 << 16).max(16),
    })
}

/// Extra tables; wear and hierarchy tables need their sections.
fn outputs_of(s: &SceneSpec, has_wear: bool, has_hierarchy: bool) -> Result<Outputs> {
    let o = s.outputs.clone().unwrap_or_default();
    if o.wear && !has_wear {
        return Err(Error::Config("outputs.wear needs a [wear] table".into()));
    }
    if o.hierarchy && !has_hierarchy {
        return Err(Error::Config(
            "outputs.hierarchy needs a [hierarchy] table".into(),
        ));
    }
    Ok(o)
}

#[cfg(test)]
mod tests {
    use super::expand;
    use crate::simulate::alsfm::scene::{RangeSpec, Sweep};

    fn range(from: f64, to: f64, count: usize) -> Vec<f64> {
        expand("load", &Sweep::Range(RangeSpec { from, to, count })).unwrap()
    }

    #[test]
    fn a_range_ends_on_its_bounds_and_crosses_zero_at_zero() {
        // The adhesion example's loads: 0.1 + k (−0.12)/6 is −1.4e-17 at
        // k = 5 and −0.020000000000000004 at k = 6 in floating point.
        let v = range(0.1, -0.02, 7);
        assert_eq!(v.len(), 7);
        assert_eq!(v[0].to_bits(), 0.1f64.to_bits());
        assert_eq!(v[5].to_bits(), 0.0f64.to_bits());
        assert_eq!(v[6].to_bits(), (-0.02f64).to_bits());
        for (k, x) in v.iter().enumerate() {
            assert!((x - (0.1 - 0.02 * k as f64)).abs() < 1e-15, "{k}: {x}");
        }
        // A point near zero but above rounding stays.
        let w = range(-1.0, 1.001, 3);
        assert!((w[1] - 0.0005).abs() < 1e-15, "{w:?}");
        assert_eq!(range(-1.0, 3.0, 5), vec![-1.0, 0.0, 1.0, 2.0, 3.0]);
        let beta = range(0.0, 90.0, 7);
        assert_eq!(beta, vec![0.0, 15.0, 30.0, 45.0, 60.0, 75.0, 90.0]);
    }
}
