//! The report of an output set: rendered from the set's tables when a run
//! publishes it (written into the set, so it never disagrees with the
//! tables), or again from a published folder (`tribo report`).

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use super::lock::Lock;
use super::publish::{replace_with_link, write_atomic, OutputSet};
use crate::error::{Error, Result};
use crate::report;
use crate::table::Table;

/// The report's file name in the output folder.
pub const REPORT: &str = "report.html";

/// The run's name in the report's title: the output folder's name.
fn title(out: &Path) -> String {
    out.file_name()
        .map_or_else(|| out.display().to_string(), |n| n.to_string_lossy().to_string())
}

/// Renders the report of `tables` into the set being written.
pub(super) fn write(set: &mut OutputSet, out: &Path, tables: &BTreeMap<String, Table>) -> Result<()> {
    let html = report::render(tables, &title(out))?;
    set.write_document(REPORT, html.as_bytes())
}

/// Renders the report of the set published in `out` again, in place, and
/// returns its path. Takes the folder's lock (waiting up to `wait`).
pub fn rewrite(out: &Path, wait: std::time::Duration) -> Result<PathBuf> {
    let current = out.join(".tribo").join("current");
    if !current.is_dir() {
        return Err(Error::Config(format!(
            "{}: no published output set here (run a pipeline into it first)",
            out.display()
        )));
    }
    let _lock = Lock::take(out, wait)?;
    let mut tables = BTreeMap::new();
    for e in std::fs::read_dir(&current).map_err(|e| Error::io(&current, e))?.flatten() {
        let name = e.file_name().to_string_lossy().to_string();
        if let Some(t) = name.strip_suffix(".parquet").filter(|t| report::reads(t)) {
            tables.insert(t.to_string(), Table::read_parquet(&e.path())?.0);
        }
    }
    let html = report::render(&tables, &title(out))?;
    let path = current.join(REPORT);
    write_atomic(&path, |w| {
        use std::io::Write as _;
        w.write_all(html.as_bytes()).map_err(|e| Error::io(&path, e))
    })?;
    let link = out.join(REPORT);
    if std::fs::read_link(&link).is_err() {
        replace_with_link(&link, &Path::new(".tribo").join("current").join(REPORT))?;
    }
    Ok(link)
}
