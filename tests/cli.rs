//! The binary in a temporary folder: exit codes, error reporting for bad
//! files in a batch, and `inspect --json`.

use crate::common;

use tribo::table::Table;

/// A batch with bad files: the good file's results are written, each bad
/// file is listed in errors.parquet with file, line and column, and the exit
/// code is 1. A non-monotonic time axis is a per-trace status, not an error.
#[test]
fn bad_files_are_listed_and_do_not_stop_the_batch() {
    let dir = tempfile::tempdir().unwrap();
    let root = common::root();
    let good = root.join("fixtures/friction/sled_mN.csv");
    let bad = root.join("fixtures/bad");
    let out = dir.path().join("out");
    let mut args: Vec<String> = vec!["friction".into(), good.display().to_string()];
    for f in [
        "bad_cell.csv",
        "unknown_unit.csv",
        "empty.csv",
        "non_monotonic.csv",
    ] {
        args.push(bad.join(f).display().to_string());
    }
    args.extend(["--out".into(), out.display().to_string()]);
    let o = common::tribo(
        dir.path(),
        &args.iter().map(String::as_str).collect::<Vec<_>>(),
    );
    assert_eq!(
        o.status.code(),
        Some(1),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );

    let (errors, _) = Table::read_parquet(&out.join("errors.parquet")).unwrap();
    let sources = errors.str("source").unwrap();
    let messages = errors.str("message").unwrap();
    let message = |name: &str| {
        let i = sources
            .iter()
            .position(|s| s.as_deref().unwrap().ends_with(name))
            .unwrap();
        messages[i].clone().unwrap()
    };
    assert_eq!(errors.height(), 3);
    let m = message("bad_cell.csv");
    assert!(
        m.contains("line 4") && m.contains("column 'Fx (N)'") && m.contains("'abc'"),
        "{m}"
    );
    let m = message("unknown_unit.csv");
    assert!(m.contains("furlong") && m.contains("column 'Fx'"), "{m}");
    let m = message("empty.csv");
    assert!(m.contains("no data"), "{m}");

    let (friction, _) = Table::read_parquet(&out.join("friction.parquet")).unwrap();
    let status = common::status_texts(&friction);
    let src = friction.str("source").unwrap();
    let i = src
        .iter()
        .position(|s| s.as_deref().unwrap().ends_with("non_monotonic.csv"))
        .unwrap();
    assert!(status[i]
        .as_deref()
        .unwrap()
        .starts_with("non_monotonic_time: time does not increase at sample 4"));
    let j = src
        .iter()
        .position(|s| s.as_deref().unwrap().ends_with("sled_mN.csv"))
        .unwrap();
    assert_eq!(status[j].as_deref(), Some("ok"));
}

/// Usage and configuration errors exit with 2 and say what is wrong.
#[test]
fn configuration_errors_exit_2() {
    let dir = tempfile::tempdir().unwrap();
    let o = common::tribo(dir.path(), &["run", "missing.toml"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("missing.toml"));

    let p = dir.path().join("p.toml");
    std::fs::write(
        &p,
        "[input]\nfiles = [\"*.csv\"]\n[output]\ndir = \"o\"\n[friction]\npeak_factor = 3\n",
    )
    .unwrap();
    let o = common::tribo(dir.path(), &["run", "p.toml"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(
        String::from_utf8_lossy(&o.stderr).contains("peak_factor"),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );

    std::fs::write(
        &p,
        "[input]\nfiles = [\"nothing_here/*.csv\"]\n[output]\ndir = \"o\"\n",
    )
    .unwrap();
    let o = common::tribo(dir.path(), &["run", "p.toml"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("matches no file"));

    let o = common::tribo(dir.path(), &["friction"]);
    assert_eq!(o.status.code(), Some(2), "clap usage error");
}

/// `inspect --json` reports the dialect, units and roles of a file.
#[test]
fn inspect_json_describes_the_file() {
    let dir = tempfile::tempdir().unwrap();
    let f = common::root().join("fixtures/friction/reciprocating_latin1.csv");
    let o = common::tribo(dir.path(), &["inspect", "--json", f.to_str().unwrap()]);
    assert!(o.status.success());
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let i = &v[0];
    assert_eq!(i["dialect"]["encoding"], "latin1");
    assert_eq!(i["dialect"]["delimiter"], ";");
    assert_eq!(i["dialect"]["decimal"], ",");
    let s = &i["sections"][0];
    assert_eq!(s["rows"], 1200);
    assert!((s["sample_rate_hz"].as_f64().unwrap() - 100.0).abs() < 1e-6);
    let cols = s["columns"].as_array().unwrap();
    let col = |name: &str| cols.iter().find(|c| c["name"] == name).unwrap();
    assert_eq!(col("Temp")["unit"], "°C");
    assert_eq!(col("Temp")["role"], "temperature");
    assert_eq!(col("Ft")["role"], "friction_force");
    assert_eq!(col("Fn")["role"], "normal_force");
    assert_eq!(col("Time")["si_unit"], "s");
}

/// `--help` names every subcommand.
#[test]
fn help_lists_the_subcommands() {
    let dir = tempfile::tempdir().unwrap();
    let o = common::tribo(dir.path(), &["--help"]);
    let text = String::from_utf8_lossy(&o.stdout);
    for cmd in ["inspect", "friction", "run"] {
        assert!(text.contains(cmd), "{text}");
    }
}

/// Output into a pipe whose reader has gone (`tribo inspect F | head -1`)
/// ends the process by SIGPIPE, as any Unix tool, not by a panic.
#[cfg(unix)]
#[test]
fn output_into_a_closed_pipe_ends_quietly() {
    use std::os::fd::{FromRawFd, OwnedFd};
    use std::os::unix::process::ExitStatusExt;
    use std::process::{Command, Stdio};
    let mut fds = [0; 2];
    // SAFETY: `pipe` fills both descriptors, each then owned once.
    assert_eq!(unsafe { libc::pipe(fds.as_mut_ptr()) }, 0);
    let (read, write) = unsafe { (OwnedFd::from_raw_fd(fds[0]), OwnedFd::from_raw_fd(fds[1])) };
    drop(read);
    let file = common::root().join("fixtures/friction/sled_mN.csv");
    let o = Command::new(env!("CARGO_BIN_EXE_tribo"))
        .args(["inspect", file.to_str().unwrap()])
        .stdout(Stdio::from(write))
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(!err.contains("panicked"), "{err}");
    assert_eq!(
        o.status.signal(),
        Some(libc::SIGPIPE),
        "{:?}: {err}",
        o.status
    );
}
