//! Throughput of ingest + extract on a 1-million-row friction trace, and of
//! writing its tables. Prints rows/s and MB/s per stage.
//!
//! cargo bench --bench ingest_extract

use std::path::Path;
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
    let rows = 1_000_000;
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
}
