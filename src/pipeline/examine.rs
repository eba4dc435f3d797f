//! One file as `tribo inspect` and the Python package see it: read as the
//! run would read it, with its kind (or why it has none). One function, so
//! the command line and `tribo.inspect` / `tribo.read` give the same
//! description and the same error.

use std::path::Path;

use crate::ingest::inspect::{inspect, Inspection};
use crate::ingest::source::Source;
use crate::ingest::{read_data, Dataset, IngestOptions, Reading};
use crate::pipeline::route::kind_of;
use crate::{Error, Result};

/// The file read as a run would read it; an error when it cannot be read
/// or is not a data file (with the reason the run's `files` table gives).
pub fn read_file(path: &Path, options: &IngestOptions) -> Result<Dataset> {
    let source = Source::open(path)?;
    match read_data(path, &source, None, options).1? {
        Reading::Data(ds) => Ok(ds),
        Reading::NotData(why) => Err(Error::NotApplicable(format!(
            "{}: not a data file: {why}",
            path.display()
        ))),
    }
}

/// The file's description and its kind: a stage's kind, or `none: ` and
/// why no stage would take it.
pub fn examine(path: &Path, options: &IngestOptions) -> Result<(Inspection, String)> {
    let ds = read_file(path, options)?;
    let kind = match kind_of(&ds, &Default::default()) {
        (Some(k), _) => k.to_string(),
        (None, why) => format!("none: {why}"),
    };
    Ok((inspect(&ds, &Default::default()), kind))
}

/// A file's description and kind as the JSON object of `tribo inspect
/// --json` (the description's fields and `kind`).
pub fn to_json(i: &Inspection, kind: &str) -> serde_json::Value {
    let mut v = serde_json::to_value(i).unwrap_or_default();
    if let Some(o) = v.as_object_mut() {
        o.insert("kind".into(), kind.into());
    }
    v
}
