//! Throughput of ingest + extract on friction traces of 1e6 and 1e7 rows
//! (`TRIBO_BENCH_ROWS=1000000,...` to choose), and the same job done by the
//! peer scripts in `benches/peers/` (pandas + scipy, polars + numpy) on the
//! same file when `python3` has their packages: whole-process times of the
//! peers against tribo in-process, as ratios from the same run.
//!
//! cargo bench --bench ingest_extract

use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::Instant;

use tribo::extract::friction::{analyse_trace, FrictionParams, SampleInfo};
use tribo::ingest::trace::friction_trace;
use tribo::ingest::{read_bytes, IngestOptions};
use tribo::signal::testing::gaussian_noise;

fn synthetic_csv(rows: usize) -> Vec<u8> {
    let noise = gaussian_noise(rows, 0.01, 42);
    let mut s = String::with_capacity(rows * 32);
    s.push_str("t (s),Fx [mN],Fz [mN]\n");
    for (i, e) in noise.iter().enumerate() {
        let t = i as f64 * 1e-4;
        let f = if t < 1.0 {
            1200.0 * t
        } else {
            1000.0 + 50.0 * ((t * 7.0).fract() - 0.5)
        };
        s.push_str(&format!("{t:.4},{:.3},{:.3}\n", f + 100.0 * e, 2000.0 + e));
    }
    s.into_bytes()
}

fn main() {
    let sizes: Vec<usize> = std::env::var("TRIBO_BENCH_ROWS")
        .ok()
        .map(|v| v.split(',').filter_map(|r| r.trim().parse().ok()).collect())
        .unwrap_or_else(|| vec![1_000_000, 10_000_000]);
    for rows in sizes {
        bench_rows(rows);
    }
}

/// Whole-process seconds of one peer script on `csv`, or `None` when Python
/// or the peer's packages are missing (the peer is then skipped, said so).
fn run_peer(script: &str, modules: &str, csv: &Path) -> Option<f64> {
    let probe = Command::new("python3")
        .args(["-c", &format!("import {modules}")])
        .output()
        .ok()?;
    if !probe.status.success() {
        println!("peer {script}: skipped (python3 lacks {modules})");
        return None;
    }
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("benches/peers");
    let out = csv.with_extension(format!("{script}.parquet"));
    let t0 = Instant::now();
    let status = Command::new("python3")
        .arg(dir.join(script))
        .arg(csv)
        .arg(&out)
        .status()
        .ok()?;
    let secs = t0.elapsed().as_secs_f64();
    let _ = std::fs::remove_file(&out);
    status.success().then_some(secs)
}

fn bench_rows(rows: usize) {
    let bytes = synthetic_csv(rows);
    let mb = bytes.len() as f64 / 1e6;
    println!("input: {rows} rows, {mb:.1} MB of CSV");

    let t0 = Instant::now();
    let ds = read_bytes(Path::new("bench.csv"), &bytes, &IngestOptions::default()).expect("read");
    let t_read = t0.elapsed().as_secs_f64();

    let t1 = Instant::now();
    let trace = friction_trace(&ds, 0, &Default::default()).expect("trace");
    let t_si = t1.elapsed().as_secs_f64();

    let t2 = Instant::now();
    let feats = analyse_trace(&trace, &SampleInfo::default(), &FrictionParams::default());
    let t_extract = t2.elapsed().as_secs_f64();
    assert_eq!(feats.segments.len(), 1);

    let report = |name: &str, secs: f64| {
        println!(
            "{name:<28} {:>8.3} s  {:>7.2} M rows/s  {:>7.1} MB/s",
            secs,
            rows as f64 / secs / 1e6,
            mb / secs
        );
    };
    report("read (decode+sniff+parse)", t_read);
    report("to SI trace", t_si);
    report("extract features", t_extract);
    report("ingest + extract, total", t_read + t_si + t_extract);
    println!(
        "check: mu_static {:.4}, mu_dynamic {:.4}, {} stick-slip events",
        feats.segments[0].mu_static.unwrap_or(f64::NAN),
        feats.segments[0].mu_dynamic.unwrap_or(f64::NAN),
        feats.segments[0].stickslip_events
    );

    let csv: PathBuf = std::env::temp_dir().join(format!("tribo_bench_{rows}.csv"));
    std::fs::write(&csv, &bytes).expect("write the bench CSV");
    let ours = t_read + t_si + t_extract;
    for (script, modules) in [
        ("pandas_scipy.py", "pandas, scipy, pyarrow"),
        ("polars_numpy.py", "polars, numpy"),
    ] {
        if let Some(secs) = run_peer(script, modules, &csv) {
            println!(
                "peer {script:<18} {secs:>8.3} s whole process; peer / tribo = {:.2}",
                secs / ours
            );
        }
    }
    let _ = std::fs::remove_file(&csv);
}
