//! One run at a time per output folder: `OUT/.tribo/lock` holds the pid,
//! host and start time of the run that writes there. A second run exits
//! with a configuration error naming the holder, or waits (`--wait`); a
//! lock whose process is gone from this host (a killed run) is taken over.
//! A lock held on another host (a folder shared over the network) is never
//! taken over: whether its run is alive cannot be told from here, and the
//! message says how to free it.

use std::fs;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant, SystemTime, UNIX_EPOCH};

use super::owner::{host_name, Liveness, Owner};
use crate::error::{Error, Result};

/// Held while a run writes into its output folder; released on drop.
#[derive(Debug)]
pub struct Lock {
    path: PathBuf,
}

impl Lock {
    /// Takes the lock of `out_dir`, waiting up to `wait` for a live holder.
    pub fn take(out_dir: &Path, wait: Duration) -> Result<Lock> {
        let dir = out_dir.join(".tribo");
        fs::create_dir_all(&dir).map_err(|e| Error::io(&dir, e))?;
        let path = dir.join("lock");
        remove_gone_drafts(&dir);
        let start = Instant::now();
        loop {
            match try_create(&path) {
                Ok(()) => return Ok(Lock { path }),
                Err(e) if e.kind() != std::io::ErrorKind::AlreadyExists => {
                    return Err(Error::io(&path, e))
                }
                Err(_) => {}
            }
            let holder = fs::read_to_string(&path).unwrap_or_default();
            if is_stale(&holder, &path) {
                // Rename first: of two runs taking over at once, one wins.
                let aside = dir.join(format!("lock.stale.{}", std::process::id()));
                if fs::rename(&path, &aside).is_ok() {
                    let _ = fs::remove_file(&aside);
                }
                continue;
            }
            if start.elapsed() >= wait {
                let elsewhere = holder_of(&holder)
                    .filter(|o| o.liveness() == Liveness::Elsewhere)
                    .map(|o| {
                        format!(
                            "; if no tribo run is alive on {}, remove {}",
                            o.host,
                            path.display()
                        )
                    })
                    .unwrap_or_default();
                return Err(Error::Config(format!(
                    "output folder {} is in use by another tribo run ({}); \
                     wait for it, or pass --wait SECONDS{elsewhere}",
                    out_dir.display(),
                    holder.trim()
                )));
            }
            std::thread::sleep(Duration::from_millis(100));
        }
    }
}

impl Drop for Lock {
    fn drop(&mut self) {
        let _ = fs::remove_file(&self.path);
    }
}

/// Creates the lock with its holder in one step: the holder is written to
/// a file of this process's own, then linked to the lock's name, which
/// fails when the lock exists. A run killed at any point leaves either no
/// lock or a whole one (a bare `create_new` then `write` could leave an
/// empty lock that no one may take over for a while), and at most its own
/// `lock.PID.new`, which [`remove_gone_drafts`] clears.
fn try_create(path: &Path) -> std::io::Result<()> {
    let draft = path.with_file_name(format!("lock.{}.new", std::process::id()));
    let since = SystemTime::now()
        .duration_since(UNIX_EPOCH)
        .map(|d| d.as_secs())
        .unwrap_or(0);
    let host = host_name();
    let mut f = fs::File::create(&draft)?;
    write!(
        f,
        "pid {} started {since} (unix s) on {host}",
        std::process::id()
    )?;
    f.sync_all()?;
    let linked = fs::hard_link(&draft, path);
    let _ = fs::remove_file(&draft);
    linked
}

/// Removes the lock drafts of runs gone from this host (killed between
/// writing a draft and linking it).
fn remove_gone_drafts(dir: &Path) {
    let Ok(entries) = fs::read_dir(dir) else {
        return;
    };
    for e in entries.flatten() {
        let name = e.file_name();
        let pid = name
            .to_str()
            .and_then(|n| n.strip_prefix("lock."))
            .and_then(|n| n.strip_suffix(".new"))
            .and_then(|n| n.parse::<u32>().ok());
        let gone = pid.is_some_and(|pid| {
            let owner = Owner {
                pid,
                host: host_name(),
            };
            owner.liveness() == Liveness::Gone
        });
        if gone {
            let _ = fs::remove_file(e.path());
        }
    }
}

/// The holder a lock names: `pid N ... on HOST` (a lock without a host,
/// written by an older version, was taken on this host).
fn holder_of(holder: &str) -> Option<Owner> {
    let words: Vec<&str> = holder.split_whitespace().collect();
    let pid = words.get(1)?.parse::<u32>().ok()?;
    let host = match words.iter().position(|w| *w == "on") {
        Some(i) => words.get(i + 1)?.to_string(),
        None => host_name(),
    };
    Some(Owner { pid, host })
}

/// A lock is stale when its process is gone from this host. A lock
/// without a whole holder (written by an older version, killed between
/// creating and writing it) is stale once a few seconds old.
fn is_stale(holder: &str, path: &Path) -> bool {
    let Some(owner) = holder_of(holder) else {
        let age = fs::metadata(path)
            .and_then(|m| m.modified())
            .ok()
            .and_then(|t| t.elapsed().ok());
        return age.is_some_and(|a| a > Duration::from_secs(5));
    };
    owner.liveness() == Liveness::Gone
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_lock_is_taken_over_only_from_a_run_gone_from_this_host() {
        let dir = tempfile::tempdir().unwrap();
        let lock = dir.path().join(".tribo/lock");
        fs::create_dir_all(lock.parent().unwrap()).unwrap();
        let gone = crate::pipeline::owner::tests::dead_pid();
        let me = Owner::me();
        let cases = [
            (
                format!("pid {gone} started 1 (unix s) on {}", me.host),
                true,
            ),
            (format!("pid {gone} started 1 (unix s)"), true),
            (
                format!("pid {} started 1 (unix s) on {}", me.pid, me.host),
                false,
            ),
            (
                format!("pid {gone} started 1 (unix s) on other-node"),
                false,
            ),
        ];
        for (holder, stale) in cases {
            fs::write(&lock, &holder).unwrap();
            let taken = Lock::take(dir.path(), Duration::ZERO);
            assert_eq!(taken.is_ok(), stale, "{holder}");
            if let Err(e) = taken {
                let m = e.to_string();
                assert!(m.contains("in use by another tribo run"), "{m}");
                let remote = holder.ends_with("other-node");
                assert_eq!(m.contains("if no tribo run is alive on other-node"), remote);
            }
            let _ = fs::remove_file(&lock);
        }
    }

    /// A taken lock holds its whole holder; a draft left by a run killed
    /// before linking it is removed by the next run, and a live run's
    /// draft is left alone.
    #[test]
    fn a_lock_is_whole_and_a_gone_runs_draft_is_cleared() {
        let dir = tempfile::tempdir().unwrap();
        let tribo = dir.path().join(".tribo");
        fs::create_dir_all(&tribo).unwrap();
        let gone = crate::pipeline::owner::tests::dead_pid();
        let me = Owner::me();
        let (dead, live) = (
            tribo.join(format!("lock.{gone}.new")),
            tribo.join(format!("lock.{}.new", std::os::unix::process::parent_id())),
        );
        fs::write(&dead, "pid").unwrap();
        fs::write(&live, "pid").unwrap();
        let lock = Lock::take(dir.path(), Duration::ZERO).unwrap();
        assert!(!dead.exists(), "a gone run's draft is removed");
        assert!(live.exists(), "a live run's draft is kept");
        let holder = fs::read_to_string(tribo.join("lock")).unwrap();
        assert_eq!(holder_of(&holder).map(|o| o.pid), Some(me.pid), "{holder}");
        assert!(!tribo.join(format!("lock.{}.new", me.pid)).exists());
        drop(lock);
        assert!(!tribo.join("lock").exists());
    }
}
