//! Sets `TRIBO_BUILD`: the package version and a hash of everything that
//! decides what tribo computes (`src/`, `schemas/`, `Cargo.lock`). Every
//! cache key begins with it, so a rebuilt tribo whose code or dependencies
//! changed never reuses results the build before computed, even when the
//! version number stayed the same (`docs/scheduling.md`).

use std::fs;
use std::path::{Path, PathBuf};

/// FNV-1a, 64 bits: stable across toolchains and platforms (std's hashers
/// promise neither), and enough to tell one source tree from another.
struct Fnv(u64);

impl Fnv {
    fn update(&mut self, bytes: &[u8]) {
        for b in bytes {
            self.0 ^= u64::from(*b);
            self.0 = self.0.wrapping_mul(0x0000_0100_0000_01b3);
        }
    }
    /// A part preceded by its length, so that parts cannot run together.
    fn part(&mut self, bytes: &[u8]) {
        self.update(&(bytes.len() as u64).to_le_bytes());
        self.update(bytes);
    }
}

/// Every file below `dir`, in a stable order.
fn files(dir: &Path, out: &mut Vec<PathBuf>) {
    let Ok(entries) = fs::read_dir(dir) else {
        return;
    };
    for e in entries.flatten() {
        let p = e.path();
        if p.is_dir() {
            files(&p, out);
        } else {
            out.push(p);
        }
    }
}

fn main() {
    let root = PathBuf::from(std::env::var("CARGO_MANIFEST_DIR").expect("cargo sets it"));
    let mut paths = Vec::new();
    for dir in ["src", "schemas"] {
        files(&root.join(dir), &mut paths);
        println!("cargo:rerun-if-changed={dir}");
    }
    paths.push(root.join("Cargo.lock"));
    println!("cargo:rerun-if-changed=Cargo.lock");
    println!("cargo:rerun-if-changed=build.rs");
    paths.sort();
    let mut h = Fnv(0xcbf2_9ce4_8422_2325);
    for p in &paths {
        let rel = p.strip_prefix(&root).unwrap_or(p);
        // Path separators as `/`, so that a checkout on another system
        // gives the same hash.
        h.part(rel.to_string_lossy().replace('\\', "/").as_bytes());
        h.part(&fs::read(p).unwrap_or_default());
    }
    let version = std::env::var("CARGO_PKG_VERSION").unwrap_or_default();
    println!("cargo:rustc-env=TRIBO_BUILD={version}+{:016x}", h.0);
}
