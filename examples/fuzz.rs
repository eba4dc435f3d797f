//! A fuzz harness on stable Rust: mutates the bundled fixtures (text
//! exports, and the binary surface files of `fixtures/surface/`: X3P, SUR,
//! ...) and the real exports in `../shared/data/real` and `real2` when present, and feeds each
//! mutant through reading, routing and every per-file stage that takes it,
//! as a pipeline would, checking that nothing panics, hangs or fails in a
//! way that would stop a batch (a table that does not fit its schema).
//!
//!     cargo run --release --example fuzz -- --seconds 600 [--execs N] [--seed 1] [--threads 2] [--corpus DIR]
//!
//! `--corpus DIR` takes the seeds from DIR only (`--corpus fixtures/surface`
//! fuzzes the binary readers alone).
//!
//! Deterministic for a seed and a thread count. An input that panics, takes
//! over 2 s, or breaks a table is written to `target/fuzz-found/`; keep it as
//! a regression fixture in `fixtures/fuzz/` (checked by
//! `tests/fuzz_regressions.rs`). Prints executions, rate and findings.

use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};
use std::time::{Duration, Instant};

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use tribo::pipeline::fuzz::{check_input, Finding};

/// Bytes of each seed file kept: mutants stay small, so the run reaches
/// millions of executions; the full files are used one time in 64.
const HEAD: usize = 4096;

fn corpus(root: &Path, only: Option<&Path>) -> Vec<(PathBuf, Vec<u8>)> {
    let mut files = Vec::new();
    let all = [
        root.join("fixtures/friction"),
        root.join("fixtures/roughness"),
        root.join("fixtures/surface"),
        root.join("fixtures/tensile"),
        root.join("fixtures/lab"),
        root.join("fixtures/bad"),
        root.join("../shared/data/real"),
        root.join("../shared/data/real2"),
    ];
    let dirs = match only {
        Some(d) => vec![root.join(d)],
        None => all.to_vec(),
    };
    for d in dirs {
        walk(&d, &mut files);
    }
    files.sort();
    files
        .into_iter()
        .filter(|p| {
            !matches!(
                p.extension().and_then(|e| e.to_str()),
                Some("md" | "py" | "toml")
            )
        })
        .filter_map(|p| std::fs::read(&p).ok().map(|b| (p, b)))
        .collect()
}

fn walk(dir: &Path, out: &mut Vec<PathBuf>) {
    for e in std::fs::read_dir(dir).into_iter().flatten().flatten() {
        let p = e.path();
        if p.is_dir() {
            walk(&p, out);
        } else if !p.to_string_lossy().contains("LICENSE") {
            out.push(p);
        }
    }
}

const EXTREMES: &[&str] = &[
    "1e99999",
    "-1e99999",
    "1e300",
    "1e-300",
    "NaN",
    "nan",
    "inf",
    "-inf",
    "0",
    "-0",
    "",
    "99999999999999999999999",
    "1,5",
    "1.000,5",
    "\"",
    "\"\"",
    "1e",
    "--1",
    "0x10",
    "   ",
];

/// One mutation of `seed` bytes.
fn mutate(rng: &mut ChaCha8Rng, seed: &[u8]) -> Vec<u8> {
    let mut b = seed.to_vec();
    for _ in 0..rng.random_range(1..4) {
        if b.is_empty() {
            b.extend_from_slice(b"x");
        }
        let at = rng.random_range(0..b.len());
        match rng.random_range(0..9) {
            0 => b[at] = rng.random(),
            1 => b.insert(
                at,
                *b",;\t\n\r\" .eE-+0123456789"
                    .get(rng.random_range(0..23))
                    .unwrap_or(&b'0'),
            ),
            2 => {
                let end = (at + rng.random_range(1..64)).min(b.len());
                b.drain(at..end);
            }
            3 => b.truncate(at),
            4 => replace_number(rng, &mut b, at),
            5 => duplicate_line(&mut b, at),
            6 => b
                .splice(at..at, std::iter::repeat_n(b'\n', rng.random_range(1..50)))
                .for_each(drop),
            7 => b
                .splice(
                    at..at,
                    std::iter::repeat_n(b'9', rng.random_range(100..5000)),
                )
                .for_each(drop),
            _ => b = to_utf16(&b, rng.random()),
        }
    }
    b
}

fn replace_number(rng: &mut ChaCha8Rng, b: &mut Vec<u8>, at: usize) {
    let start = (at..b.len()).find(|&i| b[i].is_ascii_digit());
    let Some(s) = start else { return };
    let e = (s..b.len())
        .find(|&i| !(b[i].is_ascii_digit() || b[i] == b'.' || b[i] == b','))
        .unwrap_or(b.len());
    let with = EXTREMES[rng.random_range(0..EXTREMES.len())].as_bytes();
    b.splice(s..e, with.iter().copied()).for_each(drop);
}

fn duplicate_line(b: &mut Vec<u8>, at: usize) {
    let s = b[..at]
        .iter()
        .rposition(|&c| c == b'\n')
        .map_or(0, |i| i + 1);
    let e = b[at..]
        .iter()
        .position(|&c| c == b'\n')
        .map_or(b.len(), |i| at + i + 1);
    let line = b[s..e].to_vec();
    b.splice(e..e, line).for_each(drop);
}

fn to_utf16(b: &[u8], odd: bool) -> Vec<u8> {
    let mut out = vec![0xFF, 0xFE];
    for &c in b {
        out.extend_from_slice(&[c, 0]);
    }
    if odd {
        out.pop();
    }
    out
}

struct Args {
    seconds: f64,
    execs: u64,
    seed: u64,
    threads: usize,
    corpus: Option<PathBuf>,
}

fn args() -> Args {
    let mut a = Args {
        seconds: 60.0,
        execs: u64::MAX,
        seed: 1,
        threads: 2,
        corpus: None,
    };
    let v: Vec<String> = std::env::args().collect();
    for w in v.windows(2) {
        match w[0].as_str() {
            "--seconds" => a.seconds = w[1].parse().unwrap_or(a.seconds),
            "--seed" => a.seed = w[1].parse().unwrap_or(a.seed),
            "--execs" => a.execs = w[1].parse().unwrap_or(a.execs),
            "--threads" => a.threads = w[1].parse().unwrap_or(a.threads),
            "--corpus" => a.corpus = Some(PathBuf::from(&w[1])),
            _ => {}
        }
    }
    a
}

fn main() {
    let a = args();
    // As `cargo run` gives it when it runs the example: a binary built by
    // another checkout into a shared target folder reads this one's corpus.
    let root = std::env::var_os("CARGO_MANIFEST_DIR")
        .map_or_else(|| PathBuf::from(env!("CARGO_MANIFEST_DIR")), PathBuf::from);
    let corpus = corpus(&root, a.corpus.as_deref());
    let found = root.join("target/fuzz-found");
    let execs = AtomicU64::new(0);
    let findings = AtomicU64::new(0);
    let start = Instant::now();
    let stop = Duration::from_secs_f64(a.seconds);
    std::panic::set_hook(Box::new(|_| {}));
    std::thread::scope(|s| {
        for t in 0..a.threads {
            let (corpus, execs, findings, found) = (&corpus, &execs, &findings, &found);
            s.spawn(move || {
                let mut rng = ChaCha8Rng::seed_from_u64(a.seed ^ (t as u64) << 32);
                while start.elapsed() < stop && execs.load(Ordering::Relaxed) < a.execs {
                    let (path, bytes) = &corpus[rng.random_range(0..corpus.len())];
                    let seed = if rng.random_range(0..64) == 0 {
                        bytes.as_slice()
                    } else {
                        &bytes[..bytes.len().min(HEAD)]
                    };
                    let input = mutate(&mut rng, seed);
                    let t0 = Instant::now();
                    let outcome = check_input(path, &input);
                    let slow = t0.elapsed() > Duration::from_secs(2);
                    execs.fetch_add(1, Ordering::Relaxed);
                    let finding = match outcome {
                        Some(f) => Some(f),
                        None if slow => Some(Finding::Slow(t0.elapsed())),
                        None => None,
                    };
                    if let Some(f) = finding {
                        findings.fetch_add(1, Ordering::Relaxed);
                        let name = format!(
                            "{}-{}",
                            &tribo::hash::sha256_hex(&input)[..16],
                            path.file_name().unwrap_or_default().to_string_lossy()
                        );
                        let _ = std::fs::create_dir_all(found);
                        let _ = std::fs::write(found.join(&name), &input);
                        eprintln!("finding: {f:?}: {name}");
                    }
                }
            });
        }
    });
    let n = execs.load(Ordering::Relaxed);
    let secs = start.elapsed().as_secs_f64();
    println!(
        "{n} executions in {secs:.0} s ({:.0}/s) over {} seed files, {} findings",
        n as f64 / secs,
        corpus.len(),
        findings.load(Ordering::Relaxed)
    );
    if findings.load(Ordering::Relaxed) > 0 {
        std::process::exit(1);
    }
}
