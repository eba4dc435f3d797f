//! Who made a lock or a temporary name: the host and process id, so that
//! the next run removes what a killed run left and never what a run
//! still alive made (here, or on another node sharing the folder over a
//! network file system).
//!
//! A temporary name is `<prefix>.<random>.<pid>@<host>.tmp`: unpredictable
//! (a planted link is never followed) and telling its owner.

use std::fmt;

/// A process on a host.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Owner {
    /// Its process id.
    pub pid: u32,
    /// The name of its host.
    pub host: String,
}

/// Whether an owner's process may still be running.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Liveness {
    /// Running on this host.
    Alive,
    /// Not running on this host any more.
    Gone,
    /// On another host: cannot be told from here, so taken as alive.
    Elsewhere,
}

impl Owner {
    /// This process.
    pub fn me() -> Owner {
        Owner {
            pid: std::process::id(),
            host: host_name(),
        }
    }

    /// Whether its process may still be running.
    pub fn liveness(&self) -> Liveness {
        if self.host != host_name() {
            return Liveness::Elsewhere;
        }
        match pid_alive(self.pid) {
            true => Liveness::Alive,
            false => Liveness::Gone,
        }
    }

    /// The owner written in a temporary name made by [`temp_name`].
    pub fn of_temp_name(name: &str) -> Option<Owner> {
        let stem = name.strip_suffix(".tmp")?;
        let (before, host) = stem.rsplit_once('@')?;
        let (_, pid) = before.rsplit_once('.')?;
        Some(Owner {
            pid: pid.parse().ok()?,
            host: host.to_string(),
        })
    }
}

impl fmt::Display for Owner {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "pid {} on {}", self.pid, self.host)
    }
}

/// A unique, unpredictable temporary name that tells its owner.
pub fn temp_name(prefix: &str) -> String {
    let me = Owner::me();
    format!(
        "{prefix}.{:016x}.{}@{}.tmp",
        rand::random::<u64>(),
        me.pid,
        me.host
    )
}

/// Whether `name` is a temporary name whose owner is gone: a leftover of
/// a killed run, to remove. `legacy`: what to say of a temporary name
/// that tells no owner (made by an older version).
pub fn is_leftover(name: &str, legacy: bool) -> bool {
    match Owner::of_temp_name(name) {
        Some(o) => o.liveness() == Liveness::Gone,
        None => legacy,
    }
}

/// This host's name (`localhost` when it cannot be told). Characters that
/// do not belong in a file name are replaced.
pub fn host_name() -> String {
    static HOST: std::sync::OnceLock<String> = std::sync::OnceLock::new();
    HOST.get_or_init(|| {
        let raw = system_host_name().unwrap_or_default();
        let clean: String = raw
            .trim()
            .chars()
            .map(
                |c| match c.is_ascii_alphanumeric() || c == '-' || c == '.' {
                    true => c,
                    false => '_',
                },
            )
            .collect();
        match clean.is_empty() {
            true => "localhost".into(),
            false => clean,
        }
    })
    .clone()
}

#[cfg(unix)]
fn system_host_name() -> Option<String> {
    let mut buf = [0u8; 256];
    // SAFETY: the buffer is valid for its length; the name is cut at the
    // first NUL (or at the buffer's end).
    let rc = unsafe { libc::gethostname(buf.as_mut_ptr().cast(), buf.len()) };
    if rc != 0 {
        return None;
    }
    let end = buf.iter().position(|&b| b == 0).unwrap_or(buf.len());
    Some(String::from_utf8_lossy(&buf[..end]).into_owned())
}

#[cfg(not(unix))]
fn system_host_name() -> Option<String> {
    std::env::var("COMPUTERNAME").ok()
}

/// Whether process `pid` runs on this host (signal 0 checks without
/// sending anything: `EPERM` means it runs as another user).
#[cfg(unix)]
fn pid_alive(pid: u32) -> bool {
    let Ok(pid) = libc::pid_t::try_from(pid) else {
        return false;
    };
    if pid <= 0 {
        return false;
    }
    // SAFETY: kill with signal 0 sends nothing; it only checks the pid.
    let rc = unsafe { libc::kill(pid, 0) };
    rc == 0 || std::io::Error::last_os_error().raw_os_error() == Some(libc::EPERM)
}

/// Where it cannot be told, a process is taken as alive.
#[cfg(not(unix))]
fn pid_alive(_pid: u32) -> bool {
    true
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;

    #[test]
    fn a_temporary_name_tells_its_owner() {
        let name = temp_name(".friction.parquet");
        assert!(name.starts_with(".friction.parquet.") && name.ends_with(".tmp"));
        assert_eq!(Owner::of_temp_name(&name), Some(Owner::me()));
        assert_ne!(temp_name("x"), temp_name("x"));
        let other = "set.0123456789abcdef.42@node-7.cluster.lab.tmp";
        assert_eq!(
            Owner::of_temp_name(other),
            Some(Owner {
                pid: 42,
                host: "node-7.cluster.lab".into()
            })
        );
        for none in ["set.1234.abcdef.tmp", "x.parquet", "a@b.tmp", "a.x@h.tmp"] {
            assert_eq!(Owner::of_temp_name(none), None, "{none}");
        }
    }

    #[test]
    fn only_the_names_of_gone_processes_on_this_host_are_leftovers() {
        let me = Owner::me();
        assert_eq!(me.liveness(), Liveness::Alive);
        let mine = format!("set.00.{}@{}.tmp", me.pid, me.host);
        assert!(!is_leftover(&mine, true));
        let elsewhere = format!("set.00.{}@{}x.tmp", me.pid, me.host);
        assert!(!is_leftover(&elsewhere, true));
        let gone = dead_pid();
        assert!(is_leftover(
            &format!("set.00.{gone}@{}.tmp", me.host),
            false
        ));
        assert!(is_leftover("set.1234.abcdef.tmp", true));
        assert!(!is_leftover("set.1234.abcdef.tmp", false));
    }

    /// The pid of a child that has exited and been waited for.
    pub(crate) fn dead_pid() -> u32 {
        let mut child = std::process::Command::new("true").spawn().unwrap();
        let pid = child.id();
        child.wait().unwrap();
        pid
    }
}
