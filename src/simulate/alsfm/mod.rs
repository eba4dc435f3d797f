//! ALSFM simulations (thesis Ch. 1–2, MODELS.md §5): a scene file
//! ([`scene`]) is validated into a [`plan::Plan`], which [`run`] evaluates
//! point by point on the cheapest exact path
//! ([`crate::models::alsfm::solver`]), producing the rows of
//! [`rows::AlsfmOutput`] and its tables.
//!
//! ```no_run
//! let plan = tribo::simulate::alsfm::plan::Plan::from_toml(
//!     &std::fs::read_to_string("fixtures/alsfm/wedges_beta_sweep.toml")?,
//! )?;
//! let out = tribo::simulate::alsfm::run(&plan)?;
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

pub mod driver;
pub mod plan;
pub mod rows;
pub mod scene;
pub mod surface_file;

pub use driver::run;
pub use rows::AlsfmOutput;

use std::path::Path;

use crate::error::{Error, Result};
use crate::hash::InputHash;

/// Equations and sources an ALSFM run uses (written into the provenance).
pub const REFERENCES: &[&str] = &[
    "MODELS.md §5 (ALSFM)",
    "thesis Eq. 1.10-1.22 (wedge closed forms), 1.27-1.28 (local law), 1.29-1.35 (sums), 1.41-1.42 (2-D)",
    "thesis Eq. 2.1-2.2 (adhesion), 2.5-2.9 (wear), 2.10-2.19 (hierarchy)",
];

/// Reads and validates a scene file. Returns the plan, the spec as read
/// (for the provenance) and the hashes of the scene and its surface files.
pub fn load_scene(scene: &Path) -> Result<(plan::Plan, scene::SceneSpec, Vec<InputHash>)> {
    let bytes = std::fs::read(scene).map_err(|e| Error::io(scene, e))?;
    let text = String::from_utf8(bytes.clone()).map_err(|_| {
        Error::Config(format!(
            "{}: the scene file is not UTF-8 text",
            scene.display()
        ))
    })?;
    let spec: scene::SceneSpec =
        toml::from_str(&text).map_err(|e| Error::Config(format!("{}: {e}", scene.display())))?;
    let base = scene.parent().unwrap_or(Path::new(""));
    let plan = plan::Plan::from_spec_at(&spec, base)
        .map_err(|e| Error::Config(format!("{}: {e}", scene.display())))?;
    let mut hashes = vec![InputHash::of_bytes(scene, &bytes)];
    hashes.extend(plan.surface_files.iter().cloned());
    Ok((plan, spec, hashes))
}

/// The resolved defaults of a plan (k_t, V0, velocity, …), recorded with
/// the scene in the provenance.
pub fn resolved(plan: &plan::Plan) -> serde_json::Value {
    serde_json::json!({
        "k_c": plan.springs.k_c,
        "k_t": plan.springs.k_t,
        "l0": plan.springs.l0,
        "velocity_m_per_s": plan.velocity,
        "wear": plan.wear,
        "hierarchy": plan.hierarchy,
        "case2_closed_form_margin": 1.1,
    })
}
