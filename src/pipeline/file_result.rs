//! What became of one input file in the per-file phase ([`super::files`]):
//! one [`FileResult`] from there to the published set. The stages take
//! their [`Part`]s from it, the `files` table its row, the run's state its
//! [`FileState`], the errors its failures.

use super::by_name::ByName;
use super::cache::{Failure, Route};
use super::inputs::{InputFile, Outcome};
use super::keys::Key;
use super::outcome::FileFailure;
use super::plan::{Plan, PlannedFile};
use super::shared::Shared;
use super::state::{FileStat, FileState};
use crate::error::ErrorKind;
use crate::hash::InputHash;
use crate::ingest::kind::DataKind;
use crate::stages::Tables;

/// One stage's rows for one file.
pub struct Part {
    /// The stage (index into the plan's stages).
    pub stage: usize,
    /// The key of the part in the cache.
    pub key: Key,
    /// The rows.
    pub rows: Rows,
    /// The file behind the rows, for the stage's provenance (unless the
    /// stage failed on it).
    pub input: Option<InputHash>,
}

/// A part's rows.
pub enum Rows {
    /// Made in this run: its summary tables when the cache could not
    /// store them (else they are taken from the cache's new pack).
    Made(Option<Tables>),
    /// In the cache (loaded when a stage needs them).
    Cached,
    /// The stage failed on the file (in this run, or in the cache).
    Failed(Failure),
}

/// What became of one input file.
pub enum Fate {
    /// Read with this data file (a companion), not on its own.
    Companion(String),
    /// Read, and taken by these stages.
    Taken(Vec<Part>),
    /// Taken by no stage, and why.
    NotTaken(String),
    /// Could not be read.
    Unreadable(Failure),
    /// Not in the cache: a dry run would read it.
    Pending,
}

/// One input file after the per-file phase.
pub struct FileResult {
    /// Its SHA-256, when it could be read from disk.
    pub hash: Option<InputHash>,
    /// Its size, when it could be opened.
    pub size: Option<u64>,
    /// What it is (its reader and kind, or why no stage takes it), when
    /// read or known from the cache.
    pub route: Option<Route>,
    /// BLAKE3 of its bytes and its route key (none for a companion), when
    /// read.
    pub content: Option<(std::sync::Arc<str>, Option<Key>)>,
    /// How it looked on disk when its bytes were hashed.
    pub stat: Option<FileStat>,
    /// How the files that decide its companions looked before its route
    /// key was made ([`FileState::beside`]).
    pub beside: Vec<Option<FileStat>>,
    /// Whether it was read and hashed in this run (not taken as unchanged
    /// from its stat).
    pub hashed: bool,
    /// What became of it.
    pub fate: Fate,
}

impl FileResult {
    pub(super) fn new(fate: Fate) -> Self {
        FileResult {
            hash: None,
            size: None,
            route: None,
            content: None,
            stat: None,
            beside: Vec::new(),
            hashed: false,
            fate,
        }
    }

    /// Its reader and kind, when it is data.
    pub fn read(&self) -> Option<(&std::sync::Arc<str>, Option<DataKind>)> {
        match &self.route {
            Some(Route::Data { format, kind, .. }) => Some((format, *kind)),
            _ => None,
        }
    }

    /// Whether any stage made this file's rows in this run.
    pub fn redone(&self) -> bool {
        match &self.fate {
            Fate::Taken(t) => t.iter().any(|p| matches!(p.rows, Rows::Made(_))),
            _ => false,
        }
    }

    /// Its failures: the reader's, each taking stage's, or none taking a
    /// file named as an input (`f.named`).
    pub fn failures(&self, plan: &Plan, f: &PlannedFile) -> Vec<FileFailure> {
        // The path is copied for a failure only: most inputs have none.
        let source = || f.source.clone();
        match &self.fate {
            Fate::Unreadable(e) => vec![FileFailure::from_failure(source(), "ingest", e)],
            Fate::NotTaken(why) if f.named => vec![FileFailure {
                message: format!(
                    "{}: named as an input, but no stage takes it: {why}",
                    f.source
                ),
                source: source(),
                stage: "ingest".into(),
                kind: ErrorKind::BadInput,
            }],
            Fate::Taken(parts) => parts
                .iter()
                .filter_map(|p| match &p.rows {
                    Rows::Failed(e) => {
                        let stage = plan.stages[p.stage].stage.name();
                        Some(FileFailure::from_failure(source(), stage, e))
                    }
                    _ => None,
                })
                .collect(),
            _ => Vec::new(),
        }
    }

    /// Its row of the `files` table, given its `failures`.
    pub fn row(&self, plan: &Plan, f: &PlannedFile, failures: &[FileFailure]) -> InputFile {
        let read = self.read();
        let mut row = InputFile {
            // The provenance's copy, when it has one.
            file: self
                .hash
                .as_ref()
                .map_or_else(|| f.source.as_str().into(), |h| h.path.clone()),
            size_bytes: self.size,
            sha256: self.hash.as_ref().map(|h| h.sha256.clone()),
            format: read.map(|r| r.0.clone()),
            kind: read.and_then(|r| r.1),
            stages: Vec::new(),
            outcome: Outcome::Processed,
            reason: None,
            companion_of: None,
        };
        match &self.fate {
            Fate::Companion(data) => {
                row.outcome = Outcome::Companion;
                row.companion_of = Some(data.clone());
            }
            Fate::NotTaken(why) if !f.named => {
                row.outcome = Outcome::NotTaken;
                row.reason = Some(why.clone());
            }
            Fate::Taken(parts) => {
                let name = |p: &Part| plan.stages[p.stage].stage.name();
                row.stages = parts.iter().map(name).collect();
            }
            _ => {}
        }
        if !failures.is_empty() {
            row.outcome = Outcome::Failed;
            let why: Vec<String> = failures
                .iter()
                .map(|f| format!("{}: {}", f.stage, f.message))
                .collect();
            row.reason = Some(why.join("; "));
        }
        row
    }

    /// The parts it was taken into (none when no stage took it).
    fn taken(&self) -> &[Part] {
        match &self.fate {
            Fate::Taken(taken) => taken,
            _ => &[],
        }
    }

    /// Its state after `last` (the last run's): `last` itself, shared,
    /// when it is what [`Self::state`] would make (an unchanged input).
    pub fn state_after(
        &self,
        plan: &Plan,
        last: Option<&Shared<FileState>>,
    ) -> Option<Shared<FileState>> {
        match last {
            Some(last) if self.same_state(plan, last) => Some(last.clone()),
            _ => self.state(plan).map(Shared::new),
        }
    }

    /// Whether [`Self::state`] would be `last`, found without making it.
    fn same_state(&self, plan: &Plan, last: &FileState) -> bool {
        let Some((bytes, route)) = &self.content else {
            return false;
        };
        let taken = self.taken();
        let name = |p: &Part| plan.stages[p.stage].stage.name();
        let failed = taken.iter().filter_map(|p| match &p.rows {
            Rows::Failed(e) => Some((name(p), e)),
            _ => None,
        });
        *bytes == last.bytes
            && *route == last.route
            && last.parts.len() == taken.len()
            && taken
                .iter()
                .all(|p| last.parts.get(name(p)) == Some(&p.key))
            && last.failed.len() == failed.clone().count()
            && failed.clone().all(|(n, e)| last.failed.get(n) == Some(e))
            && self.hash.as_ref().map(|h| &*h.sha256) == last.sha256.as_deref()
            && self.stat == last.stat
            && self.route == last.what
            && self.beside == last.beside
    }

    /// What the run's state keeps of it: its bytes' hash, its route and
    /// its parts' keys by stage; `None` when it was not read.
    pub fn state(&self, plan: &Plan) -> Option<FileState> {
        let (bytes, route) = self.content.clone()?;
        let taken = self.taken();
        let stage = |p: &Part| plan.stages[p.stage].stage.name().to_string();
        // Collected, each list is as long as it needs: most inputs have one
        // stage, and an insert each left room for four.
        let parts: ByName<Key> = taken.iter().map(|p| (stage(p), p.key)).collect();
        let failed = taken
            .iter()
            .filter_map(|p| match &p.rows {
                Rows::Failed(e) => Some((stage(p), e.clone())),
                _ => None,
            })
            .collect();
        Some(FileState {
            bytes,
            route,
            parts,
            sha256: self.hash.as_ref().map(|h| h.sha256.clone()),
            stat: self.stat.clone(),
            what: self.route.clone(),
            failed,
            beside: self.beside.clone(),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::error::ErrorKind;

    fn plan(dir: &std::path::Path) -> Plan {
        std::fs::write(dir.join("a.csv"), "time_s,friction_force_N\n0,1\n").unwrap();
        let p = dir.join("p.toml");
        let text = "stages = [\"friction\", \"roughness\"]\n[input]\nfiles = [\"*.csv\"]\n";
        std::fs::write(&p, format!("{text}[output]\ndir = \"out\"\n")).unwrap();
        Plan::from_file(&p).unwrap()
    }

    fn result() -> FileResult {
        let failure = Failure {
            kind: ErrorKind::BadInput,
            message: "no profile".into(),
        };
        let part = |stage, key: &str, rows| Part {
            stage,
            key: Key::of_text(key),
            rows,
            input: None,
        };
        FileResult {
            hash: Some(InputHash {
                path: "a.csv".into(),
                sha256: "5a".into(),
            }),
            size: Some(12),
            route: Some(Route::NotData("notes".into())),
            content: Some(("b3".into(), Some(Key::of_text("route")))),
            stat: Some(FileStat {
                len: 12,
                modified_ns: 1,
                changed_ns: 2,
                inode: 3,
                seen_ns: 4,
            }),
            beside: vec![
                None,
                Some(FileStat {
                    len: 5,
                    modified_ns: 6,
                    changed_ns: 7,
                    inode: 8,
                    seen_ns: 9,
                }),
            ],
            hashed: false,
            fate: Fate::Taken(vec![
                part(0, "p0", Rows::Cached),
                part(1, "p1", Rows::Failed(failure)),
            ]),
        }
    }

    /// The state is shared exactly when it is the one the result makes:
    /// each field of the last state changed in turn makes a new one.
    #[test]
    fn a_state_is_kept_only_when_it_is_the_one_made() {
        let dir = tempfile::tempdir().unwrap();
        let plan = plan(dir.path());
        let r = result();
        let last = Shared::new(r.state(&plan).unwrap());
        let kept = r.state_after(&plan, Some(&last)).unwrap();
        assert!(std::ptr::eq(&*kept, &*last));
        let changes: [fn(&mut FileState); 12] = [
            |s| s.bytes = format!("{}x", s.bytes).into(),
            |s| s.route = None,
            |s| s.parts.insert("friction".into(), Key::of_text("other")),
            |s| {
                s.parts.remove("roughness");
            },
            |s| s.parts.insert("tensile".into(), Key::of_text("p2")),
            |s| s.failed = ByName::default(),
            |s| s.sha256 = None,
            |s| s.stat.as_mut().unwrap().seen_ns += 1,
            |s| s.what = None,
            |s| s.beside[0] = s.beside[1].clone(),
            |s| {
                s.beside.pop();
            },
            |s| {
                let f = s.failed.get_mut("roughness").unwrap();
                f.message.push('!');
            },
        ];
        for (i, change) in changes.iter().enumerate() {
            let mut other = (*last).clone();
            change(&mut other);
            let other = Shared::new(other);
            let made = r.state_after(&plan, Some(&other)).unwrap();
            assert!(!std::ptr::eq(&*made, &*other), "change {i} kept");
            assert_eq!(made, last, "change {i}");
        }
        assert_eq!(r.state_after(&plan, None).unwrap(), last);
    }
}
