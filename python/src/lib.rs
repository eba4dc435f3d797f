//! The `tribo._tribo` extension: thin calls into the tribo library. Tables
//! cross into Python as the Parquet files a run publishes (read there with
//! polars), so the numbers, units and provenance are exactly the CLI's.

use std::path::{Path, PathBuf};

use pyo3::create_exception;
use pyo3::exceptions::PyException;
use pyo3::prelude::*;
use pyo3::types::PyBytes;

use tribo::ingest::IngestOptions;
use tribo::pipeline::examine::{examine, read_file, to_json};
use tribo::pipeline::spec::PipelineSpec;
use tribo::pipeline::{run, Plan, RunReport};

create_exception!(
    _tribo,
    TriboError,
    PyException,
    "A file or setting tribo cannot use; the message names the file, line and column."
);

fn err(e: tribo::Error) -> PyErr {
    TriboError::new_err(e.to_string())
}

fn options(format: Option<String>) -> IngestOptions {
    IngestOptions {
        format,
        ..Default::default()
    }
}

/// The structure of one export as JSON (`tribo inspect --json`).
#[pyfunction]
#[pyo3(signature = (path, format=None))]
fn inspect(py: Python<'_>, path: PathBuf, format: Option<String>) -> PyResult<String> {
    py.detach(|| {
        let (i, kind) = examine(&path, &options(format)).map_err(err)?;
        serde_json::to_string(&to_json(&i, &kind)).map_err(|e| TriboError::new_err(e.to_string()))
    })
}

/// One section's columns: (name, SI unit symbol, values in SI).
type Columns = Vec<(String, String, Vec<f64>)>;

/// The decoded channel of a map or profile: its name, unit, (nx, ny),
/// (dx, dy, x0, y0) in metres, its values as little-endian f64 bytes
/// (row-major; NaN where nothing was measured), the count of those, every
/// channel's (name, unit, decoded), and the file's metadata.
type Grid = (
    String,
    String,
    (usize, usize),
    (f64, f64, f64, f64),
    Py<PyBytes>,
    usize,
    Vec<(String, String, bool)>,
    Vec<(String, String)>,
);

/// Every section of an export with each channel converted to SI (a
/// channel without a unit is kept as written, unit ""), and the decoded
/// channel of a map or profile file (the height channel, or `channel`).
#[pyfunction]
#[pyo3(signature = (path, format=None, channel=None))]
fn read(
    py: Python<'_>,
    path: PathBuf,
    format: Option<String>,
    channel: Option<String>,
) -> PyResult<(Vec<(String, Columns)>, Option<Grid>)> {
    let o = IngestOptions {
        channel,
        ..options(format)
    };
    let ds = py.detach(|| read_file(&path, &o).map_err(err))?;
    let mut out = Vec::with_capacity(ds.sections.len());
    for s in &ds.sections {
        let mut cols = Vec::with_capacity(s.channels.len());
        for c in &s.channels {
            let (si, values) = match c.unit(&path).map_err(err)? {
                Some(u) => (
                    u.quantity.si_symbol().to_string(),
                    c.values.iter().map(|&v| u.to_si(v)).collect(),
                ),
                None => (String::new(), c.values.clone()),
            };
            cols.push((c.name.clone(), si, values));
        }
        out.push((s.name.clone(), cols));
    }
    let grid = ds.grids.iter().find(|g| g.data.is_some()).map(|g| {
        let d = g.data.as_ref().expect("found decoded");
        let raw: Vec<u8> = d.values.iter().flat_map(|v| v.to_le_bytes()).collect();
        let channels = ds.grids.iter();
        (
            g.name.clone(),
            g.unit.clone(),
            (g.nx, g.ny),
            (g.dx, g.dy, g.x0, g.y0),
            PyBytes::new(py, &raw).unbind(),
            d.n_invalid,
            channels
                .map(|c| (c.name.clone(), c.unit.clone(), c.data.is_some()))
                .collect(),
            ds.preamble
                .iter()
                .map(|m| (m.key.clone(), m.value.clone()))
                .collect(),
        )
    });
    Ok((out, grid))
}

/// What a run produced: the published Parquet files and the CLI's JSON
/// summary.
fn outcome(report: RunReport) -> (Vec<PathBuf>, String) {
    (report.outputs.clone(), report.summary_json())
}

/// Runs a validated plan without progress output.
fn execute(plan: &Plan, command: &str) -> PyResult<(Vec<PathBuf>, String)> {
    run(plan, command, &|| {}).map(outcome).map_err(err)
}

/// Runs one stage as its CLI command does: `settings_json` holds the keys
/// of the stage's table in a pipeline file.
#[pyfunction]
#[pyo3(signature = (stage, files, out, samples=None, format=None, settings_json="{}", traces=true))]
#[allow(clippy::too_many_arguments)]
fn run_stage(
    py: Python<'_>,
    stage: &str,
    files: Vec<String>,
    out: String,
    samples: Option<String>,
    format: Option<String>,
    settings_json: &str,
    traces: bool,
) -> PyResult<(Vec<PathBuf>, String)> {
    let settings: toml::Table = serde_json::from_str::<serde_json::Value>(settings_json)
        .map_err(|e| e.to_string())
        .and_then(|v| toml::Table::try_from(v).map_err(|e| e.to_string()))
        .map_err(|e| TriboError::new_err(format!("{stage} settings: {e}")))?;
    let mut spec = PipelineSpec::single_stage(stage, files, samples, out, format);
    spec.output.traces = traces;
    *spec.settings_mut(stage) = settings;
    py.detach(|| execute(&Plan::from_spec(&spec, Path::new("")).map_err(err)?, stage))
}

/// Runs a pipeline file (`tribo run FILE [--out DIR]`).
#[pyfunction]
#[pyo3(signature = (path, out=None))]
fn run_file(
    py: Python<'_>,
    path: PathBuf,
    out: Option<PathBuf>,
) -> PyResult<(Vec<PathBuf>, String)> {
    py.detach(|| {
        let mut plan = Plan::from_file(&path).map_err(err)?;
        if let Some(out) = out {
            plan.out_dir = out;
        }
        execute(&plan, "run")
    })
}

/// The compiled half of the `tribo` Python package.
#[pymodule]
fn _tribo(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("TriboError", m.py().get_type::<TriboError>())?;
    m.add_function(wrap_pyfunction!(inspect, m)?)?;
    m.add_function(wrap_pyfunction!(read, m)?)?;
    m.add_function(wrap_pyfunction!(run_stage, m)?)?;
    m.add_function(wrap_pyfunction!(run_file, m)?)?;
    Ok(())
}
