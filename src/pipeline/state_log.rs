//! The state as a base and a log of changes: `OUT/.tribo/state.bin` holds
//! the state as some run left it, `OUT/.tribo/state.log` what each later
//! run changed (the inputs that came, went or changed, the stages, the
//! tables). A nightly run that adds one file to a large archive appends a
//! record of that file instead of rewriting the whole state (8 MB at
//! 20 000 inputs, synced to disk); once the log outgrows half the base
//! (or holds [`MAX_RECORDS`]), the next run writes a new base and drops
//! the log.
//!
//! The log begins with the BLAKE3 of the base it follows; each record
//! carries its length and the BLAKE3 of its bytes. A record cut short by a
//! kill, or a log that follows another base (a compaction killed before it
//! removed the log), ends what is applied: the state is then the one of the
//! last record written whole, as it was of the last state written whole
//! before (whatever changed since is redone).

use std::collections::BTreeMap;
use std::fs::OpenOptions;
use std::io::{Seek, SeekFrom, Write};
use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};

use super::binfile;
use super::keys::Key;
use super::shared::Shared;
use super::splice::Splice;
use super::state::{self, Composition, Doubts, FileState, StageState, State, TableState};
use crate::error::{Error, Result};
use crate::ingest::source::Source;

/// The log's first bytes, before the base's BLAKE3.
const MAGIC: &[u8; 8] = b"tribolg1";
/// Magic and base hash.
const HEADER: usize = 8 + 32;
/// The base's first bytes: the layout of the state it holds (`2`: an
/// input keeps the stats of the files beside it that decide its
/// companions). A base without them (an older layout) is not read: every
/// input is hashed again, once, and the cache is used as it is.
const BASE_TAG: &[u8; 8] = b"tribost2";
/// A record's length and BLAKE3.
const RECORD_HEAD: usize = 8 + 32;
/// A log is kept until it would outgrow half its base, or this.
const MIN_LIMIT: u64 = 256 << 10;
/// Or until it holds this many records (each applied by every load).
const MAX_RECORDS: usize = 64;

/// The log's file.
pub(super) fn path(out_dir: &Path) -> PathBuf {
    out_dir.join(".tribo").join("state.log")
}

/// Where the log stood when the state was loaded: the base it follows,
/// the length of its records read whole (`0`: none, or no log) and their
/// number.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct LogAt {
    base: [u8; 32],
    base_len: u64,
    valid: u64,
    records: usize,
}

/// The state of `out_dir` and where its log stands, or empty when there
/// is none (or it cannot be read: then everything is redone).
pub fn load(out_dir: &Path) -> (State, Option<LogAt>) {
    match base(&state::path(out_dir)) {
        Ok(base) => match load_on(out_dir, base.bytes()) {
            Some((state, at)) => (state, Some(at)),
            None => (State::default(), None),
        },
        // A folder written by an older build: its JSON state, once.
        Err(_) => {
            let json = binfile::read(&state::json_path(out_dir), None);
            (json.unwrap_or_default(), None)
        }
    }
}

/// The state from its base's `bytes` with the log applied, and where the
/// log stands; `None` when the base cannot be read.
fn load_on(out_dir: &Path, bytes: &[u8]) -> Option<(State, LogAt)> {
    let mut state: State = binfile::decode(bytes.strip_prefix(BASE_TAG)?)?;
    let mut at = LogAt {
        base: *blake3::hash(bytes).as_bytes(),
        base_len: bytes.len() as u64,
        valid: 0,
        records: 0,
    };
    if let Ok(log) = std::fs::read(path(out_dir)) {
        (at.valid, at.records) = apply_log(&mut state, &log, &at.base);
    }
    Some((state, at))
}

/// The base's bytes, mapped (read only where the file system cannot map
/// it): read into fresh memory, its 8 MB at 20 000 inputs cost an added
/// file's run as much again to zero and copy as to decode
/// (`docs/speed.md`, "Allocator"). A base is only ever replaced whole
/// (written beside and renamed over, [`binfile::write`]), never rewritten
/// in place, so the mapped file does not change under the decoder.
fn base(path: &Path) -> std::io::Result<Source> {
    let file = std::fs::File::open(path)?;
    // SAFETY: read-only and private; tribo replaces the file by a rename,
    // so the mapped inode keeps its bytes while it is mapped.
    match unsafe { memmap2::Mmap::map(&file) } {
        Ok(map) => Ok(Source::Mapped(map)),
        Err(_) => std::fs::read(path).map(Source::Read),
    }
}

/// Applies the records of `log` that follow base `base`; the length of
/// the log read whole (0 when it follows another base) and the number of
/// records applied.
fn apply_log(state: &mut State, log: &[u8], base: &[u8; 32]) -> (u64, usize) {
    if log.len() < HEADER || &log[..8] != MAGIC || &log[8..HEADER] != base {
        return (0, 0);
    }
    let (mut at, mut records) = (HEADER, 0);
    while let Some(payload) = record_at(log, at) {
        let applied = binfile::decode::<Delta>(payload).and_then(|d| d.apply(state));
        if applied.is_none() {
            break;
        }
        at += RECORD_HEAD + payload.len();
        records += 1;
    }
    (at as u64, records)
}

/// The payload of the record at `at`, when it is whole.
fn record_at(log: &[u8], at: usize) -> Option<&[u8]> {
    let head = log.get(at..at + RECORD_HEAD)?;
    let len = usize::try_from(u64::from_le_bytes(head[..8].try_into().ok()?)).ok()?;
    let payload = log.get(at + RECORD_HEAD..(at + RECORD_HEAD).checked_add(len)?)?;
    (blake3::hash(payload).as_bytes() == &head[8..]).then_some(payload)
}

/// Saves `new`, which follows `old` (loaded at `at`): nothing when they
/// are the same, else a record appended to the log, or a new base when
/// there is no log to append to or it would outgrow its limit.
pub fn save(out_dir: &Path, old: &State, at: Option<&LogAt>, new: &State) -> Result<()> {
    append_or_compact(out_dir, old, at, new)?;
    let _ = std::fs::remove_file(state::json_path(out_dir));
    Ok(())
}

fn append_or_compact(out_dir: &Path, old: &State, at: Option<&LogAt>, new: &State) -> Result<()> {
    let Some(at) = at else {
        return match new == old {
            true => Ok(()),
            false => compact(out_dir, new),
        };
    };
    // Unchanged: told by the inputs compared once, here, and the small
    // rest (an unchanged rerun writes nothing).
    let delta = Delta::between(old, new);
    let same = delta.files.is_empty() && delta.doubts.is_none() && new.context == old.context;
    if same && new.tables == old.tables && new.stages == old.stages {
        return Ok(());
    }
    let payload = binfile::encode(&delta)?;
    let start = at.valid.max(HEADER as u64);
    let end = start + (RECORD_HEAD + payload.len()) as u64;
    if end > (at.base_len / 2).max(MIN_LIMIT) || at.records >= MAX_RECORDS {
        return compact(out_dir, new);
    }
    let mut record = Vec::with_capacity(RECORD_HEAD + payload.len());
    record.extend_from_slice(&(payload.len() as u64).to_le_bytes());
    record.extend_from_slice(blake3::hash(&payload).as_bytes());
    record.extend_from_slice(&payload);
    append(&path(out_dir), at, &record).map_err(|e| Error::io(path(out_dir), e))
}

/// Writes `record` after the log's whole records (a torn one is cut off
/// first), starting the log when it has none, and syncs it.
fn append(path: &Path, at: &LogAt, record: &[u8]) -> std::io::Result<()> {
    let mut f = OpenOptions::new()
        .write(true)
        .create(true)
        .truncate(false)
        .open(path)?;
    if at.valid == 0 {
        f.set_len(0)?;
        f.write_all(MAGIC)?;
        f.write_all(&at.base)?;
    } else {
        f.set_len(at.valid)?;
        f.seek(SeekFrom::Start(at.valid))?;
    }
    f.write_all(record)?;
    f.sync_data()
}

/// Writes `state` as the new base and drops the log (which, should it
/// survive, follows the old base and is not applied).
fn compact(out_dir: &Path, state: &State) -> Result<()> {
    binfile::write_tagged(&state::path(out_dir), BASE_TAG, state)?;
    match std::fs::remove_file(path(out_dir)) {
        Err(e) if e.kind() != std::io::ErrorKind::NotFound => Err(Error::io(path(out_dir), e)),
        _ => Ok(()),
    }
}

/// What one run changed in the state.
#[derive(Debug, Serialize, Deserialize)]
struct Delta {
    /// Inputs that came or changed (`Some`) or went (`None`).
    files: Vec<(String, Option<Shared<FileState>>)>,
    /// The stages, without what they were joined from.
    stages: BTreeMap<String, StageState>,
    /// Per stage, what it was joined from, against the stage before.
    joined: BTreeMap<String, JoinedSplice>,
    /// The tables.
    tables: BTreeMap<String, TableState>,
    /// The warnings, when they changed.
    doubts: Option<Option<Doubts>>,
    /// The context of the inputs' keys.
    context: Option<Key>,
}

impl Delta {
    /// What turns `old` into `new`.
    fn between(old: &State, new: &State) -> Delta {
        let files = State::inputs_of_both(old, new)
            .filter(|(_, was, now)| was != now)
            .map(|(path, _, now)| (path.clone(), now.cloned()))
            .collect();
        let (mut stages, mut joined) = (BTreeMap::new(), BTreeMap::new());
        for (name, s) in &new.stages {
            let was = old.stages.get(name).map(|o| &o.joined);
            joined.insert(name.clone(), JoinedSplice::between(was, &s.joined));
            let without_joined = StageState {
                key: s.key,
                without_result: s.without_result,
                notes: s.notes.clone(),
                tables: s.tables.clone(),
                joined: Composition::default(),
            };
            stages.insert(name.clone(), without_joined);
        }
        Delta {
            files,
            stages,
            joined,
            tables: new.tables.clone(),
            doubts: (old.doubts != new.doubts).then(|| new.doubts.clone()),
            context: new.context,
        }
    }

    /// Applies the change to `state`; `None`, leaving it as it was, when
    /// the change does not follow it.
    fn apply(self, state: &mut State) -> Option<()> {
        let was = |name: &str| state.stages.get(name).map(|s| &s.joined);
        let fits = self.stages.keys().all(|name| {
            let splice = self.joined.get(name);
            splice.is_some_and(|j| j.fits(was(name)))
        });
        if !fits {
            return None;
        }
        let (mut stages, mut joined) = (self.stages, self.joined);
        for (name, s) in &mut stages {
            let mut c = state
                .stages
                .get_mut(name)
                .map_or_else(Composition::default, |o| std::mem::take(&mut o.joined));
            joined.remove(name)?.apply_to(&mut c);
            s.joined = c;
        }
        state.files.merge(self.files);
        state.stages = stages;
        state.tables = self.tables;
        if let Some(d) = self.doubts {
            state.doubts = d;
        }
        state.context = self.context;
        Some(())
    }
}

/// A stage's [`Composition`] against the one before it.
#[derive(Debug, Serialize, Deserialize)]
struct JoinedSplice {
    parts: Splice<super::keys::Key>,
    rows: BTreeMap<String, Splice<u64>>,
}

impl JoinedSplice {
    fn between(old: Option<&Composition>, new: &Composition) -> Self {
        let rows = new.rows.iter().map(|(table, now)| {
            let was = old.and_then(|o| o.rows.get(table));
            (
                table.clone(),
                Splice::between(was.map_or(&[], Vec::as_slice), now),
            )
        });
        JoinedSplice {
            parts: Splice::between(old.map_or(&[], |o| &o.parts), &new.parts),
            rows: rows.collect(),
        }
    }

    /// Whether it applies to `old` (`None`: the stage had none).
    fn fits(&self, old: Option<&Composition>) -> bool {
        let rows = |table: &str| old.and_then(|o| o.rows.get(table)).map_or(0, Vec::len);
        self.parts.fits(old.map_or(0, |o| o.parts.len()))
            && self.rows.iter().all(|(table, s)| s.fits(rows(table)))
    }

    /// Turns `c` into the new composition, in place (a list of 20 000
    /// keys is moved, not copied, by each record of the log); it
    /// [`fits`](Self::fits) `c`.
    fn apply_to(self, c: &mut Composition) {
        self.parts.apply_to(&mut c.parts);
        let mut rows = BTreeMap::new();
        for (table, splice) in self.rows {
            let mut v = c.rows.remove(&table).unwrap_or_default();
            splice.apply_to(&mut v);
            rows.insert(table, v);
        }
        c.rows = rows;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::pipeline::keys::Key;

    /// A state of `n` inputs and one stage joined from their parts.
    fn state(n: usize, tag: &str) -> State {
        let mut s = State::default();
        let mut joined = Composition::default();
        for i in 0..n {
            let key = Key::of_text(&format!("{tag}{i}"));
            let mut f = FileState {
                bytes: format!("b{i}").into(),
                ..Default::default()
            };
            f.parts.insert("friction".into(), key);
            s.files.insert(format!("in/{i:03}.csv"), f.into());
            joined.parts.push(key);
        }
        joined.rows.insert("friction".into(), vec![1; n]);
        s.stages.insert(
            "friction".into(),
            StageState {
                key: Key::of_text(tag),
                without_result: 0,
                notes: Vec::new(),
                tables: vec!["friction".into()],
                joined,
            },
        );
        s
    }

    #[test]
    fn a_run_appends_what_changed_and_a_torn_record_is_not_applied() {
        let dir = tempfile::tempdir().unwrap();
        let out = dir.path();
        let load = || super::load(out);
        let a = state(40, "a");
        save(out, &State::default(), None, &a).unwrap();
        assert!(!path(out).exists(), "a first save writes the base");
        let (got, at) = load();
        assert_eq!(got, a);
        save(out, &a, at.as_ref(), &a).unwrap();
        assert!(!path(out).exists(), "an unchanged state writes nothing");
        // One input added, one changed, one gone.
        let mut b = a.clone();
        b.files
            .insert("in/zzz.csv".into(), FileState::default().into());
        b.files.get_mut("in/005.csv").unwrap().make_mut().bytes = "changed".into();
        b.files.remove("in/007.csv");
        b.stages.get_mut("friction").unwrap().joined.parts[3] = Key::of_text("new");
        save(out, &a, at.as_ref(), &b).unwrap();
        let base = std::fs::metadata(state::path(out)).unwrap();
        let (got, at) = load();
        assert_eq!(got, b);
        let small = std::fs::metadata(path(out)).unwrap().len();
        assert!(small < base.len() / 4, "{small} of {}", base.len());
        let mut c = b.clone();
        c.doubts = Some(Doubts {
            key: Key::of_text("d"),
            rows: Vec::new(),
        });
        save(out, &b, at.as_ref(), &c).unwrap();
        assert_eq!(load().0, c);
        // The last record cut short by a kill: the state before it.
        let log = std::fs::read(path(out)).unwrap();
        std::fs::write(path(out), &log[..log.len() - 3]).unwrap();
        let (got, at) = load();
        assert_eq!(got, b);
        // The next record replaces the torn one.
        save(out, &b, at.as_ref(), &c).unwrap();
        assert_eq!(load().0, c);
        // A new base: a log left beside it follows the old one and is not
        // applied.
        let d = state(3, "d");
        save(out, &c, None, &d).unwrap();
        std::fs::write(path(out), &log).unwrap();
        assert_eq!(load().0, d);
    }

    /// A base is read only under its layout's tag: the same state's bytes
    /// without it (as a build before the tag wrote them) are refused,
    /// whatever they would decode to, and the next save writes a new base.
    #[test]
    fn a_base_of_another_layout_is_not_read() {
        let dir = tempfile::tempdir().unwrap();
        let out = dir.path();
        let a = state(5, "a");
        save(out, &State::default(), None, &a).unwrap();
        let tagged = std::fs::read(state::path(out)).unwrap();
        assert_eq!(&tagged[..8], BASE_TAG);
        assert_eq!(load(out).0, a);
        std::fs::write(state::path(out), binfile::encode(&a).unwrap()).unwrap();
        let (got, at) = load(out);
        assert_eq!((got, at), (State::default(), None));
        save(out, &State::default(), None, &a).unwrap();
        assert_eq!(std::fs::read(state::path(out)).unwrap(), tagged);
    }

    #[test]
    fn the_log_is_folded_into_a_new_base_once_it_outgrows_its_limit() {
        let dir = tempfile::tempdir().unwrap();
        let out = dir.path();
        let mut last = state(10, "s");
        save(out, &State::default(), None, &last).unwrap();
        let mut folded = false;
        for k in 0..400 {
            let (old, at) = load(out);
            assert_eq!(old, last, "run {k}");
            let new = state(10 + k, &format!("s{k}-"));
            save(out, &old, at.as_ref(), &new).unwrap();
            folded |= !path(out).exists();
            let log = std::fs::metadata(path(out)).map_or(0, |m| m.len());
            assert!(log <= MIN_LIMIT, "run {k}: {log}");
            last = new;
        }
        assert!(folded);
        assert_eq!(load(out).0, last);
    }

    #[test]
    fn a_log_of_small_records_is_folded_after_its_record_limit() {
        let dir = tempfile::tempdir().unwrap();
        let out = dir.path();
        let mut last = state(1000, "s");
        save(out, &State::default(), None, &last).unwrap();
        let mut records = Vec::new();
        for k in 0..2 * MAX_RECORDS {
            let (old, at) = load(out);
            assert_eq!(old, last, "run {k}");
            records.push(at.as_ref().unwrap().records);
            let mut new = old.clone();
            new.files
                .insert(format!("in/new{k:04}.csv"), FileState::default().into());
            new.stages
                .get_mut("friction")
                .unwrap()
                .joined
                .parts
                .push(Key::of_text(&format!("n{k}")));
            save(out, &old, at.as_ref(), &new).unwrap();
            last = new;
        }
        assert_eq!(records.iter().max(), Some(&MAX_RECORDS));
        assert_eq!(
            records.iter().filter(|&&n| n == 0).count(),
            2,
            "{records:?}"
        );
        assert_eq!(load(out).0, last);
    }
}
