//! A run's inputs as the search for a companion's data file needs them:
//! the input that is a given path, or the one of its name in another case
//! in its folder ([`same_file`]), in O(log n). Scanning every input for
//! each companion made planning quadratic: 2 000 stylus profiles (6 000
//! files) took 0.75 s to plan.

use std::collections::HashMap;
use std::ffi::OsString;
use std::path::Path;
use std::sync::OnceLock;

/// A file's folder and its name in lower case: two paths with the same
/// are the same file on a case-insensitive file system, as an instrument
/// written on Windows names them.
type Folded<'p> = (Option<&'p Path>, Option<OsString>);

fn folded(p: &Path) -> Folded<'_> {
    (p.parent(), p.file_name().map(|n| n.to_ascii_lowercase()))
}

/// Whether `a` and `b` name the same file: equal, or the same name in
/// another case in the same folder.
pub(super) fn same_file(a: &Path, b: &Path) -> bool {
    a == b || folded(a) == folded(b)
}

/// A run's inputs; sorted the first time one is looked for (most runs
/// have no companion, and look for none), and by folded name the first
/// time a path is not among them as it is spelt.
pub struct Inputs<'a> {
    paths: &'a [&'a Path],
    sorted: OnceLock<Vec<&'a Path>>,
    by_folded: OnceLock<HashMap<Folded<'a>, &'a Path>>,
}

impl<'a> Inputs<'a> {
    /// The inputs `paths`, in any order.
    pub fn new(paths: &'a [&'a Path]) -> Self {
        Inputs {
            paths,
            sorted: OnceLock::new(),
            by_folded: OnceLock::new(),
        }
    }

    /// The input that is the file `path` ([`same_file`]): itself when it
    /// is an input, else the first in path order of its folded name.
    pub fn find(&self, path: &Path) -> Option<&'a Path> {
        let sorted = self.sorted.get_or_init(|| {
            let mut sorted = self.paths.to_vec();
            sorted.sort_unstable();
            sorted
        });
        if let Ok(i) = sorted.binary_search(&path) {
            return Some(sorted[i]);
        }
        let by_folded = self.by_folded.get_or_init(|| {
            let mut map = HashMap::with_capacity(sorted.len());
            for p in sorted.iter().rev() {
                map.insert(folded(p), *p);
            }
            map
        });
        by_folded.get(&folded(path)).copied()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Found as a scan of every input with [`same_file`] finds it: by its
    /// path, else by its name in any case in the same folder, never in
    /// another folder.
    #[test]
    fn an_input_is_found_as_a_scan_finds_it() {
        let names = ["a/3.TX1", "a/3.tx1", "a/4.Tx2", "b/5.asc", "a/6.tx1"];
        let paths: Vec<&Path> = names.iter().map(Path::new).collect();
        let inputs = Inputs::new(&paths);
        let wanted = [
            "a/3.TX1", "a/3.tx1", "a/3.Tx1", "a/4.TX2", "b/5.ASC", "a/5.asc", "c/6.tx1", "a/7.tx1",
        ];
        for w in wanted {
            let w = Path::new(w);
            let scan = paths.iter().copied().find(|p| *p == w).or_else(|| {
                let mut by_name: Vec<&Path> =
                    paths.iter().copied().filter(|p| same_file(p, w)).collect();
                by_name.sort();
                by_name.first().copied()
            });
            assert_eq!(inputs.find(w), scan, "{}", w.display());
        }
        assert_eq!(
            inputs.find(Path::new("a/3.Tx1")),
            Some(Path::new("a/3.TX1"))
        );
        assert_eq!(inputs.find(Path::new("a/5.asc")), None);
    }
}
