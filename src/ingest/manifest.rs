//! The sample manifest: a CSV that describes each test file (sample id,
//! load, area, pattern, material, …), joined on the file name.
//!
//! The manifest is generic: any columns are kept, and each stage reads the
//! ones it knows with typed getters that name the line and column of a bad
//! value. The `file` column matches an input by its file name, or by a path
//! suffix when several inputs share a name. Tables keyed by another column
//! (the samples table of `tribo fit coulomb`, keyed by `sample_id`) are read
//! by the same code ([`Manifest::read_keyed`]).

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use super::dialect::{parse_number, split_fields};
use super::text::Text;
use crate::error::{Error, Location, Result};

/// One manifest row.
#[derive(Debug, Clone, PartialEq)]
pub struct ManifestRow {
    /// The key column's value (`file` for a sample manifest).
    pub key: String,
    /// Every column by header name (including `file`), trimmed; empty cells
    /// are absent.
    pub fields: BTreeMap<String, String>,
    /// 1-based line in the manifest.
    pub line: usize,
}

/// A parsed manifest.
#[derive(Debug, Clone, Default)]
pub struct Manifest {
    /// The manifest file.
    pub path: PathBuf,
    /// Rows in file order.
    pub rows: Vec<ManifestRow>,
}

impl Manifest {
    /// Reads a manifest CSV (comma, semicolon or tab; first row is the header
    /// and must have a `file` column).
    pub fn read(path: &Path) -> Result<Manifest> {
        let bytes = std::fs::read(path).map_err(|e| Error::io(path, e))?;
        Manifest::from_bytes(path, &bytes)
    }

    /// [`Manifest::read`] of a file already in memory.
    pub fn from_bytes(path: &Path, bytes: &[u8]) -> Result<Manifest> {
        let m = Manifest::keyed_from_bytes(path, bytes, "file")?;
        m.check_unique()?;
        Ok(m)
    }

    /// Checks that no file has two rows: which one applies would be a
    /// guess. (Tables keyed by `sample_id` may repeat it, one row per file.)
    fn check_unique(&self) -> Result<()> {
        for (i, r) in self.rows.iter().enumerate() {
            if let Some(first) = self.rows[..i].iter().find(|f| f.key == r.key) {
                return Err(Error::input(
                    Location::line(&self.path, r.line).with_column("file"),
                    format!(
                        "{} is also on line {}: each file may have one row, \
                         or which one applies would be a guess",
                        super::text::quoted(&r.key),
                        first.line
                    ),
                ));
            }
        }
        Ok(())
    }

    /// Reads a CSV table whose rows are identified by the column `key`
    /// (non-empty in every row); otherwise as [`Manifest::read`].
    pub fn read_keyed(path: &Path, key: &str) -> Result<Manifest> {
        let bytes = std::fs::read(path).map_err(|e| Error::io(path, e))?;
        Manifest::keyed_from_bytes(path, &bytes, key)
    }

    /// [`Manifest::read_keyed`] of a file already in memory.
    pub fn keyed_from_bytes(path: &Path, bytes: &[u8], key: &str) -> Result<Manifest> {
        let text = Text::decode(path, bytes)?;
        let header_line = text
            .lines()
            .position(|l| !l.trim().is_empty())
            .ok_or_else(|| {
                Error::input(
                    Location::file(path),
                    format!("empty table; expected a header row with a '{key}' column"),
                )
            })?;
        let header = text.line(header_line);
        let delimiter = [',', ';', '\t']
            .into_iter()
            .max_by_key(|d| header.matches(*d).count())
            .unwrap_or(',');
        let names: Vec<String> = split_fields(header, delimiter)
            .iter()
            .map(|s| s.trim().to_string())
            .collect();
        let key_col = names.iter().position(|n| n == key).ok_or_else(|| {
            Error::input(
                Location::line(path, header_line + 1),
                format!("no '{key}' column in the header {names:?}"),
            )
        })?;
        let mut rows = Vec::new();
        for (i, line) in text.lines().enumerate().skip(header_line + 1) {
            if line.trim().is_empty() {
                continue;
            }
            let cells = split_fields(line, delimiter);
            if cells.len() > names.len()
                && cells[names.len()..].iter().any(|c| !c.trim().is_empty())
            {
                return Err(Error::input(
                    Location::line(path, i + 1),
                    format!("{} fields, but the header has {}", cells.len(), names.len()),
                ));
            }
            let fields: BTreeMap<String, String> = names
                .iter()
                .zip(cells.iter())
                .filter(|(_, v)| !v.trim().is_empty())
                .map(|(k, v)| (k.clone(), v.trim().to_string()))
                .collect();
            let value = fields.get(&names[key_col]).cloned().ok_or_else(|| {
                Error::input(
                    Location::line(path, i + 1).with_column(key),
                    format!("empty {key}"),
                )
            })?;
            rows.push(ManifestRow {
                key: value,
                fields,
                line: i + 1,
            });
        }
        Ok(Manifest {
            path: path.to_path_buf(),
            rows,
        })
    }

    /// The row for an input file: an exact file-name match, else the row
    /// whose `file` is a suffix of the input's path.
    pub fn find(&self, input: &Path) -> Option<&ManifestRow> {
        let name = input.file_name()?.to_str()?;
        let by_name: Vec<&ManifestRow> = self.rows.iter().filter(|r| r.key == name).collect();
        if by_name.len() == 1 {
            return Some(by_name[0]);
        }
        self.rows
            .iter()
            .find(|r| input.ends_with(Path::new(&r.key)))
    }

    /// Checks that no row matches several of `inputs` (a bare file name
    /// shared by files in two folders): which file the row describes would
    /// be a guess. The error names the row and the files.
    pub fn check_unambiguous(&self, inputs: &[&Path]) -> Result<()> {
        for r in &self.rows {
            let hits: Vec<&&Path> = inputs
                .iter()
                .filter(|p| p.ends_with(Path::new(&r.key)))
                .collect();
            if hits.len() > 1 {
                let names: Vec<String> = hits.iter().map(|p| p.display().to_string()).collect();
                return Err(Error::input(
                    Location::line(&self.path, r.line).with_column("file"),
                    format!(
                        "{} matches {} input files ({}): give enough of the path to name one",
                        super::text::quoted(&r.key),
                        hits.len(),
                        names.join(", ")
                    ),
                ));
            }
        }
        Ok(())
    }

    /// The rows that match none of `inputs` (by the rule of [`Self::find`]).
    pub fn unmatched<'a>(&'a self, inputs: &'a [&Path]) -> impl Iterator<Item = &'a ManifestRow> {
        self.rows.iter().filter(|r| {
            !inputs
                .iter()
                .any(|p| self.find(p).is_some_and(|f| f.line == r.line))
        })
    }

    /// A numeric field of a row; `Ok(None)` when absent; an error naming the
    /// manifest line and column when it is not a number.
    pub fn f64(&self, row: &ManifestRow, column: &str) -> Result<Option<f64>> {
        let Some(v) = row.fields.get(column) else {
            return Ok(None);
        };
        match parse_number(v, '.') {
            Some(x) if x.is_finite() => Ok(Some(x)),
            _ => Err(Error::input(
                Location::line(&self.path, row.line).with_column(column),
                format!("expected a number, found {}", super::text::quoted(v)),
            )),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn manifest(text: &str) -> (tempfile::TempDir, Result<Manifest>) {
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("samples.csv");
        std::fs::write(&p, text).unwrap();
        let m = Manifest::read(&p);
        (dir, m)
    }

    #[test]
    fn a_file_with_two_rows_is_an_error_naming_both() {
        let (_d, m) = manifest("file,normal_force_N\na.csv,1\nb.csv,2\na.csv,3\n");
        let e = m.unwrap_err().to_string();
        assert!(e.contains("line 4") && e.contains("also on line 2"), "{e}");
    }

    #[test]
    fn a_bare_name_matching_two_inputs_is_an_error() {
        let (_d, m) = manifest("file,normal_force_N\nx.csv,1\nb/y.csv,2\n");
        let m = m.unwrap();
        let (a, b, c) = (
            Path::new("a/x.csv"),
            Path::new("b/x.csv"),
            Path::new("b/y.csv"),
        );
        let e = m.check_unambiguous(&[a, b, c]).unwrap_err().to_string();
        assert!(
            e.contains("line 2") && e.contains("a/x.csv") && e.contains("b/x.csv"),
            "{e}"
        );
        assert!(m.check_unambiguous(&[a, c]).is_ok());
    }

    #[test]
    fn reads_and_joins_on_file_name() {
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("samples.csv");
        std::fs::write(&p, "file,sample_id,mass_g\na.csv,S1,200\nsub/b.csv,S2,x\n").unwrap();
        let m = Manifest::read(&p).unwrap();
        let a = m.find(Path::new("/data/a.csv")).unwrap();
        assert_eq!(a.fields["sample_id"], "S1");
        assert_eq!(m.f64(a, "mass_g").unwrap(), Some(200.0));
        let b = m.find(Path::new("/x/sub/b.csv")).unwrap();
        let e = m.f64(b, "mass_g").unwrap_err().to_string();
        assert!(
            e.contains("line 3") && e.contains("mass_g") && e.contains("'x'"),
            "{e}"
        );
        assert!(m.find(Path::new("c.csv")).is_none());
    }
}
