//! The least a rerun can do per input (#32): list the inputs' folder and
//! stat every file in it, on all cores, as `tribo run` does before it can
//! tell that nothing changed. `benches/incremental.sh` builds it with
//! `rustc` alone (std only, no crate) and prints its time beside each
//! folder size's runs: what no design that stats each input can go below.
//!
//!     rustc -O benches/floor/list_stat.rs -o list_stat && ./list_stat DIR [REPS]
//!
//! Prints the median over REPS (5) of the milliseconds the listing took,
//! those the stats took, and the number of files.

use std::path::Path;
use std::time::Instant;

fn main() {
    let mut args = std::env::args().skip(1);
    let Some(dir) = args.next() else {
        eprintln!("usage: list_stat DIR [REPS]");
        std::process::exit(2);
    };
    let reps: usize = args.next().and_then(|r| r.parse().ok()).unwrap_or(5);
    let threads = std::thread::available_parallelism().map_or(1, |n| n.get());
    let (mut lists, mut stats, mut files) = (Vec::new(), Vec::new(), 0);
    for _ in 0..reps {
        let t = Instant::now();
        let names: Vec<_> = match std::fs::read_dir(&dir) {
            Ok(entries) => entries.flatten().map(|e| e.path()).collect(),
            Err(e) => {
                eprintln!("{dir}: {e}");
                std::process::exit(1);
            }
        };
        let listed = t.elapsed().as_secs_f64() * 1e3;
        let t = Instant::now();
        let chunk = names.len().div_ceil(threads).max(1);
        let seen: usize = std::thread::scope(|s| {
            let each: Vec<_> = names
                .chunks(chunk)
                .map(|part| s.spawn(move || part.iter().filter(|p| stat(p)).count()))
                .collect();
            each.into_iter().map(|h| h.join().unwrap_or(0)).sum()
        });
        stats.push(t.elapsed().as_secs_f64() * 1e3);
        lists.push(listed);
        files = seen;
    }
    println!("{:.1} {:.1} {files}", median(lists), median(stats));
}

/// Whether `p` is a file, from its stat (one call that returns its size,
/// times and inode, as `tribo run` takes them).
fn stat(p: &Path) -> bool {
    std::fs::metadata(p).is_ok_and(|m| m.is_file())
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}
