//! The `friction` stage (MODELS.md §1): for each friction trace, the SI
//! trace of every section and its features — static peak, dynamic
//! plateau, stick-slip, strokes, velocity steps — as the tables
//! `friction`, `friction_steps`, `stickslip` and `traces`.
//!
//! ```toml
//! [friction]                      # every key optional (FrictionParams)
//! peak_noise_factor = 3.0
//! files = ["traces/*.csv"]        # optional: these files, whatever their kind
//! ```

use super::friction_tables::{friction_table, steps_table, stickslip_table, traces_table};
use super::{settings, Consumes, FileInput, Output, PlanContext, Stage, StagePlan, Tables};
use crate::error::Result;
use crate::extract::friction::{analyse_trace, FrictionParams, SampleInfo, TraceFeatures};
use crate::ingest::kind::DataKind;
use crate::ingest::radius::{track_radii, RadiusHints};
use crate::ingest::trace::{friction_traces, ManifestHints, Trace};
use crate::report::figures::{self, friction::FrictionTables};
use crate::status::Code;

/// The registry entry.
pub struct Friction;

/// Everything the stage produced for one file.
#[derive(Debug, Clone)]
pub struct FrictionFile {
    /// The path as given.
    pub source: String,
    /// Manifest information.
    pub sample: SampleInfo,
    /// One trace per section, in SI.
    pub traces: Vec<Trace>,
    /// Features per trace.
    pub features: Vec<TraceFeatures>,
}

impl Stage for Friction {
    fn name(&self) -> &'static str {
        "friction"
    }
    fn about(&self) -> &'static str {
        "static and dynamic friction, stick-slip, strokes and velocity steps of friction traces"
    }
    fn plan(&self, table: toml::Table, ctx: &PlanContext) -> Result<Box<dyn StagePlan>> {
        let params: FrictionParams = settings("friction", table)?;
        params.validate()?;
        Ok(Box::new(FrictionPlan {
            params,
            traces: ctx.traces,
            figures: ctx.figures,
        }))
    }
}

struct FrictionPlan {
    params: FrictionParams,
    traces: bool,
    figures: bool,
}

const TABLES: [&str; 4] = ["friction", "friction_steps", "stickslip", "traces"];

/// Reads the SI trace of every section of one file and extracts its
/// features. Errors are bad input (unknown unit, missing column); a trace
/// that reads but cannot be analysed gives rows with a status instead.
pub fn analyse_file(file: FileInput, params: &FrictionParams) -> Result<FrictionFile> {
    let sample = SampleInfo::from_manifest(file.manifest, file.path)?;
    // Each section's track radius: the manifest's, the file's, the stage
    // positions', the name's (ingest::radius).
    let radius_hints = RadiusHints::from_manifest(file.manifest, file.path)?;
    let hints = ManifestHints {
        normal_force_n: sample.normal_force_n,
        track_radius_m: None,
        radii: track_radii(&file.dataset, &radius_hints)?,
    };
    let traces = friction_traces(file.dataset, file.columns, &hints)?;
    let features = traces
        .iter()
        .map(|t| {
            let mut f = analyse_trace(t, &sample, params);
            doubt_named_radius(t, &mut f);
            f
        })
        .collect();
    Ok(FrictionFile {
        source: file.path.display().to_string(),
        sample,
        traces,
        features,
    })
}

/// A sliding speed from a track radius that only the file's name gives is
/// a guess about a name: every step of the trace says so.
fn doubt_named_radius(t: &Trace, f: &mut TraceFeatures) {
    let Some(r) = t.track_radius.filter(|r| r.source.from_file_name()) else {
        return;
    };
    let detail = format!(
        "the track radius {:.4} mm that turns rpm into the sliding speed comes from the file's name \
         (give track_radius_mm, track_centre_mm or step_track_radius_mm in the manifest)",
        r.radius_m * 1e3
    );
    for (_, s) in &mut f.steps {
        s.status.push(Code::RadiusFromFileName, detail.clone());
    }
}

impl StagePlan for FrictionPlan {
    fn name(&self) -> &'static str {
        "friction"
    }
    fn consumes(&self) -> Consumes {
        Consumes::Files(&[DataKind::FrictionTrace])
    }
    fn produces(&self) -> Vec<&'static str> {
        let n = if self.traces { 4 } else { 3 };
        let mut names = TABLES[..n].to_vec();
        if self.figures {
            names.push("friction_figures");
        }
        names
    }
    fn parameters(&self) -> serde_json::Value {
        serde_json::to_value(&self.params).unwrap_or_default()
    }
    fn references(&self) -> Vec<String> {
        vec!["MODELS.md §1 (friction traces)".into()]
    }
    fn run_file(&self, file: FileInput) -> Result<Tables> {
        let f = analyse_file(file, &self.params)?;
        let one = std::slice::from_ref(&f);
        let mut out = vec![
            ("friction", friction_table(one)?),
            ("friction_steps", steps_table(one)?),
            ("stickslip", stickslip_table(one)?),
        ];
        if self.figures {
            let drawn = figures::friction::figures(
                &f.source,
                &f.traces,
                &FrictionTables {
                    rows: &out[0].1,
                    steps: &out[1].1,
                    events: &out[2].1,
                },
            );
            out.push(("friction_figures", figures::to_table(&drawn)?));
        }
        if self.traces {
            out.push(("traces", traces_table(vec![f])?));
        }
        Ok(out)
    }
    fn assemble(&self, tables: Tables) -> Result<Output> {
        // A segment without either coefficient has no result.
        let without = both_null(&tables)?;
        let mut out = Output::new(tables);
        out.without_result = without;
        Ok(out)
    }
}

fn both_null(tables: &Tables) -> Result<usize> {
    let Some((_, t)) = tables.iter().find(|(n, _)| *n == "friction") else {
        return Ok(0);
    };
    let (s, d) = (t.f64("mu_static")?, t.f64("mu_dynamic")?);
    Ok(s.iter()
        .zip(&d)
        .filter(|(s, d)| s.is_none() && d.is_none())
        .count())
}
