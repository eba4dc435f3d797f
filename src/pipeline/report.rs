//! The report of an output set: rendered from the set's tables when a run
//! publishes it (written into the set, so it never disagrees with the
//! tables), or again from a published folder (`tribo report`).

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use rayon::prelude::*;

use super::atomic::{write_atomic, write_docs, Doc};
use super::dataset::read_table;
use super::keys::{Key, KeyBuilder};
use super::lock::Lock;
use super::publish::{replace_with_link, OutputSet};
use super::registry;
use super::state::{stamped_file, TableState};
use crate::error::{Error, Result};
use crate::report;
use crate::schema::{Show, TableDef};
use crate::table::Table;

/// The report's file name in the output folder.
pub const REPORT: &str = "report.html";

/// The run's name in the report's title: the output folder's name.
pub(super) fn title(out: &Path) -> String {
    let out = std::fs::canonicalize(out).unwrap_or_else(|_| out.to_path_buf());
    out.file_name().map_or_else(
        || out.display().to_string(),
        |n| n.to_string_lossy().to_string(),
    )
}

/// Where the state records the report's pages of file sections: each as
/// `report/pages/<page>`, with its outline's key and its file's stamp.
const PAGES_STATE: &str = "report/pages";

/// Renders the report of `tables` into the set being written, the figure
/// tables `kept` holds read a page at a time. A page of file sections
/// whose outline ([`report::Report::outline`]) is the one `last` records
/// for the published page, which is as it was written, is linked from
/// there, neither rendered nor read: when one file is added to an archive,
/// only its page is. Returns each page's state (its outline's key).
pub(super) fn write(
    set: &mut OutputSet,
    out: &Path,
    tables: &BTreeMap<String, Table>,
    kept: report::FigureFiles,
    last: &BTreeMap<String, TableState>,
) -> Result<Vec<(String, TableState)>> {
    let defs = registry::all();
    let r = report::render(tables, &defs, &title(out), kept)?;
    set.write_document(REPORT, r.index.as_bytes())?;
    let n = r.pages();
    if n == 0 {
        return Ok(Vec::new());
    }
    let keys: Vec<Key> = (0..n)
        .into_par_iter()
        .map(|i| KeyBuilder::new("report page").part(&r.outline(i)).finish())
        .collect();
    let published = std::fs::canonicalize(out.join(report::PAGES_DIR)).ok();
    let unchanged = |i: usize| {
        let old = last.get(&page_state(&r.page_name(i)));
        let dir = published.as_ref();
        old.zip(dir)
            .is_some_and(|(o, d)| o.is_file(&d.join(r.page_name(i)), keys[i]))
    };
    let dir = set.write_folder(report::PAGES_DIR, n, |i| match unchanged(i) {
        true => Ok(Doc::Kept(r.page_name(i))),
        false => r.page(i).map(|(name, html)| Doc::Made(name, html)),
    })?;
    // Each page's state from its file in the new set, kept pages too: one
    // is copied where the folder takes no hard link, with a new time.
    (0..n)
        .map(|i| {
            let page = dir.join(r.page_name(i));
            let state = TableState::of_file(&page, keys[i]);
            let missing = || Error::io(&page, std::io::ErrorKind::NotFound.into());
            Ok((page_state(&r.page_name(i)), state.ok_or_else(missing)?))
        })
        .collect()
}

/// The name of a page's state: `report/pages/<page>`.
fn page_state(page: &str) -> String {
    format!("{PAGES_STATE}/{page}")
}

/// The pages' states in `last` (a report kept keeps them).
pub(super) fn page_states(last: &BTreeMap<String, TableState>) -> Vec<(String, TableState)> {
    let prefix = page_state("");
    let after = last.range(prefix.clone()..);
    after
        .take_while(|(k, _)| k.starts_with(&prefix))
        .map(|(k, s)| (k.clone(), s.clone()))
        .collect()
}

/// Whether `OUT/report` holds the pages the last run published with its
/// report, each as it was written, and no other (a report kept without
/// them would link to nothing; one edited by hand is made again).
pub(super) fn pages_intact(out: &Path, pages: &[(String, TableState)]) -> bool {
    if pages.is_empty() {
        return true;
    }
    let dir = out.join(report::PAGES_DIR);
    let listed = std::fs::read_dir(&dir).map_or(0, |d| d.flatten().count());
    let prefix = page_state("");
    listed == pages.len()
        && pages.iter().all(|(name, s)| {
            let file = dir.join(name.strip_prefix(&prefix).unwrap_or(name));
            s.is_file(&file, s.key)
        })
}

/// Renders the report of the set published in `out` again, in place, from
/// the tables the run rendered it from (those it shows or with a status,
/// whose doubts it counts), and returns its path. Takes the folder's lock (waiting up to `wait`).
pub fn rewrite(out: &Path, wait: std::time::Duration) -> Result<PathBuf> {
    let current = out.join(".tribo").join("current");
    if !current.is_dir() {
        return Err(Error::Config(format!(
            "{}: no published output set here (run a pipeline into it first)",
            out.display()
        )));
    }
    let _lock = Lock::take(out, wait)?;
    let defs = registry::all();
    let mut tables = BTreeMap::new();
    for def in published(&defs, &current, |d| d.in_report() || d.has_status()) {
        tables.insert(def.name.to_string(), read_table(&def.path_in(out))?);
    }
    let r = report::render(&tables, &defs, &title(out), report::FigureFiles::none())?;
    rewrite_pages(out, &current, &r)?;
    let path = current.join(REPORT);
    write_atomic(&path, |w| {
        use std::io::Write as _;
        w.write_all(r.index.as_bytes())
            .map_err(|e| Error::io(&path, e))
    })?;
    let link = out.join(REPORT);
    if std::fs::read_link(&link).is_err() {
        replace_with_link(&link, &Path::new(".tribo").join("current").join(REPORT))?;
    }
    Ok(link)
}

/// The report's pages of the current set `current` replaced by `r`'s:
/// written into a folder of their own, renamed into place (the old
/// folder moved aside first, then removed), linked from `OUT/report`
/// (the link removed when there are none).
fn rewrite_pages(out: &Path, current: &Path, r: &report::Report) -> Result<()> {
    let dir = current.join(report::PAGES_DIR);
    let pid = std::process::id();
    let aside = current.join(format!(".{}.old.{pid}", report::PAGES_DIR));
    if dir.exists() {
        std::fs::rename(&dir, &aside).map_err(|e| Error::io(&dir, e))?;
    }
    let link = out.join(report::PAGES_DIR);
    if r.pages() == 0 {
        if std::fs::read_link(&link).is_ok() {
            let _ = std::fs::remove_file(&link);
        }
    } else {
        let new = current.join(format!(".{}.new.{pid}", report::PAGES_DIR));
        let page = |i| r.page(i).map(|(name, html)| Doc::Made(name, html));
        write_docs(&new, r.pages(), page, Some(&aside))?;
        std::fs::rename(&new, &dir).map_err(|e| Error::io(&dir, e))?;
        if std::fs::read_link(&link).is_err() {
            let to = Path::new(".tribo").join("current").join(report::PAGES_DIR);
            replace_with_link(&link, &to)?;
        }
    }
    let _ = std::fs::remove_dir_all(&aside);
    Ok(())
}

/// Writes every figure of the set published in `out` as an SVG file in
/// `dest` (`<file stem>[-<part>]-<figure>.svg`); returns the paths.
pub fn export_figures(out: &Path, dest: &Path) -> Result<Vec<PathBuf>> {
    std::fs::create_dir_all(dest).map_err(|e| Error::io(dest, e))?;
    let mut written = Vec::new();
    let defs = registry::all();
    for def in published(&defs, out, |d| d.show == Show::Figures) {
        let t = read_table(&def.path_in(out))?;
        let col = |c: &str| report::figures::texts(&t, c);
        let (source, part, figure, svg) = (col("source"), col("part"), col("figure"), col("svg"));
        for i in 0..t.height() {
            let stem = Path::new(&source[i])
                .file_stem()
                .map_or(source[i].clone(), |s| s.to_string_lossy().to_string());
            let name = match part[i].is_empty() {
                true => format!("{stem}-{}", figure[i]),
                false => format!("{stem}-{}-{}", part[i], figure[i]),
            };
            let safe: String = name
                .chars()
                .map(|c| {
                    if c.is_alphanumeric() || "-_.".contains(c) {
                        c
                    } else {
                        '_'
                    }
                })
                .collect();
            let file = dest.join(format!("{safe}.svg"));
            write_atomic(&file, |w| {
                use std::io::Write as _;
                w.write_all(svg[i].as_bytes())
                    .map_err(|e| Error::io(&file, e))
            })?;
            written.push(file);
        }
    }
    Ok(written)
}

/// The tables of `defs` that `filter` takes and `dir` holds (a table's
/// file, or a dataset's manifest): a published set, or an output folder.
fn published<'a>(
    defs: &'a [&'static TableDef],
    dir: &'a Path,
    filter: impl Fn(&TableDef) -> bool + 'a,
) -> impl Iterator<Item = &'static TableDef> + 'a {
    defs.iter()
        .copied()
        .filter(move |d| filter(d) && stamped_file(dir, d).exists())
}
