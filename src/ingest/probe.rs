//! The column names of a file as tribo reads them, from its first lines:
//! what a pipeline's `[ingest] units` keys and `columns` overrides are
//! checked against before a run computes anything.

use std::io::Read;
use std::path::Path;

use super::{binary, choose_reader, read_path, read_text, IngestOptions, Text};
use crate::error::{Error, Result};

/// Bytes read for the header of a text export: every export seen keeps its
/// header and first rows well inside this.
const HEAD: usize = 256 * 1024;

/// The names of the columns (and grid channels) of `path`, read with
/// `options` less its unit overrides (the names, not the overrides, are in
/// question). A text export is read from its first [`HEAD`] bytes, cut at
/// a line end; a file that does not read from its head (a binary format, a
/// layout whose end is needed, a cut through a UTF-16 character) is read
/// whole.
pub fn column_names(path: &Path, options: &IngestOptions) -> Result<Vec<String>> {
    let options = IngestOptions {
        units: Default::default(),
        force: false,
        ..options.clone()
    };
    let head = read_head(path)?;
    let whole = head.len() < HEAD;
    let from_head = head_names(path, &head, &options);
    match from_head {
        Ok(names) => Ok(names),
        Err(e) if whole => Err(e),
        Err(_) => read_path(path, &options).map(|ds| names_of(&ds)),
    }
}

/// At most [`HEAD`] bytes of the file, cut after its last complete line
/// when the file is longer.
fn read_head(path: &Path) -> Result<Vec<u8>> {
    let file = std::fs::File::open(path).map_err(|e| Error::io(path, e))?;
    let mut head = Vec::with_capacity(HEAD);
    file.take(HEAD as u64 + 1)
        .read_to_end(&mut head)
        .map_err(|e| Error::io(path, e))?;
    if head.len() > HEAD {
        let cut = head[..HEAD]
            .iter()
            .rposition(|&b| b == b'\n')
            .map_or(0, |i| i + 1);
        head.truncate(cut);
    }
    Ok(head)
}

fn head_names(path: &Path, head: &[u8], options: &IngestOptions) -> Result<Vec<String>> {
    if let Some(ds) = binary::read(&binary::Bytes::new(path, head), options)? {
        return Ok(names_of(&ds));
    }
    let text = Text::decode(path, head)?;
    let ds = read_text(path, &text, choose_reader(&text, options)?, options)?;
    Ok(names_of(&ds))
}

fn names_of(ds: &super::Dataset) -> Vec<String> {
    let columns = ds
        .sections
        .iter()
        .flat_map(|s| &s.channels)
        .map(|c| &c.name);
    let grids = ds.grids.iter().map(|g| &g.name);
    columns.chain(grids).cloned().collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn write(dir: &Path, name: &str, text: &str) -> std::path::PathBuf {
        let p = dir.join(name);
        std::fs::write(&p, text).unwrap();
        p
    }

    #[test]
    fn names_come_from_the_header_as_read() {
        let dir = tempfile::tempdir().unwrap();
        let p = write(
            dir.path(),
            "a.csv",
            "Time [s];Friction force [N];Normal force [N]\n0;1,5;10\n1;1,6;10\n",
        );
        let names = column_names(&p, &IngestOptions::default()).unwrap();
        assert_eq!(names, ["Time", "Friction force", "Normal force"]);
    }

    /// A file longer than the head is read from its head; its names are
    /// the whole file's.
    #[test]
    fn a_long_file_is_read_from_its_head() {
        let dir = tempfile::tempdir().unwrap();
        let mut text = String::from("t,F\n");
        for i in 0..40_000 {
            text.push_str(&format!("{i},{}.25\n", i % 7));
        }
        assert!(text.len() > HEAD);
        let p = write(dir.path(), "long.csv", &text);
        let o = IngestOptions::default();
        assert_eq!(column_names(&p, &o).unwrap(), ["t", "F"]);
        let whole = read_path(&p, &o).unwrap();
        assert_eq!(names_of(&whole), ["t", "F"]);
    }

    /// The unit overrides are not applied: a contradicting one is the
    /// file's own failure later, not a reason to lose its names here.
    #[test]
    fn unit_overrides_do_not_fail_the_probe() {
        let dir = tempfile::tempdir().unwrap();
        let p = write(dir.path(), "a.csv", "t [s],F [N]\n0,1\n1,2\n");
        let mut o = IngestOptions::default();
        o.units.insert("F".into(), "kN".into());
        assert_eq!(column_names(&p, &o).unwrap(), ["t", "F"]);
    }
}
