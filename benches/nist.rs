//! NIST StRD accuracy and speed: prints the LRE table per problem and start
//! (the same as `tribo fit nist`) and the wall time of the whole suite.
//! Run: `cargo bench --bench nist [-- DIR]`.

mod common;

use std::path::PathBuf;
use std::time::Instant;

use tribo::fit::nist::{format_table, run_dir};
use tribo::fit::LmParams;

fn main() {
    let dir = std::env::args()
        .skip(1)
        .find(|a| !a.starts_with('-'))
        .map(PathBuf::from)
        .unwrap_or_else(|| common::root().join("../shared/data/nist_strd"));
    if !dir.is_dir() {
        eprintln!("note: {} absent; nothing to benchmark", dir.display());
        return;
    }
    let t = Instant::now();
    let rows = match run_dir(&dir, &LmParams::default()) {
        Ok(r) => r,
        Err(e) => {
            eprintln!("error: {e}");
            std::process::exit(2);
        }
    };
    let once = t.elapsed();
    let reps = 20;
    let t = Instant::now();
    for _ in 0..reps {
        std::hint::black_box(run_dir(&dir, &LmParams::default()).ok());
    }
    let per = t.elapsed() / reps;
    print!("{}", format_table(&rows));
    println!(
        "suite (27 problems x 2 starts, parse + fit): first {once:?}, mean of {reps}: {per:?}"
    );
}
