//! A scheduled rerun over an unchanged folder against a full run with
//! `--force`: 200 friction traces of 20 000 rows each, friction stage plus
//! the Coulomb fit. Prints both times and their ratio (goal ≤ 2 %).
//!
//! cargo bench --bench rerun

use std::path::Path;
use std::time::Instant;

use tribo::pipeline::{run_with, Plan, RunOptions};
use tribo::signal::testing::gaussian_noise;

const FILES: usize = 200;
const ROWS: usize = 20_000;

/// A sled trace: a static peak, then a noisy plateau (tension in mN).
fn trace(seed: u64) -> String {
    let noise = gaussian_noise(ROWS, 0.01, seed);
    let mut s = String::with_capacity(ROWS * 28);
    s.push_str("t (s),Fx [mN],Fz [mN]\n");
    for (i, e) in noise.iter().enumerate() {
        let t = i as f64 * 1e-3;
        let f = if t < 1.0 { 1200.0 * t } else { 1000.0 };
        s.push_str(&format!("{t:.3},{:.3},{:.3}\n", f + 100.0 * e, 2000.0 + e));
    }
    s
}

fn write_folder(dir: &Path) {
    std::fs::create_dir_all(dir.join("traces")).expect("mkdir");
    let mut manifest = String::from("file,sample_id,apparent_area_m2,pattern\n");
    for i in 0..FILES {
        let name = format!("trace_{i:03}.csv");
        std::fs::write(dir.join("traces").join(&name), trace(i as u64)).expect("write");
        manifest.push_str(&format!("{name},S{},1e-4,P{}\n", i % 20, i % 4));
    }
    std::fs::write(dir.join("samples.csv"), manifest).expect("write");
    let pipeline = "stages = [\"friction\", \"coulomb\"]\n[input]\nfiles = [\"traces/*.csv\"]\n\
                    samples = \"samples.csv\"\n[output]\ndir = \"out\"\n[coulomb]\nby = [\"pattern\"]\n";
    std::fs::write(dir.join("p.toml"), pipeline).expect("write");
}

fn timed(plan: &Plan, force: bool) -> f64 {
    let opts = RunOptions {
        force,
        ..Default::default()
    };
    let t = Instant::now();
    let report = run_with(plan, "bench", &|| {}, &opts).expect("run");
    let secs = t.elapsed().as_secs_f64();
    assert_eq!(report.succeeded, FILES);
    secs
}

fn main() {
    let dir = std::env::temp_dir().join(format!("tribo-rerun-bench-{}", std::process::id()));
    write_folder(&dir);
    let plan = Plan::from_file(&dir.join("p.toml")).expect("plan");
    let mb: u64 = (0..FILES)
        .map(|i| {
            std::fs::metadata(dir.join(format!("traces/trace_{i:03}.csv"))).map_or(0, |m| m.len())
        })
        .sum();
    println!("{FILES} traces of {ROWS} rows, {:.0} MB", mb as f64 / 1e6);
    timed(&plan, true); // warm-up: the page cache and the cache folder
    let mut full = Vec::new();
    let mut rerun = Vec::new();
    for _ in 0..3 {
        full.push(timed(&plan, true));
        rerun.push(timed(&plan, false));
    }
    let median = |v: &mut Vec<f64>| {
        v.sort_by(f64::total_cmp);
        v[v.len() / 2]
    };
    let (f, r) = (median(&mut full), median(&mut rerun));
    println!("full run (--force)      {f:>8.3} s (median of 3)");
    println!("unchanged rerun         {r:>8.3} s (median of 3)");
    println!("rerun / full            {:>8.2} %", 100.0 * r / f);
    let _ = std::fs::remove_dir_all(&dir);
}
