//! Reading a 4096 × 4096 binary map, in process (#29 item 5): for each
//! format, a file written by the test writers (`tests/common/writers*.rs`)
//! is read from a warm page cache by tribo's binary readers (open, map,
//! decode the height channel into `f64` metres; no hash) and, as the
//! floor, copied into memory (`std::fs::read`). Each time is the median of
//! `TRIBO_BENCH_RUNS` runs (default 5 here) after one warm-up; the ratios
//! are read / copy of the file and read / copy of the `f64` NPY file (the
//! bytes of the decoded heights: the floor of a format whose samples are
//! narrower than the `f64` it decodes to). Peak memory is the heap allocated during the read above
//! what was allocated before it (a counting allocator), against the
//! decoded heights (`nx · ny · 8` bytes); the file's own pages are mapped,
//! the page cache's, and not counted.
//!
//! `TRIBO_BENCH_SIDE` changes the side (default 4096).
//!
//! cargo bench --bench read_map

#[path = "common/mod.rs"]
mod bench;

/// The test writers, under the module path they expect (`crate::common`);
/// this benchmark uses a few of them.
#[allow(dead_code)]
mod common {
    #[path = "../../tests/common/writers.rs"]
    pub mod writers;
    #[path = "../../tests/common/writers_arrays.rs"]
    pub mod writers_arrays;
    #[path = "../../tests/common/writers_optical.rs"]
    pub mod writers_optical;
    #[path = "../../tests/common/writers_spm.rs"]
    pub mod writers_spm;
}

use std::alloc::{GlobalAlloc, Layout, System};
use std::path::Path;
use std::sync::atomic::{AtomicUsize, Ordering::Relaxed};
use std::time::Instant;

use common::writers::{sur, x3p, Sur, Surface, X3p, X3pType};
use common::writers_arrays::npy;
use common::writers_optical::tmd;
use common::writers_spm::{bcr, frt};
use tribo::ingest::binary::{read, Bytes};
use tribo::ingest::source::Source;
use tribo::ingest::IngestOptions;

/// The system allocator, counting the bytes live and their peak.
struct Counting;

static LIVE: AtomicUsize = AtomicUsize::new(0);
static PEAK: AtomicUsize = AtomicUsize::new(0);

unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, l: Layout) -> *mut u8 {
        let now = LIVE.fetch_add(l.size(), Relaxed) + l.size();
        PEAK.fetch_max(now, Relaxed);
        System.alloc(l)
    }
    // Forwarded, not left to the defaults (allocate then zero, or copy):
    // the system's calloc and realloc are what a read really costs.
    unsafe fn alloc_zeroed(&self, l: Layout) -> *mut u8 {
        let now = LIVE.fetch_add(l.size(), Relaxed) + l.size();
        PEAK.fetch_max(now, Relaxed);
        System.alloc_zeroed(l)
    }
    unsafe fn realloc(&self, p: *mut u8, l: Layout, size: usize) -> *mut u8 {
        let now = LIVE.fetch_add(size, Relaxed) + size;
        PEAK.fetch_max(now, Relaxed);
        LIVE.fetch_sub(l.size(), Relaxed);
        System.realloc(p, l, size)
    }
    unsafe fn dealloc(&self, p: *mut u8, l: Layout) {
        LIVE.fetch_sub(l.size(), Relaxed);
        System.dealloc(p, l)
    }
}

#[global_allocator]
static ALLOC: Counting = Counting;

/// The files to read: name, whether compressed, bytes.
fn files(s: &Surface) -> Vec<(&'static str, bool, Vec<u8>)> {
    let x3p_of = |deflate| {
        let o = X3p {
            kind: X3pType::D,
            deflate,
            ..X3p::default()
        };
        x3p(s, &o)
    };
    let sur_of = |compressed| {
        let o = Sur {
            compressed,
            ..Sur::default()
        };
        sur(s, &o)
    };
    vec![
        ("npy <f8", false, npy(&s.z, &[s.ny, s.nx], "<f8", false, 1)),
        ("tmd f4", false, tmd(s, "bench", true, (0.0, 0.0))),
        ("bcrf f4", false, bcr(s, true, false, &[])),
        ("frt u16", false, frt(s, true, 1e-10, &[])),
        ("sur i32", false, sur_of(false)),
        ("x3p f8 stored", false, x3p_of(false)),
        ("x3p f8 deflate", true, x3p_of(true)),
        ("sur i32 zlib", true, sur_of(true)),
    ]
}

/// Median seconds of `runs` calls of `f`, after one warm-up.
fn median(runs: usize, mut f: impl FnMut()) -> f64 {
    f();
    let mut t: Vec<f64> = (0..runs)
        .map(|_| {
            let s = Instant::now();
            f();
            s.elapsed().as_secs_f64()
        })
        .collect();
    t.sort_by(f64::total_cmp);
    t[t.len() / 2]
}

/// One read of `path`: its height grid's point count, and the heap peak
/// above the heap before it.
fn read_once(path: &Path) -> (usize, usize) {
    let before = LIVE.load(Relaxed);
    PEAK.store(before, Relaxed);
    let source = Source::open(path).expect("open");
    let ds = read(
        &Bytes::from_source(path, &source),
        &IngestOptions::default(),
    )
    .expect("read")
    .expect("a binary format");
    let g = ds
        .grids
        .iter()
        .find(|g| g.height)
        .expect("a height channel");
    let n = g.data.as_ref().map_or(0, |d| d.values.len());
    drop(ds);
    (n, PEAK.load(Relaxed) - before)
}

fn main() {
    let side: usize = std::env::var("TRIBO_BENCH_SIDE")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(4096);
    let runs = std::env::var("TRIBO_BENCH_RUNS")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(5);
    println!("load average at start: {}", bench::load_average());
    let s = Surface::waves(side, side, 1e-7, 1e-7, 3e-8, 1e-8);
    let heights = (side * side * 8) as f64;
    let dir = tempfile::tempdir().expect("temporary folder");
    println!(
        "map {side} x {side}, median of {runs} runs, heights {:.1} MB",
        heights / 1e6
    );
    println!(
        "{:<15} {:>7} {:>8} {:>8} {:>10} {:>10} {:>12}",
        "format", "MB", "copy_s", "read_s", "read/copy", "read/copy8", "peak/heights"
    );
    let mut copy8 = None;
    for (name, compressed, bytes) in files(&s) {
        let path = dir.path().join(name.replace(' ', "_"));
        std::fs::write(&path, &bytes).expect("write");
        drop(bytes);
        let copy = median(runs, || drop(std::fs::read(&path).expect("copy")));
        let copy8 = *copy8.get_or_insert(copy);
        let read_s = median(runs, || {
            read_once(&path);
        });
        let (n, peak) = read_once(&path);
        assert_eq!(n, side * side, "{name}: every point decoded");
        let mb = std::fs::metadata(&path).map_or(0, |m| m.len()) as f64 / 1e6;
        println!(
            "{:<15} {mb:>7.1} {copy:>8.3} {read_s:>8.3} {:>10.2} {:>10.2} {:>12.2}{}",
            name,
            read_s / copy,
            read_s / copy8,
            peak as f64 / heights,
            if compressed { "  (compressed)" } else { "" }
        );
        let _ = std::fs::remove_file(&path);
    }
    println!("load average at end: {}", bench::load_average());
}
