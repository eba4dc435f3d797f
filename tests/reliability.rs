//! Nothing lost, nothing mixed: one bad value fails its own file only; a
//! run killed at any moment, or two runs at once, never leave a mixed or
//! partial set of tables visible; temporary files are never reached
//! through a planted link and do not outlive the next run.

use std::collections::BTreeSet;
use std::path::Path;
use std::process::{Child, Command, Stdio};
use std::time::Duration;

use tribo::table::Table;

use crate::common;

/// A folder with the lab's traces and profiles and two pipelines that
/// differ in one friction parameter (so every table of one differs from
/// the other's in its `tribo.pipeline` metadata).
fn lab() -> tempfile::TempDir {
    let dir = tempfile::tempdir().unwrap();
    for sub in ["friction", "profiles"] {
        common::copy_tree(
            &common::root().join("fixtures/lab").join(sub),
            &dir.path().join("lab").join(sub),
        );
    }
    std::fs::copy(
        common::root().join("fixtures/lab/samples.csv"),
        dir.path().join("lab/samples.csv"),
    )
    .unwrap();
    for (name, factor) in [("a.toml", 3.0), ("b.toml", 4.0)] {
        std::fs::write(
            dir.path().join(name),
            format!(
                "stages = [\"friction\", \"roughness\", \"coulomb\"]\n[input]\nfiles = [\"lab/*/*\"]\n\
                 samples = \"lab/samples.csv\"\n[output]\ndir = \"out\"\n[friction]\n\
                 peak_noise_factor = {factor}\n[coulomb]\nby = [\"pattern\"]\n"
            ),
        )
        .unwrap();
    }
    dir
}

fn spawn(dir: &Path, pipeline: &str) -> Child {
    Command::new(env!("CARGO_BIN_EXE_tribo"))
        .current_dir(dir)
        .args(["run", pipeline, "--force"])
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .unwrap()
}

/// The visible set: every table readable, and all from one run (one
/// `tribo.pipeline` value; a dataset's files are each the provenance of
/// the run that made them, and are read through the set's manifest).
/// Returns the table names.
fn one_complete_set(out: &Path) -> BTreeSet<String> {
    let names = common::parquet_names(out);
    let runs: BTreeSet<String> = names
        .iter()
        .filter(|n| {
            // Readable (a dataset through the set's manifest).
            let _ = common::read_table(&out.join(n));
            n.ends_with(".parquet")
        })
        .map(|n| {
            let (_, kv) = Table::read_parquet(&out.join(n)).unwrap();
            kv.into_iter()
                .find(|(k, _)| k == "tribo.pipeline")
                .map(|(_, v)| v)
                .unwrap_or_default()
        })
        .collect();
    assert!(
        runs.len() <= 1,
        "tables of {} runs side by side",
        runs.len()
    );
    names
}

fn temp_files(out: &Path) -> Vec<String> {
    let mut found = Vec::new();
    // The cache's entries and datasets' folders too.
    let cache = out.join(".tribo/cache");
    let dirs = [
        out.to_path_buf(),
        out.join(".tribo"),
        out.join("traces"),
        cache.join("parts"),
        cache.join("packs"),
        cache.join("stages"),
    ];
    for dir in dirs {
        for e in std::fs::read_dir(dir).into_iter().flatten().flatten() {
            let n = e.file_name().to_string_lossy().to_string();
            if n.ends_with(".tmp") {
                found.push(n);
            }
        }
    }
    // A dataset's files its published manifest does not list.
    let manifest = out.join("traces.dataset.json");
    if let Ok(m) = tribo::pipeline::dataset::read_manifest(&manifest) {
        for f in common::files_with_ext(&out.join("traces"), "parquet") {
            let n = f.file_name().unwrap().to_string_lossy().to_string();
            if !m.files.contains(&n) {
                found.push(n);
            }
        }
    }
    let sets = std::fs::read_dir(out.join(".tribo/sets")).map_or(0, |d| d.count());
    if sets > 1 {
        found.push(format!("{sets} sets"));
    }
    found
}

#[test]
fn kill_9_at_any_moment_leaves_one_complete_set() {
    let lab = lab();
    let dir = lab.path();
    let out = dir.join("out");
    assert_eq!(
        common::tribo(dir, &["run", "a.toml"]).status.code(),
        Some(0)
    );
    let full = one_complete_set(&out);
    assert!(full.len() >= 7, "{full:?}");
    for trial in 0..24u64 {
        let pipeline = if trial % 2 == 0 { "b.toml" } else { "a.toml" };
        let mut child = spawn(dir, pipeline);
        // Spread over the run (about 0.3 s): 0 to 460 ms.
        std::thread::sleep(Duration::from_millis(trial * 20));
        let _ = child.kill();
        let _ = child.wait();
        assert_eq!(one_complete_set(&out), full, "trial {trial}");
    }
    // (Forced: a rerun keeps the tables whose inputs did not change, with
    // the provenance of the run that computed them.)
    let o = common::tribo(dir, &["run", "a.toml", "--force"]);
    assert_eq!(o.status.code(), Some(0));
    assert_eq!(one_complete_set(&out), full);
    assert!(temp_files(&out).is_empty(), "{:?}", temp_files(&out));
}

#[test]
fn two_runs_at_once_never_mix() {
    let lab = lab();
    let dir = lab.path();
    let out = dir.join("out");
    for _ in 0..4 {
        let a = spawn(dir, "a.toml");
        let b = spawn(dir, "b.toml");
        let codes: Vec<Option<i32>> = [a, b]
            .into_iter()
            .map(|c| c.wait_with_output().unwrap().status.code())
            .collect();
        // One wins; the other either finished after it or was refused (2).
        assert!(codes.contains(&Some(0)), "{codes:?}");
        assert!(codes.iter().all(|c| matches!(c, Some(0 | 2))), "{codes:?}");
        one_complete_set(&out);
    }
    // Nothing either run staged is left once the next run is done.
    assert_eq!(
        common::tribo(dir, &["run", "a.toml"]).status.code(),
        Some(0)
    );
    assert!(temp_files(&out).is_empty(), "{:?}", temp_files(&out));
}

#[test]
fn a_planted_link_at_a_temporary_name_is_not_followed() {
    let dir = tempfile::tempdir().unwrap();
    let victim = dir.path().join("victim.txt");
    std::fs::write(&victim, "keep me").unwrap();
    let path = dir.path().join("x.parquet");
    // The names an attacker could predict: the old scheme, by pid.
    let pid = std::process::id();
    for name in [format!(".x.parquet.{pid}.tmp"), format!(".x.parquet.{pid}")] {
        std::os::unix::fs::symlink(&victim, dir.path().join(name)).unwrap();
    }
    tribo::pipeline::atomic::write_text_atomic(&path, "new content").unwrap();
    assert_eq!(std::fs::read_to_string(&victim).unwrap(), "keep me");
    assert_eq!(std::fs::read_to_string(&path).unwrap(), "new content");
}

/// The two inputs that once broke a whole batch: pin-on-disc `Distance`
/// cells of 1e99999 and a Dektak height of 1e300. Neither stops the other
/// files: the overflowing cells become nulls at the boundary, the profile
/// fails (or is flagged) alone.
#[test]
fn one_bad_value_fails_only_its_file() {
    let dir = tempfile::tempdir().unwrap();
    let input = dir.path().join("in");
    std::fs::create_dir_all(&input).unwrap();
    let fx = common::root().join("fixtures");
    let pod = std::fs::read(fx.join("friction/pin_on_disc_stepped.tsv")).unwrap();
    let pod = String::from_utf8_lossy(&pod).to_string();
    let bad: Vec<String> = pod
        .lines()
        .enumerate()
        .map(|(i, l)| match i {
            5 | 9 | 15 => {
                let mut c: Vec<&str> = l.split('\t').collect();
                c[1] = "1e99999";
                c.join("\t")
            }
            _ => l.to_string(),
        })
        .collect();
    std::fs::write(input.join("pod_bad.tsv"), bad.join("\n")).unwrap();
    std::fs::copy(fx.join("friction/sled_mN.csv"), input.join("sled_mN.csv")).unwrap();
    let dektak = std::fs::read(fx.join("roughness/dektak/dektak-1.csv")).unwrap();
    let text = String::from_utf8_lossy(&dektak).to_string();
    let mut lines: Vec<String> = text.lines().map(str::to_string).collect();
    let last = lines
        .iter()
        .rposition(|l| {
            l.split(',')
                .take(2)
                .all(|c| c.trim().parse::<f64>().is_ok())
        })
        .unwrap();
    let cells: Vec<&str> = lines[last].split(',').collect();
    lines[last] = format!("{},1e300", cells[0]);
    std::fs::write(input.join("dektak_bad.csv"), lines.join("\n")).unwrap();
    std::fs::copy(
        fx.join("roughness/nanovea/test1.txt"),
        input.join("test1.txt"),
    )
    .unwrap();
    std::fs::write(
        dir.path().join("s.csv"),
        "file,sample_id,normal_force_N\npod_bad.tsv,P2,3\n",
    )
    .unwrap();
    std::fs::write(
        dir.path().join("p.toml"),
        "stages = [\"friction\", \"roughness\"]\n[input]\nfiles = [\"in/*\"]\nsamples = \"s.csv\"\n[output]\ndir = \"out\"\n",
    )
    .unwrap();
    let o = common::tribo(dir.path(), &["run", "p.toml"]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(matches!(o.status.code(), Some(0 | 1)), "{err}");
    let out = dir.path().join("out");
    // The good files are in their tables.
    assert!(
        common::sources(&out, "friction").contains("sled_mN.csv"),
        "{err}"
    );
    assert!(
        common::sources(&out, "roughness").contains("test1.txt"),
        "{err}"
    );
    // The three overflowing cells are nulls from the boundary on (the
    // trace's position), not infinities in the tables.
    let traces = common::read_table(&out.join("traces"));
    let src = traces.str("source").unwrap();
    let pos = traces.f64("position_m").unwrap();
    let nulls = src
        .iter()
        .zip(&pos)
        .filter(|(s, p)| s.as_deref().is_some_and(|s| s.ends_with("pod_bad.tsv")) && p.is_none())
        .count();
    assert_eq!(nulls, 3);
    assert!(pos.iter().flatten().all(|p| p.is_finite()));
    // The profile is either in errors.parquet, naming it, or in its table
    // with a status that is not `ok`.
    let (errors, _) = Table::read_parquet(&out.join("errors.parquet")).unwrap();
    let failed: Vec<String> = errors
        .str("source")
        .unwrap()
        .into_iter()
        .flatten()
        .collect();
    let (file, table) = ("dektak_bad.csv", "roughness");
    let in_errors = failed.iter().any(|s| s.ends_with(file));
    let (t, _) = Table::read_parquet(&out.join(format!("{table}.parquet"))).unwrap();
    let src = t.str("source").unwrap();
    let status = t.str("status").unwrap();
    let flagged = src
        .iter()
        .zip(&status)
        .filter(|(s, _)| s.as_deref().is_some_and(|s| s.ends_with(file)))
        .any(|(_, st)| st.as_deref() != Some("ok"));
    assert!(in_errors || flagged, "{file}: {err}");
}

/// Messages name the right line and column, quote the offending token cut
/// to 80 characters, and call an encoding problem one.
#[test]
fn messages_point_at_the_cause() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    std::fs::write(d.join("nonum.csv"), "Time,Force\nfoo,bar\nbaz,qux\n").unwrap();
    let junk = format!(
        "t,Fx,Fz\n0,1,2\n0.1,{}x,2\n0.2,1,2\n",
        "9".repeat(5_000_000)
    );
    std::fs::write(d.join("junk.csv"), junk).unwrap();
    let mut odd = vec![0xFF, 0xFE];
    for c in b"t,Fx,Fz\n0,1,2\n0.1,1,2\n" {
        odd.extend_from_slice(&[*c, 0]);
    }
    odd.pop();
    std::fs::write(d.join("odd16.csv"), odd).unwrap();
    std::fs::write(
        d.join("unit.csv"),
        "T (s),Fx [gf2],Fz [N]\n0,1,2\n0.1,1,2\n",
    )
    .unwrap();
    let cases = [
        ("nonum.csv", "line 2: no data found: expected numeric rows after the header on line 1, found 'foo,bar'"),
        ("junk.csv", "line 3, column 'Fx'"),
        ("odd16.csv", "encoding: UTF-16"),
        ("unit.csv", "column 'Fx': unknown unit 'gf2'"),
    ];
    for (file, want) in cases {
        let o = common::tribo(d, &["friction", file, "--out", "out"]);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(1), "{err}");
        assert!(err.contains(want), "{file}: {err}");
        assert!(err.len() < 2000, "{file}: {} bytes of messages", err.len());
    }
}

/// A file too large for the memory left fails alone, with a message that
/// says how much it needs and what the limit is, before it is read; the
/// other files' results are written (TRIBO_MEMORY_LIMIT stands in for a
/// machine with little memory).
#[test]
fn a_file_too_large_for_memory_fails_alone() {
    let dir = tempfile::tempdir().unwrap();
    let mut big = String::from("t (s),Fx (N),Fz (N)\n");
    for i in 0..40_000 {
        let t = i as f64 * 1e-3;
        big.push_str(&format!(
            "{t:.3},{:.4},1.0\n",
            if t < 1.0 { 0.6 * t } else { 0.5 }
        ));
    }
    std::fs::write(dir.path().join("big.csv"), &big).unwrap();
    let small: String = big.lines().take(3000).map(|l| format!("{l}\n")).collect();
    std::fs::write(dir.path().join("small.csv"), small).unwrap();
    // big.csv is about 720 kB: it needs ~2.2 MB; small.csv ~50 kB fits in 1 MB.
    let out = Command::new(env!("CARGO_BIN_EXE_tribo"))
        .current_dir(dir.path())
        .env("TRIBO_MEMORY_LIMIT", "1M")
        .args(["friction", "big.csv", "small.csv", "--out", "out"])
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{err}");
    assert!(
        err.contains("big.csv")
            && err.contains("needs about")
            && err.contains("TRIBO_MEMORY_LIMIT is 1.0 MB"),
        "{err}"
    );
    assert_eq!(
        common::sources(&dir.path().join("out"), "friction"),
        BTreeSet::from(["small.csv".to_string()])
    );
}

/// Recovery: what killed runs left (staging sets, temporary files) is
/// removed by the next run, never what a run still alive made, on this
/// host or another one sharing the folder.
#[test]
fn leftovers_of_gone_runs_go_those_of_live_runs_stay() {
    let lab = lab();
    let dir = lab.path();
    let out = dir.join("out");
    assert_eq!(
        common::tribo(dir, &["run", "a.toml"]).status.code(),
        Some(0)
    );
    let host = tribo::pipeline::owner::host_name();
    let mut gone = Command::new("true").spawn().unwrap();
    let dead = gone.id();
    gone.wait().unwrap();
    let me = std::process::id();
    let sets = out.join(".tribo/sets");
    let name = |prefix: &str, pid: u32, host: &str| format!("{prefix}.00ff.{pid}@{host}.tmp");
    let staged = [
        (name("set", dead, &host), false),
        (name("set", me, &host), true),
        (name("set", dead, "other-node"), true),
        ("set.1234.00ff.tmp".to_string(), false),
        ("set-0123456789abcdef".to_string(), false),
    ];
    for (s, _) in &staged {
        std::fs::create_dir_all(sets.join(s)).unwrap();
        std::fs::write(sets.join(s).join("friction.parquet"), "partial").unwrap();
    }
    let temps = [
        (name(".friction.parquet", dead, &host), false),
        (name(".friction.parquet", me, &host), true),
        (name(".friction.parquet", dead, "other-node"), true),
    ];
    for (t, _) in &temps {
        std::fs::write(out.join(t), "partial").unwrap();
    }
    assert_eq!(
        common::tribo(dir, &["run", "a.toml"]).status.code(),
        Some(0)
    );
    for (s, stays) in &staged {
        assert_eq!(sets.join(s).exists(), *stays, "{s}");
    }
    for (t, stays) in &temps {
        assert_eq!(out.join(t).exists(), *stays, "{t}");
    }
    one_complete_set(&out);
}

/// An output folder copied with its links followed (`cp -rL`, as a copy
/// to a share or a zip does), or moved, runs again: exit 0, the same
/// tables, the links made again, nothing left over.
#[test]
fn a_folder_copied_with_links_followed_or_moved_runs_again() {
    let lab = lab();
    let dir = lab.path();
    let out = dir.join("out");
    assert_eq!(
        common::tribo(dir, &["run", "a.toml"]).status.code(),
        Some(0)
    );
    let fresh = dir.join("fresh");
    common::copy_tree(&out, &fresh);
    std::fs::remove_dir_all(fresh.join(".tribo")).unwrap();
    for flags in ["-rL", "-rLp"] {
        let copy = dir.join("copy");
        let cp = Command::new("cp")
            .args([flags, "out", "copy"])
            .current_dir(dir)
            .status()
            .unwrap();
        assert!(cp.success());
        assert!(!std::fs::symlink_metadata(copy.join(".tribo/current"))
            .unwrap()
            .file_type()
            .is_symlink());
        std::fs::remove_dir_all(&out).unwrap();
        std::fs::rename(&copy, &out).unwrap();
        let o = common::tribo(dir, &["run", "a.toml"]);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(0), "{flags}: {err}");
        assert!(std::fs::symlink_metadata(out.join(".tribo/current"))
            .unwrap()
            .file_type()
            .is_symlink());
        for t in common::parquet_names(&out) {
            // A dataset's folder stays a folder; its manifest is the link.
            let t = match t.ends_with(".parquet") {
                true => t,
                false => format!("{t}.dataset.json"),
            };
            let link = std::fs::symlink_metadata(out.join(&t)).unwrap();
            assert!(link.file_type().is_symlink(), "{flags}: {t}");
        }
        common::same_tables(&fresh, &out);
        assert!(temp_files(&out).is_empty(), "{:?}", temp_files(&out));
    }
    // Moved: the links are relative, the cache's entries whole.
    let moved = dir.join("moved");
    std::fs::rename(&out, &moved).unwrap();
    let o = common::tribo(dir, &["run", "a.toml", "--out", "moved", "--json"]);
    assert_eq!(o.status.code(), Some(0));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(v["files_processed"], 0, "{v}");
    common::same_tables(&fresh, &moved);
}
