//! Each input's reading options and where its files are found, made once
//! per distinct case: a folder of thousands of files matches a handful of
//! override sets, and its glob is one directory listing.

use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::Arc;

use super::planned::FileOptions;
use super::spec::IngestSpec;
use crate::error::{Error, Result};

/// A file's options with their text as cache keys take it.
pub type Options = (Arc<FileOptions>, Arc<str>);

/// The options of files, by which overrides match them.
pub struct OptionsFor<'a> {
    spec: &'a IngestSpec,
    patterns: Vec<glob::Pattern>,
    made: HashMap<Vec<bool>, Options>,
}

impl<'a> OptionsFor<'a> {
    /// The options `spec` gives.
    pub fn new(spec: &'a IngestSpec) -> Result<Self> {
        let patterns = spec
            .overrides
            .iter()
            .map(|ov| override_pattern(ov.files.as_deref().unwrap_or("")))
            .collect::<Result<_>>()?;
        Ok(OptionsFor {
            spec,
            patterns,
            made: HashMap::new(),
        })
    }

    /// The options of the file at `path`: the defaults, then each
    /// matching override in order; checked by `check` when first made.
    pub fn of(
        &mut self,
        path: &Path,
        check: impl Fn(&FileOptions) -> Result<()>,
    ) -> Result<Options> {
        let mask: Vec<bool> = self.patterns.iter().map(|p| hits(p, path)).collect();
        if let Some(o) = self.made.get(&mask) {
            return Ok(o.clone());
        }
        let mut o = FileOptions::default();
        apply(&mut o, self.spec);
        for (ov, _) in self.spec.overrides.iter().zip(&mask).filter(|(_, &m)| m) {
            apply(&mut o, ov);
        }
        check(&o)?;
        let key: Arc<str> = format!("{o:?}").into();
        let made = (Arc::new(o), key);
        self.made.insert(mask, made.clone());
        Ok(made)
    }
}

/// Lays the options of one `[ingest]` table over `o`.
fn apply(o: &mut FileOptions, spec: &IngestSpec) {
    o.ingest.overlay(&spec.options);
    o.columns.extend(spec.columns.clone());
}

/// Whether an override's glob takes a file: matched against its name and
/// against its whole path.
pub fn hits(pat: &glob::Pattern, path: &Path) -> bool {
    pat.matches_path(path)
        || path
            .file_name()
            .and_then(|n| n.to_str())
            .is_some_and(|n| pat.matches(n))
}

/// An override's glob, compiled.
pub fn override_pattern(glob: &str) -> Result<glob::Pattern> {
    glob::Pattern::new(glob)
        .map_err(|e| Error::Config(format!("ingest.override files = '{glob}': {e}")))
}

/// The files a glob matches. A glob whose only wild part is the file name
/// (`traces/*.csv`, a lab folder's usual shape) is one listing of its
/// folder, each entry's type taken from the listing (a stat only for a
/// link); any other is walked by `glob`. Both give the same paths.
pub fn glob_files(pattern: &str) -> std::result::Result<Vec<PathBuf>, String> {
    let path = Path::new(pattern);
    let (parent, name) = match (path.parent(), path.file_name().and_then(|n| n.to_str())) {
        (Some(p), Some(n)) => (p, n),
        _ => return walk(pattern),
    };
    let literal_parent = !parent.to_string_lossy().contains(['*', '?', '[']);
    let Ok(pat) = glob::Pattern::new(name) else {
        return walk(pattern);
    };
    if !literal_parent {
        return walk(pattern);
    }
    let listed = if parent.as_os_str().is_empty() {
        Path::new(".")
    } else {
        parent
    };
    let Ok(entries) = std::fs::read_dir(listed) else {
        return Ok(Vec::new());
    };
    let opts = glob::MatchOptions::new();
    let mut names = Vec::new();
    for e in entries.flatten() {
        // The name as the entry's own string, not copied (a large folder's
        // names were three allocations each).
        let Ok(n) = e.file_name().into_string() else {
            continue;
        };
        if !pat.matches_with(&n, opts) {
            continue;
        }
        let is_file = match e.file_type() {
            Ok(t) if t.is_symlink() => parent.join(&n).is_file(),
            Ok(t) => t.is_file(),
            Err(_) => parent.join(&n).is_file(),
        };
        if is_file {
            names.push(n);
        }
    }
    // One folder: its paths sort as their names (compared as bytes, not
    // as paths component by component).
    names.sort_unstable();
    let joined = |n: String| {
        let mut p = PathBuf::with_capacity(parent.as_os_str().len() + 1 + n.len());
        p.push(parent);
        p.push(n);
        p
    };
    Ok(names.into_iter().map(joined).collect())
}

/// The files `glob` finds for `pattern`.
fn walk(pattern: &str) -> std::result::Result<Vec<PathBuf>, String> {
    Ok(glob::glob(pattern)
        .map_err(|e| e.to_string())?
        .filter_map(|r| r.ok())
        .filter(|p| p.is_file())
        .collect())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The folder listing finds what `glob` finds: the same paths, files
    /// only (not a folder whose name matches), hidden files as `glob`
    /// takes them, links to files, and nothing for a missing folder.
    #[test]
    fn listing_finds_what_glob_finds() {
        let dir = tempfile::tempdir().unwrap();
        let d = dir.path().join("traces");
        std::fs::create_dir_all(d.join("sub.csv")).unwrap();
        for n in ["a.csv", "b.CSV", ".hidden.csv", "c.csv.bak", "[x].csv"] {
            std::fs::write(d.join(n), "t\n").unwrap();
        }
        #[cfg(unix)]
        std::os::unix::fs::symlink(d.join("a.csv"), d.join("link.csv")).unwrap();
        let base = d.to_string_lossy().to_string();
        for pat in [
            "*.csv",
            "*.[cC][sS][vV]",
            "?.csv",
            "*",
            "[[]x].csv",
            "nothing*",
        ] {
            let pattern = format!("{base}/{pat}");
            let fast = glob_files(&pattern).unwrap();
            assert_eq!(fast, walk(&pattern).unwrap(), "{pat}");
        }
        assert!(glob_files(&format!("{base}/*.csv")).unwrap().len() >= 3);
        let missing = format!("{base}/none/*.csv");
        assert_eq!(glob_files(&missing).unwrap(), walk(&missing).unwrap());
        let nested = format!("{}/*/*.csv", dir.path().display());
        assert_eq!(glob_files(&nested).unwrap(), walk(&nested).unwrap());
    }
}
