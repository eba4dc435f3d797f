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

use std::path::{Path, PathBuf};

use crate::error::{Error, Result};
use crate::report::{InputHash, Provenance};

/// What a scene-file run wrote.
#[derive(Debug, Clone)]
pub struct RunSummary {
    /// The rows.
    pub output: AlsfmOutput,
    /// Tables written.
    pub written: Vec<PathBuf>,
    /// Scene points whose status is not `ok`.
    pub failures: usize,
}

/// Equations and sources an ALSFM run uses (written into the provenance).
pub const REFERENCES: &[&str] = &[
    "MODELS.md §5 (ALSFM)",
    "thesis Eq. 1.10-1.22 (wedge closed forms), 1.27-1.28 (local law), 1.29-1.35 (sums), 1.41-1.42 (2-D)",
    "thesis Eq. 2.1-2.2 (adhesion), 2.5-2.9 (wear), 2.10-2.19 (hierarchy)",
];

/// Reads a scene file, validates it, runs it and writes the tables into
/// `out` (created if missing). The provenance holds the scene, the resolved
/// defaults (k_t, V0, velocity) and the scene file's SHA-256.
pub fn run_scene_file(scene: &Path, out: &Path) -> Result<RunSummary> {
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
    let output = run(&plan)?;
    std::fs::create_dir_all(out).map_err(|e| Error::io(out, e))?;
    let mut prov = Provenance::new(
        "simulate alsfm",
        serde_json::json!({
            "scene": spec,
            "resolved": {
                "k_c": plan.springs.k_c,
                "k_t": plan.springs.k_t,
                "l0": plan.springs.l0,
                "velocity_m_per_s": plan.velocity,
                "wear": plan.wear,
                "hierarchy": plan.hierarchy,
                "case2_closed_form_margin": 1.1,
            }
        }),
    );
    prov.inputs.push(InputHash::of_bytes(scene, &bytes));
    prov.inputs.extend(plan.surface_files.iter().cloned());
    prov.references = REFERENCES.iter().map(|s| s.to_string()).collect();
    let written = output.write(out, &prov)?;
    let failures = output.failures();
    Ok(RunSummary {
        output,
        written,
        failures,
    })
}
