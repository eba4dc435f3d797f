//! Scheduled reprocessing: a rerun redoes only what changed, says so in
//! its `--json` summary, and its tables equal a fresh run's over the same
//! folder.

use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::Duration;

use crate::common;

/// The demo lab folder copied into a temporary folder, with a pipeline
/// `p.toml` writing to `out/`.
struct Lab {
    dir: tempfile::TempDir,
}

const STAGES: &[&str] = common::LAB_STAGES;

impl Lab {
    fn new() -> Lab {
        Lab {
            dir: common::lab_folder(&common::lab_pipeline(STAGES, "")),
        }
    }
    fn path(&self, rel: &str) -> PathBuf {
        self.dir.path().join(rel)
    }
    /// `tribo run p.toml --json ARGS`: the summary, after checking the exit code.
    fn run(&self, args: &[&str]) -> serde_json::Value {
        let mut all = vec!["run", "p.toml", "--json"];
        all.extend(args);
        let o = common::tribo(self.dir.path(), &all);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(0), "{err}");
        serde_json::from_slice(&o.stdout).unwrap_or_else(|e| panic!("{e}: {err}"))
    }
    /// A fresh run of the folder as it is now, into `fresh/`, compared with
    /// `out/`.
    fn equals_fresh_run(&self) {
        let fresh = self.path("fresh");
        let _ = std::fs::remove_dir_all(&fresh);
        let o = common::tribo(self.dir.path(), &["run", "p.toml", "--out", "fresh"]);
        assert_eq!(o.status.code(), Some(0));
        common::same_tables(&self.path("out"), &fresh);
    }
}

fn count(v: &serde_json::Value, key: &str) -> u64 {
    v[key]
        .as_u64()
        .unwrap_or_else(|| panic!("{key} missing in {v}"))
}

/// The summary's `phases_s`: every phase of a run that publishes, in the
/// order they run, each a time, together no longer than the command took.
fn phases_add_up(v: &serde_json::Value, wall: f64) {
    let phases = v["phases_s"].as_array().expect("phases_s");
    let names: Vec<&str> = phases.iter().filter_map(|p| p["phase"].as_str()).collect();
    let order = [
        "plan",
        "state",
        "files",
        "join",
        "table_stages",
        "tables",
        "report",
        "commit",
    ];
    assert_eq!(names, order, "{v}");
    let seconds: Vec<f64> = phases
        .iter()
        .filter_map(|p| p["seconds"].as_f64())
        .collect();
    assert_eq!(seconds.len(), order.len(), "{v}");
    assert!(
        seconds.iter().all(|s| s.is_finite() && *s >= 0.0),
        "{seconds:?}"
    );
    let sum: f64 = seconds.iter().sum();
    assert!(sum > 0.0 && sum <= wall, "phases {sum} s, command {wall} s");
}

/// 21 data files in the lab folder (and a notes file).
const N: u64 = 21;

#[test]
fn a_rerun_reuses_everything_and_a_change_redoes_only_it() {
    let lab = Lab::new();
    let t = std::time::Instant::now();
    let first = lab.run(&[]);
    let wall = t.elapsed().as_secs_f64();
    assert_eq!(count(&first, "files_processed"), N);
    assert_eq!(count(&first, "files_unrouted"), 1);
    assert_eq!(count(&first, "stages_run"), 6);
    phases_add_up(&first, wall);

    let t = std::time::Instant::now();
    let again = lab.run(&[]);
    phases_add_up(&again, t.elapsed().as_secs_f64());
    assert_eq!(count(&again, "files_processed"), 0);
    assert_eq!(count(&again, "files_reused"), N);
    assert_eq!(count(&again, "stages_run"), 0);
    assert_eq!(count(&again, "stages_reused"), 6);
    assert_eq!(again["tables"], first["tables"]);
    // The warnings of an unchanged rerun are the last run's (kept with the
    // state, not read again from the tables); the lab has some.
    assert!(count(&first, "warnings") > 0, "{first}");
    assert_eq!(again["warnings"], first["warnings"]);
    lab.equals_fresh_run();

    // One changed trace: that file only, and the stages that read it.
    let f = lab.path("lab/friction/sled_F1_100g.csv");
    let text = std::fs::read_to_string(&f).unwrap();
    std::fs::write(&f, text.replacen("\n", "\n\n", 1)).unwrap();
    let changed = lab.run(&[]);
    assert_eq!(count(&changed, "files_processed"), 1);
    assert_eq!(count(&changed, "files_reused"), N - 1);
    // friction, coulomb and ice (it reads friction_steps) run again;
    // roughness, tensile and the tensile summary do not.
    assert_eq!(count(&changed, "stages_run"), 3);
    lab.equals_fresh_run();

    // A deleted profile: its rows leave the tables.
    std::fs::remove_file(lab.path("lab/profiles/dektak-1.csv")).unwrap();
    let deleted = lab.run(&[]);
    assert_eq!(count(&deleted, "files_processed"), 0);
    assert_eq!(count(&deleted, "files_reused"), N - 1);
    let sources = common::sources(&lab.path("out"), "roughness");
    assert!(!sources.iter().any(|s| s.contains("dektak")), "{sources:?}");
    lab.equals_fresh_run();
}

#[test]
fn a_changed_parameter_reruns_its_stage_and_what_reads_it() {
    let lab = Lab::new();
    // Inputs long unchanged: not read again, their keys are the state's
    // while the pipeline is the same, and made again when it is not.
    age(&lab);
    lab.run(&[]);
    let same = lab.run(&[]);
    assert_eq!(count(&same, "files_hashed"), 0, "{same}");
    assert_eq!(count(&same, "files_processed"), 0, "{same}");
    let changed = common::lab_pipeline(STAGES, "[tensile]\neffective_threshold = 0.1\n");
    std::fs::write(lab.path("p.toml"), changed).unwrap();
    let v = lab.run(&[]);
    // The three fibre curves are redone (so read again); the friction
    // traces and profiles are not.
    assert_eq!(count(&v, "files_hashed"), 3, "{v}");
    assert_eq!(count(&v, "files_processed"), 3);
    assert_eq!(count(&v, "files_reused"), N - 3);
    assert_eq!(count(&v, "stages_run"), 2, "{v}");
    assert_eq!(count(&v, "stages_reused"), 4);
    lab.equals_fresh_run();
    let again = lab.run(&[]);
    assert_eq!(count(&again, "files_processed"), 0, "{again}");
    assert_eq!(count(&again, "stages_run"), 0, "{again}");
    // A changed manifest row redoes its file only, though no input changed.
    let m = lab.path("lab/samples.csv");
    let rows = std::fs::read_to_string(&m).unwrap();
    let changed = rows.replacen("sled_F1_50g.csv,F-1,50,", "sled_F1_50g.csv,F-1,55,", 1);
    assert_ne!(changed, rows);
    std::fs::write(&m, changed).unwrap();
    let row = lab.run(&[]);
    assert_eq!(count(&row, "files_processed"), 1, "{row}");
    lab.equals_fresh_run();
    // --force recomputes everything.
    let forced = lab.run(&["--force"]);
    assert_eq!(count(&forced, "files_processed"), N);
    assert_eq!(count(&forced, "stages_run"), 6);
}

#[test]
fn a_dry_run_lists_what_would_be_redone_and_writes_nothing() {
    let lab = Lab::new();
    lab.run(&[]);
    let state = lab.path("out/.tribo/state.bin");
    let before = std::fs::read(&state).unwrap();
    let f = lab.path("lab/fibres/t150_knotted.txt");
    let text = std::fs::read_to_string(&f).unwrap();
    std::fs::write(&f, format!("{text}\n")).unwrap();
    let v = lab.run(&["--dry-run"]);
    let redo = v["redo"].as_array().unwrap();
    let names: Vec<(&str, &str)> = redo
        .iter()
        .map(|r| (r["name"].as_str().unwrap(), r["reason"].as_str().unwrap()))
        .collect();
    assert!(
        names
            .iter()
            .any(|(n, r)| n.ends_with("t150_knotted.txt") && *r == "changed file"),
        "{names:?}"
    );
    for stage in ["tensile", "tensile-summary"] {
        assert!(names.iter().any(|(n, _)| *n == stage), "{names:?}");
    }
    assert!(!names.iter().any(|(n, _)| *n == "friction"), "{names:?}");
    assert_eq!(std::fs::read(&state).unwrap(), before);
    assert!(!lab.path("out/.tribo/state.log").exists());
}

#[test]
fn a_second_run_on_a_held_folder_exits_2_naming_the_holder() {
    let lab = Lab::new();
    std::fs::create_dir_all(lab.path("out/.tribo")).unwrap();
    let lock = lab.path("out/.tribo/lock");
    // This test process is alive: the folder is held.
    std::fs::write(
        &lock,
        format!("pid {} started 0 (unix s)", std::process::id()),
    )
    .unwrap();
    let o = common::tribo(lab.dir.path(), &["run", "p.toml"]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(
        err.contains(&format!("pid {}", std::process::id())),
        "{err}"
    );
    // A lock of a process that no longer exists is taken over.
    if Path::new("/proc").is_dir() {
        std::fs::write(&lock, "pid 4194304999 started 0 (unix s)").unwrap();
        lab.run(&[]);
        assert!(!lock.exists());
    }
}

/// kill -9 at several moments of a run, then a rerun: its tables equal a
/// clean run's.
#[test]
fn a_killed_run_is_completed_by_the_next() {
    let lab = Lab::new();
    for delay_ms in [30, 120, 250] {
        let mut child = Command::new(env!("CARGO_BIN_EXE_tribo"))
            .current_dir(lab.dir.path())
            .args(["run", "p.toml", "--force"])
            .stdout(Stdio::null())
            .stderr(Stdio::null())
            .spawn()
            .unwrap();
        std::thread::sleep(Duration::from_millis(delay_ms));
        let _ = child.kill();
        let _ = child.wait();
        // Whatever is published is readable (on a loaded machine the run
        // may be killed before it made its folder).
        let out = lab.path("out");
        let published = match out.is_dir() {
            true => common::parquet_names(&out),
            false => Default::default(),
        };
        for t in published {
            common::read_table(&lab.path("out").join(&t));
        }
    }
    lab.run(&[]);
    lab.equals_fresh_run();
    let again = lab.run(&[]);
    assert_eq!(count(&again, "files_processed"), 0);
}

/// The files of the traces dataset are the cache's parts (one file, two
/// names). A file rewritten in place in `OUT/traces/` (as
/// `df.to_parquet(...)` does; it keeps its folder's stamp, so only
/// `--verify` looks at it) is not taken from the cache: the input is read
/// again and the file published again. A later run with a second
/// file adds that file's traces and keeps the first's. Every run's tables
/// equal a fresh run's.
#[test]
fn the_traces_dataset_shares_its_files_with_the_cache() {
    use std::os::unix::fs::MetadataExt;
    let dir = tempfile::tempdir().unwrap();
    let lab = common::root().join("fixtures/lab/friction");
    for f in ["HT-2n-6-4_2_001.csv", "HT-2n-6-4_2_050.csv"] {
        std::fs::copy(lab.join(f), dir.path().join(f)).unwrap();
    }
    let run = |files: &str, out: &str, extra: &[&str]| {
        let toml = format!(
            "stages = [\"friction\"]\n[input]\nfiles = [{files}]\n[output]\ndir = \"{out}\"\n"
        );
        std::fs::write(dir.path().join("p.toml"), toml).unwrap();
        let mut args = vec!["run", "p.toml", "--json"];
        args.extend(extra);
        let o = common::tribo(dir.path(), &args);
        assert_eq!(
            o.status.code(),
            Some(0),
            "{}",
            String::from_utf8_lossy(&o.stderr)
        );
        serde_json::from_slice::<serde_json::Value>(&o.stdout).unwrap()
    };
    let fresh = |files: &str| {
        let _ = std::fs::remove_dir_all(dir.path().join("fresh"));
        run(files, "fresh", &[]);
        common::same_tables(&dir.path().join("out"), &dir.path().join("fresh"));
    };
    let traces = dir.path().join("out/traces");
    let inodes = |dir: &Path| -> Vec<(u64, u64)> {
        let mut v: Vec<_> = walk(dir)
            .into_iter()
            .filter(|p| p.extension().is_some_and(|e| e == "parquet"))
            .map(|p| std::fs::metadata(&p).unwrap())
            .map(|m| (m.ino(), m.dev()))
            .collect();
        v.sort();
        v
    };
    let cached_traces = |out: &Path| -> Vec<(u64, u64)> {
        let mut v: Vec<_> = walk(&out.join(".tribo/cache/parts"))
            .into_iter()
            .filter(|p| p.to_string_lossy().ends_with(".traces.parquet"))
            .map(|p| std::fs::metadata(&p).unwrap())
            .map(|m| (m.ino(), m.dev()))
            .collect();
        v.sort();
        v
    };
    let one = "\"HT-2n-6-4_2_001.csv\"";
    run(one, "out", &[]);
    let published = inodes(&traces);
    assert_eq!(published.len(), 1, "{published:?}");
    assert_eq!(cached_traces(&dir.path().join("out")), published);
    fresh(one);

    // Rewritten in place: the input is read again, its file published again.
    let file = common::files_with_ext(&traces, "parquet").remove(0);
    let friction = std::fs::read(dir.path().join("out/friction.parquet")).unwrap();
    std::fs::write(&file, friction).unwrap();
    let again = run(one, "out", &["--verify"]);
    assert_eq!(again["files_processed"], 1, "{again}");
    fresh(one);
    let first = inodes(&traces);
    assert_eq!(cached_traces(&dir.path().join("out")), first);

    let two = "\"HT-2n-6-4_2_001.csv\", \"HT-2n-6-4_2_050.csv\"";
    let grown = run(two, "out", &[]);
    assert_eq!(grown["files_processed"], 1, "{grown}");
    assert_eq!(grown["files_reused"], 1, "{grown}");
    fresh(two);
    let both = inodes(&traces);
    assert_eq!(both.len(), 2);
    // The first input's file stays as it was (not written again).
    assert!(both.contains(&first[0]), "{both:?} {first:?}");
    assert_eq!(cached_traces(&dir.path().join("out")), both);
}

/// The folders that grow with the inputs (`OUT/traces/`, the cache's
/// `parts/`) are listed only when something other than the last run
/// changed them. Left as the last run left them, a deleted input's files
/// leave both by name; a file put there by anyone else (a killed run, a
/// hand) changes the folder's stamp, so the next run lists the folder and
/// removes it. Either way the folders hold exactly the set's files.
#[test]
fn grown_folders_are_listed_only_when_changed_by_another() {
    let lab = Lab::new();
    let parquet = |rel: &str| -> Vec<String> {
        let mut v: Vec<String> = walk(&lab.path(rel))
            .into_iter()
            .map(|p| p.file_name().unwrap().to_string_lossy().to_string())
            .filter(|n| n.ends_with(".parquet"))
            .collect();
        v.sort();
        v
    };
    let listed = || -> Vec<String> {
        let text = std::fs::read_to_string(lab.path("out/traces.dataset.json")).unwrap();
        let m: serde_json::Value = serde_json::from_str(&text).unwrap();
        let mut v: Vec<String> = m["files"]
            .as_array()
            .unwrap()
            .iter()
            .map(|f| f.as_str().unwrap().to_string())
            .collect();
        v.sort();
        v
    };
    let keys = |names: &[String]| -> Vec<String> {
        let mut v: Vec<String> = names
            .iter()
            .map(|n| n.trim_end_matches(".parquet").rsplit('-').next().unwrap()[..16].to_string())
            .collect();
        v.sort();
        v
    };
    lab.run(&[]);
    lab.run(&[]);
    assert!(lab.path("out/.tribo/swept.bin").exists());
    assert_eq!(parquet("out/traces"), listed());

    // Known folders: the deleted input's files go by name.
    std::fs::remove_file(lab.path("lab/friction/sled_F1_100g.csv")).unwrap();
    let after = lab.run(&[]);
    assert_eq!(count(&after, "files_processed"), 0, "{after}");
    let published = parquet("out/traces");
    assert_eq!(published, listed());
    assert!(!published.iter().any(|n| n.starts_with("sled_F1_100g")));
    // The cache's traces files are the published ones.
    let cached = || -> Vec<String> {
        let names = parquet("out/.tribo/cache/parts").into_iter();
        keys(
            &names
                .filter(|n| n.ends_with(".traces.parquet"))
                .collect::<Vec<_>>(),
        )
    };
    assert_eq!(cached(), keys(&published));
    lab.equals_fresh_run();

    // Strays: the folders' stamps changed, so both are listed and swept.
    let stray = "stray-0123456789abcdef.parquet";
    std::fs::write(lab.path("out/traces").join(stray), b"x").unwrap();
    let part = format!("{}.traces.parquet", "ab".repeat(32));
    std::fs::write(lab.path("out/.tribo/cache/parts").join(&part), b"x").unwrap();
    let swept = lab.run(&[]);
    assert_eq!(count(&swept, "files_processed"), 0, "{swept}");
    assert_eq!(parquet("out/traces"), listed());
    assert!(!lab.path("out/.tribo/cache/parts").join(&part).exists());
    assert_eq!(cached(), keys(&published));
    lab.equals_fresh_run();
}

/// The last run's state stands for the cache only while the cache's
/// folders are as that run left them: with a pack removed by hand (or
/// the whole cache), the state no longer stands, the packs are read, and
/// what they lack is made again; the tables are a fresh run's.
#[test]
fn a_cache_changed_by_hand_is_read_again_not_trusted() {
    let lab = Lab::new();
    lab.run(&[]);
    lab.run(&[]);
    let packs = lab.path("out/.tribo/cache/packs");
    let pack = std::fs::read_dir(&packs).unwrap().flatten().next().unwrap();
    std::fs::remove_dir_all(pack.path()).unwrap();
    let again = lab.run(&[]);
    assert_eq!(count(&again, "files_processed"), N, "{again}");
    lab.equals_fresh_run();
    let kept = lab.run(&[]);
    assert_eq!(count(&kept, "files_processed"), 0, "{kept}");

    std::fs::remove_dir_all(lab.path("out/.tribo/cache")).unwrap();
    let again = lab.run(&[]);
    assert_eq!(count(&again, "files_processed"), N, "{again}");
    lab.equals_fresh_run();
}

/// A part file that no pack lists, put into `parts/` with the folder's
/// stamp left as the last run recorded it (as another build's parts are,
/// listed only in packs this build cannot read). Returns it and a part
/// of the run's own.
fn plant_orphan_part(lab: &Lab, name: &str) -> (PathBuf, PathBuf) {
    let parts = lab.path("out/.tribo/cache/parts");
    let stamp = std::fs::metadata(&parts).unwrap().modified().unwrap();
    let part = walk(&parts).into_iter().next().unwrap();
    let orphan = parts.join(format!("{}.traces.parquet", name.repeat(32)));
    std::fs::copy(&part, &orphan).unwrap();
    let dir = std::fs::File::open(&parts).unwrap();
    dir.set_modified(stamp).unwrap();
    (orphan, part)
}

/// A pack whose index cannot be read (damaged, or written by a build of
/// another format: every build reads only the entries it made) is
/// removed, and so are the parts only it listed: `parts/` is listed once,
/// as it is when the last run's context (build, pipeline) was another.
/// Otherwise those parts stayed on disk for good, the folder looking as
/// the last run left it.
#[test]
fn an_unreadable_pack_and_the_parts_only_it_knew_are_removed() {
    let lab = Lab::new();
    lab.run(&[]);
    lab.run(&[]);
    let (orphan, part) = plant_orphan_part(&lab, "ab");
    let packs = lab.path("out/.tribo/cache/packs");
    let pack = std::fs::read_dir(&packs).unwrap().flatten().next().unwrap();
    let foreign = packs.join("pack-000000000000000000000001-00000000");
    std::fs::create_dir(&foreign).unwrap();
    for f in walk(&pack.path()) {
        std::fs::copy(&f, foreign.join(f.file_name().unwrap())).unwrap();
    }
    std::fs::write(foreign.join("index.bin"), b"another build's index").unwrap();

    let again = lab.run(&[]);
    assert_eq!(count(&again, "files_processed"), 0, "{again}");
    assert!(!foreign.exists(), "the unreadable pack stays");
    assert!(!orphan.exists(), "a part no readable pack lists stays");
    assert!(part.exists());
    lab.equals_fresh_run();

    // Another context: the packs are this build's, the parts' folder is
    // as the last run left it, but a part the last context's packs
    // listed may be one this build cannot read.
    let (orphan, _) = plant_orphan_part(&lab, "cd");
    let changed = common::lab_pipeline(STAGES, "[tensile]\neffective_threshold = 0.1\n");
    std::fs::write(lab.path("p.toml"), changed).unwrap();
    let v = lab.run(&[]);
    assert_eq!(count(&v, "files_processed"), 3, "{v}");
    assert!(!orphan.exists(), "a part of another context stays");
    lab.equals_fresh_run();
    let kept = lab.run(&[]);
    assert_eq!(count(&kept, "files_processed"), 0, "{kept}");
}

/// Every file under `dir`.
/// Sets every input's modification time an hour back (a file written
/// within the time grain of a run is read again by the next).
fn age(lab: &Lab) {
    let past = std::time::SystemTime::now() - Duration::from_secs(3600);
    for p in walk(&lab.path("lab")) {
        set_modified(&p, past);
    }
}

fn set_modified(p: &Path, t: std::time::SystemTime) {
    let f = std::fs::File::options().write(true).open(p).unwrap();
    f.set_modified(t).unwrap();
}

/// A state that cannot be read (damaged, or written by another build)
/// says nothing of the cache: every input is read again, but what the
/// cache holds is taken from it, not made again.
#[test]
fn an_unreadable_state_redoes_no_cached_file() {
    let lab = Lab::new();
    lab.run(&[]);
    let state = lab.path("out/.tribo/state.bin");
    std::fs::write(&state, b"not a state").unwrap();
    let _ = std::fs::remove_file(lab.path("out/.tribo/state.log"));
    let again = lab.run(&[]);
    assert_eq!(count(&again, "files_hashed"), count(&again, "files"));
    assert_eq!(count(&again, "files_processed"), 0, "{again}");
    assert_eq!(count(&again, "files_reused"), N);
    lab.equals_fresh_run();
}

fn walk(dir: &Path) -> Vec<PathBuf> {
    let mut out = Vec::new();
    for e in std::fs::read_dir(dir).unwrap().flatten() {
        match e.path().is_dir() {
            true => out.extend(walk(&e.path())),
            false => out.push(e.path()),
        }
    }
    out
}

/// An input whose size, times and inode are the ones the last run saw is
/// not read again. A file rewritten with its old size and modification
/// time is (its change time moved), and `--verify` reads every file.
#[test]
fn an_unchanged_input_is_known_by_its_stat_without_reading_it() {
    let lab = Lab::new();
    age(&lab);
    let past = std::time::SystemTime::now() - Duration::from_secs(3600);
    let set_past = |p: &Path| set_modified(p, past);
    let first = lab.run(&[]);
    let files = count(&first, "files");
    assert_eq!(count(&first, "files_hashed"), files);
    let again = lab.run(&[]);
    assert_eq!(count(&again, "files_hashed"), 0, "{again}");
    assert_eq!(count(&again, "files_reused"), N);
    assert_eq!(again["tables"], first["tables"]);
    lab.equals_fresh_run();

    // Same size, same modification time, other bytes.
    let f = lab.path("lab/friction/sled_F1_100g.csv");
    let mut bytes = std::fs::read(&f).unwrap();
    let i = bytes
        .iter()
        .rposition(|b| (b'0'..=b'8').contains(b))
        .unwrap();
    bytes[i] += 1;
    std::fs::write(&f, &bytes).unwrap();
    set_past(&f);
    let changed = lab.run(&[]);
    assert_eq!(count(&changed, "files_hashed"), 1, "{changed}");
    assert_eq!(count(&changed, "files_processed"), 1, "{changed}");
    lab.equals_fresh_run();

    let verified = lab.run(&["--verify"]);
    assert_eq!(count(&verified, "files_hashed"), files);
    assert_eq!(count(&verified, "files_processed"), 0);
    // The provenance keeps each input's SHA-256, also when not read.
    let (t, _) = tribo::table::Table::read_parquet(&lab.path("out/files.parquet")).unwrap();
    let sha = tribo::hash::sha256_hex(&bytes);
    assert!(
        t.str("sha256").unwrap().contains(&Some(sha.clone())),
        "no {sha}"
    );
}

/// The cache keeps its small entries (routes, summary rows, failures) in
/// packs of many inputs, not a file each: a run makes one pack; a table
/// lost from the output comes back from the packs without reading any
/// input; entries made dead by changed inputs are dropped by joining the
/// live ones into one pack, which the next runs still find.
#[test]
fn small_cache_entries_are_packed_and_found_again() {
    let lab = Lab::new();
    let packs = || -> Vec<String> {
        let dir = lab.path("out/.tribo/cache/packs");
        let mut v: Vec<String> = std::fs::read_dir(dir)
            .unwrap()
            .flatten()
            .map(|e| e.file_name().to_string_lossy().to_string())
            .collect();
        v.sort();
        v
    };
    lab.run(&[]);
    assert_eq!(packs().len(), 1, "{:?}", packs());
    // Per input, only the dataset files the output set shares.
    let parts = walk(&lab.path("out/.tribo/cache/parts"));
    assert!(!parts.is_empty());
    for p in &parts {
        let name = p.file_name().unwrap().to_string_lossy();
        let table = name
            .trim_end_matches(".parquet")
            .rsplit('.')
            .next()
            .unwrap();
        let def = tribo::pipeline::registry::find(table).unwrap();
        assert!(def.is_dataset(), "{name}");
    }
    assert!(!lab.path("out/.tribo/cache/routes").exists());

    // The published summary table is gone: joined again from the packs.
    std::fs::remove_file(lab.path("out/friction.parquet")).unwrap();
    let again = lab.run(&[]);
    assert_eq!(count(&again, "files_processed"), 0, "{again}");
    assert_eq!(count(&again, "files_reused"), N, "{again}");
    assert!(lab.path("out/friction.parquet").exists());
    lab.equals_fresh_run();

    // One input changed run after run: its old entries die, and the packs
    // are joined before they pile up.
    let f = lab.path("lab/friction/sled_F1_100g.csv");
    for k in 0..10 {
        let text = std::fs::read_to_string(&f).unwrap();
        std::fs::write(&f, format!("{text}\n")).unwrap();
        let changed = lab.run(&[]);
        assert_eq!(count(&changed, "files_processed"), 1, "run {k}: {changed}");
        assert!(packs().len() <= 8, "run {k}: {:?}", packs());
    }
    assert!(packs().len() < 10, "{:?}", packs());
    let same = lab.run(&[]);
    assert_eq!(count(&same, "files_processed"), 0, "{same}");
    lab.equals_fresh_run();
    std::fs::remove_file(lab.path("out/friction_steps.parquet")).unwrap();
    let rejoined = lab.run(&[]);
    assert_eq!(count(&rejoined, "files_processed"), 0, "{rejoined}");
    lab.equals_fresh_run();
}

/// An unchanged rerun writes no table: `files`, `errors` and the report
/// are the last set's files (links to the same files), and the state is
/// not rewritten; a changed input writes them again.
#[test]
fn an_unchanged_rerun_keeps_the_last_sets_files() {
    use std::os::unix::fs::MetadataExt;
    let lab = Lab::new();
    let ids = || -> Vec<(String, u64)> {
        [
            "files.parquet",
            "errors.parquet",
            "report.html",
            "friction.parquet",
        ]
        .iter()
        .map(|f| {
            (
                f.to_string(),
                std::fs::metadata(lab.path("out").join(f)).unwrap().ino(),
            )
        })
        .collect()
    };
    // The state: its base, and the log of what later runs changed.
    let state = || {
        ["state.bin", "state.log"].map(|f| {
            std::fs::metadata(lab.path("out/.tribo").join(f))
                .and_then(|m| m.modified())
                .ok()
        })
    };
    // Written long before (a file written within the time grain of a run
    // is hashed again by the next, which records when it saw it).
    let past = std::time::SystemTime::now() - Duration::from_secs(3600);
    for p in walk(&lab.path("lab")) {
        let f = std::fs::File::options().write(true).open(&p).unwrap();
        f.set_modified(past).unwrap();
    }
    let first = lab.run(&[]);
    let (before, saved) = (ids(), state());
    let again = lab.run(&[]);
    assert_eq!(ids(), before);
    assert_eq!(state(), saved);
    assert_eq!(again["warnings"], first["warnings"]);
    lab.equals_fresh_run();

    let f = lab.path("lab/friction/sled_F1_100g.csv");
    let text = std::fs::read_to_string(&f).unwrap();
    std::fs::write(&f, format!("{text}\n")).unwrap();
    let changed = lab.run(&[]);
    assert_eq!(count(&changed, "files_processed"), 1, "{changed}");
    let after = ids();
    for ((name, a), (_, b)) in before.iter().zip(&after) {
        // Each holds the input's new rows or, in its provenance, its new
        // SHA-256 (`errors` too: its provenance lists every input).
        assert_ne!(a, b, "{name}");
    }
    assert_ne!(state(), saved);
    lab.equals_fresh_run();
}

/// A stylus profile `1.tx2` whose heights are in the unit its `.tx3`
/// conditions give, in a folder with a pipeline of the roughness stage
/// over `glob`.
struct Profile {
    dir: tempfile::TempDir,
}

impl Profile {
    fn new(glob: &str) -> Profile {
        let dir = tempfile::tempdir().unwrap();
        let mut tx2 = vec!["4.00000".to_string(), "400".to_string()];
        tx2.extend((0..400).map(|i| format!("{:.4}", 1.5 * (i as f64 * 0.3).sin() - 0.2)));
        std::fs::write(dir.path().join("1.tx2"), tx2.join("\n")).unwrap();
        let p = format!(
            "stages = [\"roughness\"]\n[input]\nfiles = [\"{glob}\"]\n[output]\ndir = \"out\"\n"
        );
        std::fs::write(dir.path().join("p.toml"), p).unwrap();
        Profile { dir }
    }
    /// Writes the conditions file `name` with heights in `unit` (`um`,
    /// `nm`: the same size).
    fn conditions(&self, name: &str, unit: &str) -> PathBuf {
        let text = format!(
            "Date\t08.04.2025\nOutput unit\tmm,{unit}\nEvaluation length\t4.0mm\n\
             Cutoff\t0.8mm\nLs cutoff\t2.5um\nFilter type\tGaussian\n"
        );
        let path = self.dir.path().join(name);
        std::fs::write(&path, text).unwrap();
        path
    }
    fn run(&self) -> serde_json::Value {
        let o = common::tribo(self.dir.path(), &["run", "p.toml", "--json"]);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(0), "{err}");
        serde_json::from_slice::<serde_json::Value>(&o.stdout).unwrap()
    }
    fn ra(&self) -> f64 {
        let path = self.dir.path().join("out/roughness.parquet");
        let (t, _) = tribo::table::Table::read_parquet(&path).unwrap();
        match t.f64("Ra_m").unwrap()[..] {
            [Some(ra)] => ra,
            ref other => panic!("one Ra expected: {other:?}"),
        }
    }
    /// A fresh run into `fresh/` has `out/`'s tables.
    fn equals_fresh_run(&self) {
        let fresh = self.dir.path().join("fresh");
        let _ = std::fs::remove_dir_all(&fresh);
        let o = common::tribo(self.dir.path(), &["run", "p.toml", "--out", "fresh"]);
        assert_eq!(o.status.code(), Some(0));
        common::same_tables(&self.dir.path().join("out"), &fresh);
    }
}

/// A companion read with its data file (a `.tx3`'s measuring conditions
/// beside its `.tx2` profile, whose output unit says what the heights are
/// in) is part of what the data file's results are made of: changing it
/// redoes the data file, whose own bytes and stat are unchanged, and the
/// rerun's tables equal a fresh run's.
#[test]
fn a_changed_companion_redoes_its_data_file() {
    let p = Profile::new("*.tx2");
    let tx3 = p.conditions("1.tx3", "um");
    assert_eq!(count(&p.run(), "files_processed"), 1);
    let in_um = p.ra();
    assert_eq!(count(&p.run(), "files_processed"), 0, "nothing changed");

    std::fs::write(
        &tx3,
        std::fs::read_to_string(&tx3)
            .unwrap()
            .replace("um\n", "nm\n"),
    )
    .unwrap();
    let changed = p.run();
    assert_eq!(count(&changed, "files_processed"), 1, "{changed}");
    let in_nm = p.ra();
    assert!(
        (in_nm / in_um - 1e-3).abs() < 1e-9,
        "{in_um} m, then {in_nm} m"
    );
    p.equals_fresh_run();
}

/// A companion is known unchanged by its stat, as a data file is: an
/// unchanged rerun of a profile whose `.tx3` is an input reads neither
/// file. A companion written again with the same size and modification
/// time (only its change time tells), or one that appears beside the data
/// file (`1.TX3`, which its software's upper case makes the one read),
/// redoes the data file.
#[test]
fn an_unchanged_companion_is_not_read_again() {
    let p = Profile::new("1.*");
    let tx3 = p.conditions("1.tx3", "um");
    // Written long before: a file written within the time grain of a run
    // is hashed again by the next.
    let past = std::time::SystemTime::now() - Duration::from_secs(3600);
    let set_past = |path: &Path| {
        let f = std::fs::File::options().write(true).open(path).unwrap();
        f.set_modified(past).unwrap();
    };
    set_past(&tx3);
    set_past(&p.dir.path().join("1.tx2"));
    let first = p.run();
    assert_eq!(count(&first, "files_hashed"), 2, "{first}");
    let in_um = p.ra();
    let again = p.run();
    assert_eq!(count(&again, "files_hashed"), 0, "{again}");
    assert_eq!(count(&again, "files_reused"), 1, "{again}");
    p.equals_fresh_run();

    p.conditions("1.tx3", "nm");
    set_past(&tx3);
    let changed = p.run();
    // The .tx3, and the profile read again with it.
    assert_eq!(count(&changed, "files_hashed"), 2, "{changed}");
    assert_eq!(count(&changed, "files_processed"), 1, "{changed}");
    assert!((p.ra() / in_um - 1e-3).abs() < 1e-9, "{}", p.ra());
    assert_eq!(count(&p.run(), "files_hashed"), 0);

    set_past(&p.conditions("1.TX3", "um"));
    let appeared = p.run();
    assert_eq!(count(&appeared, "files_processed"), 1, "{appeared}");
    assert!((p.ra() / in_um - 1.0).abs() < 1e-12, "{}", p.ra());
    p.equals_fresh_run();
}

/// Same folder, same tables, whatever the threads: each summary table's
/// rows and dictionaries (a status column's categories are part of the
/// type pandas, polars and DuckDB read) equal a one-thread run's, though
/// the parts are made, and packed, in thread order.
#[test]
fn tables_are_the_same_whatever_the_threads() {
    let lab = Lab::new();
    let run = |threads: &str, out: &str| {
        let o = Command::new(env!("CARGO_BIN_EXE_tribo"))
            .current_dir(lab.dir.path())
            .env("RAYON_NUM_THREADS", threads)
            .args(["run", "p.toml", "--out", out])
            .output()
            .unwrap();
        assert_eq!(
            o.status.code(),
            Some(0),
            "{}",
            String::from_utf8_lossy(&o.stderr)
        );
    };
    run("1", "one");
    for (i, threads) in ["4", "8", "4"].iter().enumerate() {
        let out = format!("many{i}");
        run(threads, &out);
        common::same_tables(&lab.path("one"), &lab.path(&out));
    }
}

/// The same pipeline given by another path (run from the folder above)
/// names every input otherwise, so nothing is reused: the run says why,
/// naming an input as each run named it. A rerun as the last run was
/// given says nothing.
#[test]
fn a_pipeline_given_by_another_path_says_why_nothing_is_reused() {
    let lab = Lab::new();
    lab.run(&[]);
    let parent = lab.dir.path().parent().unwrap();
    let name = lab.dir.path().file_name().unwrap().to_str().unwrap();
    let pipeline = format!("{name}/p.toml");
    let o = common::tribo(parent, &["run", &pipeline, "--json"]);
    assert_eq!(
        o.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(count(&v, "files_reused"), 0, "{v}");
    let notes = v["notes"].to_string();
    assert!(
        notes.contains("every input is new to this folder's cache"),
        "{notes}"
    );
    assert!(notes.contains(&format!("names '{name}/")), "{notes}");
    let again = common::tribo(parent, &["run", &pipeline, "--json"]);
    let v: serde_json::Value = serde_json::from_slice(&again.stdout).unwrap();
    assert!(!v["notes"].to_string().contains("is new to"), "{v}");
    assert_eq!(count(&v, "files_reused"), N, "{v}");
}
