//! One run at a time per output folder: `OUT/.tribo/lock` holds the pid
//! and start time of the run that writes there. A second run exits with
//! a configuration error naming the holder, or waits (`--wait`); a lock
//! whose process is gone (a killed run) is taken over.

use std::fs::{self, OpenOptions};
use std::io::Write;
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant, SystemTime, UNIX_EPOCH};

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
                return Err(Error::Config(format!(
                    "output folder {} is in use by another tribo run ({}); \
                     wait for it, or pass --wait SECONDS",
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

fn try_create(path: &Path) -> std::io::Result<()> {
    let mut f = OpenOptions::new().write(true).create_new(true).open(path)?;
    let since = SystemTime::now()
        .duration_since(UNIX_EPOCH)
        .map(|d| d.as_secs())
        .unwrap_or(0);
    write!(f, "pid {} started {} (unix s)", std::process::id(), since)?;
    f.sync_all()
}

/// A lock is stale when its process no longer exists. Where that cannot be
/// told (no `/proc`), it is assumed alive. A lock without a pid (a run
/// killed between creating and writing it) is stale once a few seconds old.
fn is_stale(holder: &str, path: &Path) -> bool {
    let pid = holder
        .split_whitespace()
        .nth(1)
        .and_then(|p| p.parse::<u32>().ok());
    let Some(pid) = pid else {
        let age = fs::metadata(path)
            .and_then(|m| m.modified())
            .ok()
            .and_then(|t| t.elapsed().ok());
        return age.is_some_and(|a| a > Duration::from_secs(5));
    };
    let proc = Path::new("/proc");
    proc.is_dir() && !proc.join(pid.to_string()).exists()
}
