//! The cache's small entries: what a file is (its route) and what a
//! per-file stage made of it (a part's tables, or its failure), as packs
//! ([`super::pack`]) keep them.

use serde::{Deserialize, Serialize};

use super::stamp::Stamp;
use crate::error::{Error, ErrorKind};
use crate::ingest::kind::DataKind;

/// A failure as the cache keeps it.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Failure {
    /// Its family.
    pub kind: ErrorKind,
    /// The message with its location.
    pub message: String,
}

impl From<&Error> for Failure {
    fn from(e: &Error) -> Self {
        Failure {
            kind: e.kind(),
            message: e.to_string(),
        }
    }
}

/// What a file is, once read.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub enum Route {
    /// Data: its reader, and its kind when its columns tell (else why
    /// not).
    Data {
        /// The reader that understood it (shared by every copy).
        #[serde(deserialize_with = "super::shared::shared_name")]
        format: std::sync::Arc<str>,
        /// The kind.
        kind: Option<DataKind>,
        /// Why no kind, when none (the columns it has).
        unknown: String,
    },
    /// Not data (a notes file), and why.
    NotData(String),
    /// Cannot be read.
    Unreadable(Failure),
}

/// A file's route with its SHA-256 (for the provenance).
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct RouteEntry {
    /// SHA-256 of the bytes, hex (shared with the state and provenance).
    #[serde(deserialize_with = "super::shared::shared_str")]
    pub sha256: std::sync::Arc<str>,
    /// What it is.
    pub route: Route,
}

/// What a part holds: its tables, or the stage's failure.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub(super) enum PartEntry {
    Tables(Vec<StoredTable>),
    Failed(Failure),
}

/// One table of a part: its name, and the stamp of its file when the
/// output set shares it (a dataset's file).
#[derive(Debug, Clone, Serialize, Deserialize)]
pub(super) struct StoredTable {
    pub(super) name: String,
    pub(super) linked: Option<Stamp>,
}
