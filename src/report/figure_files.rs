//! Figure tables the report reads from files, a page's files at a time,
//! instead of taking them whole: the figures of every input of an archive
//! are most of what a report reads (a file per input, about 1 GB in memory
//! at 20 000 friction traces), and a page that did not change needs none
//! of them.

use std::collections::BTreeMap;
use std::path::PathBuf;

use crate::error::Result;
use crate::table::Table;

/// Where a source's rows of a figure table are: `(table, source)` to the
/// file holding those rows alone (`None`: the source has none).
type Locate<'a> = dyn Fn(&str, &str) -> Option<PathBuf> + Sync + 'a;

/// The figure tables kept in files, with where each source's rows are. A
/// file's name must name its content (as a cache part's, its key, does):
/// two pages whose files have the same names show the same figures
/// ([`FigureFiles::name`] stands for them in a page's outline).
pub struct FigureFiles<'a> {
    tables: Vec<&'static str>,
    locate: Box<Locate<'a>>,
}

impl<'a> FigureFiles<'a> {
    /// None: every figure table is among the report's tables.
    pub fn none() -> Self {
        FigureFiles {
            tables: Vec::new(),
            locate: Box::new(|_, _| None),
        }
    }

    /// The figure tables `tables`, each source's rows in the file `locate`
    /// gives (the table's name, the source).
    pub fn new(
        tables: Vec<&'static str>,
        locate: impl Fn(&str, &str) -> Option<PathBuf> + Sync + 'a,
    ) -> Self {
        FigureFiles {
            tables,
            locate: Box::new(locate),
        }
    }

    /// Whether the table `name` is read from files.
    pub(super) fn holds(&self, name: &str) -> bool {
        self.tables.contains(&name)
    }

    /// Each table's rows for `sources`, read from their files in parallel.
    pub(super) fn read(&self, sources: &[String]) -> Result<BTreeMap<&'static str, Table>> {
        let mut out = BTreeMap::new();
        for &name in &self.tables {
            let paths: Vec<PathBuf> = sources
                .iter()
                .filter_map(|s| (self.locate)(name, s))
                .collect();
            if let Some(t) = Table::read_stacked(&paths)? {
                out.insert(name, t);
            }
        }
        Ok(out)
    }

    /// Writes what stands for `source`'s figures of `table` in a page's
    /// outline: the name of the file they are read from (not its folder:
    /// a folder moved changes no page). Whether there is one.
    pub(super) fn name(&self, h: &mut String, table: &str, source: &str) -> bool {
        let Some(p) = (self.locate)(table, source) else {
            return false;
        };
        h.push_str("<!-- ");
        h.push_str(&p.file_name().unwrap_or_default().to_string_lossy());
        h.push_str(" -->\n");
        true
    }
}
