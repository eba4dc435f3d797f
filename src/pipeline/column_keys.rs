//! Every column a pipeline names in `[ingest]` — a `units` key, a
//! `columns` override — is a column of at least one input file it applies
//! to. A name that matches none is a typo that would leave the column read
//! with the file's own unit or role guess, so the run stops before
//! computing anything, naming the key and the columns it could have meant.

use std::collections::BTreeMap;
use std::path::Path;

use super::planned::PlannedFile;
use super::spec::IngestSpec;
use crate::error::{Error, Result};
use crate::ingest::probe::column_names;
use crate::ingest::roles::Role;

/// One `[ingest]` table: the defaults (every file) or an override (the
/// files its glob matches).
struct Scope<'a> {
    label: String,
    spec: &'a IngestSpec,
    files: Vec<&'a PlannedFile>,
}

/// Checks every `units` key and `columns` value of `[ingest]` and its
/// overrides against the column names of the files each applies to. Files
/// are probed from their heads, each at most once, and only until every
/// name is found; a file that cannot be read is skipped here (it fails on
/// its own in the run).
pub fn check(
    spec: &IngestSpec,
    files: &[PlannedFile],
    matches: impl Fn(&str, &Path) -> bool,
) -> Result<()> {
    let data: Vec<&PlannedFile> = files.iter().filter(|f| f.companion_of.is_none()).collect();
    let mut scopes = vec![Scope {
        label: "[ingest]".into(),
        spec,
        files: data.clone(),
    }];
    for ov in &spec.overrides {
        let glob = ov.files.as_deref().unwrap_or("");
        scopes.push(Scope {
            label: format!("[[ingest.override]] files = '{glob}'"),
            spec: ov,
            files: data
                .iter()
                .copied()
                .filter(|f| matches(glob, &f.path))
                .collect(),
        });
    }
    let mut probed = Probed::default();
    for scope in &scopes {
        check_scope(scope, &mut probed)?;
    }
    Ok(())
}

/// The names each file was found to have (`None`: it could not be read).
#[derive(Default)]
struct Probed(BTreeMap<std::path::PathBuf, Option<Vec<String>>>);

impl Probed {
    fn names(&mut self, f: &PlannedFile) -> Option<&[String]> {
        self.0
            .entry(f.path.clone())
            .or_insert_with(|| column_names(&f.path, &f.options.ingest).ok())
            .as_deref()
    }
}

/// What names a column in `[ingest]`.
#[derive(Clone, Copy)]
enum Naming {
    /// A key of `units`.
    Units,
    /// The value of a `columns` override, for this role.
    Column(Role),
}

fn check_scope(scope: &Scope, probed: &mut Probed) -> Result<()> {
    let named = scope
        .spec
        .options
        .units
        .keys()
        .map(|k| (Naming::Units, k.as_str()))
        .chain(
            scope
                .spec
                .columns
                .iter()
                .map(|(r, c)| (Naming::Column(*r), c.as_str())),
        );
    for (what, name) in named {
        let found = scope
            .files
            .iter()
            .any(|f| probed.names(f).is_some_and(|n| n.iter().any(|c| c == name)));
        if !found {
            return Err(unmatched(scope, what, name, probed));
        }
    }
    Ok(())
}

/// The error for a name no file has, with the columns of the first file
/// that could be read, for the user to see what was meant.
fn unmatched(scope: &Scope, what: Naming, name: &str, probed: &mut Probed) -> Error {
    let seen = scope.files.iter().find_map(|f| {
        probed
            .names(f)
            .map(|n| (f.path.display().to_string(), n.join(", ")))
    });
    let hint = match seen {
        Some((path, names)) => format!("; the columns of {path} are: {names}"),
        None => String::new(),
    };
    let what = match what {
        Naming::Units => "units key".to_string(),
        Naming::Column(role) => format!("columns override {} =", role.key()),
    };
    Error::Config(format!(
        "{} {what} '{name}' matches no column of the {} input files it applies to \
         (names are matched exactly, as `tribo inspect` shows them){hint}",
        scope.label,
        scope.files.len()
    ))
}
