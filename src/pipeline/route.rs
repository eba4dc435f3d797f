//! Routing: which per-file stages take an input file, and why none does.
//! One rule, used by the run ([`super::files`]), the fuzz harness
//! ([`super::fuzz`]) and `tribo inspect`.

use std::collections::BTreeMap;

use crate::ingest::kind::{classify, DataKind};
use crate::ingest::roles::Role;
use crate::ingest::Dataset;
use crate::stages::{Consumes, StagePlan};

/// Indices of the per-file stages among `stages`.
pub fn per_file<'a>(stages: impl IntoIterator<Item = &'a dyn StagePlan>) -> Vec<usize> {
    per_file_of(stages).collect()
}

fn per_file_of<'a, I: IntoIterator<Item = &'a dyn StagePlan>>(
    stages: I,
) -> impl Iterator<Item = usize> + use<'a, I> {
    let takes_files = |s: &dyn StagePlan| matches!(s.consumes(), Consumes::Files(_));
    stages
        .into_iter()
        .enumerate()
        .filter_map(move |(i, s)| takes_files(s).then_some(i))
}

/// The stages (indices into `stages`) that take a file: those whose own
/// `files` list it (`forced`), else those that read its kind. A file whose
/// columns say nothing goes to the only per-file stage when there is just
/// one (which then says what it misses), and to none otherwise. Asked for
/// every input of a run: nothing but the answer is allocated.
pub fn takers<'a>(
    stages: impl IntoIterator<Item = &'a dyn StagePlan>,
    forced: &[usize],
    kind: Option<DataKind>,
) -> Vec<usize> {
    if !forced.is_empty() {
        return forced.to_vec();
    }
    let reads =
        |s: &dyn StagePlan, k| matches!(s.consumes(), Consumes::Files(ks) if ks.contains(&k));
    match kind {
        Some(k) => stages
            .into_iter()
            .enumerate()
            .filter_map(|(i, s)| reads(s, k).then_some(i))
            .collect(),
        None => {
            let mut per_file = per_file_of(stages);
            match (per_file.next(), per_file.next()) {
                (Some(only), None) => vec![only],
                _ => Vec::new(),
            }
        }
    }
}

/// A read file's kind, or why it has none (the columns it has).
pub fn kind_of(ds: &Dataset, columns: &BTreeMap<Role, String>) -> (Option<DataKind>, String) {
    match classify(ds, columns) {
        Some(k) => (Some(k), String::new()),
        None => (None, unknown_columns(ds)),
    }
}

/// Why no stage takes a read file: its kind that no stage of the pipeline
/// reads, or `unknown` (why it has no kind).
pub fn untaken_reason(kind: Option<DataKind>, unknown: &str) -> String {
    match kind {
        Some(k) => format!("a {k}, and no stage of this pipeline reads {k} files"),
        None => unknown.to_string(),
    }
}

/// Why a file has no kind: the columns it has.
fn unknown_columns(ds: &Dataset) -> String {
    let cols: Vec<&str> = ds
        .sections
        .iter()
        .flat_map(|s| s.channels.iter().map(|c| c.name.as_str()))
        .take(8)
        .collect();
    format!(
        "no stage recognises its columns {cols:?}; name their roles in \
         [[ingest.override]] columns, or list the file in a stage's files"
    )
}
