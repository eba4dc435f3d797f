//! Paths as users write them.

use std::path::{Component, Path, PathBuf};

/// Removes `.` and `name/..` from a path without touching the file system,
/// so that outputs name `fixtures/a.csv`, not `pipelines/../fixtures/a.csv`.
pub fn clean_path(path: &Path) -> PathBuf {
    let mut out: Vec<Component> = Vec::new();
    for c in path.components() {
        match c {
            Component::CurDir => {}
            Component::ParentDir if matches!(out.last(), Some(Component::Normal(_))) => {
                out.pop();
            }
            c => out.push(c),
        }
    }
    if out.is_empty() {
        return PathBuf::from(".");
    }
    out.iter().collect()
}
