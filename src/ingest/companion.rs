//! Companion files: files that hold part of one measurement and are read
//! with its data file, not as inputs of their own (a Surfcom `.tx3`
//! conditions file with its `.tx2` data, a catman `.TSX` job file). The
//! pipeline asks [`data_file_of`] for every input; a companion is listed
//! in the run's `files` table as `companion`, naming its data file, and is
//! not routed to a stage. The reader of the data file reads it.

use std::path::Path;

/// Companion extensions and the data-file extensions they go with
/// (lower case): a companion is `<stem>.<companion>` beside
/// `<stem>.<data>`. A reader that reads a companion adds its line here.
const COMPANIONS: &[(&str, &[&str])] = &[];

/// The data file among `inputs` that `path` is read with, when `path` is a
/// companion of one of them.
pub fn data_file_of<'a>(path: &Path, inputs: &[&'a Path]) -> Option<&'a Path> {
    companion_in(COMPANIONS, path, inputs)
}

fn companion_in<'a>(
    table: &[(&str, &[&str])],
    path: &Path,
    inputs: &[&'a Path],
) -> Option<&'a Path> {
    let ext = path.extension()?.to_str()?.to_ascii_lowercase();
    let (_, data) = table.iter().find(|(c, _)| *c == ext)?;
    inputs.iter().copied().find(|p| {
        p.parent() == path.parent()
            && p.file_stem() == path.file_stem()
            && p.extension()
                .and_then(|e| e.to_str())
                .is_some_and(|e| data.contains(&e.to_ascii_lowercase().as_str()))
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_companion_names_the_data_file_beside_it() {
        let table: &[(&str, &[&str])] = &[("tx3", &["tx2"])];
        let (data, cond, other) = (
            Path::new("lab/s1.TX2"),
            Path::new("lab/s1.tx3"),
            Path::new("other/s1.tx2"),
        );
        let inputs = [other, data, cond];
        assert_eq!(companion_in(table, cond, &inputs), Some(data));
        assert_eq!(companion_in(table, data, &inputs), None);
        // Without its data file among the inputs, it is an input of its own.
        assert_eq!(companion_in(table, cond, &[cond]), None);
    }
}
