//! Beyond one machine: shards fill the cache, a run without a shard
//! assembles the tables, and the result equals a single-machine run's —
//! here with shards run one after another, and on a real Slurm (a job
//! array and a dependent merge job) where one is running.

use std::path::PathBuf;
use std::process::Command;

use crate::common;

/// The lab folder, its extraction and fits, an ice grid (a simulation that
/// reads no table: one unit) and the demo's spring-block study against the
/// run's own Coulomb fits (its runs spread over the shards).
fn lab() -> tempfile::TempDir {
    let mut stages = common::LAB_STAGES.to_vec();
    stages.extend(["ice-grid", "spring-block"]);
    let dir = common::lab_folder(&common::lab_pipeline(
        &stages,
        "[ice-grid]\nt = [-10.0]\nphi = [7.3]\n[spring-block]\nscene = \"sb/spring_block_study.toml\"\n",
    ));
    common::copy_tree(
        &common::root().join("pipelines/demo"),
        &dir.path().join("sb"),
    );
    dir
}

fn run_json(dir: &std::path::Path, args: &[&str]) -> serde_json::Value {
    let mut all = vec!["run", "p.toml", "--json"];
    all.extend(args);
    let o = common::tribo(dir, &all);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(0), "{err}");
    serde_json::from_slice(&o.stdout).unwrap_or_else(|e| panic!("{e}: {err}"))
}

fn single_run(dir: &std::path::Path) -> PathBuf {
    let o = common::tribo(dir, &["run", "p.toml", "--out", "single", "--threads", "1"]);
    assert_eq!(o.status.code(), Some(0));
    dir.join("single")
}

#[test]
fn shards_then_a_merge_equal_one_run() {
    let lab = lab();
    let dir = lab.path();
    let mut processed = 0;
    // Shards run in any order, each on its own share.
    for i in [0, 2, 1] {
        let v = run_json(dir, &["--shard", &format!("{i}/3")]);
        assert!(
            v["tables"].as_array().unwrap().is_empty(),
            "a shard publishes nothing"
        );
        processed += v["files_processed"].as_u64().unwrap();
    }
    assert_eq!(processed, 21, "every data file in exactly one shard");
    // Rerunning the array redoes nothing.
    for i in 0..3 {
        let v = run_json(dir, &["--shard", &format!("{i}/3")]);
        assert_eq!(v["files_processed"], 0);
    }
    let merged = run_json(dir, &[]);
    assert_eq!(merged["files_processed"], 0, "{merged}");
    assert_eq!(merged["files_reused"], 21);
    // The ice grid (a simulation reading no table) ran in a shard, and so
    // did every run of the study: the merge computes none.
    assert_eq!(merged["stages_reused"], 1, "{merged}");
    assert_eq!(merged["runs_computed"], 0, "{merged}");
    assert!(merged["runs_reused"].as_u64().unwrap() >= 6, "{merged}");
    common::same_tables(&dir.join("out"), &single_run(dir));
    // The merge's report, its files' figures read from the shards' cache
    // parts, is the one `tribo report` makes from the published tables.
    let report = dir.join("out/report.html");
    let merged = std::fs::read_to_string(&report).unwrap();
    assert!(merged.matches("<svg").count() > 21, "each file's figures");
    let o = common::tribo(dir, &["report", "out"]);
    assert_eq!(
        o.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    assert_eq!(std::fs::read_to_string(&report).unwrap(), merged);
}

/// Where `sbatch` talks to a running Slurm (`.ci/run` starts a one-node
/// cluster with `scripts/local-slurm.sh`).
fn slurm_available() -> bool {
    let ok = Command::new("sinfo")
        .args(["-h", "-o", "%T"])
        .output()
        .is_ok_and(|o| o.status.success() && !o.stdout.is_empty());
    if !ok {
        eprintln!(
            "skipped: no running Slurm (sinfo failed); `.ci/run` starts one with \
             scripts/local-slurm.sh, which needs root and Debian's slurm-wlm and munge"
        );
    }
    ok
}

#[test]
fn a_slurm_job_array_and_merge_equal_one_run() {
    if !slurm_available() {
        return;
    }
    let lab = lab();
    let dir = lab.path();
    let o = common::tribo(
        dir,
        &["slurm", "p.toml", "--shards", "3", "--submit", "--wait"],
    );
    let out = String::from_utf8_lossy(&o.stdout);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(0), "{out}\n{err}");
    assert!(
        out.contains("array job") && out.contains("merge job"),
        "{out}"
    );
    let logs = common::files_with_ext(&dir.join("out/slurm/logs"), "out");
    assert_eq!(logs.len(), 4, "three tasks and the merge: {logs:?}");
    let merge_log = logs
        .iter()
        .find(|p| p.to_string_lossy().contains("merge-"))
        .map(|p| std::fs::read_to_string(p).unwrap())
        .unwrap();
    let summary: serde_json::Value =
        serde_json::from_str(merge_log.lines().last().unwrap()).unwrap();
    assert_eq!(summary["files_processed"], 0, "{merge_log}");
    assert_eq!(summary["runs_computed"], 0, "{merge_log}");
    common::same_tables(&dir.join("out"), &single_run(dir));
}
