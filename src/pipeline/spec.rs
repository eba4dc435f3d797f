//! The pipeline file as written by the user (TOML), before validation.
//!
//! ```toml
//! stages = ["friction", "roughness", "coulomb"]  # run order follows the needs
//!
//! [input]
//! files = ["../lab/**/*"]                  # globs, relative to this file
//! samples = "../lab/samples.csv"           # the sample manifest
//! strict = false                           # true: an unmatched row is an error
//!
//! [output]
//! dir = "../out/demo"
//! traces = true                            # the per-sample traces table
//! report = true                            # figures and report.html
//!
//! [ingest]                                 # for every file
//! columns = { friction_force = "Fx" }      # role = column
//! units = { Time = "s" }                   # column = unit
//! force = false                            # true: even against the file's unit
//!
//! [[ingest.override]]                      # for files matching a glob
//! files = "*.tsv"
//! format = "csm-pin-on-disc"
//! channel = "Intensity"                    # a binary file's channel (default: heights)
//!
//! [friction]                               # one table per stage
//! peak_noise_factor = 5.0
//! files = ["sled/*.csv"]                   # per-file stages: these files only
//!
//! [coulomb]
//! by = ["pattern"]
//! inputs = { friction = "old/friction.parquet" }  # table stages: a table from a file
//! ```
//!
//! Each stage validates its own table ([`crate::stages::Stage::plan`]);
//! `files` and `inputs` are the pipeline's and are taken out first.

use std::collections::BTreeMap;
use std::path::Path;

use serde::{Deserialize, Serialize};

use crate::error::{Error, Result};
use crate::ingest::roles::Role;
use crate::ingest::IngestOptions;
use crate::stages;

/// The whole pipeline file.
#[derive(Debug, Clone, Serialize)]
pub struct PipelineSpec {
    /// Stages to run. Default: `["friction"]`.
    pub stages: Vec<String>,
    /// Inputs.
    pub input: InputSpec,
    /// Where outputs go.
    pub output: OutputSpec,
    /// Ingestion options.
    pub ingest: IngestSpec,
    /// Each stage's table, by stage name.
    pub settings: BTreeMap<String, toml::Table>,
}

/// The keys of a pipeline file that are not stage tables.
const TOP_KEYS: [&str; 4] = ["stages", "input", "output", "ingest"];

impl PipelineSpec {
    /// Parses a pipeline file's text; `origin` names it in errors.
    pub fn from_toml(text: &str, origin: &Path) -> Result<PipelineSpec> {
        let cfg = |e: String| Error::Config(format!("{}: {e}", origin.display()));
        let mut root: toml::Table = toml::from_str(text).map_err(|e| cfg(e.to_string()))?;
        fn take<T: serde::de::DeserializeOwned>(
            root: &mut toml::Table,
            key: &str,
        ) -> std::result::Result<Option<T>, toml::de::Error> {
            root.remove(key).map(toml::Value::try_into).transpose()
        }
        let stages: Option<Vec<String>> =
            take(&mut root, "stages").map_err(|e| cfg(format!("stages: {e}")))?;
        let input: Option<InputSpec> =
            take(&mut root, "input").map_err(|e| cfg(format!("[input]: {e}")))?;
        let output: Option<OutputSpec> =
            take(&mut root, "output").map_err(|e| cfg(format!("[output]: {e}")))?;
        let ingest: Option<IngestSpec> =
            take(&mut root, "ingest").map_err(|e| cfg(format!("[ingest]: {e}")))?;
        if let Some(i) = &ingest {
            i.check_keys().map_err(|e| cfg(format!("[ingest]: {e}")))?;
        }
        let output = output.ok_or_else(|| cfg("no [output] table; expected dir = \"…\"".into()))?;
        let mut settings = BTreeMap::new();
        for (key, value) in root {
            if stages::find(&key).is_none() {
                return Err(cfg(format!(
                    "unknown table or key '{key}'; expected {} or a stage: {}",
                    TOP_KEYS.join(", "),
                    stages::names()
                )));
            }
            let toml::Value::Table(t) = value else {
                return Err(cfg(format!("'{key}' must be a table ([{key}])")));
            };
            settings.insert(key, t);
        }
        let spec = PipelineSpec {
            stages: stages.unwrap_or_else(|| vec!["friction".into()]),
            input: input.unwrap_or_default(),
            output,
            ingest: ingest.unwrap_or_default(),
            settings,
        };
        spec.check_stage_names().map_err(|e| cfg(e.to_string()))?;
        Ok(spec)
    }

    /// Every listed stage exists, once; every stage table belongs to a
    /// listed stage (a table for a stage that does not run is a typo).
    fn check_stage_names(&self) -> Result<()> {
        for (i, s) in self.stages.iter().enumerate() {
            if stages::find(s).is_none() {
                return Err(Error::Config(format!(
                    "unknown stage '{s}'; known stages: {}",
                    stages::names()
                )));
            }
            if self.stages[..i].contains(s) {
                return Err(Error::Config(format!("stage '{s}' is listed twice")));
            }
        }
        if let Some(k) = self.settings.keys().find(|k| !self.stages.contains(k)) {
            return Err(Error::Config(format!(
                "[{k}] is given but '{k}' is not in stages = {:?}",
                self.stages
            )));
        }
        Ok(())
    }

    /// A one-stage pipeline over `files` (globs), writing to `out`: what the
    /// single-stage commands build from their arguments.
    pub fn single_stage(
        stage: &str,
        files: Vec<String>,
        samples: Option<String>,
        out: String,
        format: Option<String>,
    ) -> Self {
        PipelineSpec {
            stages: vec![stage.to_string()],
            input: InputSpec {
                files,
                samples,
                strict: false,
            },
            output: OutputSpec {
                dir: out,
                traces: true,
                report: true,
            },
            ingest: IngestSpec {
                options: IngestOptions {
                    format,
                    ..Default::default()
                },
                ..Default::default()
            },
            settings: BTreeMap::new(),
        }
    }

    /// The settings of `stage`, to fill from command-line flags.
    pub fn settings_mut(&mut self, stage: &str) -> &mut toml::Table {
        self.settings.entry(stage.to_string()).or_default()
    }
}

/// `[input]`.
#[derive(Debug, Clone, Default, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct InputSpec {
    /// File globs, relative to the pipeline file. A path without glob
    /// characters names a file: if no stage takes it, that is an error.
    #[serde(default)]
    pub files: Vec<String>,
    /// The sample manifest, relative to the pipeline file.
    #[serde(default)]
    pub samples: Option<String>,
    /// A manifest row that matches no input file is an error (else a
    /// warning: a lab's sample sheet may list more files than a run reads).
    #[serde(default)]
    pub strict: bool,
}

/// `[output]`.
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct OutputSpec {
    /// Output folder, relative to the pipeline file.
    pub dir: String,
    /// Write the per-sample `traces` table (the largest). Default true.
    #[serde(default = "yes")]
    pub traces: bool,
    /// Draw each stage's figures and write `report.html` with the set.
    /// Default true.
    #[serde(default = "yes")]
    pub report: bool,
}

fn yes() -> bool {
    true
}

/// `[ingest]`: options for reading files. The same table serves as the
/// default for every file and, in `[[ingest.override]]`, for the files whose
/// name or path matches the glob `files` (overrides apply in order, after
/// the defaults; they cannot nest). Besides its own keys it holds the
/// reading options themselves, [`IngestOptions`], with their key names.
#[derive(Debug, Clone, Default, Deserialize, Serialize)]
pub struct IngestSpec {
    /// Only in an override: the glob matched against the file name and
    /// against the whole path.
    #[serde(default)]
    pub files: Option<String>,
    /// Column name for a role.
    #[serde(default)]
    pub columns: BTreeMap<Role, String>,
    /// How to read the files.
    #[serde(flatten)]
    pub options: IngestOptions,
    /// Per-glob overrides.
    #[serde(default, rename = "override")]
    pub overrides: Vec<IngestSpec>,
    /// Keys that are none of the above, refused by [`IngestSpec::check_keys`]
    /// (`deny_unknown_fields` does not work with a flattened field).
    #[serde(flatten, skip_serializing)]
    unknown: BTreeMap<String, toml::Value>,
}

impl IngestSpec {
    /// Refuses a key that is neither this table's nor an [`IngestOptions`]
    /// key, naming it and the keys expected (those of overrides too).
    fn check_keys(&self) -> std::result::Result<(), String> {
        if !self.unknown.is_empty() {
            // The options' own error names the key and lists their keys.
            let table = toml::Value::Table(self.unknown.clone().into_iter().collect());
            if let Err(e) = table.try_into::<IngestOptions>() {
                return Err(format!(
                    "{}, or `files`, `columns`, `override`",
                    e.to_string().trim_end()
                ));
            }
        }
        self.overrides.iter().try_for_each(IngestSpec::check_keys)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse(text: &str) -> Result<PipelineSpec> {
        PipelineSpec::from_toml(text, Path::new("p.toml"))
    }

    #[test]
    fn ingest_reads_the_options_and_refuses_unknown_keys() {
        let head = "[output]\ndir = \"out\"\n";
        let s = parse(&format!(
            "{head}[ingest]\ndecimal = \",\"\ncolumns = {{ normal_force = \"Fz\" }}\n\
             [[ingest.override]]\nfiles = \"*.tsv\"\nformat = \"generic\"\nforce = true\n"
        ))
        .unwrap();
        assert_eq!(s.ingest.options.decimal, Some(','));
        assert_eq!(s.ingest.columns.get(&Role::NormalForce).unwrap(), "Fz");
        let ov = &s.ingest.overrides[0];
        assert_eq!(ov.files.as_deref(), Some("*.tsv"));
        assert_eq!(ov.options.format.as_deref(), Some("generic"));
        assert!(ov.options.force && !s.ingest.options.force);
        for table in [
            "[ingest]\ncolour = 1\n",
            "[[ingest.override]]\nfiles = \"*\"\ncolour = 1\n",
        ] {
            let e = parse(&format!("{head}{table}")).unwrap_err().to_string();
            for word in ["p.toml", "[ingest]", "`colour`", "`format`", "`override`"] {
                assert!(e.contains(word), "expected {word} in: {e}");
            }
        }
    }
}
