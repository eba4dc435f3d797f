//! The last run's state, read while the plan lists the inputs: at 20 000
//! inputs each takes about 20 ms, mostly on one core, and neither needs
//! the other. A state read before the folder's lock is taken is used only
//! if its files are still the ones read once the lock is held (another
//! run may have published in between); otherwise it is read again.

use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex};
use std::thread::JoinHandle;

use super::stamp::Stamp;
use super::state::State;
use super::state_log::{self, LogAt};

/// A state and where its log stood, as [`state_log::load`] gives them.
pub type Loaded = (State, Option<LogAt>);

/// The stamps of the state's two files (base and log), before reading.
type Stamps = [Option<Stamp>; 2];

/// The thread reading it, until its state is taken.
type Reading = Mutex<Option<JoinHandle<(Stamps, Loaded)>>>;

/// A state being read on a thread of its own for the output folder `dir`.
#[derive(Clone)]
pub struct Preload {
    dir: PathBuf,
    reading: Arc<Reading>,
}

impl std::fmt::Debug for Preload {
    fn fmt(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
        write!(f, "Preload({})", self.dir.display())
    }
}

fn stamps(dir: &Path) -> Stamps {
    [super::state::path(dir), state_log::path(dir)].map(|p| Stamp::of(&p))
}

impl Preload {
    /// Begins reading the state of the output folder `dir` (`None`
    /// without a thread to be had: the run reads it then).
    pub fn start(dir: &Path) -> Option<Preload> {
        let owned = dir.to_path_buf();
        let handle = std::thread::Builder::new()
            .spawn(move || {
                let before = stamps(&owned);
                (before, state_log::load(&owned))
            })
            .ok()?;
        Some(Preload {
            dir: dir.to_path_buf(),
            reading: Arc::new(Mutex::new(Some(handle))),
        })
    }

    /// The state it read for `dir`, if its files are still what they were
    /// when it began (call with the folder's lock held); `None` when it
    /// is another folder's, was taken already, or is out of date.
    pub fn take(&self, dir: &Path) -> Option<Loaded> {
        if self.dir != dir {
            return None;
        }
        let handle = self.reading.lock().ok()?.take()?;
        let (before, loaded) = handle.join().ok()?;
        (before == stamps(dir)).then_some(loaded)
    }
}

/// The last run's state in `dir` (none with `force`): `preload`'s when
/// it is still current, else read now.
pub(super) fn last_state(dir: &Path, force: bool, preload: Option<&Preload>) -> Loaded {
    if force {
        return (State::default(), None);
    }
    preload
        .and_then(|p| p.take(dir))
        .unwrap_or_else(|| state_log::load(dir))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::pipeline::state::FileState;

    fn with_input(name: &str) -> State {
        let mut s = State::default();
        s.files.insert(name.into(), FileState::default().into());
        s
    }

    fn finished(p: &Preload) {
        while !p.reading.lock().unwrap().as_ref().unwrap().is_finished() {
            std::thread::sleep(std::time::Duration::from_millis(1));
        }
    }

    /// A state read ahead is the one `load` reads, once, for its folder
    /// only; one whose files changed after it was read is not used.
    #[test]
    fn a_state_read_ahead_is_used_only_while_current() {
        let dir = tempfile::tempdir().unwrap();
        let out = dir.path();
        let a = with_input("in/a.csv");
        state_log::save(out, &State::default(), None, &a).unwrap();
        let p = Preload::start(out).unwrap();
        assert!(p.take(&out.join("other")).is_none());
        let (got, at) = p.take(out).unwrap();
        assert_eq!((&got, &at), (&a, &state_log::load(out).1));
        assert!(p.take(out).is_none(), "taken once");
        // Another run publishes after the state was read: read again.
        let p = Preload::start(out).unwrap();
        finished(&p);
        let b = with_input("in/b.csv");
        state_log::save(out, &a, at.as_ref(), &b).unwrap();
        assert!(p.take(out).is_none());
        assert_eq!(last_state(out, false, Some(&p)).0, b);
        assert_eq!(last_state(out, true, None).0, State::default());
    }
}
