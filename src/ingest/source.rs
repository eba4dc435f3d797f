//! A file's bytes as read for ingest: a large file is memory-mapped, and
//! the pages the parser of a long block has finished with are handed back
//! to the kernel ([`Source::release`]), so that the file is never resident
//! beside the columns parsed from it (peak memory, `docs/speed.md`).
//! Released pages of a mapping read back from the page cache with the
//! file's content, so a release never changes what is read, only what is
//! resident. The passes before the parse (hashes, decoding) release
//! nothing: the parse reads every page again, and a page released before it
//! would only be faulted back in, while nothing else large is resident yet.
//! Small files are read into memory: a mapping gains nothing there.
//!
//! A file rewritten while it is being read can give a mix of old and new
//! bytes through a mapping (a truncated one, a bus error); lab exports are
//! written once and then read, so tribo maps only files of at least
//! [`MAP_FROM`] bytes.

use std::path::Path;

use crate::error::{Error, Result};

/// Files of at least this size are mapped rather than read.
pub const MAP_FROM: u64 = 16 << 20;

/// Below this, `update_rayon` is slower than `update` (blake3's
/// documentation: 128 KiB on x86-64).
const PARALLEL_BLAKE3_FROM: usize = 128 << 10;

/// The bytes of one input file.
#[derive(Debug)]
pub enum Source {
    /// Read into memory.
    Read(Vec<u8>),
    /// Mapped read-only.
    Mapped(memmap2::Mmap),
}

impl Source {
    /// Opens `path`: checks that reading it fits in memory
    /// ([`super::memory::check`]), then reads or maps it.
    pub fn open(path: &Path) -> Result<Source> {
        let io = |e| Error::io(path, e);
        let size = std::fs::metadata(path).map_err(io)?.len();
        super::memory::check(path, size)?;
        if size < MAP_FROM {
            return std::fs::read(path).map(Source::Read).map_err(io);
        }
        let file = std::fs::File::open(path).map_err(io)?;
        // SAFETY: the mapping is read-only and private; a file changed
        // under it is the hazard stated in the module's documentation.
        let map = unsafe { memmap2::Mmap::map(&file) }.map_err(io)?;
        Ok(Source::Mapped(map))
    }

    /// The bytes.
    pub fn bytes(&self) -> &[u8] {
        match self {
            Source::Read(v) => v,
            Source::Mapped(m) => m,
        }
    }

    /// Hands the whole pages inside `range` (byte offsets) back to the
    /// kernel; a no-op for bytes read into memory.
    pub fn release(&self, range: std::ops::Range<usize>) {
        let Source::Mapped(map) = self else {
            return;
        };
        let page = page_size();
        let start = range.start.div_ceil(page) * page;
        let end = (range.end.min(map.len()) / page) * page;
        if end > start {
            // SAFETY: the mapping is read-only and file-backed: dropped
            // pages are read back from the file when touched again, so no
            // byte seen through `bytes` changes.
            let _ = unsafe {
                map.unchecked_advise_range(memmap2::UncheckedAdvice::DontNeed, start, end - start)
            };
        }
    }

    /// Lower-case hex SHA-256 of the bytes (the provenance's hash).
    pub fn sha256(&self) -> String {
        crate::hash::sha256_hex(self.bytes())
    }

    /// Lower-case hex BLAKE3 of the bytes (a cache key's content part:
    /// several times faster than SHA-256, so that a rerun which finds every
    /// file in the cache is quick). BLAKE3 is a tree hash: the subtrees of a
    /// large input are hashed on rayon's threads (`update_rayon`) and
    /// joined into the standard digest, the one `blake3::hash` gives; an
    /// input too small to gain from threads is hashed on this one.
    pub fn blake3(&self) -> String {
        let bytes = self.bytes();
        let mut h = blake3::Hasher::new();
        match bytes.len() >= PARALLEL_BLAKE3_FROM {
            true => h.update_rayon(bytes),
            false => h.update(bytes),
        };
        h.finalize().to_hex().to_string()
    }
}

fn page_size() -> usize {
    // SAFETY: sysconf has no preconditions.
    let p = unsafe { libc::sysconf(libc::_SC_PAGESIZE) };
    usize::try_from(p).ok().filter(|&p| p > 0).unwrap_or(4096)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A mapped file hashes to the SHA-256 of its bytes (the same as
    /// `sha256_hex` on a copy, and as the known digest of "abc"), and reads
    /// the same bytes after its pages are released.
    #[test]
    fn mapped_bytes_hash_and_survive_release() {
        let dir = std::env::temp_dir().join(format!("tribo-source-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("big.csv");
        let body: Vec<u8> = (0..MAP_FROM as usize + 12_345)
            .map(|i| b"0123456789,\n"[i % 12])
            .collect();
        std::fs::write(&path, &body).unwrap();
        let s = Source::open(&path).unwrap();
        assert!(matches!(s, Source::Mapped(_)));
        assert_eq!(s.sha256(), crate::hash::sha256_hex(&body));
        assert_eq!(s.blake3(), blake3::hash(&body).to_hex().to_string());
        s.release(0..body.len());
        assert!(s.bytes() == body.as_slice());
        let small = dir.join("abc");
        std::fs::write(&small, b"abc").unwrap();
        let s = Source::open(&small).unwrap();
        assert!(matches!(s, Source::Read(_)));
        assert_eq!(
            s.sha256(),
            "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad"
        );
        std::fs::remove_dir_all(&dir).unwrap();
    }

    /// The BLAKE3 hashed on several threads is the standard digest, below,
    /// at and above the size that takes threads.
    #[test]
    fn parallel_blake3_is_the_standard_digest() {
        let sizes = [0, 1, 1024, PARALLEL_BLAKE3_FROM - 1, PARALLEL_BLAKE3_FROM];
        let more = [3 * 1024 * 1024 + 17, 9 << 20];
        for n in sizes.into_iter().chain(more) {
            let body: Vec<u8> = (0..n).map(|i| (i * 7 + i / 4093) as u8).collect();
            let want = blake3::hash(&body).to_hex().to_string();
            assert_eq!(Source::Read(body).blake3(), want, "{n} bytes");
        }
    }
}
