//! The arguments every command over input files shares (`friction`,
//! `roughness`, `tensile`, `plot`), declared once and flattened into each.

use std::path::PathBuf;

use tribo::pipeline::spec::PipelineSpec;

use super::exec::params_file;

/// Input files, where the tables go and how the files are read.
#[derive(clap::Args, Debug)]
pub struct FileArgs {
    /// Input files (globs are expanded); `tribo inspect FILE` shows how a
    /// file is read.
    #[arg(required = true)]
    pub files: Vec<String>,
    /// Output folder for the tables, errors.parquet and report.html.
    #[arg(long, required = true)]
    pub out: Option<PathBuf>,
    /// Sample manifest CSV (file, sample_id, ... as in a pipeline's
    /// [input] samples), joined on the file name.
    #[arg(long)]
    pub samples: Option<PathBuf>,
    /// Force a reader instead of sniffing (e.g. cetr-umt, dektak,
    /// t150-nanosuite, delimited).
    #[arg(long)]
    pub format: Option<String>,
}

impl FileArgs {
    /// A pipeline of `stage` over the files.
    pub fn spec(&self, stage: &str) -> PipelineSpec {
        PipelineSpec::single_stage(
            stage,
            self.files.clone(),
            self.samples.as_ref().map(|p| p.display().to_string()),
            self.out
                .as_ref()
                .map(|o| o.display().to_string())
                .unwrap_or_default(),
            self.format.clone(),
        )
    }
}

/// [`FileArgs`] and the settings of the one stage the command runs.
#[derive(clap::Args, Debug)]
pub struct StageArgs {
    /// Files, output, samples, reader.
    #[command(flatten)]
    pub files: FileArgs,
    /// The stage's settings as a TOML file, with the keys of the stage's
    /// table in a pipeline file ([friction], [roughness], [tensile]).
    #[arg(long)]
    pub params: Option<PathBuf>,
}

impl StageArgs {
    /// A pipeline of `stage` over the files, with the settings of
    /// `--params`.
    pub fn spec(&self, stage: &str) -> tribo::Result<PipelineSpec> {
        let mut spec = self.files.spec(stage);
        *spec.settings_mut(stage) = params_file(self.params.as_deref())?;
        Ok(spec)
    }
}
