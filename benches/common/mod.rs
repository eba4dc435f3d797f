//! What the benchmarks that run whole processes share: timing a command
//! under `/usr/bin/time` (median of several runs, peak resident memory) and
//! finding the peer scripts and the Python that runs them.

#![allow(dead_code)] // each benchmark uses its own part

use std::path::{Path, PathBuf};
use std::process::Command;

/// Whole-process seconds (wall, and CPU: user + system) and peak resident
/// set (MB) of one command. On a machine shared with other work the CPU
/// seconds scatter less than the wall seconds.
#[derive(Clone, Copy)]
pub struct Measured {
    pub secs: f64,
    pub cpu_secs: f64,
    pub rss_mb: f64,
}

/// The median time and the largest peak of [`repeats`] runs of `program
/// args`: a peer's time scatters from run to run (a polars peer from 2.3
/// to 4.7 s on the same file), so one run's ratio says little. A tribo
/// command names its output folder as `fresh`, removed before each run so
/// that no run finds the previous one's cache.
pub fn measure_in(program: &Path, args: &[&str], fresh: Option<&Path>) -> Option<Measured> {
    let mut all: Vec<Measured> = (0..repeats())
        .map(|_| {
            if let Some(dir) = fresh {
                let _ = std::fs::remove_dir_all(dir);
            }
            measure_once(program, args)
        })
        .collect::<Option<_>>()?;
    all.sort_by(|a, b| a.secs.total_cmp(&b.secs));
    let mut cpu: Vec<f64> = all.iter().map(|m| m.cpu_secs).collect();
    cpu.sort_by(f64::total_cmp);
    Some(Measured {
        secs: all[all.len() / 2].secs,
        cpu_secs: cpu[cpu.len() / 2],
        rss_mb: all.iter().map(|m| m.rss_mb).fold(0.0, f64::max),
    })
}

/// [`measure_in`] of a command that writes nothing to keep.
pub fn measure(program: &Path, args: &[&str]) -> Option<Measured> {
    measure_in(program, args, None)
}

/// Runs per whole-process measurement (`TRIBO_BENCH_RUNS`, default 3).
pub fn repeats() -> usize {
    std::env::var("TRIBO_BENCH_RUNS")
        .ok()
        .and_then(|v| v.parse().ok())
        .filter(|&n| n > 0)
        .unwrap_or(3)
}

/// Runs `program args` under `/usr/bin/time -f "%e %M %U %S"`; `None` when it
/// fails (said so).
fn measure_once(program: &Path, args: &[&str]) -> Option<Measured> {
    let out = Command::new("/usr/bin/time")
        .args(["-f", "%e %M %U %S"])
        .arg(program)
        .args(args)
        .output()
        .ok()?;
    if !out.status.success() {
        println!(
            "{} {args:?} failed: {}",
            program.display(),
            String::from_utf8_lossy(&out.stderr)
        );
        return None;
    }
    let stderr = String::from_utf8_lossy(&out.stderr);
    let last = stderr.lines().last()?;
    let mut it = last.split_whitespace();
    let secs = it.next()?.parse().ok()?;
    let kb: f64 = it.next()?.parse().ok()?;
    let user: f64 = it.next()?.parse().ok()?;
    let system: f64 = it.next()?.parse().ok()?;
    Some(Measured {
        secs,
        cpu_secs: user + system,
        rss_mb: kb / 1024.0,
    })
}

/// Whether `python` can import `modules` (said so when not).
pub fn python_has(python: &Path, modules: &str) -> bool {
    let ok = Command::new(python)
        .args(["-c", &format!("import {modules}")])
        .output()
        .is_ok_and(|o| o.status.success());
    if !ok {
        println!(
            "peers needing {modules}: skipped ({} lacks them)",
            python.display()
        );
    }
    ok
}

/// The repository root: as `cargo bench` gives it when it runs the
/// benchmark, so that a binary built from another checkout into a shared
/// target folder looks here, not where it was built.
pub fn root() -> PathBuf {
    std::env::var_os("CARGO_MANIFEST_DIR")
        .map_or_else(|| PathBuf::from(env!("CARGO_MANIFEST_DIR")), PathBuf::from)
}

/// A script of `benches/peers/`.
pub fn peer(script: &str) -> String {
    root()
        .join("benches/peers")
        .join(script)
        .display()
        .to_string()
}

/// The Python that runs the peers: `TRIBO_PEER_PYTHON`, else the virtual
/// environment `scripts/python-tests.sh` makes in the cargo target folder
/// (it holds surfalize and SurfaceTopography), else `python3`.
pub fn peer_python() -> PathBuf {
    if let Some(p) = std::env::var_os("TRIBO_PEER_PYTHON") {
        return PathBuf::from(p);
    }
    let venv = std::env::var_os("CARGO_TARGET_DIR")
        .map(PathBuf::from)
        .unwrap_or_else(|| root().join("target"))
        .join("python-venv/bin/python");
    if venv.exists() {
        venv
    } else {
        PathBuf::from("python3")
    }
}

/// The release binary of this package.
pub fn tribo() -> &'static Path {
    Path::new(env!("CARGO_BIN_EXE_tribo"))
}

/// The load average, printed at the start and end of a benchmark.
pub fn load_average() -> String {
    std::fs::read_to_string("/proc/loadavg")
        .unwrap_or_default()
        .trim()
        .to_string()
}
