//! What the report costs on a long trace: one friction trace of 1e7 rows
//! (`TRIBO_BENCH_ROWS` to change it) through the friction stage, traces
//! table off, with and without `report = true`; prints both times, the
//! difference (goal < 1 s) and the size of report.html (goal < 2 MB).
//! Runs are interleaved, three of each; the minimum is reported.
//!
//! cargo bench --bench report

use std::path::Path;
use std::time::Instant;

use tribo::pipeline::{run_with, Plan, RunOptions};
use tribo::signal::testing::gaussian_noise;

fn rows() -> usize {
    std::env::var("TRIBO_BENCH_ROWS")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(10_000_000)
}

/// A ramp to a static peak, then a 7 Hz saw-tooth with noise (mN).
fn write_trace(path: &Path, n: usize) {
    use std::io::Write;
    let noise = gaussian_noise(n, 0.01, 7);
    let mut w = std::io::BufWriter::new(std::fs::File::create(path).expect("create"));
    writeln!(w, "t (s),Fx [mN],Fz [mN]").expect("write");
    for (i, e) in noise.iter().enumerate() {
        let t = i as f64 * 1e-4;
        let f = if t < 1.0 {
            1200.0 * t
        } else {
            1000.0 + 80.0 * ((t * 7.0).fract() - 0.5)
        };
        writeln!(w, "{t:.4},{:.3},{:.3}", f + 100.0 * e, 2000.0 + e).expect("write");
    }
}

fn pipeline(dir: &Path, report: bool) -> Plan {
    let name = if report { "with.toml" } else { "without.toml" };
    let text = format!(
        "stages = [\"friction\"]\n[input]\nfiles = [\"long.csv\"]\n[output]\n\
         dir = \"out-{report}\"\ntraces = false\nreport = {report}\n"
    );
    std::fs::write(dir.join(name), text).expect("write");
    Plan::from_file(&dir.join(name)).expect("plan")
}

fn timed(plan: &Plan) -> f64 {
    let opts = RunOptions {
        force: true,
        ..Default::default()
    };
    let t = Instant::now();
    run_with(plan, "bench", &|| {}, &opts).expect("run");
    t.elapsed().as_secs_f64()
}

fn main() {
    let n = rows();
    let dir = std::env::temp_dir().join(format!("tribo-report-bench-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("mkdir");
    write_trace(&dir.join("long.csv"), n);
    let (with, without) = (pipeline(&dir, true), pipeline(&dir, false));
    let (mut a, mut b) = (f64::INFINITY, f64::INFINITY);
    for _ in 0..3 {
        b = b.min(timed(&without));
        a = a.min(timed(&with));
    }
    let size = std::fs::metadata(dir.join("out-true/report.html")).map_or(0, |m| m.len());
    println!("{n} rows, friction stage, traces off (min of 3, interleaved):");
    println!("  without report  {b:8.3} s");
    println!("  with report     {a:8.3} s   (+{:.3} s)", a - b);
    println!("  report.html     {:8.3} MB", size as f64 / 1e6);
    let _ = std::fs::remove_dir_all(&dir);
}
