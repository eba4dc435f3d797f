//! Throughput and memory of ingest + friction extraction on traces of 1e6
//! and 1e7 rows (`TRIBO_BENCH_ROWS=1000000,...` to choose), and of a
//! 10 M-point roughness profile (`TRIBO_BENCH_PROFILE=0` to skip), against
//! the peer scripts in `benches/peers/` (pandas + scipy, polars + numpy) on
//! the same files when `python3` has their packages. Whole processes are
//! timed with `/usr/bin/time` (seconds and peak resident memory as the OS
//! reports it), the median of `TRIBO_BENCH_RUNS` runs (default 3); ratios
//! come from the same run.
//!
//! cargo bench --bench ingest_extract

mod common;

use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::Instant;

use common::{measure, measure_in, peer, python_has, repeats, tribo, Measured};

use tribo::extract::friction::{analyse_trace, FrictionParams, SampleInfo};
use tribo::extract::roughness::fractal::synthesize_self_affine;
use tribo::ingest::trace::friction_trace;
use tribo::ingest::{read_path, IngestOptions};
use tribo::signal::testing::gaussian_noise;
use tribo::table::{Codec, TableBuilder, CODEC};

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
    let load = std::fs::read_to_string("/proc/loadavg").unwrap_or_default();
    println!("load average at start: {}", load.trim());
    println!(
        "whole processes: median time and largest peak of {} runs each",
        repeats()
    );
    let runs: Vec<Run> = sizes.into_iter().map(bench_rows).collect();
    if let (Some(a), Some(b)) = (runs.first(), runs.last()) {
        if b.rows > a.rows {
            let slope = |ta: f64, tb: f64| (tb / ta).ln() / (b.rows as f64 / a.rows as f64).ln();
            println!(
                "log-log slope of whole-process time, {} to {} rows: tribo --no-traces {:.3}, with traces {:.3}",
                a.rows,
                b.rows,
                slope(a.no_traces.secs, b.no_traces.secs),
                slope(a.traces.secs, b.traces.secs)
            );
        }
    }
    if std::env::var("TRIBO_BENCH_PROFILE").as_deref() != Ok("0") {
        bench_profile(10_000_000);
    }
    let load = std::fs::read_to_string("/proc/loadavg").unwrap_or_default();
    println!("load average at end: {}", load.trim());
}

struct Run {
    rows: usize,
    no_traces: Measured,
    traces: Measured,
}

fn row(name: &str, m: Measured, ours: Measured, mb: f64) {
    println!(
        "{name:<40} {:>8.3} s {:>7.0} MB/s  peak RSS {:>7.0} MB ({:.2}x file)  / tribo = {:.2}",
        m.secs,
        mb / m.secs,
        m.rss_mb,
        m.rss_mb / mb,
        m.secs / ours.secs
    );
}

fn bench_rows(rows: usize) -> Run {
    let bytes = synthetic_csv(rows);
    let mb = bytes.len() as f64 / 1e6;
    let dir = std::env::temp_dir().join(format!("tribo_bench_{rows}"));
    std::fs::create_dir_all(&dir).expect("bench dir");
    let csv: PathBuf = dir.join("trace.csv");
    std::fs::write(&csv, &bytes).expect("write the bench CSV");
    drop(bytes);
    println!("\n== {rows} rows, {mb:.1} MB of CSV ==");
    in_process(&csv, rows, mb);

    let c = csv.to_str().expect("UTF-8 temp path");
    let out = dir.join("out");
    let o = out.to_str().expect("UTF-8 temp path");
    let fresh = Some(out.as_path());
    let no_traces =
        measure_in(tribo(), &["friction", c, "--out", o, "--no-traces"], fresh).expect("tribo");
    let traces = measure_in(tribo(), &["friction", c, "--out", o], fresh).expect("tribo");
    let inspect = measure(tribo(), &["inspect", c]).expect("tribo inspect");
    println!("whole process (seconds, throughput, peak RSS, time / tribo --no-traces):");
    row("tribo friction --no-traces", no_traces, no_traces, mb);
    row("tribo friction (traces table on)", traces, no_traces, mb);
    row("tribo inspect (parse alone)", inspect, no_traces, mb);
    let py = Path::new("python3");
    let p_out = dir.join("peer.parquet");
    let p = p_out.to_str().expect("UTF-8 temp path");
    if python_has(Path::new("python3"), "polars, numpy") {
        let s = peer("polars_numpy.py");
        if let Some(m) = measure(py, &[&s, c, p]) {
            row("polars + numpy peer", m, no_traces, mb);
        }
        if let Some(m) = measure(py, &[&s, c, p, "--traces"]) {
            row("polars + numpy peer --traces", m, traces, mb);
            println!("  (its ratio is against tribo with traces)");
        }
        let r = peer("polars_read.py");
        if let Some(m) = measure(py, &[&r, c]) {
            row("polars.read_csv alone (whole process)", m, inspect, mb);
            println!("  (its ratio is against tribo inspect)");
        }
    }
    if python_has(Path::new("python3"), "pandas, scipy, pyarrow") {
        let s = peer("pandas_scipy.py");
        if let Some(m) = measure(py, &[&s, c, p]) {
            row("pandas + scipy peer", m, no_traces, mb);
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
    Run {
        rows,
        no_traces,
        traces,
    }
}

/// tribo's stages in this process, and polars.read_csv timed inside Python
/// (start-up excluded): parse speed against parse speed.
fn in_process(csv: &Path, rows: usize, mb: f64) {
    let t0 = Instant::now();
    let ds = read_path(csv, &IngestOptions::default()).expect("read");
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
            "{name:<40} {:>8.3} s  {:>7.2} M rows/s  {:>7.1} MB/s",
            secs,
            rows as f64 / secs / 1e6,
            mb / secs
        );
    };
    println!("in process:");
    report("read (file, decode, sniff, parse)", t_read);
    report("to SI trace", t_si);
    report("extract features", t_extract);
    println!(
        "check: mu_static {:.4}, mu_dynamic {:.4}, {} stick-slip events",
        feats.segments[0].mu_static.unwrap_or(f64::NAN),
        feats.segments[0].mu_dynamic.unwrap_or(f64::NAN),
        feats.segments[0].stickslip_events
    );
    codecs(&trace, csv);
    if python_has(Path::new("python3"), "polars") {
        let out = Command::new("python3")
            .arg(peer("polars_read.py"))
            .arg(csv)
            .output();
        let secs = out
            .ok()
            .and_then(|o| String::from_utf8(o.stdout).ok())
            .and_then(|s| s.split_whitespace().next()?.parse::<f64>().ok());
        if let Some(secs) = secs {
            report("polars.read_csv (inside Python)", secs);
            println!("  parse: polars time / tribo time = {:.2}", secs / t_read);
        }
    }
}

/// The trace as the traces table holds it, written with each codec: write
/// time and file size, the measurement behind `table::CODEC`.
fn codecs(trace: &tribo::ingest::trace::Trace, csv: &Path) {
    let n = trace.len();
    let table = TableBuilder::new()
        .str_runs("source", [(Some(csv.display().to_string()), n)])
        .str_runs("section", [(Some("1"), n)])
        .i64_runs("stroke", [(Some(1), n)])
        .f64_vec("time_s", trace.time_s.clone())
        .f64_vec("friction_force_N", trace.friction_n.clone())
        .f64_vec("normal_force_N", trace.normal_n.clone().unwrap_or_default())
        .build()
        .expect("table");
    let path = csv.with_extension("parquet");
    println!("traces-like table, {n} rows, by codec (write time, size):");
    for codec in [Codec::Uncompressed, Codec::Snappy, Codec::Lz4, Codec::Zstd] {
        let t = Instant::now();
        let file = std::fs::File::create(&path).expect("create");
        table
            .write_parquet_codec(std::io::BufWriter::new(file), &[], &[], codec)
            .expect("write");
        let secs = t.elapsed().as_secs_f64();
        let size = std::fs::metadata(&path).map_or(0, |m| m.len()) as f64 / 1e6;
        let chosen = if codec == CODEC { "  (chosen)" } else { "" };
        println!(
            "  {:<14} {secs:>7.3} s {size:>8.1} MB{chosen}",
            format!("{codec:?}")
        );
    }
    let _ = std::fs::remove_file(&path);
}

/// A 10 M-point self-affine profile as `x [um],z [um]` text: `tribo
/// roughness --detrend mean` whole process against the polars + numpy peer.
fn bench_profile(points: usize) {
    let z = synthesize_self_affine(points, 0.7, 1e-6, 7);
    let mut s = String::with_capacity(points * 24);
    s.push_str("x [um],z [um]\n");
    for (i, v) in z.iter().take(points).enumerate() {
        s.push_str(&format!("{:.3},{:.5}\n", i as f64 * 0.1, v * 1e6));
    }
    let mb = s.len() as f64 / 1e6;
    let dir = std::env::temp_dir().join("tribo_bench_profile");
    std::fs::create_dir_all(&dir).expect("bench dir");
    let csv = dir.join("profile.csv");
    std::fs::write(&csv, s).expect("write the profile");
    println!("\n== profile: {points} points, {mb:.1} MB ==");
    let c = csv.to_str().expect("UTF-8 temp path");
    let o = dir.join("out");
    let args = [
        "roughness",
        c,
        "--out",
        o.to_str().expect("UTF-8"),
        "--detrend",
        "mean",
    ];
    let Some(ours) = measure_in(tribo(), &args, Some(&o)) else {
        return;
    };
    row("tribo roughness --detrend mean", ours, ours, mb);
    if python_has(Path::new("python3"), "polars, numpy") {
        let p = dir.join("peer.parquet");
        let py = Path::new("python3");
        if let Some(m) = measure(
            py,
            &[&peer("polars_roughness.py"), c, p.to_str().expect("UTF-8")],
        ) {
            row("polars + numpy roughness peer", m, ours, mb);
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
}
