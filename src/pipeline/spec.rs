//! The pipeline file as written by the user (TOML), before validation.
//!
//! ```toml
//! [input]
//! files = ["../fixtures/friction/*.csv"]   # globs, relative to this file
//! samples = "../fixtures/friction/samples.csv"
//!
//! [output]
//! dir = "../out/demo"
//!
//! [ingest]                                 # for every file
//! columns = { friction_force = "Fx" }      # role = column
//! units = { Time = "s" }                   # column = unit
//!
//! [[ingest.override]]                      # for files matching a glob
//! files = "*.tsv"
//! format = "csm-pin-on-disc"
//!
//! [friction]                               # stage parameters
//! peak_noise_factor = 5.0
//! ```

use std::collections::BTreeMap;

use serde::{Deserialize, Serialize};

use crate::extract::friction::FrictionParams;
use crate::extract::roughness::stage::RoughnessSpec;
use crate::extract::tensile::TensileParams;
use crate::ingest::roles::Role;

/// The whole pipeline file.
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct PipelineSpec {
    /// Inputs.
    pub input: InputSpec,
    /// Where outputs go.
    pub output: OutputSpec,
    /// Ingestion options.
    #[serde(default)]
    pub ingest: IngestSpec,
    /// Stages to run, in order. Default: `["friction"]`.
    #[serde(default = "default_stages")]
    pub stages: Vec<String>,
    /// Friction stage parameters.
    #[serde(default)]
    pub friction: FrictionParams,
    /// Roughness stage settings.
    #[serde(default)]
    pub roughness: RoughnessSpec,
    /// Tensile stage parameters.
    #[serde(default)]
    pub tensile: TensileParams,
}

impl PipelineSpec {
    /// A one-stage pipeline over `files` (globs), writing to `out`, with
    /// default settings: what the single-stage commands (`tribo friction`,
    /// `tribo roughness`) build from their arguments.
    pub fn single_stage(
        stage: &str,
        files: Vec<String>,
        samples: Option<String>,
        out: String,
        format: Option<String>,
    ) -> Self {
        PipelineSpec {
            input: InputSpec { files, samples },
            output: OutputSpec { dir: out },
            ingest: IngestSpec {
                format,
                ..Default::default()
            },
            stages: vec![stage.to_string()],
            friction: Default::default(),
            roughness: Default::default(),
            tensile: Default::default(),
        }
    }
}

fn default_stages() -> Vec<String> {
    vec!["friction".into()]
}

/// `[input]`.
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct InputSpec {
    /// File globs, relative to the pipeline file.
    pub files: Vec<String>,
    /// The sample manifest, relative to the pipeline file.
    #[serde(default)]
    pub samples: Option<String>,
}

/// `[output]`.
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct OutputSpec {
    /// Output folder, relative to the pipeline file.
    pub dir: String,
}

/// `[ingest]`: options for reading files. The same table serves as the
/// default for every file and, in `[[ingest.override]]`, for the files whose
/// name or path matches the glob `files` (overrides apply in order, after
/// the defaults; they cannot nest).
#[derive(Debug, Clone, Default, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct IngestSpec {
    /// Only in an override: the glob matched against the file name and
    /// against the whole path.
    #[serde(default)]
    pub files: Option<String>,
    /// Reader name instead of sniffing.
    #[serde(default)]
    pub format: Option<String>,
    /// Column name for a role.
    #[serde(default)]
    pub columns: BTreeMap<Role, String>,
    /// Unit for a column name.
    #[serde(default)]
    pub units: BTreeMap<String, String>,
    /// Field delimiter instead of sniffing.
    #[serde(default)]
    pub delimiter: Option<char>,
    /// Decimal mark instead of sniffing.
    #[serde(default)]
    pub decimal: Option<char>,
    /// Per-glob overrides.
    #[serde(default, rename = "override")]
    pub overrides: Vec<IngestSpec>,
}
