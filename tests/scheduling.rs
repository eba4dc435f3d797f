//! The scheduling recipes of `docs/scheduling/` are valid: the systemd
//! units pass `systemd-analyze verify`, the cron line has five valid
//! fields, and the flags both use are accepted by `tribo run`.

use std::path::Path;
use std::process::Command;

use crate::common;

fn docs() -> std::path::PathBuf {
    common::root().join("docs/scheduling")
}

/// The `tribo run` arguments after the binary in a command line.
fn tribo_args(line: &str) -> Vec<String> {
    let words: Vec<&str> = line.split_whitespace().collect();
    let at = words
        .iter()
        .position(|w| w.ends_with("/tribo"))
        .expect("a tribo command");
    words[at + 1..]
        .iter()
        .take_while(|w| !w.starts_with(">>") && !w.starts_with("2>"))
        .map(|w| w.to_string())
        .collect()
}

/// The flags are accepted: the same command, on the demo, as a dry run.
fn flags_are_accepted(args: &[String]) {
    assert_eq!(args[0], "run");
    let mut real: Vec<&str> = vec!["run", "pipelines/demo.toml", "--dry-run"];
    real.extend(args[2..].iter().map(String::as_str));
    let o = common::tribo(&common::root(), &real);
    assert_eq!(
        o.status.code(),
        Some(0),
        "{:?}: {}",
        real,
        String::from_utf8_lossy(&o.stderr)
    );
}

fn valid_cron_field(f: &str, lo: u32, hi: u32) -> bool {
    f.split(',').all(|part| {
        let (range, step) = match part.split_once('/') {
            Some((r, s)) => (r, s.parse::<u32>().is_ok_and(|s| s > 0)),
            None => (part, true),
        };
        let in_range = |v: &str| v.parse::<u32>().is_ok_and(|v| (lo..=hi).contains(&v));
        let range_ok = range == "*"
            || in_range(range)
            || range
                .split_once('-')
                .is_some_and(|(a, b)| in_range(a) && in_range(b));
        step && range_ok
    })
}

#[test]
fn the_cron_line_is_valid() {
    let text = std::fs::read_to_string(docs().join("crontab")).unwrap();
    let line = text
        .lines()
        .find(|l| !l.trim().is_empty() && !l.starts_with('#'))
        .unwrap();
    let fields: Vec<&str> = line.split_whitespace().take(5).collect();
    let bounds = [(0, 59), (0, 23), (1, 31), (1, 12), (0, 7)];
    for (f, (lo, hi)) in fields.iter().zip(bounds) {
        assert!(valid_cron_field(f, lo, hi), "cron field {f} in {line}");
    }
    assert!(!valid_cron_field("61", 0, 59));
    flags_are_accepted(&tribo_args(line));
}

#[test]
fn the_systemd_units_verify() {
    let service = std::fs::read_to_string(docs().join("tribo-nightly.service")).unwrap();
    let exec = service
        .lines()
        .find_map(|l| l.strip_prefix("ExecStart="))
        .unwrap();
    flags_are_accepted(&tribo_args(exec));
    let Ok(o) = Command::new("systemd-analyze").arg("--version").output() else {
        eprintln!("skipped: systemd-analyze is not installed; the units were not verified");
        return;
    };
    assert!(o.status.success());
    // The units as installed, with the binary built here in place of
    // /usr/local/bin/tribo (verify checks that it exists).
    let dir = tempfile::tempdir().unwrap();
    let bin = env!("CARGO_BIN_EXE_tribo");
    std::fs::write(
        dir.path().join("tribo-nightly.service"),
        service
            .replace("/usr/local/bin/tribo", bin)
            .replace("/srv/lab", &dir.path().display().to_string()),
    )
    .unwrap();
    std::fs::copy(
        docs().join("tribo-nightly.timer"),
        dir.path().join("tribo-nightly.timer"),
    )
    .unwrap();
    let units: Vec<String> = ["tribo-nightly.timer", "tribo-nightly.service"]
        .iter()
        .map(|u| dir.path().join(u).display().to_string())
        .collect();
    let o = Command::new("systemd-analyze")
        .arg("verify")
        .args(&units)
        .env("SYSTEMD_LOG_LEVEL", "warning")
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(o.status.success(), "systemd-analyze verify: {err}");
    assert!(Path::new(&units[0]).exists());
}
